//! How the state iteration of one step ended: its [`Outcome`] and
//! [`Summary`], or the [`Failed`] solve that stopped it.

use super::law::ContactState;
use super::system::{InterfaceSolution, SolveFailure};

/// Why a step's state iteration ended without converging: the one
/// record of it that the step's [`Summary`], errors, fallbacks and
/// safety trials carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Stop {
    /// It ran `[solver] max_iterations`, the states still changing.
    MaxIterations,
    /// A state set came back after other ones in between.
    Cycled,
    /// The states settled, but the last solve's forces break the law.
    LawBroken,
}

impl Stop {
    /// summary.json's `cycled`.
    pub fn cycled(self) -> bool {
        self == Stop::Cycled
    }

    /// summary.json's `law_broken`.
    pub fn law_broken(self) -> bool {
        self == Stop::LawBroken
    }
}

/// How the state iteration of one step went.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    pub iterations: usize,
    pub converged: bool,
    /// Why it ended without converging: `None` where it converged (or
    /// runs). A cycle is said first: the paper rule stops at one, and
    /// the law is judged only at states that settled ([`super::iteration`]).
    pub stop: Option<Stop>,
    /// Iterations that solved the last one's relations again, tightly
    /// (counted in `iterations`): a loose solve's verdict the cycle
    /// breaker could not be sure of, or a settled loose answer taken again
    /// late in the step ([`super::iteration::run`]).
    pub tight_resolves: usize,
    /// Where the Newton iteration did not end the step and it was solved
    /// again by augmented Lagrangian rounds (`[solver]
    /// augmented_lagrangian`): how many, and their springs' last stretch.
    /// `iterations` counts both.
    pub augmented: Option<super::augmented::Rounds>,
    /// Cycles broken by changing one pair at a time (robust rule).
    pub cycles_broken: usize,
    /// Stalls or cycles ended by solving the cluster of pairs they were
    /// on set by set (robust rule, `cluster`).
    pub clusters_solved: usize,
    /// Pairs opened in tension between the Coulomb apex c / f and f_t.
    pub apex_openings: usize,
    /// State sets of every iteration (the ones solved with).
    pub history: Vec<Vec<ContactState>>,
    /// Halvings of the load step ([`super::cutting`]): 0 when it was solved whole.
    pub cuts: usize,
    /// Where the pieces of a cut step that converged ended, as fractions
    /// of the step (empty when it was not cut).
    pub pieces: Vec<f64>,
    /// The step did not converge and was not cut, being the same problem
    /// at any load ([`super::cutting::scales`]): a half of it repeats it.
    pub scaled: bool,
    /// The piece of a cut step that did not converge at the deepest cut.
    pub stopped_at: Option<(f64, f64)>,
    /// The strength factors an initial stage was brought down through
    /// ([`super::ramp`]), the first the in-situ mobilisation, the last 1
    /// where it converged; empty where it was solved at the strength given.
    pub strengths: Vec<f64>,
}

impl Summary {
    /// Why a step that did not converge stopped (read only where it did
    /// not: a converged one has no [`Stop`]).
    pub fn why_not(&self) -> Stop {
        self.stop.unwrap_or(Stop::MaxIterations)
    }

    /// A state set came back after other ones in between.
    pub fn cycled(&self) -> bool {
        self.stop == Some(Stop::Cycled)
    }

    /// Ends the summary of an iteration that stops: converged where its
    /// states settled (`unchanged`) and their forces keep the law, else
    /// why not, a cycle said first.
    pub(super) fn end(&mut self, unchanged: bool, law_broken: bool) {
        self.converged = unchanged && !law_broken;
        self.stop = if self.converged {
            None
        } else if self.cycled() {
            Some(Stop::Cycled)
        } else if law_broken {
            Some(Stop::LawBroken)
        } else {
            Some(Stop::MaxIterations)
        };
    }
}

/// How the state iteration of one step ended: the states it ended with,
/// the last solve, and how it went.
pub struct Outcome {
    pub states: Vec<ContactState>,
    pub solution: InterfaceSolution,
    pub summary: Summary,
    /// How far each pair's stresses are from the law in its state
    /// ([`super::law::law_residual`] over its area): round-off where the
    /// iteration converged.
    pub law_residual: Vec<f64>,
    /// Every pair that has cracked by the step's end
    /// ([`super::history::cracked`]): in an earlier step, on the way
    /// through this one, or open or slipping at its end. What the outputs
    /// judge strength by (the residual cohesion, no tension).
    pub cracked: Vec<bool>,
}

/// A failed iteration: the failure and the states it happened with.
#[derive(Clone, Debug)]
pub struct Failed {
    pub failure: SolveFailure,
    pub states: Vec<ContactState>,
    pub iteration: usize,
    /// The augmented Lagrangian rounds among the iterations, where the
    /// step was solved again by them and they did not end it either.
    pub augmented: Option<super::augmented::Rounds>,
}
