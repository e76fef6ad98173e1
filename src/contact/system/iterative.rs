//! The interface system without S: the unknowns `x = [m; r]` of
//! [`super::coords`], `K x` applied part by part through each part's
//! interior factor ([`crate::substructure::interior`]),
//!
//! ```text
//! K x = sum_p W_p^T T_p Q_p^T  S_p  Q_p T_p^T W_p x       (S_p x = K_cc x - K_ci K_ii^-1 K_ic x)
//! ```
//!
//! and each set of pair relations solved by GMRES ([`super::gmres`]) in the
//! means and the free relative displacements, the tied ones moved to the
//! right-hand side. Nothing of size nc^2 exists: memory is the parts'
//! interior factors plus a few vectors per GMRES iteration, and a contact
//! iteration costs a number of sparse sweeps instead of a dense
//! factorisation. Each solve starts from the last one's answer, so a
//! contact iteration that changes few pairs costs few GMRES iterations.
//!
//! The preconditioner is block Jacobi: per pair (its means and relative
//! displacements) and per join node, the diagonal blocks of the parts'
//! K_cc in the same coordinates (the face basis of quadratic faces left
//! out), with the friction law's linearisation on the pair's slipping rows.

use std::sync::Mutex;

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::coords::{for_each_load, Axis, Terms, Var};
use crate::contact::frame::Frame;
use super::gmres;
use super::reduce::combine;
use super::{coords, Relation};
use crate::contact::basis;
use crate::contact::law::ContactState;
use crate::substructure::interior::SharedSolve;

/// Relative tolerance of each interface solve, against the load.
pub const TOLERANCE: f64 = 1e-10;
const RESTART: usize = 200;
const MAX_ITERATIONS: usize = 5_000;

/// A part as the interface sees it.
pub struct AppliedPart {
    pub solve: SharedSolve,
    /// The unknowns of each interface DOF, in local axes and the face basis.
    pub terms: Vec<Terms>,
    /// Frame of each interface node.
    pub frames: Vec<Frame>,
    /// Transformed face edges.
    pub edges: Vec<[usize; 3]>,
    /// Condensed loads, one per case (global axes, nodal basis).
    pub g: Vec<Vec<f64>>,
}

/// Which block of the preconditioner an unknown is in, and where.
#[derive(Clone, Copy)]
struct Place {
    block: usize,
    at: usize,
}

/// The interface system, applied; see the module header.
pub struct Iterative {
    nd: usize,
    nm: usize,
    nr: usize,
    parts: Vec<AppliedPart>,
    /// Right-hand sides over `[m; r]` per case, and of the prescribed values at ramp 1.
    b: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    /// Diagonal blocks (row-major) and the unknowns of each.
    blocks: Vec<(Vec<usize>, Vec<f64>)>,
    place: Vec<Place>,
    threads: usize,
    /// The last solution, where the next solve starts.
    last: Mutex<Option<Vec<f64>>>,
    /// GMRES iterations of every solve so far.
    pub iterations: Mutex<Vec<usize>>,
}

/// What a solve gives the interface problem.
pub struct Answer {
    /// `[m; r]`.
    pub x: Vec<f64>,
    /// `K x - b` on the relative rows: `-λ`.
    pub residual_r: Vec<f64>,
    /// `||J dx - rhs|| / ||b||` of the GMRES solve.
    pub residual: f64,
}

impl Iterative {
    /// Sets up the right-hand sides (one application of S per part, for
    /// the prescribed values) and the preconditioner's blocks; `groups`
    /// lists the unknowns of each pair and join node.
    pub fn new(nd: usize, nm: usize, nr: usize, parts: Vec<AppliedPart>, groups: Vec<Vec<Var>>) -> Iterative {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let n = nm + nr;
        let idx = |v: Var| match v {
            Var::M(i) => i,
            Var::R(i) => nm + i,
        };
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let mut b = vec![vec![0.0; n]; cases];
        for part in &parts {
            for (case, g) in part.g.iter().enumerate() {
                let y = part.to_unknowns(g.clone());
                for_each_load(&y, &part.terms, |v, x| b[case][idx(v)] += x);
            }
        }
        let mut it = Iterative {
            nd,
            nm,
            nr,
            parts,
            b,
            b_fixed: vec![0.0; n],
            blocks: Vec::new(),
            place: vec![Place { block: usize::MAX, at: 0 }; n],
            threads,
            last: Mutex::new(None),
            iterations: Mutex::new(Vec::new()),
        };
        // -K w0: the prescribed values at ramp 1
        if it.parts.iter().any(|p| p.terms.iter().any(|t| t.constant != 0.0)) {
            let kw0 = it.apply_with(&vec![0.0; n], 1.0);
            it.b_fixed = kw0.iter().map(|v| -v).collect();
        }
        // the preconditioner's blocks
        for (bi, vars) in groups.iter().enumerate() {
            let members: Vec<usize> = vars.iter().map(|&v| idx(v)).collect();
            for (at, &u) in members.iter().enumerate() {
                it.place[u] = Place { block: bi, at };
            }
            let k = members.len();
            it.blocks.push((members, vec![0.0; k * k]));
        }
        for part in &it.parts {
            let diag = part.solve.diagonal_blocks(nd);
            for (q, f) in part.frames.iter().enumerate() {
                let d = &diag[q * nd * nd..(q + 1) * nd * nd];
                // F D F^T
                let mut local = [[0.0; 3]; 3];
                for a in 0..nd {
                    for c in 0..nd {
                        local[a][c] = (0..nd).map(|i| f[a][i] * (0..nd).map(|j| d[i * nd + j] * f[c][j]).sum::<f64>()).sum();
                    }
                }
                for a in 0..nd {
                    let ta = &part.terms[q * nd + a];
                    for c in 0..nd {
                        let tc = &part.terms[q * nd + c];
                        for &(vi, ci) in &ta.vars[..ta.n] {
                            for &(vj, cj) in &tc.vars[..tc.n] {
                                let (pi, pj) = (it.place[idx(vi)], it.place[idx(vj)]);
                                if pi.block == pj.block && pi.block != usize::MAX {
                                    let (members, m) = &mut it.blocks[pi.block];
                                    let k = members.len();
                                    m[pi.at * k + pj.at] += ci * cj * local[a][c];
                                }
                            }
                        }
                    }
                }
            }
        }
        it
    }

    /// The diagonal of the preconditioner's block at relative displacement `r`.
    pub fn diagonal_r(&self, r: usize) -> f64 {
        let p = self.place[self.nm + r];
        let (members, m) = &self.blocks[p.block];
        m[p.at * members.len() + p.at]
    }

    /// `K x`.
    fn apply(&self, x: &[f64]) -> Vec<f64> {
        self.apply_with(x, 0.0)
    }

    /// `K (x + ramp w0)`: the parts side by side in the machine's threads.
    fn apply_with(&self, x: &[f64], ramp: f64) -> Vec<f64> {
        let n = self.nm + self.nr;
        let nm = self.nm;
        let one = |part: &AppliedPart| -> Vec<f64> {
            let d = part.from_unknowns(x, ramp, nm, self.nd);
            let y = part.to_unknowns(part.solve.apply(&d, 1));
            let mut out = vec![0.0; n];
            for_each_load(&y, &part.terms, |v, val| match v {
                Var::M(i) => out[i] += val,
                Var::R(i) => out[nm + i] += val,
            });
            out
        };
        let threads = self.threads.min(self.parts.len()).max(1);
        let partials: Vec<Vec<f64>> = if threads == 1 {
            self.parts.iter().map(one).collect()
        } else {
            let chunk = self.parts.len().div_ceil(threads);
            std::thread::scope(|scope| {
                let handles: Vec<_> = self.parts.chunks(chunk).map(|ps| scope.spawn(move || ps.iter().map(one).collect::<Vec<_>>())).collect();
                handles.into_iter().flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
            })
        };
        let mut out = vec![0.0; n];
        for p in partials {
            for (o, v) in out.iter_mut().zip(p) {
                *o += v;
            }
        }
        out
    }

    /// Solves the pairs' relations `rel` (pair `p`'s local axes numbered by
    /// `axes[p]`) under the load factors `lambda`; `None` when GMRES does
    /// not get below 1e-6 (a singular system: a body sliding freely).
    pub fn solve(&self, axes: &[[Axis; 3]], rel: &[Relation], lambda: &[f64]) -> Option<Answer> {
        let (nd, nm, nr) = (self.nd, self.nm, self.nr);
        let n = nm + nr;
        let b = combine(&self.b, &self.b_fixed, lambda);
        // the start: the last answer, with the tied relative displacements set
        let mut x0 = self.last.lock().ok().and_then(|l| l.clone()).filter(|l| l.len() == n).unwrap_or_else(|| vec![0.0; n]);
        let mut free = vec![true; n];
        // slipping rows: (row, normal row, coupling, [(column, spring)])
        let mut slip_rows: Vec<(usize, Option<usize>, f64, Vec<(usize, f64)>, f64)> = Vec::new();
        for (p, rl) in rel.iter().enumerate() {
            for a in 0..nd {
                if let Some(ri) = axes[p][a].r() {
                    if !rl.free_axis(a) {
                        free[nm + ri] = false;
                        x0[nm + ri] = rl.target[a];
                    }
                }
            }
            if rl.state == ContactState::Slip {
                let rn = axes[p][0].r().map(|r| nm + r);
                for a in 1..nd {
                    let Some(ra) = axes[p][a].r() else { continue };
                    let springs = (1..nd).filter_map(|c| axes[p][c].r().map(|rc| (nm + rc, rl.spring[a][c]))).filter(|s| s.1 != 0.0).collect();
                    slip_rows.push((nm + ra, rn, rl.coupling[a], springs, rl.force[a]));
                }
            }
        }
        let unknowns: Vec<usize> = (0..n).filter(|&i| free[i]).collect();
        // rows of J x (full = K x): the slipping rows take in their normal row and springs
        let rows = |full: &mut Vec<f64>, x: &[f64]| {
            for (i, rn, ca, springs, _) in &slip_rows {
                let mut v = full[*i];
                if let Some(rn) = rn {
                    v += ca * full[*rn];
                }
                v += springs.iter().map(|&(c, s)| s * x[c]).sum::<f64>();
                full[*i] = v;
            }
        };
        let mut e0 = self.apply(&x0);
        for (e, bi) in e0.iter_mut().zip(&b) {
            *e -= bi;
        }
        rows(&mut e0, &x0);
        for (i, _, _, _, force) in &slip_rows {
            e0[*i] += force;
        }
        let rhs: Vec<f64> = unknowns.iter().map(|&i| -e0[i]).collect();
        let expand = |v: &[f64]| -> Vec<f64> {
            let mut full = vec![0.0; n];
            for (&i, &x) in unknowns.iter().zip(v) {
                full[i] = x;
            }
            full
        };
        let j = |v: &[f64]| -> Vec<f64> {
            let dx = expand(v);
            let mut full = self.apply(&dx);
            rows(&mut full, &dx);
            unknowns.iter().map(|&i| full[i]).collect()
        };
        let precondition = self.preconditioner(&free, &slip_rows.iter().map(|s| (s.0, s.1, s.2, s.3.clone())).collect::<Vec<_>>());
        let m = |v: &[f64]| -> Vec<f64> {
            let full = expand(v);
            let out = precondition(&full);
            unknowns.iter().map(|&i| out[i]).collect()
        };
        let scale = b.iter().map(|v| v * v).sum::<f64>().sqrt().max(rhs.iter().map(|v| v * v).sum::<f64>().sqrt()).max(f64::MIN_POSITIVE);
        let (dx, conv) = gmres::solve(j, m, &rhs, TOLERANCE * scale, RESTART, MAX_ITERATIONS);
        if let Ok(mut its) = self.iterations.lock() {
            its.push(conv.iterations);
        }
        let residual = conv.residual / scale;
        if !conv.converged && !(residual <= 1e-6) {
            return None;
        }
        let mut x = x0;
        for (&i, d) in unknowns.iter().zip(&dx) {
            x[i] += d;
        }
        let kx = self.apply(&x);
        let residual_r = (0..nr).map(|r| kx[nm + r] - b[nm + r]).collect();
        if let Ok(mut last) = self.last.lock() {
            *last = Some(x.clone());
        }
        Some(Answer { x, residual_r, residual })
    }

    /// `M^-1`: each block restricted to its free unknowns, with the
    /// slipping rows as in [`Self::solve`], factorised once per solve.
    fn preconditioner(&self, free: &[bool], slip_rows: &[(usize, Option<usize>, f64, Vec<(usize, f64)>)]) -> impl Fn(&[f64]) -> Vec<f64> + '_ {
        let mut slip_of = std::collections::HashMap::new();
        for (k, s) in slip_rows.iter().enumerate() {
            slip_of.insert(s.0, k);
        }
        let factors: Vec<(Vec<usize>, Option<faer::linalg::solvers::PartialPivLu<f64>>)> = self
            .blocks
            .iter()
            .map(|(members, m)| {
                let k = members.len();
                let at: Vec<usize> = (0..k).filter(|&a| free[members[a]]).collect();
                let mut local = Mat::<f64>::from_fn(at.len(), at.len(), |i, j| m[at[i] * k + at[j]]);
                for (li, &a) in at.iter().enumerate() {
                    let Some(&s) = slip_of.get(&members[a]) else { continue };
                    let (_, rn, ca, springs) = &slip_rows[s];
                    if let Some(pn) = rn.and_then(|rn| members.iter().position(|&u| u == rn)) {
                        for (lj, &b) in at.iter().enumerate() {
                            local[(li, lj)] += ca * m[pn * k + b];
                        }
                    }
                    for &(c, sp) in springs {
                        if let Some(lj) = at.iter().position(|&b| members[b] == c) {
                            local[(li, lj)] += sp;
                        }
                    }
                }
                let members: Vec<usize> = at.iter().map(|&a| members[a]).collect();
                let lu = (!members.is_empty()).then(|| local.partial_piv_lu());
                (members, lu)
            })
            .collect();
        move |v: &[f64]| {
            let mut out = v.to_vec();
            for (members, lu) in &factors {
                let Some(lu) = lu else { continue };
                let rhs = Mat::<f64>::from_fn(members.len(), 1, |i, _| v[members[i]]);
                let z = lu.solve(&rhs);
                for (i, &u) in members.iter().enumerate() {
                    let zi = z[(i, 0)];
                    out[u] = if zi.is_finite() { zi } else { v[u] };
                }
            }
            out
        }
    }
}

impl AppliedPart {
    /// The part's interface displacements (global axes, nodal basis) for
    /// the unknowns `x` and the prescribed values at `ramp`.
    fn from_unknowns(&self, x: &[f64], ramp: f64, nm: usize, nd: usize) -> Vec<f64> {
        let mut d = vec![0.0; self.terms.len()];
        for (q, f) in self.frames.iter().enumerate() {
            let mut local = [0.0; 3];
            for (a, l) in local.iter_mut().enumerate().take(nd) {
                let t = &self.terms[q * nd + a];
                *l = t.constant * ramp
                    + t.vars[..t.n]
                        .iter()
                        .map(|&(v, c)| c * match v {
                            Var::M(i) => x[i],
                            Var::R(i) => x[nm + i],
                        })
                        .sum::<f64>();
            }
            for c in 0..nd {
                d[q * nd + c] = (0..nd).map(|a| f[a][c] * local[a]).sum();
            }
        }
        basis::to_nodal(&mut d, nd, &self.edges);
        d
    }

    /// A force on the part's interface (global axes, nodal basis) in the
    /// face basis and local axes: `T Q^T y`.
    fn to_unknowns(&self, mut y: Vec<f64>) -> Vec<f64> {
        let nd = self.terms.len() / self.frames.len().max(1);
        basis::transform_load(&mut y, nd, &self.edges);
        coords::rotate_vector(&mut y, nd, &self.frames);
        y
    }
}
