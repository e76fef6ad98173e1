//! A part's own stiffness, interior and interface, with its interface in
//! the interface's basis: what the sides' factor ([`super::sides`]) takes
//! where every pair deforms, and K_mm's factor ([`super::means_whole`])
//! where pairs are tied, in place of the part's dense S.
//!
//! With the interface DOFs written `d_c = M d'` (M = Q T^T: the face basis
//! and the pairs' frames, [`super::coords::localise`]),
//!
//! ```text
//! K' = [K_ii     K_ic M    ]      its Schur complement onto d' is
//!      [M^T K_ci M^T K_cc M]      M^T S M, the part's localised S
//! ```
//!
//! so a factor of the parts' K' side by side, with the springs between
//! their sides, solves what the factor of their S does: a right-hand side
//! on the sides' DOFs, zero on the interiors, gives the sides' answer. But
//! S is a dense clique over a part's interface, which nested dissection
//! cannot cut, while K' keeps the mesh's sparsity: on the 86k tunnel
//! (148 blocks, 63,450 interface DOFs) the factor over the parts' S held
//! 114 million values, the one over their K' 63 million, for 36,000 more
//! DOFs (the interiors).
//!
//! The parts are assembled again here (0.4 s of the 86k tunnel's 7.7, in
//! two threads) rather than each keeping its K past its condensation: a
//! part condensed on another MPI rank is assembled the same way on rank 0.

use super::coords::localise;
use crate::contact::frame::Frame;
use crate::fem::sparse::SymMatrix;
use crate::model::Model;
use crate::substructure::{assembly, interior_nodes, numbering, Part};

/// A part's stiffness `K'` in the interface's basis; see the module header.
pub(super) struct Own {
    /// Interior DOFs, numbered first; the interface's follow in the part's
    /// order (that of its S and its terms).
    pub ni: usize,
    /// The model node of each interior DOF.
    pub nodes: Vec<usize>,
    /// The lower triangle (row >= column) over `0..ni + nc`.
    pub entries: Vec<(u32, u32, f64)>,
}

impl Own {
    /// The entries `part`'s K' would hold, counted from its mesh's pattern
    /// (the lower triangle over its interior and interface DOFs) without
    /// assembling it: what [`super::sparse`] weighs K_mm's two factors by.
    pub fn count(model: &Model, part: &Part) -> usize {
        let (dof_of, ni, nc) = numbering(model, part);
        let cells = part.cells.iter().map(|&(b, c)| model.bodies[b].cells[c].nodes.as_slice());
        SymMatrix::pattern(ni + nc, model.nd, &dof_of, cells).row_idx.len()
    }

    /// `part`'s K' with its interface nodes' `frames` and transformed face
    /// `edges`; None where it cannot be assembled (it was when condensed).
    pub fn of(model: &Model, part: &Part, frames: &[Frame], edges: &[[usize; 3]]) -> Option<Own> {
        let (dof_of, ni, nc) = numbering(model, part);
        let k = assembly::assemble(model, &part.cells, &dof_of, ni + nc).ok()?.k;
        let mut entries = Vec::new();
        // K_cc dense (both triangles), and the interior rows that reach the
        // interface as dense rows of K_ic
        let mut k_cc = vec![0.0; nc * nc];
        let mut row_of = vec![usize::MAX; ni];
        let (mut rows, mut which): (Vec<Vec<f64>>, Vec<usize>) = (Vec::new(), Vec::new());
        for c in 0..k.n {
            for e in k.col_ptr[c]..k.col_ptr[c + 1] {
                let (r, v) = (k.row_idx[e], k.values[e]);
                if c >= ni {
                    k_cc[(r - ni) + (c - ni) * nc] = v;
                    k_cc[(c - ni) + (r - ni) * nc] = v;
                } else if r >= ni {
                    if row_of[c] == usize::MAX {
                        row_of[c] = rows.len();
                        rows.push(vec![0.0; nc]);
                        which.push(c);
                    }
                    rows[row_of[c]][r - ni] = v;
                } else {
                    entries.push((r as u32, c as u32, v));
                }
            }
        }
        let (k_cc, rows) = localise(&k_cc, &rows, model.nd, frames, edges);
        let at = |u: usize| (ni + u) as u32;
        for (&c, row) in which.iter().zip(&rows) {
            entries.extend(row.iter().enumerate().filter(|e| *e.1 != 0.0).map(|(u, &v)| (at(u), c as u32, v)));
        }
        for v in 0..nc {
            entries
                .extend((v..nc).map(|u| (u, k_cc[u + v * nc])).filter(|e| e.1 != 0.0).map(|(u, x)| (at(u), at(v), x)));
        }
        Some(Own { ni, nodes: interior_nodes(&dof_of, model.nd, ni), entries })
    }
}
