//! The point of least norm in a polyhedron, `min |x|` subject to
//! `g_i . x <= h_i` (least-distance programming), by Lawson and Hanson's
//! reduction to non-negative least squares (*Solving Least Squares
//! Problems*, 1974, ch. 23: algorithms LDP and NNLS).
//!
//! A junction's tied forces within every pair's limit are such a point
//! ([`super::junction`]): the constraints are cuts of the pairs' Coulomb
//! cones, a few dozen at most, and often nearly parallel (a pair cut again
//! at a shear that has turned a little). NNLS works on the constraints'
//! multipliers and only ever solves with a set of independent columns, so
//! more cuts than unknowns, or cuts that repeat one another, are no harder
//! than a few independent ones.

use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the multipliers' optimality test and of the
/// least-squares solves (the data are scaled to O(1)).
const TOL: f64 = 1e-12;

/// The point of least norm with `g_i . x <= h_i` for every i; None when
/// the constraints leave no point.
///
/// LDP: with `E = [-G^T; -h^T]` and `f = (0, ..., 0, 1)`, the solution u
/// of `min |E u - f|, u >= 0` gives `r = E u - f`; r = 0 when the
/// constraints are inconsistent, and else `x = -r_(1..k) / r_(k+1)`.
pub fn least_norm_point(g: &[DVector<f64>], h: &[f64]) -> Option<DVector<f64>> {
    let k = g.first().map_or(0, |v| v.len());
    // each cut scaled to a unit normal; a cut without a normal holds or never can
    let mut rows: Vec<(DVector<f64>, f64)> = Vec::with_capacity(g.len());
    for (gi, &hi) in g.iter().zip(h) {
        let n = gi.norm();
        if n > 0.0 {
            rows.push((gi / n, hi / n));
        } else if hi < 0.0 {
            return None;
        }
    }
    if rows.is_empty() {
        return Some(DVector::zeros(k));
    }
    let scale = rows.iter().fold(1.0f64, |m, r| m.max(r.1.abs()));
    let e = DMatrix::<f64>::from_fn(k + 1, rows.len(), |i, j| if i < k { -rows[j].0[i] } else { -rows[j].1 / scale });
    let mut f = DVector::<f64>::zeros(k + 1);
    f[k] = 1.0;
    let u = nnls(&e, &f);
    let r = &e * u - &f;
    if r.norm() <= 1e-10 || r[k] >= 0.0 {
        return None;
    }
    // x solves the problem with h scaled by 1/scale: scale it back
    Some(DVector::from_fn(k, |i, _| -r[i] / r[k] * scale))
}

/// Lawson and Hanson's NNLS: `min |E u - f|` over `u >= 0`. Columns enter
/// the passive set P while the gradient `E^T (f - E u)` has a positive
/// part outside it; a least-squares solution on P with a negative entry is
/// cut back to the boundary and the columns it zeroes leave P.
fn nnls(e: &DMatrix<f64>, f: &DVector<f64>) -> DVector<f64> {
    let m = e.ncols();
    let mut u = DVector::<f64>::zeros(m);
    let mut passive = vec![false; m];
    let tol = TOL * e.norm().max(f.norm()).max(f64::MIN_POSITIVE);
    for _ in 0..(3 * m + 10) {
        let w = e.transpose() * (f - e * &u);
        let Some(t) = (0..m).filter(|&j| !passive[j] && w[j] > tol).max_by(|&a, &b| w[a].total_cmp(&w[b])) else {
            return u;
        };
        passive[t] = true;
        for _ in 0..=m {
            let z = solve_on(e, f, &passive);
            if (0..m).all(|j| !passive[j] || z[j] > 0.0) {
                u = z;
                break;
            }
            // step from u towards z until the first passive entry reaches 0
            let alpha = (0..m)
                .filter(|&j| passive[j] && z[j] <= 0.0)
                .map(|j| u[j] / (u[j] - z[j]))
                .fold(f64::INFINITY, f64::min);
            u += (&z - &u) * alpha;
            for j in 0..m {
                if passive[j] && u[j] <= tol {
                    passive[j] = false;
                    u[j] = 0.0;
                }
            }
        }
    }
    u
}

/// The least-squares solution of `E_P z = f` on the passive columns P, zero elsewhere.
fn solve_on(e: &DMatrix<f64>, f: &DVector<f64>, passive: &[bool]) -> DVector<f64> {
    let cols: Vec<usize> = (0..passive.len()).filter(|&j| passive[j]).collect();
    let ep = DMatrix::<f64>::from_fn(e.nrows(), cols.len(), |i, c| e[(i, cols[c])]);
    let zp = (crate::fem::bounded::svd(ep, true, true))
        .and_then(|svd| svd.solve(f, TOL).ok())
        .unwrap_or_else(|| DVector::zeros(cols.len()));
    let mut z = DVector::<f64>::zeros(passive.len());
    for (c, &j) in cols.iter().enumerate() {
        z[j] = zp[c];
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: &[f64]) -> DVector<f64> {
        DVector::from_column_slice(x)
    }

    /// One half-plane away from the origin: the foot of the perpendicular.
    #[test]
    fn one_cut_gives_the_foot_of_the_perpendicular() {
        let x = least_norm_point(&[v(&[3.0, 4.0])], &[-10.0]).expect("a point");
        assert!((&x - v(&[-1.2, -1.6])).norm() < 1e-14, "{x}");
        // the origin itself where it is inside
        let x = least_norm_point(&[v(&[3.0, 4.0])], &[1.0]).expect("a point");
        assert!(x.norm() < 1e-15);
    }

    /// Two cuts meeting at a corner, and the same cuts repeated with
    /// slightly turned normals (more cuts than unknowns): the corner.
    #[test]
    fn a_corner_of_nearly_parallel_cuts() {
        // x >= 1, y >= 2: the corner (1, 2)
        let mut g = vec![v(&[-1.0, 0.0]), v(&[0.0, -1.0])];
        let mut h = vec![-1.0, -2.0];
        for a in [1e-9, 2e-9, -1e-9] {
            g.push(v(&[-1.0, a]));
            h.push(-1.0 + 2.0 * a);
            g.push(v(&[a, -1.0]));
            h.push(-2.0 + a);
        }
        let x = least_norm_point(&g, &h).expect("a point");
        assert!((&x - v(&[1.0, 2.0])).norm() < 1e-12, "{x}");
        for (gi, hi) in g.iter().zip(&h) {
            assert!(gi.dot(&x) <= hi + 1e-12);
        }
    }

    /// x <= -1 and x >= 1 leave nothing.
    #[test]
    fn inconsistent_cuts_leave_no_point() {
        assert!(least_norm_point(&[v(&[1.0]), v(&[-1.0])], &[-1.0, -1.0]).is_none());
        assert!(least_norm_point(&[v(&[0.0, 0.0])], &[-1.0]).is_none());
    }
}
