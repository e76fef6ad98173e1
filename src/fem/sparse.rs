//! Symmetric sparse matrices (lower triangle, compressed columns) built from
//! element connectivity, and their sparse Cholesky factorisation (faer,
//! supernodal, AMD ordering, sequential).
//!
//! DOF numbering is the caller's: `dof_of[node * nd + c]` is the equation
//! number of component `c` of `node`, or [`NONE`] for a DOF that is not an
//! unknown (supported, or not part of this matrix).

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::linalg::LltError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{MatMut, Side};

/// Marks a DOF that is not an unknown of the matrix.
pub const NONE: usize = usize::MAX;

/// A symmetric matrix stored as its lower triangle in CSC form.
#[derive(Clone, Debug)]
pub struct SymMatrix {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
}

impl SymMatrix {
    /// The sparsity pattern of the lower triangle for cells given by their
    /// node lists, with `nd` DOFs per node numbered by `dof_of`.
    pub fn pattern<'a>(n: usize, nd: usize, dof_of: &[usize], cells: impl Iterator<Item = &'a [usize]>) -> SymMatrix {
        // a node stands for itself by its lowest equation, so that the work
        // arrays are the matrix's size, not the model's: a block of the
        // 1,000-block cube has 81 of the model's 79,600 nodes, and an
        // adjacency list per model node for each block took 2.6 % of the
        // run's CPU; a node without an equation has no column
        let lowest = |node: usize| (0..nd).map(|c| dof_of[node * nd + c]).min().filter(|&d| d != NONE);
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
        // the lowest equation of each equation's node
        let mut node_of = vec![NONE; n];
        for nodes in cells {
            for &a in nodes {
                let Some(k) = lowest(a) else { continue };
                adj[k].extend(nodes.iter().map(|&b| b as u32));
                for c in 0..nd {
                    let d = dof_of[a * nd + c];
                    if d != NONE {
                        node_of[d] = k;
                    }
                }
            }
        }
        for list in adj.iter_mut().filter(|l| !l.is_empty()) {
            list.sort_unstable();
            list.dedup();
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        let mut rows = Vec::new();
        for col in 0..n {
            rows.clear();
            let node: &[u32] = if node_of[col] == NONE { &[] } else { &adj[node_of[col]] };
            for &j in node {
                for c in 0..nd {
                    let r = dof_of[j as usize * nd + c];
                    if r != NONE && r >= col {
                        rows.push(r);
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

    /// The lower triangle of a matrix made of dense cliques (the unknowns
    /// of each clique coupled to one another, e.g. a substructure's
    /// interface), every diagonal entry present. Unlike [`Self::pattern`]
    /// it keeps no adjacency lists: a column's rows are gathered from the
    /// cliques that hold it.
    pub fn from_cliques(n: usize, cliques: &[Vec<usize>]) -> SymMatrix {
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

    /// Adds an element matrix `ke` (row-major, `dofs.len()` square) at the
    /// equations `dofs` ([`NONE`] entries are skipped).
    pub fn add(&mut self, dofs: &[usize], ke: &[f64]) {
        let m = dofs.len();
        for b in 0..m {
            let col = dofs[b];
            if col == NONE {
                continue;
            }
            let (lo, hi) = (self.col_ptr[col], self.col_ptr[col + 1]);
            let rows = &self.row_idx[lo..hi];
            for a in 0..m {
                let row = dofs[a];
                if row == NONE || row < col {
                    continue;
                }
                if let Ok(k) = rows.binary_search(&row) {
                    self.values[lo + k] += ke[a * m + b];
                }
            }
        }
    }

    /// Entry (row, col) of the full symmetric matrix (zero outside the pattern).
    pub fn get(&self, row: usize, col: usize) -> f64 {
        let (r, c) = if row >= col { (row, col) } else { (col, row) };
        let (lo, hi) = (self.col_ptr[c], self.col_ptr[c + 1]);
        match self.row_idx[lo..hi].binary_search(&r) {
            Ok(k) => self.values[lo + k],
            Err(_) => 0.0,
        }
    }

    /// y = A x with the full symmetric matrix.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for col in 0..self.n {
            for k in self.col_ptr[col]..self.col_ptr[col + 1] {
                let row = self.row_idx[k];
                let v = self.values[k];
                y[row] += v * x[col];
                if row != col {
                    y[col] += v * x[row];
                }
            }
        }
        y
    }

    /// Normwise backward error of `x` as a solution of `(A + shift) x = b`,
    /// `||A' x - b|| / (||A'|| ||x|| + ||b||)` in the infinity norm, where
    /// `shift` adds `alpha` to the diagonal from equation `from` on.
    pub fn backward_error(&self, x: &[f64], b: &[f64], alpha: f64, from: usize) -> f64 {
        let mut r = self.mul(x);
        let mut row_abs = vec![0.0; self.n];
        for col in 0..self.n {
            for k in self.col_ptr[col]..self.col_ptr[col + 1] {
                let (row, v) = (self.row_idx[k], self.values[k].abs());
                row_abs[row] += v;
                if row != col {
                    row_abs[col] += v;
                }
            }
        }
        for i in from..self.n {
            r[i] += alpha * x[i];
            row_abs[i] += alpha;
        }
        let inf = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0, |m: f64, a| m.max(a.abs()));
        let rn = inf(&mut r.iter().zip(b).map(|(a, b)| a - b));
        let den = inf(&mut row_abs.iter().copied()) * inf(&mut x.iter().copied()) + inf(&mut b.iter().copied());
        if den > 0.0 {
            rn / den
        } else {
            0.0
        }
    }
}

/// Why a factorisation failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum FactorError {
    /// The matrix is not positive definite: some rigid-body motion is free.
    #[error("the stiffness matrix is singular or indefinite (a rigid-body motion is not held)")]
    NotPositiveDefinite,
    /// Memory or another resource ran out.
    #[error("sparse factorisation failed: {0}")]
    Resource(String),
}

/// Sparse Cholesky factor `A = L L^T` of a [`SymMatrix`].
pub struct Cholesky {
    llt: Llt<usize, f64>,
    pub n: usize,
}

impl Cholesky {
    pub fn factor(a: &SymMatrix) -> Result<Cholesky, FactorError> {
        if a.n == 0 {
            return Err(FactorError::NotPositiveDefinite);
        }
        let symbolic = SymbolicSparseColMat::new_checked(a.n, a.n, a.col_ptr.clone(), None, a.row_idx.clone());
        let mat = SparseColMat::new(symbolic, a.values.clone());
        let sym =
            SymbolicLlt::try_new(mat.symbolic(), Side::Lower).map_err(|e| FactorError::Resource(format!("{e:?}")))?;
        let llt = Llt::try_new_with_symbolic(sym, mat.as_ref(), Side::Lower).map_err(|e| match e {
            LltError::Numeric(_) => FactorError::NotPositiveDefinite,
            LltError::Generic(g) => FactorError::Resource(format!("{g:?}")),
        })?;
        Ok(Cholesky { llt, n: a.n })
    }

    /// Solves `A x = b` in place for one right-hand side.
    pub fn solve(&self, b: &mut [f64]) {
        let m = MatMut::from_column_major_slice_mut(b, self.n, 1);
        self.llt.solve_in_place(m);
    }

    /// Solves `A X = B` in place for the columns of `b` (column-major, `n x k`).
    pub fn solve_many(&self, b: &mut [f64], k: usize) {
        let m = MatMut::from_column_major_slice_mut(b, self.n, k);
        self.llt.solve_in_place(m);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D chain of springs 0-1-2-3 with node 0 held: K is tridiagonal.
    fn chain() -> SymMatrix {
        let dof_of = [NONE, 0, 1, 2];
        let cells: Vec<[usize; 2]> = vec![[0, 1], [1, 2], [2, 3]];
        let mut a = SymMatrix::pattern(3, 1, &dof_of, cells.iter().map(|c| &c[..]));
        for c in &cells {
            let dofs = [dof_of[c[0]], dof_of[c[1]]];
            a.add(&dofs, &[1.0, -1.0, -1.0, 1.0]);
        }
        a
    }

    /// The pattern is every pair of equations two nodes of a cell carry,
    /// whatever their numbering: two components a node, some of them
    /// supported, equations numbered out of node order, a node in no cell
    /// (its equations columns without rows) and nodes with no equation.
    #[test]
    fn the_pattern_is_every_pair_of_equations_a_cell_couples() {
        let (n_nodes, nd) = (30, 2);
        let mut rng = crate::test_rng::Lcg::new(7);
        let mut dof_of = vec![NONE; n_nodes * nd];
        let mut n = 0;
        for slot in (0..n_nodes * nd).rev().filter(|&i| i % 7 != 3 && i / nd != 4) {
            dof_of[slot] = n;
            n += 1;
        }
        // node 29 is in no cell
        let cells: Vec<Vec<usize>> = (0..12).map(|_| (0..4).map(|_| rng.below(29)).collect()).collect();
        let a = SymMatrix::pattern(n, nd, &dof_of, cells.iter().map(|c| c.as_slice()));
        let mut expected = std::collections::BTreeSet::new();
        for cell in &cells {
            for (&x, &y) in cell.iter().flat_map(|x| cell.iter().map(move |y| (x, y))) {
                for (cx, cy) in (0..nd).flat_map(|cx| (0..nd).map(move |cy| (cx, cy))) {
                    let (i, j) = (dof_of[x * nd + cx], dof_of[y * nd + cy]);
                    if i != NONE && j != NONE && i >= j {
                        expected.insert((j, i));
                    }
                }
            }
        }
        let got: std::collections::BTreeSet<(usize, usize)> =
            (0..n).flat_map(|j| a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]].iter().map(move |&i| (j, i))).collect();
        assert_eq!(a.row_idx.len(), got.len(), "no row twice");
        assert_eq!(got, expected);
        let lonely: Vec<usize> = dof_of[29 * nd..].iter().copied().filter(|&d| d != NONE).collect();
        assert!(!lonely.is_empty() && lonely.iter().all(|&d| a.col_ptr[d] == a.col_ptr[d + 1]), "node 29's columns");
    }

    #[test]
    fn the_pattern_of_two_cliques_is_their_union() {
        let k = SymMatrix::from_cliques(4, &[vec![0, 2], vec![1, 2, 3]]);
        let cols: Vec<Vec<usize>> = (0..4).map(|j| k.row_idx[k.col_ptr[j]..k.col_ptr[j + 1]].to_vec()).collect();
        assert_eq!(cols, vec![vec![0, 2], vec![1, 2, 3], vec![2, 3], vec![3]]);
    }

    #[test]
    fn chain_of_springs_solves_exactly() {
        let a = chain();
        assert_eq!(a.row_idx.len(), 5);
        assert_eq!(a.get(0, 0), 2.0);
        assert_eq!(a.get(2, 2), 1.0);
        assert_eq!(a.get(0, 1), -1.0);
        let chol = Cholesky::factor(&a).expect("positive definite");
        // unit force at the free end: displacements 1, 2, 3
        let mut x = vec![0.0, 0.0, 1.0];
        chol.solve(&mut x);
        for (i, v) in x.iter().enumerate() {
            assert!((v - (i + 1) as f64).abs() < 1e-12);
        }
        let y = a.mul(&x);
        assert!((y[2] - 1.0).abs() < 1e-12 && y[0].abs() < 1e-12);
    }

    #[test]
    fn unsupported_chain_is_reported_singular() {
        let dof_of = [0, 1];
        let mut a = SymMatrix::pattern(2, 1, &dof_of, std::iter::once(&[0usize, 1][..]));
        a.add(&[0, 1], &[1.0, -1.0, -1.0, 1.0]);
        assert!(matches!(Cholesky::factor(&a), Err(FactorError::NotPositiveDefinite)));
    }
}
