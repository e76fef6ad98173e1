//! The closed forms' checks in words: what `analytic` computes against
//! the scene's `[analytic]`, written as report.md sections and summary.json
//! entries, and the paper's Tables 1 and 2 of `subcontact paper`.
//!
//! For Lamé's cylinder, the paper's tables (units of 1e-2 MPa), theory
//! against each run, the paper's numbers beside them for the paper's own
//! cylinder. For the lined tunnel, its data and coefficients, thrust and
//! moment against the thin ring angle by angle, the largest differences,
//! and what those differences are made of besides the model's error.

use std::fmt::Write;

use serde_json::json;

use super::number::sig;
use crate::analytic::lining::{Comparison, TunnelCheck, STEP_DEG, THICKNESS_POINTS};
use crate::analytic::paper_tables::{self as paper, CylinderCheck, Tables};
use crate::analytic::{Analytic, Check, Lame, LinedTunnel, TunnelSlip};

/// The tables' unit: stresses in 1e-2 MPa.
const UNIT: f64 = 100.0;

/// What the model's departure from the closed form is called and what the
/// closed form assumes, for report.md's labels: an "error" where the closed
/// form solves the model's problem exactly, a "difference" where it
/// idealises it (a thin ring in an infinite plane against a thick lining in
/// a finite box).
pub fn labels(analytic: &Analytic) -> (&'static str, &'static str) {
    match analytic {
        Analytic::LameCylinder { .. } => ("error", "Lamé's thick-walled cylinder (exact plane elasticity)"),
        Analytic::LinedTunnel(_) => ("difference", "Einstein & Schwartz's thin ring in an infinite elastic plane"),
    }
}

/// The check's sections of report.md (empty without a check).
pub fn report(check: &Check) -> String {
    match check {
        Check::None => String::new(),
        Check::Cylinder(c) => cylinder_report(c),
        Check::Tunnel(t) => tunnel_report(t),
    }
}

/// The check's entries of summary.json: the lining's comparison.
pub fn summary(check: &Check) -> serde_json::Map<String, serde_json::Value> {
    let mut map = serde_json::Map::new();
    if let Check::Tunnel(TunnelCheck { comparison: Some(c), .. }) = check {
        map.insert("lining".into(), lining_summary(c));
    }
    map
}

/// The tables of one run, and a word on the error norms when the bodies'
/// materials differ.
fn cylinder_report(c: &CylinderCheck) -> String {
    let mut report = paper_tables(&c.lame, &[("this run", &c.tables)], c.with_paper);
    if c.materials_differ {
        let _ = writeln!(
            report,
            "\nThe bodies have different materials: the error norms compare each body with Lamé's cylinder of its own E and nu, \
             which is the solution only where the bodies do not hold each other's radial displacement (free sliding along radial cuts), \
             not across a bonded change of material. The tables' sigma_r and sigma_theta do not depend on the material."
        );
    }
    report
}

fn pct(v: f64, exact: f64) -> String {
    format!("{:+.2} %", 100.0 * (v - exact) / exact.abs())
}

/// A column group's header and rule: the paper's column when `with_paper`,
/// then one per run, each with its error.
fn group_columns(runs: &[(&str, &Tables)], with_paper: bool) -> (String, String) {
    let (mut head, mut rule) = (String::new(), String::new());
    if with_paper {
        head += " paper | error |";
        rule += "---|---|";
    }
    for (name, _) in runs {
        head += &format!(" {name} | error |");
        rule += "---|---|";
    }
    (head, rule)
}

/// A column group's cells in one row: theory, the paper's value and the
/// runs' values (in MPa), each with its error against theory.
fn group_cells(theory: f64, paper: Option<f64>, values: impl Iterator<Item = Option<f64>>) -> String {
    let mut row = format!(" {theory:.2} |");
    if let Some(p) = paper {
        row += &format!(" {p:.2} | {} |", pct(p, theory));
    }
    for v in values {
        row += &match v {
            Some(a) => format!(" {:.3} | {} |", a * UNIT, pct(a * UNIT, theory)),
            None => " – | – |".into(),
        };
    }
    row
}

/// Table 1 and Table 2 of Lamé's cylinder `l` with one column group per run,
/// in units of 1e-2 MPa; the paper's values beside theory when `with_paper`.
/// Table 2 only when some run has contact.
pub fn paper_tables(l: &Lame, runs: &[(&str, &Tables)], with_paper: bool) -> String {
    let mut s = table1(l, runs, with_paper);
    if runs.iter().any(|(_, t)| t.table2.is_some()) {
        s += &table2(l, runs, with_paper);
    }
    s
}

/// Table 1: sigma_r and sigma_theta along a radius.
fn table1(l: &Lame, runs: &[(&str, &Tables)], with_paper: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Table 1: stresses along a radius (1e-2 MPa)\n");
    let (head, rule) = group_columns(runs, with_paper);
    let _ = writeln!(s, "| r (m) | sigma_r theory |{head} sigma_theta theory |{head}\n|---|---|{rule}---|{rule}");
    for (i, &r) in paper::TABLE1_R.iter().enumerate() {
        let (sr, st) = (l.sigma_r(r) * UNIT, l.sigma_theta(r) * UNIT);
        let paper = |v: [f64; 5]| with_paper.then_some(v[i]);
        let values = |f: fn((f64, f64)) -> f64| runs.iter().map(move |(_, t)| t.table1[i].map(f));
        let _ = writeln!(
            s,
            "| {r:.1} |{}{}",
            group_cells(sr, paper(paper::TABLE1_SR_PAPER), values(|v| v.0)),
            group_cells(st, paper(paper::TABLE1_ST_PAPER), values(|v| v.1))
        );
    }
    s
}

/// Table 2: the contact normal stress on the 45-degree cut.
fn table2(l: &Lame, runs: &[(&str, &Tables)], with_paper: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Table 2: contact normal stress on the 45-degree cut (1e-2 MPa)\n");
    let (head, rule) = group_columns(runs, with_paper);
    let _ = writeln!(s, "| r (m) | theory (sigma_theta) |{head}\n|---|---|{rule}");
    for (i, &r) in paper::TABLE2_R.iter().enumerate() {
        let values = runs.iter().map(|(_, t)| t.table2.as_ref().and_then(|v| v[i]));
        let cells = group_cells(l.sigma_theta(r) * UNIT, with_paper.then_some(paper::TABLE2_PAPER[i]), values);
        let _ = writeln!(s, "| {r:.1} |{cells}");
    }
    s
}

/// summary.json's `lining`: the errors, their scales and the rows.
fn lining_summary(c: &Comparison) -> serde_json::Value {
    json!({
        "thrust_error": c.thrust_error, "moment_error": c.moment_error,
        "published_moment_error": c.published_moment_error, "displacement_error": c.displacement_error,
        "thrust_scale": c.thrust_scale, "moment_scale": c.moment_scale,
        "rows": c.rows.iter().map(|r| json!({ "theta_deg": r.theta_deg, "thrust": r.thrust, "thrust_theory": r.thrust_theory,
            "moment": r.moment, "moment_theory": r.moment_theory })).collect::<Vec<_>>(),
    })
}

/// The lining's section: the tunnel's data, the table against theory (or
/// why there is none) and, with a table, the caveat on its differences.
fn tunnel_report(t: &TunnelCheck) -> String {
    let tu = &t.tunnel;
    let mut s = tunnel_data(tu);
    let Some(c) = &t.comparison else {
        let (ri, ro) = tu.lining_radii();
        let _ = writeln!(s, "The lining body `{}` covers none of the angles 0, {STEP_DEG}, ... degrees between r = {ri} and {ro}: check radius and thickness in [analytic].", tu.lining.group);
        return s;
    };
    s += &lining_table(c);
    s += &caveat(tu, t.reach);
    s
}

/// The section's title, the tunnel's data, its coefficients and what the
/// table compares.
fn tunnel_data(tu: &LinedTunnel) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\n## Lining: thrust and moment against Einstein & Schwartz (1979), a thin ring in an infinite elastic plane\n"
    );
    let co = tu.coefficients();
    let (ri, ro) = tu.lining_radii();
    let _ = writeln!(
        s,
        "Lining `{}` (E = {}, nu = {}) in ground `{}` (E = {}, nu = {}); middle-surface radius R = {}, thickness t = {} (r = {} .. {}); far field P = {} (vertical), K P = {} (horizontal); interface: {}.",
        tu.lining.group,
        tu.lining.e,
        tu.lining.nu,
        tu.ground.group,
        tu.ground.e,
        tu.ground.nu,
        tu.radius,
        tu.thickness,
        ri,
        ro,
        tu.p,
        tu.k * tu.p,
        match tu.slip {
            TunnelSlip::None => "no slip (bonded)",
            TunnelSlip::Full => "full slip (no shear)",
        }
    );
    let _ = writeln!(
        s,
        "C* = {:.5}, F* = {:.5}, a0* = {:.6}, a2* = {:.6}{}.",
        co.c,
        co.f,
        co.a0,
        co.a2,
        co.b2.map(|b| format!(", b2* = {b:.6}")).unwrap_or_default()
    );
    let (_, _, m2) = tu.modes();
    let m0 = tu.uniform_moment();
    let _ = writeln!(
        s,
        "\nThrust T (compression positive) and moment M about the middle surface (positive: tension on the outer fibre) per unit length; theta from the springline (+x) towards the crown (+y). FE: the hoop stress integrated through the thickness at {THICKNESS_POINTS} Gauss points. Theory: T as published; M = M0 + M2 cos 2theta, the published M2 = {m2:.5} plus the uniform moment M0 = T0 R I/(A R^2 + I) = {m0:.5} of the same thin ring (its curvature change under the uniform shortening, which the published formula leaves out). Errors relative to the largest |T| and |M| of the theory.\n"
    );
    s
}

/// Thrust and moment against the thin ring angle by angle, and the largest
/// differences.
fn lining_table(c: &Comparison) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| theta (deg) | T FE | T thin ring | FE - thin ring | M FE | M thin ring | FE - thin ring |\n|---|---|---|---|---|---|---|"
    );
    for r in &c.rows {
        let _ = writeln!(
            s,
            "| {:.1} | {:.5} | {:.5} | {:+.2} % | {:.5} | {:.5} | {:+.2} % |",
            r.theta_deg,
            r.thrust,
            r.thrust_theory,
            100.0 * (r.thrust - r.thrust_theory) / c.thrust_scale,
            r.moment,
            r.moment_theory,
            100.0 * (r.moment - r.moment_theory) / c.moment_scale.max(f64::MIN_POSITIVE)
        );
    }
    let _ = writeln!(
        s,
        "\nLargest difference from the thin ring: thrust {:.2} % of max |T| = {:.5}, moment {:.2} % of max |M| = {:.5}.",
        100.0 * c.thrust_error,
        c.thrust_scale,
        100.0 * c.moment_error,
        c.moment_scale
    );
    let _ = writeln!(
        s,
        "Against the published moment M2 cos 2theta alone: {:.2} % of |M2|.",
        100.0 * c.published_moment_error
    );
    let _ = writeln!(
        s,
        "Displacement of the lining's middle surface against the thin ring's: largest difference {:.2} % of max |u|. (The displacement L2 difference above covers the whole block, whose far part departs from the closed form's infinite plane.)",
        100.0 * c.displacement_error
    );
    s
}

/// What the comparison's differences are made of besides the model's own
/// error: the closed form's thin ring (`t/R`) and infinite plane (the
/// model reaching `reach` from the centre).
fn caveat(tu: &LinedTunnel, reach: f64) -> String {
    let ratio = tu.thickness / tu.radius;
    format!(
        "\nThe differences are not the model's error alone: Einstein & Schwartz's ring is thin (its thrust and moment act on the middle surface, the ring's own shear and thickness are left out), and this lining has t/R = {}{}; their ground is an infinite plane, and this model's reaches {} R from the centre (its boundary stiffens or softens the ground by an amount that falls with the distance). A difference of the order of t/R is the closed form's, not the mesh's.\n",
        sig(ratio, 3),
        if ratio > 0.05 { ", beyond the thin ring's range (t/R well below 0.05)" } else { "" },
        sig(reach / tu.radius, 3),
    )
}
