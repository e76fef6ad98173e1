//! What a foundation engineer reads besides the contact states: the
//! load–settlement picture of the probes over the load steps, and the
//! bearing pressure of a base with water in its joint, effective and total.
//!
//! Reference: the statics of a rigid block (any statics text). A block of
//! weight W on a wet base with water against its upstream face: the base
//! carries the total normal force W whatever the water under it, acting at
//! x = B/2 + H_w h / (3 W) from the heel (H_w = gw h^2 / 2, at h/3); the
//! effective force is W - U (U = u B, the uplift of a uniform u).
//!
//! Goal: (1) `settlement.svg` is written for a scene with probes and
//! several load steps, one curve per probe, at its stated size, and not
//! for one step; (2) `bearing.csv` of a wet base has the total columns:
//! total = effective + water to round-off, the total force W and its
//! point of action the statics' to 1e-6; a dry scene keeps its header.
//!
//! ```text
//!        ~~~ h = 3          block B = 4, H = 3 (gamma_c = 2.4 x 9.81)
//!   H_w ->|########|
//!         |########|
//!   ------+========+------  base: f = 0.7, f_t = 0; water level 3
//!   |        rock         |
//!   +---------------------+  bottom held
//! ```

mod common;

use common::{csv_num, csv_rows, json, Case};

const GW: f64 = 9.81;
const B: f64 = 4.0;
const HB: f64 = 3.0;
const LEVEL: f64 = 3.0;
const W: f64 = B * HB * 2.4 * 9.81;

/// The block on rock, meshed with quadratic quads and triangles.
const BLOCK_GEO: &str = r#"SetFactory("OpenCASCADE");
Rectangle(1) = {-4, -4, 0, 12, 4};
Rectangle(2) = {0, 0, 0, 4, 3};
BooleanFragments{ Surface{1, 2}; Delete; }{}
e = 1e-6;
Physical Surface("rock") = {Surface In BoundingBox{-4 - e, -4 - e, -e, 8 + e, e, e}};
Physical Surface("block") = {Surface In BoundingBox{-e, -e, -e, 4 + e, 3 + e, e}};
Physical Curve("base") = {Curve In BoundingBox{-e, -e, -e, 4 + e, e, e}};
Physical Curve("upstream") = {Curve In BoundingBox{-e, -e, -e, e, 3 + e, e}};
Physical Curve("bottom") = {Curve In BoundingBox{-4 - e, -4 - e, -e, 8 + e, -4 + e, e}};
Mesh.CharacteristicLengthMax = 0.5;
"#;

/// The block scene; `water`: the base's water entry (empty: dry).
fn block(water: &str) -> String {
    format!(
        "title = \"block on a wet base\"\nmesh = \"block.geo\"\nanalysis = \"plane_strain\"\ngravity = [0.0, -9.81]\n\n[gmsh]\norder = 2\n\n\
         [materials.concrete]\nE = 2.5e7\nnu = 0.2\ndensity = 2.4\n\n[materials.rock]\nE = 2.0e7\nnu = 0.25\n\n\
         [[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"block\"\nmaterial = \"concrete\"\n\n\
         [[contacts]]\ngroup = \"base\"\nfriction = 0.7\ntensile_strength = 0.0\n{water}\n\n\
         [[supports]]\ngroup = \"bottom\"\nfix = [\"x\", \"y\"]\n\n\
         [[loads]]\ngroup = \"upstream\"\npressure = {{ surface = {LEVEL}, unit_weight = {GW} }}\n"
    )
}

/// (2) The wet base: total = effective + water, the total the block's
/// statics; the dry base keeps the header it had.
#[test]
fn a_wet_base_reports_effective_water_and_total_bearing() {
    let case = Case::new("engineer-wet-base");
    case.write("block.geo", BLOCK_GEO);
    let wet = case.write("wet.toml", &block(&format!("water = {{ level = {LEVEL}, unit_weight = {GW} }}")));
    case.run(&wet).expect("the wet block solves");
    let rows = csv_rows(&case.out("wet").join("bearing.csv"));
    let base = rows.iter().find(|r| r["contact"] == "base" && r["block_i"].is_empty()).expect("the base's row");
    let (n_eff, water, n_tot) =
        (csv_num(base, "normal_force"), csv_num(base, "water_force"), csv_num(base, "normal_force_total"));
    let uplift = GW * LEVEL * B;
    let h_w = GW * LEVEL * LEVEL / 2.0;
    let x_total = B / 2.0 + h_w * LEVEL / (3.0 * W);
    let x_got = csv_num(base, "x_p_total");
    eprintln!(
        "wet base: N' = {n_eff:.6}, U = {water:.6} (u B = {uplift:.6}), N = {n_tot:.6} (W = {W:.6}); total acts at x = {x_got:.6} (statics {x_total:.6}), e = {:.6}",
        csv_num(base, "e_1_total")
    );
    assert!((n_eff + water - n_tot).abs() < 1e-9 * W, "total = effective + water");
    assert!((water / uplift - 1.0).abs() < 1e-9, "U = u B: {water} against {uplift}");
    assert!((n_tot / W - 1.0).abs() < 1e-6, "N + U = W: {n_tot} against {W}");
    assert!((x_got - x_total).abs() < 1e-6 * B, "where the total acts: {x_got} against {x_total}");
    // e along the face's tangent t1 (n of side I turned +90 degrees)
    let e_x = csv_num(base, "e_1_total") * csv_num(base, "t1_x");
    assert!((e_x - (x_total - B / 2.0)).abs() < 1e-6 * B, "its eccentricity: {e_x}");
    let s = json(&case.out("wet").join("summary.json"));
    let g = &s["bearing"][0];
    assert!((g["total"]["force"].as_f64().expect("total force") - n_tot).abs() < 1e-9 * W, "summary.json agrees");
    // the dry base: the header it always had, no water columns
    let dry = case.write("dry.toml", &block(""));
    case.run(&dry).expect("the dry block solves");
    let text = common::read(&case.out("dry").join("bearing.csv"));
    let head = text.lines().next().expect("header");
    assert!(head.ends_with(",p_mean,p_design,window,in_kern") && !head.contains("total"), "{head}");
}

/// The beam of tests/point_loads.rs with a point load ramped over
/// `steps` load steps and two probes.
fn beam(steps: usize) -> String {
    format!(
        "title = \"beam\"\nmesh = \"beam2d.geo\"\nanalysis = \"plane_strain\"\n\n[gmsh]\norder = 2\n\n[materials.m]\nE = 1000.0\nnu = 0.25\n\n\
         [[bodies]]\ngroup = \"beam\"\nmaterial = \"m\"\n\n[[supports]]\ngroup = \"pin\"\nfix = [\"x\", \"y\"]\n\n\
         [[supports]]\ngroup = \"roller\"\nfix = [\"y\"]\n\n[[loads]]\ngroup = \"load\"\nforce = [0.0, -10.0]\n\n\
         [solver]\nload_steps = {steps}\n\n[[probes]]\nname = \"bottom\"\nfrom = [0.5, 0.0]\nto = [3.5, 0.0]\npoints = 7\n\n\
         [[probes]]\nname = \"quarter\"\nfrom = [1.0, 0.0]\nto = [1.0, 0.4]\npoints = 3\n"
    )
}

/// (1) settlement.svg: written with several load steps, one curve per
/// probe at the stated size; not written for one step.
#[test]
fn the_load_settlement_picture_has_a_curve_per_probe() {
    let case = Case::new("engineer-settlement");
    case.copy("tests/geo/beam2d.geo");
    let scene = case.write("ramp.toml", &beam(4));
    case.run(&scene).expect("the beam solves");
    let svg = common::read(&case.out("ramp").join("settlement.svg"));
    assert!(svg.contains("width=\"640\"") && svg.contains("height=\"420\""), "its size");
    // a curve: a polyline through the four steps' points
    let curves = svg
        .split("<polyline")
        .skip(1)
        .filter(|p| {
            let points = p.split("points=\"").nth(1).and_then(|q| q.split('"').next()).unwrap_or("");
            points.split_whitespace().count() == 4
        })
        .count();
    eprintln!("settlement.svg: {} bytes, {curves} curves of four points", svg.len());
    assert_eq!(curves, 2, "one curve per probe");
    assert!(svg.contains("bottom (point") && svg.contains("quarter (point"), "the legend names the probes");
    let one = case.write("once.toml", &beam(1));
    case.run(&one).expect("the beam solves in one step");
    assert!(!case.out("once").join("settlement.svg").exists(), "one load step: no curve to draw");
    assert!(case.out("once").join("probes.csv").exists());
}
