//! A sparse Cholesky factor kept in single precision: a preconditioner's,
//! where an answer to 1e-4 is enough and reading half the bytes is what
//! counts (a substitution streams the whole factor through memory once
//! forwards and once back).
//!
//! Measured on the means of the 512-block cube of `make bench-blocks`
//! (36,092 equations, 5.4e7 factor values): factorisation 0.79 s against
//! 1.8 s in double precision, one substitution 0.022 s against 0.042 s
//! (two right-hand sides cost the same as one: the factor is read once),
//! `||K x - b|| / ||b||` 2.7e-5.
//!
//! The matrix is scaled by a power of two to a largest diagonal entry near
//! 1 before it is rounded, and every right-hand side likewise: stiffnesses
//! near 1e-200 or 1e+200 (which single precision cannot hold) give the same
//! digits as near 1, times that power of two.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltParams;
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side, Spec};

use super::ordering::Ordering;
use super::schur::symbolic;
use crate::fem::sparse::{FactorError, SymMatrix};
use crate::fem::vec3::to_one;

/// `K = L L^T` in single precision; see the module header.
pub struct SingleCholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f32>,
    /// The power of two K was scaled by before rounding.
    scale: f64,
}

impl SingleCholesky {
    /// Factorises `k` (lower triangle), ordered by `ordering` (`node_of`
    /// the node of each equation, for nested dissection).
    pub fn factor(k: &SymMatrix, node_of: &[usize], ordering: Ordering) -> Result<SingleCholesky, FactorError> {
        let n = k.n;
        let symbolic = symbolic(k, n, node_of, ordering)?;
        let diagonal: Vec<f64> = (0..n).map(|c| k.get(c, c)).collect();
        let scale = to_one(&diagonal);
        let vals: Vec<f32> = k.values.iter().map(|&v| (v * scale) as f32).collect();
        let a = SparseColMatRef::new(SymbolicSparseColMatRef::new_checked(n, n, &k.col_ptr, None, &k.row_idx), &vals);
        let resource = |e: &dyn std::fmt::Debug| FactorError::Resource(format!("{e:?}"));
        let mut values = Vec::new();
        values.try_reserve_exact(symbolic.len_val()).map_err(|e| resource(&e))?;
        values.resize(symbolic.len_val(), 0.0f32);
        let mut buf = MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f32>(Par::Seq, Spec::<LltParams, f32>::default()))
            .map_err(|e| resource(&e))?;
        symbolic
            .factorize_numeric_llt(&mut values, a, Side::Lower, Default::default(), Par::Seq, MemStack::new(&mut buf), Default::default())
            .map_err(|_| FactorError::NotPositiveDefinite)?;
        Ok(SingleCholesky { symbolic, values, scale })
    }

    /// `K^-1 b`, to single precision.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let n = b.len();
        let t = to_one(b);
        let mut x: Vec<f32> = b.iter().map(|&v| (v * t) as f32).collect();
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut buf = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f32>(1, Par::Seq));
        llt.solve_in_place_with_conj(Conj::No, MatMut::from_column_major_slice_mut(&mut x, n, 1), Par::Seq, MemStack::new(&mut buf));
        let back = self.scale / t;
        x.iter().map(|&v| f64::from(v) * back).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D Laplacian of n equations (stiffness times `e`), lower triangle.
    fn laplacian(n: usize, e: f64) -> SymMatrix {
        let mut col_ptr = vec![0];
        let (mut row_idx, mut values) = (Vec::new(), Vec::new());
        for c in 0..n {
            row_idx.push(c);
            values.push(2.0 * e);
            if c + 1 < n {
                row_idx.push(c + 1);
                values.push(-e);
            }
            col_ptr.push(row_idx.len());
        }
        SymMatrix { n, col_ptr, row_idx, values }
    }

    /// Single-precision accurate, and the same digits for a stiffness
    /// 2^-664 (about 1e-200) times smaller, times 2^664.
    #[test]
    fn solves_to_single_precision_at_any_scale() {
        let n = 50;
        let k = laplacian(n, 3.0);
        let node_of: Vec<usize> = (0..n).collect();
        let want: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let b = k.mul(&want);
        let f = SingleCholesky::factor(&k, &node_of, Ordering::Amd).expect("positive definite");
        let x = f.solve(&b);
        let err = x.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(err > 0.0 && err < 1e-3, "error {err}");
        let s = 2f64.powi(-664);
        let tiny = laplacian(n, 3.0 * s);
        let ft = SingleCholesky::factor(&tiny, &node_of, Ordering::Amd).expect("positive definite");
        let xt = ft.solve(&b);
        assert!(xt.iter().zip(&x).all(|(a, b)| *a == b / s), "scaled by 2^-664");
    }
}
