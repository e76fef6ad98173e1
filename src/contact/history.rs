//! What carries over from iteration to iteration and from step to step
//! ([`History`]): the states, the cracks, where each pair ended; whether a
//! pair is cracked ([`cracked`]), the crack memory of a step
//! ([`start_step`], [`mark_cracks`]), the law of a pair that has parted
//! ([`law_at`]: no cohesion left) and the commit of a converged step
//! ([`commit`]).

use super::law::{ContactState, Strength};
use super::pair_law::PairLaw;
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
    /// Pairs that have parted ([`parted`]) in a converged step; how often
    /// each has been solved open in the current one after being solved
    /// closed (an opening), and whether it was solved open last.
    pub parted: Vec<bool>,
    pub openings: Vec<u32>,
    pub solved_open: Vec<bool>,
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
    /// Where each pair's spring carries nothing, for joints that deform
    /// ([`super::elastic`]); empty for rigid ones.
    pub unloaded: Vec<[f64; 3]>,
    /// Each pair's force under the in-situ stress alone at a unit factor of
    /// load case `insitu_case` (local axes, on body I; empty without it):
    /// what rigid ties carry before anything moves, where a junction's
    /// share of its force starts from (see [`super::system::Relation::prior`]).
    pub insitu: Vec<[f64; 3]>,
    pub insitu_case: usize,
    /// The springs (per unit area) that rigid joints are solved through
    /// where their Newton iteration does not end a step
    /// ([`super::augmented`]; `[solver] augmented_lagrangian`): None where
    /// the run does not ask for it.
    pub penalty: Option<super::law::Stiffness>,
}

impl History {
    /// Every pair stuck, nothing cracked or slipped.
    pub fn new(n: usize) -> History {
        History {
            states: vec![ContactState::Stick; n],
            cracked: vec![false; n],
            cracking: vec![false; n],
            parted: vec![false; n],
            openings: vec![0; n],
            solved_open: vec![false; n],
            offset: vec![[0.0; 3]; n],
            rel_start: vec![[0.0; 3]; n],
            force: vec![[0.0; 3]; n],
            dir: vec![[0.0; 3]; n],
            sigma_n: vec![0.0; n],
            unloaded: Vec::new(),
            insitu: Vec::new(),
            insitu_case: 0,
            penalty: None,
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

/// Whether a pair has parted: opened, closed and opened again in one
/// step (this one or an earlier converged one). A single opening that a
/// later iterate closes costs nothing: the first solve of a step, all
/// stuck, puts pairs in tension that the answer has closed, and which of
/// them it does depends on the step's size, not on the load path.
pub(crate) fn parted(h: &History, p: usize) -> bool {
    h.parted[p] || opened_twice(h, p)
}

/// Whether pair `p` has opened, closed and opened again in this step.
pub(crate) fn opened_twice(h: &History, p: usize) -> bool {
    h.openings[p] >= 2
}

/// Pair `p`'s law as it stands in `h`: a pair that has parted has lost
/// its residual cohesion as well (see `law.rs`: the tension cut-off).
pub(crate) fn law_at(h: &History, laws: &[PairLaw], p: usize) -> PairLaw {
    let law = laws[p];
    if parted(h, p) {
        PairLaw { strength: Strength { residual_cohesion: 0.0, ..law.strength }, ..law }
    } else {
        law
    }
}

/// Starts a step's crack memory: nothing cracked in it yet.
pub(crate) fn start_step(h: &mut History) {
    h.cracking.clear();
    h.cracking.resize(h.states.len(), false);
    h.openings.clear();
    h.openings.resize(h.states.len(), 0);
    h.solved_open = h.states.iter().map(|&s| s == ContactState::Open).collect();
}

/// Marks the pairs solved slipping or open in an iteration of the step
/// after its first as cracked in it.
pub(crate) fn mark_cracks(h: &mut History) {
    for (c, s) in h.cracking.iter_mut().zip(&h.states) {
        *c |= *s != ContactState::Stick;
    }
    for p in 0..h.states.len() {
        let open = h.states[p] == ContactState::Open;
        h.openings[p] += u32::from(open && !h.solved_open[p]);
        h.solved_open[p] = open;
    }
}

/// Forgets the cracks `pairs` made in the step's iterates (the cluster
/// search holding them stuck: [`crate::contact::cluster`]); cracks of
/// earlier steps stay.
pub(crate) fn forget_step_cracks(h: &mut History, pairs: impl IntoIterator<Item = usize>) {
    for p in pairs {
        h.cracking[p] = false;
        h.openings[p] = 0;
    }
}

/// Commits a converged step: where it ended, and the cracks it made (in
/// its last states and on the way there).
pub(crate) fn commit(h: &mut History, solution: &InterfaceSolution) {
    h.rel_start = solution.rel.clone();
    h.force = solution.forces.clone();
    for p in 0..h.states.len() {
        h.cracked[p] |= h.cracking[p] || h.states[p] != ContactState::Stick;
        h.parted[p] |= opened_twice(h, p);
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
        assert_eq!(
            limit(&PairLaw { strength: S, slip: SlipLaw::Coulomb, stiffness: None }, cracked(&h, 0), 1.0).cohesion,
            0.0
        );
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
            locked_off: Vec::new(),
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
    #[test]
    fn a_pair_that_opens_twice_in_a_step_closes_without_its_residual_cohesion() {
        // residual cohesion 0.5 (kept once slipping); pair 0 slips, pair 1
        // opens (solved open, then closed, then open again)
        let laws =
            [PairLaw { strength: Strength { residual_cohesion: 0.5, ..S }, slip: SlipLaw::Coulomb, stiffness: None };
                2];
        let mut h = History::new(2);
        start_step(&mut h);
        let cohesion = |h: &History, p| law_at(h, &laws, p).strength.effective(cracked(h, p)).1;
        let solve = |h: &mut History, states: [ContactState; 2]| {
            h.states = states.to_vec();
            mark_cracks(h);
        };
        solve(&mut h, [Slip, Open]);
        solve(&mut h, [Slip, Stick]);
        assert_eq!((cohesion(&h, 0), cohesion(&h, 1)), (0.5, 0.5), "one opening: the iteration feeling its way");
        solve(&mut h, [Stick, Open]);
        h.states = vec![Stick, Open];
        assert_eq!((cohesion(&h, 0), cohesion(&h, 1)), (0.5, 0.0), "slipped: the residual; parted: none");
        // closing after a move of 0.01 along the joint (force 0.1 < c = 0.5):
        // the slipped pair's cohesion holds it, the parted one slips
        let closing = Trial { force: [0.0; 3], area: 1.0, slip: [0.0, 0.01, 0.0], gap: -1e-3, stiffness: 10.0 };
        let judged = |p| judge(Open, &closing, &law_at(&h, &laws, p).strength, true, true, 1e-12, 0.0);
        assert_eq!((judged(0), judged(1)), (Stick, Slip));
        // parted is committed with the step and outlives it
        let solution = InterfaceSolution {
            pairs: Vec::new(),
            forces: vec![[0.0; 3]; 2],
            rel: vec![[0.0; 3]; 2],
            d_c: Vec::new(),
            residual: 0.0,
            accuracy: 0.0,
            loose: false,
            inexact: false,
            as_tied: vec![None; 2],
            water: Vec::new(),
            locked_off: Vec::new(),
        };
        h.states = vec![Stick, Slip];
        commit(&mut h, &solution);
        start_step(&mut h);
        assert_eq!((cohesion(&h, 0), cohesion(&h, 1)), (0.5, 0.0));
        // a cluster's set holding it stuck forgets the step's openings
        let mut g = History::new(1);
        start_step(&mut g);
        for s in [Open, Stick, Open, Stick] {
            g.states = vec![s];
            mark_cracks(&mut g);
        }
        forget_step_cracks(&mut g, [0]);
        assert_eq!(law_at(&g, &laws, 0).strength.residual_cohesion, 0.5);
    }
}
