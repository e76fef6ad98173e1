//! Scenes that were refused for the wrong reason (issue 20, "Messages that
//! blame the wrong thing"), through the real binary and the gmsh CLI: they
//! ended as "loss of equilibrium: the load along the contact exceeds what
//! friction and cohesion can carry".
//!
//! 1. Units. A scene means the same in any consistent units, so its numbers
//!    scaled by 2^-664 (1.05e-200) must give the same states and the same
//!    results times that factor: E and every stress-like input (loads,
//!    cohesion) scaled, the forces are near 1e-200 and their squares
//!    underflowed (the contact law's norms, the friction residual, GMRES,
//!    the least-norm forces at crossing joints); E alone scaled, the
//!    displacements are near 1e+200 and their squares overflowed. Scaled
//!    up by 2^664 the stresses are near 1e+200: refused, saying so.
//!
//! ```text
//!   blocks3d (coarse)
//!     (0.3, 0, -1)
//!     +-------+
//!     | upper |
//!  +==+=joint=+==+
//!  |    lower    |
//!  +-------------+
//! ```

mod common;

use std::collections::HashMap;

use common::cli::{clean_failure, says};
use common::{csv_num, csv_rows, json, scenes, Case};

/// 2^-664, about 1.05e-200: a power of two, exact to scale by.
fn tiny() -> f64 {
    2f64.powi(-664)
}

/// The scene text with `E` of every material (`all`: and every
/// stress-like number, the loads, densities and strengths) times `s`.
fn scaled(text: &str, s: f64, all: bool) -> String {
    let stress_like = ["density", "cohesion", "tensile_strength", "residual_cohesion", "pressure", "unit_weight", "traction"];
    fn walk(v: &mut toml::Value, key: &str, s: f64, keys: &dyn Fn(&str) -> bool) {
        match v {
            toml::Value::Float(x) if keys(key) => *x *= s,
            toml::Value::Integer(i) if keys(key) => *v = toml::Value::Float(*i as f64 * s),
            toml::Value::Table(t) => t.iter_mut().for_each(|(k, v)| walk(v, k, s, keys)),
            toml::Value::Array(a) => a.iter_mut().for_each(|v| walk(v, key, s, keys)),
            _ => {}
        }
    }
    let mut scene: toml::Value = toml::from_str(text).expect("the scene parses");
    walk(&mut scene, "", s, &|k: &str| k == "E" || (all && stress_like.contains(&k)));
    toml::to_string(&scene).expect("the scene writes")
}

/// Solves `scene` into `out` (extra flags `args`); the run must succeed.
fn solve(case: &Case, scene: &str, out: &str, args: &[&str]) -> (Vec<HashMap<String, String>>, serde_json::Value) {
    let o = case.cli(&[&["solve", scene, "--out", out, "--quiet"], args].concat());
    assert!(o.status.success(), "{scene} {args:?}: {}", String::from_utf8_lossy(&o.stderr));
    (csv_rows(&case.dir.join(out).join("contact.csv")), json(&case.dir.join(out).join("summary.json")))
}

/// The scaled run against the run in the scene's own units: the same
/// states and iterations, its stresses `force` and gaps and slips `length`
/// times the unscaled ones (relative to the largest, 1e-10: the CSV's 13
/// digits; unscaled they differed by up to the whole value).
fn same_but_scaled(what: &str, base: &(Vec<HashMap<String, String>>, serde_json::Value), run: &(Vec<HashMap<String, String>>, serde_json::Value), force: f64, length: f64) {
    assert_eq!(base.1["contact"]["iterations"], run.1["contact"]["iterations"], "{what}: contact iterations");
    for (cols, factor) in [(["sigma_n", "tau_t", "tau_b"].as_slice(), force), (["gap", "slip"].as_slice(), length)] {
        let largest = base.0.iter().flat_map(|r| cols.iter().map(|c| csv_num(r, c).abs())).fold(0.0, f64::max);
        for (a, b) in base.0.iter().zip(&run.0) {
            assert_eq!(a["status"], b["status"], "{what}: the state of pair {}", a["pair"]);
            for c in cols {
                let d = (csv_num(b, c) / factor - csv_num(a, c)).abs();
                assert!(d <= 1e-10 * largest, "{what}: pair {} {c}: {} scaled back against {}", a["pair"], csv_num(b, c) / factor, csv_num(a, c));
            }
        }
    }
}

#[test]
fn a_scene_whose_numbers_are_near_1e_minus_200_solves_as_in_its_own_units() {
    // partial slip in 3D: 6 iterations, 71 stick / 82 slip in its own units
    let case = Case::new("blame-units");
    let scene = scenes::coarse_blocks(&case);
    let text = common::read(&case.dir.join(scene));
    case.write("all.toml", &scaled(&text, tiny(), true));
    case.write("e.toml", &scaled(&text, tiny(), false));
    for interface in ["dense", "iterative", "sparse"] {
        let base = solve(&case, scene, &format!("base-{interface}"), &["--interface", interface]);
        let all = solve(&case, "all.toml", &format!("all-{interface}"), &["--interface", interface]);
        same_but_scaled(&format!("E and loads x 2^-664, {interface}"), &base, &all, tiny(), 1.0);
        let e = solve(&case, "e.toml", &format!("e-{interface}"), &["--interface", interface]);
        same_but_scaled(&format!("E x 2^-664, {interface}"), &base, &e, 1.0, 1.0 / tiny());
    }
    // scaled up, the stresses are near 1e+200: their squares leave double
    // precision in the von Mises stress, and the run says so
    case.write("huge.toml", &scaled(&text, 1.0 / tiny(), true));
    let o = case.cli(&["solve", "huge.toml", "--out", "huge", "--quiet"]);
    let msg = clean_failure(&case, &o, &case.dir.join("huge"));
    says(&msg, &["huge.toml", "not finite numbers", "give them in other units", "No result files were written"]);
}

#[test]
fn crossing_joints_share_their_forces_in_units_near_1e_minus_200_as_in_their_own() {
    // geo/tunnel_joints: three joint sets cross around the opening; the
    // junctions' tied forces are the least-norm ones within each pair's limit
    let case = Case::new("blame-units-junctions");
    case.copy("geo/tunnel_joints.geo");
    let text = scenes::edited("geo/tunnel_joints.toml", &[]);
    case.write("tunnel.toml", &text);
    case.write("all.toml", &scaled(&text, tiny(), true));
    let base = solve(&case, "tunnel.toml", "base", &[]);
    assert!(base.0.iter().any(|r| r["status"] != "2"), "the joints must slip or open somewhere");
    let all = solve(&case, "all.toml", "all", &[]);
    same_but_scaled("tunnel_joints, E and loads x 2^-664", &base, &all, tiny(), 1.0);
}
