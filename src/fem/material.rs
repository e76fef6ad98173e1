//! Isotropic linear elasticity for the four analyses, in Voigt notation with
//! engineering shear strains.
//!
//! Strain components per analysis (the rows of B):
//! - plane strain / plane stress: `[xx, yy, xy]`
//! - axisymmetric (r = x, axis = y): `[rr, zz, tt, rz]` stored as `[xx, yy, zz, xy]`,
//!   the hoop component taking the out-of-plane `zz` slot
//! - solid: `[xx, yy, zz, xy, yz, xz]`
//!
//! Reported stresses always have six components `[xx, yy, zz, xy, yz, xz]`;
//! in plane strain `s_zz = lambda (e_xx + e_yy)`, in plane stress `s_zz = 0`.
//! A plane strain element under B-bar (`element`) has an out-of-plane
//! strain e_zz of its own: it follows the three components (slot 3 of the
//! strain passed to [`full_stress`], zero otherwise), and
//! [`plane_strain_with_zz`] gives D its row.

use super::Analysis;

/// Lamé parameters from Young's modulus and Poisson's ratio.
pub fn lame(e: f64, nu: f64) -> (f64, f64) {
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    (lambda, mu)
}

/// Number of strain components of an analysis.
pub fn n_strain(analysis: Analysis) -> usize {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => 3,
        Analysis::Axisymmetric => 4,
        Analysis::Solid => 6,
    }
}

/// The constitutive matrix, row-major `n_strain x n_strain`.
pub fn d_matrix(analysis: Analysis, e: f64, nu: f64) -> Vec<f64> {
    let (lambda, mu) = lame(e, nu);
    let n = n_strain(analysis);
    let mut d = vec![0.0; n * n];
    // number of normal components coupled by lambda
    let (normals, lam) = match analysis {
        // plane stress: the in-plane lambda is 2 lambda mu / (lambda + 2 mu)
        Analysis::PlaneStress => (2, 2.0 * lambda * mu / (lambda + 2.0 * mu)),
        Analysis::PlaneStrain => (2, lambda),
        Analysis::Axisymmetric => (3, lambda),
        Analysis::Solid => (3, lambda),
    };
    for i in 0..normals {
        for j in 0..normals {
            d[i * n + j] = lam;
        }
        d[i * n + i] += 2.0 * mu;
    }
    for i in normals..n {
        d[i * n + i] = mu;
    }
    d
}

/// The plane strain D (rows and columns xx, yy, xy) with the out-of-plane
/// normal restored: rows and columns `(xx, yy, zz, xy)`, the layout of the
/// axisymmetric D. Isotropic: lambda is `D[xx][yy]`, lambda + 2 mu `D[xx][xx]`.
pub fn plane_strain_with_zz(d: &[f64]) -> Vec<f64> {
    let (lambda, normal) = (d[1], d[0]);
    #[rustfmt::skip]
    let d4 = vec![
        d[0], d[1], lambda, d[2],
        d[3], d[4], lambda, d[5],
        lambda, lambda, normal, 0.0,
        d[6], d[7], 0.0, d[8],
    ];
    d4
}

/// Stress in the six reported components from the analysis' strain vector
/// (in plane strain, slot 3 may carry e_zz: see the module doc).
pub fn full_stress(analysis: Analysis, e: f64, nu: f64, d: &[f64], strain: &[f64]) -> [f64; 6] {
    let n = n_strain(analysis);
    let mut s = [0.0; 6];
    let mut sv = [0.0; 6];
    for i in 0..n {
        sv[i] = (0..n).map(|j| d[i * n + j] * strain[j]).sum();
    }
    match analysis {
        Analysis::PlaneStrain => {
            let (lambda, mu) = lame(e, nu);
            let ezz = strain[3];
            s[0] = sv[0] + lambda * ezz;
            s[1] = sv[1] + lambda * ezz;
            s[2] = lambda * (strain[0] + strain[1] + ezz) + 2.0 * mu * ezz;
            s[3] = sv[2];
        }
        Analysis::PlaneStress => {
            s[0] = sv[0];
            s[1] = sv[1];
            s[3] = sv[2];
        }
        Analysis::Axisymmetric => {
            s[..4].copy_from_slice(&sv[..4]);
        }
        Analysis::Solid => s = sv,
    }
    s
}

/// Von Mises equivalent stress of `[xx, yy, zz, xy, yz, xz]`.
pub fn von_mises(s: &[f64; 6]) -> f64 {
    let [xx, yy, zz, xy, yz, xz] = *s;
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) + 3.0 * (xy * xy + yz * yz + xz * xz)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_stress_matches_textbook_matrix() {
        let (e, nu) = (210.0, 0.3);
        let d = d_matrix(Analysis::PlaneStress, e, nu);
        let c = e / (1.0 - nu * nu);
        let expect = [c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * (1.0 - nu) / 2.0];
        for (a, b) in d.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12 * e);
        }
    }

    #[test]
    fn plane_strain_matches_textbook_matrix() {
        let (e, nu) = (210.0, 0.3);
        let d = d_matrix(Analysis::PlaneStrain, e, nu);
        let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let expect = [c * (1.0 - nu), c * nu, 0.0, c * nu, c * (1.0 - nu), 0.0, 0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0];
        for (a, b) in d.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12 * e);
        }
    }

    #[test]
    fn uniaxial_solid_stress_gives_young_modulus() {
        // strain state of a uniaxial stress s in x: e_xx = s/E, e_yy = e_zz = -nu s/E
        let (e, nu, s) = (3.0e4, 0.25, 7.0);
        let d = d_matrix(Analysis::Solid, e, nu);
        let strain = [s / e, -nu * s / e, -nu * s / e, 0.0, 0.0, 0.0];
        let st = full_stress(Analysis::Solid, e, nu, &d, &strain);
        assert!((st[0] - s).abs() < 1e-12 * s);
        assert!(st[1].abs() < 1e-12 * s && st[2].abs() < 1e-12 * s);
        assert!((von_mises(&st) - s).abs() < 1e-12 * s);
    }
}
