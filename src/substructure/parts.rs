//! Parts: the pieces of the model that are condensed one by one.
//!
//! Bodies that share nodes move as one, so they form one part (a dam's
//! blocks joined where their joints end on the base). With
//! `[solver] substructures = K` each part of enough cells is cut further
//! into K pieces by METIS (`METIS_PartMeshDual`: cells joined through shared
//! faces, balanced by cell count, the cut minimised). The pieces keep their
//! shared nodes (bonded joins): such a node is on the interface of every
//! piece that has it and is always tied, so the answer is the uncut one;
//! each piece is factorised alone, in its own thread or on its own MPI rank.
//!
//! A part's interface is every node it shares: contact pair nodes, and
//! joins with other pieces.

use crate::fem::sparse::NONE;
use crate::model::topology::UnionFind;
use crate::model::{Model, PartName};

/// One part: its cells, the bodies they belong to, and the nodes it shares.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Part {
    /// The bodies the part's cells belong to (for messages), ascending.
    pub bodies: Vec<usize>,
    /// The part's cells: (body, index in that body's `cells`), ascending.
    pub cells: Vec<(usize, usize)>,
    /// Model nodes of this part that are in contact pairs or shared with
    /// another part, ascending.
    pub interface: Vec<usize>,
    /// (piece, pieces) when cut from a larger part.
    pub piece: Option<(usize, usize)>,
}

impl Part {
    /// The part's nodes, ascending.
    pub fn nodes(&self, model: &Model) -> Vec<usize> {
        let mut nodes: Vec<usize> =
            self.cells.iter().flat_map(|&(b, c)| model.bodies[b].cells[c].nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// Its bodies' labels and its piece, for a message.
    pub fn describe(&self, model: &Model) -> PartName {
        PartName { bodies: self.bodies.iter().map(|&b| model.bodies[b].label()).collect(), piece: self.piece }
    }
}

/// Groups bodies into parts by shared model nodes.
pub fn parts(model: &Model) -> Vec<Part> {
    let mut sets = UnionFind::new(model.bodies.len());
    let mut owner = vec![NONE; model.n_nodes()];
    for (b, body) in model.bodies.iter().enumerate() {
        for c in &body.cells {
            for &n in &c.nodes {
                if owner[n] == NONE {
                    owner[n] = b;
                } else {
                    sets.join(owner[n], b);
                }
            }
        }
    }
    let mut parts: Vec<Part> = sets
        .groups()
        .into_iter()
        .map(|bodies| {
            let cells = bodies.iter().flat_map(|&b| (0..model.bodies[b].cells.len()).map(move |c| (b, c))).collect();
            Part { bodies, cells, interface: Vec::new(), piece: None }
        })
        .collect();
    set_interfaces(model, &mut parts);
    parts
}

/// Every part's interface: its pair nodes and the nodes it shares with
/// other parts.
fn set_interfaces(model: &Model, parts: &mut [Part]) {
    let mut in_pair = vec![false; model.n_nodes()];
    for p in &model.pairs {
        in_pair[p.k] = true;
        in_pair[p.l] = true;
    }
    let mut holders = vec![0u32; model.n_nodes()];
    let nodes: Vec<Vec<usize>> = parts.iter().map(|p| p.nodes(model)).collect();
    for list in &nodes {
        for &n in list {
            holders[n] += 1;
        }
    }
    for (p, list) in parts.iter_mut().zip(&nodes) {
        p.interface = list.iter().copied().filter(|&n| in_pair[n] || holders[n] > 1).collect();
    }
}

/// The unknowns of a model cut into `parts`, as a run counts them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DofCounts {
    /// Interior free DOFs of every part plus the interface DOFs.
    pub total: usize,
    /// DOFs of the nodes the parts share: a pair node with all its
    /// components, a join between pieces with its free ones; each node once.
    pub interface: usize,
}

/// The DOFs of `parts` without assembling them (`subcontact check`): the
/// same numbers as [`super::numbering`] gives part by part.
pub fn dof_counts(model: &Model, parts: &[Part]) -> DofCounts {
    let nd = model.nd;
    let free = |n: usize| (0..nd).filter(|&c| model.prescribed[n * nd + c].is_none()).count();
    let mut in_pair = vec![false; model.n_nodes()];
    for p in &model.pairs {
        in_pair[p.k] = true;
        in_pair[p.l] = true;
    }
    let mut shared = vec![false; model.n_nodes()];
    for &n in parts.iter().flat_map(|p| &p.interface) {
        shared[n] = true;
    }
    let interface: usize =
        (0..model.n_nodes()).filter(|&n| shared[n]).map(|n| if in_pair[n] { nd } else { free(n) }).sum();
    // a node that is not shared belongs to one part
    let mut used = vec![false; model.n_nodes()];
    for &k in model.bodies.iter().flat_map(|b| &b.cells).flat_map(|c| &c.nodes) {
        used[k] = true;
    }
    let interior: usize = (0..model.n_nodes()).filter(|&n| used[n] && !shared[n]).map(free).sum();
    DofCounts { total: interior + interface, interface }
}

/// The fewest cells a part needs to be cut into `k` pieces (fewer: kept whole).
pub const MIN_CELLS_PER_PIECE: usize = 8;

/// Cuts every part of at least `k * MIN_CELLS_PER_PIECE` cells into `k`
/// pieces (METIS, cells joined through their faces); `k <= 1` keeps them.
pub fn cut(model: &Model, parts: Vec<Part>, k: usize) -> Vec<Part> {
    if k <= 1 {
        return parts;
    }
    let mut out = Vec::new();
    for part in parts {
        if part.cells.len() < k * MIN_CELLS_PER_PIECE {
            out.push(part);
            continue;
        }
        let piece_of = partition(model, &part.cells, k);
        let mut pieces: Vec<Part> = (0..k)
            .map(|i| Part { bodies: Vec::new(), cells: Vec::new(), interface: Vec::new(), piece: Some((i, k)) })
            .collect();
        for (&cell, &i) in part.cells.iter().zip(&piece_of) {
            pieces[i].cells.push(cell);
        }
        for p in &mut pieces {
            p.bodies = p.cells.iter().map(|&(b, _)| b).collect();
            p.bodies.dedup();
        }
        out.extend(pieces.into_iter().filter(|p| !p.cells.is_empty()));
    }
    set_interfaces(model, &mut out);
    out
}

/// The piece (0..k) of every cell, by `METIS_PartMeshDual` on the cells'
/// corner nodes (two cells are neighbours when they share a face: 2 corners
/// in 2D, 3 in 3D).
fn partition(model: &Model, cells: &[(usize, usize)], k: usize) -> Vec<usize> {
    use metis_sys::idx_t;
    let mut id = std::collections::HashMap::new();
    let mut eptr: Vec<idx_t> = vec![0];
    let mut eind: Vec<idx_t> = Vec::new();
    for &(b, c) in cells {
        let cell = &model.bodies[b].cells[c];
        for &n in &cell.nodes[..cell.kind.n_corners()] {
            let next = id.len() as idx_t;
            eind.push(*id.entry(n).or_insert(next));
        }
        eptr.push(eind.len() as idx_t);
    }
    let mut ne = cells.len() as idx_t;
    let mut nn = id.len() as idx_t;
    let mut ncommon: idx_t = if model.nd == 3 { 3 } else { 2 };
    let mut nparts = k as idx_t;
    let mut objval: idx_t = 0;
    let mut epart: Vec<idx_t> = vec![0; cells.len()];
    let mut npart: Vec<idx_t> = vec![0; id.len()];
    let mut options = [0 as idx_t; metis_sys::METIS_NOPTIONS as usize];
    let _one = super::ordering::metis_lock();
    // SAFETY: the arrays have the lengths METIS reads (ne + 1, eptr[ne], ne,
    // nn, METIS_NOPTIONS) and outlive the call; METIS keeps no pointer.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        options[metis_sys::moptions_et_METIS_OPTION_NUMBERING as usize] = 0;
        metis_sys::METIS_PartMeshDual(
            &mut ne,
            &mut nn,
            eptr.as_mut_ptr(),
            eind.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            &mut ncommon,
            &mut nparts,
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            &mut objval,
            epart.as_mut_ptr(),
            npart.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        // a failed cut is not an error: the part stays in one piece
        return vec![0; cells.len()];
    }
    epart.into_iter().map(|p| (p as usize).min(k - 1)).collect()
}
