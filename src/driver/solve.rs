//! Stages 4–6 of a run, on one process or spread over MPI ranks:
//!
//! 4. cut the model into parts (bodies joined by shared nodes, each cut into
//!    `substructures` pieces), give each part an owner rank, and let every
//!    rank assemble, factorise and condense its own parts (several at once
//!    in threads);
//! 5. rank 0 gathers the condensed operators (S, G and the interface nodes
//!    of each part), sets up the interface and runs the contact iteration
//!    of every load step; nothing travels during the iteration;
//! 6. rank 0 sends each part's interface displacements to its owner, which
//!    recovers the part's interior; rank 0 gathers the displacements and
//!    recovers the stresses.
//!
//! A failure on any rank (a part nothing holds, a failed iteration) ends
//! every rank with the first failure's message. Serial runs take the same
//! path with [`Serial`](crate::parallel::Serial), which moves nothing.

use std::time::Instant;

use anyhow::{anyhow, bail, Result};

use super::messages::failure_message;
use super::remote::{serve, Ranks};
use super::{progress, RunOptions};
use crate::contact::law::Strength;
use crate::contact::system::iterative::Remote;
use crate::contact::system::{InterfaceProblem, InterfaceSolution, ITERATIVE_FROM};
use crate::contact::InterfaceSolver;
use crate::contact::traction::ConsistentTraction;
use crate::contact::{self, History, Outcome, PairLaw};
use crate::model::Model;
use crate::parallel::{Comm, CommExt};
use crate::recover;
use crate::results::{ContactRun, Counters, RankStats, StepResult, Timings};
use crate::scene::{Scene, TractionRecovery};
use crate::substructure::{self, Condensation, Condensed, Operator, OperatorRef, Part};

/// What stages 4–6 give rank 0.
pub(super) struct Solved {
    pub steps: Vec<StepResult>,
    pub dofs_total: usize,
    pub dofs_interface: usize,
    pub parts: usize,
    pub condensed_parts: usize,
    pub residual_interface: f64,
    pub residual_assembled: f64,
    pub counters: Counters,
    pub ranks: Vec<RankStats>,
}

/// Every rank's result of a stage; the first failure, in rank order, ends
/// every rank with its message.
pub(super) fn agree<T>(comm: &dyn Comm, r: Result<T>) -> Result<T> {
    if comm.size() == 1 {
        return r;
    }
    let mine: Option<String> = r.as_ref().err().map(|e| format!("{e:#}"));
    let first: Option<String> = comm.broadcast(&comm.gather(&mine).into_iter().flatten().next());
    match (r, first) {
        (Ok(v), None) => Ok(v),
        (_, Some(msg)) => Err(anyhow!(msg)),
        (Err(e), None) => Err(e),
    }
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

/// The share of the machine's memory the parts' factors may keep through
/// the contact iteration. Above it they are freed once the parts are
/// condensed and made again to recover the interiors: a strip pair of
/// 1.09e6 DOFs and a 2.4e4-DOF joint (docs/bench3d.md) ran out of 24 GB
/// keeping them.
const FACTOR_SHARE: f64 = 0.3;

/// The machine's memory in bytes (Linux; `u64::MAX` elsewhere: never short).
fn physical_memory() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("MemTotal:")).and_then(|l| l.split_whitespace().nth(1)).and_then(|v| v.parse::<u64>().ok()))
        .map_or(u64::MAX, |kb| kb * 1024)
}

/// Peak resident memory of this process in bytes (Linux; 0 elsewhere).
fn peak_memory() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| l.split_whitespace().nth(1)).and_then(|v| v.parse::<u64>().ok()))
        .map_or(0, |kb| kb * 1024)
}

/// The pair laws of the model's pairs, from the scene's contacts.
fn laws(model: &Model, scene: &Scene) -> Vec<PairLaw> {
    model
        .pairs
        .iter()
        .map(|p| {
            let c = &scene.contacts[p.contact];
            PairLaw {
                strength: Strength { friction: c.friction, cohesion: c.cohesion, tensile_strength: c.tensile_strength, residual_cohesion: c.residual_cohesion },
                slip: c.slip,
            }
        })
        .collect()
}

/// What rank 0 sends every rank at each load step.
#[derive(serde::Serialize, serde::Deserialize)]
enum Order {
    /// Recover these parts (index, interface displacements) under these load factors.
    Recover { lambda: Vec<f64>, parts: Vec<(usize, Vec<f64>)> },
    /// The run failed on rank 0 with this message.
    Stop(String),
}

/// Recovers the interiors of `mine` under `lambda`: the displacements of
/// their nodes, part by part (node order of `Part::nodes`).
fn recover_parts(model: &Model, mine: &[(usize, Condensed)], d_c: &[(usize, Vec<f64>)], lambda: &[f64]) -> Vec<(usize, Vec<f64>)> {
    let nd = model.nd;
    let mut u = vec![0.0; model.n_nodes() * nd];
    mine.iter()
        .zip(d_c)
        .map(|((i, c), (j, d))| {
            debug_assert_eq!(i, j);
            c.recover(model, d, lambda, &mut u);
            let values = c.part.nodes(model).iter().flat_map(|&n| u[n * nd..n * nd + nd].to_vec()).collect();
            (*i, values)
        })
        .collect()
}

pub(super) fn solve(scene: &Scene, model: &Model, opts: &RunOptions, comm: &dyn Comm, timings: &mut Timings) -> Result<Option<Solved>> {
    let nd = model.nd;
    let root = comm.is_root();
    // 4. Parts, owners, condensation.
    let t = Instant::now();
    let k = opts.substructures.unwrap_or(scene.solver.substructures);
    let whole = substructure::parts(model);
    let uncut = whole.len();
    let parts = substructure::cut(model, whole, k);
    let n_parts = parts.len();
    if k > 1 && root && n_parts < uncut * k {
        let kept: Vec<String> = parts
            .iter()
            .filter(|p| p.piece.is_none())
            .map(|p| format!("{} ({} cells)", p.bodies.iter().map(|&b| format!("\"{}\"", model.bodies[b].name)).collect::<Vec<_>>().join(", "), p.cells.len()))
            .collect();
        if !kept.is_empty() {
            progress(opts, &format!("not cut into {k} substructures, too few cells (at least {} per piece): {}", substructure::parts::MIN_CELLS_PER_PIECE, kept.join("; ")));
        }
    }
    if comm.size() > n_parts {
        bail!(
            "{}: {} MPI ranks but the model has {n_parts} part(s): every rank needs a part. Cut the bodies into more substructures ([solver] substructures = {} or --substructures {}), or run on at most {n_parts} rank(s)",
            scene.path.display(),
            comm.size(),
            comm.size().div_ceil(n_parts.max(1)) * k.max(1),
            comm.size().div_ceil(n_parts.max(1)) * k.max(1),
        );
    }
    let owner = owners(model, &parts, comm.size());
    let all_parts: Vec<Part> = parts.clone();
    let mine_parts: Vec<(usize, Part)> = parts.into_iter().enumerate().filter(|(i, _)| owner[*i] == comm.rank()).collect();
    let threads = opts.threads.unwrap_or_else(|| (std::thread::available_parallelism().map_or(1, |n| n.get()) / comm.size()).max(1));
    progress(opts, &format!("assembling and factorising {n_parts} part(s){}", if comm.size() > 1 { format!(" on {} ranks", comm.size()) } else if threads > 1 { format!(" in {threads} threads") } else { String::new() }));
    let iface_dofs: usize = all_parts.iter().map(|p| p.interface.len() * nd).sum();
    let how = match opts.interface.unwrap_or(scene.solver.interface) {
        InterfaceSolver::Iterative => Condensation::Applied,
        InterfaceSolver::Auto if iface_dofs >= ITERATIVE_FROM => Condensation::Applied,
        _ => Condensation::Dense,
    };
    // the other ranks apply their parts' S while rank 0 solves the interface
    let service = how == Condensation::Applied && comm.size() > 1;
    if how == Condensation::Applied && root {
        progress(opts, &format!("{iface_dofs} interface DOFs over the parts: no S formed, the interface solved by GMRES through the parts' interior factors"));
    }
    let (index, mine_only): (Vec<usize>, Vec<Part>) = mine_parts.into_iter().unzip();
    let condensed = agree(comm, substructure::condense_parts(model, mine_only, threads, how).map_err(anyhow::Error::from))?;
    let mut mine: Vec<(usize, Condensed)> = index.into_iter().zip(condensed).collect();
    // the wall time, split between assembly and condensation as the parts spent it
    let wall = t.elapsed().as_secs_f64();
    let spent: f64 = mine.iter().map(|(_, c)| c.assemble_s + c.condense_s).sum();
    let share = if spent > 0.0 { wall / spent } else { 0.0 };
    timings.assemble = mine.iter().map(|(_, c)| c.assemble_s).sum::<f64>() * share;
    timings.condense = wall - timings.assemble;
    let condense_rank = wall;
    // factors that would crowd the interface out of memory are dropped now
    // and made again, a part at a time, to recover the interiors
    let factor_bytes: usize = mine.iter().map(|(_, c)| c.factor_bytes).sum();
    if how == Condensation::Dense && factor_bytes as f64 > FACTOR_SHARE * physical_memory() as f64 {
        for (_, c) in mine.iter_mut() {
            c.drop_factor();
        }
        progress(opts, &format!("the parts' factors ({:.1} GB) are freed for the interface and made again for the recovery", factor_bytes as f64 / 1e9));
    }

    // 5. The interface on rank 0.
    let t_problem = Instant::now();
    let received: Vec<(usize, Operator)> = if comm.size() > 1 {
        let ops: Vec<(usize, Operator)> = mine.iter_mut().map(|(i, c)| (*i, c.take_operator())).collect();
        let mut all: Vec<(usize, Operator)> = comm.gather(&ops).into_iter().flatten().collect();
        all.sort_by_key(|(i, _)| *i);
        all
    } else {
        Vec::new()
    };
    let stats_local = (
        mine.iter().map(|(_, c)| c.ni + c.nc).sum::<usize>(),
        mine.iter().map(|(_, c)| c.nc).sum::<usize>(),
        mine.iter().filter(|(_, c)| c.nc > 0).count(),
        mine.iter().map(|(_, c)| c.backward_error).fold(0.0, f64::max),
    );
    let stats: Vec<(usize, usize, usize, f64)> = comm.gather(&stats_local);
    let other_ranks = Ranks { comm, owner: owner.clone() };
    let remote: Option<&dyn Remote> = if service { Some(&other_ranks) } else { None };
    let interface = |ops: &[OperatorRef]| -> Result<Option<InterfaceProblem>> {
        if ops.iter().all(|o| o.nc == 0) {
            return Ok(None);
        }
        Ok(Some(InterfaceProblem::new(model, ops, remote, threads)?))
    };
    let problem = if root {
        let ops: Vec<OperatorRef> = if comm.size() > 1 {
            // this rank's own parts apply their S here
            (received.iter())
                .map(|(i, o)| match mine.iter().find(|(j, _)| j == i) {
                    Some((_, c)) if c.is_applied() => c.operator(),
                    _ => o.as_ref(),
                })
                .collect()
        } else {
            mine.iter().map(|(_, c)| c.operator()).collect()
        };
        let built = interface(&ops);
        if service {
            other_ranks.done();
        }
        agree(comm, built)?
    } else {
        if service {
            serve(comm, &mine);
        }
        agree(comm, Ok(None))?
    };
    drop(received);
    // the interface holds what it needs of every S
    for (_, c) in mine.iter_mut() {
        c.drop_schur();
    }
    let part_refs: Vec<&Part> = all_parts.iter().collect();
    let laws = laws(model, scene);
    let consistent = scene.contacts.iter().any(|c| c.traction == TractionRecovery::Consistent);
    let traction = if root && consistent && !model.pairs.is_empty() {
        Some(ConsistentTraction::new(model).map_err(|e| anyhow!("{}: consistent contact traction: the interface mass matrix: {e}", scene.path.display()))?)
    } else {
        None
    };
    let mut hist = History::new(model.pairs.len());
    // skip what the scene does not ask for: interior displacements only for
    // fields, probes or errors; stresses only when asked
    let need_stress = scene.output.wants("stress");
    let need_u = need_stress || scene.output.wants("displacement") || !scene.probes.is_empty() || scene.analytic.is_some();
    let mut counters = Counters { factorisations: n_parts, condensed_parts: stats.iter().map(|s| s.2).sum(), ..Default::default() };
    let mut residual_interface: f64 = 0.0;
    let mut steps: Vec<StepResult> = Vec::new();
    let (mut interface_s, mut recover_s) = (t_problem.elapsed().as_secs_f64(), 0.0);
    let n_steps = scene.solver.load_steps;
    if root && !model.pairs.is_empty() {
        progress(opts, &format!("contact iteration on {} pairs, {} load step(s)", model.pairs.len(), n_steps));
    }
    let bytes_before_steps = comm.bytes_sent();
    // bytes this rank sends while rank 0 iterates (the S d of the iterative interface)
    let mut bytes_interface = 0;
    for step in 1..=n_steps {
        let lambda: Vec<f64> = model.cases.iter().map(|c| c[step - 1]).collect();
        // 5. the contact iteration (rank 0)
        let t = Instant::now();
        let bytes_before = comm.bytes_sent();
        let mut contact_step = None;
        let mut d_c: Vec<Vec<f64>> = all_parts.iter().map(|p| vec![0.0; p.interface.len() * nd]).collect();
        let mut failed = None;
        if let Some(problem) = problem.as_ref().filter(|_| root) {
            let solution: Option<InterfaceSolution> = if model.pairs.is_empty() {
                // bonded substructures only: one solve, nothing to iterate
                problem.solve(&[], &lambda).ok()
            } else {
                match contact::iterate(problem, &laws, scene.solver.rule, &lambda, &mut hist, scene.solver.max_iterations) {
                    Ok(Outcome { states, solution, summary }) => {
                        let contact::Summary { iterations, converged, cycled, cycles_broken, apex_openings, history } = summary;
                        residual_interface = residual_interface.max(solution.residual);
                        counters.interface_solves += iterations;
                        let mut pairs = solution.pairs.clone();
                        if let Some(tr) = &traction {
                            let t = tr.recover(&solution.forces, problem.basis());
                            for (p, pr) in pairs.iter_mut().enumerate() {
                                if scene.contacts[model.pairs[p].contact].traction == TractionRecovery::Consistent {
                                    pr.sigma_n = t[p][0];
                                    pr.tau_t = t[p][1];
                                    pr.tau_b = t[p][2];
                                }
                            }
                        }
                        let areas = (0..pairs.len()).map(|p| problem.area(p)).collect();
                        contact_step = Some(ContactRun { states, pairs, frames: problem.frames().to_vec(), areas, apex_openings, iterations, converged, cycled, cycles_broken, history });
                        Some(solution)
                    }
                    Err(f) => {
                        failed = Some(failure_message(model, &part_refs, scene, step, f));
                        None
                    }
                }
            };
            match solution {
                Some(s) => d_c = s.d_c,
                None if failed.is_none() => failed = Some(format!("{}: the bonded interface system of the substructures is singular: a body is not held", scene.path.display())),
                None => {}
            }
        }
        if service {
            if root {
                other_ranks.done();
            } else {
                serve(comm, &mine);
            }
        }
        bytes_interface += comm.bytes_sent() - bytes_before;
        interface_s += t.elapsed().as_secs_f64();
        // 6. recovery of the parts on their owners
        let t = Instant::now();
        let order = match &failed {
            Some(msg) => Order::Stop(msg.clone()),
            None => Order::Recover { lambda: lambda.clone(), parts: Vec::new() },
        };
        let mut u = vec![0.0; model.n_nodes() * nd];
        let values: Vec<(usize, Vec<f64>)> = if comm.size() == 1 {
            if let Some(msg) = failed {
                bail!(msg);
            }
            if need_u {
                let d: Vec<(usize, Vec<f64>)> = mine.iter().map(|(i, _)| (*i, std::mem::take(&mut d_c[*i]))).collect();
                recover_parts(model, &mine, &d, &lambda)
            } else {
                Vec::new()
            }
        } else {
            // rank 0 tells every rank what to recover (or to stop)
            let per_rank: Vec<Order> = (0..comm.size())
                .map(|r| match &order {
                    Order::Stop(m) => Order::Stop(m.clone()),
                    Order::Recover { lambda, .. } => Order::Recover {
                        lambda: lambda.clone(),
                        parts: if need_u { (0..n_parts).filter(|&i| owner[i] == r).map(|i| (i, d_c[i].clone())).collect() } else { Vec::new() },
                    },
                })
                .collect();
            let mine_order: Order = comm.scatter(&per_rank);
            let (lambda_r, d) = match mine_order {
                Order::Stop(msg) => bail!(msg),
                Order::Recover { lambda, parts } => (lambda, parts),
            };
            let local = if need_u { recover_parts(model, &mine, &d, &lambda_r) } else { Vec::new() };
            comm.gather(&local).into_iter().flatten().collect()
        };
        if need_u {
            counters.interior_recoveries += n_parts;
        }
        if root {
            for (i, vals) in &values {
                for (q, &n) in all_parts[*i].nodes(model).iter().enumerate() {
                    u[n * nd..n * nd + nd].copy_from_slice(&vals[q * nd..q * nd + nd]);
                }
            }
        }
        let stresses = if root && need_stress {
            counters.stress_recoveries += 1;
            recover::nodal_stresses(model, &u)
        } else {
            Vec::new()
        };
        recover_s += t.elapsed().as_secs_f64();
        let stop = contact_step.as_ref().is_some_and(|c| !c.converged);
        if opts.verbose && root && n_steps > 1 {
            progress(opts, &format!("load step {step}/{n_steps} done"));
        }
        steps.push(StepResult { step, load_factor: lambda[0], case_factors: lambda.clone(), u, stresses, contact: contact_step });
        // every rank stops with rank 0 (an unconverged step ends the run)
        if comm.broadcast(&stop) {
            break;
        }
    }
    timings.interface = interface_s;
    timings.recover = recover_s;
    let bytes_per_step = (comm.bytes_sent() - bytes_before_steps) / steps.len().max(1) as u64;
    let rank_stats = RankStats {
        rank: comm.rank(),
        parts: mine.iter().map(|(i, _)| *i).collect(),
        dofs: stats_local.0,
        condense_s: condense_rank,
        peak_memory_bytes: peak_memory(),
        bytes_sent: comm.bytes_sent(),
        bytes_sent_per_step: bytes_per_step,
        bytes_sent_interface: bytes_interface,
        bytes_sent_per_contact_iteration: 0,
    };
    let mut ranks: Vec<RankStats> = comm.gather(&rank_stats);
    // rank 0 knows how many contact iterations there were
    for r in ranks.iter_mut() {
        r.bytes_sent_per_contact_iteration = r.bytes_sent_interface / counters.interface_solves.max(1) as u64;
    }
    drop(mine);
    if !root {
        return Ok(None);
    }
    // a node shared by several parts is counted once; a pair node with all
    // its components (as without substructures), a join with its free ones
    let mut shared: Vec<usize> = all_parts.iter().flat_map(|p| p.interface.iter().copied()).collect();
    shared.sort_unstable();
    shared.dedup();
    let mut in_pair = vec![false; model.n_nodes()];
    for p in &model.pairs {
        in_pair[p.k] = true;
        in_pair[p.l] = true;
    }
    let interface_dofs: usize = shared.iter().map(|&n| if in_pair[n] { nd } else { (0..nd).filter(|&c| model.prescribed[n * nd + c].is_none()).count() }).sum();
    let interior_dofs: usize = stats.iter().map(|s| s.0 - s.1).sum();
    counters.interface_applications_per_solve = problem.as_ref().map_or_else(Vec::new, |p| p.applications());
    counters.interface_applications = counters.interface_applications_per_solve.iter().sum();
    Ok(Some(Solved {
        steps,
        dofs_total: interior_dofs + interface_dofs,
        dofs_interface: interface_dofs,
        parts: n_parts,
        condensed_parts: stats.iter().map(|s| s.2).sum(),
        residual_interface,
        residual_assembled: stats.iter().map(|s| s.3).fold(0.0, f64::max),
        counters,
        ranks,
    }))
}
