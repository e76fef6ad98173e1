//! The sparse interface's memory of W, the interface condensed onto the
//! relative displacements, entry by entry where K_mm's factor allows it:
//!
//! ```text
//! W_ab = K_rr,ab - (K_mr e_a)^T K_mm^-1 (K_mr e_b)
//!      = K_rr,ab - f_a f_b (L^-1 P K_mr e_a) . (L^-1 P K_mr e_b)
//! ```
//!
//! with `K_mm = P^T L L^T P` (through the bonded model's factor, whose
//! interiors the columns are zero on, the same). A column `K_mr e_a` is
//! non-zero on the means of the one or two parts that hold `a`, so its
//! forward substitution reaches only the supernodes on its path to the
//! root ([`crate::substructure::sparse_forward`]), and two of them meet
//! only on the separators above both. The exact block reads W at a few
//! hundred rows and columns (the free relative displacements, the
//! slipping pairs' normal rows, the junctions'): each displacement's
//! forward substitution is kept, each entry formed the first time it is
//! read and kept too. Where the whole columns of W ([`super::w_columns`])
//! cost a substitution forward and back through the whole factor and a
//! product with every part's S, one per column: the 86k tunnel's 266
//! columns 0.97 s.

use super::threads::in_threads;
use super::w_columns::MAX_BYTES;
use crate::substructure::sparse_forward::Forward;

/// No slot (a displacement without a forward substitution).
const NONE: usize = usize::MAX;

/// W's entries kept and what they are formed from, by slot (the order the
/// displacements were added in); see the module header.
pub(super) struct WEntries {
    /// The slot of each relative displacement, [`NONE`] where it has none.
    slot_of: Vec<usize>,
    /// Each slot's displacement, its `L^-1 P K_mr e_a` and its `f_a`.
    displacement: Vec<usize>,
    forward: Vec<(Forward, f64)>,
    /// K_rr's column at each slot: (relative row, value), ascending.
    k_rr: Vec<Vec<(usize, f64)>>,
    /// W's column at each slot over the slots, NaN where not formed.
    cols: Vec<Vec<f64>>,
    /// The bytes the forward substitutions and K_rr's columns hold.
    bytes: usize,
    /// The displacements some block has had a free column at, and how many.
    column: Vec<bool>,
    columns: usize,
}

impl WEntries {
    /// None kept yet, over `nr` relative displacements.
    pub fn new(nr: usize) -> WEntries {
        WEntries {
            slot_of: vec![NONE; nr],
            displacement: Vec::new(),
            forward: Vec::new(),
            k_rr: Vec::new(),
            cols: Vec::new(),
            bytes: 0,
            column: vec![false; nr],
            columns: 0,
        }
    }

    /// Whether a block over the free columns `cols` is formed: where the
    /// whole columns of W at every displacement free so far would fit in
    /// [`MAX_BYTES`], as with them ([`super::w_columns`]). Beyond, the
    /// blocks grow too (the 1,000-block cube's first: 2,900 free
    /// columns), and their entries and LU took 297 s of its run. Counts
    /// the columns of a block admitted.
    pub fn admit(&mut self, cols: &[Vec<(usize, f64)>]) -> bool {
        let mut new: Vec<usize> = cols.iter().flatten().map(|&(i, _)| i).filter(|&i| !self.column[i]).collect();
        new.sort_unstable();
        new.dedup();
        if !self.room(new.len()) {
            return false;
        }
        new.iter().for_each(|&i| self.column[i] = true);
        self.columns += new.len();
        true
    }

    /// Whether `more` displacements could still have free columns: what
    /// W's diagonal keeps its forward substitutions by
    /// ([`WEntries::admit`]'s bound; the cubes of make bench-blocks,
    /// whose blocks it refuses, substitute their diagonal's columns
    /// without keeping them).
    pub fn room(&self, more: usize) -> bool {
        (self.columns + more) * self.column.len() * 4 <= MAX_BYTES && self.bytes() <= MAX_BYTES
    }

    /// Of `idx`, the relative displacements with no forward substitution
    /// yet, ascending.
    pub fn missing(&self, idx: &[usize]) -> Vec<usize> {
        let mut m: Vec<usize> = idx.iter().copied().filter(|&i| self.slot_of[i] == NONE).collect();
        m.sort_unstable();
        m.dedup();
        m
    }

    /// Keeps displacement `a`'s forward substitution (and `f_a`) and its
    /// column of K_rr (relative rows, ascending).
    pub fn add(&mut self, a: usize, forward: (Forward, f64), k_rr: Vec<(usize, f64)>) {
        self.bytes += forward.0.bytes() + 16 * k_rr.len();
        self.slot_of[a] = self.forward.len();
        self.displacement.push(a);
        self.forward.push(forward);
        self.k_rr.push(k_rr);
        self.cols.push(Vec::new());
    }

    /// The bytes held.
    pub fn bytes(&self) -> usize {
        self.bytes + 8 * self.cols.iter().map(Vec::len).sum::<usize>()
    }

    /// Forms W's entries at `rows` and the displacements of `cols` not
    /// formed yet, in `threads`: each a product of two forward
    /// substitutions ([`Forward::dot`]). Every one of them has its
    /// forward substitution.
    pub fn form(&mut self, rows: &[usize], cols: &[Vec<(usize, f64)>], threads: usize) {
        let mut at: Vec<usize> = cols.iter().flatten().map(|&(c, _)| self.slot_of[c]).collect();
        at.sort_unstable();
        at.dedup();
        let rows: Vec<usize> = rows.iter().map(|&r| self.slot_of[r]).collect();
        let wanted: Vec<(usize, usize)> = (at.iter())
            .flat_map(|&j| rows.iter().map(move |&i| (i, j)))
            .filter(|&(i, j)| self.cols[j].get(i).is_none_or(|w| w.is_nan()))
            .collect();
        let values = in_threads(&wanted, threads, |&(i, j)| {
            let ((xi, fi), (xj, fj)) = (&self.forward[i], &self.forward[j]);
            let k = &self.k_rr[j];
            let k_ij = k.binary_search_by_key(&self.displacement[i], |e| e.0).map_or(0.0, |at| k[at].1);
            k_ij - fi * fj * xi.dot(xj)
        });
        for (&(i, j), w) in wanted.iter().zip(values) {
            for (a, b) in [(i, j), (j, i)] {
                let col = &mut self.cols[b];
                if col.len() <= a {
                    col.resize(a + 1, f64::NAN);
                }
                col[a] = w;
            }
        }
    }

    /// `(K_mr e_a)^T K_mm^-1 K_mr e_a`, what K_mm takes off W's diagonal
    /// at a displacement with a forward substitution.
    pub fn energy(&self, a: usize) -> f64 {
        let (x, f) = &self.forward[self.slot_of[a]];
        f * f * x.dot(x)
    }

    /// `W z` at the rows `rows` of `w` (the others left as they are) for a
    /// free column `z` (relative displacement, coefficient), all formed
    /// ([`WEntries::form`]).
    pub fn times_at(&self, z: &[(usize, f64)], rows: &[usize], w: &mut [f64]) {
        let cols: Vec<(&[f64], f64)> = z.iter().map(|&(c, zc)| (&self.cols[self.slot_of[c]][..], zc)).collect();
        for &r in rows {
            let i = self.slot_of[r];
            w[r] = cols.iter().map(|&(col, zc)| zc * col[i]).sum();
        }
    }
}
