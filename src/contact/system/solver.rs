//! The seam between the interface problem and its solvers: [`Solver`]
//! solves one set of relations and gives an [`Answer`].

use std::any::Any;
use std::sync::Arc;

use super::freedom::Freedom;
use crate::contact::law::ContactState;

/// Where a solver's next solve starts: its last answer and the state set
/// solved for it (an iterative solver starts from that answer, and stops
/// loose where the states changed). Taken after a solve and given back
/// before another, so that where a search starts a trial from a state
/// that held, its solves start from that state's answer, not from
/// whichever trial was solved last. Opaque: each solver reads its own;
/// empty for a direct solver.
#[derive(Clone, Default)]
pub struct WarmStart(pub(super) Option<Arc<dyn Any + Send + Sync>>);

/// A way of solving the interface system: the seam between
/// [`super::InterfaceProblem`] and its solvers ([`super::dense::Dense`],
/// [`super::sparse::Sparse`], [`super::iterative::Iterative`]).
pub trait Solver {
    /// Solves one set of relations, given by the free directions `fr` of
    /// the relative displacements (`states`: the state set, to tell whether
    /// it changed since the last solve), under the load factors `lambda`;
    /// `None` when the system is singular (the problem then finds out why).
    /// `accuracy`: how finely the forces must come out (an iterative
    /// solver's tolerance; a direct one is exact).
    fn solve(&self, fr: &Freedom, states: &[ContactState], lambda: &[f64], accuracy: Accuracy) -> Option<Answer>;
    /// The system's diagonal at relative displacement `r` (the scale that
    /// turns a pair's slip into a force).
    fn diagonal(&self, r: usize) -> f64;
    /// The diagonal at the relative displacements `rs` is about to be
    /// asked for: a solver that forms it on demand (the sparse interface,
    /// a substitution through its means' factor for each) forms those it
    /// lacks together.
    fn prepare_diagonal(&self, _rs: &[usize]) {}
    /// Applications of the parts' S by each solve so far (empty for a
    /// solver that formed S).
    fn counts(&self) -> Vec<usize>;
    /// Where the solves' time went, for a solver that times its stages.
    fn split(&self) -> Option<Split> {
        None
    }
    /// Where the next solve would start.
    fn warm_start(&self) -> WarmStart {
        WarmStart::default()
    }
    /// Starts the next solve where `start` says (taken from this solver).
    /// What a solver keeps between solves beyond the answer is formed
    /// afresh from there: the sparse interface forgets the preconditioner
    /// of the pairs that deform, which a loose answer depends on, so a
    /// trial's solves do not depend on the trial solved before it.
    fn start_from(&self, _start: &WarmStart) {}
}

/// Seconds of the sparse interface's solves, by stage (summed over them).
#[derive(Clone, Debug, Default)]
pub struct Split {
    /// Assembling and factorising the preconditioner's block of free
    /// relative displacements.
    pub factor: f64,
    /// GMRES: the operator's and the preconditioner's applications.
    pub gmres: f64,
    /// Of `gmres`, the substitutions through K_mm's factor.
    pub means: f64,
    /// Refining the means to double precision after GMRES.
    pub refine: f64,
    /// Of `factor`, computing W's columns (substitutions through K_mm's
    /// factor and sweeps of the parts).
    pub columns: f64,
    /// Where each solve starts: the last answer moved onto the new
    /// relations and K applied to it (what the equations lack).
    pub start: f64,
    /// Outside the solver, filled by [`super::InterfaceProblem`]: the
    /// checks of what holds the parts before each solve.
    pub checks: f64,
    /// Outside the solver: the free directions of each solve's relations
    /// (the junctions' ties).
    pub relations: f64,
    /// Outside the solver: the pairs' forces and the parts' displacements
    /// from each answer (the junctions' shares).
    pub forces: f64,
    /// W's diagonal where the pairs' stiffness is read (a substitution
    /// through K_mm's factor per relative displacement), and what it is
    /// formed from, at setup.
    pub diagonal: f64,
}

/// How finely a solve must resolve the forces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Accuracy {
    /// As the answer: the iterative interfaces' tight tolerance.
    Answer,
    /// A Newton step on the friction under held states, while the law is
    /// this far from met (the largest friction residual of a slipping
    /// pair, a force): a fraction of it is enough, an inexact Newton step
    /// (see [`super::iterative::tolerance`]).
    Step(f64),
    /// As the answer, even where the states changed since the last solve:
    /// late in a step, where the states it decides are not left to a
    /// loose solve ([`crate::contact::iteration`]).
    Tight,
}

impl Accuracy {
    /// Whether a solve whose states changed may stop at the iterative
    /// interfaces' loose tolerance.
    pub fn may_be_loose(self) -> bool {
        self != Accuracy::Tight
    }
}

/// What a [`Solver`] gives the interface problem.
pub struct Answer {
    /// The means and the relative displacements.
    pub m: Vec<f64>,
    pub r: Vec<f64>,
    /// `W r - c` (`K x - b` on the relative rows): `-λ`.
    pub residual_r: Vec<f64>,
    /// Relative residual of the solve.
    pub residual: f64,
    /// The residual of an iterative solve in force units (2-norm over the
    /// rows it solved; 0 for a direct solve): the forces are not resolved
    /// more finely than this.
    pub accuracy: f64,
    /// Solved to a loose tolerance (see [`super::InterfaceSolution::loose`]).
    pub loose: bool,
    /// Solved as a Newton step, to a fraction of the law's residual
    /// ([`Accuracy::Step`]) rather than the tight tolerance.
    pub inexact: bool,
}

/// Where the interface's solves put springs on every pair, which the
/// sparse interface builds for ([`super::sparse::Sparse::new`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Springs {
    /// Rigid joints only.
    Never,
    /// Every joint deforms (`normal_stiffness`).
    Always,
    /// Rigid joints whose steps the augmented Lagrangian rounds may solve
    /// again with springs on every pair ([`crate::contact::augmented`]).
    InRounds,
}
