//! Restarted flexible GMRES (Saad, *Iterative Methods for Sparse Linear
//! Systems*, 2nd ed., Alg. 9.6): right preconditioning, modified
//! Gram-Schmidt Arnoldi, Givens rotations on the Hessenberg matrix. Right
//! preconditioning keeps the monitored residual the true one, `b - A x`.
//!
//! Flexible: a cycle keeps each `z_j = M^-1 v_j` it applied `A` to and
//! steps along them, `x += Z y`, where plain GMRES (Alg. 9.5) keeps the
//! basis alone and steps along `M^-1 (V y)`. The two are one where `M^-1`
//! is linear; the sparse interface's is a factor in single precision
//! (`SingleCholesky`), which rounds what it is given to 24 bits and is
//! as far from linear as that rounding times its condition number. On
//! the 34k tunnel with joints of k_n = 5e7 MPa/m (tests/convergence.rs)
//! plain GMRES ended cycles whose estimate was 1.7e-2 at a true residual
//! of 2.3, or 1.2e-3 at 16: its solves stalled, and on each of six
//! meshes the iteration took the interface for singular. Flexible, each
//! cycle's estimate is its true residual to four digits, and the scene
//! converges in 12 iterations on all six. The price is `restart` vectors
//! more, kept while a cycle runs (docs/convergence.md).
//!
//! The interface systems it serves are unsymmetric where the friction law
//! is linearised (a slipping pair's tangential rows take in its normal
//! force), so conjugate gradients would not do.

use crate::fem::vec3::{length, to_one};

/// How a GMRES run ended.
#[derive(Clone, Copy, Debug)]
pub struct Convergence {
    /// Operator applications.
    pub iterations: usize,
    /// `||b - A x||`.
    pub residual: f64,
    /// The residual reached the tolerance.
    pub converged: bool,
}

/// What a solve aims at, as residuals `||b - A x||`: `tol`, where it
/// stops; `enough`, above which its caller has no use for the answer
/// (below `tol` where a loose solve stops short of what a tight one uses).
#[derive(Clone, Copy, Debug)]
pub struct Target {
    pub tol: f64,
    pub enough: f64,
}

/// A restart cycle that leaves the residual above [`Target::enough`] (and
/// the tolerance) ends the solve when, at the rate it cut the residual,
/// reaching them would take more than this many times the cycles left. Restarted GMRES
/// on a singular system (a block that slides freely: no answer) cuts the
/// residual to some fraction of its start and stalls there, each cycle a
/// little less; without this the solve ran out its 5,000 applications.
/// Measured on the 3D slope of tests/corpus with joints that deform at
/// the factor of safety's failing trial F = 4 (27,122 unknowns, 33 ms an
/// application): two such solves stalled at 1.2e-4 and 2.5e-4 of the load
/// (rates per cycle of 0.84-0.87 by their 10th cycle, 0.9999 by their
/// 25th) where `enough` was 1e-6; this stops them at their 10th and 8th
/// cycles. A solve converging as GMRES(m) does, its rate slowing with the
/// restarts, is not stopped while it could still get there at half its
/// last rate's pace.
const STALLED: f64 = 2.0;

/// Solves `A x = b` from `x = 0` to `||b - A x|| <= target.tol`,
/// restarting every `restart` iterations, at most `max_iterations`
/// applications of `a` (and fewer where the residual stalls: [`stalls`]);
/// `m` applies the preconditioner `M^-1`.
pub fn solve(
    a: impl Fn(&[f64]) -> Vec<f64>,
    m: impl Fn(&[f64]) -> Vec<f64>,
    b: &[f64],
    target: Target,
    restart: usize,
    max_iterations: usize,
) -> (Vec<f64>, Convergence) {
    let Target { tol, enough } = target;
    // b scaled to a largest entry near 1 (exactly: the iterates are those
    // of b itself to the last bit, times a power of two), so that neither
    // the squares of the residuals nor their products leave double
    // precision when the forces are near 1e-200 or 1e+200
    let s = to_one(b);
    if s != 1.0 {
        let b1: Vec<f64> = b.iter().map(|v| v * s).collect();
        let target = Target { tol: tol * s, enough: enough * s };
        let (x, c) = solve(a, m, &b1, target, restart, max_iterations);
        return (x.iter().map(|v| v / s).collect(), Convergence { residual: c.residual / s, ..c });
    }
    let n = b.len();
    let mut x = vec![0.0; n];
    let mut r = b.to_vec();
    let mut beta = length(&r);
    let mut iterations = 0;
    while beta > tol && iterations < max_iterations {
        let start = beta;
        // Arnoldi on A M^-1 from r / beta
        let mut v: Vec<Vec<f64>> = vec![r.iter().map(|x| x / beta).collect()];
        let mut h: Vec<Vec<f64>> = Vec::new(); // columns of the Hessenberg matrix
        let (mut cs, mut sn) = (Vec::<f64>::new(), Vec::<f64>::new());
        let mut g = vec![beta];
        let mut k = 0;
        let mut z: Vec<Vec<f64>> = Vec::new(); // M^-1 of each of v
        while k < restart && iterations < max_iterations {
            z.push(m(&v[k]));
            let mut w = a(&z[k]);
            iterations += 1;
            let mut hk = vec![0.0; k + 2];
            for (i, vi) in v.iter().enumerate() {
                hk[i] = dot(&w, vi);
                axpy(-hk[i], vi, &mut w);
            }
            hk[k + 1] = length(&w);
            let (c, s) = rotate(&mut hk, &cs, &sn, k);
            g.push(-s * g[k]);
            g[k] *= c;
            cs.push(c);
            sn.push(s);
            let breakdown = hk[k + 1] == 0.0 || !hk[k + 1].is_finite();
            let next = w.iter().map(|x| x / hk[k + 1]).collect();
            hk.truncate(k + 1);
            h.push(hk);
            k += 1;
            if g[k].abs() <= tol || breakdown {
                break;
            }
            v.push(next);
        }
        // y = H^-1 g (upper triangular after the rotations), x += Z y
        let y = back_substitute(&h, &g, k);
        for (zi, yi) in z.iter().zip(&y) {
            axpy(*yi, zi, &mut x);
        }
        let ax = a(&x);
        r = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
        beta = length(&r);
        iterations += 1;
        if !beta.is_finite() || y.iter().any(|v| !v.is_finite()) {
            break;
        }
        if stalls(target, (start, beta), k == restart, max_iterations.saturating_sub(iterations) / (restart + 1)) {
            break;
        }
    }
    (x, Convergence { iterations, residual: beta, converged: beta <= tol })
}

/// Whether a restart cycle that took the true residual from `start` to
/// `beta` (above `target.tol`) ends the solve, `full` where it ran its
/// `restart` applications (else its estimate met the tolerance),
/// `cycles_left` the full cycles the budget still holds:
/// - where it left the residual no lower than it found it: the next cycle
///   would start where this one did and repeat it, but for round-off. At
///   the round-off floor it dithers: a tight solve on the 3D slope with
///   joints that deform (27,122 unknowns, tolerance 1.036e-10) reached
///   1.037e-10 in 426 applications and restarted 19 times more between
///   1.04e-10 and 1.11e-10, each cycle's estimate below the tolerance,
///   before one dipped below it at 1,040;
/// - above what is of use, where reaching it (or the tolerance, if that is
///   looser: a loose solve's) at the cycle's rate would take more than
///   [`STALLED`] times the cycles left.
fn stalls(target: Target, (start, beta): (f64, f64), full: bool, cycles_left: usize) -> bool {
    let goal = target.enough.max(target.tol);
    let rate = beta / start;
    if rate >= 1.0 {
        return true;
    }
    full && beta > goal && (goal / beta).ln() / rate.ln() > STALLED * cycles_left as f64
}

/// Applies the Givens rotations so far (`cs`, `sn`) to the new column
/// `hk` of the Hessenberg matrix, then the one that zeroes `hk[k + 1]`,
/// which it returns as (cos, sin).
fn rotate(hk: &mut [f64], cs: &[f64], sn: &[f64], k: usize) -> (f64, f64) {
    for i in 0..k {
        let t = cs[i] * hk[i] + sn[i] * hk[i + 1];
        hk[i + 1] = -sn[i] * hk[i] + cs[i] * hk[i + 1];
        hk[i] = t;
    }
    let d = hk[k].hypot(hk[k + 1]);
    let (c, s) = if d == 0.0 { (1.0, 0.0) } else { (hk[k] / d, hk[k + 1] / d) };
    hk[k] = d;
    (c, s)
}

/// `y = H^-1 g` for the first `k` columns `h` of the rotated (upper
/// triangular) Hessenberg matrix.
fn back_substitute(h: &[Vec<f64>], g: &[f64], k: usize) -> Vec<f64> {
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|j| h[j][i] * y[j]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    y
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (y, x) in y.iter_mut().zip(x) {
        *y += alpha * x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The test system's size.
    const N: usize = 200;

    /// An unsymmetric tridiagonal operator (convection-diffusion).
    fn convection(x: &[f64]) -> Vec<f64> {
        (0..N)
            .map(|i| {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < N { x[i + 1] } else { 0.0 };
                3.0 * x[i] - 1.4 * left - 0.6 * right
            })
            .collect()
    }

    /// A target whose answers are of use down to `tol` alone.
    fn to(tol: f64) -> Target {
        Target { tol, enough: tol }
    }

    fn jacobi(v: &[f64]) -> Vec<f64> {
        v.iter().map(|x| x / 3.0).collect()
    }

    /// Jacobi preconditioned, restarted: the answer to 1e-10.
    #[test]
    fn solves_an_unsymmetric_system_across_restarts() {
        let want: Vec<f64> = (0..N).map(|i| ((i as f64) * 0.1).sin()).collect();
        let b = convection(&want);
        let (x, c) = solve(convection, jacobi, &b, to(1e-12), 20, 1000);
        assert!(c.converged, "{c:?}");
        assert!(c.iterations > 20, "restarted at least once: {c:?}");
        let err = x.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(err < 1e-10, "error {err}");
    }

    /// The same system with b near 1e-200 (and 1e+200): the answer times
    /// that power of two to the last bit, in as many iterations (unscaled
    /// the squares of the residuals underflowed to zero: "converged" at x = 0).
    #[test]
    fn a_right_hand_side_near_1e_minus_200_is_solved_as_near_1() {
        let want: Vec<f64> = (0..N).map(|i| ((i as f64) * 0.1).sin()).collect();
        let b = convection(&want);
        let (x, c) = solve(convection, jacobi, &b, to(1e-12), 20, 1000);
        for s in [2f64.powi(-664), 2f64.powi(664)] {
            let bs: Vec<f64> = b.iter().map(|v| v * s).collect();
            let (xs, cs) = solve(convection, jacobi, &bs, to(1e-12 * s), 20, 1000);
            assert!(cs.converged && cs.iterations == c.iterations, "{cs:?} against {c:?}");
            assert!(xs.iter().zip(&x).all(|(a, b)| *a == b * s), "scaled by {s:e}");
        }
    }

    /// A preconditioner that is not linear (as a factor in single
    /// precision is not, to its rounding times its condition number; here
    /// Jacobi that halves a negative entry's divisor): the steps are along
    /// what it gave, so the residual said is the true one, reached in 39
    /// applications. Stepping along `M^-1 (V y)` (plain GMRES) took 286.
    #[test]
    fn a_preconditioner_that_is_not_linear_still_converges() {
        let want: Vec<f64> = (0..N).map(|i| ((i as f64) * 0.1).sin()).collect();
        let b = convection(&want);
        let bent = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| if *x > 0.0 { x / 3.0 } else { x / 1.5 }).collect() };
        let (x, c) = solve(convection, bent, &b, to(1e-10), 20, 1000);
        let ax = convection(&x);
        let true_residual = length(&b.iter().zip(&ax).map(|(b, a)| b - a).collect::<Vec<_>>());
        assert!(c.converged && true_residual <= 1e-10, "{c:?}, true residual {true_residual:e}");
        assert!((c.residual - true_residual).abs() <= 1e-12, "{c:?} against {true_residual:e}");
        assert!(c.iterations < 100, "{c:?}");
    }

    /// A singular system whose right-hand side is not in the range (a
    /// block free to slide under a load along its freedom): the residual
    /// cannot go below the load's part in the null space. The solve gives
    /// up after its first cycles that make no headway, not after every
    /// application allowed (1,001 before, at the same residual to 1e-10),
    /// and the same system with b in the range is solved to its tolerance.
    #[test]
    fn a_residual_that_stalls_above_what_is_of_use_ends_the_solve() {
        // the convection operator with its last unknown cut loose
        let singular = |x: &[f64]| {
            let mut y = convection(x);
            y[N - 1] = 0.0;
            y
        };
        let mut b = vec![1.0; N];
        let stalled = solve(singular, jacobi, &b, Target { tol: 1e-12, enough: 1e-6 }, 20, 1000).1;
        assert!(!stalled.converged && (1.0..1.1).contains(&stalled.residual), "{stalled:?}");
        assert!(stalled.iterations <= 4 * 21, "stopped after its cycles that made no headway: {stalled:?}");
        b[N - 1] = 0.0;
        let solved = solve(singular, jacobi, &b, Target { tol: 1e-12, enough: 1e-6 }, 20, 1000).1;
        assert!(solved.converged, "{solved:?}");
    }

    /// A tolerance below what double precision can reach: the solve ends
    /// at the first cycle that leaves the residual no lower, not after
    /// every application: at 2.0e-15, its tenth cycle (210 applications;
    /// stepping along `M^-1 (V y)`, fewer than 200).
    #[test]
    fn a_residual_at_the_round_off_floor_ends_the_solve() {
        let want: Vec<f64> = (0..N).map(|i| ((i as f64) * 0.1).sin()).collect();
        let b = convection(&want);
        let c = solve(convection, jacobi, &b, Target { tol: 1e-25, enough: 1e-6 }, 20, 1000).1;
        assert!(!c.converged && c.residual < 1e-12, "{c:?}");
        assert!(c.iterations <= 11 * 21, "{c:?}");
    }
}
