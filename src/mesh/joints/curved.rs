//! Quadratic elements that fold where they follow a curved face, made
//! straight: the deterministic stand-in for gmsh's high-order optimiser
//! in the joint cutter's session.
//!
//! gmsh 4.8's `Mesh.HighOrderOptimize` (the elastic analogy and the patch
//! optimiser alike) orders its work by memory address: run twice on the
//! same model, with the addresses shuffled as Linux shuffles them, it
//! moves the mid-side nodes of the elements it mends to other places
//! (measured: 882 of 10,935 nodes of geo/tunnel3d.toml, up to 8.9 mm, so
//! the contact iteration took 53 or 48 steps). The cutter therefore runs
//! gmsh without it and, where the .geo asked for it, mends the same
//! elements itself, in node-tag order: a quadratic element whose least
//! Jacobian, relative to its straight sibling's, is below the threshold
//! (`Mesh.HighOrderThresholdMin`, gmsh's own bound of what it optimises)
//! gets its mid-side nodes back on its straight edges. A straight element
//! is as valid as its linear mesh. Moving a shared node bends no
//! neighbour further, but is checked again, a few passes at most.

use std::collections::{BTreeSet, HashMap};

use crate::fem::shape;
use crate::mesh::cell_kind::CellKind;

/// Passes over the elements whose nodes moved.
const PASSES: usize = 4;

/// A quadratic element kind and, for each of its mid-side nodes, its
/// index and the two corners it lies between (from the reference nodes).
fn edges(kind: CellKind) -> Vec<(usize, usize, usize)> {
    let r = shape::reference_nodes(kind);
    let nc = shape::linear_sibling(kind).n_nodes();
    let mut out = Vec::new();
    for (m, x) in r.iter().enumerate().skip(nc) {
        let mid = |a: usize, b: usize| (0..3).all(|d| ((r[a][d] + r[b][d]) / 2.0 - x[d]).abs() < 1e-12);
        if let Some((a, b)) = (0..nc).flat_map(|a| (a + 1..nc).map(move |b| (a, b))).find(|&(a, b)| mid(a, b)) {
            out.push((m, a, b));
        }
    }
    out
}

/// The least Jacobian determinant of the element at its nodes and centre,
/// over its straight sibling's (1 for a straight element, below 0 folded).
pub(super) fn quality(kind: CellKind, x: &[[f64; 3]]) -> f64 {
    let dim = kind.dim();
    let det = |k: CellKind, xi: [f64; 3]| {
        let nn = k.n_nodes();
        let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
        shape::eval(k, xi, &mut n, &mut dn);
        let mut j = [[0.0; 3]; 3];
        for (p, g) in x.iter().zip(&dn) {
            for (c, col) in j.iter_mut().enumerate().take(dim) {
                for i in 0..3 {
                    col[i] += p[i] * g[c];
                }
            }
        }
        if dim == 2 {
            j[0][0] * j[1][1] - j[0][1] * j[1][0]
        } else {
            crate::fem::vec3::dot(j[0], crate::fem::vec3::cross(j[1], j[2]))
        }
    };
    let centre = shape::reference_centre(kind);
    let straight = det(shape::linear_sibling(kind), centre);
    if straight <= 0.0 {
        return f64::NEG_INFINITY;
    }
    shape::reference_nodes(kind)
        .iter()
        .chain([&centre])
        .map(|&xi| det(kind, xi) / straight)
        .fold(f64::INFINITY, f64::min)
}

/// What [`straighten`] did: the elements made straight, and the least
/// quality before and after.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Straightened {
    pub elements: usize,
    pub before: f64,
    pub after: f64,
}

/// Moves the mid-side nodes of every element of `kind` whose [`quality`]
/// is below `threshold` onto its straight edges. `coords` maps node tags
/// to places (updated); `elements` holds the node tags, `kind.n_nodes()`
/// per element. Returns what it did and the nodes moved, in tag order.
pub(super) fn straighten(
    kind: CellKind,
    elements: &[usize],
    coords: &mut HashMap<usize, [f64; 3]>,
    threshold: f64,
) -> (Straightened, BTreeSet<usize>) {
    let per = kind.n_nodes();
    let edges = edges(kind);
    let q = |e: &[usize], c: &HashMap<usize, [f64; 3]>| {
        let x: Vec<[f64; 3]> = e.iter().map(|t| c.get(t).copied().unwrap_or([f64::NAN; 3])).collect();
        quality(kind, &x)
    };
    let before = elements.chunks_exact(per).map(|e| q(e, coords)).fold(f64::INFINITY, f64::min);
    let mut moved = BTreeSet::new();
    let mut done = BTreeSet::new();
    for _ in 0..PASSES {
        let bad: Vec<usize> = (0..elements.len() / per)
            .filter(|&i| !done.contains(&i) && q(&elements[i * per..(i + 1) * per], coords) < threshold)
            .collect();
        if bad.is_empty() {
            break;
        }
        for i in bad {
            let e = &elements[i * per..(i + 1) * per];
            for &(m, a, b) in &edges {
                let (Some(&xa), Some(&xb)) = (coords.get(&e[a]), coords.get(&e[b])) else { continue };
                coords.insert(e[m], std::array::from_fn(|d| (xa[d] + xb[d]) / 2.0));
                moved.insert(e[m]);
            }
            done.insert(i);
        }
    }
    let after = elements.chunks_exact(per).map(|e| q(e, coords)).fold(f64::INFINITY, f64::min);
    (Straightened { elements: done.len(), before, after }, moved)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tet10 on the corners (0,0,0), (1,0,0), (0,1,0), (0,0,1), the
    /// mid-side node between corners 0 and 1 pushed by `dz` along z.
    fn tet(dz: f64) -> (Vec<usize>, HashMap<usize, [f64; 3]>) {
        let r = shape::reference_nodes(CellKind::Tet10);
        let mut c: HashMap<usize, [f64; 3]> = r.iter().enumerate().map(|(i, x)| (i + 1, *x)).collect();
        let (m, _, _) = edges(CellKind::Tet10).into_iter().find(|&(_, a, b)| (a, b) == (0, 1)).expect("edge 0-1");
        c.get_mut(&(m + 1)).expect("node")[2] += dz;
        ((1..=10).collect(), c)
    }

    /// The edge 0-1 bent by dz: along it (y = z = 0, x = t) the Jacobian
    /// over the straight one is 1 - 4 dz (1 - 2 t) (d/dz of the bubble
    /// 4 l0 l1 dz), least at t = 0: 1 - 4 dz. Made straight it is 1.
    #[test]
    fn a_bent_edge_is_measured_and_made_straight() {
        assert_eq!(edges(CellKind::Tet10).len(), 6);
        assert_eq!(edges(CellKind::Tri6).len(), 3);
        for dz in [0.0, 0.1, 0.2, 0.4] {
            let (e, c) = tet(dz);
            let x: Vec<[f64; 3]> = e.iter().map(|t| c[t]).collect();
            let q = quality(CellKind::Tet10, &x);
            assert!((q - (1.0 - 4.0 * dz)).abs() < 1e-12, "dz {dz}: {q}");
        }
        let (e, mut c) = tet(0.4);
        let (done, moved) = straighten(CellKind::Tet10, &e, &mut c, 0.1);
        assert_eq!((done.elements, moved.len()), (1, 6));
        assert!((done.before + 0.6).abs() < 1e-12 && (done.after - 1.0).abs() < 1e-12, "{done:?}");
        let (e, mut c) = tet(0.2);
        let (done, moved) = straighten(CellKind::Tet10, &e, &mut c, 0.1);
        assert_eq!((done.elements, moved.len()), (0, 0), "0.2 is above the threshold");
    }
}
