//! The trials of one safety search on rank 0: what a factor F does to the
//! scene ([`Varied`]: the strength of the chosen contacts divided by F, or
//! the chosen loads multiplied by F), the contact iteration at F from the
//! last state that held (or the initial stage and the load steps from
//! their start, below 1), and the verdict only converged iterations give.
//!
//! A trial whose iteration does not converge decides nothing yet: it is
//! retried from the same state in [`RETRY_STEPS`] smaller increments of F,
//! each with [`RETRY_ITERATIONS`] times `[solver] max_iterations` (below 1:
//! a step of the load path again from its start with more iterations; each
//! is solved, and cut, as the run solves it). A converged loss of
//! equilibrium on the way fails the trial; if a step still does not
//! converge, the trial stays undecided ([`Verdict::Undecided`]).

use std::time::Instant;

use crate::contact::safety::{Reduce, Strengths, Verdict};
use crate::contact::system::{InterfaceProblem, SolveFailure, WarmStart};
use crate::contact::{self, Failed, History, Outcome, PairLaw, Stop};
use crate::driver::progress::progress;
use crate::driver::run_options::RunOptions;
use crate::driver::steps::{fresh_history, Step};
use crate::results::{state_counts, Failure, FailureKind, SearchKind, Trial, Undecided};
use crate::scene::Safety;

/// Increments a trial that did not converge is retried in.
pub(super) const RETRY_STEPS: usize = 4;
/// The retry's iterations per step, in `[solver] max_iterations`.
pub(super) const RETRY_ITERATIONS: usize = 4;

/// What F changes.
pub(super) enum Varied {
    /// The strength of the pairs `chosen` divided by F as `reduce` says.
    Strength { chosen: Vec<bool>, reduce: Reduce },
    /// The load cases `cases` multiplied by F.
    Load { cases: Vec<usize> },
}

impl Varied {
    /// The laws at F, from the search's own `laws`.
    fn laws(&self, laws: &[PairLaw], f: f64) -> Vec<PairLaw> {
        match self {
            Varied::Strength { chosen, reduce } => contact::safety::reduced(laws, chosen, *reduce, f),
            Varied::Load { .. } => laws.to_vec(),
        }
    }

    /// The load factors at F, from those of the scene `lambda`.
    pub(super) fn lambda(&self, lambda: &[f64], f: f64) -> Vec<f64> {
        match self {
            Varied::Strength { .. } => lambda.to_vec(),
            Varied::Load { cases } => {
                (lambda.iter().enumerate()).map(|(c, &l)| if cases.contains(&c) { l * f } else { l }).collect()
            }
        }
    }
}

/// A state that held: its factor and load factors, where the states and
/// slips stand, the iteration's outcome (None at F = 1: the last load
/// step's), and where its interface solves ended, for the trials that
/// start from it.
pub(super) struct Held {
    pub factor: f64,
    pub lambda: Vec<f64>,
    pub history: History,
    pub outcome: Option<Outcome>,
    pub start: WarmStart,
}

/// The trials of one search, and their log.
pub(super) struct Trials<'s, 'a> {
    step: &'s Step<'a>,
    problem: &'s InterfaceProblem<'s>,
    pub varied: Varied,
    /// The pair laws the factors apply to (the scene's, with the search's
    /// strength convention).
    laws: Vec<PairLaw>,
    /// The last load step's load factors.
    pub lambda: Vec<f64>,
    opts: &'s RunOptions,
    /// What the progress lines start with ("safety", or the other strength's).
    label: String,
    pub trials: Vec<Trial>,
    pub iterations: usize,
    /// Halvings of the load steps and stage pieces the trials cut.
    cuts: usize,
    pub residual: f64,
}

/// Where a trial started: when, and the search's iterations and cuts.
struct Started {
    at: Instant,
    iterations: usize,
    cuts: usize,
}

impl<'s, 'a> Trials<'s, 'a> {
    /// No trial yet.
    pub fn new(
        step: &'s Step<'a>,
        varied: Varied,
        laws: Vec<PairLaw>,
        opts: &'s RunOptions,
        label: String,
    ) -> Trials<'s, 'a> {
        let problem = step.problem.expect("a search has an interface");
        let n = step.scene.solver.load_steps;
        let lambda = step.model.cases.iter().map(|c| c[n - 1]).collect();
        let trials = Vec::new();
        Trials { step, problem, varied, laws, lambda, opts, label, trials, iterations: 0, cuts: 0, residual: 0.0 }
    }

    /// One trial upward: the contact iteration at `f` from a copy of
    /// `from`, retried in smaller steps when it does not converge.
    pub fn up(&mut self, f: f64, from: &Held) -> Verdict<Held, Failure> {
        let max = self.step.scene.solver.max_iterations;
        match self.attempt(f, from, max, false) {
            Verdict::Undecided(e) => {
                let step = (f - from.factor) / RETRY_STEPS as f64;
                self.say(&format!(
                    "F = {f:.4} did not converge ({}): retrying from F = {:.4} in {RETRY_STEPS} steps of {step:.4} with up to {} contact iterations each",
                    e.kind.describe(),
                    from.factor,
                    max * RETRY_ITERATIONS
                ));
                self.retry(f, from)
            }
            v => v,
        }
    }

    /// The retry of `up`: `f` reached from `from` in smaller steps.
    fn retry(&mut self, f: f64, from: &Held) -> Verdict<Held, Failure> {
        let max = self.step.scene.solver.max_iterations * RETRY_ITERATIONS;
        let mut at: Option<Held> = None;
        for j in 1..=RETRY_STEPS {
            let fj = from.factor + (f - from.factor) * j as f64 / RETRY_STEPS as f64;
            match self.attempt(fj, at.as_ref().unwrap_or(from), max, true) {
                Verdict::Holds(h) => at = Some(h),
                other => return other,
            }
        }
        at.map_or_else(|| Verdict::Undecided(self.no_steps()), Verdict::Holds)
    }

    /// The failure of a retry with no step (never: RETRY_STEPS >= 1).
    fn no_steps(&self) -> Failure {
        Failure {
            kind: FailureKind::NotConverged(Stop::MaxIterations),
            blocks: Vec::new(),
            states: Vec::new(),
            iteration: 0,
            lambda: self.lambda.clone(),
            mechanism: None,
        }
    }

    /// The contact iteration at `f` from a copy of `from`, with at most `max` iterations.
    fn attempt(&mut self, f: f64, from: &Held, max: usize, retry: bool) -> Verdict<Held, Failure> {
        let t = self.start();
        let mut h = from.history.clone();
        self.problem.start_from(&from.start);
        let (laws, lambda) = (self.varied.laws(&self.laws, f), self.varied.lambda(&self.lambda, f));
        let verdict = self.iterate(&laws, &lambda, &mut h, max);
        self.log(f, from.factor, t, verdict.as_ref(), retry);
        match verdict {
            Ok(outcome) => Verdict::Holds(self.held(f, lambda, h, outcome)),
            Err(e) => verdict_of(e),
        }
    }

    /// One trial of the load path at `f` from its start (below 1): the
    /// initial stage when the scene has one, then every load step, each at
    /// `f` (the stage too: see [`super::below`]), a step that does not
    /// converge retried with more iterations. Each is solved as the run
    /// solves it: the stage ([`Step::iterate_stage`]) where the in-situ
    /// stress puts the joints beyond the trial's strength through the
    /// strength ramp from there, a load step ([`Step::iterate_step`]) cut
    /// in halves where it does not converge. Holds with where the last
    /// step ended.
    pub fn path(&mut self, f: f64) -> Verdict<Held, Failure> {
        let t = self.start();
        let mut h = fresh_history(self.step.model, self.step.problem, &self.step.laws);
        let laws = self.varied.laws(&self.laws, f);
        let (step, model) = (self.step, self.step.model);
        let mut last = None;
        // the stage from nothing, then each load step from where the last ended
        let mut lambda = vec![0.0; model.cases.len()];
        if let Some(factors) = model.stage_factors() {
            lambda = self.varied.lambda(&factors, f);
            let stage = |h: &mut History, max| step.iterate_stage(&laws, &lambda, h, step.budget(max), &mut |_| {});
            match self.path_step(f, "the initial stage", &lambda, &mut h, stage) {
                Ok(o) => {
                    if let Some(top) = o.summary.strengths.first() {
                        self.say(&format!(
                            "F = {f:.4}: the initial stage in {} contact iterations, the strength brought down from {top:.4} times the trial's (the in-situ stress is beyond it)",
                            o.summary.iterations
                        ));
                    }
                    last = Some(o);
                }
                Err(e) => return self.failed(f, t, e),
            }
        }
        for k in 0..step.scene.solver.load_steps {
            let to = self.varied.lambda(&model.cases.iter().map(|c| c[k]).collect::<Vec<_>>(), f);
            let from = std::mem::replace(&mut lambda, to);
            let load =
                |h: &mut History, max| step.iterate_step(&laws, (&from, &lambda), h, step.budget(max), &mut |_| {});
            match self.path_step(f, &format!("load step {}", k + 1), &lambda, &mut h, load) {
                Ok(o) => last = Some(o),
                Err(e) => return self.failed(f, t, e),
            }
        }
        let outcome = last.expect("at least one load step");
        self.log(f, 0.0, t, Ok(&outcome), false);
        Verdict::Holds(self.held(f, lambda, h, outcome))
    }

    /// Where the interface's next solve would start.
    pub fn warm_start(&self) -> WarmStart {
        self.problem.warm_start()
    }

    /// The state that held at `f`, where the solves stand now.
    fn held(&self, f: f64, lambda: Vec<f64>, history: History, outcome: Outcome) -> Held {
        Held { factor: f, lambda, history, outcome: Some(outcome), start: self.problem.warm_start() }
    }

    /// A trial of the load path started at `t` that failed with `e`, logged.
    fn failed(&mut self, f: f64, t: Started, e: Failure) -> Verdict<Held, Failure> {
        self.log(f, 0.0, t, Err(&e), false);
        verdict_of(e)
    }

    /// One step `name` of the load path at `f` to the factors `lambda`,
    /// `solve`d from `h` with at most so many iterations (per piece),
    /// judged; retried from its start with more iterations when it does
    /// not converge (each piece of the stage's ramp, or of the load step's
    /// cuts, with more).
    fn path_step(
        &mut self,
        f: f64,
        name: &str,
        lambda: &[f64],
        h: &mut History,
        solve: impl Fn(&mut History, usize) -> Result<Outcome, Failed>,
    ) -> Result<Outcome, Failure> {
        let most = self.step.scene.solver.max_iterations;
        let start = h.clone();
        let result = self.judge(solve(h, most), lambda);
        if !matches!(&result, Err(e) if matches!(e.kind, FailureKind::NotConverged { .. })) {
            return result;
        }
        *h = start;
        let max = most * RETRY_ITERATIONS;
        self.say(&format!("F = {f:.4}: {name} did not converge: retrying it with up to {max} contact iterations"));
        self.judge(solve(h, max), lambda)
    }

    /// The contact iteration under `laws` and `lambda` from `h`, judged.
    fn iterate(&mut self, laws: &[PairLaw], lambda: &[f64], h: &mut History, max: usize) -> Result<Outcome, Failure> {
        let rule = self.step.scene.solver.rule;
        let r = contact::iterate(self.problem, laws, rule, lambda, h, max);
        self.judge(r, lambda)
    }

    /// A converged iteration, or how it failed under `lambda` (the blocks
    /// it names).
    fn judge(&mut self, r: Result<Outcome, Failed>, lambda: &[f64]) -> Result<Outcome, Failure> {
        match r {
            Ok(o) => {
                self.iterations += o.summary.iterations;
                self.cuts += o.summary.cuts;
                if o.summary.converged {
                    self.residual = self.residual.max(o.solution.residual);
                    return Ok(o);
                }
                Err(Failure {
                    kind: FailureKind::NotConverged(o.summary.why_not()),
                    blocks: Vec::new(),
                    states: o.states,
                    iteration: o.summary.iterations,
                    lambda: lambda.to_vec(),
                    mechanism: None,
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
                Err(Failure {
                    kind,
                    blocks,
                    states: f.states,
                    iteration: f.iteration,
                    lambda: lambda.to_vec(),
                    mechanism: None,
                })
            }
        }
    }

    /// A progress line of this search.
    pub fn say(&self, what: &str) {
        progress(self.opts, &format!("{}: {what}", self.label));
    }

    /// A trial starts now.
    fn start(&self) -> Started {
        Started { at: Instant::now(), iterations: self.iterations, cuts: self.cuts }
    }

    /// Records a trial started at `t` and says how it went: a trial that
    /// holds, with the contact iterations and cuts of all its steps.
    fn log(&mut self, f: f64, from: f64, t: Started, r: Result<&Outcome, &Failure>, retry: bool) {
        let (spent, cuts) = (self.iterations - t.iterations, self.cuts - t.cuts);
        let (holds, iterations, states, failed) = match r {
            Ok(o) => (true, spent, state_counts(&o.states), None),
            Err(e) => (false, e.iteration, state_counts(&e.states), Some(e.kind)),
        };
        let k = states;
        let cut = match cuts {
            0 => String::new(),
            1 => " (1 cut)".to_string(),
            n => format!(" ({n} cuts)"),
        };
        let what = match r {
            Ok(_) => {
                format!("holds: {iterations} contact iteration(s){cut}, {} stick / {} slip / {} open", k[2], k[1], k[0])
            }
            Err(e) if matches!(e.kind, FailureKind::NotConverged { .. }) => {
                format!("decides nothing: {} ({iterations} contact iterations)", e.kind.describe())
            }
            Err(e) => format!(
                "fails at contact iteration {iterations}: {}{}",
                e.kind.describe(),
                named(self.step.model, &e.blocks)
            ),
        };
        self.say(&format!("F = {f:.4}{} {what}", if retry { " (retry)" } else { "" }));
        self.trials.push(Trial {
            factor: f,
            from,
            holds,
            iterations,
            states,
            seconds: t.at.elapsed().as_secs_f64(),
            failed,
            retry,
        });
    }
}

/// A failed trial's verdict: undecided when its iteration did not converge.
fn verdict_of<S>(e: Failure) -> Verdict<S, Failure> {
    match e.kind {
        FailureKind::NotConverged { .. } => Verdict::Undecided(e),
        _ => Verdict::Fails(e),
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

/// What F varies in the scene's search.
pub(super) fn varied(step: &Step, options: &Safety) -> Varied {
    match &options.raise {
        Some(r) => {
            let model = step.model;
            let mut cases: Vec<usize> = r.loads.iter().map(|&i| model.load_cases[i]).collect();
            if r.gravity {
                cases.push(model.gravity_case);
            }
            Varied::Load { cases }
        }
        None => Varied::Strength {
            chosen: step.model.pairs.iter().map(|p| options.contacts.contains(&p.contact)).collect(),
            reduce: options.reduce,
        },
    }
}

/// The trials of a search with the strength convention `strengths`.
pub(super) fn trials<'s, 'a>(
    step: &'s Step<'a>,
    options: &Safety,
    strengths: Strengths,
    opts: &'s RunOptions,
    label: &str,
) -> Trials<'s, 'a> {
    let laws = match options.raise {
        Some(_) => step.laws.clone(),
        None => strengths.laws(&step.laws),
    };
    Trials::new(step, varied(step, options), laws, opts, label.to_string())
}

/// The trials that decided nothing, for the results.
pub(super) fn undecided(u: &[(f64, Failure)]) -> Vec<Undecided> {
    u.iter()
        .map(|(f, e)| {
            let stop = match e.kind {
                FailureKind::NotConverged(stop) => stop,
                _ => Stop::MaxIterations,
            };
            Undecided { factor: *f, iterations: e.iteration, stop }
        })
        .collect()
}

/// What a scene's `[safety]` searches.
pub(super) fn kind(options: &Safety) -> SearchKind {
    match options.raise {
        Some(_) => SearchKind::Load,
        None => SearchKind::Strength(options.strengths),
    }
}
