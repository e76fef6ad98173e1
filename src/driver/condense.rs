//! Stage 4: every rank assembles, factorises and condenses its own parts
//! (several at once in threads), frees the factors that would crowd the
//! interface out of memory, and rank 0 gathers the condensed operators and
//! sets up the interface ([`InterfaceProblem`]).

use std::time::Instant;

use super::plan::{self, Plan};
use super::progress::progress;
use super::ranks::{agree, Ranks};
use super::run_options::RunOptions;
use crate::contact::system::iterative::Remote;
use crate::contact::system::InterfaceProblem;
use crate::contact::water::Water;
use crate::error::Result;
use crate::model::Model;
use crate::substructure::{self, Condensation, Condensed, OperatorRef};

/// The share of the machine's memory the parts' factors may keep through
/// the contact iteration. Above it they are freed once the parts are
/// condensed and made again to recover the interiors: a strip pair of
/// 1.09e6 DOFs and a 2.4e4-DOF joint (docs/bench3d.md) ran out of 24 GB
/// keeping them.
const FACTOR_SHARE: f64 = 0.3;

/// This rank's condensed parts, and the interface on rank 0.
pub(super) struct Parts<'r> {
    /// This rank's parts: (index in the plan, condensed part).
    pub mine: Vec<(usize, Condensed)>,
    /// The interface, on rank 0 when some part has one.
    pub problem: Option<InterfaceProblem<'r>>,
    /// This rank's parts in numbers, and all ranks' together (on rank 0).
    pub local: PartStats,
    pub all: PartStats,
    /// Seconds assembling and condensing (the wall time, split as the parts
    /// spent it), this rank's wall time, and setting up the interface.
    pub assemble_s: f64,
    pub condense_s: f64,
    pub wall_s: f64,
    pub interface_s: f64,
}

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

/// Condenses this rank's parts of `plan` and sets up the interface.
pub(super) fn condense<'r>(model: &Model, plan: &Plan, opts: &RunOptions, ranks: &'r Ranks) -> Result<Parts<'r>> {
    agree(ranks.comm(), memory(model, plan, opts, ranks.rank()))?;
    let t = Instant::now();
    let n_parts = plan.parts.len();
    let on = if ranks.size() > 1 {
        format!(" on {} ranks", ranks.size())
    } else if plan.threads > 1 {
        format!(" in {} threads", plan.threads)
    } else {
        String::new()
    };
    progress(opts, &format!("assembling and factorising {n_parts} part(s){on}"));
    if let Some(note) = plan.kind.note(plan.interface_dofs) {
        progress(opts, &note);
    }
    let (index, own): (Vec<usize>, Vec<_>) = (plan.parts.iter().enumerate())
        .filter(|(i, _)| plan.owner[*i] == ranks.rank())
        .map(|(i, p)| (i, p.clone()))
        .unzip();
    let condensed = agree(
        ranks.comm(),
        substructure::condense_parts(model, own, plan.threads, plan.kind.condensation()).map_err(Into::into),
    )?;
    let mut mine: Vec<(usize, Condensed)> = index.into_iter().zip(condensed).collect();
    // the wall time, split between assembly and condensation as the parts spent it
    let wall_s = t.elapsed().as_secs_f64();
    let spent: f64 = mine.iter().map(|(_, c)| c.assemble_s + c.condense_s).sum();
    let share = if spent > 0.0 { wall_s / spent } else { 0.0 };
    let assemble_s = mine.iter().map(|(_, c)| c.assemble_s).sum::<f64>() * share;
    free_factors(&mut mine, plan.kind.condensation(), opts);

    let t = Instant::now();
    let local = PartStats::of(&mine);
    let all = PartStats::total(&ranks.gather(&local).unwrap_or_default());
    let problem = ranks.interface(&mut mine, |ops, remote| interface(model, ops, remote, plan))?;
    // the interface holds what it needs of every S
    for (_, c) in mine.iter_mut() {
        c.drop_schur();
    }
    Ok(Parts {
        mine,
        problem,
        local,
        all,
        assemble_s,
        condense_s: wall_s - assemble_s,
        wall_s,
        interface_s: t.elapsed().as_secs_f64(),
    })
}

/// The DOFs and this rank's estimated peak memory, said before anything
/// is factorised; more than is available is an error unless ignored.
fn memory(model: &Model, plan: &Plan, opts: &RunOptions, rank: usize) -> Result<()> {
    let plan::Memory { need, dofs, fits } = plan::memory(model, plan, rank);
    let available = match &fits {
        Ok(a) => a.clone(),
        Err(e) => e.available.clone(),
    };
    progress(
        opts,
        &format!(
            "{} DOFs ({} interface); estimated peak memory {} of {} available",
            dofs.total,
            dofs.interface,
            crate::memory::human(need.total),
            crate::memory::human(available.bytes)
        ),
    );
    match fits {
        Err(e) if !opts.ignore_memory_estimate => Err(e.into()),
        _ => Ok(()),
    }
}

/// The interface of the parts' operators `ops`, when some part has one.
fn interface<'r>(
    model: &Model,
    ops: &[OperatorRef],
    remote: Option<&'r dyn Remote>,
    plan: &Plan,
) -> Result<Option<InterfaceProblem<'r>>> {
    if ops.iter().all(|o| o.nc == 0) {
        return Ok(None);
    }
    let problem = InterfaceProblem::new(model, ops, remote, (plan.threads, plan.springs), plan.kind)?;
    Ok(Some(problem.with_water(Water::new(model))))
}

/// Factors that would crowd the dense interface out of memory are dropped
/// now and made again, a part at a time, to recover the interiors.
fn free_factors(mine: &mut [(usize, Condensed)], how: Condensation, opts: &RunOptions) {
    let factor_bytes: usize = mine.iter().map(|(_, c)| c.factor_bytes).sum();
    if how == Condensation::Dense && factor_bytes as f64 > FACTOR_SHARE * crate::memory::physical() {
        for (_, c) in mine.iter_mut() {
            c.drop_factor();
        }
        progress(
            opts,
            &format!(
                "the parts' factors ({:.1} GB) are freed for the interface and made again for the recovery",
                factor_bytes as f64 / 1e9
            ),
        );
    }
}
