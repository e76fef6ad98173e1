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
//! 2. A 2D joint that slips both ways. A block pressed onto its base whose
//!    underside contracts (an auxetic block, nu = -0.99, plane stress) or
//!    spreads (a soft pad on a stiff base) slips towards (away from) a
//!    point that sticks. A Newton step of the robust rule let every pair of
//!    the joint slip at once, and in 2D a slipping pair's linearised
//!    friction holds nothing along its slip: the set left the block free to
//!    slide, and the run was refused although the block carries no shear
//!    load at all. The converged answer holds every pair to Coulomb's law,
//!    carries the load (closed form: sum sigma_n A = -p w) and balances
//!    the joint's shear on the block (sum tau_x A = 0).
//!
//! ```text
//!   blocks3d (coarse)          contact_stack.geo, quad9, n = 4 (8)
//!     (0.3, 0, -1)                 p = 1 on w = 2
//!     +-------+                  +-----------+
//!     | upper |                  |    top    |  nu = -0.99 (or a soft pad)
//!  +==+=joint=+==+            <--+==joint====+-->  slips both ways, f = 0.2 (0.1)
//!  |    lower    |               |  bottom   |
//!  +-------------+               +-----------+  base held in x and y
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
    let stress_like =
        ["density", "cohesion", "tensile_strength", "residual_cohesion", "pressure", "unit_weight", "traction"];
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
fn same_but_scaled(
    what: &str,
    base: &(Vec<HashMap<String, String>>, serde_json::Value),
    run: &(Vec<HashMap<String, String>>, serde_json::Value),
    force: f64,
    length: f64,
) {
    assert_eq!(base.1["contact"]["iterations"], run.1["contact"]["iterations"], "{what}: contact iterations");
    for (cols, factor) in [(["sigma_n", "tau_t", "tau_b"].as_slice(), force), (["gap", "slip"].as_slice(), length)] {
        let largest = base.0.iter().flat_map(|r| cols.iter().map(|c| csv_num(r, c).abs())).fold(0.0, f64::max);
        for (a, b) in base.0.iter().zip(&run.0) {
            assert_eq!(a["status"], b["status"], "{what}: the state of pair {}", a["pair"]);
            for c in cols {
                let d = (csv_num(b, c) / factor - csv_num(a, c)).abs();
                assert!(
                    d <= 1e-10 * largest,
                    "{what}: pair {} {c}: {} scaled back against {}",
                    a["pair"],
                    csv_num(b, c) / factor,
                    csv_num(a, c)
                );
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

/// Two stacked blocks of contact_stack.geo (quad9, `n` divisions), the
/// base held in x and y, pressed by p = 1 on the top face (w = 2), the
/// joint's friction `f`; `materials` holds the two material tables, the
/// bottom's "base" and the top's "top".
fn pressed(analysis: &str, n: usize, f: f64, materials: &str) -> String {
    format!(
        "title = \"a block pressed onto its base\"\nmesh = \"contact_stack.geo\"\nanalysis = \"{analysis}\"\n\n[gmsh]\norder = 2\nsetnumber = {{ n = {n}, quad = 1 }}\n\n{materials}\n\
         [[bodies]]\ngroup = \"bottom\"\nmaterial = \"base\"\n\n[[bodies]]\ngroup = \"top\"\nmaterial = \"top\"\n\n\
         [[contacts]]\ngroup = \"joint\"\nfriction = {f:?}\n\n[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n\n\
         [[loads]]\ngroup = \"top_face\"\ntraction = [0.0, -1.0]\n"
    )
}

/// Solves a pressed block: every pair holds Coulomb's law with friction `f`
/// (slipping: |tau| = f |sigma_n| to 1e-12; stuck: within it; open: no
/// stress), the joint carries the load, sum sigma_n A = -p w = -2 (1e-9),
/// and its shear on the top block balances, sum tau_x A = 0 (1e-9 of sum
/// |tau_x| A). Returns (stick, slip) counts.
fn holds_coulomb(case: &Case, scene: &str, f: f64) -> (usize, usize) {
    let (rows, _) = solve(case, scene, scene.trim_end_matches(".toml"), &[]);
    let (mut load, mut shear, mut shear_abs) = (0.0, 0.0, 0.0);
    let mut count = [0; 3];
    for r in &rows {
        let (sn, tau, area) = (csv_num(r, "sigma_n"), csv_num(r, "tau_t").abs(), csv_num(r, "area"));
        let status: usize = r["status"].parse().expect("status");
        count[status] += 1;
        match status {
            2 => assert!(
                tau < -f * sn,
                "{scene}: stuck pair {} carries |tau| = {tau} beyond f |sigma_n| = {}",
                r["pair"],
                -f * sn
            ),
            1 => assert!(
                (tau + f * sn).abs() <= 1e-12 * sn.abs(),
                "{scene}: slipping pair {}: |tau| = {tau}, f |sigma_n| = {}",
                r["pair"],
                -f * sn
            ),
            _ => assert!(sn == 0.0 && csv_num(r, "gap") >= 0.0, "{scene}: open pair {} carries {sn}", r["pair"]),
        }
        load += sn * area;
        shear += csv_num(r, "tau_x") * area;
        shear_abs += csv_num(r, "tau_x").abs() * area;
    }
    assert!((load + 2.0).abs() <= 1e-9, "{scene}: the joint carries {load}, not -p w = -2");
    assert!(shear.abs() <= 1e-9 * shear_abs, "{scene}: the joint's shear on the block sums to {shear} of {shear_abs}");
    assert!(count[1] > 0, "{scene}: the joint must slip");
    (count[2], count[1])
}

#[test]
fn an_auxetic_block_pressed_onto_its_base_slips_both_ways_and_is_solved() {
    let case = Case::new("blame-auxetic");
    case.copy("tests/geo/contact_stack.geo");
    for nu in [-0.99f64, -0.97] {
        let materials =
            format!("[materials.base]\nE = 1000.0\nnu = {nu:?}\n\n[materials.top]\nE = 1000.0\nnu = {nu:?}\n");
        let scene = format!("auxetic{}.toml", (-nu * 100.0).round());
        case.write(&scene, &pressed("plane_stress", 4, 0.2, &materials));
        let (stick, slip) = holds_coulomb(&case, &scene, 0.2);
        if nu == -0.99 {
            // refused before: every pair slipping at iteration 4
            assert_eq!((stick, slip), (1, 8), "nu = -0.99: one pair sticks where the slip turns");
        }
    }
}

#[test]
fn a_soft_pad_pressed_onto_a_stiff_base_slips_both_ways_and_is_solved() {
    // a rubber-like pad (E = 100, nu = 0.45) spreads on concrete (E = 1e4):
    // refused before at iteration 4 with all 17 pairs slipping
    let case = Case::new("blame-pad");
    case.copy("tests/geo/contact_stack.geo");
    let materials = "[materials.base]\nE = 10000.0\nnu = 0.2\n\n[materials.top]\nE = 100.0\nnu = 0.45\n";
    case.write("pad.toml", &pressed("plane_strain", 8, 0.1, materials));
    assert_eq!(holds_coulomb(&case, "pad.toml", 0.1), (1, 16));
}
