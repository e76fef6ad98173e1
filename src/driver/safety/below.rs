//! A scene whose load steps lose equilibrium as given (at F = 1) with a
//! safety search: unsafe as given. F is sought below 1 ([`downward`](crate::contact::safety::downward), every
//! trial running the load steps from the start with the strength raised to
//! 1 / F, or the raised loads multiplied by F), the blocks' mechanism at
//! F = 1 is named, and the results that exist are kept for the output:
//!
//! - the last load step that held at F = 1, and the failing step's last
//!   iterate (the step run again, stopped one iteration before the solve
//!   that found no equilibrium), which is not in equilibrium: its contact
//!   summary says it did not converge;
//! - the last state that holds below 1 as the safety search's state.
//!
//! A scene with an initial stage runs it first in every trial, at the
//! trial's strength (or loads): the strength divided by F holds from the
//! start of the path, in situ too, as RS2's shear strength reduction
//! reduces the strength of every stage. F is then one factor for the
//! whole path, and a stage that the in-situ stress already fails at full
//! strength (a block its joints cannot hold) has an F below 1 like any
//! load step; a stage kept at full strength would have none. Each trial
//! solves the stage as the run does ([`Step::iterate_stage`]): where the
//! in-situ stress puts the joints beyond the trial's strength (F times
//! the scene's mobilisation where c and f are both divided), through the
//! strength ramp from there ([`crate::contact::ramp`]). The stage is
//! replayed with the scene's laws too, as the run solved it: the load
//! steps kept start from its state, and its displacements are taken off
//! theirs as in the run. A stage that fails at F = 1 leaves no load step
//! to write: the run ends with the search's error alone. The search
//! upward from a path that holds at F = 1 starts from where the stage and
//! the steps left it, and reduces the strength from there.
//!
//! With peak strengths (the search's default) the load path may hold at
//! F = 1 although the load steps, which lose cohesion where pairs crack,
//! did not: the search then goes upward from there, and the run still ends
//! with the load steps' error.

use super::recovery::{self, recovered};
use super::trials::{kind, trials, undecided, Held, Trials};
use crate::contact::safety::{self as reduction, OnUndecided, Verdict};
use crate::contact::{self, History, Outcome};
use crate::driver::condense::Parts;
use crate::driver::mechanism;
use crate::driver::messages::{ContactError, SafetyError};
use crate::driver::ranks::Ranks;
use crate::driver::run_options::RunOptions;
use crate::driver::steps::{fresh_history, LoadSteps, Step};
use crate::error::{Error, Result};
use crate::parallel::CommExt;
use crate::results::SafetyRun;
use crate::results::{Failure, SearchCost};

/// What a run that fails at F = 1 keeps: the steps whose results exist,
/// the search below 1, and the error to end with once they are written.
pub(in crate::driver) struct Below {
    pub done: LoadSteps,
    pub safety: Option<SafetyRun>,
    pub error: Error,
}

/// The load steps' error `err` of a scene with a safety search: when they
/// lost equilibrium at F = 1, the search below 1 and the results that
/// exist ([`Below`]); any other failure (or a scene without `[safety]`)
/// is passed on. On ranks other than 0 `safety` is None.
pub(in crate::driver) fn below_one(
    step: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
    err: Error,
) -> Result<Below> {
    let Some(options) = &step.scene.safety else { return Err(err) };
    let at_one = match &err {
        Error::Contact(e) if matches!(**e, ContactError::Sliding { .. } | ContactError::NotHeld { .. }) => {
            Some(e.as_ref().clone())
        }
        _ => None,
    };
    if !ranks.comm().broadcast(&at_one.is_some()) {
        return Err(err);
    }
    let t = std::time::Instant::now();
    let searched = ranks.on_root(&parts.mine, || {
        let mut t = trials(step, options, options.strengths, opts, "safety");
        let replay = replay(step);
        let found = search(&mut t, options, step);
        (found, replay, t.trials, t.iterations)
    });
    let search_s = t.elapsed().as_secs_f64();
    // the results that exist: the last step that held, the failing
    // step's last iterate, the last hold below 1 (every rank recovers)
    let (found, replay, trials_run, iterations) = match searched {
        Some((f, r, t, i)) => (Some(f), Some(r), t, i),
        None => (None, None, Vec::new(), 0),
    };
    let mut done = replayed(step, parts, ranks, replay)?;
    let mut found = found;
    let hold = found.as_mut().and_then(|f| f.held.as_mut()).map(|h| (0, h.lambda.clone(), h.outcome.take()));
    let has_hold = ranks.comm().broadcast(&hold.as_ref().is_some_and(|h| h.2.is_some()));
    let last = if has_hold {
        let hold = hold.and_then(|(s, l, o)| o.map(|o| (s, l, o)));
        recovered(step, parts, ranks, hold, &mut done)?
    } else {
        None
    };
    let Some(found) = found else {
        return Ok(Below { done, safety: None, error: err });
    };
    let error = found.error(options, at_one.expect("rank 0 knows the failure"));
    let du = last.as_ref().map_or_else(Vec::new, |l| l.u.clone());
    let safety = SafetyRun {
        kind: kind(options),
        factor: found.held.as_ref().map(|h| h.factor),
        fails_at: found.fails.as_ref().map(|f| f.0),
        failure: found.fails.map(|f| f.1),
        decided: found.decided,
        undecided: found.undecided,
        below_one: true,
        other: None,
        last,
        du,
        cost: SearchCost {
            trials: trials_run.len(),
            contact_iterations: iterations,
            interface_applications: 0,
            search_s,
            recover_s: 0.0,
            factorisations: 0,
        },
        trials: trials_run,
    };
    Ok(Below { done, safety: Some(safety), error })
}

/// The replayed stage and load steps recovered (on rank 0 `replay`, None
/// elsewhere), every rank taking part: the stage's displacements, then
/// the steps whose results exist, reset by them.
fn replayed(step: &Step, parts: &Parts, ranks: &Ranks, replay: Option<Replay>) -> Result<LoadSteps> {
    let mut done = LoadSteps::default();
    let (stage, replay) = replay.map(|r| (r.stage, r.steps)).unzip();
    let stage = stage.flatten();
    if ranks.comm().broadcast(&stage.is_some()) {
        done.stage = recovery::stage(step, parts, ranks, stage, &mut done)?;
    }
    let mut outcomes: Vec<Option<Replayed>> = replay.map_or_else(Vec::new, |r| r.into_iter().map(Some).collect());
    let n = ranks.comm().broadcast(&outcomes.len());
    for k in 0..n {
        let o = outcomes.get_mut(k).and_then(Option::take).map(|o| (o.step, o.lambda, o.outcome));
        if let Some(r) = recovered(step, parts, ranks, o, &mut done)? {
            done.steps.push(r);
        }
    }
    Ok(done)
}

/// What the search below 1 found on rank 0.
struct Found {
    held: Option<Held>,
    fails: Option<(f64, Failure)>,
    decided: bool,
    undecided: Vec<crate::results::Undecided>,
    /// How the blocks move at F = 1, for a reader.
    at_one: Option<(String, crate::contact::mechanism::BlockState)>,
}

impl Found {
    /// The error the run ends with.
    fn error(&self, options: &crate::scene::Safety, at_one: ContactError) -> Error {
        SafetyError::Unsafe {
            at_one,
            holds: self.held.as_ref().map(|h| h.factor),
            fails: self.fails.as_ref().map_or(f64::INFINITY, |f| f.0),
            max_factor: options.steps.max_factor,
            mechanism: self.at_one.clone(),
            load: options.raise.is_some(),
            results: None,
        }
        .into()
    }
}

/// The load path at F = 1 again (with the search's strength convention),
/// then F below 1; the mechanism of each failure named.
fn search(t: &mut Trials, options: &crate::scene::Safety, step: &Step) -> Found {
    let stage = if step.model.stage_factors().is_some() { "the initial stage and " } else { "" };
    t.say(&format!(
        "the load steps fail at F = 1: seeking F below 1, each trial running {stage}the load steps from the start"
    ));
    let at_one = match t.path(1.0) {
        Verdict::Fails(e) | Verdict::Undecided(e) => e,
        Verdict::Holds(h) => {
            t.say("the load path holds at F = 1 with the search's peak strengths (the load steps lost cohesion where pairs cracked): seeking F upward from there");
            return upward_from(t, options, step, h);
        }
    };
    let mut at_one = at_one;
    at_one.mechanism = mechanism::of(step.model, &at_one.blocks, &at_one.states, &at_one.lambda);
    let told = at_one.mechanism.as_ref().map(|m| (crate::contact::mechanism::describe(step.model, m), m.kind));
    let b = reduction::downward(&options.steps, at_one, |f| t.path(f));
    let decided = b.decided(&options.steps);
    let (f, mut e) = b.fails.expect("a search below 1 keeps a failure");
    if e.mechanism.is_none() {
        e.mechanism = mechanism::of(step.model, &e.blocks, &e.states, &e.lambda);
    }
    Found { held: b.holds.map(|h| h.1), fails: Some((f, e)), decided, undecided: undecided(&b.undecided), at_one: told }
}

/// The search upward from a load path that holds at F = 1 (`start`, with
/// peak strengths where the load steps lost cohesion): its bracket as a
/// [`Found`].
fn upward_from(t: &mut Trials, options: &crate::scene::Safety, step: &Step, start: Held) -> Found {
    let b = reduction::upward(&options.steps, start, OnUndecided::PassOver, |f, from: &Held| t.up(f, from));
    let decided = b.decided(&options.steps);
    let fails = b.fails.map(|(f, mut e)| {
        e.mechanism = mechanism::of(step.model, &e.blocks, &e.states, &e.lambda);
        (f, e)
    });
    Found { held: b.holds.map(|h| h.1), fails, decided, undecided: undecided(&b.undecided), at_one: None }
}

/// The replay on rank 0: the initial stage that held (its load factors and
/// outcome), and the load steps' results that exist.
struct Replay {
    stage: Option<(Vec<f64>, Outcome)>,
    steps: Vec<Replayed>,
}

/// A replayed load step on rank 0: its number, load factors and outcome.
struct Replayed {
    step: usize,
    lambda: Vec<f64>,
    outcome: Outcome,
}

/// The scene's initial stage (when it has one) and load steps again with
/// its own laws: the stage when it held, then the last load step that
/// held and the failing step's last iterate when it had one (no step when
/// the stage did not hold).
fn replay(step: &Step) -> Replay {
    let model = step.model;
    let mut h = fresh_history(model, step.problem, &step.laws);
    let stage = match model.stage_factors() {
        None => None,
        Some(factors) => {
            // as the run solved it (through the strength ramp where it needs one)
            match step.iterate_stage(&step.laws, &factors, &mut h, step.run_budget(), &mut |_| {}) {
                Ok(o) if o.summary.converged => Some((factors, o)),
                _ => return Replay { stage: None, steps: Vec::new() },
            }
        }
    };
    Replay { stage, steps: replay_steps(step, h) }
}

/// The scene's load steps again with its own laws from `h`, each cut as
/// the run cut it ([`Step::iterate_step`]): the last that held, and the
/// failing step's last iterate when it had one (the step run again uncut,
/// stopped one iteration before the solve that found no equilibrium).
fn replay_steps(step: &Step, mut h: History) -> Vec<Replayed> {
    let (model, solver) = (step.model, &step.scene.solver);
    let problem = step.problem.expect("a search has an interface");
    let mut held: Option<Replayed> = None;
    // each step from where the last ended (the stage, or nothing)
    let mut from = model.stage_factors().unwrap_or_else(|| vec![0.0; model.cases.len()]);
    for k in 1..=solver.load_steps {
        let lambda: Vec<f64> = model.cases.iter().map(|c| c[k - 1]).collect();
        let before = h.clone();
        match step.iterate_step(&step.laws, (&from, &lambda), &mut h, step.run_budget(), &mut |_| {}) {
            Ok(o) if o.summary.converged => {
                from.clone_from(&lambda);
                held = Some(Replayed { step: k, lambda, outcome: o });
            }
            Ok(o) => {
                return held.into_iter().chain([Replayed { step: k, lambda, outcome: o }]).collect();
            }
            Err(f) => {
                let mut h = before;
                let iterate = (f.iteration > 1)
                    .then(|| contact::iterate(problem, &step.laws, solver.rule, &lambda, &mut h, f.iteration - 1).ok())
                    .flatten()
                    .map(|outcome| Replayed { step: k, lambda, outcome });
                return held.into_iter().chain(iterate).collect();
            }
        }
    }
    held.into_iter().collect()
}
