//! The dense interface solver: the interface system reduced once to the
//! relative displacements ([`super::reduce`]: `W r - c = -λ`; the bonded
//! joins of substructures eliminated first by a sparse factorisation when
//! they outnumber the contact unknowns, [`super::joins`]), and each set of
//! pair relations solved densely in its free relative displacements: a
//! Cholesky factorisation of `W_ff` when every relation is symmetric, LU
//! where the friction law's linearisation couples a slipping row to the
//! pair's normal force.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::coords::{self, Axis, Blocks};
use super::joins::{self, JoinElimination, SparseBlocks};
use super::layout::Layout;
use super::reduce::{NotHeld, Reduced};
use super::{Answer, Relation, Solver};
use crate::contact::law::ContactState;
use crate::fem::sparse::NONE;
use crate::substructure::{OperatorRef, SchurRef};

/// The interface reduced to the relative displacements; see the module header.
pub struct Dense {
    reduced: Reduced,
    /// The join means, when they were eliminated sparsely.
    joined: Option<JoinElimination>,
}

impl Dense {
    /// Reduces the interface of the densely condensed `parts` (in the order
    /// of `layout.parts`); fails when even every pair stuck leaves a body free.
    pub(super) fn new(layout: &Layout, parts: &[OperatorRef]) -> Result<Dense, NotHeld> {
        let (nd, nm, nm_pairs, nr) = (layout.nd, layout.nm, layout.nm_pairs, layout.nr);
        let nj = nm - nm_pairs;
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let (blocks, joined) = if joins::worth_it(nj, nm_pairs, nr) {
            let cliques: Vec<Vec<coords::Terms>> = parts.iter().zip(&layout.parts).map(|(p, map)| layout.terms_of(p.nc, map)).collect();
            let mut node_of = vec![0; nj];
            for (j, axes) in layout.joins.iter().enumerate() {
                for a in axes {
                    if let Axis::Joined { m } = *a {
                        node_of[m - nm_pairs] = j;
                    }
                }
            }
            let mut sparse = SparseBlocks::new(nm_pairs, nj, nr, cases, &cliques, node_of);
            for ((part, map), terms) in parts.iter().zip(&layout.parts).zip(&cliques) {
                if let Some(s) = dense_s(part) {
                    let (s, g) = coords::localise(s, part.g, nd, &layout.frames_of(map), &map.edges);
                    sparse.add_part(&s, &g, terms);
                }
            }
            let (blocks, joined) = sparse.condense().map_err(|_| NotHeld)?;
            (blocks, Some(joined))
        } else {
            let mut blocks = Blocks::zeros(nm, nr, cases);
            for (part, map) in parts.iter().zip(&layout.parts) {
                if let Some(s) = dense_s(part) {
                    blocks.add_part(s, part.g, nd, &layout.terms_of(part.nc, map), &layout.frames_of(map), &map.edges);
                }
            }
            (blocks, None)
        };
        Ok(Dense { reduced: Reduced::new(blocks)?, joined })
    }
}

impl Solver for Dense {
    fn solve(&self, axes: &[[Axis; 3]], rel: &[Relation], lambda: &[f64]) -> Option<Answer> {
        let reduced = &self.reduced;
        let c = reduced.c_at(lambda);
        let (mut r, free) = tied(axes, rel, reduced.w.nrows());
        let (wf, rhs, fidx, symmetric) = free_system(reduced, axes, rel, &c, &r, &free);
        let nf = fidx.len();
        let z = if nf == 0 {
            Mat::<f64>::zeros(0, 1)
        } else if symmetric {
            wf.llt(Side::Lower).ok()?.solve(&rhs)
        } else {
            wf.partial_piv_lu().solve(&rhs)
        };
        if z.col(0).iter().any(|v| !v.is_finite()) {
            return None;
        }
        let residual = if nf == 0 {
            0.0
        } else {
            let res = &wf * &z - &rhs;
            res.norm_l2() / rhs.norm_l2().max(f64::MIN_POSITIVE)
        };
        // Singular up to round-off (a body sliding freely on slipping pairs)
        // lets the factorisation pass: its residual is O(1), not O(eps).
        if residual > 1e-6 {
            return None;
        }
        for (f, &i) in fidx.iter().enumerate() {
            r[i] = z[(f, 0)];
        }
        let residual_r = reduced.residual(&r, &c);
        let mut m = reduced.means(&r, lambda);
        if let Some(joined) = &self.joined {
            let m_j = joined.means(&m, &r, lambda);
            m.extend(m_j);
        }
        Some(Answer { m, r, residual_r, residual, loose: false })
    }

    fn diagonal(&self, r: usize) -> f64 {
        self.reduced.w[(r, r)]
    }

    fn counts(&self) -> Vec<usize> {
        Vec::new()
    }
}

/// The relative displacements tied by the relations (their values) and
/// which ones are free.
fn tied(axes: &[[Axis; 3]], rel: &[Relation], nr: usize) -> (Vec<f64>, Vec<bool>) {
    let mut r = vec![0.0; nr];
    let mut free = vec![true; nr];
    for (p, rl) in rel.iter().enumerate() {
        for (a, axis) in axes[p].iter().enumerate() {
            if let Some(ri) = axis.r() {
                if !rl.free_axis(a) {
                    free[ri] = false;
                    r[ri] = rl.target[a];
                }
            }
        }
    }
    (r, free)
}

/// The system of the free relative displacements: `W_ff`, `c - W r_T` on
/// the free rows, with the slipping pairs' friction law on their free
/// tangential rows, `(W r - c)_t + force + coupling (W r - c)_n + spring r
/// = 0`; the free rows' indices, and whether the matrix is symmetric.
fn free_system(reduced: &Reduced, axes: &[[Axis; 3]], rel: &[Relation], c: &[f64], r: &[f64], free: &[bool]) -> (Mat<f64>, Mat<f64>, Vec<usize>, bool) {
    let w = &reduced.w;
    let nr = w.nrows();
    let fidx: Vec<usize> = (0..nr).filter(|&i| free[i]).collect();
    let mut pos = vec![NONE; nr];
    for (f, &i) in fidx.iter().enumerate() {
        pos[i] = f;
    }
    let nf = fidx.len();
    // c - W r_T: the known part of every row
    let mut known = c.to_vec();
    for j in (0..nr).filter(|&j| !free[j] && r[j] != 0.0) {
        let rj = r[j];
        for (i, v) in known.iter_mut().enumerate() {
            *v -= w[(i, j)] * rj;
        }
    }
    let mut wf = Mat::<f64>::from_fn(nf, nf, |fi, fj| w[(fidx[fi], fidx[fj])]);
    let mut rhs = Mat::<f64>::from_fn(nf, 1, |fi, _| known[fidx[fi]]);
    let mut symmetric = true;
    for (p, rl) in rel.iter().enumerate().filter(|(_, rl)| rl.state == ContactState::Slip) {
        let rn = axes[p][0].r();
        for a in 1..3 {
            let Some(ra) = axes[p][a].r() else { continue };
            let i = pos[ra];
            rhs[(i, 0)] -= rl.force[a];
            if let (Some(rn), true) = (rn, rl.coupling[a] != 0.0) {
                symmetric = false;
                let ca = rl.coupling[a];
                for (fj, &j) in fidx.iter().enumerate() {
                    wf[(i, fj)] += ca * w[(rn, j)];
                }
                rhs[(i, 0)] += ca * known[rn];
            }
            for (cax, axis) in axes[p].iter().enumerate().skip(1) {
                if rl.spring[a][cax] == 0.0 {
                    continue;
                }
                if let Some(rc) = axis.r() {
                    wf[(i, pos[rc])] += rl.spring[a][cax];
                    if rl.spring[a][cax] != rl.spring[cax][a] {
                        symmetric = false;
                    }
                }
            }
        }
    }
    (wf, rhs, fidx, symmetric)
}

/// The S of a densely condensed part with an interface.
fn dense_s<'a>(p: &OperatorRef<'a>) -> Option<&'a [f64]> {
    match p.s {
        SchurRef::Dense(s) if p.nc > 0 => Some(s),
        _ => None,
    }
}
