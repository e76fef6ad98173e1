//! Joints that deform (`normal_stiffness`, `shear_stiffness` on a
//! contact), end to end through the real gmsh CLI on the two stacked blocks
//! of tests/geo/contact_stack.geo (quad9, plane strain, E = 1000, ν =
//! 0.25, the joint at y = 1, the top face at y = 2):
//!
//! - under a uniform pressure q the joint closes by q / k_n and the top
//!   face settles by that much more than on a rigid joint, to round-off
//!   (the stress is uniform: every element is exact);
//! - springs that start carrying the in-situ stress leave a rock mass in
//!   equilibrium with it where it is (a joint that did not would close by
//!   σ / k_n);
//! - as k_n = k_s grows the answer tends to the rigid joint's, the forces'
//!   difference falling as 1 / k (a fitted rate), with the rigid joint's
//!   states;
//! - the dense, sparse and iterative interfaces give one answer;
//! - a block pushed along the joint beyond its friction slides, and the
//!   run says so.

mod common;

use common::measure::loglog_slope;
use common::scenes::springs;
use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

/// The stacked blocks with `joint` in the contact and `load` on the top
/// face; `bodies` added to each body (an initial stress), `solver` lines.
fn stack(case: &Case, name: &str, joint: &str, load: &str, bodies: &str, solver: &str) -> Run {
    case.copy("tests/geo/contact_stack.geo");
    let scene = format!(
        r#"title = "two stacked blocks"
mesh = "contact_stack.geo"
analysis = "plane_strain"

[gmsh]
order = 2
setnumber = {{ n = 4, quad = 1 }}

[materials.m]
E = 1000.0
nu = 0.25

[[bodies]]
group = "bottom"
material = "m"
{bodies}
[[bodies]]
group = "top"
material = "m"
{bodies}
[[contacts]]
group = "joint"
friction = 0.5
{joint}

[[supports]]
group = "base"
fix = ["y"]

[[supports]]
group = "corner"
fix = ["x"]

[[loads]]
group = "top_face"
{load}

[solver]
{solver}
"#
    );
    let path = case.write(&format!("{name}.toml"), &scene);
    case.run(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// (x, u_y) of every node on the top face.
fn top_settlement(run: &Run) -> Vec<(f64, f64)> {
    let u = &run.last().u;
    (run.model.coords.iter().enumerate())
        .filter(|(_, x)| (x[1] - 2.0).abs() < 1e-9)
        .map(|(n, x)| (x[0], u[2 * n + 1]))
        .collect()
}

#[test]
fn a_joint_closes_by_the_pressure_over_its_normal_stiffness() {
    let case = Case::new("stiff-settle");
    let (q, k_n) = (1.0, 100.0);
    let rigid = stack(&case, "rigid", "", "pressure = 1.0", "", "");
    let stiff = stack(&case, "stiff", &springs(k_n, 50.0), "pressure = 1.0", "", "");
    let c = stiff.contact().expect("contact");
    assert!(c.summary.converged);
    for (p, r) in c.pairs.iter().enumerate() {
        assert_eq!(c.states[p], ContactState::Stick, "pair {p}");
        assert!((r.sigma_n + q).abs() < 1e-10, "pair {p}: sigma_n {}", r.sigma_n);
        assert!((r.gap + q / k_n).abs() < 1e-12, "pair {p}: gap {} against -q / k_n", r.gap);
    }
    let (a, b) = (top_settlement(&rigid), top_settlement(&stiff));
    assert!(!a.is_empty() && a.len() == b.len());
    for ((x, ua), (_, ub)) in a.iter().zip(&b) {
        let extra = ub - ua;
        eprintln!("x = {x:.3}: u_y {ua:.6e} rigid, {ub:.6e} stiff, extra {extra:.6e}");
        assert!((extra + q / k_n).abs() < 1e-11, "x = {x}: the joint adds {extra:e}, not -q / k_n");
    }
}

#[test]
fn springs_start_carrying_the_in_situ_stress() {
    // sigma_yy = -2 in both blocks, balanced by the top face's pressure:
    // nothing moves, joint or not; springs that started unloaded would
    // close the joint by 2 / k_n = 0.02
    let case = Case::new("stiff-insitu");
    let initial = "initial_stress = [0.0, -2.0, 0.0, 0.0]\n";
    let run = stack(&case, "insitu", &springs(100.0, 50.0), "pressure = 2.0", initial, "");
    let c = run.contact().expect("contact");
    assert!(c.summary.converged);
    let most = run.last().u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    eprintln!("in situ with stiff joints: max |u| = {most:.3e}");
    assert!(most < 1e-12, "the in-situ stress moved the blocks by {most:e}");
    // the gap is measured from where the spring is unloaded: closed by
    // sigma_n / k_n in situ
    for r in &c.pairs {
        assert!((r.sigma_n + 2.0).abs() < 1e-10 && (r.gap + 0.02).abs() < 1e-12, "{r:?}");
    }
}

#[test]
fn a_preloaded_joint_slips_as_one_loaded_from_nothing() {
    // the same total stress, once with the pressure in situ (the top
    // face's load keeps it, and adds a shear), once loaded from nothing:
    // one step each, the same forces pair by pair (pairs near the edges
    // slip), the in-situ joint starting closed by 2 / k_n
    let case = Case::new("stiff-preload-slip");
    let initial = "initial_stress = [0.0, -2.0, 0.0, 0.0]\n";
    let joint = springs(100.0, 50.0);
    let load = "traction = [0.9, -2.0]";
    let insitu = stack(&case, "insitu", &joint, load, initial, "");
    let whole = stack(&case, "whole", &joint, load, "", "");
    let (a, b) = (insitu.contact().expect("contact"), whole.contact().expect("contact"));
    assert!(a.summary.converged && b.summary.converged);
    assert!(a.states.contains(&ContactState::Slip), "{:?}", a.states);
    assert_eq!(a.states, b.states);
    for (x, y) in a.pairs.iter().zip(&b.pairs) {
        let d = (x.sigma_n - y.sigma_n).abs().max((x.tau_t - y.tau_t).abs()).max((x.gap - y.gap).abs() * 100.0);
        assert!(d < 1e-9, "{x:?} against {y:?}");
    }
}

#[test]
fn stiff_joints_tend_to_the_rigid_joint_as_one_over_the_stiffness() {
    // the top block rocks under a shear on its top face: pairs stick and
    // slip along the joint
    let case = Case::new("stiff-limit");
    let load = "traction = [0.3, -1.0]";
    let rigid = stack(&case, "rigid", "", load, "", "");
    let rc = rigid.contact().expect("contact");
    let ks = [1e5, 1e7, 1e9];
    let mut diffs = Vec::new();
    for k in ks {
        let run = stack(&case, &format!("k{k:e}"), &springs(k, k), load, "", "");
        let c = run.contact().expect("contact");
        assert!(c.summary.converged);
        assert_eq!(c.states, rc.states, "k = {k:e}: the rigid joint's states");
        let d = (c.pairs.iter().zip(&rc.pairs))
            .map(|(a, b)| (a.sigma_n - b.sigma_n).abs().max((a.tau_t - b.tau_t).abs()))
            .fold(0.0, f64::max);
        eprintln!("k_n = k_s = {k:e}: max |force difference| / area to the rigid joint {d:.3e}");
        diffs.push(d);
    }
    let rate = loglog_slope(&ks, &diffs);
    eprintln!("fitted rate {rate:.4}");
    assert!((rate + 1.0).abs() < 0.02, "the difference falls as k^{rate}, not 1 / k");
    assert!(diffs[2] < 1e-6);
}

#[test]
fn every_interface_solver_gives_one_answer() {
    let case = Case::new("stiff-solvers");
    let load = "traction = [0.3, -1.0]";
    let runs: Vec<Run> = ["dense", "sparse", "iterative"]
        .iter()
        .map(|i| stack(&case, i, &springs(100.0, 50.0), load, "", &format!("interface = \"{i}\"")))
        .collect();
    let dense = runs[0].contact().expect("contact");
    let count = |s| dense.states.iter().filter(|&&x| x == s).count();
    assert!(count(ContactState::Stick) > 0 && count(ContactState::Slip) > 0, "{:?}", dense.states);
    for (name, run) in ["sparse", "iterative"].iter().zip(&runs[1..]) {
        let c = run.contact().expect("contact");
        assert!(c.summary.converged);
        assert_eq!(c.states, dense.states, "{name}");
        for (a, b) in c.pairs.iter().zip(&dense.pairs) {
            let d = (a.sigma_n - b.sigma_n).abs().max((a.tau_t - b.tau_t).abs()).max((a.gap - b.gap).abs() * 100.0);
            assert!(d < 1e-9, "{name}: {a:?} against {b:?}");
        }
    }
    for run in &runs {
        let c = run.contact().expect("contact");
        let worst = c.law_residual.iter().fold(0.0f64, |m, &r| m.max(r));
        assert!(worst < 1e-9, "law residual {worst:e}");
        // a slipping pair is at its Coulomb bound, a stuck one within it
        for (p, r) in c.pairs.iter().enumerate() {
            let bound = -0.5 * r.sigma_n;
            match c.states[p] {
                ContactState::Slip => assert!((r.tau_t.abs() - bound).abs() < 1e-9, "pair {p}: {r:?}"),
                _ => assert!(r.tau_t.abs() <= bound + 1e-9, "pair {p}: {r:?}"),
            }
        }
    }
}

#[test]
fn a_block_pushed_beyond_its_friction_slides() {
    let case = Case::new("stiff-slides");
    case.copy("tests/geo/contact_stack.geo");
    let text = format!(
        "mesh = \"contact_stack.geo\"\nanalysis = \"plane_strain\"\n[gmsh]\norder = 2\n[materials.m]\nE = 1000.0\nnu = 0.25\n\
         [[bodies]]\ngroup = \"bottom\"\nmaterial = \"m\"\n[[bodies]]\ngroup = \"top\"\nmaterial = \"m\"\n\
         [[contacts]]\ngroup = \"joint\"\nfriction = 0.5\n{}\n\
         [[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n\
         [[loads]]\ngroup = \"top_face\"\ntraction = [0.8, -1.0]\n",
        springs(100.0, 50.0)
    );
    let path = case.write("slide.toml", &text);
    let out = case.cli(&["solve", path.to_str().expect("path"), "--quiet"]);
    let msg = common::cli::clean_failure(&case, &out, &case.out("slide"));
    common::cli::says(&msg, &["body \"top\" slides", "friction"]);
}
