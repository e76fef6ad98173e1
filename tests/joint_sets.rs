//! Joint sets by orientation (issue 31): the rock mass the tool cuts from
//! `[[joint_sets]]` against the same rock mass built by hand in gmsh, the
//! user's groups through the cut, and the input it refuses; and the cut
//! alone, through libgmsh without a scene (three oblique sets through a box
//! with a tunnel: the blocks fill the rock, the areas add up).
//!
//! Reference: the `.geo` a user had to write before (`tests/geo/
//! joint_sets_by_hand.geo`: each plane built from its dip and dip
//! direction, the rock fragmented, every face sorted into its group by its
//! corner points) against 15 lines of box minus a tunnel and three
//! `[[joint_sets]]` (60/030, 70/150, 10/270; 5, 5 and 4 m apart).
//!
//! ```text
//!        z                      a 20 m cube, x -10..10, y 0..20, z -10..10,
//!        |   .------------.     minus a tunnel of radius 3 along y;
//!        |  /  /   /   / /|     cut by three sets into 171 blocks
//!        | .--/---/---/-. |
//!        | |   .----.   | |     groups: rock, top, base, sides, ends, wall
//!        | |  (      )  | .
//!        | |   `----'   |/
//!        | '------------'
//!        o-------------------- x
//! ```

mod common;

use common::cli::{clean_failure, says};
use common::{repo_text, Case};
use subcontact::contact::law::ContactState;
use subcontact::fem::vec3::{cross, norm, sub};
use subcontact::mesh::joints::{
    cut_and_mesh, read_report, CutJob, CutReport, JointError, JointSpec, MeshArgs, Orientation, Placement,
};
use subcontact::mesh::msh::read_msh;
use subcontact::mesh::Mesh;
use subcontact::model::Model;
use subcontact::scene::Scene;

/// The user's rock: 15 lines.
const ROCK_GEO: &str = r#"// A 20 m cube of rock with a tunnel of radius 3 m along y.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.0, Name "Parameters/element size"} ];
Box(1) = {-10, 0, -10, 20, 20, 20};
Cylinder(2) = {0, -1, 0, 0, 22, 0, 3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
MeshSize{ PointsOf{ Volume{:}; } } = lc;
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("top") = Surface In BoundingBox{-10 - e, -e, 10 - e, 10 + e, 20 + e, 10 + e};
Physical Surface("base") = Surface In BoundingBox{-10 - e, -e, -10 - e, 10 + e, 20 + e, -10 + e};
Physical Surface("sides") = Surface In BoundingBox{-10 - e, -e, -10 - e, -10 + e, 20 + e, 10 + e};
Physical Surface("sides") += Surface In BoundingBox{10 - e, -e, -10 - e, 10 + e, 20 + e, 10 + e};
Physical Surface("ends") = Surface In BoundingBox{-10 - e, -e, -10 - e, 10 + e, e, 10 + e};
Physical Surface("ends") += Surface In BoundingBox{-10 - e, 20 - e, -10 - e, 10 + e, 20 + e, 10 + e};
Physical Surface("wall") = Surface In BoundingBox{-3 - e, -e, -3 - e, 3 + e, 20 + e, 3 + e};
"#;

/// What both scenes share: rock, gravity, supports; the element size
/// given, not left to the .geo's default (in one process gmsh's API keeps
/// an earlier session's -setnumber for a DefineConstant of the same name).
const HEAD: &str = r#"analysis = "solid"
[gmsh]
setnumber = { lc = 2.0 }
[materials.rock]
E = 5000.0
nu = 0.25
[[bodies]]
group = "rock"
material = "rock"
[[supports]]
group = "base"
fix = ["x", "y", "z"]
[[loads]]
group = "top"
pressure = 1.0
"#;

const SETS: &str = r#"
[[joint_sets]]
name = "J1"
dip = 60.0
dip_direction = 30.0
spacing = 5.0
offset = 1.3
friction = 0.7
[[joint_sets]]
name = "J2"
dip = 70.0
dip_direction = 150.0
spacing = 5.0
friction = 0.7
[[joint_sets]]
name = "J3"
dip = 10.0
dip_direction = 270.0
spacing = 4.0
offset = 0.5
friction = 0.7
"#;

/// The mesh and model of a scene of the case (meshed into its results).
fn model_of(case: &Case, scene: &std::path::Path) -> (Mesh, Model) {
    let scene = Scene::load(scene).expect("scene");
    let (mesh, _, _) = subcontact::driver::load_mesh(&scene, &case.out(&scene.name), false).expect("mesh");
    let model = Model::build(&mesh, &scene.model_spec()).expect("model");
    (mesh, model)
}

/// Volume of a linear tetrahedron.
fn tet_volume(p: [[f64; 3]; 4]) -> f64 {
    let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, v, w) = (d(p[0], p[1]), d(p[0], p[2]), d(p[0], p[3]));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])).abs()
        / 6.0
}

/// Every block's volume (from its tetrahedra's corners), sorted.
fn block_volumes(model: &Model) -> Vec<f64> {
    let mut v: Vec<f64> = model
        .bodies
        .iter()
        .map(|b| b.cells.iter().map(|c| tet_volume([0, 1, 2, 3].map(|i| model.coords[c.nodes[i]]))).sum::<f64>())
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

/// The area of a group's triangles (their corners).
fn area(mesh: &Mesh, group: &str) -> f64 {
    let g = mesh.group(group).unwrap_or_else(|| panic!("group {group}"));
    g.cells
        .iter()
        .map(|c| {
            let [a, b, d] = [0, 1, 2].map(|k| mesh.coords[c.nodes[k]]);
            0.5 * norm(cross(sub(b, a), sub(d, a)))
        })
        .sum()
}

/// Done-when 1 of issue 31: the same blocks (count, and every block's
/// volume to 1 %) and the same joint areas (1 %) from 15 lines and three
/// [[joint_sets]] as from the .geo built by hand; and the user's groups
/// keep their areas through the cut.
#[test]
fn joint_sets_give_the_rock_mass_built_by_hand() {
    let case = Case::new("joint-sets-by-hand");
    case.write("rock.geo", ROCK_GEO);
    let sets = case.write("sets.toml", &format!("mesh = \"rock.geo\"\n{HEAD}{SETS}"));
    case.copy("tests/geo/joint_sets_by_hand.geo");
    let contacts: String =
        ["J1", "J2", "J3"].iter().map(|j| format!("[[contacts]]\ngroup = \"{j}\"\nfriction = 0.7\n")).collect();
    let hand = case.write("hand.toml", &format!("mesh = \"joint_sets_by_hand.geo\"\n{HEAD}{contacts}"));
    let (mesh_s, model_s) = model_of(&case, &sets);
    // the by-hand .geo through the cutter without joints: its mesh, and its
    // blocks' exact volumes (OpenCASCADE's) as the joint sets' report has them
    let hand_geo = case.dir.join("joint_sets_by_hand.geo");
    let args = MeshArgs { geo: &hand_geo, dim: 3, order: 1, setnumber: &[("lc".into(), 2.0)], clscale: None };
    let hand_msh = case.dir.join("hand.msh");
    let by_hand = cut_and_mesh(
        &args,
        &CutJob { joints: vec![], max_blocks: 1000, structured: false, merge_slivers: false },
        &hand_msh,
    )
    .expect("by hand");
    let mesh_h = subcontact::mesh::msh::read_msh(&hand_msh).expect("the by-hand mesh");
    let model_h = Model::build(&mesh_h, &Scene::load(&hand).expect("scene").model_spec()).expect("model");

    assert_eq!(model_s.bodies.len(), model_h.bodies.len(), "blocks: joint sets against by hand");
    assert_eq!(model_s.bodies.len(), 171);
    let exact = |r: CutReport| {
        let mut v: Vec<f64> = r.blocks.iter().map(|b| b.volume).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let report = read_report(&case.out("sets").join("mesh/sets.msh")).expect("the cut's report");
    let (vs, vh) = (exact(report), exact(by_hand));
    assert_eq!(vs.len(), vh.len());
    let worst = vs.iter().zip(&vh).map(|(a, b)| (a - b).abs() / b).fold(0.0, f64::max);
    let total: f64 = vs.iter().sum();
    eprintln!("171 blocks, volume {total:.6} (8000 - 180 pi = {:.6}); largest relative difference of a block's volume {worst:.1e}, smallest block {:.2e}", 8000.0 - 180.0 * std::f64::consts::PI, vs[0]);
    assert!(worst < 1e-6, "a block's volume differs by {worst:.2e}");
    // and as meshed: the same within the chords that cut the tunnel's wall
    let (ms, mh) = (block_volumes(&model_s), block_volumes(&model_h));
    let worst = ms.iter().zip(&mh).map(|(a, b)| (a - b).abs() / b).fold(0.0, f64::max);
    eprintln!("as meshed: largest relative difference {worst:.1e}");
    assert!(worst < 0.03, "a meshed block's volume differs by {worst:.2e}");
    for j in ["J1", "J2", "J3"] {
        let (a, b) = (area(&mesh_s, j), area(&mesh_h, j));
        eprintln!("{j}: area {a:.3} (joint sets) against {b:.3} (by hand)");
        assert!((a - b).abs() < 0.01 * b, "{j}: {a} against {b}");
    }
    for (g, exact) in [("top", 400.0), ("base", 400.0), ("sides", 800.0)] {
        let a = area(&mesh_s, g);
        assert!((a - exact).abs() < 1e-9 * exact, "{g}: {a} against {exact}");
    }
    assert!((area(&mesh_s, "wall") - area(&mesh_h, "wall")).abs() < 0.01 * area(&mesh_h, "wall"));
}

/// A 10 m cube whose every face is a group.
const CUBE_GEO: &str = r#"SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.5, Name "Parameters/element size"} ];
Box(1) = {0, 0, 0, 10, 10, 10};
MeshSize{ PointsOf{ Volume{1}; } } = lc;
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 10 + e, 10 + e};
Physical Surface("x1") = Surface In BoundingBox{10 - e, -e, -e, 10 + e, 10 + e, 10 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 10 + e, e, 10 + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 10 - e, -e, 10 + e, 10 + e, 10 + e};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, 10 + e, 10 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 10 - e, 10 + e, 10 + e, 10 + e};
"#;

/// The cube cut by two oblique sets and a horizontal one, strong joints.
fn cube_scene(case: &Case, extra: &str) -> std::path::PathBuf {
    case.write("cube.geo", CUBE_GEO);
    let joint = |name: &str, dip: f64, dd: f64, spacing: f64| {
        format!("[[joint_sets]]\nname = \"{name}\"\ndip = {dip}\ndip_direction = {dd}\nspacing = {spacing}\noffset = 0.37\nfriction = 0.6\ncohesion = 1e3\ntensile_strength = 1e3\n")
    };
    let text = format!(
        "mesh = \"cube.geo\"\nanalysis = \"solid\"\n{extra}[materials.rock]\nE = 1000.0\nnu = 0.25\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n{}{}{}[[supports]]\ngroup = \"base\"\nfix = [\"z\"]\n[[supports]]\ngroup = \"x0\"\nfix = [\"x\"]\n[[supports]]\ngroup = \"y0\"\nfix = [\"y\"]\n[[loads]]\ngroup = \"top\"\npressure = 1.0\n[[loads]]\ngroup = \"x1\"\npressure = 0.5\n",
        joint("A", 45.0, 45.0, 4.0),
        joint("B", 60.0, 200.0, 5.0),
        joint("C", 0.0, 0.0, 3.3)
    );
    case.write("cube.toml", &text)
}

/// Two single joints whose traces meet the cube's back edge 1 mm apart
/// (the plane x = 5, and one of dip 45 / 045 through (4.999, 10, 10))
/// cross 0.7 mm inside it and cut a corner block a hair thick, which
/// `merge_slivers` bonds across its face on B. Its face on A stays a
/// contact, three pairs of 1e-7 m² where A's median pair has 2.6 m², as
/// tests/corpus/dam3d.toml's two sets left at its side
/// (docs/convergence.md): `check` says so, naming the group and the place.
/// Moved 0.5 m apart, the joints cut none and it says nothing.
#[test]
fn joints_whose_traces_meet_a_hair_apart_are_said() {
    let case = Case::new("sets-hairline");
    case.write("cube.geo", CUBE_GEO);
    let scene = |offset: f64| {
        let joint = |name: &str, dip: f64, dd: f64, offset: f64| {
            format!("[[joint_sets]]\nname = \"{name}\"\ndip = {dip}\ndip_direction = {dd}\nspacing = 100.0\noffset = {offset}\nfriction = 0.6\n")
        };
        format!(
            "mesh = \"cube.geo\"\nanalysis = \"solid\"\nmerge_slivers = true\n[materials.rock]\nE = 1000.0\nnu = 0.25\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n{}{}[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n[[loads]]\ngroup = \"top\"\npressure = 1.0\n",
            joint("A", 90.0, 90.0, 5.0),
            joint("B", 45.0, 45.0, offset)
        )
    };
    // n . (4.999, 10, 10) with n = (1/2, 1/2, 1/sqrt 2)
    let through = 0.5 * 4.999 + 0.5 * 10.0 + 10.0 / 2f64.sqrt();
    let check = |name: &str, offset: f64| {
        let o = case.cli(&["check", &case.write(name, &scene(offset)).to_string_lossy()]);
        let said = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{said}");
        said
    };
    let said = check("hair.toml", through);
    let a = "contact \"A\" has 3 pair(s)";
    common::cli::says(&said, &[a, "a facet a hair wide", "at (5.000, 9.999, 10.000)", "Move one joint set's offset"]);
    let apart = check("apart.toml", through + 0.5);
    assert!(!apart.contains("hair"), "traces 0.7 m apart are no hairline:\n{apart}");
}

/// Done-when 2 of issue 31: the user's support and load groups survive
/// the cutting. Every face of the cube is a group; the joints cut each
/// into pieces, which keep its area, and the supports and loads on them
/// act as on the intact cube: with joints that hold (cohesion and tensile
/// strength 1e3), pressure p = 1 on top and q = 0.5 on x = 10 give the
/// uniform stress sigma_zz = -p, sigma_xx = -q, so (E = 1000, nu = 0.25,
/// L = 10) u_z(top) = L (-p + nu q) / E, u_x(x = 10) = L (-q + nu p) / E,
/// u_y(y = 10) = L nu (p + q) / E, which linear tetrahedra reproduce
/// exactly.
#[test]
fn the_users_groups_survive_the_cutting() {
    let case = Case::new("joint-sets-groups");
    let scene = cube_scene(&case, "");
    let run = case.run(&scene).expect("the jointed cube solves");
    let mesh = subcontact::mesh::msh::read_msh(&case.out("cube").join("mesh/cube.msh")).expect("mesh");
    for g in ["x0", "x1", "y0", "y1", "base", "top"] {
        let a = area(&mesh, g);
        let pieces = mesh.group(g).map_or(0, |grp| grp.cells.len());
        assert!((a - 100.0).abs() < 1e-9, "{g}: area {a} in {pieces} facets");
    }
    let blocks = run.model.bodies.len();
    assert!(blocks > 20, "the sets cut the cube into {blocks} blocks");
    let c = run.contact().expect("contacts");
    assert!(c.states.iter().all(|s| *s == ContactState::Stick), "every joint holds");
    let (e, nu, l, p, q) = (1000.0, 0.25, 10.0, 1.0, 0.5);
    let exact = [l * (-q + nu * p) / e, l * nu * (p + q) / e, l * (-p + nu * q) / e];
    let u = &run.last().u;
    let mut worst = 0.0f64;
    for (m, x) in run.model.coords.iter().enumerate() {
        for d in 0..3 {
            worst = worst.max((u[m * 3 + d] - exact[d] * x[d] / l).abs());
        }
    }
    eprintln!(
        "{blocks} blocks, {} pairs: largest displacement error {worst:.1e} of {:.1e}",
        c.states.len(),
        exact[2].abs()
    );
    assert!(worst < 1e-9 * exact[2].abs(), "uniform strain: error {worst:e}");
}

/// Done-when 4 of issue 31: a set that cuts nothing, and more blocks than
/// max_blocks, each one clear paragraph from the binary, exit status 1,
/// no result file.
#[test]
fn joints_that_cut_nothing_or_too_much_are_refused() {
    let case = Case::new("joint-sets-refused");
    cube_scene(&case, "");
    let text = common::read(&case.dir.join("cube.toml"));
    case.write(
        "nothing.toml",
        &text.replacen("spacing = 4\n", "spacing = 400\n", 1).replacen("offset = 0.37", "offset = 50", 1),
    );
    let msg = clean_failure(&case, &case.cli(&["solve", "nothing.toml", "--quiet"]), &case.out("nothing"));
    says(
        &msg,
        &[
            "nothing.toml: joint_sets[0] (\"A\", 45/045) cuts nothing",
            "n . x = 50 + k 400",
            "runs from 0 to 17.071068",
            "change offset or spacing",
        ],
    );
    case.write("many.toml", &format!("max_blocks = 7\n{text}"));
    let msg = clean_failure(&case, &case.cli(&["solve", "many.toml", "--quiet"]), &case.out("many"));
    says(
        &msg,
        &["many.toml: the joints cut the bodies into", "more than max_blocks = 7", "raise the top-level `max_blocks`"],
    );
    let built_in = "Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};\nLine(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\nCurve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\nPhysical Surface(\"rock\") = {1};\nPhysical Curve(\"base\") = {1};\n";
    case.write("square.geo", built_in);
    case.write("square.toml", "mesh = \"square.geo\"\nanalysis = \"plane_strain\"\n[materials.rock]\nE = 1.0\nnu = 0.2\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[joint_sets]]\nname = \"J\"\nangle = 30\nspacing = 0.3\n[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n");
    let msg = clean_failure(&case, &case.cli(&["solve", "square.toml", "--quiet"]), &case.out("square"));
    says(&msg, &["square.geo` is not an OpenCASCADE model", "SetFactory(\"OpenCASCADE\");"]);
    case.write("taken.toml", &text.replacen("name = \"A\"", "name = \"top\"", 1));
    let msg = clean_failure(&case, &case.cli(&["solve", "taken.toml", "--quiet"]), &case.out("taken"));
    says(&msg, &["taken.toml: joint_sets[0]: the joint name \"top\" is already a physical group", "another name"]);
}

/// contact.csv's rows keyed by contact group, position and normal (a
/// crossing line holds several pairs at one place: their values sorted),
/// with the state and sigma_n, tau_t, tau_b.
fn pair_rows(path: &std::path::Path) -> std::collections::BTreeMap<String, Vec<(i64, [f64; 3])>> {
    let mut out: std::collections::BTreeMap<String, Vec<(i64, [f64; 3])>> = Default::default();
    for r in common::csv_rows(path) {
        let num = |k: &str| common::csv_num(&r, k);
        let key = format!(
            "{} {}",
            r["contact"],
            ["x", "y", "z", "n_x", "n_y", "n_z"]
                .map(|k| format!("{:.6}", (num(k) * 1e6).round() / 1e6 + 0.0))
                .join(" ")
        );
        let status = num("status") as i64;
        out.entry(key).or_default().push((status, [num("sigma_n"), num("tau_t"), num("tau_b")]));
    }
    for v in out.values_mut() {
        v.sort_by(|a, b| a.0.cmp(&b.0).then(a.1[0].total_cmp(&b.1[0])));
    }
    out
}

/// `make rockmass` as an engineer writes it (geo/rockmass_sets.toml: a cube
/// and three [[joint_sets]], `structured`) solves as the rock mass built by
/// hand (geo/rockmass.toml on geo/rockmass.geo), here at 2 x 2 x 2 blocks
/// of 3 x 3 x 3 hex20: the same mesh, so every pair in the same state with
/// the same stresses, to the contact solve's tolerance.
#[test]
fn joint_sets_solve_as_the_rockmass_built_by_hand() {
    let case = Case::new("joint-sets-rockmass");
    case.copy("geo/rockmass.geo");
    case.copy("geo/rockmass_sets.geo");
    let hand = common::scenes::edited(
        "geo/rockmass.toml",
        &[(
            "setnumber = { n = 4, m = 2, hex = 1, serendipity = 1 }",
            "setnumber = { n = 2, m = 3, hex = 1, serendipity = 1 }",
        )],
    );
    let sets = common::scenes::edited("geo/rockmass_sets.toml", &[("lc = 1.25,", "lc = 2.5,")])
        .replace("spacing = 2.5", "spacing = 5.0");
    let (a, b) = (
        case.run(&case.write("hand.toml", &hand)).expect("by hand"),
        case.run(&case.write("sets.toml", &sets)).expect("sets"),
    );
    assert_eq!(a.model.bodies.len(), 8);
    assert_eq!((a.stats.dofs.total, a.model.pairs.len()), (b.stats.dofs.total, b.model.pairs.len()), "the same mesh");
    let (ra, rb) = (pair_rows(&case.out("hand").join("contact.csv")), pair_rows(&case.out("sets").join("contact.csv")));
    let only: Vec<&String> =
        ra.keys().filter(|k| !rb.contains_key(*k)).chain(rb.keys().filter(|k| !ra.contains_key(*k))).collect();
    assert!(only.is_empty(), "{} pair places in one run only, e.g. {:?}", only.len(), only.first());
    let mut worst = 0.0f64;
    for (k, va) in &ra {
        let vb = &rb[k];
        assert_eq!(
            va.iter().map(|v| v.0).collect::<Vec<_>>(),
            vb.iter().map(|v| v.0).collect::<Vec<_>>(),
            "states at {k}"
        );
        for (x, y) in va.iter().zip(vb) {
            worst = (0..3).map(|i| (x.1[i] - y.1[i]).abs()).fold(worst, f64::max);
        }
    }
    let c = b.contact().expect("contact");
    let k = |s| common::measure::count(c, s);
    eprintln!(
        "8 blocks, {} pairs ({} stick / {} slip / {} open), {} DOFs: largest difference of a stress {worst:.1e} (loads 1 MPa)",
        c.states.len(),
        k(ContactState::Stick),
        k(ContactState::Slip),
        k(ContactState::Open),
        b.stats.dofs.total
    );
    assert!(worst < 1e-6, "stresses differ by {worst:e}");
}

/// Water on a joint the tool cuts (issue 31): `water` on a `[[joints]]`
/// entry acts on the contact group the cut makes of its faces. A 4 m x 4 m
/// square of rock on a fixed base, held on frictionless rollers at its
/// sides, cut at y = 2 by a horizontal joint holding water at u = 0.02
/// (uniform): the block above the joint weighs W = rho g 4 x 2 = 0.21189,
/// the water lifts it by U = 4 u = 0.08 and the joint carries the rest:
/// the effective normal force N = U - W = -0.13189 (per metre, tension
/// positive), and the level form (water up to y = 4.0387, u = gw (h - 2))
/// gives the same. Without the water, N = -W.
#[test]
fn water_on_a_cut_joint_lifts_the_block_above_it() {
    let case = Case::new("joint-sets-water");
    case.write(
        "square.geo",
        "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {-2, 0, 0, 4, 4};\nMeshSize{ PointsOf{ Surface{1}; } } = 0.5;\ne = 1e-3;\nPhysical Surface(\"rock\") = {1};\nPhysical Curve(\"base\") = Curve In BoundingBox{-2 - e, -e, -e, 2 + e, e, e};\nPhysical Curve(\"sides\") = Curve In BoundingBox{-2 - e, -e, -e, -2 + e, 4 + e, e};\nPhysical Curve(\"sides\") += Curve In BoundingBox{2 - e, -e, -e, 2 + e, 4 + e, e};\n",
    );
    let scene = |water: &str| {
        format!("mesh = \"square.geo\"\nanalysis = \"plane_strain\"\ngravity = [0.0, -9.81]\n[materials.rock]\nE = 5000.0\nnu = 0.25\ndensity = 2.7e-3\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[joints]]\nname = \"lift\"\nangle = 0.0\npoint = [0.0, 2.0]\nfriction = 0.6\n{water}[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n[[supports]]\ngroup = \"sides\"\nfix = [\"x\"]\n")
    };
    let w = 2.7e-3 * 9.81 * 8.0;
    let level = 2.0 + 0.02 / 0.00981;
    for (name, water, u) in [
        ("dry", String::new(), 0.0),
        ("uniform", "water = { pressure = 0.02 }\n".to_string(), 0.08),
        ("level", format!("water = {{ level = {level}, unit_weight = 0.00981 }}\n"), 0.08),
    ] {
        case.write(&format!("{name}.toml"), &scene(&water));
        let o = case.cli(&["solve", &format!("{name}.toml"), "--quiet"]);
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        let s = common::json(&case.out(name).join("summary.json"));
        let g = &s["contact"]["groups"][0];
        assert_eq!(g["name"], "lift");
        let (n, uplift) = (g["normal_force"].as_f64().expect("N"), g["uplift"].as_f64().expect("U"));
        eprintln!("{name}: U = {uplift:.6} (exact {u}), N = {n:.6} (exact {:.6})", u - w);
        assert!((uplift - u).abs() < 1e-9, "{name}: U = {uplift}, exact {u}");
        assert!((n - (u - w)).abs() < 1e-6 * w, "{name}: N = {n}, exact U - W = {}", u - w);
    }
}

/// A block that a joint set cut off and that nothing holds is named by
/// its number, as blocks.csv names it ("rock #2"), not by its group, which
/// every block of the cut shares: the square above with water at 0.5 in
/// the joint, more than the 0.21 the upper block weighs per unit area,
/// and the sides holding x alone.
#[test]
fn a_free_block_is_named_by_its_number() {
    let case = Case::new("joint-sets-free-block");
    case.write(
        "square.geo",
        "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {-2, 0, 0, 4, 4};\nMeshSize{ PointsOf{ Surface{1}; } } = 1.0;\ne = 1e-3;\nPhysical Surface(\"rock\") = {1};\nPhysical Curve(\"base\") = Curve In BoundingBox{-2 - e, -e, -e, 2 + e, e, e};\nPhysical Curve(\"sides\") = Curve In BoundingBox{-2 - e, -e, -e, -2 + e, 4 + e, e};\nPhysical Curve(\"sides\") += Curve In BoundingBox{2 - e, -e, -e, 2 + e, 4 + e, e};\n",
    );
    case.write("lift.toml", "mesh = \"square.geo\"\nanalysis = \"plane_strain\"\ngravity = [0.0, -9.81]\n[materials.rock]\nE = 5000.0\nnu = 0.25\ndensity = 2.7e-3\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n[[joints]]\nname = \"lift\"\nangle = 0.0\npoint = [0.0, 2.0]\nfriction = 0.6\nwater = { pressure = 0.5 }\n[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\"]\n[[supports]]\ngroup = \"sides\"\nfix = [\"x\"]\n");
    let o = case.cli(&["solve", "lift.toml", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "lifted by 0.5 > 0.21, the upper block must be free: {err}");
    assert!(err.contains("body \"rock #"), "the free block by its number: {err}");
    assert!(!err.contains("\"rock\""), "not the group every block shares: {err}");
}

/// `merge_slivers = true` (issue 31): geo/tunnel_joints.toml in a 10 m box
/// (W = 5) makes 27 blocks of which 3 are slivers (the thinnest 0.068 thick
/// where the mesh size is 2); merged, each is bonded to a neighbour across
/// its largest joint face, so the model has 27 - 3 = 24 blocks and the
/// contact groups lose those faces' pairs; by default nothing changes.
/// That variant still does not converge with or without the merge: one
/// pair of joints_a at (-1.44, 4.5), away from the slivers (x < -4.9),
/// cycles between stick and slip (report.md: "did not settle").
#[test]
fn slivers_merge_into_a_neighbour_when_asked() {
    let case = Case::new("joint-sets-slivers");
    case.copy("geo/tunnel_joints.geo");
    let small = common::scenes::edited(
        "geo/tunnel_joints.toml",
        &[("setnumber = { lc = 0.6, lc_far = 2.0 }", "setnumber = { lc = 0.6, lc_far = 2.0, W = 5 }")],
    );
    let mut counts = Vec::new();
    for (name, text) in [("as_cut", small.clone()), ("merged", format!("merge_slivers = true\n{small}"))] {
        let scene = case.write(&format!("{name}.toml"), &text);
        let (_, model) = model_of(&case, &scene);
        let report = read_report(&case.out(name).join(format!("mesh/{name}.msh"))).expect("the cut's report");
        let slivers = report.blocks.iter().filter(|b| b.is_sliver()).count();
        eprintln!(
            "{name}: {} blocks, {slivers} slivers, {} merged: {} bodies, {} pairs",
            report.blocks.len(),
            report.merged,
            model.bodies.len(),
            model.pairs.len()
        );
        assert_eq!((report.blocks.len(), slivers), (27, 3), "{name}");
        counts.push((report.merged, model.bodies.len(), model.pairs.len()));
    }
    assert_eq!((counts[0].0, counts[0].1), (0, 27), "by default every block is a body");
    assert_eq!((counts[1].0, counts[1].1), (3, 24), "each sliver bonded to one neighbour");
    assert!(counts[1].2 < counts[0].2, "the bonded faces have no pairs: {counts:?}");
}

/// make tunnel3d (issue 31): geo/tunnel3d.toml, the 3D tunnel through
/// three oblique sets given as [[joint_sets]], against the same rock mass
/// built by hand (tests/geo/tunnel3d_joints.geo with
/// tests/geo/tunnel3d_joints_coarse.toml): the same 148 blocks and joint
/// areas (1312.3, 1316.6, 1657.1 m2 to 1e-3) and the same resultants to
/// 1 % (measured: N 0.09 %, 0.01 %, 0.02 %; the meshes differ, 51,558 and
/// 44,471 DOFs), every block held; the cut one within the corpus' 30
/// contact iterations (issue 28: 24 measured at 7f3f6aa, three runs; 38
/// earlier, 80 before the breaker stopped holding friction that does not
/// settle).
#[test]
#[ignore = "make stress: two solves of about 10 s"]
fn tunnel3d_by_joint_sets_solves_as_the_one_built_by_hand() {
    let case = Case::new("joint-sets-tunnel3d");
    for f in [
        "geo/tunnel3d.geo",
        "geo/tunnel3d.toml",
        "tests/geo/tunnel3d_joints.geo",
        "tests/geo/tunnel3d_joints_coarse.toml",
    ] {
        case.copy(f);
    }
    let mut groups = Vec::new();
    for scene in ["tunnel3d", "tunnel3d_joints_coarse"] {
        let o = case.cli(&["solve", &format!("{scene}.toml"), "--quiet"]);
        assert!(o.status.success(), "{scene}: {}", String::from_utf8_lossy(&o.stderr));
        let s = common::json(&case.out(scene).join("summary.json"));
        groups.push(s["contact"]["groups"].as_array().expect("groups").clone());
        if scene == "tunnel3d" {
            let its = s["contact"]["iterations"].as_u64().expect("iterations");
            assert!(its <= 30, "tunnel3d: {its} contact iterations");
            let rows = common::csv_rows(&case.out(scene).join("blocks.csv"));
            assert_eq!(rows.len(), 148, "blocks");
            assert!(rows.iter().all(|r| r["state"] == "held"), "every block held");
        }
    }
    for (a, b) in groups[0].iter().zip(&groups[1]) {
        let f = |g: &serde_json::Value, k: &str| g[k].as_f64().expect("number");
        let (ta, tb) = (f(&a["area"], "total"), f(&b["area"], "total"));
        eprintln!("{}: area {ta:.2} / {tb:.2}, N {:.2} / {:.2}", a["name"], f(a, "normal_force"), f(b, "normal_force"));
        assert!((ta / tb - 1.0).abs() < 1e-3, "{}: area {ta} against {tb}", a["name"]);
        assert!((f(a, "normal_force") / f(b, "normal_force") - 1.0).abs() < 0.01, "{}: N", a["name"]);
        assert!((f(a, "shear_force") / f(b, "shear_force") - 1.0).abs() < 0.01, "{}: T", a["name"]);
    }
}

/// A 10 m cube with a tunnel of radius 2 along y through its middle;
/// every face of the cube a group, the tunnel's wall a group.
const TUNNEL_BOX_GEO: &str = r#"
SetFactory("OpenCASCADE");
DefineConstant[ lc = {1.5, Name "lc"} ];
Box(1) = {0, 0, 0, 10, 10, 10};
Cylinder(2) = {5, -1, 5, 0, 12, 0, 2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
MeshSize{ PointsOf{ Volume{:}; } } = lc;
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 10 - e, 10 + e, 10 + e, 10 + e};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, 10 + e, 10 + e, e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 10 + e, 10 + e};
Physical Surface("wall") = Surface In BoundingBox{3 - e, -e, 3 - e, 7 + e, 10 + e, 7 + e};
"#;

/// One set of parallel joints through the body `rock`.
fn set(name: &str, dip: f64, dd: f64, spacing: f64, offset: f64) -> JointSpec {
    JointSpec {
        key: format!("joint_sets[{name}]"),
        name: name.to_string(),
        orientation: Orientation::Dip { dip, dip_direction: dd },
        placement: Placement::Set { spacing, offset },
        bodies: vec!["rock".to_string()],
        persistence: None,
        extent: None,
        snap: 0.0,
    }
}

/// Cuts `geo` by `joints` through libgmsh (no scene, no driver) and reads the mesh.
fn cut_box(case: &Case, geo: &str, dim: usize, joints: Vec<JointSpec>) -> Result<(Mesh, CutReport), JointError> {
    let geo = case.write("model.geo", geo);
    let out = case.dir.join("model.msh");
    let args = MeshArgs { geo: &geo, dim, order: 1, setnumber: &[], clscale: None };
    let report =
        cut_and_mesh(&args, &CutJob { joints, max_blocks: 1000, structured: false, merge_slivers: false }, &out)?;
    Ok((read_msh(&out).expect("the cut mesh reads"), report))
}

/// Three oblique sets through the box with a tunnel: the blocks fill the
/// rock's volume 1000 - 40 pi, each set is a contact group of its own, the
/// box's faces and the wall keep their groups (cut into pieces), and the
/// mesh's facets of each set add up to the areas the report gives.
#[test]
fn three_sets_cut_a_box_with_a_tunnel() {
    let case = Case::new("joints-three-sets");
    let sets =
        vec![set("J1", 60.0, 30.0, 3.0, 1.3), set("J2", 70.0, 150.0, 3.0, 0.5), set("J3", 10.0, 270.0, 2.5, 0.2)];
    let (mesh, report) = cut_box(&case, TUNNEL_BOX_GEO, 3, sets).expect("the cut succeeds");
    let volume: f64 = report.blocks.iter().map(|b| b.volume).sum();
    let exact = 1000.0 - 40.0 * std::f64::consts::PI;
    assert!((volume - exact).abs() < 1e-6 * exact, "blocks fill the rock: {volume} against {exact}");
    assert!(report.blocks.iter().all(|b| b.body == "rock"));
    for name in ["rock", "top", "base", "x0", "wall", "J1", "J2", "J3"] {
        assert!(mesh.group(name).is_some_and(|g| !g.cells.is_empty()), "group {name} survives the cut");
    }
    // the top face keeps its area, 10 x 10, in pieces
    let top = area(&mesh, "top");
    assert!((top - 100.0).abs() < 1e-9 * 100.0, "top area {top}");
    let wall = area(&mesh, "wall");
    assert!((wall - 40.0 * std::f64::consts::PI).abs() < 0.02 * 40.0 * std::f64::consts::PI, "wall area {wall}");
    // every set meets the tunnel, whose wall the facets cut by chords: the
    // holes come out a little small
    for j in &report.joints {
        let a = area(&mesh, &j.name);
        assert!(a >= j.area() && a < 1.01 * j.area(), "{}: mesh {a} against {}", j.name, j.area());
    }
}

/// A 8 x 4 x 8 m box with a tunnel of radius 1.5 m, quadratic, with the
/// .geo asking for gmsh's high-order optimisation (as geo/tunnel3d.geo).
const SMALL_TUNNEL_GEO: &str = r#"SetFactory("OpenCASCADE");
Box(1) = {-4, 0, -4, 8, 4, 8};
Cylinder(2) = {0, -1, 0, 0, 6, 0, 1.5};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("base") = Surface In BoundingBox{-4 - e, -e, -4 - e, 4 + e, 4 + e, -4 + e};
Physical Surface("top") = Surface In BoundingBox{-4 - e, -e, 4 - e, 4 + e, 4 + e, 4 + e};
wall() = Surface In BoundingBox{-1.5 - e, -e, -1.5 - e, 1.5 + e, 4 + e, 1.5 + e};
Physical Surface("wall") = {wall()};
MeshSize{ PointsOf{ Volume{1}; } } = 2.0;
MeshSize{ PointsOf{ Surface{wall()}; } } = 1.0;
Mesh.HighOrderOptimize = 2;
"#;

/// Issue 28: the 3D joint-set cut meshes the same run to run. gmsh 4.8's
/// high-order optimisation orders its work by memory address, so the
/// tunnel3d scene's mid-side nodes round the opening moved by up to
/// 8.9 mm between two runs; the cutter now makes the folded quadratic
/// elements straight itself (3 here). Two cuts of the same scene in one
/// process (the heap as different as between runs): every node at the
/// same place, bit for bit.
#[test]
fn the_3d_cut_meshes_the_same_twice() {
    let case = Case::new("joint-sets-twice");
    case.write("small.geo", SMALL_TUNNEL_GEO);
    let text = format!(
        "mesh = \"small.geo\"\nanalysis = \"solid\"\n[gmsh]\norder = 2\n[materials.rock]\nE = 5000.0\nnu = 0.25\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n{}{}[[supports]]\ngroup = \"base\"\nfix = [\"x\", \"y\", \"z\"]\n[[loads]]\ngroup = \"top\"\npressure = 1.0\n",
        "[[joint_sets]]\nname = \"J1\"\ndip = 50.0\ndip_direction = 60.0\nspacing = 2.5\noffset = 0.3\nfriction = 0.7\n",
        "[[joint_sets]]\nname = \"J2\"\ndip = 70.0\ndip_direction = 200.0\nspacing = 3.0\noffset = 0.5\nfriction = 0.7\n",
    );
    let mut meshes = Vec::new();
    for name in ["first", "second"] {
        let scene = case.write(&format!("{name}.toml"), &text);
        let (mesh, _) = model_of(&case, &scene);
        let report = read_report(&case.out(name).join(format!("mesh/{name}.msh"))).expect("the cut's report");
        eprintln!("{name}: {} nodes, {} straightened", mesh.coords.len(), report.straightened);
        assert!(report.straightened > 0, "{name}: the curved wall folds some tet10 here");
        meshes.push(mesh);
    }
    assert_eq!(meshes[0].coords.len(), meshes[1].coords.len(), "node count");
    let moved = meshes[0].coords.iter().zip(&meshes[1].coords).filter(|(a, b)| a != b).count();
    assert_eq!(moved, 0, "{moved} of {} nodes moved between the runs", meshes[0].coords.len());
}

/// The corpus' block mass (tests/corpus/blocks3d.geo: a box of rock on a
/// slab, three sets through the rock only): the slab's bottom face, which
/// no joint reaches, keeps its group "ground" (12 x 8 m at z = -1), and
/// the rock's west face its 6 x 6 m at x = 0. gmsh 4.8's fragment map had
/// given "ground" a piece of a joint inside the rock: its support held
/// the rock there and left the slab free.
#[test]
fn groups_no_joint_reaches_keep_their_faces() {
    let case = Case::new("joints-untouched-groups");
    let geo = repo_text("tests/corpus/blocks3d.geo");
    let mut sets =
        vec![set("jx", 84.0, 90.0, 2.0, 1.0), set("jy", 88.0, 180.0, 2.5, -1.8), set("jz", 8.0, 200.0, 6.0, 2.5)];
    sets.iter_mut().for_each(|j| j.snap = 0.3);
    let (mesh, report) = cut_box(&case, &geo, 3, sets).expect("the cut succeeds");
    assert_eq!(report.blocks.iter().filter(|b| b.body == "rock").count(), 36, "36 blocks of rock");
    for (g, exact) in [("ground", 96.0), ("west", 36.0), ("seat", 60.0)] {
        let a = area(&mesh, g);
        assert!((a - exact).abs() < 1e-9 * exact, "{g}: area {a}, not {exact}");
    }
    let ground = mesh.group("ground").expect("the group ground");
    let z: Vec<f64> = ground.cells.iter().flat_map(|c| c.nodes.iter().map(|&n| mesh.coords[n][2])).collect();
    assert!(z.iter().all(|&z| (z + 1.0).abs() < 1e-9), "ground lies at z = -1: {z:?}");
}
