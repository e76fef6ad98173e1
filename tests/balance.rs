//! A converged contact answer balances: the supports' reactions carry the
//! applied loads to round-off (issue 28, tunnel4sets carried 0.95 MN in x
//! with nothing applied in x).
//!
//! Reference: equilibrium of the whole model. The in-situ stress's nodal
//! forces sum to zero over each cell, the pairs' forces are equal and
//! opposite, so Σ reactions = −Σ applied exactly, and every free DOF holds
//! nothing. Scene: tests/corpus/tunnel4sets.geo at a coarse lc (tet10, the
//! joints' faces tri6, whose pairs work in the transformed interface
//! basis), two of its joint sets, k0 = 0.7, rollers on five faces, the
//! overburden on the top. Before the pairs' forces were taken back to the
//! nodes, the remainder was (0.89, -2.52, 6.26) MN of 566.7 and the free
//! DOFs' residual 0.61 of the largest force there.

mod common;

use common::{json_vec3, Case};

const SCENE: &str = r#"
title = "balance: tunnel through two joint sets, coarse tet10"
mesh = "tunnel4sets.geo"
analysis = "solid"
gravity = [0.0, 0.0, -9.81]
merge_slivers = true
[gmsh]
order = 2
setnumber = { lc = 5.0, lc_far = 10.0 }
[materials.rock]
E = 1.0e4
nu = 0.25
density = 2.6e-3
[[bodies]]
group = "rock"
material = "rock"
k0 = 0.7
surface = 60.0
[[joint_sets]]
name = "J1"
dip = 55.0
dip_direction = 20.0
spacing = 6.0
offset = 1.0
snap = 0.5
friction = 0.75
[[joint_sets]]
name = "J3"
dip = 15.0
dip_direction = 250.0
spacing = 6.0
offset = 0.5
snap = 1.3
friction = 0.75
[[supports]]
group = "bottom"
fix = ["z"]
[[supports]]
group = "west"
fix = ["x"]
[[supports]]
group = "east"
fix = ["x"]
[[supports]]
group = "south"
fix = ["y"]
[[supports]]
group = "north"
fix = ["y"]
[[loads]]
group = "top"
pressure = 1.14777
"#;

#[test]
fn jointed_tet10_tunnel_reactions_balance_the_loads() {
    let case = Case::new("balance-tunnel-two-sets");
    case.copy("tests/corpus/tunnel4sets.geo");
    case.write("two.toml", SCENE);
    let run = case.cli(&["solve", "two.toml", "--out", "r", "--quiet"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let s = common::json(&case.dir.join("r/summary.json"));
    assert_eq!(s["contact"]["converged"], serde_json::Value::Bool(true));
    assert!(s["contact"]["states"]["stick"].as_u64().unwrap_or(0) > 0, "the joints carry the load");
    let body = &s["reactions"]["bodies"][0];
    let (applied, remainder) = (json_vec3(&body["applied"]), json_vec3(&body["remainder"]));
    let scale = applied.iter().map(|v| v.abs()).fold(0.0, f64::max);
    assert!(scale > 500.0, "the weight and the overburden: {applied:?}");
    for (c, r) in remainder.iter().enumerate() {
        assert!(r.abs() <= 1e-9 * scale, "component {c}: loads + contacts + supports = {r} of {scale}");
    }
    let free = s["reactions"]["free_residual"].as_f64().expect("free_residual");
    assert!(free < 1e-9, "the free DOFs at the supports hold {free} of the largest force there");
}
