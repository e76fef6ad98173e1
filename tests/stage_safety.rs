//! The factor of safety below 1 of a scene with an initial stage: every
//! trial runs the stage, then the load steps, from the start, at the
//! trial's strength (`src/driver/safety/below.rs`).
//!
//! Reference: a Coulomb block. A 2 x 1 m block (plane strain, tri6) sits
//! on a horizontal joint (f = tan 20, c = 0.005) on a base fixed at its
//! bottom; both carry a uniform in-situ stress σ0 (σxx = σyy = -0.1, τxy)
//! and their weight. In the stage the hold keeps the block's free faces at
//! σ0 n (the rock round it), so the joint carries the in-situ traction and
//! the weight: N = A |σyy| + W, T = A |τxy|, and the block slides once
//! F > (c A + N f) / T (every pair slipping, the block free).
//!
//! ```text
//!           +-------+        <- block, faces held at σ0 n in the stage
//!           | block |   p -> (a pressure on its left face in step 1)
//!   +-------+=======+------+ <- joint (A = 2 m), f = tan 20, c = 0.005
//!   |        base          |
//!   +----------------------+ <- fixed
//! ```
//!
//! With τxy = 0.06 the stage itself fails at F = 1 (F = 0.8506): before,
//! the search below 1 ran the load steps without the stage, they held at
//! F = 1, and it went upward to max_factor (F = 10). With τxy = 0.02 the
//! stage holds and step 1, which releases the hold (the block then
//! carries its weight and the loads alone: the in-situ stress sums to
//! nothing over it), fails under a pressure p on the block's left face
//! and q on its top: F = (c A + (q A + W) f) / p.

mod common;

use common::{json, Case};
use subcontact::driver::SafetyError;
use subcontact::Error;

const GEO: &str = r#"
DefineConstant[ lc = {0.25, Name "lc"} ];
Point(1) = {0, 0, 0, lc}; Point(2) = {4, 0, 0, lc}; Point(3) = {4, 1, 0, lc};
Point(4) = {3, 1, 0, lc}; Point(5) = {1, 1, 0, lc}; Point(6) = {0, 1, 0, lc};
Point(7) = {3, 2, 0, lc}; Point(8) = {1, 2, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {4, 7}; Line(8) = {7, 8}; Line(9) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9}; Plane Surface(2) = {2};
Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("joint") = {4};
Physical Curve("bottom") = {1};
Physical Curve("back") = {9};
Physical Curve("lid") = {8};
"#;

const FRICTION: f64 = 0.36397023426620234;
const COHESION: f64 = 0.005;
const AREA: f64 = 2.0;
/// The block's weight, ρ g V.
const WEIGHT: f64 = 2.7e-3 * 9.81 * 2.0;
const SIGMA: f64 = 0.1;

/// The scene with the in-situ shear `tau` and more TOML (`loads`).
fn scene(tau: f64, loads: &str) -> String {
    let stress = format!("initial_stress = [-{SIGMA}, -{SIGMA}, -{SIGMA}, {tau}]");
    format!(
        r#"mesh = "block.geo"
analysis = "plane_strain"
gravity = [0.0, -9.81]
[gmsh]
order = 2
[materials.rock]
E = 1.0e3
nu = 0.25
density = 2.7e-3
[[bodies]]
group = "base"
material = "rock"
{stress}
[[bodies]]
group = "block"
material = "rock"
{stress}
[[contacts]]
group = "joint"
friction = {FRICTION}
cohesion = {COHESION}
[[supports]]
group = "bottom"
fix = ["x", "y"]
[solver]
initial_stage = true
[safety]
tolerance = 1e-3
{loads}"#
    )
}

/// Where the search below 1 put F: (holds, fails from), from its error.
fn bracket(e: Error) -> (f64, f64) {
    match e.without_scene() {
        Error::Safety(s) => match *s {
            SafetyError::Unsafe { holds, fails, .. } => (holds.expect("a factor that holds"), fails),
            other => panic!("not unsafe as given: {other}"),
        },
        other => panic!("not a safety error: {other}"),
    }
}

#[test]
fn a_block_the_in_situ_shear_slides_in_the_stage_has_its_coulomb_factor() {
    let tau = 0.06;
    let exact = (COHESION * AREA + (SIGMA * AREA + WEIGHT) * FRICTION) / (tau * AREA);
    assert!(exact < 0.9, "the stage fails at F = 1: {exact}");
    let case = Case::new("stage-safety-slides");
    case.write("block.geo", GEO);
    let Err(err) = case.run(&case.write("block.toml", &scene(tau, ""))) else { panic!("unsafe as given") };
    let (holds, fails) = bracket(err);
    eprintln!("the stage slides: F in [{holds}, {fails}], (c A + N f) / T = {exact}");
    assert!(holds <= exact && exact <= fails, "F in [{holds}, {fails}], (c A + N f) / T = {exact}");
    assert!(fails - holds <= 2e-3 * exact, "the bracket [{holds}, {fails}] is wider than the tolerance");
}

#[test]
fn a_block_that_holds_in_the_stage_and_slides_under_the_load_has_its_coulomb_factor() {
    let (p, q) = (0.15, 0.12);
    // the stage holds: (c A + N f) / T at the in-situ shear 0.02
    let tau = 0.02;
    let stage = (COHESION * AREA + (SIGMA * AREA + WEIGHT) * FRICTION) / (tau * AREA);
    assert!(stage > 2.0, "the stage holds: {stage}");
    let exact = (COHESION * AREA + (q * AREA + WEIGHT) * FRICTION) / p;
    assert!(exact < 0.9, "step 1 fails at F = 1: {exact}");
    let loads = format!("[[loads]]\ngroup = \"back\"\npressure = {p}\n[[loads]]\ngroup = \"lid\"\npressure = {q}\n");
    let case = Case::new("stage-safety-step");
    case.write("block.geo", GEO);
    case.write("block.toml", &scene(tau, &loads));
    let o = case.cli(&["solve", "block.toml", "--out", "r", "--quiet"]);
    assert!(!o.status.success(), "unsafe as given");
    let s = json(&case.dir.join("r/summary.json"));
    let safety = &s["safety"];
    assert_eq!(safety["below_one"].as_bool(), Some(true));
    let (holds, fails) = (safety["factor"].as_f64().expect("factor"), safety["fails_at"].as_f64().expect("fails_at"));
    eprintln!("step 1 slides: F in [{holds}, {fails}], (c A + N f) / p = {exact}");
    assert!(holds <= exact && exact <= fails, "F in [{holds}, {fails}], (c A + N f) / p = {exact}");
    // the stage replayed before the steps that are written: it held, every
    // pair stuck, and the block settled under its weight in it
    let stage = &s["initial_stage"];
    let pairs = s["contact"]["groups"][0]["pairs"].as_u64().expect("pairs");
    assert_eq!(stage["states"]["stick"].as_u64(), Some(pairs), "{stage}");
    assert!(stage["largest_displacement"].as_f64().expect("largest") > 1e-6, "{stage}");
}

/// The in-situ shear beyond the joint's strength, the block held in the
/// stage by its weight: τ = 0.05 mobilises the joint m = τ / (c + f σ) =
/// 1.208 in situ, yet the stage holds at F = 1, (c A + (σ A + W) f) /
/// (τ A) = 1.021 (the joint keeps its cohesion where it slips: with the
/// default residual cohesion 0 the stage fails at F = 1). Step 1 then
/// slides the block at F = (c A + (q A + W) f) / p = 0.923 > 1 / m, so
/// every trial of the search below 1 runs a stage the in-situ stress puts
/// beyond the trial's strength (m F > 1: c and f are both divided by F).
/// Each solves it as the run does, through the strength ramp from 1.01 m F
/// times the trial's strength (`contact/ramp.rs`); before, the trials ran
/// it at once, the way that left the jointed tunnel of
/// tests/initial_stage.rs unconverged, and the stage written with the
/// steps was replayed that way too (no `strength_ramp`).
#[test]
fn every_trial_whose_stage_is_beyond_its_strength_runs_it_through_the_ramp() {
    let (tau, p, q) = (0.05, 0.15, 0.15);
    let m = tau / (COHESION + FRICTION * SIGMA);
    let stage = (COHESION * AREA + (SIGMA * AREA + WEIGHT) * FRICTION) / (tau * AREA);
    let exact = (COHESION * AREA + (q * AREA + WEIGHT) * FRICTION) / p;
    assert!(m > 1.2 && stage > 1.0, "beyond in situ ({m}), the stage holds ({stage})");
    assert!(exact < 0.95 && m * exact > 1.1, "step 1 fails at F = {exact}, its trials beyond in situ");
    let loads = format!("[[loads]]\ngroup = \"back\"\npressure = {p}\n[[loads]]\ngroup = \"lid\"\npressure = {q}\n");
    let keeps = format!("cohesion = {COHESION}\nresidual_cohesion = {COHESION}\n");
    let toml = scene(tau, &loads).replacen(&format!("cohesion = {COHESION}\n"), &keeps, 1);
    assert!(toml.contains("residual_cohesion"), "the joint keeps its cohesion");
    let case = Case::new("stage-safety-ramp");
    case.write("block.geo", GEO);
    case.write("block.toml", &toml);
    let o = case.cli(&["solve", "block.toml", "--out", "r"]);
    assert!(!o.status.success(), "unsafe as given");
    let s = json(&case.dir.join("r/summary.json"));
    let safety = &s["safety"];
    let (holds, fails) = (safety["factor"].as_f64().expect("factor"), safety["fails_at"].as_f64().expect("fails_at"));
    eprintln!("step 1 slides after a stage beyond in situ: F in [{holds}, {fails}], (c A + (q A + W) f) / p = {exact}");
    assert!(holds <= exact && exact <= fails, "F in [{holds}, {fails}], (c A + (q A + W) f) / p = {exact}");
    // every trial's stage came down from 1 % above its own mobilisation,
    // each trial's progress line says (F, from where)
    let err = String::from_utf8_lossy(&o.stderr);
    let ramps: Vec<(f64, f64)> = (err.lines())
        .filter_map(|l| {
            let (f, rest) = l.split_once("safety: F = ")?.1.split_once(": the initial stage in ")?;
            let top = rest.split_once("brought down from ")?.1.split(' ').next()?;
            Some((f.parse().ok()?, top.parse().ok()?))
        })
        .collect();
    let trials = safety["trials"].as_array().expect("trials");
    assert!(trials.len() >= 5, "{} trials", trials.len());
    for t in trials {
        let f = t["factor"].as_f64().expect("factor");
        let Some(&(_, top)) = ramps.iter().find(|r| (r.0 - f).abs() < 1e-4) else {
            panic!("no ramp at F = {f}: {err}")
        };
        assert!((top / (1.01 * m * f) - 1.0).abs() < 1e-3, "F = {f}: from {top}, 1.01 m F = {}", 1.01 * m * f);
    }
    // the stage written with the steps is the run's: through the ramp too
    let ramp: Vec<f64> = (s["initial_stage"]["strength_ramp"].as_array().expect("strength_ramp").iter())
        .filter_map(|v| v.as_f64())
        .collect();
    assert!(ramp.len() >= 3 && (ramp[0] / (1.01 * m) - 1.0).abs() < 1e-9, "the stage's ramp: {ramp:?}");
    assert_eq!(ramp.last(), Some(&1.0), "{ramp:?}");
}

/// A stage that fails writes no results, so the in-situ warning that says
/// why (the set the in-situ stress puts beyond its strength, and how much
/// of it) goes on stderr with the error. The stress is uniform, so every
/// pair of the joint is beyond it: τ = 0.06 > c + f σ = 0.0414.
#[test]
fn a_stage_that_fails_says_which_set_the_in_situ_stress_is_beyond() {
    let tau = 0.06;
    assert!(tau > COHESION + FRICTION * SIGMA);
    let case = Case::new("stage-fails-says");
    case.write("block.geo", GEO);
    case.write("block.toml", &scene(tau, "").replace("[safety]\ntolerance = 1e-3\n", ""));
    let o = case.cli(&["solve", "block.toml", "--out", "r", "--quiet"]);
    assert!(!o.status.success(), "the block slides in the stage");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("initial equilibrium stage"), "{err}");
    let warning = err.lines().find(|l| l.starts_with("warning:") && l.contains("the in-situ stress puts"));
    let warning = warning.unwrap_or_else(|| panic!("no in-situ warning: {err}"));
    let counts: Vec<&str> = warning.split("puts ").nth(1).expect("counts").split_whitespace().take(5).collect();
    assert_eq!(counts[1..4], ["of", "the", counts[0]], "every pair is beyond: {warning}");
    assert!(warning.contains("pairs of contact \"joint\" beyond its strength"), "{warning}");
}

/// geo/tunnel_joints.toml with an initial stage, k0 = 0.1 and its joints
/// 2.3 times weaker: the in-situ stress mobilises joints_a 2.68 times its
/// strength, so the run's stage comes down a strength ramp of 35 pieces;
/// the excavation (step 1) then frees a block at the base with the
/// residual strength, and the search below 1 runs the stage at F = 1
/// again with peak strength. Before, the trials and the replay of the
/// stage before the steps written solved it at once: the replay did not
/// converge, so no result was written (and the trial at F = 1 reached a
/// stage of its own, not the run's: F in [1.0828, 1.0836]); now both
/// solve it as the run does (343 iterations, 35 pieces from 2.708), the
/// load path holds at F = 1 with peak strength and F is sought upward
/// (F in [1.0836, 1.0844]), and the stage, the failing step's last
/// iterate and the state at F are written. About 20 s.
#[test]
fn the_stage_replayed_for_the_results_is_the_runs_through_the_ramp() {
    let case = Case::new("stage-safety-tunnel");
    case.copy("geo/tunnel_joints.geo");
    let weak = |f: f64, c: f64| format!("friction = {:.6}\ncohesion = {:.6}\n", f / 2.3, c / 2.3);
    let toml = common::scenes::edited(
        "geo/tunnel_joints.toml",
        &[
            ("k0 = 0.25\nsurface", "k0 = 0.1\nsurface"),
            ("friction = 0.4\n", &format!("friction = {:.6}\n", 0.4 / 2.3)),
            ("friction = 0.85\ncohesion = 0.1\n", &weak(0.85, 0.1)),
            ("friction = 0.85\ncohesion = 0.1\n", &weak(0.85, 0.1)),
        ],
    ) + "\n[solver]\ninitial_stage = true\n[safety]\n";
    case.write("tunnel.toml", &toml);
    let o = case.cli(&["solve", "tunnel.toml", "--out", "r", "--quiet"]);
    assert!(!o.status.success(), "the excavation frees a block at F = 1");
    let summary = case.dir.join("r/summary.json");
    assert!(summary.exists(), "no results written: {}", String::from_utf8_lossy(&o.stderr));
    let s = json(&summary);
    let stage = &s["initial_stage"];
    assert_eq!(stage["converged"], true, "{stage}");
    let ramp: Vec<f64> =
        stage["strength_ramp"].as_array().expect("strength_ramp").iter().filter_map(|v| v.as_f64()).collect();
    assert!(ramp.len() > 20 && (2.6..2.8).contains(&ramp[0]), "the stage's ramp: {ramp:?}");
    assert_eq!(ramp.last(), Some(&1.0), "{ramp:?}");
    let factor = s["safety"]["factor"].as_f64().expect("factor");
    assert!(factor >= 1.0, "the load path holds at F = 1 with peak strength: F = {factor}");
}
