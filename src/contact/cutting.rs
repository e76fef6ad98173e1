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
//! not converge (`driver::fallback`), the pieces are a last try before
//! it and each takes at most [`PIECE_ITERATIONS`] ([`Budget`]); the
//! step solved whole keeps `max_iterations`, as do the pieces where
//! nothing follows them.
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
use super::iterate;
use super::options::StateRule;
use super::outcome::{Failed, Outcome};
use super::pair_law::PairLaw;
use crate::contact::system::InterfaceProblem;

/// The most iterations a cut piece takes where joints that deform take
/// over a step its rigid joints do not end (`driver::fallback`): the
/// corpus' bound on a step. A piece carries half its parent's load or
/// less, from where its parent started. On the three corpus scenes whose
/// rigid joints fall back (blocks3d, dam3d, slope3d_c005), the pieces
/// that converged took 3 to 5 iterations but one (blocks3d's first half,
/// 48), and every other piece ran its whole `max_iterations` (100) or
/// stopped at a set that broke the law after 48 to 90; no step ended
/// rigid through its cuts. Their rigid attempts took 411, 396 and 359
/// iterations, 201, 190 and 190 with this bound, to the same fallback
/// answers (docs/convergence.md, "A cut piece's iterations where the
/// fallback follows").
pub const PIECE_ITERATIONS: usize = 30;

/// What a load step may spend: its iterations and halvings
/// ([`iterate_cutting`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Iterations of the step solved whole (`[solver] max_iterations`).
    pub iterations: usize,
    /// Halvings where it does not converge (`[solver] max_cuts`).
    pub cuts: usize,
    /// Iterations of each cut piece: `iterations`, or fewer
    /// ([`Budget::short_pieces`]).
    pub piece: usize,
}

impl Budget {
    /// `iterations` for the step whole and for each of its pieces, halved
    /// down to `cuts` times.
    pub fn new(iterations: usize, cuts: usize) -> Budget {
        Budget { iterations, cuts, piece: iterations }
    }

    /// The same, with each cut piece given at most [`PIECE_ITERATIONS`].
    pub fn short_pieces(self) -> Budget {
        Budget { piece: self.piece.min(PIECE_ITERATIONS), ..self }
    }

    /// The iterations of a piece halved `depth` times.
    pub(super) fn at(self, depth: usize) -> usize {
        if depth == 0 {
            self.iterations
        } else {
            self.piece
        }
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
        let mut outcome = iterate(problem, laws, rule, &at(b), h, budget.at(depth)).map_err(|mut f| {
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
    fn a_short_budget_shortens_the_cut_pieces_alone() {
        let budget = Budget::new(100, 3);
        assert_eq!((budget.at(0), budget.at(1), budget.at(3)), (100, 100, 100));
        let short = budget.short_pieces();
        assert_eq!((short.at(0), short.at(1), short.at(3), short.cuts), (100, PIECE_ITERATIONS, PIECE_ITERATIONS, 3));
        // never more than the step's own budget
        let few = Budget::new(8, 4).short_pieces();
        assert_eq!((few.at(0), few.at(2)), (8, 8));
    }
}
