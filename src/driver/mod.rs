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

mod messages;
mod remote;
mod solve;

use crate::analytic;
use crate::contact::law::PairResult;
use crate::contact::InterfaceSolver;
use crate::mesh::{gmsh, msh, Mesh};
use crate::model::Model;
use crate::output;
use crate::parallel::{Comm, CommExt, Serial};
use crate::recover;
use crate::scene::{MeshSource, Scene};

// what a run returns, defined in `results` (which the writers read)
pub use crate::results::{state_counts, ContactRun, Counters, RankStats, Run, StepResult, Timings};

/// Options of a run beyond the scene.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    pub out: Option<PathBuf>,
    /// Pieces each part is cut into (overrides `[solver] substructures`).
    pub substructures: Option<usize>,
    /// Parts condensed at once on each rank (default: the cores per rank).
    pub threads: Option<usize>,
    /// How the interface is solved (overrides `[solver] interface`).
    pub interface: Option<InterfaceSolver>,
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

/// Runs a validated scene end to end on this one process and writes its results.
pub fn run_scene(scene: Scene, opts: &RunOptions) -> Result<Run> {
    Ok(run_on(scene, opts, &Serial)?.expect("one process is rank 0"))
}

/// The path of the mesh a scene reads (the gmsh output for a .geo).
fn mesh_path(scene: &Scene, out: &Path) -> PathBuf {
    match &scene.mesh {
        MeshSource::Msh(p) => p.clone(),
        MeshSource::Geo(_) => out.join("mesh").join(format!("{}.msh", scene.name)),
    }
}

/// Runs a validated scene on the ranks of `comm`: every rank builds the
/// model and condenses its parts; rank 0 meshes, iterates, recovers the
/// stresses, writes the results and gets the [`Run`] (the others `None`).
pub fn run_on(mut scene: Scene, opts: &RunOptions, comm: &dyn Comm) -> Result<Option<Run>> {
    let t0 = Instant::now();
    let mut timings = Timings::default();
    // sparse work is sequential: parts run side by side instead (threads, ranks)
    faer::set_global_parallelism(faer::Par::Seq);
    let root = comm.is_root();
    let opts = &RunOptions { verbose: opts.verbose && root, ..opts.clone() };

    // 1. Scene.
    if opts.bonded {
        scene.contacts.clear();
    }
    let out = opts.out.clone().unwrap_or_else(|| PathBuf::from("results").join(&scene.name));

    // 2. Mesh: rank 0 runs gmsh, then every rank reads the file.
    progress(opts, "meshing");
    let t = Instant::now();
    let meshed = if root { load_mesh(&scene, &out).map(Some) } else { Ok(None) };
    let meshed = solve::agree(comm, meshed)?;
    let (mesh, msh_path, mesh_cached) = match meshed {
        Some(m) => m,
        None => {
            let p = mesh_path(&scene, &out);
            (msh::read_msh(&p)?, p, true)
        }
    };
    timings.mesh = t.elapsed().as_secs_f64();

    // 3. Model.
    let t = Instant::now();
    let model = Model::build(&mesh, &scene.model_spec())?;
    drop(mesh);
    timings.model = t.elapsed().as_secs_f64();

    // 4.–6. Parts, condensation, contact iteration, recovery.
    let Some(solved) = solve::solve(&scene, &model, opts, comm, &mut timings)? else {
        return Ok(None);
    };
    let steps = solved.steps;
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
    timings.recover += t.elapsed().as_secs_f64();

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
        dofs_total: solved.dofs_total,
        dofs_interface: solved.dofs_interface,
        parts: solved.parts,
        condensed_parts: solved.condensed_parts,
        residual_interface: solved.residual_interface,
        residual_assembled: solved.residual_assembled,
        counters: solved.counters,
        ranks: solved.ranks,
        check: Default::default(),
    };

    // 7. Output, all at once.
    if opts.skip_output {
        run.timings.total = t0.elapsed().as_secs_f64();
        if let Some(c) = run.contact.as_ref().filter(|c| !c.converged) {
            bail!("{}: {}", run.scene.path.display(), not_converged(&run, c));
        }
        return Ok(Some(run));
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
    Ok(Some(run))
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

