//! Contact in 3D on the meshes gmsh makes (issue: 3D contact).
//!
//! Two blocks (geo/blocks3d.geo: OpenCASCADE boxes joined by
//! BooleanFragments, the shared face the contact "joint"), meshed as users
//! mesh: unstructured tet4 / tet10, structured hex8 / hex20 / hex27.
//!
//! 1. Contact patch test per kind: the base held, the other faces loaded by
//!    a uniform stress with shear (sigma_zz = -1, sigma_xz = 0.2,
//!    sigma_yz = -0.1, sigma_xx = sigma_yy = -1/3 of the strain field
//!    u = (2 e_xz z, 2 e_yz z, e_zz z)); every pair must stick and carry
//!    exactly that traction (to 1e-8), tri6 and quad8 faces included.
//! 2. Partial slip: the upper block pushed by (0.3, 0, -1) on its top, f =
//!    0.5: it holds as a whole but slips at the trailing edge. Every kind, two
//!    mesh sizes, plus an oblique push (0.45, 0.15, -1) that lifts a corner:
//!    the iteration converges in a bounded number of iterations that does
//!    not grow with the mesh, the Coulomb conditions hold at every pair, and
//!    the joint carries exactly the load.
//! 3. The same states and stresses when the model is turned in space.
//! 4. The contact patch test across joints of wedges (tests/geo/
//!    contact_wedges.geo: blocks extruded from a triangulated plan, as
//!    layered ground is made): two layers pressed together across their
//!    triangles (tri3, tri6 faces), and two blocks side by side across
//!    their quadrangles (quad4, quad8, quad9), prism6, prism15, prism18;
//!    and the upper layer's self-weight on the lower one (sides on
//!    rollers): sigma_n = -rho g h at every pair, and the joint carries
//!    the weight to round-off.
//! 5. The same patch test across a face of pyramids (tests/geo/
//!    contact_pyramids.geo: hexahedra above, tetrahedra below, pyramids
//!    between them on the joint), pyramid5, pyramid13, pyramid14.
//! 6. A wedge in a groove held by friction alone along the groove while
//!    every pair slips down its face (tests/geo/wedge_groove.geo).

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::driver::ContactError;
use subcontact::results::{ContactRun, Run};
use subcontact::scene::StateRule;

/// Element kinds: (name, gmsh order, hex, serendipity).
const KINDS: [(&str, usize, usize, usize); 5] =
    [("tet4", 1, 0, 0), ("tet10", 2, 0, 0), ("hex8", 1, 1, 0), ("hex20", 2, 1, 1), ("hex27", 2, 1, 0)];

/// A blocks3d scene: E = 1000, nu = 0.25, the joint with friction 0.5 and
/// no cohesion or tensile strength, the base held, and `loads` (TOML).
fn scene(kind: (&str, usize, usize, usize), lc: f64, mesh: &str, loads: &str) -> String {
    let (_, order, hex, ser) = kind;
    let gmsh = if mesh.ends_with(".geo") {
        format!("[gmsh]\norder = {order}\nsetnumber = {{ lc = {lc}, hex = {hex}, serendipity = {ser} }}")
    } else {
        String::new()
    };
    format!(
        r#"title = "blocks"
mesh = "{mesh}"
analysis = "solid"

{gmsh}

[materials.m]
E = 1000.0
nu = 0.25

[[bodies]]
group = "lower"
material = "m"

[[bodies]]
group = "upper"
material = "m"

[[contacts]]
group = "joint"
friction = 0.5
cohesion = 0.0
tensile_strength = 0.0

[[supports]]
group = "base"
fix = ["x", "y", "z"]

{loads}
"#
    )
}

fn traction(group: &str, t: [f64; 3]) -> String {
    format!("[[loads]]\ngroup = \"{group}\"\ntraction = [{:?}, {:?}, {:?}]\n\n", t[0], t[1], t[2])
}

/// The uniform stress of the contact patch tests (sigma_xx, sigma_zz,
/// sigma_xz, sigma_yz; sigma_yy = sigma_xx, sigma_xy = 0).
const PATCH: (f64, f64, f64, f64) = (-1.0 / 3.0, -1.0, 0.2, -0.1);

/// The tractions of [`PATCH`] on the faces of a box (top, x0, x1, y0, y1;
/// the base held).
fn patch_loads() -> String {
    let (sxx, szz, sxz, syz) = PATCH;
    [
        traction("top", [sxz, syz, szz]),
        traction("x1", [sxx, 0.0, sxz]),
        traction("x0", [-sxx, 0.0, -sxz]),
        traction("y1", [0.0, sxx, syz]),
        traction("y0", [0.0, -sxx, -syz]),
    ]
    .concat()
}

fn solve(case: &Case, name: &str, text: &str) -> Run {
    case.run(&case.write(&format!("{name}.toml"), text)).unwrap_or_else(|e| panic!("{name}: {e:#}"))
}

fn contact(run: &Run) -> &ContactRun {
    run.contact().expect("a contact run")
}

#[test]
fn uniform_stress_with_shear_crosses_the_joint_exactly_on_every_3d_kind() {
    let case = Case::new("contact3d-patch");
    case.copy("geo/blocks3d.geo");
    let (_, szz, sxz, syz) = PATCH;
    let loads = patch_loads();
    for kind in KINDS {
        let name = kind.0;
        let run = solve(&case, name, &scene(kind, 0.5, "blocks3d.geo", &loads));
        let c = contact(&run);
        let face = run.model.interfaces[0].facets[0].kind.name();
        let mut worst: f64 = 0.0;
        for p in 0..c.states.len() {
            assert_eq!(c.states[p], ContactState::Stick, "{name}: pair {p} sticks");
            let (r, t) = (&c.pairs[p], c.shear(p));
            // body I is the lower block: n = +z, the traction on it is (sxz, syz, szz)
            worst = worst.max((r.sigma_n - szz).abs()).max((t[0] - sxz).abs()).max((t[1] - syz).abs()).max(t[2].abs());
        }
        eprintln!(
            "{name} ({face} faces): {} pairs, {} iteration(s), max traction error {worst:.1e}",
            c.states.len(),
            c.summary.iterations
        );
        assert!(worst < 1e-8, "{name}: the uniform traction crosses the joint exactly ({worst:.2e})");
        assert_eq!(c.summary.iterations, 1, "{name}: stuck from the start");
    }
}

/// The Coulomb conditions at every pair of a converged run (no cohesion, no
/// tensile strength, friction f), and the joint's resultant against the
/// load `total` on the upper block. Returns (pairs stick, slip, open).
fn check_coulomb(name: &str, c: &ContactRun, f: f64, total: [f64; 3]) -> [usize; 3] {
    assert!(c.summary.converged, "{name}: converged");
    let scale = c.pairs.iter().map(|r| r.sigma_n.abs()).fold(0.0, f64::max);
    let tol = 1e-8 * scale;
    let mut n = [0; 3];
    let mut resultant = [0.0; 3];
    for (p, r) in c.pairs.iter().enumerate() {
        match c.states[p] {
            ContactState::Open => {
                assert!(
                    r.sigma_n.abs() < tol && r.tau() < tol,
                    "{name}: open pair {p} carries nothing ({} {})",
                    r.sigma_n,
                    r.tau()
                );
                assert!(r.gap > -tol, "{name}: open pair {p} does not interpenetrate ({})", r.gap);
            }
            ContactState::Slip => {
                assert!(r.sigma_n <= tol, "{name}: slipping pair {p} is not in tension ({})", r.sigma_n);
                assert!(
                    (r.tau() - f * r.sigma_n.abs()).abs() < tol,
                    "{name}: slipping pair {p}: |tau| {} = f |sigma_n| {}",
                    r.tau(),
                    f * r.sigma_n.abs()
                );
            }
            ContactState::Stick => {
                assert!(r.sigma_n <= tol, "{name}: stuck pair {p} is not in tension ({})", r.sigma_n);
                assert!(
                    r.tau() <= f * r.sigma_n.abs() + tol,
                    "{name}: stuck pair {p}: |tau| {} <= f |sigma_n| {}",
                    r.tau(),
                    f * r.sigma_n.abs()
                );
            }
        }
        n[c.states[p].code() as usize] += 1;
        let fp = c.force(p);
        for i in 0..3 {
            resultant[i] += fp[i];
        }
    }
    // the lower block (body I) carries what the upper one is loaded with
    let e = (0..3).map(|i| (resultant[i] - total[i]).abs()).fold(0.0, f64::max);
    assert!(e < 1e-9, "{name}: the joint carries the load: {resultant:?} against {total:?} ({e:.1e})");
    n
}

#[test]
fn partial_slip_converges_in_a_bounded_number_of_iterations_on_every_kind_and_mesh() {
    let case = Case::new("contact3d-slip");
    case.copy("geo/blocks3d.geo");
    let push = [0.3, 0.0, -1.0];
    let mut rows = Vec::new();
    for kind in KINDS {
        let mut its = Vec::new();
        for lc in [0.25, 0.125] {
            let name = format!("{}_lc{lc}", kind.0);
            let run = solve(&case, &name, &scene(kind, lc, "blocks3d.geo", &traction("top", push)));
            let c = contact(&run);
            let [open, slip, stick] = check_coulomb(&name, c, 0.5, push);
            assert!(slip > 0 && stick > 0, "{name}: partial slip ({stick} stick, {slip} slip)");
            assert!(
                open * 20 < c.states.len(),
                "{name}: the joint stays closed but at the trailing corner ({open} open)"
            );
            rows.push(format!(
                "{name}: {} pairs, {stick} stick / {slip} slip / {open} open, {} iterations",
                c.states.len(),
                c.summary.iterations
            ));
            its.push(c.summary.iterations);
        }
        assert!(its.iter().all(|&k| k <= 15), "{}: bounded iterations {its:?}", kind.0);
        assert!(its[1] <= its[0] + 4, "{}: the count does not grow with the mesh {its:?}", kind.0);
    }
    eprintln!("{}", rows.join("\n"));
}

#[test]
fn an_oblique_push_that_lifts_a_corner_converges_with_slip_in_its_direction() {
    let case = Case::new("contact3d-oblique");
    case.copy("geo/blocks3d.geo");
    let push = [0.45, 0.15, -1.0];
    for (kind, lc) in [(KINDS[3], 0.125), (KINDS[1], 0.125)] {
        let name = format!("{}_oblique", kind.0);
        let run = solve(&case, &name, &scene(kind, lc, "blocks3d.geo", &traction("top", push)));
        let c = contact(&run);
        let [open, slip, stick] = check_coulomb(&name, c, 0.5, push);
        eprintln!(
            "{name}: {} pairs, {stick} stick / {slip} slip / {open} open, {} iterations",
            c.states.len(),
            c.summary.iterations
        );
        assert!(open > 0 && slip > 0 && stick > 0, "{name}: a lifted corner, slip and stick");
        assert!(c.summary.iterations <= 15, "{name}: {} iterations", c.summary.iterations);
        // the trailing corner (x = 0, y = 0) lifts
        let corner = (0..c.states.len()).find(|&p| {
            let x = run.model.coords[run.model.pairs[p].k];
            x[0].abs() < 1e-9 && x[1].abs() < 1e-9
        });
        assert_eq!(
            c.states[corner.expect("a pair at the corner")],
            ContactState::Open,
            "{name}: the trailing corner lifts"
        );
        // the friction on the lower block points along the push
        for p in (0..c.states.len()).filter(|&p| c.states[p] == ContactState::Slip) {
            let t = c.shear(p);
            let cos = (t[0] * push[0] + t[1] * push[1]) / (t[0].hypot(t[1]) * push[0].hypot(push[1]));
            assert!(cos > 0.5, "{name}: pair {p} is dragged along the push ({t:?})");
        }
    }
}

/// `R x` for the rotation by `angle` about the unit `axis` (Rodrigues).
fn rotate(axis: [f64; 3], angle: f64, x: [f64; 3]) -> [f64; 3] {
    let (s, c) = angle.sin_cos();
    let d = axis[0] * x[0] + axis[1] * x[1] + axis[2] * x[2];
    let k = [axis[1] * x[2] - axis[2] * x[1], axis[2] * x[0] - axis[0] * x[2], axis[0] * x[1] - axis[1] * x[0]];
    std::array::from_fn(|i| x[i] * c + k[i] * s + axis[i] * d * (1.0 - c))
}

/// An ASCII MSH 4.1 file with every node moved by `f` (the `$Nodes`
/// section: a header, then blocks of `dim tag parametric n`, n tags, n
/// coordinate lines).
fn turn_msh(text: &str, f: impl Fn([f64; 3]) -> [f64; 3]) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    let mut i = 0;
    while i < lines.len() {
        out.push(lines[i].to_string());
        if lines[i].starts_with("$Nodes") {
            let head: Vec<usize> = lines[i + 1].split_whitespace().map(|w| w.parse().expect("node header")).collect();
            out.push(lines[i + 1].to_string());
            i += 2;
            for _ in 0..head[0] {
                let block: Vec<usize> = lines[i].split_whitespace().map(|w| w.parse().expect("block header")).collect();
                assert_eq!(block[2], 0, "no parametric coordinates");
                let n = block[3];
                out.extend(lines[i..=i + n].iter().map(|l| l.to_string()));
                for l in &lines[i + 1 + n..i + 1 + 2 * n] {
                    let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().expect("coordinate")).collect();
                    let r = f([v[0], v[1], v[2]]);
                    out.push(format!("{:.17e} {:.17e} {:.17e}", r[0], r[1], r[2]));
                }
                i += 1 + 2 * n;
            }
            continue;
        }
        i += 1;
    }
    out.join("\n") + "\n"
}

#[test]
fn turning_the_model_in_space_changes_neither_states_nor_stresses() {
    let case = Case::new("contact3d-rotated");
    case.copy("geo/blocks3d.geo");
    let kind = KINDS[1];
    let push = [0.3, 0.0, -1.0];
    // mesh once; the turned model has the same mesh with turned nodes
    common::cli::gmsh(
        &case,
        &["-3", "-order", "2", "-setnumber", "lc", "0.2", "-setnumber", "hex", "0", "blocks3d.geo", "-o", "blocks.msh"],
    );
    let n = 14f64.sqrt();
    let (axis, angle) = ([1.0 / n, 2.0 / n, 3.0 / n], 0.7);
    let text = common::read(&case.dir.join("blocks.msh"));
    case.write("turned.msh", &turn_msh(&text, |x| rotate(axis, angle, x)));
    let a = solve(&case, "straight", &scene(kind, 0.2, "blocks.msh", &traction("top", push)));
    let b = solve(&case, "turned", &scene(kind, 0.2, "turned.msh", &traction("top", rotate(axis, angle, push))));
    let (ca, cb) = (contact(&a), contact(&b));
    assert_eq!(ca.states.len(), cb.states.len());
    let scale = ca.pairs.iter().map(|r| r.sigma_n.abs()).fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for p in 0..ca.states.len() {
        let xa = rotate(axis, angle, a.model.coords[a.model.pairs[p].k]);
        let q = (0..cb.states.len())
            .find(|&q| {
                let xb = b.model.coords[b.model.pairs[q].k];
                (0..3).all(|i| (xa[i] - xb[i]).abs() < 1e-9)
            })
            .expect("the same pair in the turned model");
        assert_eq!(ca.states[p], cb.states[q], "pair at {:?}", a.model.coords[a.model.pairs[p].k]);
        let (ra, rb) = (&ca.pairs[p], &cb.pairs[q]);
        let ta = rotate(axis, angle, ca.shear(p));
        let tb = cb.shear(q);
        worst =
            worst.max((ra.sigma_n - rb.sigma_n).abs()).max((0..3).map(|i| (ta[i] - tb[i]).abs()).fold(0.0, f64::max));
    }
    eprintln!("turned model: {} pairs, states equal, max stress difference {:.1e} of {scale}", ca.states.len(), worst);
    assert!(worst < 1e-8 * scale, "stresses agree when turned ({worst:.2e})");
}

/// f_t above the Coulomb apex c / f: a joint in tension above c / f has no
/// shear strength left. `check` and `solve` warn; pulled between c / f and
/// f_t, the joint opens (the block, held by nothing else, is reported as
/// held by nothing, not as sliding under a shear it does not carry);
/// pulled below c / f it holds in tension.
#[test]
fn a_tensile_strength_above_the_coulomb_apex_is_reported_and_the_joint_opens_above_it() {
    let case = Case::new("contact3d-apex");
    case.copy("geo/blocks3d.geo");
    let joint = (
        "friction = 0.5\ncohesion = 0.0\ntensile_strength = 0.0",
        "friction = 0.5\ncohesion = 0.25\ntensile_strength = 2.0",
    );
    let pulled =
        |t: f64| scene(KINDS[2], 0.5, "blocks3d.geo", &traction("top", [0.0, 0.0, t])).replacen(joint.0, joint.1, 1);
    case.write("above.toml", &pulled(1.0));
    case.write("below.toml", &pulled(0.4));
    let out = case.cli(&["check", "above.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "check passes: {err}");
    for want in [
        "warning:",
        "contacts[0] (\"joint\")",
        "tensile_strength = 2",
        "Coulomb apex c / f = 0.25 / 0.5 = 0.5:",
        "open there",
    ] {
        assert!(err.contains(want), "check warns with {want:?}: {err}");
    }
    let out = case.cli(&["solve", "above.toml", "--out", "above", "--quiet"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the pulled block comes off: {err}");
    assert!(err.starts_with("error:") && err.contains("held by nothing") && err.contains("opened"), "{err}");
    assert!(err.contains("contacts[0] opens at c / f = 0.5"), "the message says where the apex let go: {err}");
    assert!(!err.contains("friction and cohesion"), "no talk of a shear load that is not there: {err}");
    let run = case.run(&case.dir.join("below.toml")).expect("below the apex it holds");
    let c = contact(&run);
    assert!(c.states.iter().all(|&s| s == ContactState::Stick), "below c / f every pair sticks");
    let mean = c.pairs.iter().zip(&c.areas).map(|(r, a)| r.sigma_n * a).sum::<f64>();
    assert!((mean - 0.4).abs() < 1e-9, "the joint carries the pull in tension ({mean})");
    let summary = common::json(&case.out("below").join("summary.json"));
    assert_eq!(summary["warnings"].as_array().map(|a| a.len()), Some(1), "summary.json lists the warning");
}

/// The contact patch test across joints of wedges: the base held, the
/// other faces loaded by the uniform stress of test 1 (sigma_zz = -1,
/// sigma_xz = 0.2, sigma_yz = -0.1, sigma_xx = sigma_yy = -1/3); friction
/// 0.8, so that the vertical joint (sigma_n = -1/3, tau = 0.2) sticks too.
/// Every pair sticks and carries the traction sigma n exactly.
#[test]
fn uniform_stress_crosses_joints_of_wedges_exactly() {
    let case = Case::new("contact3d-wedges");
    case.copy("tests/geo/contact_wedges.geo");
    let (sxx, szz, sxz, syz) = PATCH;
    let sigma = [[sxx, 0.0, sxz], [0.0, sxx, syz], [sxz, syz, szz]];
    let loads = patch_loads();
    for stacked in [1, 0] {
        for (name, order, ser) in [("prism6", 1, 0), ("prism18", 2, 0), ("prism15", 2, 1)] {
            let text = scene((name, order, 0, ser), 0.4, "contact_wedges.geo", &loads)
                .replace("friction = 0.5", "friction = 0.8")
                .replace(", hex = 0,", &format!(", stacked = {stacked},"));
            let name = format!("{name}-{}", if stacked == 1 { "stacked" } else { "side-by-side" });
            let run = solve(&case, &name, &text);
            assert!(
                run.model
                    .bodies
                    .iter()
                    .flat_map(|b| &b.cells)
                    .all(|c| c.kind.name() == name.split('-').next().unwrap()),
                "{name}: wedges only"
            );
            let c = contact(&run);
            let face = run.model.interfaces[0].facets[0].kind.name();
            let mut worst: f64 = 0.0;
            let mut on_base = 0;
            for p in 0..c.states.len() {
                // the vertical joint ends on the held base: there both sides
                // are held in every direction, the supports carry the force
                // and the pair reports none
                if run.model.coords[run.model.pairs[p].k][2] == 0.0 {
                    on_base += 1;
                    assert!(c.pairs[p].sigma_n == 0.0 && stacked == 0, "{name}: pair {p} on the base");
                    continue;
                }
                assert_eq!(c.states[p], ContactState::Stick, "{name}: pair {p} sticks");
                // body I is the lower (left) block: sigma n is the traction on it
                let n = c.frames[p][0];
                let t: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| sigma[i][j] * n[j]).sum());
                let sn: f64 = (0..3).map(|i| t[i] * n[i]).sum();
                let shear = c.shear(p);
                worst = worst.max((c.pairs[p].sigma_n - sn).abs());
                for i in 0..3 {
                    worst = worst.max((shear[i] - (t[i] - sn * n[i])).abs());
                }
            }
            eprintln!("{name} ({face} faces): {} pairs ({on_base} on the base), {} iteration(s), max traction error {worst:.1e}", c.states.len(), c.summary.iterations);
            assert!(worst < 1e-8, "{name}: the uniform traction crosses the joint exactly ({worst:.2e})");
            // stuck from the start, the base's pairs too: held on both
            // sides in every direction, they stay shut (they were judged
            // open on their zero force, one iteration more)
            assert_eq!(c.summary.iterations, 1, "{name}: iterations");
            assert!(
                (0..c.states.len()).all(|p| c.states[p] == ContactState::Stick),
                "{name}: every pair sticks, the base's too"
            );
        }
    }
}

/// The contact patch test across a face of pyramids (issue 19: contact on
/// the pyramids' quadrangles): tests/geo/contact_pyramids.geo, hexahedra
/// above the joint and tetrahedra below, which gmsh joins to the joint's
/// quadrangles by pyramids. The uniform stress of test 1; every pair sticks
/// and carries sigma n exactly, pyramid5, pyramid13 and pyramid14.
#[test]
fn uniform_stress_crosses_a_joint_onto_pyramids_exactly() {
    let case = Case::new("contact3d-pyramids");
    case.copy("tests/geo/contact_pyramids.geo");
    let (_, szz, sxz, syz) = PATCH;
    let loads = patch_loads();
    for (name, order, ser) in [("pyramid5", 1, 0), ("pyramid14", 2, 0), ("pyramid13", 2, 1)] {
        // (contact_pyramids.geo has no `hex` parameter: it is always hexahedra above)
        let text = scene((name, order, 0, ser), 0.3, "contact_pyramids.geo", &loads)
            .replace(", hex = 0,", ",")
            .replace("friction = 0.5", "friction = 0.8");
        let run = solve(&case, name, &text);
        let c = contact(&run);
        // the lower block's cells on the joint are pyramids of this kind
        let joint: std::collections::HashSet<usize> = run.model.pairs.iter().map(|p| p.k).collect();
        let on_joint: Vec<&str> = (run.model.bodies[0].cells.iter())
            .filter(|cell| cell.nodes.iter().filter(|n| joint.contains(n)).count() >= 4)
            .map(|cell| cell.kind.name())
            .collect();
        assert!(
            !on_joint.is_empty() && on_joint.iter().all(|k| *k == name),
            "{name}: the joint's lower side is pyramids: {on_joint:?}"
        );
        let mut worst: f64 = 0.0;
        for p in 0..c.states.len() {
            assert_eq!(c.states[p], ContactState::Stick, "{name}: pair {p} sticks");
            let (r, t) = (&c.pairs[p], c.shear(p));
            worst = worst.max((r.sigma_n - szz).abs()).max((t[0] - sxz).abs()).max((t[1] - syz).abs()).max(t[2].abs());
        }
        eprintln!(
            "{name}: {} pairs, {} cells on the joint, max traction error {worst:.1e}",
            c.states.len(),
            on_joint.len()
        );
        assert!(worst < 1e-8, "{name}: the uniform traction crosses the joint exactly ({worst:.2e})");
    }
}

/// Self-weight across a joint of wedges: the layers of contact_wedges.geo
/// (stacked) on rollers (x0, x1 held in x, y0, y1 in y, the base in z),
/// gravity down; the joint carries the upper layer's weight. The stress is
/// -rho g (2h - z) vertically (the lateral ones K0 times it), linear in z:
/// prism15 and prism18 represent it; prism6 does not (its stress is
/// constant through each cell), but the upper layer's own equilibrium gives
/// the joint the consistent weight of each column, uniform over the plan.
/// Every pair's sigma_n is -rho g h to round-off (measured 4e-16 to 3e-15).
#[test]
fn self_weight_crosses_a_joint_of_wedges_exactly() {
    let case = Case::new("contact3d-wedges-weight");
    case.copy("tests/geo/contact_wedges.geo");
    let (rho, g, h, area) = (2.0e-2, 9.81, 0.6, 1.0 * 0.8);
    let supports = "[[supports]]\ngroup = \"x0\"\nfix = [\"x\"]\n\n[[supports]]\ngroup = \"x1\"\nfix = [\"x\"]\n\n\
                    [[supports]]\ngroup = \"y0\"\nfix = [\"y\"]\n\n[[supports]]\ngroup = \"y1\"\nfix = [\"y\"]\n";
    for (name, order, ser) in [("prism6", 1, 0), ("prism18", 2, 0), ("prism15", 2, 1)] {
        let text = scene((name, order, 0, ser), 0.4, "contact_wedges.geo", supports)
            .replace(", hex = 0,", ", stacked = 1,")
            .replace("fix = [\"x\", \"y\", \"z\"]", "fix = [\"z\"]")
            .replace("analysis = \"solid\"\n", &format!("analysis = \"solid\"\ngravity = [0.0, 0.0, {:?}]\n", -g))
            .replace("nu = 0.25\n", &format!("nu = 0.25\ndensity = {rho:?}\n"));
        let run = solve(&case, &format!("{name}-weight"), &text);
        let c = contact(&run);
        let want = -rho * g * h;
        let (mut worst, mut weight) = (0.0f64, 0.0);
        for p in 0..c.states.len() {
            assert_eq!(c.states[p], ContactState::Stick, "{name}: pair {p} sticks");
            worst =
                worst.max((c.pairs[p].sigma_n - want).abs()).max(c.shear(p).iter().fold(0.0f64, |m, t| m.max(t.abs())));
            weight += c.force(p)[2];
        }
        // the lower layer is body I (n = +z): the joint pushes it down by the weight
        let upper = rho * g * h * area;
        eprintln!("{name}: {} pairs, sigma_n within {worst:.1e} of -rho g h = {want}, joint force {weight:.12} against the weight {upper:.12}", c.states.len());
        assert!((weight + upper).abs() < 1e-10 * upper, "{name}: the joint carries the weight ({weight} vs {upper})");
        assert!(worst < 1e-8 * want.abs(), "{name}: sigma_n = -rho g h at every pair ({worst:.2e})");
    }
}

/// A wedge held across its slip by friction alone (issue 19 item 4: a wedge
/// in a groove): tests/geo/wedge_groove.geo, the wedge's two faces sloping
/// 45 degrees against the rock and nothing under it, its self-weight W =
/// rho g V (V = 0.84 x 2) on them, friction 0.3 below tan 45: every pair
/// slips down its face, and only friction holds the wedge along the groove,
/// where no load pushes it. The robust rule linearises the Coulomb law with
/// a stiffness across the slip, so the wedge is held: the faces carry W
/// exactly, and every pair |tau| = f |sigma_n|. It was refused at the
/// second iteration as a loss of equilibrium, "the load along the contact
/// exceeds what friction and cohesion can carry", with no load along the
/// groove at all. Frictionless, nothing holds the wedge along the groove,
/// and it is refused as that.
#[test]
fn a_wedge_slipping_down_its_groove_is_held_along_it_by_friction() {
    let case = Case::new("contact3d-wedge-groove");
    case.copy("tests/geo/wedge_groove.geo");
    let text = |f: f64| {
        format!(
            "title = \"a wedge in a groove\"\nmesh = \"wedge_groove.geo\"\nanalysis = \"solid\"\ngravity = [0.0, 0.0, -10.0]\n[gmsh]\norder = 1\nsetnumber = {{ lc = 0.3 }}\n\
             [materials.rock]\nE = 1.0e4\nnu = 0.25\ndensity = 2.5\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[bodies]]\ngroup = \"wedge\"\nmaterial = \"rock\"\n\
             [[contacts]]\ngroup = \"faces\"\nfriction = {f:?}\n[[supports]]\ngroup = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]\n"
        )
    };
    let run = solve(&case, "held", &text(0.3));
    let c = contact(&run);
    assert!(
        c.summary.converged && c.states.iter().all(|&s| s == ContactState::Slip),
        "every pair slips: {:?}",
        c.states
    );
    // the force on the rock (body I) is the wedge's weight
    let w = 2.5 * 10.0 * 0.84 * 2.0;
    let total: [f64; 3] = std::array::from_fn(|i| (0..c.states.len()).map(|p| c.force(p)[i]).sum());
    let coulomb = (0..c.states.len())
        .map(|p| (c.pairs[p].tau() - 0.3 * c.pairs[p].sigma_n.abs()).abs() / c.pairs[p].sigma_n.abs())
        .fold(0.0, f64::max);
    eprintln!("wedge in a groove: {} pairs slip in {} iterations; force on the rock {total:?} (W = {w}); Coulomb residual {coulomb:.1e}", c.states.len(), c.summary.iterations);
    assert!(
        total[0].abs() < 1e-9 * w && total[1].abs() < 1e-9 * w && (total[2] + w).abs() < 1e-9 * w,
        "the faces carry the weight: {total:?}"
    );
    assert!(coulomb < 1e-9, "every pair at the Coulomb limit ({coulomb:.1e})");
    // the paper's rule gives a slipping pair a fixed shear: nothing holds
    // the wedge along the groove, and the message says that rule is why
    case.write("paper.toml", &format!("{}[solver]\nrule = \"paper\"\n", text(0.3)));
    match case.contact_error(&case.dir.join("paper.toml")) {
        ContactError::Sliding { bodies, no_shear, rule, .. } => {
            assert!(bodies == ["wedge"] && !no_shear && rule == StateRule::Paper, "{bodies:?} {no_shear} {rule:?}")
        }
        other => panic!("the paper's rule lets the wedge slide, not {other:?}"),
    }
    let out = case.cli(&["solve", "paper.toml", "--quiet"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the paper's rule, which gives a slipping pair a fixed shear")
            && err.contains("rule = \"robust\""),
        "{err}"
    );
    case.write("frictionless.toml", &text(0.0));
    match case.contact_error(&case.dir.join("frictionless.toml")) {
        ContactError::Sliding { bodies, no_shear, .. } => {
            assert!(bodies == ["wedge"] && no_shear, "{bodies:?} {no_shear}")
        }
        other => panic!("frictionless, the wedge slides along the groove, not {other:?}"),
    }
}
