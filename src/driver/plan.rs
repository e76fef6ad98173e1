//! Stage 4's plan, the same on every rank: the parts (bodies joined by
//! shared nodes, each cut into `substructures` pieces), the rank that owns
//! each, the threads a rank condenses its parts in, and how the interface
//! is solved (the one place that turns `[solver] interface` into an
//! [`InterfaceKind`], which decides how the parts are condensed); and what
//! a rank's parts will need of memory ([`memory`]), which `solve` says
//! before it factorises and `check` ([`preview`]) says instead of running.

use super::messages::PlanError;
use super::progress::progress;
use super::run_options::RunOptions;
use crate::contact::system::{InterfaceKind, Springs};
use crate::memory::{Available, Estimate, TooLarge};
use crate::model::Model;
use crate::scene::Scene;
use crate::substructure::parts::DofCounts;
use crate::substructure::{self, Part};

/// What stage 4 does, part by part.
pub(super) struct Plan {
    pub parts: Vec<Part>,
    /// The rank of each part.
    pub owner: Vec<usize>,
    /// Parts a rank condenses at once.
    pub threads: usize,
    /// How the interface is solved, and so how the parts are condensed.
    pub kind: InterfaceKind,
    /// Interface DOFs summed over the parts (what decides `kind` by default).
    pub interface_dofs: usize,
    /// Where the interface's solves put springs on every pair: every
    /// contact's joints deform (`normal_stiffness`), and the sparse
    /// interface factorises its means only where asked; or rigid joints
    /// may be solved again by augmented Lagrangian rounds.
    pub springs: Springs,
}

/// The plan of a run on `ranks` MPI ranks (1 without MPI).
pub(super) fn plan(scene: &Scene, model: &Model, opts: &RunOptions, ranks: usize) -> Result<Plan, PlanError> {
    let k = opts.substructures.unwrap_or(scene.solver.substructures);
    let parts = cut(model, k, opts);
    if ranks > parts.len() {
        return Err(PlanError::TooManyRanks { ranks, parts: parts.len(), substructures: k });
    }
    let owner = owners(model, &parts, ranks);
    let threads =
        opts.threads.unwrap_or_else(|| (std::thread::available_parallelism().map_or(1, |n| n.get()) / ranks).max(1));
    let nd = model.nd;
    let interface_dofs: usize = parts.iter().map(|p| p.interface.len() * nd).sum();
    let kind = InterfaceKind::choose(opts.interface.unwrap_or(scene.solver.interface), &parts, nd);
    let springs = if scene.joints_deform() {
        Springs::Always
    } else if super::fallback::takes_rounds(scene) {
        Springs::InRounds
    } else {
        Springs::Never
    };
    Ok(Plan { parts, owner, threads, kind, interface_dofs, springs })
}

/// What a rank's parts need of memory at the run's peak, the run's DOFs,
/// and whether it fits in what the machine has (`Err`: it does not).
pub struct Memory {
    pub need: Estimate,
    pub dofs: DofCounts,
    pub fits: Result<Available, TooLarge>,
}

/// The memory of `rank`'s parts of `plan` (rank 0 also solves the interface).
pub(super) fn memory(model: &Model, plan: &Plan, rank: usize) -> Memory {
    let mine: Vec<&Part> =
        (plan.parts.iter().enumerate()).filter(|(i, _)| plan.owner[*i] == rank).map(|(_, p)| p).collect();
    let steps = model.cases.first().map_or(1, |c| c.len());
    let need = crate::memory::estimate(model, &mine, plan.kind, plan.threads, rank == 0, plan.interface_dofs, steps);
    let dofs = substructure::parts::dof_counts(model, &plan.parts);
    let fits = crate::memory::check(need, [dofs.total, dofs.interface], mine.len());
    Memory { need, dofs, fits }
}

/// What `solve` would do with the model, told before doing it: the number
/// of parts of its plan on one rank, and their memory.
pub struct Preview {
    pub parts: usize,
    pub memory: Memory,
}

/// The plan of `solve` on one rank, previewed by `check`.
pub fn preview(scene: &Scene, model: &Model, opts: &RunOptions) -> Result<Preview, PlanError> {
    let plan = plan(scene, model, opts, 1)?;
    Ok(Preview { parts: plan.parts.len(), memory: memory(model, &plan, 0) })
}

/// The model's parts, each cut into `k` pieces where it has the cells for
/// them (and a note of the parts left whole).
fn cut(model: &Model, k: usize, opts: &RunOptions) -> Vec<Part> {
    let whole = substructure::parts(model);
    let uncut = whole.len();
    let parts = substructure::cut(model, whole, k);
    if k > 1 && parts.len() < uncut * k {
        let kept: Vec<String> = (parts.iter().filter(|p| p.piece.is_none()))
            .map(|p| {
                format!(
                    "{} ({} cells)",
                    p.bodies.iter().map(|&b| format!("\"{}\"", model.bodies[b].name)).collect::<Vec<_>>().join(", "),
                    p.cells.len()
                )
            })
            .collect();
        if !kept.is_empty() {
            progress(
                opts,
                &format!(
                    "not cut into {k} substructures, too few cells (at least {} per piece): {}",
                    substructure::parts::MIN_CELLS_PER_PIECE,
                    kept.join("; ")
                ),
            );
        }
    }
    parts
}

/// The owner rank of every part: largest parts first, each to the rank with
/// the least work so far (work ~ nodes^1.5, the sparse factorisation's
/// growth in 3D).
fn owners(model: &Model, parts: &[Part], ranks: usize) -> Vec<usize> {
    let work: Vec<f64> = parts.iter().map(|p| (p.nodes(model).len() as f64).powf(1.5)).collect();
    let mut order: Vec<usize> = (0..parts.len()).collect();
    order.sort_by(|&a, &b| work[b].total_cmp(&work[a]).then(a.cmp(&b)));
    let mut load = vec![0.0f64; ranks];
    let mut owner = vec![0; parts.len()];
    for p in order {
        let r = (0..ranks).min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b))).expect("a rank");
        owner[p] = r;
        load[r] += work[p];
    }
    owner
}
