//! Lined circular tunnel against Einstein & Schwartz (1979).
//!
//! Reference: H. H. Einstein, C. W. Schwartz, "Simplified analysis for
//! tunnel supports", J. Geotech. Eng. Div. ASCE 105 (GT4), 1979, 499–518:
//! thrust and moment of a circular lining in elastic ground under excavation
//! loading, lining and ground bonded (no slip) or sliding (full slip); the
//! formulas are in `src/analytic/tunnel.rs`, which re-derives them.
//!
//! Goal: the substructure method with the lining and the rock as two bodies
//! in contact reproduces the closed form's thrust and moment within 3 % of
//! their largest values, for both interface conditions, on the shipped
//! scenes `geo/tunnel.toml` (no slip) and `geo/tunnel_slip.toml` (full
//! slip); the in-situ sigma_zz does not matter in plane; and the far
//! boundary at 10 R is too close for the moment (why the scenes use 40 R).
//!
//! ```text
//!    y  far_y: pressure P             quarter model, plane strain
//!    +----------------------+         rock: in-situ [-K P, -P, szz, 0],
//!    |                      |               E = 48, nu = 0.34
//!    |        rock          | far_x:  lining: stress-free at first,
//!    |.                     | K P             E_l = 25000, nu_l = 0.15,
//!    |  .  lining r = R -+ t/2                R = 5 (middle), t = 0.125
//!    +---+------------------+-- x     interface: contact (stick | slip)
//! ```
//!
//! Parameters (m, MPa): P = 0.6, K = 0.5, rock to |x|, |y| <= 200 (40 R);
//! quad9, lc = 0.1 at the lining, 4 elements through its thickness.

mod common;

use common::measure::max_abs;
use common::{read, repo_text, Case};
use subcontact::analytic::lining::{self, Comparison};
use subcontact::analytic::TunnelSlip;
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;
use subcontact::scene::{Analytic, Scene};

/// Copies the shipped scene `name` (and tunnel.geo) into the case as `out`,
/// edited by `edit`.
fn scene(case: &Case, name: &str, out: &str, edit: impl Fn(String) -> String) -> std::path::PathBuf {
    case.copy("geo/tunnel.geo");
    let text = repo_text(&format!("geo/{name}.toml"));
    case.write(out, &edit(text))
}

fn compare(run: &Run) -> Comparison {
    let Some(Analytic::LinedTunnel(tu)) = &run.scene.analytic else { panic!("a lined tunnel") };
    lining::compare(tu, &run.solution()).expect("a lined-tunnel comparison")
}

/// Least-squares (c0, c2) of c0 + c2 cos 2theta through the rows.
fn modes(c: &Comparison, value: impl Fn(&lining::Row) -> f64) -> (f64, f64) {
    let (mut s11, mut s12, mut s22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for r in &c.rows {
        let c2 = (2.0 * r.theta_deg.to_radians()).cos();
        let v = value(r);
        s11 += 1.0;
        s12 += c2;
        s22 += c2 * c2;
        b1 += v;
        b2 += v * c2;
    }
    let det = s11 * s22 - s12 * s12;
    ((b1 * s22 - b2 * s12) / det, (s11 * b2 - s12 * b1) / det)
}

fn check_variant(run: &Run, state: ContactState, slip: TunnelSlip) -> Comparison {
    let contact = run.contact().expect("a contact run");
    assert!(contact.summary.converged, "contact iteration converged");
    assert!(contact.summary.iterations <= 3, "{} iterations", contact.summary.iterations);
    assert!(contact.states.iter().all(|s| *s == state), "every pair {state:?}");
    let Some(Analytic::LinedTunnel(tu)) = &run.scene.analytic else { panic!("a lined tunnel") };
    assert_eq!(tu.slip, slip);
    let c = compare(run);
    // the quarter model: 0, 7.5, ..., 90 degrees
    assert_eq!(c.rows.len(), 13, "rows at {:?}", c.rows.iter().map(|r| r.theta_deg).collect::<Vec<_>>());
    assert!(c.thrust_error < 0.03, "thrust error {:.4} of max |T| {:.4}", c.thrust_error, c.thrust_scale);
    assert!(c.moment_error < 0.03, "moment error {:.4} of max |M| {:.5}", c.moment_error, c.moment_scale);
    assert!(c.displacement_error < 0.03, "lining displacement error {:.4}", c.displacement_error);
    // the varying part of the moment against the published formula alone
    let (m0, m2) = modes(&c, |r| r.moment);
    assert!((m2 - tu.modes().2).abs() < 0.03 * c.moment_scale, "M2 {m2} vs {}", tu.modes().2);
    assert!((m0 - tu.uniform_moment()).abs() < 0.03 * c.moment_scale, "M0 {m0} vs {}", tu.uniform_moment());
    // K < 1: the springline carries more thrust and bends outward-in-tension
    let (first, last) = (c.rows.first().expect("0 deg"), c.rows.last().expect("90 deg"));
    assert!(first.thrust > last.thrust && first.moment > 0.0 && last.moment < 0.0);
    eprintln!(
        "{}: thrust error {:.2} % of {:.4}, moment error {:.2} % of {:.5} (published M2 alone {:.2} %), lining displacement {:.2} %, {} DOFs, {:.2} s",
        run.scene.name,
        100.0 * c.thrust_error,
        c.thrust_scale,
        100.0 * c.moment_error,
        c.moment_scale,
        100.0 * c.published_moment_error,
        100.0 * c.displacement_error,
        run.stats.dofs.total,
        run.stats.timings.total
    );
    c
}

#[test]
fn einstein_schwartz_no_slip() {
    let case = Case::new("tunnel-no-slip");
    let run = case.run(&scene(&case, "tunnel", "tunnel.toml", |s| s)).expect("no-slip run");
    check_variant(&run, ContactState::Stick, TunnelSlip::None);
    let report = read(&case.out("tunnel").join("report.md"));
    assert!(report.contains("## Lining: thrust and moment") && report.contains("| 90.0 |"), "{report}");
}

#[test]
fn einstein_schwartz_full_slip() {
    let case = Case::new("tunnel-full-slip");
    let run = case.run(&scene(&case, "tunnel_slip", "tunnel_slip.toml", |s| s)).expect("full-slip run");
    check_variant(&run, ContactState::Slip, TunnelSlip::Full);
    // no shear crosses the interface
    let pairs = &run.contact().expect("contact").pairs;
    let sn = max_abs(pairs.iter().map(|p| p.sigma_n));
    let tau = pairs.iter().map(|p| p.tau_t.hypot(p.tau_b)).fold(0.0, f64::max);
    assert!(sn > 0.3 && tau < 1e-9 * sn, "sigma_n {sn}, tau {tau}");
    assert!(pairs.iter().all(|p| p.sigma_n < 0.0), "the interface stays in compression");
}

#[test]
fn in_situ_szz_does_not_change_the_plane_answer() {
    let case = Case::new("tunnel-szz");
    let a = case.run(&scene(&case, "tunnel", "tunnel.toml", |s| s)).expect("szz = nu (sxx + syy)");
    let edited = scene(&case, "tunnel", "szz0.toml", |s| {
        let t = s.replace("initial_stress = [-0.3, -0.6, -0.306, 0.0]", "initial_stress = [-0.3, -0.6, 0.0, 0.0]");
        assert_ne!(t, s, "the shipped scene's initial stress");
        t
    });
    let b = case.run(&edited).expect("szz = 0");
    let scale = max_abs(a.last().u.iter().copied());
    let du = a.last().u.iter().zip(&b.last().u).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(du <= 1e-12 * scale, "displacements differ by {du}");
    for (x, y) in compare(&a).rows.iter().zip(&compare(&b).rows) {
        assert!((x.thrust - y.thrust).abs() < 1e-12 && (x.moment - y.moment).abs() < 1e-12);
    }
}

#[test]
fn far_boundary_at_10_radii_is_too_close_for_the_moment() {
    // Full slip (the lining bends as the ground ovalises), D = 10 R: loading
    // the far boundary with sigma0 . n overestimates M, holding it
    // underestimates it, each by more than the 3 % budget; at 40 R both
    // agree with the closed form (coarse mesh: lc = 0.2, 3 elements through).
    let case = Case::new("tunnel-far");
    let mesh =
        |d: f64, nr: usize| format!("setnumber = {{ lc = 0.2, nl = 3, nr = {nr}, R = 5.0, t = 0.125, D = {d:.1} }}");
    let shipped = "setnumber = { lc = 0.1, nl = 4, nr = 52, R = 5.0, t = 0.125, D = 200.0 }";
    let held = |s: String| {
        s.replace(
            "[[loads]]\ngroup = \"far_x\"\npressure = 0.3",
            "[[supports]]\ngroup = \"far_x\"\nfix = [\"x\", \"y\"]\n# pressure = 0.3",
        )
        .replace(
            "[[loads]]\ngroup = \"far_y\"\npressure = 0.6",
            "[[supports]]\ngroup = \"far_y\"\nfix = [\"x\", \"y\"]\n# pressure = 0.6",
        )
    };
    let mut m2_error = Vec::new();
    for (d, nr, hold) in [(50.0, 30, false), (50.0, 30, true), (200.0, 44, false)] {
        let path = scene(&case, "tunnel_slip", &format!("far_{d}_{hold}.toml"), |s| {
            assert!(s.contains(shipped), "the shipped mesh line");
            let s = s.replace(shipped, &mesh(d, nr));
            if hold {
                held(s)
            } else {
                s
            }
        });
        let run = case.run(&path).expect("far-boundary run");
        let c = compare(&run);
        let Some(Analytic::LinedTunnel(tu)) = &run.scene.analytic else { panic!("a lined tunnel") };
        let (_, m2) = modes(&c, |r| r.moment);
        m2_error.push((m2 - tu.modes().2) / tu.modes().2);
    }
    eprintln!(
        "M2 error: D = 10 R loaded {:+.3}, held {:+.3}; D = 40 R loaded {:+.3}",
        m2_error[0], m2_error[1], m2_error[2]
    );
    assert!(m2_error[0] > 0.04, "loaded far boundary at 10 R: {:+.3}", m2_error[0]);
    assert!(m2_error[1] < -0.02, "held far boundary at 10 R: {:+.3}", m2_error[1]);
    assert!(m2_error[2].abs() < 0.025, "loaded far boundary at 40 R: {:+.3}", m2_error[2]);
}

#[test]
fn lined_tunnel_scene_rules() {
    let case = Case::new("tunnel-rules");
    case.copy("geo/tunnel.geo");
    let base = repo_text("geo/tunnel.toml");
    let parse = |text: &str| Scene::parse(text, &case.dir.join("t.toml"));
    let ok = parse(&base).expect("the shipped scene parses");
    let Some(Analytic::LinedTunnel(tu)) = &ok.analytic else { panic!("lined tunnel") };
    assert_eq!((tu.radius, tu.thickness, tu.p, tu.k, tu.slip), (5.0, 0.125, 0.6, 0.5, TunnelSlip::None));
    assert_eq!((tu.lining.e, tu.lining.nu, tu.ground.e, tu.ground.nu, tu.szz0), (25000.0, 0.15, 48.0, 0.34, -0.306));
    let rejects = |from: &str, to: &str, words: &[&str]| {
        assert!(base.contains(from), "{from}");
        let msg = parse(&base.replace(from, to)).expect_err(to).to_string();
        for w in words {
            assert!(msg.contains(w), "`{w}` not in: {msg}");
        }
    };
    rejects("slip = \"none\"", "slip = \"partial\"", &["analytic.slip", "\"partial\"", "\"full\""]);
    rejects("lining = \"lining\"", "lining = \"tube\"", &["analytic.lining", "\"tube\"", "\"rock\""]);
    rejects("ground = \"rock\"", "ground = \"lining\"", &["analytic.ground", "another body"]);
    rejects("k = 0.5", "k = 0.4", &["bodies[1].initial_stress", "[-0.3, -0.6, -0.306, 0]", "-0.24"]);
    rejects("radius = 5.0", "radius = 5.0\na = 3.0", &["analytic.a", "lined_tunnel", "\"radius\""]);
    rejects("thickness = 0.125\np", "thickness = 12.0\np", &["analytic.thickness", "< 2 radius"]);
    rejects("analysis = \"plane_strain\"", "analysis = \"plane_stress\"", &["analytic.kind", "plane_strain"]);
    rejects(
        "material = \"concrete\"\n",
        "material = \"concrete\"\ninitial_stress = [0, 0, 0, 0]\n",
        &["bodies[0].initial_stress", "stress-free"],
    );
    rejects("p = 0.6\n", "", &["analytic.p", "missing"]);
}
