//! The results of a safety search ([`SafetyRun`]), beside the run's own:
//!
//! - `safety.csv`: one row per trial (factor, the factor it started from,
//!   whether it held, contact iterations, states, seconds, why it failed);
//! - the last converged state at F: `<name>_safety.vtu`,
//!   `<name>_safety_contact.vtu` and `safety_contact.csv` (the columns of
//!   the run's own), and its pictures with the prefix `safety_`: the model
//!   deformed by the displacement since F = 1 (the mechanism as it starts),
//!   the contact stresses along each interface, and in 3D the plan of every
//!   joint by state with the slip directions;
//! - `summary.json`'s `safety` object and report.md's section, which set
//!   the search's F beside each reduced contact's own limit equilibrium
//!   from its resultants, `F_joint = (c A + N f) / T` (N the normal force,
//!   T the magnitude of the summed shear force, A the closed area, c and f
//!   the scene's): the hand check of a joint that slides as one plane.

use std::fmt::Write;

use anyhow::Result;
use serde_json::{json, Value};

use super::files::Staged;
use super::picture::{self, Snapshot};
use crate::contact::law::ContactState;
use crate::results::{state_counts, ContactRun, Run, SafetyRun};
use crate::scene::Safety;

/// The safety search's files, when the run made one.
pub(super) fn stage(run: &Run, staged: &mut Staged, drawn: &mut picture::Drawn) -> Result<()> {
    let Some(s) = &run.safety else { return Ok(()) };
    let (model, name) = (&run.model, &run.scene.name);
    staged.add("safety.csv", trials_csv(s).into_bytes());
    staged.add(
        &format!("{name}_safety.vtu"),
        super::bodies_vtu(model, &s.last.u, &s.last.stresses, run.scene.output.wants("displacement"))?,
    );
    if let Some(c) = &s.last.contact {
        staged.add(&format!("{name}_safety_contact.vtu"), super::contact_vtu(model, c)?);
        staged.add("safety_contact.csv", super::contact_csv(model, c).into_bytes());
    }
    // the mechanism: the model deformed and coloured by the displacement since F = 1
    let title =
        format!("{}: F = {}, the last state that holds; displacement since F = 1", run.scene.title, fmt_f(s.factor));
    let snap = Snapshot {
        title: &title,
        model,
        u: &s.du,
        stresses: &[],
        contact: s.last.contact.as_ref(),
        region: run.scene.output.frame.as_ref(),
    };
    drawn.draw(&format!("safety_{}", picture::deformed_file(&[])), || {
        picture::deformed_png(&snap, picture::Field::Displacement, None)
    });
    // the joints at F: along each interface, and in 3D in plan by state
    let Some(c) = &s.last.contact else { return Ok(()) };
    let title = format!("{}: F = {}, the last state that holds", run.scene.title, fmt_f(s.factor));
    drawn.draw("safety_interfaces.svg", || Ok(picture::interface_plot_svg(model, c)?.into_bytes()));
    let plans = drawn.plans(model);
    for p in &plans {
        drawn.draw(&format!("safety_{}", p.file), || picture::plan_png(&title, model, c, p));
    }
    if let Some(f) = picture::joints_file(&plans) {
        drawn.draw(&format!("safety_{f}"), || picture::joints_png(&title, model, c, &plans));
    }
    Ok(())
}

/// One row per trial.
fn trials_csv(s: &SafetyRun) -> String {
    let mut out = String::from("trial,factor,from,holds,iterations,stick,slip,open,seconds,failure\n");
    for (i, t) in s.trials.iter().enumerate() {
        let k = t.states;
        let _ = writeln!(
            out,
            "{},{:.9},{:.9},{},{},{},{},{},{:.6},{}",
            i + 1,
            t.factor,
            t.from,
            t.holds,
            t.iterations,
            k[2],
            k[1],
            k[0],
            t.seconds,
            t.failed.map_or("", |f| f.key())
        );
    }
    out
}

/// A reduced contact's resultants in one state: normal force N
/// (compression positive), the magnitude T of its summed shear force, its
/// closed area and its pairs' states.
struct Joint {
    normal: f64,
    shear: f64,
    area: f64,
    states: [usize; 3],
}

impl Joint {
    fn of(run: &Run, c: &ContactRun, contact: usize) -> Joint {
        let (mut normal, mut shear, mut area, mut states) = (0.0, [0.0; 3], 0.0, Vec::new());
        for (p, _) in run.model.pairs.iter().enumerate().filter(|(_, q)| q.contact == contact) {
            states.push(c.states[p]);
            if c.states[p] == ContactState::Open {
                continue;
            }
            normal -= c.pairs[p].sigma_n * c.areas[p];
            let t = c.shear(p);
            (0..3).for_each(|i| shear[i] += t[i] * c.areas[p]);
            area += c.areas[p];
        }
        Joint { normal, shear: shear.iter().map(|x| x * x).sum::<f64>().sqrt(), area, states: state_counts(&states) }
    }

    /// `(c A + N f) / T` with the scene's c and f (infinite without shear).
    fn factor(&self, cohesion: f64, friction: f64) -> f64 {
        (cohesion * self.area + self.normal.max(0.0) * friction) / self.shear
    }
}

/// `summary.json`'s `safety` object.
pub(super) fn summary(run: &Run) -> Option<Value> {
    let (s, o) = (run.safety.as_ref()?, run.scene.safety.as_ref()?);
    let model = &run.model;
    let failure = s.failure.as_ref().map(|f| {
        json!({ "kind": f.kind.key(), "iteration": f.iteration, "blocks": blocks(run, &f.blocks), "contacts": o.contacts.iter().map(|&i| {
            let k = state_counts(&model.pairs.iter().zip(&f.states).filter(|(p, _)| p.contact == i).map(|(_, &st)| st).collect::<Vec<_>>());
            json!({ "contact": model.interfaces[i].name, "stick": k[2], "slip": k[1], "open": k[0] })
        }).collect::<Vec<_>>() })
    });
    let joints: Vec<Value> = o.contacts.iter().map(|&i| {
        let sc = &run.scene.contacts[i];
        let at = |c: Option<&ContactRun>| c.map(|c| {
            let j = Joint::of(run, c, i);
            json!({ "normal_force": j.normal, "shear_force": j.shear, "closed_area": j.area, "factor_from_resultants": finite(j.factor(sc.cohesion, sc.friction)),
                    "states": { "stick": j.states[2], "slip": j.states[1], "open": j.states[0] } })
        });
        json!({ "contact": model.interfaces[i].name, "friction": sc.friction, "cohesion": sc.cohesion, "at_1": at(run.contact()), "at_factor": at(s.last.contact.as_ref()) })
    }).collect();
    Some(json!({
        "factor": s.factor,
        "fails_at": s.fails_at,
        "found": s.fails_at.is_some(),
        "bound_reached": s.fails_at.is_none(),
        "reduced": o.reduce.names(),
        "contacts": o.contacts.iter().map(|&i| model.interfaces[i].name.clone()).collect::<Vec<_>>(),
        "step": o.step, "tolerance": o.tolerance, "max_factor": o.max_factor,
        "failure": failure,
        "joints": joints,
        "trials": s.trials.iter().map(|t| json!({ "factor": t.factor, "from": t.from, "holds": t.holds, "iterations": t.iterations,
            "states": { "stick": t.states[2], "slip": t.states[1], "open": t.states[0] }, "seconds": t.seconds, "failure": t.failed.map(|f| f.key()) })).collect::<Vec<_>>(),
        "cost": s.cost,
        "cost_per_trial": { "contact_iterations": s.cost.contact_iterations as f64 / s.cost.trials.max(1) as f64, "seconds": s.cost.search_s / s.cost.trials.max(1) as f64 },
    }))
}

/// The blocks for summary.json: body group, block (1-based) of how many.
fn blocks(run: &Run, ids: &[usize]) -> Vec<Value> {
    ids.iter().map(|&b| {
        let body = &run.model.bodies[b];
        json!({ "body": body.name, "block": body.block.map(|k| k.index + 1), "of": body.block.map(|k| k.of), "centre": body.block.map(|k| k.centre) })
    }).collect()
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// A factor as the report writes it: four decimals, trailing zeros kept short.
fn fmt_f(v: f64) -> String {
    let t = format!("{v:.4}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A factor of the bracket: six decimals, trailing zeros dropped.
fn fmt_g(v: f64) -> String {
    let t = format!("{v:.6}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// report.md's section (empty without a search).
pub fn report(run: &Run) -> String {
    let (Some(s), Some(o)) = (&run.safety, &run.scene.safety) else { return String::new() };
    let mut r = String::from("\n## Factor of safety against sliding\n\n");
    let what = format!("{} divided by F on {}", o.reduce.names().join(", "), contacts(run, o));
    match (s.fails_at, &s.failure) {
        (Some(f), Some(fail)) => {
            let _ = writeln!(r, "**F = {}** by strength reduction ({what}), from the state of the last load step: it holds at F = {} and fails at F = {} (tolerance {} × F).\n", fmt_f(s.factor), fmt_g(s.factor), fmt_g(f), o.tolerance);
            let who = if fail.blocks.is_empty() {
                "the solver named no block".to_string()
            } else {
                run.model.body_names(&fail.blocks)
            };
            let _ = writeln!(
                r,
                "At F = {} (contact iteration {}): {}: {who}.\n",
                fmt_g(f),
                fail.iteration,
                fail.kind.describe()
            );
        }
        _ => {
            let _ = writeln!(r, "**F > {}**: the search reached its bound (safety.max_factor = {}) and the scene still holds there ({what}). Raise max_factor to find F.\n", fmt_f(s.factor), o.max_factor);
        }
    }
    joints_table(&mut r, run, s, o);
    let c = &s.cost;
    let per = |x: f64| x / c.trials.max(1) as f64;
    let _ = writeln!(
        r,
        "\nThe search: {} trials, {} contact iterations ({:.1} per trial), {:.3} s on the condensed interface ({:.4} s per trial), {:.3} s to recover the last state that holds; sparse factorisations: {} for the whole run (one per part), none in the search.\n",
        c.trials, c.contact_iterations, per(c.contact_iterations as f64), c.search_s, per(c.search_s), c.recover_s, run.stats.counters.factorisations
    );
    let _ = writeln!(
        r,
        "| trial | F | from F | holds | contact iterations | stick / slip / open |\n|---|---|---|---|---|---|"
    );
    for (i, t) in s.trials.iter().enumerate() {
        let k = t.states;
        let _ = writeln!(
            r,
            "| {} | {} | {} | {} | {} | {} / {} / {} |",
            i + 1,
            fmt_f(t.factor),
            fmt_f(t.from),
            if t.holds { "yes" } else { t.failed.map_or("no", |f| f.key()) },
            t.iterations,
            k[2],
            k[1],
            k[0]
        );
    }
    pictures(&mut r, run, s);
    r
}

/// The chosen contacts: "all contacts" or their names.
fn contacts(run: &Run, o: &Safety) -> String {
    let names: Vec<String> = o.contacts.iter().map(|&i| format!("`{}`", run.model.interfaces[i].name)).collect();
    if o.contacts.len() == run.scene.contacts.len() {
        format!("all contacts ({})", names.join(", "))
    } else {
        names.join(", ")
    }
}

/// Each reduced contact at F = 1, at F and at failure, with its own limit
/// equilibrium from its resultants.
fn joints_table(r: &mut String, run: &Run, s: &SafetyRun, o: &Safety) {
    let _ = writeln!(r, "Each reduced contact: its pairs stick / slip / open at F = 1, at F and at failure; its normal force N and shear force T at F = 1, and its own limit equilibrium from them, F_joint = (c A + N f) / T (A its closed area; the factor of a joint that slides as one plane).\n");
    let _ = writeln!(
        r,
        "| contact | F = 1 | F = {} | failure | N | T | F_joint |\n|---|---|---|---|---|---|---|",
        fmt_f(s.factor)
    );
    let fmt_k = |k: [usize; 3]| format!("{} / {} / {}", k[2], k[1], k[0]);
    for &i in &o.contacts {
        let sc = &run.scene.contacts[i];
        let at_1 = run.contact().map(|c| Joint::of(run, c, i));
        let at_f = s.last.contact.as_ref().map(|c| Joint::of(run, c, i));
        let failed = s.failure.as_ref().map(|f| {
            state_counts(
                &run.model
                    .pairs
                    .iter()
                    .zip(&f.states)
                    .filter(|(p, _)| p.contact == i)
                    .map(|(_, &st)| st)
                    .collect::<Vec<_>>(),
            )
        });
        let (n, t, fj) = at_1.as_ref().map_or(("–".into(), "–".into(), "–".into()), |j| {
            (format!("{:.4e}", j.normal), format!("{:.4e}", j.shear), fmt_f(j.factor(sc.cohesion, sc.friction)))
        });
        let _ = writeln!(
            r,
            "| `{}` | {} | {} | {} | {n} | {t} | {fj} |",
            run.model.interfaces[i].name,
            at_1.map_or("–".into(), |j| fmt_k(j.states)),
            at_f.map_or("–".into(), |j| fmt_k(j.states)),
            failed.map_or("–".into(), fmt_k)
        );
    }
}

/// The pictures of the last state that holds.
fn pictures(r: &mut String, run: &Run, s: &SafetyRun) {
    let f = fmt_f(s.factor);
    let _ = writeln!(
        r,
        "\n![the model deformed by the displacement from F = 1 to F = {f}: the mechanism as it starts](safety_{})",
        picture::deformed_file(&[])
    );
    if s.last.contact.is_none() {
        return;
    }
    let _ = writeln!(r, "\n![contact normal and shear stress along each interface at F = {f}](safety_interfaces.svg)");
    let plans = picture::plan_files(&run.model);
    if let Some(j) = picture::joints_file(&plans) {
        let _ = writeln!(r, "\n![every contact surface by state at F = {f}](safety_{j})");
    }
    for p in plans.iter().take(6) {
        let name = &run.model.interfaces[p.interface].name;
        let _ = writeln!(
            r,
            "\n![plan view of {name} at F = {f}: where it sticks, slips and opens; sigma_n](safety_{})",
            p.file
        );
    }
}
