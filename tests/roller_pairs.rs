//! Pairs on supported faces: a wedge of rock on a joint dipping 65 degrees
//! down towards a frictionless roller wall (tests/geo/roller_wedge.geo and
//! .toml), in plane strain and extruded (solid, its sides held in z).
//!
//! Goal (issue 28): the pair where a joint meets a roller keeps the
//! joint's own frame. Both of its copies are held in x, so its only
//! relative motion is along the wall, and that motion changes its gap
//! (by n_y dy): it is a closed contact that carries a pressure, not a
//! slip. Snapped onto the wall's axis (before), it read sigma_n = 0 and
//! slipped along y (and z) at zero friction; the wedge took 4 contact
//! iterations in 2D and 6 in 3D with 3 and 15 pairs slipping, and the
//! extruded joint's resultant had a z part of 1.6e-3 MN.
//!
//! ```text
//!          +-------------------+------+  L = 10
//!          |                  / wedge |
//!          |       ground    /        |  east: ux held (a roller)
//!          |                / joint   |
//!          |               +----------+  A = (L, 1): the pair at the roller
//!          +--------------------------+  base held
//! ```
//!
//! Closed forms: the roller carries no vertical force, so the joint
//! carries the wedge's weight `rho g A_wedge` (per unit width in 2D, times
//! w in 3D); extruded with its sides held in z, the joint's resultant has
//! no z part. At A the pair sticks with the true normal (sin 65, cos 65),
//! a pressure of the order of the joint's mean, and a shear within
//! Coulomb's cone (f = 0.7 < tan 65: what holds the wedge there is the
//! wall, through the joint's pressure).

mod common;

use common::scenes::edited;
use common::{csv_num, csv_rows, json, json_vec3, Case};
use serde_json::Value;

const L: f64 = 10.0;
const A_Y: f64 = 1.0;
const DIP: f64 = 65.0;
const FRICTION: f64 = 0.7;
const RHO_G: f64 = 2.6e-3 * 9.81;
/// The extruded scene's width along z.
const W: f64 = 2.0;

/// The wedge's area: a right triangle with legs L - a (on the wall) and
/// (L - a) / tan(dip) (on the top).
fn wedge_area() -> f64 {
    let h = L - A_Y;
    0.5 * h * h / DIP.to_radians().tan()
}

/// Solves `toml` (written into a case with the geometry) and returns its
/// summary and contact.csv rows.
fn solve(name: &str, toml: &str) -> (Value, Vec<std::collections::HashMap<String, String>>) {
    let case = Case::new(name);
    case.copy("tests/geo/roller_wedge.geo");
    case.write("roller_wedge.toml", toml);
    let o = case.cli(&["solve", "roller_wedge.toml", "--out", "out", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = case.dir.join("out");
    (json(&out.join("summary.json")), csv_rows(&out.join("contact.csv")))
}

/// The joint carries the wedge's `weight` (on body I, the ground: down),
/// nothing along z, and the pairs at the roller stick with a pressure.
fn check(summary: &Value, rows: &[std::collections::HashMap<String, String>], weight: f64) {
    let contact = &summary["contact"];
    assert_eq!(contact["converged"], true);
    let joint = &contact["groups"][0];
    let force = json_vec3(&joint["force"]);
    eprintln!("joint force {force:?} against the weight {weight:.6}; {} iterations", contact["iterations"]);
    assert!((force[1] + weight).abs() < 1e-9 * weight, "the joint carries the wedge: {force:?}");
    assert!(force[2].abs() < 1e-9 * weight, "nothing along z: {force:?}");
    let area = joint["area"]["total"].as_f64().expect("the joint's area");
    let mean = -joint["normal_force"].as_f64().expect("its normal force") / area;
    let (s, c) = DIP.to_radians().sin_cos();
    let at_roller: Vec<_> =
        rows.iter().filter(|r| (csv_num(r, "x") - L).abs() < 1e-9 && (csv_num(r, "y") - A_Y).abs() < 1e-9).collect();
    assert!(!at_roller.is_empty(), "pairs at the roller");
    for r in at_roller {
        let (sigma, tau) = (csv_num(r, "sigma_n"), csv_num(r, "tau_t").hypot(csv_num(r, "tau_b")));
        eprintln!("at the roller, z = {}: status {}, sigma_n {sigma:.4e}, tau {tau:.4e}", r["z"], r["status"]);
        assert_eq!(r["status"], "2", "the pair at the roller sticks");
        assert!((csv_num(r, "n_x") - s).abs() < 1e-9 && (csv_num(r, "n_y") - c).abs() < 1e-9, "the joint's normal");
        assert!(sigma < -0.5 * mean, "a pressure ({sigma:.4e}) of the order of the joint's mean ({mean:.4e})");
        assert!(tau <= -FRICTION * sigma * (1.0 + 1e-9), "within Coulomb's cone: {tau:.4e}");
    }
}

#[test]
fn a_wedge_against_a_roller_is_carried_by_its_joint_with_a_pressure_at_the_wall() {
    let (summary, rows) = solve("roller_wedge", &common::repo_text("tests/geo/roller_wedge.toml"));
    check(&summary, &rows, RHO_G * wedge_area());
}

#[test]
fn the_same_wedge_extruded_carries_nothing_along_the_wall() {
    let toml = edited(
        "tests/geo/roller_wedge.toml",
        &[
            ("analysis = \"plane_strain\"", "analysis = \"solid\""),
            ("gravity = [0.0, -9.81]", "gravity = [0.0, -9.81, 0.0]"),
            ("order = 2", "order = 2\nsetnumber = { solid = 1 }"),
            ("fix = [\"x\", \"y\"]", "fix = [\"x\", \"y\", \"z\"]"),
        ],
    ) + "\n[[supports]]\ngroup = \"sides\"\nfix = [\"z\"]\n";
    let (summary, rows) = solve("roller_wedge3d", &toml);
    check(&summary, &rows, RHO_G * wedge_area() * W);
}
