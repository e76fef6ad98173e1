//! The reference elements of gmsh: each [`CellKind`]'s reference cell, the
//! coordinates of its nodes in gmsh's order, the edge and face tables that
//! say which mid-edge and face nodes sit where, the faces of each 3D cell
//! ([`faces`]), and the reference centre.
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
//! | Prism6/15/18    | unit triangle × ζ ∈ [-1, 1]: 0..2 the triangle at ζ = -1, 3..5 above them | 1 |
//! | Pyramid5/13/14  | base [-1, 1]² at ζ = 0 as Quad4, apex 4 at (0, 0, 1); \|ξ\|, \|η\| ≤ 1 - ζ | 4/3 |
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
//!
//! Prism6 / Prism15 (ζ up: the triangle (0,1,2) of ζ = -1 below (3,4,5);
//! a wedge made by extruding a triangle, gmsh's "prism", VTK's "wedge"):
//!
//!            3                         3
//!          ,/|`\                     ,/|`\
//!        ,/  |  `\                 12  |  13
//!      ,/    |    `\             ,/    8    `\
//!     4------+------5            4------14-----5
//!     |      |      |            |      |      |
//!     |      0      |            |      0      |
//!     |    ,/ `\    |           10    ,/ `\    11
//!     |  ,/     `\  |            |  ,6     `7  |
//!     |,/         `\|            |,/         `\|
//!     1-------------2            1------9------2
//!
//!  edges:  6 = (0,1)   7 = (0,2)   8 = (0,3)   9 = (1,2)  10 = (1,4)
//!         11 = (2,5)  12 = (3,4)  13 = (3,5)  14 = (4,5)
//!
//! Prism18 = Prism15 + the centres of the quadrangular faces 15 (0,1,4,3),
//!           i.e. η = 0; 16 (0,2,5,3), ξ = 0; 17 (1,2,5,4), ξ + η = 1.
//!
//! Pyramid5 / Pyramid13 (ζ up; the base is the Quad4 of ζ = 0, 0 and 3
//! at the back):
//!
//!                  4                              4
//!                ,/|\                           ,/|\
//!              ,/ .'|\                        ,/ .'|\
//!            ,/   | | \                     ,7   |  12 \
//!          ,/    .' | `.                  ,/    .'  |  `.
//!        ,/      |  '.  \               ,/     9    |    11
//!      0--------.'--|---3 `.          0------6-.'---|--3   `.
//!       `\      |   |    `\ \          `\      |    |   `\   \
//!         `\   .'   |      `\\           5    .'    |     10  \
//!           `\ |    |        `\            `\ |     |       `\ \
//!             `1------------------2           1--------8---------2
//!
//!  edges:  5 = (0,1)   6 = (0,3)   7 = (0,4)   8 = (1,2)
//!          9 = (1,4)  10 = (2,3)  11 = (2,4)  12 = (3,4)
//!
//! Pyramid14 = Pyramid13 + the base centre 13.
//! ```
//!
//! (The edge and face orders of the prisms and pyramids were read off
//! gmsh 4.8.4's own order-2 meshes: each mid-edge node at the midpoint of
//! the corners listed, each face node at its face's centre.)

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

const QUAD4: [[f64; 3]; 4] = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];

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

const TET4: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

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
pub const HEX_EDGES: [[usize; 2]; 12] =
    [[0, 1], [0, 3], [0, 4], [1, 2], [1, 5], [2, 3], [2, 6], [3, 7], [4, 5], [4, 7], [5, 6], [6, 7]];

/// Faces of the hexahedron, in gmsh order (Hex27 face node 20 + i is the
/// centre of face i). Corner order as gmsh's (outward normal).
pub const HEX_FACES: [[usize; 4]; 6] =
    [[0, 3, 2, 1], [0, 1, 5, 4], [0, 4, 7, 3], [1, 2, 6, 5], [2, 3, 7, 6], [4, 5, 6, 7]];

const PRISM6: [[f64; 3]; 6] =
    [[0.0, 0.0, -1.0], [1.0, 0.0, -1.0], [0.0, 1.0, -1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];

const PRISM18: [[f64; 3]; 18] = [
    [0.0, 0.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [0.5, 0.0, -1.0], //  6: edge (0,1)
    [0.0, 0.5, -1.0], //  7: edge (0,2)
    [0.0, 0.0, 0.0],  //  8: edge (0,3)
    [0.5, 0.5, -1.0], //  9: edge (1,2)
    [1.0, 0.0, 0.0],  // 10: edge (1,4)
    [0.0, 1.0, 0.0],  // 11: edge (2,5)
    [0.5, 0.0, 1.0],  // 12: edge (3,4)
    [0.0, 0.5, 1.0],  // 13: edge (3,5)
    [0.5, 0.5, 1.0],  // 14: edge (4,5)
    [0.5, 0.0, 0.0],  // 15: face (0,1,4,3), η = 0
    [0.0, 0.5, 0.0],  // 16: face (0,2,5,3), ξ = 0
    [0.5, 0.5, 0.0],  // 17: face (1,2,5,4), ξ + η = 1
];

/// Edges of the prism, in gmsh order (mid-edge node 6 + i is on edge i).
pub const PRISM_EDGES: [[usize; 2]; 9] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 4], [2, 5], [3, 4], [3, 5], [4, 5]];

const PYRAMID14: [[f64; 3]; 14] = [
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, -1.0, 0.0],  //  5: edge (0,1)
    [-1.0, 0.0, 0.0],  //  6: edge (0,3)
    [-0.5, -0.5, 0.5], //  7: edge (0,4)
    [1.0, 0.0, 0.0],   //  8: edge (1,2)
    [0.5, -0.5, 0.5],  //  9: edge (1,4)
    [0.0, 1.0, 0.0],   // 10: edge (2,3)
    [0.5, 0.5, 0.5],   // 11: edge (2,4)
    [-0.5, 0.5, 0.5],  // 12: edge (3,4)
    [0.0, 0.0, 0.0],   // 13: base centre
];

/// Edges of the pyramid, in gmsh order (mid-edge node 5 + i is on edge i).
pub const PYRAMID_EDGES: [[usize; 2]; 8] = [[0, 1], [0, 3], [0, 4], [1, 2], [1, 4], [2, 3], [2, 4], [3, 4]];

/// One face of a 3D reference cell: its kind (Tri3/6, Quad4/8/9) and the
/// cell's local node numbers in the face kind's own gmsh order (corners,
/// mid-edge nodes, centre), corners counter-clockwise seen from outside.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    pub kind: CellKind,
    pub nodes: Vec<usize>,
}

/// The faces of a cell kind, in gmsh's face order, each with outward
/// corner order: tetrahedron (0,2,1) (0,1,3) (0,3,2) (3,1,2); hexahedron
/// [`HEX_FACES`]; prism (0,2,1) (3,4,5) (0,1,4,3) (0,3,5,2) (1,2,5,4);
/// pyramid (0,1,4) (3,0,4) (1,2,4) (2,3,4) (0,3,2,1). A quadrangular face
/// has its centre node where the cell has one (Hex27, Prism18, the base of
/// Pyramid14), so a face of a cell is the facet gmsh writes for it. Cells of
/// dimension below 3 have no faces (empty).
pub fn faces(kind: CellKind) -> Vec<Face> {
    const TET: [&[usize]; 4] = [&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[3, 1, 2]];
    const PRISM: [&[usize]; 5] = [&[0, 2, 1], &[3, 4, 5], &[0, 1, 4, 3], &[0, 3, 5, 2], &[1, 2, 5, 4]];
    const PYRAMID: [&[usize]; 5] = [&[0, 1, 4], &[3, 0, 4], &[1, 2, 4], &[2, 3, 4], &[0, 3, 2, 1]];
    let hex: Vec<&[usize]> = HEX_FACES.iter().map(|f| &f[..]).collect();
    // corner lists, the cell's edge table, its first mid-edge node, and the
    // centre node of each face (None where the cell has none)
    type Table<'a> = (&'a [&'a [usize]], &'a [[usize; 2]], usize, &'a [Option<usize>]);
    let (corners, edges, first_mid, centres): Table = match kind {
        CellKind::Tet4 | CellKind::Tet10 => (&TET, &TET_EDGES, 4, &[None; 4]),
        CellKind::Hex8 | CellKind::Hex20 => (&hex, &HEX_EDGES, 8, &[None; 6]),
        CellKind::Hex27 => (&hex, &HEX_EDGES, 8, &[Some(20), Some(21), Some(22), Some(23), Some(24), Some(25)]),
        CellKind::Prism6 | CellKind::Prism15 => (&PRISM, &PRISM_EDGES, 6, &[None; 5]),
        CellKind::Prism18 => (&PRISM, &PRISM_EDGES, 6, &[None, None, Some(15), Some(16), Some(17)]),
        CellKind::Pyramid5 | CellKind::Pyramid13 => (&PYRAMID, &PYRAMID_EDGES, 5, &[None; 5]),
        CellKind::Pyramid14 => (&PYRAMID, &PYRAMID_EDGES, 5, &[None, None, None, None, Some(13)]),
        _ => return Vec::new(),
    };
    corners
        .iter()
        .zip(centres)
        .map(|(c, centre)| {
            let nc = c.len();
            let mut nodes = c.to_vec();
            if kind.order() == 2 {
                for i in 0..nc {
                    let (a, b) = (c[i], c[(i + 1) % nc]);
                    let e = edges
                        .iter()
                        .position(|e| *e == [a, b] || *e == [b, a])
                        .expect("a face's edge is an edge of its cell");
                    nodes.push(first_mid + e);
                }
            }
            nodes.extend(centre);
            let kind = match (nc, nodes.len()) {
                (3, 3) => CellKind::Tri3,
                (3, _) => CellKind::Tri6,
                (4, 4) => CellKind::Quad4,
                (4, 8) => CellKind::Quad8,
                _ => CellKind::Quad9,
            };
            Face { kind, nodes }
        })
        .collect()
}

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
        CellKind::Prism6 => &PRISM6,
        CellKind::Prism15 => &PRISM18[..15],
        CellKind::Prism18 => &PRISM18,
        CellKind::Pyramid5 => &PYRAMID14[..5],
        CellKind::Pyramid13 => &PYRAMID14[..13],
        CellKind::Pyramid14 => &PYRAMID14,
    }
}

/// Reference centre of the element, the mean of its corners (for e.g.
/// orientation tests, and where Newton starts in `locate`).
pub fn reference_centre(kind: CellKind) -> [f64; 3] {
    match kind {
        CellKind::Tri3 | CellKind::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        CellKind::Tet4 | CellKind::Tet10 => [0.25, 0.25, 0.25],
        CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14 => [0.0, 0.0, 0.2],
        _ => [0.0; 3],
    }
}

/// The corner-node (first-order) kind on the same reference cell: Tri6 -> Tri3,
/// Tet10 -> Tet4, Quad8/Quad9 -> Quad4, Hex20/Hex27 -> Hex8, Line3 -> Line2,
/// Prism15/Prism18 -> Prism6, Pyramid13/Pyramid14 -> Pyramid5; first-order
/// kinds map to themselves.
pub fn linear_sibling(kind: CellKind) -> CellKind {
    match kind {
        CellKind::Line3 => CellKind::Line2,
        CellKind::Tri6 => CellKind::Tri3,
        CellKind::Quad8 | CellKind::Quad9 => CellKind::Quad4,
        CellKind::Tet10 => CellKind::Tet4,
        CellKind::Hex20 | CellKind::Hex27 => CellKind::Hex8,
        CellKind::Prism15 | CellKind::Prism18 => CellKind::Prism6,
        CellKind::Pyramid13 | CellKind::Pyramid14 => CellKind::Pyramid5,
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
        CellKind::Prism6 | CellKind::Prism15 | CellKind::Prism18 => {
            xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1.0 + tol && xi[2].abs() <= 1.0 + tol
        }
        CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14 => {
            let r = 1.0 - xi[2];
            xi[2] >= -tol && r >= -tol && xi[0].abs() <= r + tol && xi[1].abs() <= r + tol
        }
        _ => xi[..d].iter().all(|&t| t.abs() <= 1.0 + tol),
    }
}
