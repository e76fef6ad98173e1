//! A planar rock slope whose friction alone cannot hold it (tan phi < tan
//! psi): the cohesion of its sliding plane carries the rest. Written from
//! the figures (tests/geo/planar_slide.geo), not from a repository scene,
//! as a user would, and solved by the real binary: its factor of safety
//! against Hoek & Bray's closed form (Rock Slope Engineering, planar
//! failure with a tension crack in the upper slope surface)
//!
//!   F = (c A + (W cos psi - U - V sin psi) tan phi) / (W sin psi + V cos psi)
//!
//! dry, with water in the tension crack (V) and with it on the plane too
//! (U, falling linearly from the crack's level to nothing at the toe).
//!
//! Figures: H = 20 m, face 70 degrees, plane psi = 35 degrees, crack z = 6
//! m deep with z_w = 4 m of water, c = 50 kPa, phi = 30 degrees, rock 2.6
//! t/m3 (units kN, m, kPa); the scene and the closed form are
//! tests/common/slopes.rs's. Measured: F within 0.002 % of the closed form,
//! the closed form inside the search's bracket (tolerance 1e-4 x F); U =
//! 1/2 gw z_w A to round-off. Tolerance asserted: the closed form within
//! the bracket widened by one search tolerance, 1e-4 x F.

mod common;

use common::cli::says;
use common::json;
use common::slopes::planar::{self, hoek_bray, TOL};
use serde_json::Value;

/// The closed form inside the search's bracket, widened by a tolerance.
fn assert_bracket(what: &str, safety: &Value, exact: f64) {
    let f = safety["factor"].as_f64().expect("factor");
    let fails = safety["fails_at"].as_f64().expect("a failure found");
    eprintln!("{what}: F = {f:.6} (fails at {fails:.6}) against {exact:.6}: {:+.4} %", 100.0 * (f / exact - 1.0));
    assert!(f * (1.0 - TOL) <= exact && exact <= fails * (1.0 + TOL), "{what}: [{f}, {fails}] against {exact}");
}

/// With the cohesion kept where the plane slips (residual_cohesion = c),
/// the load steps hold and the search finds Hoek & Bray's F dry, with V
/// and with U and V; the plane's water is U = 1/2 gw z_w A.
#[test]
fn a_slope_held_by_its_cohesion_slides_at_hoek_and_brays_factor_dry_and_wet() {
    let case = planar::case("planar-slide-held");
    let (u, _) = planar::water_forces();
    for (name, water, crack, exact) in planar::waters() {
        case.write(&format!("{name}.toml"), &planar::scene(&planar::kept(), water, crack));
        let o = case.cli(&["solve", &format!("{name}.toml"), "--out", name, "--quiet"]);
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        let s = json(&case.dir.join(name).join("summary.json"));
        assert_bracket(name, &s["safety"], exact);
        assert_eq!(s["safety"]["decided"].as_bool(), Some(true), "{name}");
        if !water.is_empty() {
            let uplift = s["water"][0]["uplift"].as_f64().expect("the plane's uplift");
            assert!((uplift / u - 1.0).abs() < 1e-9, "U = {uplift} against 1/2 gw z_w A = {u}");
        }
    }
}

/// Silent on residual_cohesion (0 by default), the load step loses the
/// cohesion where the plane slips and cannot stand on friction alone:
/// exit status 1, yet the message and summary.json give the peak
/// strength's F, which limit equilibrium keeps, at Hoek & Bray's value.
#[test]
fn the_same_slope_silent_on_its_residual_cohesion_fails_its_step_but_names_the_peak_factor() {
    let case = planar::case("planar-slide-silent");
    case.write("silent.toml", &planar::scene("", "", false));
    let o = case.cli(&["solve", "silent.toml", "--out", "silent", "--quiet"]);
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    let exact = hoek_bray(0.0, 0.0);
    says(&msg, &["unsafe as given", "stands by limit equilibrium", &format!("F = {exact:.4}")]);
    let s = json(&case.dir.join("silent/summary.json"));
    assert_eq!(s["safety"]["strength"].as_str(), Some("peak"));
    assert_bracket("silent", &s["safety"], exact);
}
