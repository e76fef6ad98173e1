//! The reference elements of gmsh: each [`CellKind`]'s reference cell, the
//! coordinates of its nodes in gmsh's order, the edge and face tables that
//! say which mid-edge and face nodes sit where, and the reference centre.
//!
//! # Reference elements
//!
//! As in gmsh, reference coordinates are written (ξ, η, ζ) = `xi[0..3]`:
//!
//! | kind            | reference cell                                   | volume |
//! |-----------------|--------------------------------------------------|--------|
//! | Point1          | the single point 0                               | 1      |
//! | Line2, Line3    | ξ ∈ [-1, 1]                                      | 2      |
//! | Tri3, Tri6      | unit simplex, nodes (0,0), (1,0), (0,1)          | 1/2    |
//! | Quad4/8/9       | [-1, 1]², nodes (-1,-1), (1,-1), (1,1), (-1,1)   | 4      |
//! | Tet4, Tet10     | unit simplex, (0,0,0), (1,0,0), (0,1,0), (0,0,1) | 1/6    |
//! | Hex8/20/27      | [-1, 1]³, 0..3 at ζ = -1 counter-clockwise from (-1,-1,-1), 4..7 above them | 8 |
//!
//! # Node orders (gmsh's)
//!
//! Corners come first, then one node per edge in gmsh's edge order, then
//! (Quad9, Hex27) face centres and the volume centre. Each mid-edge node
//! sits at the middle of its edge, each face node at the face centre.
//!
//! ```text
//! Line2:  0-----------1 --> ξ        Line3:  0-----2-----1
//!       ξ=-1        ξ=+1
//!
//! Tri3:                     Tri6:
//!  η
//!  ^
//!  2                         2
//!  |`\                       |`\
//!  |  `\                     |  `\
//!  |    `\                   5    `4         edges: 3 = (0,1)
//!  |      `\                 |      `\              4 = (1,2)
//!  |        `\               |        `\            5 = (2,0)
//!  0----------1 --> ξ        0-----3----1
//!
//! Quad4:                 Quad8:                 Quad9:
//!  η
//!  ^
//!  3-----------2         3-----6-----2          3-----6-----2
//!  |           |         |           |          |           |
//!  |           |         |           |          |           |
//!  |           |         7           5          7     8     5
//!  |           |         |           |          |           |
//!  |           |         |           |          |           |
//!  0-----------1 --> ξ   0-----4-----1          0-----4-----1
//!  edges: 4 = (0,1), 5 = (1,2), 6 = (2,3), 7 = (3,0); 8 = centre
//!
//! Tet4 / Tet10 (ζ up, ξ to the right, η into the page towards node 2):
//!
//!    ζ
//!    3                                  3
//!    |`\.                               |`\.
//!    | \ `\.                            | \ `\.
//!    |  \  `\.                          |  8  `9.
//!    |   \    `\.                       7   \    `\.
//!    |    2 .    `\.                    |    2 .    `\.
//!    |  .    ` .    `\.                 |  6     5.    `\.
//!    |.          ` .   `\.              |.          ` .   `\.
//!    0-----------------` 1 --> ξ        0--------4--------` 1
//!
//!  edges: 4 = (0,1), 5 = (1,2), 6 = (2,0), 7 = (3,0), 8 = (3,2), 9 = (3,1)
//!  (note: node 8 is on edge 2-3 and node 9 on edge 1-3, gmsh's order)
//!
//! Hex8 / Hex20 (ζ up, ξ to the right, η into the page):
//!
//!        7----------6             7----19----6
//!       /|         /|            /|         /|
//!      / |        / |          17 |       18 |
//!     /  |       /  |          /  15      /  14
//!    4----------5   |         4----16----5   |
//!    |   |      |   |         |   |      |   |
//!    |   3------|---2         |   3----13|---2
//!    |  /       |  /         10  /      12  /
//!    | /        | /           | 9        | 11
//!    |/         |/            |/         |/
//!    0----------1 --> ξ       0-----8----1
//!
//!  edges:  8 = (0,1)   9 = (0,3)  10 = (0,4)  11 = (1,2)
//!         12 = (1,5)  13 = (2,3)  14 = (2,6)  15 = (3,7)
//!         16 = (4,5)  17 = (4,7)  18 = (5,6)  19 = (6,7)
//!
//! Hex27 = Hex20 + face centres 20 (ζ=-1), 21 (η=-1), 22 (ξ=-1), 23 (ξ=+1),
//!         24 (η=+1), 25 (ζ=+1), and the volume centre 26.
//! ```

use crate::mesh::CellKind;

// ---------------------------------------------------------------------------
// Reference node tables (gmsh order)
// ---------------------------------------------------------------------------

const POINT1: [[f64; 3]; 1] = [[0.0, 0.0, 0.0]];

const LINE2: [[f64; 3]; 2] = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];

const LINE3: [[f64; 3]; 3] = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];

const TRI3: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

const TRI6: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.5, 0.0, 0.0], // 3: edge (0,1)
    [0.5, 0.5, 0.0], // 4: edge (1,2)
    [0.0, 0.5, 0.0], // 5: edge (2,0)
];

/// Edges of the triangle, in gmsh order (mid-edge node 3 + i is on edge i).
pub const TRI_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

const QUAD4: [[f64; 3]; 4] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

const QUAD8: [[f64; 3]; 8] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 0.0], // 4: edge (0,1)
    [1.0, 0.0, 0.0],  // 5: edge (1,2)
    [0.0, 1.0, 0.0],  // 6: edge (2,3)
    [-1.0, 0.0, 0.0], // 7: edge (3,0)
];

const QUAD9: [[f64; 3]; 9] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 0.0], // 4: edge (0,1)
    [1.0, 0.0, 0.0],  // 5: edge (1,2)
    [0.0, 1.0, 0.0],  // 6: edge (2,3)
    [-1.0, 0.0, 0.0], // 7: edge (3,0)
    [0.0, 0.0, 0.0],  // 8: centre
];

/// Edges of the quadrangle, in gmsh order (mid-edge node 4 + i is on edge i).
pub const QUAD_EDGES: [[usize; 2]; 4] = [[0, 1], [1, 2], [2, 3], [3, 0]];

const TET4: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

const TET10: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0], // 4: edge (0,1)
    [0.5, 0.5, 0.0], // 5: edge (1,2)
    [0.0, 0.5, 0.0], // 6: edge (2,0)
    [0.0, 0.0, 0.5], // 7: edge (3,0)
    [0.0, 0.5, 0.5], // 8: edge (3,2)
    [0.5, 0.0, 0.5], // 9: edge (3,1)
];

/// Edges of the tetrahedron, in gmsh order (mid-edge node 4 + i is on edge i).
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

const HEX8: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

const HEX20: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0], //  8: edge (0,1)
    [-1.0, 0.0, -1.0], //  9: edge (0,3)
    [-1.0, -1.0, 0.0], // 10: edge (0,4)
    [1.0, 0.0, -1.0],  // 11: edge (1,2)
    [1.0, -1.0, 0.0],  // 12: edge (1,5)
    [0.0, 1.0, -1.0],  // 13: edge (2,3)
    [1.0, 1.0, 0.0],   // 14: edge (2,6)
    [-1.0, 1.0, 0.0],  // 15: edge (3,7)
    [0.0, -1.0, 1.0],  // 16: edge (4,5)
    [-1.0, 0.0, 1.0],  // 17: edge (4,7)
    [1.0, 0.0, 1.0],   // 18: edge (5,6)
    [0.0, 1.0, 1.0],   // 19: edge (6,7)
];

const HEX27: [[f64; 3]; 27] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0], //  8: edge (0,1)
    [-1.0, 0.0, -1.0], //  9: edge (0,3)
    [-1.0, -1.0, 0.0], // 10: edge (0,4)
    [1.0, 0.0, -1.0],  // 11: edge (1,2)
    [1.0, -1.0, 0.0],  // 12: edge (1,5)
    [0.0, 1.0, -1.0],  // 13: edge (2,3)
    [1.0, 1.0, 0.0],   // 14: edge (2,6)
    [-1.0, 1.0, 0.0],  // 15: edge (3,7)
    [0.0, -1.0, 1.0],  // 16: edge (4,5)
    [-1.0, 0.0, 1.0],  // 17: edge (4,7)
    [1.0, 0.0, 1.0],   // 18: edge (5,6)
    [0.0, 1.0, 1.0],   // 19: edge (6,7)
    [0.0, 0.0, -1.0],  // 20: face (0,3,2,1), ζ = -1
    [0.0, -1.0, 0.0],  // 21: face (0,1,5,4), η = -1
    [-1.0, 0.0, 0.0],  // 22: face (0,4,7,3), ξ = -1
    [1.0, 0.0, 0.0],   // 23: face (1,2,6,5), ξ = +1
    [0.0, 1.0, 0.0],   // 24: face (2,3,7,6), η = +1
    [0.0, 0.0, 1.0],   // 25: face (4,5,6,7), ζ = +1
    [0.0, 0.0, 0.0],   // 26: volume centre
];

/// Edges of the hexahedron, in gmsh order (mid-edge node 8 + i is on edge i).
pub const HEX_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [0, 3],
    [0, 4],
    [1, 2],
    [1, 5],
    [2, 3],
    [2, 6],
    [3, 7],
    [4, 5],
    [4, 7],
    [5, 6],
    [6, 7],
];

/// Faces of the hexahedron, in gmsh order (Hex27 face node 20 + i is the
/// centre of face i). Corner order as gmsh's (outward normal).
pub const HEX_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [0, 1, 5, 4],
    [0, 4, 7, 3],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [4, 5, 6, 7],
];

/// Reference coordinates of the element's nodes, gmsh order (unused components 0).
pub fn reference_nodes(kind: CellKind) -> &'static [[f64; 3]] {
    match kind {
        CellKind::Point1 => &POINT1,
        CellKind::Line2 => &LINE2,
        CellKind::Line3 => &LINE3,
        CellKind::Tri3 => &TRI3,
        CellKind::Tri6 => &TRI6,
        CellKind::Quad4 => &QUAD4,
        CellKind::Quad8 => &QUAD8,
        CellKind::Quad9 => &QUAD9,
        CellKind::Tet4 => &TET4,
        CellKind::Tet10 => &TET10,
        CellKind::Hex8 => &HEX8,
        CellKind::Hex20 => &HEX20,
        CellKind::Hex27 => &HEX27,
    }
}

/// Reference centre of the element (for e.g. orientation tests).
pub fn reference_centre(kind: CellKind) -> [f64; 3] {
    match kind {
        CellKind::Tri3 | CellKind::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        CellKind::Tet4 | CellKind::Tet10 => [0.25, 0.25, 0.25],
        _ => [0.0; 3],
    }
}

/// The corner-node (first-order) kind on the same reference cell: Tri6 -> Tri3,
/// Tet10 -> Tet4, Quad8/Quad9 -> Quad4, Hex20/Hex27 -> Hex8, Line3 -> Line2;
/// first-order kinds map to themselves.
pub fn linear_sibling(kind: CellKind) -> CellKind {
    match kind {
        CellKind::Line3 => CellKind::Line2,
        CellKind::Tri6 => CellKind::Tri3,
        CellKind::Quad8 | CellKind::Quad9 => CellKind::Quad4,
        CellKind::Tet10 => CellKind::Tet4,
        CellKind::Hex20 | CellKind::Hex27 => CellKind::Hex8,
        k => k,
    }
}

/// Whether `xi` lies in the reference cell of `kind`, boundary included,
/// with tolerance `tol` (in reference coordinates). Only the first
/// `kind.dim()` components are looked at.
pub fn inside_reference(kind: CellKind, xi: [f64; 3], tol: f64) -> bool {
    let d = kind.dim();
    match kind {
        CellKind::Point1 => true,
        CellKind::Tri3 | CellKind::Tri6 | CellKind::Tet4 | CellKind::Tet10 => {
            xi[..d].iter().all(|&t| t >= -tol) && xi[..d].iter().sum::<f64>() <= 1.0 + tol
        }
        _ => xi[..d].iter().all(|&t| t.abs() <= 1.0 + tol),
    }
}
