//! The factor of safety against sliding by strength reduction (issue 18),
//! through the gmsh CLI and the real binary (`subcontact safety`, or
//! `solve` on a scene with `[safety]`), against the closed forms of limit
//! equilibrium.
//!
//! References: a block on an inclined plane (any statics text); the
//! symmetric wedge of Hoek & Bray, *Rock Slope Engineering* (F = sin beta /
//! sin(xi/2) tan(phi) / tan(psi)); the 2D gravity dam's base by hand from
//! its own contact resultants, F = (c A + N tan phi) / T.
//!
//! Goal, one statement per test: (1) a block on a plane inclined at theta,
//! 2D and 3D (the slope turned in plan), slides at F = tan(phi) / tan(theta)
//! without cohesion and at (c A + W cos(theta) tan(phi)) / (W sin(theta))
//! with it, within 1 %, and with only tan(phi) reduced at W cos(theta)
//! tan(phi) / (W sin(theta) - c A); the search costs contact iterations,
//! never a factorisation; (2) the elastic wedge in a V-groove reaches the
//! rigid-block factor within 1 % on two meshes, and on its sharp crease
//! (h0 = 0); (3) the dam's search finds
//! the F of its base's resultants; (4) DESIGN.md §5's block on a 20 degree
//! slope with f = 0.3645 has F = f / tan 20; (5) a scene that fails at F = 1
//! is unsafe as given: a clean failure naming the block, with its F < 1 (the
//! same closed form); a search that reaches max_factor says so; (6) a
//! wedge with cohesion near the limit (tet10, F = 1.048) slides at Hoek &
//! Bray's factor with cohesion within 1 %, silent on residual_cohesion (the
//! load steps fail, the search says F >= 1 with peak strength) or not.
//!
//! ```text
//!   2D and 3D (tests/geo/contact_stack*.geo)    wedge (geo/wedge.geo), section
//!          g (turned by theta)                         +----+----+
//!        \ |                                            \ wedge /   xi = 90
//!         \|  +-------+ top (W)                          \     /    y along the line,
//!          v  +=joint=+ f, c                               \___/     plunging at psi
//!             +-------+ bottom, base held               crevice
//! ```
//!
//! Parameters: the top block 2 x 1 (x 1), density 1, g = 10: W = 20, joint
//! area A = 2; theta = 20 degrees; f = 0.6, c = 1 (residual cohesion = c,
//! so that slipping pairs keep it as limit equilibrium assumes). Wedge:
//! geo/wedge.toml (xi = 90, psi = 30, phi = 35: F = 1.7151). Tolerances:
//! 1 % on the closed forms as the issue states (the bracket itself is
//! 1e-3 x F wide; the measured errors are printed and are far smaller).

mod common;

use common::cli::{clean_failure, says};
use common::scenes::edited;
use common::{json, read, Case};
use serde_json::Value;

const THETA: f64 = 20.0;
const F_COEF: f64 = 0.6;
const COHESION: f64 = 1.0;
/// The top block's weight and the joint's area (2 x 1 x 1, density 1, g = 10).
const W: f64 = 20.0;
const AREA: f64 = 2.0;

/// The block of tests/geo/contact_stack*.geo on a plane inclined at theta:
/// the model stays axis-aligned and gravity is turned, along x in 2D and
/// at 30 degrees from x in plan in 3D.
fn incline(solid: bool, friction: f64, cohesion: f64, safety: &str) -> String {
    let (s, c) = THETA.to_radians().sin_cos();
    let (mesh, gmsh, gravity, analysis) = if solid {
        let (a, b) = 30f64.to_radians().sin_cos();
        (
            "contact_stack3d.geo",
            "order = 2\nsetnumber = { n = 3, nz = 2, hex = 1, serendipity = 1 }",
            format!("[{}, {}, {}]", 10.0 * s * b, -10.0 * c, 10.0 * s * a),
            "solid",
        )
    } else {
        (
            "contact_stack.geo",
            "order = 2\nsetnumber = { n = 4 }",
            format!("[{}, {}]", 10.0 * s, -10.0 * c),
            "plane_strain",
        )
    };
    let fix = if solid { "[\"x\", \"y\", \"z\"]" } else { "[\"x\", \"y\"]" };
    format!(
        "title = \"a block on a plane inclined at {THETA} degrees\"\nmesh = \"{mesh}\"\nanalysis = \"{analysis}\"\ngravity = {gravity}\n\n[gmsh]\n{gmsh}\n\n\
         [materials.rock]\nE = 1000.0\nnu = 0.25\ndensity = 1.0\n\n[[bodies]]\ngroup = \"bottom\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"top\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"joint\"\nfriction = {friction:?}\ncohesion = {cohesion:?}\nresidual_cohesion = {cohesion:?}\ntensile_strength = 0.0\n\n\
         [[supports]]\ngroup = \"base\"\nfix = {fix}\n\n{safety}"
    )
}

/// Runs `subcontact ARGS` in the case and returns its summary.json's
/// `safety`, the whole summary and stderr; the run must succeed.
fn safety_run(case: &Case, args: &[&str], out: &str) -> (Value, Value, String) {
    let mut all = args.to_vec();
    all.extend(["--out", out]);
    let o = case.cli(&all);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "subcontact {all:?} failed:\n{stderr}");
    let summary = json(&case.dir.join(out).join("summary.json"));
    (summary["safety"].clone(), summary, stderr)
}

/// F found within `tol` of `exact`, the exact value inside (or within the
/// tolerance of) the bracket.
fn assert_factor(what: &str, safety: &Value, exact: f64, tol: f64) -> f64 {
    let f = safety["factor"].as_f64().expect("factor");
    let fails = safety["fails_at"].as_f64().expect("a failure found");
    eprintln!("{what}: F = {f:.5} (fails at {fails:.5}) against {exact:.5}: {:+.3} %", 100.0 * (f / exact - 1.0));
    assert!(f <= fails && fails - f <= 1.001e-3 * f + 1e-12, "{what}: bracket [{f}, {fails}] within the tolerance");
    assert!((f / exact - 1.0).abs() < tol, "{what}: F = {f} against {exact}");
    f
}

/// The search costs contact iterations on the condensed interface: the
/// parts are factorised once, whatever the trials.
fn assert_cost(what: &str, safety: &Value, summary: &Value) {
    let parts = summary["parts"]["total"].as_u64().expect("parts");
    assert_eq!(summary["counters"]["factorisations"].as_u64(), Some(parts), "{what}: one factorisation per part");
    assert_eq!(safety["cost"]["factorisations"].as_u64(), Some(0), "{what}: none in the search");
    let trials = safety["cost"]["trials"].as_u64().expect("trials");
    let its = safety["cost"]["contact_iterations"].as_u64().expect("iterations");
    assert_eq!(trials as usize, safety["trials"].as_array().map_or(0, Vec::len));
    assert!(trials >= 3 && its >= trials, "{what}: {trials} trials, {its} contact iterations");
    let steps: u64 = summary["steps"]
        .as_array()
        .expect("steps")
        .iter()
        .map(|s| s["contact"]["iterations"].as_u64().unwrap_or(0))
        .sum();
    assert_eq!(
        summary["counters"]["interface_solves"].as_u64(),
        Some(steps + its),
        "{what}: the counters count the search's iterations"
    );
    eprintln!(
        "{what}: {trials} trials, {its} contact iterations ({:.1} per trial), {:.4} s per trial",
        its as f64 / trials as f64,
        safety["cost_per_trial"]["seconds"].as_f64().unwrap_or(0.0)
    );
}

#[test]
fn a_block_on_an_inclined_plane_slides_at_the_limit_equilibrium_factor_in_2d_and_3d() {
    let case = Case::new("safety-incline");
    case.copy("tests/geo/contact_stack.geo");
    case.copy("tests/geo/contact_stack3d.geo");
    let t = THETA.to_radians();
    let (wn, wt) = (W * t.cos(), W * t.sin());
    for solid in [false, true] {
        let dim = if solid { "3D" } else { "2D" };
        // no cohesion: F = tan(phi) / tan(theta); the scene has no [safety]
        let scene = format!("incline{dim}.toml");
        case.write(&scene, &incline(solid, F_COEF, 0.0, ""));
        let (s, summary, stderr) = safety_run(&case, &["safety", &scene], &format!("out{dim}"));
        assert_factor(&format!("{dim}, c = 0"), &s, F_COEF / t.tan(), 0.01);
        assert_cost(dim, &s, &summary);
        assert_eq!(s["failure"]["kind"], "sliding", "{dim}");
        assert_eq!(s["failure"]["blocks"][0]["body"], "top", "{dim}: the top block slides");
        says(&stderr, &["safety: F = 1.1000 holds", "fails at contact iteration", "\"top\""]);
        let dir = case.dir.join(format!("out{dim}"));
        for f in [
            "safety.csv",
            "safety_contact.csv",
            "safety_deformed_displacement.png",
            "safety_interfaces.svg",
            &format!("incline{dim}_safety.vtu"),
        ] {
            assert!(dir.join(f).is_file(), "{dim}: {f} written");
        }
        if solid {
            assert!(dir.join("safety_plan_joint.png").is_file(), "3D: the joint's plan at F");
        }
        let report = read(&dir.join("report.md"));
        says(
            &report,
            &[
                "## Factor of safety",
                "none in the search",
                "(safety_deformed_displacement.png)",
                "**Mechanism: sliding.**",
            ],
        );

        // cohesion kept while slipping: (c A + W cos tan phi) / (W sin)
        let scene = format!("cohesion{dim}.toml");
        case.write(&scene, &incline(solid, F_COEF, COHESION, "[safety]\n"));
        let (s, _, quiet) = safety_run(&case, &["solve", &scene, "--quiet"], &format!("coh{dim}"));
        assert!(!quiet.contains("safety: F ="), "--quiet silences the progress: {quiet}");
        assert_factor(&format!("{dim}, c = {COHESION}"), &s, (COHESION * AREA + wn * F_COEF) / wt, 0.01);

        // only tan(phi) reduced: W cos tan(phi) / F + c A = W sin
        let scene = format!("friction{dim}.toml");
        case.write(&scene, &incline(solid, F_COEF, COHESION, "[safety]\nreduce = [\"friction\"]\n"));
        let (s, _, _) = safety_run(&case, &["solve", &scene, "--quiet"], &format!("fric{dim}"));
        assert_eq!(s["reduced"], serde_json::json!(["friction"]));
        assert_factor(&format!("{dim}, tan(phi) alone"), &s, wn * F_COEF / (wt - COHESION * AREA), 0.01);
    }
}

/// DESIGN.md §5: a block held only by friction on a 20 degree slope holds
/// at f = 0.3645 and slides at 0.2; its factor is f / tan 20 on both sides
/// of 1 (below 1 the scene is unsafe as given: a clean failure that names
/// the block and gives F, each trial the load step from its start).
#[test]
fn the_block_of_design_section_5_and_an_unsafe_one() {
    let case = Case::new("safety-design5");
    case.copy("tests/geo/contact_stack.geo");
    let tan = THETA.to_radians().tan();
    case.write("holds.toml", &incline(false, 0.3645, 0.0, "[safety]\ntolerance = 1e-4\n"));
    let (s, _, _) = safety_run(&case, &["solve", "holds.toml", "--quiet"], "holds");
    assert_factor("f = 0.3645", &s, 0.3645 / tan, 0.001);

    case.write("slides.toml", &incline(false, 0.3, 0.0, ""));
    let o = case.cli(&["safety", "slides.toml", "--out", "slides", "--quiet"]);
    let msg = failed_with_results(&o);
    says(
        &msg,
        &[
            "slides.toml: unsafe as given",
            "(F = 1)",
            "\"top\" slides along \"joint\"",
            "below 1: F = 0.",
            "the results in slides are",
            "raise the friction or cohesion",
        ],
    );
    // what exists is written: the failing step's last iterate, flagged
    // (not in equilibrium), and the mechanism
    let summary = json(&case.dir.join("slides/summary.json"));
    assert_eq!(summary["contact"]["converged"].as_bool(), Some(false), "the last iterate is not in equilibrium");
    assert_eq!(summary["safety"]["below_one"].as_bool(), Some(true));
    assert_eq!(summary["safety"]["failure"]["mechanism"]["kind"], "sliding");
    for f in ["slides.vtu", "mechanism.png", "safety.csv", "slides_safety.vtu", "report.md"] {
        assert!(case.dir.join("slides").join(f).is_file(), "{f} written");
    }
    let f: f64 = msg
        .split("below 1: F = ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|v| v.parse().ok())
        .expect("F in the message");
    eprintln!("f = 0.3: unsafe as given, F = {f} against {:.5}", 0.3 / tan);
    assert!((f / (0.3 / tan) - 1.0).abs() < 0.01, "F = {f} below 1");
}

/// geo/wedge.toml (Hoek & Bray): the elastic wedge slides at the rigid
/// block's factor on a coarse and a finer mesh. It settles into the V
/// under its weight and its joints lock shear across the line of
/// intersection; as F rises the wedge slides along the line, which turns
/// its friction along the line and releases that shear, so that at failure
/// the normal forces are the rigid block's. On the sharp crease (h0 = 0:
/// no crevice, a junction at every crease node whose stuck pairs tie shear
/// only along the crease) it does too; it ended at F = 1.472 on an
/// iteration that did not converge before the crease was treated so.
#[test]
fn the_wedge_in_a_v_groove_reaches_the_rigid_block_factor_on_two_meshes() {
    let case = Case::new("safety-wedge");
    case.copy("geo/wedge.geo");
    let (xi, phi, psi) = (90f64.to_radians(), 35f64.to_radians(), 30f64.to_radians());
    let rigid = 1.0 / (xi / 2.0).sin() * phi.tan() / psi.tan();
    for (name, set) in [("2.0", "lc = 2.0"), ("1.4", "lc = 1.4"), ("crease", "lc = 2.0, h0 = 0")] {
        let scene = format!("wedge{name}.toml");
        case.write(&scene, &edited("geo/wedge.toml", &[("lc = 1.0 }", &format!("{set} }}"))]));
        let (s, summary, _) = safety_run(&case, &["solve", &scene, "--quiet"], &format!("out{name}"));
        assert_factor(&format!("wedge, {set}"), &s, rigid, 0.01);
        assert_cost(&format!("wedge, {set}"), &s, &summary);
        assert_eq!(s["failure"]["blocks"][0]["body"], "wedge");
        // at F the joints carry the rigid block's normal force, f N / T = F
        let at_f = &s["joints"][0]["at_factor"];
        let from_resultants = at_f["factor_from_resultants"].as_f64().expect("F_joint");
        assert!((from_resultants / rigid - 1.0).abs() < 0.01, "{set}: f N / T = {from_resultants}");
        assert!(case.dir.join(format!("out{name}/safety_joints.png")).is_file(), "both faces by state");
    }
}

/// geo/dam.toml: the search against the base's own limit equilibrium by
/// hand from contact.csv at F = 1 (the base has no cohesion: F = f N / T).
#[test]
fn the_dams_base_slides_at_the_factor_of_its_resultants() {
    let case = Case::new("safety-dam");
    case.copy("geo/dam.geo");
    case.copy("geo/dam.toml");
    let (s, summary, _) = safety_run(&case, &["safety", "dam.toml", "--quiet"], "dam");
    let csv = read(&case.dir.join("dam/contact.csv"));
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("column {name}"));
    let (mut n, mut t) = (0.0, [0.0; 2]);
    for line in lines {
        let v: Vec<&str> = line.split(',').collect();
        if v[col("contact")] != "base" {
            continue;
        }
        let x = |name: &str| v[col(name)].parse::<f64>().expect("number");
        n -= x("sigma_n") * x("area");
        t[0] += x("tau_x") * x("area");
        t[1] += x("tau_y") * x("area");
    }
    let hand = 0.75 * n / t[0].hypot(t[1]);
    eprintln!("dam base: N = {n:.4} MN/m, T = {:.4} MN/m: F = f N / T = {hand:.5}", t[0].hypot(t[1]));
    assert_factor("dam", &s, hand, 0.002);
    assert_cost("dam", &s, &summary);
    let blocks: Vec<&str> =
        s["failure"]["blocks"].as_array().expect("blocks").iter().filter_map(|b| b["body"].as_str()).collect();
    assert_eq!(blocks, ["block_1", "block_2", "block_3"], "the dam slides on its base");
}

/// A search bounded below the block's factor (1.65) ends at its bound:
/// a result (exit 0, F > 1.5 on stdout), with a warning that says so.
#[test]
fn a_search_that_reaches_its_bound_says_so() {
    let case = Case::new("safety-bound");
    case.copy("tests/geo/contact_stack.geo");
    case.write("bound.toml", &incline(false, F_COEF, 0.0, "[safety]\nstep = 0.2\nmax_factor = 1.5\n"));
    let o = case.cli(&["solve", "bound.toml", "--out", "bound"]);
    let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "a bound is a result: {stderr}");
    says(&stdout, &["F > 1.5 (the search reached its bound)"]);
    says(
        &stderr,
        &[
            "safety: F = 1.2000 holds",
            "safety: F = 1.4000 holds",
            "safety: F = 1.5000 holds",
            "warning: ",
            "reached its bound safety.max_factor = 1.5",
            "Raise max_factor",
        ],
    );
    let s = json(&case.dir.join("bound/summary.json"))["safety"].clone();
    assert_eq!(
        (s["bound_reached"].as_bool(), s["factor"].as_f64(), s["fails_at"].as_f64()),
        (Some(true), Some(1.5), None)
    );
    says(&read(&case.dir.join("bound/report.md")), &["**F > 1.5**: the search reached its bound"]);
}

/// Hoek & Bray's planar slope (geo/planar_slope.toml, dry tension crack):
/// limit equilibrium keeps the plane's peak cohesion over the whole
/// sliding surface, F = (c A + W cos(psi) tan(phi)) / (W sin(psi)); the
/// scene is silent on residual_cohesion (0 by default), which the load
/// steps' crack memory takes where pairs slip. The headline is the peak
/// factor within 1 %; the residual one (tan(phi) / tan(psi) = 1 once the
/// cohesion is lost) is given beside it, labelled, with a warning that the
/// scene's silence chose the headline; `strength = "residual"` swaps them.
#[test]
fn the_planar_slope_keeps_its_peak_cohesion_as_limit_equilibrium_does() {
    let case = Case::new("safety-planar");
    case.copy("geo/planar_slope.geo");
    case.copy("geo/planar_slope.toml");
    // the block's own closed form, from the .geo's figures
    let (h, face, psi, xc, c, gamma) = (20.0f64, 60f64.to_radians(), 35f64.to_radians(), 20.0, 25.0, 2.6 * 9.81);
    let pts = [[0.0, 0.0], [xc, xc * psi.tan()], [xc, h], [h / face.tan(), h]];
    let area =
        0.5 * (0..4).map(|i| pts[i][0] * pts[(i + 1) % 4][1] - pts[(i + 1) % 4][0] * pts[i][1]).sum::<f64>().abs();
    let (w, a, phi) = (area * gamma, xc / psi.cos(), psi);
    let peak = (c * a + w * psi.cos() * phi.tan()) / (w * psi.sin());
    let residual = phi.tan() / psi.tan();
    let (s, _, stderr) = safety_run(&case, &["solve", "planar_slope.toml"], "peak");
    assert_factor("planar slope, peak", &s, peak, 0.01);
    assert_eq!((s["strength"].as_str(), s["strength_given"].as_bool()), (Some("peak"), Some(false)));
    let other = s["other"]["factor"].as_f64().expect("the residual factor beside");
    eprintln!("planar slope, residual: F = {other:.5} against tan(phi) / tan(psi) = {residual:.5}");
    assert!((other / residual - 1.0).abs() < 0.01 && s["other"]["differs"].as_bool() == Some(true));
    says(
        &stderr,
        &[
            "warning: ",
            "keeps each joint's peak strength",
            "residual_cohesion, 0 by default and not given for \"plane\"",
        ],
    );
    says(
        &read(&case.dir.join("peak/report.md")),
        &[
            "For comparison, with residual strength",
            "> **Warning:**",
            "**Mechanism: sliding.** \"block\" slides along \"plane\"",
        ],
    );
    // the scene's residual strengths as the headline, on request
    case.write("residual.toml", &edited("geo/planar_slope.toml", &[("[safety]", "[safety]\nstrength = \"residual\"")]));
    let (s, _, stderr) = safety_run(&case, &["solve", "residual.toml"], "residual");
    assert_factor("planar slope, residual", &s, residual, 0.01);
    assert!((s["other"]["factor"].as_f64().expect("peak beside") / peak - 1.0).abs() < 0.01);
    says(&stderr, &["[safety] strength = \"residual\", and \"plane\" give no residual_cohesion"]);
    says(
        &read(&case.dir.join("residual/report.md")),
        &["strength reduction, residual strength", "For comparison, with peak strength"],
    );
}

/// geo/dam.toml with a cohesive base (c = 0.1 MPa kept where pairs slip,
/// residual_cohesion = c): every trial converges, and the search finds
/// its base's own limit equilibrium over the closed (compressed) length,
/// F = (c A + N tan(phi)) / T, by hand from contact.csv at F = 1, as
/// USACE's cracked-base analysis takes it.
#[test]
fn the_dam_with_cohesion_kept_slides_at_its_bases_factor_every_trial_converged() {
    let case = Case::new("safety-dam-cohesion");
    case.copy("geo/dam.geo");
    let base = "group = \"base\"\nfriction = 0.75\ncohesion = 0.0";
    case.write(
        "dam.toml",
        &edited(
            "geo/dam.toml",
            &[(base, "group = \"base\"\nfriction = 0.75\ncohesion = 0.1\nresidual_cohesion = 0.1")],
        ),
    );
    let (s, summary, _) = safety_run(&case, &["safety", "dam.toml", "--quiet"], "dam");
    let rows = common::csv_rows(&case.dir.join("dam/contact.csv"));
    let (mut n, mut t, mut area) = (0.0, [0.0; 2], 0.0);
    for r in rows.iter().filter(|r| r["contact"] == "base" && r["status"] != "0") {
        let x = |k: &str| common::csv_num(r, k);
        n -= x("sigma_n") * x("area");
        t[0] += x("tau_x") * x("area");
        t[1] += x("tau_y") * x("area");
        area += x("area");
    }
    let hand = (0.1 * area + 0.75 * n) / t[0].hypot(t[1]);
    eprintln!("dam base with c = 0.1: closed length {area:.3} m, N = {n:.4}, F = (c A + N f) / T = {hand:.5}");
    assert_factor("dam, c kept", &s, hand, 0.005);
    assert_cost("dam, c kept", &s, &summary);
    let trials = s["trials"].as_array().expect("trials");
    assert!(trials.iter().all(|t| t["failure"] != "not_converged"), "every trial converged");
    assert_eq!(s["decided"].as_bool(), Some(true));
}

/// A trial whose contact iteration does not converge decides nothing: with
/// the paper's rule, which cycles once the stout block's heel opens (the
/// block of tests/topple.rs, b/h = 0.5 on a 20 degree plane), trials cycle
/// even when retried in smaller steps with more iterations. F is then what
/// converged trials bracket, the closed form tan(phi) / tan(theta) inside,
/// and the run ends non-zero after writing its results, saying so. Its
/// advice is the robust rule alone (more iterations do not end a cycle),
/// and taken it decides F: the closed form to the search's tolerance.
#[test]
fn a_factor_that_converged_trials_do_not_decide_is_not_reported_as_found() {
    let case = Case::new("safety-undecided");
    case.copy("tests/geo/topple.geo");
    let (s, c) = THETA.to_radians().sin_cos();
    let scene = format!(
        "title = \"cycling trials\"\nmesh = \"topple.geo\"\nanalysis = \"plane_strain\"\ngravity = [{}, {}]\n\n[gmsh]\norder = 2\nsetnumber = {{ b = 1.0, h = 2.0, n = 4 }}\n\n\
         [materials.rock]\nE = 1000.0\nnu = 0.25\ndensity = 1.0\n\n[[bodies]]\ngroup = \"base\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"joint\"\nfriction = 0.84\n\n[[supports]]\ngroup = \"base_bottom\"\nfix = [\"x\", \"y\"]\n\n[solver]\nrule = \"paper\"\n\n[safety]\n",
        10.0 * s,
        -10.0 * c
    );
    case.write("cycles.toml", &scene);
    let o = case.cli(&["solve", "cycles.toml", "--out", "cycles"]);
    let msg = failed_with_results(&o);
    says(
        &msg,
        &[
            "the factor of safety is not decided",
            "even when retried",
            "Converged trials hold at F = ",
            "F lies between them",
            "the results in cycles",
            "Solve it with [solver] rule = \"robust\" (the default)",
        ],
    );
    assert!(!msg.contains("max_iterations") && !msg.contains("safety.step"), "nothing that cannot help: {msg}");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(!stdout.contains("F = 2.3"), "no factor printed as found: {stdout}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    says(&stderr, &["did not converge", "retrying from F = ", "(retry)"]);
    let safety = json(&case.dir.join("cycles/summary.json"))["safety"].clone();
    let (h, f) = (safety["factor"].as_f64().expect("holds"), safety["fails_at"].as_f64().expect("fails"));
    let exact = 0.84 / THETA.to_radians().tan();
    eprintln!("paper rule: converged trials bracket [{h}, {f}] around {exact:.5}");
    assert!(h <= exact && exact <= f, "[{h}, {f}] brackets {exact}");
    assert_eq!((safety["decided"].as_bool(), safety["found"].as_bool()), (Some(false), Some(false)));
    let undecided = safety["undecided"].as_array().expect("undecided");
    assert!(!undecided.is_empty());
    for u in undecided {
        // (the paper's rule cycles; it does not answer to the law's residual)
        assert_eq!((&u["cycled"], &u["law_broken"]), (&Value::Bool(true), &Value::Bool(false)), "{u}");
    }
    says(&read(&case.dir.join("cycles/report.md")), &["**F not decided**"]);

    // the advice taken
    case.write("advised.toml", &scene.replacen("rule = \"paper\"", "rule = \"robust\"", 1));
    let (s, _, _) = safety_run(&case, &["solve", "advised.toml", "--quiet"], "advised");
    eprintln!("robust rule, as advised: F = {} (fails at {})", s["factor"], s["fails_at"]);
    assert_eq!((s["decided"].as_bool(), s["found"].as_bool()), (Some(true), Some(true)), "{s}");
    assert_factor("advised", &s, exact, 0.002);
}

/// The one-paragraph error of a run that ends with exit status 1 after
/// writing its results (the last line of stderr, after any progress).
fn failed_with_results(o: &std::process::Output) -> String {
    let stderr = String::from_utf8_lossy(&o.stderr).trim().to_string();
    assert_eq!(o.status.code(), Some(1), "exit status 1:\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let msg = stderr.lines().last().unwrap_or_default().to_string();
    assert!(msg.starts_with("error: "), "the error last, one paragraph:\n{stderr}");
    msg
}

/// A misspelt key of [safety] is named, as everywhere in a scene.
#[test]
fn a_misspelt_safety_key_is_named() {
    let case = Case::new("safety-misspelt");
    case.copy("tests/geo/contact_stack.geo");
    case.write("typo.toml", &incline(false, F_COEF, 0.0, "[safety]\ntolerence = 1e-3\n"));
    let o = case.cli(&["safety", "typo.toml", "--out", "typo", "--quiet"]);
    let msg = clean_failure(&case, &o, &case.dir.join("typo"));
    says(&msg, &["typo.toml", "(in safety)", "unknown field `tolerence`", "`tolerance`", "Unknown keys are errors"]);
}

/// A wedge in a V-groove (geo/wedge.geo, tet10 at lc = 2: xi = 90 degrees,
/// d = 4, crevice h0 = 0.25, L = 12, the line of intersection plunging at
/// psi = 30 degrees) on joints with cohesion, near the limit, written as a
/// user would: tan(phi) = tan 20 degrees, c = 3 kPa. Hoek & Bray's rigid
/// wedge with cohesion on both planes (beta = 90 degrees),
/// `F = (c A + W cos(psi) tan(phi) / sin(xi / 2)) / (W sin(psi))` with A
/// the two joint faces' area and W the wedge's weight: 1.0481, of which the
/// cohesion gives 0.157 (friction alone: 0.892). Silent on
/// residual_cohesion, the load steps lose the cohesion where pairs slip and
/// the scene fails as given; the search keeps the peak strength and finds
/// F >= 1, said so (not "below 1"): 1.0475 since a pair that has parted
/// closes without cohesion (1.048 before; src/contact/law.rs). With
/// residual_cohesion = c the load steps hold and the search finds the same F.
#[test]
fn a_cohesive_wedge_near_the_limit_slides_at_hoek_and_brays_factor() {
    let case = Case::new("safety-cohesive-wedge");
    case.copy("geo/wedge.geo");
    let (xi, psi, tan_phi, c) = (90f64.to_radians(), 30f64.to_radians(), 20f64.to_radians().tan(), 0.003);
    let (d, h0, l, gamma) = (4.0, 0.25, 12.0, 2.6e-3 * 9.81);
    let (b, bc) = (d * (xi / 2.0).tan(), d * (xi / 2.0).tan() * h0 / d);
    let area = 2.0 * (b - bc).hypot(d - h0) * l;
    let w = gamma * (b + bc) * (d - h0) * l;
    let exact = (c * area + w * psi.cos() * tan_phi / (xi / 2.0).sin()) / (w * psi.sin());
    let scene = |residual: &str| {
        format!(
            "title = \"a cohesive wedge near the limit\"\nmesh = \"wedge.geo\"\nanalysis = \"solid\"\n\
             gravity = [0.0, {}, {}]\n\n[gmsh]\norder = 2\n\
             setnumber = {{ lc = 2.0, xi = 90, d = {d}, h0 = {h0}, L = {l} }}\n\n\
             [materials.rock]\nE = 1.0e4\nnu = 0.25\ndensity = 2.6e-3\n\n\
             [[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n\n[[bodies]]\ngroup = \"wedge\"\nmaterial = \"rock\"\n\n\
             [[contacts]]\ngroup = \"groove\"\nfriction = {tan_phi}\ncohesion = {c}\n{residual}\n\
             [[supports]]\ngroup = \"rock_base\"\nfix = [\"x\", \"y\", \"z\"]\n\n\
             [[supports]]\ngroup = \"rock_sides\"\nfix = [\"x\"]\n\n\
             [[supports]]\ngroup = \"rock_ends\"\nfix = [\"y\"]\n\n[safety]\ntolerance = 1.0e-4\n",
            -9.81 * psi.sin(),
            -9.81 * psi.cos()
        )
    };
    // silent on residual_cohesion: unsafe as given, F >= 1 with peak strength
    case.write("silent.toml", &scene(""));
    let msg = failed_with_results(&case.cli(&["solve", "silent.toml", "--out", "silent", "--quiet"]));
    says(&msg, &["unsafe as given", "with the peak strength kept", "is F = 1.04", "residual_cohesion"]);
    assert!(!msg.contains("below 1") && !msg.contains("none was made"), "{msg}");
    let s = json(&case.dir.join("silent/summary.json"))["safety"].clone();
    assert_factor("cohesive wedge, silent", &s, exact, 0.01);
    // the cohesion kept in the load steps too: they hold, the same F
    case.write("kept.toml", &scene(&format!("residual_cohesion = {c}\n")));
    let (s, _, _) = safety_run(&case, &["solve", "kept.toml", "--quiet"], "kept");
    assert_factor("cohesive wedge, residual_cohesion = c", &s, exact, 0.01);
    assert_eq!(s["failure"]["mechanism"]["kind"], "sliding");
}
