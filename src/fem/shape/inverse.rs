//! The inverse of the reference map: [`locate`] finds the reference
//! coordinates of a physical point in a cell by Newton on
//! `x(xi) = Σ N_a(xi) x_a`, [`map_point`] evaluates the map. Both work in
//! coordinates relative to the cell's first node, so that a cell at map
//! coordinates (x ~ 4e6, h ~ 0.1) keeps the digits of its size: the
//! residual and the Jacobian are differences of nearby coordinates, which
//! subtracting the first node makes exact before anything is summed.

use super::{eval, inside_reference, reference_centre};
use crate::mesh::CellKind;

/// Tolerance (in reference coordinates) of the "inside" test of [`locate`].
pub const LOCATE_TOL: f64 = 1e-8;

/// Physical point x(xi) = Σ N_a(xi) `coords[a]` of the cell with node
/// coordinates `coords` (gmsh order).
pub fn map_point(kind: CellKind, coords: &[[f64; 3]], xi: [f64; 3]) -> [f64; 3] {
    debug_assert_eq!(coords.len(), kind.n_nodes());
    let nn = kind.n_nodes();
    let mut n = [0.0; 27];
    let mut dn = [[0.0; 3]; 27];
    eval(kind, xi, &mut n[..nn], &mut dn[..nn]);
    let o = coords[0];
    let mut x = [0.0; 3];
    for (na, c) in n[..nn].iter().zip(coords) {
        for i in 0..3 {
            x[i] += na * (c[i] - o[i]);
        }
    }
    std::array::from_fn(|i| o[i] + x[i])
}

/// Inverse map: the reference coordinates of physical point x in the cell whose node
/// coordinates are `coords` (gmsh order; for 2D kinds z is ignored), by Newton; Some(xi) only if
/// x lies inside the cell or on its boundary (tolerance ~1e-8 in reference coordinates). Only for
/// cells whose dim equals the space dimension (2D cells in the plane z=0 with 2D coordinates; 3D cells).
///
/// Line kinds are handled the same way on the x axis (y, z ignored); Point1
/// always gives None. Newton starts at the reference centre, with a simple
/// backtracking on the residual; a cell whose Jacobian is singular on the
/// way, or no convergence within 50 steps, gives None.
pub fn locate(kind: CellKind, coords: &[[f64; 3]], x: [f64; 3]) -> Option<[f64; 3]> {
    debug_assert_eq!(coords.len(), kind.n_nodes(), "locate: wrong number of coordinates for {}", kind.name());
    let d = kind.dim();
    if d == 0 || coords.len() != kind.n_nodes() {
        return None;
    }
    // 1. the cell's length scale, for the residual tolerance
    let h = cell_size(coords, d)?;
    // 2. Newton from the reference centre
    let mut residual = Residual::new(kind, coords, x);
    let (xi, rn) = newton(&mut residual, h)?;
    // 3. a converged point inside the cell
    if rn > 1e-10 * h {
        return None;
    }
    if inside_reference(kind, xi, LOCATE_TOL) {
        Some(xi)
    } else {
        None
    }
}

/// The diagonal of the cell's box in its `d` dimensions; None when it is
/// zero or not finite.
fn cell_size(coords: &[[f64; 3]], d: usize) -> Option<f64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for c in coords {
        for i in 0..d {
            lo[i] = lo[i].min(c[i]);
            hi[i] = hi[i].max(c[i]);
        }
    }
    let h = (0..d).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
    (h.is_finite() && h > 0.0).then_some(h)
}

/// The residual r = x - x(xi) of the inverse map and its Jacobian
/// `J[i][j] = dx_i/dxi_j`, everything relative to the cell's first node.
struct Residual {
    kind: CellKind,
    d: usize,
    nn: usize,
    rel: [[f64; 3]; 27],
    x: [f64; 3],
    n: [f64; 27],
    dn: [[f64; 3]; 27],
}

impl Residual {
    fn new(kind: CellKind, coords: &[[f64; 3]], x: [f64; 3]) -> Residual {
        let o = coords[0];
        let mut rel = [[0.0; 3]; 27];
        for (r, c) in rel.iter_mut().zip(coords) {
            *r = std::array::from_fn(|i| c[i] - o[i]);
        }
        let x: [f64; 3] = std::array::from_fn(|i| x[i] - o[i]);
        Residual { kind, d: kind.dim(), nn: kind.n_nodes(), rel, x, n: [0.0; 27], dn: [[0.0; 3]; 27] }
    }

    /// r at `xi`, and J into `jac` when asked.
    fn at(&mut self, xi: [f64; 3], jac: Option<&mut [[f64; 3]; 3]>) -> [f64; 3] {
        let (d, nn) = (self.d, self.nn);
        eval(self.kind, xi, &mut self.n[..nn], &mut self.dn[..nn]);
        let mut r = [0.0; 3];
        r[..d].copy_from_slice(&self.x[..d]);
        let mut j = [[0.0; 3]; 3];
        for a in 0..nn {
            for i in 0..d {
                r[i] -= self.n[a] * self.rel[a][i];
                for k in 0..d {
                    j[i][k] += self.dn[a][k] * self.rel[a][i];
                }
            }
        }
        if let Some(out) = jac {
            *out = j;
        }
        r
    }

    fn norm(&self, r: &[f64; 3]) -> f64 {
        r[..self.d].iter().map(|v| v * v).sum::<f64>().sqrt()
    }
}

/// Newton on the residual from the reference centre, at most 50 steps,
/// each backtracked: the last iterate and its residual norm; None when the
/// Jacobian turns singular or the residual not finite.
fn newton(residual: &mut Residual, h: f64) -> Option<([f64; 3], f64)> {
    let d = residual.d;
    let mut xi = reference_centre(residual.kind);
    let mut jac = [[0.0; 3]; 3];
    let mut r = residual.at(xi, Some(&mut jac));
    let mut rn = residual.norm(&r);
    for _ in 0..50 {
        let step = solve_small(d, jac, r)?;
        let step_norm = step[..d].iter().map(|v| v * v).sum::<f64>().sqrt();
        let t;
        (xi, t) = backtrack(residual, xi, step, rn);
        r = residual.at(xi, Some(&mut jac));
        rn = residual.norm(&r);
        if !rn.is_finite() {
            return None;
        }
        if t * step_norm <= 1e-14 || rn <= 1e-14 * h {
            break;
        }
    }
    Some((xi, rn))
}

/// Backtracking: the step from `xi` halved while the residual grows above
/// `rn` (down to 1/1024): the new iterate and the step's fraction.
fn backtrack(residual: &mut Residual, xi: [f64; 3], step: [f64; 3], rn: f64) -> ([f64; 3], f64) {
    let mut t = 1.0;
    loop {
        let mut trial = xi;
        for j in 0..residual.d {
            // Keep the iterate in a generous box around the reference cell
            // so that the polynomial map cannot blow up.
            trial[j] = (xi[j] + t * step[j]).clamp(-3.0, 3.0);
        }
        let trial_r = residual.at(trial, None);
        if residual.norm(&trial_r) <= rn || t < 1e-3 {
            return (trial, t);
        }
        t *= 0.5;
    }
}

/// Solves the d x d system a s = b (d <= 3) by Gaussian elimination with
/// partial pivoting; None when a is (numerically) singular.
fn solve_small(d: usize, mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let scale = a[..d].iter().flat_map(|row| row[..d].iter()).fold(0.0f64, |m, v| m.max(v.abs()));
    if !scale.is_finite() || scale <= 0.0 {
        return None;
    }
    for col in 0..d {
        let p = (col..d).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[p][col].abs() <= 1e-13 * scale {
            return None;
        }
        a.swap(col, p);
        b.swap(col, p);
        let pivot_row = a[col];
        for i in col + 1..d {
            let f = a[i][col] / pivot_row[col];
            for (aik, pk) in a[i][col..d].iter_mut().zip(&pivot_row[col..d]) {
                *aik -= f * pk;
            }
            b[i] -= f * b[col];
        }
    }
    let mut s = [0.0; 3];
    for i in (0..d).rev() {
        let mut v = b[i];
        for k in i + 1..d {
            v -= a[i][k] * s[k];
        }
        s[i] = v / a[i][i];
    }
    Some(s)
}
