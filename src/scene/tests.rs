//! Scene unit tests: the full example of DESIGN.md §4 parses, defaults are
//! applied, and every rule rejects with a one-paragraph message that names
//! the scene file, the key path and what to do.

use super::*;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

mod water;

/// The full example of DESIGN.md §4.
const EXAMPLE: &str = r#"
title    = "Thick-walled cylinder, quarter model"
mesh     = "cylinder.geo"      # .geo (meshed by the gmsh CLI) or .msh; relative to this file
analysis = "plane_strain"      # plane_strain | plane_stress | axisymmetric | solid
thickness = 1.0                # plane analyses only

[gmsh]                          # used when mesh is a .geo
order = 2                       # element order (gmsh -order)
setnumber = { lc = 0.2 }        # gmsh -setnumber NAME VALUE

[materials.rock]
E = 2.0e5
nu = 0.167
density = 0.0                   # optional, with top-level gravity = [gx, gy, gz]

[[bodies]]                      # one substructure per entry
group = "body_1"                # physical surface (2D) / volume (3D)
material = "rock"

[[contacts]]
group = "A-A"                   # one physical curve/surface shared by two bodies,
# groups = ["face_1", "face_2"] # or two groups whose nodes coincide pairwise
friction = 0.8
cohesion = 2.0e4
tensile_strength = 3.0e5
slip = "coulomb"                # coulomb (default) | frictionless (the paper)

[[supports]]
group = "symmetry_x0"           # a physical point, curve or surface
fix = ["x"]                     # components held at zero; or prescribe: ux = 0.001 (uy, uz)

[[loads]]
group = "inner_surface"
pressure = 0.1                  # positive presses into the body; or traction = [tx, ty(, tz)]

[solver]
load_steps = 1
max_iterations = 100

[[probes]]                      # sample the solution along a line
name = "radial"
from = [2.7716, 1.1481]
to   = [4.6194, 1.9134]
points = 6

[analytic]                      # optional known solution, for error norms
kind = "lame_cylinder"
a = 3.0
b = 5.0
p = 0.1
"#;

/// A fresh directory holding `cylinder.geo`, `cylinder.msh` and `cyl.toml`
/// (the latter with `text`); returns the scene path.
fn write_scene(text: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "subcontact_scene_test_{}_{}",
        std::process::id(),
        N.fetch_add(1, Ordering::SeqCst)
    ));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("cylinder.geo"), "// test\n").expect("write geo");
    std::fs::write(dir.join("cylinder.msh"), "").expect("write msh");
    let path = dir.join("cyl.toml");
    std::fs::write(&path, text).expect("write scene");
    path
}

/// Remove the directory `write_scene` made for `path`.
fn clean(path: &Path) {
    if let Some(dir) = path.parent() {
        let _ = std::fs::remove_dir_all(dir);
    }
}

fn load(text: &str) -> Result<Scene, SceneError> {
    let path = write_scene(text);
    let r = Scene::load(&path);
    clean(&path);
    r
}

/// A minimal valid 2D scene plus `extra` appended.
fn minimal(extra: &str) -> String {
    format!(
        "mesh = \"cylinder.geo\"\nanalysis = \"plane_strain\"\n[materials.rock]\nE = 1.0\nnu = 0.2\n[[bodies]]\ngroup = \"b1\"\nmaterial = \"rock\"\n{extra}"
    )
}

fn minimal_solid(extra: &str) -> String {
    minimal(extra).replace("plane_strain", "solid")
}

/// Expect an error whose message names the scene file and each of `needles`.
fn rejects(text: &str, needles: &[&str]) -> String {
    let path = write_scene(text);
    let result = Scene::load(&path);
    clean(&path);
    let msg = match result {
        Ok(_) => panic!("accepted, expected an error mentioning {needles:?}:\n{text}"),
        Err(e) => e.to_string(),
    };
    assert!(msg.starts_with(&path.display().to_string()), "does not start with the file name: {msg}");
    for n in needles {
        assert!(msg.contains(n), "message lacks {n:?}: {msg}");
    }
    assert!(!msg.contains('\n'), "not one paragraph: {msg}");
    msg
}

#[test]
fn design_example_parses() {
    let path = write_scene(EXAMPLE);
    let s = Scene::load(&path).expect("example scene");
    assert_eq!(s.name, "cyl");
    assert_eq!(s.title, "Thick-walled cylinder, quarter model");
    assert_eq!(s.mesh, MeshSource::Geo(path.parent().unwrap().join("cylinder.geo")));
    assert_eq!(s.analysis, Analysis::PlaneStrain);
    assert_eq!(s.analysis.dim(), 2);
    assert_eq!(s.thickness, 1.0);
    assert_eq!(
        s.gmsh,
        GmshOptions { order: 2, setnumber: vec![("lc".into(), 0.2)], clscale: None, timeout: 600.0, structured: false }
    );
    let rock = Material { e: 2.0e5, nu: 0.167, density: 0.0 };
    assert_eq!(s.materials["rock"], rock);
    let body_1 = BodySpec { key: "bodies[0]".into(), group: "body_1".into(), material: rock, initial: None };
    assert_eq!(s.bodies, vec![body_1]);
    assert_eq!(
        s.contacts,
        vec![Contact {
            groups: ContactGroups::Shared("A-A".into()),
            strength: Strength { friction: 0.8, cohesion: 2.0e4, tensile_strength: 3.0e5, residual_cohesion: 0.0 },
            slip: SlipLaw::Coulomb,
            stiffness: None,
            residual_given: false,
            traction: TractionRecovery::Lumped,
            water: None,
        }]
    );
    assert_eq!(
        s.supports,
        vec![SupportSpec {
            key: "supports[0]".into(),
            group: "symmetry_x0".into(),
            fix: [true, false, false],
            prescribed: [None; 3]
        }]
    );
    let inner = LoadSpec {
        key: "loads[0]".into(),
        group: "inner_surface".into(),
        kind: LoadKind::Pressure(0.1),
        factors: None,
    };
    assert_eq!(s.loads, vec![inner]);
    assert_eq!(s.solver, Solver::default());
    assert_eq!(
        s.probes,
        vec![Probe { name: "radial".into(), from: [2.7716, 1.1481, 0.0], to: [4.6194, 1.9134, 0.0], points: 6 }]
    );
    assert_eq!(s.analytic, Some(Analytic::LameCylinder { a: 3.0, b: 5.0, p: 0.1 }));
    assert_eq!(s.output, Output::default());
    // parse() from a string gives the same scene.
    assert_eq!(Scene::parse(EXAMPLE, &path).expect("parse"), s);
    clean(&path);
}

#[test]
fn defaults_applied() {
    let s = load(&minimal("[[contacts]]\ngroup = \"i\"\n")).expect("minimal scene");
    assert_eq!(s.title, "cyl");
    assert_eq!(s.thickness, 1.0);
    assert_eq!(s.gravity, [0.0; 3]);
    assert_eq!(s.gmsh, GmshOptions { order: 1, setnumber: vec![], clscale: None, timeout: 600.0, structured: false });
    assert_eq!(s.materials["rock"].density, 0.0);
    let c = &s.contacts[0];
    assert_eq!(c.strength, Strength { friction: 0.0, cohesion: 0.0, tensile_strength: 0.0, residual_cohesion: 0.0 });
    assert_eq!(c.slip, SlipLaw::Coulomb);
    assert_eq!(s.solver, Solver::default());
    assert!(s.supports.is_empty() && s.loads.is_empty() && s.probes.is_empty());
    assert_eq!(s.analytic, None);
    assert_eq!(s.output.fields, vec!["displacement".to_string(), "stress".to_string()]);
    assert!(s.output.wants("stress"));
}

#[test]
fn other_forms_accepted() {
    let s = load(&("gravity = [0, 0, -9.81]\n".to_string() + &minimal_solid(
        "[[contacts]]\ngroups = [\"f1\", \"f2\"]\nslip = \"frictionless\"\ncohesion = 2\nresidual_cohesion = 1\n\
         [[supports]]\ngroup = \"s\"\nfix = [\"x\", \"z\"]\nuy = -0.001\n[[loads]]\ngroup = \"top\"\ntraction = [0, 0, -1]\n\
         [gmsh]\nclscale = 0.5\nsetnumber = { n = 4, lc = 0.1 }\n[output]\nfields = [\"stress\"]\n",
    )))
    .expect("solid scene");
    assert_eq!(s.gravity, [0.0, 0.0, -9.81]);
    assert_eq!(s.analysis.dim(), 3);
    assert_eq!(s.contacts[0].groups, ContactGroups::Pair("f1".into(), "f2".into()));
    assert_eq!(s.contacts[0].slip, SlipLaw::Frictionless);
    assert_eq!(s.supports[0].fix, [true, false, true]);
    assert_eq!(s.supports[0].prescribed, [None, Some(-0.001), None]);
    assert_eq!(s.loads[0].kind, LoadKind::Traction([0.0, 0.0, -1.0]));
    assert_eq!(s.gmsh.setnumber, vec![("lc".into(), 0.1), ("n".into(), 4.0)]);
    assert_eq!(s.gmsh.clscale, Some(0.5));
    assert_eq!(s.output.fields, vec!["stress".to_string()]);
    assert!(!s.output.wants("displacement"));

    let top = "gravity = [0, -9.81]\n".to_string() + &minimal("[[loads]]\ngroup = \"t\"\ntraction = [1, 2, 0]\n");
    let s = load(&top).expect("2D gravity");
    assert_eq!(s.gravity, [0.0, -9.81, 0.0]);
    assert_eq!(s.loads[0].kind, LoadKind::Traction([1.0, 2.0, 0.0]));

    let msh = minimal("").replace("cylinder.geo", "cylinder.msh");
    assert!(matches!(load(&msh).expect("msh").mesh, MeshSource::Msh(_)));
}

#[test]
fn missing_file() {
    let path = std::env::temp_dir().join("subcontact_no_such_dir/none.toml");
    let msg = Scene::load(&path).expect_err("missing").to_string();
    assert!(msg.starts_with(&path.display().to_string()) && msg.contains("cannot read"), "{msg}");
}

#[test]
fn toml_syntax_and_types() {
    rejects(&minimal("friction = \n"), &["line 9, column 12", "bodies[0]", "invalid string"]);
    rejects(&minimal("[solver]\nload_steps = \"two\"\n"), &["line 10", "(in solver)", "expected i64"]);
    rejects(&minimal("").replace("plane_strain", "plane"), &["line 2", "plane_strain", "axisymmetric"]);
    rejects(&minimal("[[contacts]]\ngroup = \"i\"\nslip = \"stick\"\n"), &["contacts[0]", "coulomb", "frictionless"]);
}

#[test]
fn misspelt_key() {
    let m = rejects(
        &minimal("[[contacts]]\ngroup = \"a\"\n[[contacts]]\ngroup = \"i\"\nfrction = 0.8\n"),
        &["frction", "line 13", "contacts[1]", "friction", "tensile_strength"],
    );
    assert!(m.contains("Unknown keys are errors"), "{m}");
    rejects(&minimal("").replace("nu = 0.2", "nu = 0.2\ne = 3"), &["materials.rock", "unknown field `e`", "`E`"]);
    rejects(&("titel = \"x\"\n".to_string() + &minimal("")), &["titel", "line 1", "`title`"]);
}

#[test]
fn mesh_rules() {
    rejects(&minimal("").replace("cylinder.geo", "cylinder.stl"), &["mesh", "cylinder.stl", ".geo", ".msh"]);
    rejects(&minimal("").replace("cylinder.geo", "other.geo"), &["mesh", "other.geo", "does not exist"]);
    rejects(&minimal("").replace("mesh = \"cylinder.geo\"\n", ""), &["mesh", "missing"]);
    rejects(&minimal("").replace("analysis = \"plane_strain\"\n", ""), &["analysis", "missing"]);
    rejects(&minimal("[gmsh]\norder = 2\n").replace("cylinder.geo", "cylinder.msh"), &["gmsh", ".geo", "cylinder.msh"]);
}

#[test]
fn material_rules() {
    let m = |from: &str, to: &str| minimal("").replace(from, to);
    rejects(&m("E = 1.0", "E = 0.0"), &["materials.rock.E", "= 0", "> 0"]);
    rejects(&m("E = 1.0", "E = inf"), &["materials.rock.E", "inf"]);
    rejects(&m("E = 1.0", "E = -5"), &["materials.rock.E", "-5"]);
    let msg = rejects(&m("nu = 0.2", "nu = 0.5"), &["materials.rock.nu", "= 0.5", "incompressible", "0.499"]);
    assert!(msg.contains("-1 < nu < 0.5"), "{msg}");
    rejects(&m("nu = 0.2", "nu = -1.0"), &["materials.rock.nu", "-1"]);
    rejects(&m("nu = 0.2", "nu = 0.2\ndensity = -1"), &["materials.rock.density", "-1", ">= 0"]);
    rejects(&m("nu = 0.2", ""), &["materials.rock.nu", "missing"]);
    rejects(
        &m("[materials.rock]", "[materials.\"soft clay\"]")
            .replace("\"rock\"", "\"soft clay\"")
            .replace("E = 1.0", "E = 0"),
        &["materials.\"soft clay\".E"],
    );
}

#[test]
fn plane_and_solid_rules() {
    rejects(&("thickness = 0\n".to_string() + &minimal("")), &["thickness", "= 0", "> 0"]);
    rejects(&("thickness = 2\n".to_string() + &minimal_solid("")), &["thickness", "solid", "remove"]);
    rejects(&("gravity = [1]\n".to_string() + &minimal("")), &["gravity", "[1]", "2 components"]);
    rejects(&("gravity = [1, 2, 3, 4]\n".to_string() + &minimal("")), &["gravity", "2 components"]);
    rejects(&("gravity = [0, -9.8]\n".to_string() + &minimal_solid("")), &["gravity", "3 components"]);
    rejects(&("gravity = [0, -9.8, 1]\n".to_string() + &minimal("")), &["gravity", "z component must be 0"]);
    rejects(&minimal("[[supports]]\ngroup = \"s\"\nfix = [\"z\"]\n"), &["supports[0].fix", "\"z\"", "solid"]);
    rejects(&minimal("[[supports]]\ngroup = \"s\"\nuz = 0.1\n"), &["supports[0].uz", "solid"]);
    rejects(&minimal("[[loads]]\ngroup = \"l\"\ntraction = [0, 0, 1]\n"), &["loads[0].traction", "z component"]);
    rejects(&minimal_solid("[[loads]]\ngroup = \"l\"\ntraction = [0, 1]\n"), &["loads[0].traction", "3 components"]);
    let probe = "[[probes]]\nname = \"p\"\nfrom = [0, 0, 1]\nto = [1, 1]\npoints = 3\n";
    rejects(&minimal(probe), &["probes[0].from", "z component"]);
    rejects(&minimal_solid(probe), &["probes[0].to", "3 components"]);
}

#[test]
fn body_rules() {
    let no_bodies = "mesh = \"cylinder.geo\"\nanalysis = \"solid\"\n[materials.rock]\nE = 1\nnu = 0.1\n";
    rejects(no_bodies, &["bodies", "at least one"]);
    rejects(
        &minimal("[[bodies]]\ngroup = \"b2\"\nmaterial = \"steel\"\n"),
        &["bodies[1].material", "\"steel\"", "\"rock\""],
    );
    rejects(&minimal("[[bodies]]\ngroup = \"b1\"\nmaterial = \"rock\"\n"), &["bodies[1].group", "\"b1\"", "bodies[0]"]);
    rejects(&minimal("[[bodies]]\nmaterial = \"rock\"\n"), &["bodies[1].group", "missing"]);
    rejects(&minimal("[[bodies]]\ngroup = \"\"\nmaterial = \"rock\"\n"), &["bodies[1].group", "empty"]);
    let no_mat = "mesh = \"cylinder.geo\"\nanalysis = \"solid\"\n[[bodies]]\ngroup = \"b\"\nmaterial = \"rock\"\n";
    rejects(no_mat, &["bodies[0].material", "none are defined"]);
}

#[test]
fn contact_rules() {
    let c = |body: &str| minimal(&format!("[[contacts]]\ngroup = \"ok\"\n[[contacts]]\n{body}\n"));
    rejects(&c("friction = 0.1"), &["contacts[1]", "group", "groups"]);
    rejects(&c("group = \"a\"\ngroups = [\"b\", \"c\"]"), &["contacts[1]", "both"]);
    rejects(&c("groups = [\"b\"]"), &["contacts[1].groups", "[\"b\"]", "exactly 2"]);
    rejects(&c("groups = [\"b\", \"c\", \"d\"]"), &["contacts[1].groups", "exactly 2"]);
    rejects(&c("groups = [\"b\", \"b\"]"), &["contacts[1].groups", "differ"]);
    rejects(&c("group = \"b1\""), &["contacts[1].group", "\"b1\"", "bodies[0]"]);
    rejects(&c("group = \"ok\""), &["contacts[1].group", "contacts[0]"]);
    rejects(&c("friction = -0.1\ngroup = \"x\""), &["contacts[1].friction", "-0.1", ">= 0"]);
    rejects(&c("friction = nan\ngroup = \"x\""), &["contacts[1].friction", "NaN", "finite"]);
    rejects(&c("cohesion = -1\ngroup = \"x\""), &["contacts[1].cohesion", "-1"]);
    rejects(&c("tensile_strength = -1\ngroup = \"x\""), &["contacts[1].tensile_strength", "-1"]);
    rejects(&c("residual_cohesion = -1\ngroup = \"x\""), &["contacts[1].residual_cohesion", "-1"]);
    rejects(
        &c("cohesion = 1\nresidual_cohesion = 2\ngroup = \"x\""),
        &["contacts[1].residual_cohesion", "= 2", "cohesion (1)"],
    );
}

#[test]
fn joint_stiffness_rules() {
    let stiff = "normal_stiffness = 100\nshear_stiffness = 10";
    let c = |first: &str, second: &str| {
        minimal(&format!("[[contacts]]\ngroup = \"ok\"\n{first}\n[[contacts]]\ngroup = \"x\"\n{second}\n"))
    };
    let both = load(&c(stiff, stiff)).expect("stiffness on every contact");
    assert_eq!(both.contacts[1].stiffness, Some(Stiffness { normal: 100.0, shear: 10.0 }));
    assert_eq!(load(&c("", "")).expect("rigid joints").contacts[0].stiffness, None);
    rejects(&c(stiff, "normal_stiffness = 100"), &["contacts[1].shear_stiffness", "missing", "both", "rigid"]);
    rejects(&c(stiff, "shear_stiffness = 10"), &["contacts[1].normal_stiffness", "missing", "MPa/m"]);
    rejects(&c(stiff, "normal_stiffness = 0\nshear_stiffness = 10"), &["contacts[1].normal_stiffness", "0", "> 0"]);
    rejects(&c(stiff, "normal_stiffness = 1\nshear_stiffness = -1"), &["contacts[1].shear_stiffness", "-1", "> 0"]);
    rejects(&c(stiff, "normal_stiffness = inf\nshear_stiffness = 1"), &["contacts[1].normal_stiffness", "> 0"]);
    rejects(&c(stiff, ""), &["contacts[1].normal_stiffness", "missing", "contacts[0]", "every contact"]);
    rejects(&c("", stiff), &["contacts[0].normal_stiffness", "contacts[1]"]);
    let paper = c(stiff, stiff) + "[solver]\nrule = \"paper\"\n";
    rejects(&paper, &["solver.rule", "\"paper\"", "rigid joints only", "robust"]);
}

#[test]
fn support_rules() {
    let s = |body: &str| minimal(&format!("[[supports]]\ngroup = \"s\"\n{body}\n"));
    rejects(&s(""), &["supports[0]", "fix", "ux"]);
    rejects(&s("fix = []"), &["supports[0]", "holds nothing"]);
    rejects(&s("fix = [\"w\"]"), &["supports[0].fix", "\"w\"", "\"x\", \"y\""]);
    rejects(&s("fix = [\"x\", \"x\"]"), &["supports[0].fix", "twice"]);
    rejects(&s("fix = [\"x\"]\nux = 0.1"), &["supports[0].ux", "0.1", "also in fix"]);
    rejects(&s("uy = inf"), &["supports[0].uy", "finite"]);
    rejects(&minimal("[[supports]]\nfix = [\"x\"]\n"), &["supports[0].group", "missing"]);
    rejects(&s("fix = [\"x\"]\nuz = 1").replace("plane_strain", "axisymmetric"), &["supports[0].uz", "axisymmetric"]);
}

#[test]
fn load_rules() {
    let l = |body: &str| minimal(&format!("[[loads]]\ngroup = \"l\"\n{body}\n"));
    rejects(&l(""), &["loads[0]", "pressure", "traction"]);
    rejects(&l("pressure = 1\ntraction = [1, 0]"), &["loads[0]", "both"]);
    rejects(&l("pressure = nan"), &["loads[0].pressure", "finite"]);
    rejects(&l("traction = [1, nan]"), &["loads[0].traction", "finite"]);
}

#[test]
fn solver_gmsh_probe_rules() {
    rejects(&minimal("[solver]\nload_steps = 0\n"), &["solver.load_steps", "= 0", "at least 1"]);
    rejects(&minimal("[solver]\nmax_iterations = -3\n"), &["solver.max_iterations", "-3"]);
    rejects(&minimal("[gmsh]\norder = 3\n"), &["gmsh.order", "= 3", "1", "2"]);
    rejects(&minimal("[gmsh]\nclscale = 0\n"), &["gmsh.clscale", "> 0"]);
    rejects(&minimal("[gmsh]\nsetnumber = { lc = inf }\n"), &["gmsh.setnumber.lc", "finite"]);
    rejects(&minimal("[gmsh]\nsetnumber = { \"a b\" = 1 }\n"), &["gmsh.setnumber.\"a b\"", "DefineConstant"]);
    let p =
        |name: &str, pts: i64| format!("[[probes]]\nname = \"{name}\"\nfrom = [0, 0]\nto = [1, 1]\npoints = {pts}\n");
    rejects(&minimal(&p("a", 1)), &["probes[0].points", "= 1", "at least 2"]);
    rejects(&minimal(&(p("a", 3) + &p("a", 3))), &["probes[1].name", "\"a\"", "unique"]);
    rejects(
        &minimal("[[probes]]\nname = \"a\"\nfrom = [1, 1]\nto = [1, 1]\npoints = 3\n"),
        &["probes[0].to", "non-zero length"],
    );
    rejects(&minimal("[[probes]]\nname = \"a\"\nfrom = [1, 1]\nto = [2, 1]\n"), &["probes[0].points", "missing"]);
}

#[test]
fn analytic_and_output_rules() {
    let a = |body: &str| minimal(&format!("[analytic]\n{body}\n"));
    rejects(&a("kind = \"lame_cylinder\"\na = 5\nb = 3\np = 1"), &["analytic.b", "= 3", "a = 5"]);
    rejects(&a("kind = \"lame_cylinder\"\na = 0\nb = 3\np = 1"), &["analytic.a", "= 0", "> 0"]);
    rejects(&a("kind = \"lame_cylinder\"\na = 1\nb = 3\np = inf"), &["analytic.p", "finite"]);
    rejects(&a("kind = \"lame_cylinder\"\na = 1\nb = 3"), &["analytic.p", "missing"]);
    rejects(&a("kind = \"kirsch\""), &["analytic.kind", "\"kirsch\"", "\"lame_cylinder\""]);
    rejects(&a("kind = \"lame_cylinder\"\na = 1\nb = 3\np = 1\nq = 2"), &["analytic", "unknown field `q`"]);
    rejects(
        &minimal("[output]\nfields = [\"strain\"]\n"),
        &["output.fields[0]", "\"strain\"", "\"displacement\", \"stress\""],
    );
    rejects(&minimal("[output]\nfields = [\"stress\", \"stress\"]\n"), &["output.fields[1]", "twice"]);
}

/// `[output] frame`: a box in the analysis's coordinates or bodies of the
/// scene, what the deformed picture frames (issue 19).
#[test]
fn output_frame_is_a_box_or_bodies() {
    let s = load(&minimal("[output]\nframe = { from = [-1, -2], to = [3, 4] }\n")).expect("a 2D box");
    assert_eq!(s.output.frame, Some(Region::Box { from: [-1.0, -2.0, 0.0], to: [3.0, 4.0, 0.0] }));
    assert_eq!(s.output.fields, Output::default().fields, "the fields keep their default");
    let s = load(&minimal_solid("[output]\nframe = { from = [0, 0, 0], to = [1, 1, 1] }\nfields = [\"stress\"]\n"))
        .expect("a 3D box");
    assert_eq!(s.output.frame, Some(Region::Box { from: [0.0; 3], to: [1.0; 3] }));
    let s = load(&minimal("[output]\nframe = { bodies = [\"b1\"] }\n")).expect("bodies");
    assert_eq!(s.output.frame, Some(Region::Bodies(vec!["b1".into()])));
    assert_eq!(load(&minimal("")).expect("no frame").output.frame, None);

    rejects(
        &minimal("[output]\nframe = { from = [0, 5], to = [1, 4] }\n"),
        &["output.frame.to", "[1, 4]", "its y must exceed from's (5)"],
    );
    rejects(
        &minimal_solid("[output]\nframe = { from = [0, 0], to = [1, 1] }\n"),
        &["output.frame.from", "3 components"],
    );
    rejects(
        &minimal("[output]\nframe = { bodies = [\"lining\"] }\n"),
        &["output.frame.bodies[0]", "\"lining\"", "\"b1\""],
    );
    rejects(&minimal("[output]\nframe = { bodies = [] }\n"), &["output.frame.bodies", "at least one body"]);
    rejects(&minimal("[output]\nframe = { from = [0, 0] }\n"), &["output.frame", "either the box", "or the bodies"]);
    rejects(
        &minimal("[output]\nframe = { from = [0, 0], to = [1, 1], bodies = [\"b1\"] }\n"),
        &["output.frame", "either"],
    );
    rejects(&minimal("[output]\nframe = { centre = [0, 0] }\n"), &["unknown field `centre`"]);
}

/// `[safety]` (issue 18): defaults, choices, and every rule named by its
/// key; misspelt keys are errors like everywhere else.
#[test]
fn safety_rules() {
    let joints =
        "[[contacts]]\ngroup = \"base\"\nfriction = 0.75\n[[contacts]]\ngroups = [\"j_a\", \"j_b\"]\ncohesion = 1.0\n";
    let with = |table: &str| minimal(&format!("{joints}[safety]\n{table}"));
    assert_eq!(load(&minimal(joints)).expect("no table").safety, None);
    let s = load(&with("")).expect("defaults").safety.expect("a table");
    assert_eq!(s, Safety::all(2));
    assert_eq!(
        (s.reduce, s.contacts.as_slice(), s.steps),
        (Reduce::ALL, &[0, 1][..], Steps { step: 0.1, tolerance: 1e-3, max_factor: 10.0 })
    );
    let s = load(&with("reduce = [\"cohesion\", \"friction\"]\ncontacts = [\"j_b\"]\nstep = 0.05\ntolerance = 1e-4\nmax_factor = 3.0\n")).expect("choices").safety.expect("a table");
    assert_eq!(s.reduce, Reduce { friction: true, cohesion: true, tensile_strength: false });
    let steps = Steps { step: 0.05, tolerance: 1e-4, max_factor: 3.0 };
    assert_eq!((s.contacts.as_slice(), s.steps), (&[1][..], steps));
    assert_eq!(
        load(&with("contacts = [\"j_a|j_b\", \"base\"]\n"))
            .expect("a pair by both names")
            .safety
            .expect("table")
            .contacts,
        vec![0, 1]
    );

    let m = rejects(&with("tolerence = 0.01\n"), &["tolerence", "safety", "`tolerance`", "`max_factor`"]);
    assert!(m.contains("Unknown keys are errors"), "{m}");
    rejects(
        &with("reduce = [\"phi\"]\n"),
        &["safety.reduce[0] = \"phi\"", "\"friction\", \"cohesion\", \"tensile_strength\""],
    );
    rejects(&with("reduce = [\"friction\", \"friction\"]\n"), &["safety.reduce[1]", "twice"]);
    rejects(&with("reduce = []\n"), &["safety.reduce", "empty"]);
    rejects(&with("contacts = [\"bse\"]\n"), &["safety.contacts[0] = \"bse\"", "\"base\", \"j_a|j_b\""]);
    rejects(&with("contacts = [\"base\", \"base\"]\n"), &["safety.contacts[1]", "contacts[0] again"]);
    rejects(&with("contacts = []\n"), &["safety.contacts", "empty"]);
    rejects(&with("step = 0\n"), &["safety.step = 0", "> 0"]);
    rejects(&with("tolerance = 1.5\n"), &["safety.tolerance = 1.5", "below 1"]);
    rejects(&with("tolerance = -1e-3\n"), &["safety.tolerance", "> 0"]);
    rejects(&with("max_factor = 1.0\n"), &["safety.max_factor = 1", "exceed 1"]);
    rejects(&with("max_factor = nan\n"), &["safety.max_factor", "finite"]);
    // nothing to reduce: the base has no cohesion, the pair no friction
    rejects(
        &with("reduce = [\"cohesion\"]\ncontacts = [\"base\"]\n"),
        &["safety", "reduces nothing", "cohesion", "\"base\""],
    );
    rejects(&with("reduce = [\"tensile_strength\"]\n"), &["reduces nothing", "tensile_strength"]);
    rejects(&minimal("[safety]\n"), &["safety", "has none", "[[contacts]]"]);
}

#[test]
fn joint_sets_and_joints_parse() {
    let s = load(&minimal_solid(
        "[[contacts]]\ngroup = \"c\"\nfriction = 0.1\n[[joint_sets]]\nname = \"J1\"\ndip = 60\ndip_direction = 30\nspacing = 5\noffset = 1.3\nfriction = 0.7\ncohesion = 0.1\n[[joints]]\nname = \"fault\"\ndip = 80\ndip_direction = 0\npoint = [1, 2, 3]\npersistence = 4\nshape = \"disc\"\n",
    ))
    .expect("valid");
    assert_eq!(s.joints.len(), 2);
    assert_eq!(s.contacts.len(), 3, "the joints are the last contacts");
    assert_eq!(s.contacts[1].groups, ContactGroups::Shared("J1".to_string()));
    assert_eq!((s.contacts[1].strength.friction, s.contacts[1].strength.cohesion), (0.7, 0.1));
    assert_eq!(s.contacts[2].strength.friction, 0.0);
    assert_eq!(s.joints[0].bodies, vec!["b1".to_string()], "default: every body");
    assert_eq!(s.joints[0].placement, crate::mesh::joints::Placement::Set { spacing: 5.0, offset: 1.3 });
    assert_eq!(s.joints[1].persistence.as_ref().map(|p| p.shape), Some(crate::mesh::joints::Shape::Disc));
    assert_eq!(
        (s.contact_key(0), s.contact_key(1), s.contact_key(2)),
        ("contacts[0]".into(), "joint_sets[0]".into(), "joints[0]".into())
    );
    assert_eq!(s.model_spec().contacts[2].key, "joints[0]");
    assert_eq!(s.max_blocks, 1000);
    assert!(s.cut_job().is_some_and(|c| c.joints.len() == 2));
    // 2D: a trace by its angle
    let s = load(
        &minimal("[[joint_sets]]\nname = \"bedding\"\nangle = 0\nspacing = 3\nmax_blocks = 5\n")
            .replace("max_blocks = 5\n", "")
            .replace("mesh =", "max_blocks = 5\nmesh ="),
    )
    .expect("valid 2D");
    assert_eq!(s.joints[0].orientation, crate::mesh::joints::Orientation::Angle(0.0));
    assert_eq!(s.max_blocks, 5);
    assert!(!s.merge_slivers && !s.cut_job().expect("a cut").merge_slivers, "merge_slivers is off by default");
    let merged = load(
        &("merge_slivers = true\n".to_string()
            + &minimal_solid("[[joint_sets]]\nname = \"J\"\ndip = 0\ndip_direction = 0\nspacing = 1\n")),
    )
    .expect("merge_slivers");
    assert!(merged.cut_job().expect("a cut").merge_slivers);
    assert!(load(&minimal_solid("")).expect("valid").cut_job().is_none());
}

#[test]
fn joint_rules() {
    let set = |body: &str| minimal_solid(&format!("[[joint_sets]]\nname = \"J1\"\n{body}\n"));
    let ok = "dip = 60\ndip_direction = 30\nspacing = 5";
    rejects(&set("dip = 95\ndip_direction = 30\nspacing = 5"), &["joint_sets[0].dip", "= 95", "0 (horizontal) to 90"]);
    rejects(&set("dip = -1\ndip_direction = 30\nspacing = 5"), &["joint_sets[0].dip", "= -1"]);
    rejects(
        &set("dip = 60\ndip_direction = 360\nspacing = 5"),
        &["joint_sets[0].dip_direction", "= 360", "0 <= dip_direction < 360", "is 0 degrees"],
    );
    rejects(&set("dip = 60\ndip_direction = -30\nspacing = 5"), &["joint_sets[0].dip_direction", "is 330 degrees"]);
    rejects(&set("dip = 60\ndip_direction = 30\nspacing = 0"), &["joint_sets[0].spacing", "= 0", "> 0"]);
    rejects(&set("dip = 60\ndip_direction = 30\nspacing = -2"), &["joint_sets[0].spacing", "= -2"]);
    rejects(&set("dip = 60\ndip_direction = 30"), &["joint_sets[0].spacing", "missing"]);
    rejects(&set("dip_direction = 30\nspacing = 5"), &["joint_sets[0].dip", "missing"]);
    rejects(&set(&format!("{ok}\nangle = 3")), &["joint_sets[0].angle", "2D"]);
    rejects(&set(&format!("{ok}\npoint = [0, 0, 0]")), &["joint_sets[0].point", "[[joints]]"]);
    rejects(&set(&format!("{ok}\ngroup = \"x\"")), &["joint_sets[0]", "remove group"]);
    rejects(&set(&format!("{ok}\nfriction = -1")), &["joint_sets[0].friction", "-1"]);
    let wet = load(&set(&format!("{ok}\nwater = {{ pressure = 0.1 }}"))).expect("water on a joint set");
    let water = wet.contacts.last().and_then(|c| c.water.as_ref()).expect("the set's contact is wet");
    assert_eq!(water.pressure, crate::scene::WaterPressure::Uniform(0.1));
    rejects(&set(&format!("{ok}\nwater = {{ pressure = -0.1 }}")), &["joint_sets[0].water", "-0.1", ">= 0"]);
    rejects(&set(&format!("{ok}\nwater = {{ presure = 0.1 }}")), &["joint_sets[0].water", "presure"]);
    rejects(&set(&format!("{ok}\nwater = {{ level = 1, face = \"up\" }}")), &["joint_sets[0].water.face", "up"]);
    rejects(&set(&format!("{ok}\nbodies = [\"nope\"]")), &["joint_sets[0].bodies[0]", "\"nope\"", "\"b1\""]);
    rejects(&set(&format!("{ok}\npersistence = 2")), &["joint_sets[0].gap", "missing"]);
    rejects(&set(&format!("{ok}\ngap = 2")), &["joint_sets[0]", "persistence"]);
    rejects(&set(&format!("{ok}\npersistence = 0\ngap = 1")), &["joint_sets[0].persistence", "= 0"]);
    rejects(
        &set(&format!("{ok}\nextent = {{ from = [0, 0, 0], to = [1, -1, 1] }}")),
        &["joint_sets[0].extent.to", "y must exceed"],
    );
    rejects(&set(&format!("{ok}\nsnap = -1")), &["joint_sets[0].snap", "-1"]);
    let m = rejects(&set(&format!("{ok}\nspacin = 2")), &["spacin", "joint_sets[0]", "Unknown keys are errors"]);
    assert!(m.contains("`friction`") && m.contains("\"dip_direction\""), "{m}");
    rejects(&set(&ok.replace("J1", "b1")).replace("\"J1\"", "\"b1\""), &["joint_sets[0].name", "bodies[0]"]);
    let two = minimal_solid(&format!(
        "[[joint_sets]]\nname = \"J\"\n{ok}\n[[joints]]\nname = \"J\"\ndip = 1\ndip_direction = 0\npoint = [0, 0, 0]\n"
    ));
    rejects(&two, &["joints[0].name", "joint_sets[0]"]);
    let single =
        |body: &str| minimal_solid(&format!("[[joints]]\nname = \"F\"\ndip = 60\ndip_direction = 30\n{body}\n"));
    rejects(&single("spacing = 3\npoint = [0, 0, 0]"), &["joints[0]", "[[joint_sets]]"]);
    rejects(&single(""), &["joints[0].point", "missing"]);
    rejects(&single("point = [0, 0, 0]\npersistence = 2\ngap = 1"), &["joints[0].gap", "does not apply"]);
    rejects(&minimal(&format!("[[joint_sets]]\nname = \"J\"\n{ok}")), &["joint_sets[0]", "angle"]);
    rejects(&("max_blocks = 0\n".to_string() + &minimal_solid("")), &["max_blocks", "at least 1"]);
    rejects(&minimal_solid("[gmsh]\nstructured = true\n"), &["gmsh.structured", "Transfinite"]);
    rejects(
        &minimal_solid(&format!("[[joint_sets]]\nname = \"J\"\n{ok}")).replace("cylinder.geo", "cylinder.msh"),
        &["joint_sets[0]", "ready mesh"],
    );
}

/// `[safety] strength` (peak by default, residual on request) and `load`,
/// the load factor search (issue 29, issue 34 item 3): the loads it
/// raises get a load case of their own; misnamed loads and a table that
/// both reduces and raises are errors.
#[test]
fn safety_strength_and_load_rules() {
    let base = "[[contacts]]\ngroup = \"base\"\nfriction = 0.75\ncohesion = 1.0\n[[loads]]\ngroup = \"back\"\ntraction = [1.0, 0.0]\n[[loads]]\ngroup = \"top\"\npressure = 1.0\nfactors = [1.0]\n";
    let with = |table: &str| {
        minimal(&format!("{base}[safety]\n{table}")).replacen("analysis", "gravity = [0.0, -9.81]\nanalysis", 1)
    };
    let s = load(&with("")).expect("defaults").safety.expect("a table");
    assert_eq!((s.strengths, s.strength_given, s.raise.is_none()), (Strengths::Peak, false, true));
    let s = load(&with("strength = \"residual\"\n")).expect("residual").safety.expect("a table");
    assert_eq!((s.strengths, s.strength_given), (Strengths::Residual, true));
    rejects(&with("strength = \"soft\"\n"), &["safety.strength = \"soft\"", "\"peak\"", "\"residual\""]);
    let scene = load(&with("load = [\"gravity\", \"back\"]\n")).expect("a load search");
    assert_eq!(scene.safety.as_ref().and_then(|s| s.raise.clone()), Some(Raise { loads: vec![0], gravity: true }));
    // the raised loads get the ramp as factors of their own; the others keep theirs
    let spec = scene.model_spec();
    assert_eq!(spec.loads[0].factors, Some(vec![1.0]));
    assert_eq!(spec.loads[1].factors, Some(vec![1.0]));
    assert_eq!(spec.gravity_factors, Some(vec![1.0]));
    assert_eq!(load(&with("")).expect("no load search").model_spec().loads[0].factors, None);
    rejects(&with("load = [\"front\"]\n"), &["safety.load[0] = \"front\"", "\"back\", \"top\", \"gravity\""]);
    rejects(&with("load = [\"back\", \"back\"]\n"), &["safety.load[1]", "twice"]);
    rejects(&with("load = []\n"), &["safety.load", "empty"]);
    rejects(&with("load = [\"back\"]\nstrength = \"peak\"\n"), &["safety.strength", "one or the other"]);
    rejects(&minimal(&format!("{base}[safety]\nload = [\"gravity\"]\n")), &["safety.load[0]", "no gravity"]);
}
