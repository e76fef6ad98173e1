//! The sparse interface solver, for many small parts: a rock mass of
//! hundreds of blocks, where the joints are most of the model and the
//! dense interface (W of every relative displacement) would not fit.
//!
//! In the unknowns `[m; r]` of [`super::coords`] the means are unknowns
//! under every set of relations, so their block is factorised once, sparse
//! (a clique per part, METIS nested dissection in 3D), and a set of states
//! leaves free only the relative displacements of its open and slipping
//! pairs, `r = r0 + Z y`:
//!
//! ```text
//! [ K_mm       K_mr Z          ] [m]   [ b_m              ]
//! [ Z^T K_rm   Z^T K_rr Z + F  ] [y] = [ Z^T (b_r - K_rr r0) - f ]     (F, f: the friction law's rows)
//! ```
//!
//! solved by GMRES ([`super::gmres`]) preconditioned by the block upper
//! triangle `P = [K_mm, K_mr Z; 0, A_yy]`: y from the free relative
//! displacements with the means held, then the means through K_mm's
//! factor. With K_mm exact the preconditioned system is
//! `[I, 0; *, S A_yy^-1]`, S the free block of the Schur complement
//! (`Z^T W Z + F`, `W = K_rr - K_rm K_mm^-1 K_mr`). `A_yy` is S itself,
//! formed from W's columns at the free relative displacements
//! ([`super::w_columns`]): each computed once, the first time a solve
//! leaves its displacement free (a substitution through K_mm's factor,
//! all of a solve's new ones in one pass), then kept; the preconditioned
//! system is the identity to single precision, and a solve takes 2 or 3
//! GMRES iterations to the loose tolerance and 7 to the tight one (the
//! 3D tunnel of `make tunnel3d`: 159 applications in 40 contact
//! iterations instead of 528 in 38 with `A_yy = Z^T K_rr Z + springs`,
//! which is what a solve falls back on where the columns would take
//! too much memory).
//!
//! Because K_mm enters only the preconditioner, its factor is kept in
//! single precision ([`crate::substructure::single_precision`]): half the bytes to
//! stream per substitution and to factorise (docs/kernels.md). The
//! residual GMRES monitors is K's own, in double precision, and after
//! each solve the means are refined to double precision for the
//! relative displacements found, so that a stuck
//! pair's force is what K makes of the displacements on both sides: the
//! round-off of a direct solve, not the tolerance of an iterative one,
//! where a joint carries nothing (at a free surface).
//!
//! Where every pair deforms (joints with springs, [`Freedom::deforming`])
//! no axis is tied, every relative displacement is free, and the system
//! of a solve is `K + F` over `[m; r]`, F the springs (unsymmetric only
//! at slipping pairs). The preconditioner is then its symmetric part,
//! whole, factorised once a load through the sides' own DOFs
//! ([`super::sides`]): GMRES mends only the slipping pairs' terms and the
//! springs of pairs that changed state since (the 86k tunnel: 21
//! applications in 4 iterations).
//!
//! A stuck pair costs nothing. Each solve starts from the last answer
//! (means and relative displacements); a solve whose state set differs
//! from the last one's stops at the iterative interface's loose tolerance
//! ([`super::iterative`]), and one under held states whose friction has
//! not settled at a thousandth of the law's residual (an inexact Newton
//! step, [`super::iterative::tolerance`]): the 3D tunnel's held solves
//! took 6-7 applications each to the tight tolerance, now 2.

use std::cell::{Cell, RefCell};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use faer::linalg::matmul::matmul;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Accum, Mat, MatRef, Par};

use super::coords::{add_clique, fixed_load, for_each_load, localise, CliqueScratch, Terms, Var};
use super::freedom::Freedom;
use super::gmres;
use super::iterative::{give_start, keep_start, target, tolerance, LastStates, USABLE};
use super::layout::{Layout, PartMap};
use super::means_whole;
use super::own::Own;
use super::reduce::{combine, NotHeld};
use super::sides::Sides;
use super::solver::{Accuracy, Answer, Solver, Split, Springs, WarmStart};
use super::threads::{in_runs, in_threads};
use super::w_columns::{self, WColumns};
use super::w_entries::WEntries;
use crate::contact::law::ContactState;
use crate::fem::sparse::{Cholesky, SymMatrix};
use crate::fem::vec3::length;
use crate::model::topology::UnionFind;
use crate::model::Model;
use crate::substructure::ordering::Ordering;
use crate::substructure::schur::PartialCholesky;
use crate::substructure::single_precision::SingleCholesky;
use crate::substructure::sparse_forward::Forward;
use crate::substructure::{OperatorRef, SchurRef};

const RESTART: usize = 200;
const MAX_ITERATIONS: usize = 5_000;
/// A loose solve preconditioned by `Z^T K_rr Z` (W's columns would not
/// fit) also stops once it has cut the residual it started from by this
/// much. A hundredfold, as before 9297534: that commit dropped it because
/// the coarse tunnel's loose forces were off by up to 39 % of the largest
/// pair force, but the tunnels now take the exact block (it reaches the
/// loose tolerance in 2 or 3 applications and keeps it alone), and only
/// the block masses take this path. Measured 2026-12-04 against 1e-4:
/// the 1,000-block cube 95 applications instead of 148 (2 / 9 iterations
/// instead of 2 / 10; six twin pairs at joint crossings carry the same
/// force through the other twin, law residual 7e-15), 512 blocks 80
/// instead of 111, 64 blocks 63 instead of 76, those two the same states
/// pair by pair; scripts/regress and the corpus the same.
const LOOSE_REDUCTION: f64 = 1e-2;
/// At most this many refinements of the means after a solve (each gains
/// the single-precision factor's 4-5 digits).
const REFINEMENTS: usize = 6;
/// The refinement stops once the means' residual is below this fraction of
/// the load: K's products round off at 2e-14 of it (the 512-block cube),
/// where a last correction gained nothing but cost a substitution and a
/// sweep (2 in 7 of the refinement's work).
const REFINED: f64 = 1e-13;
/// Columns of W computed at once (each a vector over the means and one
/// over r in memory while they are).
const W_BATCH: usize = 64;

/// Where every pair deforms, a solve that took more GMRES applications
/// than this forms the free block's factor afresh for the next (the kept
/// one's springs are those of the states it was formed under). About what
/// a factor costs in applications: blocks3d_stiff 0.24 s against 5 ms an
/// application, the 86k tunnel 2.9 s against 45 ms.
const REFORM_AFTER: usize = 50;
/// The relative displacements whose W diagonal is found in one pass
/// through the supernodes of K_mm's factor their columns reach (sorted by
/// where they begin). The paths to the root separators are most of the
/// work whatever the batch: at 16, 64 and 256 a column's pass reads 37,
/// 39 and 45 % of the factor on average (the 512-block cube), and fewer
/// columns a pass read the top more often.
const W_DIAGONAL_BATCH: usize = 64;
/// Where every pair deforms, the free block `M` (every relative
/// displacement) is factorised in single precision, ordered by nested
/// dissection from this many unknowns (AMD below, as
/// [`Ordering::choose`]). The 86k tunnel with deforming joints (33,823
/// unknowns, 28 million entries in M's lower triangle), AMD in double
/// precision -> this: its factorisation 66-91 s -> 6.4 s, the same 190
/// GMRES applications, the same states, forces within 3e-9.
const SINGLE_BLOCK: usize = 5_000;

/// A column over the means by its non-zeros: (mean, value).
type MeanColumn = Vec<(usize, f64)>;

/// A part's condensed matrix in the pairs' local axes, and the unknowns of
/// each of its interface DOFs.
struct Local {
    s: Vec<f64>,
    terms: Vec<Terms>,
}

/// The interface with its means factorised; see the module header.
pub struct Sparse {
    nd: usize,
    nm: usize,
    nr: usize,
    parts: Vec<Local>,
    /// Each part's own stiffness ([`Own`]): what K_mm's factor is formed
    /// from, and where springs come ([`Springs`]) the sides' factor; kept
    /// past the interface's setup only there.
    own: Option<Vec<Own>>,
    /// Where the solves put springs on every pair.
    springs: Springs,
    /// K_mm's factor, and the mean of each node it is ordered by: formed
    /// with the interface, or where every pair deforms at its first use
    /// ([`Sparse::means`]); None where K_mm does not factorise.
    k_mm: OnceLock<Option<Means>>,
    node_of: Vec<usize>,
    /// W's diagonal where a pair's stiffness has been asked for, None
    /// elsewhere ([`Sparse::w_diagonal`]); K_rr's diagonal and where the
    /// parts hold each relative displacement ([`Sparse::holders`]), what
    /// it is formed from.
    w_diag: Mutex<Vec<Option<f64>>>,
    k_rr: Vec<f64>,
    holders: Vec<Vec<(usize, usize, f64)>>,
    /// The loads over `[m; r]`, per load case and for the prescribed values at ramp 1.
    b: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    threads: usize,
    /// The last answer, where the next solve starts.
    last: Mutex<Option<Arc<Last>>>,
    last_states: LastStates,
    iterations: Mutex<Vec<usize>>,
    /// Where the solves' time went.
    split: Mutex<Split>,
    /// W where the free blocks have read it: chosen at the first.
    w: Mutex<Option<WMemory>>,
    /// The free block's factor kept for the next solve of the same load
    /// where every pair deforms ([`Freedom::deforming`]).
    kept: Mutex<Option<Kept>>,
}

/// A free block's factor, the load factors it was formed under and its
/// free directions: reused while they are the same.
struct Kept {
    lambda: Vec<f64>,
    cols: Vec<Vec<(usize, f64)>>,
    block: Arc<Preconditioner>,
}

/// W where the free blocks read it: entry by entry where K_mm's factor
/// substitutes sparse columns ([`super::w_entries`]), else whole columns
/// ([`super::w_columns`]).
enum WMemory {
    Columns(WColumns),
    Entries(WEntries),
}

impl Sparse {
    /// The interface of the densely condensed `parts` (in the order of
    /// `layout.parts`), swept in `threads`; fails when even every pair
    /// stuck leaves a body free. Where every pair's joint deforms
    /// ([`Springs::Always`]) K_mm is factorised only if asked for: the
    /// solves are preconditioned by all of K with the springs
    /// ([`super::sides`]), and its factor was a quarter of the 86k
    /// tunnel's run (4.5 of 20 s). Where rigid joints may be solved again
    /// with springs ([`Springs::InRounds`]) the parts' own stiffness is
    /// kept for those solves' preconditioner too (the sides' factor over
    /// it, not over the parts' S side by side): the fine tet4 tunnel's
    /// 66 iterations of rounds, factorisations 5.8-6.4 -> 3.4-3.7 s and
    /// interface 31.6-35.0 -> 26.4-30.8 s (three runs each). The rest is
    /// GMRES, 4,850 applications (60 in the 12 solves at the first
    /// round's stiffness): what the factor leaves out grows with the
    /// springs, which the rounds stiffen 6,561-fold. The slipping pairs'
    /// couplings put back by Woodbury's identity took a fifth of the
    /// applications off and cost more in substitutions (factorisations
    /// 12.5 s); the 588 junctions' lifts were not tried. A factor in
    /// double precision took none off.
    pub(super) fn new(
        model: &Model,
        layout: &Layout,
        parts: &[OperatorRef],
        (threads, springs): (usize, Springs),
    ) -> Result<Sparse, NotHeld> {
        let deforming = springs == Springs::Always;
        let keep_own = springs != Springs::Never;
        let (nd, nm, nr) = (layout.nd, layout.nm, layout.nr);
        let cases = parts.iter().map(|p| p.g.len()).max().unwrap_or(1);
        let mut local = Vec::with_capacity(parts.len());
        let mut b = vec![vec![0.0; nm + nr]; cases];
        let mut b_fixed = vec![0.0; nm + nr];
        let at = |v: Var| match v {
            Var::M(i) => i,
            Var::R(i) => nm + i,
        };
        let dense: Vec<(&[f64], &OperatorRef, &PartMap)> = (parts.iter().zip(&layout.parts))
            .filter_map(|(part, map)| match part.s {
                SchurRef::Dense(s) if part.nc > 0 => Some((s, part, map)),
                _ => None,
            })
            .collect();
        // the parts' own stiffness: where springs come the sides'
        // factor's, and K_mm's through the bonded model
        // ([`super::means_whole`]) where the means are and that pays
        let bonded = !deforming && bonded_pays(model, &dense, threads);
        let own = (keep_own || bonded)
            .then(|| {
                in_threads(&dense, threads, |(_, part, map)| Own::of(model, part.part, &map.frames, &map.edges))
                    .into_iter()
                    .collect::<Option<Vec<Own>>>()
            })
            .flatten();
        let node_of = mean_nodes(layout);
        let own_factor = own.as_ref().filter(|_| bonded);
        let (localised, k_mm) = localise_and_factor(&dense, own_factor, &node_of, nd, threads);
        for ((_, _, map), (s, g)) in dense.iter().zip(localised) {
            for (bc, gc) in b.iter_mut().zip(&g) {
                for_each_load(gc, &map.terms, |i, x| bc[at(i)] += x);
            }
            fixed_load(&s, &map.terms, |i, x| b_fixed[at(i)] += x);
            local.push(Local { s, terms: map.terms.clone() });
        }
        let mut solver = Sparse {
            nd,
            nm,
            nr,
            parts: local,
            // (only the sides' factor needs them past K_mm's, formed above
            // where it pays)
            own: own.filter(|_| keep_own),
            springs,
            k_mm: k_mm.map_or_else(OnceLock::new, OnceLock::from),
            node_of,
            w_diag: Mutex::new(vec![None; nr]),
            k_rr: Vec::new(),
            holders: Vec::new(),
            b,
            b_fixed,
            threads: threads.max(1),
            last: Mutex::new(None),
            last_states: LastStates::default(),
            iterations: Mutex::new(Vec::new()),
            split: Mutex::new(Split::default()),
            w: Mutex::new(None),
            kept: Mutex::new(None),
        };
        if !deforming && solver.means().is_none() {
            return Err(NotHeld);
        }
        let t = Instant::now();
        solver.k_rr = solver.diagonal_r();
        solver.holders = solver.holders();
        solver.add_split(|s| s.diagonal = t.elapsed().as_secs_f64());
        Ok(solver)
    }

    /// `K [m; r]`, the parts swept in threads: (its mean rows, its relative rows).
    fn apply(&self, m: &[f64], r: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (nm, nr) = (self.nm, self.nr);
        let value = |v: Var| match v {
            Var::M(i) => m[i],
            Var::R(i) => r[i],
        };
        let sweep = |parts: &[Local]| -> Vec<f64> {
            let mut y = vec![0.0; nm + nr];
            let mut x = Vec::new();
            let mut out = Vec::new();
            for p in parts {
                let nc = p.terms.len();
                x.clear();
                x.extend(p.terms.iter().map(|t| t.vars[..t.n].iter().map(|&(v, c)| c * value(v)).sum::<f64>()));
                out.clear();
                out.resize(nc, 0.0);
                for (col, &xv) in p.s.chunks_exact(nc).zip(&x) {
                    if xv != 0.0 {
                        out.iter_mut().zip(col).for_each(|(o, s)| *o += s * xv);
                    }
                }
                for (t, &o) in p.terms.iter().zip(&out) {
                    for &(v, c) in &t.vars[..t.n] {
                        match v {
                            Var::M(i) => y[i] += c * o,
                            Var::R(i) => y[nm + i] += c * o,
                        }
                    }
                }
            }
            y
        };
        // (two parts a thread at least)
        let threads = if self.parts.len() < 2 * self.threads { 1 } else { self.threads };
        let mut sums = in_runs(&self.parts, threads, sweep).into_iter();
        let mut y = sums.next().unwrap_or_else(|| vec![0.0; nm + nr]);
        for s in sums {
            y.iter_mut().zip(&s).for_each(|(a, b)| *a += b);
        }
        let yr = y.split_off(nm);
        (y, yr)
    }

    /// `K_mr r`: the means' rows of `K [0; r]`.
    fn k_mr(&self, r: &[f64]) -> Vec<f64> {
        self.apply(&vec![0.0; self.nm], r).0
    }

    /// K_mm's factor, formed at its first use (through the bonded model
    /// where every pair deforms); None where K_mm does not factorise.
    fn means(&self) -> Option<&Means> {
        (self.k_mm.get_or_init(|| {
            if let Some(own) = self.own.as_ref().filter(|_| self.springs == Springs::Always) {
                let terms: Vec<&[Terms]> = self.parts.iter().map(|p| &p.terms[..]).collect();
                return bonded_factor(own, &terms, &self.node_of, self.nd, self.threads);
            }
            let k = means_matrix(&self.parts, self.nm);
            Means::factor(&k, &self.node_of, Ordering::choose(self.nm, self.nd), self.threads)
        }))
        .as_ref()
    }

    /// `K_mm^-1 v`, to the factor's precision (NaN where K_mm does not
    /// factorise: a solve through it gives no answer).
    fn solve_means(&self, v: &[f64]) -> Vec<f64> {
        if self.nm == 0 {
            return Vec::new();
        }
        self.means().map_or_else(|| vec![f64::NAN; v.len()], |f| f.solve(v))
    }

    /// The means for the relative displacements `r`, `K_mm m = b_m - K_mr
    /// r`, refined from `m` to double precision (residuals in double, the
    /// corrections through the means' factor); returns `K [m; r]` at the
    /// refined means (its mean rows, its relative rows).
    /// A stuck pair's force is what K makes of the displacements on both
    /// sides: round-off, not the solve's tolerance, where it carries nothing.
    /// `known`: `K [m; r]` where the solve formed it already.
    fn refine_means(
        &self,
        m: &mut [f64],
        r: &[f64],
        (b_m, scale): (&[f64], f64),
        mut known: Option<(Vec<f64>, Vec<f64>)>,
    ) -> (Vec<f64>, Vec<f64>) {
        if self.k_mm.get().is_none() {
            return known.unwrap_or_else(|| self.apply(m, r));
        }
        let mut last = f64::INFINITY;
        for _ in 0..REFINEMENTS {
            let (k_m, k_r) = known.take().unwrap_or_else(|| self.apply(m, r));
            let res: Vec<f64> = b_m.iter().zip(&k_m).map(|(b, k)| b - k).collect();
            let size = length(&res);
            if size <= REFINED * scale || size >= 0.5 * last {
                return (k_m, k_r);
            }
            last = size;
            m.iter_mut().zip(self.solve_means(&res)).for_each(|(m, d)| *m += d);
        }
        self.apply(m, r)
    }

    /// Where a solve starts: the last answer, its r moved onto r0 +
    /// span(Z), `r_s = r0 + Z y0`, and `K [m_s; r_s]`; the substitutions it took.
    fn start(&self, free: &Free, b_m: &[f64]) -> (Start, usize) {
        let fr = free.fr;
        let (nm, nr) = (self.nm, self.nr);
        let last = self.last.lock().ok().and_then(|l| l.clone()).filter(|l| l.m.len() == nm && l.r.len() == nr);
        let y0 = match &last {
            Some(l) => free.restrict(&l.r.iter().zip(&fr.r0).map(|(l, r0)| l - r0).collect::<Vec<_>>()),
            None => vec![0.0; fr.cols.len()],
        };
        let mut r_s = fr.r0.clone();
        r_s.iter_mut().zip(free.expand(&y0)).for_each(|(r, e)| *r += e);
        match last {
            Some(l) => {
                // K [m; r_s] = K [m; r] + K [0; r_s - r]: r_s differs from the
                // last answer's r only where a pair's relation changed, and a
                // product of few nonzeros sweeps no part's S in whole
                let dr: Vec<f64> = r_s.iter().zip(&l.r).map(|(a, b)| a - b).collect();
                let (mut k_m, mut k_r) = (l.k_m.clone(), l.k_r.clone());
                if dr.iter().any(|&d| d != 0.0) {
                    let (d_m, d_r) = self.apply(&vec![0.0; nm], &dr);
                    k_m.iter_mut().zip(d_m).for_each(|(k, d)| *k += d);
                    k_r.iter_mut().zip(d_r).for_each(|(k, d)| *k += d);
                }
                (Start { m: l.m.clone(), y0, k_m, k_r }, 0)
            }
            // where every pair deforms and the means have no factor, from
            // m = 0: the preconditioner is all of K
            None if self.k_mm.get().is_none() => {
                let m = vec![0.0; nm];
                let (k_m, k_r) = self.apply(&m, &r_s);
                (Start { m, y0, k_m, k_r }, 0)
            }
            None => {
                let k_mr_r = self.k_mr(&r_s);
                let m = self.solve_means(&b_m.iter().zip(&k_mr_r).map(|(b, k)| b - k).collect::<Vec<_>>());
                let (k_m, k_r) = self.apply(&m, &r_s);
                (Start { m, y0, k_m, k_r }, 1)
            }
        }
    }

    /// `K [0; e_i]` for each relative displacement `i` of `idx`: (its
    /// mean rows, its relative rows), from the parts that hold it alone.
    fn unit_products(&self, idx: &[usize]) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
        (idx.iter())
            .map(|&i| {
                let (mut k_m, mut k_r) = (vec![0.0; self.nm], vec![0.0; self.nr]);
                self.unit_column(&self.holders[i], |v, x| match v {
                    Var::M(j) => k_m[j] += x,
                    Var::R(j) => k_r[j] += x,
                });
                (k_m, k_r)
            })
            .unzip()
    }

    /// Each entry of K's column at a relative displacement held where
    /// `holders` says, handed to `add` (its unknown, its value): what W's
    /// columns and its diagonal are built from.
    fn unit_column(&self, holders: &[(usize, usize, f64)], mut add: impl FnMut(Var, f64)) {
        for &(q, u, c) in holders {
            let p = &self.parts[q];
            let nc = p.terms.len();
            for (tw, &s) in p.terms.iter().zip(&p.s[u * nc..(u + 1) * nc]) {
                for &(vw, cw) in &tw.vars[..tw.n] {
                    add(vw, c * cw * s);
                }
            }
        }
    }

    /// The relative rows of `K [t; 0]` for every column `t` of `ts`
    /// (over the means), each part's S applied to all of them at once.
    fn k_rm_many(&self, ts: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let (nr, k) = (self.nr, ts.len());
        let sweep = |parts: &[Local]| -> Vec<Vec<f64>> {
            let mut out = vec![vec![0.0; nr]; k];
            for p in parts {
                let nc = p.terms.len();
                let x = Mat::<f64>::from_fn(nc, k, |u, c| {
                    let t = &p.terms[u];
                    t.vars[..t.n]
                        .iter()
                        .map(|&(v, cv)| match v {
                            Var::M(j) => cv * ts[c][j],
                            Var::R(_) => 0.0,
                        })
                        .sum()
                });
                let mut y = Mat::<f64>::zeros(nc, k);
                matmul(
                    y.as_mut(),
                    Accum::Replace,
                    MatRef::from_column_major_slice(&p.s, nc, nc),
                    x.as_ref(),
                    1.0,
                    Par::Seq,
                );
                for (u, t) in p.terms.iter().enumerate() {
                    for &(v, cv) in &t.vars[..t.n] {
                        if let Var::R(j) = v {
                            for (c, o) in out.iter_mut().enumerate() {
                                o[j] += cv * y[(u, c)];
                            }
                        }
                    }
                }
            }
            out
        };
        let threads = if self.parts.len() < 2 * self.threads { 1 } else { self.threads };
        let mut sums = in_runs(&self.parts, threads, sweep).into_iter();
        let mut out = sums.next().unwrap_or_else(|| vec![vec![0.0; nr]; k]);
        for s in sums {
            out.iter_mut().zip(&s).for_each(|(a, b)| a.iter_mut().zip(b).for_each(|(a, b)| *a += b));
        }
        out
    }

    /// `W e_i = K_rr e_i - K_rm K_mm^-1 K_mr e_i` over r for each relative
    /// displacement `i` of `idx`: the substitutions through K_mm's factor
    /// all at once.
    fn w_columns_of(&self, idx: &[usize]) -> Vec<Vec<f64>> {
        let (k_m, mut k_r) = self.unit_products(idx);
        let Some(means) = self.means() else { return vec![vec![f64::NAN; self.nr]; idx.len()] };
        let t = means.solve_many(&k_m);
        for (w, kt) in k_r.iter_mut().zip(self.k_rm_many(&t)) {
            w.iter_mut().zip(kt).for_each(|(w, v)| *w -= v);
        }
        k_r
    }

    /// The free block of a solve, `Z^T W Z` with the friction law's and
    /// the junctions' rows, from W's entries or columns (what it lacks
    /// formed first, [`Sparse::form_w`]), factorised; None when they would
    /// take too much memory or the block is singular.
    fn exact_block(&self, free: &Free) -> Option<Preconditioner> {
        let n = free.fr.cols.len();
        if n == 0 || self.nm == 0 {
            return None;
        }
        let means = self.means()?;
        // W z only at the rows the block's equations read (its free rows,
        // the slipping pairs' normal rows, the junctions' with free
        // columns): the 86k tunnel's 289-333 of 31,725
        let rows = free.rows();
        let mut memory = self.w.lock().ok()?;
        let w = self.w_memory(&mut memory, means);
        let t = Instant::now();
        let formed = self.form_w(w, means, free.fr, &rows);
        self.add_split(|s| s.columns += t.elapsed().as_secs_f64());
        formed?;
        let mut e = vec![0.0; n];
        let mut a = Mat::<f64>::zeros(n, n);
        let mut wz = vec![0.0; self.nr];
        for (c, z) in free.fr.cols.iter().enumerate() {
            e[c] = 1.0;
            match w {
                WMemory::Columns(w) => w.times_at(z, &rows, &mut wz),
                WMemory::Entries(w) => w.times_at(z, &rows, &mut wz),
            }
            let col = free.operator(&e, &wz);
            e[c] = 0.0;
            col.iter().enumerate().for_each(|(i, &v)| a[(i, c)] = v);
        }
        let lu = a.partial_piv_lu();
        let probe = lu.solve(Mat::<f64>::from_fn(n, 1, |_, _| 1.0));
        (0..n).all(|i| probe[(i, 0)].is_finite()).then_some(Preconditioner::Exact(lu))
    }

    /// Forms what W lacks for a free block over `fr` that reads it at
    /// `rows`: the forward substitutions of the displacements there, or
    /// the whole columns at `fr`'s; None where keeping them would take
    /// more than [`w_columns::MAX_BYTES`].
    fn form_w(&self, w: &mut WMemory, means: &Means, fr: &Freedom, rows: &[usize]) -> Option<()> {
        match w {
            WMemory::Columns(w) => {
                for batch in w.missing(fr)?.chunks(W_BATCH) {
                    let cols = self.w_columns_of(batch);
                    w.add(batch, cols);
                }
            }
            WMemory::Entries(w) => {
                w.admit(&fr.cols).then_some(())?;
                self.forward_into(w, means, rows);
                w.form(rows, &fr.cols, self.threads);
                (w.bytes() <= w_columns::MAX_BYTES).then_some(())?;
            }
        }
        Some(())
    }

    /// W's memory, chosen at its first use: entries where `means`
    /// substitutes sparse columns, else whole columns.
    fn w_memory<'a>(&self, memory: &'a mut Option<WMemory>, means: &Means) -> &'a mut WMemory {
        memory.get_or_insert_with(|| match means.sparse_forward(&[]) {
            Some(_) => WMemory::Entries(WEntries::new(self.nr)),
            None => WMemory::Columns(WColumns::new(self.nr)),
        })
    }

    /// Keeps in `w` the forward substitutions of the displacements `idx`
    /// that lack one, in passes of at most [`W_DIAGONAL_BATCH`] spread
    /// over the threads (see [`Sparse::w_diagonal`]).
    fn forward_into(&self, w: &mut WEntries, means: &Means, idx: &[usize]) {
        let mut missing = w.missing(idx);
        if missing.is_empty() {
            return;
        }
        let forward = self.in_passes(means, &mut missing, |batch| means.sparse_forward(batch).unwrap_or_default());
        for (&a, x) in missing.iter().zip(forward) {
            w.add(a, x, self.relative_column(&self.holders[a]));
        }
    }

    /// The free block's factor of a solve under `lambda`: formed, or where
    /// every pair deforms the last one formed under the same load (its
    /// springs those of the solve it was formed for: the pairs that have
    /// changed state since are few, and GMRES corrects for them; the
    /// 86k-DOF tunnel's block took 68 s to factorise at every solve, in double
    /// precision and AMD order; 6.4 s now, [`SINGLE_BLOCK`]).
    fn free_block(&self, free: &Free, lambda: &[f64]) -> Arc<Preconditioner> {
        let fr = free.fr;
        if fr.deforming {
            if let Ok(kept) = self.kept.lock() {
                if let Some(k) = kept.as_ref().filter(|k| k.lambda == lambda && k.cols == fr.cols) {
                    return k.block.clone();
                }
            }
        }
        let whole = || fr.deforming.then(|| Preconditioner::whole(self, fr)).flatten();
        let block = Arc::new(self.exact_block(free).or_else(whole).unwrap_or_else(|| Preconditioner::new(self, fr)));
        if fr.deforming {
            if let Ok(mut kept) = self.kept.lock() {
                *kept = Some(Kept { lambda: lambda.to_vec(), cols: fr.cols.clone(), block: block.clone() });
            }
        }
        block
    }

    /// Counts a solve's GMRES `applications` (and the means'
    /// `substitutions`); where every pair deforms, forgets the kept factor
    /// after a solve of more than [`REFORM_AFTER`] applications: its
    /// springs are too far from these states'.
    fn count(&self, fr: &Freedom, applications: usize, substitutions: usize) {
        if let Ok(mut its) = self.iterations.lock() {
            its.push(applications + substitutions);
        }
        if fr.deforming && applications > REFORM_AFTER {
            if let Ok(mut kept) = self.kept.lock() {
                *kept = None;
            }
        }
    }

    /// Adds a solve's seconds to the split.
    fn add_split(&self, add: impl FnOnce(&mut Split)) {
        if let Ok(mut split) = self.split.lock() {
            add(&mut split);
        }
    }

    /// W's diagonal, `K_rr - K_rm K_mm^-1 K_mr`, at the relative
    /// displacements of `idx` that lack it: the pair stiffness the robust
    /// rule's friction Newton turns slips into forces with
    /// (`InterfaceProblem::stiffness`), the dense interface's. K_rr's own
    /// (the means held, so stiffer) sent the jointed tet10 tunnel
    /// (tests/geo/tunnel3d_joints_coarse.toml) down another Newton path
    /// from iteration 3, which cycled for 400 iterations where the dense
    /// interface converged in 38.
    ///
    /// Formed only where a pair's stiffness is read, a slipping pair's or an
    /// open one's that closes (`law::stiffness_in`): a few hundred of the tunnel's 31,704
    /// relative displacements, which all took the setup's longest stage.
    /// One forward substitution through K_mm's factor per displacement
    /// (`|L^-1 P K_mr e_i|^2`), those asked for together in passes of at
    /// most [`W_DIAGONAL_BATCH`], the passes spread over the threads. A
    /// column `K_mr e_i` is non-zero on the means of the one or two parts
    /// that hold the displacement alone ([`Sparse::holders`]), so a pass
    /// substitutes only the supernodes on its columns' paths to the root
    /// ([`crate::substructure::sparse_forward`]: the 1,000-block cube's
    /// diagonal 145 -> 22 s, docs/blocks.md). Gives W's diagonal at `idx`
    /// back.
    fn w_diagonal(&self, idx: &[usize]) -> Vec<f64> {
        let mut d = self.w_diag.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let mut missing: Vec<usize> = idx.iter().copied().filter(|&i| d[i].is_none()).collect();
        // (nothing missing forms no factor)
        let means = if missing.is_empty() { None } else { self.means() };
        if let Some(means) = means {
            let t = Instant::now();
            let lowered = self.lowered(means, &mut missing);
            // (K_mm's single-precision factor could lose a W far softer than
            // K_rr: that keeps K_rr's)
            for (&i, l) in missing.iter().zip(lowered) {
                let (k, w) = (self.k_rr[i], self.k_rr[i] - l);
                d[i] = Some(if w > 1e-6 * k { w } else { k });
            }
            self.add_split(|s| s.diagonal += t.elapsed().as_secs_f64());
        }
        idx.iter().map(|&i| d[i].unwrap_or(self.k_rr[i])).collect()
    }

    /// `(K_mr e_i)^T K_mm^-1 K_mr e_i` at each relative displacement of
    /// `missing` (deduplicated and sorted as [`Sparse::mean_columns`]
    /// does): from the forward substitutions W's entries keep, formed
    /// where they lack them (the exact block reads the same displacements
    /// and more), else by a pass of their own.
    fn lowered(&self, means: &Means, missing: &mut Vec<usize>) -> Vec<f64> {
        let mut memory = self.w.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let WMemory::Entries(w) = self.w_memory(&mut memory, means) {
            missing.sort_unstable();
            missing.dedup();
            if w.room(w.missing(missing).len()) {
                self.forward_into(w, means, missing);
                return missing.iter().map(|&i| w.energy(i)).collect();
            }
        }
        self.in_passes(means, missing, |batch| means.energies(batch, self.nm))
    }

    /// `pass` over the mean columns at the relative displacements
    /// `missing` ([`Sparse::mean_columns`], which sorts them), in passes of
    /// at most [`W_DIAGONAL_BATCH`] spread over the threads: one result
    /// per displacement, in `missing`'s order.
    fn in_passes<T: Send>(
        &self,
        means: &Means,
        missing: &mut Vec<usize>,
        pass: impl Fn(&[MeanColumn]) -> Vec<T> + Sync,
    ) -> Vec<T> {
        let k_m = self.mean_columns(means, missing);
        let per = missing.len().div_ceil(self.threads).min(W_DIAGONAL_BATCH);
        let batches: Vec<&[MeanColumn]> = k_m.chunks(per).collect();
        let threads = self.threads.min(batches.len()).max(1);
        let runs = in_runs(&batches, threads, |run| run.iter().flat_map(|batch| pass(batch)).collect::<Vec<T>>());
        runs.into_iter().flatten().collect()
    }

    /// The mean rows of K's columns at the relative displacements
    /// `missing`, each as its non-zeros; `missing` deduplicated and sorted
    /// as the columns are, by where their substitutions begin
    /// ([`Means::leaf`]), so that a batch's share a path through the factor.
    fn mean_columns(&self, means: &Means, missing: &mut Vec<usize>) -> Vec<MeanColumn> {
        missing.sort_unstable();
        missing.dedup();
        let mut cols: Vec<(usize, usize, MeanColumn)> = (missing.iter())
            .map(|&i| {
                let c = self.mean_column(&self.holders[i]);
                (means.leaf(&c), i, c)
            })
            .collect();
        cols.sort_by_key(|&(leaf, i, _)| (leaf, i));
        *missing = cols.iter().map(|&(_, i, _)| i).collect();
        cols.into_iter().map(|(_, _, c)| c).collect()
    }

    /// For each relative displacement, where the parts hold it: (part,
    /// its interface DOF, the coefficient of the displacement there).
    fn holders(&self) -> Vec<Vec<(usize, usize, f64)>> {
        let mut at = vec![Vec::new(); self.nr];
        for (q, p) in self.parts.iter().enumerate() {
            for (u, t) in p.terms.iter().enumerate() {
                for &(v, c) in &t.vars[..t.n] {
                    if let Var::R(i) = v {
                        at[i].push((q, u, c));
                    }
                }
            }
        }
        at
    }

    /// The mean rows of K's column at a relative displacement held where
    /// `holders` says: its non-zeros (mean, value), a mean's terms summed.
    fn mean_column(&self, holders: &[(usize, usize, f64)]) -> MeanColumn {
        self.sparse_column(holders, |v| if let Var::M(j) = v { Some(j) } else { None })
    }

    /// The relative rows of that column, likewise: K_rr's.
    fn relative_column(&self, holders: &[(usize, usize, f64)]) -> Vec<(usize, f64)> {
        self.sparse_column(holders, |v| if let Var::R(j) = v { Some(j) } else { None })
    }

    /// The rows `pick` numbers of K's column at a relative displacement
    /// held where `holders` says: (row, value), ascending, a row's terms
    /// summed.
    fn sparse_column(&self, holders: &[(usize, usize, f64)], pick: impl Fn(Var) -> Option<usize>) -> MeanColumn {
        let mut k = Vec::new();
        self.unit_column(holders, |v, x| {
            if let Some(j) = pick(v) {
                k.push((j, x));
            }
        });
        k.sort_unstable_by_key(|&(j, _)| j);
        k.dedup_by(|b, a| {
            let same = a.0 == b.0;
            if same {
                a.1 += b.1;
            }
            same
        });
        k
    }

    /// A place id for each of the `n` unknowns `index` numbers: the
    /// unknowns of the interface nodes that coincide there, and of the
    /// springs `with` that join them (a junction's, whose copies may share
    /// no unknown where a support holds them).
    fn places(&self, index: impl Fn(Var) -> Option<usize>, n: usize, with: &[(Vec<usize>, Vec<f64>)]) -> Vec<usize> {
        let mut sets = UnionFind::new(n);
        for p in &self.parts {
            for node in p.terms.chunks(self.nd.max(1)) {
                let mut vars = node.iter().flat_map(|t| t.vars[..t.n].iter().filter_map(|&(v, _)| index(v)));
                let Some(first) = vars.next() else { continue };
                vars.for_each(|v| sets.join(first, v));
            }
        }
        for (xs, _) in with {
            if let Some((&first, rest)) = xs.split_first() {
                rest.iter().for_each(|&x| sets.join(first, x));
            }
        }
        (0..n).map(|v| sets.root(v)).collect()
    }

    /// The diagonal of `K_rr`, one sweep per part.
    fn diagonal_r(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.nr];
        for p in &self.parts {
            let nc = p.terms.len();
            for (u, tu) in p.terms.iter().enumerate() {
                for (v, tv) in p.terms.iter().enumerate() {
                    for &(i, ci) in &tu.vars[..tu.n] {
                        for &(j, cj) in &tv.vars[..tv.n] {
                            if let (Var::R(a), Var::R(b)) = (i, j) {
                                if a == b {
                                    d[a] += ci * cj * p.s[u + v * nc];
                                }
                            }
                        }
                    }
                }
            }
        }
        d
    }
}

impl Solver for Sparse {
    fn solve(&self, fr: &Freedom, states: &[ContactState], lambda: &[f64], accuracy: Accuracy) -> Option<Answer> {
        let (nm, nr) = (self.nm, self.nr);
        let mut b = combine(&self.b, &self.b_fixed, lambda);
        fr.push(&mut b[nm..]);
        let (b_m, b_r) = b.split_at(nm);
        let free = Free { fr, nr };
        let t = Instant::now();
        let (Start { m: m_s, y0, k_m, k_r }, substitutions) = self.start(&free, b_m);
        // what the equations lack at the start: the means' rows, then the free ones
        let known: Vec<f64> = b_r.iter().zip(&k_r).map(|(b, k)| b - k).collect();
        let mut rhs0: Vec<f64> = b_m.iter().zip(&k_m).map(|(b, k)| b - k).collect();
        rhs0.extend(free.rhs(&known, &y0));
        self.add_split(|s| s.start += t.elapsed().as_secs_f64());
        // GMRES's last product (x, K's rows): its answer's ([`answer_product`])
        let last_product = RefCell::new(None);
        let a = |x: &[f64]| {
            let (dm, dy) = x.split_at(nm);
            let (mut out, k_r) = self.apply(dm, &free.expand(dy));
            let ops = free.operator(dy, &k_r);
            *last_product.borrow_mut() = Some((x.to_vec(), out.clone(), k_r));
            out.extend(ops);
            out
        };
        // P = [K_mm, K_mr Z; 0, Z^T K_rr Z]: y from the second row, then the means
        let t = Instant::now();
        let schur = self.free_block(&free, lambda);
        let factor_s = t.elapsed().as_secs_f64();
        let means_s = Cell::new(0.0);
        let precondition = |v: &[f64]| {
            if let Preconditioner::Whole(f) = &*schur {
                return f.solve(v);
            }
            let (v_m, v_y) = v.split_at(nm);
            let dy = schur.apply(v_y);
            let k_mr_z = self.k_mr(&free.expand(&dy));
            let t = Instant::now();
            let mut out = self.solve_means(&v_m.iter().zip(&k_mr_z).map(|(v, k)| v - k).collect::<Vec<_>>());
            means_s.set(means_s.get() + t.elapsed().as_secs_f64());
            out.extend(dy);
            out
        };
        let scale = length(&b).max(length(&rhs0)).max(f64::MIN_POSITIVE);
        let loose = self.last_states.loose(states) && accuracy.may_be_loose();
        let (mut tolerance, looser) = tolerance(loose, accuracy, scale);
        if loose && !matches!(*schur, Preconditioner::Exact(_)) {
            tolerance = tolerance.max(LOOSE_REDUCTION * length(&rhs0));
        }
        let t = Instant::now();
        let (dx, conv) = gmres::solve(a, precondition, &rhs0, target(tolerance, scale), RESTART, MAX_ITERATIONS);
        self.add_split(|s| {
            s.factor += factor_s;
            s.gmres += t.elapsed().as_secs_f64();
            s.means += means_s.get();
        });
        self.count(fr, conv.iterations, substitutions);

        let residual = conv.residual / scale;
        // (a NaN residual is no answer either)
        if !conv.converged && !(residual <= USABLE) {
            return None;
        }
        let (dm, dy) = dx.split_at(nm);
        let mut m: Vec<f64> = m_s.iter().zip(dm).map(|(a, b)| a + b).collect();
        let y: Vec<f64> = y0.iter().zip(dy).map(|(a, b)| a + b).collect();
        let mut r = fr.r0.clone();
        r.iter_mut().zip(free.expand(&y)).for_each(|(v, e)| *v += e);
        let t = Instant::now();
        let known = answer_product(last_product.into_inner(), &dx, (&k_m, &k_r));
        let (k_m, k_r) = self.refine_means(&mut m, &r, (b_m, scale), known);
        self.add_split(|s| s.refine += t.elapsed().as_secs_f64());
        let residual_r = k_r.iter().zip(b_r).map(|(k, b)| k - b).collect();
        if !residual.is_finite() || m.iter().chain(&r).any(|v| !v.is_finite()) {
            return None;
        }
        if let Ok(mut last) = self.last.lock() {
            *last = Some(Arc::new(Last { m: m.clone(), r: r.clone(), k_m, k_r: k_r.clone() }));
        }

        Some(Answer { m, r, residual_r, residual, accuracy: conv.residual, loose, inexact: looser && !loose })
    }

    fn diagonal(&self, r: usize) -> f64 {
        self.w_diagonal(&[r])[0]
    }

    fn prepare_diagonal(&self, rs: &[usize]) {
        self.w_diagonal(rs);
    }

    fn counts(&self) -> Vec<usize> {
        self.iterations.lock().map(|v| v.clone()).unwrap_or_default()
    }

    fn split(&self) -> Option<Split> {
        self.split.lock().ok().map(|s| s.clone())
    }

    fn warm_start(&self) -> WarmStart {
        keep_start(&self.last, &self.last_states)
    }

    /// Forgets the free block's factor kept where every pair deforms: the
    /// next solve forms it afresh with the springs of the states it starts
    /// from, so that a trial started from a state that held takes the same
    /// path whatever was solved in between. A fresh factor for each trial
    /// also serves its solves better than one formed trials before: the 3D
    /// slope with both searches (docs/safety.md) took 5,676 GMRES
    /// applications in all where it took 8,027 with each held state
    /// keeping its factor, which also kept 145 MB more (12 % of the peak).
    fn start_from(&self, start: &WarmStart) {
        give_start(start, &self.last, &self.last_states);
        if let Ok(mut kept) = self.kept.lock() {
            *kept = None;
        }
    }
}

/// A solve's answer kept for the next: the means, the relative
/// displacements and `K [m; r]` (mean rows, relative rows).
struct Last {
    m: Vec<f64>,
    r: Vec<f64>,
    k_m: Vec<f64>,
    k_r: Vec<f64>,
}

/// Where a solve starts: the means, the free unknowns and `K [m; r]` at
/// the relative displacements they make.
struct Start {
    m: Vec<f64>,
    y0: Vec<f64>,
    k_m: Vec<f64>,
    k_r: Vec<f64>,
}

/// The free directions of one solve: `Z` and the friction law's rows on them.
struct Free<'f> {
    fr: &'f Freedom,
    nr: usize,
}

impl Free<'_> {
    /// `Z y` over r.
    fn expand(&self, y: &[f64]) -> Vec<f64> {
        let mut v = vec![0.0; self.nr];
        for (col, &yc) in self.fr.cols.iter().zip(y) {
            for &(i, z) in col {
                v[i] += z * yc;
            }
        }
        v
    }

    /// `Z^T v`.
    fn restrict(&self, v: &[f64]) -> Vec<f64> {
        self.fr.cols.iter().map(|col| col.iter().map(|&(i, z)| z * v[i]).sum()).collect()
    }

    /// `Z^T w` with the friction law's terms on the free rows: the coupling
    /// of a slipping row to its normal force, the springs of the slip
    /// direction, the junctions' springs and the lift of their implicit
    /// pressures (`w = W Z y`).
    fn operator(&self, y: &[f64], w: &[f64]) -> Vec<f64> {
        let fr = self.fr;
        let mut out = self.restrict(w);
        for s in &fr.slips {
            let i = fr.pos[s.row];
            if let (Some(rn), true) = (s.normal, s.coupling != 0.0) {
                out[i] += s.coupling * w[rn];
            }
            out[i] += s.springs.iter().map(|&(rc, k)| k * y[fr.pos[rc]]).sum::<f64>();
        }
        // (a junction without free columns adds nothing: 2,047 of the 86k
        // tunnel's, each lift a product, at each of the exact block's columns)
        for jb in fr.junctions.iter().filter(|jb| !jb.cols.is_empty()) {
            let lifted = jb.lifted(|i| w[i], y);
            for (a, fa) in jb.cols.clone().enumerate() {
                out[fa] += jb.cols.clone().enumerate().map(|(c, fc)| jb.kz[(a, c)] * y[fc]).sum::<f64>()
                    + lifted.as_ref().map_or(0.0, |l| l[a]);
            }
        }
        out
    }

    /// The rows of r that [`Free::operator`] reads, ascending.
    fn rows(&self) -> Vec<usize> {
        let fr = self.fr;
        let mut rows: Vec<usize> = (fr.cols.iter().flatten().map(|&(i, _)| i))
            .chain(fr.slips.iter().filter_map(|s| s.normal))
            .chain(
                fr.junctions.iter().filter(|jb| jb.lift.is_some() && !jb.cols.is_empty()).flat_map(|jb| jb.r.clone()),
            )
            .collect();
        rows.sort_unstable();
        rows.dedup();
        rows
    }

    /// The right-hand side less `A y0`, from `known = c - W (r0 + Z y0)`:
    /// what the free rows lack at `y0`.
    fn rhs(&self, known: &[f64], y0: &[f64]) -> Vec<f64> {
        let fr = self.fr;
        let mut rhs = self.restrict(known);
        for s in &fr.slips {
            let i = fr.pos[s.row];
            rhs[i] -= s.force + s.springs.iter().map(|&(rc, k)| k * y0[fr.pos[rc]]).sum::<f64>();
            if let (Some(rn), true) = (s.normal, s.coupling != 0.0) {
                rhs[i] += s.coupling * known[rn];
            }
        }
        for jb in fr.junctions.iter().filter(|jb| !jb.cols.is_empty()) {
            let lifted = jb.lifted(|i| -known[i], y0);
            for (a, fa) in jb.cols.clone().enumerate() {
                rhs[fa] -= jb.fz[a]
                    + jb.cols.clone().enumerate().map(|(c, fc)| jb.kz[(a, c)] * y0[fc]).sum::<f64>()
                    + lifted.as_ref().map_or(0.0, |l| l[a]);
            }
        }
        rhs
    }
}

/// The free block of the preconditioner, `A_yy`: the Schur complement's
/// own, or where W's columns would take too much memory `M = Z^T K_rr Z`
/// with the springs of the slipping pairs and junctions (symmetric; the
/// coupling to the normal force left out), factorised (in single precision
/// where every pair deforms, [`SINGLE_BLOCK`]); its diagonal when that
/// factorisation fails.
enum Preconditioner {
    /// The whole free block, from W ([`Sparse::exact_block`]).
    Exact(PartialPivLu<f64>),
    Factor(Cholesky),
    /// `M` where every pair deforms.
    Single(Box<SingleCholesky>),
    /// All of K over `[m; y]` with the springs where every pair deforms
    /// ([`Preconditioner::whole`]): applied to the whole residual.
    Whole(Box<Sides>),
    Diagonal(Vec<f64>),
}

impl Preconditioner {
    /// `M` over the free columns of `fr`, factorised; see the type.
    fn new(sp: &Sparse, fr: &Freedom) -> Preconditioner {
        let n = fr.cols.len();
        if n == 0 {
            return Preconditioner::Diagonal(Vec::new());
        }
        let entries = Preconditioner::entries(sp, fr);
        Preconditioner::factor(&lower_from_entries(n, entries), fr.deforming, sp.threads)
    }

    /// Where every pair deforms, the whole of `K` with the springs over
    /// `[m; r]`, factorised in single precision through the sides' DOFs
    /// ([`super::sides`]): the preconditioner then leaves GMRES only the
    /// slipping pairs' unsymmetric terms and the springs of pairs that
    /// changed state since it was formed to mend. None where a free
    /// column is not one relative displacement, or the sides do not
    /// factorise.
    fn whole(sp: &Sparse, fr: &Freedom) -> Option<Preconditioner> {
        let nm = sp.nm;
        let n = nm + fr.cols.len();
        let mut col_of = vec![usize::MAX; sp.nr];
        for (c, col) in fr.cols.iter().enumerate() {
            // (a junction's columns list its zeros)
            let mut on = col.iter().filter(|e| e.1 != 0.0);
            match (on.next(), on.next()) {
                (Some(&(i, z)), None) if z == 1.0 && col_of[i] == usize::MAX => col_of[i] = nm + c,
                _ => return None,
            }
        }
        let index = |v: Var| match v {
            Var::M(i) => Some(i),
            Var::R(i) => (col_of[i] != usize::MAX).then_some(col_of[i]),
        };
        let springs = springs(fr, nm, true);
        let place_of = sp.places(index, n, &springs);
        let parts: Vec<(&[f64], &[Terms])> = sp.parts.iter().map(|p| (&p.s[..], &p.terms[..])).collect();
        let sides = Sides::new(&parts, sp.own.as_deref(), index, n, &springs, &place_of, (sp.nd, sp.threads))?;
        Some(Preconditioner::Whole(Box::new(sides)))
    }

    /// The lower triangle's entries (row, column, value) of `Z^T K_rr Z`
    /// with the springs of the slipping pairs and junctions.
    fn entries(sp: &Sparse, fr: &Freedom) -> Vec<(usize, usize, f64)> {
        let n = fr.cols.len();
        let mut cols_of: Vec<Vec<(usize, f64)>> = vec![Vec::new(); sp.nr];
        for (c, col) in fr.cols.iter().enumerate() {
            for &(i, z) in col {
                cols_of[i].push((c, z));
            }
        }
        let mut entries: Vec<(usize, usize, f64)> = Vec::new();
        let mut free: Vec<(usize, usize, f64)> = Vec::new(); // (local DOF, local column, coefficient)
                                                             // the part's free columns, and each column's place among them
        let (mut local, mut place) = (Vec::new(), vec![usize::MAX; n]);
        let mut block = Vec::new();
        for p in &sp.parts {
            free.clear();
            for (u, t) in p.terms.iter().enumerate() {
                for &(v, c) in &t.vars[..t.n] {
                    if let Var::R(i) = v {
                        for &(col, z) in &cols_of[i] {
                            if place[col] == usize::MAX {
                                place[col] = local.len();
                                local.push(col);
                            }
                            free.push((u, place[col], c * z));
                        }
                    }
                }
            }
            // Z_p^T S_p Z_p over the part's free columns, then its lower
            // triangle: one entry per pair of columns, not per pair of the
            // terms they touch (the 1,000-block cube: 0.3 million entries
            // per solve instead of 1.5, 0.03 s instead of 0.14)
            let (nc, nf) = (p.terms.len(), local.len());
            block.clear();
            block.resize(nf * nf, 0.0);
            for &(u, a, x) in &free {
                for &(v, b, y) in &free {
                    block[a + b * nf] += x * y * p.s[u + v * nc];
                }
            }
            for (a, &ca) in local.iter().enumerate() {
                for (b, &cb) in local.iter().enumerate() {
                    if ca >= cb {
                        entries.push((ca, cb, block[a + b * nf]));
                    }
                }
            }
            for &c in &local {
                place[c] = usize::MAX;
            }
            local.clear();
        }
        for (dofs, ke) in springs(fr, 0, false) {
            let m = dofs.len();
            for (b, &col) in dofs.iter().enumerate() {
                for (a, &row) in dofs.iter().enumerate() {
                    if row >= col {
                        entries.push((row, col, ke[a * m + b]));
                    }
                }
            }
        }
        entries
    }

    /// `m` factorised: in single precision where every pair deforms
    /// ([`SINGLE_BLOCK`]), else in double; its diagonal where neither holds.
    fn factor(m: &SymMatrix, deforming: bool, threads: usize) -> Preconditioner {
        let n = m.n;
        if deforming {
            // every relative displacement free: 33,823 of them on the 86k
            // tunnel, its block 28 million entries
            let ordering = if n >= SINGLE_BLOCK { Ordering::NestedDissection } else { Ordering::Amd };
            let each: Vec<usize> = (0..n).collect();
            if let Ok(f) = SingleCholesky::factor(m, &each, ordering, threads) {
                return Preconditioner::Single(Box::new(f));
            }
        }
        match Cholesky::factor(m) {
            Ok(f) => Preconditioner::Factor(f),
            Err(_) => Preconditioner::Diagonal((0..n).map(|i| m.get(i, i)).collect()),
        }
    }

    fn apply(&self, v: &[f64]) -> Vec<f64> {
        match self {
            Preconditioner::Exact(lu) => {
                let x = lu.solve(Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]));
                (0..v.len()).map(|i| x[(i, 0)]).collect()
            }
            Preconditioner::Factor(f) => {
                let mut x = v.to_vec();
                f.solve(&mut x);
                x
            }
            Preconditioner::Single(f) => f.solve(v),
            Preconditioner::Whole(f) => f.solve(v),
            Preconditioner::Diagonal(d) => v.iter().zip(d).map(|(x, d)| if *d > 0.0 { x / d } else { *x }).collect(),
        }
    }
}

/// The springs of the slipping pairs and of the junctions, each a small
/// dense matrix (row-major) at its unknowns, the free columns numbered
/// from `off`. As they are, a slipping pair's coupling to its normal force
/// halved into both triangles (the free block M's). `positive` for a
/// factor that must stay positive definite (the sides' factor,
/// [`Preconditioner::whole`]): a slipping pair's own springs without the
/// coupling, and each junction's [`positive_part`]. The coupling, and a
/// slipping junction's friction rows, made the whole indefinite once pairs
/// slipped: blocks3d_stiff's second step could not be factorised (not
/// positive definite even shifted by 1e-2 of its diagonal) and was
/// preconditioned by the free block alone, 2,900 GMRES applications where
/// GMRES now corrects for what is left out.
fn springs(fr: &Freedom, off: usize, positive: bool) -> Vec<(Vec<usize>, Vec<f64>)> {
    let mut out = Vec::new();
    for s in &fr.slips {
        let i = fr.pos[s.row];
        for &(rc, k) in &s.springs {
            let j = fr.pos[rc];
            if i == j {
                out.push((vec![off + i], vec![k]));
            } else if !positive {
                out.push((vec![off + i, off + j], vec![0.0, 0.5 * k, 0.5 * k, 0.0]));
            }
        }
    }
    for jb in &fr.junctions {
        let dofs: Vec<usize> = jb.cols.clone().map(|c| off + c).collect();
        let m = dofs.len();
        if m == 0 {
            // (a junction whose every row is tied has no springs: the
            // fallback of a 3D slope's step 3 met one, docs/corpus.md)
            continue;
        }
        let kz = if positive { positive_part(&jb.kz) } else { jb.kz.clone() };
        out.push((dofs, (0..m * m).map(|e| kz[(e / m, e % m)]).collect()));
    }
    out
}

/// The symmetric part of `k` with its negative eigenvalues dropped: the
/// nearest positive semi-definite matrix to it (in the Frobenius norm).
/// An empty `k` (a junction whose rows are all tied) is its own: nalgebra
/// panics on it ("Unable to compute the symmetric tridiagonal
/// decomposition of an empty matrix", the fallback of a 3D slope's step 3:
/// docs/corpus.md). Where the eigen-decomposition does not converge
/// ([`crate::fem::bounded`]), the diagonal's positive part.
fn positive_part(k: &nalgebra::DMatrix<f64>) -> nalgebra::DMatrix<f64> {
    if k.is_empty() {
        return k.clone();
    }
    let sym = (k + k.transpose()) * 0.5;
    match crate::fem::bounded::symmetric_eigen(sym.clone()) {
        Some(e) => {
            let kept = e.eigenvalues.map(|l| l.max(0.0));
            &e.eigenvectors * nalgebra::DMatrix::from_diagonal(&kept) * e.eigenvectors.transpose()
        }
        None => nalgebra::DMatrix::from_diagonal(&sym.diagonal().map(|d| d.max(0.0))),
    }
}

/// The lower triangle of an `n x n` symmetric matrix from (row >= col,
/// col, value) entries, repeated ones summed; every diagonal entry present.
pub(super) fn lower_from_entries(n: usize, entries: Vec<(usize, usize, f64)>) -> SymMatrix {
    // bucketed by column, then each column sorted by row (a sort of all
    // the entries at once took 0.012 s of a 0.02 s preconditioner on the
    // 512-block cube); a column's bucket starts with its diagonal
    let mut start = vec![0usize; n + 1];
    for &(_, c, _) in &entries {
        start[c + 1] += 1;
    }
    for c in 0..n {
        start[c + 1] += start[c] + 1;
    }
    let mut next = start.clone();
    let mut bucket = vec![(0usize, 0.0f64); start[n]];
    for c in 0..n {
        bucket[next[c]] = (c, 0.0);
        next[c] += 1;
    }
    for (r, c, v) in entries {
        bucket[next[c]] = (r, v);
        next[c] += 1;
    }
    let mut col_ptr = vec![0usize; n + 1];
    let (mut row_idx, mut values): (Vec<usize>, Vec<f64>) =
        (Vec::with_capacity(bucket.len()), Vec::with_capacity(bucket.len()));
    for c in 0..n {
        let column = &mut bucket[start[c]..start[c + 1]];
        column.sort_by_key(|&(r, _)| r);
        for &(r, v) in column.iter() {
            if row_idx.len() > col_ptr[c] && row_idx.last() == Some(&r) {
                *values.last_mut().expect("a value") += v;
            } else {
                row_idx.push(r);
                values.push(v);
            }
        }
        col_ptr[c + 1] = row_idx.len();
    }
    SymMatrix { n, col_ptr, row_idx, values }
}

/// The factor of `K_mm`: single precision where it holds (it only
/// preconditions: the solve's residual is taken with K itself), double
/// where single precision is too coarse for it (`||K x - b|| / ||b||` above
/// 1e-3 on a test vector: K_mm far from well-conditioned) or breaks down.
///
/// Its unknowns may be more than the means, the means first: K_b's, the
/// bonded model's ([`super::means_whole`]), whose interiors a right-hand
/// side is zero on and an answer is not read at.
enum Means {
    Single(SingleCholesky),
    Double(PartialCholesky, usize),
}

impl Means {
    fn factor(k: &SymMatrix, node_of: &[usize], ordering: Ordering, threads: usize) -> Option<Means> {
        if let Ok(f) = SingleCholesky::factor(k, node_of, ordering, threads) {
            // the test vector: K times a smooth field of ones
            let x: Vec<f64> = (0..k.n).map(|i| 1.0 + 0.5 * (i as f64 * 0.01).sin()).collect();
            let b = k.mul(&x);
            let err = k.mul(&f.solve(&b)).iter().zip(&b).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
            if err <= SINGLE_ACCURACY * length(&b) {
                return Some(Means::Single(f));
            }
        }
        PartialCholesky::factor(k, k.n, node_of, ordering, faer::Par::Seq).ok().map(|f| Means::Double(f, k.n))
    }

    /// The factor's unknowns.
    fn n(&self) -> usize {
        match self {
            Means::Single(f) => f.n(),
            Means::Double(_, n) => *n,
        }
    }

    /// `K_mm^-1` of every column of `bs`, in one pass through the factor.
    fn solve_many(&self, bs: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let (nm, n) = (bs.first().map_or(0, Vec::len), self.n());
        let padded: Vec<Vec<f64>> = bs.iter().map(|b| pad(b, n)).collect();
        let mut xs = match self {
            Means::Single(f) => f.solve_many(&padded),
            Means::Double(f, _) => {
                let mut x: Vec<f64> = padded.concat();
                f.solve_many(&mut x, bs.len());
                x.chunks_exact(n.max(1)).take(bs.len()).map(<[f64]>::to_vec).collect()
            }
        };
        xs.iter_mut().for_each(|x| x.truncate(nm));
        xs
    }

    /// `b^T K_mm^-1 b` of every column of `bs`, each given by its
    /// non-zeros (mean, value; `n` means in all): the forward substitution alone, through
    /// the supernodes the columns reach, where the factor allows it.
    fn energies(&self, bs: &[MeanColumn], n: usize) -> Vec<f64> {
        if let Means::Single(f) = self {
            if let Some(e) = f.sparse_energies(bs) {
                return e;
            }
        }
        let dense: Vec<Vec<f64>> = (bs.iter())
            .map(|c| {
                let mut b = vec![0.0; n];
                c.iter().for_each(|&(j, v)| b[j] += v);
                b
            })
            .collect();
        let t = self.solve_many(&dense);
        dense.iter().zip(&t).map(|(a, b)| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>()).collect()
    }

    /// Each column's forward substitution and its factor
    /// ([`SingleCholesky::sparse_forward`]); None where the factor allows
    /// no sparse substitution.
    fn sparse_forward(&self, bs: &[MeanColumn]) -> Option<Vec<(Forward, f64)>> {
        match self {
            Means::Single(f) => f.sparse_forward(bs),
            Means::Double(..) => None,
        }
    }

    /// Where the substitution of a column with the non-zeros `b` begins
    /// (its lowest supernode): what [`Sparse::mean_columns`] sorts by.
    fn leaf(&self, b: &[(usize, f64)]) -> usize {
        match self {
            Means::Single(f) => f.leaf(b.iter().map(|&(j, _)| j)),
            Means::Double(..) => 0,
        }
    }

    fn solve(&self, v: &[f64]) -> Vec<f64> {
        let mut x = match self {
            Means::Single(f) => f.solve(&pad(v, f.n())),
            Means::Double(f, n) => {
                let mut x = pad(v, *n);
                f.solve_many(&mut x, 1);
                x
            }
        };
        x.truncate(v.len());
        x
    }
}

/// `K [m; r]` at a solve's answer, `[m_s + dm; r_s + Z dy]`, from the
/// start's (`at_start`, mean and relative rows) and GMRES's `last`
/// product (its x, its mean and relative rows): `K [m_s; r_s] + K [dm; Z
/// dy]`, where that x is the answer `dx` times a power of two, as GMRES's
/// last product is. It saves the refinement one product with every S
/// (the 86k tunnel's 14 solves: 0.25 s).
fn answer_product(
    last: Option<(Vec<f64>, Vec<f64>, Vec<f64>)>,
    dx: &[f64],
    at_start: (&[f64], &[f64]),
) -> Option<(Vec<f64>, Vec<f64>)> {
    let (x, p_m, p_r) = last?;
    let t = power_of_two(&x, dx)?;
    let add = |k: &[f64], p: Vec<f64>| k.iter().zip(p).map(|(k, p)| k + p / t).collect::<Vec<f64>>();
    Some((add(at_start.0, p_m), add(at_start.1, p_r)))
}

/// The power of two `t` with `x = t y` to the last bit, where there is one
/// (and `y` is not zero).
fn power_of_two(x: &[f64], y: &[f64]) -> Option<f64> {
    let (a, b) = x.iter().zip(y).find(|(_, &b)| b != 0.0)?;
    let t = a / b;
    let exact = t.is_finite() && t > 0.0 && t == 2f64.powi(t.log2().round() as i32);
    (exact && x.len() == y.len() && x.iter().zip(y).all(|(a, b)| *a == t * b)).then_some(t)
}

/// `v` with zeros after it to `n` entries (an interior's right-hand side).
fn pad(v: &[f64], n: usize) -> Vec<f64> {
    let mut p = v.to_vec();
    p.resize(n.max(v.len()), 0.0);
    p
}

/// A part's S (column-major) and loads in the pairs' frames.
type Localised = (Vec<f64>, Vec<Vec<f64>>);

/// Each dense part's S and loads in the pairs' frames, in threads; and
/// with the parts' `own` stiffness K_mm's factor in a thread of its own
/// beside them (one thread's work: 0.9 s of the 86k tunnel's, and the S
/// 0.29 s in one).
fn localise_and_factor(
    dense: &[(&[f64], &OperatorRef, &PartMap)],
    own: Option<&Vec<Own>>,
    node_of: &[usize],
    nd: usize,
    threads: usize,
) -> (Vec<Localised>, Option<Option<Means>>) {
    std::thread::scope(|scope| {
        let factor = own.map(|own| {
            let terms: Vec<&[Terms]> = dense.iter().map(|(_, _, map)| &map.terms[..]).collect();
            scope.spawn(move || bonded_factor(own, &terms, node_of, nd, threads))
        });
        let localised = in_threads(dense, threads, |(s, part, map)| localise(s, part.g, nd, &map.frames, &map.edges));
        (localised, factor.map(|f| f.join().unwrap_or_else(|e| std::panic::resume_unwind(e))))
    })
}

/// Whether K_mm is factorised through the bonded model of the parts'
/// own stiffness ([`super::means_whole`]) rather than from the parts'
/// cliques of means: where the cliques would hold [`BONDED_PAYS`] times
/// the parts' own entries or more. The entries are counted from the
/// mesh, not formed: the cubes below, which do not take K_b, formed them
/// for nothing (the 64 blocks' 8.9 million).
fn bonded_pays(model: &Model, dense: &[(&[f64], &OperatorRef, &PartMap)], threads: usize) -> bool {
    let cliques: f64 = (dense.iter())
        .map(|(_, _, map)| {
            let m = clique(&map.terms).len() as f64;
            m * (m + 1.0) / 2.0
        })
        .sum();
    let entries: usize = in_threads(dense, threads, |(_, part, _)| Own::count(model, part.part)).into_iter().sum();
    cliques >= BONDED_PAYS * entries as f64
}

/// Measured (cliques / own entries, and K_b's factor against the
/// cliques' K_mm's): the 86k tunnel 6.4 (34.5 against 72.8 million
/// values, its run 10.6 -> 7.2 s); the cubes of make bench-blocks, 64
/// blocks 4.0 (147 against 105 million), 512 blocks 1.8 (57 against 54),
/// 1,000 blocks 1.9 (146 against 149), each 5-11 % slower with K_b.
/// Between 4.0 and 6.4, a quarter from each.
const BONDED_PAYS: f64 = 5.0;

/// K_mm's factor through the bonded model ([`super::means_whole`]) of the
/// parts' `own` stiffness and the `terms` of their interface DOFs.
fn bonded_factor(own: &[Own], terms: &[&[Terms]], mean_node: &[usize], nd: usize, threads: usize) -> Option<Means> {
    let (k, node_of) = means_whole::bonded(own, terms, mean_node);
    Means::factor(&k, &node_of, Ordering::choose(k.n, nd), threads)
}

/// How close a single-precision factor of K_mm must come on its test
/// vector to be kept (the 512-block cube: 2.7e-5).
const SINGLE_ACCURACY: f64 = 1e-3;

/// `K_mm`, sparse: a clique of means per part.
fn means_matrix(parts: &[Local], nm: usize) -> SymMatrix {
    let means = |v: Var| match v {
        Var::M(i) => Some(i),
        Var::R(_) => None,
    };
    let cliques: Vec<Vec<usize>> = parts.iter().map(|p| clique(&p.terms)).collect();
    let mut k = SymMatrix::from_cliques(nm, &cliques);
    let mut scratch = CliqueScratch::new(nm);
    for p in parts {
        add_clique(&mut k, &p.s, &p.terms, means, &mut scratch);
    }
    k
}

/// The means a part's interface DOFs (`terms`) reach, ascending: its
/// clique in K_mm.
fn clique(terms: &[Terms]) -> Vec<usize> {
    let mut c: Vec<usize> = (terms.iter())
        .flat_map(|t| t.vars[..t.n].iter().filter_map(|&(v, _)| if let Var::M(i) = v { Some(i) } else { None }))
        .collect();
    c.sort_unstable();
    c.dedup();
    c
}

/// A node id per mean (a lone pair, a junction or a join), for nested
/// dissection to keep a node's means together.
fn mean_nodes(layout: &Layout) -> Vec<usize> {
    let mut node = vec![0; layout.nm];
    let mut id = 0;
    let mut mark = |ms: &mut dyn Iterator<Item = usize>| {
        for m in ms {
            node[m] = id;
        }
        id += 1;
    };
    for (ax, j) in layout.axes.iter().zip(&layout.in_junction) {
        if j.is_none() {
            mark(&mut ax.iter().filter_map(|a| a.m()));
        }
    }
    for jn in &layout.junctions {
        mark(&mut jn.m.iter().copied());
    }
    for ax in &layout.joins {
        mark(&mut ax.iter().filter_map(|a| a.m()));
    }
    node
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A junction's springs as the sides' factor takes them: a symmetric
    /// positive definite block unchanged; an unsymmetric, indefinite one
    /// (a slipping junction's friction rows) symmetrised with its negative
    /// eigenvalue dropped.
    /// GMRES's last product is taken for its answer's only where its x is
    /// the answer times a power of two to the last bit.
    #[test]
    fn a_product_is_reused_only_at_a_power_of_two_of_the_answer() {
        let y = [0.0, 1.5, -3.25e-200, 7.0];
        let times = |t: f64| y.iter().map(|v| v * t).collect::<Vec<f64>>();
        assert_eq!(power_of_two(&times(1.0), &y), Some(1.0));
        assert_eq!(power_of_two(&times(2f64.powi(-40)), &y), Some(2f64.powi(-40)));
        assert_eq!(power_of_two(&times(3.0), &y), None);
        let mut off = times(4.0);
        off[3] = f64::from_bits(off[3].to_bits() + 1);
        assert_eq!(power_of_two(&off, &y), None, "one bit apart");
        assert_eq!(power_of_two(&times(-2.0), &y), None);
        assert_eq!(power_of_two(&[0.0; 4], &[0.0; 4]), None);
        assert_eq!(power_of_two(&times(1.0)[..3], &y), None, "another length");
    }

    #[test]
    fn an_empty_junction_block_is_its_own_positive_part() {
        let empty = nalgebra::DMatrix::<f64>::zeros(0, 0);
        assert_eq!(positive_part(&empty).shape(), (0, 0));
    }

    #[test]
    fn a_junctions_springs_keep_only_their_positive_part() {
        let spd = nalgebra::DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 1.0, 3.0]);
        assert!((positive_part(&spd) - &spd).amax() < 1e-12);
        // symmetric part [[1, 2], [2, 1]]: eigenvalues 3 (along (1, 1)) and -1
        let k = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 3.0, 1.0, 1.0]);
        let p = positive_part(&k);
        let expected = nalgebra::DMatrix::from_row_slice(2, 2, &[1.5, 1.5, 1.5, 1.5]);
        assert!((&p - expected).amax() < 1e-12, "{p}");
        assert!(p.symmetric_eigenvalues().min() > -1e-12);
    }

    /// The lower entries of a chain of `n` unit springs, each unknown
    /// with `diagonal(i)` on its diagonal.
    fn chain(n: usize, diagonal: impl Fn(usize) -> f64) -> Vec<(usize, usize, f64)> {
        let mut entries = Vec::new();
        for i in 0..n {
            entries.push((i, i, diagonal(i)));
            if i > 0 {
                entries.push((i, i - 1, -1.0));
            }
        }
        entries
    }

    /// A factor of K_b over [means; interiors] solves K_mm, the Schur
    /// complement onto the means, from a right-hand side over the means
    /// alone (padded with zeros on the interiors): one column and many, to
    /// single precision; checked against K_mm formed and solved densely.
    #[test]
    fn a_factor_of_the_bonded_model_solves_the_means_schur_complement() {
        // a chain of 12 unknowns, the first 4 the means, its ends joined
        let n = 12;
        let mut entries = chain(n, |i| 2.2 + 0.05 * i as f64);
        entries.push((n - 1, 0, -0.3));
        let k = lower_from_entries(n, entries);
        let node_of: Vec<usize> = (0..n).collect();
        let means = Means::factor(&k, &node_of, Ordering::Amd, 1).expect("a factor");
        let full = nalgebra::DMatrix::from_fn(n, n, |r, c| k.get(r, c));
        let nm = 4;
        let (a, b) = (full.view((0, 0), (nm, nm)), full.view((0, nm), (nm, n - nm)));
        let d = full.view((nm, nm), (n - nm, n - nm)).into_owned();
        let schur = a - b * d.try_inverse().expect("an inverse") * b.transpose();
        let v = vec![1.0, -0.5, 0.25, 2.0];
        let want = schur.lu().solve(&nalgebra::DVector::from_column_slice(&v)).expect("a solve");
        let one = means.solve(&v);
        let many = means.solve_many(&[v.clone(), v.iter().map(|x| 2.0 * x).collect()]);
        assert_eq!((one.len(), many[0].len(), many[1].len()), (nm, nm, nm));
        for i in 0..nm {
            assert!((one[i] - want[i]).abs() < 1e-5 * want.amax(), "{i}: {} against {}", one[i], want[i]);
            assert!((many[0][i] - want[i]).abs() < 1e-5 * want.amax());
            assert!((many[1][i] - 2.0 * want[i]).abs() < 2e-5 * want.amax());
        }
    }

    /// The free block `M` where the sides do not factorise (the fallback
    /// of [`Sparse::free_block`]): where every pair deforms, factorised in
    /// single precision, and its solve within single precision's reach of
    /// M's; elsewhere in double, to round-off.
    #[test]
    fn the_free_block_is_factorised_in_single_precision_where_every_pair_deforms() {
        // a chain of springs, each unknown also held by its own
        let n = 40;
        let m = lower_from_entries(n, chain(n, |i| 2.5 + 0.01 * i as f64));
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (0.3 * i as f64).sin()).collect();
        for (deforming, within) in [(true, 1e-5), (false, 1e-12)] {
            let p = Preconditioner::factor(&m, deforming, 2);
            assert_eq!(matches!(p, Preconditioner::Single(_)), deforming);
            let x = p.apply(&b);
            let r: Vec<f64> = m.mul(&x).iter().zip(&b).map(|(a, b)| a - b).collect();
            assert!(length(&r) <= within * length(&b), "deforming {deforming}: residual {:e}", length(&r) / length(&b));
        }
    }
}
