//! The check that the supports hold the model: every rigid-body motion of
//! every cluster of bodies (joined by shared nodes or contacts, contacts
//! counted as closed) must move some prescribed DOF. A free one makes the
//! stiffness singular only up to round-off, which the Cholesky factorisation
//! may not notice, so it is caught here with a message naming the bodies and
//! the motion, and, where they lie on another body without sharing its
//! nodes (volumes that were not fused), saying so and how to fuse them.

use super::body::Body;
use super::build_input::Builder;
use super::errors::{ModelError, Unfused};
use super::quality;
use super::topology::UnionFind;
use crate::fem::element::dofs_per_node;
use crate::fem::rigid::{self, RigidModes};

/// Fails naming the bodies and the motion when some rigid-body motion of a
/// cluster of bodies is stopped by no prescribed DOF. Bodies sharing a
/// model node, or joined by a contact pair `links` (k, l), are one cluster.
pub(super) fn check_held(
    b: &Builder,
    coords: &[[f64; 3]],
    bodies: &[Body],
    links: &[(usize, usize)],
    prescribed: &[Option<f64>],
) -> Result<(), ModelError> {
    let analysis = b.spec.analysis;
    let nd = dofs_per_node(analysis);
    let mut body_of = vec![usize::MAX; coords.len()];
    let mut sets = UnionFind::new(bodies.len());
    for (i, body) in bodies.iter().enumerate() {
        for &n in body.cells.iter().flat_map(|c| &c.nodes) {
            if body_of[n] == usize::MAX {
                body_of[n] = i;
            } else {
                sets.join(body_of[n], i);
            }
        }
    }
    for &(k, l) in links {
        if body_of[k] != usize::MAX && body_of[l] != usize::MAX {
            sets.join(body_of[k], body_of[l]);
        }
    }
    let names = rigid::names(analysis);
    for r in 0..bodies.len() {
        let members: Vec<usize> = (0..bodies.len()).filter(|&i| sets.root(i) == r).collect();
        if members.is_empty() {
            continue;
        }
        let mut nodes: Vec<usize> =
            members.iter().flat_map(|&i| bodies[i].cells.iter().flat_map(|c| c.nodes.iter().copied())).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &n in &nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(coords[n][d]);
                hi[d] = hi[d].max(coords[n][d]);
            }
        }
        let centre: [f64; 3] = std::array::from_fn(|d| 0.5 * (lo[d] + hi[d]));
        let size = (0..3).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
        // Gram matrix of the rigid modes over the prescribed DOFs: singular
        // exactly when some combination of them moves no prescribed DOF
        let supported =
            nodes.iter().flat_map(|&n| (0..nd).filter(move |&a| prescribed[n * nd + a].is_some()).map(move |a| (n, a)));
        let g = RigidModes::new(analysis, centre, size).gram_of_supports(coords, supported);
        // (a Gram matrix that does not decompose, not finite, tells
        // nothing of the body: the solve does)
        let Some(eig) = crate::fem::bounded::symmetric_eigen(g) else { continue };
        let mut free: Vec<&str> = (0..names.len())
            .filter(|&k| eig.eigenvalues[k] < 1e-9)
            .map(|k| names[eig.eigenvectors.column(k).iamax()])
            .collect();
        free.sort_unstable();
        free.dedup();
        if !free.is_empty() {
            let others: Vec<usize> =
                (0..coords.len()).filter(|&n| body_of[n] != usize::MAX && sets.root(body_of[n]) != r).collect();
            let lying = quality::lying_on(coords, &nodes, &others).map(|(nodes, first, on)| Unfused {
                nodes,
                at: coords[first],
                on: bodies[body_of[on]].label(),
                dim: analysis.dim(),
            });
            return Err(ModelError::NotHeld {
                bodies: members.iter().map(|&i| bodies[i].label()).collect(),
                free: free.into_iter().map(String::from).collect(),
                lying,
            });
        }
    }
    Ok(())
}
