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
//! 60: tau / |sigma_n| = 0.3464 with k0 = 0.5 (below tan 35 = 0.7002: the
//! joint carries it), 0.7423 with k0 = 0.25 (beyond: it slips; the in-situ
//! warning's "mobilised up to 1.060"). The same box extruded 4 m (tet10)
//! checks the 3D faces. Closed forms: nothing moves where the joint
//! carries the stress; a pressure p on the top after the stage settles the
//! confined column by `p y / M` (M the constrained modulus), the stage's
//! own displacements taken off.

mod common;

use common::measure::max_abs;
use common::{csv_num, csv_rows, json, json_vec3, Case};
use subcontact::driver::{state_counts, Run};

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

/// The same box in 3D: the section above extruded 4 m along y (tet10),
/// rollers on its four sides.
const GEO_3D: &str = r#"
DefineConstant[ lc = {2.0, Name "lc"} ];
x0 = 2.0; x1 = 2.0 + 8.0 / Tan(Pi / 3);
Point(1) = {0, 0, 0, lc}; Point(2) = {x0, 0, 0, lc}; Point(3) = {10, 0, 0, lc};
Point(4) = {10, 0, 8, lc}; Point(5) = {x1, 0, 8, lc}; Point(6) = {0, 0, 8, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
out[] = Extrude {0, 4, 0} { Surface{1, 2}; };
Physical Volume("foot") = {out[1]};
Physical Volume("hanging") = {out[7]};
Physical Surface("joint") = {out[3]};
Physical Surface("base") = {out[2], out[8]};
Physical Surface("left") = {out[5]};
Physical Surface("right") = {out[9]};
Physical Surface("front") = {1, 2};
Physical Surface("back") = {out[0], out[6]};
Physical Surface("top") = {out[4], out[10]};
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
{}
[solver]
initial_stage = {stage}
[output]
fields = ["displacement", "stress"]
{loads}"#,
        common::scenes::on_rollers("base")
    )
}

/// `scene` in 3D: gravity along -z, the front and back on rollers too.
fn scene_3d(k0: f64, loads: &str) -> String {
    scene(k0, true, loads).replace("plane_strain", "solid").replace("[0.0, -9.81]", "[0.0, 0.0, -9.81]").replace(
        "fix = [\"x\", \"y\"]",
        "fix = [\"x\", \"y\", \"z\"]\n[[supports]]\ngroup = \"front\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"back\"\nfix = [\"y\"]",
    )
}

fn run(name: &str, toml: &str) -> (Case, Run) {
    let case = Case::new(name);
    case.write("box.geo", if toml.contains("solid") { GEO_3D } else { GEO });
    let run = case.run(&case.write("box.toml", toml)).expect("run");
    (case, run)
}

/// A piece of the stage's strength ramp that does not converge is halved
/// as a load step is, and each attempt is said on the terminal as it
/// ends, with the joints' strengths it ran between: the in-situ stress at
/// k0 = 0.25 mobilises the joint up to 1.060, so the ramp starts at
/// 1.071 times its strength and comes down in three pieces (1.047 the
/// first's end). Two iterations a piece are too few here (three are
/// enough), and one cut leaves the stage unconverged.
#[test]
fn a_stage_piece_halved_is_said_with_its_strengths() {
    let case = Case::new("stage-said");
    case.write("box.geo", GEO);
    let solver = "initial_stage = true\nmax_iterations = 2\nmax_cuts = 1\nrigid_fallback = false";
    case.write("box.toml", &scene(0.25, true, "").replace("initial_stage = true", solver));
    let o = case.cli(&["solve", "box.toml", "--out", "box"]);
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "two iterations a piece and one cut do not end the stage:\n{said}");
    let first = "initial stage, the joints' strength 1.071 -> 1.047 times theirs: not converged in 2 iteration(s) (";
    let halves = "solving it again in two halves from where it started, up to 2 iterations each";
    let half = "initial stage, the joints' strength 1.071 -> 1.059 times theirs: not converged in 2 iteration(s) (";
    common::cli::says(&said, &[first, halves, half]);
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

/// The largest departure of `u` from the confined column's settlement
/// under a pressure p on its top, `u_v = -p v / M` along the vertical axis
/// `v`, nothing across it.
fn from_column(run: &Run, u: &[f64], p: f64) -> f64 {
    let (model, nd) = (&run.model, run.model.nd);
    let v = nd - 1;
    let m = E * 0.75 / (1.25 * 0.5);
    (0..model.n_nodes())
        .map(|k| {
            let x = model.coords[k][v];
            (0..nd)
                .map(|c| if c == v { (u[k * nd + c] + p * x / m).abs() } else { u[k * nd + c].abs() })
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// The column's settlement at the top under the pressure of `PRESSURE`.
fn settlement() -> f64 {
    0.05 * 8.0 / (E * 0.75 / (1.25 * 0.5))
}

#[test]
fn after_the_stage_a_load_reports_its_own_displacements_alone() {
    // the joint slipped in the stage, then a pressure p on the top: its
    // increment on the joint, d tau / d sigma_n = (1 - nu / (1 - nu)) sin 60
    // cos 60 / (cos^2 60 + nu / (1 - nu) sin^2 60) = 0.577 < tan 35, sticks
    // it, so what is reported is the confined column's own settlement
    // u_y = -p y / M, u_x = 0 (the stage's displacements taken off)
    let (_, run) = run("stage-load", &scene(0.25, true, PRESSURE));
    let stage = run.initial_stage.as_ref().expect("the stage ran");
    assert!(stage.states[1] > 0, "the stage slips the joint: {:?}", stage.states);
    let reported = from_column(&run, &run.last().u, 0.05);
    let total = from_column(&run, &stage.total(&run.last().u), 0.05);
    let scale = settlement();
    assert!(reported < 0.005 * scale, "reported: {reported:e} from -p y / M ({scale:e}); with the stage's {total:e}");
    assert!(total > 0.02 * scale, "the stage moved too little to tell: {total:e} of {scale:e}");
}

#[test]
fn in_3d_the_stage_holds_a_joint_that_carries_the_stress_and_slips_one_that_cannot() {
    // k0 = 0.5: the tet10 faces take the hold load, nothing moves
    let (_, held) = run("stage-3d-holds", &scene_3d(0.5, ""));
    let stage = held.initial_stage.as_ref().expect("the stage ran");
    let pairs = held.model.pairs.len();
    assert!(pairs > 20, "{pairs} pairs");
    assert_eq!(stage.states, [0, 0, pairs], "every pair sticks in the stage");
    assert!(stage.largest < 1e-12 * reference(), "stage moved {:e} of {:e}", stage.largest, reference());
    // k0 = 0.25: it slips in the stage; a pressure then settles the column
    let (_, run) = run("stage-3d-load", &scene_3d(0.25, PRESSURE));
    let stage = run.initial_stage.as_ref().expect("the stage ran");
    assert!(stage.states[1] > pairs / 2, "the stage slips the joint: {:?}", stage.states);
    let reported = from_column(&run, &run.last().u, 0.05);
    let total = from_column(&run, &stage.total(&run.last().u), 0.05);
    let scale = settlement();
    // (every pair sticks under the load: the column exactly)
    assert!(reported < 1e-9 * scale, "reported: {reported:e} from -p z / M ({scale:e}); with the stage's {total:e}");
    assert!(total > 0.02 * scale, "the stage moved too little to tell: {total:e} of {scale:e}");
}

/// `scene_3d` with the stage, or without it and gravity in two equal steps.
fn still_3d(stage: bool) -> String {
    let toml = scene_3d(0.25, "");
    if stage {
        return toml;
    }
    toml.replace("initial_stage = true", "initial_stage = false\nload_steps = 2\ngravity_factors = [1.0, 1.0]")
}

#[test]
fn in_3d_a_step_that_changes_nothing_after_the_joint_slipped_ends_at_once() {
    // the pairs the stage slipped sit on their bound with a slip of
    // round-off in the next step (1e-21 to 1e-19): admissible stuck and
    // slipping, each keeps its state (they flipped on their round-off: 400
    // iterations and 3 cuts before)
    let (_, on) = run("stage-3d-still", &still_3d(true));
    let stage = on.initial_stage.as_ref().expect("the stage ran");
    let pairs = on.model.pairs.len();
    assert!(stage.converged && stage.states[1] > pairs / 2, "the stage slips the joint: {:?}", stage.states);
    let c = on.contact().expect("contact");
    let it = (c.summary.iterations, c.summary.cuts);
    assert!(c.summary.converged && it.0 <= 3 && it.1 == 0, "no load, yet {it:?} iterations and cuts");
    assert_eq!(state_counts(&c.states), stage.states, "the step keeps the stage's states");
    let moved = max_abs(on.last().u.iter().copied());
    assert!(moved < 1e-8 * stage.largest, "no load, yet {moved:e} after the stage ({:e} in it)", stage.largest);
    // without the stage: gravity in two equal steps, the second the first's
    let (_, two) = run("two-equal-steps-3d", &still_3d(false));
    assert_eq!(two.steps.len(), 2);
    let [first, second] = [0, 1].map(|k| two.steps[k].contact.as_ref().expect("contact"));
    assert!(first.summary.converged && first.states.iter().filter(|s| s.code() == 1).count() > pairs / 2);
    let it = (second.summary.iterations, second.summary.cuts);
    assert!(second.summary.converged && it.0 <= 3 && it.1 == 0, "the same load again: {it:?} iterations and cuts");
    assert_eq!(first.states, second.states, "the second step keeps the first's states");
    let (u1, u2) = (&two.steps[0].u, &two.steps[1].u);
    let diff = max_abs(u1.iter().zip(u2).map(|(a, b)| a - b));
    assert!(diff < 1e-8 * max_abs(u1.iter().copied()), "the second step moved {diff:e}");
}

/// A circular opening (R = 2 m) in a 16 x 4 x 16 m box (OpenCASCADE,
/// tet10, its wall curved), the rock cut by `[[joint_sets]]`.
const TUNNEL_GEO: &str = r#"
SetFactory("OpenCASCADE");
W = 16; L = 4; H = 16; R = 2;
Box(1) = {-W / 2, 0, -H / 2, W, L, H};
Cylinder(2) = {0, -1, 0, 0, L + 2, 0, R};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("top") = Surface In BoundingBox{-W / 2 - e, -e, H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("bottom") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, -H / 2 + e};
Physical Surface("sides") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, -W / 2 + e, L + e, H / 2 + e};
Physical Surface("sides") += Surface In BoundingBox{W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("ends") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, e, H / 2 + e};
Physical Surface("ends") += Surface In BoundingBox{-W / 2 - e, L - e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
wall() = Surface In BoundingBox{-R - e, -e, -R - e, R + e, L + e, R + e};
Physical Surface("wall") = {wall()};
MeshSize{ PointsOf{ Volume{1}; } } = 4.0;
MeshSize{ PointsOf{ Surface{wall()}; } } = 1.5;
Mesh.HighOrderOptimize = 2;
"#;

/// The tunnel 50 m deep (its top 42 m down), k0 = 0.5, two joint sets
/// striking along the tunnel (60/090 and 70/270, tau / sigma_n 0.346 and
/// 0.288 < tan 35), the sides and base fixed, the ends on rollers (normal
/// to the sets' strike), the overburden rho g 42 m on the top after the
/// stage.
const TUNNEL: &str = r#"
mesh = "tunnel.geo"
analysis = "solid"
gravity = [0.0, 0.0, -9.81]
[gmsh]
order = 2
[materials.rock]
E = 5000.0
nu = 0.25
density = 2.7e-3
[[bodies]]
group = "rock"
material = "rock"
k0 = 0.5
surface = 50.0
[[joint_sets]]
name = "J1"
dip = 60.0
dip_direction = 90.0
spacing = 5.0
offset = 1.3
friction = 0.7002
[[joint_sets]]
name = "J2"
dip = 70.0
dip_direction = 270.0
spacing = 5.0
offset = 0.7
friction = 0.7002
[[supports]]
group = "sides"
fix = ["x", "y", "z"]
[[supports]]
group = "bottom"
fix = ["x", "y", "z"]
[[supports]]
group = "ends"
fix = ["y"]
[[loads]]
group = "top"
pressure = 1.112454
[solver]
initial_stage = true
"#;

#[test]
fn a_jointed_tet10_tunnel_stays_put_in_the_stage() {
    let case = Case::new("stage-tunnel");
    case.write("tunnel.geo", TUNNEL_GEO);
    let run = case.run(&case.write("tunnel.toml", TUNNEL)).expect("run");
    let stage = run.initial_stage.as_ref().expect("the stage ran");
    let pairs = run.model.pairs.len();
    assert!(pairs > 500, "{pairs} pairs: the sets cut the rock");
    assert_eq!(stage.states, [0, 0, pairs], "every pair sticks in the stage");
    assert!(stage.iterations <= 2, "{} iterations", stage.iterations);
    // rho g H^2 / 2M of the 16 m box; what is left is the quadrature of
    // the curved tet10 at the wall (the tunnel without joints: 1.7e-8 m)
    let m = 5000.0 * 0.75 / (1.25 * 0.5);
    let scale = RHO_G * 256.0 / (2.0 * m);
    assert!(stage.largest < 1e-4 * scale, "the stage moved {:e} of {scale:e}", stage.largest);
}

/// The same tunnel on rollers (sides held in x, base in z): the sets meet
/// the sides obliquely (60 and 70 degrees), and the pairs there keep the
/// joints' own frames (`contact/frame.rs`). Before, the 70-degree set's
/// normal was turned onto x there, its pressure went into the support and
/// its pairs slipped at σn = 0: the stage took 4 iterations, 12 pairs
/// slipped and the rock moved 5.9e-4 m (ρgH²/2M = 5.6e-4). Now it stays
/// put as with fixed sides.
#[test]
fn the_jointed_tunnel_on_rollers_stays_put_in_the_stage_too() {
    let case = Case::new("stage-tunnel-rollers");
    case.write("tunnel.geo", TUNNEL_GEO);
    let on_rollers = TUNNEL
        .replacen("group = \"sides\"\nfix = [\"x\", \"y\", \"z\"]", "group = \"sides\"\nfix = [\"x\"]", 1)
        .replacen("group = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]", "group = \"bottom\"\nfix = [\"z\"]", 1);
    assert_ne!(on_rollers, TUNNEL, "the scene's supports are edited");
    let run = case.run(&case.write("tunnel.toml", &on_rollers)).expect("run");
    let stage = run.initial_stage.as_ref().expect("the stage ran");
    let pairs = run.model.pairs.len();
    assert_eq!(stage.states, [0, 0, pairs], "every pair sticks in the stage");
    assert!(stage.iterations <= 2, "{} iterations", stage.iterations);
    let m = 5000.0 * 0.75 / (1.25 * 0.5);
    let scale = RHO_G * 256.0 / (2.0 * m);
    assert!(stage.largest < 1e-4 * scale, "the stage moved {:e} of {scale:e}", stage.largest);
}

/// The tunnel on rollers at k0 = 0.25: both sets are beyond tan 35 in
/// situ (mobilised 1.060 and 1.019 of it), so the stage slips them.
/// Solved at the scene's strength at once, the stage changed 120-220 of
/// its 884 pairs every iteration where the two sets cross and did not
/// converge (400 iterations, 3 cuts: docs/convergence.md, "Where two sets
/// cross in 3D"); halving the stage's load cannot help, every fraction of
/// it mobilises the joints alike. The strength ramp (`contact/ramp.rs`)
/// starts where none is beyond and brings it down in pieces of at most
/// 3 %: 13 iterations to 469 stick / 415 slip. Step 1 (the overburden on
/// the top) is not asserted, and its rigid joints do not fall back (with
/// joints that deform the crown wedge of body "rock #9" falls at step 1,
/// and the run writes nothing).
#[test]
fn at_k0_a_quarter_the_jointed_tunnel_finds_the_stage_where_the_sets_cross() {
    let case = Case::new("stage-tunnel-k0-quarter");
    case.write("tunnel.geo", TUNNEL_GEO);
    let scene = quarter_on_rollers(TUNNEL) + "max_iterations = 40\nmax_cuts = 0\nrigid_fallback = false\n";
    assert!(scene.contains("k0 = 0.25") && scene.contains("fix = [\"z\"]"), "the scene is edited");
    // (step 1 may or may not converge in 40: the stage's answer is written either way)
    let run = case.run(&case.write("tunnel.toml", &scene));
    let summary = case.out("tunnel").join("summary.json");
    let failed = run.err().map(|e| format!("{e:#}")).unwrap_or_default();
    assert!(summary.exists(), "no results: {failed}");
    let s = json(&summary);
    let stage = &s["initial_stage"];
    let iterations = stage["iterations"].as_u64().expect("the stage's iterations");
    assert_eq!(stage["converged"], true, "the stage converges: {stage}");
    assert!(iterations <= 30, "{iterations} iterations in the stage");
    let slip = stage["states"]["slip"].as_u64().expect("slip count");
    assert!(slip > 100, "the sets slip in the stage: {stage}");
    // the ramp: from just above the largest mobilisation (1.060) down to 1
    let ramp: Vec<f64> =
        stage["strength_ramp"].as_array().expect("strength_ramp").iter().filter_map(|v| v.as_f64()).collect();
    assert!(ramp.len() >= 3, "the strength came down in pieces: {ramp:?}");
    assert!((1.06..1.08).contains(&ramp[0]), "the ramp starts above the mobilisation 1.060: {ramp:?}");
    assert_eq!(ramp.last(), Some(&1.0), "it ends at the scene's strength: {ramp:?}");
    assert!(ramp.windows(2).all(|w| w[1] < w[0] && w[0] / w[1] <= 1.03 + 1e-12), "pieces of at most 3 %: {ramp:?}");
    // the report says it
    let report = std::fs::read_to_string(case.out("tunnel").join("report.md")).expect("report.md");
    assert!(report.contains("strength brought down from 1.07"), "report.md says the ramp");
}

/// The same tunnel with the fallback on: step 1's rigid joints do not
/// converge (given 40 iterations; since fd096fc at the latest they
/// settle at the 22nd on states whose forces break the law, residual
/// 0.26 of the largest traction, where this test had asserted the 40),
/// and with joints that deform the crown
/// wedge falls. The run is refused and writes no results, and its message
/// names the body and says it was the run with joints that deform, and
/// their stiffness, that found it (the warning before it says why).
#[test]
#[ignore = "make stress: about 35 s"]
fn a_fallback_that_finds_a_falling_block_says_it_was_the_fallback() {
    let case = Case::new("stage-tunnel-k0-quarter-fallback");
    case.write("tunnel.geo", TUNNEL_GEO);
    case.write("tunnel.toml", &(quarter_on_rollers(TUNNEL) + "max_iterations = 40\nmax_cuts = 0\n"));
    let o = case.cli(&["solve", "tunnel.toml", "--out", "out", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let error = err.lines().find(|l| l.starts_with("error: ")).unwrap_or_else(|| panic!("an error line: {err}"));
    common::cli::says(
        error,
        &[
            "tunnel.toml: ",
            "\"rock #9\"",
            "(in the run with joints that deform, normal_stiffness = ",
            "rigid_fallback = false",
        ],
    );
    common::cli::says(&err, &["warning: rigid joints did not converge at load step 1 ("]);
    for file in ["summary.json", "contact.csv", "report.md"] {
        assert!(!case.dir.join("out").join(file).exists(), "a refused run writes no {file} (its mesh it keeps)");
    }
}

/// `tunnel` at k0 = 0.25, its sides and base on rollers (x and z held).
fn quarter_on_rollers(tunnel: &str) -> String {
    tunnel
        .replacen("k0 = 0.5", "k0 = 0.25", 1)
        .replacen("group = \"sides\"\nfix = [\"x\", \"y\", \"z\"]", "group = \"sides\"\nfix = [\"x\"]", 1)
        .replacen("group = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]", "group = \"bottom\"\nfix = [\"z\"]", 1)
}

/// The k0 = 0.25 tunnel with its top the ground surface (no load on it,
/// the rock 8-24 m deep), on rollers.
fn shallow_quarter() -> String {
    let shallow = TUNNEL.replacen("surface = 50.0", "surface = 8.0", 1).replacen(
        "[[loads]]\ngroup = \"top\"\npressure = 1.112454\n",
        "",
        1,
    );
    let scene = quarter_on_rollers(&shallow);
    assert!(scene.contains("surface = 8.0") && !scene.contains("[[loads]]") && scene.contains("fix = [\"z\"]"));
    scene
}

/// The shallow tunnel's in-situ stress puts 421 of J1's 431 pairs and
/// 438 of J2's 453 beyond their strength. At the crossings of J1 and J2
/// on the end rollers (50° corners, which lock themselves at tan 35°) the
/// verdict let slip the diagonal through a corner, a slip the crossing
/// locks, and turned to the other diagonal: the stage never converged
/// (406 iterations and 3 cuts, docs/convergence.md). A corner's slip is
/// now freed by its twin (src/contact/crossing.rs): with the opening's
/// wall held the stage and the step converge, the law met; with the
/// opening cut, step 1 drops the crown wedge, as the 2D section does.
#[test]
fn the_shallow_quarter_stage_converges_where_its_crossings_lock_a_corner() {
    let case = Case::new("stage-tunnel-shallow");
    case.write("tunnel.geo", TUNNEL_GEO);
    let held = shallow_quarter() + "max_cuts = 0\n[[supports]]\ngroup = \"wall\"\nfix = [\"x\", \"y\", \"z\"]\n";
    case.write("held.toml", &held);
    let o = case.cli(&["solve", "held.toml", "--out", "held", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = json(&case.dir.join("held/summary.json"));
    assert_eq!(s["initial_stage"]["converged"], true, "{}", s["initial_stage"]);
    let stage = s["initial_stage"]["iterations"].as_u64().expect("stage iterations");
    assert!(stage <= 30, "the stage in {stage} iterations");
    let law = s["contact"]["law_residual"]["relative"].as_f64().expect("law residual");
    assert!(law < 1e-9, "the law's residual is {law:e} of the largest traction");
    case.write("cut.toml", &(shallow_quarter() + "max_cuts = 0\n"));
    let o = case.cli(&["solve", "cut.toml", "--out", "cut", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("is held by nothing at load step 1"), "{err}");
    assert!(err.contains("body \"rock #") && !case.dir.join("cut/summary.json").exists(), "{err}");
}

/// The same tunnel at k0 = 0.25 with its top the ground surface (no
/// load on it, the rock 8-24 m deep, [`shallow_quarter`]): its stage
/// converges
/// (`the_shallow_quarter_stage_converges_where_its_crossings_lock_a_corner`),
/// given 7 iterations without cuts; here it is given 5. A stage that does
/// not converge ends the run as a load
/// step does: non-zero, its last iterate written as the one step (step 0)
/// with `converged = false`, report.md saying where the states kept
/// changing and contact.csv marking those pairs, so that an engineer can
/// see where the rock mass did not settle.
#[test]
fn a_stage_that_does_not_converge_writes_its_last_iterate_and_where() {
    let case = Case::new("stage-tunnel-unsettled");
    case.write("tunnel.geo", TUNNEL_GEO);
    let scene = shallow_quarter() + "max_iterations = 5\nmax_cuts = 0\nload_steps = 2\n";
    case.write("tunnel.toml", &scene);
    let o = case.cli(&["solve", "tunnel.toml", "--out", "r", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "the stage does not converge in 5: {err}");
    assert!(
        err.contains("did not converge in the initial equilibrium stage") && err.contains("the results in"),
        "{err}"
    );
    let out = case.dir.join("r");
    let s = json(&out.join("summary.json"));
    assert_eq!(s["initial_stage"]["converged"], false, "{}", s["initial_stage"]);
    let steps = s["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), 1, "no load step starts from a stage that failed");
    assert_eq!(steps[0]["step"], 0, "the stage's iterate is step 0");
    assert_eq!(steps[0]["contact"]["converged"], false);
    let rows = csv_rows(&out.join("contact.csv"));
    let changed = rows.iter().filter(|r| csv_num(r, "changes") > 0.0).count();
    assert!(
        changed > 0 && changed < rows.len(),
        "contact.csv marks the pairs that changed: {changed} of {}",
        rows.len()
    );
    let report = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    assert!(report.contains("| initial equilibrium stage | NOT converged after"), "report.md's stage row");
    assert!(report.contains("## Where the iteration did not settle"), "report.md says where");
    assert!(report.contains("The initial stage did not converge: the joints' strength"), "report.md says the ramp");
    let names: Vec<String> = case.files_in(&out);
    assert!(names.iter().any(|n| n == "tunnel_contact.vtu"), "the contact VTU of the one step: {names:?}");
}

/// The tunnel with its top the ground surface (`surface` at the box's
/// top, no load on it): after the stage, step 1 releases the hold, and
/// the only face it loads is the opening's wall, so step 1 is the
/// excavation alone. Its answer is the run without the stage (the joints
/// carry the k0 = 0.5 stress, so the stage moves 8e-9 m, the quadrature
/// of the curved wall: the total u is the run's, the reported one that
/// less the stage's), the same states, and the supports carry the rock's weight, ρ g
/// (W L H - π R² L): the in-situ stress's nodal forces sum to nothing
/// and the hold is 0.
#[test]
fn after_the_stage_the_excavation_alone_is_the_run_without_it() {
    let case = Case::new("stage-tunnel-excavation");
    case.write("tunnel.geo", TUNNEL_GEO);
    let bare = TUNNEL
        .replace("surface = 50.0", "surface = 8.0")
        .replace("[[loads]]\ngroup = \"top\"\npressure = 1.112454\n", "")
        + "[output]\nfields = [\"displacement\"]\n";
    assert!(!bare.contains("[[loads]]") && bare.contains("surface = 8.0"), "the top is the ground surface");
    let on = case.run(&case.write("on.toml", &bare)).expect("run");
    let off =
        case.run(&case.write("off.toml", &bare.replace("initial_stage = true", "initial_stage = false"))).expect("run");
    let stage = on.initial_stage.as_ref().expect("the stage ran");
    assert_eq!(stage.states, [0, 0, on.model.pairs.len()], "every pair sticks in the stage");
    let (c_on, c_off) = (on.contact().expect("contact"), off.contact().expect("contact"));
    assert!(c_on.summary.converged && c_off.summary.converged);
    assert_eq!(c_on.states, c_off.states, "the excavation after the stage keeps the run's states");
    let (u_on, u_off) = (&on.last().u, &off.last().u);
    let scale = max_abs(u_off.iter().copied());
    assert!(scale > 1e3 * stage.largest, "the excavation moves {scale:e}, the stage {:e}", stage.largest);
    // the total (the stage's u and the step's) is the run's; what is
    // reported departs from it by the stage's own 8e-9 m, no more
    let total = max_abs(stage.total(u_on).iter().zip(u_off).map(|(a, b)| a - b));
    let diff = max_abs(u_on.iter().zip(u_off).map(|(a, b)| a - b));
    eprintln!("excavation {scale:e}, stage {:e}: total departs by {total:e}, reported by {diff:e}", stage.largest);
    assert!(total < 1e-6 * scale, "the total after the stage departs by {total:e} of {scale:e}");
    assert!(diff < stage.largest + 1e-6 * scale, "the excavation after the stage departs by {diff:e} of {scale:e}");
    // the supports carry the weight of the rock left
    let s = json(&case.out("on").join("summary.json"));
    let body = &s["reactions"]["bodies"][0];
    let (supports, remainder) = (json_vec3(&body["supports"]), json_vec3(&body["remainder"]));
    let weight = RHO_G * (16.0 * 4.0 * 16.0 - std::f64::consts::PI * 4.0 * 4.0);
    assert!((supports[2] / weight - 1.0).abs() < 1e-3, "the supports carry {} of the weight {weight}", supports[2]);
    for (c, r) in remainder.iter().enumerate() {
        assert!(r.abs() < 1e-9 * weight, "component {c}: loads + contacts + supports = {r} of {weight}");
    }
}

/// The tunnel's cross-section in plane strain (tri6): the 16 m box, the
/// R = 2 m opening, the two sets as above, rollers at the sides and base,
/// the overburden on the top after the stage. Over the crown the sets cut
/// a wedge of 0.074 m² (J1 dipping 60 degrees one way, J2 70 the other,
/// apex up), held only by the tangential stress at the crown, which is
/// (3 k0 - 1) sigma_v round a circular opening (Kirsch): +0.5 sigma_v at
/// k0 = 0.5, the wedge clamped; -0.25 sigma_v at k0 = 0.25, tension the
/// joints cannot carry, and the wedge falls once step 1 cuts the opening.
const SECTION_GEO: &str = r#"
SetFactory("OpenCASCADE");
W = 16; H = 16; R = 2;
Rectangle(1) = {-W / 2, -H / 2, 0, W, H};
Disk(2) = {0, 0, 0, R};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
e = 1e-3;
Physical Surface("rock") = {1};
Physical Curve("top") = Curve In BoundingBox{-W / 2 - e, H / 2 - e, -e, W / 2 + e, H / 2 + e, e};
Physical Curve("bottom") = Curve In BoundingBox{-W / 2 - e, -H / 2 - e, -e, W / 2 + e, -H / 2 + e, e};
Physical Curve("sides") = Curve In BoundingBox{-W / 2 - e, -H / 2 - e, -e, -W / 2 + e, H / 2 + e, e};
Physical Curve("sides") += Curve In BoundingBox{W / 2 - e, -H / 2 - e, -e, W / 2 + e, H / 2 + e, e};
wall() = Curve In BoundingBox{-R - e, -R - e, -e, R + e, R + e, e};
Physical Curve("wall") = {wall()};
MeshSize{ PointsOf{ Surface{1}; } } = 1.5;
MeshSize{ PointsOf{ Curve{wall()}; } } = 0.5;
"#;

fn section(k0: f64) -> String {
    format!(
        r#"mesh = "section.geo"
analysis = "plane_strain"
gravity = [0.0, -9.81]
[gmsh]
order = 2
[materials.rock]
E = 5000.0
nu = 0.25
density = 2.7e-3
[[bodies]]
group = "rock"
material = "rock"
k0 = {k0}
surface = 50.0
[[joint_sets]]
name = "J1"
angle = -60.0
spacing = 5.0
offset = 1.3
friction = 0.7002
[[joint_sets]]
name = "J2"
angle = 70.0
spacing = 5.0
offset = 0.7
friction = 0.7002
[[supports]]
group = "sides"
fix = ["x"]
[[supports]]
group = "bottom"
fix = ["y"]
[[loads]]
group = "top"
pressure = 1.112454
[solver]
initial_stage = true
"#
    )
}

/// A key block: at k0 = 0.5 the crown wedge stays (the run converges and
/// blocks.csv has it held); at k0 = 0.25 the run is refused at load step 1
/// (not the stage), naming the wedge and where it is — a refusal writes
/// no blocks.csv to look "rock #12" up in — and writing no results.
#[test]
fn a_crown_wedge_in_a_tensile_crown_falls_and_the_refusal_says_which_and_where() {
    let case = Case::new("stage-section-crown-wedge");
    case.write("section.geo", SECTION_GEO);
    let half = case.run(&case.write("half.toml", &section(0.5))).expect("k0 = 0.5 converges");
    assert!(half.initial_stage.is_some(), "the stage ran");
    assert!(half.contact().expect("contact").summary.converged, "k0 = 0.5: the wedge is clamped");
    let blocks = csv_rows(&case.out("half").join("blocks.csv"));
    let crown = blocks
        .iter()
        .find(|r| csv_num(r, "x").abs() < 1.0 && (2.0..3.0).contains(&csv_num(r, "y")))
        .expect("a block over the crown");
    assert!(csv_num(crown, "volume") < 0.1, "the crown wedge is the small one: {crown:?}");
    assert_eq!(crown.get("state").map(String::as_str), Some("held"), "{crown:?}");
    case.write("quarter.toml", &section(0.25));
    let o = case.cli(&["solve", "quarter.toml", "--out", "q", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "k0 = 0.25: the wedge falls: {err}");
    assert!(err.contains("at load step 1, contact iteration"), "the step is named after a stage: {err}");
    assert!(err.contains("held by nothing") || err.contains("slides or rotates freely"), "{err}");
    let name = crown.get("name").expect("blocks.csv names the block");
    let centre =
        err.split(&format!("body \"{name}\" (centre at (")).nth(1).unwrap_or_else(|| panic!("{name} and where: {err}"));
    let xy: Vec<f64> = centre.split(')').next().unwrap_or("").split(", ").filter_map(|v| v.parse().ok()).collect();
    assert!(xy.len() == 3 && xy[0].abs() < 1.0 && (2.0..3.0).contains(&xy[1]), "over the crown: {xy:?} in {err}");
    assert!(!case.dir.join("q").join("summary.json").exists(), "a refused run writes no results");
}
