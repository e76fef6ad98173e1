//! The section forces of `[[sections]]` ([`crate::recover::sections`]) as
//! people read them: `sections.csv` (one row per cut), summary.json's
//! `sections`, report.md's "Section forces" and, for a beam or ring cut at
//! several stations, `section_<name>.svg` (N, V and M along it; skipped
//! with a warning when it cannot be drawn, [`pictures`]).

use std::fmt::Write;

use super::csv::csv_field;
use super::number::{clean, num};
use super::picture::{Drawn, PictureError};
use super::plot::{self, Panel, Series};
use crate::recover::sections::{SectionForces, Sides, Station};
use crate::results::Run;

/// The cut's resultants as (name, value) in the analysis's components.
fn values(s: &Station, dim: usize) -> Vec<(&'static str, f64)> {
    if dim == 2 {
        vec![("N", s.n()), ("V", s.v()), ("M", s.m())]
    } else {
        vec![("N", s.n()), ("V2", s.v()), ("V3", s.v3()), ("T", s.t()), ("M2", s.m2()), ("M3", s.m())]
    }
}

/// What `position` means for a section of `kind`.
fn position_label(kind: &str) -> &'static str {
    match kind {
        "ring" => "angle (deg)",
        "beam" => "distance along the axis",
        _ => "position",
    }
}

/// `sections.csv`: one row per cut (None without sections).
pub fn csv(run: &Run) -> Option<String> {
    let secs = &run.checks.sections;
    if secs.is_empty() {
        return None;
    }
    let dim = run.about.analysis.dim();
    let names: Vec<&str> = values(&dummy(), dim).iter().map(|v| v.0).collect();
    let mut s =
        format!("section,kind,station,position,x,y,z,n_x,n_y,n_z,e2_x,e2_y,e2_z,depth,sides,{}\n", names.join(","));
    for sec in secs {
        for (i, st) in sec.stations.iter().enumerate() {
            let nums: Vec<String> = [st.position]
                .iter()
                .chain(&st.at)
                .chain(&st.frame[0])
                .chain(&st.frame[1])
                .chain(std::iter::once(&st.depth))
                .map(|v| format!("{v:.12e}"))
                .collect();
            let vals: Vec<String> = values(st, dim).iter().map(|v| format!("{:.12e}", v.1)).collect();
            let _ = writeln!(
                s,
                "{},{},{i},{},{},{}",
                csv_field(&sec.name),
                sec.kind,
                nums.join(","),
                sides(st.sides),
                vals.join(",")
            );
        }
    }
    Some(s)
}

/// The CSV word of [`Sides`].
fn sides(s: Sides) -> &'static str {
    match s {
        Sides::Both => "both",
        Sides::End => "end",
        Sides::Symmetry => "symmetry",
    }
}

fn dummy() -> Station {
    Station {
        position: 0.0,
        at: [0.0; 3],
        frame: [[0.0; 3]; 3],
        force: [0.0; 3],
        moment: [0.0; 3],
        depth: 0.0,
        sides: Sides::Both,
    }
}

/// summary.json's `sections` (None without sections).
pub fn summary(run: &Run) -> Option<serde_json::Value> {
    let secs = &run.checks.sections;
    if secs.is_empty() {
        return None;
    }
    let dim = run.about.analysis.dim();
    let one = |sec: &SectionForces| {
        let stations: Vec<serde_json::Value> = sec
            .stations
            .iter()
            .map(|st| {
                let mut v = serde_json::json!({ "position": st.position, "at": st.at, "normal": st.frame[0],
                    "e2": st.frame[1], "depth": st.depth, "sides": st.sides, "force": st.force, "moment": st.moment });
                for (k, x) in values(st, dim) {
                    v[k] = x.into();
                }
                v
            })
            .collect();
        serde_json::json!({ "name": sec.name, "kind": sec.kind, "missed": sec.missed, "stations": stations })
    };
    Some(serde_json::Value::Array(secs.iter().map(one).collect()))
}

/// The pictures of the sections cut along a beam or round a ring, through
/// the pictures' skip-on-failure path: one that cannot be drawn (fewer
/// than two of its cuts meet the body, or they all lie at one place) is
/// left out with a warning, every other file written. A line or plane is
/// one cut: its forces are in the tables alone.
pub fn pictures(run: &Run, drawn: &mut Drawn) {
    let dim = run.about.analysis.dim();
    for sec in run.checks.sections.iter().filter(|s| along(s)) {
        drawn.draw(&file(sec), || picture(dim, sec));
    }
}

/// Whether a section is cut at stations along a member (a beam or ring).
fn along(sec: &SectionForces) -> bool {
    matches!(sec.kind, "beam" | "ring")
}

/// Why a section along a member has no picture (None: it can be drawn).
fn undrawable(sec: &SectionForces) -> Option<String> {
    let n = sec.stations.len();
    let all = n + sec.missed;
    if n < 2 {
        return Some(format!(
            "section `{}`: {n} of its {all} cuts meet{} its body, and a diagram along it needs two: check the body and `stations`",
            sec.name,
            if n == 1 { "s" } else { "" }
        ));
    }
    let (lo, hi) = sec
        .stations
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), st| (lo.min(st.position), hi.max(st.position)));
    let span = hi - lo;
    if !(span.is_finite() && span > 1e-12 * hi.abs().max(lo.abs())) {
        return Some(format!(
            "section `{}`: its {n} cuts all lie at one place, so there is nothing to draw along it",
            sec.name
        ));
    }
    None
}

/// The picture of a section cut at several stations: N, V and M along it.
pub fn picture(dim: usize, sec: &SectionForces) -> Result<Vec<u8>, PictureError> {
    if let Some(why) = undrawable(sec) {
        return Err(PictureError::Empty(why));
    }
    let series = |k: usize| {
        let name = values(&sec.stations[0], dim)[k].0;
        let points = sec.stations.iter().map(|st| (st.position, values(st, dim)[k].1)).collect();
        [Series { label: name.to_string(), points }]
    };
    let (n, v, m) = (series(0), series(1), series(dim * 3 - 4));
    let x = position_label(sec.kind);
    let title = |what: &str| format!("{} ({what})", sec.name);
    let (tn, tv, tm) = (title("normal force, tension +"), title("shear force"), title("bending moment"));
    let panels = [
        Panel { title: &tn, x_label: x, y_label: "N", log_x: false, log_y: false, series: &n },
        Panel { title: &tv, x_label: x, y_label: "V", log_x: false, log_y: false, series: &v },
        Panel { title: &tm, x_label: x, y_label: "M", log_x: false, log_y: false, series: &m },
    ];
    Ok(plot::svg(&panels, 420, 320)?.into_bytes())
}

/// The picture's file name.
pub fn file(sec: &SectionForces) -> String {
    format!("section_{}.svg", sec.name.replace([' ', '/', '\\'], "_"))
}

/// report.md's section (empty without sections).
pub fn report(run: &Run) -> String {
    let secs = &run.checks.sections;
    if secs.is_empty() {
        return String::new();
    }
    let dim = run.about.analysis.dim();
    let mut s = String::from("\n## Section forces\n\n");
    let _ = writeln!(
        s,
        "The force and moment that the material behind each cut (its -n side) receives from the material ahead of it, from the cells' nodal forces (their stresses at the integration points), totals over the thickness in a plane analysis{}. N is tension positive; V and M follow the beam convention for a cut whose n runs along the member and e2 up through it (M > 0 sagging: tension at -e2); a ring's n runs round it and e2 inward, so N = -thrust and M > 0 puts the outer fibre in tension. Moments about the middle of the cut across the member.\n",
        if run.steps.len() > 1 { ", at the last load step" } else { "" }
    );
    for sec in secs {
        let _ = writeln!(s, "### `{}` ({})\n", sec.name, describe(sec));
        if sec.stations.is_empty() {
            let _ = writeln!(s, "The cut meets no cell of its bodies: check where it lies.\n");
            continue;
        }
        let vals = values(&sec.stations[0], dim);
        let scale = sec.stations.iter().flat_map(|st| values(st, dim)).fold(0.0, |a: f64, v| a.max(v.1.abs()));
        let head: Vec<&str> = vals.iter().map(|v| v.0).collect();
        let _ = writeln!(
            s,
            "| {} | at | depth | {} |\n|---|---|---|{}",
            position_label(sec.kind),
            head.join(" | "),
            "---|".repeat(head.len())
        );
        for st in &sec.stations {
            let row: Vec<String> = values(st, dim).iter().map(|v| num(clean(v.1, scale))).collect();
            let at: Vec<String> = st.at[..dim].iter().map(|&v| num(v)).collect();
            let side = match st.sides {
                Sides::Both => "",
                Sides::End => " (end)",
                Sides::Symmetry => " (symmetry)",
            };
            let _ = writeln!(
                s,
                "| {}{side} | ({}) | {} | {} |",
                num(clean(st.position, 1.0)),
                at.join(", "),
                num(st.depth),
                row.join(" | ")
            );
        }
        if sec.missed > 0 {
            let _ = writeln!(s, "\n{} of its cuts meet no cell.", sec.missed);
        }
        if along(sec) && undrawable(sec).is_none() {
            let _ = writeln!(s, "\n![N, V and M along `{}`]({})", sec.name, file(sec));
        }
        s.push('\n');
    }
    s
}

/// "a ring of 13 cuts" and the like.
fn describe(sec: &SectionForces) -> String {
    let n = sec.stations.len() + sec.missed;
    match sec.kind {
        "ring" => format!("a ring cut at {n} angles"),
        "beam" => format!("a beam cut at {n} stations"),
        "plane" => "a plane cut".into(),
        _ => "a line across the member".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(position: f64, m: f64) -> Station {
        let mut st = dummy();
        st.position = position;
        st.frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        st.moment = [0.0, 0.0, m];
        st
    }

    fn beam(name: &str, stations: Vec<Station>, missed: usize) -> SectionForces {
        SectionForces { name: name.into(), kind: "beam", stations, missed }
    }

    /// A beam cut at one point, and one whose cuts all lie at one place,
    /// are skipped with a warning naming them; a good one beside them is
    /// drawn.
    #[test]
    fn an_odd_section_is_skipped_with_a_warning_and_the_rest_drawn() {
        let secs = [
            beam("good", vec![at(0.0, 0.0), at(1.0, 2.0), at(2.0, 0.0)], 0),
            beam("one point", vec![at(0.5, 1.0)], 24),
            beam("no length", vec![at(3.0, 1.0), at(3.0, 1.0)], 0),
        ];
        let mut d = Drawn::default();
        for sec in &secs {
            d.draw(&file(sec), || picture(2, sec));
        }
        let drawn: Vec<&str> = d.files.iter().map(|f| f.0.as_str()).collect();
        assert_eq!(drawn, ["section_good.svg"]);
        assert_eq!(d.skipped.len(), 2, "{:?}", d.skipped);
        assert!(
            d.skipped[0].starts_with("section_one_point.svg was not drawn")
                && d.skipped[0].contains("1 of its 25 cuts")
        );
        assert!(d.skipped[1].contains("section `no length`") && d.skipped[1].contains("at one place"));
        assert!(d.skipped.iter().all(|w| w.contains("the other result files are written")));
    }
}
