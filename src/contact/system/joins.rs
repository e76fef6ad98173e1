//! Bonded joins eliminated by a sparse factorisation.
//!
//! A body cut into substructures ([solver] substructures) is held together
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
//! Measured on the 5.7e5-DOF column of docs/scaling.md cut into 4 pieces
//! per body (18,252 join DOFs, 5,046 contact DOFs): the dense elimination
//! took 93 s of the interface stage; here the factorisation is 1.0e12 flops
//! (AMD's ordering: 1.9e12) and the interface stage 54 s, the whole run
//! 118 s instead of 157 s, for 16.2 GB peak instead of 14.7 (the sparse
//! matrix and its factor beside the dense blocks). The pieces' cliques stay
//! dense, so this is a constant factor, not a change of order: what would
//! change the order is not forming the pieces' S at all (docs/scaling.md).

use super::coords::{fixed_load, for_each_entry, for_each_load, Blocks, Terms, Var};
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
    /// scratch: the local index of each unknown in the part being added
    local: Vec<usize>,
    /// scratch: the position of each row in the column being filled
    pos: Vec<usize>,
}

/// What recovers the join means once the pairs' unknowns are known.
pub struct JoinElimination {
    nj: usize,
    factor: PartialCholesky,
    b_j: Vec<Vec<f64>>,
    b_j_fixed: Vec<f64>,
    /// `b_c - b'_c` per load case and for the prescribed values.
    shift: Vec<Vec<f64>>,
    shift_fixed: Vec<f64>,
}

/// The factorisation failed: the bonded interface is singular.
#[derive(Debug)]
pub struct Singular;

impl SparseBlocks {
    /// `nm` pair means (`Var::M(0..nm)`), `nj` join means (`Var::M(nm..nm +
    /// nj)`), `nr` relative displacements; `cliques[p]` the terms of each
    /// part's interface DOFs (the pattern of the sparse matrix).
    pub fn new(nm: usize, nj: usize, nr: usize, cases: usize, cliques: &[Vec<Terms>], node_of: Vec<usize>) -> SparseBlocks {
        let n = nj + nm + nr;
        let vars: Vec<Vec<usize>> = cliques.iter().map(|terms| unknowns(terms, nm, nj)).collect();
        SparseBlocks {
            nj,
            nm,
            nr,
            node_of,
            k: pattern(n, &vars),
            b: vec![vec![0.0; n]; cases],
            b_fixed: vec![0.0; n],
            local: vec![usize::MAX; n],
            pos: vec![usize::MAX; n],
        }
    }

    /// Adds one part (its `s` and `g` already in local axes, see
    /// [`super::coords::localise`]).
    pub fn add_part(&mut self, s: &[f64], g: &[Vec<f64>], terms: &[Terms]) {
        let vars = unknowns(terms, self.nm, self.nj);
        let m = vars.len();
        for (a, &v) in vars.iter().enumerate() {
            self.local[v] = a;
        }
        // K_p in the part's unknowns, then into the sparse lower triangle
        let mut kp = vec![0.0; m * m];
        for_each_entry(s, terms, |i, j, x| {
            let (a, b) = (self.local[index(i, self.nm, self.nj)], self.local[index(j, self.nm, self.nj)]);
            kp[a + b * m] += x;
        });
        for (b, &col) in vars.iter().enumerate() {
            let (lo, hi) = (self.k.col_ptr[col], self.k.col_ptr[col + 1]);
            for p in lo..hi {
                self.pos[self.k.row_idx[p]] = p;
            }
            for (a, &row) in vars.iter().enumerate() {
                if row >= col {
                    self.k.values[self.pos[row]] += kp[a + b * m];
                }
            }
        }
        for &v in &vars {
            self.local[v] = usize::MAX;
        }
        let (nm, nj) = (self.nm, self.nj);
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
        let factor = PartialCholesky::factor(&k, nj, &node_of, Ordering::NestedDissection, par).map_err(|_| Singular)?;
        drop(k);
        let s = factor.schur(par);
        let alpha = factor.alpha();
        // b'_c = b_c + (S + alpha I) x_c with K' [x_J; x_c] = [b_J; 0], every case at once
        let cols: Vec<&Vec<f64>> = b.iter().chain(std::iter::once(&b_fixed)).collect();
        let mut x = vec![0.0; (nj + nc) * cols.len()];
        for (q, bq) in cols.iter().enumerate() {
            x[q * (nj + nc)..q * (nj + nc) + nj].copy_from_slice(&bq[..nj]);
        }
        factor.solve_many(&mut x, cols.len());
        let shifts: Vec<Vec<f64>> = (0..cols.len())
            .map(|q| {
                let xc = &x[q * (nj + nc) + nj..(q + 1) * (nj + nc)];
                // b_c - b'_c = -(S + alpha I) x_c
                (0..nc).map(|i| -(alpha * xc[i] + (0..nc).map(|j| s[i + j * nc] * xc[j]).sum::<f64>())).collect()
            })
            .collect();
        let mut blocks = Blocks::zeros(nm, nr, b.len());
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
        let reduced_load = |bq: &[f64], shift: &[f64], bm: &mut Vec<f64>, br: &mut Vec<f64>| {
            for i in 0..nc {
                let v = bq[nj + i] - shift[i];
                if i < nm {
                    bm[i] = v;
                } else {
                    br[i - nm] = v;
                }
            }
        };
        for (case, bq) in b.iter().enumerate() {
            reduced_load(bq, &shifts[case], &mut blocks.b_m[case], &mut blocks.b_r[case]);
        }
        reduced_load(&b_fixed, &shifts[b.len()], &mut blocks.b_m_fixed, &mut blocks.b_r_fixed);
        let mut shift = shifts;
        let shift_fixed = shift.pop().expect("the prescribed values' column");
        let b_j = b.iter().map(|bq| bq[..nj].to_vec()).collect();
        let b_j_fixed = b_fixed[..nj].to_vec();
        Ok((blocks, JoinElimination { nj, factor, b_j, b_j_fixed, shift, shift_fixed }))
    }
}

impl JoinElimination {
    /// The join means for the pairs' means `m` and relative displacements
    /// `r` under the load factors `lambda`.
    pub fn means(&self, m: &[f64], r: &[f64], lambda: &[f64]) -> Vec<f64> {
        let nj = self.nj;
        let d_c: Vec<f64> = m.iter().chain(r).copied().collect();
        let nc = d_c.len();
        let alpha = self.factor.alpha();
        let shift = combine(&self.shift, &self.shift_fixed, lambda);
        let s_d = self.factor.apply_schur(&d_c);
        let mut x = combine(&self.b_j, &self.b_j_fixed, lambda);
        x.extend((0..nc).map(|i| shift[i] + s_d[i] + alpha * d_c[i]));
        self.factor.solve_many(&mut x, 1);
        x.truncate(nj);
        x
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

/// The lower triangle of a matrix made of dense cliques (each part's
/// unknowns), every diagonal entry present.
fn pattern(n: usize, cliques: &[Vec<usize>]) -> SymMatrix {
    let mut holders: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (p, c) in cliques.iter().enumerate() {
        for &v in c {
            holders[v].push(p as u32);
        }
    }
    let mut mark = vec![usize::MAX; n];
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0);
    let mut row_idx = Vec::new();
    let mut rows = Vec::new();
    for j in 0..n {
        rows.clear();
        rows.push(j);
        mark[j] = j;
        for &p in &holders[j] {
            for &v in &cliques[p as usize] {
                if v > j && mark[v] != j {
                    mark[v] = j;
                    rows.push(v);
                }
            }
        }
        rows.sort_unstable();
        row_idx.extend_from_slice(&rows);
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    SymMatrix { n, col_ptr, row_idx, values: vec![0.0; nnz] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pattern_of_two_cliques_is_their_union() {
        let k = pattern(4, &[vec![0, 2], vec![1, 2, 3]]);
        let cols: Vec<Vec<usize>> = (0..4).map(|j| k.row_idx[k.col_ptr[j]..k.col_ptr[j + 1]].to_vec()).collect();
        assert_eq!(cols, vec![vec![0, 2], vec![1, 2, 3], vec![2, 3], vec![3]]);
    }
}
