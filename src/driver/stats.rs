//! What a run cost and how well it went, in named numbers: each rank's
//! parts ([`PartStats`], gathered on rank 0), the model's unknowns counted
//! once ([`interface_dofs`]), each rank's share ([`RankStats`]) and the
//! run's [`Stats`] for summary.json and report.md.

use std::path::PathBuf;

use super::condense::Parts;
use super::ranks::Ranks;
use super::steps::LoadSteps;
use crate::model::Model;
use crate::results::{Counters, Dofs, PartCounts, RankStats, Residuals, Stats, Timings};
use crate::substructure::{Condensed, Part};

/// A rank's condensed parts in numbers.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct PartStats {
    /// Interior and interface equations.
    pub interior: usize,
    pub interface: usize,
    /// Parts with an interface.
    pub condensed: usize,
    /// The largest backward error of their sparse solves.
    pub backward_error: f64,
}

impl PartStats {
    pub fn of(mine: &[(usize, Condensed)]) -> PartStats {
        PartStats {
            interior: mine.iter().map(|(_, c)| c.ni).sum(),
            interface: mine.iter().map(|(_, c)| c.nc).sum(),
            condensed: mine.iter().filter(|(_, c)| c.nc > 0).count(),
            backward_error: mine.iter().map(|(_, c)| c.backward_error).fold(0.0, f64::max),
        }
    }

    /// All ranks' parts together.
    pub fn total(all: &[PartStats]) -> PartStats {
        PartStats {
            interior: all.iter().map(|s| s.interior).sum(),
            interface: all.iter().map(|s| s.interface).sum(),
            condensed: all.iter().map(|s| s.condensed).sum(),
            backward_error: all.iter().map(|s| s.backward_error).fold(0.0, f64::max),
        }
    }
}

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
    shared.iter().map(|&n| if in_pair[n] { nd } else { (0..nd).filter(|&c| model.prescribed[n * nd + c].is_none()).count() }).sum()
}

/// What this rank did: its parts, its condensation's wall time, its memory
/// and the bytes it sent.
pub(super) fn rank(ranks: &Ranks, parts: &Parts, done: &LoadSteps) -> RankStats {
    RankStats {
        rank: ranks.rank(),
        parts: parts.mine.iter().map(|(i, _)| *i).collect(),
        dofs: parts.local.interior + parts.local.interface,
        condense_s: parts.wall_s,
        peak_memory_bytes: peak_memory(),
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

/// The machine's memory in bytes (Linux; `u64::MAX` elsewhere: never short).
pub(super) fn physical_memory() -> u64 {
    meminfo("/proc/meminfo", "MemTotal:").map_or(u64::MAX, |kb| kb * 1024)
}

/// Peak resident memory of this process in bytes (Linux; 0 elsewhere).
pub(super) fn peak_memory() -> u64 {
    meminfo("/proc/self/status", "VmHWM:").map_or(0, |kb| kb * 1024)
}

/// The value in kB of the line of `file` that starts with `key`.
fn meminfo(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    text.lines().find(|l| l.starts_with(key)).and_then(|l| l.split_whitespace().nth(1)).and_then(|v| v.parse::<u64>().ok())
}
