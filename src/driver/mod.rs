//! The pipeline of one run, in the order data flows, on one process or
//! spread over MPI ranks ([`ranks`]: the only code that knows rank 0 from
//! the others):
//!
//! 1. read and validate the scene;
//! 2. mesh the .geo with the gmsh CLI (cached) or read the .msh;
//! 3. build the model: bodies, loads, supports, contact pairs;
//! 4. [`plan`] the parts (bodies joined by shared nodes, cut into
//!    substructures), their owner ranks and how they are condensed;
//!    [`condense`] them, each rank its own (parts without contact are
//!    solved directly), and set up the interface on rank 0;
//! 5. and 6. the load [`steps`]: iterate the contact states on the
//!    interface, recover interior displacements and stresses; then, when
//!    the scene has `[safety]`, the factor of safety against sliding by
//!    strength reduction ([`safety`]) from where the last step ended;
//! 7. errors and probes of the last step, the check the scene's
//!    `[analytic]` asks for, then every result file at once (none when
//!    anything failed).
//!
//! Each stage returns plain data; [`stats`] turns what they measured into
//! the run's statistics and [`messages`] turns their failures into one
//! paragraph each.

use std::path::{Path, PathBuf};
use std::time::Instant;

mod about;
mod condense;
mod fallback;
mod mechanism;
mod meshing;
pub(crate) mod messages;
mod plan;
mod progress;
mod ranks;
mod run_options;
mod safety;
mod stats;
mod steps;
mod warnings;

pub use fallback::said as fallback_said;
pub use meshing::{gmsh_job, load_mesh, mesh_into};
pub use messages::{Apex, At, ContactError, PlanError, SafetyError, NOT_CUT};
pub use plan::{preview, Memory, Preview};
use progress::{progress, say};
pub use run_options::RunOptions;
pub use warnings::{insitu_warnings, model_warnings};

use crate::analytic;
use crate::contact::law::PairResult;
use crate::contact::safety::OnUndecided;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::model::Model;
use crate::output;
use crate::output::files::{Stage, Staged};
use crate::parallel::{Comm, Serial};
use crate::recover;
use crate::scene::Scene;

// what a run returns, defined in `results` (which the writers read)
pub use crate::results::{
    state_counts, Checks, ContactRun, Counters, Fallback, RankStats, Run, Stats, StepResult, Timings,
};
use crate::substructure::Condensation;

/// Runs a scene file end to end and writes its results.
pub fn run(scene_path: &Path, opts: &RunOptions) -> Result<Run> {
    run_scene(Scene::load(scene_path)?, opts)
}

/// Runs a validated scene end to end on this one process and writes its results.
pub fn run_scene(scene: Scene, opts: &RunOptions) -> Result<Run> {
    Ok(run_on(scene, opts, &Serial)?.expect("one process is rank 0"))
}

/// Runs a validated scene on the ranks of `comm`: every rank builds the
/// model and condenses its parts; rank 0 meshes, iterates, recovers the
/// stresses, writes the results and gets the [`Run`] (the others `None`).
pub fn run_on(mut scene: Scene, opts: &RunOptions, comm: &dyn Comm) -> Result<Option<Run>> {
    let t0 = Instant::now();
    // sparse work is sequential: parts run side by side instead (threads, ranks)
    faer::set_global_parallelism(faer::Par::Seq);
    let opts = &ranks::options(comm, opts);

    // 1. Scene.
    if opts.bonded {
        scene.bond_all();
    }
    let out = opts.out_dir(&scene);

    // 2. Mesh: rank 0 makes the run's staging directory and runs gmsh
    // into it (or takes the cached mesh), then every rank reads the file.
    progress(opts, "meshing");
    let t = Instant::now();
    let (mesh, msh, mesh_cached, stage) = ranks::mesh(comm, &scene, &out, opts)?;
    let timings = Timings { mesh: t.elapsed().as_secs_f64(), ..Default::default() };
    let (writer, path) = (scene.name.clone(), scene.path.clone());
    let mut to = Writing { out, t0, stage };
    // the file context of the stages' errors about the scene, added once
    let result = solve(scene, opts, comm, (mesh, msh, mesh_cached), timings, &mut to).map_err(|e| e.in_scene(&path));
    // a run that ends without committing its results keeps its mesh
    if let Some(stage) = to.stage.filter(Stage::has_files) {
        let _ = stage.commit(Staged::amend(&to.out, &writer), &mut |m| say(m));
    }
    result
}

/// Where and how a run's results go: the directory, the run's start, and
/// its staging directory (rank 0) until the commit takes it.
struct Writing {
    out: PathBuf,
    t0: Instant,
    stage: Option<Stage>,
}

/// Steps 3 to 7 of [`run_on`], on the mesh of step 2; where rigid joints
/// did not converge, again with joints that deform ([`fallback`]).
fn solve(
    scene: Scene,
    opts: &RunOptions,
    comm: &dyn Comm,
    (mesh, msh, mesh_cached): (Mesh, PathBuf, bool),
    timings: Timings,
    to: &mut Writing,
) -> Result<Option<Run>> {
    let again = fallback::eligible(&scene).then(|| (mesh.clone(), msh.clone()));
    let given = Try::Given { may_fall: again.is_some() };
    let rigid = attempt(scene, opts, comm, (mesh, msh, mesh_cached), timings.clone(), given, to)?;
    let (scene, record, (mesh, msh), unheld) = match (rigid, again) {
        (Attempt::Fell(scene, record, unheld), Some(again)) => (*scene, record.map(|r| *r), again, unheld),
        (Attempt::Ran(run), _) => return Ok(run.map(|r| *r)),
        (Attempt::Fell(..), None) => unreachable!("only an eligible scene falls back"),
    };
    // (where the rigid joints left a body unheld, said once the joints
    // that deform hold it: where they do not, the rigid error is all the
    // run says)
    let warning = record.as_ref().map(|r| format!("warning: {}", fallback::said(r)));
    let said_after = unheld.is_some();
    if !said_after {
        warning.iter().for_each(|w| say(w));
    }
    // the rigid attempt's factors are gone: their pages back to the system
    crate::memory::give_back();
    let taken = scene.contacts.first().and_then(|c| c.stiffness);
    let fell = attempt(scene, opts, comm, (mesh, msh, mesh_cached), timings, Try::Fallback(record), to);
    let fell = fell.map_err(|e| match (unheld, taken) {
        // a scene that holds nothing with joints that deform either: the
        // rigid joints' error says so
        (Some(rigid), _) if fallback::unheld(&e).is_some() => *rigid,
        (_, Some(k)) => e.in_fallback(k),
        (_, None) => e,
    });
    let fell = fell?;
    if said_after {
        warning.iter().for_each(|w| say(w));
    }
    match fell {
        Attempt::Ran(run) => Ok(run.map(|r| *r)),
        Attempt::Fell(..) => unreachable!("joints that deform do not fall back"),
    }
}

/// What one attempt at steps 3 to 7 gave: the run (written), or, where
/// its rigid joints did not converge and the scene lets the run fall
/// back, the scene with joints that deform and the record of why (on
/// rank 0), with the rigid joints' error where they stopped at a state
/// set that holds nothing.
enum Attempt {
    Ran(Option<Box<Run>>),
    Fell(Box<Scene>, Option<Box<Fallback>>, Option<Box<crate::error::Error>>),
}

/// Which attempt at steps 3 to 7 a run makes: the scene as given
/// (`may_fall`: whether its rigid joints may fall back), or the fallback
/// (its record, on rank 0).
enum Try {
    Given { may_fall: bool },
    Fallback(Option<Fallback>),
}

/// Steps 3 to 7 on the mesh of step 2, as `this` says.
fn attempt(
    scene: Scene,
    opts: &RunOptions,
    comm: &dyn Comm,
    (mesh, msh, mesh_cached): (Mesh, PathBuf, bool),
    mut timings: Timings,
    this: Try,
    to: &mut Writing,
) -> Result<Attempt> {
    // 3. Model.
    let t = Instant::now();
    let model = Model::build(&mesh, &scene.model_spec())?;
    drop(mesh);
    timings.model = t.elapsed().as_secs_f64();

    // 4. Parts, owners, condensation, the interface.
    let plan = plan::plan(&scene, &model, opts, comm.size())?;
    let ranks = ranks::Ranks::new(comm, plan.owner.clone(), plan.kind.condensation() == Condensation::Applied);
    let parts = condense::condense(&model, &plan, opts, &ranks)?;

    // 5.–6. The load steps: contact iteration, recovery; then the safety
    // search when the scene asks for one (a scene that fails at full
    // strength is unsafe as given).
    let step = steps::Step::new(&scene, &model, &plan, &parts, (&ranks, opts))?;
    let may_fall = matches!(this, Try::Given { may_fall: true });
    let (mut done, safety, failed) = match steps_or_fall(&step, &parts, opts, &ranks, may_fall, to.t0)? {
        Ok(done) => done,
        Err(fell) => return Ok(fell),
    };
    let safety = match failed {
        Some(_) => safety,
        None => match safety_or_fall(&step, &parts, opts, &ranks, &mut done, may_fall, to.t0)? {
            Ok(safety) => safety,
            Err(fell) => return Ok(fell),
        },
    };
    drop(step);
    let gathered = ranks.gather(&stats::rank(&ranks, &parts, &done));
    stats::add_timings(&mut timings, &parts, &done);
    let all = parts.all;
    let interface_solver = if parts.problem.is_some() { plan.kind.name() } else { "none" };
    // the factors go before the results are written
    drop(parts);
    let Some(rank_stats) = gathered else { return Ok(Attempt::Ran(None)) };
    let measured = stats::Measured {
        msh,
        mesh_cached,
        timings,
        counters: done.counters,
        residual_interface: done.residual_interface,
        ranks: rank_stats,
        interface_solver,
    };
    let stats = stats::stats(&model, &plan.parts, all, measured);
    let initial_stage = done.stage;
    let about = about::about(&scene, &model);
    let mut run = Run {
        scene,
        about,
        model,
        steps: done.steps,
        stats,
        checks: Checks::default(),
        safety,
        initial_stage,
        fallback: match this {
            Try::Fallback(record) => record,
            Try::Given { .. } => None,
        },
    };

    // 7. What the last step is checked against, then the output, all at once.
    let t = Instant::now();
    run.checks = checks(&run);
    run.stats.timings.recover += t.elapsed().as_secs_f64();
    write(run, opts, to, failed).map(|run| Attempt::Ran(Some(Box::new(run))))
}

/// The load steps, the safety search below one where they failed, and
/// what they failed with ([`safety::steps_or_below`]).
type Stepped = (steps::LoadSteps, Option<crate::results::SafetyRun>, Option<Error>);

/// The load steps of `step` and what they failed with
/// ([`safety::steps_or_below`]); or, where the scene's rigid joints
/// `may_fall` back and they ended a step unconverged or stopped at a state
/// set that holds nothing, the attempt that falls back (the run began at
/// `t0`).
fn steps_or_fall(
    step: &steps::Step,
    parts: &condense::Parts,
    opts: &RunOptions,
    ranks: &ranks::Ranks,
    may_fall: bool,
    t0: Instant,
) -> Result<std::result::Result<Stepped, Attempt>> {
    let (scene, model, comm) = (step.scene, step.model, ranks.comm());
    let done = match safety::steps_or_below(step, parts, opts, ranks) {
        Err(e) if may_fall => {
            let seconds = t0.elapsed().as_secs_f64();
            let Some((scene, record)) = fallback::fall_unheld(scene, model, &e, comm, seconds) else {
                return Err(e);
            };
            return Ok(Err(Attempt::Fell(Box::new(scene), record.map(Box::new), Some(Box::new(e)))));
        }
        done => done?,
    };
    if may_fall && done.2.is_none() {
        let seconds = t0.elapsed().as_secs_f64();
        if let Some((scene, record)) = fallback::fall(scene, model, &done.0.steps, comm, seconds) {
            return Ok(Err(Attempt::Fell(Box::new(scene), record.map(Box::new), None)));
        }
    }
    Ok(Ok(done))
}

/// The scene's safety search from where the load steps left `done`
/// ([`safety::run`]); or, where the scene's rigid joints `may_fall` back
/// and a trial decided nothing, even retried, the attempt that falls
/// back: the search stops there (the run began at `t0`).
fn safety_or_fall(
    step: &steps::Step,
    parts: &condense::Parts,
    opts: &RunOptions,
    ranks: &ranks::Ranks,
    done: &mut steps::LoadSteps,
    may_fall: bool,
    t0: Instant,
) -> Result<std::result::Result<Option<crate::results::SafetyRun>, Attempt>> {
    let on_undecided = if may_fall { OnUndecided::Stop } else { OnUndecided::PassOver };
    let safety = safety::run(step, parts, opts, ranks, done, on_undecided)?;
    if may_fall {
        let (scene, model, comm) = (step.scene, step.model, ranks.comm());
        let seconds = t0.elapsed().as_secs_f64();
        if let Some((scene, record)) = fallback::fall_undecided(scene, model, safety.as_ref(), comm, seconds) {
            return Ok(Err(Attempt::Fell(Box::new(scene), record.map(Box::new), None)));
        }
    }
    Ok(Ok(safety))
}

/// Errors against the scene's closed form (body by body, each in its own
/// material), the probes, the reactions and the section forces, on the
/// last load step (after an initial stage, from its total displacements;
/// the probes' displacements those of the loads alone).
fn checks(run: &Run) -> Checks {
    let (model, last) = (&run.model, run.last());
    let total = run.initial_stage.as_ref().map(|s| StepResult {
        u: s.total(&last.u),
        stresses: Vec::new(),
        case_factors: last.case_factors.clone(),
        contact: last.contact.clone(),
        ..*last
    });
    let (last, stage) = (total.as_ref().unwrap_or(last), run.initial_stage.as_ref());
    let exact = run.scene.analytic.as_ref().map(|a| analytic::exact(a, model));
    let errors = exact.as_ref().map(|e| recover::errors(model, &last.u, e));
    let contact_error_max = match (&exact, &last.contact) {
        (Some(e), Some(c)) => Some(contact_error(model, e, &c.pairs)),
        _ => None,
    };
    let probe = |p: &crate::scene::Probe| {
        let mut samples = recover::probe(model, &last.u, p);
        if let Some(stage) = stage {
            for (s, s0) in samples.iter_mut().zip(recover::probe(model, &stage.u, p)) {
                (0..3).for_each(|c| s.displacement[c] -= s0.displacement[c]);
            }
        }
        samples
    };
    let probes = run.scene.probes.iter().map(|p| (p.name.clone(), probe(p))).collect();
    let groups: Vec<String> = run.scene.bodies.iter().map(|b| b.group.clone()).collect();
    let reactions = (!model.supports.is_empty()).then(|| recover::reactions::reactions(model, last, &groups));
    let sections = recover::sections::section_forces(model, &last.u, &run.scene.sections);
    Checks { errors, contact_error_max, probes, analytic: Default::default(), reactions, sections }
}

/// Writes every result file of `run` to `out` at once (with the scene's
/// `[analytic]` check), or none with `skip_output`; then the run's error,
/// if any: `failed` (the load steps lost equilibrium, the scene is unsafe
/// as given), a safety factor that converged trials did not decide, or a
/// last step that did not converge.
fn write(mut run: Run, opts: &RunOptions, to: &mut Writing, failed: Option<Error>) -> Result<Run> {
    let (out, t0) = (to.out.as_path(), to.t0);
    if opts.skip_output {
        run.stats.timings.total = t0.elapsed().as_secs_f64();
        return match ended(&run, None, failed) {
            Some(e) => Err(e),
            None => Ok(run),
        };
    }
    progress(opts, &format!("writing results to {}", out.display()));
    let t = Instant::now();
    // what the scene's [analytic] compares beyond the error norms
    if let Some(a) = &run.scene.analytic {
        run.checks.analytic = analytic::check(a, &run.solution());
    }
    run.stats.timings.total = t0.elapsed().as_secs_f64();
    let derived = output::Derived::of(&run);
    let (staged, skipped) = output::stage(&run, &derived, out)?;
    for w in skipped {
        say(&format!("warning: {w}"));
    }
    run.stats.timings.output = t.elapsed().as_secs_f64();
    run.stats.timings.total = t0.elapsed().as_secs_f64();
    // the summary carries the final timings
    let staged = output::restage_summary(staged, &run, &derived)?;
    // one transaction: the files an earlier run of this scene wrote and
    // this one did not (more load steps, contacts, probes) go, nothing else
    let committed = match to.stage.take() {
        Some(stage) => stage.commit(staged, &mut |m| say(m)),
        None => staged.commit_with(&mut |m| say(m)),
    };
    committed.map_err(|source| Error::Results { out: out.to_path_buf(), source })?;
    match ended(&run, Some(out.to_path_buf()), failed) {
        Some(e) => Err(e),
        None => Ok(run),
    }
}

/// The error a run ends with once its results are written (to `results`):
/// `failed`, the safety search's, or a last step that did not converge.
fn ended(run: &Run, results: Option<PathBuf>, failed: Option<Error>) -> Option<Error> {
    let written = |e: SafetyError| match &results {
        Some(out) => e.written(out.clone()),
        None => e,
    };
    if let Some(e) = failed {
        return Some(match e {
            Error::Safety(s) => written(*s).into(),
            e => e,
        });
    }
    if let Some(e) = safety::undecided_error(run) {
        return Some(written(e).into());
    }
    not_converged(run, results).map(Into::into)
}

/// The error of a run whose last step did not converge; `results`: where
/// its results were written.
fn not_converged(run: &Run, results: Option<PathBuf>) -> Option<ContactError> {
    let c = run.contact().filter(|c| !c.summary.converged)?;
    Some(ContactError::NotConverged {
        step: At::named(&run.scene, run.last().step),
        iterations: c.summary.iterations,
        stop: c.summary.why_not(),
        slipping_back: output::slipping_back(c),
        rigid_joints: fallback::advised(run),
        fell_back: run.fallback.is_some(),
        cuts: c.summary.cuts,
        scaled: c.summary.scaled,
        rule: run.scene.solver.rule,
        results,
    })
}

/// Max |sigma_n - exact normal traction| over the pairs, relative to the
/// largest exact one; the closed form of the body of each pair's node k.
fn contact_error(model: &Model, exact: &[Box<dyn analytic::Exact>], pairs: &[PairResult]) -> f64 {
    let mut body_of = vec![0; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        body.cells.iter().flat_map(|c| &c.nodes).for_each(|&n| body_of[n] = b);
    }
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for (p, r) in model.pairs.iter().zip(pairs) {
        let s = exact[body_of[p.k]].stress(model.coords[p.k]);
        let n = p.normal;
        let t = [
            s[0] * n[0] + s[3] * n[1] + s[5] * n[2],
            s[3] * n[0] + s[1] * n[1] + s[4] * n[2],
            s[5] * n[0] + s[4] * n[1] + s[2] * n[2],
        ];
        let sn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        worst = worst.max((r.sigma_n - sn).abs());
        scale = scale.max(sn.abs());
    }
    worst / scale.max(f64::MIN_POSITIVE)
}
