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
use crate::fem::bounded::eigenvalues;

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

/// The largest gain of the friction's feedback on the pressures at which
/// they are solved for: the largest real part of the eigenvalues of
/// `A R`. Solved for, the pressures are `(I - A R)^-1 A u`; with one pair
/// `p = a u / (1 - g)`, which keeps the sign of the share without the
/// friction while g < 1 and turns it over beyond: a tension the friction
/// it reverses holds up, as a crossing of the 2D jointed tunnel gave (its
/// pair toggled between slipping and open for 100 iterations). Below 3/4
/// every eigenvalue of `I - A R` has a real part of at least 1/4. Beyond,
/// the pressures are the last solve's (in one run of that tunnel, 43 of
/// 1,702 junction solves; with 1/2 `make tunnel-joints` took 39 contact
/// iterations instead of 28, before the loops' note was kept for the load).
///
/// The gain was the spectral radius (and before it `||A R||_inf`, which
/// only bounds it: tests/corpus/tunnel4sets.toml's junction of pairs 159,
/// 160 and 5528-5531 had 0.82 there and a spectral radius of 0.066, and
/// its friction, lagged, settled 2-6 fold a solve for its last ten
/// iterations; and `--substructures 2 --interface iterative` on
/// geo/dam.toml ended with pair 2 open where the dense interface has it
/// slipping). The radius also counts a feedback that turns the pressures
/// over, an eigenvalue of large modulus and negative real part: lagged,
/// the pressures then grow as they alternate, but solved for they are
/// well posed (`I - A R` the larger for it). tests/corpus/
/// tunnel4sets_linear.toml's junction at the wall node where J1, J3 and
/// J4 cross has a radius of 3.66 and no real part above 0.69: lagged, the
/// cluster search's secant steps settled its pressures in 23 iterations
/// (32 in all; docs/corpus.md); solved for, 14 in all, the same states
/// pair by pair. The 10 m jointed tunnel of tests/convergence.rs: 8
/// where 21 (a junction of radius 1.05 and real parts below 0.33 solved
/// for; another whose eigenvalue 1.05 is real still lagged).
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
        if !(gain(&ar) <= GAIN) {
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

/// The largest real part of `m`'s eigenvalues, or `||m||_inf`, which
/// bounds it, where that is below [`GAIN`] already (no eigenvalues
/// needed); NaN where `m` is not finite or its eigenvalues were not found.
fn gain(m: &DMatrix<f64>) -> f64 {
    if !m.iter().all(|v| v.is_finite()) {
        return f64::NAN;
    }
    let bound = (0..m.nrows()).map(|i| m.row(i).iter().map(|v| v.abs()).sum::<f64>()).fold(0.0, f64::max);
    if bound <= GAIN {
        return bound;
    }
    eigenvalues(m).map_or(f64::NAN, |z| z.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max))
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
    use crate::fem::bounded::largest_eigenvalue;

    #[test]
    fn the_gain_is_the_largest_real_part_not_the_radius_or_the_row_sums() {
        // rows summing to 0.9, eigenvalues 0.1 and 0: solved for
        let m = DMatrix::from_row_slice(2, 2, &[0.1, 0.8, 0.0, 0.0]);
        assert!((gain(&m) - 0.1).abs() < 1e-12);
        let turn = |modulus: f64, angle: f64| {
            let (c, s) = (modulus * angle.cos(), modulus * angle.sin());
            DMatrix::from_row_slice(2, 2, &[c, -s, s, c])
        };
        // a turn of modulus 0.9 by 0.3 rad: real parts 0.86, not
        assert!((gain(&turn(0.9, 0.3)) - 0.9 * 0.3f64.cos()).abs() < 1e-12);
        assert!(gain(&turn(0.9, 0.3)) > GAIN);
        // of modulus 3.66 by 2 rad, or a pressure turned over 3.66-fold
        // (tunnel4sets_linear's radius): solved for, I - A R the larger
        assert!(gain(&turn(3.66, 2.0)) < 0.0);
        assert_eq!(gain(&DMatrix::from_row_slice(1, 1, &[-3.66])), -3.66);
        // a wedge's friction that would turn its pressure to a tension: not
        assert!(gain(&DMatrix::from_row_slice(1, 1, &[1.05])) > GAIN);
        // below the bound already: the bound
        let m = DMatrix::from_row_slice(2, 2, &[0.2, 0.3, 0.0, 0.1]);
        assert_eq!(gain(&m), 0.5);
        let m = DMatrix::from_row_slice(1, 1, &[f64::NAN]);
        assert!(gain(&m).is_nan());
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
            let _ = tx.send((largest_eigenvalue(&companion()), gain(&companion())));
        });
        let (r, g) = rx.recv_timeout(std::time::Duration::from_secs(20)).expect("the eigenvalues end");
        let exact = 1.7748092111017977f64.powf(0.1);
        assert!(r.is_none_or(|r| (r - exact).abs() < 1e-9), "{r:?}");
        // (a gain not found is beyond the bound, as one not finite; the
        // largest real part is the positive real root's)
        assert!(if r.is_none() { g.is_nan() } else { (g - exact).abs() < 1e-9 }, "{g}");
    }
}
