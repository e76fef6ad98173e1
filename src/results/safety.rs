//! What a safety search found ([`SafetyRun`]): the factor of safety F (the
//! largest factor that held) and the smallest that failed, both from
//! converged trials, the trials that decided nothing, why and where it
//! failed ([`Failure`]: the blocks that move and how, the pairs' states),
//! every trial in order ([`Trial`]), the last converged state at F, the
//! factor with the other strength convention ([`OtherFactor`]), and what
//! the search cost ([`SearchCost`]: contact iterations, not
//! factorisations). Plain data, like the rest of [`crate::results`].

use super::step::StepResult;
use crate::contact::law::ContactState;
use crate::contact::mechanism::Mechanism;
use crate::contact::safety::Strengths;
use crate::contact::Stop;

/// What a search varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SearchKind {
    /// Strength reduction, each pair keeping the strength said once it cracks.
    Strength(Strengths),
    /// A load factor search: the chosen loads multiplied by F.
    Load,
}

/// The safety search of a run.
pub struct SafetyRun {
    pub kind: SearchKind,
    /// The largest factor that held; None when a search below 1 found none
    /// down to 1 / max_factor.
    pub factor: Option<f64>,
    /// The smallest factor that failed; None when the search reached
    /// `max_factor` and the scene held there (F is at least the bound), or
    /// when no trial above the last hold converged.
    pub fails_at: Option<f64>,
    /// Why the trial at `fails_at` failed.
    pub failure: Option<Failure>,
    /// Converged trials closed the bracket to the tolerance (or reached the
    /// bound holding): the factor is what it says.
    pub decided: bool,
    /// Trials whose iteration did not converge even when retried.
    pub undecided: Vec<Undecided>,
    /// The scene loses equilibrium as given (F = 1): F was sought below 1,
    /// each trial running the load steps from the start.
    pub below_one: bool,
    /// The factor with the other strength convention, where it was sought.
    pub other: Option<OtherFactor>,
    pub trials: Vec<Trial>,
    /// The last converged state, at `factor` (the last load step when no
    /// factor above 1 held; None when none held).
    pub last: Option<StepResult>,
    /// The displacement from F = 1 to `factor` (nodal, like `last.u`): the
    /// mechanism as it starts (empty below 1).
    pub du: Vec<f64>,
    pub cost: SearchCost,
}

/// The same search with the other strength convention (peak against the
/// scene's residual strengths).
#[derive(Clone, Debug)]
pub struct OtherFactor {
    pub strengths: Strengths,
    pub factor: Option<f64>,
    pub fails_at: Option<f64>,
    pub decided: bool,
    pub trials: usize,
    /// Contact iterations of its trials.
    pub iterations: usize,
}

/// A trial that decided nothing.
#[derive(Clone, Copy, Debug)]
pub struct Undecided {
    pub factor: f64,
    pub iterations: usize,
    pub stop: Stop,
}

/// One trial of the search.
#[derive(Clone, Debug)]
pub struct Trial {
    pub factor: f64,
    /// The factor of the state it started from (0 for a trial that ran
    /// the load steps from their start).
    pub from: f64,
    pub holds: bool,
    pub iterations: usize,
    /// Open, slip and stick pairs it ended with (those it failed with).
    pub states: [usize; 3],
    pub seconds: f64,
    /// Why it failed.
    pub failed: Option<FailureKind>,
    /// A step of the retry of a trial that did not converge.
    pub retry: bool,
}

/// How a trial failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FailureKind {
    /// The interface system is singular: blocks slide or rotate freely on
    /// their slipping pairs (the loss of equilibrium).
    Sliding,
    /// Blocks held by nothing once their pairs opened.
    NotHeld,
    /// No state set was found within `[solver] max_iterations`, as the
    /// iteration stopped: such a trial decides nothing (it is retried).
    NotConverged(Stop),
}

impl FailureKind {
    /// The summary.json spelling.
    pub fn key(self) -> &'static str {
        match self {
            FailureKind::Sliding => "sliding",
            FailureKind::NotHeld => "not_held",
            FailureKind::NotConverged(_) => "not_converged",
        }
    }

    /// What happened, for a reader.
    pub fn describe(self) -> &'static str {
        match self {
            FailureKind::Sliding => "loss of equilibrium: blocks slide or rotate freely on their contacts",
            FailureKind::NotHeld => "blocks held by nothing once their contacts opened",
            FailureKind::NotConverged(Stop::Cycled) => "no equilibrium found: the contact states cycle",
            FailureKind::NotConverged(Stop::LawBroken) => {
                "no equilibrium found: the contact states settled, but their forces break the contact law"
            }
            FailureKind::NotConverged(Stop::MaxIterations) => "no equilibrium found within [solver] max_iterations",
        }
    }
}

/// Where the search failed: the trial at `fails_at`.
#[derive(Clone, Debug)]
pub struct Failure {
    pub kind: FailureKind,
    /// The blocks (model bodies) that slide or are not held, ascending
    /// (none named when the solver did not find them).
    pub blocks: Vec<usize>,
    /// Every pair's state when it failed.
    pub states: Vec<ContactState>,
    pub iteration: usize,
    /// The load factors it failed under (of every load case).
    pub lambda: Vec<f64>,
    /// The blocks' rigid motion, named (for a converged loss of equilibrium).
    pub mechanism: Option<Mechanism>,
}

/// What the search cost beyond the load steps.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct SearchCost {
    pub trials: usize,
    /// Contact iterations (interface solves) of all trials.
    pub contact_iterations: usize,
    /// Applications of the parts' S by the iterative interface (0 dense).
    pub interface_applications: usize,
    /// Seconds in the trials (the interface alone) and in recovering the
    /// last converged state.
    pub search_s: f64,
    pub recover_s: f64,
    /// Sparse factorisations the search did: none, the parts are condensed once.
    pub factorisations: usize,
}
