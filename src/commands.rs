//! What each subcommand does, on top of the driver; the only place besides
//! `main` that prints to the terminal. A closed stdout or stderr (`solve
//! s.toml 2>&1 | head -1`) silences the lines, not the run: the results
//! are the data, and a reader that left is no reason to throw them away.

use std::path::Path;

/// `println!` that ignores a closed stdout (a pipe whose reader left).
macro_rules! outln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($t)*);
    }};
}

/// `eprintln!` that ignores a closed stderr.
macro_rules! errln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}

use crate::analytic::{self, paper_tables as paper};
use crate::driver::{self, RunOptions};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::parallel::Comm;
use crate::results::{state_counts, Run};
use crate::scene::Scene;

pub fn solve(scene: &Path, opts: &RunOptions, comm: &dyn Comm) -> Result<()> {
    solved(driver::run_on(Scene::load(scene)?, opts, comm)?, opts)
}

/// `solve` with a safety search, the scene's `[safety]` or the defaults.
pub fn safety(scene: &Path, opts: &RunOptions, comm: &dyn Comm) -> Result<()> {
    solved(driver::run_on(Scene::load(scene)?.with_safety()?, opts, comm)?, opts)
}

/// What a solved run says on the terminal (rank 0's; the others say nothing).
fn solved(run: Option<Run>, opts: &RunOptions) -> Result<()> {
    let Some(run) = run else {
        return Ok(()); // not rank 0: rank 0 reports
    };
    // say what happened: pairs that opened between the Coulomb apex and f_t
    if run.steps.iter().filter_map(|s| s.contact.as_ref()).any(|c| c.summary.apex_openings > 0) {
        warn(&run.scene.warnings());
    }
    if !run.scene.bonded {
        warn(&crate::driver::model_warnings(&run.scene, &run.model));
    }
    warn(&crate::driver::insitu_warnings(&run.scene, &run.model));
    print_summary(&run, &opts.out_dir(&run.scene));
    Ok(())
}

/// Warnings on stderr, one paragraph each.
fn warn(warnings: &[String]) {
    for w in warnings {
        errln!("warning: {w}");
    }
}

fn print_summary(run: &Run, out: &Path) {
    let st = &run.stats;
    outln!("{}: {} DOFs ({} interface), {:.2} s", run.scene.name, st.dofs.total, st.dofs.interface, st.timings.total);
    if let Some(c) = run.contact() {
        let k = state_counts(&c.states);
        outln!(
            "  contact: {} pairs, {} iteration(s), {} stick / {} slip / {} open",
            c.states.len(),
            c.summary.iterations,
            k[2],
            k[1],
            k[0]
        );
    }
    if let Some(f) = &run.fallback {
        outln!(
            "  joints that deform (normal / shear stiffness {} / {}): rigid joints did not converge in {} iteration(s)",
            f.stiffness.normal,
            f.stiffness.shear,
            f.iterations
        );
    }
    if let Some(e) = &run.checks.errors {
        outln!(
            "  error vs closed form: displacement {:.3e}, stress {:.3e} (relative L2)",
            e.displacement_l2,
            e.stress_l2
        );
    }
    if let Some(s) = &run.safety {
        print_safety(run, s);
    }
    outln!("  results in {}", out.display());
}

/// The factor of safety in a line saying what it is (strength reduction
/// with which strength, or a load factor; decided or only bracketed), the
/// mechanism, the factor with the other strength where it differs, and
/// warnings: a search that reached its bound, a headline the scene's
/// silence chose.
fn print_safety(run: &Run, s: &crate::results::SafetyRun) {
    let g = |v: f64| format!("{v:.6}").trim_end_matches('0').trim_end_matches('.').to_string();
    let what = crate::output::safety_label(run, s);
    let factor = s.factor.unwrap_or(0.0);
    match (s.fails_at, s.decided) {
        (Some(f), true) => outln!("  {what} F = {factor:.4} (holds at {}, fails at {})", g(factor), g(f)),
        (Some(f), false) => outln!(
            "  {what}: NOT DECIDED, between F = {} (holds) and {} (fails): trials between did not converge",
            g(factor),
            g(f)
        ),
        (None, true) => {
            outln!("  {what} F > {factor} (the search reached its bound)");
            warn(&[format!("{}: the safety search reached its bound safety.max_factor = {factor} and the scene still holds there: F is at least that. Raise max_factor in [safety] to find F", run.scene.path.display())]);
        }
        (None, false) => outln!("  {what}: NOT DECIDED, at least F = {} (holds): no trial above converged", g(factor)),
    }
    if let Some(m) = s.failure.as_ref().and_then(|f| f.mechanism.as_ref()) {
        outln!("  mechanism: {} ({})", crate::contact::mechanism::describe(&run.model, m), m.kind.key());
    }
    if let Some(o) = &s.other {
        if let Some(line) = crate::output::other_factor_line(run, s, o) {
            outln!("  {line}");
        }
    }
    warn(&crate::output::safety_warnings(run));
}

pub fn check(scene_path: &Path, allow_geo_commands: bool) -> Result<()> {
    let scene = Scene::load(scene_path)?;
    let out = Path::new("results").join(&scene.name);
    let (mesh, msh, _) = driver::load_mesh(&scene, &out, allow_geo_commands)?;
    let in_scene = |e: crate::Error| e.in_scene(&scene.path);
    let model = Model::build(&mesh, &scene.model_spec()).map_err(|e| in_scene(e.into()))?;
    // the plan solve would make; a run that would not fit in memory fails the check, before it says anything
    let driver::Preview { parts, memory } = driver::preview(&scene, &model, &RunOptions::default())?;
    let (need, dofs) = (memory.need, memory.dofs);
    let available = memory.fits.map_err(|e| in_scene(e.into()))?;
    outln!("{}: scene and mesh `{}` are consistent", scene_path.display(), msh.display());
    outln!(
        "  {} bodies, {} elements, {} model nodes, {} contact pairs, {} part(s)",
        model.bodies.len(),
        model.bodies.iter().map(|b| b.cells.len()).sum::<usize>(),
        model.n_nodes(),
        model.pairs.len(),
        parts
    );
    outln!(
        "  {} DOFs ({} interface); estimated peak memory {} of {} available",
        dofs.total,
        dofs.interface,
        crate::memory::human(need.total),
        crate::memory::human(available.bytes)
    );
    if let Some(cut) = scene.cut_job().and(crate::mesh::joints::read_report(&msh)) {
        let dim = scene.analysis.dim();
        outln!("  joints:");
        for line in crate::output::cut::summary(&cut, &scene.joints, dim) {
            outln!("    {line}");
        }
        warn(&crate::output::cut::warnings(&cut, dim));
    }
    warn(&scene.warnings());
    warn(&crate::driver::model_warnings(&scene, &model));
    warn(&crate::driver::insitu_warnings(&scene, &model));
    Ok(())
}

pub fn paper(fine: &Path, paper: &Path, verbose: bool) -> Result<()> {
    let opts = RunOptions { verbose, ..Default::default() };
    let run_paper = driver::run(paper, &opts)?;
    print_summary(&run_paper, &opts.out_dir(&run_paper.scene));
    let run_fine = driver::run(fine, &opts)?;
    let fine_out = opts.out_dir(&run_fine.scene);
    print_summary(&run_fine, &fine_out);
    let lame = run_paper.scene.analytic.as_ref().and_then(|a| analytic::lame(a, &run_paper.model));
    let (on_paper, on_fine) = (paper::tables(&run_paper.solution()), paper::tables(&run_fine.solution()));
    let runs = [("paper mesh (30 hex8)", &on_paper), ("default mesh", &on_fine)];
    let tables = lame.map(|l| crate::output::closed_form::paper_tables(&l, &runs, true)).unwrap_or_default();
    outln!("{tables}");
    // read and write report.md in one transaction on the directory
    let lock = crate::output::files::Lock::acquire(&fine_out, &mut |m| errln!("subcontact: {m}"))?;
    let path = fine_out.join("report.md");
    let mut text = std::fs::read_to_string(&path).map_err(|source| Error::Read { path: path.clone(), source })?;
    text += "\n# The paper's tables: theory, the paper, this tool on the paper's mesh and on the default mesh\n";
    text += &tables;
    let mut staged = crate::output::files::Staged::amend(&fine_out, &run_fine.scene.name);
    staged.add("report.md", text.into_bytes());
    staged.commit_locked(&lock).map_err(|source| Error::Write { path: path.clone(), source })?;
    outln!("tables written to {}", path.display());
    Ok(())
}

pub fn bench(scene: &Path, opts: &crate::bench::BenchOptions) -> Result<()> {
    use indicatif::{ProgressBar, ProgressStyle};
    if opts.orders.iter().any(|&o| o != 1 && o != 2) || opts.levels == 0 || !(opts.ratio > 1.0) {
        return Err(Error::BenchOptions);
    }
    let total = (opts.orders.len() * opts.levels) as u64;
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message("meshing and solving level 0");
    let (rows, out) = crate::bench::bench(scene, opts, &mut |done, _, msg| {
        bar.set_position(done as u64);
        bar.println(msg);
    })?;
    bar.finish_and_clear();
    let title = scene.display().to_string();
    let files = crate::bench::write(&rows, &out, &title)?;
    outln!("{}", crate::bench::table(&rows));
    for f in files {
        outln!("wrote {}", f.display());
    }
    Ok(())
}
