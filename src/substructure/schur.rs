//! Condensation by partial factorisation: the interior DOFs are ordered
//! first (AMD within them) and the interface DOFs last, so one sparse
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

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltParams;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side, Spec};

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
    /// interface) with the interface ordered last.
    pub fn factor(k: &SymMatrix, ni: usize) -> Result<PartialCholesky, FactorError> {
        let n = k.n;
        if ni == 0 {
            return Err(FactorError::NotPositiveDefinite);
        }
        let resource = |e: &dyn std::fmt::Debug| FactorError::Resource(format!("{e:?}"));
        // AMD on the interior block (its lower triangle; AMD orders A + A^T)
        let mut ii_ptr = Vec::with_capacity(ni + 1);
        let mut ii_idx = Vec::new();
        ii_ptr.push(0);
        for c in 0..ni {
            ii_idx.extend(k.row_idx[k.col_ptr[c]..k.col_ptr[c + 1]].iter().copied().filter(|&r| r < ni));
            ii_ptr.push(ii_idx.len());
        }
        let ii = SymbolicSparseColMatRef::new_checked(ni, ni, &ii_ptr, None, &ii_idx);
        let mut fwd = vec![0usize; n];
        let mut inv = vec![0usize; n];
        {
            let mut buf = MemBuffer::try_new(amd::order_scratch::<usize>(ni, ii_idx.len())).map_err(|e| resource(&e))?;
            amd::order(&mut fwd[..ni], &mut inv[..ni], ii, amd::Control::default(), MemStack::new(&mut buf)).map_err(|e| resource(&e))?;
        }
        for i in ni..n {
            fwd[i] = i;
            inv[i] = i;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
        let a_sym = SymbolicSparseColMatRef::new_checked(n, n, &k.col_ptr, None, &k.row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(a_sym, Side::Lower, SymmetricOrdering::Custom(perm), params).map_err(|e| resource(&e))?;
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
        let par = Par::Seq;
        let mut buf = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::<LltParams, f64>::default()))
            .map_err(|e| resource(&e))?;
        symbolic
            .factorize_numeric_llt(&mut values, a, Side::Lower, Default::default(), par, MemStack::new(&mut buf), Default::default())
            .map_err(|_| FactorError::NotPositiveDefinite)?;
        Ok(PartialCholesky { symbolic, values, n, ni, alpha })
    }

    /// Solves `K' x = b` in place for the `k` columns of `b` (column-major).
    pub fn solve_many(&self, b: &mut [f64], k: usize) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut buf = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(k, Par::Seq));
        llt.solve_in_place_with_conj(Conj::No, MatMut::from_column_major_slice_mut(b, self.n, k), Par::Seq, MemStack::new(&mut buf));
    }

    /// The shift added to the interface diagonal.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// The Schur complement `S = L_cc L_cc^T - alpha I`, column-major.
    pub fn schur(&self) -> Vec<f64> {
        let (n, ni) = (self.n, self.ni);
        let nc = n - ni;
        let mut l = vec![0.0; nc * nc]; // L_cc column-major
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the factorisation is forced supernodal")
        };
        let llt = SupernodalLltRef::new(sym, &self.values);
        for s in 0..sym.n_supernodes() {
            let node = llt.supernode(s);
            let start = node.start();
            let val = node.val();
            let ncols = val.ncols();
            if start + ncols <= ni {
                continue;
            }
            let pattern = node.pattern();
            for jc in 0..ncols {
                let j = start + jc;
                if j < ni {
                    continue;
                }
                for p in jc..val.nrows() {
                    let r = if p < ncols { start + p } else { pattern[p - ncols] };
                    l[(r - ni) + (j - ni) * nc] = val[(p, jc)];
                }
            }
        }
        // S = L L^T - alpha I (lower-triangular L)
        let mut s = vec![0.0; nc * nc];
        for j in 0..nc {
            for i in j..nc {
                let kmax = j; // L[i][k] L[j][k] for k <= j
                let mut acc = 0.0;
                for k in 0..=kmax {
                    acc += l[i + k * nc] * l[j + k * nc];
                }
                s[i + j * nc] = acc;
                s[j + i * nc] = acc;
            }
            s[j + j * nc] -= self.alpha;
        }
        s
    }
}
