//! Condensation by partial factorisation: the interior DOFs are ordered
//! first (AMD or nested dissection within them, see [`super::ordering`])
//! and the interface DOFs last, so one sparse
//! Cholesky factorisation of the whole part yields the Schur complement in
//! its trailing block:
//!
//! ```text
//! [K_ii K_ic]   [L_ii  0  ] [L_ii^T L_ci^T]
//! [K_ci K_cc] = [L_ci L_cc] [ 0     L_cc^T]     S = K_cc - K_ci K_ii^-1 K_ic = L_cc L_cc^T
//! ```
//!
//! This costs about one factorisation, against one solve per interface
//! column for `K_ii^-1 K_ic`. A body held only by its contacts has a singular
//! S, so the trailing block is factorised shifted, `K' = K + alpha E_c`
//! (E_c the identity on the interface DOFs, alpha the largest diagonal entry
//! of K_cc): `S = L_cc L_cc^T - alpha I`. Solves with K' give everything else:
//! `K' [x_i; x_c] = [F_i; 0]` yields `G = F_c + (S + alpha I) x_c`, and
//! `K' [d_i; d_c] = [F_i; F_c + f_c + alpha d_c]` recovers the interior.
//!
//! The dense work is faer's: the numeric factorisation's supernodes (the
//! trailing one is the dense nc x nc block) and the product `L_cc L_cc^T`
//! (blocked, SIMD triangular matmul, nc^3 / 3 flops); its rate against
//! faer's dense LLT and the scalar loop it replaced: docs/kernels.md.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltParams;
use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, MatMut, MatRef, Par, Side, Spec};

use super::ordering::{self, Ordering};
use crate::fem::sparse::{FactorError, SymMatrix};

/// A sparse Cholesky factor of a part with its interface ordered last.
pub struct PartialCholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    n: usize,
    ni: usize,
    alpha: f64,
}

impl PartialCholesky {
    /// Factorises `k` (lower triangle; equations `0..ni` interior, `ni..n`
    /// interface) with the interior ordered by `ordering` (`node_of[e]` the
    /// node of interior equation `e`) and the interface last; `par` is the
    /// parallelism of the numeric factorisation.
    pub fn factor(
        k: &SymMatrix,
        ni: usize,
        node_of: &[usize],
        ordering: Ordering,
        par: Par,
    ) -> Result<PartialCholesky, FactorError> {
        let n = k.n;
        let resource = |e: &dyn std::fmt::Debug| FactorError::Resource(format!("{e:?}"));
        let symbolic = symbolic(k, ni, node_of, ordering)?;
        let a_sym = SymbolicSparseColMatRef::new_checked(n, n, &k.col_ptr, None, &k.row_idx);
        // the shift on the interface diagonal
        let mut vals = k.values.clone();
        let mut alpha: f64 = 0.0;
        for c in ni..n {
            alpha = alpha.max(k.get(c, c).abs());
        }
        if alpha == 0.0 {
            alpha = 1.0;
        }
        for c in ni..n {
            let p = k.col_ptr[c]; // the diagonal is the first entry of a lower column
            debug_assert_eq!(k.row_idx[p], c);
            vals[p] += alpha;
        }
        let a = SparseColMatRef::new(a_sym, &vals);
        let mut values = Vec::new();
        values.try_reserve_exact(symbolic.len_val()).map_err(|e| resource(&e))?;
        values.resize(symbolic.len_val(), 0.0);
        let mut buf =
            MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::<LltParams, f64>::default()))
                .map_err(|e| resource(&e))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a,
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|_| FactorError::NotPositiveDefinite)?;
        Ok(PartialCholesky { symbolic, values, n, ni, alpha })
    }

    /// Solves `K' x = b` in place for the `k` columns of `b` (column-major).
    pub fn solve_many(&self, b: &mut [f64], k: usize) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut buf = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(k, Par::Seq));
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, self.n, k),
            Par::Seq,
            MemStack::new(&mut buf),
        );
    }

    /// The shift added to the interface diagonal.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Size of the factor: stored values and the flops of its numeric
    /// factorisation (sum over the factor's columns of their squared
    /// lengths).
    pub fn stats(&self) -> FactorStats {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            return FactorStats { values: 0, flops: 0.0 };
        };
        let mut flops = 0.0;
        for s in 0..sym.n_supernodes() {
            let cols = sym.supernode_end()[s] - sym.supernode_begin()[s];
            let rows = cols + sym.supernode(s).pattern().len();
            for j in 0..cols {
                flops += ((rows - j) as f64).powi(2);
            }
        }
        FactorStats { values: sym.len_val(), flops }
    }

    /// The Schur complement `S = L_cc L_cc^T - alpha I`, column-major and
    /// full (both triangles). `L_cc` is gathered from the trailing
    /// supernodes into a dense lower triangle and multiplied by faer's
    /// blocked triangular product (nc^3 / 3 flops).
    pub fn schur(&self, par: Par) -> Vec<f64> {
        let (n, ni) = (self.n, self.ni);
        let nc = n - ni;
        let mut l = vec![0.0; nc * nc]; // L_cc, column-major
        self.for_each_trailing(|j, r, v| l[r + j * nc] = v);
        // the lower triangle of L L^T, then mirrored
        let l = MatRef::from_column_major_slice(&l, nc, nc);
        let mut out = vec![0.0; nc * nc];
        triangular::matmul(
            MatMut::from_column_major_slice_mut(&mut out, nc, nc),
            BlockStructure::TriangularLower,
            Accum::Replace,
            l,
            BlockStructure::TriangularLower,
            l.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            par,
        );
        for j in 0..nc {
            out[j + j * nc] -= self.alpha;
            for i in j + 1..nc {
                out[j + i * nc] = out[i + j * nc];
            }
        }
        out
    }
}

impl PartialCholesky {
    /// The condensed loads `G = F_c - K_ci K_ii^-1 F_i` of the load vectors
    /// `f` (each `[F_i; F_c]`), with `s` this factor's [`Self::schur`]:
    /// `K' [x_i; x_c] = [F_i; 0]` gives `G = F_c + (S + alpha I) x_c`, every
    /// case in one solve and one product. Also the solutions `x`
    /// (column-major, n per case), for their backward error.
    pub fn condensed_loads(&self, s: &[f64], f: &[Vec<f64>]) -> (Vec<Vec<f64>>, Vec<f64>) {
        let (n, ni) = (self.n, self.ni);
        let nc = n - ni;
        let cases = f.len();
        let mut x: Vec<f64> =
            f.iter().flat_map(|fk| fk[..ni].iter().copied().chain(std::iter::repeat_n(0.0, nc))).collect();
        self.solve_many(&mut x, cases);
        // one product S X_c for all cases (S read once); X_c is the trailing nc rows of x
        let mut sx = vec![0.0; nc * cases];
        if cases > 0 && nc > 0 {
            let x_c = MatRef::from_column_major_slice_with_stride(&x[ni..], nc, cases, n);
            let s_ref = MatRef::from_column_major_slice(s, nc, nc);
            matmul(MatMut::from_column_major_slice_mut(&mut sx, nc, cases), Accum::Replace, s_ref, x_c, 1.0, Par::Seq);
        }
        let g = (0..cases)
            .map(|k| {
                let xc = &x[k * n + ni..(k + 1) * n];
                (0..nc).map(|r| f[k][ni + r] + self.alpha * xc[r] + sx[r + k * nc]).collect()
            })
            .collect();
        (g, x)
    }

    /// The interior displacements for the interface displacements `d_c`
    /// under the load `f = [F_i; F_c]` whose condensed load is `g`:
    /// `K' [d_i; d_c] = [F_i; F_c + (S d_c - G) + alpha d_c]`, with `S d_c`
    /// from the factor ([`Self::apply_schur`]).
    pub fn interior(&self, f: &[f64], g: &[f64], d_c: &[f64]) -> Vec<f64> {
        let ni = self.ni;
        let s_d = self.apply_schur(d_c);
        let mut x = f.to_vec();
        for r in 0..d_c.len() {
            x[ni + r] += s_d[r] - g[r] + self.alpha * d_c[r];
        }
        self.solve_many(&mut x, 1);
        x.truncate(ni);
        x
    }

    /// `S x = L_cc L_cc^T x - alpha x`, straight from the factor's trailing
    /// supernodes (no dense S needed: what recovers a part's interior once
    /// its S has gone to the interface).
    pub fn apply_schur(&self, x: &[f64]) -> Vec<f64> {
        // t = L_cc^T x, then y = L_cc t - alpha x
        let mut t = vec![0.0; x.len()];
        self.for_each_trailing(|j, r, v| t[j] += v * x[r]);
        let mut y: Vec<f64> = x.iter().map(|v| -self.alpha * v).collect();
        self.for_each_trailing(|j, r, v| y[r] += v * t[j]);
        y
    }

    /// Calls `f(j, r, L_cc[r, j])` for every stored entry of `L_cc`, the
    /// factor's trailing block (`j`, `r` counted from the first interface
    /// equation), read from the supernodes that hold interface columns.
    fn for_each_trailing(&self, mut f: impl FnMut(usize, usize, f64)) {
        let ni = self.ni;
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            return; // an empty factor (see `symbolic`)
        };
        let llt = SupernodalLltRef::new(sym, &self.values);
        for s in 0..sym.n_supernodes() {
            let node = llt.supernode(s);
            let (start, val, pattern) = (node.start(), node.val(), node.pattern());
            let ncols = val.ncols();
            for jc in (0..ncols).filter(|&jc| start + jc >= ni) {
                let col = val.col(jc);
                let j = start + jc - ni;
                for p in jc..ncols {
                    f(j, start + p - ni, col[p]);
                }
                for (p, &r) in pattern.iter().enumerate() {
                    f(j, r - ni, col[ncols + p]);
                }
            }
        }
    }
}

/// The supernodal symbolic factorisation of `k` with its equations `0..ni`
/// ordered by `ordering` (`node_of` as [`ordering::interior`]) and the
/// rest last. Forced supernodal, faer still gives an empty matrix a
/// simplicial one (its flops per stored value are 0 / 0): the interior of
/// a block whose every node lies on its contacts (a small tet10 block of a
/// jointed rock mass, whose factor the iterative interface takes alone).
/// Such a factor stores nothing: [`PartialCholesky::stats`] and the
/// trailing block read it as empty.
pub(super) fn symbolic(
    k: &SymMatrix,
    ni: usize,
    node_of: &[usize],
    ordering: Ordering,
) -> Result<SymbolicCholesky<usize>, FactorError> {
    let n = k.n;
    let mut fwd = ordering::interior(k, ni, node_of, ordering)?;
    fwd.extend(ni..n);
    let mut inv = vec![0usize; n];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
    let a_sym = SymbolicSparseColMatRef::new_checked(n, n, &k.col_ptr, None, &k.row_idx);
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    factorize_symbolic_cholesky(a_sym, Side::Lower, SymmetricOrdering::Custom(perm), params)
        .map_err(|e| FactorError::Resource(format!("{e:?}")))
}

/// Size and cost of a sparse factor.
#[derive(Clone, Copy, Debug)]
pub struct FactorStats {
    /// Stored values (supernodes are dense: this counts their zeros).
    pub values: usize,
    /// Flops of the numeric factorisation, `sum_j c_j^2` over the factor's
    /// columns of `c_j` entries.
    pub flops: f64,
}
