//! What a run cost and how well it went, in named numbers, from what the
//! stages return: the model's unknowns counted once ([`interface_dofs`]),
//! each rank's share ([`RankStats`]: its parts, as
//! [`super::condense::PartStats`] counts them, its time, memory and bytes)
//! and the run's [`Stats`] for summary.json and report.md.

use std::path::PathBuf;

use super::condense::{PartStats, Parts};
use super::ranks::Ranks;
use super::steps::LoadSteps;
use crate::model::Model;
use crate::results::{Counters, Dofs, PartCounts, RankStats, Residuals, Stats, Timings};
use crate::substructure::Part;

/// The interface's unknowns: a node shared by several parts is counted
/// once; a pair node with all its components (as without substructures), a
/// join with its free ones.
pub(super) fn interface_dofs(model: &Model, parts: &[Part]) -> usize {
    let nd = model.nd;
    let mut shared: Vec<usize> = parts.iter().flat_map(|p| p.interface.iter().copied()).collect();
    shared.sort_unstable();
    shared.dedup();
    let mut in_pair = vec![false; model.n_nodes()];
    for p in &model.pairs {
        in_pair[p.k] = true;
        in_pair[p.l] = true;
    }
    shared
        .iter()
        .map(|&n| if in_pair[n] { nd } else { (0..nd).filter(|&c| model.prescribed[n * nd + c].is_none()).count() })
        .sum()
}

/// What this rank did: its parts, its condensation's wall time, its memory
/// and the bytes it sent.
pub(super) fn rank(ranks: &Ranks, parts: &Parts, done: &LoadSteps) -> RankStats {
    RankStats {
        rank: ranks.rank(),
        parts: parts.mine.iter().map(|(i, _)| *i).collect(),
        dofs: parts.local.interior + parts.local.interface,
        condense_s: parts.wall_s,
        peak_memory_bytes: crate::memory::peak(),
        bytes_sent: ranks.bytes_sent(),
        bytes_sent_per_step: done.bytes / done.done.max(1) as u64,
        bytes_sent_interface: done.bytes_interface,
        bytes_sent_per_contact_iteration: 0,
    }
}

/// The seconds of stages 4 to 6.
pub(super) fn add_timings(t: &mut Timings, parts: &Parts, done: &LoadSteps) {
    t.assemble = parts.assemble_s;
    t.condense = parts.condense_s;
    t.interface = parts.interface_s + done.interface_s;
    if let Some(split) = parts.problem.as_ref().and_then(|p| p.split()) {
        t.interface_factor = Some(split.factor);
        t.interface_gmres = Some(split.gmres);
        t.interface_refine = Some(split.refine);
        t.interface_columns = Some(split.columns);
        t.interface_start = Some(split.start);
        t.interface_checks = Some(split.checks);
        t.interface_relations = Some(split.relations);
        t.interface_forces = Some(split.forces);
        t.interface_diagonal = Some(split.diagonal);
        t.interface_setup = Some(parts.interface_s);
    }
    t.recover = done.recover_s;
}

/// What the steps measured, for [`stats`].
pub(super) struct Measured {
    pub msh: PathBuf,
    pub mesh_cached: bool,
    pub timings: Timings,
    pub counters: Counters,
    pub residual_interface: f64,
    pub ranks: Vec<RankStats>,
    /// How the interface was solved.
    pub interface_solver: &'static str,
}

/// The run's statistics on rank 0, from its parts (all ranks'), the plan's
/// parts and what the steps measured.
pub(super) fn stats(model: &Model, parts: &[Part], all: PartStats, m: Measured) -> Stats {
    let interface = interface_dofs(model, parts);
    let mut counters = Counters { factorisations: parts.len(), condensed_parts: all.condensed, ..m.counters };
    counters.interface_applications = counters.interface_applications_per_solve.iter().sum();
    let mut ranks = m.ranks;
    // rank 0 knows how many contact iterations there were
    for r in ranks.iter_mut() {
        r.bytes_sent_per_contact_iteration = r.bytes_sent_interface / counters.interface_solves.max(1) as u64;
    }
    Stats {
        msh: m.msh,
        mesh_cached: m.mesh_cached,
        interface_solver: m.interface_solver,
        dofs: Dofs { total: all.interior + interface, interface },
        parts: PartCounts { total: parts.len(), condensed: all.condensed },
        residuals: Residuals { interface: m.residual_interface, assembled: all.backward_error },
        timings: m.timings,
        counters,
        ranks,
    }
}
