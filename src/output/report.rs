//! `report.md`: what a person reads first. The scene, the model's size, the
//! contact iteration, timings, errors against the closed form, probes, and
//! for Lamé's cylinder the paper's tables side by side with this run.

use std::fmt::Write;

use crate::results::{state_counts, Run};
use crate::scene::{Analysis, Analytic};

/// The paper's Table 1 (r, sigma_r, sigma_theta; units 1e-2 MPa) and Table 2
/// (r, contact sigma_n), theory and the paper's numerical values (DESIGN.md §3).
pub const TABLE1_R: [f64; 5] = [3.2, 3.6, 4.0, 4.4, 4.8];
pub const TABLE1_SR_PAPER: [f64; 5] = [-8.00, -5.13, -3.10, -1.59, -0.40];
pub const TABLE1_ST_PAPER: [f64; 5] = [19.28, 16.40, 14.46, 12.90, 11.65];
pub const TABLE2_R: [f64; 6] = [3.0, 3.4, 3.8, 4.2, 4.6, 5.0];
pub const TABLE2_PAPER: [f64; 6] = [21.02, 17.53, 15.14, 13.40, 12.10, 10.55];

/// Polar (sigma_r, sigma_theta) of a stress about the z axis (plane, solid)
/// or of an axisymmetric stress.
pub fn polar(analysis: Analysis, x: [f64; 3], s: &[f64; 6]) -> (f64, f64) {
    if analysis == Analysis::Axisymmetric {
        return (s[0], s[2]);
    }
    let r = x[0].hypot(x[1]);
    let (c, sn) = (x[0] / r, x[1] / r);
    (s[0] * c * c + s[1] * sn * sn + 2.0 * s[3] * sn * c, s[0] * sn * sn + s[1] * c * c - 2.0 * s[3] * sn * c)
}

/// Contact sigma_n at radius r, interpolated linearly between the pairs.
pub fn contact_sigma_n_at(run: &Run, r: f64) -> Option<f64> {
    let c = run.contact.as_ref()?;
    let mut pts: Vec<(f64, f64)> = run
        .model
        .pairs
        .iter()
        .zip(&c.pairs)
        .map(|(p, res)| {
            let x = run.model.coords[p.k];
            (x[0].hypot(x[1]), res.sigma_n)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // several pairs at one radius (3D: through the thickness) are averaged
    let mut merged: Vec<(f64, f64, f64)> = Vec::new();
    for (rr, s) in pts {
        match merged.last_mut() {
            Some(m) if (m.0 - rr).abs() < 1e-9 * rr.abs().max(1.0) => {
                m.1 += s;
                m.2 += 1.0;
            }
            _ => merged.push((rr, s, 1.0)),
        }
    }
    let pts: Vec<(f64, f64)> = merged.into_iter().map(|(r, s, n)| (r, s / n)).collect();
    let tol = 1e-9 * r.abs().max(1.0);
    let i = pts.iter().position(|p| p.0 >= r - tol)?;
    if (pts[i].0 - r).abs() <= tol {
        return Some(pts[i].1);
    }
    if i == 0 {
        return None;
    }
    let (a, b) = (pts[i - 1], pts[i]);
    Some(a.1 + (b.1 - a.1) * (r - a.0) / (b.0 - a.0))
}

/// Stresses at the Table 1 radii from the first probe: (sigma_r, sigma_theta).
pub fn table1_values(run: &Run) -> Vec<Option<(f64, f64)>> {
    TABLE1_R
        .iter()
        .map(|&r| {
            run.probes.iter().flat_map(|(_, s)| s.iter()).find(|s| s.found && (s.x[0].hypot(s.x[1]) - r).abs() < 1e-6 * r).map(|s| polar(run.model.analysis, s.x, &s.stress))
        })
        .collect()
}

fn pct(v: f64, exact: f64) -> String {
    format!("{:+.2} %", 100.0 * (v - exact) / exact.abs())
}

fn lame(run: &Run) -> Option<crate::analytic::Lame> {
    match run.scene.analytic.as_ref()? {
        Analytic::LameCylinder { a, b, p } => {
            let b0 = &run.model.bodies[0];
            Some(crate::analytic::Lame { a: *a, b: *b, p: *p, e: b0.e, nu: b0.nu, analysis: run.model.analysis })
        }
        Analytic::LinedTunnel(_) => None,
    }
}

fn is_paper_cylinder(run: &Run) -> bool {
    matches!(run.scene.analytic, Some(Analytic::LameCylinder { a, b, p }) if a == 3.0 && b == 5.0 && (p - 0.1).abs() < 1e-12)
}

/// The report of one run.
pub fn report(run: &Run) -> String {
    let mut s = String::new();
    let sc = &run.scene;
    let _ = writeln!(s, "# {}\n", sc.title);
    let _ = writeln!(s, "Scene `{}`, analysis {}, mesh `{}`{}.\n", sc.path.display(), sc.analysis, run.msh.display(), if run.mesh_cached { " (cached)" } else { "" });
    let _ = writeln!(s, "| quantity | value |\n|---|---|");
    let _ = writeln!(s, "| bodies | {} |", run.model.bodies.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", "));
    let _ = writeln!(s, "| elements | {} |", run.model.bodies.iter().map(|b| b.cells.len()).sum::<usize>());
    let _ = writeln!(s, "| model nodes (after contact split) | {} |", run.model.n_nodes());
    let _ = writeln!(s, "| DOFs (unknowns) | {} |", run.dofs_total);
    let _ = writeln!(s, "| interface DOFs | {} |", run.dofs_interface);
    let _ = writeln!(s, "| parts (condensed) | {} ({}) |", run.parts, run.condensed_parts);
    if let Some(c) = &run.contact {
        let k = state_counts(&c.states);
        let _ = writeln!(s, "| contact pairs | {} |", c.states.len());
        let _ = writeln!(s, "| contact iterations | {} ({}) |", c.iterations, if c.converged { "converged" } else if c.cycled { "NOT converged: the states cycle" } else { "NOT converged" });
        let _ = writeln!(s, "| states stick / slip / open | {} / {} / {} |", k[2], k[1], k[0]);
        let _ = writeln!(s, "| interface residual | {:.2e} |", run.residual_interface);
    }
    let t = &run.timings;
    let _ = writeln!(
        s,
        "| time mesh / assemble / condense / interface / recover / output / total (s) | {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} / {:.3} |",
        t.mesh, t.assemble, t.condense, t.interface, t.recover, t.output, t.total
    );
    if let Some(e) = &run.errors {
        let _ = writeln!(s, "| displacement error (relative L2) | {:.3e} |", e.displacement_l2);
        let _ = writeln!(s, "| stress error (relative L2) | {:.3e} |", e.stress_l2);
        if let Some(c) = run.contact_error_max {
            let _ = writeln!(s, "| contact sigma_n error (max, relative) | {:.3e} |", c);
        }
    }
    if run.steps.len() > 1 {
        let _ = writeln!(s, "\n## Load steps\n\n| step | ramp k/N | iterations | stick / slip / open | converged |\n|---|---|---|---|---|");
        for st in &run.steps {
            match &st.contact {
                Some(c) => {
                    let k = state_counts(&c.states);
                    let _ = writeln!(s, "| {} | {:.4} | {} | {} / {} / {} | {} |", st.step, st.load_factor, c.iterations, k[2], k[1], k[0], if c.converged { "yes" } else { "NO" });
                }
                None => {
                    let _ = writeln!(s, "| {} | {:.4} | – | – | – |", st.step, st.load_factor);
                }
            }
        }
    }
    if let Some(c) = &run.contact {
        if c.cycles_broken > 0 {
            let _ = writeln!(s, "\nThe state iteration cycled {} time(s); each cycle was broken by changing only the most violated pair per iteration.", c.cycles_broken);
        }
        if !c.converged {
            let _ = writeln!(s, "\n## Last two state sets\n");
            let _ = writeln!(s, "| pair | {} |", c.history.iter().rev().take(2).rev().enumerate().map(|(i, _)| format!("iteration {}", c.iterations - 1 + i)).collect::<Vec<_>>().join(" | "));
            let _ = writeln!(s, "|---|---|---|");
            for p in 0..c.states.len() {
                let cols: Vec<&str> = c.history.iter().rev().take(2).rev().map(|h| h[p].name()).collect();
                let _ = writeln!(s, "| {p} | {} |", cols.join(" | "));
            }
        }
    }
    let _ = writeln!(s, "\n![the deformed shape, contact pairs coloured by state]({})", super::picture::deformed_file(&run.stresses));
    if run.contact.is_some() {
        let _ = writeln!(s, "\n![contact normal and shear stress along each interface](interfaces.svg)");
    }
    if lame(run).is_some() {
        s += &lame_tables(&[("this run", run)], is_paper_cylinder(run));
    }
    s += &crate::lining::report_section(run);
    for (name, samples) in &run.probes {
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
    let _ = writeln!(s, "\nOpen `{}.vtu`{} in ParaView (File > Open), colour by `von_mises` or `displacement`; `Warp By Vector` on `displacement` shows the deformed shape.", sc.name, if run.contact.is_some() { format!(" and `{}_contact.vtu`", sc.name) } else { String::new() });
    s
}

/// Table 1 and Table 2 with one column group per run, in units of 1e-2 MPa.
pub fn lame_tables(runs: &[(&str, &Run)], with_paper: bool) -> String {
    let mut s = String::new();
    let Some(l) = lame(runs[0].1) else { return s };
    let u = 100.0; // 1e-2 MPa
    let _ = writeln!(s, "\n## Table 1: stresses along a radius (1e-2 MPa)\n");
    let mut head = String::from("| r (m) | sigma_r theory |");
    let mut rule = String::from("|---|---|");
    if with_paper {
        head += " paper | error |";
        rule += "---|---|";
    }
    for (name, _) in runs {
        head += &format!(" {name} | error |");
        rule += "---|---|";
    }
    head += " sigma_theta theory |";
    rule += "---|";
    if with_paper {
        head += " paper | error |";
        rule += "---|---|";
    }
    for (name, _) in runs {
        head += &format!(" {name} | error |");
        rule += "---|---|";
    }
    let _ = writeln!(s, "{head}\n{rule}");
    let values: Vec<Vec<Option<(f64, f64)>>> = runs.iter().map(|(_, r)| table1_values(r)).collect();
    for (i, &r) in TABLE1_R.iter().enumerate() {
        let (sr, st) = (l.sigma_r(r) * u, l.sigma_theta(r) * u);
        let mut row = format!("| {r:.1} | {sr:.2} |");
        if with_paper {
            row += &format!(" {:.2} | {} |", TABLE1_SR_PAPER[i], pct(TABLE1_SR_PAPER[i], sr));
        }
        for v in &values {
            row += &match v[i] {
                Some((a, _)) => format!(" {:.3} | {} |", a * u, pct(a * u, sr)),
                None => " – | – |".into(),
            };
        }
        row += &format!(" {st:.2} |");
        if with_paper {
            row += &format!(" {:.2} | {} |", TABLE1_ST_PAPER[i], pct(TABLE1_ST_PAPER[i], st));
        }
        for v in &values {
            row += &match v[i] {
                Some((_, b)) => format!(" {:.3} | {} |", b * u, pct(b * u, st)),
                None => " – | – |".into(),
            };
        }
        let _ = writeln!(s, "{row}");
    }
    if runs.iter().all(|(_, r)| r.contact.is_none()) {
        return s;
    }
    let _ = writeln!(s, "\n## Table 2: contact normal stress on the 45-degree cut (1e-2 MPa)\n");
    let mut head = String::from("| r (m) | theory (sigma_theta) |");
    let mut rule = String::from("|---|---|");
    if with_paper {
        head += " paper | error |";
        rule += "---|---|";
    }
    for (name, _) in runs {
        head += &format!(" {name} | error |");
        rule += "---|---|";
    }
    let _ = writeln!(s, "{head}\n{rule}");
    for (i, &r) in TABLE2_R.iter().enumerate() {
        let th = l.sigma_theta(r) * u;
        let mut row = format!("| {r:.1} | {th:.2} |");
        if with_paper {
            row += &format!(" {:.2} | {} |", TABLE2_PAPER[i], pct(TABLE2_PAPER[i], th));
        }
        for (_, run) in runs {
            row += &match contact_sigma_n_at(run, r) {
                Some(v) => format!(" {:.3} | {} |", v * u, pct(v * u, th)),
                None => " – | – |".into(),
            };
        }
        let _ = writeln!(s, "{row}");
    }
    s
}
