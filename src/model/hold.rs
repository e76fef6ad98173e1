//! The hold load of the initial equilibrium stage (`[solver]
//! initial_stage`): the in-situ traction `σ0(x) n` on every boundary facet
//! of every body that carries an initial stress, less its contact facets.
//!
//! The initial stress's load and gravity's add up to `-∫ N σ0 n dA` over
//! a body's whole boundary when `σ0` is in equilibrium with the weight
//! (geostatic k0 stress is, and tri6 / tet10 integrate it exactly); with
//! the hold load on its outer faces, what is left is the in-situ traction
//! on its joints alone, which a joint that can carry it carries without
//! moving. Supported faces take it too (only their reactions change).
//!
//! A boundary facet is a face of a body's cell that no other cell of the
//! model shares (corners compared in model nodes, so faces across a
//! contact, whose nodes were split, are on the boundary); the contact
//! facets are those of the interfaces, on side I in their own nodes and on
//! side II in the nodes their pairs give (a node in no pair, the tip of a
//! joint, is shared).

use std::collections::{HashMap, HashSet};

use super::{FacetLoad, LoadKind, Model};
use crate::fem::element;
use crate::fem::shape::{self, QUAD_EDGES, TRI_EDGES};
use crate::mesh::{Cell, CellKind};

/// The hold loads of `model` in load case `case`.
pub(super) fn loads(model: &Model, case: usize) -> Vec<FacetLoad> {
    let joints = contact_keys(model);
    // every face of every cell: (body, element, facet in model nodes)
    let mut faces: HashMap<Vec<usize>, Vec<(usize, usize, Cell)>> = HashMap::new();
    for (b, body) in model.bodies.iter().enumerate() {
        for (e, cell) in body.cells.iter().enumerate() {
            for facet in local_facets(cell) {
                faces.entry(key(&facet)).or_default().push((b, e, facet));
            }
        }
    }
    let mut out: Vec<FacetLoad> = Vec::new();
    for (k, mut on) in faces {
        if on.len() != 1 || joints.contains(&k) {
            continue;
        }
        let (body, element, facet) = on.pop().expect("one face");
        let b = &model.bodies[body];
        let Some(stress) = b.initial else { continue };
        let cell = &b.cells[element];
        let fc: Vec<[f64; 3]> = facet.nodes.iter().map(|&n| model.coords[n]).collect();
        let cc: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| model.coords[n]).collect();
        let sign = element::outward_sign(facet.kind, &fc, cell.kind, &cc);
        let kind = LoadKind::InSitu { stress, density: b.material.density, gravity: model.gravity };
        out.push(FacetLoad { cell: facet, sign, kind, body, element, case });
    }
    // one order whatever the hash map's
    out.sort_unstable_by_key(|l| (l.body, l.element, key(&l.cell)));
    out
}

/// The sorted corners of a facet.
fn key(facet: &Cell) -> Vec<usize> {
    let mut k = facet.nodes[..facet.kind.n_corners()].to_vec();
    k.sort_unstable();
    k
}

/// The keys of every contact facet, on both its sides.
fn contact_keys(model: &Model) -> HashSet<Vec<usize>> {
    let at = model.facet_pairs();
    let mut out = HashSet::new();
    for (i, interface) in model.interfaces.iter().enumerate() {
        for (f, facet) in interface.facets.iter().enumerate() {
            out.insert(key(facet));
            let mut other = facet.clone();
            for (a, n) in other.nodes.iter_mut().enumerate() {
                if let Some(pair) = model.pairs.get(at[i][f][a]) {
                    *n = pair.l;
                }
            }
            out.insert(key(&other));
        }
    }
    out
}

/// The faces (3D) or edges (2D) of a cell as facets in its nodes, with
/// the cell's tag.
fn local_facets(cell: &Cell) -> Vec<Cell> {
    let (kind, tag) = (cell.kind, cell.tag);
    let of =
        |kind: CellKind, local: &[usize]| Cell { kind, nodes: local.iter().map(|&a| cell.nodes[a]).collect(), tag };
    let edges = |table: &[[usize; 2]], first_mid: usize| -> Vec<Cell> {
        (table.iter().enumerate())
            .map(|(i, e)| match kind.order() {
                2 => of(CellKind::Line3, &[e[0], e[1], first_mid + i]),
                _ => of(CellKind::Line2, e),
            })
            .collect()
    };
    match kind {
        CellKind::Tri3 | CellKind::Tri6 => edges(&TRI_EDGES, 3),
        CellKind::Quad4 | CellKind::Quad8 | CellKind::Quad9 => edges(&QUAD_EDGES, 4),
        _ => shape::faces(kind).into_iter().map(|f| of(f.kind, &f.nodes)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::local_facets;
    use crate::mesh::{Cell, CellKind};

    #[test]
    fn a_tri6_has_three_quadratic_edges_with_their_mid_nodes() {
        let cell = Cell { kind: CellKind::Tri6, nodes: vec![10, 11, 12, 13, 14, 15], tag: 7 };
        let f = local_facets(&cell);
        let nodes: Vec<Vec<usize>> = f.iter().map(|c| c.nodes.clone()).collect();
        assert_eq!(nodes, vec![vec![10, 11, 13], vec![11, 12, 14], vec![12, 10, 15]]);
        assert!(f.iter().all(|c| c.kind == CellKind::Line3 && c.tag == 7));
    }

    #[test]
    fn a_tet10_has_four_tri6_faces() {
        let cell = Cell { kind: CellKind::Tet10, nodes: (0..10).collect(), tag: 1 };
        let f = local_facets(&cell);
        assert_eq!(f.len(), 4);
        assert!(f.iter().all(|c| c.kind == CellKind::Tri6 && c.nodes.len() == 6));
    }
}
