//! The oracle of the VTU tests: reference cells in gmsh's order, built
//! from gmsh's edge and face tables, and VTK's definition of each kind to
//! check node positions against; and a small mesh of given kinds with
//! fields to write. Shared by the unit tests beside it and by
//! tests/vtu_readback.rs (which includes this file by its path), so it
//! names only what both reach: the parent module's `Cell`, `CellKind`,
//! `Field`, `IntField` and `vtu_bytes`.

use super::{vtu_bytes, Cell, CellKind, Field, IntField};

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
pub(super) fn gmsh_reference(kind: CellKind) -> Vec<[f64; 3]> {
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
pub(super) fn vtk_geometry_error(kind: CellKind, vtk: &[[f64; 3]]) -> Option<String> {
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

/// A mesh of the given kinds, one reference cell each, moved apart, and
/// its fields: point `displacement` (3), `stress` (6), `von_mises` (1);
/// cell `stress` (6), `von_mises` (1) and int `body`.
pub(super) struct TestMesh {
    pub(super) points: Vec<[f64; 3]>,
    pub(super) cells: Vec<Cell>,
    pub(super) displacement: Vec<f64>,
    pub(super) stress: Vec<f64>,
    pub(super) von_mises: Vec<f64>,
    pub(super) cell_stress: Vec<f64>,
    pub(super) cell_von_mises: Vec<f64>,
    pub(super) body: Vec<i32>,
}

impl TestMesh {
    pub(super) fn new(kinds: &[CellKind]) -> Self {
        let mut points = Vec::new();
        let mut cells = Vec::new();
        for (c, &kind) in kinds.iter().enumerate() {
            let first = points.len();
            for p in gmsh_reference(kind) {
                points.push([p[0] + 3.0 * c as f64, p[1], p[2]]);
            }
            cells.push(Cell { kind, nodes: (first..points.len()).collect(), tag: 100 + c as u64 });
        }
        let np = points.len();
        let nc = cells.len();
        let displacement = (0..3 * np).map(|i| 1e-3 * i as f64 - 0.1).collect();
        let stress = (0..6 * np).map(|i| (i as f64).sin() * 1e8).collect();
        let von_mises = (0..np).map(|i| 1.0 / (i as f64 + 3.0)).collect();
        let cell_stress = (0..6 * nc).map(|i| -(i as f64) * 0.5e6 + 1.0 / 3.0).collect();
        let cell_von_mises = (0..nc).map(|i| 2.5e7 * (i as f64 + 1.0)).collect();
        let body = (0..nc as i32).map(|i| i % 2 - 7).collect();
        TestMesh { points, cells, displacement, stress, von_mises, cell_stress, cell_von_mises, body }
    }

    pub(super) fn bytes(&self) -> Vec<u8> {
        vtu_bytes(
            &self.points,
            &self.cells,
            &[
                Field { name: "displacement", n_comp: 3, values: &self.displacement },
                Field { name: "stress", n_comp: 6, values: &self.stress },
                Field { name: "von_mises", n_comp: 1, values: &self.von_mises },
            ],
            &[
                Field { name: "stress", n_comp: 6, values: &self.cell_stress },
                Field { name: "von_mises", n_comp: 1, values: &self.cell_von_mises },
            ],
            &[IntField { name: "body", values: &self.body }],
        )
        .unwrap()
    }
}
