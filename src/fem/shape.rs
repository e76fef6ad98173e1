//! Lagrange shape functions on gmsh's reference elements: the shape
//! functions and their gradients with respect to the reference coordinates
//! ([`eval`]). The reference cells, their node coordinates in gmsh's order
//! and the edge and face tables are in `shape/nodes.rs`; the inverse map
//! (physical point -> reference coordinates, by Newton) in
//! `shape/inverse.rs`; the tests in `shape/tests.rs`. Nothing here knows
//! about elasticity or about the mesh beyond the cell kind.
//!
//! Line, Quad4/Quad9, Hex8/Hex27 are tensor-product Lagrange polynomials;
//! Quad8 and Hex20 are the serendipity ones; Tri and Tet are linear or
//! quadratic Lagrange polynomials in barycentric coordinates. Prism6 and
//! Prism18 are the products Tri3 × Line2 and Tri6 × Line3; Prism15 is the
//! serendipity wedge (its quadrangular faces are Quad8's, its triangles
//! Tri6's). All of them are built from the node tables, so node order lives
//! in one place (the tables) and the Kronecker test checks both agree.
//!
//! Pyramids have no polynomial basis that is conforming with both the
//! hexahedra on their base and the tetrahedra on their sides; theirs are
//! rational (Bergot, Cohen and Duruflé, "Higher-order finite elements for
//! hybrid meshes using new nodal pyramidal elements", J. Sci. Comput. 42,
//! 2010). With `q = ξη / (1 - ζ)` the spaces are
//!
//! ```text
//! Pyramid5:  P1 + {q}                    base: Q1 (Quad4)    sides: P1 (Tri3)
//! Pyramid13: P2 + {q, ξ q, η q}          base: Quad8's       sides: P2 (Tri6)
//! Pyramid14: P2 + {q, ξ q, η q, q²}      base: Q2 (Quad9)    sides: P2 (Tri6)
//! ```
//!
//! so a pyramid's base matches the face of a hex8 / hex20 / hex27 (or a
//! prism's quadrangle) and its sides the faces of tetrahedra: the mesh stays
//! conforming. On a side, say η = -(1 - ζ), q = -ξ is a polynomial, and
//! inside the cell |q| ≤ 1 - ζ, so the functions are continuous up to the
//! apex and their gradients bounded (direction-dependent at the apex
//! itself, where `eval` returns the limit along the axis). Each space
//! contains P1 (P2), so patch tests and rates hold. The nodal basis is the
//! modal one times the inverse of its Vandermonde matrix at the nodes,
//! computed once.

mod inverse;
mod nodes;
#[cfg(test)]
mod tests;

pub use inverse::{locate, map_point, LOCATE_TOL};
pub use nodes::{
    faces, inside_reference, linear_sibling, reference_centre, reference_nodes, Face, HEX_EDGES, HEX_FACES,
    PRISM_EDGES, PYRAMID_EDGES, QUAD_EDGES, TET_EDGES, TRI_EDGES,
};

use std::sync::OnceLock;

use crate::mesh::CellKind;

// ---------------------------------------------------------------------------
// Shape functions
// ---------------------------------------------------------------------------

/// Shape functions `n[a]` and their reference gradients `dn[a][j] = dN_a/dxi_j`
/// (j < kind.dim(), other components 0) at xi.
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
        CellKind::Prism6 => prism_tensor(1, nodes, xi, n, dn),
        CellKind::Prism18 => prism_tensor(2, nodes, xi, n, dn),
        CellKind::Prism15 => prism_serendipity(nodes, xi, n, dn),
        CellKind::Pyramid5 | CellKind::Pyramid13 | CellKind::Pyramid14 => pyramid(kind, xi, n, dn),
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

/// Barycentric coordinates of the unit triangle at (ξ, η) and their
/// gradients: L0 = 1 - ξ - η, L1 = ξ, L2 = η.
fn barycentric(xi: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    ([1.0 - xi[0] - xi[1], xi[0], xi[1]], [[-1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
}

/// The triangle corner at (ξ, η) (0, 1, 2), or the triangle edge whose
/// middle it is (3 + the index in [`TRI_EDGES`]).
fn triangle_position(p: [f64; 3]) -> usize {
    let tri6 = reference_nodes(CellKind::Tri6);
    tri6.iter().position(|t| t[0] == p[0] && t[1] == p[1]).expect("a prism node sits over a Tri6 node")
}

/// Prism6 (order 1) and Prism18 (order 2): the product of the triangle's
/// Lagrange function of the node's (ξ, η) and the line's of its ζ.
fn prism_tensor(order: usize, nodes: &[[f64; 3]], xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let tri = if order == 1 { CellKind::Tri3 } else { CellKind::Tri6 };
    let mut nt = [0.0; 6];
    let mut dnt = [[0.0; 3]; 6];
    let m = tri.n_nodes();
    simplex(2, if order == 1 { &[] } else { &TRI_EDGES }, xi, &mut nt[..m], &mut dnt[..m]);
    for (a, c) in nodes.iter().enumerate() {
        let t = triangle_position(*c);
        let (v, g) = lagrange_1d(order, c[2], xi[2]);
        n[a] = nt[t] * v;
        dn[a] = [dnt[t][0] * v, dnt[t][1] * v, nt[t] * g];
    }
}

/// Prism15, the serendipity wedge: with L the barycentric coordinates,
/// corners `½ L_t (1 + ζ_a ζ)(2 L_t + ζ_a ζ - 2)`, the triangles' mid-edge
/// nodes `2 L_s L_t (1 + ζ_a ζ)`, the vertical mid-edge nodes `L_t (1 - ζ²)`.
fn prism_serendipity(nodes: &[[f64; 3]], xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let (l, dl) = barycentric(xi);
    let z = xi[2];
    for (a, c) in nodes.iter().enumerate() {
        let t = triangle_position(*c);
        let za = c[2];
        if za == 0.0 {
            n[a] = l[t] * (1.0 - z * z);
            dn[a] = [dl[t][0] * (1.0 - z * z), dl[t][1] * (1.0 - z * z), -2.0 * z * l[t]];
        } else if t < 3 {
            let (h, dh) = (1.0 + za * z, za);
            let k = 2.0 * l[t] + za * z - 2.0;
            n[a] = 0.5 * l[t] * h * k;
            let dxy = |j: usize| 0.5 * h * dl[t][j] * (k + 2.0 * l[t]);
            dn[a] = [dxy(0), dxy(1), 0.5 * l[t] * (dh * k + h * za)];
        } else {
            let [s, u] = TRI_EDGES[t - 3];
            let h = 1.0 + za * z;
            n[a] = 2.0 * l[s] * l[u] * h;
            let dxy = |j: usize| 2.0 * h * (dl[s][j] * l[u] + l[s] * dl[u][j]);
            dn[a] = [dxy(0), dxy(1), 2.0 * l[s] * l[u] * za];
        }
    }
}

/// The modal functions of the pyramids (see the module doc) at xi, with
/// their gradients, in the order 1, ξ, η, ζ, q (Pyramid5's five), ξ², η²,
/// ζ², ξη, ξζ, ηζ, ξq, ηq (Pyramid13's thirteen), q² (Pyramid14's last).
fn pyramid_modes(xi: [f64; 3]) -> ([f64; 14], [[f64; 3]; 14]) {
    let [x, y, z] = xi;
    // At the apex (r = 0) inside the cell x = y = 0: q and its gradient
    // take their values along the axis, 0.
    let r = 1.0 - z;
    let r = if r.abs() < 1e-300 { 1e-300 } else { r };
    let q = x * y / r;
    let dq = [y / r, x / r, q / r];
    let f = [1.0, x, y, z, q, x * x, y * y, z * z, x * y, x * z, y * z, x * q, y * q, q * q];
    let g = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        dq,
        [2.0 * x, 0.0, 0.0],
        [0.0, 2.0 * y, 0.0],
        [0.0, 0.0, 2.0 * z],
        [y, x, 0.0],
        [z, 0.0, x],
        [0.0, z, y],
        [q + x * dq[0], x * dq[1], x * dq[2]],
        [y * dq[0], q + y * dq[1], y * dq[2]],
        [2.0 * q * dq[0], 2.0 * q * dq[1], 2.0 * q * dq[2]],
    ];
    (f, g)
}

/// The nodal basis of a pyramid kind in its modal one: `c[j * m + a]` is
/// the coefficient of mode j in N_a (m = the number of nodes), the inverse
/// of the Vandermonde matrix `V[a][j] = mode_j(node_a)`, refined by two
/// steps of `C <- C + C (I - V C)` so that the Kronecker property holds to
/// round-off.
fn pyramid_coefficients(kind: CellKind) -> &'static [f64] {
    static TABLES: OnceLock<[Vec<f64>; 3]> = OnceLock::new();
    let tables = TABLES.get_or_init(|| {
        [CellKind::Pyramid5, CellKind::Pyramid13, CellKind::Pyramid14].map(|k| {
            use nalgebra::DMatrix;
            let nodes = reference_nodes(k);
            let m = nodes.len();
            let v = DMatrix::from_fn(m, m, |a, j| pyramid_modes(nodes[a]).0[j]);
            let mut c = v.clone().lu().try_inverse().expect("the pyramid's nodes are unisolvent for its space");
            let eye = DMatrix::<f64>::identity(m, m);
            for _ in 0..2 {
                c = &c + &c * (&eye - &v * &c);
            }
            // row-major: mode j, node a
            (0..m * m).map(|i| c[(i / m, i % m)]).collect()
        })
    });
    match kind {
        CellKind::Pyramid5 => &tables[0],
        CellKind::Pyramid13 => &tables[1],
        _ => &tables[2],
    }
}

/// Pyramid5, Pyramid13, Pyramid14: `N_a = Σ_j c[j][a] mode_j`.
fn pyramid(kind: CellKind, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let m = kind.n_nodes();
    let c = pyramid_coefficients(kind);
    let (f, g) = pyramid_modes(xi);
    for a in 0..m {
        let (mut v, mut d) = (0.0, [0.0; 3]);
        for j in 0..m {
            let cj = c[j * m + a];
            v += cj * f[j];
            for i in 0..3 {
                d[i] += cj * g[j][i];
            }
        }
        n[a] = v;
        dn[a] = d;
    }
}
