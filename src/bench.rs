//! `subcontact bench`: run time against error. The scene is meshed at
//! successive refinements (its one `setnumber` parameter, or gmsh's
//! `-clscale`, divided by `ratio` per level) for each element order; each
//! mesh is solved with contact and, for the floor of one linear solve, bonded
//! (one sparse factorisation of the whole model). Writes `bench.csv`,
//! `bench.md` (table, fitted convergence rates) and `bench.svg` (error
//! against run time and against DOFs, log–log, one line per order).

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::driver::{self, RunOptions};
use crate::error::{Error, Result};
use crate::output::files::Staged;
use crate::output::plot::{self, Panel, Series};
use crate::recover::Sample;
use crate::results::Run;
use crate::scene::Scene;

/// What to run.
#[derive(Clone, Debug)]
pub struct BenchOptions {
    pub levels: usize,
    pub orders: Vec<usize>,
    /// Refinement ratio between levels (h is divided by it).
    pub ratio: f64,
    /// The parameter value of level 0 (default: the scene's).
    pub start: Option<f64>,
    /// Skip levels whose estimated DOF count exceeds this.
    pub max_dofs: usize,
    /// Also time the bonded monolithic solve of each mesh.
    pub monolithic: bool,
    pub out: Option<PathBuf>,
}

/// One row of bench.csv.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Row {
    pub order: usize,
    pub level: usize,
    pub h: f64,
    pub dofs: usize,
    pub interface_dofs: usize,
    pub iterations: usize,
    pub time_s: f64,
    pub time_mesh_s: f64,
    pub time_solve_s: f64,
    pub time_monolithic_s: f64,
    pub error_displacement_l2: f64,
    pub error_stress_l2: f64,
    pub error_contact_max: f64,
    pub time_assemble_s: f64,
    pub time_condense_s: f64,
    pub time_interface_s: f64,
    pub time_recover_s: f64,
    /// The probe samples of the run (for errors against the finest level
    /// when the scene has no closed form).
    #[serde(skip)]
    pub probes: Vec<Sample>,
}

pub const CSV_HEADER: &str = "order,level,h,dofs,interface_dofs,iterations,time_s,time_mesh_s,time_solve_s,error_displacement_l2,error_stress_l2,error_contact_max,time_monolithic_s,time_assemble_s,time_condense_s,time_interface_s,time_recover_s";

impl Row {
    pub fn csv(&self) -> String {
        format!(
            "{},{},{:.6e},{},{},{},{:.4},{:.4},{:.4},{:.6e},{:.6e},{:.6e},{:.4},{:.4},{:.4},{:.4},{:.4}",
            self.order,
            self.level,
            self.h,
            self.dofs,
            self.interface_dofs,
            self.iterations,
            self.time_s,
            self.time_mesh_s,
            self.time_solve_s,
            self.error_displacement_l2,
            self.error_stress_l2,
            self.error_contact_max,
            self.time_monolithic_s,
            self.time_assemble_s,
            self.time_condense_s,
            self.time_interface_s,
            self.time_recover_s
        )
    }
}

fn solve_time(run: &Run) -> f64 {
    let t = &run.stats.timings;
    t.assemble + t.condense + t.interface + t.recover
}

/// The refined copy of a scene at one order and level, and its h.
fn refined(base: &Scene, order: usize, level: usize, opts: &BenchOptions) -> (Scene, f64) {
    let mut s = base.clone();
    s.gmsh.order = order;
    let f = opts.ratio.powi(level as i32);
    // the parameter named lc, or the scene's only one
    let param = s.gmsh.setnumber.iter().position(|(k, _)| k == "lc").or((s.gmsh.setnumber.len() == 1).then_some(0));
    if let Some(i) = param {
        let v = &mut s.gmsh.setnumber[i].1;
        *v = opts.start.unwrap_or(*v) / f;
        let h = *v;
        return (s, h);
    }
    let c = opts.start.unwrap_or(s.gmsh.clscale.unwrap_or(1.0)) / f;
    s.gmsh.clscale = Some(c);
    (s, c)
}

/// Runs the study; `progress(done, total, message)` after each solve.
pub fn bench(
    scene_path: &std::path::Path,
    opts: &BenchOptions,
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<(Vec<Row>, PathBuf)> {
    let mut base = Scene::load(scene_path)?;
    // run time against error of the load steps: no safety search
    base.safety = None;
    if !matches!(base.mesh, crate::scene::MeshSource::Geo(_)) {
        return Err(Error::BenchNeedsGeo { scene: scene_path.to_path_buf() });
    }
    let out = opts.out.clone().unwrap_or_else(|| PathBuf::from("results").join(&base.name));
    let total = opts.orders.len() * opts.levels;
    let mut rows = Vec::new();
    let mut done = 0;
    for &order in &opts.orders {
        let mut last_dofs = 0usize;
        for level in 0..opts.levels {
            let dim = base.analysis.dim() as i32;
            if last_dofs > 0 && (last_dofs as f64) * opts.ratio.powi(dim) > 1.5 * opts.max_dofs as f64 {
                done += 1;
                progress(done, total, &format!("order {order} level {level}: skipped (over {} DOFs)", opts.max_dofs));
                continue;
            }
            let (scene, h) = refined(&base, order, level, opts);
            let dir = out.join("bench").join(format!("p{order}_l{level}"));
            let ro = RunOptions { out: Some(dir.clone()), skip_output: true, ..Default::default() };
            let run = driver::run_scene(scene.clone(), &ro)?;
            let mono = if opts.monolithic {
                let rb = driver::run_scene(scene, &RunOptions { bonded: true, ..ro.clone() })?;
                solve_time(&rb)
            } else {
                f64::NAN
            };
            let (e, t) = (run.checks.errors.as_ref(), &run.stats.timings);
            let row = Row {
                order,
                level,
                h,
                dofs: run.stats.dofs.total,
                interface_dofs: run.stats.dofs.interface,
                iterations: run.contact().map_or(0, |c| c.summary.iterations),
                time_s: t.total,
                time_mesh_s: t.mesh,
                time_solve_s: solve_time(&run),
                time_monolithic_s: mono,
                error_displacement_l2: e.map_or(f64::NAN, |e| e.displacement_l2),
                error_stress_l2: e.map_or(f64::NAN, |e| e.stress_l2),
                error_contact_max: run.checks.contact_error_max.unwrap_or(f64::NAN),
                time_assemble_s: t.assemble,
                time_condense_s: t.condense,
                time_interface_s: t.interface,
                time_recover_s: t.recover,
                probes: run.checks.probes.iter().flat_map(|(_, p)| p.iter().cloned()).collect(),
            };
            last_dofs = row.dofs;
            done += 1;
            progress(done, total, &format!("order {order} level {level}: {} DOFs, {} interface, {} iterations, {:.2} s (bonded {:.2} s), stress error {:.2e}", row.dofs, row.interface_dofs, row.iterations, row.time_s, row.time_monolithic_s, row.error_stress_l2));
            rows.push(row);
        }
    }
    if base.analytic.is_none() {
        against_reference(&mut rows);
    }
    Ok((rows, out))
}

/// Without a closed form: the errors of every level against the finest
/// level of the highest order (its own errors stay NaN), measured on the
/// scene's probes: relative L2 over the probe points of the displacement
/// and of the stress.
fn against_reference(rows: &mut [Row]) {
    let Some(best) = (0..rows.len()).max_by_key(|&i| (rows[i].order, rows[i].dofs)) else { return };
    let reference = rows[best].probes.clone();
    if reference.is_empty() {
        return;
    }
    for (i, row) in rows.iter_mut().enumerate() {
        if i == best || row.probes.len() != reference.len() {
            continue;
        }
        let rel = |f: &dyn Fn(&Sample) -> Vec<f64>| {
            let (mut num, mut den) = (0.0, 0.0);
            for (a, b) in row.probes.iter().zip(&reference).filter(|(a, b)| a.found && b.found) {
                for (x, y) in f(a).iter().zip(f(b)) {
                    num += (x - y) * (x - y);
                    den += y * y;
                }
            }
            (num / den.max(f64::MIN_POSITIVE)).sqrt()
        };
        row.error_displacement_l2 = rel(&|s| s.displacement.to_vec());
        row.error_stress_l2 = rel(&|s| s.stress.to_vec());
    }
}

/// Least-squares slope of log(y) against log(x) over finite positive points.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> =
        points.iter().filter(|q| q.0 > 0.0 && q.1 > 0.0 && q.1.is_finite()).map(|q| (q.0.ln(), q.1.ln())).collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
    let my = p.iter().map(|q| q.1).sum::<f64>() / n;
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    Some(sxy / sxx)
}

/// An error for the table: "–" where there is none (no closed form, or the
/// reference level itself; bench.csv keeps NaN).
fn error(e: f64) -> String {
    if e.is_nan() {
        "–".into()
    } else {
        format!("{e:.3e}")
    }
}

/// The Markdown table and the fitted rates.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from("| order | level | h | DOFs | interface DOFs | iterations | total (s) | mesh (s) | solve (s) | monolithic (s) | solve / monolithic | displacement error | stress error | contact error |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {:.4} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.2} | {} | {} | {} |",
            r.order,
            r.level,
            r.h,
            r.dofs,
            r.interface_dofs,
            r.iterations,
            r.time_s,
            r.time_mesh_s,
            r.time_solve_s,
            r.time_monolithic_s,
            r.time_solve_s / r.time_monolithic_s,
            error(r.error_displacement_l2),
            error(r.error_stress_l2),
            error(r.error_contact_max)
        );
    }
    s += "\nConvergence rates fitted on log(error) against log(h), all levels:\n\n| order | displacement | stress | contact |\n|---|---|---|---|\n";
    let mut orders: Vec<usize> = rows.iter().map(|r| r.order).collect();
    orders.dedup();
    for o in orders {
        let sel: Vec<&Row> = rows.iter().filter(|r| r.order == o).collect();
        let rate = |f: &dyn Fn(&Row) -> f64| {
            loglog_slope(&sel.iter().map(|r| (r.h, f(r))).collect::<Vec<_>>())
                .map_or("–".into(), |v| format!("{v:.2}"))
        };
        let _ = writeln!(
            s,
            "| {o} | {} | {} | {} |",
            rate(&|r| r.error_displacement_l2),
            rate(&|r| r.error_stress_l2),
            rate(&|r| r.error_contact_max)
        );
    }
    s
}

/// Writes bench.csv, bench.md and bench.svg.
pub fn write(rows: &[Row], out: &std::path::Path, title: &str) -> Result<Vec<PathBuf>> {
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    for r in rows {
        csv += &r.csv();
        csv.push('\n');
    }
    let mut orders: Vec<usize> = rows.iter().map(|r| r.order).collect();
    orders.dedup();
    let series = |x: &dyn Fn(&Row) -> f64| -> Vec<Series> {
        orders
            .iter()
            .map(|&o| Series {
                label: format!("order {o}"),
                points: rows.iter().filter(|r| r.order == o).map(|r| (x(r), r.error_stress_l2)).collect(),
            })
            .collect()
    };
    let by_time = series(&|r| r.time_s);
    let by_dofs = series(&|r| r.dofs as f64);
    let svg = plot::svg(
        &[
            Panel {
                title: "stress error against run time",
                x_label: "run time (s)",
                y_label: "relative L2 stress error",
                log_x: true,
                log_y: true,
                series: &by_time,
            },
            Panel {
                title: "stress error against DOFs",
                x_label: "DOFs",
                y_label: "relative L2 stress error",
                log_x: true,
                log_y: true,
                series: &by_dofs,
            },
        ],
        560,
        420,
    )
    .map_err(|source| Error::Drawing { file: "bench.svg", source })?;
    let note = if rows
        .iter()
        .any(|r| r.error_displacement_l2.is_nan() && r.order == rows.iter().map(|q| q.order).max().unwrap_or(0))
        && rows.iter().any(|r| r.error_displacement_l2.is_finite())
    {
        "Errors without a closed form: relative L2 of displacement and stress at the scene's probe points against the finest level of the highest order (the reference, whose own errors are left out).\n\n"
    } else {
        ""
    };
    let md = format!("# Benchmark: {title}\n\n![error against run time and DOFs](bench.svg)\n\n{note}{}", table(rows));
    let mut staged = Staged::new(out, "bench");
    staged.add("bench.csv", csv.into_bytes());
    staged.add("bench.md", md.into_bytes());
    staged.add("bench.svg", svg.into_bytes());
    Ok(staged.commit()?)
}
