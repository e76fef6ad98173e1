//! The interface system: the condensed parts in the pairs' local frames and
//! in mean / relative coordinates, solved for one set of pair relations.
//!
//! Per part, `S' = T Q^T S Q T^T`, `G' = T Q^T G` (T block-diagonal, one pair
//! frame per interface node; Q the face basis of [`super::basis`], the
//! identity on linear faces). Per pair and local axis the two sides' DOFs
//! are written as a mean `m` and a relative displacement `r = d'_l - d'_k`:
//!
//! ```text
//! d'_k = m - r/2,  d'_l = m + r/2        (neither side supported)
//! d'_k = v,        d'_l = v + r          (k held at v; likewise for l)
//! ```
//!
//! i.e. `d' = W y + w0`. The condensed equations `S' d' = G' + f` with the
//! contact force λ on body I at k and -λ on body II at l become
//!
//! ```text
//! K y - b = [0 on the means; -λ on the relative displacements],
//! K = W^T S' W,   b = W^T (G' - S' w0)
//! ```
//!
//! so the contact force of every pair is the residual of its `r` rows, and a
//! set of contact states is a choice, per axis, between a known `r` (tied:
//! stick on every axis, slip on the normal) and a known relation for λ
//! (open: λ = 0; slip: the friction law's force, possibly linearised in the
//! pair's slip and normal force). K is formed once; each state set solves
//! the rows it leaves free. A supported axis of a pair is a prescribed `d'`;
//! its force is read on the unsupported side, and is zero where both are
//! supported (the supports carry it).

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::basis::{self, FaceBasis};
use super::frame::{aligned_axis, frame, Frame};
use super::law::{ContactState, PairResult};
use super::rigid::{free_parts, RigidModes, Tie};
use crate::fem::sparse::NONE;
use crate::model::{Model, ModelError};
use crate::substructure::Condensed;

/// How one local axis of a pair enters the unknowns `y`.
#[derive(Clone, Copy, Debug)]
enum Axis {
    /// Neither side held: `d'_k = m - r/2`, `d'_l = m + r/2`.
    Free { m: usize, r: usize },
    /// Side k held at `v` (per unit ramp): `d'_k = v`, `d'_l = v + r`.
    HeldK { r: usize, v: f64 },
    /// Side l held at `v`: `d'_l = v`, `d'_k = v - r`.
    HeldL { r: usize, v: f64 },
    /// Both sides held.
    Held { vk: f64, vl: f64 },
    /// The axis does not exist (the third axis in 2D).
    Absent,
}

impl Axis {
    fn r(self) -> Option<usize> {
        match self {
            Axis::Free { r, .. } | Axis::HeldK { r, .. } | Axis::HeldL { r, .. } => Some(r),
            _ => None,
        }
    }

    /// `d'` of side `s` (0 = k, 1 = l) as `sum c y + const * ramp`.
    fn terms(self, s: usize) -> ([(usize, f64); 2], usize, f64) {
        let none = (NONE, 0.0);
        match (self, s) {
            (Axis::Free { m, r }, 0) => ([(m, 1.0), (r, -0.5)], 2, 0.0),
            (Axis::Free { m, r }, _) => ([(m, 1.0), (r, 0.5)], 2, 0.0),
            (Axis::HeldK { v, .. }, 0) => ([none, none], 0, v),
            (Axis::HeldK { r, v }, _) => ([(r, 1.0), none], 1, v),
            (Axis::HeldL { r, v }, 0) => ([(r, -1.0), none], 1, v),
            (Axis::HeldL { v, .. }, _) => ([none, none], 0, v),
            (Axis::Held { vk, .. }, 0) => ([none, none], 0, vk),
            (Axis::Held { vl, .. }, _) => ([none, none], 0, vl),
            (Axis::Absent, _) => ([none, none], 0, 0.0),
        }
    }
}

/// Where a part's interface nodes sit among the pairs.
struct PartMap {
    /// (pair, side) of each interface node of the part, in the part's order.
    nodes: Vec<(usize, usize)>,
    /// Transformed edges, as positions in `nodes`.
    edges: Vec<[usize; 3]>,
}

/// What a pair's unknowns are asked to satisfy in one solve.
#[derive(Clone, Copy, Debug)]
pub struct Relation {
    pub state: ContactState,
    /// `r` on tied axes: stick ties all axes, slip the normal one (its
    /// target is 0: the pair touches).
    pub target: [f64; 3],
    /// On free tangential axes of slipping pairs, the force on body I is
    /// `force + coupling * p + spring * r` (local t, b components; p = -λ_n
    /// the normal pressure force), so that a Newton step can linearise the
    /// Coulomb law; zero for the paper's fixed friction force.
    pub force: [f64; 3],
    pub coupling: [f64; 3],
    pub spring: [[f64; 3]; 3],
}

impl Relation {
    /// Stuck at `target`, open, or slipping with a known tangential force.
    pub fn simple(state: ContactState, target: [f64; 3], force: [f64; 3]) -> Relation {
        Relation { state, target, force, coupling: [0.0; 3], spring: [[0.0; 3]; 3] }
    }

    fn free_axis(&self, a: usize) -> bool {
        match self.state {
            ContactState::Stick => false,
            ContactState::Slip => a > 0,
            ContactState::Open => true,
        }
    }
}

/// The interface problem, set up once; solved for any set of relations.
pub struct InterfaceProblem {
    nd: usize,
    pub frames: Vec<Frame>,
    pub basis: FaceBasis,
    axes: Vec<[Axis; 3]>,
    ny: usize,
    /// `W^T S' W`, dense, column-major.
    k: Mat<f64>,
    /// `W^T G'` per load case, and `-W^T S' w0` for the prescribed values
    /// at ramp 1.
    b_cases: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    parts: Vec<PartMap>,
    /// Rigid motions of each part and the position of each pair, to tell
    /// which parts nothing holds.
    rigid: Vec<RigidModes>,
    positions: Vec<[f64; 3]>,
    /// (part, position) of each pair's k and l.
    at: Vec<[(usize, usize); 2]>,
}

/// Result of one interface solve.
pub struct InterfaceSolution {
    pub pairs: Vec<PairResult>,
    /// Contact force on body I at each pair, local axes (n, t, b), in the
    /// interface basis.
    pub forces: Vec<[f64; 3]>,
    /// Relative displacement `d'_l - d'_k` at each pair, local axes.
    pub rel: Vec<[f64; 3]>,
    /// Global nodal interface displacements of each part (order of its interface nodes).
    pub d_c: Vec<Vec<f64>>,
    /// Relative residual of the dense interface solve.
    pub residual: f64,
}

/// Why an interface solve failed.
pub enum SolveFailure {
    /// These bodies are held by nothing.
    NotHeld(Vec<usize>),
    /// These bodies slide (or rotate) freely on slipping pairs: nothing holds
    /// them tangentially (empty when the cause is not found).
    Singular(Vec<usize>),
}

/// `T A T^T` in place for a dense column-major `nc x nc` matrix whose
/// node blocks are rotated by `t[node]`.
fn rotate_matrix(s: &mut [f64], nc: usize, nd: usize, t: &[Frame]) {
    let mut tmp = [0.0; 3];
    // columns: S T^T
    for i in 0..nc {
        for (q, tq) in t.iter().enumerate() {
            for a in 0..nd {
                tmp[a] = (0..nd).map(|c| s[i + (q * nd + c) * nc] * tq[a][c]).sum();
            }
            for a in 0..nd {
                s[i + (q * nd + a) * nc] = tmp[a];
            }
        }
    }
    // rows: T (S T^T)
    for j in 0..nc {
        for (q, tq) in t.iter().enumerate() {
            for a in 0..nd {
                tmp[a] = (0..nd).map(|c| tq[a][c] * s[q * nd + c + j * nc]).sum();
            }
            for a in 0..nd {
                s[q * nd + a + j * nc] = tmp[a];
            }
        }
    }
}

fn rotate_vector(g: &mut [f64], nd: usize, t: &[Frame]) {
    for (q, tq) in t.iter().enumerate() {
        let v: Vec<f64> = (0..nd).map(|a| (0..nd).map(|c| tq[a][c] * g[q * nd + c]).sum()).collect();
        g[q * nd..q * nd + nd].copy_from_slice(&v);
    }
}

impl InterfaceProblem {
    pub fn new(model: &Model, parts: &[Condensed]) -> Result<InterfaceProblem, ModelError> {
        let nd = model.nd;
        let np = model.pairs.len();
        let basis = FaceBasis::new(model);
        let mut where_is = vec![(NONE, NONE); model.n_nodes()];
        for (pi, p) in parts.iter().enumerate() {
            for (q, &n) in p.part.interface.iter().enumerate() {
                where_is[n] = (pi, q);
            }
        }
        // frames, and the prescribed local values of each side (nodal basis)
        let mut frames = Vec::with_capacity(np);
        let mut fixed: Vec<[[Option<f64>; 3]; 2]> = Vec::with_capacity(np);
        for pair in &model.pairs {
            let mut sup = [false; 3];
            for node in [pair.k, pair.l] {
                for c in 0..nd {
                    sup[c] |= model.prescribed[node * nd + c].is_some();
                }
            }
            let f = frame(nd, pair.normal, sup);
            let mut fx = [[None; 3]; 2];
            for (side, node) in [pair.k, pair.l].into_iter().enumerate() {
                for c in 0..nd {
                    if let Some(v) = model.prescribed[node * nd + c] {
                        let (a, sign) = aligned_axis(&f, nd, c).ok_or_else(|| ModelError::Invalid {
                            scene: model.scene.clone(),
                            key: "supports".into(),
                            msg: format!(
                                "the contact node at {:?} is supported in direction {} which is not along its contact frame (normal {:?}): support it along the contact normal or tangent",
                                model.coords[node],
                                ["x", "y", "z"][c],
                                pair.normal
                            ),
                        })?;
                        fx[side][a] = Some(sign * v);
                    }
                }
            }
            frames.push(f);
            fixed.push(fx);
        }
        // prescribed values in the face basis (per side, local axis)
        if !basis.is_nodal() {
            for side in 0..2 {
                for a in 0..nd {
                    let v: Vec<f64> = fixed.iter().map(|fx| fx[side][a].unwrap_or(0.0)).collect();
                    let mut t = v.clone();
                    for &[m, c1, c2] in &basis.edges {
                        t[m] = (v[m] - basis::ALPHA * (v[c1] + v[c2])) / (1.0 - 2.0 * basis::ALPHA);
                    }
                    for (p, fx) in fixed.iter_mut().enumerate() {
                        if fx[side][a].is_some() {
                            fx[side][a] = Some(t[p]);
                        }
                    }
                }
            }
        }
        // unknowns
        let mut ny = 0;
        let mut next = || {
            ny += 1;
            ny - 1
        };
        let axes: Vec<[Axis; 3]> = fixed
            .iter()
            .map(|fx| {
                std::array::from_fn(|a| {
                    if a >= nd {
                        return Axis::Absent;
                    }
                    match (fx[0][a], fx[1][a]) {
                        (None, None) => {
                            let m = next();
                            Axis::Free { m, r: next() }
                        }
                        (Some(v), None) => Axis::HeldK { r: next(), v },
                        (None, Some(v)) => Axis::HeldL { r: next(), v },
                        (Some(vk), Some(vl)) => Axis::Held { vk, vl },
                    }
                })
            })
            .collect();
        let at: Vec<[(usize, usize); 2]> = model.pairs.iter().map(|p| [where_is[p.k], where_is[p.l]]).collect();
        let maps: Vec<PartMap> = parts
            .iter()
            .enumerate()
            .map(|(pi, p)| {
                let mut nodes = vec![(NONE, 0); p.part.interface.len()];
                for (pair, sides) in at.iter().enumerate() {
                    for (s, &(pp, q)) in sides.iter().enumerate() {
                        if pp == pi {
                            nodes[q] = (pair, s);
                        }
                    }
                }
                let edges = basis::part_edges(&basis, |pair| {
                    let [(pk, qk), (pl, ql)] = at[pair];
                    [(pk == pi).then_some(qk), (pl == pi).then_some(ql)]
                });
                PartMap { nodes, edges }
            })
            .collect();
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let mut k = Mat::<f64>::zeros(ny, ny);
        let mut b_cases = vec![vec![0.0; ny]; cases];
        let mut b_fixed = vec![0.0; ny];
        for (part, map) in parts.iter().zip(&maps) {
            let nc = part.nc;
            if nc == 0 {
                continue;
            }
            let t: Vec<Frame> = map.nodes.iter().map(|&(pair, _)| frames[pair]).collect();
            let mut s = part.s.clone();
            basis::transform_matrix(&mut s, nc, nd, &map.edges);
            rotate_matrix(&mut s, nc, nd, &t);
            // d'_u = sum_i c_i y_i + w0_u: the terms of every part DOF
            let terms: Vec<([(usize, f64); 2], usize, f64)> =
                (0..nc).map(|u| {
                    let (pair, side) = map.nodes[u / nd];
                    axes[pair][u % nd].terms(side)
                }).collect();
            let w0: Vec<f64> = terms.iter().map(|t| t.2).collect();
            for v in 0..nc {
                let (tv, nv, _) = terms[v];
                for u in 0..nc {
                    let (tu, nu, _) = terms[u];
                    let suv = s[u + v * nc];
                    if suv == 0.0 {
                        continue;
                    }
                    for &(i, ci) in &tu[..nu] {
                        for &(j, cj) in &tv[..nv] {
                            k[(i, j)] += ci * cj * suv;
                        }
                    }
                }
            }
            for (case, gc) in part.g.iter().enumerate() {
                let mut g = gc.clone();
                basis::transform_load(&mut g, nd, &map.edges);
                rotate_vector(&mut g, nd, &t);
                for u in 0..nc {
                    let (tu, nu, _) = terms[u];
                    for &(i, ci) in &tu[..nu] {
                        b_cases[case][i] += ci * g[u];
                    }
                }
            }
            if w0.iter().any(|&v| v != 0.0) {
                for u in 0..nc {
                    let sw: f64 = (0..nc).map(|v| s[u + v * nc] * w0[v]).sum();
                    let (tu, nu, _) = terms[u];
                    for &(i, ci) in &tu[..nu] {
                        b_fixed[i] -= ci * sw;
                    }
                }
            }
        }
        let rigid = parts.iter().map(|p| RigidModes::new(model, &p.part.bodies)).collect();
        let positions = model.pairs.iter().map(|p| model.coords[p.k]).collect();
        Ok(InterfaceProblem { nd, frames, basis, axes, ny, k, b_cases, b_fixed, parts: maps, rigid, positions, at })
    }

    /// The area pair `p` controls (in the interface basis), > 0.
    pub fn area(&self, p: usize) -> f64 {
        self.basis.areas[p]
    }

    /// Number of pairs.
    pub fn n_pairs(&self) -> usize {
        self.axes.len()
    }

    /// A stiffness of pair `p`'s relative displacement (the mean diagonal
    /// of its `r` rows): the scale that turns a slip into a force.
    pub fn stiffness(&self, p: usize) -> f64 {
        let d: Vec<f64> = self.axes[p].iter().filter_map(|a| a.r()).map(|r| self.k[(r, r)]).collect();
        if d.is_empty() {
            1.0
        } else {
            d.iter().sum::<f64>() / d.len() as f64
        }
    }

    /// Solves the interface system for the relations `rel` of every pair
    /// under the load factors `lambda` (case 0 also scales prescribed values).
    pub fn solve(&self, rel: &[Relation], lambda: &[f64]) -> Result<InterfaceSolution, SolveFailure> {
        let nd = self.nd;
        let ramp = lambda[0];
        let states: Vec<ContactState> = rel.iter().map(|r| r.state).collect();
        // A part nothing holds makes the system singular only up to
        // round-off: decide it from the states and the supports first.
        if let failure @ SolveFailure::NotHeld(_) = self.diagnose(&states) {
            return Err(failure);
        }
        let sliding = self.free(&states, false);
        if !sliding.is_empty() {
            return Err(SolveFailure::Singular(sliding));
        }
        let ny = self.ny;
        let mut b = self.b_fixed.iter().map(|v| v * ramp).collect::<Vec<f64>>();
        for (bc, &l) in self.b_cases.iter().zip(lambda) {
            if l != 0.0 {
                for (o, v) in b.iter_mut().zip(bc) {
                    *o += l * v;
                }
            }
        }
        // free unknowns, and the known values of tied ones
        let mut y = vec![0.0; ny];
        let mut free = vec![true; ny];
        for (p, r) in rel.iter().enumerate() {
            for a in 0..nd {
                if let Some(ri) = self.axes[p][a].r() {
                    if !r.free_axis(a) {
                        free[ri] = false;
                        y[ri] = r.target[a];
                    }
                }
            }
        }
        let fidx: Vec<usize> = (0..ny).filter(|&i| free[i]).collect();
        let mut pos = vec![NONE; ny];
        for (f, &i) in fidx.iter().enumerate() {
            pos[i] = f;
        }
        let nf = fidx.len();
        // K y_T: the known part of every row
        let mut ky_t = vec![0.0; ny];
        for j in (0..ny).filter(|&j| !free[j] && y[j] != 0.0) {
            let yj = y[j];
            for (i, v) in ky_t.iter_mut().enumerate() {
                *v += self.k[(i, j)] * yj;
            }
        }
        let mut kf = Mat::<f64>::zeros(nf, nf);
        for (fj, &j) in fidx.iter().enumerate() {
            for (fi, &i) in fidx.iter().enumerate() {
                kf[(fi, fj)] = self.k[(i, j)];
            }
        }
        let mut rhs = Mat::<f64>::zeros(nf, 1);
        for (fi, &i) in fidx.iter().enumerate() {
            rhs[(fi, 0)] = b[i] - ky_t[i];
        }
        // slipping pairs: the friction force on their free tangential rows
        let mut symmetric = true;
        for (p, r) in rel.iter().enumerate() {
            if r.state != ContactState::Slip {
                continue;
            }
            let rn = self.axes[p][0].r();
            for a in 1..nd {
                let Some(ra) = self.axes[p][a].r() else { continue };
                let i = pos[ra];
                rhs[(i, 0)] -= r.force[a];
                if let (Some(rn), true) = (rn, r.coupling[a] != 0.0) {
                    symmetric = false;
                    let ca = r.coupling[a];
                    for (fj, &j) in fidx.iter().enumerate() {
                        kf[(i, fj)] += ca * self.k[(rn, j)];
                    }
                    rhs[(i, 0)] += ca * (b[rn] - ky_t[rn]);
                }
                for c in 1..nd {
                    if r.spring[a][c] == 0.0 {
                        continue;
                    }
                    if let Some(rc) = self.axes[p][c].r() {
                        kf[(i, pos[rc])] += r.spring[a][c];
                        if r.spring[a][c] != r.spring[c][a] {
                            symmetric = false;
                        }
                    }
                }
            }
        }
        let z = if nf == 0 {
            Mat::<f64>::zeros(0, 1)
        } else if symmetric {
            match kf.llt(Side::Lower) {
                Ok(l) => l.solve(&rhs),
                Err(_) => return Err(self.diagnose(&states)),
            }
        } else {
            kf.partial_piv_lu().solve(&rhs)
        };
        if z.col(0).iter().any(|v| !v.is_finite()) {
            return Err(self.diagnose(&states));
        }
        let residual = if nf == 0 {
            0.0
        } else {
            let res = &kf * &z - &rhs;
            res.norm_l2() / rhs.norm_l2().max(f64::MIN_POSITIVE)
        };
        // Singular up to round-off (a body sliding freely on slipping pairs)
        // lets the factorisation pass: its residual is O(1), not O(eps).
        if residual > 1e-6 {
            return Err(self.diagnose(&states));
        }
        for (f, &i) in fidx.iter().enumerate() {
            y[i] = z[(f, 0)];
        }
        // the contact forces: the residual of the r rows
        let mut forces = vec![[0.0; 3]; rel.len()];
        let mut rels = vec![[0.0; 3]; rel.len()];
        for (p, ax) in self.axes.iter().enumerate() {
            for a in 0..nd {
                match ax[a] {
                    Axis::Held { vk, vl } => rels[p][a] = (vl - vk) * ramp,
                    Axis::Absent => {}
                    axis => {
                        let r = axis.r().expect("an axis with r");
                        rels[p][a] = y[r];
                        // the force of a free axis is what its relation
                        // prescribes (an open pair's is exactly zero, not
                        // the round-off of its residual)
                        if !rel[p].free_axis(a) || rel[p].state == ContactState::Slip {
                            let kr: f64 = (0..ny).map(|j| self.k[(r, j)] * y[j]).sum();
                            forces[p][a] = -(kr - b[r]);
                        }
                    }
                }
            }
            if rel[p].state == ContactState::Slip {
                let pn = -forces[p][0];
                let r = &rel[p];
                for a in 1..nd {
                    if self.axes[p][a].r().is_some() {
                        forces[p][a] = r.force[a] + r.coupling[a] * pn + (1..nd).map(|c| r.spring[a][c] * rels[p][c]).sum::<f64>();
                    }
                }
            }
        }
        let pairs = (0..rel.len())
            .map(|p| {
                let area = self.basis.areas[p];
                let (f, r) = (forces[p], rels[p]);
                PairResult { sigma_n: f[0] / area, tau_t: f[1] / area, tau_b: f[2] / area, gap: r[0], slip: r[1].hypot(r[2]) }
            })
            .collect();
        // interface displacements of every part, global axes, nodal basis
        let d_c = self
            .parts
            .iter()
            .map(|map| {
                let mut d = vec![0.0; map.nodes.len() * nd];
                for (q, &(pair, side)) in map.nodes.iter().enumerate() {
                    let mut local = [0.0; 3];
                    for (a, l) in local.iter_mut().enumerate().take(nd) {
                        let (t, n, c) = self.axes[pair][a].terms(side);
                        *l = c * ramp + t[..n].iter().map(|&(i, ci)| ci * y[i]).sum::<f64>();
                    }
                    let f = &self.frames[pair];
                    for c in 0..nd {
                        d[q * nd + c] = (0..nd).map(|a| f[a][c] * local[a]).sum();
                    }
                }
                basis::to_nodal(&mut d, nd, &map.edges);
                d
            })
            .collect();
        Ok(InterfaceSolution { pairs, forces, rel: rels, d_c, residual })
    }

    /// Parts that a rigid motion moves which the supports and the pairs tied
    /// by `states` do not stop; `slip_holds`: count slipping pairs as stuck
    /// (then only open pairs release anything).
    fn free(&self, states: &[ContactState], slip_holds: bool) -> Vec<usize> {
        let nd = self.nd;
        let ties = states.iter().enumerate().flat_map(|(p, st)| {
            let axes = match st {
                ContactState::Stick => nd,
                ContactState::Slip if slip_holds => nd,
                ContactState::Slip => 1,
                ContactState::Open => 0,
            };
            let [(pk, _), (pl, _)] = self.at[p];
            (0..axes).map(move |a| Tie { parts: [pk, pl], x: self.positions[p], dir: self.frames[p][a] })
        });
        free_parts(&self.rigid, ties)
    }

    /// Why the interface system is singular: parts held by nothing once
    /// their open pairs let go, or else a part sliding on slipping pairs.
    fn diagnose(&self, states: &[ContactState]) -> SolveFailure {
        let free = self.free(states, true);
        if free.is_empty() {
            SolveFailure::Singular(self.free(states, false))
        } else {
            SolveFailure::NotHeld(free)
        }
    }
}
