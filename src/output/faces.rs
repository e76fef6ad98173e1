//! The contact resultants ([`super::resultants`]) as the outputs give them:
//! `faces.csv` (one row per block face pair, every one), summary.json's
//! `contact.groups` (every group) and `contact.faces` (the count and the
//! most mobilised face pairs), and report.md's two tables: every contact
//! group, and the [`MOST_FACES`] most mobilised face pairs that matter, so
//! that the report stays readable with hundreds of blocks. Ranked by the
//! largest mobilised friction away from supported nodes, leaving out
//! slivers and faces held by supports at every pair
//! ([`Resultants::left_out`]), each with its reason in faces.csv.
//!
//! Where a joint meets a support, a pair with a supported node carries
//! only what the contact takes: the support takes the rest (both copies
//! of a pair on the fixed base are held). A face's force is what its
//! contact pairs carry, so a face touching a support reads less than the
//! joint transmits by the blocks' equilibrium (CalculiX's contact forces,
//! on the 64-block rock mass: 1.11 times ours on the vertical faces at the
//! fixed base, a median 0.15 % apart elsewhere); `supported_pairs` counts
//! such pairs.

use std::fmt::Write;

use serde_json::json;

use super::resultants::{FacePair, LeftOut, Resultant, Resultants, SLIVER};
use crate::contact::law::Stiffness;
use crate::model::Model;
use crate::results::Run;

/// Face pairs in report.md's table and summary.json's `most_mobilised`.
pub const MOST_FACES: usize = 20;

/// A block as the tables name it: its body group, and its number when the
/// group is cut into several blocks (`rock #3`), as `Body::label` counts.
pub fn block_name(model: &Model, b: usize) -> String {
    let body = &model.bodies[b];
    match body.block {
        Some(k) => format!("{} #{}", body.name, k.index + 1),
        None => body.name.clone(),
    }
}

/// `faces.csv`: one row per face pair. Blocks as contact.csv's `block_i`,
/// `block_ii` (the VTU's cell data `block`), then named; the face's centre
/// and mean normal, its areas, the resultant on side I (global), N and T
/// in the mean frame, the largest mobilised friction and where, and the
/// uplift U of the water in the joint (0 when dry).
pub fn faces_csv(model: &Model, r: &Resultants) -> String {
    let mut s = String::from(
        "contact,block_i,block_ii,name_i,name_ii,pairs,x,y,z,n_x,n_y,n_z,area,area_stick,area_slip,area_open,f_x,f_y,f_z,normal_force,shear_force,mobilised_max,mobilised_x,mobilised_y,mobilised_z,uplift,supported_pairs,mobilised_unsupported,ranked\n",
    );
    for (f, out) in r.faces.iter().zip(r.left_out()) {
        let q = &f.resultant;
        let numbers: Vec<String> = (q.centre.iter().chain(&q.normal))
            .chain(&[q.area(), q.areas[2], q.areas[1], q.areas[0]])
            .chain(&q.force)
            .chain(&[q.normal_force(), q.shear_force(), q.mobilised])
            .chain(&q.mobilised_at)
            .chain(&[q.uplift()])
            .map(|v| format!("{v:.12e}"))
            .collect();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{:.12e},{}",
            super::csv_field(&model.interfaces[f.contact].name),
            f.blocks[0],
            f.blocks[1],
            super::csv_field(&block_name(model, f.blocks[0])),
            super::csv_field(&block_name(model, f.blocks[1])),
            q.pairs,
            numbers.join(","),
            q.supported,
            q.mobilised_free,
            out.map_or("yes", LeftOut::key)
        );
    }
    s
}

fn resultant_json(q: &Resultant) -> serde_json::Value {
    json!({
        "pairs": q.pairs,
        "area": { "total": q.area(), "stick": q.areas[2], "slip": q.areas[1], "open": q.areas[0] },
        "centre": q.centre,
        "normal": q.normal,
        "force": q.force,
        "normal_force": q.normal_force(),
        "shear_force": q.shear_force(),
        "mobilised_max": q.mobilised,
        "mobilised_at": q.mobilised_at,
        "uplift": q.uplift(),
    })
}

fn face_json(model: &Model, f: &FacePair) -> serde_json::Value {
    let mut v = resultant_json(&f.resultant);
    v["contact"] = json!(model.interfaces[f.contact].name);
    v["block_i"] = json!(f.blocks[0]);
    v["block_ii"] = json!(f.blocks[1]);
    v["name_i"] = json!(block_name(model, f.blocks[0]));
    v["name_ii"] = json!(block_name(model, f.blocks[1]));
    v
}

/// summary.json's `contact.groups` (every group, by name) and
/// `contact.faces` (how many, the file with all of them, the most
/// mobilised).
pub fn summary(model: &Model, r: &Resultants) -> (serde_json::Value, serde_json::Value) {
    let groups = (r.groups.iter().enumerate())
        .map(|(g, q)| {
            let mut v = resultant_json(q);
            v["name"] = json!(model.interfaces[g].name);
            v["face_pairs"] = json!(r.faces.iter().filter(|f| f.contact == g).count());
            v
        })
        .collect::<Vec<_>>();
    let out = r.left_out();
    let count = |w: LeftOut| out.iter().filter(|o| **o == Some(w)).count();
    let faces = json!({
        "count": r.faces.len(),
        "file": "faces.csv",
        "left_out": { "supported": count(LeftOut::Supported), "sliver": count(LeftOut::Sliver), "sliver_below": SLIVER },
        "most_mobilised": r.ranked(MOST_FACES).into_iter().map(|f| face_json(model, f)).collect::<Vec<_>>(),
    });
    (json!(groups), faces)
}

/// The contacts whose joints deform: their group's name and stiffness.
fn deforming(run: &Run) -> Vec<(Option<&str>, Stiffness)> {
    (run.about.contacts.iter().enumerate())
        .filter_map(|(i, c)| c.stiffness.map(|k| (run.model.interfaces.get(i).map(|g| g.name.as_str()), k)))
        .collect()
}

/// summary.json's `contact.joint_stiffness`: each contact's normal and
/// shear stiffness where the joints deform, null where they are rigid.
pub fn stiffness_json(run: &Run) -> serde_json::Value {
    let stiff = deforming(run);
    if stiff.is_empty() {
        return serde_json::Value::Null;
    }
    json!(stiff
        .iter()
        .map(|(name, k)| json!({ "contact": name, "normal": k.normal, "shear": k.shear }))
        .collect::<Vec<_>>())
}

/// report.md's sentence on joints that deform (empty where they are rigid).
fn stiffness_note(run: &Run) -> String {
    let each: Vec<String> = deforming(run)
        .iter()
        .map(|(name, k)| format!("`{}` {} / {}", name.unwrap_or("?"), k.normal, k.shear))
        .collect();
    if each.is_empty() {
        return String::new();
    }
    format!("The joints deform: normal / shear stiffness (stress per length) {}. A closed pair is a spring: its gap is its closure from where the spring is unloaded (sigma_n / k_n; the in-situ stress's closure included), its slip the spring's shear and the plastic slip together.\n\n", each.join(", "))
}

/// report.md's section on the contact groups and the most mobilised face
/// pairs (empty without contacts).
pub fn report(run: &Run, r: Option<&super::resultants::Resultants>) -> String {
    let Some(r) = r else { return String::new() };
    let m = &run.model;
    let mut s = String::new();
    let _ = writeln!(s, "\n## Contact groups\n");
    let _ = writeln!(
        s,
        "Resultant force F on side I (global x, y, z); N = F . n and T = |F - N n| in the group's mean frame n (tension positive); mobilised friction |tau| / (c - f sigma_n), 1 where a pair slips or opens or has no strength left.\n"
    );
    s.push_str(&stiffness_note(run));
    let wet = !m.water.is_empty();
    if wet {
        let _ = writeln!(s, "With water in a joint, F and N are the solid-to-solid forces (the effective normal stress sigma_n'), and U the water's force pushing the faces apart: the total normal force across the joint is N - U.\n");
    }
    let (u_head, u_rule) = if wet { (" U |", "---|") } else { ("", "") };
    let _ = writeln!(
        s,
        "| contact | face pairs | pairs | area stick / slip / open | mean normal n | F | N | T | mobilised max (at) |{u_head}"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|{u_rule}");
    for (g, q) in r.groups.iter().enumerate() {
        let faces = r.faces.iter().filter(|f| f.contact == g).count();
        let u = if wet { format!(" {:.4e} |", q.uplift()) } else { String::new() };
        let _ =
            writeln!(s, "| {} | {faces} | {} | {} | {} |{u}", m.interfaces[g].name, q.pairs, areas(q), forces(q, m.nd));
    }
    let most = r.ranked(MOST_FACES);
    let out = r.left_out();
    let (supported, slivers) = (
        out.iter().filter(|o| **o == Some(LeftOut::Supported)).count(),
        out.iter().filter(|o| **o == Some(LeftOut::Sliver)).count(),
    );
    let which = match r.faces.len() - supported - slivers {
        1 => "The one block face pair".to_string(),
        n if most.len() < n => format!("The {} most mobilised of {n} block face pairs", most.len()),
        n => format!("All {n} block face pairs, most mobilised first"),
    };
    let left = if supported + slivers > 0 {
        format!(" Left out: {slivers} sliver(s) below {:.0} % of their contact group's median face area, {supported} held by supports at every pair (faces.csv, column `ranked`).", 100.0 * SLIVER)
    } else {
        String::new()
    };
    let _ = writeln!(s, "\n## Block faces\n\n{which} (a face pair: the part of a contact group between two blocks; every one in `faces.csv`), ranked by the largest mobilised friction away from supported nodes.{left} The same quantities in the face's mean frame, and the face's centre. Where a joint meets a support the support takes part of what its pairs would carry (of what the loads add: the in-situ stress the joint keeps): a face's force is what its contact pairs carry, below what the joint transmits by the blocks' equilibrium on faces that touch a support (`supported_pairs` in faces.csv).\n");
    let _ = writeln!(s, "| contact | block I | block II | centre | area stick / slip / open | mean normal n | F | N | T | mobilised max (at) |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for f in most {
        let q = &f.resultant;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            m.interfaces[f.contact].name,
            block_name(m, f.blocks[0]),
            block_name(m, f.blocks[1]),
            point(q.centre, m.nd),
            areas(q),
            forces(q, m.nd)
        );
    }
    s
}

fn areas(q: &Resultant) -> String {
    format!("{:.4} / {:.4} / {:.4}", q.areas[2], q.areas[1], q.areas[0])
}

/// Mean normal, F, N, T and the largest mobilised friction, as table
/// cells (vectors of `nd` components).
fn forces(q: &Resultant, nd: usize) -> String {
    let force = vector(q.force, nd, |v| format!("{v:.4e}"));
    format!(
        "{} | {force} | {:.4e} | {:.4e} | {:.3} {}",
        point(q.normal, nd),
        q.normal_force(),
        q.shear_force(),
        q.mobilised,
        point(q.mobilised_at, nd)
    )
}

/// A position or direction: x, y (and z in a solid model).
fn point(x: [f64; 3], nd: usize) -> String {
    vector(x, nd, |v| format!("{v:.3}"))
}

fn vector(x: [f64; 3], nd: usize, f: impl Fn(f64) -> String) -> String {
    let c: Vec<String> = x[..nd.clamp(2, 3)].iter().map(|&v| f(v)).collect();
    format!("({})", c.join(", "))
}
