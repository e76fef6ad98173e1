//! A junction's slipping pairs' friction, implicit in their pressure.
//!
//! A slipping pair's friction is linearised in its own pressure force p
//! (`force + coupling p + spring rel`, [`Relation`](crate::contact::system::Relation)). A lone pair's p is a
//! row of the system (its normal's `W r - c`), so the coupling is a term of
//! its equation and Newton converges quadratically. At a junction p is the
//! split of the force the tied rows carry, known only after the solve;
//! taking it from the last solve made Newton converge tenfold an iteration
//! on junction pairs (the 512-block cube of `make bench-blocks`: the last
//! five or six solves of a step). Here it is solved with the rest. With
//! `u = W r - c + k r + f0` over the junction's r (f0 the friction at
//! p = 0) and R the friction per unit pressure (a column per slipping pair):
//!
//! ```text
//! p = A (u + R p)        so   p = M A u,   M = (I - A R)^-1
//! ```
//!
//! A the least-norm split's rows of the slipping pairs' normals (its `-λ_n`
//! per unit of carried force). The junction's equations `Z^T (u + R p) = 0`
//! become
//!
//! ```text
//! (Z^T + L) u = 0,   L = Z^T R M A
//! ```
//!
//! which is what the interface solvers take ([`super::super::Lift`]).
//! Once the least-norm share has broken a limit at a slipping pair's normal
//! (the loops then carry part of its pressure, chosen after the solve),
//! the junction's pressures are solved for through the tangent of the last
//! solve's share ([`super::tangent`]: `A` its rows, plus a constant) while
//! the junction ties the same rows, and are the last solve's
//! (`Relation::pressure`) in the solve after its tied rows change; it
//! stays so until the load changes:
//! - taking the loops' part from the last solve and the rest implicitly
//!   kept the 2D jointed tunnel (`make tunnel-joints`) cycling between five
//!   state sets for 100 iterations;
//! - switching back to solving for them as soon as a solve's loops let go
//!   kept the 8 hex20 blocks of tests/geo/cross3d.geo under an oblique
//!   load (dense interface) toggling two pairs for 100 iterations, as the
//!   junction's way of solving changed with them.

use nalgebra::{DMatrix, DVector};

use super::row::NORMAL;
use super::split::Split;
use super::tangent::Tangent;
use crate::fem::bounded::largest_eigenvalue;

/// A junction's friction in its slipping pairs' pressures.
#[derive(Clone, Debug)]
pub struct Pressure {
    /// The junction's pairs (indices there) whose pressure is solved for.
    pub pairs: Vec<usize>,
    /// The friction per unit pressure of each, over r (n_r x pairs).
    pub r: DMatrix<f64>,
    /// `M A` (pairs x n_r) and `M p0`: `p = M A u + M p0` (p0 the
    /// pressures at u = 0 of a share that meets a limit, see [`Tangent`]).
    pub ma: DMatrix<f64>,
    pub base: DVector<f64>,
}

/// The largest gain of the friction's feedback on the pressures, the
/// spectral radius of `A R`, at which they are solved for. Beyond one,
/// taking them from the last solve diverges, and solving for them can give
/// a pressure of the wrong sign, a tension the friction it reverses holds
/// up: a crossing of the 2D jointed tunnel did so, and its pair toggled
/// between slipping and open for 100 iterations. Below 3/4 the pressures
/// are the limit of the last-solve ones; beyond, they are the last solve's (in
/// one run of that tunnel, 43 of 1,702 junction solves; with 1/2 `make
/// tunnel-joints` took 39 contact iterations instead of 28, before the
/// loops' note was kept for the load).
///
/// The gain was bounded by `||A R||_inf`, which only bounds the spectral
/// radius: tests/corpus/tunnel4sets.toml's junction of pairs 159, 160 and
/// 5528-5531 had 0.82 there and a spectral radius of 0.066, and its
/// friction, lagged, settled 2-6 fold a solve for its last ten iterations;
/// and `--substructures 2 --interface iterative` on geo/dam.toml ended with
/// pair 2 open where the dense interface has it slipping (both keep the
/// law; the heel's junction shares its force one way or the other).
const GAIN: f64 = 0.75;

impl Pressure {
    /// The pressures of `pairs` (junction indices, each with its friction
    /// per unit pressure over r in `r`'s columns) under `split`, or under
    /// the `tangent` of its share where its loops carry part of them. None
    /// where the split does not tie a pair's normal, or the feedback is
    /// beyond [`GAIN`].
    pub(super) fn new(
        pairs: Vec<usize>,
        r: DMatrix<f64>,
        split: &Split,
        tangent: Option<&Tangent>,
    ) -> Option<Pressure> {
        let n_r = r.nrows();
        let rows: Vec<usize> =
            pairs.iter().map(|&j| split.rows.iter().position(|&row| row == (j, NORMAL))).collect::<Option<_>>()?;
        // p = -λ_n of the share of -u: A u + p0
        let (a, p0) = match tangent {
            Some(t) => (
                DMatrix::<f64>::from_fn(pairs.len(), n_r, |s, c| t.j[(rows[s], c)]),
                DVector::<f64>::from_fn(pairs.len(), |s, _| -t.offset[rows[s]]),
            ),
            None => (
                DMatrix::<f64>::from_fn(pairs.len(), n_r, |s, c| split.d[rows[s]] * split.pinv[(rows[s], c)]),
                DVector::zeros(pairs.len()),
            ),
        };
        let ar = &a * &r;
        if !(spectral_radius(&ar) <= GAIN) {
            return None;
        }
        let m = (DMatrix::<f64>::identity(pairs.len(), pairs.len()) - ar).try_inverse()?;
        Some(Pressure { ma: &m * a, base: m * p0, pairs, r })
    }

    /// The pressures at `u` (over the junction's r).
    pub fn at(&self, u: &DVector<f64>) -> DVector<f64> {
        &self.ma * u + &self.base
    }
}

/// The largest modulus of `m`'s eigenvalues, or `||m||_inf`, which bounds
/// it, where that is below [`GAIN`] already (no eigenvalues needed); NaN
/// where `m` is not finite or its eigenvalues were not found.
fn spectral_radius(m: &DMatrix<f64>) -> f64 {
    if !m.iter().all(|v| v.is_finite()) {
        return f64::NAN;
    }
    let bound = (0..m.nrows()).map(|i| m.row(i).iter().map(|v| v.abs()).sum::<f64>()).fold(0.0, f64::max);
    if bound <= GAIN {
        return bound;
    }
    largest_eigenvalue(m).unwrap_or(f64::NAN)
}

/// Whether the share `lambda` of `split`'s rows is not the least-norm one
/// `plain` at the normal of a pair `slipping` says slips: the loops carry
/// part of its pressure.
pub(super) fn looped(
    split: &Split,
    lambda: &DVector<f64>,
    plain: &DVector<f64>,
    slipping: impl Fn(usize) -> bool,
) -> bool {
    let scale = lambda.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (split.rows.iter().enumerate())
        .any(|(i, &(j, dir))| dir == NORMAL && slipping(j) && (lambda[i] - plain[i]).abs() > LOOPED * scale)
}

/// A share differs from the least-norm one by more than this (of its
/// largest force) where the loops carry part of it (the cuts keep 1e-9
/// inside the limits).
const LOOPED: f64 = 1e-12;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gain_is_the_spectral_radius_not_its_row_sum_bound() {
        // rows summing to 0.9, eigenvalues 0.1 and 0: solved for
        let m = DMatrix::from_row_slice(2, 2, &[0.1, 0.8, 0.0, 0.0]);
        assert!((spectral_radius(&m) - 0.1).abs() < 1e-12);
        // a turn of modulus 0.9: not
        let (c, s) = (0.9 * 0.3f64.cos(), 0.9 * 0.3f64.sin());
        let m = DMatrix::from_row_slice(2, 2, &[c, -s, s, c]);
        assert!((spectral_radius(&m) - 0.9).abs() < 1e-12);
        // below the bound already: the bound
        let m = DMatrix::from_row_slice(2, 2, &[0.2, 0.3, 0.0, 0.1]);
        assert_eq!(spectral_radius(&m), 0.5);
        let m = DMatrix::from_row_slice(1, 1, &[f64::NAN]);
        assert!(spectral_radius(&m).is_nan());
    }

    /// nalgebra issue #611: the companion matrix of x^10 - 1.7748 (its
    /// eigenvalues the ten roots, of modulus 1.7748^(1/10) = 1.0590), on
    /// which nalgebra 0.33's `complex_eigenvalues` loops for ever
    /// (measured: no answer in two minutes).
    fn companion() -> DMatrix<f64> {
        let mut m = DMatrix::zeros(10, 10);
        m[(0, 9)] = 1.7748092111017977;
        for i in 1..10 {
            m[(i, i - 1)] = 1.0;
        }
        m
    }

    #[test]
    fn eigenvalues_a_schur_decomposition_does_not_find_end_in_none() {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send((largest_eigenvalue(&companion()), spectral_radius(&companion())));
        });
        let (r, radius) = rx.recv_timeout(std::time::Duration::from_secs(20)).expect("the eigenvalues end");
        let exact = 1.7748092111017977f64.powf(0.1);
        assert!(r.is_none_or(|r| (r - exact).abs() < 1e-9), "{r:?}");
        // (a radius not found is beyond the gain, as one not finite)
        assert!(if r.is_none() { radius.is_nan() } else { radius == r.unwrap_or(0.0) }, "{radius}");
    }
}
