//! Rigid joints solved through stiff springs: augmented Lagrangian rounds
//! (`[solver] augmented_lagrangian`), where the semismooth Newton
//! iteration of [`super::newton`] does not end a step.
//!
//! Each round solves the step with every closed pair a spring of
//! stiffness `K = A diag(k_n, k_s, k_s)` (the return mapping of joints that
//! deform, [`super::elastic`]) loaded with a multiplier `μ`: its force is
//! `μ + K (r - t)`, t where the rigid joint holds it (its normal at 0, its
//! shear where the step started, or where it closed if it was open then:
//! [`Elastic::holding`]). Between rounds the multiplier takes the
//! force the round ended with (Uzawa's update, the augmented Lagrangian
//! treatment of frictional contact of Simo & Laursen 1992; a slipping
//! pair's is at its Coulomb bound, an open one's nothing), and the springs
//! stiffen [`GROWTH`]-fold up to [`STIFFEST`] times the first. At the fixed
//! point `r = t` wherever the pairs hold: the spring carries the
//! multiplier and stretches by nothing, so the forces are the rigid
//! joints' and keep their law. The rounds end where no closed pair's
//! spring stretches by more than [`CLOSED`] of the largest force.
//!
//! Why: on the jointed tunnels the rigid iteration's states wander among
//! crossing pairs at the edge of stick and slip (docs/convergence.md),
//! while springs make each of them strictly stick or slip, and a round of
//! them converges in a few iterations from the last; the multipliers then
//! take the stretch out of the springs. Measured on
//! tests/corpus/tunnel4sets_linear_fine.toml (rigid: 100 iterations, not
//! converged): 15 rounds, 66 iterations, stretch 7e-10 of the largest force;
//! the 34k tunnel (rigid: 300, not converged): 14 rounds, 93 iterations.
//! With fixed springs the stretch fell only 0.9-fold a round; stiffened
//! tenfold a round, a round's own iteration did not end (1,000 times).

use super::elastic::{springs, Elastic};
use super::frame::tangential;
use super::history::{opened_twice, History};
use super::iteration;
use super::law::{ContactState, Stiffness};
use super::outcome::Outcome;
use super::pair_law::PairLaw;
use super::system::InterfaceProblem;
use crate::fem::vec3::norm;

/// The springs stiffen this much a round ...
const GROWTH: f64 = 3.0;
/// ... up to this many times the first round's (3^8).
const STIFFEST: f64 = 6561.0;
/// The rounds end where no closed pair's spring stretches by more than
/// this fraction of the largest pair force (its stretch times its
/// stiffness): the rigid answer to well within the law's tolerance.
const CLOSED: f64 = 1e-9;
/// At most this many rounds.
const ROUNDS: usize = 20;
/// The rounds give up where the stretch has not fallen below this
/// fraction of what it was [`STALL_ROUNDS`] rounds before: a state set
/// whose rigid joints have no answer, where the multipliers grow without
/// end and the stretch falls as one over the rounds (the two-set tunnel
/// of tests/convergence.rs, rounds from its step's start with springs
/// capped at 81 times the first: 9.3e-4, 7.6e-4, 6.7e-4, 5.9e-4, 5.3e-4
/// ... of the largest force with the states unchanged, three pairs in
/// other states than those its rigid iteration ends in).
const STALL: f64 = 0.5;
const STALL_ROUNDS: usize = 4;

/// How the rounds went: how many, their iterations, and the last one's
/// largest stretch (of the largest force; infinite where a round's own
/// iteration did not end; the default, no rounds, only to add to).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rounds {
    pub rounds: usize,
    pub iterations: usize,
    pub stretch: f64,
}

impl Rounds {
    /// Whether they ended the step: the springs closed.
    pub fn closed(&self) -> bool {
        self.stretch <= CLOSED
    }

    /// These rounds counted after those `before` (of the pieces of a cut
    /// step before this one): theirs and these, and these' stretch.
    pub fn after(self, before: Option<Rounds>) -> Rounds {
        let b = before.unwrap_or_default();
        Rounds { rounds: b.rounds + self.rounds, iterations: b.iterations + self.iterations, stretch: self.stretch }
    }
}

/// Solves the step under `lambda` from the states in `h` by rounds of
/// springs of stiffness `k` (per unit area; the first round's), the
/// rounds' iterations `max_iterations` in all (as many as the Newton
/// attempt before them: a step whose rounds do not close takes at most
/// twice the iterations it did without them). Where the springs close,
/// the outcome, `h` committed as the rigid rule commits it; elsewhere
/// (a round that does not end, or fails; a stretch that stalls; no
/// rounds left) how far they went, `h` as it was.
pub(super) fn run(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    lambda: &[f64],
    h: &mut History,
    max_iterations: usize,
    k: Stiffness,
) -> Result<(Outcome, Rounds), Rounds> {
    let n = laws.len();
    let factor = lambda.get(h.insitu_case).copied().unwrap_or(0.0);
    // the multipliers start at the last step's forces, or the in-situ ones
    let mut mult: Vec<[f64; 3]> = (0..n)
        .map(|p| match h.insitu.get(p) {
            Some(f) if h.force[p] == [0.0; 3] => f.map(|x| factor * x),
            _ => h.force[p],
        })
        .collect();
    let mut target: Vec<[f64; 3]> = (h.rel_start.iter().map(|r| tangential(*r))).map(|t| [0.0, t[1], t[2]]).collect();
    let (mut states, mut warm) = (h.states.clone(), None);
    let (mut cracked, mut parted) = (h.cracked.clone(), h.parted.clone());
    let mut went = Rounds { rounds: 0, iterations: 0, stretch: f64::INFINITY };
    let (mut scale, mut stretches) = (1.0, Vec::new());
    for round in 0..ROUNDS {
        let kr = Stiffness { normal: k.normal * scale, shear: k.shear * scale };
        let spring_laws: Vec<PairLaw> = laws.iter().map(|l| PairLaw { stiffness: Some(kr), ..*l }).collect();
        let stiff = |p: usize| springs(kr, problem.area(p));
        let mut hr = h.clone();
        hr.states.clone_from(&states);
        (hr.cracked, hr.parted) = (cracked.clone(), parted.clone());
        // (each round linearised where the last ended)
        if let Some((rel, force)) = warm.take() {
            (hr.rel_start, hr.force) = (rel, force);
        }
        hr.unloaded = (0..n).map(|p| std::array::from_fn(|a| target[p][a] - mult[p][a] / stiff(p)[a])).collect();
        hr.offset.clone_from(&target);
        let rule = Elastic::new(problem, &spring_laws, &hr).holding(&h.states);
        let left = max_iterations.saturating_sub(went.iterations);
        if left == 0 {
            return Err(went);
        }
        let solved = iteration::run(rule, problem, &spring_laws, lambda, &mut hr, left.into());
        went.rounds = round + 1;
        went.iterations += solved.as_ref().map_or_else(|f| f.iteration, |o| o.summary.iterations);
        let Ok(outcome) = solved.inspect_err(|_| went.stretch = f64::INFINITY) else { return Err(went) };
        target.clone_from(&hr.offset);
        went.stretch =
            if outcome.summary.converged { update(&outcome, &target, stiff, &mut mult) } else { f64::INFINITY };
        if went.closed() {
            return Ok(finish(h, hr, outcome, went, &target));
        }
        let stalls = round >= STALL_ROUNDS && went.stretch > STALL * stretches[round - STALL_ROUNDS];
        if !outcome.summary.converged || stalls {
            return Err(went);
        }
        stretches.push(went.stretch);
        for p in 0..n {
            cracked[p] |= hr.cracked[p] || hr.cracking[p] || outcome.states[p] != ContactState::Stick;
            parted[p] |= hr.parted[p] || opened_twice(&hr, p);
        }
        states.clone_from(&outcome.states);
        warm = Some((outcome.solution.rel.clone(), outcome.solution.forces.clone()));
        scale = (scale * GROWTH).min(STIFFEST);
    }
    Err(went)
}

/// The largest stretch of a closed pair's spring (its force, of the
/// largest pair force) at the end of a round, `stiff` its springs; and
/// the multipliers `mult` made the round's forces (Uzawa's update).
fn update(outcome: &Outcome, target: &[[f64; 3]], stiff: impl Fn(usize) -> [f64; 3], mult: &mut [[f64; 3]]) -> f64 {
    let solution = &outcome.solution;
    let largest = solution.forces.iter().map(|f| norm(*f)).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    let mut stretch = 0.0f64;
    for (p, m) in mult.iter_mut().enumerate() {
        let (r, kp) = (solution.rel[p], stiff(p));
        let pulled: [f64; 3] = match outcome.states[p] {
            ContactState::Open => [0.0; 3],
            ContactState::Slip => [kp[0] * (r[0] - target[p][0]), 0.0, 0.0],
            ContactState::Stick => std::array::from_fn(|a| kp[a] * (r[a] - target[p][a])),
        };
        stretch = stretch.max(norm(pulled) / largest);
        *m = if outcome.states[p] == ContactState::Open { [0.0; 3] } else { solution.forces[p] };
    }
    stretch
}

/// The rounds' end in `h` as the rigid rule leaves it: no springs, the
/// stick references where the step started (an open pair's where it is),
/// the friction's directions those of the slipping pairs' forces.
fn finish(
    h: &mut History,
    mut hr: History,
    mut outcome: Outcome,
    went: Rounds,
    target: &[[f64; 3]],
) -> (Outcome, Rounds) {
    let solution = &outcome.solution;
    hr.unloaded = Vec::new();
    for p in 0..target.len() {
        hr.offset[p] = match outcome.states[p] {
            ContactState::Open => tangential(solution.rel[p]),
            _ => [0.0, target[p][1], target[p][2]],
        };
        let shear = tangential(solution.forces[p]);
        if outcome.states[p] == ContactState::Slip && norm(shear) > 0.0 {
            hr.dir[p] = shear.map(|x| x / norm(shear));
        }
        hr.sigma_n[p] = solution.pairs[p].sigma_n;
    }
    *h = hr;
    outcome.summary.iterations = went.iterations;
    (outcome, went)
}
