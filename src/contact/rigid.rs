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
        let supported = nodes
            .iter()
            .flat_map(|&n| (0..nd).filter(move |&c| model.prescribed[n * nd + c].is_some()).map(move |c| (n, c)));
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
///
/// A part whose own supports, and ties to parts already found held, stop
/// its rigid motions is held: found so part by part from the supported
/// ones outward (a few 6 x 6 eigenproblems per part, so that a rock mass
/// of a thousand blocks costs milliseconds). Parts held only together
/// (two blocks that each need the other) are left to the eigenproblem of
/// `C^T C` over what remains, one group of parts joined by ties at a time,
/// with ties to held parts acting as supports.
pub fn free_parts(parts: &[PartModes], ties: impl Iterator<Item = Tie>) -> Vec<usize> {
    let np = parts.len();
    let Some(first) = parts.first() else { return Vec::new() };
    let nm = n_modes(first.modes.analysis());
    let ties: Vec<Tie> = ties.filter(|t| t.parts[0] != t.parts[1]).collect();
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); np];
    for (i, t) in ties.iter().enumerate() {
        at[t.parts[0]].push(i);
        at[t.parts[1]].push(i);
    }
    // each part's supports, then its ties to held parts as it learns of them
    let mut gram: Vec<DMatrix<f64>> = parts.iter().map(|p| p.gram.clone()).collect();
    let mut held = vec![false; np];
    let mut found: Vec<usize> = (0..np).filter(|&p| full_rank(&gram[p])).collect();
    found.iter().for_each(|&p| held[p] = true);
    while let Some(p) = found.pop() {
        for &i in &at[p] {
            let t = &ties[i];
            let q = if t.parts[0] == p { t.parts[1] } else { t.parts[0] };
            if held[q] {
                continue;
            }
            add_outer(&mut gram[q], &parts[q].modes.along(t.x, t.dir)[..nm]);
            if full_rank(&gram[q]) {
                held[q] = true;
                found.push(q);
            }
        }
    }
    let mut free = Vec::new();
    for group in groups(&held, &ties) {
        free.extend(free_in(parts, &gram, &ties, &group, nm));
    }
    free.sort_unstable();
    free
}

/// The parts not held, in groups joined by ties between them.
fn groups(held: &[bool], ties: &[Tie]) -> Vec<Vec<usize>> {
    let np = held.len();
    let mut root: Vec<usize> = (0..np).collect();
    fn find(r: &mut [usize], mut i: usize) -> usize {
        while r[i] != i {
            r[i] = r[r[i]];
            i = r[i];
        }
        i
    }
    for t in ties.iter().filter(|t| !held[t.parts[0]] && !held[t.parts[1]]) {
        let (a, b) = (find(&mut root, t.parts[0]), find(&mut root, t.parts[1]));
        root[a.max(b)] = a.min(b);
    }
    let mut of_root: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for p in (0..np).filter(|&p| !held[p]) {
        let r = find(&mut root, p);
        of_root.entry(r).or_default().push(p);
    }
    of_root.into_values().collect()
}

/// The parts of `group` that a rigid motion moves: the null space of
/// `C^T C` over the group, each part's supports and ties to held parts
/// already in `gram`.
fn free_in(parts: &[PartModes], gram: &[DMatrix<f64>], ties: &[Tie], group: &[usize], nm: usize) -> Vec<usize> {
    let mut index = std::collections::HashMap::new();
    for (i, &p) in group.iter().enumerate() {
        index.insert(p, i);
    }
    let mut m = DMatrix::<f64>::zeros(nm * group.len(), nm * group.len());
    for (i, &p) in group.iter().enumerate() {
        m.view_mut((i * nm, i * nm), (nm, nm)).copy_from(&gram[p]);
    }
    for t in ties {
        let (Some(&i), Some(&j)) = (index.get(&t.parts[0]), index.get(&t.parts[1])) else { continue };
        let (rp, rq) = (parts[t.parts[0]].modes.along(t.x, t.dir), parts[t.parts[1]].modes.along(t.x, t.dir));
        let row: Vec<(usize, f64)> =
            (0..nm).map(|a| (i * nm + a, rp[a])).chain((0..nm).map(|a| (j * nm + a, -rq[a]))).collect();
        for &(r, a) in &row {
            for &(c, b) in &row {
                m[(r, c)] += a * b;
            }
        }
    }
    let eig = m.symmetric_eigen();
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    let mut free = vec![false; group.len()];
    for (k, &lambda) in eig.eigenvalues.iter().enumerate() {
        if lambda > 1e-12 * big && big > 0.0 {
            continue;
        }
        let v = eig.eigenvectors.column(k);
        for (i, f) in free.iter_mut().enumerate() {
            let w: f64 = (0..nm).map(|a| v[i * nm + a].powi(2)).sum::<f64>().sqrt();
            *f |= w > 1e-6;
        }
    }
    group.iter().zip(free).filter(|(_, f)| *f).map(|(&p, _)| p).collect()
}

/// Whether a part's Gram matrix stops all its rigid motions.
fn full_rank(g: &DMatrix<f64>) -> bool {
    let eig = g.clone().symmetric_eigen();
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    big > 0.0 && eig.eigenvalues.iter().all(|&l| l > 1e-12 * big)
}

/// `g += r r^T`.
fn add_outer(g: &mut DMatrix<f64>, r: &[f64]) {
    for (i, a) in r.iter().enumerate() {
        for (j, b) in r.iter().enumerate() {
            g[(i, j)] += a * b;
        }
    }
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
    fn a_three_hinged_arch_is_held_only_together_and_not_when_its_hinges_line_up() {
        // two halves, each pinned to held ground at its foot (a, b) and to
        // the other at the crown c: neither is held alone, both together
        // unless a, b and c lie on one line
        let plane = |center| part(Analysis::PlaneStrain, center, &[]);
        let ground = || {
            part(
                Analysis::PlaneStrain,
                [2.0, -1.0, 0.0],
                &[([0.0, -1.0, 0.0], 0), ([0.0, -1.0, 0.0], 1), ([4.0, -1.0, 0.0], 1)],
            )
        };
        let pin = |p: usize, q: usize, x: [f64; 3]| {
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|dir| Tie { parts: [p, q], x, dir })
        };
        let arch = |crown: [f64; 3]| {
            let parts = [ground(), plane([1.0, 1.0, 0.0]), plane([3.0, 1.0, 0.0])];
            let ties = [pin(0, 1, [0.0, 0.0, 0.0]), pin(0, 2, [4.0, 0.0, 0.0]), pin(1, 2, crown)];
            free_parts(&parts, ties.into_iter().flatten())
        };
        assert_eq!(arch([2.0, 2.0, 0.0]), Vec::<usize>::new(), "a three-hinged arch stands");
        assert_eq!(arch([2.0, 0.0, 0.0]), vec![1, 2], "hinges on one line: a mechanism");
        // one half alone on its pin turns
        let parts = [ground(), plane([1.0, 1.0, 0.0])];
        assert_eq!(free_parts(&parts, pin(0, 1, [0.0, 0.0, 0.0]).into_iter()), vec![1]);
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
        let one =
            vec![Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: n }, Tie { parts: [0, 1], x: [1.0, 1.0, 0.0], dir: t }];
        assert_eq!(free_parts(&parts, one.into_iter()), vec![1]);
        // without the x support the bottom slides too, and the stuck top with it
        let loose = plane([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1)]);
        let top = plane([1.0, 1.5, 0.0], &[]);
        assert_eq!(free_parts(&[loose, top], joint(&[n, t]).into_iter()), vec![0, 1]);
    }
}
