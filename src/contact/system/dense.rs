//! One solve of the dense interface: W (the relative displacements'
//! stiffness, means eliminated once, [`super::reduce`]) restricted to the
//! free directions of a set of relations ([`super::Freedom`]),
//!
//! ```text
//! r = r0 + Z y,    Z^T (W r - c + friction) = 0,
//! ```
//!
//! with the lone slipping pairs' friction rows (their force coupled to
//! their normal force, springs along their slip) and the junctions'
//! springs and forces on their own columns. A lone pair's free axis is a
//! column of one entry, so without junctions this is the rows of W the
//! state set leaves free, as in the paper.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::joins::JoinElimination;
use super::reduce::Reduced;
use super::Freedom;

/// The relative displacements, `W r - c`, the means and the residual of
/// the solve; None when the restricted system is singular (a body sliding
/// freely, or one nothing holds).
#[allow(clippy::type_complexity)]
pub(super) fn solve(reduced: &Reduced, joined: Option<&JoinElimination>, fr: &Freedom, lambda: &[f64]) -> Option<(Vec<f64>, Vec<f64>, Vec<f64>, f64)> {
    let w = &reduced.w;
    let nr = w.nrows();
    let c = reduced.c_at(lambda);
    let mut r = fr.r0.clone();
    let nf = fr.cols.len();
    // c - W r0: the known part of every row
    let mut known = c.clone();
    for j in (0..nr).filter(|&j| r[j] != 0.0) {
        let rj = r[j];
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
    // lone slipping pairs: the friction force on their free tangential rows,
    // (W r - c)_t + force + coupling (W r - c)_n + spring r = 0
    let mut symmetric = true;
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
        for &(rc, k) in &s.springs {
            wf[(i, fr.pos[rc])] += k;
        }
        // the springs of one pair are symmetric (k (I - n n^T))
    }
    // junctions: their slipping pairs' springs and forces on their columns
    for jb in &fr.junctions {
        for (a, fa) in jb.cols.clone().enumerate() {
            rhs[(fa, 0)] -= jb.fz[a];
            for (b, fb) in jb.cols.clone().enumerate() {
                wf[(fa, fb)] += jb.kz[(a, b)];
            }
        }
    }
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
    for (f, col) in fr.cols.iter().enumerate() {
        for &(i, zi) in col {
            r[i] += zi * z[(f, 0)];
        }
    }
    let wr_c = reduced.residual(&r, &c);
    let mut m = reduced.means(&r, lambda);
    if let Some(joined) = joined {
        let m_j = joined.means(&m, &r, lambda);
        m.extend(m_j);
    }
    Some((r, wr_c, m, residual))
}
