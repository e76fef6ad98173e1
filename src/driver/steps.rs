//! Stages 5 and 6, load step by load step, as deal.II's step-41 runs its
//! loop: at each step rank 0 iterates the contact states on the interface
//! ([`contact::iterate`]), the parts' owners recover their interiors, rank 0
//! recovers the stresses and records the step, and a step that did not
//! converge stops the run. States, cracks and slip carry over from step to
//! step ([`History`]).
//!
//! With `[solver] initial_stage` a step 0 comes first: gravity, the
//! initial stresses and the hold load at 1, every other load at 0
//! ([`Model::stage_factors`]), through the same iteration and History; the
//! load steps then start from its factors and state, and its displacements
//! are taken off theirs once their stresses are recovered (stresses and
//! pair forces stay totals).

use std::time::Instant;

use super::condense::Parts;
use super::messages::ContactError;
use super::plan::Plan;
use super::progress::progress;
use super::ranks::{agree, Ranks};
use super::run_options::RunOptions;
use crate::contact::cutting::{Attempt, Budget};
use crate::contact::system::{Accuracy, InterfaceProblem};
use crate::contact::traction::ConsistentTraction;
use crate::contact::Limit;
use crate::contact::{self, History, Outcome, PairLaw};
use crate::error::Result;
use crate::model::Model;
use crate::recover;
use crate::results::{state_counts, ContactRun, Counters, InitialStage, PairWater, StepResult};
use crate::scene::{Scene, StateRule, TractionRecovery};

/// What the load steps did: the steps (on rank 0), and what they cost.
#[derive(Default)]
pub(super) struct LoadSteps {
    pub steps: Vec<StepResult>,
    /// Steps run (on every rank).
    pub done: usize,
    pub counters: Counters,
    /// The largest relative residual of the contact iterations' last solves.
    pub residual_interface: f64,
    pub interface_s: f64,
    pub recover_s: f64,
    /// Bytes this rank sent in all steps, and during the contact
    /// iterations (the S d of the iterative interface).
    pub bytes: u64,
    pub bytes_interface: u64,
    /// States, cracks and slips where the last step ended (on rank 0).
    pub history: History,
    /// The initial equilibrium stage, when the scene asks for one (on rank 0).
    pub stage: Option<InitialStage>,
}

/// One step's interface answer on rank 0.
struct Answer {
    /// Each part's interface displacements.
    d_c: Vec<Vec<f64>>,
    contact: Option<ContactRun>,
}

/// What every step reads (and the safety search after them).
pub(super) struct Step<'a> {
    pub scene: &'a Scene,
    pub model: &'a Model,
    pub plan: &'a Plan,
    pub problem: Option<&'a InterfaceProblem<'a>>,
    /// The scene's pair laws, at full strength.
    pub laws: Vec<PairLaw>,
    traction: Option<ConsistentTraction>,
    /// What the run was asked (its progress lines).
    opts: &'a RunOptions,
}

impl<'a> Step<'a> {
    /// What the steps of `scene` read, on every rank.
    pub fn new(
        scene: &'a Scene,
        model: &'a Model,
        plan: &'a Plan,
        parts: &'a Parts,
        (ranks, opts): (&Ranks, &'a RunOptions),
    ) -> Result<Step<'a>> {
        let traction = agree(ranks.comm(), traction(scene, model, parts.problem.as_ref()).map_err(Into::into))?;
        let (problem, laws) = (parts.problem.as_ref(), laws(model, scene));
        Ok(Step { scene, model, plan, problem, laws, traction, opts })
    }

    /// Whether the steps recover the stresses and the interior
    /// displacements: only for fields, probes or errors that need them.
    pub fn needs(&self) -> (bool, bool) {
        let scene = self.scene;
        let need_stress = scene.output.wants("stress");
        (
            need_stress,
            need_stress || scene.output.wants("displacement") || !scene.probes.is_empty() || scene.analytic.is_some(),
        )
    }
}

/// Runs every load step of the scene.
pub(super) fn run(this: &Step, parts: &Parts, opts: &RunOptions, ranks: &Ranks) -> Result<LoadSteps> {
    let (scene, model) = (this.scene, this.model);
    // skip what the scene does not ask for
    let (need_stress, need_u) = this.needs();
    let n_steps = scene.solver.load_steps;
    if !model.pairs.is_empty() {
        progress(opts, &format!("contact iteration on {} pairs, {} load step(s)", model.pairs.len(), n_steps));
    }
    let mut out = LoadSteps::default();
    let mut history = fresh_history(model, this.problem, &this.laws);
    if super::fallback::takes_rounds(scene) {
        history.penalty = Some(super::fallback::stiffness(scene, model).0);
    }
    let bytes_before = ranks.bytes_sent();
    let (stage, failed) = stage(this, parts, opts, ranks, (need_stress, &mut history), &mut out)?;
    out.stage = stage;
    if failed {
        // its last iterate is the run's one step: no load step starts from it
        out.history = history;
        return Ok(out);
    }
    let start = model.stage_factors().unwrap_or_else(|| vec![0.0; model.cases.len()]);
    for step in 1..=n_steps {
        let lambda: Vec<f64> = model.cases.iter().map(|c| c[step - 1]).collect();
        let from: Vec<f64> =
            (model.cases.iter().zip(&start)).map(|(c, s)| if step > 1 { c[step - 2] } else { *s }).collect();
        // 5. and 6. iterate and recover the interiors
        let (u, contact) = solve(this, parts, ranks, (step, &from, &lambda), need_u, &mut history, &mut out)?;
        // the stresses on rank 0
        let t = Instant::now();
        out.done += 1;
        // record the step; one that did not converge ends the run
        let stop = contact.as_ref().is_some_and(|c| !c.summary.converged);
        if let Some(mut u) = u {
            let stresses = stresses(model, &u, need_stress, &mut out);
            reset(&mut u, out.stage.as_ref());
            out.steps.push(StepResult {
                step,
                load_factor: lambda[0],
                case_factors: lambda.clone(),
                u,
                stresses,
                contact,
            });
        }
        out.recover_s += t.elapsed().as_secs_f64();
        if n_steps > 1 {
            progress(opts, &format!("load step {step}/{n_steps} {}", if stop { "did not converge" } else { "done" }));
        }
        if ranks.stop(stop) {
            break;
        }
    }
    out.bytes = ranks.bytes_sent() - bytes_before;
    out.history = history;
    out.counters.interface_applications_per_solve = parts.problem.as_ref().map_or_else(Vec::new, |p| p.applications());
    Ok(out)
}

/// Where a load path starts from nothing (the run's load steps, a safety
/// trial's below 1, the replay of the failing step): every pair stuck,
/// nothing cracked or slipped, and where the joints deform (`laws` with
/// springs, on rank 0: `problem`) their springs carrying the in-situ
/// stress, unloaded at [`contact::elastic::unloaded`]. Without them
/// [`contact::iterate`] runs the rigid rule.
pub(super) fn fresh_history(model: &Model, problem: Option<&InterfaceProblem>, laws: &[PairLaw]) -> History {
    let mut history = History::new(model.pairs.len());
    let Some(problem) = problem else { return history };
    let traction = crate::model::insitu::tractions(model);
    if traction.iter().any(|t| *t != [0.0; 3]) {
        history.insitu = contact::elastic::insitu_forces(problem, &traction);
        history.insitu_case = model.initial_case;
    }
    if let Some(stiffness) = contact::elastic::stiffness(laws) {
        history.unloaded = contact::elastic::unloaded(problem, &stiffness, &traction);
    }
    history
}

/// The initial equilibrium stage, when the model has one: its contact
/// iteration from nothing to [`Model::stage_factors`] in `history`, and its
/// displacements (recovered whatever the output needs: every step's are
/// taken off by them); and whether it failed. One that does not converge
/// ends the run, as a load step does: no load step can start from it, and
/// its last iterate is written as the run's one step (step 0, its own
/// displacements, nothing taken off), for report.md and contact.csv to
/// say where it did not settle.
fn stage(
    this: &Step,
    parts: &Parts,
    opts: &RunOptions,
    ranks: &Ranks,
    (need_stress, history): (bool, &mut History),
    out: &mut LoadSteps,
) -> Result<(Option<InitialStage>, bool)> {
    let model = this.model;
    let Some(factors) = model.stage_factors() else { return Ok((None, false)) };
    progress(opts, "initial equilibrium stage: the in-situ stress with the contacts active");
    let zero = vec![0.0; factors.len()];
    let solved = solve(this, parts, ranks, (0, &zero, &factors), true, history, out);
    let (u, contact) = solved.inspect_err(|_| insitu_told(this, ranks))?;
    let summary = contact
        .as_ref()
        .map(|c| c.summary.clone())
        .unwrap_or_else(|| crate::contact::Summary { converged: true, ..Default::default() });
    let failed = ranks.stop(!summary.converged);
    if failed {
        insitu_told(this, ranks);
    }
    let Some(u) = u else { return Ok((None, failed)) };
    let states = contact.as_ref().map_or([0; 3], |c| state_counts(&c.states));
    let mut staged = initial_stage(model, &summary, states, factors.clone(), u);
    if failed {
        let u = std::mem::take(&mut staged.u);
        staged.u = vec![0.0; u.len()];
        let stresses = stresses(model, &u, need_stress, out);
        out.steps.push(StepResult { step: 0, load_factor: 0.0, case_factors: factors, u, stresses, contact });
    }
    Ok((Some(staged), failed))
}

/// The nodal stresses of the displacements `u` when the output wants
/// them (counted in `out`), else none.
fn stresses(model: &Model, u: &[f64], need_stress: bool, out: &mut LoadSteps) -> Vec<crate::recover::BodyStress> {
    if !need_stress {
        return Vec::new();
    }
    out.counters.stress_recoveries += 1;
    recover::nodal_stresses(model, u)
}

/// The in-situ warnings on stderr (rank 0) when the stage fails: a run
/// that succeeds says them with its results, one that fails in the stage
/// with its error (they name the joint sets the in-situ stress puts
/// beyond their strength, which is why a stage fails).
fn insitu_told(this: &Step, ranks: &Ranks) {
    use std::io::Write;
    if ranks.rank() != 0 {
        return;
    }
    for w in super::warnings::insitu_warnings(this.scene, this.model) {
        let _ = writeln!(std::io::stderr(), "warning: {w}");
    }
}

/// The initial stage's result from its contact `summary`, its `states`
/// counts, its load factors and its displacements `u`.
pub(super) fn initial_stage(
    model: &Model,
    summary: &crate::contact::Summary,
    states: [usize; 3],
    case_factors: Vec<f64>,
    u: Vec<f64>,
) -> InitialStage {
    let nd = model.nd;
    let length = |k: usize| u[k * nd..k * nd + nd].iter().map(|v| v * v).sum::<f64>().sqrt();
    let largest_at = (0..model.n_nodes()).max_by(|&a, &b| length(a).total_cmp(&length(b))).unwrap_or(0);
    InitialStage {
        iterations: summary.iterations,
        converged: summary.converged,
        cuts: summary.cuts,
        states,
        strength_ramp: summary.strengths.clone(),
        case_factors,
        largest: if model.n_nodes() > 0 { length(largest_at) } else { 0.0 },
        largest_at,
        u,
    }
}

/// Step `step` from the factors `from` to `lambda`: the contact states
/// iterated on rank 0 (the other ranks apply their S), then the interiors
/// recovered on their owners when `need_u`. The displacements (on rank 0)
/// and the contact result.
fn solve(
    this: &Step,
    parts: &Parts,
    ranks: &Ranks,
    (step, from, lambda): (usize, &[f64], &[f64]),
    need_u: bool,
    history: &mut History,
    out: &mut LoadSteps,
) -> Result<(Option<Vec<f64>>, Option<ContactRun>)> {
    let (t, bytes) = (Instant::now(), ranks.bytes_sent());
    let answer = ranks.on_root(&parts.mine, || this.iterate(step, (from, lambda), history, out));
    out.bytes_interface += ranks.bytes_sent() - bytes;
    out.interface_s += t.elapsed().as_secs_f64();
    let t = Instant::now();
    let (d_c, contact) = match answer {
        Some(Ok(a)) => (Some(Ok(a.d_c)), a.contact),
        Some(Err(e)) => (Some(Err(e.into())), None),
        None => (None, None),
    };
    let u = ranks.recover(this.model, &this.plan.parts, &parts.mine, d_c, lambda, need_u)?;
    if need_u {
        out.counters.interior_recoveries += this.plan.parts.len();
    }
    out.recover_s += t.elapsed().as_secs_f64();
    Ok((u, contact))
}

/// The progress line of an attempt of `what` ("load step 3/4", "initial
/// stage") that was cut, `seconds` after the last: the whole step halved,
/// or a piece.
fn attempt_said(what: &str, a: Attempt, budget: Budget, seconds: f64) -> String {
    let of = match a.strength {
        Some((from, to)) => format!(", the joints' strength {from:.3} -> {to:.3} times theirs"),
        None if (a.from, a.to) == (0.0, 1.0) => String::new(),
        None => format!(" {} -> {} of its load", a.from, a.to),
    };
    let (its, end) = (a.iterations, if a.converged { "converged" } else { "not converged" });
    let why = if a.cycled { ", the states cycling" } else { "" };
    let then = if a.halved {
        let Limit { most, settling } = budget.iterations;
        let more = if budget.iterations.runs_on() {
            format!(" ({settling} while their states all but settle)")
        } else {
            String::new()
        };
        format!(": solving it again in two halves from where it started, up to {most} iterations each{more}")
    } else {
        String::new()
    };
    format!("{what}{of}: {end} in {its} iteration(s){why} ({seconds:.1} s){then}")
}

/// Takes the initial stage's displacements off a step's.
pub(super) fn reset(u: &mut [f64], stage: Option<&InitialStage>) {
    if let Some(s) = stage {
        u.iter_mut().zip(&s.u).for_each(|(a, b)| *a -= b);
    }
}

impl Step<'_> {
    /// The interface displacements of every part at load step `step` from
    /// the factors `from` to `lambda`, and the contact result: the state
    /// iteration (its step cut where it does not converge), or one solve
    /// when the parts are joined by bonded interfaces alone.
    fn iterate(
        &self,
        step: usize,
        (from, lambda): (&[f64], &[f64]),
        history: &mut History,
        out: &mut LoadSteps,
    ) -> Result<Answer, ContactError> {
        let nd = self.model.nd;
        let Some(problem) = self.problem else {
            // nothing condensed: every part was solved directly
            return Ok(Answer {
                d_c: self.plan.parts.iter().map(|p| vec![0.0; p.interface.len() * nd]).collect(),
                contact: None,
            });
        };
        if self.model.pairs.is_empty() {
            let solution = problem.solve(&[], lambda, Accuracy::Answer).map_err(|_| ContactError::BondedNotHeld)?;
            return Ok(Answer { d_c: solution.d_c, contact: None });
        }
        let budget = self.run_budget();
        // a cut step's attempts as they end: a long wait, said
        let what = match step {
            0 => "initial stage".to_string(),
            _ => format!("load step {step}/{}", self.scene.solver.load_steps),
        };
        let mut t = Instant::now();
        let mut told = |a: Attempt| {
            progress(self.opts, &attempt_said(&what, a, budget, t.elapsed().as_secs_f64()));
            t = Instant::now();
        };
        // the initial stage (step 0, from nothing) as a safety trial solves it
        let outcome = if step == 0 {
            self.iterate_stage(&self.laws, lambda, history, budget, &mut told)
        } else {
            self.iterate_step(&self.laws, (from, lambda), history, budget, &mut told)
        };
        let outcome = outcome.map_err(|f| ContactError::failed(self.model, &self.plan.parts, self.scene, step, f))?;
        out.residual_interface = out.residual_interface.max(outcome.solution.residual);
        out.counters.interface_solves += outcome.summary.iterations;
        let (contact, d_c) = self.contact_run(problem, outcome, lambda);
        Ok(Answer { d_c, contact: Some(contact) })
    }

    /// Where the initial stage's strength ramp starts with the pairs
    /// carrying `laws` ([`contact::ramp::iterate_stage`]): the largest
    /// in-situ mobilisation beyond their strength, or 0 (none beyond, or
    /// the paper's rule: the stage solved as a load step is).
    fn stage_mobilised(&self, laws: &[PairLaw]) -> f64 {
        if self.scene.solver.rule == StateRule::Robust {
            super::warnings::insitu_mobilised(self.scene, self.model, laws)
        } else {
            0.0
        }
    }

    /// The initial stage on rank 0 with the pairs carrying `laws`, from
    /// nothing (`h` new) to the load factors `to`, as the run solves it:
    /// through the strength ramp where the in-situ stress puts the joints
    /// beyond `laws` ([`Step::stage_mobilised`]), each piece halved as
    /// `budget` says, each attempt of a stage so halved `told` as it ends.
    /// The one place that solves the stage, for the run's (step 0), a
    /// safety trial's and the replay before a search below 1.
    pub fn iterate_stage(
        &self,
        laws: &[PairLaw],
        to: &[f64],
        h: &mut History,
        budget: Budget,
        told: &mut dyn FnMut(Attempt),
    ) -> Result<Outcome, contact::Failed> {
        let problem = self.problem.expect("rank 0 has the interface");
        let (zero, rule) = (vec![0.0; to.len()], self.scene.solver.rule);
        let mobilised = self.stage_mobilised(laws);
        contact::ramp::iterate_stage(problem, (laws, mobilised), rule, (&zero, to), h, budget, told)
    }

    /// A load step on rank 0 with the pairs carrying `laws`, from the load
    /// factors `from` (where `h` ended) to `to`, as the run solves it: cut
    /// in halves where it does not converge as `budget` says
    /// ([`contact::cutting`]), each attempt of a cut step `told` as it
    /// ends. The one place that solves a load step, for the run's and a
    /// safety trial's.
    pub fn iterate_step(
        &self,
        laws: &[PairLaw],
        (from, to): (&[f64], &[f64]),
        h: &mut History,
        budget: Budget,
        told: &mut dyn FnMut(Attempt),
    ) -> Result<Outcome, contact::Failed> {
        let problem = self.problem.expect("rank 0 has the interface");
        contact::cutting::iterate_cutting(problem, laws, self.scene.solver.rule, (from, to), h, budget, told)
    }

    /// `max_iterations` for a step and for each of its pieces, halved
    /// down to `[solver] max_cuts` times where it does not converge (the
    /// paper's rule is kept as the paper has it: no cutting). A safety
    /// trial's, which gives the iterations it retries with.
    pub fn budget(&self, max_iterations: usize) -> Budget {
        let solver = &self.scene.solver;
        Budget::new(max_iterations, if solver.rule == StateRule::Paper { 0 } else { solver.max_cuts })
    }

    /// The run's: `[solver] max_iterations` a step and each of its cut
    /// pieces, and where rigid joints fall back to joints that deform
    /// when a step does not converge ([`super::fallback::eligible`]), at
    /// most [`contact::cutting::SHORT_ITERATIONS`]: the rigid attempt is a
    /// try before the fallback, which has ended every corpus scene whose
    /// rigid step did not end in as many (docs/convergence.md, "A rigid
    /// step held to 30 iterations where the fallback follows").
    pub fn run_budget(&self) -> Budget {
        let budget = self.budget(self.scene.solver.max_iterations);
        if super::fallback::eligible(self.scene) {
            budget.short()
        } else {
            budget
        }
    }

    /// A step's contact result from the iteration's outcome (the stresses
    /// of contacts with `traction = "consistent"` recovered from the pair
    /// forces), the water in the joints at its states under `lambda`, and
    /// the parts' interface displacements.
    pub fn contact_run(
        &self,
        problem: &InterfaceProblem,
        outcome: Outcome,
        lambda: &[f64],
    ) -> (ContactRun, Vec<Vec<f64>>) {
        let Outcome { states, solution, summary, law_residual, cracked } = outcome;
        let mut pairs = solution.pairs;
        if let Some(tr) = &self.traction {
            let t = tr.recover(&solution.forces, problem.basis());
            for (p, pr) in pairs.iter_mut().enumerate() {
                if self.scene.contacts[self.model.pairs[p].contact].traction == TractionRecovery::Consistent {
                    pr.sigma_n = t[p][0];
                    pr.tau_t = t[p][1];
                    pr.tau_b = t[p][2];
                }
            }
        }
        let areas = (0..pairs.len()).map(|p| problem.area(p)).collect();
        let water = problem.water().map(|w| PairWater {
            pressure: w.pressures(self.model, &states, lambda),
            force: w.forces(&states, lambda),
        });
        let frames = problem.frames().to_vec();
        let locked_off = solution.locked_off;
        let run = ContactRun { states, pairs, frames, areas, summary, water, law_residual, cracked, locked_off };
        (run, solution.d_c)
    }
}

/// The pair laws of the model's pairs, from the scene's contacts.
fn laws(model: &Model, scene: &Scene) -> Vec<PairLaw> {
    (model.pairs.iter())
        .map(|p| {
            let c = &scene.contacts[p.contact];
            PairLaw { strength: c.strength, slip: c.slip, stiffness: c.stiffness }
        })
        .collect()
}

/// The consistent traction recovery, on rank 0 when some contact asks for it.
fn traction(
    scene: &Scene,
    model: &Model,
    problem: Option<&InterfaceProblem>,
) -> Result<Option<ConsistentTraction>, ContactError> {
    let consistent = scene.contacts.iter().any(|c| c.traction == TractionRecovery::Consistent);
    if problem.is_none() || !consistent || model.pairs.is_empty() {
        return Ok(None);
    }
    ConsistentTraction::new(model).map(Some).map_err(|e| ContactError::Traction { reason: e })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cut_steps_attempts_are_said_with_their_share_of_the_load() {
        let budget = Budget::new(100, 3).short();
        let at = |from, to, converged, halved| Attempt {
            from,
            to,
            iterations: 30,
            converged,
            cycled: false,
            halved,
            strength: None,
        };
        let whole = attempt_said("load step 3/4", at(0.0, 1.0, false, true), budget, 5.8);
        assert_eq!(whole, "load step 3/4: not converged in 30 iteration(s) (5.8 s): solving it again in two halves from where it started, up to 30 iterations each (100 while their states all but settle)");
        // where nothing follows, the pieces take the step's own budget
        let long = attempt_said(
            "load step 3/4",
            Attempt { iterations: 100, ..at(0.0, 1.0, false, true) },
            Budget::new(100, 3),
            44.8,
        );
        assert_eq!(long, "load step 3/4: not converged in 100 iteration(s) (44.8 s): solving it again in two halves from where it started, up to 100 iterations each");
        // one that stopped in an orbit says so
        let orbit = attempt_said(
            "load step 2/2",
            Attempt { iterations: 27, cycled: true, ..at(0.0, 1.0, false, true) },
            budget,
            15.4,
        );
        assert_eq!(orbit, "load step 2/2: not converged in 27 iteration(s), the states cycling (15.4 s): solving it again in two halves from where it started, up to 30 iterations each (100 while their states all but settle)");
        let held =
            attempt_said("load step 3/4", Attempt { iterations: 3, ..at(0.75, 0.875, true, false) }, budget, 0.6);
        assert_eq!(held, "load step 3/4 0.75 -> 0.875 of its load: converged in 3 iteration(s) (0.6 s)");
        // the deepest piece that does not converge ends the step: no halves
        let last = attempt_said("load step 3/4", at(0.875, 1.0, false, false), budget, 5.6);
        assert_eq!(last, "load step 3/4 0.875 -> 1 of its load: not converged in 30 iteration(s) (5.6 s)");
        // an initial stage cut as a load step is
        let stage = attempt_said("initial stage", at(0.0, 0.5, true, false), budget, 1.2);
        assert_eq!(stage, "initial stage 0 -> 0.5 of its load: converged in 30 iteration(s) (1.2 s)");
        // and a piece of its strength ramp says the strengths
        let piece = Attempt { strength: Some((1.0707, 1.0353)), ..at(1.0, 0.5, false, true) };
        assert_eq!(
            attempt_said("initial stage", piece, budget, 0.3),
            "initial stage, the joints' strength 1.071 -> 1.035 times theirs: not converged in 30 iteration(s) (0.3 s): solving it again in two halves from where it started, up to 30 iterations each (100 while their states all but settle)"
        );
    }
}
