//! Point loads and moments, and the supports' reactions, against the
//! statics of statically determinate beams.
//!
//! Reference: the equilibrium of a rigid body (any statics text): on a
//! statically determinate support the reactions follow from the loads'
//! resultant alone, whatever the body's stiffness, so the finite element
//! reactions must match them to round-off.
//!
//! Goal: a `force = [..]` on a physical point, a force with a moment at a
//! stated `point` spread over a boundary curve or surface, and a moment on
//! a whole body (a `[[bodies]]` group) carry exactly their resultant in 2D
//! and 3D: the reactions in summary.json are the statics' to 1e-9 of the
//! load, and every body's balance closes. What cannot carry a load is
//! refused in one paragraph that says what to do instead.
//!
//! ```text
//!   2D (tests/geo/beam2d.geo)              3D (tests/geo/beam3d.geo)
//!            F at "load" (a, h)             "load" (a, b/2, h) on the top
//!   +--------v---------------------+        A (0, 0, 0): x, y, z held
//!   |            beam              |        B (0, b, 0): x, z held
//!   o------------------------------o        C (L, 0, 0): z held
//!  pin (x, y)                  roller (y)
//! ```
//!
//! Parameters: L = 4, h = 0.4, a = 1 (2D, quad9 40 x 4); L = 4, b = h =
//! 0.4, a = 1 (3D, hex27 20 x 2 x 2); E = 1000, nu = 0.25; no gravity.

mod common;

use common::cli::{says, solve_fails};
use common::{json, Case};
use serde_json::Value;

/// A beam scene of `dim` (2 or 3) with `loads` (TOML `[[loads]]` entries).
fn beam(dim: usize, loads: &str) -> String {
    let (mesh, analysis, supports) = if dim == 2 {
        (
            "beam2d.geo",
            "plane_strain",
            "[[supports]]\ngroup = \"pin\"\nfix = [\"x\", \"y\"]\n\n[[supports]]\ngroup = \"roller\"\nfix = [\"y\"]\n",
        )
    } else {
        (
            "beam3d.geo",
            "solid",
            "[[supports]]\ngroup = \"A\"\nfix = [\"x\", \"y\", \"z\"]\n\n[[supports]]\ngroup = \"B\"\nfix = [\"x\", \"z\"]\n\n[[supports]]\ngroup = \"C\"\nfix = [\"z\"]\n",
        )
    };
    format!(
        "title = \"beam\"\nmesh = \"{mesh}\"\nanalysis = \"{analysis}\"\n\n[gmsh]\norder = 2\n\n[materials.m]\nE = 1000.0\nnu = 0.25\n\n[[bodies]]\ngroup = \"beam\"\nmaterial = \"m\"\n\n{supports}\n{loads}"
    )
}

/// Solves `text` as `name` in the case; summary.json.
fn solve(case: &Case, name: &str, text: &str) -> Value {
    let scene = case.write(&format!("{name}.toml"), text);
    case.run(&scene).unwrap_or_else(|e| panic!("{name}: {e:#}"));
    json(&case.out(name).join("summary.json"))
}

/// The reaction force of the support `group`.
fn reaction(summary: &Value, group: &str) -> [f64; 3] {
    let s = summary["reactions"]["supports"].as_array().expect("reactions.supports");
    let r = s.iter().find(|r| r["group"] == group).unwrap_or_else(|| panic!("no reaction of {group}"));
    common::json_vec3(&r["force"])
}

/// Every reaction within `tol` of the expected (group, force) pairs, and
/// every body's balance closed to `tol`.
fn assert_reactions(summary: &Value, expected: &[(&str, [f64; 3])], tol: f64) {
    for (group, want) in expected {
        let got = reaction(summary, group);
        for c in 0..3 {
            assert!((got[c] - want[c]).abs() < tol, "{group}: reaction {got:?}, statics {want:?}");
        }
    }
    for b in summary["reactions"]["bodies"].as_array().expect("reactions.bodies") {
        let r = common::json_vec3(&b["remainder"]);
        assert!(r.iter().all(|v| v.abs() < tol), "{}: the balance leaves {r:?}", b["group"]);
    }
    let free = summary["reactions"]["free_residual"].as_f64().expect("free_residual");
    assert!(free < 1e-9, "the nodal forces at free DOFs next to the supports: {free:e}");
}

/// 2D: a point force, a force with a moment spread over the top and a
/// moment on the whole beam each give the statics' reactions.
#[test]
fn point_force_patch_force_and_body_moment_carry_their_resultant_in_2d() {
    let case = Case::new("point-loads-2d");
    case.copy("tests/geo/beam2d.geo");
    let (l, h, a) = (4.0, 0.4, 1.0);
    // F = (3, -10) at (a, h): moments about the pin give the roller
    let (fx, fy) = (3.0, -10.0);
    let s = solve(&case, "point", &beam(2, "[[loads]]\ngroup = \"load\"\nforce = [3.0, -10.0]\n"));
    let roller = (h * fx - a * fy) / l;
    assert_reactions(&s, &[("pin", [-fx, -fy - roller, 0.0]), ("roller", [0.0, roller, 0.0])], 1e-9 * 10.0);
    // 8 down at (3, h) with a counterclockwise moment of 2, on the top
    let s = solve(
        &case,
        "patch",
        &beam(2, "[[loads]]\ngroup = \"top\"\nforce = [0.0, -8.0]\nmoment = 2.0\npoint = [3.0, 0.4]\n"),
    );
    assert_reactions(&s, &[("pin", [0.0, 2.5, 0.0]), ("roller", [0.0, 5.5, 0.0])], 1e-9 * 10.0);
    // a moment of 5 on the beam: a couple of 5 / L in the supports
    let s = solve(&case, "couple", &beam(2, "[[loads]]\ngroup = \"beam\"\nmoment = 5.0\n"));
    assert_reactions(&s, &[("pin", [0.0, 5.0 / l, 0.0]), ("roller", [0.0, -5.0 / l, 0.0])], 1e-9 * 10.0);
}

/// 2D: the beam's weight and a pseudo-static earthquake (kh = 0.2 along x,
/// kv = 0.1 up) on it: the body forces' resultant at the beam's centroid
/// gives the statics' reactions, and the balance counts the seismic part.
#[test]
fn weight_and_a_seismic_load_give_the_statics_reactions() {
    let case = Case::new("point-loads-seismic");
    case.copy("tests/geo/beam2d.geo");
    let (l, h, rho, g) = (4.0, 0.4, 2.0, 10.0);
    let quake = "[[loads]]\nseismic = { kh = 0.2, kv = 0.1 }\n";
    let text = beam(2, quake)
        .replace("analysis = \"plane_strain\"\n", "analysis = \"plane_strain\"\ngravity = [0.0, -10.0]\n")
        .replace("nu = 0.25\n", "nu = 0.25\ndensity = 2.0\n");
    let s = solve(&case, "quake", &text);
    // the body force rho L h (kh g, -g + kv g) at (L/2, h/2)
    let m = rho * l * h;
    let (fx, fy) = (m * 0.2 * g, m * (0.1 * g - g));
    let roller = (0.5 * h * fx - 0.5 * l * fy) / l;
    assert_reactions(&s, &[("pin", [-fx, -fy - roller, 0.0]), ("roller", [0.0, roller, 0.0])], 1e-9 * m * g);
}

/// 3D: a point force on the top, a force with a moment on the top face and
/// a moment on the whole beam, on three point supports.
#[test]
fn point_force_patch_force_and_body_moment_carry_their_resultant_in_3d() {
    let case = Case::new("point-loads-3d");
    case.copy("tests/geo/beam3d.geo");
    let (l, b, a) = (4.0, 0.4, 1.0);
    let p = 10.0;
    // P down at (a, b/2, h): moments about the lines A-C (x axis) and A-B (y axis)
    let s = solve(&case, "point", &beam(3, "[[loads]]\ngroup = \"load\"\nforce = [0.0, 0.0, -10.0]\n"));
    let (rb, rc) = (p * (b / 2.0) / b, p * a / l);
    let tol = 1e-9 * p;
    assert_reactions(&s, &[("A", [0.0, 0.0, p - rb - rc]), ("B", [0.0, 0.0, rb]), ("C", [0.0, 0.0, rc])], tol);
    // P down at the top's centroid with a moment of 1 about x: B takes
    // P/2 - M/b, C takes P/2
    let s = solve(
        &case,
        "patch",
        &beam(3, "[[loads]]\ngroup = \"top\"\nforce = [0.0, 0.0, -10.0]\nmoment = [1.0, 0.0, 0.0]\n"),
    );
    let (rb, rc) = (p / 2.0 - 1.0 / b, p / 2.0);
    assert_reactions(&s, &[("A", [0.0, 0.0, p - rb - rc]), ("B", [0.0, 0.0, rb]), ("C", [0.0, 0.0, rc])], tol);
    // a moment of 2 about y on the beam: C takes 2 / L, A the opposite
    let s = solve(&case, "couple", &beam(3, "[[loads]]\ngroup = \"beam\"\nmoment = [0.0, 2.0, 0.0]\n"));
    assert_reactions(&s, &[("A", [0.0, 0.0, -2.0 / l]), ("B", [0.0; 3]), ("C", [0.0, 0.0, 2.0 / l])], tol);
}

/// A probe's history over load steps (probes_history.csv): the point force
/// ramped in four steps on the linear beam moves every probe point by
/// k/4 of its last displacement, and the last step's rows are probes.csv's.
#[test]
fn a_probe_history_follows_the_load_ramp() {
    let case = Case::new("point-loads-history");
    case.copy("tests/geo/beam2d.geo");
    let loads = "[[loads]]\ngroup = \"load\"\nforce = [0.0, -10.0]\n\n[solver]\nload_steps = 4\n\n[[probes]]\nname = \"bottom\"\nfrom = [0.5, 0.0]\nto = [3.5, 0.0]\npoints = 7\n";
    solve(&case, "ramp", &beam(2, loads));
    let out = case.out("ramp");
    let rows = |file: &str| -> Vec<Vec<f64>> {
        let text = common::read(&out.join(file));
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect()).collect()
    };
    let (history, last) = (rows("probes_history.csv"), rows("probes.csv"));
    assert_eq!(history.len(), 4 * 7, "seven points at four steps");
    // columns: step, load_factor, then probes.csv's (uy the 8th of those)
    let uy = |r: &Vec<f64>, off: usize| r[off + 6];
    let (mut worst, mut sag) = (0.0f64, 0.0f64);
    for (i, r) in history.iter().enumerate() {
        let (k, factor) = (r[0], r[1]);
        assert_eq!((k as usize, factor), (i / 7 + 1, (i / 7 + 1) as f64 / 4.0), "row {i}: step and factor");
        let end = uy(&last[i % 7], 0);
        worst = worst.max((uy(r, 2) - factor * end).abs() / end.abs());
        sag = sag.min(end);
    }
    eprintln!("probe history: 4 steps x 7 points, uy against the ramp within {worst:.1e}; largest sag {sag:.4e}");
    assert!(sag < 0.0 && worst < 1e-9, "uy follows the load factor: {worst:e}");
}

/// What cannot carry a load says what to do instead, before anything is
/// solved: a moment on one point, a pressure on a point, a force in
/// axisymmetry, a moment of the wrong shape.
#[test]
fn loads_that_cannot_be_carried_are_refused_with_what_to_do() {
    let case = Case::new("point-loads-refused");
    case.copy("tests/geo/beam2d.geo");
    let refused = |name: &str, loads: &str, needles: &[&str]| {
        case.write(&format!("{name}.toml"), &beam(2, loads));
        let msg = solve_fails(&case, &format!("{name}.toml"), &format!("results/{name}"));
        says(&msg, needles);
    };
    refused(
        "moment_on_point",
        "[[loads]]\ngroup = \"load\"\nforce = [0.0, -1.0]\nmoment = 1.0\n",
        &["loads[0].moment", "single point carries no moment", "small patch"],
    );
    refused(
        "pressure_on_point",
        "[[loads]]\ngroup = \"load\"\npressure = 1.0\n",
        &["loads[0].group", "\"load\" is a physical point", "force = [..]", "small patch"],
    );
    refused(
        "moment_vector_2d",
        "[[loads]]\ngroup = \"beam\"\nmoment = [0.0, 0.0, 1.0]\n",
        &["loads[0].moment", "one number"],
    );
    refused(
        "force_and_pressure",
        "[[loads]]\ngroup = \"top\"\npressure = 1.0\nforce = [0.0, 1.0]\n",
        &["loads[0]", "split it into several [[loads]] entries"],
    );
    refused("point_alone", "[[loads]]\ngroup = \"top\"\npressure = 1.0\npoint = [0.0, 0.0]\n", &["loads[0].point"]);
}
