//! Contact between the parts: pairs, frames, the law and the state
//! iteration of the substructure interface method.
//!
//! Each iteration solves the interface system for one set of pair states
//! (stick: tied; slip: tied along the normal, a friction force along the
//! joint; open: free) and judges every pair from the result, until the
//! states and the friction forces no longer change. Two rules
//! (`[solver] rule`):
//!
//! - `robust` (default, [`newton`]): a semismooth Newton method on the
//!   condensed interface in the spirit of the primal-dual active set method
//!   of Hüeber, Stadler & Wohlmuth (SIAM J. Sci. Comput. 30(2), 2008): the
//!   stick/slip/open sets and the friction forces are found together; the
//!   friction force of a slipping pair is linearised in its slip and in its
//!   normal force (slip direction free in the joint plane), so that the
//!   iteration converges superlinearly once the sets settle;
//! - `paper` ([`paper`]): the paper's iteration, every pair judged by eq.
//!   15–17 from its stresses alone; a slipping pair carries the Coulomb
//!   shear of the last iteration along its last slip direction (zero with
//!   `slip = "frictionless"`); cycles are reported, not resolved.
//!
//! Both run one skeleton ([`iteration`]: solve, judge, stop) and commit a
//! converged step in one place ([`commit`]). Both keep the paper's law with
//! its extensions: Coulomb with cohesion,
//! tension cut-off, crack memory (a pair that opened or slipped keeps
//! `f_t = 0` and the residual cohesion: from the iteration it did so to the
//! end of its step, and in every step after a converged one), re-closure of
//! open pairs, and states, cracks and slip that carry over from load step
//! to load step (friction is path-dependent). Water in a joint ([`water`])
//! is a load on both faces of its pairs, so the force solved for is the
//! solid-to-solid one and the law judges the effective normal stress.

pub mod basis;
pub mod capacity;
mod cluster;
pub mod cutting;
pub mod frame;
mod iteration;
pub mod law;
pub mod mechanism;
pub mod mobility;
pub mod newton;
pub mod options;
pub mod paper_rule;
pub mod safety;
pub mod system;
pub mod traction;
pub mod water;

use law::{ContactState, Strength};
use system::{InterfaceProblem, InterfaceSolution, SolveFailure};

pub use options::{InterfaceSolver, SlipLaw, StateRule, TractionRecovery};

/// The law of one pair.
#[derive(Clone, Copy, Debug)]
pub struct PairLaw {
    pub strength: Strength,
    pub slip: SlipLaw,
}

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

/// How the state iteration of one step went.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    pub iterations: usize,
    pub converged: bool,
    /// A state set came back after other ones in between (paper rule: the
    /// iteration stops there).
    pub cycled: bool,
    /// Cycles broken by changing one pair at a time (robust rule).
    pub cycles_broken: usize,
    /// Stalls or cycles ended by solving the cluster of pairs they were
    /// on set by set (robust rule, [`cluster`]).
    pub clusters_solved: usize,
    /// Pairs opened in tension between the Coulomb apex c / f and f_t.
    pub apex_openings: usize,
    /// State sets of every iteration (the ones solved with).
    pub history: Vec<Vec<ContactState>>,
    /// Halvings of the load step ([`cutting`]): 0 when it was solved whole.
    pub cuts: usize,
    /// Where the pieces of a cut step that converged ended, as fractions
    /// of the step (empty when it was not cut).
    pub pieces: Vec<f64>,
    /// The piece of a cut step that did not converge at the deepest cut.
    pub stopped_at: Option<(f64, f64)>,
}

/// How the state iteration of one step ended: the states it ended with,
/// the last solve, and how it went.
pub struct Outcome {
    pub states: Vec<ContactState>,
    pub solution: InterfaceSolution,
    pub summary: Summary,
    /// How far each pair's stresses are from the law in its state
    /// ([`law::law_residual`] over its area): round-off where the
    /// iteration converged.
    pub law_residual: Vec<f64>,
    /// Every pair that has cracked by the step's end ([`cracked`]): in an
    /// earlier step, on the way through this one, or open or slipping at
    /// its end. What the outputs judge strength by (the residual cohesion,
    /// no tension).
    pub cracked: Vec<bool>,
}

/// A failed iteration: the failure and the states it happened with.
#[derive(Clone, Debug)]
pub struct Failed {
    pub failure: SolveFailure,
    pub states: Vec<ContactState>,
    pub iteration: usize,
}

/// Runs the state iteration of one load step under the load factors
/// `lambda`, starting from and updating `h`.
pub fn iterate(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    rule: StateRule,
    lambda: &[f64],
    h: &mut History,
    max_iterations: usize,
) -> Result<Outcome, Failed> {
    let mut outcome = match rule {
        StateRule::Robust => iteration::run(newton::Newton::new(problem, laws, h), problem, lambda, h, max_iterations),
        StateRule::Paper => iteration::run(paper_rule::Paper::new(problem, laws), problem, lambda, h, max_iterations),
    }?;
    let before: Vec<bool> = (h.cracked.iter().zip(&h.cracking)).map(|(a, b)| *a || *b).collect();
    outcome.law_residual = law_residuals(problem, laws, &before, &outcome);
    outcome.cracked = (before.iter().zip(&outcome.states)).map(|(c, s)| *c || *s != ContactState::Stick).collect();
    Ok(outcome)
}

/// Every pair's [`law::law_residual`] in the outcome's states, over its
/// area (stress units); `cracked`: cracked in an earlier step or earlier
/// in this one.
fn law_residuals(problem: &InterfaceProblem, laws: &[PairLaw], cracked: &[bool], o: &Outcome) -> Vec<f64> {
    (0..laws.len())
        .map(|p| {
            let (force, rel, area) = (o.solution.forces[p], o.solution.rel[p], problem.area(p));
            let trial = law::Trial { force, area, slip: [0.0; 3], gap: rel[0], stiffness: problem.stiffness(p) };
            let state = o.states[p];
            let cracked = cracked[p] || state != ContactState::Stick;
            let coulomb = laws[p].slip == SlipLaw::Coulomb;
            law::law_residual(state, &trial, &laws[p].strength, cracked, coulomb) / area
        })
        .collect()
}

/// The tangential part of a vector in a pair's local axes (n, t, b).
pub(crate) fn tangential(v: [f64; 3]) -> [f64; 3] {
    [0.0, v[1], v[2]]
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

/// What pair `p` can carry in force, by its law and whether it is cracked.
pub(crate) fn limit(law: &PairLaw, cracked: bool, area: f64) -> system::Limit {
    let (_, c) = law.strength.effective(cracked);
    system::Limit {
        tension: law.strength.tensile_limit(cracked) * area,
        cohesion: c * area,
        friction: law.strength.friction,
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
    use super::law::{judge, Trial};
    use super::*;
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
