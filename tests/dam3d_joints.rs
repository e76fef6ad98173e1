//! A gravity dam in 3D whose contraction joints cross its lift joints
//! (geo/dam3d_joints.toml, issue 17): three monoliths in a stepped valley,
//! each cut into lifts at z = 20 and 35 m; self-weight, then the reservoir
//! at half and full pressure.
//!
//! ```text
//!   section of every monolith: x = 0 upstream, downstream face
//!   x_d(z) = B - (B - c) z / H (H = 50, crest c = 5, base B = 28)
//!
//!   the dam above a plane z = z0 (the whole length L = 30 m) is held by
//!   that plane alone: its weight and the water on its upstream face
//!     W(z0) = rho g sum_m w_m A(max(z0, base_m), H)
//!     T(z0) = k gamma_w sum_m w_m (H - max(z0, base_m))^2 / 2
//!   with A(a, b) = B (b - a) - (B - c) (b^2 - a^2) / (2 H) the section's
//!   area between a and b, w_m = 10 m and base_m = 10, 0, 10 m the
//!   monoliths' widths and bases, k the reservoir's factor.
//! ```
//!
//! The base (every face between the dam and the rock, the steps' sides
//! included) carries F = (T(0), 0, -W(0)) on the rock, and each lift joint
//! plane F = (T(z0), 0, -W(z0)) on the lifts below it: summary.json's
//! `contact.groups` for the base, faces.csv's face pairs of one plane for
//! the lifts, at every load step, to 1e-8. Run at a coarse mesh (lc = 6 m).
//! States: the heel opens under the full reservoir and not under
//! self-weight; the crossing lines have four blocks around every node;
//! every step converges in 12 contact iterations or fewer.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;

const RHO_G: f64 = 2.4e-3 * 9.81;
const GAMMA_W: f64 = 0.00981;
const H: f64 = 50.0;
const CREST: f64 = 5.0;
const B: f64 = 28.0;
/// Width and base of each monolith.
const MONOLITHS: [(f64, f64); 3] = [(10.0, 10.0), (10.0, 0.0), (10.0, 10.0)];

/// The section's area between z = a and z = b.
fn area(a: f64, b: f64) -> f64 {
    B * (b - a) - (B - CREST) * (b * b - a * a) / (2.0 * H)
}

/// The weight of the dam above z0 and the water thrust on it at reservoir factor k.
fn above(z0: f64, k: f64) -> (f64, f64) {
    MONOLITHS.iter().fold((0.0, 0.0), |(w, t), &(width, base)| {
        let a = z0.max(base);
        (w + RHO_G * width * area(a, H), t + k * GAMMA_W * width * (H - a).powi(2) / 2.0)
    })
}

#[test]
fn the_base_and_every_lift_joint_carry_the_dam_above_them_and_the_water() {
    let case = Case::new("dam3d-joints");
    case.copy("geo/dam3d_joints.geo");
    let text = common::scenes::edited(
        "geo/dam3d_joints.toml",
        &[("setnumber = { lc = 4.0 }", "setnumber = { lc = 6.0, lc_rock = 25.0 }")],
    );
    let scene = case.write("dam3d_joints.toml", &text);
    let run = case.run(&scene).unwrap_or_else(|e| panic!("dam3d_joints: {e:#}"));
    let m = &run.model;
    assert_eq!(m.bodies.len(), 1 + 3 * 3, "the rock and three lifts per monolith");

    // where the contraction joint y = 10 crosses the lift joint z = 20, four
    // blocks meet: every node of that line has four copies
    let on_line =
        |x: [f64; 3]| (x[1] - 10.0).abs() < 1e-9 && (x[2] - 20.0).abs() < 1e-9 && x[0] > 1e-9 && x[0] < 18.8 - 1e-9;
    let mut copies: std::collections::BTreeMap<usize, std::collections::BTreeSet<usize>> = Default::default();
    for p in &m.pairs {
        for n in [p.k, p.l] {
            if on_line(m.coords[n]) {
                copies.entry(m.mesh_node[n]).or_default().insert(n);
            }
        }
    }
    assert!(
        !copies.is_empty() && copies.values().all(|c| c.len() == 4),
        "four copies along the crossing line: {copies:?}"
    );

    // the forces, at every load step; each step's files are the last step's
    // only, so the steps are read from the run and the last one also from the files
    let base = m.interfaces.iter().position(|i| i.name == "base").expect("base");
    let lifts = m.interfaces.iter().position(|i| i.name == "lifts").expect("lifts");
    let body = m.body_of_node();
    for (s, k) in [(0, 0.0), (1, 0.5), (2, 1.0)] {
        let c = run.steps[s].contact.as_ref().expect("contact");
        assert!(c.summary.converged, "step {}: converged", s + 1);
        // Newton converges quadratically on the crossing lines' slipping
        // pairs too, whose pressure is the split of what their junction's
        // ties carry, solved with the rest (7 / 6 / 10 iterations; 16 / 14
        // / 22 with the last solve's pressure)
        assert!(c.summary.iterations <= 12, "step {}: {} contact iterations", s + 1, c.summary.iterations);
        let sum = |which: &dyn Fn(usize) -> bool| {
            (0..m.pairs.len()).filter(|&p| which(p)).fold([0.0; 3], |f, p| {
                let fp = c.force(p);
                [f[0] + fp[0], f[1] + fp[1], f[2] + fp[2]]
            })
        };
        for (what, z0, f) in [
            ("base", 0.0, sum(&|p| m.pairs[p].contact == base)),
            (
                "lift joint z = 20",
                20.0,
                sum(&|p| m.pairs[p].contact == lifts && (m.coords[m.pairs[p].k][2] - 20.0).abs() < 1e-9),
            ),
            (
                "lift joint z = 35",
                35.0,
                sum(&|p| m.pairs[p].contact == lifts && (m.coords[m.pairs[p].k][2] - 35.0).abs() < 1e-9),
            ),
        ] {
            let (w, t) = above(z0, k);
            let want = [t, 0.0, -w];
            let err = (0..3).map(|i| (f[i] - want[i]).abs()).fold(0.0, f64::max) / w.hypot(t);
            eprintln!("step {}: {what} carries {f:?} against {want:?} ({err:.1e})", s + 1);
            assert!(err < 1e-8, "step {}: the {what} carries {f:?}, not {want:?}", s + 1);
        }
        // side I of the base is the rock, of a lift joint the lift below
        assert!((0..m.pairs.len())
            .filter(|&p| m.pairs[p].contact == base)
            .all(|p| m.bodies[body[m.pairs[p].k]].name == "rock"));
    }

    // the same from the files of the last step: summary.json's base, faces.csv's lift joints
    let out = case.out("dam3d_joints");
    let summary = common::json(&out.join("summary.json"));
    let groups = summary["contact"]["groups"].as_array().expect("contact.groups");
    let g = groups.iter().find(|g| g["name"] == "base").expect("base");
    let (w, t) = above(0.0, 1.0);
    let f = common::json_vec3(&g["force"]);
    assert!(
        (f[0] - t).abs() < 1e-8 * w && f[1].abs() < 1e-8 * w && (f[2] + w).abs() < 1e-8 * w,
        "summary.json's base carries {f:?}"
    );
    assert_eq!(g["face_pairs"], 3, "the base: one face pair per monolith");
    let faces = common::csv_rows(&out.join("faces.csv"));
    for z0 in [20.0, 35.0] {
        let rows: Vec<_> =
            faces.iter().filter(|r| r["contact"] == "lifts" && (common::csv_num(r, "z") - z0).abs() < 1e-9).collect();
        assert_eq!(rows.len(), 3, "the lift joint z = {z0}: one face pair per monolith");
        let fx: f64 = rows.iter().map(|r| common::csv_num(r, "f_x")).sum();
        let fz: f64 = rows.iter().map(|r| common::csv_num(r, "f_z")).sum();
        let (w, t) = above(z0, 1.0);
        assert!(
            (fx - t).abs() < 1e-8 * w && (fz + w).abs() < 1e-8 * w,
            "faces.csv's lift joint z = {z0}: ({fx}, {fz}) against ({t}, {})",
            -w
        );
    }

    // the heel (x = 0 on the base) opens under the full reservoir, not under self-weight
    let heel: Vec<usize> = (0..m.pairs.len())
        .filter(|&p| {
            m.pairs[p].contact == base && m.coords[m.pairs[p].k][0].abs() < 1e-9 && m.pairs[p].normal[2] > 0.99
        })
        .collect();
    assert!(!heel.is_empty());
    let states = |s: usize| &run.steps[s].contact.as_ref().expect("contact").states;
    assert!(heel.iter().all(|&p| states(0)[p] != ContactState::Open), "self-weight keeps the heel closed");
    assert!(heel.iter().any(|&p| states(2)[p] == ContactState::Open), "the full reservoir opens the heel");
}

/// geo/dam3d_joints_uplift.toml at the coarse mesh: the reservoir at 42 m,
/// the base's uplift through a drain line and its cracks filling. Every
/// step converges (before the crack stayed in its sheet and an open pair
/// with sigma_n' = 0 at the heel's corner kept open, step 2 did not); the
/// base's solid-to-solid force and its water's force together carry the
/// dam's weight and the water's thrust, F + W_u = (T(0), 0, -W(0)), to
/// 3e-5 (the level cuts facets of the upstream face: 1.0e-5 measured); the floors' cracks (sheets of normal z) stay short, as in 2D
/// (geo/dam_uplift.toml: 1 m of the 28 m base; none here at lc = 6 m), and
/// the steps' sides (normal y), which open along their length, fill on
/// their own sheets.
#[test]
fn with_uplift_the_base_carries_the_dam_and_its_cracks_stay_in_their_sheets() {
    let case = Case::new("dam3d-joints-uplift");
    case.copy("geo/dam3d_joints.geo");
    let text = common::scenes::edited(
        "geo/dam3d_joints_uplift.toml",
        &[("setnumber = { lc = 4.0 }", "setnumber = { lc = 6.0, lc_rock = 25.0 }")],
    );
    let scene = case.write("dam3d_joints_uplift.toml", &text);
    let run = case.run(&scene).unwrap_or_else(|e| panic!("dam3d_joints_uplift: {e:#}"));
    let m = &run.model;
    let base = m.interfaces.iter().position(|i| i.name == "base").expect("base");
    for (s, k) in [(0, 0.0), (1, 0.5), (2, 1.0)] {
        let c = run.steps[s].contact.as_ref().expect("contact");
        assert!(c.summary.converged, "step {}: converged", s + 1);
        assert!(c.summary.iterations <= 30, "step {}: {} contact iterations", s + 1, c.summary.iterations);
        let water = c.water.as_ref().expect("the base's water");
        let f = (0..m.pairs.len()).filter(|&p| m.pairs[p].contact == base).fold([0.0; 3], |f, p| {
            let (fp, wp) = (c.force(p), water.force[p]);
            [f[0] + fp[0] + wp[0], f[1] + fp[1] + wp[1], f[2] + fp[2] + wp[2]]
        });
        let (w, _) = above(0.0, k);
        // the thrust of a reservoir at 42 m: T = k gamma_w sum w_m (42 - base_m)^2 / 2
        let t42: f64 = MONOLITHS.iter().map(|&(width, b)| k * GAMMA_W * width * (42.0 - b).powi(2) / 2.0).sum();
        let want = [t42, 0.0, -w];
        let err = (0..3).map(|i| (f[i] - want[i]).abs()).fold(0.0, f64::max) / w.hypot(t42);
        eprintln!("step {}: the base carries {f:?} against {want:?} ({err:.1e})", s + 1);
        // the level at 42 m cuts facets of the upstream face, whose
        // pressure's kink the quadrature integrates to 1.0e-5
        assert!(err < 3e-5, "step {}: the base carries {f:?}, not {want:?}", s + 1);
    }

    let out = case.out("dam3d_joints_uplift");
    let summary = common::json(&out.join("summary.json"));
    let cracks = summary["water"][0]["cracks"].as_array().expect("water.cracks").clone();
    eprintln!("cracks: {cracks:?}");
    for c in &cracks {
        let n = common::json_vec3(&c["normal"]);
        let tip = c["tip"].as_f64().expect("tip");
        if n[2].abs() > 0.99 {
            assert!(tip <= 6.0, "a floor's heel crack reaches s = {tip}: at most one element (6 m) here");
        } else {
            assert!(n[1].abs() > 0.99, "a crack on the sheet of normal {n:?}: only floors and steps' sides");
        }
    }
    let uplift = summary["water"][0]["uplift"].as_f64().expect("uplift");
    assert!(uplift > 0.0, "the base's water pushes the dam up: U = {uplift}");
}
