//! The water in the joints as report.md and summary.json give it: per
//! contact group with water, how its pressure is given, the factor it had
//! at the last load step, its largest pressure, its uplift U (the water's
//! force pushing the faces apart, [`super::resultants`]) and, for a joint
//! whose cracks fill, how far the crack from its face reaches.

use std::fmt::Write;

use serde_json::json;

use crate::contact::water::Water;
use crate::model::water::{Crack, Field};
use crate::results::{ContactRun, Run};

/// One group's water at the last load step.
struct Row {
    name: String,
    given: String,
    factor: f64,
    max_pressure: f64,
    uplift: f64,
    /// Whether its cracks fill from a face, and how far one has in each
    /// sheet that has one (with the sheet's normal), farthest first.
    fills: bool,
    cracks: Vec<(Crack, [f64; 3])>,
}

fn rows(run: &Run) -> Vec<Row> {
    let (m, Some(c)) = (&run.model, run.contact()) else { return Vec::new() };
    let Some(water) = Water::new(m) else { return Vec::new() };
    let cracks = water.cracks(&c.states);
    let last = run.last();
    let groups = super::resultants::of_run(run).map(|r| r.groups).unwrap_or_default();
    (m.water.iter().zip(cracks))
        .map(|(w, crack)| {
            let height = ["x", "y", "z"][w.vertical];
            let given = match &w.field {
                Field::Uniform(u) => format!("uniform u = {u}"),
                Field::Plane { unit_weight, plane, .. } => {
                    let y = if w.vertical == 2 { format!(" + {} y", plane[2]) } else { String::new() };
                    format!("u = {unit_weight} (h - {height}), h = {} + {} x{y}", plane[0], plane[1])
                }
                Field::Level { unit_weight, along, diagram } => {
                    let pts: Vec<String> = diagram.points.iter().map(|p| format!("({}, {})", p[0], p[1])).collect();
                    let level = if pts.len() == 1 {
                        format!("level {}", diagram.points[0][1])
                    } else {
                        format!("levels (s, h) {}", pts.join(", "))
                    };
                    let drain = diagram
                        .drain
                        .map_or(String::new(), |d| format!(", drain at s = {} of efficiency {}", d.at, d.efficiency));
                    format!(
                        "u = {unit_weight} (h - {}), {level}{drain}, s = x . ({:.3}, {:.3}, {:.3})",
                        ["x", "y", "z"][w.vertical],
                        along[0],
                        along[1],
                        along[2]
                    )
                }
            };
            let name = m.interfaces[w.contact].name.clone();
            let max_pressure = pressures(m, c, w.contact).fold(0.0, f64::max);
            let uplift = groups.get(w.contact).map_or(0.0, |g| g.uplift());
            let mut cracks: Vec<(Crack, [f64; 3])> = (crack.into_iter().zip(w.fill.iter().flat_map(|f| &f.sheets)))
                .filter_map(|(c, sheet)| c.map(|c| (c, sheet.normal)))
                .collect();
            cracks.sort_by(|a, b| b.0.tip.total_cmp(&a.0.tip));
            Row {
                name,
                given,
                factor: last.case_factors[w.case],
                max_pressure,
                uplift,
                fills: w.fill.is_some(),
                cracks,
            }
        })
        .collect()
}

fn pressures<'a>(m: &'a crate::model::Model, c: &'a ContactRun, contact: usize) -> impl Iterator<Item = f64> + 'a {
    (0..m.pairs.len()).filter(move |&p| m.pairs[p].contact == contact).map(|p| c.water_pressure(p))
}

/// report.md's section on the water in the joints (empty when dry).
pub fn report(run: &Run) -> String {
    let rows = rows(run);
    if rows.is_empty() {
        return String::new();
    }
    let mut s = String::from("\n## Water in the joints\n\n");
    let _ = writeln!(s, "The water pressure u acts on both faces of every pair, open ones too, pushing them apart; the law judges the effective normal stress sigma_n' = sigma_n + u (tension positive). contact.csv gives `sigma_n` (total), `water_pressure` and `sigma_n_eff`; U is the water's force pushing the faces apart. At the last load step:\n");
    let _ = writeln!(s, "| contact | water | factor | largest u | U | crack filled from the face |");
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for r in rows {
        let crack = match (r.cracks.as_slice(), r.fills) {
            ([(c, _)], _) => format!("to s = {:.4} (level {})", c.tip, c.level),
            ([], true) => "none open".into(),
            ([], false) => "–".into(),
            (many, _) => {
                let each: Vec<String> = (many.iter())
                    .map(|(c, n)| {
                        format!("to s = {:.4} on the sheet of normal ({:.3}, {:.3}, {:.3})", c.tip, n[0], n[1], n[2])
                    })
                    .collect();
                format!("{} (level {})", each.join("; "), many[0].0.level)
            }
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4e} | {:.4e} | {crack} |",
            r.name, r.given, r.factor, r.max_pressure, r.uplift
        );
    }
    s
}

/// summary.json's `water` (None when dry).
pub fn summary(run: &Run) -> Option<serde_json::Value> {
    let rows = rows(run);
    (!rows.is_empty()).then(|| {
        json!(rows
            .iter()
            .map(|r| json!({
                "contact": r.name,
                "water": r.given,
                "factor": r.factor,
                "max_pressure": r.max_pressure,
                "uplift": r.uplift,
                "crack_tip": r.cracks.first().map(|c| c.0.tip),
                "cracks": r.cracks.iter().map(|(c, n)| json!({ "tip": c.tip, "normal": n })).collect::<Vec<_>>(),
            }))
            .collect::<Vec<_>>())
    })
}
