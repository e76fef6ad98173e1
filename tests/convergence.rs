//! The contact iteration on the scenes engineers build (issue 28): a load
//! step that does not converge is cut and converges to the uncut answer;
//! one that still does not converge says where its states kept changing,
//! in a report that stays readable; and (make stress) a 3D tunnel through
//! three oblique joint sets on tet10 converges to states that keep the law,
//! meshed as given and coarser away from the opening.

mod common;

use common::{csv_num, csv_rows, json, read, Case};
use serde_json::Value;

/// The dam of geo/dam.toml with a base of cohesion 0.1 kept once it slips,
/// every load applied in one step, `solver` the `[solver]` table's keys.
/// Solved whole, it takes 9 iterations.
fn dam(case: &Case, name: &str, solver: &str) {
    case.copy("geo/dam.geo");
    let text = common::scenes::edited(
        "geo/dam.toml",
        &[
            (
                "group = \"base\"\nfriction = 0.75\ncohesion = 0.0",
                "group = \"base\"\nfriction = 0.75\ncohesion = 0.1\nresidual_cohesion = 0.1",
            ),
            ("factors = [0.0, 0.5, 1.0]", "factors = [1.0]"),
            ("factors = [0.0, 0.5, 1.0]", "factors = [1.0]"),
            ("load_steps = 3\ngravity_factors = [1.0, 1.0, 1.0]", solver),
        ],
    );
    case.write(name, &text);
}

#[test]
fn a_step_that_does_not_converge_is_cut_and_converges_to_the_uncut_answer() {
    let case = Case::new("conv-cut");
    dam(&case, "whole.toml", "max_iterations = 100");
    dam(&case, "cut.toml", "max_iterations = 8\nmax_cuts = 4");
    let mut said = String::new();
    for (scene, out) in [("whole.toml", "whole"), ("cut.toml", "cut")] {
        // (the cut one not quiet: its attempts are said as they end)
        let args = ["solve", scene, "--out", out, "--quiet"];
        let o = case.cli(if out == "whole" { &args } else { &args[..4] });
        said = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{scene}: {said}");
    }
    let (whole, cut) = (json(&case.dir.join("whole/summary.json")), json(&case.dir.join("cut/summary.json")));
    let its = whole["contact"]["iterations"].as_u64().expect("iterations");
    assert!(its > 8, "solved whole, the step needs more than the cut scene's 8 iterations: {its}");
    assert_eq!(whole["contact"]["cuts"], 0);
    let c = &cut["contact"];
    eprintln!(
        "dam in one step: {its} iterations whole; cut {} times, pieces {}, {} iterations",
        c["cuts"], c["pieces"], c["iterations"]
    );
    assert_eq!(c["converged"], Value::Bool(true));
    let cuts = c["cuts"].as_u64().expect("cuts");
    assert!((1..=4).contains(&cuts), "cut {cuts} times");
    let pieces: Vec<f64> = c["pieces"].as_array().expect("pieces").iter().filter_map(Value::as_f64).collect();
    assert_eq!(pieces.last(), Some(&1.0), "the last piece ends the step: {pieces:?}");
    assert!(pieces.windows(2).all(|w| w[0] < w[1]) && pieces[0] > 0.0, "{pieces:?}");
    // the same states and stresses (cohesion kept once slipping: no path)
    let (a, b) = (csv_rows(&case.dir.join("whole/contact.csv")), csv_rows(&case.dir.join("cut/contact.csv")));
    assert!(a.len() > 100 && a.len() == b.len(), "every pair a row: {} and {}", a.len(), b.len());
    let scale = a.iter().map(|r| csv_num(r, "sigma_n").abs()).fold(0.0, f64::max);
    for (ra, rb) in a.iter().zip(&b) {
        assert_eq!(ra["status"], rb["status"], "pair {}", ra["pair"]);
        for key in ["sigma_n", "tau_t"] {
            let d = (csv_num(ra, key) - csv_num(rb, key)).abs();
            assert!(d <= 1e-8 * scale, "pair {} {key}: {d:e}", ra["pair"]);
        }
    }
    let report = read(&case.dir.join("cut/report.md"));
    assert!(report.contains(&format!("was cut {cuts} time(s)")), "report says the cuts:\n{report}");
    // the wait said as it goes: the whole step halved, then each piece
    let halves = "solving it again in two halves from where it started, up to 8 iterations each";
    common::cli::says(&said, &["load step 1/1: not converged in 8 iteration(s) (", halves]);
    let end = pieces.len() - 2;
    let last = format!("load step 1/1 {} -> 1 of its load: converged in", pieces[end]);
    assert!(said.contains(&last), "the last piece said:\n{said}");
}

#[test]
fn a_step_that_still_does_not_converge_says_where_its_states_kept_changing() {
    let case = Case::new("conv-unsettled");
    dam(&case, "short.toml", "max_iterations = 4\nmax_cuts = 0");
    let o = case.cli(&["solve", "short.toml", "--out", "out", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    common::cli::says(&err, &["short.toml", "did not converge after 4 iteration(s)", "`changes`"]);
    assert!(!err.contains("cut"), "no cut was tried: {err}");
    let out = case.dir.join("out");
    let s = json(&out.join("summary.json"));
    assert_eq!(s["contact"]["converged"], Value::Bool(false));
    let unsettled = s["contact"]["unsettled_pairs"].as_u64().expect("unsettled_pairs");
    let rows = csv_rows(&out.join("contact.csv"));
    assert_eq!(rows.len() as u64, s["contact"]["pairs"].as_u64().expect("pairs"), "every pair a row");
    let changed = rows.iter().filter(|r| csv_num(r, "changes") > 0.0).count();
    assert!(changed > 0 && changed as u64 == unsettled, "contact.csv marks {changed}, summary {unsettled}");
    assert!(read(&out.join("short_contact.vtu")).contains("Name=\"changes\""), "the contact VTU has the field");
    let report = read(&out.join("report.md"));
    for want in [
        "## Where the iteration did not settle",
        "| contact group | pairs that changed |",
        "| blocks | pairs that changed |",
        "| block | pairs that changed on its faces | volume | supports it touches |",
        "| sigma_n | tau | law residual | at the last iteration |",
        "Stresses and the law residual in stress units, at the last iteration.",
    ] {
        assert!(report.contains(want), "report.md lacks {want:?}:\n{report}");
    }
    assert!(report.lines().count() < 150, "the report stays readable: {} lines", report.lines().count());
    // the base's pairs changed: the rock under it is held at its bottom
    // and sides, the dam's block on it by nothing but its joints
    let row = |name: &str| report.lines().find(|l| l.starts_with(&format!("| \"{name}\" |"))).unwrap_or("");
    assert!(row("rock").ends_with("| \"rock_bottom\" (x, y), \"rock_sides\" (x) |"), "{report}");
    assert!(row("block_1").ends_with("| none |"), "{report}");
    let worst = base_law_residual(&rows);
    assert!(worst > 1e-6, "the unsettled base is off its law: {worst:e}");
    let reported = s["contact"]["law_residual"]["relative"].as_f64().expect("contact.law_residual");
    assert!(reported >= worst * (1.0 - 1e-9), "summary {reported:e} below the base's {worst:e}");
    assert!(report.contains("| contact law residual"), "report.md gives the law residual:\n{report}");
    // a converged run writes none of it, and keeps the law to round-off
    dam(&case, "long.toml", "max_iterations = 100");
    assert!(case.cli(&["solve", "long.toml", "--out", "long", "--quiet"]).status.success());
    let worst = base_law_residual(&csv_rows(&case.dir.join("long/contact.csv")));
    assert!(worst < 1e-9, "converged base off its law by {worst:e}");
    assert!(!read(&case.dir.join("long/contact.csv")).lines().next().unwrap_or("").contains("changes"));
    assert!(!read(&case.dir.join("long/report.md")).contains("did not settle"));
}

/// The worst distance of the dam's base pairs from their law (friction
/// 0.75, cohesion and residual cohesion 0.1, no tension), computed here
/// from contact.csv's stresses, relative to the largest traction; checks
/// that the `law_residual` column says the same pair by pair.
fn base_law_residual(rows: &[Row]) -> f64 {
    let traction = |r| csv_num(r, "sigma_n").hypot(csv_num(r, "tau_t").hypot(csv_num(r, "tau_b")));
    let scale = rows.iter().map(traction).fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for r in rows.iter().filter(|r| r["contact"] == "base" && csv_num(r, "gap") >= 0.0) {
        let (sn, tau) = (csv_num(r, "sigma_n"), csv_num(r, "tau_t").hypot(csv_num(r, "tau_b")));
        let bound = (0.1 - 0.75 * sn).max(0.0);
        let residual = match csv_num(r, "status") as i64 {
            2 => sn.max(0.0).max(tau - bound),
            1 => sn.max(0.0).max((tau - bound).abs()),
            _ => sn.hypot(tau),
        };
        // (written to 7 digits)
        let column = csv_num(r, "law_residual");
        assert!(
            (residual - column).abs() <= 1e-6 * residual + 1e-9 * scale,
            "pair {}: {residual:e} here, {column:e} written",
            r["pair"]
        );
        worst = worst.max(residual / scale);
    }
    worst
}

#[test]
fn max_cuts_takes_a_count() {
    let case = Case::new("conv-bad-cuts");
    dam(&case, "bad.toml", "max_cuts = -1");
    let msg = common::cli::solve_fails(&case, "bad.toml", "out");
    common::cli::says(&msg, &["solver.max_cuts", "-1", "at least 0"]);
}

/// Solves `scene` (the text of a scene on tests/geo/tunnel3d_joints.geo,
/// friction 0.7002 on every set) and returns its iterations, the worst
/// pair's distance from Coulomb's law, relative to the largest traction,
/// and whether rigid joints fell back to joints that deform.
fn tunnel_through_joints(tag: &str, scene: &str) -> (u64, f64, bool) {
    let (its, worst, fell, _) = tunnel_rows(tag, "tests/geo/tunnel3d_joints.geo", scene);
    (its, worst, fell)
}

/// One step of rigid joints alone: no cuts, 300 iterations, no fallback.
const RIGID_ALONE: &str = "\n[solver]\nmax_cuts = 0\nmax_iterations = 300\nrigid_fallback = false\n";

/// Asserts that the rigid joints of `scene` on `geo` converge, in at
/// most `most` iterations, every pair within `law` of Coulomb's law
/// (relative to the largest traction); the rows of its contact.csv.
fn rigid_converges(tag: &str, geo: &str, scene: &str, most: u64, law: f64) -> Vec<Row> {
    let (its, worst, fell, rows) = tunnel_rows(tag, geo, scene);
    assert!(!fell, "the rigid joints converge");
    assert!(its <= most, "{its} iterations");
    assert!(worst < law, "law residual {worst:e}");
    rows
}

/// [`tunnel_through_joints`] on the repository's `geo` (copied beside
/// the scene), with the rows of its contact.csv.
fn tunnel_rows(tag: &str, geo: &str, scene: &str) -> (u64, f64, bool, Vec<Row>) {
    let case = Case::new(tag);
    case.copy(geo);
    case.write("tunnel.toml", scene);
    let o = case.cli(&["solve", "tunnel.toml", "--out", "out", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = json(&case.dir.join("out/summary.json"));
    let its = s["contact"]["iterations"].as_u64().expect("iterations");
    let rows = csv_rows(&case.dir.join("out/contact.csv"));
    assert_eq!(rows.len() as u64, s["contact"]["pairs"].as_u64().expect("pairs"), "every pair a row");
    let f = 0.7002;
    let scale = rows
        .iter()
        .map(|r| csv_num(r, "sigma_n").hypot(csv_num(r, "tau_t").hypot(csv_num(r, "tau_b"))))
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for r in &rows {
        let (sn, tau) = (csv_num(r, "sigma_n"), csv_num(r, "tau_t").hypot(csv_num(r, "tau_b")));
        let residual = match r["status"].as_str() {
            "2" => (tau - f * (-sn).max(0.0)).max(0.0) + sn.max(0.0),
            "1" => (tau - f * (-sn).max(0.0)).abs() + sn.max(0.0),
            _ => sn.abs() + tau,
        };
        worst = worst.max(residual / scale);
    }
    let fell = !s["contact"]["rigid_fallback"].is_null();
    eprintln!("{tag}: {its} iterations, {} pairs, law residual {worst:.1e}, fallback {fell}", rows.len());
    (its, worst, fell, rows)
}

/// A row of contact.csv, by column.
type Row = std::collections::HashMap<String, String>;

/// The text of the 34k-DOF tunnel: tests/geo/tunnel3d_joints_coarse.toml
/// meshed coarser away from the opening (lc_far 6).
fn tunnel_34k() -> String {
    let scene = common::repo_text("tests/geo/tunnel3d_joints_coarse.toml");
    let coarser = scene.replacen("lc_far = 4.0", "lc_far = 6.0", 1);
    assert_ne!(coarser, scene, "the edit applies");
    coarser
}

/// The 3D tunnel of tests/geo/tunnel3d_joints.geo, 44k DOFs, 7,160 pairs,
/// 148 blocks: before issue 28 the sparse interface wandered for 85
/// iterations (and 100+ at 47k DOFs); it converges in 27 (three runs at
/// 7f3f6aa, the dense interface too, to the same states; 34 in the
/// forty-eighth session, 42 while the cycle breaker held decided
/// changes), to states that keep Coulomb's law pair by pair: within the
/// corpus' 30 a step.
#[test]
#[ignore = "make stress: about 10 s"]
fn a_tunnel_through_three_oblique_joint_sets_converges_to_states_that_keep_the_law() {
    let scene = common::repo_text("tests/geo/tunnel3d_joints_coarse.toml");
    rigid_converges("conv-tunnel3d", "tests/geo/tunnel3d_joints.geo", &scene, 30, 1e-8);
}

/// The same tunnel on the iterative interface (`interface =
/// "iterative"`): the same states as the sparse interface's, pair by
/// pair, in 35 iterations where that takes 27 (the friction scale of
/// src/contact/system/iterative/stiffness.rs, above W's, makes its
/// Newton steps on the friction shorter: docs/convergence.md, the
/// forty-ninth session). Since a rigid step takes 30 iterations where
/// the fallback follows, it goes past them only because its states have
/// all but settled (0 or 1 pairs an iteration from its 20th:
/// `contact::Limit`); without that it fell back at its 30th.
#[test]
#[ignore = "make stress: about 2 min"]
fn the_tunnel_on_the_iterative_interface_goes_past_30_where_its_states_settle() {
    let scene = common::repo_text("tests/geo/tunnel3d_joints_coarse.toml");
    let sparse = rigid_converges("conv-tunnel3d-sparse", "tests/geo/tunnel3d_joints.geo", &scene, 30, 1e-8);
    let iterative = format!("{scene}\n[solver]\ninterface = \"iterative\"\n");
    let rows = rigid_converges("conv-tunnel3d-iterative", "tests/geo/tunnel3d_joints.geo", &iterative, 40, 1e-8);
    assert_eq!(rows.len(), sparse.len());
    let differ = rows.iter().zip(&sparse).filter(|(a, b)| a["status"] != b["status"]).count();
    assert_eq!(differ, 0, "the same states as the sparse interface's");
}

/// The same tunnel meshed coarser away from the opening (lc_far 6: 34k
/// DOFs, 5,890 pairs), in one step without cuts: a cluster of eight pairs
/// round a node where J1 meets J2 kept changing state for 300 iterations,
/// the friction of the junction's slipping pairs settling tenfold per
/// iteration or not at all, its pressures taken from the last solve. With
/// them solved for through the tangent of the junction's share it
/// converged in 40. Rigid joints alone (`rigid_fallback = false`): the
/// open question of whether the rigid law has a state set here.
#[test]
#[ignore = "issue 28: not converged since c6a9a60 (docs/convergence.md); make stress-open, 50 s"]
fn the_tunnel_meshed_coarser_away_from_the_opening_converges_without_cuts() {
    let scene = format!("{}{RIGID_ALONE}", tunnel_34k());
    rigid_converges("conv-tunnel3d-34k", "tests/geo/tunnel3d_joints.geo", &scene, 50, 1e-7);
}

/// The same, with `[solver] augmented_lagrangian`: after the Newton
/// iteration's 300, augmented Lagrangian rounds through stiff springs
/// end the step at the rigid joints' answer (14 rounds, 93 iterations,
/// 141 s in all; 5,818 stick / 70 slip / 2 open), every pair within
/// round-off of the law, no stuck pair slipping.
#[test]
#[ignore = "make stress: about 150 s"]
fn the_34k_tunnel_with_rigid_joints_ends_through_augmented_rounds() {
    let scene = format!("{}{RIGID_ALONE}augmented_lagrangian = true\n", tunnel_34k());
    let rows = rigid_converges("conv-tunnel3d-34k-augmented", "tests/geo/tunnel3d_joints.geo", &scene, 450, 1e-9);
    let stuck_slip = (rows.iter().filter(|r| r["status"] == "2")).map(|r| csv_num(r, "slip").abs()).fold(0.0, f64::max);
    assert!(stuck_slip < 1e-10, "a stuck pair slips by {stuck_slip:e} m");
}

/// The two-set tunnel whose rigid joints take 16 iterations, given 12
/// and `[solver] augmented_lagrangian`: the rounds started from its step's
/// start do not end it either (the rounds have 12 iterations in all, as
/// the Newton attempt: measured, the 3rd round has 2 left and does not
/// end in them; given 12 each, the 7th, at 729 times the first's
/// springs, did not end in its 12), so the run ends as without them
/// (status 1, the Newton iteration's last iterate), and summary.json and
/// report.md say the rounds did not close.
#[test]
#[ignore = "make stress: about 35 s"]
fn augmented_rounds_that_do_not_end_a_step_leave_the_newton_iterations() {
    let case = Case::new("conv-augmented-open");
    let text = common::scenes::tunnel_two_sets(&case);
    let solver = "\n[solver]\nmax_cuts = 0\nmax_iterations = 12\nrigid_fallback = false\n";
    case.write("plain.toml", &format!("{text}{solver}"));
    case.write("rounds.toml", &format!("{text}{solver}augmented_lagrangian = true\n"));
    for stem in ["plain", "rounds"] {
        let o = case.cli(&["solve", &format!("{stem}.toml"), "--out", stem, "--quiet"]);
        assert_eq!(o.status.code(), Some(1), "{stem}: {}", String::from_utf8_lossy(&o.stderr));
    }
    let csv = |dir: &str| std::fs::read_to_string(case.dir.join(dir).join("contact.csv")).expect("contact.csv");
    assert_eq!(csv("plain"), csv("rounds"), "the Newton iteration's last iterate");
    let c = &json(&case.dir.join("rounds/summary.json"))["contact"];
    let rounds = &c["augmented"];
    eprintln!("two-set tunnel, 12 iterations: {rounds}");
    assert_eq!(rounds["closed"], false, "{rounds}");
    let more = rounds["iterations"].as_u64().expect("the rounds' iterations");
    assert_eq!(c["iterations"].as_u64(), Some(12 + more), "Newton's and the rounds'");
    let report = std::fs::read_to_string(case.dir.join("rounds/report.md")).expect("report.md");
    assert!(report.contains("They did not end it either"), "{report}");
    // with the fallback, its record counts the rounds among the rigid
    // attempt's iterations, and says so
    let fallback = "\n[solver]\nmax_cuts = 0\nmax_iterations = 12\naugmented_lagrangian = true\n";
    case.write("fallback.toml", &format!("{text}{fallback}"));
    let o = case.cli(&["solve", "fallback.toml", "--out", "fallback"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "the fallback converges: {stderr}");
    let fell = &json(&case.dir.join("fallback/summary.json"))["contact"]["rigid_fallback"];
    assert_eq!(fell["augmented"]["iterations"].as_u64(), Some(more), "{fell}");
    assert_eq!(fell["iterations"].as_u64(), Some(12 + more), "{fell}");
    let rounds = fell["augmented"]["rounds"].as_u64().expect("the rounds");
    let said = format!("({} iteration(s), {more} of them in {rounds} augmented Lagrangian round(s), ", 12 + more);
    eprintln!("{said}");
    assert!(stderr.contains(&said), "{said}: {stderr}");
}

/// The same 34k-DOF tunnel with joints that deform (k_n = 5,000 MPa/m,
/// E per metre; k_s a tenth of it: src/contact/elastic.rs): every pair a
/// spring, no ties, no junction shares to settle. 4 iterations where the
/// rigid joints never end, the law checked pair by pair from contact.csv.
#[test]
#[ignore = "make stress: about 10 s"]
fn the_tunnel_with_joints_that_deform_converges() {
    let coarser = tunnel_34k();
    let stiff =
        coarser.replace("friction = 0.7002", "friction = 0.7002\nnormal_stiffness = 5.0e3\nshear_stiffness = 5.0e2");
    assert_eq!(stiff.matches("normal_stiffness").count(), 3, "the edit applies to every set");
    let (its, worst, fell) = tunnel_through_joints(
        "conv-tunnel3d-34k-stiff",
        &format!("{stiff}\n[solver]\nmax_cuts = 0\nmax_iterations = 300\n"),
    );
    assert!(!fell, "joints that deform do not fall back");
    assert!(its <= 10, "{its} iterations");
    assert!(worst < 1e-8, "law residual {worst:e}");
}

/// The same 34k-DOF tunnel with joints stiffer and stiffer: k_n = 5e5,
/// 5e6 and 5e7 MPa/m (360 to 36,000 times E / s; k_s a tenth of it). Each
/// converges (6, 11, 12 iterations measured; at 5e7 the sparse interface's
/// GMRES must be flexible, its preconditioner being single precision:
/// src/contact/system/gmres.rs), the states are the same pair
/// by pair from 5e6 on (5,802 / 86 / 2; 5e8 too), and the forces of the
/// lone pairs away from the supports tend to a limit as 1 / k_n: their
/// median change falls tenfold for a tenfold stiffness (8.9e-4, 9.3e-5,
/// 9.4e-6 MPa measured up to 5e8: order 0.98, 1.00). So rigid joints, the limit of stiff
/// ones, have an answer here; the rigid iteration does not reach it
/// (docs/convergence.md, thirty-first session).
#[test]
#[ignore = "make stress: about 90 s"]
fn the_tunnel_with_stiffer_and_stiffer_joints_tends_to_one_answer() {
    let coarser = tunnel_34k();
    let runs: Vec<_> = [5.0e5, 5.0e6, 5.0e7]
        .iter()
        .map(|&k: &f64| {
            let stiff = coarser
                .replace("friction = 0.7002", &format!("friction = 0.7002\n{}", common::scenes::springs(k, k / 10.0)));
            assert_eq!(stiff.matches("normal_stiffness").count(), 3, "the edit applies to every set");
            let tag = format!("conv-tunnel3d-34k-k{}", k.log10().round());
            let (its, worst, fell, rows) = tunnel_rows(
                &tag,
                "tests/geo/tunnel3d_joints.geo",
                &format!("{stiff}\n[solver]\nmax_cuts = 0\nmax_iterations = 300\n"),
            );
            assert!(!fell && its <= 30, "k_n = {k:e}: {its} iterations");
            assert!(worst < 1e-8, "k_n = {k:e}: law residual {worst:e}");
            rows
        })
        .collect();
    let states = |rows: &[Row]| -> Vec<String> { rows.iter().map(|r| r["status"].clone()).collect() };
    assert_eq!(states(&runs[1]), states(&runs[2]), "the same states at 5e6 and 5e7");
    // lone pairs (no twin at their point) off the supported faces: the
    // forces a junction or a support shares with another are not the pair's alone
    let at = |r: &Row| ["x", "y", "z"].map(|k| r[k].clone());
    let mut twins = std::collections::HashMap::new();
    runs[0].iter().for_each(|r| *twins.entry(at(r)).or_insert(0) += 1);
    let supported = |r: &Row| {
        let (x, y, z) = (csv_num(r, "x"), csv_num(r, "y"), csv_num(r, "z"));
        (x.abs() - 12.0).abs() < 1e-6 || y.abs() < 1e-6 || (y - 12.0).abs() < 1e-6 || (z + 12.0).abs() < 1e-6
    };
    let lone: Vec<usize> =
        (0..runs[0].len()).filter(|&p| twins[&at(&runs[0][p])] == 1 && !supported(&runs[0][p])).collect();
    // the median change: a pair next to one that changed state from 5e5
    // to 5e6 moves by more than the stiffness' 1 / k
    let change = |a: usize, b: usize| -> f64 {
        let mut d: Vec<f64> = lone
            .iter()
            .map(|&p| {
                let d = |k: &str| csv_num(&runs[a][p], k) - csv_num(&runs[b][p], k);
                d("sigma_n").abs().max(d("tau_t").hypot(d("tau_b")))
            })
            .collect();
        d.sort_by(f64::total_cmp);
        d[d.len() / 2]
    };
    let (first, second) = (change(0, 1), change(1, 2));
    let order = (first / second).log10();
    eprintln!("{} lone pairs: median change {first:.3e}, then {second:.3e} MPa: order {order:.2}", lone.len());
    assert!(lone.len() > 1000, "{} lone pairs", lone.len());
    assert!((0.85..1.15).contains(&order), "the forces tend to a limit as 1 / k_n: order {order}");
}

/// The same 34k-DOF tunnel as a user writes it, rigid joints and the
/// default [solver]: its rigid joints do not converge (100 iterations,
/// not cut: a step from no load on joints of friction alone, whose halves
/// repeat it; 400 iterations and 3 cuts before), and the run falls back
/// to joints that deform (k_n = 10 E / s, s = 3.6 m the mean block size),
/// which converge and keep the law pair by pair: the run ends, status 0,
/// and says it fell back.
#[test]
#[ignore = "make stress: about 15 s"]
fn the_tunnel_with_rigid_joints_ends_through_the_fallback() {
    let coarser = tunnel_34k();
    let (its, worst, fell) = tunnel_through_joints("conv-tunnel3d-34k-fallback", &coarser);
    assert!(fell, "the rigid joints do not converge here");
    assert!(its <= 10, "{its} iterations");
    assert!(worst < 1e-8, "law residual {worst:e}");
}

/// The 34k tunnel's rigid joints cycle round block 73, a 1.9 m^3 wedge
/// on the frictionless end roller (report.md names it, with its volume
/// and the roller). With the ends clamped the same scene converges with
/// rigid joints (20 iterations measured, 5,776 / 111 / 3): the roller's
/// wedge, not the crossings alone, is what does not end
/// (docs/convergence.md, thirty-second session).
#[test]
#[ignore = "make stress: about 15 s"]
fn the_34k_tunnel_with_its_ends_clamped_converges_with_rigid_joints() {
    let clamped =
        tunnel_34k().replacen("group = \"ends\"\nfix = [\"y\"]", "group = \"ends\"\nfix = [\"x\", \"y\", \"z\"]", 1);
    assert!(clamped.contains("fix = [\"x\", \"y\", \"z\"]"), "the edit applies");
    let scene = format!("{clamped}{RIGID_ALONE}");
    rigid_converges("conv-tunnel3d-34k-clamped", "tests/geo/tunnel3d_joints.geo", &scene, 30, 1e-8);
}

/// Issue 28's speed case as written (docs/convergence/tunnel3d_86k.toml:
/// make tunnel3d's scene at lc = 2 throughout, 99,095 DOFs, 13,179
/// pairs), rigid joints and the default [solver]: 100 iterations without
/// an end, then the fallback (41.5 s), until the junctions shared only
/// what comes after the in-situ stress (f9d2945): the end roller's
/// crossing had been given the joints' in-situ force. Now the rigid
/// joints converge in 14 iterations (13,075 / 104 / 0, 11.3 s), with no
/// fallback, and keep the law pair by pair.
#[test]
#[ignore = "make stress: about 20 s"]
fn the_fine_tunnel_with_rigid_joints_converges_without_the_fallback() {
    let scene = common::repo_text("docs/convergence/tunnel3d_86k.toml");
    let scene = scene.replacen("mesh = \"../../geo/tunnel3d.geo\"", "mesh = \"tunnel3d.geo\"", 1);
    assert!(scene.contains("mesh = \"tunnel3d.geo\""), "the edit applies");
    let rows = rigid_converges("conv-tunnel3d-86k", "geo/tunnel3d.geo", &scene, 30, 1e-8);
    assert!(rows.len() > 13_000, "{} pairs", rows.len());
}

/// The joint stiffness a step of rigid joints that did not converge
/// advises, taken as said: the two-set tunnel (tests/interface_paths.rs'
/// kept mesh, 1,779 pairs) does not converge in 12 iterations with rigid
/// joints (it takes 16, dense and sparse; 45-49 before the forty-first
/// session, and this test gave it 20); with `rigid_fallback = false` the run stops and names a
/// stiffness (k_n = 10 E / s, s the mean block size), and with it the
/// scene converges. By default the run takes that stiffness itself: the
/// same states and forces as the scene that gives it, said on the
/// terminal, in summary.json and report.md, exit status 0.
#[test]
fn the_joint_stiffness_a_step_that_did_not_converge_advises_ends_it() {
    let case = Case::new("conv-advice");
    let text = common::scenes::tunnel_two_sets(&case);
    let solver = "\n[solver]\nmax_cuts = 0\nmax_iterations = 12\n";
    case.write("rigid.toml", &format!("{text}{solver}rigid_fallback = false\n"));
    let o = case.cli(&["solve", "rigid.toml", "--out", "rigid", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    common::cli::says(
        &err,
        &["did not converge after 12 iteration(s)", "[[joint_sets]] entry", "Joints that deform", "rigid_fallback"],
    );
    // the values advised, read off the message
    let value = |key: &str| -> f64 {
        let at = err.find(&format!("{key} = ")).unwrap_or_else(|| panic!("{key} advised: {err}")) + key.len() + 3;
        err[at..].split_whitespace().next().and_then(|v| v.parse().ok()).expect("a number")
    };
    let (k_n, k_s) = (value("normal_stiffness"), value("shear_stiffness"));
    assert!(
        k_n > 5000.0 && (k_s - k_n / 10.0).abs() <= 1e-3 * k_s,
        "10 E / s with s below 10 m, and a tenth: {k_n}, {k_s}"
    );
    let stiff = text.replace("friction = 0.7002", &format!("friction = 0.7002\n{}", common::scenes::springs(k_n, k_s)));
    assert_eq!(stiff.matches("normal_stiffness").count(), 2, "both sets deform");
    case.write("stiff.toml", &format!("{stiff}{solver}"));
    let o = case.cli(&["solve", "stiff.toml", "--out", "stiff", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let c = &json(&case.dir.join("stiff/summary.json"))["contact"];
    let (its, law) =
        (c["iterations"].as_u64().expect("iterations"), c["law_residual"]["relative"].as_f64().expect("law"));
    eprintln!("two-set tunnel with the advised springs: {its} iterations, law residual {law:.1e}");
    assert!(its <= 8, "{its} iterations");
    assert!(law < 1e-8, "law residual {law:e}");

    // the default: the run falls back to that stiffness by itself
    case.write("fallback.toml", &format!("{text}{solver}"));
    let o = case.cli(&["solve", "fallback.toml", "--out", "fallback", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    common::cli::says(
        &err,
        &["warning: rigid joints did not converge at load step 1 (12 iteration(s)", "joints that deform"],
    );
    let summary = json(&case.dir.join("fallback/summary.json"));
    let f = &summary["contact"]["rigid_fallback"];
    assert_eq!(f["iterations"].as_u64(), Some(12), "{f}");
    assert_eq!((f["normal_stiffness"].as_f64(), f["shear_stiffness"].as_f64()), (Some(k_n), Some(k_s)), "{f}");
    assert_eq!(summary["contact"]["converged"], true);
    assert_eq!(summary["contact"]["iterations"].as_u64(), Some(its));
    let csv = |dir: &str| std::fs::read_to_string(case.dir.join(dir).join("contact.csv")).expect("contact.csv");
    assert_eq!(csv("fallback"), csv("stiff"), "the fallback solves the scene that gives its stiffness");
    let report = std::fs::read_to_string(case.dir.join("fallback/report.md")).expect("report.md");
    assert!(
        report.contains("**Joints that deform in place of rigid ones:** rigid joints did not converge"),
        "{report}"
    );
}

/// A step from no load on joints of friction alone is the same problem at
/// any load, so it is not cut: the two-set tunnel given 12 iterations
/// (rigid joints, `rigid_fallback = false`) stops after its 12 and says
/// why it was not cut. The evidence that cutting it cannot help: with a
/// cohesion of 1e-9 MPa on one set (so that the rule lets it cut) it is
/// cut three times and each piece repeats the whole step's iterations,
/// the last one at an eighth of the load ending in the same states pair
/// by pair, after the same state counts, with an eighth of the pressures.
#[test]
fn a_step_that_is_the_same_problem_at_any_load_is_not_cut() {
    let case = Case::new("conv-scaled");
    let text = common::scenes::tunnel_two_sets(&case);
    let solver = "\n[solver]\nmax_iterations = 12\nrigid_fallback = false\n";
    case.write("scaled.toml", &format!("{text}{solver}"));
    let cohesive = text.replacen("friction = 0.7002", "friction = 0.7002\ncohesion = 1e-9", 1);
    case.write("cohesive.toml", &format!("{cohesive}{solver}"));
    for name in ["scaled", "cohesive"] {
        let o = case.cli(&["solve", &format!("{name}.toml"), "--out", name, "--quiet"]);
        assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
        if name == "scaled" {
            common::cli::says(
                &String::from_utf8_lossy(&o.stderr),
                &["after 12 iteration(s), not cut: it starts from no load, on joints of friction alone"],
            );
        }
    }
    let (a, b) = (json(&case.dir.join("scaled/summary.json")), json(&case.dir.join("cohesive/summary.json")));
    let (a, b) = (&a["contact"], &b["contact"]);
    assert_eq!((a["iterations"].as_u64(), a["cuts"].as_u64(), &a["scaled"]), (Some(12), Some(0), &Value::Bool(true)));
    assert_eq!((b["iterations"].as_u64(), b["cuts"].as_u64(), &b["scaled"]), (Some(48), Some(3), &Value::Bool(false)));
    assert_eq!(a["history"], b["history"], "the eighth of the load goes through the same state counts");
    let (whole, eighth) =
        (csv_rows(&case.dir.join("scaled/contact.csv")), csv_rows(&case.dir.join("cohesive/contact.csv")));
    assert!(whole.len() > 1000 && whole.len() == eighth.len(), "{} and {} pairs", whole.len(), eighth.len());
    let scale = whole.iter().map(|r| csv_num(r, "sigma_n").abs()).fold(0.0, f64::max);
    for (w, e) in whole.iter().zip(&eighth) {
        assert_eq!(w["status"], e["status"], "pair {}", w["pair"]);
        let d = (csv_num(w, "sigma_n") - 8.0 * csv_num(e, "sigma_n")).abs();
        assert!(d <= 1e-6 * scale, "pair {}: sigma_n {} against 8 x {}", w["pair"], w["sigma_n"], e["sigma_n"]);
    }
    let report = read(&case.dir.join("scaled/report.md"));
    assert!(
        report.contains("The load step did not converge whole and was not cut: it starts from no load"),
        "{report}"
    );
}

/// A cut piece starts from where its step started, not from the last
/// iterate of the attempt that did not converge. The 3D slope of the
/// corpus with half its cohesion (tests/corpus/slope3d_c005.toml), rigid
/// joints given 30 iterations and one cut: its step 3 does not converge
/// whole, and its first half, started from the answer step 2 ended with,
/// converges in 3; its second half does not, and the run falls back to
/// joints that deform, saying that the rigid joints held half the step's
/// load. Started from the whole step's last iterate (the interface's
/// GMRES begins at the last answer), the first half went through 30
/// state sets of up to 738 changes and did not converge (no piece held;
/// with 100 iterations, it took 100 and did not).
#[test]
#[ignore = "make stress: about 45 s"]
fn a_cut_piece_starts_where_its_step_started() {
    let case = Case::new("conv-cut-start");
    case.copy("tests/corpus/slope3d.geo");
    let text = common::repo_text("tests/corpus/slope3d_c005.toml");
    let solver = "load_steps = 4\nmax_iterations = 30\nmax_cuts = 1";
    assert!(text.contains("\nload_steps = 4"), "the corpus slope is solved in four steps");
    case.write("slope.toml", &text.replacen("load_steps = 4", solver, 1));
    let o = case.cli(&["solve", "slope.toml", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "the fallback converges: {stderr}");
    let fell = &json(&case.dir.join("out/summary.json"))["contact"]["rigid_fallback"];
    eprintln!("slope3d_c005, step 3 cut once: {fell}");
    assert_eq!((fell["step"].as_u64(), fell["cuts"].as_u64()), (Some(3), Some(1)), "{fell}");
    assert_eq!(fell["held"].as_f64(), Some(0.5), "the first half held: {fell}");
    let its = fell["iterations"].as_u64().expect("iterations");
    assert!(its <= 30 + 5 + 30, "30 whole, a few in the first half, 30 in the second: {its}");
    common::cli::says(&stderr, &["its cut pieces held 0.5 of its load", "check the margin with a [safety] search"]);
}

/// The fallback in 2D: geo/tunnel_joints.toml (three sets, plane strain)
/// takes 11 iterations with rigid joints; given 10, it falls back to k_n
/// = 10 E / s with s = sqrt(A / n) (the bounding box's area shared among
/// its blocks), which converges in 9, contact.csv the same as the scene
/// with those keys written; the rigid joints stopped close to the law,
/// so the warning says more iterations may end them rigid, and given 20
/// they do (11, no fallback).
#[test]
fn the_fallback_in_2d_takes_the_block_size_of_an_area() {
    let case = Case::new("conv-fallback-2d");
    case.copy("geo/tunnel_joints.geo");
    let scene = common::repo_text("geo/tunnel_joints.toml");
    let solver = "\n[solver]\nmax_iterations = 10\nmax_cuts = 0\n";
    case.write("rigid.toml", &format!("{scene}{solver}"));
    let o = case.cli(&["solve", "rigid.toml", "--out", "rigid", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    common::cli::says(&err, &["rigid joints did not converge", "more [solver] max_iterations may end them rigid"]);
    let f = json(&case.dir.join("rigid/summary.json"))["contact"]["rigid_fallback"].clone();
    let num = |k: &str| f[k].as_f64().unwrap_or_else(|| panic!("{k}: {f}"));
    let (k_n, k_s, e, s) = (num("normal_stiffness"), num("shear_stiffness"), num("modulus"), num("block_size"));
    assert_eq!(e, 5000.0);
    // the box of the 2D model shared among its blocks, to the power 1/2
    assert!(s > 1.0 && s < 10.0, "block size {s}");
    assert!((k_n - 10.0 * e / s).abs() <= 5e-4 * k_n, "k_n = 10 E / s to four digits: {k_n} against {}", 10.0 * e / s);
    assert!((k_s - k_n / 10.0).abs() <= 5e-4 * k_s, "{k_s}");
    let stiff = scene.replace("friction = ", &format!("{}\nfriction = ", common::scenes::springs(k_n, k_s)));
    assert_eq!(stiff.matches("normal_stiffness").count(), 3, "every set deforms");
    case.write("stiff.toml", &format!("{stiff}{solver}"));
    let o = case.cli(&["solve", "stiff.toml", "--out", "stiff", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = |dir: &str| std::fs::read_to_string(case.dir.join(dir).join("contact.csv")).expect("contact.csv");
    assert_eq!(csv("rigid"), csv("stiff"), "the fallback solves the scene that gives its stiffness");
    // the advice helps: given 20 iterations, the rigid joints converge
    let more = solver.replace("max_iterations = 10", "max_iterations = 20");
    case.write("more.toml", &format!("{scene}{more}"));
    let o = case.cli(&["solve", "more.toml", "--out", "more", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let c = json(&case.dir.join("more/summary.json"))["contact"].clone();
    assert_eq!(c["converged"].as_bool(), Some(true), "{c}");
    assert!(c["rigid_fallback"].is_null(), "rigid, no fallback: {}", c["rigid_fallback"]);
    assert_eq!(c["iterations"].as_u64(), Some(11), "{}", c["iterations"]);
}

/// geo/tunnel_joints.toml (k0 = 0.25) with the set dipping 60 degrees
/// given f = 0.5 and no cohesion: Mohr's circle puts every pair of it at
/// tau / sigma_n = (1 - k0) sin 60 cos 60 / (cos^2 60 + k0 sin^2 60) =
/// 0.74231 of the in-situ stress, 1.4846 times what f = 0.5 carries; the
/// other sets (cohesion 0.1, f = 0.85) hold, and so does the scene as given.
#[test]
fn in_situ_stress_beyond_a_joints_strength_is_named_before_solving() {
    let case = Case::new("conv-insitu");
    case.copy("geo/tunnel_joints.geo");
    let scene = common::repo_text("geo/tunnel_joints.toml");
    case.write("as_given.toml", &scene);
    let weak = scene.replacen(
        "name = \"joints_a\"\nangle = 60.0\nspacing = 4.0\noffset = 3.5\nfriction = 0.85\ncohesion = 0.1",
        "name = \"joints_a\"\nangle = 60.0\nspacing = 4.0\noffset = 3.5\nfriction = 0.5",
        1,
    );
    assert_ne!(weak, scene, "the edit applies");
    case.write("weak.toml", &weak);
    let given = case.cli(&["check", "as_given.toml"]);
    assert!(given.status.success());
    assert!(!String::from_utf8_lossy(&given.stderr).contains("in-situ"), "the scene as given holds");
    let o = case.cli(&["check", "weak.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "a warning, not an error: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.contains("in-situ stress")).collect();
    assert_eq!(lines.len(), 1, "one warning, for joints_a alone: {err}");
    common::cli::says(lines[0], &["weak.toml", "contact \"joints_a\"", "mobilised up to 1.485 of it", "k0"]);
    let (n, of) = {
        let w: Vec<&str> = lines[0].split_whitespace().collect();
        let at = w.iter().position(|&x| x == "puts").expect("puts N of the M pairs");
        (w[at + 1].to_string(), w[at + 4].to_string())
    };
    assert_eq!(n, of, "every pair of the set is beyond: {}", lines[0]);
    // and the results say it too (whether the opening then holds is not the point here)
    case.cli(&["solve", "weak.toml", "--out", "out", "--quiet"]);
    let s = json(&case.dir.join("out/summary.json"));
    let warnings = s["warnings"].as_array().expect("warnings");
    assert!(warnings.iter().any(|w| w.as_str().is_some_and(|w| w.contains("in-situ stress"))), "{warnings:?}");
}

/// The unit normal of a set of dip and dip direction (degrees; x east,
/// y north, z up).
fn set_normal(dip: f64, dip_direction: f64) -> [f64; 3] {
    let (d, a) = (dip.to_radians(), dip_direction.to_radians());
    [d.sin() * a.sin(), d.sin() * a.cos(), d.cos()]
}

/// The corpus cavern (tests/corpus/cavern3d.toml: tet10, sets J1 50/040
/// and J2 65/130, f = 0.7, a uniform full-tensor in-situ stress) checked
/// in 3D, in shear and in tension. A uniform stress puts the same
/// traction on every pair of a set, so a set is beyond its strength at
/// all its pairs or none. In shear, both sets given f = 0.3: J2 carries
/// tau / sigma_n = 0.394780 of the cavern's stress (Cauchy, sigma n), 1.316
/// times what f = 0.3 carries; J1 0.269413, within it. In tension, the
/// stress -10 I + 12 n1 n1^T: 2 MPa across J1 and no shear on it, J2 at
/// tau / sigma_n = 0.344 (holds): J1 is beyond with f_t = 0 and 1.5,
/// not with 3.
#[test]
fn in_situ_stress_beyond_a_3d_joint_set_in_shear_and_in_tension() {
    let case = Case::new("conv-insitu-3d");
    case.copy("tests/corpus/cavern3d.geo");
    let scene = common::repo_text("tests/corpus/cavern3d.toml");
    let warned = |name: &str, text: &str| -> Vec<String> {
        case.write(name, text);
        let o = case.cli(&["check", name]);
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert!(o.status.success(), "{name}: a warning, not an error: {err}");
        err.lines().filter(|l| l.contains("in-situ stress")).map(str::to_string).collect()
    };
    let all_pairs = |line: &str| {
        let w: Vec<&str> = line.split_whitespace().collect();
        let at = w.iter().position(|&x| x == "puts").expect("puts N of the M pairs");
        assert_eq!(w[at + 1], w[at + 4], "every pair of the set is beyond: {line}");
    };
    assert!(warned("as_given.toml", &scene).is_empty(), "the cavern as given holds");
    // shear
    let weak = scene.replace("friction = 0.7", "friction = 0.3");
    assert_eq!(weak.matches("friction = 0.3").count(), 2, "the edit applies to both sets");
    let lines = warned("weak.toml", &weak);
    assert_eq!(lines.len(), 1, "one warning, for J2 alone: {lines:?}");
    common::cli::says(&lines[0], &["contact \"J2\"", "beyond Coulomb", "mobilised up to 1.316 of it"]);
    all_pairs(&lines[0]);
    // tension: -10 I + 12 n1 n1^T
    let n = set_normal(50.0, 40.0);
    let s = |i: usize, j: usize| 12.0 * n[i] * n[j] - if i == j { 10.0 } else { 0.0 };
    let tensor = [s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)].map(|x| format!("{x:.12}")).join(", ");
    let given = "initial_stress = [-12.0, -9.0, -15.0, -2.0, 1.5, -3.0]";
    assert!(scene.contains(given), "the edit applies");
    let pulled = scene.replace(given, &format!("initial_stress = [{tensor}]"));
    let j1 = "offset = 1.5\nsnap = 3.2\nfriction = 0.7";
    assert!(pulled.contains(j1), "the edit applies");
    for (f_t, beyond) in [(None, true), (Some(1.5), true), (Some(3.0), false)] {
        let text = match f_t {
            Some(f_t) => pulled.replace(j1, &format!("{j1}\ncohesion = 3.0\ntensile_strength = {f_t}")),
            None => pulled.clone(),
        };
        let lines = warned("pulled.toml", &text);
        if !beyond {
            assert!(lines.is_empty(), "f_t = {f_t:?} carries the 2 MPa: {lines:?}");
            continue;
        }
        assert_eq!(lines.len(), 1, "f_t = {f_t:?}: one warning, for J1 alone: {lines:?}");
        common::cli::says(&lines[0], &["contact \"J1\"", "in tension beyond f_t"]);
        assert!(!lines[0].contains("beyond Coulomb"), "a set in tension is not counted in shear: {}", lines[0]);
        all_pairs(&lines[0]);
    }
}

/// geo/tunnel_joints.toml in a 10 m box (docs/convergence/
/// tunnel_joints_10m.toml), one step without cuts: four pairs of a
/// crossing (24, 25, 95, 96) all slip, and the junction took their
/// pressures from the last solve, a fixed point whose friction's gain on
/// them is above 1: with the states held the friction residual grew 5 %
/// per iteration, 100 iterations (413 with 3 cuts) without converging.
/// The stall was caught after five held solves and those pressures solved
/// for by multisecant steps (`contact/cluster.rs`): converged in 16.
/// Since joints meeting a roller obliquely keep their own frame (655d6a0)
/// it takes 24, the same states but pair 143, where joints_b (60 degrees)
/// meets the bottom roller: open along x on the projected frame before,
/// stuck now on its own plane (sigma_n 0, its shear 0.095 within its
/// cohesion; law residual 4.4e-11 of the largest traction); 21 at
/// f5e94f8. The junction's feedback has a spectral radius of 1.05 but
/// no eigenvalue of real part above 0.33: its pressures are solved for
/// in every solve since that is the bound (`junction/pressure.rs`,
/// `GAIN`), and it converges in 8 without a stall, the same states pair
/// by pair (pressures within 1e-9 MPa).
#[test]
fn a_crossing_whose_slipping_pairs_wedge_it_converges_once_its_pressures_are_solved_for() {
    let case = Case::new("conv-tunnel-10m");
    case.copy("geo/tunnel_joints.geo");
    let scene = common::repo_text("docs/convergence/tunnel_joints_10m.toml");
    let scene = scene.replacen("../../geo/tunnel_joints.geo", "tunnel_joints.geo", 1);
    case.write("tunnel.toml", &format!("{scene}\n[solver]\nmax_cuts = 0\n"));
    let o = case.cli(&["solve", "tunnel.toml", "--out", "out", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = json(&case.dir.join("out/summary.json"));
    let c = &s["contact"];
    assert_eq!(c["converged"], Value::Bool(true));
    let its = c["iterations"].as_u64().expect("iterations");
    assert!(its <= 10, "{its} iterations");
    assert_eq!(c["clusters_solved"].as_u64(), Some(0), "no stall: the pressures solved for");
    let worst = c["law_residual"]["relative"].as_f64().expect("law residual");
    assert!(worst < 1e-6, "law residual {worst:e}");
    let slip = c["states"]["slip"].as_u64().expect("slip");
    assert!(slip >= 4, "the crossing's four pairs slip: {slip} slipping");
    let rows = csv_rows(&case.dir.join("out/contact.csv"));
    for p in [24, 25, 95, 96] {
        let status = rows.iter().find(|r| r["pair"] == p.to_string()).map(|r| r["status"].clone());
        assert_eq!(status.as_deref(), Some("1"), "pair {p} slips");
    }
}
