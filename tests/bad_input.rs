//! Bad input through the real binary (DESIGN.md §4, "Command line"): every
//! mistake a user can make in a scene, its mesh or the command line ends with
//! exit status 1 and a one-paragraph `error: ...` on stderr that names the
//! culprit (file, key or physical group) and says what to do — no panic, no
//! backtrace, nothing on stdout, and no result file (.vtu, .csv, .json, .md)
//! in the results directory. The mesh cache (`<out>/mesh/*.msh`, `.msh.key`)
//! is an input and may stay. Scenes are the paper's cylinder (coarsened to
//! lc = 0.2) with one thing broken, or two stacked blocks; meshes come from
//! the real gmsh CLI.

mod common;

use common::cli::{clean_failure, gmsh, says};
use common::{repo_text, scenes, Case};

/// The repository's cylinder scene, coarsened, with `edits` applied (each
/// `from` must occur; the first occurrence is replaced), written as
/// `<name>.toml` next to a copy of cylinder.geo. Returns the scene's file name.
fn cylinder(case: &Case, name: &str, edits: &[(&str, &str)]) -> String {
    case.copy("geo/cylinder.geo");
    let edits: Vec<(&str, &str)> = [("lc = 0.05", "lc = 0.2")].iter().chain(edits).copied().collect();
    let file = format!("{name}.toml");
    case.write(&file, &scenes::edited("geo/cylinder.toml", &edits));
    file
}

/// Two unit squares stacked: "ground" (below) and "block" (above) meeting on
/// the curve "joint"; "base" is y = 0, "top" is y = 2.
const BLOCKS_GEO: &str = r#"
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Point(5) = {1, 2, 0}; Point(6) = {0, 2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
Transfinite Curve{:} = 5; Transfinite Surface{1, 2}; Recombine Surface{1, 2};
Physical Surface("ground") = {1};
Physical Surface("block") = {2};
Physical Curve("base") = {1};
Physical Curve("joint") = {3};
Physical Curve("top") = {6};
"#;

const BLOCKS_MATERIAL: &str =
    "mesh = \"blocks.geo\"\nanalysis = \"plane_strain\"\n[materials.rock]\nE = 1000.0\nnu = 0.25\n";

/// Runs `subcontact solve SCENE --out out --quiet` in the case and checks the
/// failure is clean; returns the message.
fn solve_fails(case: &Case, scene: &str) -> String {
    common::cli::solve_fails(case, scene, "out")
}

#[test]
fn unknown_body_group_is_named_with_the_groups_the_mesh_has() {
    let case = Case::new("bad-body-group");
    let scene = cylinder(&case, "bad", &[("\"body_2\"", "\"body_3\"")]);
    let msg = solve_fails(&case, &scene);
    says(
        &msg,
        &[
            "bad.toml",
            "bodies[1].group",
            "\"body_3\"",
            "not a physical group",
            "\"body_2\" (surface)",
            "Check the name",
        ],
    );
}

#[test]
fn unknown_support_group_is_named() {
    let case = Case::new("bad-support-group");
    let scene = cylinder(&case, "bad", &[("\"symmetry_x0\"", "\"symmetry_x1\"")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "supports[0].group", "\"symmetry_x1\"", "\"symmetry_x0\" (curve)", "Check the name"]);
}

#[test]
fn unknown_load_group_is_named() {
    let case = Case::new("bad-load-group");
    let scene = cylinder(&case, "bad", &[("group = \"inner\"", "group = \"innr\"")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "loads[0].group", "\"innr\"", "\"inner\" (curve)", "Check the name"]);
}

#[test]
fn misspelt_key_frction_is_named_with_its_line_and_the_expected_keys() {
    let case = Case::new("bad-frction");
    let scene = cylinder(&case, "bad", &[("friction = 0.8", "frction = 0.8")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "line ", "contacts[0]", "frction", "`friction`", "correct the spelling"]);
}

#[test]
fn misspelt_interface_solver_is_named_with_the_choices() {
    let case = Case::new("bad-interface");
    let scene = cylinder(&case, "bad", &[("friction = 0.8", "friction = 0.8\n[solver]\ninterface = \"iterativ\"")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "solver", "iterativ", "`auto`", "`dense`", "`iterative`"]);
}

#[test]
fn poisson_ratio_of_one_half_is_rejected_suggesting_0_499() {
    let case = Case::new("bad-nu");
    let scene = cylinder(&case, "bad", &[("nu = 0.167", "nu = 0.5")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "materials.concrete.nu", "0.5", "incompressible", "use 0.499"]);
}

#[test]
fn negative_young_modulus_is_rejected() {
    let case = Case::new("bad-e");
    let scene = cylinder(&case, "bad", &[("E = 2.0e5", "E = -2.0e5")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "materials.concrete.E", "-200000", "> 0"]);
}

#[test]
fn young_modulus_beyond_double_precision_is_rejected_saying_to_change_units() {
    // (1e-310 is subnormal: the solve ended in NaN displacements blamed on
    // the loads; 1.7e308 in "not held ... add a support")
    let case = Case::new("bad-e-range");
    for (e, shown) in [("1e-310", "= 1e-310"), ("1.7e308", "= 1.7e308")] {
        let scene = cylinder(&case, "bad", &[("E = 2.0e5", &format!("E = {e}"))]);
        let msg = solve_fails(&case, &scene);
        says(
            &msg,
            &["bad.toml", "materials.concrete.E", shown, "between 1e-300 and 1e300", "double precision", "other units"],
        );
    }
}

#[test]
fn missing_mesh_file_is_named() {
    let case = Case::new("bad-no-mesh");
    let scene = cylinder(
        &case,
        "bad",
        &[("mesh = \"cylinder.geo\"", "mesh = \"nothere.msh\""), ("[gmsh]\norder = 2\nsetnumber = { lc = 0.2 }\n", "")],
    );
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "mesh", "nothere.msh", "does not exist", "correct the path"]);
}

#[test]
fn truncated_msh_ascii_or_binary_is_reported_as_truncated() {
    let case = Case::new("bad-truncated");
    case.copy("geo/cylinder.geo");
    for (file, binary) in [("x.msh", false), ("xb.msh", true)] {
        let full = format!("full-{file}");
        let mut args =
            vec!["cylinder.geo", "-2", "-order", "2", "-setnumber", "lc", "0.2", "-format", "msh41", "-o", &full];
        if binary {
            args.push("-bin");
        }
        gmsh(&case, &args);
        let bytes = std::fs::read(case.dir.join(&full)).expect("gmsh's mesh");
        std::fs::write(case.dir.join(file), &bytes[..bytes.len() / 2]).expect("truncated mesh");
        let scene = cylinder(
            &case,
            "bad",
            &[
                ("mesh = \"cylinder.geo\"", &format!("mesh = \"{file}\"")),
                ("[gmsh]\norder = 2\nsetnumber = { lc = 0.2 }\n", ""),
            ],
        );
        let msg = solve_fails(&case, &scene);
        says(&msg, &[file, "not a complete MSH 4.1 file", "truncated", "Mesh the .geo again"]);
    }
}

#[test]
fn block_held_only_by_a_contact_that_opens_is_named() {
    // The block is pulled off the ground: its only contact opens and nothing
    // else holds it; the paper's scheme would divide by zero here.
    let case = Case::new("bad-block-pulled-off");
    case.write("blocks.geo", BLOCKS_GEO);
    let scene = BLOCKS_MATERIAL.to_string()
        + "[[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\n[[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\
           [[contacts]]\ngroup = \"joint\"\nfriction = 0.5\n\
           [[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n\
           [[loads]]\ngroup = \"top\"\ntraction = [0.0, 1.0]\n";
    case.write("blocks.toml", &scene);
    let msg = solve_fails(&case, "blocks.toml");
    says(&msg, &["blocks.toml", "body \"block\"", "held by nothing", "open", "Add a support"]);
    assert!(!msg.contains("\"ground\""), "only the block is loose:\n{msg}");
}

#[test]
fn body_without_any_support_is_named() {
    let case = Case::new("bad-no-support");
    case.write("blocks.geo", BLOCKS_GEO);
    let scene = BLOCKS_MATERIAL.to_string()
        + "[[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\n[[loads]]\ngroup = \"joint\"\npressure = 1.0\n";
    case.write("ground.toml", &scene);
    let msg = solve_fails(&case, "ground.toml");
    says(&msg, &["body \"ground\"", "not held", "Add a support"]);
}

#[test]
fn cylinder_without_its_x_symmetry_support_is_reported_not_solved() {
    // Only y = 0 holds anything; x translation of the whole quarter is free.
    // At lc = 0.2 the interface solve notices, but blames friction and names
    // no body; at lc = 0.05 nothing notices.
    let case = Case::new("bad-partial-support");
    for lc in ["lc = 0.2", "lc = 0.05"] {
        let scene =
            cylinder(&case, "bad", &[("lc = 0.2", lc), ("[[supports]]\ngroup = \"symmetry_x0\"\nfix = [\"x\"]\n", "")]);
        let msg = solve_fails(&case, &scene);
        says(&msg, &["bad.toml", "body_1", "body_2", "Add a support"]);
    }
}

#[test]
fn geo_syntax_error_reports_gmsh_errors_and_the_file() {
    let case = Case::new("bad-geo-syntax");
    let geo = repo_text("geo/cylinder.geo");
    assert!(geo.contains("Line(3) = {5, 4};"), "geo/cylinder.geo changed: update this test");
    case.write("bad_syntax.geo", &geo.replacen("Line(3) = {5, 4};", "Line(3) = {5, 4", 1));
    let scene = cylinder(&case, "bad", &[("mesh = \"cylinder.geo\"", "mesh = \"bad_syntax.geo\"")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["gmsh failed on", "bad_syntax.geo", "syntax error", "fix the .geo"]);
    assert!(case.files_in(&case.dir.join("out")).is_empty(), "a failed gmsh must leave no mesh behind");
}

#[test]
fn curve_used_as_body_is_a_wrong_dimension_error() {
    let case = Case::new("bad-dimension");
    let scene = cylinder(&case, "bad", &[("\"body_2\"", "\"outer\"")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["bad.toml", "bodies[1].group", "\"outer\"", "physical curve", "surface is needed"]);
}

#[test]
fn empty_physical_group_is_named_as_empty() {
    let case = Case::new("bad-empty-group");
    let geo = repo_text("geo/cylinder.geo");
    // gmsh 4.8.4 keeps the name in $PhysicalNames, without elements and without a word.
    case.write("ghost.geo", &(geo + "Physical Surface(\"ghost\") = {99};\nPhysical Curve(\"ghost_curve\") = {99};\n"));
    for (edit, key, group) in [
        (("\"body_2\"", "\"ghost\""), "bodies[1].group", "\"ghost\""),
        (("\"symmetry_x0\"", "\"ghost_curve\""), "supports[0].group", "\"ghost_curve\""),
    ] {
        let scene = cylinder(&case, "bad", &[("mesh = \"cylinder.geo\"", "mesh = \"ghost.geo\""), edit]);
        let msg = solve_fails(&case, &scene);
        says(&msg, &["bad.toml", key, group, "without elements", "Check the entity numbers"]);
    }
}

#[test]
fn plane_analysis_on_a_3d_mesh_says_to_use_solid() {
    let case = Case::new("bad-plane-on-3d");
    case.copy("geo/cylinder_paper.geo");
    gmsh(&case, &["cylinder_paper.geo", "-3", "-format", "msh41", "-o", "paper3d.msh"]);
    let base = repo_text("geo/cylinder_paper.toml");
    // the .geo meshed as a plane analysis asks (gmsh -2), and a 3D .msh
    for mesh in ["cylinder_paper.geo", "paper3d.msh"] {
        for from in [
            "analysis = \"solid\"",
            "from = [2.956414504, 1.224586984, 0.5]",
            "to = [4.434621756, 1.836880476, 0.5]",
            "[[supports]]\ngroup = \"faces_z\"\nfix = [\"z\"]\n",
        ] {
            assert!(base.contains(from), "geo/cylinder_paper.toml changed: update this test ({from:?})");
        }
        let mut text = base
            .replace("analysis = \"solid\"", "analysis = \"plane_strain\"")
            .replace(", 1.224586984, 0.5]", ", 1.224586984]")
            .replace(", 1.836880476, 0.5]", ", 1.836880476]")
            .replace("[[supports]]\ngroup = \"faces_z\"\nfix = [\"z\"]\n", "")
            .replace("mesh = \"cylinder_paper.geo\"", &format!("mesh = \"{mesh}\""));
        if mesh.ends_with(".msh") {
            text = text.replace("[gmsh]\norder = 1\n", ""); // a .msh takes no [gmsh] options
        }
        case.write("bad.toml", &text);
        let msg = solve_fails(&case, "bad.toml");
        says(&msg, &["bad.toml", "analysis", "plane_strain", "3D", "analysis = \"solid\""]);
    }
}

#[test]
fn missing_scene_file_is_named_once() {
    let case = Case::new("bad-no-scene");
    let msg = solve_fails(&case, "missing.toml");
    says(&msg, &["missing.toml", "cannot read the scene file", "Check the path"]);
    assert_eq!(msg.matches("No such file or directory").count(), 1, "the cause is repeated:\n{msg}");
}

#[test]
fn help_lists_solve_check_and_paper() {
    let case = Case::new("help");
    let out = case.cli(&["--help"]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in ["Usage: subcontact", "solve", "check", "paper", "--help", "summary.json"] {
        assert!(text.contains(needle), "--help lacks {needle:?}:\n{text}");
    }
    let out = case.cli(&["solve", "--help"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("--out") && text.contains("<SCENE>"), "{text}");
}

#[test]
fn zero_substructures_or_threads_are_refused_by_the_command_line() {
    let case = Case::new("bad-counts");
    case.copy("geo/cylinder.geo");
    case.copy("geo/cylinder.toml");
    for (flag, value) in [("--substructures", "0"), ("--threads", "0"), ("--threads", "two")] {
        let out = case.cli(&["solve", "cylinder.toml", flag, value]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{flag} {value} was accepted");
        says(&err, &[flag]);
        assert!(err.contains("at least 1") || err.contains("not a whole number"), "{flag} {value}: {err}");
        assert!(!case.dir.join("results/cylinder/summary.json").exists(), "{flag} {value} wrote results");
    }
}

#[test]
fn check_passes_on_the_cylinder_and_writes_no_results() {
    let case = Case::new("check-ok");
    case.copy("geo/cylinder.geo");
    case.copy("geo/cylinder.toml");
    let out = case.cli(&["check", "cylinder.toml"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "check failed: {}", String::from_utf8_lossy(&out.stderr));
    says(&stdout, &["cylinder.toml", "consistent", "2 bodies", "81 contact pairs"]);
    let results = case.dir.join("results");
    let files = case.files_in(&results);
    assert!(files.iter().all(|f| common::cli::mesh_cache(&results, f)), "check wrote results: {files:?}");
    assert!(files.contains(&"cylinder/mesh/cylinder.msh".to_string()), "check keeps the mesh: {files:?}");
}

#[test]
fn check_fails_cleanly_on_a_bad_scene() {
    let case = Case::new("check-bad");
    let scene = cylinder(&case, "bad", &[("\"body_2\"", "\"body_3\"")]);
    let out = case.cli(&["check", &scene]);
    let msg = clean_failure(&case, &out, &case.dir.join("results"));
    says(&msg, &["bad.toml", "bodies[1].group", "\"body_3\"", "Check the name"]);
    let scene = cylinder(&case, "bad2", &[("nu = 0.167", "nu = 0.5")]);
    let out = case.cli(&["check", &scene]);
    let msg = clean_failure(&case, &out, &case.dir.join("results"));
    says(&msg, &["bad2.toml", "materials.concrete.nu", "0.499"]);
}

/// Issue 19: a contact group that misses the other body named one body and
/// the first facet it met, however far from the other body that was. A
/// block on a ground block (tests/geo/block_on_ground.geo), contact groups
/// as users get them wrong: the message names both bodies, says whether the
/// group takes in faces of two bodies or outer faces, and hints at
/// BooleanFragments only when the two were meshed apart.
#[test]
fn a_contact_group_that_misses_the_other_body_says_how() {
    let case = Case::new("contact-group-misses");
    case.copy("tests/geo/block_on_ground.geo");
    let scene = |name: &str, fragments: u8, contact: &str| {
        let text = format!(
            "mesh = \"block_on_ground.geo\"\nanalysis = \"solid\"\n[gmsh]\norder = 1\nsetnumber = {{ lc = 0.5, fragments = {fragments} }}\n\
             [materials.rock]\nE = 100.0\nnu = 0.3\n[[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\n[[bodies]]\ngroup = \"block\"\nmaterial = \"rock\"\n\
             [[contacts]]\n{contact}\nfriction = 0.5\n[[supports]]\ngroup = \"bottom\"\nfix = [\"x\", \"y\", \"z\"]\n"
        );
        case.write(&format!("{name}.toml"), &text);
        let msg = solve_fails(&case, &format!("{name}.toml"));
        eprintln!("{name}: {msg}");
        msg
    };
    // the ground's top, meshed apart from the block: most of it lies far
    // from the block, but some of it against the block's base
    let msg = scene("apart", 0, "group = \"ground_top\"");
    says(
        &msg,
        &[
            "apart.toml",
            "contacts[0].group",
            "\"ground_top\"",
            "touches only body \"ground\"",
            "lies against body \"block\"",
            "does not share its nodes",
            "BooleanFragments",
        ],
    );
    // the same with shared nodes: the group takes in the ground's outer top
    let msg = scene("outer", 1, "group = \"ground_top\"");
    says(
        &msg,
        &[
            "outer.toml",
            "\"ground_top\"",
            "touch only one body",
            "body \"ground\"",
            "between two bodies",
            "Leave its outer faces out",
        ],
    );
    assert!(!msg.contains("BooleanFragments"), "the bodies share their nodes: no advice to fragment them: {msg}");
    // one side of groups = [..] takes in faces of two bodies
    let msg = scene("two_bodies", 1, "groups = [\"outer_tops\", \"block_base\"]");
    says(
        &msg,
        &[
            "two_bodies.toml",
            "contacts[0].groups[0]",
            "\"outer_tops\" bounds body \"block\" and body \"ground\"",
            "each group is the face of one body",
        ],
    );
    // one side of groups = [..] is the face the two bodies share
    let msg = scene("shared", 1, "groups = [\"ground_top\", \"block_base\"]");
    says(
        &msg,
        &[
            "shared.toml",
            "\"ground_top\" lies between body \"ground\" and body \"block\"",
            "share its nodes",
            "group = \"ground_top\"",
        ],
    );
}

/// A misspelt `[gmsh] setnumber` name was ignored (issue 32: `lcc = 0.02`
/// meshed at the default size, 1,576 DOFs instead of 34,448, exit 0):
/// refused, naming the names the .geo defines, before gmsh runs.
#[test]
fn a_setnumber_name_the_geo_does_not_define_is_refused() {
    let case = Case::new("bad-setnumber");
    let scene = cylinder(&case, "lcc", &[("setnumber = { lc = 0.2 }", "setnumber = { lcc = 0.02 }")]);
    let msg = solve_fails(&case, &scene);
    says(&msg, &["[gmsh] setnumber", "`lcc`", "cylinder.geo", "DefineConstant): lc"]);
    assert!(!case.dir.join("results/lcc/mesh").exists(), "gmsh ran");
}

/// A .geo's SystemCall ran (issue 32); now refused unless allowed.
#[test]
fn shell_commands_in_a_geo_are_refused_unless_allowed() {
    let case = Case::new("bad-geo-commands");
    let scene = cylinder(&case, "calls", &[]);
    let geo = std::fs::read_to_string(case.dir.join("cylinder.geo")).expect("geo");
    let touched = case.dir.join("ran-a-shell");
    case.write("cylinder.geo", &format!("{geo}\nSystemCall \"touch {}\";\n", touched.display()));
    let msg = solve_fails(&case, &scene);
    says(&msg, &["cylinder.geo", "SystemCall (line", "--allow-geo-commands"]);
    assert!(!touched.exists());
    let o = case.cli(&["check", &scene, "--allow-geo-commands"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(touched.exists(), "allowed, the command runs");
}

/// Messages that named the wrong thing (issue 32): a count too large ended
/// in "out of memory … try --interface iterative", a thickness of 1e308 in
/// "not held", a scene that is /dev/zero in out of memory, a .msh path that
/// is a directory in "does not exist", an empty .geo blamed the cached .msh.
#[test]
fn counts_sizes_and_paths_beyond_reason_are_named_for_what_they_are() {
    let case = Case::new("bad-beyond");
    for (name, edit, needles) in [
        (
            "steps",
            ("[[probes]]", "[solver]\nload_steps = 1000000000000\n\n[[probes]]"),
            &["solver.load_steps", "at most 100000"][..],
        ),
        ("points", ("points = 5", "points = 1000000000000"), &["probes[0].points", "at most 1000000"][..]),
        ("thick", ("thickness = 1.0", "thickness = 1e308"), &["thickness", "1e100", "other units"][..]),
    ] {
        let scene = cylinder(&case, name, &[edit]);
        let msg = solve_fails(&case, &scene);
        says(&msg, needles);
        assert!(!msg.contains("memory") && !msg.contains("not held"), "{msg}");
    }
    let o = case.cli(&["solve", "/dev/zero", "--out", "zero", "--quiet"]);
    let msg = clean_failure(&case, &o, &case.dir.join("zero"));
    says(&msg, &["/dev/zero", "not a plain file"]);
    // a .msh path that is a directory
    std::fs::create_dir_all(case.dir.join("folder.msh")).expect("dir");
    let scene = cylinder(
        &case,
        "folder",
        &[("mesh = \"cylinder.geo\"", "mesh = \"folder.msh\""), ("[gmsh]\norder = 2\nsetnumber = { lc = 0.2 }\n", "")],
    );
    let msg = solve_fails(&case, &scene);
    says(&msg, &["folder.msh", "is a directory"]);
    assert!(!msg.contains("does not exist"), "{msg}");
    // an empty .geo
    case.write("empty.geo", "// nothing yet\n");
    let scene = cylinder(
        &case,
        "empty",
        &[("mesh = \"cylinder.geo\"", "mesh = \"empty.geo\""), ("setnumber = { lc = 0.2 }", "")],
    );
    let msg = solve_fails(&case, &scene);
    says(&msg, &["gmsh made no mesh of", "empty.geo", "Physical"]);
    assert!(!msg.contains("empty.msh"), "{msg}");
}
