//! A part for the iterative interface: its interior factorised alone, and
//! its Schur complement applied, never formed.
//!
//! ```text
//! S x = K_cc x - K_ci K_ii^-1 K_ic x       G = F_c - K_ci K_ii^-1 F_i
//! d_i = K_ii^-1 (F_i - K_ic d_c)
//! ```
//!
//! The interface ordered last ([`super::schur`]) makes every interior
//! separator that touches the interface fill into the interface rows, and
//! the trailing block is a dense nc x nc triangle. Here the interface is
//! not in the factor at all: K_ii alone is ordered and factorised, and the
//! coupling K_ic is kept as its few nonzeros. One application of S is one
//! forward and one backward sweep through that factor.

use std::sync::Arc;

use super::ordering::Ordering;
use super::schur::PartialCholesky;
use crate::fem::sparse::{FactorError, SymMatrix};

/// `K_ii` factorised, with the coupling and interface blocks of the part.
pub struct InteriorSolve {
    chol: PartialCholesky,
    ni: usize,
    nc: usize,
    /// Entries of K_ci: (interface row, interior column, value).
    k_ci: Vec<(u32, u32, f64)>,
    /// Lower triangle of K_cc: (row, column, value), row >= column.
    k_cc: Vec<(u32, u32, f64)>,
}

/// Shared by the part (to recover its interior) and the interface (to apply S).
pub type SharedSolve = Arc<InteriorSolve>;

impl InteriorSolve {
    /// Splits `k` (lower triangle; equations `0..ni` interior, `ni..` interface)
    /// and factorises its interior block.
    pub fn factor(
        k: &SymMatrix,
        ni: usize,
        node_of: &[usize],
        ordering: Ordering,
        par: faer::Par,
    ) -> Result<InteriorSolve, FactorError> {
        let nc = k.n - ni;
        let mut col_ptr = Vec::with_capacity(ni + 1);
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        let (mut k_ci, mut k_cc) = (Vec::new(), Vec::new());
        col_ptr.push(0);
        for j in 0..k.n {
            for p in k.col_ptr[j]..k.col_ptr[j + 1] {
                let (r, v) = (k.row_idx[p], k.values[p]);
                if j >= ni {
                    k_cc.push(((r - ni) as u32, (j - ni) as u32, v));
                } else if r >= ni {
                    k_ci.push(((r - ni) as u32, j as u32, v));
                } else {
                    row_idx.push(r);
                    values.push(v);
                }
            }
            if j < ni {
                col_ptr.push(row_idx.len());
            }
        }
        let k_ii = SymMatrix { n: ni, col_ptr, row_idx, values };
        let chol = PartialCholesky::factor(&k_ii, ni, node_of, ordering, par)?;
        Ok(InteriorSolve { chol, ni, nc, k_ci, k_cc })
    }

    /// Bytes of the factor's values.
    pub fn factor_bytes(&self) -> usize {
        self.chol.stats().values * std::mem::size_of::<f64>()
    }

    /// `S x` for the `k` columns of `x` (column-major, nc rows each). Zero
    /// columns are not solved for (a coarse space's columns are zero on
    /// most parts).
    pub fn apply(&self, x: &[f64], k: usize) -> Vec<f64> {
        let nc = self.nc;
        let nonzero: Vec<usize> = (0..k).filter(|&c| x[c * nc..(c + 1) * nc].iter().any(|&v| v != 0.0)).collect();
        if nonzero.len() == k {
            return self.apply_dense(x, k);
        }
        let packed: Vec<f64> = nonzero.iter().flat_map(|&c| x[c * nc..(c + 1) * nc].iter().copied()).collect();
        let sx = self.apply_dense(&packed, nonzero.len());
        let mut y = vec![0.0; nc * k];
        for (j, &c) in nonzero.iter().enumerate() {
            y[c * nc..(c + 1) * nc].copy_from_slice(&sx[j * nc..(j + 1) * nc]);
        }
        y
    }

    fn apply_dense(&self, x: &[f64], k: usize) -> Vec<f64> {
        let (ni, nc) = (self.ni, self.nc);
        let mut z = vec![0.0; ni * k];
        for &(r, j, v) in &self.k_ci {
            for c in 0..k {
                z[j as usize + c * ni] += v * x[r as usize + c * nc];
            }
        }
        self.chol.solve_many(&mut z, k);
        let mut y = vec![0.0; nc * k];
        for c in 0..k {
            let (x, y) = (&x[c * nc..(c + 1) * nc], &mut y[c * nc..(c + 1) * nc]);
            for &(r, j, v) in &self.k_cc {
                let (r, j) = (r as usize, j as usize);
                y[r] += v * x[j];
                if r != j {
                    y[j] += v * x[r];
                }
            }
        }
        for &(r, j, v) in &self.k_ci {
            for c in 0..k {
                y[r as usize + c * nc] -= v * z[j as usize + c * ni];
            }
        }
        y
    }

    /// The condensed loads `G = F_c - K_ci K_ii^-1 F_i` of the load vectors
    /// `f` (each `[F_i; F_c]`), all cases in one solve; also `K_ii^-1 F_i`
    /// (column-major, ni per case), for the backward error.
    pub fn condensed_loads(&self, f: &[Vec<f64>]) -> (Vec<Vec<f64>>, Vec<f64>) {
        let ni = self.ni;
        let mut x: Vec<f64> = f.iter().flat_map(|fk| fk[..ni].iter().copied()).collect();
        self.chol.solve_many(&mut x, f.len());
        let g = f
            .iter()
            .enumerate()
            .map(|(case, fk)| {
                let mut g = fk[ni..].to_vec();
                for &(r, j, v) in &self.k_ci {
                    g[r as usize] -= v * x[j as usize + case * ni];
                }
                g
            })
            .collect();
        (g, x)
    }

    /// The interior displacements `K_ii^-1 (F_i - K_ic d_c)` for the load
    /// `f = [F_i; F_c]` and the interface displacements `d_c`.
    pub fn interior(&self, f: &[f64], d_c: &[f64]) -> Vec<f64> {
        let mut x = f[..self.ni].to_vec();
        for &(r, j, v) in &self.k_ci {
            x[j as usize] -= v * d_c[r as usize];
        }
        self.chol.solve_many(&mut x, 1);
        x
    }

    /// The `nd x nd` diagonal block of K_cc at each interface node
    /// (row-major per node): a cheap stand-in for S's diagonal blocks.
    pub fn diagonal_blocks(&self, nd: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.nc * nd];
        for &(r, j, v) in &self.k_cc {
            let (r, j) = (r as usize, j as usize);
            if r / nd == j / nd {
                let (q, a, b) = (r / nd, r % nd, j % nd);
                out[q * nd * nd + a * nd + b] = v;
                out[q * nd * nd + b * nd + a] = v;
            }
        }
        out
    }
}
