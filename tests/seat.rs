//! A block sliding round a curved, faceted seat: a half-disc of radius R
//! in a semicircular cradle cut into the ground (contact "seat", linear
//! facets of unequal length: the mesh size differs at the arc's ends and
//! its bottom), gravity turned by theta. The one motion the cradle leaves
//! free is the rotation about the arc's centre O; friction alone holds it.
//!
//! Goal (issue 29): the mechanism of the failing trial is named the way
//! the solver's own check of free parts saw it. The facets' normals are a
//! few 1e-4 off the radius, so tying the slipping pairs by their normals
//! exactly held the rotation (weakly) and no mechanism was named; with the
//! facets' slack ([`pair_ties`] in src/contact/mobility.rs, one rule for both)
//! the block slides round "seat", turning about O.
//!
//! ```text
//!          y
//!   +------O------+  O = (0, 0), R = 1: "block", the half-disc below y = 0
//!   |   \ blk /   |
//!   |    '---'    |  "seat": the arc, tan(phi) = 0.3
//!   |   ground    |
//!   +-------------+  "ground_bottom" held, y = -2
//! ```
//!
//! Closed forms: the block turns about O (the centre of the arc, within
//! 5 % of R). Its friction can hold at most the moment `R (tan phi / F)
//! sum N` about O, the normal forces passing through O, against gravity's
//! `W |OG| sin(theta)` (|OG| = 4 R / (3 pi)); force balance asks
//! `sum N >= W / sqrt(1 + (tan phi / F)^2)`, so at the limit
//! `F >= tan(phi) R / (|OG| sin(theta) sqrt(1 + (tan phi / F)^2))`.

mod common;

use common::{json, Case};

const THETA: f64 = 10.0;
const TAN_PHI: f64 = 0.3;

fn scene() -> String {
    let (s, c) = THETA.to_radians().sin_cos();
    format!(
        "title = \"a half-disc in a cradle, gravity turned {THETA} degrees\"\nmesh = \"seat.geo\"\n\
         analysis = \"plane_strain\"\ngravity = [{}, {}]\n\n\
         [materials.rock]\nE = 1000.0\nnu = 0.25\ndensity = 1.0\n\n\
         [[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"seat\"\nfriction = {TAN_PHI}\n\n\
         [[supports]]\ngroup = \"ground_bottom\"\nfix = [\"x\", \"y\"]\n\n[safety]\n",
        10.0 * s,
        -10.0 * c
    )
}

#[test]
fn a_block_on_a_faceted_arc_slides_round_it_about_the_arcs_centre() {
    let case = Case::new("seat");
    case.copy("tests/geo/seat.geo");
    case.write("seat.toml", &scene());
    let o = case.cli(&["solve", "seat.toml", "--out", "out", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let safety = json(&case.dir.join("out").join("summary.json"))["safety"].clone();
    let m = &safety["failure"]["mechanism"];
    assert_eq!(m["kind"], "sliding", "the mechanism named: {safety}");
    let text = m["description"].as_str().unwrap_or("");
    assert!(text.starts_with("\"block\" slides round \"seat\", turning about ("), "{text}");
    let pivot: Vec<f64> =
        m["blocks"][0]["pivot"].as_array().expect("a pivot").iter().filter_map(|v| v.as_f64()).collect();
    eprintln!("turns about ({:.4}, {:.4}) against O = (0, 0), R = 1", pivot[0], pivot[1]);
    assert!(pivot[0].hypot(pivot[1]) < 0.05, "about the arc's centre: {pivot:?}");
    // the friction circle's bound
    let f = safety["factor"].as_f64().expect("F");
    let og = 4.0 / (3.0 * std::f64::consts::PI);
    let bound = TAN_PHI / (og * THETA.to_radians().sin() * (1.0 + (TAN_PHI / f).powi(2)).sqrt());
    eprintln!("F = {f:.4}, at least {bound:.4}");
    assert!(f >= bound && f.is_finite(), "F = {f} below the bound {bound}");
}
