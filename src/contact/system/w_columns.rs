//! The sparse interface's memory of W, the interface condensed onto the
//! relative displacements,
//!
//! ```text
//! W e_i = K_rr e_i - K_rm K_mm^-1 K_mr e_i,
//! ```
//!
//! one column per relative displacement that some solve has left free,
//! over every row of r, computed the first time it is free
//! ([`super::sparse`]) and kept in single precision: it only
//! preconditions, and K_mm^-1 in it is single precision already. Each
//! column is kept over its largest entry, which stays in f64: a scene in
//! units near 1e-200 (tests/wrong_blame.rs) would underflow f32 and leave
//! the block singular. A
//! solve's free block `Z^T W Z` (with the friction law's and the
//! junctions' rows) is formed from them; the pairs that slip change from
//! one contact iteration to the next by a few, so most columns are
//! computed once a step.
//!
//! Where K_mm's factor substitutes sparse columns (single precision and
//! supernodal, as on every large interface) W is kept entry by entry
//! instead ([`super::w_entries`]: the 86k tunnel's 1.15 s of columns and
//! block 0.13 s); these whole columns serve the other factors.
//!
//! When they pay. A column costs about a tenth of a GMRES application
//! (one right-hand side of a batched substitution through K_mm's factor
//! and of a batched product with the parts' S, against one substitution
//! and two sweeps: 0.1 measured on the 86k tunnel's 245 columns and on
//! geo/rockmass.toml's 563), and the exact block saves 5-8 applications a
//! solve (the tunnel capped at 40 contact iterations: 438 applications
//! without columns, 115 with; rockmass: 64 against 20). So the columns
//! pay when the solves that use them number more than about a fiftieth of
//! the columns formed: the tunnel (40 solves, 245 columns) by far,
//! rockmass (7 solves with free pairs, 563 columns: its slipping set still
//! moves) not quite, by about 0.1 s of 1.5. Rules on what a solve knows
//! beforehand (the columns it lacks, the solves so far, the share of its
//! free set free before), replayed on both runs' per-solve counts, either
//! left rockmass as it is or cost the tunnel two to four solves without
//! the block (16-32 applications, 1.3-2.6 s): the number of solves to come
//! decides, and nothing before them tells it. So every solve forms the
//! columns it lacks, within [`MAX_BYTES`].

use std::collections::HashMap;

use super::freedom::Freedom;

/// At most this many bytes of columns are kept: a solve that would need
/// more is preconditioned without them.
pub(super) const MAX_BYTES: usize = 128 << 20;

/// The most bytes the columns over `nr` relative displacements can take:
/// [`MAX_BYTES`], or all `nr` of them in single precision (what the memory
/// estimate counts, [`crate::memory::estimate`]).
pub(crate) fn most_bytes(nr: usize) -> usize {
    MAX_BYTES.min(4 * nr * nr)
}

/// Columns of W by relative displacement; see the module header.
pub(super) struct WColumns {
    nr: usize,
    slot: HashMap<usize, usize>,
    /// Each column over its largest entry, and that entry.
    cols: Vec<(f64, Vec<f32>)>,
}

impl WColumns {
    /// None kept yet, over `nr` relative displacements.
    pub fn new(nr: usize) -> WColumns {
        WColumns { nr, slot: HashMap::new(), cols: Vec::new() }
    }

    /// The relative displacements of `fr`'s free columns that have no
    /// column of W yet (ascending), or None when keeping them would pass
    /// [`MAX_BYTES`].
    pub fn missing(&self, fr: &Freedom) -> Option<Vec<usize>> {
        let mut idx: Vec<usize> =
            fr.cols.iter().flatten().map(|&(i, _)| i).filter(|i| !self.slot.contains_key(i)).collect();
        idx.sort_unstable();
        idx.dedup();
        ((self.cols.len() + idx.len()) * self.nr * 4 <= MAX_BYTES).then_some(idx)
    }

    /// Keeps `cols[k]`, W's column at relative displacement `idx[k]`.
    pub fn add(&mut self, idx: &[usize], cols: Vec<Vec<f64>>) {
        for (&i, c) in idx.iter().zip(cols) {
            self.slot.insert(i, self.cols.len());
            let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let scale = if scale > 0.0 { scale } else { 1.0 };
            self.cols.push((scale, c.iter().map(|&v| (v / scale) as f32).collect()));
        }
    }

    /// `W z` at the rows `rows` of `w` (the others left as they are) for
    /// a free column `z` (relative displacement, coefficient), every one
    /// of whose displacements has a column.
    pub fn times_at(&self, z: &[(usize, f64)], rows: &[usize], w: &mut [f64]) {
        let cols: Vec<(f64, &[f32])> = (z.iter())
            .map(|&(i, zi)| {
                let (scale, col) = &self.cols[self.slot[&i]];
                (zi * scale, &col[..])
            })
            .collect();
        for &r in rows {
            w[r] = cols.iter().fold(0.0, |acc, &(zs, col)| acc + zs * f64::from(col[r]));
        }
    }
}
