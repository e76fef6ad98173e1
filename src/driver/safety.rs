//! The safety stage after the load steps: the factor of safety against
//! sliding by strength reduction ([`crate::contact::safety`]), as PLAXIS's
//! Safety phase or RS2/RS3's shear strength reduction would find it.
//!
//! 1. From the last load step's converged state (full strength, F = 1), F
//!    rises by `[safety] step`; each trial is the contact iteration at the
//!    last step's loads with the chosen contacts' strength divided by F,
//!    started from a copy of the last state that held (a failed trial
//!    leaves that state as it was). A trial on the condensed interface
//!    costs contact iterations, no factorisation: the parts stay as the
//!    load steps left them.
//! 2. The first trial that fails (blocks slide freely, are held by nothing,
//!    or no state set is found) brackets F; bisection closes the bracket to
//!    `tolerance × F`.
//! 3. The last converged state is recovered (interiors, stresses) for the
//!    output, with the failing trial's states and the blocks it names.
//!
//! A scene whose load steps already fail at F = 1 is unsafe as given
//! ([`unsafe_as_given`]): F is then sought below 1, each trial running the
//! load steps from the start with the strengths raised to 1 / F of the
//! scene's, and the run ends with [`SafetyError::Unsafe`]. Rank 0 runs the
//! trials while the other ranks apply their parts' S, as in the load steps.

use std::time::Instant;

use anyhow::Result;

use super::condense::Parts;
use super::messages::{ContactError, SafetyError};
use super::ranks::Ranks;
use super::steps::{LoadSteps, Step};
use super::{progress, RunOptions};
use crate::contact::safety::{self as reduction, Reduce, Steps};
use crate::contact::system::{InterfaceProblem, SolveFailure};
use crate::contact::{self, Failed, History, Outcome, PairLaw};
use crate::parallel::CommExt;
use crate::recover;
use crate::results::{state_counts, Failure, FailureKind, SafetyRun, SearchCost, StepResult, Trial};
use crate::scene::Safety;

/// A state that held: its factor, where the states and slips stand, and
/// the iteration's outcome (None at F = 1: the last load step's).
struct Held {
    factor: f64,
    history: History,
    outcome: Option<Outcome>,
}

/// The trials of one search on rank 0: the reduced contacts, the loads they
/// run under, and the log.
struct Trials<'s, 'a> {
    step: &'s Step<'a>,
    problem: &'s InterfaceProblem<'s>,
    chosen: Vec<bool>,
    reduce: Reduce,
    opts: &'s RunOptions,
    trials: Vec<Trial>,
    iterations: usize,
    residual: f64,
}

/// Runs the scene's `[safety]` search from the state the load steps left
/// (`done`), adding its cost to theirs; the search on rank 0, None elsewhere
/// and when the scene asks for none.
pub(super) fn run(
    step: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
    done: &mut LoadSteps,
) -> Result<Option<SafetyRun>> {
    let Some(options) = &step.scene.safety else { return Ok(None) };
    // a last step that did not converge has no state to reduce from (the
    // run reports it as such)
    let converged = done.steps.last().and_then(|s| s.contact.as_ref()).is_some_and(|c| c.summary.converged);
    if !ranks.comm().broadcast(&converged) {
        return Ok(None);
    }
    let model = step.model;
    let lambda: Vec<f64> = model.cases.iter().map(|c| c[step.scene.solver.load_steps - 1]).collect();
    let t = Instant::now();
    let mut searched = ranks.on_root(&parts.mine, || search(step, options, &lambda, &done.history, opts));
    let search_s = t.elapsed().as_secs_f64();
    // recover the last state that holds, unless it is the last load step's
    let t = Instant::now();
    let (need_stress, need_u) = step.needs();
    let mut recovered = None;
    if ranks.comm().broadcast(&searched.as_ref().is_some_and(|s| s.held.outcome.is_some())) {
        let answer = searched
            .as_mut()
            .and_then(|s| s.held.outcome.take())
            .map(|o| step.contact_run(step.problem.expect("a search has an interface"), o, &lambda));
        let (contact, d_c) = answer.unzip();
        let u = ranks.recover(model, &step.plan.parts, &parts.mine, d_c.map(Ok), &lambda, need_u)?;
        recovered = contact.zip(u);
    }
    let Some(s) = searched else { return Ok(None) };
    let last = done.steps.last().expect("rank 0 keeps the steps");
    let last = match recovered {
        Some((c, u)) => {
            done.counters.interior_recoveries += usize::from(need_u) * step.plan.parts.len();
            done.counters.stress_recoveries += usize::from(need_stress);
            let stresses = if need_stress { recover::nodal_stresses(model, &u) } else { Vec::new() };
            StepResult {
                step: last.step,
                load_factor: last.load_factor,
                case_factors: last.case_factors.clone(),
                u,
                stresses,
                contact: Some(c),
            }
        }
        None => StepResult {
            step: last.step,
            load_factor: last.load_factor,
            case_factors: last.case_factors.clone(),
            u: last.u.clone(),
            stresses: last.stresses.clone(),
            contact: last.contact.clone(),
        },
    };
    let recover_s = t.elapsed().as_secs_f64();
    // what the search cost, beside the load steps'
    let problem = step.problem.expect("a search has an interface");
    let applications = problem.applications();
    let before: usize = done.counters.interface_applications_per_solve.iter().sum();
    let cost = SearchCost {
        trials: s.trials.len(),
        contact_iterations: s.iterations,
        interface_applications: applications.iter().sum::<usize>() - before,
        search_s,
        recover_s,
        factorisations: 0,
    };
    done.counters.interface_solves += s.iterations;
    done.counters.interface_applications_per_solve = applications;
    done.interface_s += search_s;
    done.recover_s += recover_s;
    done.residual_interface = done.residual_interface.max(s.residual);
    let du = last.u.iter().zip(&done.steps.last().expect("steps").u).map(|(a, b)| a - b).collect();
    Ok(Some(SafetyRun {
        factor: s.held.factor,
        fails_at: s.fails.as_ref().map(|f| f.0),
        failure: s.fails.map(|f| f.1),
        trials: s.trials,
        last,
        du,
        cost,
    }))
}

/// What the search on rank 0 found.
struct Searched {
    held: Held,
    fails: Option<(f64, Failure)>,
    trials: Vec<Trial>,
    iterations: usize,
    residual: f64,
}

/// Brackets and bisects F from the state at F = 1.
fn search(step: &Step, options: &Safety, lambda: &[f64], history: &History, opts: &RunOptions) -> Searched {
    let mut trials = Trials::new(step, options, opts);
    progress(
        opts,
        &format!(
            "safety: reducing {} of {} by F from 1 in steps of {} (tolerance {} x F, at most F = {})",
            options.reduce.names().join(", "),
            contact_names(step, &options.contacts),
            options.step,
            options.tolerance,
            options.max_factor
        ),
    );
    let start = Held { factor: 1.0, history: history.clone(), outcome: None };
    let b = reduction::upward(&steps(options), start, |f, from: &Held| trials.up(f, from, lambda));
    let held = b.holds.map(|h| h.1).expect("the search upward starts from a state that holds");
    let secs: f64 = trials.trials.iter().map(|t| t.seconds).sum();
    match &b.fails {
        Some((f, _)) => progress(
            opts,
            &format!(
                "safety: F = {:.4} (holds at {}, fails at {}) after {} trials, {} contact iterations, {secs:.2} s",
                held.factor,
                six(held.factor),
                six(*f),
                trials.trials.len(),
                trials.iterations
            ),
        ),
        None => progress(
            opts,
            &format!(
                "safety: the search reached its bound: the scene still holds at F = {} (max_factor) after {} trials",
                held.factor,
                trials.trials.len()
            ),
        ),
    }
    Searched { held, fails: b.fails, trials: trials.trials, iterations: trials.iterations, residual: trials.residual }
}

impl<'s, 'a> Trials<'s, 'a> {
    /// No trial yet, on the contacts `options` chooses.
    fn new(step: &'s Step<'a>, options: &Safety, opts: &'s RunOptions) -> Trials<'s, 'a> {
        let problem = step.problem.expect("a search has an interface");
        let chosen = step.model.pairs.iter().map(|p| options.contacts.contains(&p.contact)).collect();
        Trials { step, problem, chosen, reduce: options.reduce, opts, trials: Vec::new(), iterations: 0, residual: 0.0 }
    }

    /// The laws at factor `f`.
    fn laws(&self, f: f64) -> Vec<PairLaw> {
        reduction::reduced(&self.step.laws, &self.chosen, self.reduce, f)
    }

    /// One trial upward: the contact iteration at `f` from a copy of `from`.
    fn up(&mut self, f: f64, from: &Held, lambda: &[f64]) -> Result<Held, Failure> {
        let t = Instant::now();
        let mut h = from.history.clone();
        let laws = self.laws(f);
        let solver = &self.step.scene.solver;
        let result = contact::iterate(self.problem, &laws, solver.rule, lambda, &mut h, solver.max_iterations);
        let held = self.judge(result).map(|outcome| Held { factor: f, history: h, outcome: Some(outcome) });
        self.log(f, from.factor, t, held.as_ref().map(|h| h.outcome.as_ref().expect("a trial's outcome")));
        held
    }

    /// One trial of the load path at `f` from its start (below 1).
    fn path(&mut self, f: f64) -> Result<(), Failure> {
        let t = Instant::now();
        let mut h = History::new(self.step.model.pairs.len());
        let laws = self.laws(f);
        let solver = &self.step.scene.solver;
        let mut last = None;
        for k in 0..solver.load_steps {
            let lambda: Vec<f64> = self.step.model.cases.iter().map(|c| c[k]).collect();
            match self.judge(contact::iterate(self.problem, &laws, solver.rule, &lambda, &mut h, solver.max_iterations))
            {
                Ok(o) => last = Some(o),
                Err(e) => {
                    self.log(f, 0.0, t, Err(&e));
                    return Err(e);
                }
            }
        }
        self.log(f, 0.0, t, Ok(last.as_ref().expect("at least one load step")));
        Ok(())
    }

    /// A converged iteration, or how it failed (the blocks it names).
    fn judge(&mut self, r: Result<Outcome, Failed>) -> Result<Outcome, Failure> {
        match r {
            Ok(o) => {
                self.iterations += o.summary.iterations;
                if o.summary.converged {
                    self.residual = self.residual.max(o.solution.residual);
                    return Ok(o);
                }
                Err(Failure {
                    kind: FailureKind::NotConverged { cycled: o.summary.cycled },
                    blocks: Vec::new(),
                    states: o.states,
                    iteration: o.summary.iterations,
                })
            }
            Err(f) => {
                self.iterations += f.iteration;
                let (kind, parts) = match f.failure {
                    SolveFailure::Sliding(ids) => (FailureKind::Sliding, ids),
                    SolveFailure::NotHeld(ids) => (FailureKind::NotHeld, ids),
                };
                let mut blocks: Vec<usize> =
                    parts.iter().flat_map(|&i| self.step.plan.parts[i].bodies.iter().copied()).collect();
                blocks.sort_unstable();
                blocks.dedup();
                Err(Failure { kind, blocks, states: f.states, iteration: f.iteration })
            }
        }
    }

    /// Records a trial and says how it went.
    fn log(&mut self, f: f64, from: f64, t: Instant, r: Result<&Outcome, &Failure>) {
        let (holds, iterations, states, failed) = match r {
            Ok(o) => (true, o.summary.iterations, state_counts(&o.states), None),
            Err(e) => (false, e.iteration, state_counts(&e.states), Some(e.kind)),
        };
        let k = states;
        let what = match r {
            Ok(_) => {
                format!("holds: {iterations} contact iteration(s), {} stick / {} slip / {} open", k[2], k[1], k[0])
            }
            Err(e) => format!(
                "fails at contact iteration {iterations}: {}{}",
                e.kind.describe(),
                named(self.step.model, &e.blocks)
            ),
        };
        progress(self.opts, &format!("safety: F = {f:.4} {what}"));
        self.trials.push(Trial {
            factor: f,
            from,
            holds,
            iterations,
            states,
            seconds: t.elapsed().as_secs_f64(),
            failed,
        });
    }
}

/// " (\"a\", \"b\")" naming blocks, or nothing.
fn named(model: &crate::model::Model, blocks: &[usize]) -> String {
    if blocks.is_empty() {
        String::new()
    } else {
        format!(" ({})", model.body_names(blocks))
    }
}

/// How the scene's `[safety]` chooses the factors.
fn steps(options: &Safety) -> Steps {
    Steps { step: options.step, tolerance: options.tolerance, max_factor: options.max_factor }
}

/// A factor with six decimals, trailing zeros dropped.
fn six(v: f64) -> String {
    format!("{v:.6}").trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The chosen contacts for a reader: "all contacts" or their groups.
fn contact_names(step: &Step, chosen: &[usize]) -> String {
    let model = step.model;
    if chosen.len() == model.interfaces.len() {
        return "all contacts".into();
    }
    chosen.iter().map(|&i| format!("\"{}\"", model.interfaces[i].name)).collect::<Vec<_>>().join(", ")
}

/// The error of a safety run whose load steps failed with `err`: when they
/// lost equilibrium at F = 1, the scene is unsafe as given and F is sought
/// below 1 ([`SafetyError::Unsafe`]); any other failure is passed on.
pub(super) fn unsafe_as_given(
    step: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
    err: anyhow::Error,
) -> anyhow::Error {
    let Some(options) = &step.scene.safety else { return err };
    let at_one = err
        .downcast_ref::<ContactError>()
        .filter(|e| matches!(e, ContactError::Sliding { .. } | ContactError::NotHeld { .. }))
        .cloned();
    if !ranks.comm().broadcast(&at_one.is_some()) {
        return err;
    }
    let searched = ranks.on_root(&parts.mine, || {
        let mut trials = Trials::new(step, options, opts);
        progress(
            opts,
            "safety: the load steps fail at F = 1: seeking F below 1, each trial running the load steps from the start",
        );
        let b = reduction::downward(&steps(options), (), |f| trials.path(f).map_err(|_| ()));
        (b.holds.map(|h| h.0), b.fails.map_or(1.0, |f| f.0))
    });
    match (searched, at_one) {
        (Some((holds, fails)), Some(at_one)) => {
            SafetyError::Unsafe { scene: step.scene.path.clone(), at_one, holds, fails, max_factor: options.max_factor }
                .into()
        }
        _ => err,
    }
}
