//! report.md's section on the safety search: what F is and whether
//! converged trials decided it, the mechanism and what can hold it, the
//! factor with the other strength convention, each reduced contact's hand
//! check, every trial, the cost, the pictures.

use std::fmt::Write;

use super::joint::Joint;
use super::sentences::{fmt_f, fmt_g, label, other_factor_line, warnings};
use crate::contact::mechanism::describe;
use crate::output::picture;
use crate::results::about::Safety;
use crate::results::{state_counts, Run, SafetyRun, SearchKind};

/// report.md's section (empty without a search).
pub fn report(run: &Run) -> String {
    let (Some(s), Some(o)) = (&run.safety, &run.about.safety) else { return String::new() };
    let mut r = match s.kind {
        SearchKind::Load => String::from("\n## Load factor\n\n"),
        SearchKind::Strength(_) => String::from("\n## Factor of safety\n\n"),
    };
    headline(&mut r, run, s, o);
    if let Some(m) = s.failure.as_ref().and_then(|f| f.mechanism.as_ref()) {
        let _ = writeln!(
            r,
            "**Mechanism: {}.** {}. What can hold it: {}. `mechanism.png` shows the blocks moved by that motion; `blocks.csv` gives every block's state.\n",
            m.kind.key(),
            describe(&run.model, m),
            m.kind.helps()
        );
        let _ = writeln!(r, "![the mechanism: the blocks that move, by their rigid motion](mechanism.png)\n");
    }
    if let Some(line) = s.other.as_ref().and_then(|x| other_factor_line(run, s, x)) {
        let _ = writeln!(
            r,
            "For comparison, {line}. The headline keeps the convention `[safety] strength` names ({}).\n",
            if o.strength_given { "given by the scene" } else { "peak by default: the scene does not say" }
        );
    }
    for w in warnings(run) {
        let _ = writeln!(r, "> **Warning:** {w}\n");
    }
    if s.kind != SearchKind::Load {
        joints_table(&mut r, run, s, o);
    }
    let c = &s.cost;
    let per = |x: f64| x / c.trials.max(1) as f64;
    let _ = writeln!(
        r,
        "\nThe search: {} trials, {} contact iterations ({:.1} per trial), {:.3} s on the condensed interface ({:.4} s per trial), {:.3} s to recover the last state that holds; sparse factorisations: {} for the whole run (one per part), none in the search.\n",
        c.trials, c.contact_iterations, per(c.contact_iterations as f64), c.search_s, per(c.search_s), c.recover_s, run.stats.counters.factorisations
    );
    trials_table(&mut r, s);
    pictures(&mut r, run, s);
    r
}

/// The first paragraph: F, what it is, and how sure.
fn headline(r: &mut String, run: &Run, s: &SafetyRun, o: &Safety) {
    let what = label(run, s);
    let varied = match s.kind {
        SearchKind::Load => "the raised loads multiplied by F".to_string(),
        SearchKind::Strength(_) => format!("{} divided by F on {}", o.reduce.names().join(", "), contacts(run, o)),
    };
    let peak_holds = s.factor.is_some_and(|h| h >= 1.0) && matches!(s.kind, SearchKind::Strength(_));
    let from = if s.below_one && peak_holds {
        "The load steps lose equilibrium as given (F = 1), with the residual strength they keep where pairs slip or open; each trial ran the initial stage, if any, and the load steps from the start with the search's strength"
    } else if s.below_one {
        "The scene loses equilibrium as given (F = 1), so F was sought below 1, each trial running the initial stage, if any, and the load steps from the start"
    } else {
        "From the state of the last load step"
    };
    let f = s.factor.map_or("–".into(), fmt_f);
    let _ = match (s.factor, s.fails_at, s.decided) {
        (Some(h), Some(x), true) => writeln!(r, "**F = {f}**: {what}, with {varied}. {from}: it holds at F = {} and fails at F = {} (tolerance {} × F).\n", fmt_g(h), fmt_g(x), o.steps.tolerance),
        (Some(h), Some(x), false) => writeln!(r, "**F not decided**: {what}, with {varied}. {from}: converged trials hold at F = {} and fail at F = {}; trials between did not converge, even retried in smaller steps with more iterations ({}), so F lies between them and the run ends with an error.\n", fmt_g(h), fmt_g(x), undecided(s)),
        (Some(_), None, true) => writeln!(r, "**F > {f}**: the search reached its bound (safety.max_factor = {}) and the scene still holds there ({what}, with {varied}). Raise max_factor to find F.\n", o.steps.max_factor),
        (Some(h), None, false) => writeln!(r, "**F not decided**, at least {}: {what}, with {varied}; no trial above converged ({}).\n", fmt_g(h), undecided(s)),
        (None, x, _) => writeln!(r, "**F < {}**: {what}, with {varied}. {from}: no factor held down to 1 / max_factor.\n", x.map_or("–".into(), fmt_g)),
    };
    if let (Some(x), Some(fail)) = (s.fails_at, &s.failure) {
        let who = if fail.blocks.is_empty() {
            "the solver named no block".to_string()
        } else {
            run.model.body_names(&fail.blocks)
        };
        let _ = writeln!(
            r,
            "At F = {} (contact iteration {}): {}: {who}.\n",
            fmt_g(x),
            fail.iteration,
            fail.kind.describe()
        );
    }
}

/// The factors of the trials that decided nothing.
fn undecided(s: &SafetyRun) -> String {
    let f: Vec<String> = s.undecided.iter().map(|u| format!("F = {}", fmt_g(u.factor))).collect();
    format!("no equilibrium found at {}", f.join(", "))
}

/// The chosen contacts: "all contacts" or their names.
fn contacts(run: &Run, o: &Safety) -> String {
    let names: Vec<String> = o.contacts.iter().map(|&i| format!("`{}`", run.model.interfaces[i].name)).collect();
    if o.contacts.len() == run.about.contacts.len() {
        format!("all contacts ({})", names.join(", "))
    } else {
        names.join(", ")
    }
}

/// Each reduced contact at F = 1, at F and at failure, with its own limit
/// equilibrium from its resultants.
fn joints_table(r: &mut String, run: &Run, s: &SafetyRun, o: &Safety) {
    let _ = writeln!(r, "Each reduced contact: its pairs stick / slip / open at F = 1, at F and at failure; its normal force N and shear force T at F = 1, and its own limit equilibrium from them, F_joint = (c A + N f) / T (A its closed area, c its peak cohesion; the factor of a joint that slides as one plane).\n");
    let f = s.factor.map_or("–".into(), fmt_f);
    let _ = writeln!(r, "| contact | F = 1 | F = {f} | failure | N | T | F_joint |\n|---|---|---|---|---|---|---|");
    let fmt_k = |k: [usize; 3]| format!("{} / {} / {}", k[2], k[1], k[0]);
    let at_one = if s.below_one { None } else { run.contact() };
    for &i in &o.contacts {
        let sc = &run.about.contacts[i];
        let at_1 = at_one.map(|c| Joint::of(run, c, i));
        let at_f = s.last.as_ref().and_then(|l| l.contact.as_ref()).map(|c| Joint::of(run, c, i));
        let failed = s.failure.as_ref().map(|f| {
            let of: Vec<_> =
                (run.model.pairs.iter().zip(&f.states)).filter(|(p, _)| p.contact == i).map(|(_, &st)| st).collect();
            state_counts(&of)
        });
        let (n, t, fj) = at_1.as_ref().map_or(("–".into(), "–".into(), "–".into()), |j| {
            (
                format!("{:.4e}", j.normal),
                format!("{:.4e}", j.shear),
                fmt_f(j.factor(sc.strength.cohesion, sc.strength.friction)),
            )
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

/// Every trial.
fn trials_table(r: &mut String, s: &SafetyRun) {
    let _ = writeln!(
        r,
        "| trial | F | from F | holds | contact iterations | stick / slip / open |\n|---|---|---|---|---|---|"
    );
    for (i, t) in s.trials.iter().enumerate() {
        let k = t.states;
        let verdict = match (t.holds, t.failed) {
            (true, _) => "yes",
            (false, Some(f)) if f.key() == "not_converged" => "not converged",
            (false, f) => f.map_or("no", |f| f.key()),
        };
        let _ = writeln!(
            r,
            "| {}{} | {} | {} | {verdict} | {} | {} / {} / {} |",
            i + 1,
            if t.retry { " (retry)" } else { "" },
            fmt_f(t.factor),
            fmt_f(t.from),
            t.iterations,
            k[2],
            k[1],
            k[0]
        );
    }
}

/// The pictures of the last state that holds.
fn pictures(r: &mut String, run: &Run, s: &SafetyRun) {
    let Some(last) = &s.last else { return };
    let f = s.factor.map_or("–".into(), fmt_f);
    let since = if s.below_one { "the displacement of the load steps" } else { "the displacement from F = 1" };
    let _ = writeln!(
        r,
        "\n![the model deformed by {since} to F = {f}: the mechanism as it starts](safety_{})",
        picture::deformed_file(&[])
    );
    if last.contact.is_none() {
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
