//! A sparse Cholesky factor kept in single precision: a preconditioner's,
//! where an answer to 1e-4 is enough and reading half the bytes is what
//! counts (a substitution streams the whole factor through memory once
//! forwards and once back).
//!
//! Two right-hand sides cost what one does: the factor is read once. The
//! times against double precision, and the accuracy reached on the means
//! of the 512-block cube (`||K x - b|| / ||b||` 2.7e-5), are in
//! docs/kernels.md.
//!
//! The matrix is scaled by a power of two to a largest diagonal entry near
//! 1 before it is rounded, and every right-hand side likewise: stiffnesses
//! near 1e-200 or 1e+200 (which single precision cannot hold) give the same
//! digits as near 1, times that power of two.
//!
//! `b^T K^-1 b` of right-hand sides with a few non-zeros (the sparse
//! interface's W diagonal) takes the forward substitution alone, and of
//! it only the supernodes the non-zeros reach ([`super::sparse_forward`]).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltParams;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky, SymbolicCholeskyRaw};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side, Spec};

use super::ordering::Ordering;
use super::schur::symbolic;
use super::sparse_forward::{self, Forward, Paths};
use super::two_threads::Twofold;
use crate::fem::sparse::{FactorError, SymMatrix};
use crate::fem::vec3::to_one;

/// `K = L L^T` in single precision; see the module header.
pub struct SingleCholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f32>,
    /// The power of two K was scaled by before rounding.
    scale: f64,
    /// The supernodes dealt to two threads, where there are two.
    twofold: Option<Twofold>,
    /// The supernodal elimination tree, where the factor is supernodal.
    paths: Option<Paths>,
}

impl SingleCholesky {
    /// Factorises `k` (lower triangle), ordered by `ordering` (`node_of`
    /// the node of each equation, for nested dissection).
    pub fn factor(
        k: &SymMatrix,
        node_of: &[usize],
        ordering: Ordering,
        threads: usize,
    ) -> Result<SingleCholesky, FactorError> {
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
        let mut buf = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f32>(Par::Seq, Spec::<LltParams, f32>::default()),
        )
        .map_err(|e| resource(&e))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a,
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(|_| FactorError::NotPositiveDefinite)?;
        let (twofold, paths) = match symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sn) => {
                ((threads >= 2).then(|| Twofold::new(sn)).flatten(), Some(Paths::new(sn)))
            }
            SymbolicCholeskyRaw::Simplicial(_) => (None, None),
        };
        Ok(SingleCholesky { symbolic, values, scale, twofold, paths })
    }

    /// The order of K.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// `K^-1 b`, to single precision.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let n = b.len();
        let t = to_one(b);
        let back = self.scale / t;
        if let (Some(two), SymbolicCholeskyRaw::Supernodal(sn), Some(perm)) =
            (&self.twofold, self.symbolic.raw(), self.symbolic.perm())
        {
            // (faer's own substitution permutes the same way: x = P b, then P^T x)
            let (fwd, inv) = perm.arrays();
            let mut x: Vec<f32> = fwd.iter().map(|&i| (b[i] * t) as f32).collect();
            two.solve(SupernodalLltRef::new(sn, &self.values), &mut x);
            return inv.iter().map(|&i| f64::from(x[i]) * back).collect();
        }
        let mut x: Vec<f32> = b.iter().map(|&v| (v * t) as f32).collect();
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut buf = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f32>(1, Par::Seq));
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut x, n, 1),
            Par::Seq,
            MemStack::new(&mut buf),
        );
        x.iter().map(|&v| f64::from(v) * back).collect()
    }

    /// `K^-1 b` for each column of `bs`, to single precision, in one pass
    /// through the factor: many columns read it once, so each costs its
    /// arithmetic rather than the factor's bytes (the sparse interface's
    /// columns of W, [`crate::contact::system::sparse`]). Where
    /// substitutions run in two threads, each takes half the columns:
    /// arithmetic, not bytes, is what many columns cost (the 86k tunnel's
    /// 266 columns of W in six batches: 1.37 -> 0.93 s).
    pub fn solve_many(&self, bs: &[Vec<f64>]) -> Vec<Vec<f64>> {
        if self.twofold.is_none() || bs.len() < 2 {
            return self.solve_columns(bs);
        }
        let (first, second) = bs.split_at(bs.len() / 2);
        let (mut a, b) = std::thread::scope(|scope| {
            let other = scope.spawn(|| self.solve_columns(second));
            let a = self.solve_columns(first);
            (a, other.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
        });
        a.extend(b);
        a
    }

    /// [`SingleCholesky::solve_many`] in this thread.
    fn solve_columns(&self, bs: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let (n, k) = (self.symbolic.nrows(), bs.len());
        let t: Vec<f64> = bs.iter().map(|b| to_one(b)).collect();
        let mut x = vec![0.0f32; n * k];
        for ((xc, b), &tc) in x.chunks_exact_mut(n.max(1)).zip(bs).zip(&t) {
            xc.iter_mut().zip(b).for_each(|(x, &v)| *x = (v * tc) as f32);
        }
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut buf = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f32>(k, Par::Seq));
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut x, n, k),
            Par::Seq,
            MemStack::new(&mut buf),
        );
        (x.chunks_exact(n.max(1)).zip(&t))
            .take(k)
            .map(|(xc, &tc)| xc.iter().map(|&v| f64::from(v) * self.scale / tc).collect())
            .collect()
    }

    /// `b^T K^-1 b` of each column, given by its non-zeros (row, value),
    /// to single precision: with `K = P^T L L^T P` it is `|L^-1 P b|^2`,
    /// the forward substitution alone, through the supernodes the columns
    /// reach ([`sparse_forward`]): the sparse interface's `K_mr e_i`,
    /// non-zero on the means of one or two parts. None where the factor is
    /// not supernodal.
    pub fn sparse_energies(&self, cols: &[Vec<(usize, f64)>]) -> Option<Vec<f64>> {
        let (SymbolicCholeskyRaw::Supernodal(sn), Some(paths)) = (self.symbolic.raw(), &self.paths) else {
            return None;
        };
        let (scaled, t) = self.scaled(cols);
        let e = sparse_forward::energies(SupernodalLltRef::new(sn, &self.values), paths, &scaled);
        Some(e.iter().zip(&t).map(|(e, tc)| e * self.scale / (tc * tc)).collect())
    }

    /// `L^-1 P b` of each column, given by its non-zeros (row, value), to
    /// single precision, with the factor that scales it to K's units:
    /// `a^T K^-1 b = f_a f_b (L^-1 P a) . (L^-1 P b)`
    /// ([`sparse_forward::Forward::dot`]). The forward substitution alone,
    /// through the supernodes the columns reach; None where the factor is
    /// not supernodal.
    pub fn sparse_forward(&self, cols: &[Vec<(usize, f64)>]) -> Option<Vec<(Forward, f64)>> {
        let (SymbolicCholeskyRaw::Supernodal(sn), Some(paths)) = (self.symbolic.raw(), &self.paths) else {
            return None;
        };
        let (scaled, t) = self.scaled(cols);
        let x = sparse_forward::forward(SupernodalLltRef::new(sn, &self.values), paths, &scaled);
        Some(x.into_iter().zip(&t).map(|(x, tc)| (x, self.scale.sqrt() / tc)).collect())
    }

    /// Sparse columns in the factor's ordering, each scaled by a power of
    /// two to a largest entry near 1 (single precision holds it), and those
    /// powers.
    fn scaled(&self, cols: &[Vec<(usize, f64)>]) -> (Vec<Vec<(usize, f32)>>, Vec<f64>) {
        let t: Vec<f64> = cols.iter().map(|c| to_one(&c.iter().map(|&(_, v)| v).collect::<Vec<f64>>())).collect();
        let inv = self.symbolic.perm().map(|p| p.arrays().1);
        let at = |i: usize| inv.map_or(i, |inv| inv[i]);
        let scaled =
            cols.iter().zip(&t).map(|(c, &tc)| c.iter().map(|&(i, v)| (at(i), (v * tc) as f32)).collect()).collect();
        (scaled, t)
    }

    /// The lowest supernode of the rows `rows` (K's ordering): a key to
    /// sort [`SingleCholesky::sparse_energies`]'s columns by, so that a
    /// batch's paths overlap.
    pub fn leaf(&self, rows: impl Iterator<Item = usize>) -> usize {
        let inv = self.symbolic.perm().map(|p| p.arrays().1);
        self.paths.as_ref().map_or(0, |p| p.leaf(rows.map(|i| inv.map_or(i, |inv| inv[i]))))
    }

    /// Whether substitutions run in two threads (see [`super::two_threads`]).
    pub fn twofold(&self) -> bool {
        self.twofold.is_some()
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
        let f = SingleCholesky::factor(&k, &node_of, Ordering::Amd, 1).expect("positive definite");
        let x = f.solve(&b);
        let err = x.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(err > 0.0 && err < 1e-3, "error {err}");
        let s = 2f64.powi(-664);
        let tiny = laplacian(n, 3.0 * s);
        let ft = SingleCholesky::factor(&tiny, &node_of, Ordering::Amd, 1).expect("positive definite");
        let xt = ft.solve(&b);
        assert!(xt.iter().zip(&x).all(|(a, b)| *a == b / s), "scaled by 2^-664");
    }

    /// Many columns at once give each one's own answer, to single
    /// precision, at its own scale (a zero column stays zero).
    #[test]
    fn many_columns_solve_as_one_each() {
        let n = 50;
        let k = laplacian(n, 3.0);
        let node_of: Vec<usize> = (0..n).collect();
        let f = SingleCholesky::factor(&k, &node_of, Ordering::Amd, 1).expect("positive definite");
        let bs: Vec<Vec<f64>> =
            [1.0, 1e-150, 0.0].iter().map(|&s| (0..n).map(|i| s * (1.0 + (i as f64 * 0.7).cos())).collect()).collect();
        let many = f.solve_many(&bs);
        assert_eq!(many.len(), 3);
        for (x, b) in many.iter().zip(&bs) {
            let one = f.solve(b);
            let size = one.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let apart = x.iter().zip(&one).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(apart <= 1e-6 * size, "apart {apart:e} of {size:e}");
        }
        assert!(many[2].iter().all(|&v| v == 0.0));
    }

    /// A cube of `n^3` nodes, one equation each, every cell a clique of
    /// its 8 corners (`8 I - 1` plus a little on the diagonal).
    fn cube(n: usize) -> SymMatrix {
        let id = |i: usize, j: usize, k: usize| i + n * (j + n * k);
        let mut cells = Vec::new();
        for (i, j, k) in (0..n - 1).flat_map(|i| (0..n - 1).flat_map(move |j| (0..n - 1).map(move |k| (i, j, k)))) {
            cells.push((0..8).map(|c| id(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2))).collect::<Vec<usize>>());
        }
        let mut a = SymMatrix::from_cliques(n * n * n, &cells);
        let ke: Vec<f64> = (0..64).map(|e| if e % 9 == 0 { 7.01 } else { -1.0 }).collect();
        for c in &cells {
            a.add(c, &ke);
        }
        a
    }

    /// [`cube`] of 9^3 factorised in nested dissection, and its equations.
    fn cube_factor() -> (SingleCholesky, usize) {
        let k = cube(9);
        let node_of: Vec<usize> = (0..k.n).collect();
        (SingleCholesky::factor(&k, &node_of, Ordering::NestedDissection, 1).expect("positive definite"), k.n)
    }

    /// Each of the sparse `cols` over `n` rows.
    fn dense(cols: &[Vec<(usize, f64)>], n: usize) -> Vec<Vec<f64>> {
        (cols.iter())
            .map(|c| {
                let mut b = vec![0.0; n];
                c.iter().for_each(|&(i, v)| b[i] += v);
                b
            })
            .collect()
    }

    /// Columns of a few non-zeros each (some sharing rows, one at 1e-150,
    /// one empty) give through the supernodes they reach `b^T K^-1 b` of
    /// the solve, to single precision.
    #[test]
    fn sparse_columns_reach_the_energies_of_dense_ones() {
        let (f, n) = cube_factor();
        let mut cols: Vec<Vec<(usize, f64)>> = (0..40)
            .map(|c| {
                (0..1 + c % 5).map(|j| ((c * 37 + j * 101) % n, 1.0 + (c as f64 + j as f64 * 0.3).sin())).collect()
            })
            .collect();
        cols.push(cols[3].iter().map(|&(i, v)| (i, 1e-150 * v)).collect());
        cols.push(Vec::new());
        cols.sort_by_key(|c| f.leaf(c.iter().map(|&(i, _)| i)));
        let dense = dense(&cols, n);
        let want: Vec<f64> = dense.iter().map(|b| b.iter().zip(f.solve(b)).map(|(a, x)| a * x).sum()).collect();
        let got = f.sparse_energies(&cols).expect("a supernodal factor");
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-5 * w.abs(), "b^T K^-1 b: {g:e} against {w:e}");
        }
        assert!(want.iter().filter(|&&w| w > 0.0).count() == cols.len() - 1, "one empty column");
    }

    /// The kept forward substitutions of sparse columns give `a^T K^-1 b`
    /// of every two of them (those whose paths meet only at the top
    /// separators, and one at 1e-150 against one at 1), to single
    /// precision: the sparse interface's entries of W.
    #[test]
    fn forward_substitutions_give_the_products_of_dense_solves() {
        let (f, n) = cube_factor();
        let mut cols: Vec<Vec<(usize, f64)>> = (0..12)
            .map(|c| (0..1 + c % 3).map(|j| ((c * 61 + j * 7) % n, 1.0 + 0.5 * (c + j) as f64)).collect())
            .collect();
        cols.push(cols[5].iter().map(|&(i, v)| (i, 1e-150 * v)).collect());
        let dense = dense(&cols, n);
        // two passes, as the interface forms them: the products cross them
        let (first, second) = cols.split_at(7);
        let mut kept = f.sparse_forward(first).expect("a supernodal factor");
        kept.extend(f.sparse_forward(second).expect("a supernodal factor"));
        for (a, (xa, fa)) in dense.iter().zip(&kept) {
            let solved = f.solve(a);
            for (b, (xb, fb)) in dense.iter().zip(&kept) {
                let want: f64 = b.iter().zip(&solved).map(|(b, x)| b * x).sum();
                let energy = |v: &[f64]| v.iter().zip(f.solve(v)).map(|(v, x)| v * x).sum::<f64>().sqrt();
                let size = energy(a) * energy(b);
                let got = fa * fb * xa.dot(xb);
                assert!((got - want).abs() <= 1e-5 * size, "a^T K^-1 b: {got:e} against {want:e} (of {size:e})");
            }
        }
    }

    /// Two threads substitute what one does, to single precision: the
    /// subtrees below the root separators side by side, and the top's
    /// supernodes by one thread or (all of them wide) by both.
    #[test]
    fn two_threads_give_the_answer_of_one() {
        let k = cube(22);
        let node_of: Vec<usize> = (0..k.n).collect();
        let want: Vec<f64> = (0..k.n).map(|i| 1.0 + (i as f64 * 0.01).sin()).collect();
        let b = k.mul(&want);
        let one = SingleCholesky::factor(&k, &node_of, Ordering::NestedDissection, 1).expect("positive definite");
        let mut two = SingleCholesky::factor(&k, &node_of, Ordering::NestedDissection, 2).expect("positive definite");
        assert!(!one.twofold() && two.twofold(), "a {}-value factor is shared", two.values.len());
        let x1 = one.solve(&b);
        let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let apart =
            |x: &[f64], y: &[f64]| largest(&x.iter().zip(y).map(|(a, b)| a - b).collect::<Vec<_>>()) / largest(y);
        assert!(apart(&x1, &want) < 1e-3, "one thread: {}", apart(&x1, &want));
        let x2 = two.solve(&b);
        assert!(apart(&x2, &x1) < 1e-5, "two threads against one: {}", apart(&x2, &x1));
        let shared = match two.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sn) => Twofold::with(sn, 1),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        };
        assert!(shared.is_some(), "supernodal");
        two.twofold = shared;
        let x3 = two.solve(&b);
        assert!(apart(&x3, &x1) < 1e-5, "every top supernode shared, against one thread: {}", apart(&x3, &x1));
    }
}
