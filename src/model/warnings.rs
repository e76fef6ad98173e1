//! What a built model makes legal but a user may not mean: bodies bonded
//! without a word. Two bodies that share model nodes move together there
//! (the nodes are one set of unknowns), so where no contact lies between
//! them they are glued: layered ground on purpose, or a `[[contacts]]`
//! entry forgotten. Also a mesh that is legal but suspect ([`super::quality`]):
//! sliver elements, and nodes that coincide inside one body group (volumes
//! not fused); and gravity that loads nothing, no body having a density.
//! Read from the model alone, after it is built; the writers put the
//! warnings in summary.json and report.md, the commands on stderr, each
//! with the scene file's name in front.

use super::mechanical::Model;

/// One paragraph per pair of bodies that share nodes with no contact pair
/// between them, in body order.
pub fn warnings(model: &Model) -> Vec<String> {
    let mut out = bonds(model);
    out.extend(mesh(model));
    if model.gravity.iter().any(|&g| g != 0.0) && model.bodies.iter().all(|b| b.material.density == 0.0) {
        out.push(format!(
            "gravity = {:?} is given, but no body has a density, so gravity loads nothing. Give the materials a density (in the scene's units: density * |g| is the unit weight), or leave gravity out",
            &model.gravity[..model.nd]
        ));
    }
    out
}

/// Slivers and coincident nodes, one paragraph each.
fn mesh(model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    let slivers = super::quality::slivers(model);
    if let Some((body, tag, q)) = slivers.first() {
        out.push(format!(
            "{} element(s) are nearly flat (slivers: scaled Jacobian below {:e} at a corner), the worst element {tag} of body {body} (scaled Jacobian {q:.1e}): their stiffness is ill-conditioned and their stresses unreliable. Re-mesh them (gmsh: Mesh.Optimize = 1, Mesh.OptimizeNetgen = 1)",
            slivers.len(),
            super::quality::SLIVER
        ));
    }
    for (group, n, x) in super::quality::coincident(model) {
        out.push(format!(
            "body \"{group}\" has {n} nodes that lie on another node of the same body (the first at ({:.6}, {:.6}, {:.6})): its mesh is not joined there, as when volumes are not fused, so the pieces move apart. Fuse them in the .geo (BooleanFragments, or Coherence), or give them a [[contacts]] entry if they should touch",
            x[0], x[1], x[2]
        ));
    }
    out
}

/// One paragraph per pair of bodies bonded without a contact.
fn bonds(model: &Model) -> Vec<String> {
    bonded(model)
        .into_iter()
        .map(|b| {
            let (a, c) = (&model.bodies[b.bodies[0]].name, &model.bodies[b.bodies[1]].name);
            let shared = if b.nodes == 1 { "1 node".to_string() } else { format!("{} nodes", b.nodes) };
            format!(
                "bodies \"{a}\" and \"{c}\" share {shared} and no contact lies between them, so they are bonded there: they move as one, like one body of two materials. If they should be able to open or slip, add a [[contacts]] entry for the physical group between them"
            )
        })
        .collect()
}

/// Two bodies joined by shared nodes and no contact pair.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Bonded {
    /// The two bodies, ascending.
    pub bodies: [usize; 2],
    /// How many model nodes they share.
    pub nodes: usize,
}

/// Every pair of bodies that share model nodes and have no contact pair
/// between them (a pair joins every body of its node k to every body of
/// its node l).
pub fn bonded(model: &Model) -> Vec<Bonded> {
    // the bodies of every node, ascending and without repeats
    let mut owners: Vec<Vec<usize>> = vec![Vec::new(); model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        for &k in body.cells.iter().flat_map(|c| &c.nodes) {
            if owners[k].last() != Some(&b) {
                owners[k].push(b);
            }
        }
    }
    let mut shared: std::collections::BTreeMap<[usize; 2], usize> = std::collections::BTreeMap::new();
    for list in owners.iter().filter(|l| l.len() > 1) {
        for (i, &a) in list.iter().enumerate() {
            for &b in &list[i + 1..] {
                *shared.entry([a, b]).or_default() += 1;
            }
        }
    }
    let mut touching = std::collections::BTreeSet::new();
    for p in &model.pairs {
        for &a in &owners[p.k] {
            for &b in &owners[p.l] {
                touching.insert([a.min(b), a.max(b)]);
            }
        }
    }
    shared
        .into_iter()
        .filter(|(key, _)| !touching.contains(key))
        .map(|(bodies, nodes)| Bonded { bodies, nodes })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::Analysis;
    use crate::mesh::{Cell, CellKind};
    use crate::model::{Body, Material, Pair};

    fn body(name: &str, cells: &[[usize; 3]]) -> Body {
        Body {
            name: name.into(),
            group: 0,
            block: None,
            material: Material { e: 1.0, nu: 0.2, density: 0.0 },
            cells: cells.iter().map(|n| Cell { kind: CellKind::Tri3, nodes: n.to_vec(), tag: 0 }).collect(),
            initial: None,
        }
    }

    /// Three triangles in a row: a and b share the edge 1-2, b and c the
    /// edge 3-4 (nodes 3, 4 copied to 5, 6 for c) with a pair on each of its
    /// nodes.
    fn model(pairs: bool) -> Model {
        let pair = |k, l| Pair { k, l, contact: 0, normal: [1.0, 0.0, 0.0], area: 1.0, shares: Vec::new() };
        Model {
            analysis: Analysis::PlaneStrain,
            nd: 2,
            thickness: 1.0,
            gravity: [0.0; 3],
            coords: vec![[0.0; 3]; 7],
            bodies: vec![body("a", &[[0, 1, 2]]), body("b", &[[1, 3, 2], [2, 3, 4]]), body("c", &[[5, 6, 0]])],
            loads: Vec::new(),
            nodal_loads: Vec::new(),
            supports: Vec::new(),
            prescribed: vec![None; 14],
            pairs: if pairs { vec![pair(3, 5), pair(4, 6)] } else { Vec::new() },
            interfaces: Vec::new(),
            mesh_node: (0..7).collect(),
            cases: vec![vec![1.0]],
            load_cases: Vec::new(),
            gravity_case: 0,
            initial_case: 0,
            hold_case: None,
            water: Vec::new(),
            seismic: Vec::new(),
        }
    }

    #[test]
    fn bodies_sharing_nodes_without_a_contact_are_bonded() {
        let m = model(true);
        // a and b share nodes 1 and 2; a and c share node 0; b and c only pairs
        assert_eq!(bonded(&m), vec![Bonded { bodies: [0, 1], nodes: 2 }, Bonded { bodies: [0, 2], nodes: 1 }]);
        // (the row's nodes all sit at the origin: the mesh warnings are another test's)
        let w = bonds(&m);
        assert_eq!(w.len(), 2);
        assert!(
            w[0].starts_with(
                "bodies \"a\" and \"b\" share 2 nodes and no contact lies between them, so they are bonded there"
            ),
            "{}",
            w[0]
        );
        assert!(w[1].contains("\"a\" and \"c\" share 1 node and"), "{}", w[1]);
        assert!(w[0].contains("add a [[contacts]] entry"));
    }

    #[test]
    fn a_contact_pair_between_two_bodies_that_also_share_nodes_is_no_bond_to_warn_of() {
        // b and c also share node 2 (a joint that ends where both meet)
        let mut m = model(true);
        m.bodies[2].cells.push(Cell { kind: CellKind::Tri3, nodes: vec![5, 2, 6], tag: 0 });
        assert!(!bonded(&m).iter().any(|b| b.bodies == [1, 2]));
        assert!(
            !bonded(&model(false)).iter().any(|b| b.bodies == [1, 2]),
            "no shared node, no pair: nothing joins b and c"
        );
    }
}
