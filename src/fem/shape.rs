//! Lagrange shape functions on gmsh's reference elements: the reference node
//! coordinates of every [`CellKind`], the shape functions and their gradients
//! with respect to the reference coordinates, the reference centre, and the
//! inverse map (physical point -> reference coordinates) by Newton. Nothing
//! here knows about elasticity or about the mesh beyond the cell kind.
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
//!
//! Shape functions: Line, Quad4/Quad9, Hex8/Hex27 are tensor-product Lagrange
//! polynomials; Quad8 and Hex20 are the serendipity ones; Tri and Tet are
//! linear or quadratic Lagrange polynomials in barycentric coordinates. All
//! of them are built from the node tables below, so node order lives in one
//! place (the tables) and the Kronecker test checks both agree.

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

// ---------------------------------------------------------------------------
// Shape functions
// ---------------------------------------------------------------------------

/// Shape functions n[a] and their reference gradients dn[a][j] = dN_a/dxi_j (j < kind.dim(), other components 0) at xi.
/// n.len() and dn.len() equal kind.n_nodes().
pub fn eval(kind: CellKind, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    debug_assert_eq!(n.len(), kind.n_nodes(), "eval: n has the wrong length for {}", kind.name());
    debug_assert_eq!(dn.len(), kind.n_nodes(), "eval: dn has the wrong length for {}", kind.name());
    for g in dn.iter_mut() {
        *g = [0.0; 3];
    }
    let d = kind.dim();
    let nodes = reference_nodes(kind);
    match kind {
        CellKind::Point1 => n[0] = 1.0,
        CellKind::Line2 | CellKind::Quad4 | CellKind::Hex8 => tensor_lagrange(d, 1, nodes, xi, n, dn),
        CellKind::Line3 | CellKind::Quad9 | CellKind::Hex27 => tensor_lagrange(d, 2, nodes, xi, n, dn),
        CellKind::Quad8 | CellKind::Hex20 => serendipity(d, nodes, xi, n, dn),
        CellKind::Tri3 | CellKind::Tet4 => simplex(d, &[], xi, n, dn),
        CellKind::Tri6 => simplex(d, &TRI_EDGES, xi, n, dn),
        CellKind::Tet10 => simplex(d, &TET_EDGES, xi, n, dn),
    }
}

/// 1D Lagrange basis on the nodes {-1, 1} (order 1) or {-1, 0, 1} (order 2):
/// value and derivative of the function that is 1 at `c` (one of those nodes).
fn lagrange_1d(order: usize, c: f64, t: f64) -> (f64, f64) {
    if order == 1 {
        (0.5 * (1.0 + c * t), 0.5 * c)
    } else if c == 0.0 {
        (1.0 - t * t, -2.0 * t)
    } else {
        // c = ±1: t (t + c) / 2
        (0.5 * t * (t + c), t + 0.5 * c)
    }
}

/// Tensor-product Lagrange functions on [-1,1]^d; node coordinates in {-1,0,1}.
fn tensor_lagrange(d: usize, order: usize, nodes: &[[f64; 3]], xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    for (a, c) in nodes.iter().enumerate() {
        let mut v = [0.0; 3];
        let mut g = [0.0; 3];
        for j in 0..d {
            let (vj, gj) = lagrange_1d(order, c[j], xi[j]);
            v[j] = vj;
            g[j] = gj;
        }
        n[a] = v[..d].iter().product();
        for (i, dni) in dn[a][..d].iter_mut().enumerate() {
            *dni = (0..d).map(|j| if j == i { g[j] } else { v[j] }).product();
        }
    }
}

/// Serendipity functions (Quad8, Hex20) on [-1,1]^d: corners (all |c| = 1)
/// 2^-d Π(1 + c_j t_j) (Σ c_j t_j - (d - 1)); mid-edge nodes (c_k = 0)
/// 2^-(d-1) (1 - t_k²) Π_{j≠k} (1 + c_j t_j).
fn serendipity(d: usize, nodes: &[[f64; 3]], xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    for (a, c) in nodes.iter().enumerate() {
        // lin[j] = 1 + c_j t_j (for the edge direction k of a mid node: 1 - t_k²)
        let zero = (0..d).find(|&j| c[j] == 0.0);
        let mut f = [1.0; 3];
        let mut df = [0.0; 3];
        for j in 0..d {
            if Some(j) == zero {
                f[j] = 1.0 - xi[j] * xi[j];
                df[j] = -2.0 * xi[j];
            } else {
                f[j] = 1.0 + c[j] * xi[j];
                df[j] = c[j];
            }
        }
        let prod = |skip: usize| -> f64 { (0..d).filter(|&j| j != skip).map(|j| f[j]).product() };
        match zero {
            Some(_) => {
                let s = 0.5f64.powi(d as i32 - 1);
                n[a] = s * prod(usize::MAX);
                for i in 0..d {
                    dn[a][i] = s * df[i] * prod(i);
                }
            }
            None => {
                let s = 0.5f64.powi(d as i32);
                let sum: f64 = (0..d).map(|j| c[j] * xi[j]).sum::<f64>() - (d as f64 - 1.0);
                let p = prod(usize::MAX);
                n[a] = s * p * sum;
                for i in 0..d {
                    dn[a][i] = s * (df[i] * prod(i) * sum + p * c[i]);
                }
            }
        }
    }
}

/// Lagrange functions on the unit simplex of dimension d, in barycentric
/// coordinates L_0 = 1 - Σ xi_j, L_{j+1} = xi_j. Without edges: linear
/// (N_a = L_a); with edges: quadratic, corners L_a (2 L_a - 1), then one
/// node per edge (a, b) with 4 L_a L_b.
fn simplex(d: usize, edges: &[[usize; 2]], xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let mut l = [0.0; 4];
    let mut dl = [[0.0; 3]; 4];
    l[0] = 1.0 - xi[..d].iter().sum::<f64>();
    for j in 0..d {
        l[j + 1] = xi[j];
        dl[0][j] = -1.0;
        dl[j + 1][j] = 1.0;
    }
    if edges.is_empty() {
        n[..=d].copy_from_slice(&l[..=d]);
        dn[..=d].copy_from_slice(&dl[..=d]);
        return;
    }
    for a in 0..=d {
        n[a] = l[a] * (2.0 * l[a] - 1.0);
        for j in 0..d {
            dn[a][j] = (4.0 * l[a] - 1.0) * dl[a][j];
        }
    }
    for (e, &[a, b]) in edges.iter().enumerate() {
        let m = d + 1 + e;
        n[m] = 4.0 * l[a] * l[b];
        for j in 0..d {
            dn[m][j] = 4.0 * (l[a] * dl[b][j] + l[b] * dl[a][j]);
        }
    }
}

// ---------------------------------------------------------------------------
// Inverse map
// ---------------------------------------------------------------------------

/// Tolerance (in reference coordinates) of the "inside" test of [`locate`].
pub const LOCATE_TOL: f64 = 1e-8;

/// Physical point x(xi) = Σ N_a(xi) coords[a] of the cell with node
/// coordinates `coords` (gmsh order).
pub fn map_point(kind: CellKind, coords: &[[f64; 3]], xi: [f64; 3]) -> [f64; 3] {
    debug_assert_eq!(coords.len(), kind.n_nodes());
    let nn = kind.n_nodes();
    let mut n = [0.0; 27];
    let mut dn = [[0.0; 3]; 27];
    eval(kind, xi, &mut n[..nn], &mut dn[..nn]);
    let mut x = [0.0; 3];
    for (na, c) in n[..nn].iter().zip(coords) {
        for i in 0..3 {
            x[i] += na * c[i];
        }
    }
    x
}

/// Inverse map: the reference coordinates of physical point x in the cell whose node
/// coordinates are `coords` (gmsh order; for 2D kinds z is ignored), by Newton; Some(xi) only if
/// x lies inside the cell or on its boundary (tolerance ~1e-8 in reference coordinates). Only for
/// cells whose dim equals the space dimension (2D cells in the plane z=0 with 2D coordinates; 3D cells).
///
/// Line kinds are handled the same way on the x axis (y, z ignored); Point1
/// always gives None. Newton starts at the reference centre, with a simple
/// backtracking on the residual; a cell whose Jacobian is singular on the
/// way, or no convergence within 50 steps, gives None.
pub fn locate(kind: CellKind, coords: &[[f64; 3]], x: [f64; 3]) -> Option<[f64; 3]> {
    debug_assert_eq!(coords.len(), kind.n_nodes(), "locate: wrong number of coordinates for {}", kind.name());
    let d = kind.dim();
    if d == 0 || coords.len() != kind.n_nodes() {
        return None;
    }
    let nn = kind.n_nodes();
    // Length scale of the cell, for the residual tolerance.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for c in coords {
        for i in 0..d {
            lo[i] = lo[i].min(c[i]);
            hi[i] = hi[i].max(c[i]);
        }
    }
    let h = (0..d).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
    if !h.is_finite() || h <= 0.0 {
        return None;
    }

    let mut n = [0.0; 27];
    let mut dn = [[0.0; 3]; 27];
    // Residual r = x - x(xi) and Jacobian J[i][j] = dx_i/dxi_j at xi.
    let mut residual = |xi: [f64; 3], jac: Option<&mut [[f64; 3]; 3]>| -> [f64; 3] {
        eval(kind, xi, &mut n[..nn], &mut dn[..nn]);
        let mut r = [0.0; 3];
        r[..d].copy_from_slice(&x[..d]);
        let mut j = [[0.0; 3]; 3];
        for a in 0..nn {
            for i in 0..d {
                r[i] -= n[a] * coords[a][i];
                for k in 0..d {
                    j[i][k] += dn[a][k] * coords[a][i];
                }
            }
        }
        if let Some(out) = jac {
            *out = j;
        }
        r
    };
    let norm = |r: &[f64; 3]| r[..d].iter().map(|v| v * v).sum::<f64>().sqrt();

    let mut xi = reference_centre(kind);
    let mut jac = [[0.0; 3]; 3];
    let mut r = residual(xi, Some(&mut jac));
    let mut rn = norm(&r);
    for _ in 0..50 {
        let step = solve_small(d, jac, r)?;
        let step_norm = step[..d].iter().map(|v| v * v).sum::<f64>().sqrt();
        // Backtracking: halve the step while the residual grows.
        let mut t = 1.0;
        let mut trial;
        let mut trial_r;
        let mut trial_n;
        loop {
            trial = xi;
            for j in 0..d {
                // Keep the iterate in a generous box around the reference cell
                // so that the polynomial map cannot blow up.
                trial[j] = (xi[j] + t * step[j]).clamp(-3.0, 3.0);
            }
            trial_r = residual(trial, None);
            trial_n = norm(&trial_r);
            if trial_n <= rn || t < 1e-3 {
                break;
            }
            t *= 0.5;
        }
        xi = trial;
        r = residual(xi, Some(&mut jac));
        rn = norm(&r);
        if !rn.is_finite() {
            return None;
        }
        if t * step_norm <= 1e-14 || rn <= 1e-14 * h {
            break;
        }
    }
    if rn > 1e-10 * h {
        return None;
    }
    if inside_reference(kind, xi, LOCATE_TOL) {
        Some(xi)
    } else {
        None
    }
}

/// Solves the d x d system a s = b (d <= 3) by Gaussian elimination with
/// partial pivoting; None when a is (numerically) singular.
fn solve_small(d: usize, mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let scale = a[..d].iter().flat_map(|row| row[..d].iter()).fold(0.0f64, |m, v| m.max(v.abs()));
    if !scale.is_finite() || scale <= 0.0 {
        return None;
    }
    for col in 0..d {
        let p = (col..d).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[p][col].abs() <= 1e-13 * scale {
            return None;
        }
        a.swap(col, p);
        b.swap(col, p);
        let pivot_row = a[col];
        for i in col + 1..d {
            let f = a[i][col] / pivot_row[col];
            for (aik, pk) in a[i][col..d].iter_mut().zip(&pivot_row[col..d]) {
                *aik -= f * pk;
            }
            b[i] -= f * b[col];
        }
    }
    let mut s = [0.0; 3];
    for i in (0..d).rev() {
        let mut v = b[i];
        for k in i + 1..d {
            v -= a[i][k] * s[k];
        }
        s[i] = v / a[i][i];
    }
    Some(s)
}

// ---------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds() -> impl Iterator<Item = CellKind> {
        CellKind::ALL.into_iter().filter(|k| k.dim() >= 1)
    }

    /// A few points inside (and one slightly outside) the reference cell.
    fn sample_points(kind: CellKind) -> Vec<[f64; 3]> {
        let d = kind.dim();
        let simplex = matches!(kind, CellKind::Tri3 | CellKind::Tri6 | CellKind::Tet4 | CellKind::Tet10);
        let raw: [[f64; 3]; 5] = [
            [0.1, 0.2, 0.3],
            [0.37, 0.11, 0.05],
            [0.05, 0.6, 0.21],
            [0.25, 0.25, 0.25],
            [0.7, 0.05, 0.1],
        ];
        raw.iter()
            .map(|p| {
                let mut q = [0.0; 3];
                for j in 0..d {
                    q[j] = if simplex { p[j] } else { 2.0 * p[j] - 0.9 + 0.3 * j as f64 };
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
}
