//! Result files of a run, staged in memory and written together:
//! `<name>.vtu` (bodies), `<name>_contact.vtu` (interfaces), `contact.csv`,
//! `faces.csv` (the resultants per block face pair, [`faces`]),
//! `bearing.csv` (the bearing pressure of every contact face, [`bearing`]),
//! `probes.csv` (and `probes_history.csv` over the load steps, with the
//! load–settlement picture `settlement.svg`, [`settlement`]),
//! `sections.csv` (with a picture per beam or ring,
//! [`sections`]), the pictures, the safety search's files (`safety.rs`),
//! then (once the output stage is timed) `summary.json` and `report.md`,
//! which embeds the pictures.

pub mod bearing;
pub mod blocks;
mod bodies_vtu;
pub mod closed_form;
mod contact_files;
mod csv;
pub mod cut;
mod derived;
pub mod faces;
pub mod files;
pub mod number;
pub mod picture;
pub mod plot;
pub mod reactions;
pub mod report;
pub mod resultants;
mod safety;
pub mod sections;
pub mod settlement;
mod unsettled;
pub mod vtu;
mod water;

pub use derived::Derived;
pub use safety::{label as safety_label, other_factor_line, warnings as safety_warnings};
pub use unsettled::slipping_back;

use serde_json::json;

use crate::error::{Error, Result};
use crate::fem::material::von_mises;
use crate::recover::Sample;
use crate::results::{state_counts, Run};
use bodies_vtu::bodies_vtu;
use contact_files::{contact_csv, contact_vtu};
use csv::csv_field;
use files::Staged;

/// Stages every result file of a run except `summary.json` and `report.md`
/// ([`restage_summary`] adds them with the final timings), for the
/// directory `out`; with a warning for each picture that could not be
/// drawn (left out: the other files are written).
pub fn stage(run: &Run, derived: &Derived, out: &std::path::Path) -> Result<(Staged, Vec<String>)> {
    finite(run)?;
    let last = run.last();
    // pictures a person would rather look at than read (embedded in
    // report.md), drawn beside the files (0.8 s of the 86k tunnel's 1.3)
    let snap = picture::Snapshot {
        title: &run.about.title,
        model: &run.model,
        u: &last.u,
        stresses: &last.stresses,
        contact: last.contact.as_ref(),
        region: run.about.output.frame.as_ref(),
        one_scale: run.about.output.colour_scale == crate::results::about::ColourScale::One,
    };
    let (staged, mut drawn) = std::thread::scope(|scope| {
        let pictures = scope.spawn(|| picture::pictures(&snap));
        let staged = stage_files(run, derived, out);
        (staged, pictures.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
    });
    let mut staged = staged?;
    if !run.checks.probes.is_empty() {
        staged.add("probes.csv", probes_csv(&run.checks.probes).into_bytes());
        if run.steps.len() > 1 {
            let history = settlement::history(run);
            staged.add("probes_history.csv", probes_history_csv(&history).into_bytes());
            drawn.draw(settlement::FILE, || settlement::svg(run, &history));
        }
    }
    sections::pictures(run, &mut drawn);
    if let Some(f) = picture::stereonet_file(&run.about.joints) {
        drawn.draw(f, || picture::stereonet_png(&run.about.title, &run.about.joints));
    }
    safety::stage(run, &mut staged, &mut drawn)?;
    for (file, bytes) in drawn.files {
        staged.add(&file, bytes);
    }
    Ok((staged, drawn.skipped))
}

/// The result files of [`stage`] but its pictures: the blocks, the bodies'
/// and contacts' fields, the faces, the bearing, the load steps, sections.
fn stage_files(run: &Run, derived: &Derived, out: &std::path::Path) -> Result<Staged> {
    let mut staged = Staged::new(out, &run.about.name);
    let name = &run.about.name;
    let model = &run.model;
    let last = run.last();
    let displacement = run.about.output.wants("displacement");
    // the blocks: what each does, and its state as a cell field
    let blocks = derived.blocks();
    let states: Vec<i32> = blocks.into_iter().flatten().map(|b| b.state.code()).collect();
    if let Some(b) = blocks {
        staged.add("blocks.csv", blocks::blocks_csv(model, b).into_bytes());
    }
    if let Some(b) = blocks::at_safety(run) {
        staged.add("safety_blocks.csv", blocks::blocks_csv(model, &b).into_bytes());
    }
    staged.add(&format!("{name}.vtu"), bodies_vtu(model, &last.u, &last.stresses, displacement, &states)?);
    if let Some(c) = &last.contact {
        staged.add(&format!("{name}_contact.vtu"), contact_vtu(model, c)?);
        staged.add("contact.csv", contact_csv(model, c).into_bytes());
    }
    if let Some(r) = derived.resultants() {
        staged.add("faces.csv", faces::faces_csv(model, r).into_bytes());
    }
    if let Some(b) = derived.bearing() {
        staged.add("bearing.csv", bearing::csv(run, b).into_bytes());
    }
    if run.steps.len() > 1 {
        stage_steps(run, &mut staged, displacement)?;
    }
    if let Some(csv) = sections::csv(run) {
        staged.add("sections.csv", csv.into_bytes());
    }
    Ok(staged)
}

/// One file per load step and ParaView collections over them, the time of
/// a step its load factor (a run of several steps).
fn stage_steps(run: &Run, staged: &mut Staged, displacement: bool) -> Result<()> {
    let (name, model) = (&run.about.name, &run.model);
    let mut bodies = Vec::new();
    let mut contacts = Vec::new();
    let times = &run.about.step_times;
    for st in &run.steps {
        let time = times.get(st.step.wrapping_sub(1)).copied().unwrap_or(st.step as f64);
        let f = format!("{name}_step{:03}.vtu", st.step);
        staged.add(&f, bodies_vtu(model, &st.u, &st.stresses, displacement, &[])?);
        bodies.push((time, f));
        if let Some(c) = &st.contact {
            let f = format!("{name}_contact_step{:03}.vtu", st.step);
            staged.add(&f, contact_vtu(model, c)?);
            contacts.push((time, f));
        }
    }
    staged.add(&format!("{name}.pvd"), vtu::pvd_bytes(&bodies));
    if !contacts.is_empty() {
        staged.add(&format!("{name}_contact.pvd"), vtu::pvd_bytes(&contacts));
    }
    Ok(())
}

/// Results that are not numbers (an overflow: a traction of -1e300 gives
/// a von Mises stress of inf) are an error, not files full of `inf` and
/// `null`: the first one found, by step, names what and where.
fn finite(run: &Run) -> Result<()> {
    let model = &run.model;
    let nd = model.nd;
    for st in &run.steps {
        let bad = if let Some(i) = st.u.iter().position(|v| !v.is_finite()) {
            Some(format!("the displacement at node {} is {}", i / nd, st.u[i]))
        } else if let Some((b, s)) = st
            .stresses
            .iter()
            .enumerate()
            .find_map(|(b, bs)| bs.stress.iter().find(|s| !von_mises(s).is_finite()).map(|s| (b, s)))
        {
            Some(format!("the stress in body {} is {s:?} (von Mises {})", model.bodies[b].label(), von_mises(s)))
        } else {
            st.contact.as_ref().and_then(|c| {
                c.pairs
                    .iter()
                    .position(|p| ![p.sigma_n, p.tau_t, p.tau_b, p.gap, p.slip].iter().all(|v| v.is_finite()))
                    .map(|p| format!("contact pair {p}'s values are {:?}", c.pairs[p]))
            })
        };
        if let Some(what) = bad {
            return Err(Error::NotFinite { step: st.step, what });
        }
    }
    Ok(())
}

/// Adds `summary.json` and `report.md`, both with the run's final timings
/// (the output stage's own included), so that the two files agree.
pub fn restage_summary(mut staged: Staged, run: &Run, derived: &Derived) -> Result<Staged> {
    staged.add("summary.json", serde_json::to_vec_pretty(&summary(run, derived))?);
    staged.add("report.md", report::report(run, derived).into_bytes());
    Ok(staged)
}

const PROBE_COLUMNS: &str = "probe,point,x,y,z,ux,uy,uz,sxx,syy,szz,sxy,syz,sxz,von_mises,found\n";

/// One row per probe point.
pub(crate) fn probes_csv(probes: &[(String, Vec<Sample>)]) -> String {
    let mut s = String::from(PROBE_COLUMNS);
    probe_rows(&mut s, "", probes);
    s
}

/// `probes_history.csv` (probes and more than one load step): the rows of
/// probes.csv at every step, after the step and its load factor; a
/// load–settlement curve is a point's uy (3D uz) against `load_factor`.
pub(crate) fn probes_history_csv(history: &settlement::History) -> String {
    let mut s = format!("step,load_factor,{PROBE_COLUMNS}");
    for (step, factor, probes) in history {
        probe_rows(&mut s, &format!("{step},{factor:.12e},"), probes);
    }
    s
}

fn probe_rows(s: &mut String, prefix: &str, probes: &[(String, Vec<Sample>)]) {
    for (name, samples) in probes {
        for (i, p) in samples.iter().enumerate() {
            let vals: Vec<String> =
                p.x.iter()
                    .chain(&p.displacement)
                    .chain(&p.stress)
                    .chain(std::iter::once(&p.von_mises))
                    .map(|v| format!("{v:.12e}"))
                    .collect();
            *s += &format!("{prefix}{},{i},{},{}\n", csv_field(name), vals.join(","), p.found);
        }
    }
}

/// summary.json's `steps`: each load step's factors and contact iteration.
fn steps_summary(run: &Run) -> serde_json::Value {
    json!(run
        .steps
        .iter()
        .map(|st| {
            let mut j = json!({ "step": st.step, "ramp": st.load_factor, "case_factors": st.case_factors });
            if let Some(c) = &st.contact {
                j["contact"] = step_json(c);
            }
            j
        })
        .collect::<Vec<_>>())
}

/// How one step's state iteration went: summary.json's `steps[k].contact`,
/// and the part of its `contact` that is the last step's.
fn step_json(c: &crate::results::ContactRun) -> serde_json::Value {
    let it = &c.summary;
    json!({
        "iterations": it.iterations,
        "tight_resolves": it.tight_resolves,
        "augmented": it.augmented.map(|r| json!({
            "rounds": r.rounds, "iterations": r.iterations, "closed": r.closed(), "stretch": r.stretch
        })),
        "converged": it.converged,
        "cycled": it.cycled(),
        "states": states_json(&c.states),
        "cuts": it.cuts,
        "pieces": it.pieces,
        "scaled": it.scaled,
        "locked_friction_off": locked_off(c),
    })
}

/// summary.json's `contact`: how the last step's state iteration went,
/// [`step_json`] and more (the rest of it is added by [`summary`]).
fn contact_json(c: &crate::results::ContactRun) -> serde_json::Value {
    let it = &c.summary;
    let mut v = step_json(c);
    v["pairs"] = json!(c.states.len());
    v["cycles_broken"] = json!(it.cycles_broken);
    v["clusters_solved"] = json!(it.clusters_solved);
    v["unsettled_pairs"] = json!(unsettled::changes(c).map(|k| k.iter().filter(|&&n| n > 0).count()));
    v["law_residual"] =
        json!(c.worst_law_residual().map(|(p, r)| json!({ "pair": p, "relative": r, "stress": c.law_residual[p] })));
    v["history"] = json!(it.history.iter().map(|h| states_json(h)).collect::<Vec<_>>());
    v
}

/// A state set's counts: `{ "stick", "slip", "open" }`.
fn states_json(states: &[crate::contact::law::ContactState]) -> serde_json::Value {
    let k = state_counts(states);
    json!({ "stick": k[2], "slip": k[1], "open": k[0] })
}

/// The crossings whose locked friction is off the equilibrium solved
/// (`ContactRun::locked_off`): how many, and the worst one's pairs and
/// force (absolute, and of the largest pair force); null where none is.
fn locked_off(c: &crate::results::ContactRun) -> serde_json::Value {
    json!(c.worst_locked_off().map(|(pairs, f, r)| json!({
        "crossings": c.locked_off.len(), "pairs": pairs, "force": f, "relative": r })))
}

/// summary.json's `contact.rigid_fallback`: what the rigid joints did
/// and the stiffness the run gave them instead; null where it did not
/// fall back.
fn fallback_json(run: &Run) -> serde_json::Value {
    let Some(f) = &run.fallback else { return serde_json::Value::Null };
    json!({
        "step": f.step,
        "iterations": f.iterations,
        "cuts": f.cuts,
        "scaled": f.scaled,
        "cycled": f.stop.cycled(),
        "law_broken": f.stop.law_broken(),
        "law_residual": f.law_residual,
        "unheld": f.unheld,
        "augmented": f.rounds.map(|[rounds, iterations]| json!({ "rounds": rounds, "iterations": iterations })),
        "safety": f.safety.map(|(holds, trial)| json!({ "holds": holds, "undecided": trial.factor })),
        "held": f.held,
        "seconds": f.seconds,
        "normal_stiffness": f.stiffness.normal,
        "shear_stiffness": f.stiffness.shear,
        "modulus": f.modulus,
        "block_size": f.block_size,
    })
}

/// The initial equilibrium stage in summary.json: its iteration, the
/// strength factors it was brought down through, states, factors and
/// largest displacement (taken off every step's).
fn initial_stage(run: &Run, s: &crate::results::InitialStage) -> serde_json::Value {
    json!({
        "iterations": s.iterations,
        "converged": s.converged,
        "cuts": s.cuts,
        "strength_ramp": s.strength_ramp,
        "states": { "stick": s.states[2], "slip": s.states[1], "open": s.states[0] },
        "case_factors": s.case_factors,
        "largest_displacement": s.largest,
        "largest_at": run.model.coords.get(s.largest_at),
    })
}

fn summary(run: &Run, derived: &Derived) -> serde_json::Value {
    let st = &run.stats;
    let mut v = json!({
        "scene": run.about.path.display().to_string(),
        "title": run.about.title,
        "analysis": run.about.analysis.as_str(),
        "mesh": { "file": st.msh.display().to_string(), "cached": st.mesh_cached, "nodes": run.model.n_nodes(),
                  "elements": run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>() },
        "bodies": run.model.bodies.iter().map(|b| b.name.clone()).collect::<Vec<_>>(),
        "dofs": st.dofs,
        "interface_solver": st.interface_solver,
        "parts": st.parts,
        "timings_s": st.timings,
        "residuals": st.residuals,
        "counters": st.counters,
        "ranks": st.ranks,
        "fields": run.about.output.fields,
        "warnings": run.about.warnings,
    });
    if let Some(c) = run.contact() {
        v["contact"] = contact_json(c);
        v["contact"]["joint_stiffness"] = faces::stiffness_json(run);
        v["contact"]["rigid_fallback"] = fallback_json(run);
        if let Some(r) = derived.resultants() {
            let (groups, faces) = faces::summary(&run.model, r);
            v["contact"]["groups"] = groups;
            v["contact"]["faces"] = faces;
        }
        if let Some(b) = derived.blocks() {
            v["blocks"] = blocks::summary(&run.model, b);
        }
        if let Some(b) = derived.bearing() {
            v["bearing"] = bearing::summary(run, b);
        }
    }
    v["steps"] = steps_summary(run);
    if let Some(s) = &run.initial_stage {
        v["initial_stage"] = initial_stage(run, s);
    }
    let checks = &run.checks;
    if let Some(e) = &checks.errors {
        v["errors"] = json!({ "displacement_l2": e.displacement_l2, "stress_l2": e.stress_l2, "contact_max": checks.contact_error_max });
    }
    for (key, value) in closed_form::summary(&checks.analytic) {
        v[key] = value;
    }
    let probes: serde_json::Map<String, serde_json::Value> =
        checks.probes.iter().map(|(name, s)| (name.clone(), serde_json::to_value(s).unwrap_or_default())).collect();
    v["probes"] = serde_json::Value::Object(probes);
    if let Some(s) = safety::summary(run) {
        v["safety"] = s;
    }
    if let Some(w) = water::summary(run) {
        v["water"] = w;
    }
    if let Some(r) = reactions::summary(run) {
        v["reactions"] = r;
    }
    if let Some(s) = sections::summary(run) {
        v["sections"] = s;
    }
    v
}

#[cfg(test)]
mod csv_tests {
    use super::*;

    /// A probe named with a comma or a line break broke probes.csv (issue 32).
    #[test]
    fn names_with_commas_quotes_and_line_breaks_are_quoted() {
        let sample =
            Sample { x: [1.0, 2.0, 0.0], displacement: [0.0; 3], stress: [0.0; 6], von_mises: 0.0, found: true };
        let csv = probes_csv(&[("crown, \"left\"\nside".into(), vec![sample])]);
        let row = csv.lines().skip(1).collect::<Vec<_>>().join("\n");
        assert!(row.starts_with("\"crown, \"\"left\"\"\nside\",0,1.0"), "{csv}");
        // 16 columns once the quoted field is read as one
        let unquoted = row.replacen("\"crown, \"\"left\"\"\nside\"", "x", 1);
        assert_eq!(unquoted.split(',').count(), 16, "{csv}");
        assert_eq!(csv_field(" padded"), "\" padded\"");
        assert_eq!(csv_field("plain"), "plain");
    }
}
