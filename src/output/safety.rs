//! The results of a safety search ([`SafetyRun`]), beside the run's own:
//!
//! - `safety.csv`: one row per trial (factor, the factor it started from,
//!   whether it held, contact iterations, states, seconds, why it failed,
//!   whether it was a step of a retry);
//! - the last converged state at F: `<name>_safety.vtu`,
//!   `<name>_safety_contact.vtu` and `safety_contact.csv` (the columns of
//!   the run's own), and its pictures with the prefix `safety_`: the model
//!   deformed by the displacement since F = 1 (the mechanism as it starts),
//!   the contact stresses along each interface, and in 3D the plan of every
//!   joint by state with the slip directions;
//! - `mechanism.png`: the blocks of the failing trial's mechanism moved by
//!   their rigid motion and coloured by it (the others still), the largest
//!   motion drawn 10 % of the picture's region;
//! - `summary.json`'s `safety` object and report.md's section
//!   ([`fn@report`]), which say what F is (strength reduction with peak or
//!   residual strength, or a load factor; decided by converged trials or
//!   only bracketed), name the mechanism and what can help it, set F beside
//!   the factor with the other strength convention, and beside each reduced
//!   contact's own limit equilibrium from its resultants, `F_joint = (c A +
//!   N f) / T` (N the normal force, T the magnitude of the summed shear
//!   force, A the closed area, c and f the scene's): the hand check of a
//!   joint that slides as one plane.

mod joint;
mod report;
mod sentences;

use std::fmt::Write;

use serde_json::{json, Value};

use super::files::Staged;
use super::picture::{self, Snapshot};
use crate::contact::mechanism::{describe, Mechanism};
use crate::error::Result;
use crate::results::about::Safety;
use crate::results::{state_counts, ContactRun, Run, SafetyRun, SearchKind};

use joint::Joint;
pub use report::report;
use sentences::{differ, fmt_f, raised};
pub use sentences::{label, other_factor_line, warnings};

/// The safety search's files, when the run made one.
pub(super) fn stage(run: &Run, staged: &mut Staged, drawn: &mut picture::Drawn) -> Result<()> {
    let Some(s) = &run.safety else { return Ok(()) };
    staged.add("safety.csv", trials_csv(s).into_bytes());
    if let Some(m) = s.failure.as_ref().and_then(|f| f.mechanism.as_ref()) {
        let u = mechanism_field(run, m);
        let title = format!("{}: the mechanism, {}", run.about.title, m.kind.key());
        let snap = Snapshot {
            title: &title,
            model: &run.model,
            u: &u,
            stresses: &[],
            contact: None,
            region: None,
            one_scale: false,
        };
        drawn.draw("mechanism.png", || picture::mechanism_png(&snap));
    }
    let Some(last) = &s.last else { return Ok(()) };
    let (model, name) = (&run.model, &run.about.name);
    let states: Vec<i32> = super::blocks::at_safety(run).iter().flatten().map(|b| b.state.code()).collect();
    staged.add(
        &format!("{name}_safety.vtu"),
        super::bodies_vtu::bodies_vtu(model, &last.u, &last.stresses, run.about.output.wants("displacement"), &states)?,
    );
    if let Some(c) = &last.contact {
        staged.add(&format!("{name}_safety_contact.vtu"), super::contact_files::contact_vtu(model, c)?);
        staged.add("safety_contact.csv", super::contact_files::contact_csv(model, c).into_bytes());
    }
    // the mechanism as it starts: the model deformed and coloured by the
    // displacement since F = 1 (below 1: since the start)
    let f = s.factor.map_or("-".into(), fmt_f);
    let since = if s.below_one { "the displacement of the load steps at F" } else { "displacement since F = 1" };
    let title = format!("{}: F = {f}, the last state that holds; {since}", run.about.title);
    let snap = Snapshot {
        title: &title,
        model,
        u: &s.du,
        stresses: &[],
        contact: last.contact.as_ref(),
        region: run.about.output.frame.as_ref(),
        one_scale: false,
    };
    drawn.draw(&format!("safety_{}", picture::deformed_file(&[])), || {
        picture::deformed_png(&snap, picture::Field::Displacement, None)
    });
    // the joints at F: along each interface, and in 3D in plan by state
    let Some(c) = &last.contact else { return Ok(()) };
    let title = format!("{}: F = {f}, the last state that holds", run.about.title);
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

/// Every node moved by its block's motion in the mechanism (still where
/// its block is not in it).
pub fn mechanism_field(run: &Run, m: &Mechanism) -> Vec<f64> {
    let (model, nd) = (&run.model, run.model.nd);
    let body_of = model.body_of_node();
    let mut u = vec![0.0; model.n_nodes() * nd];
    for (n, &b) in body_of.iter().enumerate() {
        if b == usize::MAX {
            continue;
        }
        let d = m.at(b, model.coords[n]);
        u[n * nd..n * nd + nd].copy_from_slice(&d[..nd]);
    }
    u
}

/// One row per trial.
fn trials_csv(s: &SafetyRun) -> String {
    let mut out = String::from("trial,factor,from,holds,iterations,stick,slip,open,seconds,failure,retry\n");
    for (i, t) in s.trials.iter().enumerate() {
        let k = t.states;
        let _ = writeln!(
            out,
            "{},{:.9},{:.9},{},{},{},{},{},{:.6},{},{}",
            i + 1,
            t.factor,
            t.from,
            t.holds,
            t.iterations,
            k[2],
            k[1],
            k[0],
            t.seconds,
            t.failed.map_or("", |f| f.key()),
            t.retry
        );
    }
    out
}

/// `summary.json`'s `safety` object.
pub(super) fn summary(run: &Run) -> Option<Value> {
    let (s, o) = (run.safety.as_ref()?, run.about.safety.as_ref()?);
    let model = &run.model;
    let failure = s.failure.as_ref().map(|f| {
        json!({ "kind": f.kind.key(), "iteration": f.iteration, "blocks": blocks(run, &f.blocks),
            "mechanism": f.mechanism.as_ref().map(|m| mechanism_json(run, m)),
            "contacts": o.contacts.iter().map(|&i| {
            let k = state_counts(&model.pairs.iter().zip(&f.states).filter(|(p, _)| p.contact == i).map(|(_, &st)| st).collect::<Vec<_>>());
            json!({ "contact": model.interfaces[i].name, "stick": k[2], "slip": k[1], "open": k[0] })
        }).collect::<Vec<_>>() })
    });
    let (kind, strength) = match s.kind {
        SearchKind::Strength(st) => ("strength", Some(st.key())),
        SearchKind::Load => ("load", None),
    };
    Some(json!({
        "kind": kind,
        "label": label(run, s),
        "strength": strength,
        "strength_given": o.strength_given,
        "factor": s.factor,
        "fails_at": s.fails_at,
        "decided": s.decided,
        "found": s.fails_at.is_some() && s.decided,
        "bound_reached": s.fails_at.is_none() && s.decided,
        "below_one": s.below_one,
        "undecided": s.undecided.iter().map(|u| json!({ "factor": u.factor, "iterations": u.iterations, "cycled": u.stop.cycled(), "law_broken": u.stop.law_broken() })).collect::<Vec<_>>(),
        "other": s.other.as_ref().map(|x| json!({ "strength": x.strengths.key(), "factor": x.factor, "fails_at": x.fails_at, "decided": x.decided, "trials": x.trials, "iterations": x.iterations, "differs": differ(s.factor, x.factor) })),
        "reduced": if s.kind == SearchKind::Load { Vec::new() } else { o.reduce.names() },
        "raised": o.raise.as_ref().map(|_| raised(run)),
        "contacts": o.contacts.iter().map(|&i| model.interfaces[i].name.clone()).collect::<Vec<_>>(),
        "step": o.steps.step, "tolerance": o.steps.tolerance, "max_factor": o.steps.max_factor,
        "failure": failure,
        "joints": joints_json(run, s, o),
        "trials": s.trials.iter().map(|t| json!({ "factor": t.factor, "from": t.from, "holds": t.holds, "iterations": t.iterations,
            "states": { "stick": t.states[2], "slip": t.states[1], "open": t.states[0] }, "seconds": t.seconds, "failure": t.failed.map(|f| f.key()), "retry": t.retry })).collect::<Vec<_>>(),
        "cost": s.cost,
        "cost_per_trial": { "contact_iterations": s.cost.contact_iterations as f64 / s.cost.trials.max(1) as f64, "seconds": s.cost.search_s / s.cost.trials.max(1) as f64 },
    }))
}

/// Each reduced contact at F = 1 and at F.
fn joints_json(run: &Run, s: &SafetyRun, o: &Safety) -> Vec<Value> {
    o.contacts.iter().map(|&i| {
        let sc = &run.about.contacts[i];
        let at = |c: Option<&ContactRun>| c.map(|c| {
            let j = Joint::of(run, c, i);
            json!({ "normal_force": j.normal, "shear_force": j.shear, "closed_area": j.area, "factor_from_resultants": finite(j.factor(sc.strength.cohesion, sc.strength.friction)),
                    "states": { "stick": j.states[2], "slip": j.states[1], "open": j.states[0] } })
        });
        let at_1 = if s.below_one { None } else { run.contact() };
        json!({ "contact": run.model.interfaces[i].name, "friction": sc.strength.friction, "cohesion": sc.strength.cohesion, "residual_cohesion": sc.strength.residual_cohesion,
                "at_1": at(at_1), "at_factor": at(s.last.as_ref().and_then(|l| l.contact.as_ref())) })
    }).collect()
}

/// The mechanism for summary.json.
fn mechanism_json(run: &Run, m: &Mechanism) -> Value {
    json!({
        "kind": m.kind.key(),
        "description": describe(&run.model, m),
        "helps": m.kind.helps(),
        "blocks": m.blocks.iter().map(|b| json!({
            "block": b.block, "name": super::faces::block_name(&run.model, b.block), "motion": b.state.key(),
            "translation": b.translation, "rotation": b.rotation, "pivot": b.pivot,
            "on": b.on.iter().map(|&c| run.model.interfaces[c].name.clone()).collect::<Vec<_>>(), "along_line": b.along_line,
        })).collect::<Vec<_>>(),
    })
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
