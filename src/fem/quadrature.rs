//! Quadrature rules on the reference cells of [`crate::fem::shape`], the
//! rule used for element stiffness matrices, and the extrapolation of values
//! known at quadrature points (stresses, strains) to the element's nodes.
//!
//! * Line, Quad, Hex: Gauss–Legendre (tensor) rules of any degree, computed
//!   on the fly.
//! * Tri, Tet: fully symmetric rules with positive weights and all points
//!   inside the cell, up to degree 8 (Tri) and 6 (Tet); the tables use the
//!   orbit structures of Dunavant (triangle) and Keast (tetrahedron), with
//!   values polished to double precision on the monomial moment equations.
//!   Above those degrees, collapsed (Duffy) Gauss–Legendre product rules of
//!   any degree, still with positive weights and interior points.
//! * Prism: the triangle's rule times Gauss–Legendre along ζ.
//! * Pyramid: a collapsed hexahedron. `ξ = a (1 - ζ)`, `η = b (1 - ζ)` maps
//!   the cube (a, b) ∈ [-1, 1]², ζ ∈ [0, 1] onto the pyramid with Jacobian
//!   `(1 - ζ)²`; Gauss–Legendre in a, b and ζ. Chosen over the rules built
//!   for the rational bases (which integrate their own space and little
//!   else) because the pull-back makes the pyramids' spaces polynomial: q =
//!   ξη/(1 - ζ) is `a b (1 - ζ)` and its gradient `(b, a, a b)`, so the
//!   stiffness integrand of an affine pyramid5 (pyramid13/14) is a
//!   polynomial of degree 2 (4) in a and b and, with the Jacobian, 2 (4) in
//!   ζ: 2 x 2 x 2 (3 x 3 x 3) points integrate it exactly, and the same
//!   construction gives rules of any degree, with positive weights and no
//!   point at the apex (where the rational gradients have no limit).
//!
//! Weights are for the reference cell itself: they add up to its volume
//! (Line 2, Tri 1/2, Quad 4, Tet 1/6, Hex 8, Prism 1, Pyramid 4/3; Point1 1).

use crate::fem::shape;
use crate::mesh::CellKind;

/// One quadrature point: reference coordinates (unused components 0) and weight.
#[derive(Clone, Copy, Debug)]
pub struct QuadPoint {
    pub xi: [f64; 3],
    pub w: f64,
}

/// Volume (length, area) of the reference cell of `kind`; 1 for Point1.
pub fn reference_volume(kind: CellKind) -> f64 {
    match kind.dim() {
        0 => 1.0,
        1 => 2.0,
        _ => match kind {
            CellKind::Tri3 | CellKind::Tri6 => 0.5,
            CellKind::Tet4 | CellKind::Tet10 => 1.0 / 6.0,
            CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => 4.0,
            CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18 => 1.0,
            CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14 => 4.0 / 3.0,
            _ => 8.0,
        },
    }
}

fn is_simplex(kind: CellKind) -> bool {
    matches!(kind, CellKind::Tri3 | CellKind::Tri6 | CellKind::Tet4 | CellKind::Tet10)
}

fn is_prism(kind: CellKind) -> bool {
    matches!(kind, CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18)
}

fn is_pyramid(kind: CellKind) -> bool {
    matches!(kind, CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14)
}

/// A rule on the reference cell of `kind` exact for polynomials of total degree <= degree on
/// simplices (Tri up to at least degree 8, Tet up to at least degree 6; above that return the highest
/// you have) and of degree <= degree in each variable on Line/Quad/Hex (Gauss–Legendre, any degree).
/// Point1: one point, weight 1.
///
/// Here simplices have rules of any degree: symmetric tables up to degree 8
/// (Tri) and 6 (Tet), collapsed Gauss–Legendre product rules above.
///
/// Prisms: exact for ξ^i η^j ζ^k with i + j <= degree and k <= degree (the
/// triangle's rule of that degree times Gauss–Legendre). Pyramids: exact
/// for every polynomial of total degree <= degree, and for the rational
/// functions whose pull-back to the cube `a^i b^j (1 - ζ)^m ζ^k` (with the
/// Jacobian) has i, j <= degree and m + k <= degree + 2, which includes the
/// products of the pyramids' basis functions (see the module doc).
///
/// Each (kind, degree) is computed once and kept: a symmetric table is
/// expanded from its orbits by permutations, which cost more than the cell
/// it integrates (the 86k tunnel asked for the degree-5 tet rule once per
/// cell, three times over, in its block table: 0.5 s).
pub fn rule(kind: CellKind, degree: usize) -> Vec<QuadPoint> {
    type Kept = Vec<((CellKind, usize), Vec<QuadPoint>)>;
    static KEPT: std::sync::Mutex<Kept> = std::sync::Mutex::new(Vec::new());
    let lock = || KEPT.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some((_, points)) = lock().iter().find(|(key, _)| *key == (kind, degree)) {
        return points.clone();
    }
    // computed unlocked: a prism's rule asks for its triangle's
    let points = computed_rule(kind, degree);
    lock().push(((kind, degree), points.clone()));
    points
}

fn computed_rule(kind: CellKind, degree: usize) -> Vec<QuadPoint> {
    let d = kind.dim();
    if d == 0 {
        return vec![QuadPoint { xi: [0.0; 3], w: 1.0 }];
    }
    if is_prism(kind) {
        return prism_rule(degree, degree / 2 + 1);
    }
    if is_pyramid(kind) {
        return pyramid_rule(degree / 2 + 1, degree / 2 + 2);
    }
    if is_simplex(kind) {
        let table = if d == 2 { tri_table(degree) } else { tet_table(degree) };
        return match table {
            Some(orbits) => expand_orbits(d, orbits),
            None => collapsed_rule(d, degree),
        };
    }
    tensor_gauss(d, degree / 2 + 1)
}

/// The rule for element stiffness: integrates B^T D B exactly on undistorted (affine) shapes:
/// Tri3/Tet4 degree 0, Tri6/Tet10 degree 2, Quad4/Hex8 2 points per direction, Quad8/Quad9/Hex20/Hex27 3 per direction.
///
/// Lines (not used for stiffness, but given for completeness and for
/// extrapolation) follow the Quad pattern: Line2 2 points, Line3 3 points;
/// Point1 its single point.
///
/// Prisms: Prism6 the triangle's degree-2 rule times 2 Gauss points (6
/// points: B^T D B is of degree 2 in (ξ, η) and in ζ), Prism15/Prism18 its
/// degree-4 rule times 3 (18 points: degree 4 and 4). Pyramids, collapsed
/// (see the module doc): Pyramid5 2 x 2 x 2, Pyramid13/Pyramid14 3 x 3 x 3.
pub fn stiffness_rule(kind: CellKind) -> Vec<QuadPoint> {
    match kind {
        CellKind::Prism6 => prism_rule(2, 2),
        CellKind::Prism15 | CellKind::Prism18 => prism_rule(4, 3),
        CellKind::Pyramid5 => pyramid_rule(2, 2),
        CellKind::Pyramid13 | CellKind::Pyramid14 => pyramid_rule(3, 3),
        CellKind::Point1 | CellKind::Tri3 | CellKind::Tet4 => rule(kind, 0),
        CellKind::Tri6 | CellKind::Tet10 => rule(kind, 2),
        CellKind::Line2 | CellKind::Quad4 | CellKind::Hex8 => tensor_gauss(kind.dim(), 2),
        CellKind::Line3 | CellKind::Quad8 | CellKind::Quad9 | CellKind::Hex20 | CellKind::Hex27 => {
            tensor_gauss(kind.dim(), 3)
        }
    }
}

/// Extrapolation from the quadrature points of `points` to the element's nodes: a row-major
/// kind.n_nodes() x points.len() matrix E with nodal = E * values_at_points. Least-squares fit of the
/// point values in the element's own shape functions when points.len() >= n_nodes and the fit is
/// well posed, otherwise in the shape functions of its linear (corner-node) sibling (Tri6→Tri3,
/// Tet10→Tet4, Quad8→Quad4, ...; a single point gives a constant), then evaluated at every node.
/// Must reproduce exactly any field the fit basis contains.
///
/// When even the linear fit is not possible (too few points, or points that
/// do not determine it), the fit is the constant mean of the point values.
/// No points gives an n_nodes x 0 (empty) matrix.
pub fn extrapolation(kind: CellKind, points: &[QuadPoint]) -> Vec<f64> {
    let nn = kind.n_nodes();
    let m = points.len();
    if m == 0 {
        return Vec::new();
    }
    let finite = points.iter().all(|p| p.xi.iter().all(|v| v.is_finite()));
    let lin = shape::linear_sibling(kind);
    let sibling = (lin != kind).then_some(lin);
    if finite {
        for basis in std::iter::once(kind).chain(sibling) {
            if m >= basis.n_nodes() {
                if let Some(e) = fit_in_basis(kind, basis, points) {
                    return e;
                }
            }
        }
    }
    // Constant fit: every node gets the mean.
    vec![1.0 / m as f64; nn * m]
}

/// E = B_nodes * pinv(A) where `A[q][b] = N^basis_b(xi_q)` and
/// `B_nodes[i][b] = N^basis_b(node_i of kind)`; None if A is rank deficient
/// or badly conditioned.
fn fit_in_basis(kind: CellKind, basis: CellKind, points: &[QuadPoint]) -> Option<Vec<f64>> {
    use nalgebra::DMatrix;
    let m = points.len();
    let k = basis.n_nodes();
    let nn = kind.n_nodes();
    let mut nb = vec![0.0; k];
    let mut dnb = vec![[0.0; 3]; k];
    let mut a = DMatrix::<f64>::zeros(m, k);
    for (q, p) in points.iter().enumerate() {
        shape::eval(basis, p.xi, &mut nb, &mut dnb);
        for b in 0..k {
            a[(q, b)] = nb[b];
        }
    }
    // pinv(A) = R^-1 Q^T from a Householder QR (A has full column rank
    // when the fit is well posed; k <= m here).
    let qr = a.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    let rmax = r.diagonal().iter().fold(0.0f64, |x, v| x.max(v.abs()));
    if !r.diagonal().iter().all(|v| v.abs() > 1e-10 * rmax) {
        return None;
    }
    let pinv = r.solve_upper_triangular(&q.transpose())?;
    // Well posed: the condition number (bounded by |A|_F |pinv|_F) is moderate.
    let cond = a.norm() * pinv.norm();
    if !cond.is_finite() || cond >= 1e8 {
        return None;
    }
    let mut e = vec![0.0; nn * m];
    for (i, &node) in shape::reference_nodes(kind).iter().enumerate() {
        shape::eval(basis, node, &mut nb, &mut dnb);
        for q in 0..m {
            e[i * m + q] = (0..k).map(|b| nb[b] * pinv[(b, q)]).sum();
        }
    }
    Some(e)
}

// ---------------------------------------------------------------------------
// Gauss–Legendre
// ---------------------------------------------------------------------------

/// The n-point Gauss–Legendre rule on [-1, 1] as (node, weight), nodes
/// increasing; exact for degree 2n - 1. n = 0 gives an empty rule.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = vec![(0.0, 0.0); n];
    // (P_n(z), P_{n-1}(z)) by the three-term recurrence.
    let legendre = |z: f64| -> (f64, f64) {
        let (mut p0, mut p1) = (1.0, z);
        for j in 2..=n {
            let jf = j as f64;
            let p2 = ((2.0 * jf - 1.0) * z * p1 - (jf - 1.0) * p0) / jf;
            p0 = p1;
            p1 = p2;
        }
        (p1, p0)
    };
    let nf = n as f64;
    for i in 0..n / 2 {
        // i-th largest root, by Newton from the usual cosine guess;
        // P_n' = n (z P_n - P_{n-1}) / (z^2 - 1).
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut converged = 0;
        for _ in 0..100 {
            let (p, pm) = legendre(z);
            let dp = nf * (z * p - pm) / (z * z - 1.0);
            let dz = p / dp;
            z -= dz;
            // Two more steps once converged, to settle the last bits.
            if dz.abs() <= 1e-15 {
                converged += 1;
                if converged == 3 {
                    break;
                }
            }
        }
        // At a root, P_n' = n P_{n-1} / (1 - z^2): w = 2 (1 - z^2) / (n P_{n-1})^2.
        let (_, pm) = legendre(z);
        let w = 2.0 * (1.0 - z * z) / (nf * pm).powi(2);
        out[i] = (-z, w);
        out[n - 1 - i] = (z, w);
    }
    if n % 2 == 1 {
        // The middle root is 0 exactly.
        let (_, pm) = legendre(0.0);
        out[n / 2] = (0.0, 2.0 / (nf * pm).powi(2));
    }
    out
}

/// Tensor-product Gauss–Legendre rule with `n` points per direction on [-1,1]^d.
fn tensor_gauss(d: usize, n: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n);
    let mut out = Vec::with_capacity(n.pow(d as u32));
    let nz = if d >= 3 { n } else { 1 };
    let ny = if d >= 2 { n } else { 1 };
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..n {
                let mut xi = [g[i].0, 0.0, 0.0];
                let mut w = g[i].1;
                if d >= 2 {
                    xi[1] = g[j].0;
                    w *= g[j].1;
                }
                if d >= 3 {
                    xi[2] = g[k].0;
                    w *= g[k].1;
                }
                out.push(QuadPoint { xi, w });
            }
        }
    }
    out
}

/// The prism's rule: the triangle's rule of total degree `tri_degree`
/// times `n` Gauss–Legendre points along ζ.
fn prism_rule(tri_degree: usize, n: usize) -> Vec<QuadPoint> {
    let tri = rule(CellKind::Tri3, tri_degree);
    let line = gauss_legendre(n);
    let mut out = Vec::with_capacity(tri.len() * n);
    for &(z, wz) in &line {
        for t in &tri {
            out.push(QuadPoint { xi: [t.xi[0], t.xi[1], z], w: t.w * wz });
        }
    }
    out
}

/// The pyramid's collapsed rule: `n_ab` Gauss–Legendre points in each of
/// a, b ∈ [-1, 1] and `n_z` in ζ ∈ [0, 1]; the point (a (1 - ζ), b (1 - ζ),
/// ζ) with weight `w_a w_b w_ζ (1 - ζ)²`.
fn pyramid_rule(n_ab: usize, n_z: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n_ab);
    let gz: Vec<(f64, f64)> = gauss_legendre(n_z).into_iter().map(|(t, w)| (0.5 * (t + 1.0), 0.5 * w)).collect();
    let mut out = Vec::with_capacity(n_ab * n_ab * n_z);
    for &(z, wz) in &gz {
        let r = 1.0 - z;
        for &(b, wb) in &g {
            for &(a, wa) in &g {
                out.push(QuadPoint { xi: [a * r, b * r, z], w: wa * wb * wz * r * r });
            }
        }
    }
    out
}

/// Collapsed (Duffy) product rule on the unit simplex of dimension d (2 or 3),
/// exact for total degree `degree`: x = u, y = (1-u) v [, z = (1-u)(1-v) w]
/// with Jacobian (1-u) [(1-u)^2 (1-v)], Gauss–Legendre in each of u, v, w.
fn collapsed_rule(d: usize, degree: usize) -> Vec<QuadPoint> {
    // Degree of the pulled-back integrand in u, v, w: degree + (d - 1), degree + (d - 2), ...
    let on01 = |n: usize| -> Vec<(f64, f64)> {
        gauss_legendre(n).into_iter().map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w)).collect()
    };
    let gu = on01((degree + d - 1) / 2 + 1);
    let gv = on01((degree + d - 2) / 2 + 1);
    let mut out = Vec::new();
    if d == 2 {
        for &(u, wu) in &gu {
            for &(v, wv) in &gv {
                out.push(QuadPoint { xi: [u, (1.0 - u) * v, 0.0], w: wu * wv * (1.0 - u) });
            }
        }
    } else {
        let gw = on01(degree / 2 + 1);
        for &(u, wu) in &gu {
            for &(v, wv) in &gv {
                for &(t, wt) in &gw {
                    out.push(QuadPoint {
                        xi: [u, (1.0 - u) * v, (1.0 - u) * (1.0 - v) * t],
                        w: wu * wv * wt * (1.0 - u) * (1.0 - u) * (1.0 - v),
                    });
                }
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------
// Symmetric simplex rules
// ---------------------------------------------------------------------------

/// One symmetry orbit of a simplex rule, in barycentric coordinates, with
/// the weight of each of its points as a fraction of the cell volume.
#[derive(Clone, Copy, Debug)]
enum Orbit {
    /// The centroid.
    Centre(f64),
    /// Tri: permutations of (a, a, 1-2a).
    S21(f64, f64),
    /// Tri: permutations of (a, b, 1-a-b).
    S111(f64, f64, f64),
    /// Tet: permutations of (a, a, a, 1-3a).
    S31(f64, f64),
    /// Tet: permutations of (a, a, 1/2-a, 1/2-a).
    S22(f64, f64),
    /// Tet: permutations of (a, a, b, 1-2a-b).
    S211(f64, f64, f64),
}

// Triangle rules (weights: fractions of the area, summing to 1).
const TRI_1: &[Orbit] = &[Orbit::Centre(1.0)];
const TRI_2: &[Orbit] = &[Orbit::S21(1.0 / 6.0, 1.0 / 3.0)];
const TRI_4: &[Orbit] =
    &[Orbit::S21(0.4459484909159647, 0.223381589678011), Orbit::S21(0.09157621350977108, 0.10995174365532236)];
/// Radon's 7-point rule: a = (6 ∓ √15)/21, w = (155 ∓ √15)/1200.
const TRI_5: &[Orbit] = &[
    Orbit::Centre(0.225),
    Orbit::S21(0.10128650732345633, 0.12593918054482717),
    Orbit::S21(0.47014206410511505, 0.13239415278850616),
];
const TRI_6: &[Orbit] = &[
    Orbit::S21(0.06308901449150332, 0.05084490637020811),
    Orbit::S21(0.24928674517090718, 0.11678627572638628),
    Orbit::S111(0.053145049844813455, 0.3103524510337874, 0.08285107561836946),
];
const TRI_8: &[Orbit] = &[
    Orbit::Centre(0.144315607677655),
    Orbit::S21(0.4592925882926284, 0.09509163426737555),
    Orbit::S21(0.17056930775164908, 0.1032173705347338),
    Orbit::S21(0.05054722831703263, 0.032458497623209265),
    Orbit::S111(0.008394777409819233, 0.2631128296349595, 0.02723031417439814),
];

// Tetrahedron rules (weights: fractions of the volume, summing to 1).
const TET_1: &[Orbit] = &[Orbit::Centre(1.0)];
/// a = (5 - √5)/20.
const TET_2: &[Orbit] = &[Orbit::S31(0.1381966011250105, 0.25)];
const TET_5: &[Orbit] = &[
    Orbit::S31(0.09273525031089146, 0.07349304311636226),
    Orbit::S31(0.3108859192633, 0.11268792571801631),
    Orbit::S22(0.04550370412564836, 0.042546020777081),
];
const TET_6: &[Orbit] = &[
    Orbit::S31(0.21460287125920846, 0.03992275025815026),
    Orbit::S31(0.040673958534602914, 0.010077211055318117),
    Orbit::S31(0.32233789014227754, 0.05535718154365085),
    Orbit::S211(0.06366100187502391, 0.26967233145831065, 0.048214285714293606),
];

fn tri_table(degree: usize) -> Option<&'static [Orbit]> {
    match degree {
        0 | 1 => Some(TRI_1),
        2 => Some(TRI_2),
        3 | 4 => Some(TRI_4),
        5 => Some(TRI_5),
        6 => Some(TRI_6),
        7 | 8 => Some(TRI_8),
        _ => None,
    }
}

fn tet_table(degree: usize) -> Option<&'static [Orbit]> {
    match degree {
        0 | 1 => Some(TET_1),
        2 => Some(TET_2),
        3..=5 => Some(TET_5),
        6 => Some(TET_6),
        _ => None,
    }
}

/// The distinct permutations of the first `n` entries of `t` (n <= 4).
fn distinct_permutations(t: [f64; 4], n: usize) -> Vec<[f64; 4]> {
    let mut out: Vec<[f64; 4]> = Vec::new();
    // Every index tuple in 0..n (as base-n digits of `code`), keeping the
    // permutations, then the distinct resulting tuples.
    for code in 0..n.pow(n as u32) {
        let mut idx = [0usize; 4];
        let mut c = code;
        for slot in idx.iter_mut().take(n) {
            *slot = c % n;
            c /= n;
        }
        if (0..n).any(|x| (0..x).any(|y| idx[x] == idx[y])) {
            continue;
        }
        let mut p = [0.0; 4];
        for s in 0..n {
            p[s] = t[idx[s]];
        }
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

/// The points of a symmetric rule on the unit simplex of dimension d:
/// barycentric (L0, L1, ...) -> xi = (L1, L2, L3).
fn expand_orbits(d: usize, orbits: &[Orbit]) -> Vec<QuadPoint> {
    let vol = if d == 2 { 0.5 } else { 1.0 / 6.0 };
    let mut out = Vec::new();
    for &o in orbits {
        let (bary, w) = match o {
            Orbit::Centre(w) => ([1.0 / (d as f64 + 1.0); 4], w),
            Orbit::S21(a, w) => ([a, a, 1.0 - 2.0 * a, 0.0], w),
            Orbit::S111(a, b, w) => ([a, b, 1.0 - a - b, 0.0], w),
            Orbit::S31(a, w) => ([a, a, a, 1.0 - 3.0 * a], w),
            Orbit::S22(a, w) => ([a, a, 0.5 - a, 0.5 - a], w),
            Orbit::S211(a, b, w) => ([a, a, b, 1.0 - 2.0 * a - b], w),
        };
        for p in distinct_permutations(bary, d + 1) {
            let mut xi = [0.0; 3];
            xi[..d].copy_from_slice(&p[1..=d]);
            out.push(QuadPoint { xi, w: w * vol });
        }
    }
    out
}

// ---------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    fn factorial(n: usize) -> f64 {
        (1..=n).map(|i| i as f64).product()
    }

    /// ∫ t^k over [-1, 1].
    fn line_moment(k: usize) -> f64 {
        if k % 2 == 1 {
            0.0
        } else {
            2.0 / (k as f64 + 1.0)
        }
    }

    /// ∫_0^1 z^k (1 - z)^m dz = k! m! / (k + m + 1)!.
    fn beta(k: usize, m: usize) -> f64 {
        factorial(k) * factorial(m) / factorial(k + m + 1)
    }

    /// Exact integral of xi^e[0] eta^e[1] zeta^e[2] over the reference cell.
    fn exact_monomial(kind: CellKind, e: [usize; 3]) -> f64 {
        let d = kind.dim();
        if is_prism(kind) {
            // the triangle's moment times the line's
            return factorial(e[0]) * factorial(e[1]) / factorial(e[0] + e[1] + 2) * line_moment(e[2]);
        }
        if is_pyramid(kind) {
            // ξ = a (1 - ζ), η = b (1 - ζ), dV = (1 - ζ)² da db dζ
            return line_moment(e[0]) * line_moment(e[1]) * beta(e[2], e[0] + e[1] + 2);
        }
        if is_simplex(kind) {
            // ∫ x^a y^b z^c over the unit simplex = a! b! c! / (a + b + c + d)!
            factorial(e[0]) * factorial(e[1]) * factorial(e[2]) / factorial(e[0] + e[1] + e[2] + d)
        } else {
            (0..d).map(|j| if e[j] % 2 == 1 { 0.0 } else { 2.0 / (e[j] as f64 + 1.0) }).product()
        }
    }

    fn integrate(points: &[QuadPoint], e: [usize; 3]) -> f64 {
        points
            .iter()
            .map(|p| p.w * p.xi[0].powi(e[0] as i32) * p.xi[1].powi(e[1] as i32) * p.xi[2].powi(e[2] as i32))
            .sum()
    }

    /// Exponents of the monomials a rule of `degree` must integrate exactly.
    fn exponents(kind: CellKind, degree: usize) -> Vec<[usize; 3]> {
        let d = kind.dim();
        let r = |j: usize| if j < d { degree } else { 0 };
        let mut out = Vec::new();
        for a in 0..=r(0) {
            for b in 0..=r(1) {
                for c in 0..=r(2) {
                    // simplices and pyramids: total degree; prisms: (ξ, η) and ζ apart
                    let beyond = ((is_simplex(kind) || is_pyramid(kind)) && a + b + c > degree)
                        || (is_prism(kind) && a + b > degree);
                    if !beyond {
                        out.push([a, b, c]);
                    }
                }
            }
        }
        out
    }

    /// One representative per reference cell.
    const CELLS: [CellKind; 7] = [
        CellKind::Line2,
        CellKind::Tri3,
        CellKind::Quad4,
        CellKind::Tet4,
        CellKind::Hex8,
        CellKind::Prism6,
        CellKind::Pyramid5,
    ];

    fn max_degree(kind: CellKind) -> usize {
        match kind.dim() {
            1 => 25,
            2 => 14,
            _ => 10,
        }
    }

    #[test]
    fn point1_is_one_point_of_weight_one() {
        let r = rule(CellKind::Point1, 5);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].w, 1.0);
        assert_eq!(stiffness_rule(CellKind::Point1).len(), 1);
    }

    #[test]
    fn weights_sum_to_the_reference_volume() {
        for kind in CellKind::ALL {
            for degree in 0..=max_degree(shape::linear_sibling(kind)).min(14) {
                let s: f64 = rule(kind, degree).iter().map(|p| p.w).sum();
                let v = reference_volume(kind);
                assert!((s - v).abs() < 1e-14 * v, "{} degree {}: {}", kind.name(), degree, s);
            }
        }
        assert_eq!(reference_volume(CellKind::Line3), 2.0);
        assert_eq!(reference_volume(CellKind::Tri6), 0.5);
        assert_eq!(reference_volume(CellKind::Quad9), 4.0);
        assert_eq!(reference_volume(CellKind::Tet10), 1.0 / 6.0);
        assert_eq!(reference_volume(CellKind::Hex27), 8.0);
    }

    #[test]
    fn rules_integrate_monomials_exactly_up_to_their_degree() {
        for kind in CELLS {
            for degree in 0..=max_degree(kind) {
                let r = rule(kind, degree);
                for e in exponents(kind, degree) {
                    let got = integrate(&r, e);
                    let want = exact_monomial(kind, e);
                    assert!(
                        (got - want).abs() <= 1e-13,
                        "{} degree {} ({} points), monomial {:?}: {} vs {} (error {:e})",
                        kind.name(),
                        degree,
                        r.len(),
                        e,
                        got,
                        want,
                        got - want
                    );
                }
            }
        }
    }

    #[test]
    fn rules_are_not_overexact_by_accident_of_the_test() {
        // Sanity check of the test itself: a degree-1 rule must fail on a
        // quadratic, so the exactness test above can detect a too weak rule.
        for kind in CELLS {
            let r = rule(kind, 1);
            let e = [2, 0, 0];
            assert!((integrate(&r, e) - exact_monomial(kind, e)).abs() > 1e-3, "{}", kind.name());
        }
    }

    /// The pyramid rules integrate the rational functions of the pyramids'
    /// spaces: `q^m ξ^i η^j ζ^k` with q = ξη / (1 - ζ) pulls back to
    /// `a^(m+i) b^(m+j) (1 - ζ)^(m+i+j+2) ζ^k`.
    #[test]
    fn pyramid_rules_integrate_the_rational_functions_of_their_degree() {
        for degree in 0..=8 {
            let r = rule(CellKind::Pyramid5, degree);
            for m in 1..=2usize {
                for i in 0..=degree.saturating_sub(m) {
                    for k in 0..=degree {
                        // within the promise: degree m + i in a, and m + i + 2 + k
                        // in ζ with the Jacobian, at most degree + 2
                        if m + i + k > degree {
                            continue;
                        }
                        let got: f64 = r
                            .iter()
                            .map(|p| {
                                let [x, y, z] = p.xi;
                                let q = x * y / (1.0 - z);
                                p.w * q.powi(m as i32) * x.powi(i as i32) * z.powi(k as i32)
                            })
                            .sum();
                        let want = line_moment(m + i) * line_moment(m) * beta(k, m + i + 2);
                        assert!((got - want).abs() < 1e-14, "degree {degree}: q^{m} x^{i} z^{k}: {got} vs {want}");
                    }
                }
            }
            // no point at the apex, positive weights, all inside
            for p in &r {
                assert!(p.w > 0.0 && p.xi[2] < 1.0 && shape::inside_reference(CellKind::Pyramid5, p.xi, 0.0));
            }
        }
    }

    #[test]
    fn prism_rules_have_positive_weights_and_interior_points() {
        for degree in 0..=10 {
            for p in rule(CellKind::Prism6, degree) {
                assert!(
                    p.w > 0.0 && shape::inside_reference(CellKind::Prism6, p.xi, 0.0),
                    "degree {degree}: {:?}",
                    p.xi
                );
            }
        }
    }

    #[test]
    fn simplex_rules_have_positive_weights_and_interior_points() {
        for kind in [CellKind::Tri3, CellKind::Tet4] {
            for degree in 0..=max_degree(kind) {
                for p in rule(kind, degree) {
                    assert!(p.w > 0.0, "{} degree {}", kind.name(), degree);
                    assert!(shape::inside_reference(kind, p.xi, 0.0), "{} degree {}: {:?}", kind.name(), degree, p.xi);
                    assert!(p.xi[..kind.dim()].iter().all(|&t| t > 0.0) && p.xi.iter().sum::<f64>() < 1.0);
                }
            }
        }
    }

    #[test]
    fn symmetric_tables_have_the_documented_sizes() {
        let sizes = |kind: CellKind, degrees: std::ops::RangeInclusive<usize>| -> Vec<usize> {
            degrees.map(|k| rule(kind, k).len()).collect()
        };
        assert_eq!(sizes(CellKind::Tri3, 0..=8), vec![1, 1, 3, 6, 6, 7, 12, 16, 16]);
        assert_eq!(sizes(CellKind::Tet4, 0..=6), vec![1, 1, 4, 14, 14, 14, 24]);
        // Each table point is distinct.
        for (kind, max) in [(CellKind::Tri3, 8), (CellKind::Tet4, 6)] {
            for degree in 0..=max {
                let r = rule(kind, degree);
                for i in 0..r.len() {
                    for j in 0..i {
                        assert!(r[i].xi != r[j].xi, "{} degree {}", kind.name(), degree);
                    }
                }
            }
        }
    }

    #[test]
    fn gauss_legendre_known_values() {
        let g = gauss_legendre(2);
        let a = 1.0 / 3f64.sqrt();
        assert!((g[0].0 + a).abs() < 2e-16 && (g[1].0 - a).abs() < 2e-16);
        assert!((g[0].1 - 1.0).abs() < 1e-15);
        let g = gauss_legendre(3);
        assert_eq!(g[1].0, 0.0);
        assert!((g[1].1 - 8.0 / 9.0).abs() < 1e-15);
        assert!((g[2].0 - 0.6f64.sqrt()).abs() < 1e-15);
        assert!((g[2].1 - 5.0 / 9.0).abs() < 1e-15);
        assert_eq!(gauss_legendre(1), vec![(0.0, 2.0)]);
        // A long rule: symmetric, increasing, exact.
        let g = gauss_legendre(40);
        for i in 0..40 {
            assert_eq!(g[i].0, -g[39 - i].0);
            if i > 0 {
                assert!(g[i].0 > g[i - 1].0);
            }
        }
        let s: f64 = g.iter().map(|(x, w)| w * x.powi(78)).sum();
        assert!((s - 2.0 / 79.0).abs() < 1e-14);
    }

    #[test]
    fn stiffness_rules_have_the_documented_sizes() {
        let want = [
            (CellKind::Point1, 1),
            (CellKind::Line2, 2),
            (CellKind::Line3, 3),
            (CellKind::Tri3, 1),
            (CellKind::Tri6, 3),
            (CellKind::Quad4, 4),
            (CellKind::Quad8, 9),
            (CellKind::Quad9, 9),
            (CellKind::Tet4, 1),
            (CellKind::Tet10, 4),
            (CellKind::Hex8, 8),
            (CellKind::Hex20, 27),
            (CellKind::Hex27, 27),
            (CellKind::Prism6, 6),
            (CellKind::Prism15, 18),
            (CellKind::Prism18, 18),
            (CellKind::Pyramid5, 8),
            (CellKind::Pyramid13, 27),
            (CellKind::Pyramid14, 27),
        ];
        assert_eq!(want.len(), CellKind::ALL.len());
        for (kind, n) in want {
            assert_eq!(stiffness_rule(kind).len(), n, "{}", kind.name());
        }
    }

    /// ∫ dN_a/dxi_i dN_b/dxi_j over the reference cell (B^T D B on an
    /// undistorted element) is integrated exactly by the stiffness rule.
    #[test]
    fn stiffness_rule_integrates_gradient_products_exactly() {
        for kind in CellKind::ALL.into_iter().filter(|k| k.dim() >= 1) {
            let nn = kind.n_nodes();
            let d = kind.dim();
            let gram = |r: &[QuadPoint]| -> Vec<f64> {
                let mut g = vec![0.0; nn * nn * d * d];
                let mut n = vec![0.0; nn];
                let mut dn = vec![[0.0; 3]; nn];
                for p in r {
                    shape::eval(kind, p.xi, &mut n, &mut dn);
                    for a in 0..nn {
                        for b in 0..nn {
                            for i in 0..d {
                                for j in 0..d {
                                    g[((a * nn + b) * d + i) * d + j] += p.w * dn[a][i] * dn[b][j];
                                }
                            }
                        }
                    }
                }
                g
            };
            let got = gram(&stiffness_rule(kind));
            let want = gram(&rule(kind, 8));
            for (x, y) in got.iter().zip(&want) {
                assert!((x - y).abs() < 1e-13, "{}: {} vs {}", kind.name(), x, y);
            }
        }
    }

    fn apply(e: &[f64], values: &[f64], nn: usize) -> Vec<f64> {
        let m = values.len();
        assert_eq!(e.len(), nn * m);
        (0..nn).map(|i| (0..m).map(|q| e[i * m + q] * values[q]).sum()).collect()
    }

    #[test]
    fn extrapolation_reproduces_constant_and_linear_fields() {
        for kind in CellKind::ALL {
            let pts = stiffness_rule(kind);
            let nn = kind.n_nodes();
            let e = extrapolation(kind, &pts);
            assert_eq!(e.len(), nn * pts.len());
            // Constant.
            let nodal = apply(&e, &vec![2.5; pts.len()], nn);
            for v in &nodal {
                assert!((v - 2.5).abs() < 1e-13, "{}: constant gives {}", kind.name(), v);
            }
            // Linear, wherever the fit basis contains the linears, i.e.
            // wherever there are at least as many points as corners (the
            // one-point rules of Tri3/Tet4/Point1 can only give a constant).
            if pts.len() >= kind.n_corners() && kind.dim() >= 1 {
                let f = |x: [f64; 3]| 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
                let vals: Vec<f64> = pts.iter().map(|p| f(p.xi)).collect();
                let nodal = apply(&e, &vals, nn);
                for (i, node) in shape::reference_nodes(kind).iter().enumerate() {
                    assert!(
                        (nodal[i] - f(*node)).abs() < 1e-12,
                        "{} node {}: {} vs {}",
                        kind.name(),
                        i,
                        nodal[i],
                        f(*node)
                    );
                }
            } else {
                assert!(matches!(kind, CellKind::Point1 | CellKind::Tri3 | CellKind::Tet4), "{}", kind.name());
            }
        }
    }

    #[test]
    fn extrapolation_reproduces_fields_of_its_fit_basis() {
        // Own basis (enough points): any shape-function combination, e.g. a
        // field that is N_a of the element itself, comes back as its nodal values.
        for kind in [CellKind::Quad8, CellKind::Quad9, CellKind::Hex20, CellKind::Hex27, CellKind::Line3] {
            let pts = stiffness_rule(kind);
            assert!(pts.len() >= kind.n_nodes());
            let nn = kind.n_nodes();
            let e = extrapolation(kind, &pts);
            let mut n = vec![0.0; nn];
            let mut dn = vec![[0.0; 3]; nn];
            let nodal_in: Vec<f64> = (0..nn).map(|a| (a as f64 * 0.37).sin()).collect();
            let vals: Vec<f64> = pts
                .iter()
                .map(|p| {
                    shape::eval(kind, p.xi, &mut n, &mut dn);
                    n.iter().zip(&nodal_in).map(|(x, y)| x * y).sum()
                })
                .collect();
            let nodal = apply(&e, &vals, nn);
            for a in 0..nn {
                assert!((nodal[a] - nodal_in[a]).abs() < 1e-12, "{} node {}", kind.name(), a);
            }
        }
        // Linear sibling (Tri6 from 3 points, Tet10 from 4): linear fields at
        // the corners and mid-edge nodes, checked above; here the fit is an
        // interpolation, so the corner values are the linear interpolant.
        for kind in [CellKind::Tri6, CellKind::Tet10] {
            let pts = stiffness_rule(kind);
            assert_eq!(pts.len(), kind.n_corners());
            let e = extrapolation(kind, &pts);
            // Mid-edge rows are the averages of their corner rows.
            let m = pts.len();
            let edges: &[[usize; 2]] = if kind == CellKind::Tri6 { &shape::TRI_EDGES } else { &shape::TET_EDGES };
            for (k, [a, b]) in edges.iter().enumerate() {
                let row = kind.n_corners() + k;
                for q in 0..m {
                    let avg = 0.5 * (e[a * m + q] + e[b * m + q]);
                    assert!((e[row * m + q] - avg).abs() < 1e-13);
                }
            }
        }
    }

    #[test]
    fn extrapolation_falls_back_to_siblings_and_constants() {
        // Quad8 from 2x2 points: too few for Quad8, so bilinear (Quad4) fit.
        let pts = rule(CellKind::Quad8, 2);
        assert_eq!(pts.len(), 4);
        let e = extrapolation(CellKind::Quad8, &pts);
        let f = |x: [f64; 3]| 0.5 - x[0] + 2.0 * x[1] + 0.75 * x[0] * x[1];
        let vals: Vec<f64> = pts.iter().map(|p| f(p.xi)).collect();
        let nodal = apply(&e, &vals, 8);
        for (i, node) in shape::reference_nodes(CellKind::Quad8).iter().enumerate() {
            assert!((nodal[i] - f(*node)).abs() < 1e-13);
        }
        // One point: a constant equal to the value.
        let one = rule(CellKind::Hex20, 0);
        assert_eq!(one.len(), 1);
        let e = extrapolation(CellKind::Hex20, &one);
        assert_eq!(e, vec![1.0; 20]);
        // Points that cannot determine a linear field (all on one line):
        // the mean.
        let line: Vec<QuadPoint> = (0..5).map(|i| QuadPoint { xi: [0.1 * i as f64, 0.0, 0.0], w: 1.0 }).collect();
        let e = extrapolation(CellKind::Tri6, &line);
        for v in e {
            assert!((v - 0.2).abs() < 1e-15);
        }
        // No points: an empty matrix.
        assert!(extrapolation(CellKind::Tet4, &[]).is_empty());
    }
}
