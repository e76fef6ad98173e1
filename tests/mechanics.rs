//! Contact mechanics beyond the seed paper, end to end through the real gmsh
//! CLI, the solver and (where the contract is the command line) the binary,
//! asserted against closed forms.
//!
//! References: NAFEMS contact benchmark CGS-4 (a block pushed up an
//! inclined plane) as stated in the issue, with the rigid-block statics of
//! any mechanics text; R. L. Taylor and P. Papadopoulos (1991), "On a patch
//! test for contact problems in two dimensions" (a uniform stress must
//! cross a contact interface exactly); the seed paper's cylinder
//! (`geo/cylinder_paper.*`, Lamé) and DESIGN.md §2 for Coulomb shear on
//! slipping pairs, re-closure, crack memory, cycle detection and load steps.
//!
//! Goal, one statement per test: (1) a block pushed across a base with no
//! cohesion slips at every pair with |tau| = f |sigma_n|, and its normal
//! forces carry the pressure exactly (with the paper's frictionless slip:
//! no shear at all); (2) NAFEMS CGS-4: the elastic block holds at 0.995 of
//! the rigid-block slip limit and is reported as a loss of equilibrium at
//! 1.005 of it; (3) a uniform pressure and shear cross the joint exactly,
//! end pairs included, for every 2D element kind, the joint also turned by
//! 30 degrees; (4) a joint pulled open in one step closes again when the
//! load reverses; (5) the paper's state rule cycles on opening joints and
//! says so, the robust rule converges; (6) consistent traction recovery on
//! the paper's mesh, measured against lumped recovery and explained;
//! (7) the stack scene opens its weak joint and holds on its strong one.
//!
//! ```text
//!   block_push.geo      cgs4.geo (turned by alpha)   mech_blocks.geo (theta)   stack.geo
//!        p                       G |                                           pull ^^^^^
//!     +-----+               +-----+ v                  +-------+ top           +--------+ anchored
//!  ux>|block|         F --> |block|                    +=joint=+               +==weak==+ opens
//!  +==+=====+==+         +==+=====+======+             +-------+ bottom        +--------+
//!  |   base    |         |      base      |            pin     roller          +=strong=+ sticks
//!  +-----------+         +----------------+                                    +--------+ base held
//! ```
//!
//! Parameters (units consistent and arbitrary unless a scene says): block
//! push E = 3e4, nu = 0.2, f = 0.3 (0.5), c = 0, p = 1 (2), ux = 1e-3;
//! CGS-4 f = 0.3, c = 0, G = 1, F/G ramped to 0.995 and 1.005 of
//! (tan(alpha) + f) / (1 - f tan(alpha)) = 0.412371; patch test E = 1000,
//! nu = 0.3, local stress sigma_xx = 0.4, sigma_yy = -2, sigma_xy = 0.6, f =
//! 0.5, c = 0 (stick: |tau| = 0.6 < f |sigma_n| = 1); closing gap E = 1000
//! blocks hanging from a pad of E = 10, f_t = 0.5, pull/push 2; stack:
//! concrete under gravity, f_t = 10 and 500 kPa, uplift 100 kPa.
//!
//! Tolerances: equilibrium sums and patch-test stresses 1e-9 relative
//! (round-off of a dense interface solve); the Coulomb shear 1e-6 relative
//! (the iteration stops when that shear has settled to 1e-12 of the largest
//! stress; 1e-6 leaves room without hiding a wrong law).

mod common;

use common::cli::{says, solve_fails};
use common::measure::{count, force_on_body_i, tangent};
use common::scenes::{self, two_blocks};
use common::{json, read, repo_text, Case};
use serde_json::Value;
use subcontact::analytic::paper_tables::contact_sigma_n_at;
use subcontact::analytic::Lame;
use subcontact::contact::law::ContactState;
use subcontact::contact::traction::ConsistentTraction;
use subcontact::contact::Stop;
use subcontact::driver::{ContactError, ContactRun, Run};
use subcontact::fem::{element::facet_point, quadrature};
use subcontact::scene::{Analysis, ContactGroups, StateRule};

// ---------------------------------------------------------------------------
// helpers

/// The contact result of load step `k` (from 1).
fn step(run: &Run, k: usize) -> &ContactRun {
    run.steps[k - 1].contact.as_ref().expect("a contact step")
}

/// `sum sigma_n A` and `sum tau_t A` over the pairs `which`.
fn resultants(run: &Run, c: &ContactRun, which: impl Fn(usize) -> bool) -> (f64, f64) {
    let (mut n, mut t) = (0.0, 0.0);
    for (p, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
        if which(p) {
            n += r.sigma_n * pair.area;
            t += r.tau_t * pair.area;
        }
    }
    (n, t)
}

/// Whether the body named `name` is body I of the first interface.
fn is_body_i(run: &Run, name: &str) -> bool {
    run.model.bodies[run.model.interfaces[0].body_i].name == name
}

/// Runs the binary on a scene of the case (results in `out`): (success, stderr).
fn solve_cli(case: &Case, scene: &str, out: &str) -> (bool, String) {
    let o = case.cli(&["solve", scene, "--out", out, "--quiet"]);
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(!stderr.contains("panicked") && !stderr.contains("RUST_BACKTRACE"), "{scene}: no panic: {stderr}");
    (o.status.success(), stderr)
}

/// Text replacements (from, to) of a scene, each applied once.
type Edits<'a> = Vec<(&'a str, &'a str)>;

/// A copy of a repository scene with text edits (see [`scenes::edited`]),
/// written into the case.
fn edited(case: &Case, repo_toml: &str, name: &str, edits: &[(&str, &str)]) -> std::path::PathBuf {
    case.write(name, &scenes::edited(repo_toml, edits))
}

// ---------------------------------------------------------------------------
// 1. a block pushed across a base: Coulomb shear on every slipping pair

/// The block's top face in block_push.geo: x = 0.5 .. 1.5.
const PUSH_WIDTH: f64 = 1.0;

/// Every step of a pushed-block run: all pairs slip with |tau| = f |sigma_n|,
/// friction drags the base along the push (+x), and the joint's resultant
/// is the pressure p over the top face (normal) and f p w (shear).
fn check_pushed_block(name: &str, run: &Run, f: f64, p: f64) {
    let w = PUSH_WIDTH * run.model.thickness;
    let base_is_i = is_body_i(run, "base");
    for (k, s) in run.steps.iter().enumerate() {
        let c = s.contact.as_ref().expect("contact");
        assert!(c.summary.converged, "{name} step {}: converged", k + 1);
        let mut worst: f64 = 0.0;
        for (i, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
            let at = run.model.coords[pair.k];
            assert_eq!(c.states[i], ContactState::Slip, "{name} step {}: pair at {at:?} slips", k + 1);
            assert!(r.sigma_n < 0.0, "{name}: pair at {at:?} in compression ({})", r.sigma_n);
            let limit = f * r.sigma_n.abs();
            let e = (r.tau() - limit).abs() / limit;
            assert!(
                e < 1e-6,
                "{name} step {}: pair at {at:?}: tau {} against f |sigma_n| = {limit} ({e:.2e})",
                k + 1,
                r.tau()
            );
            worst = worst.max(e);
            let t = tangent(pair.normal);
            let tx = (r.sigma_n * pair.normal[0] + r.tau_t * t[0]) * if base_is_i { 1.0 } else { -1.0 };
            assert!(tx > 0.0, "{name}: friction on the base at {at:?} points along the push ({tx})");
        }
        let fi = force_on_body_i(run, c, |_| true);
        let on_base = if base_is_i { fi } else { [-fi[0], -fi[1]] };
        let (sn, _) = resultants(run, c, |_| true);
        let e_n = (sn + p * w).abs() / (p * w);
        let e_y = (on_base[1] + p * w).abs() / (p * w);
        let e_x = (on_base[0] - f * p * w).abs() / (f * p * w);
        eprintln!(
            "{name} step {}: {} pairs slip, {} iteration(s); max | |tau| / f|sigma_n| - 1 | = {worst:.1e}; sum sigma_n A = {sn:.12} (p w = {}, {e_n:.1e}); friction {:.9} (f p w = {}, {e_x:.1e})",
            k + 1,
            c.pairs.len(),
            c.summary.iterations,
            p * w,
            on_base[0],
            f * p * w
        );
        assert!(e_n < 1e-9 && e_y < 1e-9, "{name}: normal forces {sn} balance the pressure {} ({e_n:.2e})", p * w);
        assert!(e_x < 1e-6, "{name}: friction {} = f p w = {} ({e_x:.2e})", on_base[0], f * p * w);
    }
}

/// geo/block_push.*: the block's side moved 1 mm under a pressure p, no
/// cohesion. Quad9 as shipped, quad4, tri6, f = 0.5 with p = 2, and the push
/// in 4 load steps under the full pressure at each (slip carried over).
#[test]
fn pushed_block_slips_at_every_pair_with_coulomb_shear_and_its_normal_forces_carry_the_pressure() {
    let case = Case::new("mech-push");
    case.copy("geo/block_push.geo");
    // triangles: the same geometry without Recombine
    let geo = repo_text("geo/block_push.geo");
    assert!(geo.contains("Recombine Surface{1, 2};"));
    case.write("block_push_tri.geo", &geo.replace("Recombine Surface{1, 2};", ""));
    let variants: [(&str, Edits, f64, f64, &str); 5] = [
        ("quad9", vec![], 0.3, 1.0, "quad9"),
        ("quad4", vec![("order = 2", "order = 1")], 0.3, 1.0, "quad4"),
        ("tri6", vec![("mesh = \"block_push.geo\"", "mesh = \"block_push_tri.geo\"")], 0.3, 1.0, "tri6"),
        (
            "f0.5_p2",
            vec![("friction = 0.3", "friction = 0.5"), ("pressure = 1.0", "pressure = 2.0")],
            0.5,
            2.0,
            "quad9",
        ),
        // the push in 4 steps (ux ramped) under the full pressure at every step
        (
            "steps",
            vec![("pressure = 1.0", "pressure = 1.0\nfactors = [1.0, 1.0, 1.0, 1.0]\n\n[solver]\nload_steps = 4")],
            0.3,
            1.0,
            "quad9",
        ),
    ];
    for (name, edits, f, p, kind) in variants {
        let scene = edited(&case, "geo/block_push.toml", &format!("push_{name}.toml"), &edits);
        let run = case.run(&scene).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        assert_eq!(run.model.bodies[0].cells[0].kind.name(), kind, "{name}: element kind");
        assert_eq!(run.steps.len(), if name == "steps" { 4 } else { 1 });
        check_pushed_block(name, &run, f, p);
    }
}

/// The paper's slip law: a slipping pair carries no shear. The block is
/// then held horizontally only by its prescribed ux; every pair slips (with
/// friction 0, and with friction 0.3 in the criterion as well: the push
/// drags every pair 1 mm), the shear is zero everywhere and the normal
/// forces still carry the pressure.
#[test]
fn frictionless_slip_carries_no_shear_and_the_pushed_block_still_carries_the_pressure() {
    let case = Case::new("mech-push-frictionless");
    case.copy("geo/block_push.geo");
    let p = 1.0;
    for (name, f) in [("f0", 0.0), ("f0.3", 0.3)] {
        let scene = edited(
            &case,
            "geo/block_push.toml",
            &format!("frictionless_{name}.toml"),
            &[("friction = 0.3", &format!("friction = {f:?}\nslip = \"frictionless\""))],
        );
        let run = case.run(&scene).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let c = run.contact().expect("contact");
        assert!(c.summary.converged);
        let w = PUSH_WIDTH * run.model.thickness;
        for (i, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
            let at = run.model.coords[pair.k];
            assert_eq!(c.states[i], ContactState::Slip, "{name}: pair at {at:?} slips");
            assert!(r.sigma_n < 0.0, "{name}: pair at {at:?} in compression");
            assert!(r.tau() < 1e-9 * p, "{name}: slipping pair at {at:?} carries no shear ({:.3e})", r.tau());
        }
        let (sn, st) = resultants(&run, c, |_| true);
        eprintln!("frictionless slip, {name}: {} pairs slip, {} iterations; sum sigma_n A = {sn:.12} (p w = {}); sum tau_t A = {st:.1e}", c.pairs.len(), c.summary.iterations, p * w);
        assert!((sn + p * w).abs() < 1e-9 * p * w, "{name}: normal forces balance the pressure: {sn}");
    }
}

/// Regression (src/contact/mod.rs): the first, all-stuck solve of a push
/// puts the joint behind the pushed side in tension, so those pairs open in
/// iteration 2 and close again in iteration 3. They used to stick where
/// iteration 2 had left them, ~1 mm along the joint: a position they never
/// had, from which they then held shear below the limit (f = 0.5, p = 2: 3
/// pairs stuck; frictionless slip with f = 0.3: 1 pair stuck with shear).
/// A pair closed when the step began that closes again after moving along
/// the joint now closes slipping.
#[test]
fn pairs_opened_only_by_an_iteration_close_again_slipping_not_stuck_where_that_iteration_left_them() {
    let case = Case::new("mech-push-reclose");
    case.copy("geo/block_push.geo");
    let variants: [(&str, &[(&str, &str)]); 2] = [
        ("f0.5_p2", &[("friction = 0.3", "friction = 0.5"), ("pressure = 1.0", "pressure = 2.0")]),
        ("frictionless_f0.3", &[("friction = 0.3", "friction = 0.3\nslip = \"frictionless\"")]),
    ];
    for (name, edits) in variants {
        let run = case
            .run(&edited(&case, "geo/block_push.toml", &format!("{name}.toml"), edits))
            .unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let c = run.contact().expect("contact");
        assert!(c.summary.converged, "{name}: converged");
        let opened =
            c.summary.history.iter().map(|h| h.iter().filter(|&&s| s == ContactState::Open).count()).max().unwrap_or(0);
        assert!(opened > 0, "{name}: pairs open during the iteration (the case exercises re-closure)");
        assert_eq!(count(c, ContactState::Slip), c.pairs.len(), "{name}: every pair slips in the end: {:?}", c.states);
        eprintln!(
            "{name}: up to {opened} pairs open during the iteration, all {} slip after {} iterations",
            c.pairs.len(),
            c.summary.iterations
        );
    }
}

// ---------------------------------------------------------------------------
// 2. NAFEMS CGS-4: the slip limit of a block pushed up an inclined plane

const TAN_ALPHA: f64 = 0.1;
const CGS4_FRICTION: f64 = 0.3;
/// Rigid-block slip limit F / G = (tan(alpha) + f) / (1 - f tan(alpha)).
const CGS4_LIMIT: f64 = (TAN_ALPHA + CGS4_FRICTION) / (1.0 - CGS4_FRICTION * TAN_ALPHA);
/// The block's weight in geo/cgs4.toml: density 0.4 * g 10 * (1 x 0.25).
const CGS4_G: f64 = 1.0;
/// F / (limit G) at the steps of geo/cgs4.toml.
const CGS4_FACTORS: [f64; 5] = [0.0, 0.5, 0.9, 0.99, 0.995];

/// Every step of a CGS-4 run below the limit: the block holds (some pairs
/// stuck, none open), slipping pairs carry f |sigma_n|, stuck ones less, and
/// the joint carries the block's loads: sum sigma_n A = -N, sum tau_t A = -T
/// with N = F sin a + G cos a, T = F cos a - G sin a (t points down the
/// slope for the base as body I, and the signs agree for the block as I).
fn check_cgs4_holds(name: &str, run: &Run) {
    let a = TAN_ALPHA.atan();
    let base_is_i = is_body_i(run, "base");
    for (k, &factor) in CGS4_FACTORS.iter().enumerate() {
        let c = step(run, k + 1);
        assert!(c.summary.converged, "{name} step {}: converged", k + 1);
        let f_push = factor * CGS4_LIMIT * CGS4_G;
        for (i, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
            let at = run.model.coords[pair.k];
            assert!(r.sigma_n < 0.0, "{name} step {}: pair at {at:?} in compression", k + 1);
            let limit = CGS4_FRICTION * r.sigma_n.abs();
            match c.states[i] {
                ContactState::Slip => assert!(
                    (r.tau() - limit).abs() < 1e-6 * limit,
                    "{name} step {}: slipping pair at {at:?}: tau {} = f |sigma_n| {limit}",
                    k + 1,
                    r.tau()
                ),
                ContactState::Stick => assert!(
                    r.tau() < limit * (1.0 + 1e-9),
                    "{name} step {}: stuck pair at {at:?} within its limit",
                    k + 1
                ),
                ContactState::Open => panic!("{name} step {}: pair at {at:?} open", k + 1),
            }
        }
        let stuck = count(c, ContactState::Stick);
        assert!(stuck > 0, "{name} step {}: the block holds (a stuck pair)", k + 1);
        let n = f_push * a.sin() + CGS4_G * a.cos();
        let t = f_push * a.cos() - CGS4_G * a.sin();
        let (sn, st) = resultants(run, c, |_| true);
        let fi = force_on_body_i(run, c, |_| true);
        let on_base = if base_is_i { fi } else { [-fi[0], -fi[1]] };
        let e = [(sn + n).abs(), (st + t).abs(), (on_base[0] - f_push).abs(), (on_base[1] + CGS4_G).abs()]
            .into_iter()
            .fold(0.0, f64::max)
            / CGS4_G;
        eprintln!(
            "CGS-4 {name} step {}: F/G = {:.6} ({factor} of the limit): {} stick / {} slip, {} iteration(s); N = {n:.9}, T = {t:.9}, equilibrium {e:.1e} G; friction used T / fN = {:.5}",
            k + 1,
            f_push / CGS4_G,
            stuck,
            count(c, ContactState::Slip),
            c.summary.iterations,
            t / (CGS4_FRICTION * n)
        );
        assert!(e < 1e-9, "{name} step {}: the joint carries the block's loads: sum sigma_n A {sn} = -N {n}, sum tau_t A {st} = -T {t}", k + 1);
    }
}

/// Below the limit the elastic block holds at every step with slipping
/// corners; 0.5 % above it the run stops at that step with "loss of
/// equilibrium" naming the block. The bracket holds for a stiff block (the
/// scene), an equally stiff one with its weight as a traction (`factors =
/// [1, ...]`, linear elements) and a soft one on triangles: with Coulomb
/// shear on slipping pairs, gross slip comes when f N is used up, which is
/// the rigid-block limit whatever the stiffness (stiffness only decides
/// where local slip starts: the corners, already under the weight alone).
#[test]
fn cgs4_block_holds_below_and_loses_equilibrium_above_the_slip_limit_within_half_a_percent() {
    let case = Case::new("mech-cgs4");
    case.copy("geo/cgs4.geo");
    let gravity_to_traction: [(&str, &str); 3] = [
        ("gravity = [0.0, -10.0]\n", ""),
        ("gravity_factors = [1.0, 1.0, 1.0, 1.0, 1.0]\n", ""),
        (
            "[solver]",
            "[[loads]]\ngroup = \"top\"\ntraction = [0.0, -1.0]\nfactors = [1.0, 1.0, 1.0, 1.0, 1.0]\n\n[solver]",
        ),
    ];
    let variants: Vec<(&str, Edits, &str)> = vec![
        ("stiff block, quad9, gravity", vec![], "quad9"),
        (
            "equal stiffness, quad4, weight as traction",
            [&[("E = 2.0e5", "E = 1.0e4"), ("order = 2", "order = 1")][..], &gravity_to_traction[..]].concat(),
            "quad4",
        ),
        ("soft block, tri6, gravity", vec![("E = 2.0e5", "E = 100.0"), ("h = 0.25 }", "h = 0.25, quad = 0 }")], "tri6"),
    ];
    for (i, (name, edits, kind)) in variants.into_iter().enumerate() {
        let below = edited(&case, "geo/cgs4.toml", &format!("below_{i}.toml"), &edits);
        let run = case.run(&below).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        assert_eq!(run.model.bodies[1].cells[0].kind.name(), kind, "{name}: element kind");
        let push = run.scene.loads.iter().find(|l| l.group == "push").expect("the push load");
        assert_eq!(push.factors.as_deref(), Some(&CGS4_FACTORS[..]), "the scene's steps");
        check_cgs4_holds(name, &run);

        // the last two steps at 0.995 and 1.005 of the limit
        let above_edits = [&edits[..], &[("0.99, 0.995]", "0.995, 1.005]")][..]].concat();
        let scene = format!("above_{i}.toml");
        edited(&case, "geo/cgs4.toml", &scene, &above_edits);
        // 0.5 % above the limit: a clean failure (exit 1, one error paragraph, no result files)
        let stderr = solve_fails(&case, &scene, &format!("out_above_{i}"));
        eprintln!("CGS-4 {name}, F/G = 1.005 x limit at step 5: {stderr}");
        says(
            &stderr,
            &[
                scene.as_str(),
                "loss of equilibrium",
                "body \"block\"",
                "load step 5,",
                "or raise the friction or cohesion of its contacts",
            ],
        );
        match case.contact_error(&case.dir.join(&scene)) {
            ContactError::Sliding { bodies, no_shear, at, .. } => {
                assert_eq!((bodies, at.step), (vec!["block".to_string()], Some(5)), "{name}");
                assert!(!no_shear, "{name}: the joint has friction: the load is to blame");
            }
            other => panic!("{name}: sliding, not {other:?}"),
        }
    }
}

// ---------------------------------------------------------------------------
// 3. contact patch test: uniform pressure and shear cross the joint exactly

/// Uniform stress in the blocks' own frame (x along the joint).
const PATCH_STRESS: [f64; 3] = [0.4, -2.0, 0.6]; // sigma_xx, sigma_yy, sigma_xy

/// The global stress tensor (xx, yy, xy) of PATCH_STRESS turned by theta.
fn patch_stress(theta_deg: f64) -> [[f64; 2]; 2] {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let r = [[c, -s], [s, c]];
    let sl = [[PATCH_STRESS[0], PATCH_STRESS[2]], [PATCH_STRESS[2], PATCH_STRESS[1]]];
    let mut out = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            out[i][j] =
                (0..2).flat_map(|k| (0..2).map(move |l| (k, l))).map(|(k, l)| r[i][k] * sl[k][l] * r[j][l]).sum();
        }
    }
    out
}

fn turn(theta_deg: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta_deg.to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// mech_blocks.geo turned by theta, every side loaded by sigma n, held by
/// a pin and a roller only (statically determinate: no reactions).
fn patch_scene(order: usize, set: &str, theta: f64, recovery: &str) -> String {
    let sigma = patch_stress(theta);
    let mut loads = String::new();
    for (group, n_local) in [
        ("base", [0.0, -1.0]),
        ("top_face", [0.0, 1.0]),
        ("left_bottom", [-1.0, 0.0]),
        ("left_top", [-1.0, 0.0]),
        ("right_bottom", [1.0, 0.0]),
        ("right_top", [1.0, 0.0]),
    ] {
        let n = turn(theta, n_local);
        let t = [sigma[0][0] * n[0] + sigma[0][1] * n[1], sigma[1][0] * n[0] + sigma[1][1] * n[1]];
        loads += &format!("[[loads]]\ngroup = \"{group}\"\ntraction = [{:?}, {:?}]\n\n", t[0], t[1]);
    }
    let head = format!(
        r#"title = "contact patch test"
mesh = "mech_blocks.geo"
analysis = "plane_strain"

[gmsh]
order = {order}
setnumber = {{ {set}, theta = {theta:?} }}"#
    );
    let joint = format!("friction = 0.5\ncohesion = 0.0\ntensile_strength = 0.0\ntraction = \"{recovery}\"");
    let supports = r#"[[supports]]
group = "pin"
fix = ["x", "y"]

[[supports]]
group = "roller"
fix = ["y"]
"#;
    two_blocks(&head, 1000.0, 0.3, &joint, &format!("{supports}\n{loads}"))
}

/// Every pair sticks and carries sigma_n = n.S.n, tau_t = t.S.n of the
/// uniform stress S to 1e-9 relative, the end pairs included, for the joint
/// along x and turned by 30 degrees, with lumped and consistent recovery.
fn contact_patch_test(kinds: &[(&str, usize, &str)]) {
    let case = Case::new(&format!("mech-patch-{}", kinds[0].0));
    case.copy("tests/geo/mech_blocks.geo");
    for &(kind, order, set) in kinds {
        for (theta, recovery) in [(0.0, "lumped"), (30.0, "lumped"), (30.0, "consistent")] {
            let name = format!("{kind}_{theta}_{recovery}");
            let run = case
                .run(&case.write(&format!("patch_{name}.toml"), &patch_scene(order, set, theta, recovery)))
                .unwrap_or_else(|e| panic!("{name}: {e:#}"));
            assert_eq!(run.model.bodies[0].cells[0].kind.name(), kind, "{name}: element kind");
            let c = run.contact().expect("contact");
            assert!(c.summary.converged);
            assert!(c.pairs.len() >= 5, "{name}: {} pairs", c.pairs.len());
            let sigma = patch_stress(theta);
            let across = turn(theta, [0.0, 1.0]);
            let mut worst: f64 = 0.0;
            for (i, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
                let at = run.model.coords[pair.k];
                let n = [pair.normal[0], pair.normal[1]];
                let dn = (n[0] * across[0] + n[1] * across[1]).abs();
                assert!((dn - 1.0).abs() < 1e-12, "{name}: pair at {at:?}: normal {n:?} across the joint");
                assert_eq!(c.states[i], ContactState::Stick, "{name}: pair at {at:?} sticks");
                let t = tangent(pair.normal);
                let sn = [sigma[0][0] * n[0] + sigma[0][1] * n[1], sigma[1][0] * n[0] + sigma[1][1] * n[1]];
                let (want_n, want_t) = (n[0] * sn[0] + n[1] * sn[1], t[0] * sn[0] + t[1] * sn[1]);
                let e = ((r.sigma_n - want_n) / want_n).abs().max(((r.tau_t - want_t) / want_t).abs());
                assert!(
                    e < 1e-9,
                    "{name}: pair at {at:?}: sigma_n {} (want {want_n}), tau_t {} (want {want_t}): {e:.2e}",
                    r.sigma_n,
                    r.tau_t
                );
                worst = worst.max(e);
            }
            eprintln!(
                "contact patch test {name}: {} pairs stick, max relative error of sigma_n, tau_t {worst:.1e}",
                c.pairs.len()
            );
        }
    }
}

#[test]
fn uniform_pressure_and_shear_cross_the_joint_exactly_with_linear_elements_also_turned_30_degrees() {
    contact_patch_test(&[("quad4", 1, "n = 4, quad = 1"), ("tri3", 1, "n = 5, quad = 0")]);
}

#[test]
fn uniform_pressure_and_shear_cross_the_joint_exactly_with_quadratic_elements_also_turned_30_degrees() {
    contact_patch_test(&[
        ("quad9", 2, "n = 3, quad = 1"),
        ("quad8", 2, "n = 3, quad = 1, serendipity = 1"),
        ("tri6", 2, "n = 4, quad = 0"),
    ]);
}

// ---------------------------------------------------------------------------
// 4.–5. a gap that opens and closes again; the paper's rule cycles on it

/// Two blocks (mech_blocks.geo) with the top one hanging from a soft pad:
/// the sides of the top block are pulled up by 2 (step 1, factor 1) and
/// pushed down by 2 (step 2, factor -1). f_t = 0.5.
fn hanging_scene(rule: &str) -> String {
    format!(
        r#"title = "a joint that opens and closes again"
mesh = "mech_blocks.geo"
analysis = "plane_strain"

[gmsh]
order = 2
setnumber = {{ n = 4, pad = 1 }}

[materials.m]
E = 1000.0
nu = 0.25

[materials.soft]
E = 10.0
nu = 0.25

[[bodies]]
group = "bottom"
material = "m"

[[bodies]]
group = "top"
material = "m"

[[bodies]]
group = "pad"
material = "soft"

[[contacts]]
group = "joint"
friction = 0.5
cohesion = 1.0
tensile_strength = 0.5

[[supports]]
group = "base"
fix = ["x", "y"]

[[supports]]
group = "pad_top"
fix = ["x", "y"]

[[loads]]
group = "left_top"
traction = [0.0, 2.0]
factors = [1.0, -1.0]

[[loads]]
group = "right_top"
traction = [0.0, 2.0]
factors = [1.0, -1.0]

[solver]
load_steps = 2
rule = "{rule}"
"#
    )
}

/// Pulled above f_t every pair opens (gap > 0, no stress); when the load
/// reverses the bodies would interpenetrate, so every pair closes again
/// (stick or slip) with gap 0 and compression, the crack keeping f_t = 0.
#[test]
fn joint_pulled_open_in_one_step_closes_again_when_the_load_reverses() {
    let case = Case::new("mech-closing");
    case.copy("tests/geo/mech_blocks.geo");
    let run = case.run(&case.write("hanging.toml", &hanging_scene("robust"))).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(run.steps.len(), 2);
    let (open, closed) = (step(&run, 1), step(&run, 2));
    assert!(open.summary.converged && closed.summary.converged);
    let mut max_gap: f64 = 0.0;
    for (i, (pair, r)) in run.model.pairs.iter().zip(&open.pairs).enumerate() {
        let at = run.model.coords[pair.k];
        assert_eq!(open.states[i], ContactState::Open, "step 1: pair at {at:?} open");
        assert!(r.gap > 0.0, "step 1: pair at {at:?} gap {}", r.gap);
        assert!(
            r.sigma_n.abs() < 1e-9 && r.tau() < 1e-9,
            "step 1: open pair at {at:?} carries nothing ({}, {})",
            r.sigma_n,
            r.tau()
        );
        max_gap = max_gap.max(r.gap);
    }
    for (i, (pair, r)) in run.model.pairs.iter().zip(&closed.pairs).enumerate() {
        let at = run.model.coords[pair.k];
        assert_ne!(closed.states[i], ContactState::Open, "step 2: pair at {at:?} closed again");
        assert!(
            r.gap.abs() <= 1e-12 * max_gap,
            "step 2: pair at {at:?} gap {:.3e} (step 1 up to {max_gap:.3e})",
            r.gap
        );
        assert!(r.sigma_n < 0.0, "step 2: pair at {at:?} in compression ({})", r.sigma_n);
        // cracked: f_t = 0 and the residual cohesion 0
        assert!(r.tau() <= 0.5 * r.sigma_n.abs() * (1.0 + 1e-6), "step 2: pair at {at:?} within the cracked limit");
    }
    eprintln!(
        "closing gap (robust): step 1 {} open in {} iteration(s), gaps up to {max_gap:.4e}; step 2 {} stick / {} slip in {} iteration(s)",
        count(open, ContactState::Open),
        open.summary.iterations,
        count(closed, ContactState::Stick),
        count(closed, ContactState::Slip),
        closed.summary.iterations
    );
}

/// The paper's rule judges an open pair, which carries no stress, as stuck
/// again: on any opening problem the states cycle. The run must say so
/// (non-zero exit, summary.json contact.converged = false and cycled = true,
/// report.md's pairs that kept changing); the robust rule converges. Two cases:
/// the hanging blocks and the stack scene.
#[test]
fn paper_rule_cycles_on_an_opening_joint_and_says_so_while_the_robust_rule_converges() {
    let case = Case::new("mech-paper-rule");
    case.copy("tests/geo/mech_blocks.geo");
    case.copy("geo/stack.geo");
    case.write("hanging_paper.toml", &hanging_scene("paper"));
    case.write("hanging_robust.toml", &hanging_scene("robust"));
    let stack = read(&case.copy("geo/stack.toml"));
    assert!(!stack.contains("[solver]"));
    case.write("stack_paper.toml", &format!("{stack}\n[solver]\nrule = \"paper\"\n"));
    case.write("stack_robust.toml", &stack);
    for name in ["hanging", "stack"] {
        let (ok, stderr) = solve_cli(&case, &format!("{name}_paper.toml"), &format!("out_{name}_paper"));
        assert!(!ok, "{name}: the paper's rule does not converge");
        for want in [format!("{name}_paper.toml"), "did not converge".into(), "the states cycle".into()] {
            assert!(stderr.contains(&want), "{name}: mentions {want:?}: {stderr}");
        }
        match case.contact_error(&case.dir.join(format!("{name}_paper.toml"))) {
            ContactError::NotConverged { stop, results, .. } => {
                assert!(stop == Stop::Cycled && results.is_some(), "{name}: cycled, results written")
            }
            other => panic!("{name}: not converged, not {other:?}"),
        }
        let dir = case.dir.join(format!("out_{name}_paper"));
        let s = json(&dir.join("summary.json"));
        assert_eq!(s["contact"]["converged"], Value::Bool(false), "{name}: summary converged");
        assert_eq!(s["contact"]["cycled"], Value::Bool(true), "{name}: summary cycled");
        let paper_its = s["contact"]["iterations"].as_u64().expect("iterations");
        let report = read(&dir.join("report.md"));
        assert!(report.contains("## Where the iteration did not settle"), "{name}: report says where: {report}");
        assert!(report.contains("pairs changed state in the last"), "{name}: how many changed: {report}");

        let (ok, stderr) = solve_cli(&case, &format!("{name}_robust.toml"), &format!("out_{name}_robust"));
        assert!(ok, "{name}: the robust rule converges: {stderr}");
        let r = json(&case.dir.join(format!("out_{name}_robust/summary.json")));
        assert_eq!(r["contact"]["converged"], Value::Bool(true));
        assert_eq!(r["contact"]["cycled"], Value::Bool(false));
        let steps: Vec<u64> = match r["steps"].as_array() {
            Some(a) if !a.is_empty() => {
                a.iter().map(|s| s["contact"]["iterations"].as_u64().expect("iterations")).collect()
            }
            _ => vec![r["contact"]["iterations"].as_u64().expect("iterations")],
        };
        eprintln!("{name}: paper rule cycles after {paper_its} iteration(s) (step 1); robust rule converges in {steps:?} iteration(s) per step");
        assert!((2..=4).contains(&paper_its), "{name}: the cycle is found at once ({paper_its})");
        assert!(steps.iter().all(|&k| (2..=10).contains(&k)), "{name}: robust iterations {steps:?}");
        // the advice names the robust rule to a run that did not use it, and
        // only then (the robust rule cut short at one iteration)
        assert!(
            stderr_of(&case, &format!("{name}_paper.toml")).contains("or the default rule = \"robust\""),
            "{name}: the paper's run is pointed to the robust rule"
        );
        case.write(&format!("{name}_short.toml"), &cut_short(&read(&case.dir.join(format!("{name}_robust.toml")))));
        match case.contact_error(&case.dir.join(format!("{name}_short.toml"))) {
            ContactError::NotConverged { rule, .. } => assert_eq!(rule, StateRule::Robust, "{name}"),
            other => panic!("{name}: not converged, not {other:?}"),
        }
        let short = stderr_of(&case, &format!("{name}_short.toml"));
        assert!(
            short.contains("did not converge") && !short.contains("rule = \"robust\""),
            "{name}: no advice to use the rule it used: {short}"
        );
        // and the advice it gets is the one that helps: the same scene with
        // the default max_iterations converged above
        assert!(short.contains("try more [solver] max_iterations"), "{name}: advice to iterate more: {short}");
    }
}

/// The stderr of `solve SCENE` in the case (to `out_<stem>`).
fn stderr_of(case: &Case, scene: &str) -> String {
    let out = case.cli(&["solve", scene, "--out", &format!("out_{}", scene.trim_end_matches(".toml")), "--quiet"]);
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A scene with `[solver] max_iterations = 1`.
fn cut_short(scene: &str) -> String {
    if scene.contains("[solver]\n") {
        scene.replacen("[solver]\n", "[solver]\nmax_iterations = 1\n", 1)
    } else {
        format!("{scene}\n[solver]\nmax_iterations = 1\n")
    }
}

// ---------------------------------------------------------------------------
// 6. consistent against lumped recovery on the paper's mesh

/// Lamé's sigma_theta at the pairs of a run's interface, and the forces the
/// consistent recovery would be given by that exact traction: `∫ N_a t dA`
/// over body I's facets (the integral ConsistentTraction inverts).
fn exact_consistent_forces(run: &Run, lame: &Lame) -> Vec<[f64; 3]> {
    let mut row = vec![usize::MAX; run.model.n_nodes()];
    for (i, p) in run.model.pairs.iter().enumerate() {
        row[p.k] = i;
    }
    let mut f = vec![[0.0; 3]; run.model.pairs.len()];
    for facet in run.model.interfaces.iter().flat_map(|i| i.facets.iter()) {
        let xe: Vec<[f64; 3]> = facet.nodes.iter().map(|&k| run.model.coords[k]).collect();
        for q in quadrature::rule(facet.kind, 12) {
            let (nf, _, da, x) = facet_point(facet.kind, &xe, q.xi);
            let t = lame.sigma_theta(x[0].hypot(x[1]));
            for (a, &node) in facet.nodes.iter().enumerate() {
                f[row[node]][0] += q.w * da * nf[a] * t;
            }
        }
    }
    f
}

/// Measured: consistent recovery is NOT closer to Lamé at the end pairs of
/// the paper's 30-hex mesh (lumped +0.72 % at r = 3, -5.07 % at r = 5;
/// consistent +11.3 % and -13.6 %). The recovery is right: given the
/// consistent forces of Lamé's traction it is within 0.6 % at both ends
/// (lumped recovery of the same forces: -5.9 % at r = 3). What is off are
/// the FE pair forces themselves: at the end pairs they differ from those
/// exact forces by +7.1 % and -7.7 % (interior pairs < 0.5 %), an error of
/// the coarse hex8 field (3 elements over 45 degrees), which M^-1 amplifies
/// (its rows alternate in sign) and lumping, a plain division by the
/// tributary area, does not; at r = 3 lumping's own bias (-5.9 %) cancels
/// it by luck. Where the pair forces are accurate (quad9 cylinder) the
/// consistent recovery is closer at both ends, as designed.
#[test]
fn consistent_recovery_is_exact_for_exact_forces_but_not_closer_on_the_paper_mesh_whose_end_forces_are_7_percent_off() {
    let case = Case::new("mech-consistent");
    case.copy("geo/cylinder_paper.geo");
    case.copy("geo/cylinder.geo");
    let lumped = case.run(&case.copy("geo/cylinder_paper.toml")).expect("lumped run");
    let consistent = case
        .run(&edited(
            &case,
            "geo/cylinder_paper.toml",
            "paper_consistent.toml",
            &[("tensile_strength = 3.0e5", "tensile_strength = 3.0e5\ntraction = \"consistent\"")],
        ))
        .expect("consistent run");
    let b = &lumped.model.bodies[0];
    let lame = Lame { a: 3.0, b: 5.0, p: 0.1, e: b.material.e, nu: b.material.nu, analysis: Analysis::PlaneStrain };
    let err =
        |run: &Run, r: f64| contact_sigma_n_at(&run.solution(), r).expect("a pair at r") / lame.sigma_theta(r) - 1.0;
    let (l3, l5, c3, c5) = (err(&lumped, 3.0), err(&lumped, 5.0), err(&consistent, 3.0), err(&consistent, 5.0));
    eprintln!("paper mesh, sigma_n / sigma_theta - 1: lumped r = 3: {:+.3} %, r = 5: {:+.3} %; consistent r = 3: {:+.3} %, r = 5: {:+.3} %", 100.0 * l3, 100.0 * l5, 100.0 * c3, 100.0 * c5);
    assert!(c3.abs() > l3.abs() && c5.abs() > l5.abs(), "measured: consistent is not closer on the paper mesh");
    assert!((0.10..0.13).contains(&c3) && (-0.15..-0.12).contains(&c5), "consistent end errors {c3:+.4} {c5:+.4}");
    assert!((0.005..0.01).contains(&l3) && (-0.06..-0.04).contains(&l5), "lumped end errors {l3:+.4} {l5:+.4}");

    // why: the recovery of the exact consistent forces is close; the FE forces are not
    let exact = exact_consistent_forces(&lumped, &lame);
    let tr = ConsistentTraction::new(&lumped.model).expect("interface mass matrix");
    let projected = tr.recover(&exact, &subcontact::contact::basis::FaceBasis::nodal(vec![0.0; exact.len()]));
    let c = lumped.contact().expect("contact");
    let mut worst_end: f64 = 0.0;
    let mut worst_inner: f64 = 0.0;
    for (i, pair) in lumped.model.pairs.iter().enumerate() {
        let x = lumped.model.coords[pair.k];
        let r = x[0].hypot(x[1]);
        let th = lame.sigma_theta(r);
        let e_proj = projected[i][0] / th - 1.0;
        let e_lumped_exact = exact[i][0] / pair.area / th - 1.0;
        let e_force = c.pairs[i].sigma_n * pair.area / exact[i][0] - 1.0;
        let end = (r - 3.0).abs() < 1e-9 || (r - 5.0).abs() < 1e-9;
        eprintln!(
            "  r = {r:.2} z = {:.0}: FE force / exact consistent force - 1 = {:+.3} %; consistent recovery of exact forces {:+.3} %, lumped {:+.3} %",
            x[2],
            100.0 * e_force,
            100.0 * e_proj,
            100.0 * e_lumped_exact
        );
        assert!(e_proj.abs() < 0.006, "r = {r}: the consistent recovery of exact forces is close ({e_proj:+.4})");
        if end {
            worst_end = worst_end.max(e_force.abs());
        } else {
            worst_inner = worst_inner.max(e_force.abs());
        }
    }
    assert!(worst_end > 0.06 && worst_inner < 0.005, "FE pair forces: ends {worst_end:.4}, interior {worst_inner:.4}");

    // where the pair forces are accurate, consistent is closer at both ends
    let fine = [("lc = 0.05", "lc = 0.2")];
    let q_lumped = case.run(&edited(&case, "geo/cylinder.toml", "quad9_lumped.toml", &fine)).expect("quad9 lumped");
    let q_consistent = case
        .run(&edited(
            &case,
            "geo/cylinder.toml",
            "quad9_consistent.toml",
            &[fine[0], ("tensile_strength = 3.0e5", "tensile_strength = 3.0e5\ntraction = \"consistent\"")],
        ))
        .expect("quad9 consistent");
    for r in [3.0, 5.0] {
        let (el, ec) = (err(&q_lumped, r), err(&q_consistent, r));
        eprintln!("quad9 cylinder (lc = 0.2), r = {r}: lumped {:+.4} %, consistent {:+.4} %", 100.0 * el, 100.0 * ec);
        assert!(ec.abs() < 0.5 * el.abs(), "quad9, r = {r}: consistent {ec:+.2e} closer than lumped {el:+.2e}");
    }
}

// ---------------------------------------------------------------------------
// 7. the stack scene: the weak joint opens, the strong one sticks

#[test]
fn stack_scene_opens_its_upper_joint_and_the_lower_joint_sticks_carrying_the_middle_block() {
    let case = Case::new("mech-stack");
    case.copy("geo/stack.geo");
    let run = case.run(&case.copy("geo/stack.toml")).unwrap_or_else(|e| panic!("{e:#}"));
    let c = run.contact().expect("contact");
    assert!(c.summary.converged);
    let lower = run
        .scene
        .contacts
        .iter()
        .position(|k| matches!(&k.groups, ContactGroups::Shared(g) if g == "lower_joint"))
        .expect("lower joint");
    let upper = 1 - lower;
    let pull = 100.0;
    let (mut n_upper, mut n_lower) = (0, 0);
    for (i, (pair, r)) in run.model.pairs.iter().zip(&c.pairs).enumerate() {
        let at = run.model.coords[pair.k];
        if pair.contact == upper {
            n_upper += 1;
            assert_eq!(c.states[i], ContactState::Open, "upper joint pair at {at:?} open");
            assert!(r.gap > 0.0, "upper joint pair at {at:?}: gap {}", r.gap);
            assert!(
                r.sigma_n.abs() < 1e-9 * pull && r.tau() < 1e-9 * pull,
                "upper joint pair at {at:?} carries nothing"
            );
        } else {
            n_lower += 1;
            assert_eq!(c.states[i], ContactState::Stick, "lower joint pair at {at:?} sticks");
            assert!(r.gap == 0.0, "lower joint pair at {at:?} closed");
        }
    }
    assert!(n_upper >= 9 && n_lower >= 9, "{n_upper} and {n_lower} pairs");
    // the middle block hangs on nothing but the lower joint: it carries its weight
    let mid = run.model.bodies.iter().find(|b| b.name == "middle").expect("middle block");
    let weight = mid.material.density * run.model.gravity[1].abs() * 2.0 * 1.0 * run.model.thickness;
    assert!(weight > 0.0);
    let (sn, st) = resultants(&run, c, |p| run.model.pairs[p].contact == lower);
    eprintln!(
        "stack: {n_upper} upper pairs open, {n_lower} lower pairs stick, {} iteration(s); lower joint sum sigma_n A = {sn:.9} (weight {weight:.9}), sum tau_t A = {st:.2e}",
        c.summary.iterations
    );
    assert!((sn + weight).abs() < 1e-9 * weight, "lower joint carries the middle block's weight: {sn} vs {weight}");
    assert!(st.abs() < 1e-9 * weight, "and no net shear: {st}");
}
