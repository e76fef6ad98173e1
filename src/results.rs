//! What a run computed, for the output writers and the callers of
//! [`crate::driver::run`], in one shape: [`Run`] is the scene and the model
//! (with [`About`], what the writers print of the scene: they read it, never
//! the scene),
//! the displacements, stresses and contact states of every load step
//! ([`Run::last`] is the answer), the run's [`Stats`] (sizes, residuals,
//! timings, counters, ranks) and its [`Checks`] (errors against a closed
//! form, probes, what the scene's `[analytic]` check adds), and after a
//! safety search its [`SafetyRun`] (`results/safety.rs`). A step's
//! [`ContactRun`] keeps the contact iteration's own [`Summary`](crate::contact::outcome::Summary). Plain data:
//! the driver fills it, the writers read it, and this module imports
//! neither.

use std::path::PathBuf;

pub mod about;
mod reactions;
mod safety;
mod step;
pub use about::{About, Applied, ContactLaw};
pub use reactions::{BodyBalance, Reactions, SupportReaction};
pub use safety::{Failure, FailureKind, OtherFactor, SafetyRun, SearchCost, SearchKind, Trial, Undecided};
pub use step::{ContactRun, PairWater, StepResult};

use crate::analytic::{Check, Solution};
use crate::contact::law::ContactState;
use crate::contact::Stop;
use crate::model::Model;
use crate::recover::sections::SectionForces;
use crate::recover::{Errors, Sample};
use crate::scene::Scene;

/// Seconds spent in each stage.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Timings {
    pub mesh: f64,
    /// Building the model: groups, contact split and pairing, loads.
    pub model: f64,
    pub assemble: f64,
    pub condense: f64,
    pub interface: f64,
    /// Of `interface`, with the sparse interface solver: assembling and
    /// factorising its preconditioner's block of free relative
    /// displacements, per solve.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_factor: Option<f64>,
    /// Of `interface`, with the sparse interface solver: GMRES (the
    /// operator's and the preconditioner's applications).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_gmres: Option<f64>,
    /// Of `interface`, with the sparse interface solver: refining the
    /// means to double precision after each GMRES solve.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_refine: Option<f64>,
    /// Of `interface_factor`: computing the columns of W it is formed from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_columns: Option<f64>,
    /// Of `interface`, with the sparse interface solver: each solve's
    /// start (K applied to the last answer moved onto the new relations).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_start: Option<f64>,
    /// Of `interface`, with the sparse interface solver: the checks of
    /// what holds the parts before each solve.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_checks: Option<f64>,
    /// Of `interface`, with the sparse interface solver: the free
    /// directions of each solve's relations (the junctions' ties).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_relations: Option<f64>,
    /// Of `interface`, with the sparse interface solver: the pairs' forces
    /// and the parts' displacements from each answer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_forces: Option<f64>,
    /// Of `interface`, with the sparse interface solver: W's diagonal (the
    /// stiffness of the pairs that slip or open, formed the first time
    /// they do; a check that reads one not yet formed forms it inside
    /// `interface_checks`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_diagonal: Option<f64>,
    /// Of `interface`, with the sparse interface solver: setting it up
    /// once, before the first load step (the pairs' layout, the parts' S
    /// in the pairs' axes, the means' factorisation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_setup: Option<f64>,
    pub recover: f64,
    pub output: f64,
    pub total: f64,
}

/// What one MPI rank (or the one process) did: its parts, its share of the
/// work, its memory and the bytes it sent.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct RankStats {
    pub rank: usize,
    /// The parts it owned (indices in the run's part list).
    pub parts: Vec<usize>,
    /// Equations of its parts.
    pub dofs: usize,
    /// Seconds it spent assembling, factorising and condensing.
    pub condense_s: f64,
    /// Its peak resident memory.
    pub peak_memory_bytes: u64,
    /// Bytes it sent in all, per load step, during the contact iterations
    /// of all steps, and per contact iteration (nothing with the dense
    /// interface, which rank 0 holds; the parts' `S d` with the iterative
    /// one).
    pub bytes_sent: u64,
    pub bytes_sent_per_step: u64,
    pub bytes_sent_interface: u64,
    pub bytes_sent_per_contact_iteration: u64,
}

/// Everything a run computed, for the output writers: the scene and the
/// model it ran, every load step, what the run cost and what it is checked
/// against.
pub struct Run {
    pub scene: Scene,
    /// What the writers print of the scene (they read this, not `scene`).
    pub about: About,
    pub model: Model,
    /// Every load step, in order (at least one; the last one is the answer).
    pub steps: Vec<StepResult>,
    pub stats: Stats,
    pub checks: Checks,
    /// The safety search after the load steps, when the run made one.
    pub safety: Option<SafetyRun>,
    /// The initial equilibrium stage before the load steps (`[solver]
    /// initial_stage`), when the run made one.
    pub initial_stage: Option<InitialStage>,
    /// Where the scene's rigid joints did not converge and the run solved
    /// it again with joints that deform (`[solver] rigid_fallback`): what
    /// the rigid run did and the stiffness taken instead.
    pub fallback: Option<Fallback>,
}

/// Rigid joints that did not converge, and the stiffness the run gave
/// every contact instead (`crate::driver`'s fallback).
#[derive(Clone, Debug)]
pub struct Fallback {
    /// Normal and shear stiffness given to every contact.
    pub stiffness: crate::contact::law::Stiffness,
    /// The softest body's Young's modulus E and the model's mean block
    /// size s the stiffness is reckoned from.
    pub modulus: f64,
    pub block_size: f64,
    /// The rigid run's last step (0: the initial stage), its iterations
    /// and halvings (or why it was not halved), why its iteration stopped,
    /// its worst pair's law residual (of the largest traction), and the
    /// rigid run's seconds.
    pub step: usize,
    pub iterations: usize,
    pub cuts: usize,
    /// Not cut, the step being the same problem at any load
    /// ([`crate::contact::Summary::scaled`]).
    pub scaled: bool,
    pub stop: Stop,
    pub law_residual: Option<f64>,
    pub seconds: f64,
    /// Where the rigid iteration stopped at a state set that holds
    /// nothing, what it left unheld ("body \"rock #41\" is held by
    /// nothing"); None where its step ended unconverged.
    pub unheld: Option<String>,
    /// The augmented Lagrangian rounds among `iterations` and their
    /// iterations, where the rigid step was solved again by them
    /// (`[solver] augmented_lagrangian`) and they did not end it either.
    pub rounds: Option<[usize; 2]>,
    /// Where the rigid step was cut and pieces of it converged: how far
    /// into the step (a fraction of its load, 0 to 1) the rigid joints
    /// held its load before a piece did not converge.
    pub held: Option<f64>,
    /// Where the fallback held each rigid step to
    /// [`crate::contact::cutting::SHORT_ITERATIONS`], fewer than the
    /// scene's `[solver] max_iterations`: that number, which a run
    /// without the fallback gives a step.
    pub short_of: Option<usize>,
    /// Where the rigid joints left the factor of safety undecided: the
    /// last factor that held and the trial above it that decided nothing,
    /// even retried in smaller steps; None where a load step fell back.
    pub safety: Option<(f64, Undecided)>,
}

/// The initial equilibrium stage: the step 0 that brings the bodies to
/// equilibrium with their in-situ stress and their contacts active. Its
/// displacements are taken off every load step's (`StepResult::u`);
/// stresses and pair forces stay totals.
#[derive(Clone, Debug, Default)]
pub struct InitialStage {
    /// Its contact iteration: iterations, whether it converged, the
    /// halvings of the stage, and how many pairs ended open, slipping and
    /// stuck (`state_counts` order).
    pub iterations: usize,
    pub converged: bool,
    pub cuts: usize,
    pub states: [usize; 3],
    /// The strength factors it was brought down through where the in-situ
    /// stress put joints beyond their strength (`Summary::strengths`).
    pub strength_ramp: Vec<f64>,
    /// The factor of every load case in the stage.
    pub case_factors: Vec<f64>,
    /// Its displacements (every node; zero where it did not converge: its
    /// last iterate is then the run's one step, step 0), and the largest
    /// of them (length) with its model node.
    pub u: Vec<f64>,
    pub largest: f64,
    pub largest_at: usize,
}

impl InitialStage {
    /// `u` plus the stage's displacements: the total displacements a
    /// step's stresses and forces come from.
    pub fn total(&self, u: &[f64]) -> Vec<f64> {
        u.iter().zip(&self.u).map(|(a, b)| a + b).collect()
    }
}

impl Run {
    /// The last load step: the run's answer.
    pub fn last(&self) -> &StepResult {
        self.steps.last().expect("a run has at least one load step")
    }

    /// The contact result of the last load step.
    pub fn contact(&self) -> Option<&ContactRun> {
        self.last().contact.as_ref()
    }

    /// What an `[analytic]` check reads of this run: its last load step.
    pub fn solution(&self) -> Solution<'_> {
        let probed =
            self.checks.probes.iter().flat_map(|(_, s)| s).filter(|s| s.found).map(|s| (s.x, s.stress)).collect();
        Solution { model: &self.model, u: &self.last().u, probed, pairs: self.contact().map(|c| &c.pairs[..]) }
    }
}

/// What a run cost and how well its solves went: the mesh file, sizes,
/// residuals, timings, counters and every rank's share.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// The mesh read, and whether gmsh's output was reused.
    pub msh: PathBuf,
    pub mesh_cached: bool,
    /// How the interface was solved: "dense", "sparse" or "iterative"
    /// (`[solver] interface`), "none" without one.
    pub interface_solver: &'static str,
    pub dofs: Dofs,
    pub parts: PartCounts,
    pub residuals: Residuals,
    pub timings: Timings,
    pub counters: Counters,
    /// Every rank's share (one entry without MPI).
    pub ranks: Vec<RankStats>,
}

/// Unknowns of the whole model, and of the interface (a node shared by
/// several parts counted once).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Dofs {
    pub total: usize,
    pub interface: usize,
}

/// Parts, and those condensed onto an interface.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct PartCounts {
    pub total: usize,
    pub condensed: usize,
}

/// The largest relative residual of the interface solves, and the largest
/// backward error of the parts' sparse solves.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Residuals {
    pub interface: f64,
    pub assembled: f64,
}

/// What the last load step is measured by: errors against the scene's
/// closed form, the probes, the supports' reactions, the section forces, and what its `[analytic]` check adds to
/// report.md and summary.json (computed with the result files: empty when
/// the run writes none).
#[derive(Default)]
pub struct Checks {
    pub errors: Option<Errors>,
    /// Max |sigma_n - exact| over the pairs, relative to the largest exact value.
    pub contact_error_max: Option<f64>,
    pub probes: Vec<(String, Vec<Sample>)>,
    pub analytic: Check,
    /// The supports' reactions and every body's balance (None without supports).
    pub reactions: Option<Reactions>,
    /// The forces of every `[[sections]]` entry.
    pub sections: Vec<SectionForces>,
}

/// How often the expensive things were done: what a scene does not need is skipped.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Counters {
    /// Sparse factorisations (one per part, whatever the iterations and steps).
    pub factorisations: usize,
    /// Parts condensed onto an interface (parts without contact are solved directly).
    pub condensed_parts: usize,
    /// Interface solves (contact iterations over all steps).
    pub interface_solves: usize,
    /// Applications of every part's S by the iterative interface (GMRES
    /// iterations over all its solves; 0 for the dense interface), and per
    /// solve (contact iteration) in order.
    pub interface_applications: usize,
    pub interface_applications_per_solve: Vec<usize>,
    /// Interior displacement recoveries (part solves after the interface).
    pub interior_recoveries: usize,
    /// Nodal stress recoveries (only when `[output] fields` has "stress").
    pub stress_recoveries: usize,
}

/// Counts of open, slip, stick.
pub fn state_counts(states: &[ContactState]) -> [usize; 3] {
    let mut c = [0; 3];
    for s in states {
        c[s.code() as usize] += 1;
    }
    c
}
