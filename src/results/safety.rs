//! What a safety search found ([`SafetyRun`]): the factor of safety F (the
//! largest factor that held) and the smallest that failed, why and where it
//! failed ([`Failure`]: the blocks that slide, the pairs' states), every
//! trial in order ([`Trial`]), the last converged state at F, and what the
//! search cost ([`SearchCost`]: contact iterations, not factorisations).
//! Plain data, like the rest of [`crate::results`].

use super::StepResult;
use crate::contact::law::ContactState;

/// The safety search of a run.
pub struct SafetyRun {
    /// The largest factor that held.
    pub factor: f64,
    /// The smallest factor that failed; None when the search reached
    /// `max_factor` and the scene held there (F is at least the bound).
    pub fails_at: Option<f64>,
    /// Why the trial at `fails_at` failed.
    pub failure: Option<Failure>,
    pub trials: Vec<Trial>,
    /// The last converged state, at `factor` (the last load step when no
    /// factor above 1 held).
    pub last: StepResult,
    /// The displacement from F = 1 to `factor` (nodal, like `last.u`): the
    /// mechanism as it starts.
    pub du: Vec<f64>,
    pub cost: SearchCost,
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
}

/// How a trial failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FailureKind {
    /// The interface system is singular: blocks slide or rotate freely on
    /// their slipping pairs (the loss of equilibrium).
    Sliding,
    /// Blocks held by nothing once their pairs opened.
    NotHeld,
    /// No state set was found within `[solver] max_iterations` (`cycled`:
    /// the states cycle): treated as failure, as strength reduction codes do.
    NotConverged { cycled: bool },
}

impl FailureKind {
    /// The summary.json spelling.
    pub fn key(self) -> &'static str {
        match self {
            FailureKind::Sliding => "sliding",
            FailureKind::NotHeld => "not_held",
            FailureKind::NotConverged { .. } => "not_converged",
        }
    }

    /// What happened, for a reader.
    pub fn describe(self) -> &'static str {
        match self {
            FailureKind::Sliding => "loss of equilibrium: blocks slide or rotate freely on their contacts",
            FailureKind::NotHeld => "blocks held by nothing once their contacts opened",
            FailureKind::NotConverged { cycled: true } => "no equilibrium found: the contact states cycle",
            FailureKind::NotConverged { cycled: false } => "no equilibrium found within [solver] max_iterations",
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
