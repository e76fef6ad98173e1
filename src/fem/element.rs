//! Element kernels: stiffness `K_e = ∫ B^T D B dV`, body forces `∫ N^T b dV`,
//! boundary tractions `∫ N^T t dA` and stresses at quadrature points.
//!
//! B-bar (Hughes 1980, "Generalization of selective integration procedures
//! to anisotropic and nonlinear media", IJNME 15): the linear quadrilateral
//! in plane strain and axisymmetry, the linear hexahedron and prism take the
//! volumetric part of their strain at the element's mean. With `b_vol` the
//! sum of the normal rows of B (xx, yy, and zz or the hoop row: the
//! dilatation),
//!
//! ```text
//! b̄_vol = (1/V) ∫ b_vol dV                    the element's mean dilatation
//! B̄_i   = B_i + (b̄_vol - b_vol) / 3          i = xx, yy, zz (hoop)
//! K_e   = ∫ B̄^T D B̄ dV,   eps = B̄ u_e        shear rows unchanged
//! ```
//!
//! so the deviatoric strain is B's, pointwise, and the dilatation one number
//! per element: lambda multiplies one constraint per element instead of
//! several (3 for a quad4 in plane strain, 4 in axisymmetry, 7 for a hex8
//! and 4 for a prism6 under the full rule), and nu -> 1/2 no longer locks. The split is the
//! 3D one in plane strain too (the solid with eps_zz = 0, B_zz = 0), so
//! B̄ gives an eps_zz and D its zz row there; a hex8 slice held on both
//! faces is then the plane strain quad4 node for node (tests/lame.rs). A
//! constant strain is left as it is (its dilatation is its mean), so the
//! patch test still holds; rigid motions have zero dilatation everywhere,
//! and the full (2 x 2, 2 x 2 x 2) rule keeps the deviatoric part
//! rank-sufficient, so no zero-energy mode appears (reduced integration of
//! the whole stiffness, or of its deviatoric part, would add some). The
//! stresses recovered use the same B̄ ([`strain`] with
//! [`mean_dilatation`]). Plane stress has no incompressibility constraint
//! (eps_zz is free), and the quadratic kinds lock far less (a quad9's
//! dilatation is a polynomial with room to vanish: its Lamé displacement
//! error grows x18 from nu = 0.3 to 0.499 where quad4's grew x128), so they
//! keep the plain B. The initial-stress load `-∫ B^T sigma0 dV` keeps the
//! plain B as well: it is the consistent nodal force of a given stress
//! field, which then balances the body force of a geostatic field exactly.
//!
//! Map coordinates: the Jacobian and the facet tangents are sums of
//! `dN_a/dxi (x_a - x_0)`, coordinates relative to the cell's first node.
//! A model at x ~ 4e6 with cells of 0.1 m would otherwise lose seven of the
//! sixteen digits of every Jacobian entry before anything is summed; the
//! differences of nearby doubles are exact. Positions handed out
//! (`Point::x`, the facet point) stay absolute, so closed forms, initial
//! stresses, load levels, probes and output all keep reading the model's
//! own coordinates: nothing downstream has to know about an origin.

use super::material::{n_strain, plane_strain_with_zz};
use super::quadrature::{self, QuadPoint};
use super::shape;
use super::Analysis;
use crate::mesh::CellKind;
// the 3-vector helpers, where callers of the element kernels found them
pub use super::vec3::{cross, dot, norm, sub};

/// A cell whose Jacobian determinant is not positive somewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inverted {
    pub det_j: f64,
}

/// Geometry of a cell at one reference point.
pub struct Point {
    /// Shape function values.
    pub n: Vec<f64>,
    /// Physical gradients dN_a/dx_j.
    pub dndx: Vec<[f64; 3]>,
    /// Jacobian determinant.
    pub det_j: f64,
    /// Physical position.
    pub x: [f64; 3],
}

/// Shape functions, physical gradients and Jacobian of a cell whose dimension
/// equals the space dimension.
pub fn point(kind: CellKind, coords: &[[f64; 3]], xi: [f64; 3]) -> Result<Point, Inverted> {
    let nn = kind.n_nodes();
    let dim = kind.dim();
    let mut n = vec![0.0; nn];
    let mut dn = vec![[0.0; 3]; nn];
    shape::eval(kind, xi, &mut n, &mut dn);
    // J[i][j] = dx_i/dxi_j, from coordinates relative to the cell's first
    // node (see the module doc: map coordinates)
    let o = coords[0];
    let mut jac = [[0.0; 3]; 3];
    let mut x = [0.0; 3];
    for a in 0..nn {
        let r = sub(coords[a], o);
        for i in 0..3 {
            x[i] += n[a] * r[i];
        }
        for i in 0..dim {
            for j in 0..dim {
                jac[i][j] += r[i] * dn[a][j];
            }
        }
    }
    let x = [o[0] + x[0], o[1] + x[1], o[2] + x[2]];
    let (det_j, inv) = if dim == 2 {
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        let inv = [[jac[1][1] / det, -jac[0][1] / det, 0.0], [-jac[1][0] / det, jac[0][0] / det, 0.0], [0.0; 3]];
        (det, inv)
    } else {
        let m = jac;
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        let mut inv = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                // inverse = adjugate / det, adj[i][j] = cofactor[j][i]
                let (r0, r1) = ((j + 1) % 3, (j + 2) % 3);
                let (c0, c1) = ((i + 1) % 3, (i + 2) % 3);
                inv[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
            }
        }
        (det, inv)
    };
    if !(det_j > 0.0) {
        return Err(Inverted { det_j });
    }
    // dN/dx_k = sum_j dN/dxi_j * dxi_j/dx_k = sum_j dn[j] inv[j][k]
    let dndx = dn
        .iter()
        .map(|g| {
            let mut d = [0.0; 3];
            for k in 0..dim {
                d[k] = (0..dim).map(|j| g[j] * inv[j][k]).sum();
            }
            d
        })
        .collect();
    Ok(Point { n, dndx, det_j, x })
}

/// Volume weight factor at a point: thickness, 2 pi r or 1.
pub fn measure(analysis: Analysis, thickness: f64, x: &[f64; 3]) -> f64 {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => thickness,
        Analysis::Axisymmetric => 2.0 * std::f64::consts::PI * x[0],
        Analysis::Solid => 1.0,
    }
}

/// DOFs per node of an analysis.
pub fn dofs_per_node(analysis: Analysis) -> usize {
    if analysis == Analysis::Solid {
        3
    } else {
        2
    }
}

/// The strain-displacement matrix B, row-major `n_strain x (nn * nd)`.
fn b_matrix(analysis: Analysis, p: &Point, b: &mut [f64]) {
    let nd = dofs_per_node(analysis);
    let nn = p.n.len();
    let w = nn * nd;
    b.iter_mut().for_each(|v| *v = 0.0);
    // On the axis (r = 0, where u_r = 0) the hoop strain u_r / r is 0 / 0;
    // its limit is du_r/dr. "On" means within round-off of the cell size
    // (quadrature points never are; probes and nodes may be).
    let on_axis = analysis == Analysis::Axisymmetric && {
        let inv_h = p.dndx.iter().fold(0.0f64, |m, g| m.max(g[0].abs()).max(g[1].abs()));
        p.x[0] * inv_h < 1e-10
    };
    for a in 0..nn {
        let g = p.dndx[a];
        let c = a * nd;
        match analysis {
            Analysis::PlaneStrain | Analysis::PlaneStress => {
                b[c] = g[0];
                b[w + c + 1] = g[1];
                b[2 * w + c] = g[1];
                b[2 * w + c + 1] = g[0];
            }
            Analysis::Axisymmetric => {
                b[c] = g[0];
                b[w + c + 1] = g[1];
                b[2 * w + c] = if on_axis { g[0] } else { p.n[a] / p.x[0] };
                b[3 * w + c] = g[1];
                b[3 * w + c + 1] = g[0];
            }
            Analysis::Solid => {
                b[c] = g[0];
                b[w + c + 1] = g[1];
                b[2 * w + c + 2] = g[2];
                b[3 * w + c] = g[1];
                b[3 * w + c + 1] = g[0];
                b[4 * w + c + 1] = g[2];
                b[4 * w + c + 2] = g[1];
                b[5 * w + c] = g[2];
                b[5 * w + c + 2] = g[0];
            }
        }
    }
}

/// Poisson's ratio from which the linear quadrilateral and hexahedron take
/// B-bar. Below it they keep the plain B: locking is mild there (quad4 Lamé
/// cylinder, plane strain, lc 0.25: displacement error 1.28e-3 at nu = 0.3,
/// 2.26e-3 at 0.3999; with B-bar 7.6e-4 at 0.4, 8.6e-4 at 0.499), and
/// B-bar's constant dilatation per element costs point stresses on coarse
/// meshes (the paper's 30-hex8 cylinder, nu = 0.167: sigma_r at the Table 1
/// radii +1.6 % at most with the plain B, up to +13 % with B-bar).
pub const B_BAR_FROM_NU: f64 = 0.4;

/// Whether an element takes its dilatation at the element's mean (B-bar,
/// see the module doc): quad4 in plane strain and axisymmetry, hex8 and
/// prism6, in a material of nu >= [`B_BAR_FROM_NU`]. (Prism6, Lamé's
/// cylinder as a quarter turn of prisms, lc 0.2, nu = 0.499: displacement
/// error 7.7e-2 and stress error 6.3 with the plain B, 3.1e-3 and 0.31
/// with B-bar, against 8.2e-4 and 4.1e-2 at nu = 0.3.)
pub fn uses_b_bar(analysis: Analysis, kind: CellKind, nu: f64) -> bool {
    nu >= B_BAR_FROM_NU
        && matches!(
            (analysis, kind),
            (Analysis::PlaneStrain | Analysis::Axisymmetric, CellKind::Quad4)
                | (Analysis::Solid, CellKind::Hex8 | CellKind::Prism6)
        )
}

/// Number of normal strain rows of B, the first ones, whose sum is the
/// dilatation: 2 in plane analyses (in plane strain eps_zz = 0), 3 in
/// axisymmetry (rr, zz, hoop) and solids.
fn n_normal(analysis: Analysis) -> usize {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => 2,
        Analysis::Axisymmetric | Analysis::Solid => 3,
    }
}

/// The element's mean dilatation row `b̄_vol = (1/V) ∫ b_vol dV` over the
/// points `(Point, weight)` of its rule, weights including the measure;
/// `b` is scratch space for B.
fn mean_dilatation_row(analysis: Analysis, points: &[(Point, f64)], b: &mut [f64]) -> Vec<f64> {
    let k = n_normal(analysis);
    let m = b.len() / n_strain(analysis);
    let mut mean = vec![0.0; m];
    let mut volume = 0.0;
    for (p, f) in points {
        b_matrix(analysis, p, b);
        for c in 0..m {
            mean[c] += f * (0..k).map(|i| b[i * m + c]).sum::<f64>();
        }
        volume += f;
    }
    mean.iter_mut().for_each(|v| *v /= volume);
    mean
}

/// B̄ at one point from B (`b`, the analysis's rows) into `out`: the
/// analysis's rows, in plane strain with the out-of-plane normal inserted,
/// `(xx, yy, zz, xy)`; each of the three normal rows gets
/// `(b̄_vol - b_vol) / 3`.
fn b_bar(analysis: Analysis, mean: &[f64], b: &[f64], out: &mut [f64]) {
    let m = mean.len();
    let k = n_normal(analysis);
    if analysis == Analysis::PlaneStrain {
        // (xx, yy, xy) -> (xx, yy, zz = 0, xy)
        out[..2 * m].copy_from_slice(&b[..2 * m]);
        out[2 * m..3 * m].iter_mut().for_each(|v| *v = 0.0);
        out[3 * m..4 * m].copy_from_slice(&b[2 * m..3 * m]);
    } else {
        out.copy_from_slice(b);
    }
    for c in 0..m {
        let shift = (mean[c] - (0..k).map(|i| b[i * m + c]).sum::<f64>()) / 3.0;
        for i in 0..3 {
            out[i * m + c] += shift;
        }
    }
}

/// Geometry of a cell at every point of a rule, with the weight
/// `w det J measure` of each.
fn rule_points(
    analysis: Analysis,
    kind: CellKind,
    coords: &[[f64; 3]],
    thickness: f64,
    rule: &[QuadPoint],
) -> Result<Vec<(Point, f64)>, Inverted> {
    rule.iter()
        .map(|q| {
            let p = point(kind, coords, q.xi)?;
            let f = q.w * p.det_j * measure(analysis, thickness, &p.x);
            Ok((p, f))
        })
        .collect()
}

/// The element's mean dilatation `b̄_vol u_e` under displacements `ue`, for
/// [`strain`]: Some for the elements that use B-bar ([`uses_b_bar`]), None
/// for the others (and for an inverted cell, whose stiffness was refused).
pub fn mean_dilatation(analysis: Analysis, kind: CellKind, nu: f64, coords: &[[f64; 3]], ue: &[f64]) -> Option<f64> {
    if !uses_b_bar(analysis, kind, nu) {
        return None;
    }
    let points = rule_points(analysis, kind, coords, 1.0, &stiffness_rule(analysis, kind)).ok()?;
    let mut b = vec![0.0; n_strain(analysis) * ue.len()];
    let mean = mean_dilatation_row(analysis, &points, &mut b);
    Some(mean.iter().zip(ue).map(|(a, u)| a * u).sum())
}

/// The quadrature rule for an element's stiffness in an analysis: the kind's
/// own stiffness rule, except for triangles in axisymmetry, where the hoop
/// strain N/r makes the one-point (tri3) and three-point (tri6) rules leave
/// a spurious zero-energy mode (and integrate curved cells poorly): there a
/// rule of degree 2 (tri3) or 4 (tri6).
pub fn stiffness_rule(analysis: Analysis, kind: CellKind) -> Vec<QuadPoint> {
    match (analysis, kind) {
        (Analysis::Axisymmetric, CellKind::Tri3) => quadrature::rule(kind, 2),
        (Analysis::Axisymmetric, CellKind::Tri6) => quadrature::rule(kind, 4),
        _ => quadrature::stiffness_rule(kind),
    }
}

/// Element stiffness, row-major `(nn nd) x (nn nd)`, written into `ke`.
#[allow(clippy::too_many_arguments)] // a kernel: the element's data, no struct to bundle it in
pub fn stiffness(
    analysis: Analysis,
    kind: CellKind,
    nu: f64,
    coords: &[[f64; 3]],
    d: &[f64],
    thickness: f64,
    rule: &[QuadPoint],
    ke: &mut Vec<f64>,
) -> Result<(), Inverted> {
    let nd = dofs_per_node(analysis);
    let m = kind.n_nodes() * nd;
    let ns = n_strain(analysis);
    ke.clear();
    ke.resize(m * m, 0.0);
    let mut b = vec![0.0; ns * m];
    let points = rule_points(analysis, kind, coords, thickness, rule)?;
    let mean = uses_b_bar(analysis, kind, nu).then(|| mean_dilatation_row(analysis, &points, &mut b));
    // with B-bar in plane strain, eps_zz joins the strain: D gets its row
    let (ns, d): (usize, std::borrow::Cow<[f64]>) = match (&mean, analysis) {
        (Some(_), Analysis::PlaneStrain) => (4, plane_strain_with_zz(d).into()),
        _ => (ns, d.into()),
    };
    let mut bb = vec![0.0; ns * m];
    let mut db = vec![0.0; ns * m];
    for (p, f) in &points {
        let f = *f;
        b_matrix(analysis, p, &mut b);
        let b: &[f64] = match &mean {
            Some(mean) => {
                b_bar(analysis, mean, &b, &mut bb);
                &bb
            }
            None => &b,
        };
        for i in 0..ns {
            for c in 0..m {
                db[i * m + c] = (0..ns).map(|k| d[i * ns + k] * b[k * m + c]).sum::<f64>() * f;
            }
        }
        for r in 0..m {
            for i in 0..ns {
                let bir = b[i * m + r];
                if bir != 0.0 {
                    let row = &mut ke[r * m..(r + 1) * m];
                    let dbi = &db[i * m..(i + 1) * m];
                    for c in 0..m {
                        row[c] += bir * dbi[c];
                    }
                }
            }
        }
    }
    Ok(())
}

/// Consistent nodal forces of a body force `g` per unit volume.
pub fn body_force(
    analysis: Analysis,
    kind: CellKind,
    coords: &[[f64; 3]],
    g: [f64; 3],
    thickness: f64,
    fe: &mut [f64],
) -> Result<(), Inverted> {
    let nd = dofs_per_node(analysis);
    let rule = quadrature::rule(kind, 2 * kind.order() + 1);
    for q in &rule {
        let p = point(kind, coords, q.xi)?;
        let f = q.w * p.det_j * measure(analysis, thickness, &p.x);
        for a in 0..kind.n_nodes() {
            for c in 0..nd {
                fe[a * nd + c] += p.n[a] * g[c] * f;
            }
        }
    }
    Ok(())
}

/// Consistent nodal forces `-∫ B^T sigma0 dV` of an initial stress field
/// `sigma0(x)` (six components `[xx, yy, zz, xy, yz, xz]`): the loads that
/// keep the stress in equilibrium where the body is whole, and release it at
/// faces the mesh leaves free (excavation).
pub fn initial_stress_force(
    analysis: Analysis,
    kind: CellKind,
    coords: &[[f64; 3]],
    sigma0: &dyn Fn([f64; 3]) -> [f64; 6],
    thickness: f64,
    rule: &[QuadPoint],
    fe: &mut [f64],
) -> Result<(), Inverted> {
    let nd = dofs_per_node(analysis);
    let m = kind.n_nodes() * nd;
    let ns = n_strain(analysis);
    let mut b = vec![0.0; ns * m];
    for q in rule {
        let p = point(kind, coords, q.xi)?;
        let f = q.w * p.det_j * measure(analysis, thickness, &p.x);
        let s = sigma0(p.x);
        let sv: Vec<f64> = match analysis {
            Analysis::PlaneStrain | Analysis::PlaneStress => vec![s[0], s[1], s[3]],
            Analysis::Axisymmetric => vec![s[0], s[1], s[2], s[3]],
            Analysis::Solid => s.to_vec(),
        };
        b_matrix(analysis, &p, &mut b);
        for c in 0..m {
            fe[c] -= f * (0..ns).map(|i| b[i * m + c] * sv[i]).sum::<f64>();
        }
    }
    Ok(())
}

/// Unit normal and area element of a boundary facet (a line in a plane
/// model, a surface in a solid) at reference point `xi`; the normal is
/// (dx/dxi rotated -90 degrees) in 2D and `a1 x a2` in 3D, to be oriented by
/// the caller. Also returns the shape values and the physical point.
pub fn facet_point(kind: CellKind, coords: &[[f64; 3]], xi: [f64; 3]) -> (Vec<f64>, [f64; 3], f64, [f64; 3]) {
    let nn = kind.n_nodes();
    let mut n = vec![0.0; nn];
    let mut dn = vec![[0.0; 3]; nn];
    shape::eval(kind, xi, &mut n, &mut dn);
    let o = coords[0];
    let mut a1 = [0.0; 3];
    let mut a2 = [0.0; 3];
    let mut x = [0.0; 3];
    for a in 0..nn {
        let r = sub(coords[a], o);
        for i in 0..3 {
            x[i] += n[a] * r[i];
            a1[i] += r[i] * dn[a][0];
            a2[i] += r[i] * dn[a][1];
        }
    }
    let x = [o[0] + x[0], o[1] + x[1], o[2] + x[2]];
    let normal = if kind.dim() == 1 { [a1[1], -a1[0], 0.0] } else { cross(a1, a2) };
    let da = norm(normal);
    let unit = if da > 0.0 { [normal[0] / da, normal[1] / da, normal[2] / da] } else { [0.0; 3] };
    (n, unit, da, x)
}

/// +1 or -1: the sign that turns the facet's natural normal into the outward
/// normal of the body cell `cell_coords` it bounds.
pub fn outward_sign(facet: CellKind, facet_coords: &[[f64; 3]], cell: CellKind, cell_coords: &[[f64; 3]]) -> f64 {
    let (_, n, _, x) = facet_point(facet, facet_coords, shape::reference_centre(facet));
    let nc = cell.n_corners();
    let mut c = [0.0; 3];
    for p in &cell_coords[..nc] {
        for i in 0..3 {
            c[i] += p[i] / nc as f64;
        }
    }
    if dot(n, sub(x, c)) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Consistent nodal forces of a traction on a boundary facet; `traction`
/// gets the point and the outward unit normal.
pub fn facet_force(
    analysis: Analysis,
    kind: CellKind,
    coords: &[[f64; 3]],
    sign: f64,
    thickness: f64,
    traction: &dyn Fn([f64; 3], [f64; 3]) -> [f64; 3],
    fe: &mut [f64],
) {
    let nd = dofs_per_node(analysis);
    let rule = quadrature::rule(kind, 2 * kind.order() + 2);
    for q in &rule {
        let (n, unit, da, x) = facet_point(kind, coords, q.xi);
        let normal = [unit[0] * sign, unit[1] * sign, unit[2] * sign];
        let t = traction(x, normal);
        let f = q.w * da * measure(analysis, thickness, &x);
        for a in 0..kind.n_nodes() {
            for c in 0..nd {
                fe[a * nd + c] += n[a] * t[c] * f;
            }
        }
    }
}

/// Strain vector (analysis components) at a point from element
/// displacements: `B u_e`, or `B̄ u_e` given the element's
/// [`mean_dilatation`] (its normal components shifted equally so that they
/// add up to the mean). In plane strain B̄ gives eps_zz != 0: it follows
/// the three components, in slot 3 (see [`super::material`]).
pub fn strain(analysis: Analysis, p: &Point, ue: &[f64], mean_dilatation: Option<f64>) -> [f64; 6] {
    let nd = dofs_per_node(analysis);
    let ns = n_strain(analysis);
    let m = p.n.len() * nd;
    let mut b = vec![0.0; ns * m];
    b_matrix(analysis, p, &mut b);
    let mut e = [0.0; 6];
    for i in 0..ns {
        e[i] = (0..m).map(|c| b[i * m + c] * ue[c]).sum();
    }
    if let Some(mean) = mean_dilatation {
        let k = n_normal(analysis);
        let shift = (mean - e[..k].iter().sum::<f64>()) / 3.0;
        e[..k].iter_mut().for_each(|v| *v += shift);
        if analysis == Analysis::PlaneStrain {
            e[3] = shift;
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::material::{d_matrix, full_stress};
    use nalgebra::DMatrix;

    /// A distorted copy of the reference cell: a non-affine map, shifted
    /// away from the axis (for axisymmetry).
    fn distorted(kind: CellKind) -> Vec<[f64; 3]> {
        shape::reference_nodes(kind)
            .iter()
            .map(|p| {
                let [x, y, z] = *p;
                [2.0 + x + 0.15 * x * y + 0.1 * y, 1.0 + 0.9 * y - 0.1 * x * x + 0.05 * z, z + 0.1 * x * y]
            })
            .collect()
    }

    /// Rigid motions of a node set: translations and rotations.
    fn rigid_modes(analysis: Analysis, xs: &[[f64; 3]]) -> Vec<Vec<f64>> {
        let nd = dofs_per_node(analysis);
        let mode =
            |f: &dyn Fn([f64; 3]) -> [f64; 3]| xs.iter().flat_map(|&x| f(x)[..nd].to_vec()).collect::<Vec<f64>>();
        match analysis {
            Analysis::Axisymmetric => vec![mode(&|_| [0.0, 1.0, 0.0])],
            Analysis::Solid => vec![
                mode(&|_| [1.0, 0.0, 0.0]),
                mode(&|_| [0.0, 1.0, 0.0]),
                mode(&|_| [0.0, 0.0, 1.0]),
                mode(&|x| [-x[1], x[0], 0.0]),
                mode(&|x| [0.0, -x[2], x[1]]),
                mode(&|x| [x[2], 0.0, -x[0]]),
            ],
            _ => vec![mode(&|_| [1.0, 0.0, 0.0]), mode(&|_| [0.0, 1.0, 0.0]), mode(&|x| [-x[1], x[0], 0.0])],
        }
    }

    #[test]
    fn element_stiffness_is_symmetric_with_exactly_the_rigid_modes_in_its_kernel() {
        use CellKind::*;
        let cases = [
            (Analysis::PlaneStrain, vec![Tri3, Tri6, Quad4, Quad8, Quad9]),
            (Analysis::PlaneStress, vec![Tri3, Tri6, Quad4, Quad8, Quad9]),
            (Analysis::Axisymmetric, vec![Tri3, Tri6, Quad4, Quad8, Quad9]),
            (
                Analysis::Solid,
                vec![Tet4, Tet10, Hex8, Hex20, Hex27, Prism6, Prism15, Prism18, Pyramid5, Pyramid13, Pyramid14],
            ),
        ];
        // nu near 1/2 too: B-bar (quad4 plane strain / axisymmetric, hex8)
        // must add no zero-energy mode however large lambda is
        for (analysis, kinds, nu) in cases.iter().flat_map(|(a, k)| [0.3, 0.4999].map(|nu| (*a, k.clone(), nu))) {
            let d = d_matrix(analysis, 1000.0, nu);
            for kind in kinds {
                let xs = distorted(kind);
                let mut ke = Vec::new();
                // the rule assembly uses: no spurious zero-energy modes
                let rule = stiffness_rule(analysis, kind);
                stiffness(analysis, kind, nu, &xs, &d, 1.0, &rule, &mut ke).expect("not inverted");
                let m = (ke.len() as f64).sqrt() as usize;
                let k = DMatrix::from_row_slice(m, m, &ke);
                let scale = k.amax();
                assert!((&k - k.transpose()).amax() < 1e-12 * scale, "{analysis:?} {kind:?} symmetric");
                for r in rigid_modes(analysis, &xs) {
                    let kr = &k * nalgebra::DVector::from_vec(r.clone());
                    let rn = r.iter().map(|v| v * v).sum::<f64>().sqrt();
                    assert!(kr.amax() < 1e-10 * scale * rn, "{analysis:?} {kind:?}: a rigid motion is in the kernel");
                }
                let eig = k.symmetric_eigen().eigenvalues;
                let zeros = eig.iter().filter(|&&l| l.abs() < 1e-9 * scale).count();
                let want = rigid_modes(analysis, &xs).len();
                assert_eq!(zeros, want, "{analysis:?} {kind:?}: {zeros} zero eigenvalues, {want} rigid modes");
                assert!(eig.iter().all(|&l| l > -1e-9 * scale), "{analysis:?} {kind:?} positive semi-definite");
            }
        }
    }
    /// Body forces: the consistent nodal forces of a uniform g add up to g
    /// times the volume, on an affine image of every 3D reference cell
    /// (the volume is |det A| times the reference volume) and on a distorted
    /// one (against a high-order rule's volume).
    #[test]
    fn body_forces_add_up_to_the_weight_on_every_3d_kind() {
        let a = [[1.2, 0.3, -0.1], [0.1, 0.9, 0.2], [-0.2, 0.1, 1.4]];
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        let g = [0.5, -2.0, -9.81];
        for kind in CellKind::ALL.into_iter().filter(|k| k.dim() == 3) {
            let affine: Vec<[f64; 3]> = shape::reference_nodes(kind)
                .iter()
                .map(|p| std::array::from_fn(|i| 2.0 + (0..3).map(|j| a[i][j] * p[j]).sum::<f64>()))
                .collect();
            for (xs, volume) in [(affine, det * quadrature::reference_volume(kind)), (distorted(kind), f64::NAN)] {
                let volume = if volume.is_nan() {
                    quadrature::rule(kind, 10).iter().map(|q| q.w * point(kind, &xs, q.xi).unwrap().det_j).sum()
                } else {
                    volume
                };
                let mut fe = vec![0.0; 3 * kind.n_nodes()];
                body_force(Analysis::Solid, kind, &xs, g, 1.0, &mut fe).expect("not inverted");
                for c in 0..3 {
                    let total: f64 = fe.iter().skip(c).step_by(3).sum();
                    assert!(
                        (total - g[c] * volume).abs() < 1e-12 * 9.81 * volume,
                        "{kind:?}: {total} vs {}",
                        g[c] * volume
                    );
                }
            }
        }
    }

    /// The elements that use B-bar.
    fn b_bar_cases() -> Vec<(Analysis, CellKind)> {
        vec![
            (Analysis::PlaneStrain, CellKind::Quad4),
            (Analysis::Axisymmetric, CellKind::Quad4),
            (Analysis::Solid, CellKind::Hex8),
            (Analysis::Solid, CellKind::Prism6),
        ]
    }

    #[test]
    fn b_bar_constrains_the_dilatation_once_per_element() {
        // D = lambda m m^T (mu = 0): K_e = lambda V b̄ b̄^T has rank one
        // with B-bar; the plain B of the full rule has rank 3 (quad4, plane
        // strain), 4 (quad4, axisymmetric), 7 (hex8), 4 (prism6): that many constraints
        // per element is what locks
        for (analysis, kind) in b_bar_cases() {
            assert!(uses_b_bar(analysis, kind, 0.49));
            assert!(!uses_b_bar(analysis, kind, 0.3), "plain B below B_BAR_FROM_NU");
            let ns = n_strain(analysis);
            let k = n_normal(analysis);
            let mut d = vec![0.0; ns * ns];
            for i in 0..k {
                for j in 0..k {
                    d[i * ns + j] = 1.0;
                }
            }
            let xs = distorted(kind);
            let mut ke = Vec::new();
            stiffness(analysis, kind, 0.49, &xs, &d, 1.0, &stiffness_rule(analysis, kind), &mut ke)
                .expect("not inverted");
            let m = (ke.len() as f64).sqrt() as usize;
            let eig = DMatrix::from_row_slice(m, m, &ke).symmetric_eigen().eigenvalues;
            let top = eig.amax();
            let rank = eig.iter().filter(|&&l| l.abs() > 1e-10 * top).count();
            assert_eq!(rank, 1, "{analysis:?} {kind:?}: volumetric stiffness of rank {rank}");
        }
    }

    #[test]
    fn b_bar_strain_is_the_strain_of_the_stiffness_and_leaves_linear_fields_alone() {
        for (analysis, kind) in b_bar_cases() {
            let xs = distorted(kind);
            let nd = dofs_per_node(analysis);
            let d = d_matrix(analysis, 1000.0, 0.45);
            let rule = stiffness_rule(analysis, kind);
            let mut ke = Vec::new();
            stiffness(analysis, kind, 0.45, &xs, &d, 1.0, &rule, &mut ke).expect("not inverted");
            let m = xs.len() * nd;
            // any displacements: u_e^T K_e u_e = ∫ eps^T D eps dV with the
            // recovered strain
            let ue: Vec<f64> = (0..m).map(|i| ((i * 7 + 3) % 11) as f64 / 11.0 - 0.4).collect();
            let mean = mean_dilatation(analysis, kind, 0.45, &xs, &ue);
            assert!(mean.is_some());
            // sigma : eps with the reported stress (plane strain: e_zz in slot 3)
            let mut energy = 0.0;
            for q in &rule {
                let p = point(kind, &xs, q.xi).unwrap();
                let f = q.w * p.det_j * measure(analysis, 1.0, &p.x);
                let e = strain(analysis, &p, &ue, mean);
                let sigma = full_stress(analysis, 1000.0, 0.45, &d, &e);
                let eps = match analysis {
                    Analysis::PlaneStrain => [e[0], e[1], e[3], e[2], 0.0, 0.0],
                    Analysis::Axisymmetric => [e[0], e[1], e[2], e[3], 0.0, 0.0],
                    _ => e,
                };
                energy += f * (0..6).map(|i| sigma[i] * eps[i]).sum::<f64>();
            }
            let kuu: f64 = (0..m).map(|r| ue[r] * (0..m).map(|c| ke[r * m + c] * ue[c]).sum::<f64>()).sum();
            assert!((kuu - energy).abs() < 1e-12 * kuu.abs(), "{analysis:?} {kind:?}: {kuu} vs {energy}");
            // a linear field (axisymmetric: u_r = a r, u_z = b z + c) has a
            // constant strain, which B-bar keeps as it is
            let lin = |x: [f64; 3]| -> [f64; 3] {
                match analysis {
                    Analysis::Axisymmetric => [0.3 * x[0], -0.2 * x[1] + 0.1, 0.0],
                    // (the distorted plane cells have z != 0 at their nodes)
                    Analysis::PlaneStrain => [0.3 * x[0] + 0.1 * x[1], 0.2 * x[0] - 0.2 * x[1], 0.0],
                    _ => [
                        0.3 * x[0] + 0.1 * x[1] - 0.05 * x[2],
                        0.2 * x[0] - 0.2 * x[1] + 0.4 * x[2],
                        0.15 * x[0] + 0.25 * x[1] + 0.1 * x[2],
                    ],
                }
            };
            let ul: Vec<f64> = xs.iter().flat_map(|&x| lin(x)[..nd].to_vec()).collect();
            let mean = mean_dilatation(analysis, kind, 0.45, &xs, &ul);
            for q in &rule {
                let p = point(kind, &xs, q.xi).unwrap();
                let (plain, bar) = (strain(analysis, &p, &ul, None), strain(analysis, &p, &ul, mean));
                assert!(
                    (0..6).all(|i| (plain[i] - bar[i]).abs() < 1e-14),
                    "{analysis:?} {kind:?}: {plain:?} vs {bar:?}"
                );
            }
        }
    }
}
