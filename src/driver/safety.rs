//! The safety stage after the load steps: the factor of safety by strength
//! reduction ([`crate::contact::safety`]), as PLAXIS's Safety phase or
//! RS2/RS3's shear strength reduction would find it, or by raising loads
//! (`[safety] load`, a load factor search).
//!
//! 1. From the last load step's converged state (F = 1), F rises by
//!    `[safety] step`; each trial ([`mod@trials`]) is the contact iteration with
//!    the chosen contacts' strength divided by F (each pair keeping its peak
//!    cohesion once it cracks, unless the scene asks for its residual
//!    strength), or with the chosen loads multiplied by F, started from a
//!    copy of the last state that held. A trial on the condensed interface
//!    costs contact iterations, no factorisation.
//! 2. The first converged trial that fails (blocks slide, topple or are
//!    held by nothing) brackets F; bisection closes the bracket to
//!    `tolerance × F`. A trial whose iteration does not converge, even
//!    retried in smaller steps with more iterations, decides nothing: F is
//!    then what converged trials bracket, and the run ends non-zero.
//! 3. The failing trial's mechanism is named ([`super::mechanism`]); the
//!    last converged state is recovered (interiors, stresses) for the output.
//! 4. Strength reduction where a pair would lose cohesion as it cracks: the
//!    same search with the other convention, for the factor beside it.
//!
//! A scene whose load steps already fail at F = 1 is unsafe as given
//! ([`below`]): F is sought below 1 and the results that exist are written.
//! Rank 0 runs the trials while the other ranks apply their parts' S, as in
//! the load steps.

mod below;
mod recovery;
mod trials;

use std::time::Instant;

use super::condense::Parts;
use super::mechanism;
use super::messages::{RetryAdvice, SafetyError};
use super::ranks::Ranks;
use super::run_options::RunOptions;
use super::steps::{LoadSteps, Step};
use crate::contact::safety::{self as reduction, Bracket, OnUndecided, Strengths};
use crate::contact::system::WarmStart;
use crate::contact::{History, Stop};
use crate::error::Result;
use crate::parallel::CommExt;
use crate::results::{Failure, OtherFactor, SafetyRun, SearchCost, SearchKind, StepResult, Trial, Undecided};
use crate::scene::Safety;
use recovery::recovered;
use trials::{kind, trials, undecided, Held, Trials};

pub(super) use below::below_one;

/// The error of a run whose safety factor converged trials did not decide.
pub(super) fn undecided_error(run: &crate::results::Run) -> Option<SafetyError> {
    let s = run.safety.as_ref().filter(|s| !s.decided && !s.below_one)?;
    let holds = s.factor.unwrap_or(1.0);
    // those that left the bracket open: above the last hold, below the failure
    let open: Vec<&Undecided> =
        s.undecided.iter().filter(|u| u.factor > holds && s.fails_at.is_none_or(|x| u.factor < x)).collect();
    Some(SafetyError::Undecided {
        holds,
        fails: s.fails_at,
        undecided: open.iter().map(|u| u.factor).collect(),
        load: s.kind == SearchKind::Load,
        rigid_joints: super::fallback::advised(run),
        retry: retry_advice(&run.scene.solver, &open),
        results: None,
    })
}

/// What may decide the trials `open` under the scene's `solver` options.
fn retry_advice(solver: &crate::scene::Solver, open: &[&Undecided]) -> RetryAdvice {
    let settling = open.iter().any(|u| u.stop == Stop::MaxIterations);
    RetryAdvice { rule: solver.rule, budget: settling.then_some(solver.max_iterations * trials::RETRY_ITERATIONS) }
}

/// Steps 5 and 6: the load steps; where they lose equilibrium, the
/// search below one (a scene that fails at full strength is unsafe as
/// given): the steps it kept, the search and the error the run ends
/// with. The error alone where nothing is left to write (no step held,
/// no iterate).
pub(super) fn steps_or_below(
    step: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
) -> Result<(LoadSteps, Option<SafetyRun>, Option<crate::error::Error>)> {
    match super::steps::run(step, parts, opts, ranks) {
        Ok(done) => Ok((done, None, None)),
        Err(e) => {
            let below = below_one(step, parts, opts, ranks, e)?;
            if !ranks.comm().broadcast(&below.safety.as_ref().is_some_and(|_| !below.done.steps.is_empty())) {
                return Err(below.error);
            }
            Ok((below.done, below.safety, Some(below.error)))
        }
    }
}

/// Runs the scene's `[safety]` search from the state the load steps left
/// (`done`), adding its cost to theirs; the search on rank 0, None elsewhere
/// and when the scene asks for none. A trial that decides nothing ends
/// the search undecided where `on_undecided` says so (rigid joints that
/// fall back).
pub(super) fn run(
    step: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
    done: &mut LoadSteps,
    on_undecided: OnUndecided,
) -> Result<Option<SafetyRun>> {
    let Some(options) = &step.scene.safety else { return Ok(None) };
    // a last step that did not converge has no state to reduce from (the
    // run reports it as such)
    let converged = done.steps.last().and_then(|s| s.contact.as_ref()).is_some_and(|c| c.summary.converged);
    if !ranks.comm().broadcast(&converged) {
        return Ok(None);
    }
    let t = Instant::now();
    let mut searched = ranks.on_root(&parts.mine, || search(step, options, &done.history, opts, on_undecided));
    let search_s = t.elapsed().as_secs_f64();
    // recover the last state that holds, unless it is the last load step's
    let t = Instant::now();
    let recovered = recover_held(step, parts, ranks, searched.as_mut().map(|s| &mut s.held), done)?;
    let Some(s) = searched else { return Ok(None) };
    let last = done.steps.last().expect("rank 0 keeps the steps");
    let last = recovered.unwrap_or_else(|| copy(last));
    let recover_s = t.elapsed().as_secs_f64();
    let cost = cost(step, done, &s, search_s, recover_s);
    let du = last.u.iter().zip(&done.steps.last().expect("steps").u).map(|(a, b)| a - b).collect();
    Ok(Some(SafetyRun {
        kind: kind(options),
        factor: Some(s.held.factor),
        fails_at: s.fails.as_ref().map(|f| f.0),
        failure: s.fails.map(|f| f.1),
        decided: s.decided,
        undecided: s.undecided,
        below_one: false,
        other: s.other,
        trials: s.trials,
        last: Some(last),
        du,
        cost,
    }))
}

/// The recovered state of `held` (on rank 0; its outcome taken), when it
/// is not the last load step's; `done` counts the recoveries.
fn recover_held(
    step: &Step,
    parts: &Parts,
    ranks: &Ranks,
    held: Option<&mut Held>,
    done: &mut LoadSteps,
) -> Result<Option<StepResult>> {
    if !ranks.comm().broadcast(&held.as_ref().is_some_and(|h| h.outcome.is_some())) {
        return Ok(None);
    }
    let o = held.and_then(|h| h.outcome.take().map(|o| (0, h.lambda.clone(), o)));
    recovered(step, parts, ranks, o, done)
}

/// A copy of a step's result.
fn copy(s: &StepResult) -> StepResult {
    StepResult {
        step: s.step,
        load_factor: s.load_factor,
        case_factors: s.case_factors.clone(),
        u: s.u.clone(),
        stresses: s.stresses.clone(),
        contact: s.contact.clone(),
    }
}

/// What the search cost beside the load steps, added to theirs.
fn cost(step: &Step, done: &mut LoadSteps, s: &Searched, search_s: f64, recover_s: f64) -> SearchCost {
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
    cost
}

/// What the search on rank 0 found.
struct Searched {
    held: Held,
    fails: Option<(f64, Failure)>,
    decided: bool,
    undecided: Vec<Undecided>,
    other: Option<OtherFactor>,
    trials: Vec<Trial>,
    iterations: usize,
    residual: f64,
}

/// Brackets and bisects F from the state at F = 1, names the failing
/// trial's mechanism and, for strength reduction where the conventions
/// differ, finds F with the other one too (not where a trial that
/// decided nothing stopped the search: `on_undecided`).
fn search(step: &Step, options: &Safety, history: &History, opts: &RunOptions, on: OnUndecided) -> Searched {
    let mut t = trials(step, options, options.strengths, opts, "safety");
    t.say(&what(step, options));
    // (where the load steps' solves ended: both searches start there)
    let start = t.warm_start();
    let b = upward(&mut t, options, (history, &start), on);
    let decided = b.decided(&options.steps);
    let stopped = on == OnUndecided::Stop && !b.undecided.is_empty();
    let held = b.holds.map(|h| h.1).expect("the search upward starts from a state that holds");
    let fails = b.fails.map(|(f, mut e)| {
        e.mechanism = mechanism::of(step.model, &e.blocks, &e.states, &e.lambda);
        (f, e)
    });
    let undecided = undecided(&b.undecided);
    match b.undecided.last().filter(|_| stopped) {
        Some((f, _)) => t.say(&format!(
            "F = {f:.4} decided nothing, even retried: the search stops there ({} trials, {} contact iterations), the last factor that held F = {:.4}",
            t.trials.len(),
            t.iterations,
            held.factor
        )),
        None => say_end(&t, held.factor, fails.as_ref().map(|f| f.0), decided, options),
    }
    let other = (options.raise.is_none() && Strengths::differ(&step.laws) && !stopped).then(|| {
        let s = options.strengths.other();
        let mut o = trials(step, options, s, opts, &format!("safety ({} strength)", s.key()));
        let b = upward(&mut o, options, (history, &start), OnUndecided::PassOver);
        let factor = b.holds.as_ref().map(|h| h.0);
        let decided = b.decided(&options.steps);
        let fails_at = b.fails.as_ref().map(|f| f.0);
        say_end(&o, factor.unwrap_or(1.0), fails_at, decided, options);
        OtherFactor { strengths: s, factor, fails_at, decided, trials: o.trials.len(), iterations: o.iterations }
    });
    Searched {
        held,
        fails,
        decided,
        undecided,
        other,
        trials: t.trials,
        iterations: t.iterations,
        residual: t.residual,
    }
}

/// The search upward from the state `history` the load steps left, and
/// where their solves ended.
fn upward(
    t: &mut Trials,
    options: &Safety,
    (history, start): (&History, &WarmStart),
    on: OnUndecided,
) -> Bracket<Held, Failure> {
    let lambda = t.lambda.clone();
    let start = Held { factor: 1.0, history: history.clone(), outcome: None, lambda, start: start.clone() };
    reduction::upward(&options.steps, start, on, |f, from: &Held| t.up(f, from))
}

/// The first progress line: what the search varies.
fn what(step: &Step, options: &Safety) -> String {
    let how = format!(
        "from 1 in steps of {} (tolerance {} x F, at most F = {})",
        options.steps.step, options.steps.tolerance, options.steps.max_factor
    );
    match &options.raise {
        Some(r) => format!("raising {} by F {how}", raised_names(step, r)),
        None => format!(
            "reducing {} of {} by F {how}, each pair keeping its {} strength once it cracks",
            options.reduce.names().join(", "),
            contact_names(step, &options.contacts),
            options.strengths.key()
        ),
    }
}

/// The last progress line of a search.
fn say_end(t: &Trials, held: f64, fails: Option<f64>, decided: bool, options: &Safety) {
    let n = t.trials.len();
    let secs: f64 = t.trials.iter().map(|t| t.seconds).sum();
    let what = match (fails, decided) {
        (Some(f), true) => format!("F = {held:.4} (holds at {}, fails at {})", six(held), six(f)),
        (Some(f), false) => format!(
            "F is not decided: converged trials hold at {} and fail at {}, and trials between did not converge",
            six(held),
            six(f)
        ),
        (None, true) => format!("the search reached its bound: the scene still holds at F = {held} (max_factor)"),
        (None, false) => format!(
            "F is not decided: converged trials hold at {}, and no trial above converged up to max_factor = {}",
            six(held),
            options.steps.max_factor
        ),
    };
    t.say(&format!("{what} after {n} trials, {} contact iterations, {secs:.2} s", t.iterations));
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

/// The raised loads for a reader.
fn raised_names(step: &Step, r: &crate::scene::Raise) -> String {
    let mut names: Vec<String> = r.loads.iter().map(|&i| format!("\"{}\"", step.scene.loads[i].group)).collect();
    if r.gravity {
        names.push("gravity".into());
    }
    names.join(", ")
}
