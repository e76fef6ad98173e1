//! Patch tests: a uniform stress state is reproduced exactly, on distorted
//! meshes, by every element kind in every analysis.
//!
//! Reference: B. M. Irons and A. Razzaque (1972), "Experience with the patch
//! test for convergence of finite elements"; O. C. Zienkiewicz and R. L.
//! Taylor, *The Finite Element Method*, vol. 1, ch. 9 (the patch test);
//! R. H. MacNeal and R. L. Harder (1985), "A proposed standard set of
//! problems to test finite element accuracy" (distorted patches).
//!
//! Goal: an element that converges must represent a state of constant
//! strain exactly, whatever the shape of the element. When the loads are
//! those of a uniform stress sigma, the finite element solution must be the
//! exact linear displacement field (up to the rigid-body motion the supports
//! leave), and the stress must equal sigma at every Gauss point, at every
//! node of the output (extrapolated and averaged) and at any probed point,
//! to round-off (1e-10 relative to |sigma|).
//!
//! ```text
//!        4 +-----------------+ 3      a domain with straight sides, each
//!         /  distorted mesh   \       side its own physical group loaded
//!        /                     \      by the traction t = sigma n
//!     A o-----------------------o B
//!       fixed x, y              fixed y (2D); 3D: A xyz, B yz, C z
//! ```
//!
//! The sides' outward normals n are computed from the `Point` coordinates of
//! the `.geo`, read by the test. Meshes (tests/geo/patch_quad.geo,
//! patch_hex.geo) follow MacNeal and Harder: a domain with no two sides
//! (faces) parallel, cut by an irregular inner quadrilateral (hexahedron)
//! into 5 (7) blocks; quadrilaterals and hexahedra are transfinite blocks
//! (checked to contain no parallelogram or parallelepiped: the corners are
//! at least 2 % of the cell size off the best affine fit), triangles and
//! tetrahedra unstructured. Second order by `gmsh -order 2` (tri6, quad9,
//! tet10, hex27) and with `Mesh.SecondOrderIncomplete = 1` (quad8, hex20).
//!
//! Prisms and pyramids (tests/geo/patch_shell.geo, the same hexahedron's
//! outer shell cut in two blocks): transfinite blocks with triangulated caps
//! (prism6, prism18, prism15: the caps are not parallel, so no prism is
//! affine); transfinite quadrangles on the outer faces around unstructured
//! tetrahedra (a pyramid on each: pyramid5, pyramid14, pyramid13, none with
//! a parallelogram base); and a block of hexahedra against a block of
//! prisms. patch_hex.geo with `mixed = 1` gives a hexahedral core in
//! tetrahedra with pyramids between them (hex8/tet4/pyramid5,
//! hex27/tet10/pyramid14, hex20/tet10/pyramid13).
//!
//! Parameters: E = 1000, nu = 0.3; plane states sigma_xx = 3, sigma_yy = -2,
//! sigma_xy = 1.5 (plane strain adds sigma_zz = nu (sigma_xx + sigma_yy));
//! axisymmetric sigma_rr = sigma_tt = 2, sigma_zz = -1.5, sigma_rz = 0
//! (equilibrium needs sigma_rr = sigma_tt; the state is then a constant
//! Cartesian tensor, so the slanted sides carry sigma n too, and only the
//! axial translation is a rigid motion: one point holds u_z); solid: all six
//! components non-zero.
//!
//! On the axis: an axisymmetric domain with one side on r = 0
//! (tests/geo/patch_axis.geo), probed from a point on the axis, where the
//! hoop strain u_r / r is 0 / 0 and the kernel must take its limit du_r/dr.
//!
//! Curved sides: a hydrostatic state sigma = -p I (p = 2.5) on an annular
//! sector (tests/geo/patch_curved*.geo) loaded by `pressure = p` on every
//! side, in plane strain, axisymmetry and 3D. The exact linear field lies in
//! the span of isoparametric quadratic elements even where they are curved,
//! and their stiffness rules integrate a curved cell's `∫ B^T sigma dV`
//! exactly for tri6, quad8, quad9 (plane), quad8, quad9 (axisymmetric),
//! hex20, hex27 and the prisms extruded from the sector's triangulated plan
//! (prism15, prism18). Not for tet10 (degree-2 rule, the integrand is cubic on a
//! curved cell: 2.6e-5 off, measured) nor for curved tri6 in axisymmetry
//! (the weight r raises the degree: 1.5e-3 off); those two are left out.

mod common;

use std::collections::HashMap;
use std::path::Path;

use common::{read, Case};
use subcontact::driver::Run;
use subcontact::fem::{element, material, quadrature};
use subcontact::mesh::CellKind;
use subcontact::recover;
use subcontact::scene::Probe;

const E: f64 = 1000.0;
const NU: f64 = 0.3;
/// Relative tolerance of every patch check.
const TOL: f64 = 1e-10;

type Vec3 = [f64; 3];

/// A uniform stress, `[xx, yy, zz, xy, yz, xz]`.
#[derive(Clone, Copy)]
struct Uniform([f64; 6]);

impl Uniform {
    fn tensor(&self) -> [[f64; 3]; 3] {
        let [xx, yy, zz, xy, yz, xz] = self.0;
        [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
    }
    /// Traction sigma n.
    fn traction(&self, n: Vec3) -> Vec3 {
        let s = self.tensor();
        std::array::from_fn(|i| (0..3).map(|j| s[i][j] * n[j]).sum())
    }
    /// Strain tensor by Hooke's law, eps = ((1 + nu) sigma - nu tr(sigma) I) / E.
    fn strain(&self) -> [[f64; 3]; 3] {
        let s = self.tensor();
        let tr = s[0][0] + s[1][1] + s[2][2];
        std::array::from_fn(|i| {
            std::array::from_fn(|j| ((1.0 + NU) * s[i][j] - if i == j { NU * tr } else { 0.0 }) / E)
        })
    }
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn unit(a: Vec3) -> Vec3 {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}
fn mat_vec(m: &[[f64; 3]; 3], v: Vec3) -> Vec3 {
    std::array::from_fn(|i| dot(m[i], v))
}

/// The `Point(k) = {x, y, z, ...}` coordinates of a .geo with literal numbers.
fn geo_points(geo: &Path) -> HashMap<usize, Vec3> {
    let text = read(geo);
    let mut pts = HashMap::new();
    for line in text.lines() {
        let Some(rest) = line.trim().strip_prefix("Point(") else { continue };
        let (id, rest) = rest.split_once(')').expect("Point(id)");
        let body = rest.split_once('{').expect("{").1.split_once('}').expect("}").0;
        let v: Vec<f64> = body.split(',').take(3).map(|s| s.trim().parse().expect("literal coordinate")).collect();
        pts.insert(id.trim().parse().expect("point id"), [v[0], v[1], v[2]]);
    }
    pts
}

fn centroid(pts: &[Vec3]) -> Vec3 {
    let n = pts.len() as f64;
    std::array::from_fn(|i| pts.iter().map(|p| p[i]).sum::<f64>() / n)
}

/// Outward unit normal of a planar face (2 points in 2D, 4 in 3D) of a convex domain with centroid `c`.
fn outward_normal(face: &[Vec3], c: Vec3) -> Vec3 {
    let n = if face.len() == 2 {
        let t = sub(face[1], face[0]);
        [t[1], -t[0], 0.0]
    } else {
        // the diagonals span the plane; they also give a planarity check
        let n = cross(sub(face[2], face[0]), sub(face[3], face[1]));
        let off = dot(sub(face[3], face[0]), unit(n)).abs();
        assert!(off < 1e-13 * dot(n, n).sqrt().sqrt(), "face is not planar ({off:e})");
        n
    };
    let n = unit(n);
    if dot(n, sub(face[0], c)) > 0.0 {
        n
    } else {
        [-n[0], -n[1], -n[2]]
    }
}

/// One element kind of a patch: the gmsh parameters that make it.
struct Kind {
    kind: CellKind,
    order: usize,
    /// Quadrilaterals / hexahedra (transfinite blocks), not simplices.
    structured: bool,
    serendipity: bool,
}

fn kinds_2d() -> Vec<Kind> {
    vec![
        Kind { kind: CellKind::Tri3, order: 1, structured: false, serendipity: false },
        Kind { kind: CellKind::Tri6, order: 2, structured: false, serendipity: false },
        Kind { kind: CellKind::Quad4, order: 1, structured: true, serendipity: false },
        Kind { kind: CellKind::Quad8, order: 2, structured: true, serendipity: true },
        Kind { kind: CellKind::Quad9, order: 2, structured: true, serendipity: false },
    ]
}

fn kinds_3d() -> Vec<Kind> {
    vec![
        Kind { kind: CellKind::Tet4, order: 1, structured: false, serendipity: false },
        Kind { kind: CellKind::Tet10, order: 2, structured: false, serendipity: false },
        Kind { kind: CellKind::Hex8, order: 1, structured: true, serendipity: false },
        Kind { kind: CellKind::Hex20, order: 2, structured: true, serendipity: true },
        Kind { kind: CellKind::Hex27, order: 2, structured: true, serendipity: false },
    ]
}

/// The scene of one patch run.
fn scene(
    geo: &str,
    analysis: &str,
    k: &Kind,
    switch: &str,
    loads: &[(String, String)],
    supports: &[(&str, &str)],
) -> String {
    let set = format!("{switch} = {}, serendipity = {}", k.structured as u8, k.serendipity as u8);
    scene_with(geo, analysis, k.order, &set, loads, supports)
}

/// The scene of one patch run, with the `setnumber` entries `set`.
fn scene_with(
    geo: &str,
    analysis: &str,
    order: usize,
    set: &str,
    loads: &[(String, String)],
    supports: &[(&str, &str)],
) -> String {
    let mut s = format!(
        "mesh = \"{geo}\"\nanalysis = \"{analysis}\"\n\n[gmsh]\norder = {order}\nsetnumber = {{ {set} }}\n\n\
         [materials.m]\nE = {E}\nnu = {NU}\n\n[[bodies]]\ngroup = \"body\"\nmaterial = \"m\"\n"
    );
    for (group, load) in loads {
        s += &format!("\n[[loads]]\ngroup = \"{group}\"\n{load}\n");
    }
    for (group, fix) in supports {
        s += &format!("\n[[supports]]\ngroup = \"{group}\"\nfix = {fix}\n");
    }
    s
}

fn fmt_vec(v: Vec3, dim: usize) -> String {
    let c: Vec<String> = v[..dim].iter().map(|x| format!("{x:.17e}")).collect();
    format!("[{}]", c.join(", "))
}

/// Largest deviations from the uniform state, relative to |sigma| (stress) and max |u| (displacement).
#[derive(Debug, Default)]
struct Deviation {
    gauss: f64,
    nodal: f64,
    probe: f64,
    displacement: f64,
}

impl Deviation {
    fn max(&self) -> f64 {
        worst(worst(self.gauss, self.nodal), worst(self.probe, self.displacement))
    }
}

/// The larger of two deviations; NaN wins (f64::max would drop it).
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

fn stress_dev(s: &[f64; 6], exact: &[f64; 6], scale: f64) -> f64 {
    s.iter().zip(exact).map(|(a, b)| (a - b).abs()).fold(0.0, worst) / scale
}

/// Compares a run with the uniform stress `sigma` (as the solver reports it,
/// six components) and the displacement `u_exact`; `probe` runs across the domain.
fn deviation(run: &Run, sigma: &[f64; 6], u_exact: &dyn Fn(Vec3) -> Vec3, probe: (Vec3, Vec3)) -> Deviation {
    let m = &run.model;
    let nd = m.nd;
    let scale = sigma.iter().fold(0.0, |a: f64, v| a.max(v.abs()));
    let mut dev = Deviation::default();
    // every Gauss point of the stiffness rule
    let mut n_points = 0;
    for body in &m.bodies {
        let d = material::d_matrix(m.analysis, body.material.e, body.material.nu);
        for cell in &body.cells {
            let xe: Vec<Vec3> = cell.nodes.iter().map(|&n| m.coords[n]).collect();
            let ue: Vec<f64> =
                cell.nodes.iter().flat_map(|&n| (0..nd).map(move |c| run.last().u[n * nd + c])).collect();
            // the strain the stiffness used: B-bar's where the cell has it
            let mean = element::mean_dilatation(m.analysis, cell.kind, body.material.nu, &xe, &ue);
            for q in quadrature::stiffness_rule(cell.kind) {
                let p = element::point(cell.kind, &xe, q.xi).expect("cell not inverted");
                let s = material::full_stress(
                    m.analysis,
                    body.material.e,
                    body.material.nu,
                    &d,
                    &element::strain(m.analysis, &p, &ue, mean),
                );
                dev.gauss = worst(dev.gauss, stress_dev(&s, sigma, scale));
                n_points += 1;
            }
        }
    }
    assert!(n_points > 0);
    // every node of the output
    for bs in &run.last().stresses {
        assert!(!bs.nodes.is_empty());
        for s in &bs.stress {
            dev.nodal = worst(dev.nodal, stress_dev(s, sigma, scale));
        }
    }
    // probed points, evaluated in the element that contains them
    let pr = Probe { name: "across".into(), from: probe.0, to: probe.1, points: 11 };
    for s in recover::probe(m, &run.last().u, &pr) {
        assert!(s.found, "probe point {:?} outside the model", s.x);
        dev.probe = worst(dev.probe, stress_dev(&s.stress, sigma, scale));
        let ue = u_exact(s.x);
        let du = (0..nd).map(|c| (s.displacement[c] - ue[c]).abs()).fold(0.0, worst);
        dev.displacement = worst(dev.displacement, du);
    }
    // every node's displacement
    let mut u_max: f64 = 0.0;
    for body in &m.bodies {
        for cell in &body.cells {
            for &n in &cell.nodes {
                let ue = u_exact(m.coords[n]);
                for c in 0..nd {
                    dev.displacement = worst(dev.displacement, (run.last().u[n * nd + c] - ue[c]).abs());
                    u_max = u_max.max(ue[c].abs());
                }
            }
        }
    }
    dev.displacement /= u_max;
    dev
}

/// How far the corners of a quadrilateral or hexahedron are from an affine
/// image of the reference cell (a parallelogram / parallelepiped), relative
/// to the longest corner-to-corner distance; 0 for simplices.
fn non_affinity(kind: CellKind, corners: &[Vec3]) -> f64 {
    if matches!(kind, CellKind::Tri3 | CellKind::Tri6 | CellKind::Tet4 | CellKind::Tet10) {
        return 0.0;
    }
    let size = corners
        .iter()
        .flat_map(|x| corners.iter().map(move |y| dot(sub(*x, *y), sub(*x, *y)).sqrt()))
        .fold(0.0, f64::max);
    let len = |v: Vec3| dot(v, v).sqrt();
    match kind.n_corners() {
        // a prism is affine when its top triangle is its bottom one translated
        6 => {
            let (d0, d1, d2) = (sub(corners[3], corners[0]), sub(corners[4], corners[1]), sub(corners[5], corners[2]));
            return len(sub(d1, d0)).max(len(sub(d2, d0))) / size;
        }
        // a pyramid is affine when its base is a parallelogram
        5 => return len(sub(sub(corners[0], corners[1]), sub(corners[3], corners[2]))) / size,
        _ => {}
    }
    let refs = &subcontact::fem::shape::reference_nodes(kind)[..corners.len()];
    // corners of [-1,1]^d: zero mean, orthogonal coordinates, so the least-
    // squares affine fit is c + sum_j xi_j a_j with a_j = sum x xi_j / n
    let c = centroid(corners);
    let nn = corners.len() as f64;
    let a: Vec<Vec3> = (0..kind.dim())
        .map(|j| std::array::from_fn(|i| corners.iter().zip(refs).map(|(x, r)| x[i] * r[j]).sum::<f64>() / nn))
        .collect();
    let mut res: f64 = 0.0;
    let mut size: f64 = 0.0;
    for (x, r) in corners.iter().zip(refs) {
        let fit: Vec3 = std::array::from_fn(|i| c[i] + (0..kind.dim()).map(|j| r[j] * a[j][i]).sum::<f64>());
        res = res.max(dot(sub(*x, fit), sub(*x, fit)).sqrt());
        for y in corners {
            size = size.max(dot(sub(*x, *y), sub(*x, *y)).sqrt());
        }
    }
    res / size
}

/// Checks the cells are all of the wanted kind and returns the smallest non-affinity over them.
fn check_mesh(run: &Run, kind: CellKind) -> f64 {
    let mut least = f64::INFINITY;
    for body in &run.model.bodies {
        assert!(!body.cells.is_empty());
        for cell in &body.cells {
            assert_eq!(cell.kind, kind, "gmsh made {} instead of {}", cell.kind.name(), kind.name());
            let corners: Vec<Vec3> = cell.nodes[..kind.n_corners()].iter().map(|&n| run.model.coords[n]).collect();
            least = least.min(non_affinity(kind, &corners));
        }
    }
    least
}

/// Checks the cells are of the wanted kinds, each of them present, and
/// returns the smallest non-affinity over the cells of kind `special`.
fn check_kinds(run: &Run, kinds: &[CellKind], special: CellKind) -> f64 {
    let mut least = f64::INFINITY;
    let mut seen = Vec::new();
    for cell in run.model.bodies.iter().flat_map(|b| &b.cells) {
        assert!(kinds.contains(&cell.kind), "gmsh made {} (expected {:?})", cell.kind.name(), kinds);
        if !seen.contains(&cell.kind) {
            seen.push(cell.kind);
        }
        if cell.kind == special {
            let corners: Vec<Vec3> = cell.nodes[..special.n_corners()].iter().map(|&n| run.model.coords[n]).collect();
            least = least.min(non_affinity(special, &corners));
        }
    }
    assert_eq!(seen.len(), kinds.len(), "gmsh made only {seen:?} of {kinds:?}");
    least
}

/// Runs the 2D patch of `analysis` for every 2D element kind: loads from
/// `sigma_in`, expects `sigma_out` (the six reported components).
fn patch_2d(analysis: &str, sigma_in: Uniform, sigma_out: [f64; 6]) {
    let case = Case::new(&format!("patch-{analysis}"));
    let geo = case.copy("tests/geo/patch_quad.geo");
    let pts = geo_points(&geo);
    let c = centroid(&[pts[&1], pts[&2], pts[&3], pts[&4]]);
    let loads: Vec<(String, String)> = [(1, 2), (2, 3), (3, 4), (4, 1)]
        .iter()
        .map(|&(i, j)| {
            let n = outward_normal(&[pts[&i], pts[&j]], c);
            (format!("side_{i}{j}"), format!("traction = {}", fmt_vec(sigma_in.traction(n), 2)))
        })
        .collect();
    let axisym = analysis == "axisymmetric";
    let supports: Vec<(&str, &str)> =
        if axisym { vec![("A", "[\"y\"]")] } else { vec![("A", "[\"x\", \"y\"]"), ("B", "[\"y\"]")] };
    let eps = sigma_in.strain();
    let (a, b) = (pts[&1], pts[&2]);
    // the rigid rotation w that keeps u_y(B) = 0 with u(A) = 0: u = eps d + w (-d_y, d_x)
    let d_ab = sub(b, a);
    let w = -mat_vec(&eps, d_ab)[1] / d_ab[0];
    let u_exact = move |x: Vec3| -> Vec3 {
        if axisym {
            // u_r = eps_tt r (no rigid radial motion), u_z = eps_zz (z - z_A)
            [eps[0][0] * x[0], eps[1][1] * (x[1] - a[1]), 0.0]
        } else {
            let d = sub(x, a);
            let u = mat_vec(&eps, d);
            [u[0] - w * d[1], u[1] + w * d[0], 0.0]
        }
    };
    if axisym {
        // the state is axisymmetric only with sigma_rr = sigma_tt
        assert_eq!(sigma_in.0[0], sigma_in.0[2]);
        assert_eq!(eps[0][0], eps[2][2]);
    }
    // a diagonal, 20 % in from the corners
    let from: Vec3 = std::array::from_fn(|i| 0.8 * pts[&1][i] + 0.2 * c[i]);
    let to: Vec3 = std::array::from_fn(|i| 0.8 * pts[&3][i] + 0.2 * c[i]);
    let mut failures = Vec::new();
    for k in kinds_2d() {
        let name = format!("{}_{analysis}", k.kind.name());
        let text = scene("patch_quad.geo", analysis, &k, "quads", &loads, &supports);
        let path = case.write(&format!("{name}.toml"), &text);
        let run = case.run(&path).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let distortion = check_mesh(&run, k.kind);
        if k.structured {
            assert!(distortion > 0.02, "{name}: the quadrilaterals are nearly parallelograms ({distortion:.3})");
        }
        let dev = deviation(&run, &sigma_out, &u_exact, (from, to));
        eprintln!(
            "{name:>24}: {} cells, least non-affinity {:.3}; max deviation gauss {:.1e} nodal {:.1e} probe {:.1e} displacement {:.1e}",
            run.model.bodies[0].cells.len(),
            if k.structured { distortion } else { f64::NAN },
            dev.gauss,
            dev.nodal,
            dev.probe,
            dev.displacement
        );
        if !(dev.max() < TOL) {
            failures.push(format!("{name}: {dev:?}"));
        }
    }
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}

fn plane_state() -> Uniform {
    Uniform([3.0, -2.0, 0.0, 1.5, 0.0, 0.0])
}

#[test]
fn uniform_stress_is_exact_in_plane_strain_on_distorted_tri3_tri6_quad4_quad8_quad9() {
    let s = plane_state();
    // sigma_zz = nu (sigma_xx + sigma_yy) keeps eps_zz = 0
    let szz = NU * (s.0[0] + s.0[1]);
    let sigma_in = Uniform([s.0[0], s.0[1], szz, s.0[3], 0.0, 0.0]);
    patch_2d("plane_strain", sigma_in, sigma_in.0);
}

#[test]
fn uniform_stress_is_exact_in_plane_stress_on_distorted_tri3_tri6_quad4_quad8_quad9() {
    let s = plane_state();
    patch_2d("plane_stress", s, s.0);
}

#[test]
fn uniform_stress_is_exact_in_axisymmetry_on_distorted_tri3_tri6_quad4_quad8_quad9() {
    // meridian components [rr, zz, tt, rz] sit in the [xx, yy, zz, xy] slots
    let s = Uniform([2.0, -1.5, 2.0, 0.0, 0.0, 0.0]);
    patch_2d("axisymmetric", s, s.0);
}

/// Regression: on the axis (r = 0) the hoop strain u_r / r is 0 / 0; the
/// probe there gave NaN stresses before the kernel took the limit du_r/dr.
#[test]
fn uniform_stress_is_exact_in_axisymmetry_up_to_and_on_the_axis() {
    let case = Case::new("patch-axis");
    let geo = case.copy("tests/geo/patch_axis.geo");
    let pts = geo_points(&geo);
    let c = centroid(&[pts[&1], pts[&2], pts[&3], pts[&4]]);
    assert!(pts[&1][0] == 0.0 && pts[&4][0] == 0.0, "side 4-1 lies on the axis");
    let sigma = Uniform([2.0, -1.5, 2.0, 0.0, 0.0, 0.0]);
    // the side on the axis carries nothing (its measure 2 pi r vanishes)
    let loads: Vec<(String, String)> = [(1, 2), (2, 3), (3, 4)]
        .iter()
        .map(|&(i, j)| {
            (
                format!("side_{i}{j}"),
                format!("traction = {}", fmt_vec(sigma.traction(outward_normal(&[pts[&i], pts[&j]], c)), 2)),
            )
        })
        .collect();
    let eps = sigma.strain();
    let y_a = pts[&1][1];
    let u_exact = move |x: Vec3| -> Vec3 { [eps[0][0] * x[0], eps[1][1] * (x[1] - y_a), 0.0] };
    // from a point on the axis, across the domain
    let from: Vec3 = [0.0, 0.5 * (pts[&1][1] + pts[&4][1]), 0.0];
    let to: Vec3 = std::array::from_fn(|i| 0.8 * pts[&3][i] + 0.2 * c[i]);
    let mut failures = Vec::new();
    for k in kinds_2d() {
        let name = format!("{}_axis", k.kind.name());
        let text = scene("patch_axis.geo", "axisymmetric", &k, "quads", &loads, &[("A", "[\"y\"]")]);
        let path = case.write(&format!("{name}.toml"), &text);
        let run = case.run(&path).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        check_mesh(&run, k.kind);
        let dev = deviation(&run, &sigma.0, &u_exact, (from, to));
        eprintln!(
            "{name:>24}: {} cells; max deviation gauss {:.1e} nodal {:.1e} probe {:.1e} displacement {:.1e}",
            run.model.bodies[0].cells.len(),
            dev.gauss,
            dev.nodal,
            dev.probe,
            dev.displacement
        );
        if !(dev.max() < TOL) {
            failures.push(format!("{name}: {dev:?}"));
        }
    }
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}

/// The rigid rotation w that, with u(A) = 0 and u = eps d + w x d (d = x - A),
/// meets the 3-2-1 conditions u_y(B) = u_z(B) = u_z(C) = 0.
fn rotation_321(eps: &[[f64; 3]; 3], db: Vec3, dc: Vec3) -> Vec3 {
    // (w x d)_c as a row over w: c = y: [-d_z, 0, d_x]; c = z: [d_y, -d_x, 0]
    let m = [[-db[2], 0.0, db[0]], [db[1], -db[0], 0.0], [dc[1], -dc[0], 0.0]];
    let r = [-mat_vec(eps, db)[1], -mat_vec(eps, db)[2], -mat_vec(eps, dc)[2]];
    let det = |m: &[[f64; 3]; 3]| dot(m[0], cross(m[1], m[2]));
    let d = det(&m);
    assert!(d.abs() > 1e-6, "the 3-2-1 points do not hold the rigid motions");
    std::array::from_fn(|j| {
        let mut mj = m;
        for (row, rv) in mj.iter_mut().zip(r) {
            row[j] = rv;
        }
        det(&mj) / d
    })
}

/// One mesh of a 3D patch: its name, the `setnumber` entries, the gmsh
/// order, the kinds it must hold, and the kind whose distortion is measured
/// (None: simplices, unstructured by nature).
struct SolidRun {
    name: String,
    set: String,
    order: usize,
    kinds: Vec<CellKind>,
    distorted: Option<CellKind>,
}

/// The 3D patch on a copy of the repository's `geo` (whose Points 1..8 are
/// the corners of MacNeal and Harder's hexahedron, its faces the physical
/// surfaces face_IJKL): every run of `runs` reproduces the uniform state.
fn solid_patch(case_name: &str, geo: &str, runs: &[SolidRun]) {
    let case = Case::new(case_name);
    let geo = case.copy(geo);
    let geo_name = geo.file_name().unwrap().to_string_lossy().to_string();
    let pts = geo_points(&geo);
    let all: Vec<Vec3> = (1..=8).map(|i| pts[&i]).collect();
    let c = centroid(&all);
    let sigma = Uniform([3.0, -2.0, 1.0, 1.5, -0.7, 0.9]);
    let faces: [[usize; 4]; 6] = [[1, 2, 3, 4], [5, 6, 7, 8], [1, 2, 6, 5], [2, 3, 7, 6], [3, 4, 8, 7], [4, 1, 5, 8]];
    let normals: Vec<Vec3> = faces.iter().map(|f| outward_normal(&f.map(|i| pts[&i]), c)).collect();
    // no two faces are parallel
    for i in 0..6 {
        for j in 0..i {
            let s = dot(normals[i], normals[j]).abs();
            assert!(s < 0.999, "faces {:?} and {:?} are parallel", faces[i], faces[j]);
        }
    }
    let loads: Vec<(String, String)> = faces
        .iter()
        .zip(&normals)
        .map(|(f, &n)| {
            (
                format!("face_{}", f.iter().map(|i| i.to_string()).collect::<String>()),
                format!("traction = {}", fmt_vec(sigma.traction(n), 3)),
            )
        })
        .collect();
    let supports = [("A", "[\"x\", \"y\", \"z\"]"), ("B", "[\"y\", \"z\"]"), ("C", "[\"z\"]")];
    let eps = sigma.strain();
    let a = pts[&1];
    let w = rotation_321(&eps, sub(pts[&2], a), sub(pts[&4], a));
    let u_exact = move |x: Vec3| -> Vec3 {
        let d = sub(x, a);
        let u = mat_vec(&eps, d);
        let r = cross(w, d);
        [u[0] + r[0], u[1] + r[1], u[2] + r[2]]
    };
    let from: Vec3 = std::array::from_fn(|i| 0.8 * pts[&1][i] + 0.2 * c[i]);
    let to: Vec3 = std::array::from_fn(|i| 0.8 * pts[&7][i] + 0.2 * c[i]);
    let mut failures = Vec::new();
    for r in runs {
        let text = scene_with(&geo_name, "solid", r.order, &r.set, &loads, &supports);
        let path = case.write(&format!("{}.toml", r.name), &text);
        let run = case.run(&path).unwrap_or_else(|e| panic!("{}: {e:#}", r.name));
        let distortion = check_kinds(&run, &r.kinds, r.distorted.unwrap_or(r.kinds[0]));
        if r.distorted.is_some() {
            assert!(distortion > 0.02, "{}: the cells are nearly affine ({distortion:.3})", r.name);
        }
        let dev = deviation(&run, &sigma.0, &u_exact, (from, to));
        eprintln!(
            "{:>24}: {} cells, least non-affinity {:.3}; max deviation gauss {:.1e} nodal {:.1e} probe {:.1e} displacement {:.1e}",
            r.name,
            run.model.bodies[0].cells.len(),
            if r.distorted.is_some() { distortion } else { f64::NAN },
            dev.gauss,
            dev.nodal,
            dev.probe,
            dev.displacement
        );
        if !(dev.max() < TOL) {
            failures.push(format!("{}: {dev:?}", r.name));
        }
    }
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}

#[test]
fn uniform_stress_is_exact_in_solids_on_distorted_tet4_tet10_hex8_hex20_hex27() {
    let runs: Vec<SolidRun> = kinds_3d()
        .into_iter()
        .map(|k| SolidRun {
            name: k.kind.name().to_string(),
            set: format!("hexes = {}, serendipity = {}", k.structured as u8, k.serendipity as u8),
            order: k.order,
            kinds: vec![k.kind],
            distorted: k.structured.then_some(k.kind),
        })
        .collect();
    solid_patch("patch-solid", "tests/geo/patch_hex.geo", &runs);
}

/// tests/geo/patch_shell.geo's runs: `cells` (1 prisms, 2 pyramids among
/// tetrahedra, 3 hexahedra and prisms) at orders 1, 2 and 2 incomplete.
fn shell_runs(cells: usize, kinds: [[CellKind; 2]; 3], distorted: [CellKind; 3]) -> Vec<SolidRun> {
    (0..3)
        .map(|i| {
            let (order, serendipity) = [(1, 0), (2, 0), (2, 1)][i];
            let mut kinds = kinds[i].to_vec();
            kinds.dedup();
            SolidRun {
                name: kinds.iter().map(|k| k.name()).collect::<Vec<_>>().join("+"),
                // one quadrangle per block face for the pyramids: the
                // subdivided ones come close to parallelograms
                set: format!("cells = {cells}, serendipity = {serendipity}, n = {}", if cells == 2 { 1 } else { 2 }),
                order,
                kinds,
                distorted: Some(distorted[i]),
            }
        })
        .collect()
}

#[test]
fn uniform_stress_is_exact_on_distorted_prism6_prism15_prism18() {
    use CellKind::*;
    // the shell's caps are not parallel: no prism has parallel triangles
    let runs = shell_runs(1, [[Prism6; 2], [Prism18; 2], [Prism15; 2]], [Prism6, Prism18, Prism15]);
    solid_patch("patch-prism", "tests/geo/patch_shell.geo", &runs);
}

#[test]
fn uniform_stress_is_exact_on_distorted_pyramid5_pyramid13_pyramid14_among_tetrahedra() {
    use CellKind::*;
    // a pyramid on each quadrangle of the faces, none of them a parallelogram
    let runs =
        shell_runs(2, [[Tet4, Pyramid5], [Tet10, Pyramid14], [Tet10, Pyramid13]], [Pyramid5, Pyramid14, Pyramid13]);
    solid_patch("patch-pyramid", "tests/geo/patch_shell.geo", &runs);
}

/// Mixed meshes: prisms against hexahedra (tests/geo/patch_shell.geo,
/// cells = 3), and a hexahedral core in tetrahedra with pyramids between
/// them (tests/geo/patch_hex.geo, mixed = 1: hex-dominant meshes of the
/// kind gmsh makes when a recombined volume meets an unstructured one).
#[test]
fn uniform_stress_is_exact_on_mixed_hexahedra_prisms_pyramids_and_tetrahedra() {
    use CellKind::*;
    let runs = shell_runs(3, [[Hex8, Prism6], [Hex27, Prism18], [Hex20, Prism15]], [Prism6, Prism18, Prism15]);
    solid_patch("patch-hex-prism", "tests/geo/patch_shell.geo", &runs);
    let runs: Vec<SolidRun> =
        [(1, 0, [Hex8, Tet4, Pyramid5]), (2, 0, [Hex27, Tet10, Pyramid14]), (2, 1, [Hex20, Tet10, Pyramid13])]
            .into_iter()
            .map(|(order, serendipity, kinds)| SolidRun {
                name: kinds.iter().map(|k| k.name()).collect::<Vec<_>>().join("+"),
                set: format!("mixed = 1, n = 2, serendipity = {serendipity}"),
                order,
                kinds: kinds.to_vec(),
                distorted: Some(kinds[2]),
            })
            .collect();
    solid_patch("patch-hex-pyramid-tet", "tests/geo/patch_hex.geo", &runs);
}

/// The largest distance of a second-order node from where the straight-
/// sided (linear sibling) element would put it, relative to the cell size:
/// 0 for straight-sided meshes.
fn curvedness(run: &Run) -> f64 {
    use subcontact::fem::shape;
    let mut worst: f64 = 0.0;
    for body in &run.model.bodies {
        for cell in &body.cells {
            let lin = shape::linear_sibling(cell.kind);
            let nc = lin.n_nodes();
            let x: Vec<Vec3> = cell.nodes.iter().map(|&n| run.model.coords[n]).collect();
            let size = (0..nc)
                .flat_map(|i| (0..nc).map(move |j| (i, j)))
                .map(|(i, j)| dot(sub(x[i], x[j]), sub(x[i], x[j])).sqrt())
                .fold(0.0, f64::max);
            let (mut n, mut dn) = (vec![0.0; nc], vec![[0.0; 3]; nc]);
            for (a, xi) in shape::reference_nodes(cell.kind).iter().enumerate() {
                shape::eval(lin, *xi, &mut n, &mut dn);
                let straight: Vec3 = std::array::from_fn(|i| (0..nc).map(|b| n[b] * x[b][i]).sum());
                worst = worst.max(dot(sub(x[a], straight), sub(x[a], straight)).sqrt() / size);
            }
        }
    }
    worst
}

/// Hydrostatic patch on a domain with curved sides: every side carries
/// `pressure = p`; returns the failures.
#[allow(clippy::too_many_arguments)]
fn hydrostatic(
    case: &Case,
    geo: &str,
    analysis: &str,
    switch: &str,
    kinds: &[Kind],
    supports: &[(&str, &str)],
    u_exact: &dyn Fn(Vec3) -> Vec3,
    sigma: [f64; 6],
    probe: (Vec3, Vec3),
) -> Vec<String> {
    let mut failures = Vec::new();
    for k in kinds {
        let name = format!("curved_{}_{analysis}", k.kind.name());
        let loads = [("boundary".to_string(), format!("pressure = {P}"))];
        let text = scene(geo, analysis, k, switch, &loads, supports);
        let path = case.write(&format!("{name}.toml"), &text);
        let run = case.run(&path).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        check_mesh(&run, k.kind);
        let curved = curvedness(&run);
        assert!(curved > 0.005, "{name}: the elements along the arcs are not curved ({curved:.1e})");
        let dev = deviation(&run, &sigma, u_exact, probe);
        eprintln!(
            "{name:>24}: {} cells, mid-node offset up to {:.3} of the cell size; max deviation gauss {:.1e} nodal {:.1e} probe {:.1e} displacement {:.1e}",
            run.model.bodies[0].cells.len(),
            curved,
            dev.gauss,
            dev.nodal,
            dev.probe,
            dev.displacement
        );
        if !(dev.max() < TOL) {
            failures.push(format!("{name}: {dev:?}"));
        }
    }
    failures
}

/// Pressure of the hydrostatic patches.
const P: f64 = 2.5;

/// Corners of the annular sector of tests/geo/patch_curved*.geo: radius r at angle t degrees.
fn polar(r: f64, t: f64) -> Vec3 {
    let t = t.to_radians();
    [r * t.cos(), r * t.sin(), 0.0]
}

#[test]
fn hydrostatic_stress_is_exact_on_curved_tri6_quad8_quad9_in_plane_strain_and_quad8_quad9_in_axisymmetry() {
    let case = Case::new("patch-curved-2d");
    case.copy("tests/geo/patch_curved.geo");
    // sigma = -p in the plane, sigma_zz = nu (sigma_xx + sigma_yy)
    let sigma = Uniform([-P, -P, -2.0 * NU * P, 0.0, 0.0, 0.0]);
    let eps = sigma.strain();
    // a dilation about A, which keeps u_y(B) = 0 only after the rotation w
    let (a, b) = (polar(2.0, 15.0), polar(4.0, 15.0));
    let d_ab = sub(b, a);
    let w = -mat_vec(&eps, d_ab)[1] / d_ab[0];
    let u_exact = move |x: Vec3| -> Vec3 {
        let d = sub(x, a);
        let u = mat_vec(&eps, d);
        [u[0] - w * d[1], u[1] + w * d[0], 0.0]
    };
    let kinds: Vec<Kind> = kinds_2d().into_iter().filter(|k| k.order == 2).collect();
    let supports = [("A", "[\"x\", \"y\"]"), ("B", "[\"y\"]")];
    let probe = (polar(2.1, 20.0), polar(3.9, 70.0));
    let mut failures =
        hydrostatic(&case, "patch_curved.geo", "plane_strain", "quads", &kinds, &supports, &u_exact, sigma.0, probe);

    // axisymmetric: sigma_rr = sigma_zz = sigma_tt = -p, u_r = eps r, u_z = eps (z - z_A)
    let sigma = Uniform([-P, -P, -P, 0.0, 0.0, 0.0]);
    let eps = sigma.strain()[0][0];
    let u_exact = move |x: Vec3| -> Vec3 { [eps * x[0], eps * (x[1] - a[1]), 0.0] };
    let kinds: Vec<Kind> = kinds_2d().into_iter().filter(|k| k.order == 2 && k.structured).collect();
    failures.extend(hydrostatic(
        &case,
        "patch_curved.geo",
        "axisymmetric",
        "quads",
        &kinds,
        &[("A", "[\"y\"]")],
        &u_exact,
        sigma.0,
        probe,
    ));
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}

#[test]
fn hydrostatic_stress_is_exact_on_curved_hex20_hex27() {
    let case = Case::new("patch-curved-3d");
    case.copy("tests/geo/patch_curved_3d.geo");
    let sigma = Uniform([-P, -P, -P, 0.0, 0.0, 0.0]);
    let eps = sigma.strain();
    let a = polar(2.0, 15.0);
    let w = rotation_321(&eps, sub(polar(4.0, 15.0), a), sub(polar(2.0, 75.0), a));
    let u_exact = move |x: Vec3| -> Vec3 {
        let d = sub(x, a);
        let u = mat_vec(&eps, d);
        let r = cross(w, d);
        [u[0] + r[0], u[1] + r[1], u[2] + r[2]]
    };
    let kinds: Vec<Kind> = kinds_3d().into_iter().filter(|k| k.order == 2 && k.structured).collect();
    let supports = [("A", "[\"x\", \"y\", \"z\"]"), ("B", "[\"y\", \"z\"]"), ("C", "[\"z\"]")];
    let (from, to) = (polar(2.1, 20.0), polar(3.9, 70.0));
    let failures = hydrostatic(
        &case,
        "patch_curved_3d.geo",
        "solid",
        "hexes",
        &kinds,
        &supports,
        &u_exact,
        sigma.0,
        ([from[0], from[1], 0.1], [to[0], to[1], 1.4]),
    );
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}

/// The hydrostatic patch on curved prisms: the sector's triangulated plan
/// extruded in layers (prism15, prism18 with arcs along the cylindrical
/// faces). Their stiffness rule integrates a curved prism's `∫ B^T sigma dV`
/// exactly: the map is quadratic in (ξ, η) and linear in ζ.
#[test]
fn hydrostatic_stress_is_exact_on_curved_prism15_prism18() {
    let case = Case::new("patch-curved-prism");
    case.copy("tests/geo/patch_curved_3d.geo");
    let sigma = Uniform([-P, -P, -P, 0.0, 0.0, 0.0]);
    let eps = sigma.strain();
    let a = polar(2.0, 15.0);
    let w = rotation_321(&eps, sub(polar(4.0, 15.0), a), sub(polar(2.0, 75.0), a));
    let u_exact = move |x: Vec3| -> Vec3 {
        let d = sub(x, a);
        let u = mat_vec(&eps, d);
        let r = cross(w, d);
        [u[0] + r[0], u[1] + r[1], u[2] + r[2]]
    };
    let kinds = [
        Kind { kind: CellKind::Prism18, order: 2, structured: true, serendipity: false },
        Kind { kind: CellKind::Prism15, order: 2, structured: true, serendipity: true },
    ];
    let supports = [("A", "[\"x\", \"y\", \"z\"]"), ("B", "[\"y\", \"z\"]"), ("C", "[\"z\"]")];
    let (from, to) = (polar(2.1, 20.0), polar(3.9, 70.0));
    let probe = ([from[0], from[1], 0.1], [to[0], to[1], 1.4]);
    let failures =
        hydrostatic(&case, "patch_curved_3d.geo", "solid", "prisms", &kinds, &supports, &u_exact, sigma.0, probe);
    assert!(failures.is_empty(), "patch test failed:\n{}", failures.join("\n"));
}
