//! Junctions: node copies in more than one pair.
//!
//! Where joints cross, every block keeps its own copy of the node and the
//! pairs follow the faces (four pairs at a crossing in 2D, twelve at a point
//! where eight blocks meet in 3D; two between the same copies on a crease).
//! The stuck pairs around a junction then form closed loops, and their ties
//! are redundant: four stuck pairs around a crossing tie four copies with
//! eight equations of which six are independent. The mean / relative
//! coordinates of a lone pair ([`super::coords`]) cannot express that, so a
//! junction (every pair of a cluster of copies joined by pairs, when the
//! cluster is more than one pair) is written in global axes:
//!
//! ```text
//! d_0 = m,  d_j = m + r_j   (j = 1..q-1, per component; r_j = d_j - d_0)
//! ```
//!
//! or, on a component some copy is held in, `d_h = v_h` for the held ones
//! and `d_j = v + r_j` for the others (v the first held value). The means m
//! are free under every state, as a lone pair's are; each pair's relative
//! displacement in its own axes is a row of the junction's r:
//!
//! ```text
//! rel_p = T_p (d_l - d_k) = C_p r + c_p ramp
//! ```
//!
//! A set of states ties some rows: `C_T r = t`. Redundant rows (the loops)
//! make C_T rank-deficient; the displacements are still unique, so r is
//! written on the null space of C_T, `r = r_0 + Z y` (C_T's singular value
//! decomposition: r_0 its least-squares solution, Z the right singular
//! vectors of its zero singular values), and only y enters the system.
//!
//! The tied forces are not unique: a self-equilibrated loop of forces can
//! be added. The interface takes the one of least `sum λ_i^2 / A_i` (A_i the
//! area of the row's pair), the limit of equally stiff joint springs per
//! unit area as their stiffness grows: what 3DEC's sub-contacts and DDA's
//! penalty springs would give with stiff joints, without their compliance,
//! and what no ordering of blocks or groups can change. Mortar methods meet
//! the same redundancy at crosspoints and remove the crosspoint's
//! multipliers (Wohlmuth 2001), which ties the crosspoint to its master
//! side; here every block keeps its copy, and a crossing can open or slip.
//! Under a uniform stress with equal areas around a crossing the
//! least-norm forces are the exact tractions `σ n A` of each face.
//!
//! Stiff joints carry the in-situ stress from the start, before anything
//! moves, and share only what comes after it; so does a junction: its
//! loops keep their part of the pairs' in-situ forces (`Relation::prior`,
//! `N Nᵀ D⁻¹ λ0` in [`split`]) and share the rest least-norm. Where a joint
//! meets a roller that holds its nodes, the support and the joint's ties
//! are such a loop: shared from nothing, the joint gave most of its
//! in-situ force to the support (tests/initial.rs: 0.137 of 0.146 MPa at a
//! geostatic box's roller; 0.18 of 1.64 MPa at the 34k tunnel's base,
//! docs/convergence.md), where the stiff joints' limit keeps it.
//!
//! A slipping pair's friction force along its free axes is its relation's
//! `force + coupling p + spring rel` as elsewhere; its pressure p, one of
//! the tied forces, is solved for with r, or taken from the last solve
//! where that cannot be done safely ([`pressure`]).

use nalgebra::{DMatrix, DVector};

use super::coords::{Terms, Var};
use super::relation::{Limit, Relation};
use crate::contact::frame::Frame;
use crate::contact::law::ContactState;
use crate::fem::vec3::{dot, norm, sub};
use crate::model::topology::UnionFind;

/// How far beyond a limit (of the largest force) the least-norm share of
/// a loop may be for [`Junction::share_with_friction`] to look for one
/// within it: a pair at its limit, as blocks3d_confined's pair 335 (5e-4
/// beyond). Taking every share beyond its limits so set blocks3d_linear's
/// step 2 cycling (not converged in 332 iterations and 3 cuts, where it
/// converges in 29) and tunnel4sets' one step took 31 iterations for 30.
const NEAR_LIMIT: f64 = 1e-2;

/// The pairs that are solved as junctions: every pair of a cluster (copies
/// joined through pairs) of more than one pair, and the pairs `general`
/// asks for (a pair whose supports do not lie along its frame). Returns
/// the clusters, pairs ascending, in order of their first pair.
pub fn clusters(pairs: &[(usize, usize)], n_nodes: usize, general: impl Fn(usize) -> bool) -> Vec<Vec<usize>> {
    let mut sets = UnionFind::new(n_nodes);
    pairs.iter().for_each(|&(k, l)| sets.join(k, l));
    let mut of_root: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    let mut all: Vec<Vec<usize>> = Vec::new();
    for (p, &(k, _)) in pairs.iter().enumerate() {
        let r = sets.root(k);
        let at = *of_root.entry(r).or_insert_with(|| {
            all.push(Vec::new());
            all.len() - 1
        });
        all[at].push(p);
    }
    all.into_iter().filter(|c| c.len() > 1 || general(c[0])).collect()
}

/// One junction: its pairs and copies, how each copy is written in the
/// unknowns, and each pair's rows.
#[derive(Clone, Debug)]
pub struct Junction {
    /// Its pairs (model pair indices), ascending.
    pub pairs: Vec<usize>,
    /// Its copies (model nodes), ascending.
    pub copies: Vec<usize>,
    /// The unknowns of each copy's components (global axes).
    pub terms: Vec<[Terms; 3]>,
    /// Its relative displacements: global indices into r.
    pub r: Vec<usize>,
    /// Its means: global indices into m.
    pub m: Vec<usize>,
    /// Per pair and local axis, the row of C over `r` and the constant per unit ramp.
    pub rows: Vec<[Vec<f64>; 3]>,
    pub consts: Vec<[f64; 3]>,
    /// Each pair's frame, and its partners: the other pairs between the
    /// same two copies (the faces of a crease or a corner).
    frames: Vec<Frame>,
    partners: Vec<Vec<usize>>,
    /// Where two joints cross (four pairs, two on each joint's plane),
    /// each pair's twin: the other pair on its plane. Empty elsewhere.
    twins: Vec<usize>,
    nd: usize,
    /// What the last set of tied rows gave (see [`Memo`]).
    memo: Memo,
    /// How far the last solve's locked pressures were from a fixed point.
    off: Off,
}

/// A closed partner's normal crosses a pair's shear plane (a crease)
/// where its part in that plane is more than this; faces of one contact
/// meet at a crease at 40 degrees or more (`CREASE_ANGLE`), where it is
/// sin 40 = 0.64.
const CROSSES: f64 = 1e-3;

/// Two pairs' normals are parallel (one plane) where their dot product is
/// within this of one: the facets of a planar joint agree to round-off.
const PARALLEL: f64 = 1e-6;

/// A junction under one set of relations.
#[derive(Clone, Debug)]
pub struct Tied {
    /// An orthonormal basis of the free directions of r (columns over the
    /// junction's r): `r = r0 + Z y`.
    pub z: DMatrix<f64>,
    /// r at y = 0: the tied rows' least-squares (least-norm) solution.
    pub r0: DVector<f64>,
    /// What the slipping pairs add over the junction's r: the springs'
    /// stiffness, and their force at r = 0 (`W r - c + k r + f = -C_T^T λ_T`).
    pub k: DMatrix<f64>,
    pub f: DVector<f64>,
    /// The tied rows, and the map from the force they must carry (over r)
    /// to their least-norm forces.
    rows: Vec<Row>,
    split: Split,
    /// The area of each of the junction's pairs.
    areas: Vec<f64>,
    /// What the tied rows carry in situ (`Relation::prior`): the loops
    /// keep their part of it.
    prior: DVector<f64>,
    /// The slipping pairs' pressures, solved for with r (see [`pressure`]);
    /// None where they are the last solve's (`Relation::pressure`, in `f`).
    pub pressure: Option<Pressure>,
}

/// A junction pair's contact force on body I and relative displacement
/// (local axes), and its force as if tied where it is locked.
type PairForces = ([f64; 3], [f64; 3], Option<[f64; 3]>);

/// How a junction's copies are numbered: each copy's displacement in
/// terms of means and relative displacements, the r index of each (copy,
/// component) (None where the copy is held or is the reference), and the
/// model's numbers of its r and m.
struct Numbering {
    terms: Vec<[Terms; 3]>,
    r_of: Vec<[Option<usize>; 3]>,
    r: Vec<usize>,
    m: Vec<usize>,
}

impl Numbering {
    /// Component by component: held copies take their prescribed value,
    /// the others the held value (or a new mean, numbered from `nm`) plus
    /// a new relative displacement (numbered from `nr`), but for the first
    /// copy of a component held nowhere, which is the mean alone.
    fn new(copies: &[usize], prescribed: &[Option<f64>], nd: usize, nm: &mut usize, nr: &mut usize) -> Numbering {
        let q = copies.len();
        let none = || Terms { vars: [(Var::M(0), 0.0); 2], n: 0, constant: 0.0 };
        let mut terms: Vec<[Terms; 3]> = (0..q).map(|_| [none(), none(), none()]).collect();
        let mut r_of = vec![[None; 3]; q];
        let (mut r, mut m) = (Vec::new(), Vec::new());
        for c in 0..nd {
            let held: Vec<Option<f64>> = copies.iter().map(|&n| prescribed[n * nd + c]).collect();
            let reference = held.iter().flatten().next().copied();
            for (j, h) in held.iter().enumerate() {
                let t = &mut terms[j][c];
                match (reference, h) {
                    (_, Some(v)) => t.constant = *v,
                    (None, None) if j == 0 => {
                        t.vars[0] = (Var::M(*nm), 1.0);
                        t.n = 1;
                        m.push(*nm);
                    }
                    (reference, None) => {
                        let mut n = 0;
                        if reference.is_none() {
                            t.vars[0] = (Var::M(*nm), 1.0);
                            n = 1;
                        }
                        t.vars[n] = (Var::R(*nr), 1.0);
                        t.n = n + 1;
                        t.constant = reference.unwrap_or(0.0);
                        r_of[j][c] = Some(r.len());
                        r.push(*nr);
                        *nr += 1;
                    }
                }
            }
            if reference.is_none() {
                *nm += 1;
            }
        }
        Numbering { terms, r_of, r, m }
    }
}

/// Each pair's relative displacement d_l - d_k along its local axes as
/// rows over the junction's `n_r` relative displacements, plus the
/// constants of the held copies.
fn pair_rows(
    pairs: &[usize],
    pair: &impl Fn(usize) -> (usize, usize, Frame),
    copies: &[usize],
    terms: &[[Terms; 3]],
    r_of: &[[Option<usize>; 3]],
    n_r: usize,
    nd: usize,
) -> (Vec<[Vec<f64>; 3]>, Vec<[f64; 3]>) {
    let mut rows = Vec::with_capacity(pairs.len());
    let mut consts = Vec::with_capacity(pairs.len());
    for &p in pairs {
        let (k, l, f) = pair(p);
        let (jk, jl) = (copies.binary_search(&k).expect("a copy"), copies.binary_search(&l).expect("a copy"));
        let mut row: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n_r]);
        let mut cst = [0.0; 3];
        for (a, row_a) in row.iter_mut().enumerate().take(nd) {
            for c in 0..nd {
                let w = f[a][c];
                if w == 0.0 {
                    continue;
                }
                // d_l - d_k along global c
                if let Some(i) = r_of[jl][c] {
                    row_a[i] += w;
                }
                if let Some(i) = r_of[jk][c] {
                    row_a[i] -= w;
                }
                cst[a] += w * (terms[jl][c].constant - terms[jk][c].constant);
            }
        }
        rows.push(row);
        consts.push(cst);
    }
    (rows, consts)
}

/// The part of v along the unit direction dir, over the first nd axes.
fn along(nd: usize, v: [f64; 3], dir: [f64; 3]) -> f64 {
    (0..nd).map(|a| v[a] * dir[a]).sum()
}

/// Where a junction is a crossing of two joints, each pair's twin: four
/// pairs, each with exactly one other of parallel normal (on one plane,
/// the two sides of the other joint). Empty where it is not one.
fn crossing_twins(frames: &[Frame]) -> Vec<usize> {
    let on_plane = |i: usize, k: usize| k != i && dot(frames[i][0], frames[k][0]).abs() > 1.0 - PARALLEL;
    let twins: Vec<Vec<usize>> =
        (0..frames.len()).map(|i| (0..frames.len()).filter(|&k| on_plane(i, k)).collect()).collect();
    if frames.len() == 4 && twins.iter().all(|t| t.len() == 1) {
        twins.iter().map(|t| t[0]).collect()
    } else {
        Vec::new()
    }
}

impl Junction {
    /// The junction of `pairs` (their (k, l) and frames given by `pair`),
    /// with the prescribed value per unit ramp of each model DOF
    /// (`prescribed[node * nd + c]`); numbers its means and relative
    /// displacements from `nm` and `nr` on.
    pub fn new(
        pairs: Vec<usize>,
        pair: impl Fn(usize) -> (usize, usize, Frame),
        prescribed: &[Option<f64>],
        nd: usize,
        nm: &mut usize,
        nr: &mut usize,
    ) -> Junction {
        let mut copies: Vec<usize> = pairs
            .iter()
            .flat_map(|&p| {
                let (k, l, _) = pair(p);
                [k, l]
            })
            .collect();
        copies.sort_unstable();
        copies.dedup();
        let Numbering { terms, r_of, r, m } = Numbering::new(&copies, prescribed, nd, nm, nr);
        let (rows, consts) = pair_rows(&pairs, &pair, &copies, &terms, &r_of, r.len(), nd);
        let frames: Vec<Frame> = pairs.iter().map(|&p| pair(p).2).collect();
        let ends: Vec<(usize, usize)> = pairs.iter().map(|&p| pair(p)).map(|(k, l, _)| (k.min(l), k.max(l))).collect();
        let partners =
            (0..pairs.len()).map(|j| (0..pairs.len()).filter(|&i| i != j && ends[i] == ends[j]).collect()).collect();
        let twins = crossing_twins(&frames);
        Junction {
            pairs,
            copies,
            terms,
            r,
            m,
            rows,
            consts,
            frames,
            partners,
            twins,
            nd,
            memo: Memo::default(),
            off: Off::default(),
        }
    }

    /// A new load: the junction solves for its slipping pairs' pressures
    /// again, until its loops carry part of one (see [`pressure`]).
    pub fn new_load(&self) {
        self.memo.reset_looped();
    }

    /// How far the pressures its last solve wrote for the locked slipping
    /// pairs are from those its forces carry (force units; 0 where they
    /// reached a fixed point or there were none): the rounds' end taken
    /// where they have none ([`fixed_point::settle`]).
    pub fn locked_off(&self) -> f64 {
        self.off.get()
    }

    /// The tied rows under `state` (of every model pair): a stuck pair's
    /// normal and [`Self::shear_dirs`], a slipping pair's normal.
    fn tied_rows(&self, state: impl Fn(usize) -> ContactState) -> Vec<Row> {
        let mut rows = Vec::new();
        for (j, &p) in self.pairs.iter().enumerate() {
            match state(p) {
                ContactState::Stick => {
                    rows.push((j, NORMAL));
                    rows.extend(self.shear_dirs(j, |q| state(q) != ContactState::Open).into_iter().map(|dir| (j, dir)));
                }
                ContactState::Slip => rows.push((j, NORMAL)),
                ContactState::Open => {}
            }
        }
        rows
    }

    /// The directions (local axes) pair j's shear is tied along when it
    /// sticks, `closed` telling which pairs are closed: its t and b axes,
    /// but on a crease (a closed partner) the crease's line alone, and in a
    /// corner (two closed partners across each other) none. The force
    /// across a crease goes through the faces' normals, stuck or slipping
    /// alike: a slipping face carries its friction along the crease (see
    /// [`Self::slip_lines`]), and a stuck one that shared the force across
    /// with its partner's normal would take that partner's pressure, and
    /// friction, away.
    fn shear_dirs(&self, j: usize, closed: impl Fn(usize) -> bool) -> Vec<[f64; 3]> {
        let f = &self.frames[j];
        let axes: Vec<[f64; 3]> = (1..self.nd).map(|a| std::array::from_fn(|c| f64::from(u8::from(c == a)))).collect();
        // the closed partners' normals seen in this pair's shear plane
        let across: Vec<[f64; 3]> = self.partners[j]
            .iter()
            .filter(|&&i| closed(self.pairs[i]))
            .map(|&i| std::array::from_fn(|a| if a == 0 || a >= self.nd { 0.0 } else { dot(self.frames[i][0], f[a]) }))
            .filter(|v: &[f64; 3]| norm(*v) > CROSSES)
            .collect();
        let Some(v) = across.first() else { return axes };
        if self.nd == 2 {
            return Vec::new();
        }
        let l = norm(*v);
        let line = [0.0, -v[2] / l, v[1] / l];
        if across.iter().any(|w| dot(*w, line).abs() > CROSSES) {
            Vec::new()
        } else {
            vec![line]
        }
    }

    /// The row of C over r along `dir` (local axes), and its constant.
    fn c_row(&self, (j, dir): Row) -> (Vec<f64>, f64) {
        let mut row = vec![0.0; self.r.len()];
        let mut cst = 0.0;
        for a in (0..self.nd).filter(|&a| dir[a] != 0.0) {
            for (x, y) in row.iter_mut().zip(&self.rows[j][a]) {
                *x += dir[a] * y;
            }
            cst += dir[a] * self.consts[j][a];
        }
        (row, cst)
    }

    /// The free directions Z of r when the rows `c_rows` are tied, and the
    /// map P from their targets `t` (padded to at least as many entries as
    /// r) to the tied rows' least-squares (least-norm) solution `r0 = P t`:
    /// `r = r0 + Z y`.
    fn null_space(&self, c_rows: &[Vec<f64>]) -> (DMatrix<f64>, DMatrix<f64>) {
        let (m_t, n_r) = (c_rows.len(), self.r.len());
        let c_t = DMatrix::<f64>::from_fn(m_t.max(n_r), n_r, |i, c| if i < m_t { c_rows[i][c] } else { 0.0 });
        // C_T = U S V^T: the null space is V's columns of zero singular
        // values; rows that do not decompose (not finite) tie nothing
        let Some(svd) = crate::fem::bounded::svd(c_t, true, true) else {
            return (DMatrix::identity(n_r, n_r), DMatrix::zeros(n_r, m_t.max(n_r)));
        };
        let (u, v_t) = (svd.u.expect("U"), svd.v_t.expect("V^T"));
        let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
        let rank_of = |s: f64| s > RANK_TOLERANCE * smax.max(f64::MIN_POSITIVE);
        let mut pinv = DMatrix::<f64>::zeros(n_r, m_t.max(n_r));
        let mut free_cols = Vec::new();
        for (i, &s) in svd.singular_values.iter().enumerate() {
            if rank_of(s) {
                pinv += v_t.row(i).transpose() * u.column(i).transpose() / s;
            } else {
                free_cols.push(i);
            }
        }
        // (a wide C_T: V^T has n_r rows whatever m_t; a row beyond m_t's
        // singular values is a free direction too)
        let z = DMatrix::<f64>::from_fn(n_r, free_cols.len(), |i, c| v_t[(free_cols[c], i)]);
        (z, pinv)
    }

    /// The line each of the junction's pairs can slip along under
    /// `states` (of every model pair): its direction in the pair's local
    /// axes `[0, t, b]` where the junction's ties leave its shear exactly
    /// one free direction, as on a crease whose other face is closed (the
    /// copies then move only along the crease), None where they leave it
    /// two or none (and in 2D).
    pub fn slip_lines(&self, states: &[ContactState]) -> Vec<Option<[f64; 3]>> {
        if self.nd < 3 || self.r.is_empty() {
            return vec![None; self.pairs.len()];
        }
        self.memo.with(self, &self.tied_rows(|p| states[p]), |t| t.rooms(self).iter().map(|r| r.line()).collect())
    }

    /// How far each of the junction's pairs can slip under `states` (of
    /// every model pair).
    pub fn rooms(&self, states: &[ContactState]) -> Vec<Room> {
        if self.r.is_empty() {
            return vec![Room::None; self.pairs.len()];
        }
        self.memo.with(self, &self.tied_rows(|p| states[p]), |t| t.rooms(self).to_vec())
    }

    /// Each pair's twin where the junction is a crossing of two joints
    /// (see [`crossing_twins`]), as junction indices; None elsewhere.
    pub fn twin(&self, j: usize) -> Option<usize> {
        self.twins.get(j).copied()
    }

    /// [`Self::rooms`] where the free directions are `z`.
    fn rooms_along(&self, z: &DMatrix<f64>) -> Vec<Room> {
        (0..self.pairs.len())
            .map(|j| {
                let scale =
                    (1..3).map(|a| self.rows[j][a].iter().map(|x| x * x).sum::<f64>().sqrt()).fold(0.0, f64::max);
                if z.ncols() == 0 || scale == 0.0 {
                    return Room::None;
                }
                // the shear axes' parts along the free directions
                let m = DMatrix::<f64>::from_fn(2, z.ncols(), |a, c| {
                    (0..self.r.len()).map(|i| self.rows[j][a + 1][i] * z[(i, c)]).sum()
                });
                let Some(svd) = crate::fem::bounded::svd(m, true, false) else { return Room::None };
                let sv = &svd.singular_values;
                match sv.iter().filter(|&&s| s > 1e-9 * scale).count() {
                    0 => Room::None,
                    1 if self.nd == 3 => {
                        let (u, k) = (svd.u.expect("U"), sv.imax());
                        Room::Line([0.0, u[(0, k)], u[(1, k)]])
                    }
                    _ => Room::Free,
                }
            })
            .collect()
    }

    /// The junction under the relations `rel` (of every model pair) at
    /// `ramp`, every state held; `area` gives each pair's area. The unit
    /// tests' entry: a solve calls [`Junction::tie_held`].
    #[cfg(test)]
    pub fn tie(&self, rel: &[Relation], ramp: f64, area: impl Fn(usize) -> f64) -> Tied {
        self.tie_held(rel, ramp, true, area)
    }

    /// The junction under the relations `rel` (of every model pair) at
    /// `ramp` (`area` gives each pair's area), `held`: whether every pair
    /// of the interface has the state it had in the last solve. A
    /// least-norm share's tangent is
    /// taken only then: while states change elsewhere, a way of solving for
    /// the pressures that changes with the loops' shares changed the path
    /// of the state search (blocks3d_linear's step 1: 30 iterations instead
    /// of 21, to other states).
    pub fn tie_held(&self, rel: &[Relation], ramp: f64, held: bool, area: impl Fn(usize) -> f64) -> Tied {
        let (nd, n_r) = (self.nd, self.r.len());
        // (a joint that deforms is tied on no axis)
        let rows = self.tied_rows(|p| if rel[p].elastic { ContactState::Open } else { rel[p].state });
        let areas: Vec<f64> = self.pairs.iter().map(|&p| area(p)).collect();
        if n_r == 0 {
            // every copy held in every component: nothing to solve for
            let zero = DMatrix::zeros(0, 0);
            let split = Split::new(&[], &rows, &areas, 0);
            return Tied {
                z: zero.clone(),
                r0: DVector::zeros(0),
                k: zero,
                f: DVector::zeros(0),
                split,
                prior: self.prior_of(&rows, rel),
                rows,
                areas,
                pressure: None,
            };
        }
        let (z, pinv, split, consts) = self
            .memo
            .with(self, &rows, |t| (t.z.clone(), t.pinv.clone(), t.split(&areas, n_r).clone(), t.consts.clone()));
        let t = DVector::<f64>::from_fn(rows.len().max(n_r), |i, _| {
            if i < rows.len() {
                let (j, dir) = rows[i];
                let target: f64 =
                    (0..nd).filter(|&a| dir[a] != 0.0).map(|a| dir[a] * rel[self.pairs[j]].target[a]).sum();
                target - consts[i] * ramp
            } else {
                0.0
            }
        });
        let r0 = pinv * t;
        // slipping pairs: springs and forces along their free axes, and
        // their friction per unit pressure (`pressure`). (A pair that has
        // just closed could take its friction at no pressure this once:
        // `make tunnel-joints` then takes 18 contact iterations instead of
        // 28, but the 1,000-block cube of `make bench-blocks` 11 instead
        // of 9, measured before the loops' note was kept for the load.)
        let mut k = DMatrix::<f64>::zeros(n_r, n_r);
        let mut f = DVector::<f64>::zeros(n_r);
        let slipping: Vec<usize> = (0..self.pairs.len())
            .filter(|&j| rel[self.pairs[j]].state == ContactState::Slip && !rel[self.pairs[j]].elastic)
            .collect();
        let coupled: Vec<usize> =
            slipping.iter().copied().filter(|&j| rel[self.pairs[j]].coupling.iter().any(|&c| c != 0.0)).collect();
        let per_pressure = DMatrix::<f64>::from_fn(n_r, coupled.len(), |i, s| {
            let (j, rl) = (coupled[s], &rel[self.pairs[coupled[s]]]);
            (1..nd).map(|a| self.rows[j][a][i] * rl.coupling[a]).sum()
        });
        // where the loops have carried part of a pressure, through the
        // tangent of the last solve's share if it tied the same rows; else
        // the last solve's pressures (see `pressure`)
        let prior = self.prior_of(&rows, rel);
        let pressure = if !self.memo.looped() {
            Pressure::new(coupled, per_pressure, &split, Some(&Tangent::plain(&split, &prior)))
        } else {
            let tangent = self.memo.tangent(&rows).filter(|t| held || !t.plain);
            tangent.and_then(|t| Pressure::new(coupled, per_pressure, &split, Some(&t)))
        };
        // (a closed joint that deforms has springs on every axis)
        let springy = (0..self.pairs.len()).filter(|&j| {
            let rl = &rel[self.pairs[j]];
            rl.elastic && rl.state != ContactState::Open
        });
        let springs: Vec<usize> = slipping.iter().copied().chain(springy).collect();
        self.add_springs(&springs, rel, pressure.is_some(), ramp, &mut k, &mut f);
        Tied { z, r0, k, f, rows, split, areas, prior, pressure }
    }

    /// Adds the springs and forces of the junction's pairs `springs` (a
    /// slipping pair's on its shear axes, a closed deforming joint's on
    /// all) over its r to `k` and `f`; `solved`: the slipping pairs'
    /// pressures are solved for (else the last solve's are in `f`).
    fn add_springs(
        &self,
        springs: &[usize],
        rel: &[Relation],
        solved: bool,
        ramp: f64,
        k: &mut DMatrix<f64>,
        f: &mut DVector<f64>,
    ) {
        let nd = self.nd;
        for &j in springs {
            let rl = &rel[self.pairs[j]];
            let lagged = if solved { 0.0 } else { rl.pressure };
            let axes = if rl.elastic { 0..nd } else { 1..nd };
            for a in axes.clone() {
                let row_a = DVector::from_column_slice(&self.rows[j][a]);
                let mut fa = rl.force[a] + rl.coupling[a] * lagged;
                for c in axes.clone() {
                    let s = rl.spring[a][c];
                    if s == 0.0 {
                        continue;
                    }
                    fa += s * self.consts[j][c] * ramp;
                    let row_c = DVector::from_column_slice(&self.rows[j][c]);
                    *k += &row_a * row_c.transpose() * s;
                }
                *f += &row_a * fa;
            }
        }
    }

    /// The contact force on body I of each of the junction's pairs (local
    /// axes), its relative displacement, and its force as if tied where it
    /// is locked, from the junction's r and `g = -(W r - c)` on it (the
    /// force the pairs must carry, over r).
    ///
    /// A free axis is locked when the tied rows fix it (its row has no part
    /// along the free directions Z): an open pair whose copies the loop's
    /// other ties keep together has a zero gap whatever it carries; a
    /// slipping pair they keep from slipping has no slip. Tying it would
    /// change no displacement, only the forces, so its gap or slip cannot
    /// tell its state: the forces with every locked axis tied can, the
    /// least-norm ones within every pair's limit (None where nothing is
    /// locked). They tell whether the pair can stick; a slipping pair
    /// that cannot is judged by its first force, the one the outputs
    /// report: where the loop can only carry its friction with the pair
    /// in tension, it opens (a T-junction under a dam's base did so,
    /// tests/junctions.rs).
    pub fn forces(
        &self,
        tied: &Tied,
        rel: &[Relation],
        r: &DVector<f64>,
        g: &DVector<f64>,
        ramp: f64,
    ) -> Vec<PairForces> {
        let rels = self.relative(r, ramp);
        if self.pairs.iter().all(|&p| rel[p].elastic) {
            // joints that deform carry what their springs do
            return rels.iter().zip(&self.pairs).map(|(&x, &p)| (rel[p].spring_force(x), x, None)).collect();
        }
        let limits: Vec<Limit> = self.pairs.iter().map(|&p| rel[p].limit).collect();
        let mut out = self.carried_forces(tied, rel, &rels, r, g, &limits);
        let locked = self.locked_rows(tied, rel, &rels);
        if locked.is_empty() {
            return out;
        }
        let as_tied = self.forces_as_tied(tied, rel, &out, &locked, g, &limits);
        for &(j, _) in &locked {
            out[j].2 = Some(as_tied[j]);
        }
        out
    }

    /// Each pair's relative displacement (local axes) at r.
    fn relative(&self, r: &DVector<f64>, ramp: f64) -> Vec<[f64; 3]> {
        let nd = self.nd;
        (0..self.pairs.len())
            .map(|j| {
                std::array::from_fn(|a| {
                    if a < nd {
                        DVector::from_column_slice(&self.rows[j][a]).dot(r) + self.consts[j][a] * ramp
                    } else {
                        0.0
                    }
                })
            })
            .collect()
    }

    /// The pairs' forces from the tied rows' share of g and the slipping
    /// pairs' relations, with their relative displacements (`rels`) and no
    /// forces as tied yet.
    fn carried_forces(
        &self,
        tied: &Tied,
        rel: &[Relation],
        rels: &[[f64; 3]],
        r: &DVector<f64>,
        g: &DVector<f64>,
        limits: &[Limit],
    ) -> Vec<PairForces> {
        let nd = self.nd;
        // the slipping pairs' pressures, and what the tied rows carry: g
        // less the slipping pairs' friction
        let pressures = tied.pressure.as_ref().map(|pr| pr.at(&(&tied.k * r + &tied.f - g)));
        let friction = match (&tied.pressure, &pressures) {
            (Some(pr), Some(p)) => &tied.f + &pr.r * p,
            _ => tied.f.clone(),
        };
        let mut carried = g - (&tied.k * r + friction);
        let mut lambda = tied.split.forces(&carried, limits, &tied.prior);
        let mut pressure: Vec<f64> = self.pairs.iter().map(|&p| rel[p].pressure).collect();
        if let (Some(pr), Some(p)) = (&tied.pressure, &pressures) {
            for (&j, &pj) in pr.pairs.iter().zip(p.iter()) {
                pressure[j] = pj;
            }
        }
        let beyond = tied.split.beyond(&lambda, limits);
        if let Some(pr) = tied.pressure.as_ref().filter(|_| beyond > 0.0 && beyond <= NEAR_LIMIT) {
            if let Some((within, dp)) = self.share_with_friction(tied, pr, &lambda, limits) {
                for (&j, &d) in pr.pairs.iter().zip(dp.iter()) {
                    pressure[j] += d;
                }
                carried -= &pr.r * dp;
                lambda = within;
            }
        }
        self.off.set(0.0);
        if tied.pressure.is_none() {
            let stuck = self.locked_slipping(tied, rel, rels);
            if !stuck.is_empty() {
                (carried, lambda) = self.settle_locked(tied, rel, &stuck, carried, lambda, limits, &mut pressure);
            }
        }
        let slipping = |j: usize| rel[self.pairs[j]].state == ContactState::Slip;
        let looped = pressure::looped(&tied.split, &lambda, &tied.split.plain(&carried, &tied.prior), slipping);
        self.memo.set_looped(looped);
        // (a share that met no limit is the least-norm one: the next solve
        // with the same tied rows takes its pressures through it too, if
        // it holds every state, [`Junction::tie_held`])
        self.memo.set_tangent(if looped {
            Tangent::at(&tied.split, &carried, &lambda, limits)
        } else {
            Some(Tangent::plain(&tied.split, &tied.prior))
        });
        let mut out: Vec<PairForces> = rels.iter().map(|&x| ([0.0; 3], x, None)).collect();
        for (&(j, dir), &l) in tied.rows.iter().zip(lambda.iter()) {
            for a in (0..nd).filter(|&a| dir[a] != 0.0) {
                out[j].0[a] += l * dir[a];
            }
        }
        for (j, &p) in self.pairs.iter().enumerate() {
            let rl = &rel[p];
            if rl.state != ContactState::Slip {
                continue;
            }
            for a in 1..nd {
                out[j].0[a] = rl.force[a]
                    + rl.coupling[a] * pressure[j]
                    + (1..nd).map(|c| rl.spring[a][c] * rels[j][c]).sum::<f64>();
            }
        }
        out
    }

    /// The share within every limit where the least-norm one breaks one
    /// by little ([`NEAR_LIMIT`]) and the loops alone cannot mend it,
    /// their forces moving the slipping pairs' pressures `pr`, and so
    /// their friction, with them.
    ///
    /// Round a crossing line whose two stuck pairs carry the friction of
    /// its two slipping ones, the loop shares those pairs' pressures, and
    /// trading pressure between them moves the friction a stuck pair
    /// carries along the line: blocks3d_confined's pair 335, stuck 0.08 %
    /// beyond its bound along the line under the least-norm share (which
    /// no loop force mends with the friction held) and, released,
    /// slipping 2.3e-8 m against its friction, flipped between the two
    /// for 400 iterations. With P = D pinv, R the friction per unit
    /// pressure and E the slipping normals' rows (`Δp = -E Δλ`), the
    /// loops' forces are `(I - P R E)^-1 D N s`. Where the slip directions
    /// of the pairs that trade differ, the trade also pushes along the
    /// junction's free directions (`Z^T R E Δλ`): the share is then the
    /// next solve's to balance, which takes the pressures through its
    /// tangent (the loops now carry part of them, [`pressure`]). Holding
    /// to shares that push nowhere found none at pair 335. Returns the
    /// share and the pressures' change; None where no share meets every
    /// limit.
    fn share_with_friction(
        &self,
        tied: &Tied,
        pr: &Pressure,
        lambda: &DVector<f64>,
        limits: &[Limit],
    ) -> Option<(DVector<f64>, DVector<f64>)> {
        let split = &tied.split;
        let (m, n_r, n_null) = (split.rows.len(), self.r.len(), split.null.ncols());
        if n_null == 0 {
            return None;
        }
        let rows: Vec<usize> =
            pr.pairs.iter().map(|&j| split.rows.iter().position(|&row| row == (j, NORMAL))).collect::<Option<_>>()?;
        let p = DMatrix::<f64>::from_fn(m, n_r, |i, c| split.d[i] * split.pinv[(i, c)]);
        let re =
            DMatrix::<f64>::from_fn(n_r, m, |c, i| rows.iter().position(|&x| x == i).map_or(0.0, |s| pr.r[(c, s)]));
        let dn = DMatrix::<f64>::from_fn(m, n_null, |i, c| split.d[i] * split.null[(i, c)]);
        let loops = (DMatrix::<f64>::identity(m, m) - &p * &re).try_inverse()? * dn;
        let within = split.within(lambda, &loops, limits);
        if split.breaks(&within, limits) {
            return None;
        }
        let dp = DVector::<f64>::from_fn(rows.len(), |s, _| lambda[rows[s]] - within[rows[s]]);
        Some((within, dp))
    }

    /// What `rows` carry in situ (the pairs' `prior` forces).
    fn prior_of(&self, rows: &[Row], rel: &[Relation]) -> DVector<f64> {
        DVector::from_iterator(rows.len(), rows.iter().map(|&(j, dir)| dot(rel[self.pairs[j]].prior, dir)))
    }

    /// The free rows the ties lock (no part along Z): open pairs' normals,
    /// and slipping pairs' shear where they have not slipped (a slip the
    /// loop had locked elsewhere could not be tied back: their shear is
    /// judged by their slip, as any other pair's).
    fn locked_rows(&self, tied: &Tied, rel: &[Relation], rels: &[[f64; 3]]) -> Vec<Row> {
        let nd = self.nd;
        let is_locked = |row: Row| {
            let row = DVector::from_vec(self.c_row(row).0);
            tied.z.ncols() == 0 || (tied.z.transpose() * &row).norm() <= 1e-9 * row.norm()
        };
        let scale = rels.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
        let mut locked: Vec<Row> = Vec::new();
        for (j, &p) in self.pairs.iter().enumerate() {
            match rel[p].state {
                ContactState::Open if is_locked((j, NORMAL)) => locked.push((j, NORMAL)),
                ContactState::Slip => {
                    let shear = self.shear_dirs(j, |q| rel[q].state != ContactState::Open);
                    let unmoved =
                        shear.iter().all(|&dir| along(nd, sub(rels[j], rel[p].target), dir).abs() <= 1e-10 * scale);
                    if unmoved && shear.iter().all(|&dir| is_locked((j, dir))) {
                        locked.extend(shear.iter().map(|&dir| (j, dir)));
                    }
                }
                _ => {}
            }
        }
        locked
    }

    /// The least-norm forces with the `locked` axes tied too; the other
    /// free axes keep what their relations give them (`out`).
    fn forces_as_tied(
        &self,
        tied: &Tied,
        rel: &[Relation],
        out: &[PairForces],
        locked: &[Row],
        g: &DVector<f64>,
        limits: &[Limit],
    ) -> Vec<[f64; 3]> {
        let nd = self.nd;
        let mut rows: Vec<Row> = tied.rows.iter().chain(locked).copied().collect();
        rows.sort_by_key(|&(j, dir)| (j, dir.iter().position(|&x| x != 0.0)));
        // each pair's force less its parts along the rows: what stays
        let mut kept: Vec<[f64; 3]> = out.iter().map(|o| o.0).collect();
        for &(j, dir) in &rows {
            let f = along(nd, kept[j], dir);
            for a in (0..nd).filter(|&a| dir[a] != 0.0) {
                kept[j][a] -= f * dir[a];
            }
        }
        let mut carried = g.clone();
        for (j, f) in kept.iter().enumerate() {
            for a in (0..nd).filter(|&a| f[a] != 0.0) {
                carried -= DVector::from_column_slice(&self.rows[j][a]) * f[a];
            }
        }
        let c_rows: Vec<Vec<f64>> = rows.iter().map(|&row| self.c_row(row).0).collect();
        let prior = self.prior_of(&rows, rel);
        let lambda = Split::new(&c_rows, &rows, &tied.areas, g.len()).forces(&carried, limits, &prior);
        let mut as_tied = kept;
        for (&(j, dir), &l) in rows.iter().zip(lambda.iter()) {
            for a in (0..nd).filter(|&a| dir[a] != 0.0) {
                as_tied[j][a] += l * dir[a];
            }
        }
        as_tied
    }

    /// The slipping pairs (junction indices) with a friction coupled to
    /// their pressure whose shear the loop's ties lock: they have not
    /// slipped, and no free direction moves them along their shear.
    fn locked_slipping(&self, tied: &Tied, rel: &[Relation], rels: &[[f64; 3]]) -> Vec<usize> {
        let nd = self.nd;
        let scale = rels.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
        let locked = |row: Row| {
            let row = DVector::from_vec(self.c_row(row).0);
            tied.z.ncols() == 0 || (tied.z.transpose() * &row).norm() <= 1e-9 * row.norm()
        };
        (0..self.pairs.len())
            .filter(|&j| {
                let rl = &rel[self.pairs[j]];
                if rl.state != ContactState::Slip || rl.coupling.iter().all(|&c| c == 0.0) {
                    return false;
                }
                let shear = self.shear_dirs(j, |q| rel[q].state != ContactState::Open);
                !shear.is_empty()
                    && shear.iter().all(|&dir| along(nd, sub(rels[j], rl.target), dir).abs() <= 1e-10 * scale)
                    && shear.iter().all(|&dir| locked((j, dir)))
            })
            .collect()
    }

    /// The pressures of the slipping pairs `stuck` whose shear the loop
    /// locks, where they are the last solve's: their friction
    /// `force + coupling p` moves no displacement (their shear has no part
    /// along Z), only the share of the loop's forces, which gives them
    /// their pressure back. That fixed point is the junction's own, so it is
    /// iterated here, r held, instead of over contact iterations (a 3D
    /// tunnel through three joint sets took 20 contact iterations a time
    /// creeping along it). Returns the carried force and its share at the
    /// pressures found ([`fixed_point::settle`]), which it writes into
    /// `pressure`. Where the rounds reach none (a wedge: the friction,
    /// carried round the loop or into a roller, gives the pair's normal
    /// back as much pressure as it took, or more; or they cycle), the
    /// pressures stay the last solve's: on the 86k tunnel a J2 pair at the
    /// end roller went to 1e34 in 200 rounds, and the iteration never
    /// recovered. The pair is then judged by its force as tied (`forces`):
    /// a locked slip changes no displacement.
    #[allow(clippy::too_many_arguments)]
    fn settle_locked(
        &self,
        tied: &Tied,
        rel: &[Relation],
        stuck: &[usize],
        carried: DVector<f64>,
        lambda: DVector<f64>,
        limits: &[Limit],
        pressure: &mut [f64],
    ) -> (DVector<f64>, DVector<f64>) {
        let nd = self.nd;
        let Some(normal) = stuck
            .iter()
            .map(|&j| tied.split.rows.iter().position(|&row| row == (j, NORMAL)))
            .collect::<Option<Vec<usize>>>()
        else {
            return (carried, lambda);
        };
        // the friction per unit pressure of each over r, and the pressure it was linearised at
        let per: Vec<DVector<f64>> = stuck
            .iter()
            .map(|&j| {
                let rl = &rel[self.pairs[j]];
                (1..nd).fold(DVector::zeros(self.r.len()), |acc, a| {
                    acc + DVector::from_column_slice(&self.rows[j][a]) * rl.coupling[a]
                })
            })
            .collect();
        let base: Vec<f64> = stuck.iter().map(|&j| rel[self.pairs[j]].pressure).collect();
        let p: Vec<f64> = normal.iter().map(|&i| (-lambda[i]).max(0.0)).collect();
        let scale = carried.amax().max(f64::MIN_POSITIVE);
        let at = |p: &[f64]| {
            let now = per.iter().zip(p).zip(&base).fold(carried.clone(), |acc, ((v, &pj), &b)| acc - v * (pj - b));
            let lambda = tied.split.forces(&now, limits, &tied.prior);
            let next: Vec<f64> = normal.iter().map(|&i| (-lambda[i]).max(0.0)).collect();
            (now, lambda, next)
        };
        let Some((p, (now, lambda, _), off)) = fixed_point::settle(&at, p, scale) else {
            let lambda = tied.split.forces(&carried, limits, &tied.prior);
            return (carried, lambda);
        };
        self.off.set(if off > fixed_point::CLOSE * scale { off } else { 0.0 });
        for (&j, &pj) in stuck.iter().zip(&p) {
            pressure[j] = pj;
        }
        (now, lambda)
    }
}

mod fixed_point;
pub mod pressure;
mod room;
mod row;
mod split;
mod tangent;
mod tie_cache;
use fixed_point::Off;
use pressure::Pressure;
pub use room::Room;
use row::{Row, NORMAL};
use split::{Split, RANK_TOLERANCE};
use tangent::Tangent;
use tie_cache::Memo;

#[cfg(test)]
mod tests;
