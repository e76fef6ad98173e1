//! Which parts can still move as rigid bodies under a set of contact states.
//!
//! A part's rigid motions are `u(x) = R(x) alpha` (plane: two translations
//! and the rotation about z; axisymmetric: the translation along the axis y
//! only, since moving in r strains the hoops; solid: three translations and
//! three rotations; rotations about the part's centre, lengths scaled by its
//! size so every entry is O(1)).
//! Supports ask `u_c(x) = 0` at each supported DOF, and every tied local axis
//! `a` of a pair (k on part P, l on part Q) asks `a . (u_P(x) - u_Q(x)) = 0`.
//! With C the matrix of these rows, the rigid motions nothing stops are the
//! null space of `C^T C` (size 3 or 6 per part): the interface system is
//! singular exactly when it is not empty, whatever round-off lets a
//! factorisation get away with. Decided from the geometry, never from pivots.

use nalgebra::DMatrix;

use crate::model::Model;
use crate::fem::Analysis;

/// The rigid motions of one part and what its supports make of them.
pub struct RigidModes {
    analysis: Analysis,
    center: [f64; 3],
    scale: f64,
    /// `sum r r^T` over the part's supported DOFs, r = row of R(x) (nm x nm).
    gram: Vec<f64>,
}

pub fn n_modes(analysis: Analysis) -> usize {
    match analysis {
        Analysis::PlaneStrain | Analysis::PlaneStress => 3,
        Analysis::Axisymmetric => 1,
        Analysis::Solid => 6,
    }
}

impl RigidModes {
    /// The modes of the part made of the nodes `nodes`, with its supports.
    pub fn new(model: &Model, nodes: &[usize]) -> RigidModes {
        let nd = model.nd;
        let mut center = [0.0; 3];
        for &n in nodes {
            for i in 0..3 {
                center[i] += model.coords[n][i] / nodes.len().max(1) as f64;
            }
        }
        let scale = nodes
            .iter()
            .map(|&n| (0..3).map(|i| (model.coords[n][i] - center[i]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        let mut modes = RigidModes { analysis: model.analysis, center, scale: if scale > 0.0 { scale } else { 1.0 }, gram: Vec::new() };
        let nm = n_modes(model.analysis);
        let mut gram = vec![0.0; nm * nm];
        for &n in nodes {
            for c in 0..nd {
                if model.prescribed[n * nd + c].is_some() {
                    let r = modes.along(model.coords[n], unit(c));
                    for i in 0..nm {
                        for j in 0..nm {
                            gram[i + j * nm] += r[i] * r[j];
                        }
                    }
                }
            }
        }
        modes.gram = gram;
        modes
    }

    /// `dir . R(x)`: how much each mode moves the point x along `dir`.
    pub fn along(&self, x: [f64; 3], dir: [f64; 3]) -> [f64; 6] {
        let d = [(x[0] - self.center[0]) / self.scale, (x[1] - self.center[1]) / self.scale, (x[2] - self.center[2]) / self.scale];
        match self.analysis {
            // u = t + theta e_z x d
            Analysis::PlaneStrain | Analysis::PlaneStress => [dir[0], dir[1], -d[1] * dir[0] + d[0] * dir[1], 0.0, 0.0, 0.0],
            Analysis::Axisymmetric => [dir[1], 0.0, 0.0, 0.0, 0.0, 0.0],
            // u = t + w x d: (w x d) . dir = w . (d x dir)
            Analysis::Solid => {
                let c = [d[1] * dir[2] - d[2] * dir[1], d[2] * dir[0] - d[0] * dir[2], d[0] * dir[1] - d[1] * dir[0]];
                [dir[0], dir[1], dir[2], c[0], c[1], c[2]]
            }
        }
    }
}

fn unit(c: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[c] = 1.0;
    e
}

/// One tie between two parts: the pair's position and the tied direction.
pub struct Tie {
    pub parts: [usize; 2],
    pub x: [f64; 3],
    pub dir: [f64; 3],
}

/// The parts that some rigid motion left free by supports and `ties` moves,
/// ascending; empty when every part is held.
pub fn free_parts(modes: &[RigidModes], ties: impl Iterator<Item = Tie>) -> Vec<usize> {
    let np = modes.len();
    let Some(first) = modes.first() else { return Vec::new() };
    let nm = n_modes(first.analysis);
    let n = nm * np;
    let mut m = DMatrix::<f64>::zeros(n, n);
    for (p, rm) in modes.iter().enumerate() {
        for i in 0..nm {
            for j in 0..nm {
                m[(p * nm + i, p * nm + j)] = rm.gram[i + j * nm];
            }
        }
    }
    for tie in ties {
        let [p, q] = tie.parts;
        if p == q {
            continue; // both sides move together in any rigid motion of the part
        }
        let rp = modes[p].along(tie.x, tie.dir);
        let rq = modes[q].along(tie.x, tie.dir);
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

    fn modes_2d(center: [f64; 3], supported: &[([f64; 3], usize)]) -> RigidModes {
        let mut rm = RigidModes { analysis: Analysis::PlaneStrain, center, scale: 1.0, gram: vec![0.0; 9] };
        let mut gram = vec![0.0; 9];
        for &(x, c) in supported {
            let r = rm.along(x, unit(c));
            for i in 0..3 {
                for j in 0..3 {
                    gram[i + j * 3] += r[i] * r[j];
                }
            }
        }
        rm.gram = gram;
        rm
    }

    #[test]
    fn rotation_mode_is_a_rigid_motion() {
        // a rotation about z moves (1, 0) along y and (0, 1) along -x
        let rm = RigidModes { analysis: Analysis::Solid, center: [0.0; 3], scale: 1.0, gram: vec![0.0; 36] };
        assert_eq!(rm.along([1.0, 0.0, 0.0], [0.0, 1.0, 0.0])[5], 1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])[5], -1.0);
        assert_eq!(rm.along([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])[3], 1.0);
    }

    #[test]
    fn an_axisymmetric_ring_is_held_by_an_axial_support_alone() {
        // rings need no radial support: only the axial translation is rigid
        let mut ring = RigidModes { analysis: Analysis::Axisymmetric, center: [4.0, 0.5, 0.0], scale: 1.0, gram: vec![0.0] };
        assert_eq!(free_parts(&[ring], std::iter::empty()), vec![0]);
        ring = RigidModes { analysis: Analysis::Axisymmetric, center: [4.0, 0.5, 0.0], scale: 1.0, gram: vec![1.0] };
        assert_eq!(free_parts(&[ring], std::iter::empty()), Vec::<usize>::new());
        let r = RigidModes { analysis: Analysis::Axisymmetric, center: [4.0, 0.5, 0.0], scale: 1.0, gram: vec![0.0] };
        assert_eq!(r.along([3.0, 0.0, 0.0], [1.0, 0.0, 0.0])[0], 0.0, "no radial rigid motion");
    }

    #[test]
    fn a_block_on_a_supported_block_is_held_only_while_tied() {
        // bottom: base y = 0 held in y at x = 0 and 2, x held at the origin
        let bottom = modes_2d([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1), ([0.0, 0.0, 0.0], 0)]);
        let top = modes_2d([1.0, 1.5, 0.0], &[]);
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
        let modes = [bottom, top];
        assert_eq!(free_parts(&modes, joint(&[n, t]).into_iter()), Vec::<usize>::new(), "stuck");
        assert_eq!(free_parts(&modes, joint(&[n]).into_iter()), vec![1], "slipping: slides along x");
        assert_eq!(free_parts(&modes, joint(&[]).into_iter()), vec![1], "open: held by nothing");
        // a single tied pair stops translations, not the rotation about it
        let one = vec![Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: n }, Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: t }];
        assert_eq!(free_parts(&modes, one.into_iter()), vec![1]);
        // without the x support the bottom slides too, and the stuck top with it
        let loose = modes_2d([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1)]);
        let top = modes_2d([1.0, 1.5, 0.0], &[]);
        assert_eq!(free_parts(&[loose, top], joint(&[n, t]).into_iter()), vec![0, 1]);
    }
}
