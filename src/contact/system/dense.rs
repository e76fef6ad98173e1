//! The dense interface solver: the interface system reduced once to the
//! relative displacements ([`super::reduce`]: `W r - c = -λ`; the bonded
//! joins of substructures eliminated first by a sparse factorisation when
//! they outnumber the contact unknowns, [`super::joins`]), and each set of
//! pair relations solved densely in its free directions ([`super::Freedom`]:
//! a lone pair's free axis, a junction's null space), `r = r0 + Z y`,
//! `Z^T (W r - c + friction) = 0`: a Cholesky factorisation when every
//! relation is symmetric, LU where the friction law's linearisation couples
//! a slipping row to the pair's normal force. Without junctions `Z^T W Z`
//! is the rows of W the state set leaves free, as in the paper.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::coords::{self, Axis, Blocks};
use super::freedom::Freedom;
use super::joins::{self, JoinElimination, SparseBlocks};
use super::layout::Layout;
use super::reduce::{NotHeld, Reduced};
use super::solver::{Accuracy, Answer, Solver};
use crate::contact::law::ContactState;
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
            let cliques: Vec<Vec<coords::Terms>> = layout.parts.iter().map(|map| layout.terms_of(map)).collect();
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
                    blocks.add_part(s, part.g, nd, &layout.terms_of(map), &layout.frames_of(map), &map.edges);
                }
            }
            (blocks, None)
        };
        Ok(Dense { reduced: Reduced::new(blocks)?, joined })
    }
}

impl Solver for Dense {
    fn solve(&self, fr: &Freedom, _states: &[ContactState], lambda: &[f64], _: Accuracy) -> Option<Answer> {
        let reduced = &self.reduced;
        let mut c = reduced.c_at(lambda);
        fr.push(&mut c);
        let (wf, rhs, symmetric) = free_system(reduced, fr, &c);
        let nf = fr.cols.len();
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
        let mut r = fr.r0.clone();
        for (f, col) in fr.cols.iter().enumerate() {
            for &(i, zi) in col {
                r[i] += zi * z[(f, 0)];
            }
        }
        let residual_r = reduced.residual(&r, &c);
        let mut m = reduced.means(&r, lambda);
        if let Some(joined) = &self.joined {
            let m_j = joined.means(&m, &r, lambda);
            m.extend(m_j);
        }
        Some(Answer { m, r, residual_r, residual, accuracy: 0.0, loose: false, inexact: false })
    }

    fn diagonal(&self, r: usize) -> f64 {
        self.reduced.w[(r, r)]
    }

    fn counts(&self) -> Vec<usize> {
        Vec::new()
    }
}

/// The system of the free directions: `Z^T W Z` and `Z^T (c - W r0)`
/// (a lone pair's free axis is a column of one entry: a row of W), with the
/// lone slipping pairs' friction law on their free tangential rows,
/// `(W r - c)_t + force + coupling (W r - c)_n + spring r = 0`, and the
/// junctions' springs, forces and implicit pressures' lift on their own
/// rows; and whether the matrix is symmetric.
fn free_system(reduced: &Reduced, fr: &Freedom, c: &[f64]) -> (Mat<f64>, Mat<f64>, bool) {
    let w = &reduced.w;
    let nr = w.nrows();
    let nf = fr.cols.len();
    // c - W r0: the known part of every row
    let mut known = c.to_vec();
    for j in (0..nr).filter(|&j| fr.r0[j] != 0.0) {
        let rj = fr.r0[j];
        for (i, v) in known.iter_mut().enumerate() {
            *v -= w[(i, j)] * rj;
        }
    }
    let entry = |a: &[(usize, f64)], b: &[(usize, f64)]| -> f64 {
        match (a, b) {
            ([(i, _)], [(j, _)]) => w[(*i, *j)],
            _ => a.iter().map(|&(i, zi)| b.iter().map(|&(j, zj)| zi * zj * w[(i, j)]).sum::<f64>()).sum(),
        }
    };
    let mut wf = Mat::<f64>::zeros(nf, nf);
    for (fj, cj) in fr.cols.iter().enumerate() {
        for (fi, ci) in fr.cols.iter().enumerate() {
            wf[(fi, fj)] = entry(ci, cj);
        }
    }
    let mut rhs = Mat::<f64>::zeros(nf, 1);
    for (fi, ci) in fr.cols.iter().enumerate() {
        rhs[(fi, 0)] = match ci.as_slice() {
            [(i, _)] => known[*i],
            _ => ci.iter().map(|&(i, zi)| zi * known[i]).sum(),
        };
    }
    let mut symmetric = fr.symmetric;
    for s in &fr.slips {
        let i = fr.pos[s.row];
        rhs[(i, 0)] -= s.force;
        if let (Some(rn), true) = (s.normal, s.coupling != 0.0) {
            symmetric = false;
            for (fj, cj) in fr.cols.iter().enumerate() {
                wf[(i, fj)] += s.coupling * entry(&[(rn, 1.0)], cj);
            }
            rhs[(i, 0)] += s.coupling * known[rn];
        }
        // (the springs of one pair are symmetric: k (I - n n^T))
        for &(rc, k) in &s.springs {
            wf[(i, fr.pos[rc])] += k;
        }
    }
    for jb in &fr.junctions {
        for (a, fa) in jb.cols.clone().enumerate() {
            rhs[(fa, 0)] -= jb.fz[a];
            for (b, fb) in jb.cols.clone().enumerate() {
                wf[(fa, fb)] += jb.kz[(a, b)];
            }
        }
        // the implicit pressures' lift: L (W r - c) + L k Z y on its rows
        if let Some(lift) = &jb.lift {
            symmetric = false;
            for (a, fa) in jb.cols.clone().enumerate() {
                for (x, &ri) in jb.r.iter().enumerate() {
                    let l = lift.on_w[(a, x)];
                    if l == 0.0 {
                        continue;
                    }
                    for (fj, cj) in fr.cols.iter().enumerate() {
                        wf[(fa, fj)] += l * entry(&[(ri, 1.0)], cj);
                    }
                    rhs[(fa, 0)] += l * known[ri];
                }
                for (b, fb) in jb.cols.clone().enumerate() {
                    wf[(fa, fb)] += lift.on_y[(a, b)];
                }
            }
        }
    }
    (wf, rhs, symmetric)
}

/// The S of a densely condensed part with an interface.
fn dense_s<'a>(p: &OperatorRef<'a>) -> Option<&'a [f64]> {
    match p.s {
        SchurRef::Dense(s) if p.nc > 0 => Some(s),
        _ => None,
    }
}
