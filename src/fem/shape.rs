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
//! quadratic Lagrange polynomials in barycentric coordinates. All of them
//! are built from the node tables, so node order lives in one place (the
//! tables) and the Kronecker test checks both agree.

mod inverse;
mod nodes;
#[cfg(test)]
mod tests;

pub use inverse::{locate, map_point, LOCATE_TOL};
pub use nodes::{
    inside_reference, linear_sibling, reference_centre, reference_nodes, HEX_EDGES, HEX_FACES, QUAD_EDGES, TET_EDGES, TRI_EDGES,
};

use crate::mesh::CellKind;

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
