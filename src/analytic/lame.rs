//! Lamé's thick-walled cylinder (inner radius a, outer b, internal pressure
//! p, axis z through the origin; for axisymmetric models r = x, axis = y):
//!
//! ```text
//! k = p a^2 / (b^2 - a^2)
//! sigma_r = k (1 - b^2/r^2)     sigma_theta = k (1 + b^2/r^2)
//! plane strain (and axisymmetric / solid with the axial displacement held):
//!   u_r = (1 + nu) k / E ((1 - 2 nu) r + b^2 / r),  sigma_axial = 2 nu k
//! plane stress:
//!   u_r = k / E ((1 - nu) r + (1 + nu) b^2 / r),    sigma_axial = 0
//! ```

use super::exact::Exact;
use crate::fem::Analysis;

/// Lamé's cylinder for one analysis and material.
#[derive(Clone, Debug)]
pub struct Lame {
    pub a: f64,
    pub b: f64,
    pub p: f64,
    pub e: f64,
    pub nu: f64,
    pub analysis: Analysis,
}

impl Lame {
    fn k(&self) -> f64 {
        self.p * self.a * self.a / (self.b * self.b - self.a * self.a)
    }
    pub fn sigma_r(&self, r: f64) -> f64 {
        self.k() * (1.0 - self.b * self.b / (r * r))
    }
    pub fn sigma_theta(&self, r: f64) -> f64 {
        self.k() * (1.0 + self.b * self.b / (r * r))
    }
    pub fn u_r(&self, r: f64) -> f64 {
        let (k, e, nu, b) = (self.k(), self.e, self.nu, self.b);
        match self.analysis {
            Analysis::PlaneStress => k / e * ((1.0 - nu) * r + (1.0 + nu) * b * b / r),
            _ => (1.0 + nu) * k / e * ((1.0 - 2.0 * nu) * r + b * b / r),
        }
    }
    fn axial(&self) -> f64 {
        match self.analysis {
            Analysis::PlaneStress => 0.0,
            _ => 2.0 * self.nu * self.k(),
        }
    }
}

impl Exact for Lame {
    fn displacement(&self, x: [f64; 3]) -> [f64; 3] {
        if self.analysis == Analysis::Axisymmetric {
            return [self.u_r(x[0]), 0.0, 0.0];
        }
        let r = x[0].hypot(x[1]);
        let u = self.u_r(r);
        [u * x[0] / r, u * x[1] / r, 0.0]
    }
    fn stress(&self, x: [f64; 3]) -> [f64; 6] {
        if self.analysis == Analysis::Axisymmetric {
            let r = x[0];
            return [self.sigma_r(r), self.axial(), self.sigma_theta(r), 0.0, 0.0, 0.0];
        }
        let r = x[0].hypot(x[1]);
        let (c, s) = (x[0] / r, x[1] / r);
        let (sr, st) = (self.sigma_r(r), self.sigma_theta(r));
        [sr * c * c + st * s * s, sr * s * s + st * c * c, self.axial(), (sr - st) * s * c, 0.0, 0.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_table_values() {
        // DESIGN.md §3, units 1e-2 MPa; the printed values are cut, not
        // rounded (sigma_r(3.2) = -8.108 is printed -8.10, sigma_theta(4.0) =
        // 14.414 is printed 14.4), hence the tolerance of 0.015
        let l = Lame { a: 3.0, b: 5.0, p: 0.1, e: 2.0e5, nu: 0.167, analysis: Analysis::PlaneStrain };
        let sr = [-8.10, -5.23, -3.16, -1.63, -0.47];
        let st = [19.35, 16.47, 14.4, 12.88, 11.72];
        for (i, r) in [3.2, 3.6, 4.0, 4.4, 4.8].iter().enumerate() {
            assert!((l.sigma_r(*r) * 100.0 - sr[i]).abs() < 0.015, "{r}");
            assert!((l.sigma_theta(*r) * 100.0 - st[i]).abs() < 0.015, "{r}");
        }
        // the boundary conditions: sigma_r(a) = -p, sigma_r(b) = 0
        assert!((l.sigma_r(3.0) + 0.1).abs() < 1e-15);
        assert!(l.sigma_r(5.0).abs() < 1e-15);
    }

    #[test]
    fn displacement_satisfies_hooke_in_plane_strain() {
        // eps_theta = u/r must equal ((1+nu)/E)((1-nu) s_t - nu s_r)
        let l = Lame { a: 3.0, b: 5.0, p: 0.1, e: 2.0e5, nu: 0.3, analysis: Analysis::PlaneStrain };
        let r = 3.7;
        let lhs = l.u_r(r) / r;
        let rhs = (1.0 + l.nu) / l.e * ((1.0 - l.nu) * l.sigma_theta(r) - l.nu * l.sigma_r(r));
        assert!((lhs - rhs).abs() < 1e-12 * rhs.abs());
    }
}
