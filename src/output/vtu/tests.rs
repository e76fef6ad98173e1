//! The gmsh→VTK node order against VTK's own definition of each kind:
//! reference cells built from gmsh's edge and face tables, reordered, must
//! put every mid-edge and face node where VTK expects it. `readback` reads
//! the written files back.

use super::*;

mod readback;

// Reference elements in gmsh's order, built from gmsh's tables.

/// gmsh's edges of the tetrahedron, in gmsh's mid-edge node order (4..9).
const GMSH_TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];
/// gmsh's edges of the hexahedron, in gmsh's mid-edge node order (8..19).
const GMSH_HEX_EDGES: [[usize; 2]; 12] =
    [[0, 1], [0, 3], [0, 4], [1, 2], [1, 5], [2, 3], [2, 6], [3, 7], [4, 5], [4, 7], [5, 6], [6, 7]];
/// gmsh's faces of the hexahedron, in gmsh's face-centre order (20..25).
const GMSH_HEX_FACES: [[usize; 4]; 6] =
    [[0, 3, 2, 1], [0, 1, 5, 4], [0, 4, 7, 3], [1, 2, 6, 5], [2, 3, 7, 6], [4, 5, 6, 7]];

/// gmsh's edges of the prism, in gmsh's mid-edge node order (6..14).
const GMSH_PRISM_EDGES: [[usize; 2]; 9] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 4], [2, 5], [3, 4], [3, 5], [4, 5]];
/// gmsh's quadrangular faces of the prism, in prism18's face order (15..17).
const GMSH_PRISM_FACES: [[usize; 4]; 3] = [[0, 1, 4, 3], [0, 2, 5, 3], [1, 2, 5, 4]];
/// gmsh's edges of the pyramid, in gmsh's mid-edge node order (5..12).
const GMSH_PYRAMID_EDGES: [[usize; 2]; 8] = [[0, 1], [0, 3], [0, 4], [1, 2], [1, 4], [2, 3], [2, 4], [3, 4]];

/// VTK's edges of the wedge (vtkQuadraticWedge, nodes 6..14).
const VTK_WEDGE_EDGES: [[usize; 2]; 9] = [[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 3], [1, 4], [2, 5]];
/// VTK's quadrangle centres of vtkBiQuadraticQuadraticWedge (nodes 15..17).
const VTK_WEDGE_FACES: [[usize; 4]; 3] = [[0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]];
/// VTK's edges of the pyramid (vtkQuadraticPyramid, nodes 5..12).
const VTK_PYRAMID_EDGES: [[usize; 2]; 8] = [[0, 1], [1, 2], [2, 3], [3, 0], [0, 4], [1, 4], [2, 4], [3, 4]];

/// VTK's edges of the tetrahedron (vtkQuadraticTetra, nodes 4..9).
const VTK_TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];
/// VTK's edges of the hexahedron (vtkQuadraticHexahedron, nodes 8..19).
const VTK_HEX_EDGES: [[usize; 2]; 12] =
    [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]];
/// VTK's face centres of vtkTriQuadraticHexahedron (nodes 20..25):
/// x=-1, x=+1, y=-1, y=+1, z=-1, z=+1.
const VTK_HEX_FACES: [[usize; 4]; 6] =
    [[0, 3, 7, 4], [1, 2, 6, 5], [0, 1, 5, 4], [3, 2, 6, 7], [0, 1, 2, 3], [4, 5, 6, 7]];

fn mean(pts: &[[f64; 3]], ids: &[usize]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for &i in ids {
        for d in 0..3 {
            m[d] += pts[i][d];
        }
    }
    m.map(|x| x / ids.len() as f64)
}

/// Node coordinates of the reference element of `kind`, in gmsh order.
fn gmsh_reference(kind: CellKind) -> Vec<[f64; 3]> {
    let tri = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let quad = vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
    let tet = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let hex = vec![
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
    ];
    let with_edges = |mut p: Vec<[f64; 3]>, edges: &[[usize; 2]]| {
        for e in edges {
            let m = mean(&p, e);
            p.push(m);
        }
        p
    };
    let prism =
        vec![[0.0, 0.0, -1.0], [1.0, 0.0, -1.0], [0.0, 1.0, -1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let pyramid = vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let ring = |n: usize| (0..n).map(|i| [i, (i + 1) % n]).collect::<Vec<_>>();
    match kind {
        CellKind::Prism6 => prism,
        CellKind::Prism15 => with_edges(prism, &GMSH_PRISM_EDGES),
        CellKind::Prism18 => {
            let mut p = with_edges(prism, &GMSH_PRISM_EDGES);
            for f in &GMSH_PRISM_FACES {
                let m = mean(&p, f);
                p.push(m);
            }
            p
        }
        CellKind::Pyramid5 => pyramid,
        CellKind::Pyramid13 => with_edges(pyramid, &GMSH_PYRAMID_EDGES),
        CellKind::Pyramid14 => {
            let mut p = with_edges(pyramid, &GMSH_PYRAMID_EDGES);
            p.push([0.0, 0.0, 0.0]);
            p
        }
        CellKind::Point1 => vec![[0.0, 0.0, 0.0]],
        CellKind::Line2 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        CellKind::Line3 => vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        CellKind::Tri3 => tri,
        CellKind::Tri6 => with_edges(tri, &ring(3)),
        CellKind::Quad4 => quad,
        CellKind::Quad8 => with_edges(quad, &ring(4)),
        CellKind::Quad9 => {
            let mut p = with_edges(quad, &ring(4));
            p.push([0.0, 0.0, 0.0]);
            p
        }
        CellKind::Tet4 => tet,
        CellKind::Tet10 => with_edges(tet, &GMSH_TET_EDGES),
        CellKind::Hex8 => hex,
        CellKind::Hex20 => with_edges(hex, &GMSH_HEX_EDGES),
        CellKind::Hex27 => {
            let mut p = with_edges(hex, &GMSH_HEX_EDGES);
            for f in &GMSH_HEX_FACES {
                let m = mean(&p, f);
                p.push(m);
            }
            p.push([0.0, 0.0, 0.0]);
            p
        }
    }
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|d| (a[d] - b[d]).abs() < 1e-12)
}

/// Where VTK wants the corners of a kind, as positions of gmsh's reference
/// corners. All as gmsh's, except the linear wedge: VTK 9.2's
/// vtkCellValidator accepts a vtkWedge only when the right-hand normal of
/// (0,1,2) points away from (3,4,5) (and gmsh's own VTK export writes its
/// prism6 so), but accepts its quadratic wedges only in gmsh's orientation
/// (measured with ParaView 5.11's VTK 9.2.20230111, both orientations of
/// each wedge type).
fn vtk_corners(kind: CellKind) -> Vec<usize> {
    match kind {
        CellKind::Prism6 => vec![0, 2, 1, 3, 5, 4],
        _ => (0..kind.n_corners()).collect(),
    }
}

/// Checks VTK-ordered coordinates against VTK's definition of the kind:
/// corners where VTK puts them ([`vtk_corners`]), every mid-edge node at the
/// midpoint of the corners VTK expects, face centres at the mean of their
/// corners, the centre at the mean of all, no two nodes together. A
/// pyramid14 is written as VTK's 13-node quadratic pyramid.
fn vtk_geometry_error(kind: CellKind, vtk: &[[f64; 3]]) -> Option<String> {
    let (edges, faces): (Vec<[usize; 2]>, &[[usize; 4]]) = match kind {
        CellKind::Line3 => (vec![[0, 1]], &[]),
        CellKind::Tri6 => (vec![[0, 1], [1, 2], [2, 0]], &[]),
        CellKind::Quad8 | CellKind::Quad9 => (vec![[0, 1], [1, 2], [2, 3], [3, 0]], &[]),
        CellKind::Tet10 => (VTK_TET_EDGES.to_vec(), &[]),
        CellKind::Hex20 => (VTK_HEX_EDGES.to_vec(), &[]),
        CellKind::Hex27 => (VTK_HEX_EDGES.to_vec(), &VTK_HEX_FACES),
        CellKind::Prism15 => (VTK_WEDGE_EDGES.to_vec(), &[]),
        CellKind::Prism18 => (VTK_WEDGE_EDGES.to_vec(), &VTK_WEDGE_FACES),
        CellKind::Pyramid13 | CellKind::Pyramid14 => (VTK_PYRAMID_EDGES.to_vec(), &[]),
        _ => (vec![], &[]),
    };
    let n_vtk = if kind == CellKind::Pyramid14 { 13 } else { kind.n_nodes() };
    if vtk.len() != n_vtk {
        return Some(format!("{} nodes, expected {}", vtk.len(), n_vtk));
    }
    let nc = kind.n_corners();
    let gmsh = gmsh_reference(kind);
    let corners = vtk_corners(kind);
    for i in 0..nc {
        if !close(vtk[i], gmsh[corners[i]]) {
            return Some(format!("corner {i} at {:?}, expected {:?}", vtk[i], gmsh[corners[i]]));
        }
    }
    for (k, e) in edges.iter().enumerate() {
        let i = nc + k;
        if !close(vtk[i], mean(vtk, e)) {
            return Some(format!("VTK node {i} at {:?} is not the midpoint of corners {e:?}", vtk[i]));
        }
    }
    for (k, f) in faces.iter().enumerate() {
        let i = nc + edges.len() + k;
        if !close(vtk[i], mean(vtk, f)) {
            return Some(format!("VTK node {i} at {:?} is not the centre of face {f:?}", vtk[i]));
        }
    }
    let n_known = nc + edges.len() + faces.len();
    if n_vtk > n_known {
        let corners: Vec<usize> = (0..nc).collect();
        if n_vtk != n_known + 1 || !close(vtk[n_known], mean(vtk, &corners)) {
            return Some(format!("VTK node {n_known} is not the centre"));
        }
    }
    for i in 0..vtk.len() {
        for j in 0..i {
            if close(vtk[i], vtk[j]) {
                return Some(format!("nodes {i} and {j} coincide"));
            }
        }
    }
    None
}

#[test]
fn cell_type_numbers() {
    let expected = [
        (CellKind::Point1, 1),
        (CellKind::Line2, 3),
        (CellKind::Line3, 21),
        (CellKind::Tri3, 5),
        (CellKind::Tri6, 22),
        (CellKind::Quad4, 9),
        (CellKind::Quad8, 23),
        (CellKind::Quad9, 28),
        (CellKind::Tet4, 10),
        (CellKind::Tet10, 24),
        (CellKind::Hex8, 12),
        (CellKind::Hex20, 25),
        (CellKind::Hex27, 29),
        (CellKind::Prism6, 13),
        (CellKind::Prism15, 26),
        (CellKind::Prism18, 32),
        (CellKind::Pyramid5, 14),
        (CellKind::Pyramid13, 27),
        (CellKind::Pyramid14, 27),
    ];
    assert_eq!(expected.len(), CellKind::ALL.len());
    for (kind, code) in expected {
        assert_eq!(vtk_cell_type(kind), code, "{kind:?}");
    }
}

#[test]
fn permutations_put_nodes_where_vtk_expects_them() {
    for kind in CellKind::ALL {
        let gmsh = gmsh_reference(kind);
        assert_eq!(gmsh.len(), kind.n_nodes(), "{kind:?}");
        let vtk: Vec<[f64; 3]> = match vtk_from_gmsh(kind) {
            Some(perm) => {
                // A permutation of 0..n (pyramid14: of its first 13 nodes).
                let mut sorted = perm.to_vec();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..vtk_n_nodes(kind)).collect::<Vec<_>>(), "{kind:?}");
                perm.iter().map(|&g| gmsh[g]).collect()
            }
            None => gmsh.clone(),
        };
        assert_eq!(vtk_geometry_error(kind, &vtk), None, "{kind:?}");
    }
    // The check has teeth: in gmsh order these kinds fail it.
    for kind in [
        CellKind::Tet10,
        CellKind::Hex20,
        CellKind::Hex27,
        CellKind::Prism6,
        CellKind::Prism15,
        CellKind::Prism18,
        CellKind::Pyramid13,
    ] {
        assert!(vtk_geometry_error(kind, &gmsh_reference(kind)).is_some(), "{kind:?}");
    }
}
