//! `report.md`: what a person reads first. The scene, the model's size, the
//! contact iteration, timings, errors against the closed form, the pictures,
//! what the scene's `[analytic]` check adds (`Checks::analytic`), and the probes.

use std::fmt::Write;

use crate::results::{state_counts, Run};

/// The report of one run.
pub fn report(run: &Run) -> String {
    let mut s = String::new();
    let sc = &run.scene;
    let _ = writeln!(s, "# {}\n", sc.title);
    let st = &run.stats;
    let _ = writeln!(s, "Scene `{}`, analysis {}, mesh `{}`{}.\n", sc.path.display(), sc.analysis, st.msh.display(), if st.mesh_cached { " (cached)" } else { "" });
    for w in sc.warnings() {
        let _ = writeln!(s, "**Warning:** {w}.\n");
    }
    let _ = writeln!(s, "| quantity | value |\n|---|---|");
    let _ = writeln!(s, "| bodies | {} |", run.model.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", "));
    let _ = writeln!(s, "| elements | {} |", run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>());
    let _ = writeln!(s, "| model nodes (after contact split) | {} |", run.model.n_nodes());
    let _ = writeln!(s, "| DOFs (unknowns) | {} |", st.dofs.total);
    let _ = writeln!(s, "| interface DOFs | {} |", st.dofs.interface);
    let _ = writeln!(s, "| parts (condensed) | {} ({}) |", st.parts.total, st.parts.condensed);
    if st.ranks.len() > 1 {
        let _ = writeln!(
            s,
            "| MPI ranks: parts / condense (s) / peak memory (MB) | {} |",
            st.ranks.iter().map(|r| format!("{} / {:.2} / {:.0}", r.parts.len(), r.condense_s, r.peak_memory_bytes as f64 / 1e6)).collect::<Vec<_>>().join(", ")
        );
    }
    if let Some(c) = run.contact() {
        let (k, it) = (state_counts(&c.states), &c.summary);
        let _ = writeln!(s, "| contact pairs | {} |", c.states.len());
        let _ = writeln!(s, "| contact iterations | {} ({}) |", it.iterations, if it.converged { "converged" } else if it.cycled { "NOT converged: the states cycle" } else { "NOT converged" });
        let _ = writeln!(s, "| states stick / slip / open | {} / {} / {} |", k[2], k[1], k[0]);
        let _ = writeln!(s, "| interface residual | {:.2e} |", st.residuals.interface);
    }
    let t = &st.timings;
    let _ = writeln!(
        s,
        "| time mesh / assemble / condense / interface / recover / output / total (s) | {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} |",
        t.mesh, t.assemble, t.condense, t.interface, t.recover, t.output, t.total
    );
    if let Some(e) = &run.checks.errors {
        let _ = writeln!(s, "| displacement error (relative L2) | {:.3e} |", e.displacement_l2);
        let _ = writeln!(s, "| stress error (relative L2) | {:.3e} |", e.stress_l2);
        if let Some(c) = run.checks.contact_error_max {
            let _ = writeln!(s, "| contact sigma_n error (max, relative) | {:.3e} |", c);
        }
    }
    if run.steps.len() > 1 {
        let _ = writeln!(s, "\n## Load steps\n\n| step | ramp k/N | iterations | stick / slip / open | converged |\n|---|---|---|---|---|");
        for st in &run.steps {
            match &st.contact {
                Some(c) => {
                    let k = state_counts(&c.states);
                    let _ = writeln!(s, "| {} | {:.4} | {} | {} / {} / {} | {} |", st.step, st.load_factor, c.summary.iterations, k[2], k[1], k[0], if c.summary.converged { "yes" } else { "NO" });
                }
                None => {
                    let _ = writeln!(s, "| {} | {:.4} | – | – | – |", st.step, st.load_factor);
                }
            }
        }
    }
    if let Some(c) = run.contact() {
        let it = &c.summary;
        if it.cycles_broken > 0 {
            let _ = writeln!(s, "\nThe state iteration cycled {} time(s); each cycle was broken by changing only the most violated pair per iteration.", it.cycles_broken);
        }
        if !it.converged {
            let _ = writeln!(s, "\n## Last two state sets\n");
            let _ = writeln!(s, "| pair | {} |", it.history.iter().rev().take(2).rev().enumerate().map(|(i, _)| format!("iteration {}", it.iterations - 1 + i)).collect::<Vec<_>>().join(" | "));
            let _ = writeln!(s, "|---|---|---|");
            for p in 0..c.states.len() {
                let cols: Vec<&str> = it.history.iter().rev().take(2).rev().map(|h| h[p].name()).collect();
                let _ = writeln!(s, "| {p} | {} |", cols.join(" | "));
            }
        }
    }
    let _ = writeln!(s, "\n![the deformed shape, contact pairs coloured by state]({})", super::picture::deformed_file(&run.last().stresses));
    if run.contact().is_some() {
        let _ = writeln!(s, "\n![contact normal and shear stress along each interface](interfaces.svg)");
        for (ii, file) in super::picture::plan_files(&run.model) {
            let name = &run.model.interfaces[ii].name;
            let _ = writeln!(s, "\n![plan view of {name}: where it sticks, slips and opens; sigma_n]({file})\n\n*Plan view of `{name}`: where it sticks, slips and opens (left); sigma_n (right).*");
        }
    }
    s += &run.checks.analytic.report;
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
                p.x[0], p.x[1], p.x[2], p.displacement[0], p.displacement[1], p.displacement[2], p.stress[0], p.stress[1], p.stress[2], p.stress[3], p.von_mises
            );
        }
    }
    let _ = writeln!(s, "\nOpen `{}.vtu`{} in ParaView (File > Open), colour by `von_mises` or `displacement`; `Warp By Vector` on `displacement` shows the deformed shape.", sc.name, if run.contact().is_some() { format!(" and `{}_contact.vtu`", sc.name) } else { String::new() });
    s
}
