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
//!
//! A pair on a curved contact that holds only along its normal holds less
//! than its row says: its normal is the mean of its facets' normals, which
//! spread over an angle `theta` about it, and the smooth surface the facets
//! stand for may face anywhere within it. A ring in a round hole meshed in
//! facets of unequal length has normals a few 1e-4 off the radius, so the
//! rows stop the ring's rotation, weakly, where nothing does. Such a tie
//! ([`TieKind::Normal`]) comes with its slack ([`TieKind::Slack`]) across
//! the directions the pair leaves free, `-theta^2 r_t r_t^T`: a motion
//! that moves the pairs along their normals by less than their facets'
//! spread lets it move across them is free.

use std::ops::Deref;

use nalgebra::DMatrix;

use super::frame::Frame;
use crate::fem::rigid::{n_modes, RigidModes, RigidMotion};
use crate::fem::vec3::{dot, norm};
use crate::model::topology::UnionFind;
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

impl PartModes {
    /// The modes `modes` held along each (point, direction) of `supports`.
    pub fn supported(modes: RigidModes, supports: impl IntoIterator<Item = ([f64; 3], [f64; 3])>) -> PartModes {
        let gram = modes.gram(supports);
        PartModes { modes, gram }
    }
}

/// One row between two parts: the pair's position and a direction.
pub struct Tie {
    pub parts: [usize; 2],
    pub x: [f64; 3],
    pub dir: [f64; 3],
    pub kind: TieKind,
}

/// What a [`Tie`]'s row says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TieKind {
    /// The parts move alike along `dir`.
    Exact,
    /// Along `dir`, a pair's normal known only to within its facets'
    /// spread: holds with its slack beside it, never alone.
    Normal,
    /// The slack of a pair's [`TieKind::Normal`] towards `dir`, a
    /// direction the pair does not tie, by the angle (radians) its
    /// facets' normals spread over: the row counts `-angle^2` times.
    Slack(f64),
}

impl Tie {
    /// A tie that holds exactly along `dir`.
    pub fn exact(parts: [usize; 2], x: [f64; 3], dir: [f64; 3]) -> Tie {
        Tie { parts, x, dir, kind: TieKind::Exact }
    }

    /// The weight of its row in `C^T C`.
    fn weight(&self) -> f64 {
        match self.kind {
            TieKind::Exact | TieKind::Normal => 1.0,
            TieKind::Slack(angle) => -angle * angle,
        }
    }
}

/// The parts some rigid motion left free moves, and those motions.
/// Dereferences to the parts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Free {
    /// The parts, ascending.
    pub parts: Vec<usize>,
    /// Each free part's motions, in the order of `parts`: one where a
    /// single motion is left (a ring turning in its hole), else a basis of
    /// those left, each along as few of the part's modes as it can be.
    pub motions: Vec<(usize, RigidMotion)>,
}

impl Deref for Free {
    type Target = [usize];
    fn deref(&self) -> &[usize] {
        &self.parts
    }
}

/// The ties of a pair at `x` between `parts` along `dirs` (unit; the
/// pair's normal `frame[0]` first, when it holds along it), `frame` its
/// local axes (the first `nd` used) and `spread` its facets' spread
/// ([`crate::model::Model::normal_spreads`]): exact, unless the pair holds
/// along its normal alone in some tangential direction and its facets'
/// normals spread; then its normal comes with its slack across each
/// direction it leaves free (module header). The one rule for the
/// solver's check of free parts and for the mechanism of a failure.
pub fn pair_ties(parts: [usize; 2], x: [f64; 3], frame: &Frame, nd: usize, dirs: &[[f64; 3]], spread: f64) -> Vec<Tie> {
    let across = match dirs.split_first() {
        Some((&n, held)) if spread > 0.0 && n == frame[0] => loose(&frame[1..nd], held),
        _ => Vec::new(),
    };
    if across.is_empty() {
        return dirs.iter().map(|&dir| Tie::exact(parts, x, dir)).collect();
    }
    let normal = Tie { parts, x, dir: frame[0], kind: TieKind::Normal };
    let held = dirs[1..].iter().map(|&dir| Tie::exact(parts, x, dir));
    let slack = across.into_iter().map(|dir| Tie { parts, x, dir, kind: TieKind::Slack(spread) });
    std::iter::once(normal).chain(held).chain(slack).collect()
}

/// The unit directions in the span of `tangents` (orthonormal) that no
/// direction of `held` (unit, within that span) holds: an orthonormal
/// basis of what is left.
fn loose(tangents: &[[f64; 3]], held: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut basis: Vec<[f64; 3]> = Vec::new();
    let mut left = Vec::new();
    for (i, &d) in held.iter().chain(tangents).enumerate() {
        let mut v = d;
        for b in &basis {
            let c = dot(v, *b);
            v = std::array::from_fn(|i| v[i] - c * b[i]);
        }
        let len = norm(v);
        if len > 1e-6 {
            let v = v.map(|x| x / len);
            basis.push(v);
            if i >= held.len() {
                left.push(v);
            }
        }
    }
    left
}

/// The parts that some rigid motion left free by supports and `ties`
/// moves, with the motions; empty when every part is held.
///
/// A part whose own supports, and exact ties to parts already found held,
/// stop its rigid motions is held: found so part by part from the
/// supported ones outward (a few 6 x 6 eigenproblems per part, so that a
/// rock mass of a thousand blocks costs milliseconds). Parts held only
/// together (two blocks that each need the other), or only by normals with
/// slack, are left to the eigenproblem of `C^T C` over what remains, one
/// group of parts joined by ties at a time, with ties to held parts acting
/// as supports.
pub fn free_parts(parts: &[PartModes], ties: impl Iterator<Item = Tie>) -> Free {
    let np = parts.len();
    let Some(first) = parts.first() else { return Free::default() };
    let nm = n_modes(first.modes.analysis());
    let ties: Vec<Tie> = ties.filter(|t| t.parts[0] != t.parts[1]).collect();
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); np];
    for (i, t) in ties.iter().enumerate().filter(|(_, t)| t.kind == TieKind::Exact) {
        at[t.parts[0]].push(i);
        at[t.parts[1]].push(i);
    }
    // each part's supports, then its exact ties to held parts as it learns of them
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
            add_outer(&mut gram[q], &parts[q].modes.along(t.x, t.dir)[..nm], 1.0);
            if full_rank(&gram[q]) {
                held[q] = true;
                found.push(q);
            }
        }
    }
    let mut free = Free::default();
    for group in groups(&held, &ties) {
        let group_free = free_in(parts, &gram, &ties, &held, &group, nm);
        free.parts.extend(group_free.parts);
        free.motions.extend(group_free.motions);
    }
    free.parts.sort_unstable();
    free.motions.sort_by_key(|m| m.0);
    free
}

/// The parts `free` (of `np`), in groups joined by `ties` between them.
pub fn free_groups(np: usize, free: &[usize], ties: &[Tie]) -> Vec<Vec<usize>> {
    let mut held = vec![true; np];
    free.iter().filter(|&&p| p < np).for_each(|&p| held[p] = false);
    groups(&held, ties)
}

/// The parts not held, in groups joined by ties between them.
fn groups(held: &[bool], ties: &[Tie]) -> Vec<Vec<usize>> {
    let mut sets = UnionFind::new(held.len());
    for t in ties.iter().filter(|t| !held[t.parts[0]] && !held[t.parts[1]]) {
        sets.join(t.parts[0], t.parts[1]);
    }
    // a held part is joined to none: alone in its set
    sets.groups().into_iter().filter(|g| !held[g[0]]).collect()
}

/// The parts of `group` that a rigid motion moves, and their motions: the
/// null space (and the negative side, which the slack of normals makes) of
/// `C^T C` over the group, each part's supports and exact ties to held
/// parts already in `gram`.
fn free_in(
    parts: &[PartModes],
    gram: &[DMatrix<f64>],
    ties: &[Tie],
    held: &[bool],
    group: &[usize],
    nm: usize,
) -> Free {
    // the free motions, and each part's share of them
    let mut shares: Vec<Vec<Vec<f64>>> = vec![Vec::new(); group.len()];
    for v in null_space(group_matrix(parts, gram, ties, held, group, nm)) {
        for (i, share) in shares.iter_mut().enumerate() {
            let part: Vec<f64> = (0..nm).map(|a| v[i * nm + a]).collect();
            if part.iter().map(|x| x * x).sum::<f64>().sqrt() > 1e-6 {
                share.push(part);
            }
        }
    }
    let mut free = Free::default();
    for (&p, share) in group.iter().zip(shares).filter(|(_, s)| !s.is_empty()) {
        free.parts.push(p);
        free.motions.extend(echelon(share, nm).iter().map(|a| (p, parts[p].modes.motion(a))));
    }
    free
}

/// `C^T C` over the parts of `group` (`nm` modes each, in the group's
/// order): each part's `gram`, the ties between two parts of the group,
/// and the ties with slack to a part `held` (exact ones are in `gram`).
/// Ties to parts neither in the group nor in `held` are left out.
fn group_matrix(
    parts: &[PartModes],
    gram: &[DMatrix<f64>],
    ties: &[Tie],
    held: &[bool],
    group: &[usize],
    nm: usize,
) -> DMatrix<f64> {
    let mut index = std::collections::HashMap::new();
    for (i, &p) in group.iter().enumerate() {
        index.insert(p, i);
    }
    let mut m = DMatrix::<f64>::zeros(nm * group.len(), nm * group.len());
    for (i, &p) in group.iter().enumerate() {
        m.view_mut((i * nm, i * nm), (nm, nm)).copy_from(&gram[p]);
    }
    let is_held = |p: usize| held.get(p).copied().unwrap_or(false);
    for t in ties {
        let w = t.weight();
        let along = |s: usize| parts[t.parts[s]].modes.along(t.x, t.dir);
        let row: Vec<(usize, f64)> = match (index.get(&t.parts[0]), index.get(&t.parts[1])) {
            (Some(&i), Some(&j)) => {
                let (rp, rq) = (along(0), along(1));
                (0..nm).map(|a| (i * nm + a, rp[a])).chain((0..nm).map(|a| (j * nm + a, -rq[a]))).collect()
            }
            // a held part's side acts as a support (exact ties are in `gram`)
            (Some(&i), None) if is_held(t.parts[1]) && t.kind != TieKind::Exact => {
                let rp = along(0);
                (0..nm).map(|a| (i * nm + a, rp[a])).collect()
            }
            (None, Some(&j)) if is_held(t.parts[0]) && t.kind != TieKind::Exact => {
                let rq = along(1);
                (0..nm).map(|a| (j * nm + a, rq[a])).collect()
            }
            _ => continue,
        };
        for &(r, a) in &row {
            for &(c, b) in &row {
                m[(r, c)] += w * a * b;
            }
        }
    }
    m
}

/// The unit vectors of a symmetric matrix's null space and negative side
/// (eigenvalues below 1e-12 of the largest in magnitude).
/// Empty where `m` does not decompose ([`crate::fem::bounded`]): no
/// motion found.
fn null_space(m: DMatrix<f64>) -> Vec<nalgebra::DVector<f64>> {
    let Some(eig) = crate::fem::bounded::symmetric_eigen(m) else { return Vec::new() };
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    (eig.eigenvalues.iter().enumerate())
        .filter(|(_, &lambda)| !(lambda > 1e-12 * big && big > 0.0))
        .map(|(k, _)| eig.eigenvectors.column(k).into_owned())
        .collect()
}

/// A basis of the span of `rows` (vectors of length `nm`), each along as
/// few of the leading modes as it can be (reduced row echelon form).
fn echelon(rows: Vec<Vec<f64>>, nm: usize) -> Vec<Vec<f64>> {
    let mut rows = rows;
    let scale = rows.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for col in 0..nm {
        let Some(best) = (0..rows.len()).max_by(|&a, &b| rows[a][col].abs().total_cmp(&rows[b][col].abs())) else {
            break;
        };
        if rows[best][col].abs() <= 1e-6 * scale {
            continue;
        }
        let pivot = rows.swap_remove(best);
        let pivot: Vec<f64> = pivot.iter().map(|x| x / pivot[col]).collect();
        for r in rows.iter_mut().chain(basis.iter_mut()) {
            let f = r[col];
            r.iter_mut().zip(&pivot).for_each(|(x, y)| *x -= f * y);
        }
        basis.push(pivot);
    }
    basis
}

/// The rigid motion of the parts of `group` that their supports and
/// `ties` leave free, driven by `load` (for each part of the group, the
/// work its loads do in each of its modes, [`PartModes`]' scaled modes):
/// the loads projected onto the free motions, or the first free motion
/// where they do no work on any (its sign arbitrary). Parts outside the
/// group are held: a tie to one acts as a support. Each part's mode
/// amplitudes in the group's order (scaled by the largest); None when
/// nothing in the group is free.
pub fn free_motion(parts: &[PartModes], ties: &[Tie], group: &[usize], load: &[[f64; 6]]) -> Option<Vec<[f64; 6]>> {
    let nm = n_modes(parts.first()?.modes.analysis());
    let inside = |p: usize| group.contains(&p);
    let mut gram: Vec<DMatrix<f64>> = parts.iter().map(|p| p.gram.clone()).collect();
    for t in ties.iter().filter(|t| inside(t.parts[0]) != inside(t.parts[1])) {
        let p = if inside(t.parts[0]) { t.parts[0] } else { t.parts[1] };
        add_outer(&mut gram[p], &parts[p].modes.along(t.x, t.dir)[..nm], t.weight());
    }
    let null = null_space(group_matrix(parts, &gram, ties, &[], group, nm));
    let first = null.first()?;
    let g = nalgebra::DVector::from_iterator(nm * group.len(), load.iter().flat_map(|l| l[..nm].to_vec()));
    let mut v = nalgebra::DVector::<f64>::zeros(nm * group.len());
    for n in &null {
        v += n * n.dot(&g);
    }
    if v.norm() <= 1e-9 * g.norm() || g.norm() == 0.0 {
        v = first.clone();
    }
    let big = v.amax();
    Some((0..group.len()).map(|i| std::array::from_fn(|a| if a < nm { v[i * nm + a] / big } else { 0.0 })).collect())
}

/// Whether a part's Gram matrix stops all its rigid motions (not where it
/// does not decompose).
fn full_rank(g: &DMatrix<f64>) -> bool {
    let Some(eig) = crate::fem::bounded::symmetric_eigen(g.clone()) else { return false };
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    big > 0.0 && eig.eigenvalues.iter().all(|&l| l > 1e-12 * big)
}

/// `g += w r r^T`.
fn add_outer(g: &mut DMatrix<f64>, r: &[f64], w: f64) {
    for (i, a) in r.iter().enumerate() {
        for (j, b) in r.iter().enumerate() {
            g[(i, j)] += w * a * b;
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
        assert_eq!(free_parts(&[part(Analysis::Axisymmetric, center, &[])], std::iter::empty()).parts, vec![0]);
        let held = part(Analysis::Axisymmetric, center, &[([4.0, 0.0, 0.0], 1)]);
        assert_eq!(free_parts(&[held], std::iter::empty()).parts, Vec::<usize>::new());
        let radial = part(Analysis::Axisymmetric, center, &[([4.0, 0.0, 0.0], 0)]);
        assert_eq!(free_parts(&[radial], std::iter::empty()).parts, vec![0], "a radial support holds nothing rigid");
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
        let pin =
            |p: usize, q: usize, x: [f64; 3]| [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].map(|dir| Tie::exact([p, q], x, dir));
        let arch = |crown: [f64; 3]| {
            let parts = [ground(), plane([1.0, 1.0, 0.0]), plane([3.0, 1.0, 0.0])];
            let ties = [pin(0, 1, [0.0, 0.0, 0.0]), pin(0, 2, [4.0, 0.0, 0.0]), pin(1, 2, crown)];
            free_parts(&parts, ties.into_iter().flatten()).parts
        };
        assert_eq!(arch([2.0, 2.0, 0.0]), Vec::<usize>::new(), "a three-hinged arch stands");
        assert_eq!(arch([2.0, 0.0, 0.0]), vec![1, 2], "hinges on one line: a mechanism");
        // one half alone on its pin turns
        let parts = [ground(), plane([1.0, 1.0, 0.0])];
        assert_eq!(free_parts(&parts, pin(0, 1, [0.0, 0.0, 0.0]).into_iter()).parts, vec![1]);
    }

    /// A ring (part 1, centred at the origin) in a hole of held ground
    /// (part 0), tied along its normals at `n` points of the unit circle,
    /// each normal turned off the radius by `tilt(theta)`, with `spread` the
    /// angle its facets spread over (0: exact ties).
    fn ring(n: usize, tilt: impl Fn(f64) -> f64, spread: f64) -> Free {
        let ground = part(
            Analysis::PlaneStrain,
            [0.0, 0.0, 0.0],
            &[([2.0, 0.0, 0.0], 0), ([2.0, 0.0, 0.0], 1), ([-2.0, 0.0, 0.0], 1)],
        );
        let ring = part(Analysis::PlaneStrain, [0.0, 0.0, 0.0], &[]);
        let mut ties = Vec::new();
        for i in 0..n {
            let theta = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            let x = [theta.cos(), theta.sin(), 0.0];
            let a = theta + tilt(theta);
            let (normal, across) = ([a.cos(), a.sin(), 0.0], [-a.sin(), a.cos(), 0.0]);
            if spread == 0.0 {
                ties.push(Tie::exact([1, 0], x, normal));
            } else {
                ties.push(Tie { parts: [1, 0], x, dir: normal, kind: TieKind::Normal });
                ties.push(Tie { parts: [1, 0], x, dir: across, kind: TieKind::Slack(spread) });
            }
        }
        free_parts(&[ground, ring], ties.into_iter())
    }

    #[test]
    fn a_ring_turns_in_its_hole_whatever_its_facets_make_of_the_normals() {
        // normals a few 1e-4 off the radius (facets of unequal length):
        // exact rows hold the ring, weakly; with their facets' spread
        // (15 degrees a facet) they do not, and the motion is the rotation
        let off = |t: f64| 7e-4 * (3.0 * t).sin() + 2e-4 * (5.0 * t).cos();
        assert_eq!(ring(24, off, 0.0).parts, Vec::<usize>::new(), "exact rows hold it");
        let free = ring(24, off, 15f64.to_radians());
        assert_eq!(free.parts, vec![1]);
        let [(1, RigidMotion::Turn { point })] = free.motions[..] else { panic!("{:?}", free.motions) };
        assert!(point[0].hypot(point[1]) < 1e-3, "about the centre: {point:?}");
        // exactly radial normals: free either way
        assert_eq!(ring(24, |_| 0.0, 0.0).motions.len(), 1);
        // an oval (normals 0.1 rad off the radius, facets 1 degree apart)
        // is held by its shape
        assert_eq!(ring(360, |t| 0.1 * (2.0 * t).sin(), 1f64.to_radians()).parts, Vec::<usize>::new());
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
                    v.push(Tie::exact([0, 1], [x, 1.0, 0.0], dir));
                }
            }
            v
        };
        let (n, t) = ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        let parts = [bottom, top];
        assert_eq!(free_parts(&parts, joint(&[n, t]).into_iter()).parts, Vec::<usize>::new(), "stuck");
        assert_eq!(free_parts(&parts, joint(&[n]).into_iter()).parts, vec![1], "slipping: slides along x");
        assert_eq!(free_parts(&parts, joint(&[]).into_iter()).parts, vec![1], "open: held by nothing");
        // a single tied pair stops translations, not the rotation about it
        let one = vec![Tie::exact([0, 1], [1.0, 1.0, 0.0], n), Tie::exact([0, 1], [1.0, 1.0, 0.0], t)];
        assert_eq!(free_parts(&parts, one.into_iter()).parts, vec![1]);
        // the motions: the slipping top slides along x
        let free = free_parts(&parts, joint(&[n]).into_iter());
        assert_eq!(free.motions, vec![(1, RigidMotion::Translation { dir: [1.0, 0.0, 0.0], solid: false })]);
        // without the x support the bottom slides too, and the stuck top with it
        let loose = plane([1.0, 0.5, 0.0], &[([0.0, 0.0, 0.0], 1), ([2.0, 0.0, 0.0], 1)]);
        let top = plane([1.0, 1.5, 0.0], &[]);
        assert_eq!(free_parts(&[loose, top], joint(&[n, t]).into_iter()).parts, vec![0, 1]);
    }
}
