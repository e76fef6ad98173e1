//! In-situ stress. A geostatic column — sigma_v = -rho g (surface - y),
//! sigma_h = k0 sigma_v — is in equilibrium with its own weight inside a box
//! of rollers with a free top, so with `k0` and `surface` on the body and
//! gravity on, nothing moves and the reported (total) stress is the
//! geostatic one. A uniform `initial_stress` with matching tractions on the
//! boundary is a patch test of the same kind; released on a free face it
//! loads the body (excavation).

mod common;

use common::measure::max_abs;
use common::Case;

const GEO: &str = r#"
DefineConstant[ lc = {1.0, Name "lc"} ];
Point(1) = {0, 0, 0, lc}; Point(2) = {10, 0, 0, lc}; Point(3) = {10, 8, 0, lc}; Point(4) = {0, 8, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("ground") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
"#;

fn scene(initial: &str, loads: &str) -> String {
    format!(
        r#"mesh = "box.geo"
analysis = "plane_strain"
gravity = [0.0, -9.81]
[gmsh]
order = 2
[materials.soil]
E = 50.0
nu = 0.3
density = 2.0e-3
[[bodies]]
group = "ground"
material = "soil"
{initial}
{}
{loads}
[[probes]]
name = "depth"
from = [3.3, 0.5]
to = [3.3, 7.5]
points = 8
"#,
        common::scenes::on_rollers("bottom")
    )
}

#[test]
fn geostatic_stress_balances_gravity_so_nothing_moves() {
    let case = Case::new("initial-geostatic");
    case.write("box.geo", GEO);
    let toml = scene("k0 = 0.6\nsurface = 8.0", "");
    let run = case.run(&case.write("box.toml", &toml)).expect("run");
    let umax = max_abs(run.last().u.iter().copied());
    let rho_g = 2.0e-3 * 9.81;
    let scale = rho_g * 8.0;
    // the weight alone would move the top by rho g H^2 / (2 M) ~ 6e-3
    assert!(umax < 1e-12, "largest displacement {umax:e}");
    for s in &run.checks.probes[0].1 {
        let depth = 8.0 - s.x[1];
        let sv = -rho_g * depth;
        assert!((s.stress[1] - sv).abs() < 1e-10 * scale, "sigma_yy at depth {depth}: {} against {sv}", s.stress[1]);
        assert!((s.stress[0] - 0.6 * sv).abs() < 1e-10 * scale, "sigma_xx at depth {depth}");
        assert!(s.stress[3].abs() < 1e-10 * scale);
    }
}

#[test]
fn uniform_initial_stress_with_boundary_tractions_stays_uniform() {
    // sigma0 = [-2, -1, -0.9, 0.3]: tractions sigma0 . n on top and sides
    // would hold it; here the sides are rollers, so only the shear and the
    // top need tractions; with no gravity the stress stays sigma0.
    let case = Case::new("initial-uniform");
    case.write("box.geo", GEO);
    let toml =
        scene("initial_stress = [-2.0, -1.0, -0.9, 0.0]", "[[loads]]\ngroup = \"top\"\ntraction = [0.0, -1.0]\n")
            .replace("gravity = [0.0, -9.81]\n", "");
    let run = case.run(&case.write("box.toml", &toml)).expect("run");
    let umax = max_abs(run.last().u.iter().copied());
    assert!(umax < 1e-12, "largest displacement {umax:e}");
    for s in &run.checks.probes[0].1 {
        for (c, want) in [(0, -2.0), (1, -1.0), (2, -0.9), (3, 0.0)] {
            assert!((s.stress[c] - want).abs() < 1e-10, "component {c}: {} against {want}", s.stress[c]);
        }
    }
    // released at the free top: without the traction the top face unloads
    let case = Case::new("initial-released");
    case.write("box.geo", GEO);
    let toml = scene("initial_stress = [-2.0, -1.0, -0.9, 0.0]", "").replace("gravity = [0.0, -9.81]\n", "");
    let run = case.run(&case.write("box.toml", &toml)).expect("run");
    for s in &run.checks.probes[0].1 {
        // a confined column relieved of its vertical stress: sigma_yy = 0,
        // sigma_xx = -2 + nu/(1-nu) * 1 (plane strain, rollers at the sides)
        assert!(s.stress[1].abs() < 1e-9, "sigma_yy {}", s.stress[1]);
        assert!((s.stress[0] - (-2.0 + 0.3 / 0.7)).abs() < 1e-9, "sigma_xx {}", s.stress[0]);
    }
}

/// The same box as OpenCASCADE builds it, cut by two joints that cross
/// inside it and end on its rollers (`[[joint_sets]]`, one trace each).
const JOINTED: &str = r#"SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 10, 8};
e = 1e-3;
Physical Surface("ground") = {1};
Physical Curve("bottom") = Curve In BoundingBox{-e, -e, -e, 10 + e, e, e};
Physical Curve("top") = Curve In BoundingBox{-e, 8 - e, -e, 10 + e, 8 + e, e};
Physical Curve("sides") = Curve In BoundingBox{-e, -e, -e, e, 8 + e, e};
Physical Curve("sides") += Curve In BoundingBox{10 - e, -e, -e, 10 + e, 8 + e, e};
MeshSize{ PointsOf{ Surface{1}; } } = 1.0;
"#;

/// Geostatic stress in a box of rollers cut by two rigid joints that
/// cross: nothing moves, so every pair carries the in-situ traction
/// `σ0 n` where it is, exactly. Where a joint meets a roller, the support
/// and the joint's ties hold the same nodes, and rigid ties alone leave
/// their shares undetermined: the joint's is taken from what it carries
/// in situ (the limit of stiff joints, which carry it from the start).
/// Shared from nothing, the joint carried 0.137 of the 0.146 MPa at the
/// left roller (pair 0), 17 % of the rest going to the support.
#[test]
fn joints_in_a_geostatic_box_carry_the_in_situ_traction_to_the_rollers() {
    let case = Case::new("initial-jointed");
    case.write("box.geo", JOINTED);
    let (k0, rho_g, top) = (0.5, 2.7e-3 * 9.81, 8.0);
    let set = |name: &str, angle: f64, offset: f64| {
        format!("[[joint_sets]]\nname = \"{name}\"\nangle = {angle:?}\nspacing = 100.0\noffset = {offset:?}\nfriction = 0.9\n")
    };
    let toml = format!(
        "mesh = \"box.geo\"\nanalysis = \"plane_strain\"\ngravity = [0.0, -9.81]\n[gmsh]\norder = 2\n\
         [materials.rock]\nE = 5000.0\nnu = 0.25\ndensity = 2.7e-3\n\
         [[bodies]]\ngroup = \"ground\"\nmaterial = \"rock\"\nk0 = {k0:?}\nsurface = {top:?}\n\
         {}{}[[supports]]\ngroup = \"sides\"\nfix = [\"x\"]\n[[supports]]\ngroup = \"bottom\"\nfix = [\"y\"]\n",
        set("a", 20.0, 2.0),
        set("b", 100.0, -5.0),
    );
    case.write("box.toml", &toml);
    let o = case.cli(&["solve", "box.toml", "--out", "out", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = common::csv_rows(&case.dir.join("out/contact.csv"));
    let on_rollers = rows.iter().filter(|r| {
        let (x, y) = (common::csv_num(r, "x"), common::csv_num(r, "y"));
        x.abs() < 1e-9 || (x - 10.0).abs() < 1e-9 || y.abs() < 1e-9
    });
    assert!(on_rollers.count() >= 3, "both joints end on rollers");
    for r in &rows {
        let num = |k: &str| common::csv_num(r, k);
        let sv = -rho_g * (top - num("y"));
        let (nx, ny) = (num("n_x"), num("n_y"));
        let t = [k0 * sv * nx, sv * ny];
        let (sigma_n, tau) = (t[0] * nx + t[1] * ny, t[1] * nx - t[0] * ny);
        assert_eq!(r["status"], "2", "pair {} sticks", r["pair"]);
        let off = (num("sigma_n") - sigma_n).abs().max((num("tau_t").abs() - tau.abs()).abs());
        assert!(
            off < 1e-9 * rho_g * top,
            "pair {} at ({}, {}): sigma_n {} tau {} against {sigma_n}, {tau}",
            r["pair"],
            r["x"],
            r["y"],
            r["sigma_n"],
            r["tau_t"]
        );
    }
}
