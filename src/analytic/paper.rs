//! The paper's Tables 1 and 2 for Lamé's cylinder (DESIGN.md §3), the check
//! of `[analytic] kind = "lame_cylinder"`: the stresses along a radius at the
//! paper's radii (Table 1, from the probes) and the contact normal stress on
//! the 45-degree cut (Table 2, interpolated between the pairs), theory
//! against each run, and for the paper's own cylinder (a = 3, b = 5, p = 0.1)
//! the paper's numbers beside them. `subcontact paper` prints them for the
//! paper's mesh and the default one side by side.

use std::fmt::Write;

use super::{Check, Lame, Solution};
use crate::fem::Analysis;

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

/// Contact sigma_n at radius r, interpolated linearly between the pairs
/// (None without contact, or off the pairs' span).
pub fn contact_sigma_n_at(sol: &Solution, r: f64) -> Option<f64> {
    let pairs = sol.pairs?;
    let mut pts: Vec<(f64, f64)> = sol
        .model
        .pairs
        .iter()
        .zip(pairs)
        .map(|(p, res)| {
            let x = sol.model.coords[p.k];
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

/// Stresses at the Table 1 radii from the first probe point there: (sigma_r, sigma_theta).
pub fn table1_values(sol: &Solution) -> Vec<Option<(f64, f64)>> {
    TABLE1_R
        .iter()
        .map(|&r| {
            sol.probed
                .iter()
                .find(|(x, _)| (x[0].hypot(x[1]) - r).abs() < 1e-6 * r)
                .map(|(x, s)| polar(sol.model.analysis, *x, s))
        })
        .collect()
}

fn pct(v: f64, exact: f64) -> String {
    format!("{:+.2} %", 100.0 * (v - exact) / exact.abs())
}

/// Table 1 and Table 2 of Lamé's cylinder `l` with one column group per run,
/// in units of 1e-2 MPa; the paper's values beside theory when `with_paper`.
/// Table 2 only when some run has contact.
pub fn tables(l: &Lame, runs: &[(&str, &Solution)], with_paper: bool) -> String {
    let mut s = String::new();
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
    if runs.iter().all(|(_, r)| r.pairs.is_none()) {
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

/// Whether `l` is the paper's cylinder (a = 3, b = 5, p = 0.1), whose
/// tables get the paper's own values beside this run's.
pub fn is_paper_cylinder(l: &Lame) -> bool {
    l.a == 3.0 && l.b == 5.0 && (l.p - 0.1).abs() < 1e-12
}

/// The tables of one run for report.md, and a word on the error norms
/// when the bodies' materials differ (see [`super::exact`]).
pub(super) fn check(l: &Lame, sol: &Solution) -> Check {
    let mut report = tables(l, &[("this run", sol)], is_paper_cylinder(l));
    if super::materials_differ(sol.model) {
        let _ = writeln!(
            report,
            "\nThe bodies have different materials: the error norms compare each body with Lamé's cylinder of its own E and nu, \
             which is the solution only where the bodies do not hold each other's radial displacement (free sliding along radial cuts), \
             not across a bonded change of material. The tables' sigma_r and sigma_theta do not depend on the material."
        );
    }
    Check { report, ..Default::default() }
}
