//! What a run computed, for the output writers and the callers of
//! [`crate::driver::run`]: the model, the displacements, stresses and contact
//! states of every load step, errors against a closed form, probes, sizes,
//! residuals, timings and counters, and what the scene's `[analytic]` check
//! adds. Plain data: the driver fills it, the writers read it, and this
//! module imports neither.

use std::path::PathBuf;

use crate::analytic::{Check, Solution};
use crate::contact::law::{ContactState, PairResult};
use crate::model::Model;
use crate::recover::{BodyStress, Errors, Sample};
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

/// Everything a run computed, for the output writers.
pub struct Run {
    pub scene: Scene,
    pub out: PathBuf,
    pub msh: PathBuf,
    pub mesh_cached: bool,
    pub model: Model,
    pub u: Vec<f64>,
    pub stresses: Vec<BodyStress>,
    pub contact: Option<ContactRun>,
    /// Every load step (the last one is also `u`, `stresses`, `contact`).
    pub steps: Vec<StepResult>,
    pub errors: Option<Errors>,
    pub contact_error_max: Option<f64>,
    pub probes: Vec<(String, Vec<Sample>)>,
    pub timings: Timings,
    pub dofs_total: usize,
    pub dofs_interface: usize,
    pub parts: usize,
    pub condensed_parts: usize,
    pub residual_interface: f64,
    /// Backward error of the parts' sparse solves.
    pub residual_assembled: f64,
    pub counters: Counters,
    /// Every rank's share (one entry without MPI).
    pub ranks: Vec<RankStats>,
    /// What the scene's `[analytic]` check adds to report.md and
    /// summary.json; computed with the result files (empty when the run
    /// writes none).
    pub check: Check,
}

impl Run {
    /// What an `[analytic]` check reads of this run: its last load step.
    pub fn solution(&self) -> Solution<'_> {
        let probed = self.probes.iter().flat_map(|(_, s)| s).filter(|s| s.found).map(|s| (s.x, s.stress)).collect();
        Solution { model: &self.model, u: &self.u, probed, pairs: self.contact.as_ref().map(|c| &c.pairs[..]) }
    }
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

/// One load step.
pub struct StepResult {
    pub step: usize,
    /// The ramp factor k / load_steps (loads without `factors`, prescribed
    /// displacements, gravity without `gravity_factors`).
    pub load_factor: f64,
    /// The factor of every load case at this step (`Model::cases`).
    pub case_factors: Vec<f64>,
    pub u: Vec<f64>,
    /// Nodal stresses (empty when `[output] fields` leaves stress out, but
    /// for the last step).
    pub stresses: Vec<BodyStress>,
    pub contact: Option<ContactRun>,
}

/// The contact iteration's result.
#[derive(Clone)]
pub struct ContactRun {
    pub states: Vec<ContactState>,
    pub pairs: Vec<PairResult>,
    /// Each pair's frame, rows n, t, b (global components): `sigma_n`,
    /// `tau_t`, `tau_b` are along them.
    pub frames: Vec<[[f64; 3]; 3]>,
    /// The area each pair controls (its stresses times it are its forces).
    pub areas: Vec<f64>,
    /// Pairs opened in tension between the Coulomb apex c / f and f_t
    /// (where f_t exceeds the apex).
    pub apex_openings: usize,
    pub iterations: usize,
    pub converged: bool,
    pub cycled: bool,
    /// Cycles broken by changing one pair at a time.
    pub cycles_broken: usize,
    pub history: Vec<Vec<ContactState>>,
}

impl ContactRun {
    /// The shear traction of pair `p` on body I in global axes.
    pub fn shear(&self, p: usize) -> [f64; 3] {
        let (f, r) = (&self.frames[p], &self.pairs[p]);
        std::array::from_fn(|i| r.tau_t * f[1][i] + r.tau_b * f[2][i])
    }

    /// The contact force of pair `p` on body I in global axes.
    pub fn force(&self, p: usize) -> [f64; 3] {
        let (f, r, a) = (&self.frames[p], &self.pairs[p], self.areas[p]);
        std::array::from_fn(|i| (r.sigma_n * f[0][i] + r.tau_t * f[1][i] + r.tau_b * f[2][i]) * a)
    }
}

/// Counts of open, slip, stick.
pub fn state_counts(states: &[ContactState]) -> [usize; 3] {
    let mut c = [0; 3];
    for s in states {
        c[s.code() as usize] += 1;
    }
    c
}
