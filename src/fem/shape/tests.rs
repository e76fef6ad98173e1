//! Tests of the shape functions (partition of unity, Kronecker property,
//! gradients against central differences, polynomial reproduction), of
//! the node tables against gmsh's edges and faces, and of the inverse map.

use super::*;

fn kinds() -> impl Iterator<Item = CellKind> {
    CellKind::ALL.into_iter().filter(|k| k.dim() >= 1)
}

/// A few points inside (and one slightly outside) the reference cell.
fn sample_points(kind: CellKind) -> Vec<[f64; 3]> {
    let d = kind.dim();
    let simplex = matches!(kind, CellKind::Tri3 | CellKind::Tri6 | CellKind::Tet4 | CellKind::Tet10);
    let prism = matches!(kind, CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18);
    let pyramid = matches!(kind, CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14);
    let raw: [[f64; 3]; 5] =
        [[0.1, 0.2, 0.3], [0.37, 0.11, 0.05], [0.05, 0.6, 0.21], [0.25, 0.25, 0.25], [0.7, 0.05, 0.1]];
    raw.iter()
        .map(|p| {
            let mut q = [0.0; 3];
            for j in 0..d {
                q[j] = if simplex { p[j] } else { 2.0 * p[j] - 0.9 + 0.3 * j as f64 };
            }
            if prism {
                // the triangle's coordinates, ζ as on the cube
                q[0] = p[0];
                q[1] = p[1];
            }
            if pyramid {
                // ζ in [0, 0.8], (ξ, η) on the cube's pattern scaled by 1 - ζ
                q[2] = p[2] * 2.6;
                q[0] *= 1.0 - q[2];
                q[1] *= 1.0 - q[2];
            }
            q
        })
        .chain(std::iter::once(reference_centre(kind)))
        .collect()
}

fn eval_vec(kind: CellKind, xi: [f64; 3]) -> (Vec<f64>, Vec<[f64; 3]>) {
    let mut n = vec![0.0; kind.n_nodes()];
    let mut dn = vec![[0.0; 3]; kind.n_nodes()];
    eval(kind, xi, &mut n, &mut dn);
    (n, dn)
}

#[test]
fn node_tables_have_the_right_lengths() {
    for kind in CellKind::ALL {
        assert_eq!(reference_nodes(kind).len(), kind.n_nodes(), "{}", kind.name());
        // Corners are the nodes of the linear sibling.
        let lin = linear_sibling(kind);
        assert_eq!(lin.n_nodes(), kind.n_corners());
        assert_eq!(&reference_nodes(kind)[..kind.n_corners()], reference_nodes(lin), "{}", kind.name());
        // Unused components are zero.
        for p in reference_nodes(kind) {
            assert!(p[kind.dim()..].iter().all(|&v| v == 0.0));
        }
    }
}

#[test]
fn partition_of_unity_and_zero_gradient_sum() {
    for kind in kinds() {
        for xi in sample_points(kind) {
            let (n, dn) = eval_vec(kind, xi);
            let s: f64 = n.iter().sum();
            assert!((s - 1.0).abs() < 1e-14, "{} at {:?}: sum N = {}", kind.name(), xi, s);
            for j in 0..3 {
                let g: f64 = dn.iter().map(|g| g[j]).sum();
                assert!(g.abs() < 1e-13, "{} at {:?}: sum dN/dxi_{} = {}", kind.name(), xi, j, g);
            }
        }
    }
}

#[test]
fn kronecker_at_reference_nodes() {
    for kind in CellKind::ALL {
        for (b, &p) in reference_nodes(kind).iter().enumerate() {
            let (n, _) = eval_vec(kind, p);
            for (a, &v) in n.iter().enumerate() {
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-15, "{}: N_{} at node {} = {}", kind.name(), a, b, v);
            }
        }
    }
}

#[test]
fn gradients_match_central_differences() {
    let h = 1e-6;
    for kind in kinds() {
        for xi in sample_points(kind) {
            let (_, dn) = eval_vec(kind, xi);
            for j in 0..kind.dim() {
                let mut xp = xi;
                let mut xm = xi;
                xp[j] += h;
                xm[j] -= h;
                let (np, _) = eval_vec(kind, xp);
                let (nm, _) = eval_vec(kind, xm);
                for a in 0..kind.n_nodes() {
                    let fd = (np[a] - nm[a]) / (2.0 * h);
                    assert!(
                        (fd - dn[a][j]).abs() < 1e-8,
                        "{} at {:?}: dN_{}/dxi_{} = {} but FD gives {}",
                        kind.name(),
                        xi,
                        a,
                        j,
                        dn[a][j],
                        fd
                    );
                }
            }
        }
    }
}

fn midpoint(nodes: &[[f64; 3]], ids: &[usize]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for &i in ids {
        for j in 0..3 {
            m[j] += nodes[i][j] / ids.len() as f64;
        }
    }
    m
}

#[test]
fn higher_order_nodes_are_on_gmsh_edges_and_faces() {
    let check = |kind: CellKind, first: usize, edges: &[[usize; 2]]| {
        let nodes = reference_nodes(kind);
        for (e, ab) in edges.iter().enumerate() {
            assert_eq!(nodes[first + e], midpoint(nodes, ab), "{} node {}", kind.name(), first + e);
        }
    };
    check(CellKind::Line3, 2, &[[0, 1]]);
    check(CellKind::Tri6, 3, &TRI_EDGES);
    check(CellKind::Quad8, 4, &QUAD_EDGES);
    check(CellKind::Quad9, 4, &QUAD_EDGES);
    check(CellKind::Tet10, 4, &TET_EDGES);
    check(CellKind::Hex20, 8, &HEX_EDGES);
    check(CellKind::Hex27, 8, &HEX_EDGES);
    check(CellKind::Prism15, 6, &PRISM_EDGES);
    check(CellKind::Prism18, 6, &PRISM_EDGES);
    check(CellKind::Pyramid13, 5, &PYRAMID_EDGES);
    check(CellKind::Pyramid14, 5, &PYRAMID_EDGES);
    let q9 = reference_nodes(CellKind::Quad9);
    assert_eq!(q9[8], midpoint(q9, &[0, 1, 2, 3]));
    let h27 = reference_nodes(CellKind::Hex27);
    for (f, ids) in HEX_FACES.iter().enumerate() {
        assert_eq!(h27[20 + f], midpoint(h27, ids), "hex27 face node {}", 20 + f);
    }
    assert_eq!(h27[26], [0.0; 3]);
    // gmsh's face corner lists give outward normals: (p1-p0) x (p3-p0)
    // points away from the centre.
    for ids in HEX_FACES {
        let p: Vec<[f64; 3]> = ids.iter().map(|&i| h27[i]).collect();
        let u = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
        let v = [p[3][0] - p[0][0], p[3][1] - p[0][1], p[3][2] - p[0][2]];
        let nrm = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let c = midpoint(h27, &ids);
        assert!(nrm[0] * c[0] + nrm[1] * c[1] + nrm[2] * c[2] > 0.0, "face {:?} not outward", ids);
    }
}

#[test]
fn documented_node_positions() {
    // Spot checks straight from the gmsh node-ordering diagrams.
    assert_eq!(reference_nodes(CellKind::Line3)[2], [0.0, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Tri6)[3], [0.5, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Tri6)[4], [0.5, 0.5, 0.0]);
    assert_eq!(reference_nodes(CellKind::Tri6)[5], [0.0, 0.5, 0.0]);
    assert_eq!(reference_nodes(CellKind::Quad8)[4], [0.0, -1.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Quad8)[5], [1.0, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Quad8)[7], [-1.0, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Quad9)[8], [0.0, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Tet10)[7], [0.0, 0.0, 0.5]); // edge 3-0
    assert_eq!(reference_nodes(CellKind::Tet10)[8], [0.0, 0.5, 0.5]); // edge 3-2
    assert_eq!(reference_nodes(CellKind::Tet10)[9], [0.5, 0.0, 0.5]); // edge 3-1
    assert_eq!(reference_nodes(CellKind::Hex8)[6], [1.0, 1.0, 1.0]);
    assert_eq!(reference_nodes(CellKind::Hex20)[9], [-1.0, 0.0, -1.0]); // edge 0-3
    assert_eq!(reference_nodes(CellKind::Hex20)[10], [-1.0, -1.0, 0.0]); // edge 0-4
    assert_eq!(reference_nodes(CellKind::Hex20)[11], [1.0, 0.0, -1.0]); // edge 1-2
    assert_eq!(reference_nodes(CellKind::Hex20)[19], [0.0, 1.0, 1.0]); // edge 6-7
    assert_eq!(reference_nodes(CellKind::Hex27)[20], [0.0, 0.0, -1.0]);
    assert_eq!(reference_nodes(CellKind::Hex27)[22], [-1.0, 0.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Hex27)[24], [0.0, 1.0, 0.0]);
    assert_eq!(reference_nodes(CellKind::Hex27)[25], [0.0, 0.0, 1.0]);
    // prisms and pyramids, as gmsh 4.8.4 writes them (see nodes.rs)
    assert_eq!(reference_nodes(CellKind::Prism15)[7], [0.0, 0.5, -1.0]); // edge 0-2
    assert_eq!(reference_nodes(CellKind::Prism15)[8], [0.0, 0.0, 0.0]); // edge 0-3
    assert_eq!(reference_nodes(CellKind::Prism15)[9], [0.5, 0.5, -1.0]); // edge 1-2
    assert_eq!(reference_nodes(CellKind::Prism18)[16], [0.0, 0.5, 0.0]); // face 0-2-5-3
    assert_eq!(reference_nodes(CellKind::Prism18)[17], [0.5, 0.5, 0.0]); // face 1-2-5-4
    assert_eq!(reference_nodes(CellKind::Pyramid13)[6], [-1.0, 0.0, 0.0]); // edge 0-3
    assert_eq!(reference_nodes(CellKind::Pyramid13)[7], [-0.5, -0.5, 0.5]); // edge 0-4
    assert_eq!(reference_nodes(CellKind::Pyramid14)[13], [0.0, 0.0, 0.0]);
}

#[test]
fn reference_centre_is_inside_and_the_node_average_for_symmetric_kinds() {
    for kind in CellKind::ALL {
        let c = reference_centre(kind);
        assert!(inside_reference(kind, c, 0.0));
        let lin = reference_nodes(linear_sibling(kind));
        let m = midpoint(lin, &(0..lin.len()).collect::<Vec<_>>());
        for j in 0..3 {
            assert!((m[j] - c[j]).abs() < 1e-15, "{}", kind.name());
        }
    }
}

/// The quadratic interpolants reproduce quadratic fields exactly (the
/// linear ones linear fields), which checks the functions as a whole.
#[test]
fn reproduces_polynomials_of_its_order() {
    for kind in kinds() {
        let d = kind.dim();
        let f = |p: [f64; 3]| -> f64 {
            let mut v = 0.3 + 0.7 * p[0] - 0.2 * p[1] + 0.45 * p[2];
            if kind.order() == 2 {
                // Every kind of order 2 contains the complete quadratics.
                v += 0.3 * p[0] * p[0] - 0.6 * p[0] * p[1] * (d >= 2) as i32 as f64 + 0.25 * p[2] * p[2]
                    - 0.1 * p[1] * p[2];
            }
            v
        };
        let nodal: Vec<f64> = reference_nodes(kind).iter().map(|&p| f(p)).collect();
        for xi in sample_points(kind) {
            let (n, _) = eval_vec(kind, xi);
            let v: f64 = n.iter().zip(&nodal).map(|(a, b)| a * b).sum();
            assert!((v - f(xi)).abs() < 1e-13, "{} at {:?}", kind.name(), xi);
        }
    }
}

fn distorted_quad8() -> Vec<[f64; 3]> {
    // Curved sides and a non-parallelogram corner layout.
    vec![
        [0.0, 0.0, 0.0],
        [2.0, 0.2, 0.0],
        [2.3, 1.9, 0.0],
        [-0.2, 1.6, 0.0],
        [1.0, -0.15, 0.0],
        [2.25, 1.0, 0.0],
        [1.1, 1.95, 0.0],
        [0.05, 0.8, 0.0],
    ]
}

fn distorted_hex8() -> Vec<[f64; 3]> {
    vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.1, -0.1],
        [1.2, 1.1, 0.0],
        [-0.1, 0.9, 0.1],
        [0.1, -0.1, 1.0],
        [0.9, 0.0, 1.2],
        [1.3, 1.2, 1.1],
        [0.0, 1.0, 0.9],
    ]
}

#[test]
fn locate_inverts_the_map_on_distorted_cells() {
    let cases: Vec<(CellKind, Vec<[f64; 3]>)> = vec![
        (CellKind::Quad8, distorted_quad8()),
        (CellKind::Hex8, distorted_hex8()),
        (
            CellKind::Tri6,
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.5, -0.05, 0.0],
                [0.55, 0.55, 0.0],
                [0.03, 0.5, 0.0],
            ],
        ),
        (
            CellKind::Tet10,
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.5, -0.05, 0.0],
                [0.5, 0.5, 0.05],
                [0.0, 0.5, -0.02],
                [0.03, 0.0, 0.5],
                [0.0, 0.52, 0.5],
                [0.5, 0.02, 0.5],
            ],
        ),
    ];
    // prisms and pyramids under a smooth non-affine map
    let bend = |p: &[f64; 3]| [p[0] + 0.1 * p[1] * p[2], p[1] - 0.05 * p[0] * p[0], 0.8 * p[2] + 0.1 * p[0] * p[1]];
    let mut cases = cases;
    for kind in [
        CellKind::Prism6,
        CellKind::Prism15,
        CellKind::Prism18,
        CellKind::Pyramid5,
        CellKind::Pyramid13,
        CellKind::Pyramid14,
    ] {
        cases.push((kind, reference_nodes(kind).iter().map(bend).collect()));
    }
    for (kind, coords) in cases {
        let mut targets = sample_points(kind);
        // Boundary points: two of the nodes.
        targets.push(reference_nodes(kind)[1]);
        targets.push(reference_nodes(kind)[kind.n_nodes() - 1]);
        for xi in targets {
            assert!(inside_reference(kind, xi, 0.0));
            let x = map_point(kind, &coords, xi);
            let got = locate(kind, &coords, x).unwrap_or_else(|| panic!("{}: {:?} not found", kind.name(), xi));
            for j in 0..3 {
                assert!((got[j] - xi[j]).abs() < 1e-10, "{}: {:?} vs {:?}", kind.name(), got, xi);
            }
        }
    }
}

#[test]
fn locate_rejects_points_outside() {
    let q = distorted_quad8();
    // Mapped from reference points just outside, and far away.
    for xi in [[1.05, 0.0, 0.0], [0.0, -1.02, 0.0], [1.1, 1.1, 0.0]] {
        let x = map_point(CellKind::Quad8, &q, xi);
        assert_eq!(locate(CellKind::Quad8, &q, x), None, "{:?}", xi);
    }
    assert_eq!(locate(CellKind::Quad8, &q, [50.0, -30.0, 0.0]), None);
    let h = distorted_hex8();
    for xi in [[1.02, 0.0, 0.0], [0.3, -0.2, 1.01], [-1.5, 1.5, 1.5]] {
        let x = map_point(CellKind::Hex8, &h, xi);
        assert_eq!(locate(CellKind::Hex8, &h, x), None, "{:?}", xi);
    }
    assert_eq!(locate(CellKind::Hex8, &h, [10.0, 10.0, -10.0]), None);
    // Simplex: outside across the slanted face.
    let t: Vec<[f64; 3]> = reference_nodes(CellKind::Tet4).to_vec();
    assert_eq!(locate(CellKind::Tet4, &t, [0.4, 0.4, 0.21]), None);
    assert!(locate(CellKind::Tet4, &t, [0.4, 0.4, 0.19]).is_some());
    // A degenerate cell is not an error, just not found.
    let flat = vec![[0.0; 3]; 4];
    assert_eq!(locate(CellKind::Quad4, &flat, [0.0; 3]), None);
}

#[test]
fn locate_ignores_z_for_plane_cells_and_handles_lines() {
    let q: Vec<[f64; 3]> = reference_nodes(CellKind::Quad4).iter().map(|p| [2.0 * p[0] + 1.0, p[1], 0.0]).collect();
    let got = locate(CellKind::Quad4, &q, [2.0, 0.5, 7.0]).expect("inside");
    assert!((got[0] - 0.5).abs() < 1e-14 && (got[1] - 0.5).abs() < 1e-14 && got[2] == 0.0);
    let l = [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.2, 0.0, 0.0]];
    let got = locate(CellKind::Line3, &l, [2.2, 0.0, 0.0]).expect("inside");
    assert!(got[0].abs() < 1e-12);
    assert_eq!(locate(CellKind::Line3, &l, [3.1, 0.0, 0.0]), None);
    assert_eq!(locate(CellKind::Point1, &[[0.0; 3]], [0.0; 3]), None);
}

/// Conformity: on every face of a 3D cell, the functions of the nodes off
/// the face vanish, and those on it are the face kind's own functions (so
/// a pyramid13's base matches a hex20's quad8 face, a pyramid14's a
/// hex27's quad9, every triangle a tetrahedron's tri3 / tri6, a prism15's
/// sides quad8). The faces are outward and their nodes where their kind
/// puts them.
#[test]
fn faces_are_conforming_outward_and_where_their_kind_puts_their_nodes() {
    let face_points: &[[f64; 3]] = &[[0.2, 0.3, 0.0], [0.6, 0.1, 0.0], [0.05, 0.05, 0.0], [-0.7, 0.4, 0.0]];
    for kind in CellKind::ALL.into_iter().filter(|k| k.dim() == 3) {
        let nodes = reference_nodes(kind);
        let fs = faces(kind);
        assert_eq!(
            fs.len(),
            match kind.n_corners() {
                4 => 4,
                8 => 6,
                _ => 5,
            },
            "{}",
            kind.name()
        );
        // every node of the cell but its interior ones is on some face
        let mut on_faces: Vec<usize> = fs.iter().flat_map(|f| f.nodes.iter().copied()).collect();
        on_faces.sort_unstable();
        on_faces.dedup();
        let interior = usize::from(kind == CellKind::Hex27);
        assert_eq!(on_faces.len() + interior, kind.n_nodes(), "{}", kind.name());
        let centre = reference_centre(kind);
        for f in &fs {
            assert_eq!(f.nodes.len(), f.kind.n_nodes());
            assert_eq!(f.kind.order(), kind.order(), "{}", kind.name());
            let x: Vec<[f64; 3]> = f.nodes.iter().map(|&a| nodes[a]).collect();
            // the face's own nodes where its linear map puts its reference nodes
            let lin = linear_sibling(f.kind);
            let map = |s: [f64; 3]| -> [f64; 3] {
                let (n, _) = eval_vec(lin, s);
                std::array::from_fn(|i| (0..lin.n_nodes()).map(|b| n[b] * x[b][i]).sum())
            };
            for (b, s) in reference_nodes(f.kind).iter().enumerate() {
                assert_eq!(map(*s), x[b], "{} face {:?} node {b}", kind.name(), f.nodes);
            }
            // outward: (x1 - x0) x (x_last - x0) points away from the centre
            let u: [f64; 3] = std::array::from_fn(|i| x[1][i] - x[0][i]);
            let v: [f64; 3] = std::array::from_fn(|i| x[lin.n_nodes() - 1][i] - x[0][i]);
            let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
            let m = midpoint(&x, &(0..lin.n_nodes()).collect::<Vec<_>>());
            assert!(
                (0..3).map(|i| n[i] * (m[i] - centre[i])).sum::<f64>() > 0.0,
                "{} face {:?} is not outward",
                kind.name(),
                f.nodes
            );
            // the trace of the cell's functions is the face's
            for s in face_points.iter().filter(|s| inside_reference(f.kind, **s, 0.0)) {
                let (nf, _) = eval_vec(f.kind, *s);
                let (nc, _) = eval_vec(kind, map(*s));
                for a in 0..kind.n_nodes() {
                    let want = f.nodes.iter().position(|&b| b == a).map_or(0.0, |b| nf[b]);
                    assert!(
                        (nc[a] - want).abs() < 1e-14,
                        "{} face {:?} at {s:?}: N_{a} = {}, the face's {want}",
                        kind.name(),
                        f.nodes,
                        nc[a]
                    );
                }
            }
        }
    }
    assert!(faces(CellKind::Quad9).is_empty());
}

/// The pyramids' functions stay bounded up to the apex, and at the apex
/// itself are the apex node's Kronecker delta with finite gradients.
#[test]
fn pyramid_functions_are_continuous_at_the_apex() {
    for kind in [CellKind::Pyramid5, CellKind::Pyramid13, CellKind::Pyramid14] {
        let (n, dn) = eval_vec(kind, [0.0, 0.0, 1.0]);
        for a in 0..kind.n_nodes() {
            assert!((n[a] - if a == 4 { 1.0 } else { 0.0 }).abs() < 1e-15, "{}", kind.name());
            assert!(dn[a].iter().all(|g| g.is_finite()));
        }
        // approaching the apex along a side's diagonal
        for t in [1e-3, 1e-6, 1e-9] {
            let (n, dn) = eval_vec(kind, [t, -t, 1.0 - t]);
            assert!((n[4] - 1.0).abs() < 10.0 * t, "{} at 1 - {t}: N_apex = {}", kind.name(), n[4]);
            assert!(dn.iter().flatten().all(|g| g.abs() < 20.0), "{}: gradients grow near the apex", kind.name());
        }
    }
}
