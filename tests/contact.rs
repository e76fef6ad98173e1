//! Contact by the substructure interface method, end to end through the real
//! gmsh CLI: the interface solve against the monolithic bonded solve (all
//! pairs stuck must give the bonded answer to round-off, 2D and 3D), the
//! seed paper's cylinder (its 30-hex mesh and the default quad9 mesh against
//! Lamé and the paper's Table 2), separate coincident contact groups against
//! one shared curve, the contact patch test (a uniform stress crosses the
//! interface exactly, end pairs included, for linear and quadratic
//! elements, and with supports on interface nodes in 3D), a block pulled
//! off its support (every pair opens, the run names the free body and
//! writes nothing) or sliding on a frictionless joint, a curved interface
//! whose end nodes sit on symmetry supports, and the messages for bad
//! contact input.
//!
//! Scenes: `geo/cylinder*.{geo,toml}` and `tests/geo/contact_*.geo`, with
//! the scene text written by each test. Units are consistent and arbitrary.

mod common;

use std::collections::HashMap;
use std::path::Path;

use common::cli::{clean_failure, says};
use common::measure::{body_nodes, diff_to_bonded, max_abs};
use common::scenes::{self, two_blocks};
use common::Case;
use subcontact::analytic::paper_tables::{contact_sigma_n_at, TABLE2_R};
use subcontact::analytic::Lame;
use subcontact::contact::law::ContactState;
use subcontact::driver::{At, ContactError, Run};
use subcontact::scene::Analysis;

// ---------------------------------------------------------------------------
// helpers

/// Radius of the k node of every pair and its sigma_n.
fn pair_radii(run: &Run) -> Vec<(f64, f64)> {
    let c = run.contact().expect("a contact run");
    run.model
        .pairs
        .iter()
        .zip(&c.pairs)
        .map(|(p, r)| (run.model.coords[p.k][0].hypot(run.model.coords[p.k][1]), r.sigma_n))
        .collect()
}

fn assert_all(run: &Run, state: ContactState) {
    let c = run.contact().expect("a contact run");
    assert!(c.summary.converged, "contact iteration converged");
    for (i, s) in c.states.iter().enumerate() {
        assert_eq!(*s, state, "pair {i} at {:?}", run.model.coords[run.model.pairs[i].k]);
    }
}

fn lame(run: &Run) -> Lame {
    let b = &run.model.bodies[0];
    Lame { a: 3.0, b: 5.0, p: 0.1, e: b.material.e, nu: b.material.nu, analysis: Analysis::PlaneStrain }
}

/// Model nodes used by the bodies' cells.
fn used_nodes(run: &Run) -> Vec<usize> {
    let mut v: Vec<usize> =
        run.model.bodies.iter().flat_map(|b| b.cells.iter().flat_map(|c| c.nodes.iter().copied())).collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Runs the binary on a scene that must be refused (results in the default
/// `results/<stem>`): a clean failure, see [`clean_failure`]; returns the message.
fn refused(case: &Case, scene: &str) -> String {
    let stem = Path::new(scene).file_stem().expect("stem").to_string_lossy().to_string();
    clean_failure(case, &case.cli(&["solve", scene, "--quiet"]), &case.out(&stem))
}

/// The two blocks of contact_stack.geo / contact_stack3d.geo, bottom listed
/// first (body I, n = +y), with the given load on the top face. With
/// STACK_SUPPORTS_2D the top block is held by the contact alone; with
/// STACK_SUPPORTS_3D (plane strain: z faces, symmetry x = 0) it is held in x
/// and z but only the contact holds it in y.
fn stack_scene(
    geo: &str,
    analysis: &str,
    order: usize,
    setnumber: &str,
    load: &str,
    contact: &str,
    supports: &str,
) -> String {
    let head = format!(
        r#"title = "two stacked blocks"
mesh = "{geo}"
analysis = "{analysis}"

[gmsh]
order = {order}
setnumber = {{ {setnumber} }}"#
    );
    two_blocks(&head, 1000.0, 0.25, contact, &format!("{supports}\n\n[[loads]]\ngroup = \"top_face\"\n{load}\n"))
}

const STACK_SUPPORTS_2D: &str =
    "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"corner\"\nfix = [\"x\"]\n";
const STACK_SUPPORTS_3D: &str = "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"x0\"\nfix = [\"x\"]\n\n[[supports]]\ngroup = \"z_faces\"\nfix = [\"z\"]\n";
const STRONG_JOINT: &str = "friction = 0.5\ncohesion = 1.0\ntensile_strength = 2.0";

// ---------------------------------------------------------------------------
// all pairs stuck = the monolithic bonded solve

#[test]
fn all_stick_equals_bonded_solve_on_the_2d_cylinder() {
    let case = Case::new("contact-bonded-cyl2d");
    case.copy("geo/cylinder.geo");
    let scene = case.copy("geo/cylinder.toml");
    let contact = case.run(&scene).expect("contact run");
    let bonded = case.run_with(&scene, true).expect("bonded run");
    assert_all(&contact, ContactState::Stick);
    assert_eq!(contact.model.n_nodes(), bonded.model.n_nodes() + contact.model.pairs.len());
    let d = diff_to_bonded(&contact, &bonded);
    eprintln!("2D cylinder ({} pairs): max |u - u_bonded| / max|u| = {d:.2e}", contact.model.pairs.len());
    assert!(d < 1e-10, "{d:.3e}");
}

#[test]
fn all_stick_equals_bonded_solve_on_the_3d_paper_mesh() {
    let case = Case::new("contact-bonded-paper");
    case.copy("geo/cylinder_paper.geo");
    let scene = case.copy("geo/cylinder_paper.toml");
    let contact = case.run(&scene).expect("contact run");
    let bonded = case.run_with(&scene, true).expect("bonded run");
    assert_all(&contact, ContactState::Stick);
    let d = diff_to_bonded(&contact, &bonded);
    eprintln!("3D paper mesh: max |u - u_bonded| / max|u| = {d:.2e}");
    assert!(d < 1e-10, "{d:.3e}");
}

/// 3D boxes, base clamped, top face under an inclined traction: the joint
/// carries normal stress, shear in both tangential directions and bending.
#[test]
fn all_stick_equals_bonded_solve_on_3d_boxes_under_an_inclined_load() {
    let case = Case::new("contact-bonded-boxes");
    case.copy("tests/geo/contact_stack3d.geo");
    let clamped = "[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n";
    let load = "traction = [0.3, -1.0, 0.2]";
    let strong = "friction = 0.5\ncohesion = 100.0\ntensile_strength = 100.0";
    for (name, order, set) in [("hex27", 2, "n = 3, nz = 2, hex = 1"), ("tet4", 1, "n = 6, hex = 0")] {
        let scene = case.write(
            &format!("boxes_{name}.toml"),
            &stack_scene("contact_stack3d.geo", "solid", order, set, load, strong, clamped),
        );
        let contact = case.run(&scene).expect("contact run");
        let bonded = case.run_with(&scene, true).expect("bonded run");
        assert_all(&contact, ContactState::Stick);
        let c = contact.contact().expect("contact");
        let max_tau = c.pairs.iter().map(|p| p.tau()).fold(0.0, f64::max);
        assert!(max_tau > 0.1, "{name}: the joint carries shear ({max_tau})");
        let d = diff_to_bonded(&contact, &bonded);
        eprintln!("3D boxes {name} ({} pairs): max |u - u_bonded| / max|u| = {d:.2e}", c.pairs.len());
        assert!(d < 1e-10, "{name}: {d:.3e}");
    }
}

// ---------------------------------------------------------------------------
// the paper's cylinder

#[test]
fn paper_mesh_splits_84_nodes_into_96_with_12_stuck_pairs_and_matches_table2() {
    let case = Case::new("contact-paper");
    case.copy("geo/cylinder_paper.geo");
    let scene = case.copy("geo/cylinder_paper.toml");
    let run = case.run(&scene).expect("paper mesh run");
    let mesh = subcontact::mesh::msh::read_msh(&run.stats.msh).expect("read the paper mesh");
    assert_eq!(mesh.coords.len(), 84, "mesh nodes");
    let used = used_nodes(&run);
    assert_eq!(used.len(), 96, "model nodes after the split");
    let mut mesh_used: Vec<usize> = used.iter().map(|&m| run.model.mesh_node[m]).collect();
    mesh_used.sort_unstable();
    mesh_used.dedup();
    assert_eq!(mesh_used.len(), 84, "every mesh node is used");
    assert_eq!(run.model.pairs.len(), 12);
    assert_all(&run, ContactState::Stick);
    let lame = lame(&run);
    // interior pairs of Table 2 (the ends are lumped: 5 % off at r = 5, as in the paper)
    for r in &TABLE2_R[1..5] {
        let s = contact_sigma_n_at(&run.solution(), *r).expect("a pair at r");
        let e = (s - lame.sigma_theta(*r)) / lame.sigma_theta(*r);
        eprintln!(
            "paper mesh, r = {r}: sigma_n = {:.4} (1e-2 MPa), theory {:.4}, {:+.3} %",
            100.0 * s,
            100.0 * lame.sigma_theta(*r),
            100.0 * e
        );
        assert!(e.abs() < 0.01, "r = {r}: {:+.3} %", 100.0 * e);
    }
}

#[test]
fn default_cylinder_mesh_contact_stress_is_lame_sigma_theta_at_every_pair() {
    let case = Case::new("contact-cylinder");
    case.copy("geo/cylinder.geo");
    let scene = case.copy("geo/cylinder.toml");
    let run = case.run(&scene).expect("cylinder run");
    assert_all(&run, ContactState::Stick);
    let lame = lame(&run);
    let mut worst = 0.0f64;
    for (r, s) in pair_radii(&run) {
        let e = (s - lame.sigma_theta(r)) / lame.sigma_theta(r);
        assert!(e.abs() < 0.005, "pair at r = {r}: sigma_n {s}, theory {}, {:+.3} %", lame.sigma_theta(r), 100.0 * e);
        worst = worst.max(e.abs());
    }
    let mut table = 0.0f64;
    for &r in &TABLE2_R {
        let s = contact_sigma_n_at(&run.solution(), r).expect("a pair at r");
        let e = (s - lame.sigma_theta(r)) / lame.sigma_theta(r);
        assert!(e.abs() < 0.005, "Table 2, r = {r}: {:+.3} %", 100.0 * e);
        table = table.max(e.abs());
    }
    eprintln!(
        "default cylinder mesh: {} pairs, max |sigma_n / sigma_theta - 1| = {:.2e} (pairs), {:.2e} (Table 2)",
        run.model.pairs.len(),
        worst,
        table
    );
}

// ---------------------------------------------------------------------------
// groups = [a, b] against one shared curve

#[test]
fn separate_coincident_contact_groups_give_the_shared_curve_answer() {
    let case = Case::new("contact-split");
    case.copy("geo/cylinder.geo");
    case.copy("tests/geo/contact_cylinder_split.geo");
    let shared_text = scenes::edited("geo/cylinder.toml", &[("lc = 0.05", "lc = 0.1")]);
    let split_text = scenes::edited(
        "geo/cylinder.toml",
        &[
            ("lc = 0.05", "lc = 0.1"),
            ("cylinder.geo", "contact_cylinder_split.geo"),
            ("group = \"A-A\"", "groups = [\"a\", \"b\"]"),
        ],
    );
    assert_ne!(split_text, shared_text);
    let shared = case.run(&case.write("shared.toml", &shared_text)).expect("shared-curve run");
    let split = case.run(&case.write("split.toml", &split_text)).expect("split-curve run");

    // gmsh kept the two cuts apart: the split mesh has one more node per pair
    let n_pairs = split.model.pairs.len();
    assert_eq!(n_pairs, shared.model.pairs.len());
    assert_eq!(n_pairs, 41, "2 (b - a) / lc + 1 nodes on the cut of quad9");
    let split_mesh = subcontact::mesh::msh::read_msh(&split.stats.msh).expect("split mesh");
    let shared_mesh = subcontact::mesh::msh::read_msh(&shared.stats.msh).expect("shared mesh");
    assert_eq!(split_mesh.coords.len(), shared_mesh.coords.len() + n_pairs);
    assert_eq!(split.model.n_nodes(), shared.model.n_nodes());
    assert_all(&split, ContactState::Stick);

    // displacements by (body, position)
    type Keyed = ((usize, [i64; 2]), [f64; 2]);
    fn by_body_and_position(run: &Run) -> Vec<Keyed> {
        body_nodes(run)
            .into_iter()
            .map(|(b, n)| {
                let x = run.model.coords[n];
                (
                    (b, [(x[0] * 1e8).round() as i64, (x[1] * 1e8).round() as i64]),
                    [run.last().u[2 * n], run.last().u[2 * n + 1]],
                )
            })
            .collect()
    }
    let a: HashMap<_, _> = by_body_and_position(&shared).into_iter().collect();
    let b = by_body_and_position(&split);
    assert_eq!(a.len(), b.len());
    let scale = max_abs(a.values().flat_map(|u| u.iter().copied()));
    let mut worst = 0.0f64;
    for (key, u) in &b {
        let w = a.get(key).unwrap_or_else(|| panic!("node {key:?} of the split mesh is in the shared mesh"));
        worst = worst.max((u[0] - w[0]).abs()).max((u[1] - w[1]).abs());
    }
    let du = worst / scale;

    // contact stresses by position
    let sa: HashMap<[i64; 2], f64> = pair_keyed(&shared);
    let mut ds = 0.0f64;
    for (k, s) in pair_keyed(&split) {
        ds = ds.max((s - sa[&k]).abs() / s.abs());
    }
    eprintln!("groups = [a, b] vs shared curve ({n_pairs} pairs): displacements {du:.2e}, sigma_n {ds:.2e} (max relative difference)");
    assert!(du < 1e-9, "{du:.3e}");
    assert!(ds < 1e-9, "{ds:.3e}");
}

fn pair_keyed(run: &Run) -> HashMap<[i64; 2], f64> {
    let c = run.contact().expect("contact");
    run.model
        .pairs
        .iter()
        .zip(&c.pairs)
        .map(|(p, r)| {
            let x = run.model.coords[p.k];
            ([(x[0] * 1e8).round() as i64, (x[1] * 1e8).round() as i64], r.sigma_n)
        })
        .collect()
}

// ---------------------------------------------------------------------------
// tension: the contact patch test, and the block pulled off

/// Uniform tension t below f_t through the joint: every pair sticks and
/// carries exactly t, the end pairs included (lumped force over the
/// consistent area is exact for a uniform traction).
fn patch_test_2d(kinds: &[(&str, usize, &str)]) {
    let case = Case::new(&format!("contact-patch-{}", kinds[0].0));
    case.copy("tests/geo/contact_stack.geo");
    let t = 1.5;
    for (name, order, set) in kinds {
        let text = stack_scene(
            "contact_stack.geo",
            "plane_stress",
            *order,
            set,
            &format!("traction = [0.0, {t}]"),
            STRONG_JOINT,
            STACK_SUPPORTS_2D,
        );
        let run = case.run(&case.write(&format!("stack_{name}.toml"), &text)).expect("patch test run");
        let kind = run.model.bodies[0].cells[0].kind.name();
        assert_eq!(&kind, name, "element kind");
        assert_all(&run, ContactState::Stick);
        let c = run.contact().expect("contact");
        assert!(c.pairs.len() >= 5);
        let mut worst = 0.0f64;
        for (p, r) in run.model.pairs.iter().zip(&c.pairs) {
            let e = (r.sigma_n - t).abs().max(r.tau().abs()) / t;
            assert!(e < 1e-9, "{name}: pair at {:?}: sigma_n {} tau {}", run.model.coords[p.k], r.sigma_n, r.tau());
            worst = worst.max(e);
        }
        eprintln!("contact patch test {name}: {} pairs, max |sigma_n - t|, |tau| = {:.2e} t", c.pairs.len(), worst);
    }
}

#[test]
fn contact_patch_test_in_tension_is_exact_for_linear_elements() {
    patch_test_2d(&[("quad4", 1, "n = 4, quad = 1"), ("tri3", 1, "n = 5, quad = 0")]);
}

#[test]
fn contact_patch_test_in_tension_is_exact_for_quadratic_elements() {
    patch_test_2d(&[
        ("quad9", 2, "n = 3, quad = 1"),
        ("quad8", 2, "n = 3, quad = 1, serendipity = 1"),
        ("tri6", 2, "n = 4, quad = 0"),
    ]);
}

/// f_t = 2 and a pull of 2.5: the first (all stuck) solve gives sigma_n =
/// 2.5 at every pair, so all open, and the top block is held by nothing. In
/// 3D the top block keeps its plane-strain supports (z faces, x = 0): it is
/// held in x and z but not in y, which is as free.
#[test]
fn tension_above_tensile_strength_opens_every_pair_and_names_the_free_body() {
    let case = Case::new("contact-pull-off");
    case.copy("tests/geo/contact_stack.geo");
    case.copy("tests/geo/contact_stack3d.geo");
    let cases = [
        ("quad4", "contact_stack.geo", "plane_stress", 1, "n = 4, quad = 1", STACK_SUPPORTS_2D),
        ("tri6", "contact_stack.geo", "plane_stress", 2, "n = 4, quad = 0", STACK_SUPPORTS_2D),
        ("hex8", "contact_stack3d.geo", "solid", 1, "n = 3, nz = 2, hex = 1", STACK_SUPPORTS_3D),
        ("hex27", "contact_stack3d.geo", "solid", 2, "n = 3, nz = 2, hex = 1", STACK_SUPPORTS_3D),
        ("tet4", "contact_stack3d.geo", "solid", 1, "n = 4, hex = 0", STACK_SUPPORTS_3D),
    ];
    for (name, geo, analysis, order, set, supports) in cases {
        let scene = format!("pull_{name}.toml");
        let pull = if analysis == "solid" { "traction = [0.0, 2.5, 0.0]" } else { "traction = [0.0, 2.5]" };
        let text = stack_scene(geo, analysis, order, set, pull, STRONG_JOINT, supports);
        case.write(&scene, &text);
        // the pairs of the same mesh, from a run the joint holds (pull 1.5 < f_t)
        let held = case.write(&format!("held_{name}.toml"), &text.replace("2.5", "1.5"));
        let pairs = case.run(&held).expect("the same scene below f_t").model.pairs.len();
        let stderr = refused(&case, &scene);
        eprintln!("pull-off {name}: {}", stderr.trim());
        assert!(stderr.contains(&scene), "names the scene: {stderr}");
        assert!(stderr.contains("body \"top\" is held by nothing"), "names the free body: {stderr}");
        assert!(!stderr.contains("\"bottom\""), "not the supported one: {stderr}");
        assert!(stderr.contains(&format!("(0 stick, 0 slip, {pairs} open)")), "gives the states: {stderr}");
        assert!(stderr.contains("iteration 2"), "after the first (all stuck) solve: {stderr}");
        match case.contact_error(&case.dir.join(&scene)) {
            ContactError::NotHeld { bodies, at, .. } => {
                assert_eq!(
                    (bodies, at.iteration, at.states),
                    (vec!["top".to_string()], 2, [pairs as u32, 0, 0]),
                    "{name}"
                )
            }
            other => panic!("{name}: not held, not {other:?}"),
        }
    }
}

/// The same stack as a solid of revolution about the y axis (r = x): axial
/// compression p is a uniform stress, u_r linear in r. Only the base is held
/// (axially); a radial support is not needed, since moving in r strains
/// the hoops, and is not given. The linear mesh reaches the axis (a pair at
/// r = 0), the quadratic ones are rings (r = 1..3).
#[test]
fn contact_patch_test_in_compression_is_exact_in_axisymmetry() {
    let case = Case::new("contact-patch-axi");
    case.copy("tests/geo/contact_stack.geo");
    let p = 1.5;
    let base_only = "[[supports]]\ngroup = \"base\"\nfix = [\"y\"]\n";
    for (name, order, set) in [
        ("quad4", 1, "n = 4, quad = 1"),
        ("quad9", 2, "n = 3, quad = 1, x0 = 1"),
        ("tri6", 2, "n = 4, quad = 0, x0 = 1"),
    ] {
        let text = stack_scene(
            "contact_stack.geo",
            "axisymmetric",
            order,
            set,
            &format!("pressure = {p}"),
            "friction = 0.5\ncohesion = 0.0\ntensile_strength = 0.0",
            base_only,
        );
        let run = case.run(&case.write(&format!("axi_{name}.toml"), &text)).expect("axisymmetric patch test run");
        assert_eq!(run.model.bodies[0].cells[0].kind.name(), name);
        assert_all(&run, ContactState::Stick);
        let c = run.contact().expect("contact");
        let mut worst = 0.0f64;
        for (pr, r) in run.model.pairs.iter().zip(&c.pairs) {
            let e = (r.sigma_n + p).abs().max(r.tau()) / p;
            assert!(e < 1e-9, "{name}: pair at {:?}: sigma_n {} tau {}", run.model.coords[pr.k], r.sigma_n, r.tau());
            worst = worst.max(e);
        }
        eprintln!(
            "axisymmetric contact patch test {name}: {} pairs, max |sigma_n + p|, |tau| = {:.2e} p",
            c.pairs.len(),
            worst
        );
    }
}

/// A frictionless joint (no cohesion): every pair slips and nothing holds
/// the top block along the joint. The run must stop with a message, not
/// return the block slid off to infinity (or to an arbitrary place).
#[test]
fn frictionless_joint_that_lets_a_block_slide_is_refused_as_singular() {
    let case = Case::new("contact-slide-off");
    case.copy("tests/geo/contact_stack.geo");
    let frictionless = "friction = 0.0\ncohesion = 0.0\ntensile_strength = 0.0\nslip = \"frictionless\"";
    // sideways load: no equilibrium at all; straight down: equilibrium, but
    // the block's position along the joint is anyone's guess
    for (name, load) in [("sideways", "traction = [0.2, -1.5]"), ("down", "traction = [0.0, -1.5]")] {
        let scene = format!("slide_{name}.toml");
        case.write(
            &scene,
            &stack_scene(
                "contact_stack.geo",
                "plane_stress",
                1,
                "n = 4, quad = 1",
                load,
                frictionless,
                STACK_SUPPORTS_2D,
            ),
        );
        let stderr = refused(&case, &scene);
        eprintln!("slide-off {name}: {}", stderr.trim());
        says(
            &stderr,
            &[
                scene.as_str(),
                "singular",
                "iteration 2",
                "(0 stick, 5 slip, 0 open)",
                "slides or rotates freely (translation along (1.0000, 0.0000))",
                "carry no shear",
                "give the contacts friction or cohesion",
            ],
        );
        // nothing along the joint is to blame when the joint carries no shear at all
        assert!(!stderr.contains("exceeds"), "no load exceeds a shear strength of zero: {stderr}");
        match case.contact_error(&case.dir.join(&scene)) {
            ContactError::Sliding { bodies, no_shear, at, .. } => {
                assert_eq!(bodies, ["top"], "{name}");
                assert!(no_shear, "{name}: the joint carries no shear");
                assert_eq!(at, At { step: None, iteration: 2, states: [0, 5, 0], rounds: None }, "{name}");
            }
            other => panic!("{name}: sliding, not {other:?}"),
        }
    }
}

/// 3D boxes in uniform compression, plane strain by w = 0 on the z faces
/// and symmetry on x = 0: the joint's edge pairs are supported in z (and in
/// x at x = 0). With no cohesion and friction 0.2 every pair must still
/// stick with sigma_n = -p and no shear: the support reactions at those
/// nodes are not contact shear.
#[test]
fn contact_patch_test_in_3d_with_supports_on_interface_nodes() {
    let case = Case::new("contact-patch-3d");
    case.copy("tests/geo/contact_stack3d.geo");
    let p = 1.0;
    let weak = "friction = 0.2\ncohesion = 0.0\ntensile_strength = 0.0";
    for (name, order, set) in [
        ("hex8", 1, "n = 3, nz = 2, hex = 1"),
        ("hex27", 2, "n = 2, nz = 1, hex = 1"),
        ("hex20", 2, "n = 2, nz = 1, hex = 1, serendipity = 1"),
        ("tet4", 1, "n = 4, hex = 0"),
    ] {
        let text = stack_scene(
            "contact_stack3d.geo",
            "solid",
            order,
            set,
            &format!("pressure = {p}"),
            weak,
            STACK_SUPPORTS_3D,
        );
        let run = case.run(&case.write(&format!("boxes_{name}.toml"), &text)).expect("3D patch test run");
        assert_eq!(run.model.bodies[0].cells[0].kind.name(), name);
        let supported = run.model.pairs.iter().filter(|pr| run.model.prescribed[pr.k * 3 + 2].is_some()).count();
        assert!(supported > 0, "{name}: interface nodes on the z faces are supported");
        assert_all(&run, ContactState::Stick);
        let c = run.contact().expect("contact");
        let mut worst = 0.0f64;
        for (pr, r) in run.model.pairs.iter().zip(&c.pairs) {
            let e = (r.sigma_n + p).abs().max(r.tau()) / p;
            assert!(
                e < 1e-9,
                "{name}: pair at {:?}: sigma_n {} tau_t {} tau_b {}",
                run.model.coords[pr.k],
                r.sigma_n,
                r.tau_t,
                r.tau_b
            );
            worst = worst.max(e);
        }
        eprintln!(
            "3D contact patch test {name}: {} pairs ({supported} supported in z), max |sigma_n + p|, |tau| = {:.2e} p",
            c.pairs.len(),
            worst
        );
    }
}

// ---------------------------------------------------------------------------
// a curved interface whose end nodes are on symmetry supports

/// Two rings (r = 3..4 and 4..5) under internal pressure: together Lamé's
/// cylinder, so the contact carries sigma_r(4) (compression). The joint's end
/// nodes lie on x = 0 and y = 0, supported across the symmetry line while
/// the frame there comes from a curved interface.
#[test]
fn curved_interface_with_supported_end_nodes_sticks_or_slips_as_lame() {
    let case = Case::new("contact-ring");
    case.copy("tests/geo/contact_ring.geo");
    let ring = |order: usize, set: &str, contact: &str| {
        format!(
            r#"mesh = "contact_ring.geo"
analysis = "plane_strain"
[gmsh]
order = {order}
setnumber = {{ {set} }}
[materials.m]
E = 2.0e5
nu = 0.167
[[bodies]]
group = "inner_ring"
material = "m"
[[bodies]]
group = "outer_ring"
material = "m"
[[contacts]]
group = "joint"
{contact}
[[supports]]
group = "symmetry_x0"
fix = ["x"]
[[supports]]
group = "symmetry_y0"
fix = ["y"]
[[loads]]
group = "inner"
pressure = 0.1
"#
        )
    };
    let stick = "friction = 0.8\ncohesion = 1.0\ntensile_strength = 1.0";
    let frictionless = "friction = 0.0\ncohesion = 0.0\ntensile_strength = 0.0\nslip = \"frictionless\"";
    for (name, order, set) in [("quad9", 2, "lc = 0.25, quad = 1"), ("tri6", 2, "lc = 0.25, quad = 0")] {
        let scene = case.write(&format!("ring_{name}.toml"), &ring(order, set, stick));
        let run = case.run(&scene).expect("ring run");
        let bonded = case.run_with(&scene, true).expect("bonded ring run");
        assert_all(&run, ContactState::Stick);
        let d = diff_to_bonded(&run, &bonded);
        let lame = lame(&run);
        let exact = lame.sigma_r(4.0);
        let worst = pair_radii(&run).iter().map(|(_, s)| ((s - exact) / exact).abs()).fold(0.0, f64::max);
        eprintln!("ring {name}: stick vs bonded {d:.2e}; max |sigma_n / sigma_r(4) - 1| = {worst:.2e}");
        assert!(d < 1e-10, "{name}: {d:.3e}");
        assert!(worst < 0.005, "{name}: {worst:.3e}");

        // no cohesion, friction 0.8: the pairs carry no shear but the
        // end pairs' support reactions, which are not contact shear, so
        // every pair still sticks
        let scene = case.write(
            &format!("ring_{name}_cohesionless.toml"),
            &ring(order, set, "friction = 0.8\ncohesion = 0.0\ntensile_strength = 0.0"),
        );
        let cohesionless = case.run(&scene).expect("cohesionless ring run");
        assert_all(&cohesionless, ContactState::Stick);
        let d = diff_to_bonded(&cohesionless, &bonded);
        assert!(d < 1e-10, "{name} cohesionless: {d:.3e}");

        // frictionless: every pair slips; by symmetry there is no shear to lose
        let scene = case.write(&format!("ring_{name}_slip.toml"), &ring(order, set, frictionless));
        let slip = case.run(&scene).expect("frictionless ring run");
        assert_all(&slip, ContactState::Slip);
        let c = slip.contact().expect("contact");
        let worst_slip = pair_radii(&slip).iter().map(|(_, s)| ((s - exact) / exact).abs()).fold(0.0, f64::max);
        let max_tau = c.pairs.iter().map(|r| r.tau()).fold(0.0, f64::max);
        eprintln!(
            "ring {name} frictionless: max |sigma_n / sigma_r(4) - 1| = {worst_slip:.2e}, max tau = {max_tau:.2e}"
        );
        assert!(worst_slip < 0.005, "{name}: {worst_slip:.3e}");
        assert!(max_tau < 1e-9 * exact.abs(), "{name}: slipping pairs carry no shear ({max_tau:.3e})");
    }
}

// ---------------------------------------------------------------------------
// bad contact input

#[test]
fn unpaired_interface_nodes_are_refused_naming_the_groups() {
    let case = Case::new("contact-unpaired");
    case.copy("tests/geo/contact_cylinder_split.geo");
    let text = scenes::edited(
        "geo/cylinder.toml",
        &[
            ("cylinder.geo", "contact_cylinder_split.geo"),
            ("group = \"A-A\"", "groups = [\"a\", \"b\"]"),
            ("lc = 0.05", "lc = 0.5, extra = 1"),
        ],
    );
    case.write("unpaired.toml", &text);
    let stderr = refused(&case, "unpaired.toml");
    eprintln!("unpaired: {}", stderr.trim());
    says(&stderr, &["unpaired.toml", "contacts[0].groups", "\"a\"", "\"b\"", "no partner"]);
}

#[test]
fn contact_group_on_one_body_is_refused_naming_the_group_and_body() {
    let case = Case::new("contact-one-body");
    case.copy("tests/geo/contact_stack.geo");
    let text = stack_scene(
        "contact_stack.geo",
        "plane_stress",
        1,
        "n = 2",
        "traction = [0.0, 1.0]",
        STRONG_JOINT,
        STACK_SUPPORTS_2D,
    )
    .replace("group = \"joint\"", "group = \"top_face\"");
    case.write("one_body.toml", &text);
    let stderr = refused(&case, "one_body.toml");
    eprintln!("one body: {}", stderr.trim());
    says(&stderr, &["one_body.toml", "contacts[0].group", "\"top_face\"", "only body \"top\""]);
}

#[test]
fn contact_of_a_body_with_itself_is_refused_naming_the_body() {
    let case = Case::new("contact-self");
    case.copy("tests/geo/contact_cylinder_split.geo");
    let text = scenes::edited(
        "geo/cylinder.toml",
        &[
            ("cylinder.geo", "contact_cylinder_split.geo"),
            ("group = \"A-A\"", "groups = [\"a\", \"symmetry_y0\"]"),
            ("lc = 0.05", "lc = 0.5"),
        ],
    );
    case.write("self.toml", &text);
    let stderr = refused(&case, "self.toml");
    eprintln!("self contact: {}", stderr.trim());
    says(&stderr, &["self.toml", "contacts[0].groups", "\"a\"", "\"symmetry_y0\"", "body \"body_1\"", "itself"]);
}

// ---------------------------------------------------------------------------
// crack memory across load steps, both rules

/// A joint without friction or cohesion but with a tensile strength of 0.3:
/// the bottom block carries the only weight (density 1, height 1, g = 1)
/// and the top block is clamped at its top face, so the joint is pressed
/// (about -0.25) when gravity points up and pulled (about +0.1) at 0.4 of
/// it pointing down. Step 1 presses: every pair slips (no shear strength),
/// so the joint cracks. Step 2 pulls below f_t: an intact joint would hold
/// it, the cracked one (f_t = 0) opens. Both rules keep the memory. With
/// the paper's rule the same pull as a scene's only step opens nothing (it
/// judges a pair cracked from the steps before; the robust rule also from
/// its slip within the step, so there the pull alone opens the joint too).
#[test]
fn a_joint_that_slipped_in_one_load_step_opens_under_a_small_pull_in_the_next_with_both_rules() {
    let case = Case::new("contact-crack-memory");
    case.copy("tests/geo/contact_stack.geo");
    let scene = |rule: &str, factors: &str| {
        format!(
            r#"title = "crack memory"
mesh = "contact_stack.geo"
analysis = "plane_stress"
gravity = [0.0, -1.0]

[gmsh]
order = 1
setnumber = {{ n = 4, quad = 1 }}

[materials.heavy]
E = 1000.0
nu = 0.25
density = 1.0

[materials.light]
E = 1000.0
nu = 0.25

[[bodies]]
group = "bottom"
material = "heavy"

[[bodies]]
group = "top"
material = "light"

[[contacts]]
group = "joint"
friction = 0.0
cohesion = 0.0
tensile_strength = 0.3

[[supports]]
group = "base"
fix = ["y"]

[[supports]]
group = "corner"
fix = ["x"]

[[supports]]
group = "top_face"
fix = ["x", "y"]

[solver]
rule = "{rule}"
load_steps = {steps}
gravity_factors = [{factors}]
"#,
            steps = factors.split(',').count()
        )
    };
    for rule in ["paper", "robust"] {
        let run =
            case.run(&case.write(&format!("memory_{rule}.toml"), &scene(rule, "-1.0, 0.4"))).expect("two load steps");
        let [first, second] = [&run.steps[0], &run.steps[1]].map(|s| s.contact.as_ref().expect("contact"));
        assert!(first.summary.converged && second.summary.converged, "{rule}: both steps converge");
        assert!(first.pairs.iter().all(|p| p.sigma_n < -0.1), "{rule}: step 1 presses the joint");
        assert!(
            first.states.iter().all(|&s| s == ContactState::Slip),
            "{rule}: step 1 slips everywhere: {:?}",
            first.states
        );
        assert!(
            second.states.iter().all(|&s| s == ContactState::Open),
            "{rule}: step 2 opens the cracked joint: {:?}",
            second.states
        );
        eprintln!("crack memory, {rule}: step 1 {} slip, step 2 {} open", first.states.len(), second.states.len());
        if rule != "paper" {
            continue;
        }
        let once = case.run(&case.write(&format!("fresh_{rule}.toml"), &scene(rule, "0.4"))).expect("one load step");
        let c = once.contact().expect("contact");
        assert!(
            c.summary.converged && c.states.iter().all(|&s| s != ContactState::Open),
            "{rule}: the intact joint holds the pull: {:?}",
            c.states
        );
        let pull = c.pairs.iter().map(|p| p.sigma_n).fold(f64::INFINITY, f64::min);
        assert!(
            pull > 0.0 && c.pairs.iter().all(|p| p.sigma_n < 0.3),
            "{rule}: a pull below f_t everywhere (smallest {pull})"
        );
        eprintln!("the pull alone, {rule}: sigma_n from {pull:.3}, nothing opens");
    }
}
