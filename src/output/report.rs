//! `report.md`: what a person reads first. The scene, its warnings (the
//! scene's and the model's: bodies bonded without a contact), the model's
//! size, the contact iteration, timings (the same as summary.json's: both
//! are staged once the output stage is timed), the load steps with the
//! factor each load had at each step, errors against the closed form, the
//! pictures, the contact groups and most mobilised block faces
//! (faces.rs), what the scene's `[analytic]` check adds (`Checks::analytic`),
//! the safety search's factor (`safety.rs`), and the probes.

use std::fmt::Write;

use crate::contact::Stop;
use crate::results::{state_counts, Run};

/// Plan views embedded in report.md; beyond, they are listed.
const MOST_EMBEDDED: usize = 6;

/// The report of one run (`derived` from it).
pub fn report(run: &Run, derived: &super::derived::Derived) -> String {
    let mut s = String::new();
    header(&mut s, run);
    size_rows(&mut s, run);
    contact_rows(&mut s, run);
    time_and_error_rows(&mut s, run);
    if run.steps.len() > 1 {
        load_steps(&mut s, run);
    }
    iteration_notes(&mut s, run);
    pictures(&mut s, run);
    s += &super::water::report(run);
    s += &super::faces::report(run, derived.resultants());
    s += &super::blocks::run_report(run, derived.blocks());
    if let Some(b) = derived.bearing() {
        s += &super::bearing::report(run, b);
    }
    s += &super::sections::report(run);
    s += &super::reactions::report(run);
    s += &super::closed_form::report(&run.checks.analytic);
    s += &super::safety::report(run);
    probes(&mut s, run);
    let sc = &run.about;
    let _ = writeln!(s, "\nOpen `{}.vtu`{} in ParaView (File > Open), colour by `von_mises` or `displacement`; `Warp By Vector` on `displacement` shows the deformed shape.", sc.name, if run.contact().is_some() { format!(" and `{}_contact.vtu`", sc.name) } else { String::new() });
    s
}

/// The title, the scene line and the warnings.
fn header(s: &mut String, run: &Run) {
    let sc = &run.about;
    let st = &run.stats;
    let _ = writeln!(s, "# {}\n", sc.title);
    let _ = writeln!(
        s,
        "Scene `{}`, analysis {}, mesh `{}`{}.\n",
        sc.path.display(),
        sc.analysis,
        st.msh.display(),
        if st.mesh_cached { " (cached)" } else { "" }
    );
    for w in &run.about.warnings {
        let _ = writeln!(s, "**Warning:** {w}.\n");
    }
    if let Some(f) = &run.fallback {
        let _ = writeln!(s, "**Joints that deform in place of rigid ones:** {}.\n", crate::driver::fallback_said(f));
    }
}

/// The table's head and the model's size.
fn size_rows(s: &mut String, run: &Run) {
    let st = &run.stats;
    let _ = writeln!(s, "| quantity | value |\n|---|---|");
    let _ = writeln!(s, "| bodies | {} |", body_groups(&run.model));
    let _ = writeln!(s, "| elements | {} |", run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>());
    let _ = writeln!(s, "| model nodes (after contact split) | {} |", run.model.n_nodes());
    let _ = writeln!(s, "| DOFs (unknowns) | {} |", st.dofs.total);
    let _ = writeln!(s, "| interface DOFs | {} ({} interface solver) |", st.dofs.interface, st.interface_solver);
    let _ = writeln!(s, "| parts (condensed) | {} ({}) |", st.parts.total, st.parts.condensed);
    if st.ranks.len() > 1 {
        let _ = writeln!(
            s,
            "| MPI ranks: parts / condense (s) / peak memory (MB) | {} |",
            st.ranks
                .iter()
                .map(|r| format!("{} / {:.2} / {:.0}", r.parts.len(), r.condense_s, r.peak_memory_bytes as f64 / 1e6))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
}

/// The contact iteration's rows: pairs, iterations, states, residuals.
fn contact_rows(s: &mut String, run: &Run) {
    let st = &run.stats;
    if let Some(c) = run.contact() {
        let (k, it) = (state_counts(&c.states), &c.summary);
        let _ = writeln!(s, "| contact pairs | {} |", c.states.len());
        let _ = writeln!(
            s,
            "| contact iterations | {} ({}) |",
            it.iterations,
            if it.converged {
                "converged"
            } else if run.safety.as_ref().is_some_and(|s| s.below_one) {
                "NOT in equilibrium: the last iterate of the load step that lost it (the scene is unsafe as given, see the safety section)"
            } else {
                match it.stop {
                    Some(Stop::Cycled) => "NOT converged: the states cycle",
                    Some(Stop::LawBroken) => {
                        "NOT converged: the states settled, but their forces break the contact law (its residual below)"
                    }
                    _ => "NOT converged",
                }
            }
        );
        let _ = writeln!(s, "| states stick / slip / open | {} / {} / {} |", k[2], k[1], k[0]);
        if let Some(i) = run.initial_stage.as_ref().filter(|i| !i.converged) {
            let _ = writeln!(
                s,
                "| initial equilibrium stage | NOT converged after {} iterations: its last iterate is the step reported (step 0), its own displacements, largest {:.3e} |",
                i.iterations, i.largest
            );
        } else if let Some(i) = &run.initial_stage {
            let ramp = match i.strength_ramp.as_slice() {
                [] => String::new(),
                r => format!(
                    ", the joints' strength brought down from {:.3} times the scene's (where the in-situ stress put none beyond it) in {} pieces",
                    r[0],
                    r.len() - 1
                ),
            };
            let _ = writeln!(
                s,
                "| initial equilibrium stage (taken off the displacements) | {} iterations, {} / {} / {} stick / slip / open, largest displacement {:.3e}{ramp} |",
                i.iterations, i.states[2], i.states[1], i.states[0], i.largest
            );
        }
        let _ = writeln!(s, "| interface residual | {:.2e} |", st.residuals.interface);
        if let Some((p, r)) = c.worst_law_residual() {
            let group = &run.model.interfaces[run.model.pairs[p].contact].name;
            let _ =
                writeln!(s, "| contact law residual (worst pair / largest traction) | {r:.2e} (pair {p}, {group}) |");
        }
    }
}

/// The timings and the errors against the closed form.
fn time_and_error_rows(s: &mut String, run: &Run) {
    let sc = &run.about;
    let t = &run.stats.timings;
    let _ = writeln!(
        s,
        "| time mesh / model / assemble / condense / interface / recover / output / total (s) | {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} |",
        t.mesh, t.model, t.assemble, t.condense, t.interface, t.recover, t.output, t.total
    );
    if let Some(e) = &run.checks.errors {
        let (what, against) = sc.analytic.as_ref().map_or(("error", "the closed form"), super::closed_form::labels);
        let _ = writeln!(s, "| displacement {what} against {against} (relative L2) | {:.3e} |", e.displacement_l2);
        let _ = writeln!(s, "| stress {what} against {against} (relative L2) | {:.3e} |", e.stress_l2);
        if let Some(c) = run.checks.contact_error_max {
            let _ = writeln!(s, "| contact sigma_n error (max, relative) | {:.3e} |", c);
        }
    }
}

/// How the contact iteration went: cycles broken, load steps cut, pairs unsettled.
fn iteration_notes(s: &mut String, run: &Run) {
    if let Some(c) = run.contact() {
        let it = &c.summary;
        if it.cycles_broken > 0 {
            let _ = writeln!(s, "\nThe state iteration cycled {} time(s); each cycle was broken by changing only the most violated pair per iteration.", it.cycles_broken);
        }
        if it.clusters_solved > 0 {
            let _ = writeln!(s, "\nThe state iteration stalled or cycled on a few pairs {} time(s) and the cluster fallback ended it: the pressures of a stall's slipping pairs solved for (multisecant steps), or the cluster's stick / slip / open sets tried, fewest changes from the load step's start first, until one met the law at every pair.", it.clusters_solved);
        }
        if let Some(r) = it.augmented {
            let _ = writeln!(s, "\n{}", augmented_sentence(&r));
        }
        let stage = run.last().step == 0;
        if it.cuts > 0 || it.scaled || (stage && !it.strengths.is_empty()) {
            let _ = writeln!(s, "\n{}", cut_sentence(it, stage));
        }
        *s += &super::unsettled::report(&run.model, c);
    }
    locked_off(s, run);
}

/// What augmented Lagrangian rounds did to a step the Newton iteration of
/// rigid joints did not end ([`crate::contact::augmented`]).
fn augmented_sentence(r: &crate::contact::augmented::Rounds) -> String {
    let what = format!("The Newton iteration of the rigid joints did not end the last load step, so it was solved again by {} augmented Lagrangian round(s) ([solver] augmented_lagrangian; {} iteration(s), counted with Newton's): stiff springs whose load takes the force of the round before", r.rounds, r.iterations);
    if r.closed() {
        format!("{what}, until no closed pair's spring stretched by more than 1e-9 of the largest force (the last round: {:.1e}): the rigid joints' answer.", r.stretch)
    } else if r.stretch.is_finite() {
        format!("{what}. They did not end it either: their springs still stretched by {:.1e} of the largest force when the stretch stopped halving in four rounds (a state set with no rigid answer) or the rounds ran out, and the results are the Newton iteration's.", r.stretch)
    } else {
        format!("{what}. They did not end it either: the last round's own iteration did not end, and the results are the Newton iteration's.")
    }
}

/// The crossings whose locked friction is off the equilibrium solved, step
/// by step (`ContactRun::locked_off`), and what that means for their forces.
fn locked_off(s: &mut String, run: &Run) {
    let off: Vec<_> = (run.steps.iter())
        .filter_map(|st| {
            st.contact.as_ref().and_then(|c| c.worst_locked_off().map(|w| (st.step, c.locked_off.len(), w)))
        })
        .collect();
    if off.is_empty() {
        return;
    }
    let _ = writeln!(s, "
At some crossings of joints the friction of slipping pairs that the crossing locks (they cannot move along their slip) depends on their pressures, which the crossing's share of the forces gives back; there no pressures gave themselves back, and the forces reported for those pairs are one round of that search off the equilibrium solved. Read them as uncertain by that much; the states and the rest of the answer are the iteration's (docs/convergence.md, twentieth session).\n");
    for (step, n, (pairs, f, r)) in off {
        let x = run.model.coords[run.model.pairs[pairs[0]].k];
        let _ = writeln!(
            s,
            "- load step {step}: {n} crossing(s); the worst at ({:.3}, {:.3}, {:.3}), pairs {pairs:?}: {f:.3e} in force, {r:.2e} of the largest pair force",
            x[0], x[1], x.get(2).copied().unwrap_or(0.0)
        );
    }
}

/// The pictures: the deformed shape, the stereonet, the interface plot and the plan views.
fn pictures(s: &mut String, run: &Run) {
    let _ = writeln!(
        s,
        "\n![the deformed shape, contact pairs coloured by state]({})",
        super::picture::deformed_file(&run.last().stresses)
    );
    if let Some(f) = super::picture::stereonet_file(&run.about.joints) {
        let _ = writeln!(s, "\n![the joints on a stereonet]({f})\n\n*The joints: poles and great circles, lower hemisphere, equal area.*");
    }
    if run.contact().is_some() {
        let _ = writeln!(s, "\n![contact normal and shear stress along each interface](interfaces.svg)");
        plan_views(s, run);
    }
}

/// The plan views, embedded (a few) or listed (a joint set of many planes).
fn plan_views(s: &mut String, run: &Run) {
    let plans = super::picture::plan_files(&run.model);
    if let Some(f) = super::picture::joints_file(&plans) {
        let _ = writeln!(s, "\n![every contact surface by state]({f})\n\n*Every contact surface laid flat, by state: {} sheets (planes and unrolled surfaces).*", plans.len());
    }
    if plans.len() > MOST_EMBEDDED {
        // a joint set of many planes: a list, not a wall of pictures
        let _ = writeln!(s, "\nThe plan views, one per sheet: where it sticks, slips and opens; sigma_n.\n\n| file | contact | sheet |\n|---|---|---|");
        for p in &plans {
            let _ = writeln!(
                s,
                "| [{}]({}) | {} | {} |",
                p.file,
                p.file,
                run.model.interfaces[p.interface].name,
                p.describe(&run.model)
            );
        }
    } else {
        for p in &plans {
            let name = &run.model.interfaces[p.interface].name;
            let (what, which) = if p.of > 1 {
                (format!("{name} ({})", p.describe(&run.model)), format!(", {}", p.describe(&run.model)))
            } else {
                (name.clone(), String::new())
            };
            let _ = writeln!(s, "\n![plan view of {what}: where it sticks, slips and opens; sigma_n]({})\n\n*Plan view of `{name}`{which}: where it sticks, slips and opens (left); sigma_n (right).*", p.file);
        }
    }
}

/// A table of each probe's samples.
fn probes(s: &mut String, run: &Run) {
    for (name, samples) in &run.checks.probes {
        let _ = writeln!(s, "\n## Probe `{name}`\n");
        let _ = writeln!(s, "| x | y | z | ux | uy | uz | sxx | syy | szz | sxy | von Mises |\n|---|---|---|---|---|---|---|---|---|---|---|");
        for p in samples {
            if !p.found {
                let _ = writeln!(s, "| {:.4} | {:.4} | {:.4} | outside the model |||||||| ", p.x[0], p.x[1], p.x[2]);
                continue;
            }
            let _ = writeln!(
                s,
                "| {:.4} | {:.4} | {:.4} | {:.4e} | {:.4e} | {:.4e} | {:.4e} | {:.4e} | {:.4e} | {:.4e} | {:.4e} |",
                p.x[0],
                p.x[1],
                p.x[2],
                p.displacement[0],
                p.displacement[1],
                p.displacement[2],
                p.stress[0],
                p.stress[1],
                p.stress[2],
                p.stress[3],
                p.von_mises
            );
        }
    }
}

/// The load-step table: the factor each load actually had at each step
/// ([`crate::results::Applied`]), then the contact iteration of the step.
fn load_steps(s: &mut String, run: &Run) {
    let columns = &run.about.applied;
    let head: Vec<String> = columns.iter().map(|c| format!("{} | ", c.name)).collect();
    let _ = writeln!(s, "\n## Load steps\n\nThe factor that multiplies each load at each step (as given by `factors`, `gravity_factors`, or the ramp k / load_steps).\n");
    let _ = writeln!(s, "| step | {}iterations | stick / slip / open | converged |", head.concat());
    let _ = writeln!(s, "|---|{}---|---|---|", "---|".repeat(columns.len()));
    for st in &run.steps {
        let factors: String =
            columns.iter().map(|c| format!("{} | ", factor(c.factors.get(st.step.wrapping_sub(1)).copied()))).collect();
        match &st.contact {
            Some(c) => {
                let k = state_counts(&c.states);
                let _ = writeln!(
                    s,
                    "| {} | {factors}{}{} | {} / {} / {} | {} |",
                    st.step,
                    c.summary.iterations,
                    if c.summary.cuts > 0 { format!(" (cut {} time(s))", c.summary.cuts) } else { String::new() },
                    k[2],
                    k[1],
                    k[0],
                    if c.summary.converged { "yes" } else { "NO" }
                );
            }
            None => {
                let _ = writeln!(s, "| {} | {factors}– | – | – |", st.step);
            }
        }
    }
}

/// What cutting did in a load step, or in an initial stage (`stage`)
/// that did not converge: its load halved (`it.cuts` > 0) or why it was
/// not (`it.scaled`), or where the
/// in-situ stress was beyond the joints' strength the pieces of the
/// stage's strength ramp (`it.strengths`: the factors reached).
fn cut_sentence(it: &crate::contact::Summary, stage: bool) -> String {
    if let (true, Some(top), Some(end)) = (stage, it.strengths.first(), it.strengths.last()) {
        return format!(
            "The initial stage did not converge: the joints' strength, brought down from {top:.4} times the scene's, converged down to {end:.4} times it; the next piece did not converge (halved {} time(s), [solver] max_cuts).",
            it.cuts
        );
    }
    let (what, of) = if stage {
        ("initial stage did not converge", "its load")
    } else {
        ("load step did not converge whole", "the step")
    };
    if it.scaled {
        return format!("The {what} and was {} ([solver] max_cuts).", crate::driver::NOT_CUT);
    }
    let ends: Vec<String> = it.pieces.iter().map(|&t| factor(Some(t))).collect();
    let mut s = format!(
        "The {what} and was cut {} time(s) ([solver] max_cuts); its pieces converged up to {} of {of}",
        it.cuts,
        if ends.is_empty() { "none".to_string() } else { ends.join(", ") }
    );
    // (the stage's sentence ends with its pieces)
    if let Some((a, b)) = it.stopped_at.filter(|_| !stage) {
        let _ = write!(
            s,
            ", and the piece from {} to {} did not converge at the deepest cut",
            factor(Some(a)),
            factor(Some(b))
        );
    }
    s.push('.');
    s
}

/// A load factor as the user would write it: up to 4 decimals, no trailing
/// zeros.
fn factor(f: Option<f64>) -> String {
    match f {
        Some(v) if v.is_finite() => {
            let t = format!("{v:.4}");
            let t = t.trim_end_matches('0').trim_end_matches('.');
            if t == "-0" {
                "0".into()
            } else {
                t.to_string()
            }
        }
        _ => "–".into(),
    }
}

/// The body groups in scene order, each with its count of blocks where its
/// contacts cut it into several: "rock (64 blocks), lining".
fn body_groups(model: &crate::model::Model) -> String {
    let mut groups: Vec<(&str, usize)> = Vec::new();
    for b in &model.bodies {
        match groups.iter_mut().find(|(n, _)| *n == b.name) {
            Some(g) => g.1 += 1,
            None => groups.push((&b.name, 1)),
        }
    }
    groups
        .iter()
        .map(|&(n, k)| if k > 1 { format!("{n} ({k} blocks)") } else { n.to_string() })
        .collect::<Vec<_>>()
        .join(", ")
}
