//! The state iteration of one load step, common to both rules ([`Rule`]),
//! as deal.II's step-41 reads: solve the interface with the current
//! relations, judge every pair from the result, stop when the states no
//! longer change (and the rule's forces have settled), when they cycle (a
//! rule that reports cycles) or after `max_iterations`. Settled states
//! of the robust rule have converged only if every pair meets the law with
//! the forces the step reports ([`LAW_TOLERANCE`]); where one does not,
//! the step ends unconverged there (and is cut, [`super::cutting`]). A state set that
//! leaves parts free to slide is put back to the rule first, which may keep
//! one of their pairs stuck (a Newton step that overshot) before it is a
//! loss of equilibrium. A pair solved slipping or open in an iteration
//! after the first has cracked in the step ([`super::history::cracked`]) and stays
//! so to its end. A converged step is committed once, by
//! [`super::history::commit`]: where it ended, and the cracks it made.

use super::frame::tangential;
use super::history::{commit, cracked, law_at, mark_cracks, start_step, History};
use super::law::{law_residual, stiffness_in, ContactState, Trial};
use super::options::SlipLaw;
use super::outcome::{Failed, Outcome, Summary};
use super::pair_law::PairLaw;
use super::system::{Accuracy, InterfaceProblem, InterfaceSolution, Relation, SolveFailure};
use crate::fem::vec3::{norm, sub};

/// A state rule: the relations each iteration solves with, and the verdict
/// on what came out.
pub(super) trait Rule {
    /// The relation of every pair for the next solve.
    fn relations(&self, h: &History) -> Vec<Relation>;
    /// Judges a solution: every pair's next state (updating what the rule
    /// carries in `h`), and whether the friction forces have settled. A
    /// rule may count into `summary` (cycles broken, apex openings) and
    /// mark it `cycled` to stop the iteration there.
    fn judge(&mut self, h: &mut History, solution: &InterfaceSolution, summary: &mut Summary) -> Verdict;
    /// The states in `h`, the last verdict's, leave the parts `sliding`
    /// free to slide: a rule may keep one of their pairs stuck instead
    /// (true), and the step is solved again; false: the parts do slide.
    fn hold_back(&mut self, _h: &mut History, _sliding: &[usize]) -> bool {
        false
    }
    /// The states in `h`, the last verdict's, could not be solved (parts
    /// held by nothing or sliding freely, and not held back): a rule may
    /// judge them again from a shorter step (true), and the step is solved
    /// again; false: the failure stands.
    fn step_back(&mut self, _h: &mut History) -> bool {
        false
    }
    /// Whether settled states must also meet the law with the forces the
    /// step reports to have converged ([`LAW_TOLERANCE`]).
    fn answers_to_the_law(&self) -> bool {
        true
    }
    /// Where each pair's slip in this step is measured from (its stick
    /// reference along the joint): the law's residual then checks that a
    /// slipping pair's friction runs along its slip ([`law_residual`]).
    /// None: it checks magnitudes alone.
    fn slip_reference(&self) -> Option<&[[f64; 3]]> {
        None
    }
    /// What the rule keeps of a converged step beyond [`commit`].
    fn commit(self, _h: &mut History)
    where
        Self: Sized,
    {
    }
}

/// A rule's judgement of one solve.
pub(super) struct Verdict {
    pub next: Next,
    /// The slipping pairs' forces agree with the law.
    pub settled: bool,
    /// How far they are from it (the largest friction residual, a force;
    /// 0 for a rule that does not linearise the friction).
    pub law: f64,
}

/// What a rule makes of a solve's states.
pub(super) enum Next {
    /// Every pair's next state.
    States(Vec<ContactState>),
    /// The solve was loose and left undecided a change the rule waits to
    /// see decided: the same relations are solved again tightly and
    /// judged again, as an exact solver's answer would have been (at the
    /// step's last iteration, the states are kept).
    Again,
}

/// Solves the interface system with `relations`; where the states they
/// hold leave a part sliding or unheld, `rule` holds a pair back or steps
/// back and the relations of its new states are solved instead.
fn solve(
    rule: &mut impl Rule,
    problem: &InterfaceProblem,
    h: &mut History,
    relations: &mut Vec<Relation>,
    lambda: &[f64],
    accuracy: Accuracy,
) -> Result<InterfaceSolution, SolveFailure> {
    loop {
        match problem.solve(relations, lambda, accuracy) {
            Ok(solution) => return Ok(solution),
            Err(SolveFailure::Sliding(parts)) if rule.hold_back(h, &parts) => *relations = rule.relations(h),
            Err(_) if rule.step_back(h) => *relations = rule.relations(h),
            Err(failure) => return Err(failure),
        }
    }
}

/// How many iterations a step takes: `most`, and up to `settling` while
/// its states have all but settled ([`all_but_settled`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limit {
    pub most: usize,
    pub settling: usize,
}

impl From<usize> for Limit {
    /// `n` iterations, settling or not.
    fn from(n: usize) -> Limit {
        Limit { most: n, settling: n }
    }
}

impl Limit {
    /// Whether a step may go past `most` (while it all but settles).
    pub fn runs_on(self) -> bool {
        self.settling > self.most
    }

    /// The iterations of a step whose states went through `history`
    /// (one set an iteration, the last the current one).
    fn of(self, history: &[Vec<ContactState>]) -> usize {
        if self.runs_on() && all_but_settled(history) {
            self.settling
        } else {
            self.most
        }
    }
}

/// A step whose last [`SETTLING_WINDOW`] iterations each changed at most
/// [`SETTLING_CHANGES`] pairs has all but settled: its path is not a
/// wander. Measured at the 30th iteration (docs/convergence.md, "A rigid
/// step held to 30 iterations where the fallback follows"): the 44k
/// tunnel on the iterative interface changed 0 or 1 pairs an iteration
/// from its 20th and converged at its 35th; the steps that do not end in
/// 100 changed 6 to 30 (tunnel4sets_linear_fine), 13 to 24
/// (slope3d_c005's step 3) and hundreds (dam3d's step 2, a burst).
fn all_but_settled(history: &[Vec<ContactState>]) -> bool {
    let changes = |w: &[Vec<ContactState>]| w[0].iter().zip(&w[1]).filter(|(a, b)| a != b).count();
    history.len() > SETTLING_WINDOW
        && history[history.len() - SETTLING_WINDOW - 1..].windows(2).all(|w| changes(w) <= SETTLING_CHANGES)
}

/// The iterations [`all_but_settled`] looks back over, and the changes of
/// state it allows in each.
const SETTLING_WINDOW: usize = 10;
const SETTLING_CHANGES: usize = 2;

/// Runs `rule` under the load factors `lambda` from the states in `h`,
/// for at most `limit`'s iterations.
pub(super) fn run(
    mut rule: impl Rule,
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    lambda: &[f64],
    h: &mut History,
    limit: Limit,
) -> Result<Outcome, Failed> {
    let mut summary = Summary::default();
    let mut accuracy = Accuracy::Answer;
    // the relations of a settled solve that was not tight, to solve again
    let mut tighten: Option<Vec<Relation>> = None;
    start_step(h);
    loop {
        summary.iterations += 1;
        let retightened = tighten.is_some();
        summary.tight_resolves += usize::from(retightened);
        let mut relations = tighten.take().unwrap_or_else(|| rule.relations(h));
        let solution = solve(&mut rule, problem, h, &mut relations, lambda, accuracy).map_err(|failure| Failed {
            failure,
            states: h.states.clone(),
            iteration: summary.iterations,
            augmented: None,
        })?;
        if summary.iterations > 1 {
            mark_cracks(h);
        }
        summary.history.push(h.states.clone());
        let max_iterations = limit.of(&summary.history);
        let Verdict { next, settled, law } = rule.judge(h, &solution, &mut summary);
        let next = match next {
            // (a change a loose solve left undecided: its system, solved tightly)
            Next::Again if summary.iterations < max_iterations => {
                (tighten, accuracy) = (Some(relations), Accuracy::Tight);
                continue;
            }
            Next::Again => h.states.clone(),
            Next::States(next) => next,
        };
        // (a loose or inexact interface solve is never the answer: the
        // next, with the same states, is solved tightly once the friction
        // has settled; until then each is a Newton step solved to a
        // fraction of the law's residual)
        let settles = next == h.states && settled;
        let unchanged = settles && !solution.loose && !solution.inexact;
        // From TIGHTEN_AFTER on, every solve is tight, a change of states
        // too: a path that long is not left to answers that stop at 1e-6
        // of the load wherever the preconditioner takes them. The
        // unconfined block mass of tests/corpus.rs (rigid step 1, 53
        // iterations) did not converge in 100 with solves that differed
        // from these by round-off (W formed entry by entry), and did
        // with late tight ones; a step that converges sooner pays nothing.
        accuracy = match settled {
            _ if summary.iterations + 1 >= TIGHTEN_AFTER => Accuracy::Tight,
            true => Accuracy::Answer,
            false => Accuracy::Step(law),
        };
        // A settled solve that was not tight is solved again with its own
        // relations, not with the next Newton step's: the answer of the
        // system the verdict accepted, as an exact solver gives it. Taking
        // another step moved a junction's lagged pressure on the sparse
        // interface (the tunnel with two sets at lc 3: pair 41's force
        // (-0.634, -0.006, -0.444) -> (-0.622, -0.007, -0.452) with the
        // same states and residual) and set two pairs cycling, 400
        // iterations where the dense interface converged in 32
        // (tests/interface_paths.rs). Once: a solve that stays loose goes
        // on; and only late in a step ([`TIGHTEN_AFTER`]).
        if settles && !unchanged && !retightened && summary.iterations >= TIGHTEN_AFTER {
            tighten = Some(relations);
        }
        let stops = unchanged || summary.cycled() || summary.iterations >= max_iterations;
        if stops {
            return Ok(Stopped { solution, summary, next, unchanged }.end(rule, problem, laws, h));
        }
        h.states = next;
    }
}

/// Where a step's iteration stopped: its last `solution` and `summary`,
/// the states its verdict left (`next`), and whether they were
/// `unchanged`.
struct Stopped {
    solution: InterfaceSolution,
    summary: Summary,
    next: Vec<ContactState>,
    unchanged: bool,
}

impl Stopped {
    /// The step's outcome: converged where the states settled and keep the
    /// law, and then committed.
    fn end(self, rule: impl Rule, problem: &InterfaceProblem, laws: &[PairLaw], h: &mut History) -> Outcome {
        let Stopped { solution, mut summary, next, unchanged } = self;
        let law_residual = law_residuals(problem, laws, h, &solution, rule.slip_reference());
        let breaks = unchanged && rule.answers_to_the_law() && breaks_law(problem, &law_residual, &solution);
        summary.end(unchanged, breaks);
        if summary.converged {
            commit(h, &solution);
            rule.commit(h);
        }
        let states = std::mem::replace(&mut h.states, next);
        Outcome { states, solution, summary, law_residual, cracked: Vec::new() }
    }
}

/// A step whose states have settled has converged only where every pair
/// meets the law with the forces it reports to within this fraction of the
/// largest pair traction (what tests/corpus.rs asserts of summary.json).
/// The rules judge a junction pair by forces its loop could carry, which
/// are not those reported (`InterfaceSolution::as_tied`): two pairs of the
/// 2D dam on jointed rock (tests/corpus/dam2d_f070.toml) were judged
/// slipping by those and reported slipping in tension beyond their
/// strength, law residual 0.13 of the largest traction, in a step said to
/// have converged.
const LAW_TOLERANCE: f64 = 1e-6;

/// From this iteration of a step on, a settled answer that was not tight
/// is solved again with its own relations (see [`run`]); before it, the
/// next Newton step both refines and tightens it, which ends sooner where
/// the lagged forces settle: the 10 m jointed tunnel (tests/convergence.rs)
/// converges in 24 so, in 32 with every such answer solved again. From
/// it on, too, every solve is tight ([`Accuracy::Tight`]), the states it
/// decides not left to a loose one. The corpus' bound on a step's
/// iterations.
const TIGHTEN_AFTER: usize = 30;

/// Every pair's [`law_residual`] in the states of `h` with the forces of
/// `solution`, over its area (stress units): the step's answer as
/// summary.json reports it. A pair is cracked as [`cracked`] says (in an
/// earlier step, earlier in this one, or open or slipping now). A pair's
/// slip is measured from `reference` where the rule gives one, and counts
/// where its stiffness makes of it a force beyond [`LAW_TOLERANCE`] of the
/// largest force (below it, a slip has no direction the law could check).
/// A joint that deforms opens from where its normal spring is unloaded
/// (`History::unloaded`).
fn law_residuals(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    h: &History,
    solution: &InterfaceSolution,
    reference: Option<&[[f64; 3]]>,
) -> Vec<f64> {
    let scale = solution.forces.iter().map(|&f| norm(f)).fold(0.0, f64::max);
    (0..laws.len())
        .map(|p| {
            let (force, rel, area) = (solution.forces[p], solution.rel[p], problem.area(p));
            let gap = rel[0] - h.unloaded.get(p).map_or(0.0, |r0| r0[0]);
            // (a joint that deforms: its shear spring, which the slip acts on)
            let own = || laws[p].stiffness.map_or_else(|| problem.stiffness(p), |k| area * k.shear);
            let stiffness = stiffness_in(h.states[p], gap, own);
            let slip = reference.map_or([0.0; 3], |r| sub(tangential(rel), tangential(r[p])));
            let slip = if stiffness * norm(slip) > LAW_TOLERANCE * scale { slip } else { [0.0; 3] };
            let trial = Trial { force, area, slip, gap, stiffness };
            let law = law_at(h, laws, p);
            let coulomb = law.slip == SlipLaw::Coulomb;
            law_residual(h.states[p], &trial, &law.strength, cracked(h, p), coulomb) / area
        })
        .collect()
}

/// Whether a pair's residual (`residual`, stress units) exceeds
/// [`LAW_TOLERANCE`] of the largest pair traction, plus what the interface
/// solve resolved its force to (`InterfaceSolution::accuracy` over its area).
fn breaks_law(problem: &InterfaceProblem, residual: &[f64], solution: &InterfaceSolution) -> bool {
    let scale = solution.pairs.iter().map(|r| r.sigma_n.hypot(r.tau())).fold(0.0, f64::max);
    (residual.iter().enumerate()).any(|(p, &r)| r > LAW_TOLERANCE * scale + solution.accuracy / problem.area(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ContactState::{Open, Slip, Stick};

    #[test]
    fn a_step_goes_past_its_most_iterations_only_while_all_but_settled() {
        let limit = Limit { most: 30, settling: 100 };
        // eleven iterations, each changing one pair of three: settling
        let turns: Vec<Vec<ContactState>> =
            (0..11).map(|k| if k % 2 == 0 { vec![Stick, Slip, Open] } else { vec![Stick, Stick, Open] }).collect();
        assert_eq!(limit.of(&turns), 100);
        // one of them changing all three: a wander, held to `most`
        let mut wander = turns.clone();
        wander[5] = vec![Slip, Open, Stick];
        assert_eq!(limit.of(&wander), 30);
        // too short a path to tell
        assert_eq!(limit.of(&turns[..10]), 30);
        // a plain number is a limit either way
        assert_eq!(Limit::from(12).of(&turns), 12);
    }
}
