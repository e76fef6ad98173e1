//! The state iteration of one load step, common to both rules ([`Rule`]),
//! as deal.II's step-41 reads: solve the interface with the current
//! relations, judge every pair from the result, stop when the states no
//! longer change (and the rule's forces have settled), when they cycle (a
//! rule that reports cycles) or after `max_iterations`. A state set that
//! leaves parts free to slide is put back to the rule first, which may keep
//! one of their pairs stuck (a Newton step that overshot) before it is a
//! loss of equilibrium. A pair solved slipping or open in an iteration
//! after the first has cracked in the step ([`super::cracked`]) and stays
//! so to its end. A converged step is committed once, by
//! [`super::history::commit`]: where it ended, and the cracks it made.

use super::history::{commit, mark_cracks, start_step, History};
use super::law::ContactState;
use super::outcome::{Failed, Outcome, Summary};
use super::system::{Accuracy, InterfaceProblem, InterfaceSolution, Relation, SolveFailure};

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
    /// What the rule keeps of a converged step beyond [`commit`].
    fn commit(self, _h: &mut History)
    where
        Self: Sized,
    {
    }
}

/// A rule's judgement of one solve.
pub(super) struct Verdict {
    pub next: Vec<ContactState>,
    /// The slipping pairs' forces agree with the law.
    pub settled: bool,
    /// How far they are from it (the largest friction residual, a force;
    /// 0 for a rule that does not linearise the friction).
    pub law: f64,
}

/// Runs `rule` under the load factors `lambda` from the states in `h`.
pub(super) fn run(
    mut rule: impl Rule,
    problem: &InterfaceProblem,
    lambda: &[f64],
    h: &mut History,
    max_iterations: usize,
) -> Result<Outcome, Failed> {
    let mut summary = Summary::default();
    let mut accuracy = Accuracy::Answer;
    start_step(h);
    loop {
        summary.iterations += 1;
        let solution = loop {
            match problem.solve(&rule.relations(h), lambda, accuracy) {
                Ok(solution) => break solution,
                Err(SolveFailure::Sliding(parts)) if rule.hold_back(h, &parts) => {}
                Err(failure) => {
                    return Err(Failed { failure, states: h.states.clone(), iteration: summary.iterations })
                }
            }
        };
        if summary.iterations > 1 {
            mark_cracks(h);
        }
        summary.history.push(h.states.clone());
        let Verdict { next, settled, law } = rule.judge(h, &solution, &mut summary);
        // (a loose or inexact interface solve is never the answer: the
        // next, with the same states, is solved tightly once the friction
        // has settled; until then each is a Newton step solved to a
        // fraction of the law's residual)
        summary.converged = next == h.states && settled && !solution.loose && !solution.inexact;
        accuracy = if settled { Accuracy::Answer } else { Accuracy::Step(law) };
        if summary.converged || summary.cycled || summary.iterations >= max_iterations {
            if summary.converged {
                commit(h, &solution);
                rule.commit(h);
            }
            let states = std::mem::replace(&mut h.states, next);
            return Ok(Outcome { states, solution, summary, law_residual: Vec::new(), cracked: Vec::new() });
        }
        h.states = next;
    }
}
