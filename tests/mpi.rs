//! Parts on MPI ranks (cargo feature `mpi`; `make test-mpi` builds it and
//! runs these): `mpirun -np N subcontact solve` gives the serial answer to
//! 1e-10 with 2 and 3 ranks, rank 0 writes the same files, a failure on any
//! rank ends every rank with one message and no results, and more ranks
//! than parts are refused with what to do. With the iterative interface the
//! ranks apply their parts' S for rank 0's GMRES: the serial iterative
//! answer to 1e-8 (the GMRES tolerance is 1e-10 of the load, and the sums
//! of the parts come in another order). A rock mass of 27 blocks takes the
//! sparse interface: each rank condenses its blocks, rank 0 factorises
//! the means and iterates.
#![cfg(feature = "mpi")]

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::Case;

/// `mpirun -np n subcontact args...` in the case's directory.
fn mpirun(case: &Case, n: usize, args: &[&str]) -> Output {
    Command::new("mpirun")
        .args(["--allow-run-as-root", "--oversubscribe", "-np", &n.to_string(), env!("CARGO_BIN_EXE_subcontact")])
        .args(args)
        .current_dir(&case.dir)
        .output()
        .expect("mpirun (make test-mpi installs openmpi-bin)")
}

/// The numbers of a CSV file, row by row.
fn numbers(path: &Path) -> Vec<Vec<f64>> {
    common::read(path).lines().skip(1).map(|l| l.split(',').filter_map(|v| v.parse().ok()).collect()).collect()
}

/// Largest difference between two runs' CSV numbers, relative to the largest value.
fn csv_difference(a: &Path, b: &Path) -> f64 {
    let (x, y) = (numbers(a), numbers(b));
    assert_eq!(x.len(), y.len(), "{} and {}: rows", a.display(), b.display());
    let scale = x.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    x.iter().zip(&y).flat_map(|(r, s)| r.iter().zip(s).map(|(p, q)| (p - q).abs())).fold(0.0, f64::max) / scale
}

fn solve_ok(case: &Case, n: usize, scene: &str, out: &str, extra: &[&str]) {
    let mut args = vec!["solve", scene, "--out", out, "--quiet"];
    args.extend_from_slice(extra);
    let o = if n == 0 { case.cli(&args) } else { mpirun(case, n, &args) };
    assert!(o.status.success(), "{n} rank(s): {}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn parts_on_two_and_three_ranks_give_the_serial_answer() {
    let case = Case::new("mpi-same");
    common::scenes::coarse_blocks(&case);
    case.copy("geo/dam.geo");
    case.copy("geo/dam.toml");
    for (scene, cut) in [("blocks.toml", "2"), ("dam.toml", "2")] {
        let stem = scene.trim_end_matches(".toml");
        solve_ok(&case, 0, scene, &format!("{stem}_serial"), &["--substructures", cut]);
        for n in [2, 3] {
            let out = format!("{stem}_np{n}");
            solve_ok(&case, n, scene, &out, &["--substructures", cut]);
            let e = csv_difference(
                &case.dir.join(format!("{stem}_serial/contact.csv")),
                &case.dir.join(format!("{out}/contact.csv")),
            );
            eprintln!("{scene}, {n} ranks: contact.csv differs from serial by {e:.1e}");
            assert!(e < 1e-10, "{scene} on {n} ranks: {e:.2e}");
            if scene == "blocks.toml" {
                let e = csv_difference(
                    &case.dir.join(format!("{stem}_serial/probes.csv")),
                    &case.dir.join(format!("{out}/probes.csv")),
                );
                assert!(e < 1e-10, "{scene} on {n} ranks, probes: {e:.2e}");
            }
            let files = |d: &str| {
                let mut f: Vec<String> =
                    case.files_in(&case.dir.join(d)).into_iter().filter(|f| !f.starts_with("mesh")).collect();
                f.sort();
                f
            };
            assert_eq!(files(&format!("{stem}_serial")), files(&out), "rank 0 writes the same files");
            let summary = common::json(&case.dir.join(format!("{out}/summary.json")));
            let ranks = summary["ranks"].as_array().expect("ranks");
            assert_eq!(ranks.len(), n, "every rank reports");
            assert!(ranks.iter().all(|r| !r["parts"].as_array().expect("parts").is_empty()), "every rank has a part");
            assert!(
                ranks.iter().all(|r| r["bytes_sent_per_contact_iteration"] == 0),
                "nothing travels during the iteration"
            );
        }
    }
}

/// Joints that deform (src/contact/elastic.rs) on two ranks: the block on
/// block under its oblique push, its joint a spring, cut in two
/// substructures a body.
#[test]
fn joints_that_deform_on_two_ranks_give_the_serial_answer() {
    let case = Case::new("mpi-stiff");
    case.copy("geo/blocks3d.geo");
    let edits = [
        ("setnumber = { lc = 0.1, hex = 0 }", "setnumber = { lc = 0.2, hex = 0 }"),
        ("cohesion = 0.0", "cohesion = 0.0\nnormal_stiffness = 2.0e3\nshear_stiffness = 2.0e2"),
    ];
    case.write("stiff.toml", &common::scenes::edited("geo/blocks3d.toml", &edits));
    solve_ok(&case, 0, "stiff.toml", "serial", &["--substructures", "2"]);
    solve_ok(&case, 2, "stiff.toml", "np2", &["--substructures", "2"]);
    let e = csv_difference(&case.dir.join("serial/contact.csv"), &case.dir.join("np2/contact.csv"));
    eprintln!("joints that deform, 2 ranks: contact.csv differs from serial by {e:.1e}");
    assert!(e < 1e-10, "{e:.2e}");
    let summary = common::json(&case.dir.join("np2/summary.json"));
    assert!(summary["contact"]["joint_stiffness"].is_array(), "the joints deform");
    assert_eq!(summary["contact"]["converged"], true);
}

/// Rigid joints that do not converge fall back to joints that deform
/// (src/driver/fallback.rs) on two ranks as on one: the two-set tunnel
/// given 12 iterations (it needs 16 rigid), rank 0 deciding for all.
#[test]
fn rigid_joints_that_fall_back_on_two_ranks_give_the_serial_answer() {
    let case = Case::new("mpi-fallback");
    let text = common::scenes::tunnel_two_sets(&case);
    case.write("tunnel.toml", &format!("{text}\n[solver]\nmax_cuts = 0\nmax_iterations = 12\n"));
    solve_ok(&case, 0, "tunnel.toml", "serial", &[]);
    solve_ok(&case, 2, "tunnel.toml", "np2", &[]);
    let e = csv_difference(&case.dir.join("serial/contact.csv"), &case.dir.join("np2/contact.csv"));
    eprintln!("the rigid fallback, 2 ranks: contact.csv differs from serial by {e:.1e}");
    assert!(e < 1e-10, "{e:.2e}");
    let summary = common::json(&case.dir.join("np2/summary.json"));
    assert_eq!(summary["contact"]["rigid_fallback"]["iterations"], 12, "{}", summary["contact"]);
    assert_eq!(summary["contact"]["converged"], true);
}

#[test]
fn the_iterative_interface_on_two_and_three_ranks_gives_the_serial_answer() {
    let case = Case::new("mpi-iterative");
    let scene = common::scenes::coarse_blocks(&case);
    let extra = ["--substructures", "2", "--interface", "iterative"];
    solve_ok(&case, 0, scene, "serial", &extra);
    for n in [2, 3] {
        let out = format!("np{n}");
        solve_ok(&case, n, scene, &out, &extra);
        let e = csv_difference(&case.dir.join("serial/contact.csv"), &case.dir.join(format!("{out}/contact.csv")));
        let summary = common::json(&case.dir.join(format!("{out}/summary.json")));
        let ranks = summary["ranks"].as_array().expect("ranks");
        let per_iteration: Vec<u64> =
            ranks.iter().map(|r| r["bytes_sent_per_contact_iteration"].as_u64().expect("bytes")).collect();
        eprintln!("iterative interface, {n} ranks: contact.csv differs from serial by {e:.1e}; bytes sent per contact iteration {per_iteration:?}");
        assert!(e < 1e-8, "{n} ranks: {e:.2e}");
        assert!(summary["counters"]["interface_applications"].as_u64().expect("applications") > 0);
        assert!(
            per_iteration[1..].iter().all(|&b| b > 0),
            "the other ranks send S d during the iteration: {per_iteration:?}"
        );
    }
}

#[test]
fn a_rock_mass_of_27_blocks_on_two_and_three_ranks_gives_the_serial_answer() {
    // the sparse interface: each rank condenses its blocks, rank 0 factorises the means
    let case = Case::new("mpi-blocks");
    case.copy("geo/rockmass.geo");
    let text = common::scenes::edited(
        "geo/rockmass.toml",
        &[
            (
                "setnumber = { n = 4, m = 2, hex = 1, serendipity = 1 }",
                "setnumber = { n = 3, m = 1, hex = 1, serendipity = 1 }",
            ),
            ("factors = [0.0, 1.0]", "factors = [0.5, 1.0]"),
        ],
    );
    case.write("mass.toml", &text);
    solve_ok(&case, 0, "mass.toml", "serial", &[]);
    for n in [2, 3] {
        let out = format!("np{n}");
        solve_ok(&case, n, "mass.toml", &out, &[]);
        let e = csv_difference(&case.dir.join("serial/contact.csv"), &case.dir.join(format!("{out}/contact.csv")));
        let summary = common::json(&case.dir.join(format!("{out}/summary.json")));
        eprintln!("rock mass, {n} ranks: contact.csv differs from serial by {e:.1e}");
        assert_eq!(summary["interface_solver"], "sparse");
        assert_eq!(summary["ranks"].as_array().map(Vec::len), Some(n), "every rank reports");
        assert!(e < 1e-8, "{n} ranks: {e:.2e}");
    }
}

#[test]
fn more_ranks_than_parts_are_refused_saying_what_to_do() {
    // block on block: two parts (the dam, once two, has a part per block since joints cut blocks)
    let case = Case::new("mpi-too-many");
    let scene = common::scenes::coarse_blocks(&case);
    let o = mpirun(&case, 3, &["solve", scene, "--out", "out", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert_eq!(err.matches("error:").count(), 1, "one message: {err}");
    for want in ["3 MPI ranks", "2 part(s)", "substructures", "at most 2 rank(s)"] {
        assert!(err.contains(want), "says {want:?}: {err}");
    }
    assert!(no_results(&case, "out"), "no results");
}

#[test]
fn a_failure_on_any_rank_ends_every_rank_with_one_message_and_no_results() {
    let case = Case::new("mpi-fail");
    case.copy("geo/blocks3d.geo");
    // the upper block pulled off the lower one: held by nothing once the joint opens
    let text = common::scenes::edited(
        "geo/blocks3d.toml",
        &[
            ("setnumber = { lc = 0.1, hex = 0 }", "setnumber = { lc = 0.25, hex = 0 }"),
            ("traction = [0.3, 0.0, -1.0]", "traction = [0.0, 0.0, 1.0]"),
        ],
    );
    case.write("pulled.toml", &text);
    for interface in ["dense", "iterative"] {
        let o = mpirun(
            &case,
            2,
            &["solve", "pulled.toml", "--out", "out", "--quiet", "--substructures", "2", "--interface", interface],
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{interface}");
        assert_eq!(err.matches("error:").count(), 1, "{interface}: one message: {err}");
        assert!(err.contains("held by nothing"), "{interface}: {err}");
        assert!(!err.contains("panicked"), "{interface}: {err}");
        assert!(no_results(&case, "out"), "{interface}: no results");
    }
}

/// The mesh cache under MPI (issue 32): rank 0 runs gmsh into the run's
/// staging directory; a `.geo` that gmsh refuses ends every rank with one
/// message and leaves no `mesh/`, no result and no staging directory, and
/// the next good run into the same directory meshes and commits.
#[test]
fn a_failed_geo_on_two_ranks_leaves_no_mesh_and_no_stage() {
    let case = Case::new("mpi-bad-geo");
    let geo = common::repo_text("geo/blocks3d.geo");
    case.write("blocks3d.geo", &geo);
    case.write("broken.geo", &format!("{geo}\nLine(9999) = {{1, 2\n"));
    let scene = common::scenes::edited(
        "geo/blocks3d.toml",
        &[("setnumber = { lc = 0.1, hex = 0 }", "setnumber = { lc = 0.25, hex = 0 }")],
    );
    case.write("good.toml", &scene);
    case.write("bad.toml", &scene.replace("mesh = \"blocks3d.geo\"", "mesh = \"broken.geo\""));
    let o = mpirun(&case, 2, &["solve", "bad.toml", "--out", "out", "--quiet", "--substructures", "2"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert_eq!(err.matches("error:").count(), 1, "one message: {err}");
    common::cli::says(&err, &["gmsh failed on", "broken.geo", "fix the .geo"]);
    assert!(!err.contains("panicked"), "{err}");
    let out = case.dir.join("out");
    assert!(case.files_in(&out).is_empty(), "left in out/: {:?}", case.files_in(&out));
    assert!(!out.join("mesh").exists(), "out/mesh left");
    let beside = |case: &Case| -> Vec<String> {
        (std::fs::read_dir(&case.dir).expect("dir").flatten())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".out.") && n != ".out.lock")
            .collect()
    };
    assert!(beside(&case).is_empty(), "staging directories left: {:?}", beside(&case));
    solve_ok(&case, 2, "good.toml", "out", &["--substructures", "2"]);
    assert!(out.join("mesh/good.msh").is_file(), "{:?}", case.files_in(&out));
    assert!(beside(&case).is_empty(), "staging directories left: {:?}", beside(&case));
}

/// The safety search (issue 18) on ranks: rank 0 runs the trials while the
/// others apply their parts' S (iterative) or wait (dense); the factor and
/// the last state that holds are the serial ones, and a scene unsafe as
/// given fails on every rank with the serial message.
#[test]
fn the_safety_search_on_two_ranks_gives_the_serial_factor() {
    let case = Case::new("mpi-safety");
    case.copy("geo/dam.geo");
    case.copy("geo/dam.toml");
    let factor = |out: &str| {
        common::json(&case.dir.join(out).join("summary.json"))["safety"]["factor"].as_f64().expect("a factor")
    };
    for interface in ["dense", "iterative"] {
        let serial = format!("serial_{interface}");
        let args = |out: &str| {
            vec![
                "safety".to_string(),
                "dam.toml".into(),
                "--out".into(),
                out.to_string(),
                "--quiet".into(),
                "--substructures".into(),
                "2".into(),
                "--interface".into(),
                interface.into(),
            ]
        };
        let o = case.cli(&args(&serial).iter().map(String::as_str).collect::<Vec<_>>());
        assert!(o.status.success(), "serial: {}", String::from_utf8_lossy(&o.stderr));
        let np2 = format!("np2_{interface}");
        let o = mpirun(&case, 2, &args(&np2).iter().map(String::as_str).collect::<Vec<_>>());
        assert!(o.status.success(), "2 ranks: {}", String::from_utf8_lossy(&o.stderr));
        let (fs, fm) = (factor(&serial), factor(&np2));
        let e = csv_difference(
            &case.dir.join(format!("{serial}/safety_contact.csv")),
            &case.dir.join(format!("{np2}/safety_contact.csv")),
        );
        eprintln!("safety, {interface} interface: F = {fs} serial, {fm} on 2 ranks; last state differs by {e:.1e}");
        assert!((fs - fm).abs() <= 1e-3 * fs, "{interface}: F {fs} against {fm}");
        assert!(e < 1e-6, "{interface}: the last state that holds: {e:e}");
    }
    // unsafe as given: the dam's base with a tenth of its friction
    case.write(
        "weak.toml",
        &common::read(&case.dir.join("dam.toml")).replacen("friction = 0.75", "friction = 0.075", 1),
    );
    let o = mpirun(&case, 2, &["safety", "weak.toml", "--out", "weak", "--quiet", "--substructures", "2"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && !err.contains("panicked"), "{err}");
    assert_eq!(err.matches("error:").count(), 1, "one message: {err}");
    common::cli::says(&err, &["weak.toml: unsafe as given", "\"block_1\"", "below 1: F = 0.", "the results in weak"]);
    // what exists is written (issue 29): the failing step's last iterate, the mechanism
    let summary = common::json(&case.dir.join("weak/summary.json"));
    assert_eq!(summary["safety"]["below_one"].as_bool(), Some(true));
    assert!(case.dir.join("weak/blocks.csv").is_file() && case.dir.join("weak/mechanism.png").is_file());
}

/// Whether `dir` of `case` holds nothing but mesh caches (the mesh, its key,
/// a manifest listing only those, locks): what a failed run may leave.
fn no_results(case: &Case, dir: &str) -> bool {
    let dir = case.dir.join(dir);
    case.files_in(&dir).iter().all(|f| common::cli::mesh_cache(&dir, f))
}
