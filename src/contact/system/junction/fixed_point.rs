//! The fixed point `p = P(p)` of a loop's locked slipping pairs' pressures
//! (`Junction::settle_locked`): each pair's friction moves the share of
//! the loop's forces, which gives the pair its pressure back.
//!
//! P is affine between the share's limits (and where a pressure is cut
//! off at zero), so Newton's method on `P(p) - p`, its Jacobian by
//! differences and its steps taken back until the residual falls, ends
//! in a round or two where P contracts: a slow contraction (a gain of
//! 0.997 a round, as tunnel4sets' pair 2389 had) is settled to round-off
//! where 200 plain rounds leave 55 % of the way. Where Newton finds no
//! fixed point at which P contracts, the plain rounds `p <- P(p)` run as
//! before, and their end is taken unless they grew (a wedge: the last
//! round's change more than [`ROUNDS`] times the first's).
//!
//! Their end is taken even where the rounds cycle, which is not a fixed
//! point, and said: tunnel4sets' junction [1951, 5509, 5510, 5511] (with
//! the J1 pairs of its node, three joints crossing), four locked slipping
//! pairs, ends its rounds in an exact three-cycle (pair 1951: 0.033,
//! 0.090, 0.103 MN), Newton stalls at a residual of 4.3e-2 of 0.59 MN
//! (P's Jacobian has eigenvalues 1.0017 +- 0.0059i), and the pressures
//! written are the 200th round's while the forces carried are the round
//! before's: friction 7-13 % off the equilibrium solved. The third value
//! of [`settle`] is that difference, which summary.json and report.md
//! give (`locked_friction_off`). Taking no such end (the last solve's
//! pressures instead, as for a wedge) makes tunnel4sets converge in 93
//! iterations to consistent forces, but blocks3d_confined, which takes
//! such ends on its way and ends its step 1 on one (5e-6 MN), then no
//! longer converges (400 and 3 cuts); refused only once the states have
//! settled, neither converges: docs/convergence.md, twentieth session.

use std::sync::Mutex;

use nalgebra::{DMatrix, DVector};

use crate::fem::bounded::largest_eigenvalue;

/// How far a junction's last solve's locked pressures were from a fixed
/// point ([`settle`]'s third value where beyond [`CLOSE`], else 0).
#[derive(Default)]
pub(super) struct Off(Mutex<f64>);

impl Off {
    pub fn get(&self) -> f64 {
        *self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
    pub fn set(&self, off: f64) {
        *self.0.lock().unwrap_or_else(|e| e.into_inner()) = off;
    }
}

impl Clone for Off {
    fn clone(&self) -> Off {
        Off::default()
    }
}

impl std::fmt::Debug for Off {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Off({})", self.get())
    }
}

/// Plain rounds after Newton's.
const ROUNDS: usize = 200;
/// Newton's rounds, and its steps' halvings.
const NEWTON_ROUNDS: usize = 20;
const HALVINGS: usize = 30;
/// A round's largest change, of the largest carried force, at which the
/// pressures have settled.
const SETTLED: f64 = 1e-13;

/// What `P` gives at some pressures: the carried force, its share, and
/// the pressures the share gives back.
pub type Round = (DVector<f64>, DVector<f64>, Vec<f64>);

/// The pressures with `P(p) = p` from `p` (Newton takes only a fixed
/// point where P contracts, the one the rounds would reach), or the plain
/// rounds' end; the carried force and share the pressures come from; and
/// how far the pressures written are from those carried (the last
/// round's change: round-off at a fixed point). None where the rounds
/// grow.
pub fn settle(at: &impl Fn(&[f64]) -> Round, p: Vec<f64>, scale: f64) -> Option<(Vec<f64>, Round, f64)> {
    if let Some((p, round)) = newton(at, p.clone(), scale) {
        // (within round-off of a fixed point: nothing to say)
        return Some((p, round, 0.0));
    }
    rounds(at, p, scale)
}

/// A round's change, of the largest carried force, within which the
/// pressures are at a fixed point (to round-off of the share's solve).
pub const CLOSE: f64 = 1e-9;

/// The largest change `P(p) - p`.
fn change(next: &[f64], p: &[f64]) -> f64 {
    next.iter().zip(p).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
}

fn newton(at: &impl Fn(&[f64]) -> Round, mut p: Vec<f64>, scale: f64) -> Option<(Vec<f64>, Round)> {
    let k = p.len();
    let h = 1e-6 * scale;
    let residual = |next: &[f64], p: &[f64]| DVector::from_iterator(k, next.iter().zip(p).map(|(a, b)| a - b));
    let mut round = at(&p);
    for _ in 0..NEWTON_ROUNDS {
        let next = &round.2;
        if change(next, &p) <= SETTLED * scale {
            return Some((next.clone(), round));
        }
        let mut jac = DMatrix::<f64>::zeros(k, k);
        for j in 0..k {
            let mut q = p.clone();
            q[j] += h;
            let moved = at(&q).2;
            for i in 0..k {
                jac[(i, j)] = (moved[i] - next[i]) / h;
            }
        }
        // where P does not contract, its fixed point is not the one the
        // rounds approach (a wedge's, at a pressure that grows each round);
        // nor is there one to find by differences that are not finite, or
        // where its Jacobian's eigenvalues could not be found
        if jac.iter().any(|x| !x.is_finite()) || largest_eigenvalue(&jac).is_none_or(|r| r >= 1.0) {
            return None;
        }
        let res = residual(next, &p);
        let step = (DMatrix::<f64>::identity(k, k) - jac).lu().solve(&res)?;
        let before = res.norm();
        let mut alpha = 1.0;
        let (q, taken) = (0..HALVINGS).find_map(|_| {
            let q: Vec<f64> = p.iter().zip(step.iter()).map(|(a, d)| (a + alpha * d).max(0.0)).collect();
            let r = at(&q);
            alpha *= 0.5;
            (residual(&r.2, &q).norm() <= (1.0 - 1e-4 * 2.0 * alpha) * before).then_some((q, r))
        })?;
        p = q;
        round = taken;
    }
    (change(&round.2, &p) <= SETTLED * scale).then(|| (round.2.clone(), round))
}

/// The plain rounds' end and the last round's change; None where they grow.
fn rounds(at: &impl Fn(&[f64]) -> Round, mut p: Vec<f64>, scale: f64) -> Option<(Vec<f64>, Round, f64)> {
    let (mut first, mut last, mut end) = (None, 0.0, None);
    for _ in 0..ROUNDS {
        let round = at(&p);
        last = change(&round.2, &p);
        first.get_or_insert(last);
        p.clone_from(&round.2);
        end = Some(round);
        if last <= SETTLED * scale {
            break;
        }
    }
    // (at a gain of 1 each round moves them by about the first's: more
    // than all the rounds of that is a gain beyond 1, a wedge)
    let round = end.filter(|_| last <= ROUNDS as f64 * first.unwrap_or(0.0))?;
    Some((p, round, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// P(p) = a p + b, carried force and share stand-ins.
    fn affine(a: DMatrix<f64>, b: Vec<f64>) -> impl Fn(&[f64]) -> Round {
        move |p: &[f64]| {
            let x = &a * DVector::from_column_slice(p) + DVector::from_column_slice(&b);
            let next: Vec<f64> = x.iter().map(|v| v.max(0.0)).collect();
            (x.clone(), x, next)
        }
    }

    #[test]
    fn a_slow_contraction_is_settled_at_its_limit() {
        // gain 0.997 a round: 200 plain rounds leave 55 % of the way
        let at = affine(DMatrix::from_row_slice(1, 1, &[0.997]), vec![0.003]);
        let (p, _, off) = settle(&at, vec![0.1], 1.0).expect("a fixed point");
        assert!(off <= SETTLED);
        assert!((p[0] - 1.0).abs() < 1e-12, "p = {}", p[0]);
        let two = affine(DMatrix::from_row_slice(2, 2, &[0.5, 0.3, -0.2, 0.9]), vec![0.1, 0.2]);
        let (p, (_, _, next), _) = settle(&two, vec![0.0, 0.0], 1.0).expect("a fixed point");
        assert!(change(&next, &p) <= SETTLED);
    }

    #[test]
    fn pressures_that_grow_have_no_fixed_point() {
        // a wedge: each round gives back more than it took
        let grows = affine(DMatrix::from_row_slice(1, 1, &[1.5]), vec![0.1]);
        assert!(settle(&grows, vec![0.1], 1.0).is_none());
    }

    #[test]
    fn an_end_that_cycles_is_taken_and_says_how_far_off_it_is() {
        // a turn by 120 degrees about (1, 1) that grows as tunnel4sets'
        // junction's did (eigenvalues of modulus 1.0017): Newton does not
        // take its fixed point, and the rounds turn round it at a radius
        // of 0.2 (from 1.2, 1.0), 0.35 apart from one round to the next
        let (c, s) = (-0.5 * 1.0017, 0.75f64.sqrt() * 1.0017);
        let turn = DMatrix::from_row_slice(2, 2, &[c, -s, s, c]);
        let centre = DVector::from_vec(vec![1.0, 1.0]);
        let shift = &centre - &turn * &centre;
        let at = affine(turn, shift.iter().copied().collect());
        let (_, _, off) = settle(&at, vec![1.2, 1.0], 1.0).expect("the rounds' end");
        assert!(off > 0.2 && off < 0.5, "off {off}");
    }
}
