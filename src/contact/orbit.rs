//! Whether a step's iterates have entered a closed orbit: the same few
//! state sets, with the same friction residuals, over and over.
//!
//! The robust rule's cycle breaker changes one pair at a time, and where
//! that pair has no consistent state (a junction pair whose bound its
//! stuck shear exceeds threefold, and whose slip along its line runs
//! against its friction) it turns that pair back and forth for ever once
//! the cluster search has given up: the unconfined block mass
//! (tests/corpus/blocks3d.toml, rigid step 2) flipped pair 76 between
//! stick and slip from its 46th iteration to its 100th, every other
//! solve the same to the last digit (friction residuals 1.954e-5 and
//! 1.409e-7 by turns). Each solve is linearised at the last one's forces
//! and states, so once both repeat and nothing else in the rule is left
//! to change (the search done), the iterates repeat for ever and the
//! iterations left to the step are lost: the step stops, cycled.

use super::law::ContactState;

/// The longest orbit looked for, in iterations.
const MAX_PERIOD: usize = 4;

/// How many iterations an orbit must have repeated over, at least, before
/// it is taken as closed: three rounds, and past the cycle breaker's
/// holds of one state set (at most four, `newton::MAX_HOLDS`), so that
/// held solves whose friction still settles are never taken for one.
const MIN_SPAN: usize = 8;

/// Two friction residuals this close (relative) are the same solve's.
const SAME: f64 = 1e-9;

/// The period of the orbit the iterates end in, if they do: `states` and
/// `residuals` the step's iterates (each solve's state set and friction
/// residual, in order, as long as each other).
pub(super) fn period(states: &[Vec<ContactState>], residuals: &[f64]) -> Option<usize> {
    let n = states.len().min(residuals.len());
    let same = |i: usize, j: usize| {
        let (a, b) = (residuals[i], residuals[j]);
        states[i] == states[j] && (a - b).abs() <= SAME * a.abs().max(b.abs())
    };
    (1..=MAX_PERIOD).find(|&p| {
        let span = MIN_SPAN.max(3 * p);
        n >= span && (n - span + p..n).all(|i| same(i, i - p))
    })
}

#[cfg(test)]
mod tests {
    use super::period;
    use crate::contact::law::ContactState::{Open, Slip, Stick};

    /// blocks3d's pair flipping between stick and slip: a period of two
    /// once it has repeated over eight iterations, not before; a hold
    /// whose residual still falls, and a pair that flips with the
    /// friction settling, are no orbit.
    #[test]
    fn an_orbit_is_found_once_it_has_repeated() {
        let a = vec![Stick, Slip, Open];
        let b = vec![Slip, Slip, Open];
        let flip = |n: usize| -> (Vec<_>, Vec<f64>) {
            let states = (0..n).map(|i| if i % 2 == 0 { a.clone() } else { b.clone() }).collect();
            let residuals = (0..n).map(|i| if i % 2 == 0 { 1.954e-5 } else { 1.409e-7 }).collect();
            (states, residuals)
        };
        let (s, r) = flip(8);
        assert_eq!(period(&s, &r), Some(2));
        let (s, r) = flip(7);
        assert_eq!(period(&s, &r), None);
        // a different state set before the orbit does not matter
        let (mut s, mut r) = flip(9);
        s[0] = vec![Open, Open, Open];
        r[0] = 3.0;
        assert_eq!(period(&s, &r), Some(2));
        // held states whose friction settles
        let held: Vec<_> = (0..12).map(|_| a.clone()).collect();
        let falling: Vec<f64> = (0..12).map(|i| 0.5f64.powi(i)).collect();
        assert_eq!(period(&held, &falling), None);
        // the same solve again and again: a period of one
        assert_eq!(period(&held, &[2.5e-4; 12]), Some(1));
        // the flip with the friction still moving
        let (s, mut r) = flip(10);
        r.iter_mut().enumerate().for_each(|(i, x)| *x *= 1.0 + 1e-3 * i as f64);
        assert_eq!(period(&s, &r), None);
    }
}
