//! The pipeline of one run, in the order data flows:
//!
//! 1. read and validate the scene;
//! 2. mesh the .geo with the gmsh CLI (cached) or read the .msh;
//! 3. build the model: bodies, loads, supports, contact pairs;
//! 4. assemble and factorise every part once, condensing it onto its
//!    contact interface (parts without contact are solved directly);
//! 5. iterate the contact states on the interface system;
//! 6. recover interior displacements and stresses, errors and probes;
//! 7. run the check the scene's `[analytic]` asks for, then write every
//!    result file at once (none when anything failed).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};

use crate::analytic;
use crate::contact::law::{PairResult, Strength};
use crate::contact::system::{InterfaceProblem, SolveFailure};
use crate::contact::traction::ConsistentTraction;
use crate::contact::{self, History, Outcome, PairLaw};
use crate::mesh::{gmsh, msh, Mesh};
use crate::model::Model;
use crate::output;
use crate::recover;
use crate::scene::{MeshSource, Scene, TractionRecovery};
use crate::substructure::{self, Condensed};

// what a run returns, defined in `results` (which the writers read)
pub use crate::results::{state_counts, ContactRun, Counters, Run, StepResult, Timings};

/// Options of a run beyond the scene.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    pub out: Option<PathBuf>,
    /// Treat every contact as bonded (shared nodes): the monolithic solve.
    pub bonded: bool,
    /// Print stage progress on stderr.
    pub verbose: bool,
    /// Compute everything but write no result files (benchmarks).
    pub skip_output: bool,
}

fn progress(opts: &RunOptions, msg: &str) {
    if opts.verbose {
        eprintln!("subcontact: {msg}");
    }
}

/// Reads the mesh of a scene, running gmsh when it is a .geo.
pub fn load_mesh(scene: &Scene, out: &Path) -> Result<(Mesh, PathBuf, bool)> {
    match &scene.mesh {
        MeshSource::Msh(p) => Ok((msh::read_msh(p)?, p.clone(), false)),
        MeshSource::Geo(geo) => {
            let msh_path = out.join("mesh").join(format!("{}.msh", scene.name));
            let job = gmsh::GmshJob {
                geo: geo.clone(),
                msh: msh_path.clone(),
                dim: scene.analysis.dim(),
                order: scene.gmsh.order,
                setnumber: scene.gmsh.setnumber.clone(),
                clscale: scene.gmsh.clscale,
            };
            let meshed = gmsh::mesh(&job)?;
            let mesh = msh::read_msh(&msh_path)?;
            Ok((mesh, msh_path, matches!(meshed, gmsh::Meshed::Cached)))
        }
    }
}

/// Runs a scene file end to end and writes its results.
pub fn run(scene_path: &Path, opts: &RunOptions) -> Result<Run> {
    run_scene(Scene::load(scene_path)?, opts)
}

/// Runs a validated scene end to end and writes its results.
pub fn run_scene(mut scene: Scene, opts: &RunOptions) -> Result<Run> {
    let t0 = Instant::now();
    let mut timings = Timings::default();
    // sparse work is sequential: rayon did not help on 2 cores (DESIGN.md §5)
    faer::set_global_parallelism(faer::Par::Seq);

    // 1. Scene.
    if opts.bonded {
        scene.contacts.clear();
    }
    let out = opts.out.clone().unwrap_or_else(|| PathBuf::from("results").join(&scene.name));

    // 2. Mesh.
    progress(opts, "meshing");
    let t = Instant::now();
    let (mesh, msh_path, mesh_cached) = load_mesh(&scene, &out)?;
    timings.mesh = t.elapsed().as_secs_f64();

    // 3. Model.
    let t = Instant::now();
    let model = Model::build(&mesh, &scene.model_spec())?;
    drop(mesh);
    let parts = substructure::parts(&model);
    let n_parts = parts.len();
    timings.model = t.elapsed().as_secs_f64();
    let t = Instant::now();

    // 4. Assemble, factorise, condense.
    progress(opts, &format!("assembling and factorising {} part(s)", n_parts));
    let mut condensed: Vec<Condensed> = Vec::with_capacity(n_parts);
    let mut assemble_s = 0.0;
    for part in parts {
        let c = substructure::condense(&model, part)?;
        assemble_s += c.assemble_s;
        condensed.push(c);
    }
    let condense_total = t.elapsed().as_secs_f64();
    timings.assemble = assemble_s;
    timings.condense = condense_total - assemble_s;
    let dofs_total: usize = condensed.iter().map(|c| c.ni + c.nc).sum();
    let dofs_interface: usize = condensed.iter().map(|c| c.nc).sum();
    let condensed_parts = condensed.iter().filter(|c| c.nc > 0).count();

    // 5.–6. Load steps: contact iteration on the interface system, then
    // recovery of the interior displacements and stresses.
    let n_steps = scene.solver.load_steps;
    // the interface, reduced to the pairs' relative displacements (timed
    // with the contact iteration)
    let t_problem = Instant::now();
    let problem = if model.pairs.is_empty() {
        None
    } else {
        progress(opts, &format!("contact iteration on {} pairs, {} load step(s)", model.pairs.len(), n_steps));
        Some(InterfaceProblem::new(&model, &condensed)?)
    };
    let laws: Vec<PairLaw> = model
        .pairs
        .iter()
        .map(|p| {
            let c = &scene.contacts[p.contact];
            PairLaw {
                strength: Strength {
                    friction: c.friction,
                    cohesion: c.cohesion,
                    tensile_strength: c.tensile_strength,
                    residual_cohesion: c.residual_cohesion,
                },
                slip: c.slip,
            }
        })
        .collect();
    let consistent = scene.contacts.iter().any(|c| c.traction == TractionRecovery::Consistent);
    let traction = if consistent {
        Some(ConsistentTraction::new(&model).map_err(|e| anyhow::anyhow!("{}: consistent contact traction: the interface mass matrix: {e}", scene.path.display()))?)
    } else {
        None
    };
    let mut hist = History::new(model.pairs.len());
    // skip what the scene does not ask for: interior displacements only for
    // fields, probes or errors; stresses only when asked
    let need_stress = scene.output.wants("stress");
    let need_u = need_stress || scene.output.wants("displacement") || !scene.probes.is_empty() || scene.analytic.is_some();
    let mut counters = Counters { factorisations: condensed.len(), condensed_parts: condensed.iter().filter(|c| c.nc > 0).count(), ..Default::default() };
    let residual_assembled = condensed.iter().map(|c| c.backward_error).fold(0.0, f64::max);
    let mut residual_interface: f64 = 0.0;
    let mut steps: Vec<StepResult> = Vec::with_capacity(n_steps);
    let (mut interface_s, mut recover_s) = (t_problem.elapsed().as_secs_f64(), 0.0);
    for step in 1..=n_steps {
        let lambda: Vec<f64> = model.cases.iter().map(|c| c[step - 1]).collect();
        let t = Instant::now();
        let mut d_c: Vec<Vec<f64>> = condensed.iter().map(|c| vec![0.0; c.nc]).collect();
        let mut contact_step = None;
        if let Some(problem) = &problem {
            let outcome = contact::iterate(problem, &laws, scene.solver.rule, &lambda, &mut hist, scene.solver.max_iterations);
            let Outcome { states, solution, iterations, converged, cycled, cycles_broken, apex_openings, history } = match outcome {
                Ok(o) => o,
                Err(f) => bail!(failure_message(&model, &condensed, &scene, step, f)),
            };
            residual_interface = residual_interface.max(solution.residual);
            counters.interface_solves += iterations;
            let mut pairs = solution.pairs;
            if let Some(tr) = &traction {
                let t = tr.recover(&solution.forces, &problem.basis);
                for (p, pr) in pairs.iter_mut().enumerate() {
                    if scene.contacts[model.pairs[p].contact].traction == TractionRecovery::Consistent {
                        pr.sigma_n = t[p][0];
                        pr.tau_t = t[p][1];
                        pr.tau_b = t[p][2];
                    }
                }
            }
            d_c = solution.d_c;
            let areas = (0..pairs.len()).map(|p| problem.area(p)).collect();
            contact_step = Some(ContactRun { states, pairs, frames: problem.frames.clone(), areas, apex_openings, iterations, converged, cycled, cycles_broken, history });
        }
        interface_s += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut u = vec![0.0; model.n_nodes() * model.nd];
        if need_u {
            for (c, d) in condensed.iter().zip(&d_c) {
                c.recover(&model, d, &lambda, &mut u);
            }
            counters.interior_recoveries += condensed.len();
        }
        let stresses = if need_stress {
            counters.stress_recoveries += 1;
            recover::nodal_stresses(&model, &u)
        } else {
            Vec::new()
        };
        recover_s += t.elapsed().as_secs_f64();
        let stop = contact_step.as_ref().is_some_and(|c| !c.converged);
        if opts.verbose && n_steps > 1 {
            progress(opts, &format!("load step {step}/{n_steps} done"));
        }
        steps.push(StepResult { step, load_factor: lambda[0], case_factors: lambda.clone(), u, stresses, contact: contact_step });
        if stop {
            break;
        }
    }
    drop(condensed);
    timings.interface = interface_s;
    let t = Instant::now();
    let last = steps.last().expect("at least one step");
    let u = last.u.clone();
    let stresses = last.stresses.clone();
    let contact_run = last.contact.clone();
    // the closed form body by body, each in its own material
    let exact = scene.analytic.as_ref().map(|a| analytic::exact(a, &model));
    let errors = exact.as_ref().map(|e| recover::errors(&model, &u, e));
    let contact_error_max = match (&exact, &contact_run) {
        (Some(e), Some(c)) => Some(contact_error(&model, e, &c.pairs)),
        _ => None,
    };
    let probes = scene.probes.iter().map(|p| (p.name.clone(), recover::probe(&model, &u, p))).collect();
    timings.recover = recover_s + t.elapsed().as_secs_f64();

    let mut run = Run {
        scene,
        out,
        msh: msh_path,
        mesh_cached,
        model,
        u,
        stresses,
        contact: contact_run,
        steps,
        errors,
        contact_error_max,
        probes,
        timings,
        dofs_total,
        dofs_interface,
        parts: n_parts,
        condensed_parts,
        residual_interface,
        residual_assembled,
        counters,
        check: Default::default(),
    };

    // 7. Output, all at once.
    if opts.skip_output {
        run.timings.total = t0.elapsed().as_secs_f64();
        if let Some(c) = run.contact.as_ref().filter(|c| !c.converged) {
            bail!("{}: {}", run.scene.path.display(), not_converged(&run, c));
        }
        return Ok(run);
    }
    progress(opts, &format!("writing results to {}", run.out.display()));
    let t = Instant::now();
    // what the scene's [analytic] compares beyond the error norms
    if let Some(a) = &run.scene.analytic {
        run.check = analytic::check(a, &run.solution());
    }
    run.timings.total = t0.elapsed().as_secs_f64();
    let staged = output::stage(&run)?;
    run.timings.output = t.elapsed().as_secs_f64();
    run.timings.total = t0.elapsed().as_secs_f64();
    // the summary carries the final timings
    let staged = output::restage_summary(staged, &run)?;
    let written = staged.commit().with_context(|| format!("writing results to {}", run.out.display()))?;
    // files an earlier run of this scene wrote that this one did not (more
    // load steps, contacts, probes) would mislead: remove them
    for old in output::stale(&run.out, &run.scene.name, &written) {
        let _ = std::fs::remove_file(old);
    }
    if let Some(c) = &run.contact {
        if !c.converged {
            bail!(
                "{}: {}; the results in {} are those of the last iteration (summary.json contact.converged = false, report.md lists the last two state sets). Try more [solver] max_iterations, more load steps, or the default rule = \"robust\"",
                run.scene.path.display(),
                not_converged(&run, c),
                run.out.display()
            );
        }
    }
    Ok(run)
}

/// "the contact iteration did not converge [at load step k] after n iteration(s) [(the states cycle)]".
fn not_converged(run: &Run, c: &ContactRun) -> String {
    let at = match run.steps.last() {
        Some(st) if run.scene.solver.load_steps > 1 => format!(" at load step {}", st.step),
        _ => String::new(),
    };
    format!(
        "the contact iteration did not converge{at} after {} iteration(s){}",
        c.iterations,
        if c.cycled { " (the states cycle)" } else { "" }
    )
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
        let t = [s[0] * n[0] + s[3] * n[1] + s[5] * n[2], s[3] * n[0] + s[1] * n[1] + s[4] * n[2], s[5] * n[0] + s[4] * n[1] + s[2] * n[2]];
        let sn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
        worst = worst.max((r.sigma_n - sn).abs());
        scale = scale.max(sn.abs());
    }
    worst / scale.max(f64::MIN_POSITIVE)
}

fn failure_message(model: &Model, parts: &[Condensed], scene: &Scene, step: usize, f: contact::Failed) -> String {
    let at = if scene.solver.load_steps > 1 { format!("load step {step}, ") } else { String::new() };
    let counts = state_counts(&f.states);
    match f.failure {
        SolveFailure::NotHeld(ids) => {
            let bodies: Vec<usize> = ids.iter().flat_map(|&i| parts[i].part.bodies.iter().copied()).collect();
            let one = bodies.len() == 1;
            format!(
                "{path}: {what} {names} {verb} held by nothing at {at}contact iteration {it} ({stick} stick, {slip} slip, {open} open): {its} contact pairs opened and no support holds {it_them}{apex}. Add a support, or check the loads that pull the contact apart",
                apex = apex_note(scene),
                path = scene.path.display(),
                at = at,
                what = if one { "body" } else { "bodies" },
                names = model.body_names(&bodies),
                verb = if one { "is" } else { "are" },
                it = f.iteration,
                stick = counts[2],
                slip = counts[1],
                open = counts[0],
                its = if one { "its" } else { "their" },
                it_them = if one { "it" } else { "them" },
            )
        }
        SolveFailure::Singular(ids) => {
            let bodies: Vec<usize> = ids.iter().flat_map(|&i| parts[i].part.bodies.iter().copied()).collect();
            format!(
                "{}: the interface system is singular at {at}contact iteration {} ({} stick, {} slip, {} open): {} slides or rotates freely on its contacts — loss of equilibrium: the load along the contact exceeds what friction and cohesion can carry. Reduce the load, or add a support that holds it tangentially, or friction",
                scene.path.display(),
                f.iteration,
                counts[2],
                counts[1],
                counts[0],
                if bodies.is_empty() { "a body".to_string() } else { format!("{} {}", if bodies.len() == 1 { "body" } else { "bodies" }, model.body_names(&bodies)) },
            )
        }
    }
}

/// Where a contact's f_t exceeds the Coulomb apex c / f, the robust rule
/// opens its pairs at c / f already: say so where they let a body go.
fn apex_note(scene: &Scene) -> String {
    let which: Vec<String> = scene
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| c.friction > 0.0 && c.tensile_strength > c.cohesion / c.friction)
        .map(|(i, c)| format!("contacts[{i}] opens at c / f = {} (its tensile_strength {} exceeds that Coulomb apex: no shear strength is left there)", c.cohesion / c.friction, c.tensile_strength))
        .collect();
    if which.is_empty() || scene.solver.rule != crate::contact::StateRule::Robust {
        String::new()
    } else {
        format!(" ({})", which.join("; "))
    }
}
