//! Bonded joins eliminated by a sparse factorisation.
//!
//! A body cut into substructures (`[solver] substructures`) is held together
//! by joins: nodes shared by pieces, one mean per component, never open and
//! never slipping. Assembled densely with the contact unknowns, every join
//! is a row of one dense matrix whose elimination costs the cube of all the
//! interfaces together. But a piece couples only the joins on its own
//! faces, so the joins form a sparse matrix of dense cliques, one per
//! piece. Here they are the interior of one more substructure whose
//! interface is the contact unknowns:
//!
//! ```text
//! unknowns [J | P R]: J the join means, P the pairs' means, R their
//! relative displacements; each part adds its K_p = W_p^T S'_p W_p.
//!
//! K = [K_JJ K_Jc]     one sparse partial Cholesky (METIS nested dissection
//!     [K_cJ K_cc]     of the join nodes, P R last):
//!                     S = K_cc - K_cJ K_JJ^-1 K_Jc,  b'_c = b_c - K_cJ K_JJ^-1 b_J
//! ```
//!
//! S and b'_c are the dense [`Blocks`] of the pairs alone, which
//! [`super::reduce`] reduces as before; the join means follow from the
//! pairs' unknowns d_c by one solve, `m_J = K_JJ^-1 (b_J - K_Jc d_c)`.
//! With the shift of [`PartialCholesky`] (`K' = K + alpha E_c`):
//! `K' [x_J; x_c] = [b_J; 0]` gives `b'_c = b_c + (S + alpha I) x_c`, and
//! `K' [m_J; d_c] = [b_J; b_c - b'_c + (S + alpha I) d_c]` gives `m_J`.
//!
//! What it saves against the dense elimination, in time and memory, is
//! measured in docs/kernels.md and docs/scaling.md. The pieces' cliques stay
//! dense, so this is a constant factor, not a change of order: what would
//! change the order is not forming the pieces' S at all (docs/scaling.md).

use super::coords::{add_clique, fixed_load, for_each_load, Blocks, CliqueScratch, Terms, Var};
use super::reduce::combine;
use crate::fem::sparse::SymMatrix;
use crate::substructure::ordering::Ordering;
use crate::substructure::schur::PartialCholesky;

/// Whether the joins are eliminated sparsely: when they are more than twice
/// the contact unknowns. Measured on the column of docs/scaling.md: at
/// 3.6 times (4 pieces per body) the sparse elimination takes the interface
/// stage from 93 to 54 s; at 1.4 times (2 pieces) it is slower, 25 s
/// against 16 s dense. A few joins where contacts meet, as in a dam, stay
/// dense.
pub fn worth_it(joins: usize, pair_means: usize, relative: usize) -> bool {
    joins > 2 * (pair_means + relative)
}

/// The sparse system over [J | P R] while the parts are added.
pub struct SparseBlocks {
    nj: usize,
    nm: usize,
    nr: usize,
    /// the join node of each join mean (the graph nested dissection orders)
    node_of: Vec<usize>,
    k: SymMatrix,
    b: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    scratch: CliqueScratch,
}

/// What recovers the join means once the pairs' unknowns are known.
pub struct JoinElimination {
    factor: PartialCholesky,
    /// The loads `[b_J; b_c]` and the condensed ones `b'_c`, per load case
    /// and for the prescribed values at ramp 1.
    b: Vec<Vec<f64>>,
    b_fixed: Vec<f64>,
    g: Vec<Vec<f64>>,
    g_fixed: Vec<f64>,
}

/// The factorisation failed: the bonded interface is singular.
#[derive(Debug)]
pub struct Singular;

impl SparseBlocks {
    /// `nm` pair means (`Var::M(0..nm)`), `nj` join means (`Var::M(nm..nm +
    /// nj)`), `nr` relative displacements; `cliques[p]` the terms of each
    /// part's interface DOFs (the pattern of the sparse matrix).
    pub fn new(
        nm: usize,
        nj: usize,
        nr: usize,
        cases: usize,
        cliques: &[Vec<Terms>],
        node_of: Vec<usize>,
    ) -> SparseBlocks {
        let n = nj + nm + nr;
        let vars: Vec<Vec<usize>> = cliques.iter().map(|terms| unknowns(terms, nm, nj)).collect();
        SparseBlocks {
            nj,
            nm,
            nr,
            node_of,
            k: SymMatrix::from_cliques(n, &vars),
            b: vec![vec![0.0; n]; cases],
            b_fixed: vec![0.0; n],
            scratch: CliqueScratch::new(n),
        }
    }

    /// Adds one part (its `s` and `g` already in local axes, see
    /// [`super::coords::localise`]).
    pub fn add_part(&mut self, s: &[f64], g: &[Vec<f64>], terms: &[Terms]) {
        let (nm, nj) = (self.nm, self.nj);
        add_clique(&mut self.k, s, terms, |v| Some(index(v, nm, nj)), &mut self.scratch);
        for (b, gc) in self.b.iter_mut().zip(g) {
            for_each_load(gc, terms, |i, x| b[index(i, nm, nj)] += x);
        }
        let b = &mut self.b_fixed;
        fixed_load(s, terms, |i, x| b[index(i, nm, nj)] += x);
    }

    /// Eliminates the joins: the dense blocks of the pairs' unknowns, and
    /// what recovers the join means.
    pub fn condense(self) -> Result<(Blocks, JoinElimination), Singular> {
        let SparseBlocks { nj, nm, nr, node_of, k, b, b_fixed, .. } = self;
        let par = faer::get_global_parallelism();
        let nc = nm + nr;
        let factor =
            PartialCholesky::factor(&k, nj, &node_of, Ordering::NestedDissection, par).map_err(|_| Singular)?;
        drop(k);
        let s = factor.schur(par);
        // b'_c for every load case and the prescribed values, in one solve
        let mut cases = b;
        cases.push(b_fixed);
        let (mut g, _) = factor.condensed_loads(&s, &cases);
        let mut blocks = Blocks::zeros(nm, nr, g.len() - 1);
        for j in 0..nc {
            for i in 0..nc {
                let v = s[i + j * nc];
                match (i < nm, j < nm) {
                    (true, true) => blocks.k_mm[(i, j)] = v,
                    (true, false) => blocks.k_mr[(i, j - nm)] = v,
                    (false, false) => blocks.k_rr[(i - nm, j - nm)] = v,
                    (false, true) => {}
                }
            }
        }
        drop(s);
        let split = |gq: &[f64], bm: &mut Vec<f64>, br: &mut Vec<f64>| {
            bm.copy_from_slice(&gq[..nm]);
            br.copy_from_slice(&gq[nm..]);
        };
        let g_fixed = g.pop().expect("the prescribed values' column");
        let b_fixed = cases.pop().expect("the prescribed values' column");
        for (case, gq) in g.iter().enumerate() {
            split(gq, &mut blocks.b_m[case], &mut blocks.b_r[case]);
        }
        split(&g_fixed, &mut blocks.b_m_fixed, &mut blocks.b_r_fixed);
        Ok((blocks, JoinElimination { factor, b: cases, b_fixed, g, g_fixed }))
    }
}

impl JoinElimination {
    /// The join means for the pairs' means `m` and relative displacements
    /// `r` under the load factors `lambda`.
    pub fn means(&self, m: &[f64], r: &[f64], lambda: &[f64]) -> Vec<f64> {
        let d_c: Vec<f64> = m.iter().chain(r).copied().collect();
        let f = combine(&self.b, &self.b_fixed, lambda);
        let g = combine(&self.g, &self.g_fixed, lambda);
        self.factor.interior(&f, &g, &d_c)
    }
}

/// The sparse numbering: J first, then P, then R.
fn index(v: Var, nm: usize, nj: usize) -> usize {
    match v {
        Var::M(i) if i >= nm => i - nm,
        Var::M(i) => nj + i,
        Var::R(i) => nj + nm + i,
    }
}

/// The unknowns a part's DOFs touch, each once, in the sparse numbering.
fn unknowns(terms: &[Terms], nm: usize, nj: usize) -> Vec<usize> {
    let mut v: Vec<usize> = terms.iter().flat_map(|t| t.vars[..t.n].iter().map(|&(x, _)| index(x, nm, nj))).collect();
    v.sort_unstable();
    v.dedup();
    v
}
