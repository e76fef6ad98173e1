//! The initial equilibrium stage (`[solver] initial_stage = true`): a step
//! 0 that holds the bodies' outer faces at their in-situ traction, so the
//! rock mass comes to equilibrium with its joints active before any load,
//! its displacements then taken off every step's.
//!
//! A box of rock (plane strain, tri6) 10 m wide, 8 m high, rollers at the
//! sides, fixed at the base, its top the ground surface, cut by a joint
//! dipping 60 degrees from the base to the top. Geostatic stress: sigma_v
//! = -rho g depth, sigma_h = k0 sigma_v. On the joint (Mohr) sigma_n =
//! sigma_v (cos^2 60 + k0 sin^2 60) and tau = (1 - k0) sigma_v sin 60 cos
//! 60: tau / |sigma_n| = 0.3849 with k0 = 0.5 (below tan 35 = 0.7002: the
//! joint carries it), 0.7423 with k0 = 0.25 (beyond: it slips).

mod common;

use common::measure::max_abs;
use common::{json, Case};
use subcontact::driver::Run;

const GEO: &str = r#"
DefineConstant[ lc = {1.0, Name "lc"} ];
x0 = 2.0; x1 = 2.0 + 8.0 / Tan(Pi / 3);
Point(1) = {0, 0, 0, lc}; Point(2) = {x0, 0, 0, lc}; Point(3) = {10, 0, 0, lc};
Point(4) = {10, 8, 0, lc}; Point(5) = {x1, 8, 0, lc}; Point(6) = {0, 8, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Physical Surface("foot") = {1};
Physical Surface("hanging") = {2};
Physical Curve("joint") = {7};
Physical Curve("base") = {1, 2};
Physical Curve("left") = {6};
Physical Curve("right") = {3};
Physical Curve("top") = {4, 5};
"#;

const RHO_G: f64 = 2.7e-3 * 9.81;
const E: f64 = 1.0e3;

/// The scene: geostatic stress with `k0`, the joint at tan 35 degrees,
/// `stage` the initial stage's key, `loads` more TOML.
fn scene(k0: f64, stage: bool, loads: &str) -> String {
    format!(
        r#"mesh = "box.geo"
analysis = "plane_strain"
gravity = [0.0, -9.81]
[gmsh]
order = 2
[materials.rock]
E = {E}
nu = 0.25
density = 2.7e-3
[[bodies]]
group = "foot"
material = "rock"
k0 = {k0}
surface = 8.0
[[bodies]]
group = "hanging"
material = "rock"
k0 = {k0}
surface = 8.0
[[contacts]]
group = "joint"
friction = 0.7002075382097097
[[supports]]
group = "base"
fix = ["x", "y"]
[[supports]]
group = "left"
fix = ["x"]
[[supports]]
group = "right"
fix = ["x"]
[solver]
initial_stage = {stage}
[output]
fields = ["displacement", "stress"]
{loads}"#
    )
}

fn run(name: &str, toml: &str) -> (Case, Run) {
    let case = Case::new(name);
    case.write("box.geo", GEO);
    let run = case.run(&case.write("box.toml", toml)).expect("run");
    (case, run)
}

/// The weight alone would move the top by rho g H^2 / (2 M), M the
/// constrained modulus: the displacement that "nothing moves" is measured
/// against.
fn reference() -> f64 {
    let nu: f64 = 0.25;
    let m = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    RHO_G * 64.0 / (2.0 * m)
}

const PRESSURE: &str = "[[loads]]\ngroup = \"top\"\npressure = 0.05\n";

#[test]
fn a_joint_that_carries_the_in_situ_stress_moves_nothing_in_the_stage() {
    let (case, on) = run("stage-holds", &scene(0.5, true, PRESSURE));
    let stage = on.initial_stage.as_ref().expect("the stage ran");
    let pairs = on.model.pairs.len();
    assert!(pairs > 10, "{pairs} pairs");
    assert!(stage.converged);
    assert_eq!(stage.states, [0, 0, pairs], "every pair sticks in the stage");
    assert!(stage.largest < 1e-12 * reference(), "stage moved {:e} of {:e}", stage.largest, reference());
    // the hold load and gravity at 1, the pressure at 0
    let s = json(&case.out("box").join("summary.json"));
    let i = &s["initial_stage"];
    assert_eq!(i["states"]["stick"], pairs);
    assert!(i["largest_displacement"].as_f64().expect("number") < 1e-12 * reference());
    let report = common::read(&case.out("box").join("report.md"));
    assert!(report.contains("| initial equilibrium stage"), "report.md has no stage line");
    // the stage changes nothing here: the load step is the run without it
    let (_, off) = run("stage-holds-off", &scene(0.5, false, PRESSURE));
    assert!(off.initial_stage.is_none());
    let (u_on, u_off) = (&on.last().u, &off.last().u);
    let scale = max_abs(u_off.iter().copied());
    // the pressure settles the top by about p H / M
    assert!(scale > 0.1 * 0.05 * 8.0 / (E * 1.2), "{scale:e}");
    let diff = max_abs(u_on.iter().zip(u_off).map(|(a, b)| a - b));
    assert!(diff < 1e-9 * scale, "the stage changed the displacements by {diff:e} of {scale:e}");
    let (c_on, c_off) = (on.contact().expect("contact"), off.contact().expect("contact"));
    assert_eq!(c_on.states, c_off.states);
}

#[test]
fn a_joint_beyond_its_strength_slips_in_the_stage_and_the_loads_start_from_there() {
    // today's first load step: the in-situ stress alone slips the joint
    let (_, off) = run("stage-slips-off", &scene(0.25, false, ""));
    let c_off = off.contact().expect("contact");
    let slipping = c_off.states.iter().filter(|s| s.code() == 1).count();
    assert!(slipping > 0, "the joint does not slip without the stage");
    let moved = max_abs(off.last().u.iter().copied());
    assert!(moved > 1e-3 * reference(), "it moved {moved:e}");
    // the stage does the same, and the load step after it moves nothing more
    let (case, on) = run("stage-slips", &scene(0.25, true, ""));
    let stage = on.initial_stage.as_ref().expect("the stage ran");
    assert!(stage.states[1] > 0, "no pair slips in the stage: {:?}", stage.states);
    let c_on = on.contact().expect("contact");
    assert_eq!(c_on.states, c_off.states, "the step after the stage keeps its state");
    let stage_diff = max_abs(stage.u.iter().zip(&off.last().u).map(|(a, b)| a - b));
    assert!(stage_diff < 1e-8 * moved, "the stage is today's first step: {stage_diff:e} of {moved:e}");
    let reported = max_abs(on.last().u.iter().copied());
    assert!(reported < 1e-8 * moved, "no load, yet {reported:e} reported after the stage ({moved:e} in it)");
    // stresses and pair forces stay totals: those of the run without the stage
    for (a, b) in c_on.pairs.iter().zip(&c_off.pairs) {
        assert!((a.sigma_n - b.sigma_n).abs() < 1e-8 * RHO_G * 8.0, "sigma_n {} against {}", a.sigma_n, b.sigma_n);
    }
    let s = json(&case.out("box").join("summary.json"));
    assert!(s["initial_stage"]["states"]["slip"].as_u64().expect("count") > 0);
    let warned = s["warnings"].as_array().expect("warnings").iter().any(|w| {
        w.as_str().is_some_and(|w| w.contains("beyond its strength") && w.contains("initial equilibrium stage"))
    });
    assert!(warned, "the in-situ warning does not say the stage was used: {}", s["warnings"]);
}

#[test]
fn after_the_stage_a_load_reports_its_own_displacements_alone() {
    // with the joint slipped in the stage, a surface pressure: what is
    // reported is the pressure's own displacement, the stage's taken off
    let (_, with_load) = run("stage-load", &scene(0.25, true, PRESSURE));
    let stage = with_load.initial_stage.as_ref().expect("the stage ran");
    let total: Vec<f64> = stage.total(&with_load.last().u);
    let (_, off) = run("stage-load-off", &scene(0.25, false, PRESSURE));
    // the two-step path (stage, then load) ends where the one step does
    // when the joint slips the same way in both
    let c = (with_load.contact().expect("contact"), off.contact().expect("contact"));
    if c.0.states == c.1.states {
        let scale = max_abs(off.last().u.iter().copied());
        let diff = max_abs(total.iter().zip(&off.last().u).map(|(a, b)| a - b));
        assert!(diff < 1e-6 * scale, "total after the stage {diff:e} from the one-step run ({scale:e})");
    }
    // the top settles under the pressure: downward, and less than the total
    let reported = max_abs(with_load.last().u.iter().copied());
    assert!(reported > 0.0 && reported < max_abs(total.iter().copied()) + 1e-30);
}
