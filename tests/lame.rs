//! Lamé's thick-walled cylinder under internal pressure: the finite element
//! solution converges to the closed form at the rates theory predicts, in
//! plane strain, in 3D and in axisymmetry, and the paper's Table 1 is
//! reproduced on the default scene.
//!
//! Reference: G. Lamé (1852), *Leçons sur la théorie mathématique de
//! l'élasticité des corps solides*; S. P. Timoshenko and J. N. Goodier,
//! *Theory of Elasticity*, §28 (thick cylinder); the seed paper's section 3
//! and Table 1 (DESIGN.md §3). Rates: the L2 error of the displacement of
//! elements of order p falls as h^(p+1) (Aubin–Nitsche), provided the
//! curved boundary is represented by isoparametric elements of the same
//! order (Ciarlet and Raviart 1972).
//!
//! Goal: tie the whole pipeline (gmsh CLI → mesh → assembly → solve →
//! recovery → error norms) to a closed form, through rates, not just small
//! numbers; and check the paper's table within 0.5 %.
//!
//! ```text
//!        y
//!        |
//!      b +.                  a = 3, b = 5, p = 0.1 on r = a, r = b free
//!        |   .               symmetry: u_x = 0 on x = 0, u_y = 0 on y = 0
//!      a +.    .             k = p a^2 / (b^2 - a^2)
//!        | p .   .           sigma_r = k (1 - b^2/r^2), sigma_t = k (1 + b^2/r^2)
//!        +-----+---+--- x    u_r = (1 + nu) k / E ((1 - 2 nu) r + b^2 / r)
//!              a   b         (plane strain; sigma_z = 2 nu k)
//! ```
//!
//! Parameters: E = 2.0e5, nu = 0.167 (the paper's concrete), `[analytic]
//! kind = "lame_cylinder"` gives the relative L2 errors `displacement_l2`
//! and `stress_l2`. The mesh size h is the mean element size
//! sqrt(area / cells); rates are least-squares slopes on log–log axes.
//!
//! 1. Quarter annulus (geo/cylinder.geo, both halves bonded: no contact),
//!    quadrilaterals of order 1 and 2, in plane strain and plane stress:
//!    displacement rates 2 and 3, stress rates 1 and 2. The arcs are
//!    polygons for quad4 (an O(h^2) geometry error) and parabolas for quad9
//!    (O(h^3)): neither pollutes its rate, which every pair of successive
//!    meshes must show too.
//! 2. A slice of the cylinder in 3D (tests/geo/lame_slice.geo, one layer of
//!    hexahedra as thick as they are wide, w = 0 on both faces): hex8 rate
//!    2, hex27 rate 3; where its plan view is the plane strain mesh, the
//!    errors equal the plane strain ones to round-off.
//!    A quarter turn of prisms (tests/geo/lame_revolved.geo: a meridian
//!    strip of triangles revolved in layers, so that the field varies along
//!    all three reference directions of each prism): prism6 rate 2, prism15
//!    and prism18 rate 3. And the slice of pyramids (each hexahedron
//!    of the slice cut into six about its centre, the mesh written by the
//!    test with its nodes on the exact arcs): pyramid5 rate 2, pyramid13
//!    and pyramid14 rate 3.
//! 3. Axisymmetric meridian section (tests/geo/lame_axisym.geo, u_axial = 0
//!    at both ends): quad4 rate 2, quad9 rate 3.
//! 4. The paper's Table 1 from the default scene geo/cylinder.toml (two
//!    bodies in contact along the 45-degree cut, quad9, lc = 0.05): every
//!    pair stuck, sigma_r and sigma_theta at r = 3.2 ... 4.8 within 0.5 %.
//! 5. The two halves in different materials (E and 2 E), free to slide
//!    along the cut (f = 0, c = 0; the inner face pulled, so that the cut
//!    is in compression): each half is Lamé's cylinder of its own material
//!    (the stresses do not depend on E; u_r jumps at the cut), and
//!    the error norms, which take each body's own material, are as small as
//!    with one material.

mod common;

use std::time::Instant;

use common::measure::loglog_slope;
use common::scenes::lame_cylinder;
use common::Case;
use subcontact::analytic::paper_tables::table1_values;
use subcontact::analytic::Lame;
use subcontact::driver::Run;
use subcontact::mesh::CellKind;
use subcontact::scene::Analysis;

const A: f64 = 3.0;
const B: f64 = 5.0;
const P: f64 = 0.1;
const E: f64 = 2.0e5;
const NU: f64 = 0.167;

/// One mesh of a refinement study.
struct Level {
    lc: f64,
    cells: usize,
    h: f64,
    displacement_l2: f64,
    stress_l2: f64,
    seconds: f64,
}

/// Runs a scene template (with `{order}` and `{lc}` placeholders) for each
/// mesh size; `area` is the exact area (volume) of the model, `dim` its dimension.
fn study(case: &Case, name: &str, template: &str, order: usize, lcs: &[f64], area: f64, dim: i32) -> Vec<Level> {
    lcs.iter()
        .map(|&lc| {
            let text = template.replace("{order}", &order.to_string()).replace("{lc}", &lc.to_string());
            let path = case.write(&format!("{name}_p{order}_lc{lc}.toml"), &text);
            let t = Instant::now();
            let run = case.run(&path).unwrap_or_else(|e| panic!("{name}, order {order}, lc {lc}: {e:#}"));
            let seconds = t.elapsed().as_secs_f64();
            let cells: usize = run.model.bodies.iter().map(|b| b.cells.len()).sum();
            for body in &run.model.bodies {
                assert!(body.cells.iter().all(|c| c.kind.order() == order), "{name}: cells of order {order} expected");
            }
            let errors = run.checks.errors.as_ref().expect("[analytic] gives errors");
            Level {
                lc,
                cells,
                h: (area / cells as f64).powf(1.0 / dim as f64),
                displacement_l2: errors.displacement_l2,
                stress_l2: errors.stress_l2,
                seconds,
            }
        })
        .collect()
}

/// Fitted rates (displacement, stress), printed with the levels.
fn rates(title: &str, levels: &[Level]) -> (f64, f64) {
    let h: Vec<f64> = levels.iter().map(|l| l.h).collect();
    let eu: Vec<f64> = levels.iter().map(|l| l.displacement_l2).collect();
    let es: Vec<f64> = levels.iter().map(|l| l.stress_l2).collect();
    let (ru, rs) = (loglog_slope(&h, &eu), loglog_slope(&h, &es));
    eprintln!("{title}: displacement rate {ru:.3}, stress rate {rs:.3}");
    for l in levels {
        eprintln!(
            "    lc {:<6} {:>6} cells  h {:.4}  displacement_l2 {:.3e}  stress_l2 {:.3e}  {:.2} s",
            l.lc, l.cells, l.h, l.displacement_l2, l.stress_l2, l.seconds
        );
    }
    (ru, rs)
}

/// Asserts the fitted rates of elements of order p: displacement p + 1 and
/// stress p, within 0.2; and every rate between two successive meshes
/// within 0.3 of p + 1, so that neither the coarsest mesh nor round-off or
/// the boundary's approximation on the finest pollutes the fit.
fn assert_rates(what: &str, p: usize, displacement: f64, stress: f64, levels: &[Level]) {
    let p = p as f64;
    assert!(levels.len() >= 3, "{what}: a rate needs at least 3 meshes");
    assert!(
        (displacement - (p + 1.0)).abs() < 0.2,
        "{what}: displacement rate {displacement:.3}, expected {}",
        p + 1.0
    );
    assert!((stress - p).abs() < 0.2, "{what}: stress rate {stress:.3}, expected {p}");
    for w in levels.windows(2) {
        let local = (w[0].displacement_l2 / w[1].displacement_l2).ln() / (w[0].h / w[1].h).ln();
        assert!(
            (local - (p + 1.0)).abs() < 0.3,
            "{what}: displacement rate {local:.3} between lc {} and {}, expected {}",
            w[0].lc,
            w[1].lc,
            p + 1.0
        );
    }
}

/// The quarter annulus area.
fn quarter_annulus() -> f64 {
    std::f64::consts::PI / 4.0 * (B * B - A * A)
}

/// `[gmsh]` lines with the placeholders `study` fills in.
const GMSH: &str = "order = {order}\nsetnumber = { lc = {lc} }";

/// geo/cylinder.geo with both halves bonded (no contact).
fn plane_strain() -> String {
    lame_cylinder(
        "Lame cylinder, plane strain, bonded halves",
        "cylinder.geo",
        "plane_strain",
        GMSH,
        NU,
        &["body_1", "body_2"],
        &[("symmetry_x0", "[\"x\"]"), ("symmetry_y0", "[\"y\"]")],
    )
}

#[test]
fn plane_strain_displacement_converges_at_rate_2_for_quad4_and_3_for_quad9() {
    let case = Case::new("lame-plane-strain");
    case.copy("geo/cylinder.geo");
    let p1 = study(&case, "plane_strain", &plane_strain(), 1, &[0.4, 0.2, 0.1, 0.05], quarter_annulus(), 2);
    let p2 = study(&case, "plane_strain", &plane_strain(), 2, &[0.4, 0.2, 0.1, 0.05], quarter_annulus(), 2);
    let (r1, s1) = rates("plane strain quad4", &p1);
    let (r2, s2) = rates("plane strain quad9", &p2);
    assert_rates("plane strain quad4", 1, r1, s1, &p1);
    assert_rates("plane strain quad9", 2, r2, s2, &p2);
}

#[test]
fn plane_stress_displacement_converges_at_rate_2_for_quad4_and_3_for_quad9() {
    // the plane stress closed form differs (u_r = k/E ((1 - nu) r + (1 + nu) b^2/r), sigma_z = 0)
    let case = Case::new("lame-plane-stress");
    case.copy("geo/cylinder.geo");
    let template = plane_strain().replace("plane_strain", "plane_stress").replace("plane strain", "plane stress");
    let p1 = study(&case, "plane_stress", &template, 1, &[0.4, 0.2, 0.1], quarter_annulus(), 2);
    let p2 = study(&case, "plane_stress", &template, 2, &[0.4, 0.2, 0.1], quarter_annulus(), 2);
    let (r1, s1) = rates("plane stress quad4", &p1);
    let (r2, s2) = rates("plane stress quad9", &p2);
    assert_rates("plane stress quad4", 1, r1, s1, &p1);
    assert_rates("plane stress quad9", 2, r2, s2, &p2);
}

/// tests/geo/lame_slice.geo, w = 0 on both faces.
fn slice() -> String {
    lame_cylinder(
        "Lame cylinder, 3D slice with w = 0 on both faces",
        "lame_slice.geo",
        "solid",
        GMSH,
        NU,
        &["body"],
        &[("x0", "[\"x\"]"), ("y0", "[\"y\"]"), ("z0", "[\"z\"]"), ("z1", "[\"z\"]")],
    )
}

#[test]
fn solid_slice_displacement_converges_at_rate_2_for_hex8_and_3_for_hex27() {
    let case = Case::new("lame-slice");
    case.copy("tests/geo/lame_slice.geo");
    // one layer of thickness lc: the volume is the area times lc, h the in-plane size
    let p1 = study(&case, "slice", &slice(), 1, &[0.4, 0.2, 0.1], quarter_annulus(), 2);
    let p2 = study(&case, "slice", &slice(), 2, &[0.4, 0.2, 0.1], quarter_annulus(), 2);
    let (r1, s1) = rates("solid slice hex8", &p1);
    let (r2, s2) = rates("solid slice hex27", &p2);
    assert_rates("hex8", 1, r1, s1, &p1);
    assert_rates("hex27", 2, r2, s2, &p2);
    // At lc = 0.4 and 0.2 the slice's plan view is the plane strain mesh of
    // geo/cylinder.geo node for node; with w = 0 on both faces the hexahedra
    // must give the plane strain solution, so the same errors.
    case.copy("geo/cylinder.geo");
    for (order, levels) in [(1, &p1), (2, &p2)] {
        let plane = study(&case, "plane_strain", &plane_strain(), order, &[0.4, 0.2], quarter_annulus(), 2);
        for (s, q) in levels.iter().zip(&plane) {
            assert_eq!(s.cells, q.cells);
            let du = (s.displacement_l2 - q.displacement_l2).abs() / q.displacement_l2;
            let ds = (s.stress_l2 - q.stress_l2).abs() / q.stress_l2;
            eprintln!("    order {order}, lc {}: slice vs plane strain errors differ by {du:.1e} (displacement), {ds:.1e} (stress)", s.lc);
            assert!(
                du < 1e-6 && ds < 1e-6,
                "order {order}, lc {}: the slice ({:.6e}, {:.6e}) is not the plane strain solution ({:.6e}, {:.6e})",
                s.lc,
                s.displacement_l2,
                s.stress_l2,
                q.displacement_l2,
                q.stress_l2
            );
        }
    }
}

/// tests/geo/lame_revolved.geo, w = 0 on both faces.
fn revolved() -> String {
    lame_cylinder(
        "Lame cylinder, quarter turn of prisms with w = 0 on both faces",
        "lame_revolved.geo",
        "solid",
        "order = {order}\nsetnumber = { lc = {lc}, serendipity = {serendipity} }",
        NU,
        &["body"],
        &[("x0", "[\"x\"]"), ("y0", "[\"y\"]"), ("z0", "[\"z\"]"), ("z1", "[\"z\"]")],
    )
}

#[test]
fn revolved_prisms_converge_at_rate_2_for_prism6_and_3_for_prism15_and_prism18() {
    let case = Case::new("lame-revolved-prisms");
    case.copy("tests/geo/lame_revolved.geo");
    // one row of triangle pairs in z: two prisms per cell of the (r, t)
    // grid, whose size is h
    let plan = 2.0 * quarter_annulus();
    for (order, serendipity, kind) in [(1, 0, "prism6"), (2, 0, "prism18"), (2, 1, "prism15")] {
        let template = revolved().replace("{serendipity}", &serendipity.to_string());
        let levels = study(&case, kind, &template, order, &[0.4, 0.2, 0.1], plan, 2);
        let (r, s) = rates(&format!("revolved {kind}"), &levels);
        assert_rates(kind, order, r, s, &levels);
    }
}

/// The quarter-annulus slice of thickness `lc` cut into pyramids: a grid
/// of (r, t, z) cells of size ~lc (one layer), each cut into six pyramids
/// about its centre, every node placed on the exact geometry (r cos t,
/// r sin t, z), so that order-2 pyramids follow the arcs. `kind` is
/// Pyramid5, Pyramid13 or Pyramid14; the groups are those of
/// tests/geo/lame_slice.geo (body, inner, x0, y0, z0, z1), the facets
/// quad4 / quad8 / quad9. Returns the number of grid cells.
fn pyramid_slice(path: &std::path::Path, kind: CellKind, lc: f64) -> usize {
    use common::msh::{write_msh41, MshGroup};
    use std::collections::HashMap;
    use subcontact::fem::shape::HEX_FACES;
    let (nr, nt) = (((B - A) / lc).ceil() as usize, (std::f64::consts::FRAC_PI_2 * (A + B) / 2.0 / lc).ceil() as usize);
    // nodes by their position on a grid of quarter cells
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut index: HashMap<[usize; 3], usize> = HashMap::new();
    let mut node = |q: [usize; 3]| -> usize {
        *index.entry(q).or_insert_with(|| {
            let r = A + (B - A) * q[0] as f64 / (4 * nr) as f64;
            let t = std::f64::consts::FRAC_PI_2 * q[1] as f64 / (4 * nt) as f64;
            nodes.push([r * t.cos(), r * t.sin(), lc * q[2] as f64 / 4.0]);
            nodes.len() - 1
        })
    };
    // the hexahedron's corners in gmsh order, in quarter cells
    const CORNER: [[usize; 3]; 8] =
        [[0, 0, 0], [4, 0, 0], [4, 4, 0], [0, 4, 0], [0, 0, 4], [4, 0, 4], [4, 4, 4], [0, 4, 4]];
    let mid = |p: [usize; 3], q: [usize; 3]| -> [usize; 3] { std::array::from_fn(|i| (p[i] + q[i]) / 2) };
    let (mut cells, mut facets): (Vec<Vec<usize>>, Vec<Vec<Vec<usize>>>) = (Vec::new(), vec![Vec::new(); 5]);
    for i in 0..nr {
        for j in 0..nt {
            let at = |c: [usize; 3]| [4 * i + c[0], 4 * j + c[1], c[2]];
            let centre = at([2, 2, 2]);
            for (f, face) in HEX_FACES.iter().enumerate() {
                // the base turned inwards (towards the apex), as gmsh's pyramid
                let base: Vec<[usize; 3]> =
                    [face[0], face[3], face[2], face[1]].iter().map(|&c| at(CORNER[c])).collect();
                let mut q = base.clone();
                q.push(centre);
                if kind != CellKind::Pyramid5 {
                    // gmsh's edges (0,1) (0,3) (0,4) (1,2) (1,4) (2,3) (2,4) (3,4)
                    for [a, b] in [[0, 1], [0, 3], [0, 4], [1, 2], [1, 4], [2, 3], [2, 4], [3, 4]] {
                        q.push(mid(q[a], q[b]));
                    }
                }
                if kind == CellKind::Pyramid14 {
                    q.push(mid(base[0], base[2]));
                }
                let cell: Vec<usize> = q.iter().map(|&p| node(p)).collect();
                // boundary facets: the base as a quadrangle (corners, then
                // the base's mid-edge nodes 5, 8, 10, 6, then its centre)
                let side = match f {
                    2 if i == 0 => Some(0),      // r = a: inner
                    1 if j == 0 => Some(1),      // t = 0: y0
                    4 if j == nt - 1 => Some(2), // t = 90 degrees: x0
                    0 => Some(3),                // z0
                    5 => Some(4),                // z1
                    _ => None,
                };
                if let Some(side) = side {
                    let mut quad = cell[..4].to_vec();
                    if kind != CellKind::Pyramid5 {
                        quad.extend([5, 8, 10, 6].map(|k| cell[k]));
                    }
                    if kind == CellKind::Pyramid14 {
                        quad.push(cell[13]);
                    }
                    facets[side].push(quad);
                }
                cells.push(cell);
            }
        }
    }
    let quad = match kind {
        CellKind::Pyramid5 => CellKind::Quad4,
        CellKind::Pyramid13 => CellKind::Quad8,
        _ => CellKind::Quad9,
    };
    let mut groups = vec![MshGroup { name: "body".into(), dim: 3, gmsh_type: kind.gmsh_code(), cells }];
    for (name, cells) in ["inner", "y0", "x0", "z0", "z1"].iter().zip(facets) {
        groups.push(MshGroup { name: name.to_string(), dim: 2, gmsh_type: quad.gmsh_code(), cells });
    }
    write_msh41(path, &nodes, &groups);
    nr * nt
}

#[test]
fn slice_of_pyramids_converges_at_rate_2_for_pyramid5_and_3_for_pyramid13_and_pyramid14() {
    let case = Case::new("lame-slice-pyramids");
    let template = slice().replace("\n[gmsh]\n", "\n").replace(GMSH, "");
    // the quadratic ones one level coarser (their finest mesh costs most)
    for (kind, order, lcs) in [
        (CellKind::Pyramid5, 1, [0.4, 0.2, 0.1]),
        (CellKind::Pyramid13, 2, [0.5, 0.25, 0.125]),
        (CellKind::Pyramid14, 2, [0.5, 0.25, 0.125]),
    ] {
        let levels: Vec<Level> = lcs
            .iter()
            .map(|&lc| {
                let name = format!("{}_lc{lc}", kind.name());
                let grid = pyramid_slice(&case.dir.join(format!("{name}.msh")), kind, lc);
                let path =
                    case.write(&format!("{name}.toml"), &template.replace("lame_slice.geo", &format!("{name}.msh")));
                let t = Instant::now();
                let run = case.run(&path).unwrap_or_else(|e| panic!("{name}: {e:#}"));
                let seconds = t.elapsed().as_secs_f64();
                let cells: usize = run.model.bodies.iter().map(|b| b.cells.len()).sum();
                assert_eq!(cells, 6 * grid);
                assert!(run.model.bodies[0].cells.iter().all(|c| c.kind == kind));
                let errors = run.checks.errors.as_ref().expect("[analytic] gives errors");
                // h: the size of the grid's cells, each six pyramids
                Level {
                    lc,
                    cells,
                    h: (quarter_annulus() / grid as f64).sqrt(),
                    displacement_l2: errors.displacement_l2,
                    stress_l2: errors.stress_l2,
                    seconds,
                }
            })
            .collect();
        let (r, s) = rates(&format!("slice of {}", kind.name()), &levels);
        assert_rates(kind.name(), order, r, s, &levels);
    }
}

/// tests/geo/lame_axisym.geo, the axial displacement held at both ends.
fn axisymmetric() -> String {
    lame_cylinder(
        "Lame cylinder, axisymmetric, axial displacement held at both ends",
        "lame_axisym.geo",
        "axisymmetric",
        GMSH,
        NU,
        &["body"],
        &[("bottom", "[\"y\"]"), ("top", "[\"y\"]")],
    )
}

#[test]
fn axisymmetric_displacement_converges_at_rate_2_for_quad4_and_3_for_quad9() {
    let case = Case::new("lame-axisym");
    case.copy("tests/geo/lame_axisym.geo");
    let p1 = study(&case, "axisym", &axisymmetric(), 1, &[0.5, 0.25, 0.125, 0.0625], 2.0, 2);
    let p2 = study(&case, "axisym", &axisymmetric(), 2, &[0.5, 0.25, 0.125, 0.0625], 2.0, 2);
    let (r1, s1) = rates("axisymmetric quad4", &p1);
    let (r2, s2) = rates("axisymmetric quad9", &p2);
    assert_rates("axisymmetric quad4", 1, r1, s1, &p1);
    assert_rates("axisymmetric quad9", 2, r2, s2, &p2);
}

#[test]
fn default_cylinder_scene_reproduces_paper_table_1_within_half_a_percent() {
    let case = Case::new("lame-table1");
    case.copy("geo/cylinder.geo");
    let scene = case.copy("geo/cylinder.toml");
    let t = Instant::now();
    let run: Run = case.run(&scene).unwrap_or_else(|e| panic!("geo/cylinder.toml: {e:#}"));
    let seconds = t.elapsed().as_secs_f64();
    // the paper: every pair stays stuck
    let contact = run.contact().expect("the default scene has a contact");
    assert!(contact.summary.converged);
    assert!(contact.states.iter().all(|s| s.code() == 2), "every pair of the 45-degree cut stays stuck");
    let lame = Lame { a: A, b: B, p: P, e: E, nu: NU, analysis: Analysis::PlaneStrain };
    let values = table1_values(&run.solution());
    let radii = [3.2, 3.6, 4.0, 4.4, 4.8];
    assert_eq!(values.len(), radii.len());
    eprintln!("Table 1 on geo/cylinder.toml ({:.2} s), units 1e-2 MPa:", seconds);
    let mut worst: f64 = 0.0;
    for (&r, v) in radii.iter().zip(&values) {
        let (sr, st) = v.unwrap_or_else(|| panic!("no probe value at r = {r}"));
        let (er, et) = (lame.sigma_r(r), lame.sigma_theta(r));
        let (dr, dt) = ((sr - er) / er.abs(), (st - et) / et.abs());
        eprintln!(
            "    r {r}: sigma_r {:.4} (theory {:.4}, {:+.3} %), sigma_theta {:.4} (theory {:.4}, {:+.3} %)",
            sr * 100.0,
            er * 100.0,
            dr * 100.0,
            st * 100.0,
            et * 100.0,
            dt * 100.0
        );
        worst = worst.max(dr.abs()).max(dt.abs());
    }
    assert!(worst < 0.005, "Table 1 is {:.3} % off the closed form (0.5 % allowed)", worst * 100.0);
}

#[test]
fn halves_of_different_stiffness_sliding_on_the_cut_are_each_lames_cylinder_of_their_own_material() {
    let case = Case::new("lame-two-materials");
    // the inner face pulled (p < 0), so that the cut is in compression
    // (sigma_theta < 0: a slipping pair is cracked and would open in
    // tension); a frictionless cut lets body_1 slide along x and body_2
    // along -y together: the point (a, 0) of body_1 is held at Lamé's u_r(a)
    case.write("cylinder.geo", &(common::repo_text("geo/cylinder.geo") + "Physical Point(\"a0\") = {2};\n"));
    let p = -P;
    let lame = Lame { a: A, b: B, p, e: E, nu: NU, analysis: Analysis::PlaneStrain };
    let ua = lame.u_r(A);
    let scene = |e2: f64| {
        format!(
            "title = \"Lame cylinder, halves E and {e2:e}, sliding on the cut\"\nmesh = \"cylinder.geo\"\nanalysis = \"plane_strain\"\nthickness = 1.0\n\n\
             [gmsh]\norder = 2\nsetnumber = {{ lc = 0.2 }}\n\n\
             [materials.soft]\nE = {E:e}\nnu = {NU}\n\n[materials.stiff]\nE = {e2:e}\nnu = {NU}\n\n\
             [[bodies]]\ngroup = \"body_1\"\nmaterial = \"soft\"\n\n[[bodies]]\ngroup = \"body_2\"\nmaterial = \"stiff\"\n\n\
             [[contacts]]\ngroup = \"A-A\"\nfriction = 0.0\ncohesion = 0.0\ntensile_strength = 3.0e5\n\n\
             [[supports]]\ngroup = \"symmetry_x0\"\nfix = [\"x\"]\n\n[[supports]]\ngroup = \"symmetry_y0\"\nfix = [\"y\"]\n\n\
             [[supports]]\ngroup = \"a0\"\nux = {ua:e}\n\n\
             [[loads]]\ngroup = \"inner\"\npressure = {p:?}\n\n[analytic]\nkind = \"lame_cylinder\"\na = {A:?}\nb = {B:?}\np = {p:?}\n"
        )
    };
    let errors = |e2: f64| {
        let path = case.write(&format!("two_{e2:e}.toml"), &scene(e2));
        let run: Run = case.run(&path).unwrap_or_else(|e| panic!("E2 = {e2:e}: {e:#}"));
        let e = run.checks.errors.as_ref().expect("[analytic] errors");
        eprintln!(
            "E2 / E1 = {}: displacement_l2 {:.3e}, stress_l2 {:.3e}, contact {:.3e}",
            e2 / E,
            e.displacement_l2,
            e.stress_l2,
            run.checks.contact_error_max.unwrap_or(f64::NAN)
        );
        // the report says how the norms treat two materials
        assert_eq!(
            subcontact::output::closed_form::report(&run.checks.analytic).contains("different materials"),
            e2 != E,
            "report.md's note on the materials"
        );
        (e.displacement_l2, e.stress_l2)
    };
    let (u1, s1) = errors(E);
    let (u2, s2) = errors(2.0 * E);
    // with body 0's material for both halves the stiff half's displacement
    // would be off by a factor 2: 0.35 (measured), not 4.9e-6
    assert!(u2 < 3.0 * u1 && u2 < 1e-4, "displacement error {u2:.3e} with two materials, {u1:.3e} with one");
    assert!(s2 < 3.0 * s1 && s2 < 1e-2, "stress error {s2:.3e} with two materials, {s1:.3e} with one");
}
