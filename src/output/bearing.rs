//! The bearing pressure ([`crate::recover::bearing`]) of every contact
//! group and of each of its block face pairs (a footing's pads), as the
//! outputs give it: `bearing.csv` (every one), summary.json's `bearing`
//! (every group, with its face pairs when it has at most
//! [`FACES_LISTED`]), and report.md's "Bearing pressure": for each base
//! (a group whose mean normal is within 30 degrees of the vertical, y in
//! 2D, z in 3D) the group and its pads with their forces, where they act,
//! and the pressures, so that a footing group's reaction per pad needs no
//! contact split by hand. With water in a group's joint the bearing is
//! the effective (solid-to-solid) stress's, and the total (effective plus
//! water) is given beside it ([`WATER_COLUMNS`]).

use std::fmt::Write;

use serde_json::json;

use super::faces::block_name;
use super::number::{clean, num};
use super::resultants::{self, Resultant};
use crate::contact::law::ContactState;
use crate::recover::bearing::{bearing, Bearing, BearingPair};
use crate::results::Run;

/// Face pairs listed per group in summary.json and report.md.
pub const FACES_LISTED: usize = 20;

/// The bearing of a contact group (`blocks` None) or of its face pair
/// between two blocks, with the resultant of its contact forces.
pub struct FaceBearing {
    pub contact: usize,
    pub blocks: Option<[usize; 2]>,
    pub bearing: Bearing,
    pub resultant: Resultant,
    /// With water in the group: the bearing of the total normal stress
    /// (effective plus water, `sigma_n' - u`, over the whole face: the
    /// water presses open parts too), and the water's force Σ u A.
    pub total: Option<(Bearing, f64)>,
}

/// Every group's bearing, each followed by its face pairs' (None without
/// contacts).
pub fn of_run(run: &Run) -> Option<Vec<FaceBearing>> {
    of(run, &resultants::of_run(run)?)
}

/// [`of_run`] from the run's resultants `r`.
pub fn of(run: &Run, r: &resultants::Resultants) -> Option<Vec<FaceBearing>> {
    let c = run.contact()?;
    let m = &run.model;
    let body = m.body_of_node();
    let plane = run.about.analysis.dim() == 2;
    let window = run.about.output.pressure_window;
    let record = |p: usize| BearingPair {
        x: m.coords[m.pairs[p].k],
        normal: c.frames[p][0],
        area: c.areas[p],
        sigma_n: c.pairs[p].sigma_n,
        open: c.states[p] == ContactState::Open,
    };
    let wet: Vec<bool> = (0..r.groups.len()).map(|g| m.water.iter().any(|w| w.contact == g)).collect();
    // the total (effective plus water) of a wet group's pairs
    let total = |ps: &[usize]| -> Option<(Bearing, f64)> {
        let pairs: Vec<BearingPair> =
            ps.iter().map(|&p| BearingPair { sigma_n: c.sigma_n_total(p), open: false, ..record(p) }).collect();
        Some((bearing(&pairs, plane, window)?, ps.iter().map(|&p| c.water_pressure(p) * c.areas[p]).sum()))
    };
    let mut out = Vec::new();
    for (g, group) in r.groups.iter().enumerate() {
        let of_group: Vec<usize> = (0..m.pairs.len()).filter(|&p| m.pairs[p].contact == g).collect();
        let pairs: Vec<BearingPair> = of_group.iter().map(|&p| record(p)).collect();
        let Some(b) = bearing(&pairs, plane, window) else { continue };
        let t = if wet[g] { total(&of_group) } else { None };
        out.push(FaceBearing { contact: g, blocks: None, bearing: b, resultant: *group, total: t });
        let faces: Vec<_> = r.faces.iter().filter(|f| f.contact == g).collect();
        if faces.len() < 2 {
            continue;
        }
        for f in faces {
            let ps: Vec<usize> =
                of_group.iter().copied().filter(|&p| [body[m.pairs[p].k], body[m.pairs[p].l]] == f.blocks).collect();
            let pairs: Vec<BearingPair> = ps.iter().map(|&p| record(p)).collect();
            if let Some(b) = bearing(&pairs, plane, window) {
                let t = if wet[g] { total(&ps) } else { None };
                out.push(FaceBearing {
                    contact: g,
                    blocks: Some(f.blocks),
                    bearing: b,
                    resultant: f.resultant,
                    total: t,
                });
            }
        }
    }
    Some(out)
}

/// "beam | ground", or "all" for a group.
fn face_name(run: &Run, f: &FaceBearing) -> String {
    match f.blocks {
        None => "all".into(),
        Some([a, b]) => format!("{} \\| {}", block_name(&run.model, a), block_name(&run.model, b)),
    }
}

/// The columns `bearing.csv` adds when a group has water in its joint:
/// the water's force Σ u A and the bearing of the total normal stress
/// (effective plus water); the columns before them are the effective
/// (solid-to-solid) stress's, as in a dry scene.
pub const WATER_COLUMNS: &str =
    "water_force,normal_force_total,x_p_total,y_p_total,z_p_total,e_1_total,e_2_total,p_max_total,p_mean_total,p_design_total";

/// `bearing.csv`: one row per group (empty blocks) and per face pair of a
/// group of several; with water in some group, [`WATER_COLUMNS`] after
/// the others (empty in a dry group's rows).
pub fn csv(run: &Run, all: &[FaceBearing]) -> String {
    let wet = all.iter().any(|f| f.total.is_some());
    let mut s = String::from("contact,block_i,block_ii,pairs,normal_force,shear_force,x_p,y_p,z_p,e_1,e_2,width_1,width_2,t1_x,t1_y,t1_z,area,contact_area,p_max,p_max_x,p_max_y,p_max_z,p_mean,p_design,window,in_kern");
    if wet {
        s = format!("{s},{WATER_COLUMNS}");
    }
    s.push('\n');
    let plane = run.about.analysis.dim() == 2;
    for f in all {
        let b = &f.bearing;
        let (bi, bii) = f.blocks.map_or((String::new(), String::new()), |[a, c]| (a.to_string(), c.to_string()));
        let nums: Vec<String> = [b.force, f.resultant.shear_force()]
            .iter()
            .chain(&b.at)
            .chain(&b.eccentricity)
            .chain(&b.widths)
            .chain(&b.axes[0])
            .chain(&[b.area, b.contact_area, b.max_pressure])
            .chain(&b.max_at)
            .chain(&[b.mean_pressure, b.design_pressure, b.window])
            .map(|v| format!("{v:.12e}"))
            .collect();
        let _ = write!(
            s,
            "{},{bi},{bii},{},{},{}",
            super::csv::csv_field(&run.model.interfaces[f.contact].name),
            b.pairs,
            nums.join(","),
            b.in_kern(plane)
        );
        if wet {
            s += &water_cells(f);
        }
        s.push('\n');
    }
    s
}

/// A row's [`WATER_COLUMNS`], each after a comma (empty when dry).
fn water_cells(f: &FaceBearing) -> String {
    let Some((t, water)) = &f.total else { return ",".repeat(WATER_COLUMNS.split(',').count()) };
    [*water, t.force]
        .iter()
        .chain(&t.at)
        .chain(&t.eccentricity)
        .chain(&[t.max_pressure, t.mean_pressure, t.design_pressure])
        .map(|v| format!(",{v:.12e}"))
        .collect()
}

/// summary.json's `bearing`: every group, with its face pairs when it has
/// at most [`FACES_LISTED`].
pub fn summary(run: &Run, all: &[FaceBearing]) -> serde_json::Value {
    let plane = run.about.analysis.dim() == 2;
    let one = |f: &FaceBearing| {
        let mut v = serde_json::to_value(&f.bearing).unwrap_or_default();
        v["shear_force"] = json!(f.resultant.shear_force());
        v["in_kern"] = json!(f.bearing.in_kern(plane));
        if plane {
            v["from_ends"] = json!(f.bearing.from_ends());
        }
        if let Some((t, water)) = &f.total {
            v["water_force"] = json!(water);
            v["total"] = serde_json::to_value(t).unwrap_or_default();
        }
        if let Some([a, b]) = f.blocks {
            v["block_i"] = json!(a);
            v["block_ii"] = json!(b);
            v["name_i"] = json!(block_name(&run.model, a));
            v["name_ii"] = json!(block_name(&run.model, b));
        }
        v
    };
    let groups: Vec<serde_json::Value> = all
        .iter()
        .filter(|f| f.blocks.is_none())
        .map(|g| {
            let mut v = one(g);
            v["contact"] = json!(run.model.interfaces[g.contact].name);
            let faces: Vec<&FaceBearing> =
                all.iter().filter(|f| f.contact == g.contact && f.blocks.is_some()).collect();
            v["face_pairs"] = json!(faces.len());
            if faces.len() <= FACES_LISTED {
                v["faces"] = json!(faces.into_iter().map(one).collect::<Vec<_>>());
            }
            v
        })
        .collect();
    json!(groups)
}

/// Whether a group is a base: its mean normal within 30 degrees of the
/// vertical (y in 2D, z in 3D).
fn is_base(b: &Bearing, plane: bool) -> bool {
    b.normal[if plane { 1 } else { 2 }].abs() >= 30f64.to_radians().cos()
}

/// report.md's "Bearing pressure" (empty without a base).
pub fn report(run: &Run, all: &[FaceBearing]) -> String {
    let plane = run.about.analysis.dim() == 2;
    let bases: Vec<&FaceBearing> = all.iter().filter(|f| f.blocks.is_none() && is_base(&f.bearing, plane)).collect();
    if bases.is_empty() {
        return String::new();
    }
    let t = run.about.thickness;
    let mut s = String::from("\n## Bearing pressure\n\n");
    let _ = writeln!(
        s,
        "Each base (a contact group whose mean normal is within 30 degrees of the vertical) and, where it has several, each block face pair (a footing's pads): the compressive normal force N and the shear force T on it, where N acts (the pressure's centroid), its eccentricity e about the face's centroid {}, the {} in contact, the largest pressure (a singular corner's value is kept here; the pictures scale by a robust range), the mean over the part in contact, and the design pressure: the largest mean over a window of the stated width{}. Pressure compression positive; totals over the thickness in a plane analysis.\n",
        if plane { "along the face (the middle third: |e| <= B/6)" } else { "along t1 and t2 (the kern of a rectangle: |e1|/B1 + |e2|/B2 <= 1/6)" },
        if plane { "length" } else { "area" },
        if run.about.output.pressure_window.is_some() { " (`[output] pressure_window`)" } else { " (a tenth of the face's width unless `[output] pressure_window` says)" },
    );
    for g in bases {
        let name = &run.model.interfaces[g.contact].name;
        let b = &g.bearing;
        let axes = if plane {
            format!(
                "t = ({}, {}), from ({}) to ({})",
                num(b.axes[0][0]),
                num(b.axes[0][1]),
                point(b.ends[0], 2),
                point(b.ends[1], 2)
            )
        } else {
            format!("t1 = {}, t2 = {}", point(b.axes[0], 3), point(b.axes[1], 3))
        };
        let _ = writeln!(s, "### `{name}`\n\nAxes: {axes}.\n");
        if plane {
            let _ = writeln!(s, "| face | N | T | acts at | e (B/6) | from the ends | contact length / B | p max (at) | p mean | p over d (d) |\n|---|---|---|---|---|---|---|---|---|---|");
        } else {
            let _ = writeln!(s, "| face | N | T | acts at | e1, e2 (B1, B2) | in kern | area in contact / area | p max (at) | p mean | p over d (d) |\n|---|---|---|---|---|---|---|---|---|---|");
        }
        let faces = all.iter().filter(|f| f.contact == g.contact && f.blocks.is_some()).take(FACES_LISTED);
        for f in std::iter::once(g).chain(faces) {
            let _ = writeln!(s, "{}", row(run, f, plane, t));
        }
        let more = all.iter().filter(|f| f.contact == g.contact && f.blocks.is_some()).count();
        if more > FACES_LISTED {
            let _ = writeln!(s, "\n{FACES_LISTED} of its {more} face pairs; all in `bearing.csv`.");
        }
        if let Some((t, water)) = &g.total {
            let dim = if plane { 2 } else { 3 };
            let _ = writeln!(
                s,
                "\nWith water in the joint, N and the pressures above are the effective ones (solid to solid). The water pushes the faces apart with U = {}; the total normal force N + U = {} acts at ({}), e = {}; total pressure (effective plus water) largest {}, mean {}, over d {}. All in `bearing.csv`'s `*_total` columns.",
                num(*water),
                num(t.force),
                point(t.at, dim),
                t.eccentricity[..dim - 1].iter().map(|&e| num(clean(e, t.widths[0]))).collect::<Vec<_>>().join(", "),
                num(t.max_pressure),
                num(t.mean_pressure),
                num(t.design_pressure)
            );
        }
        s.push('\n');
    }
    s
}

/// One face's row of the table.
fn row(run: &Run, f: &FaceBearing, plane: bool, thickness: f64) -> String {
    let b = &f.bearing;
    let dim = if plane { 2 } else { 3 };
    let common = format!(
        "| {} | {} | {} | ({}) |",
        face_name(run, f),
        num(b.force),
        num(clean(f.resultant.shear_force(), b.force)),
        point(b.at, dim)
    );
    let pressures = format!(
        "{} ({}) | {} | {} ({}) |",
        num(b.max_pressure),
        point(b.max_at, dim),
        num(b.mean_pressure),
        num(b.design_pressure),
        num(b.window)
    );
    if plane {
        let ends = b.from_ends();
        format!(
            "{common} {} ({}) | {}, {} | {} / {} | {pressures}",
            num(clean(b.eccentricity[0], b.widths[0])),
            num(b.widths[0] / 6.0),
            num(ends[0]),
            num(ends[1]),
            num(b.contact_area / thickness),
            num(b.widths[0])
        )
    } else {
        format!(
            "{common} {}, {} ({}, {}) | {} | {} / {} | {pressures}",
            num(clean(b.eccentricity[0], b.widths[0])),
            num(clean(b.eccentricity[1], b.widths[1])),
            num(b.widths[0]),
            num(b.widths[1]),
            if b.in_kern(false) { "yes" } else { "no" },
            num(b.contact_area),
            num(b.area)
        )
    }
}

fn point(x: [f64; 3], dim: usize) -> String {
    x[..dim].iter().map(|&v| num(v)).collect::<Vec<_>>().join(", ")
}
