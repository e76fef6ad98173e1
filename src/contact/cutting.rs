//! Load-step cutting, as CalculiX's increment control: a load step whose
//! state iteration does not converge is solved again in two halves from
//! where the last converged step ended, a half that does not converge in
//! two quarters, and so on down to `max_cuts` halvings. Each piece that
//! converges is committed ([`super::history::commit`]) and carries its states,
//! cracks and slip into the next, so a path-dependent law follows the
//! finer load path. A piece that still does not converge at the deepest
//! cut ends the step unconverged, as an uncut step would.
//!
//! A piece starts where the attempt it replaces started: its history,
//! and the interface solver's warm start (the last answer an iterative
//! solve begins at: [`InterfaceProblem::start_from`]), as the safety
//! search starts each trial. From the failed attempt's last iterate,
//! far off any equilibrium, the first half of the 3D slope's step 3
//! (tests/corpus/slope3d_c005.toml) went through 100 state sets and did
//! not converge; from where the step started, it converges in 3.
//!
//! Where rigid joints fall back to joints that deform when a step does
//! not converge (`driver::fallback`), the step and its pieces are a try
//! before it and each takes at most [`SHORT_ITERATIONS`] ([`Budget`]);
//! where nothing follows them they take `max_iterations`.
//!
//! A failure other than non-convergence (a body held by nothing, a
//! singular interface) is not the step size's: it is returned at once
//! (where rigid joints may fall back, the run then tries joints that
//! deform, which tell the scene's failure from an iterate's:
//! `driver::fallback::fall_unheld`).
//!
//! Under proportional loading a cohesionless joint's states do not depend
//! on the load's size (the problem is homogeneous), so cutting only helps
//! where the path matters: cohesion and tension that crack, load cases
//! that do not grow together, slip that accumulates. A piece that is the
//! same problem at any load ([`scales`]) is therefore not cut: its first
//! half would repeat its iterations at half the load, and so on down
//! (the 34k tunnel of docs/convergence.md, three cuts: each repeated
//! the whole step's 100 state sets, its law residual halved).

use super::augmented::Rounds;
use super::history::History;
use super::options::StateRule;
use super::outcome::{Failed, Outcome};
use super::pair_law::PairLaw;
use super::{iterate, Limit};
use crate::contact::system::InterfaceProblem;

/// The most iterations a load step, and each cut piece of it, takes
/// where joints that deform take over a step its rigid joints do not
/// end (`driver::fallback`): the corpus' bound on a step. On the corpus
/// no rigid step that needed more ended rigid: blocks3d's step 1 (51)
/// came before a step 2 that fell back, and every other step or piece
/// that went past 30 ran its `max_iterations` (100) or stopped at a set
/// that broke the law. Those iterations were most of the four
/// fallback runs' time; with this bound the runs take 14.5 -> 6.5 s
/// (tunnel4sets_linear_fine), 106 -> 54 s (slope3d_c005), 168 -> 40 s
/// (blocks3d) and 395 -> 139 s (dam3d), to the same answers
/// (docs/convergence.md, "A rigid step held to 30 iterations where the
/// fallback follows"). A step whose states have all but settled by then
/// goes on to `max_iterations` ([`Limit`]): the 44k tunnel on the
/// iterative interface converges so in 35. With `rigid_fallback = false`
/// a step takes `max_iterations`.
pub const SHORT_ITERATIONS: usize = 30;

/// What a load step may spend: its iterations, whole and in each cut
/// piece, and its halvings ([`iterate_cutting`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Iterations of the step solved whole, and of each of its pieces
    /// (`[solver] max_iterations`, or fewer: [`Budget::short`]).
    pub iterations: Limit,
    /// Halvings where it does not converge (`[solver] max_cuts`).
    pub cuts: usize,
}

impl Budget {
    /// `iterations` for the step whole and for each of its pieces, halved
    /// down to `cuts` times.
    pub fn new(iterations: usize, cuts: usize) -> Budget {
        Budget { iterations: iterations.into(), cuts }
    }

    /// The same, with the step and each cut piece given at most
    /// [`SHORT_ITERATIONS`], or their own while their states have all
    /// but settled (a slow step, not a wander: [`Limit`]).
    pub fn short(self) -> Budget {
        let settling = self.iterations.settling;
        Budget { iterations: Limit { most: settling.min(SHORT_ITERATIONS), settling }, ..self }
    }
}

/// An attempt of a step that was cut, as it ends: the whole step that is
/// halved, or a piece. What a caller may tell as a long step goes
/// ([`iterate_cutting`]'s `told`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attempt {
    /// Where it started and ended, as fractions of the step.
    pub from: f64,
    pub to: f64,
    pub iterations: usize,
    pub converged: bool,
    /// It stopped in a closed orbit of state sets (`Stop::Cycled`).
    pub cycled: bool,
    /// It did not converge, and is solved again in two halves.
    pub halved: bool,
    /// A piece of the initial stage's strength ramp ([`super::ramp`]):
    /// the joints' strength where it starts and ends, as multiples of
    /// theirs (`from` and `to` are then fractions of the ramp).
    pub strength: Option<(f64, f64)>,
}

impl Attempt {
    /// The attempt from `from` to `to` (fractions of its step) whose
    /// iteration ended with `summary`, `halved` or not: a load's piece.
    pub(super) fn of(summary: &super::Summary, (from, to): (f64, f64), halved: bool) -> Attempt {
        let (iterations, converged, cycled) = (summary.iterations, summary.converged, summary.cycled());
        Attempt { from, to, iterations, converged, cycled, halved, strength: None }
    }
}

/// Runs the load step from the factors `from` (where `h` ended) to `to`,
/// cutting it in halves down to `budget.cuts` times where the iteration
/// does not converge, and handing `told` each [`Attempt`] of a step so
/// cut as it ends. The outcome is the last piece's; its summary counts
/// the iterations of every attempt and lists the pieces taken
/// ([`super::Summary::pieces`]) when the step was cut.
pub fn iterate_cutting(
    problem: &InterfaceProblem,
    laws: &[PairLaw],
    rule: StateRule,
    (from, to): (&[f64], &[f64]),
    h: &mut History,
    budget: Budget,
    told: &mut dyn FnMut(Attempt),
) -> Result<Outcome, Failed> {
    let at = |t: f64| -> Vec<f64> { from.iter().zip(to).map(|(a, b)| a + t * (b - a)).collect() };
    // pieces still to solve, the next on top: (start, end, depth) as fractions of the step
    let mut todo = vec![(0.0, 1.0, 0usize)];
    let (mut iterations, mut resolves, mut augmented) = (0, 0, None::<Rounds>);
    let mut pieces = Vec::new();
    let mut cuts = 0;
    loop {
        let (a, b, depth) = todo.pop().expect("a piece is left until the last one ends the loop");
        let scaled = depth < budget.cuts && scales(problem, laws, &at(a), h);
        let saved = (depth < budget.cuts && !scaled).then(|| (h.clone(), problem.warm_start()));
        let mut outcome = iterate(problem, laws, rule, &at(b), h, budget.iterations).map_err(|mut f| {
            f.iteration += iterations;
            f.augmented = f.augmented.map(|r| r.after(augmented)).or(augmented);
            f
        })?;
        iterations += outcome.summary.iterations;
        resolves += outcome.summary.tight_resolves;
        if let Some(r) = outcome.summary.augmented {
            augmented = Some(r.after(augmented));
        }
        let converged = outcome.summary.converged;
        let ended = converged || saved.is_none();
        if converged {
            pieces.push(b);
        }
        if depth > 0 || !ended {
            told(Attempt::of(&outcome.summary, (a, b), !ended));
        }
        if ended && (todo.is_empty() || !converged) {
            outcome.summary.scaled = scaled && !converged;
            outcome.summary.iterations = iterations;
            outcome.summary.tight_resolves = resolves;
            outcome.summary.augmented = augmented;
            outcome.summary.cuts = cuts;
            if cuts > 0 {
                outcome.summary.pieces = pieces;
                outcome.summary.stopped_at = (!converged).then_some((a, b));
            }
            return Ok(outcome);
        }
        if let Some((saved, start)) = saved.filter(|_| !converged) {
            *h = saved;
            problem.start_from(&start);
            cuts += 1;
            let mid = 0.5 * (a + b);
            todo.push((mid, b, depth + 1));
            todo.push((a, mid, depth + 1));
        }
    }
}

/// Whether the piece that starts at the load factors `start` is the same
/// problem at any size of its load: it starts from no load, with nothing
/// carried over in force or displacement in `h` (its states and cracks
/// are restored for each piece alike), on joints whose strength is their
/// friction alone, with no water in them. Every force its iteration
/// solves for is then linear in the load, and every judgement of the law
/// and every tolerance is relative to it: its first half is itself at
/// half the load, and halving it cannot help.
pub(super) fn scales(problem: &InterfaceProblem, laws: &[PairLaw], start: &[f64], h: &History) -> bool {
    let zero = |v: &[[f64; 3]]| v.iter().all(|x| *x == [0.0; 3]);
    let strength_is_friction = |l: &PairLaw| {
        let s = &l.strength;
        s.cohesion == 0.0 && s.tensile_strength == 0.0 && s.residual_cohesion == 0.0
    };
    start.iter().all(|&x| x == 0.0)
        && problem.water().is_none()
        && laws.iter().all(strength_is_friction)
        && zero(&h.offset)
        && zero(&h.rel_start)
        && zero(&h.force)
        && zero(&h.unloaded)
        && h.sigma_n.iter().all(|&x| x == 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_budget_shortens_the_step_and_its_pieces() {
        let short = Budget::new(100, 3).short();
        assert_eq!((short.iterations, short.cuts), (Limit { most: SHORT_ITERATIONS, settling: 100 }, 3));
        // never more than the step's own budget
        assert_eq!(Budget::new(8, 4).short(), Budget::new(8, 4));
    }
}
