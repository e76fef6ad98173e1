//! Which parts can still move as rigid bodies under a set of contact states.
//!
//! Each part's rigid motions are [`RigidModes`] about the part's centre,
//! lengths scaled by its size. Supports ask `u_c(x) = 0` at each supported
//! DOF, and every direction `a` in which a pair (k on part P, l on part Q)
//! is held asks `a . (u_P(x) - u_Q(x)) = 0`: its tied local axes, and
//! across a slipping pair's slip where the robust rule's friction holds it
//! (see `InterfaceProblem::free`). With C the matrix of these rows, the
//! rigid motions nothing stops are the null space of `C^T C` (size 3 or 6
//! per part): the interface system is singular exactly when it is not
//! empty, whatever round-off lets a factorisation get away with. Decided
//! from the geometry, never from pivots.

use nalgebra::DMatrix;

use crate::fem::rigid::{n_modes, RigidModes};
use crate::model::Model;

/// The rigid motions of one part and what its supports make of them.
pub struct PartModes {
    pub modes: RigidModes,
    /// [`RigidModes::gram`] over the part's supported DOFs.
    gram: DMatrix<f64>,
}

impl PartModes {
    /// The modes of the part made of the nodes `nodes` (about their mean,
    /// lengths in their largest distance from it), with its supports.
    pub fn new(model: &Model, nodes: &[usize]) -> PartModes {
        let nd = model.nd;
        let mut center = [0.0; 3];
        for &n in nodes {
            for (c, x) in center.iter_mut().zip(model.coords[n]) {
                *c += x / nodes.len().max(1) as f64;
            }
        }
        let scale = nodes
            .iter()
            .map(|&n| (0..3).map(|i| (model.coords[n][i] - center[i]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let modes = RigidModes::new(model.analysis, center, if scale > 0.0 { scale } else { 1.0 });
        let supported = nodes.iter().flat_map(|&n| (0..nd).filter(move |&c| model.prescribed[n * nd + c].is_some()).map(move |c| (n, c)));
        let gram = modes.gram_of_supports(&model.coords, supported);
        PartModes { modes, gram }
    }
}

/// One tie between two parts: the pair's position and the tied direction.
pub struct Tie {
    pub parts: [usize; 2],
    pub x: [f64; 3],
    pub dir: [f64; 3],
}

/// The parts that some rigid motion left free by supports and `ties` moves,
/// ascending; empty when every part is held.
pub fn free_parts(parts: &[PartModes], ties: impl Iterator<Item = Tie>) -> Vec<usize> {
    let np = parts.len();
    let Some(first) = parts.first() else { return Vec::new() };
    let nm = n_modes(first.modes.analysis());
    let n = nm * np;
    let mut m = DMatrix::<f64>::zeros(n, n);
    for (p, pm) in parts.iter().enumerate() {
        for i in 0..nm {
            for j in 0..nm {
                m[(p * nm + i, p * nm + j)] = pm.gram[(i, j)];
            }
        }
    }
    for tie in ties {
        let [p, q] = tie.parts;
        if p == q {
            continue; // both sides move together in any rigid motion of the part
        }
        let rp = parts[p].modes.along(tie.x, tie.dir);
        let rq = parts[q].modes.along(tie.x, tie.dir);
        let mut row = vec![(0usize, 0.0f64); 2 * nm];
        for i in 0..nm {
            row[i] = (p * nm + i, rp[i]);
            row[nm + i] = (q * nm + i, -rq[i]);
        }
        for &(i, a) in &row {
            for &(j, b) in &row {
                m[(i, j)] += a * b;
            }
        }
    }
    let eig = m.symmetric_eigen();
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    let mut free = vec![false; np];
    for (k, &lambda) in eig.eigenvalues.iter().enumerate() {
        if lambda > 1e-12 * big && big > 0.0 {
            continue;
        }
        let v = eig.eigenvectors.column(k);
        for p in 0..np {
            let w: f64 = (0..nm).map(|i| v[p * nm + i].powi(2)).sum::<f64>().sqrt();
            if w > 1e-6 {
                free[p] = true;
            }
        }
    }
    (0..np).filter(|&p| free[p]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::vec3::unit;
    use crate::fem::Analysis;

    fn part(analysis: Analysis, center: [f64; 3], supported: &[([f64; 3], usize)]) -> PartModes {
        let modes = RigidModes::new(analysis, center, 1.0);
        let gram = modes.gram(supported.iter().map(|&(x, c)| (x, unit(c))));
        PartModes { modes, gram }
    }

    #[test]
    fn an_axisymmetric_ring_is_held_by_an_axial_support_alone() {
        // rings need no radial support: only the axial translation is rigid
        let center = [4.0, 0.5, 0.0];
        assert_eq!(free_parts(&[part(Analysis::Axisymmetric, center, &[])], std::iter::empty()), vec![0]);
        let held = part(Analysis::Axisymmetric, center, &[([4.0, 0.0, 0.0], 1)]);
        assert_eq!(free_parts(&[held], std::iter::empty()), Vec::<usize>::new());
        let radial = part(Analysis::Axisymmetric, center, &[([4.0, 0.0, 0.0], 0)]);
        assert_eq!(free_parts(&[radial], std::iter::empty()), vec![0], "a radial support holds nothing rigid");
    }

    #[test]
    fn a_block_on_a_supported_block_is_held_only_while_tied() {
        let plane = |center, supported: &[([f64; 3], usize)]| part(Analysis::PlaneStrain, center, supported);
        // bottom: base y = 0 held in y at x = 0 and 2, x held at the origin
        let bottom = plane([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1), ([0.0, 0.0, 0.0], 0)]);
        let top = plane([1.0, 1.5, 0.0], &[]);
        let joint = |dirs: &[[f64; 3]]| {
            let mut v = Vec::new();
            for x in [0.0, 1.0, 2.0] {
                for &dir in dirs {
                    v.push(Tie { parts: [0, 1], x: [x, 1.0, 0.0], dir });
                }
            }
            v
        };
        let (n, t) = ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        let parts = [bottom, top];
        assert_eq!(free_parts(&parts, joint(&[n, t]).into_iter()), Vec::<usize>::new(), "stuck");
        assert_eq!(free_parts(&parts, joint(&[n]).into_iter()), vec![1], "slipping: slides along x");
        assert_eq!(free_parts(&parts, joint(&[]).into_iter()), vec![1], "open: held by nothing");
        // a single tied pair stops translations, not the rotation about it
        let one = vec![Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: n }, Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: t }];
        assert_eq!(free_parts(&parts, one.into_iter()), vec![1]);
        // without the x support the bottom slides too, and the stuck top with it
        let loose = plane([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1)]);
        let top = plane([1.0, 1.5, 0.0], &[]);
        assert_eq!(free_parts(&[loose, top], joint(&[n, t]).into_iter()), vec![0, 1]);
    }
}
