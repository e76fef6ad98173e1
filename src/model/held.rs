//! The check that the supports hold the model: every rigid-body motion of
//! every cluster of bodies (joined by shared nodes or contacts, contacts
//! counted as closed) must move some prescribed DOF. A free one makes the
//! stiffness singular only up to round-off, which the Cholesky factorisation
//! may not notice, so it is caught here with a message naming the bodies and
//! the motion.

use super::builder::Builder;
use super::topology::UnionFind;
use super::{Body, ModelError};
use crate::fem::element::dofs_per_node;
use crate::fem::Analysis;

/// Value of rigid-body mode `m` at displacement component `a` of a point at
/// `x` (relative to the cluster's centre): translations, then rotations.
fn rigid_mode(analysis: Analysis, m: usize, a: usize, x: [f64; 3]) -> f64 {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => match (m, a) {
            (0, 0) | (1, 1) => 1.0,
            (2, 0) => -x[1],
            (2, 1) => x[0],
            _ => 0.0,
        },
        // only the axial translation is rigid: a radial one strains the hoop
        Analysis::Axisymmetric => f64::from(u8::from(m == 0 && a == 1)),
        Analysis::Solid => {
            if m < 3 {
                return f64::from(u8::from(m == a));
            }
            // omega x x with omega the unit vector of axis m - 3
            let w = m - 3;
            let (i, j) = ((w + 1) % 3, (w + 2) % 3);
            if a == i {
                -x[j]
            } else if a == j {
                x[i]
            } else {
                0.0
            }
        }
    }
}

/// Fails naming the bodies and the motion when some rigid-body motion of a
/// cluster of bodies is stopped by no prescribed DOF. Bodies sharing a
/// model node, or joined by a contact pair `links` (k, l), are one cluster.
pub(super) fn check_held(b: &Builder, coords: &[[f64; 3]], bodies: &[Body], links: &[(usize, usize)], prescribed: &[Option<f64>]) -> Result<(), ModelError> {
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
    let names: &[&str] = match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => &["translation in x", "translation in y", "rotation about z"],
        Analysis::Axisymmetric => &["translation along the axis (y)"],
        Analysis::Solid => &["translation in x", "translation in y", "translation in z", "rotation about x", "rotation about y", "rotation about z"],
    };
    let nm = names.len();
    for r in 0..bodies.len() {
        let members: Vec<usize> = (0..bodies.len()).filter(|&i| sets.root(i) == r).collect();
        if members.is_empty() {
            continue;
        }
        let mut nodes: Vec<usize> = members.iter().flat_map(|&i| bodies[i].cells.iter().flat_map(|c| c.nodes.iter().copied())).collect();
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
        let mut g = nalgebra::DMatrix::<f64>::zeros(nm, nm);
        for &n in &nodes {
            let x: [f64; 3] = std::array::from_fn(|d| (coords[n][d] - centre[d]) / size);
            for a in 0..nd {
                if prescribed[n * nd + a].is_some() {
                    let phi: Vec<f64> = (0..nm).map(|m| rigid_mode(analysis, m, a, x)).collect();
                    for i in 0..nm {
                        for j in 0..nm {
                            g[(i, j)] += phi[i] * phi[j];
                        }
                    }
                }
            }
        }
        let eig = nalgebra::SymmetricEigen::new(g);
        let mut free: Vec<&str> = (0..nm).filter(|&k| eig.eigenvalues[k] < 1e-9).map(|k| names[eig.eigenvectors.column(k).iamax()]).collect();
        free.sort_unstable();
        free.dedup();
        if !free.is_empty() {
            let one = members.len() == 1;
            return Err(b.invalid(
                "supports".into(),
                format!(
                    "{} {} not held: no support stops {} {} (contacts counted as closed), so the stiffness matrix is singular. Add a support that stops it (fix = [..] on a physical point, curve or surface)",
                    if one { "body" } else { "bodies" },
                    members.iter().map(|&i| bodies[i].label()).collect::<Vec<_>>().join(", "),
                    if one { "its" } else { "their" },
                    free.join(", ")
                ),
            ));
        }
    }
    Ok(())
}
