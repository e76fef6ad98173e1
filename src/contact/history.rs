//! What carries over from iteration to iteration and from step to step
//! ([`History`]): the states, the cracks, where each pair ended; whether a
//! pair is cracked ([`cracked`]), the crack memory of a step
//! ([`start_step`], [`mark_cracks`]) and the commit of a converged step
//! ([`commit`]).

use super::law::ContactState;
use super::system::InterfaceSolution;

/// What carries over from iteration to iteration and from step to step.
#[derive(Clone, Debug, Default)]
pub struct History {
    pub states: Vec<ContactState>,
    /// Pairs that cracked in a converged step (crack memory): the states
    /// it ended with, and [`History::cracking`].
    pub cracked: Vec<bool>,
    /// Pairs that cracked in the current step: solved slipping or open in
    /// an iteration after its first ([`cracked`]). Cleared at the step's
    /// start, merged into `cracked` when it converges.
    pub cracking: Vec<bool>,
    /// Relative displacement a stuck pair is tied at along the joint (the
    /// slip accumulated before it stuck, or where it touched when it closed).
    pub offset: Vec<[f64; 3]>,
    /// Relative displacement at the start of the current step.
    pub rel_start: Vec<[f64; 3]>,
    /// Contact force on body I at the end of the last step (local axes).
    pub force: Vec<[f64; 3]>,
    /// Unit friction direction on body I of slipping pairs (local t, b).
    pub dir: Vec<[f64; 3]>,
    /// Normal stress last seen at each pair (for the Coulomb shear).
    pub sigma_n: Vec<f64>,
}

impl History {
    /// Every pair stuck, nothing cracked or slipped.
    pub fn new(n: usize) -> History {
        History {
            states: vec![ContactState::Stick; n],
            cracked: vec![false; n],
            cracking: vec![false; n],
            offset: vec![[0.0; 3]; n],
            rel_start: vec![[0.0; 3]; n],
            force: vec![[0.0; 3]; n],
            dir: vec![[0.0; 3]; n],
            sigma_n: vec![0.0; n],
        }
    }
}

/// Whether a pair has lost its tensile strength and cohesion: it cracked
/// in an earlier step, or earlier in this one, or it is open or slipping
/// now. Within a step a crack does not heal: a pair that slipped or opened
/// in one iteration and is judged stuck in the next keeps `f_t = 0` and
/// the residual cohesion, or a brittle law could crack and heal it from
/// iteration to iteration and never settle. The states a step starts with
/// are not its cracks (they are the last step's, committed if it
/// converged): a pair open at the start of a step that did not follow a
/// converged one, and that closes at once, keeps its strength.
pub(crate) fn cracked(h: &History, p: usize) -> bool {
    h.cracked[p] || h.cracking[p] || h.states[p] != ContactState::Stick
}

/// Starts a step's crack memory: nothing cracked in it yet.
pub(crate) fn start_step(h: &mut History) {
    h.cracking.clear();
    h.cracking.resize(h.states.len(), false);
}

/// Marks the pairs solved slipping or open in an iteration of the step
/// after its first as cracked in it.
pub(crate) fn mark_cracks(h: &mut History) {
    for (c, s) in h.cracking.iter_mut().zip(&h.states) {
        *c |= *s != ContactState::Stick;
    }
}

/// Forgets the cracks `pairs` made in the step's iterates (the cluster
/// search holding them stuck: [`crate::contact::cluster`]); cracks of
/// earlier steps stay.
pub(crate) fn forget_step_cracks(h: &mut History, pairs: impl IntoIterator<Item = usize>) {
    for p in pairs {
        h.cracking[p] = false;
    }
}

/// Commits a converged step: where it ended, and the cracks it made (in
/// its last states and on the way there).
pub(crate) fn commit(h: &mut History, solution: &InterfaceSolution) {
    h.rel_start = solution.rel.clone();
    h.force = solution.forces.clone();
    for p in 0..h.states.len() {
        h.cracked[p] |= h.cracking[p] || h.states[p] != ContactState::Stick;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::law::{judge, Strength, Trial};
    use crate::contact::pair_law::{limit, PairLaw};
    use crate::contact::SlipLaw;
    use ContactState::{Open, Slip, Stick};

    /// c = 1, f = 0.5, f_t = 2, residual cohesion 0.
    const S: Strength = Strength { friction: 0.5, cohesion: 1.0, tensile_strength: 2.0, residual_cohesion: 0.0 };

    /// A closed pair of unit area under sigma_n (tension positive) and shear tau, not moving.
    fn at(sigma_n: f64, tau: f64) -> Trial {
        Trial { force: [sigma_n, tau, 0.0], area: 1.0, slip: [0.0; 3], gap: 0.0, stiffness: 10.0 }
    }

    /// One pair through the iterations of a step: slipped under its peak
    /// strength, stuck again by the next verdict, then loaded at a shear
    /// between its residual bound (0.5) and its peak bound (1.5).
    fn healed_or_not(h: &mut History) -> ContactState {
        start_step(h);
        h.states[0] = Slip; // the verdict of iteration 1
        mark_cracks(h); // iteration 2 solves it slipping
        h.states[0] = Stick; // and its verdict sticks it again
        mark_cracks(h); // iteration 3 solves it stuck
        judge(Stick, &at(-1.0, 1.0), &S, cracked(h, 0), true, 0.0, 0.0)
    }

    #[test]
    fn a_crack_does_not_heal_within_its_step() {
        let mut h = History::new(1);
        assert_eq!(healed_or_not(&mut h), Slip, "cracked this step: c = 0, bound 0.5 < 1");
        assert!(cracked(&h, 0) && !h.cracked[0], "cracked in the step, not yet committed");
        assert_eq!(limit(&PairLaw { strength: S, slip: SlipLaw::Coulomb }, cracked(&h, 0), 1.0).cohesion, 0.0);
        // the rule before: cracked only by a committed step or the state now;
        // stuck again, the pair had its peak bound 1.5 back and stuck, and
        // the next solve could slip it again
        let before = h.cracked[0] || h.states[0] != Stick;
        assert_eq!(judge(Stick, &at(-1.0, 1.0), &S, before, true, 0.0, 0.0), Stick);
    }

    #[test]
    fn a_step_commits_its_cracks_and_the_next_starts_with_none_of_its_own() {
        let mut h = History::new(3);
        healed_or_not(&mut h);
        h.states[2] = Open;
        let solution = InterfaceSolution {
            pairs: Vec::new(),
            forces: vec![[0.0; 3]; 3],
            rel: vec![[0.0; 3]; 3],
            d_c: Vec::new(),
            residual: 0.0,
            accuracy: 0.0,
            loose: false,
            inexact: false,
            as_tied: vec![None; 3],
            water: Vec::new(),
        };
        commit(&mut h, &solution);
        assert_eq!(h.cracked, vec![true, false, true], "cracked on the way, and open at the end");
        start_step(&mut h);
        assert_eq!(h.cracking, vec![false; 3]);
        assert!(cracked(&h, 0), "a committed crack stays");
        // a pair open at the start of a step that did not follow a
        // converged one is not cracked once it closes
        let mut fresh = History::new(1);
        fresh.states[0] = Open;
        start_step(&mut fresh);
        fresh.states[0] = Stick;
        assert!(!cracked(&fresh, 0));
    }
}
