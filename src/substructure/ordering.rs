//! Fill-reducing orderings of a part's interior equations (the interface
//! stays last, see [`super::schur`]): AMD on the equation graph, or nested
//! dissection (METIS `METIS_NodeND`) on the node graph expanded to the
//! node's equations.
//!
//! An ordering is a forward permutation `fwd` with `fwd[new] = old` (faer's
//! convention, and METIS's `perm`; its `iperm` is the inverse `inv[old] =
//! new`). Swapping the two fails silently: the factor is still right but
//! its fill grows several times.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

use crate::fem::sparse::{FactorError, SymMatrix};

/// Which fill-reducing ordering the interior gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree on the equation graph (faer).
    Amd,
    /// Nested dissection on the node graph (METIS).
    NestedDissection,
}

impl Ordering {
    /// The ordering for a part of `ni` interior equations with `nd`
    /// components per node: nested dissection for 3D parts of 5,000 interior
    /// equations or more, AMD otherwise.
    ///
    /// Measured on this machine (block on block; flops of the supernodal
    /// factor, time of ordering + factorisation, sequential, other builds
    /// running), AMD -> nested dissection per part:
    ///
    /// | part | interior eqs | factor flops | time (s) |
    /// |---|---|---|---|
    /// | hex20, lc 0.25 | 885 | 6.1e7 -> 4.5e7 | 0.012 -> 0.039 |
    /// | tet10, lc 0.2 | 1,626 | 1.4e8 -> 1.2e8 | 0.027 -> 0.025 |
    /// | hex20, lc 0.125 | 6,669 | 6.0e9 -> 2.4e9 | 0.40 -> 0.29 |
    /// | tet10, lc 0.1 | 10,044 | 8.4e9 -> 5.3e9 | 0.54 -> 0.46 |
    /// | hex20, lc 0.0625 | 51,357 | 5.3e11 -> 1.6e11 | 16.3 -> 6.5 |
    /// | quad9 cylinder, lc 0.0125 | 323,247 | 1.8e10-3.0e10 -> 1.2e10 | 1.7-2.3 -> 3.0-3.3 |
    ///
    /// In 2D METIS saves flops but not time: it orders the 2D node graph in
    /// 1.5 s where AMD takes 0.3 s, more than the factorisation saves.
    pub fn choose(ni: usize, nd: usize) -> Ordering {
        if nd == 3 && ni >= 5_000 {
            Ordering::NestedDissection
        } else {
            Ordering::Amd
        }
    }
}

/// The forward permutation of the interior equations `0..ni` of `k` (lower
/// triangle, CSC) by `ordering`. `node_of[e]` names the node of interior
/// equation `e` (any ids below `node_of.len()`): nested dissection orders
/// the nodes and keeps each node's equations together.
pub fn interior(k: &SymMatrix, ni: usize, node_of: &[usize], ordering: Ordering) -> Result<Vec<usize>, FactorError> {
    if ni == 0 {
        // a block whose every node is on its interface (one element between joints)
        return Ok(Vec::new());
    }
    match ordering {
        Ordering::Amd => amd_order(k, ni),
        Ordering::NestedDissection => nested_dissection(k, ni, node_of),
    }
}

fn resource(e: &dyn std::fmt::Debug) -> FactorError {
    FactorError::Resource(format!("{e:?}"))
}

/// AMD on the interior block (its lower triangle; AMD orders A + A^T).
fn amd_order(k: &SymMatrix, ni: usize) -> Result<Vec<usize>, FactorError> {
    let mut ii_ptr = Vec::with_capacity(ni + 1);
    let mut ii_idx = Vec::new();
    ii_ptr.push(0);
    for c in 0..ni {
        ii_idx.extend(k.row_idx[k.col_ptr[c]..k.col_ptr[c + 1]].iter().copied().filter(|&r| r < ni));
        ii_ptr.push(ii_idx.len());
    }
    let ii = SymbolicSparseColMatRef::new_checked(ni, ni, &ii_ptr, None, &ii_idx);
    let mut fwd = vec![0usize; ni];
    let mut inv = vec![0usize; ni];
    let mut buf = MemBuffer::try_new(amd::order_scratch::<usize>(ni, ii_idx.len())).map_err(|e| resource(&e))?;
    amd::order(&mut fwd, &mut inv, ii, amd::Control::default(), MemStack::new(&mut buf)).map_err(|e| resource(&e))?;
    Ok(fwd)
}

/// One METIS call at a time: it swaps the process's SIGABRT/SIGTERM handlers
/// in and out, which two threads interleaving would leave swapped (its
/// other state is thread-local). Hold the guard across the call.
pub(crate) fn metis_lock() -> std::sync::MutexGuard<'static, ()> {
    static METIS: std::sync::Mutex<()> = std::sync::Mutex::new(());
    METIS.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// METIS nested dissection of the interior node graph, expanded to equations.
fn nested_dissection(k: &SymMatrix, ni: usize, node_of: &[usize]) -> Result<Vec<usize>, FactorError> {
    let node = compressed_nodes(&node_of[..ni]);
    let nn = node.iter().map(|&g| g + 1).max().unwrap_or(0);
    let (eq_ptr, eqs) = equations_of_nodes(&node, nn);
    let (mut xadj, mut adjncy) = node_graph(k, &node, nn)?;
    let perm = metis_node_nd(&mut xadj, &mut adjncy, nn)?;
    // perm[new] = old node: emit each node's equations in that order
    let mut fwd = Vec::with_capacity(ni);
    for &g in &perm {
        fwd.extend_from_slice(&eqs[eq_ptr[g as usize]..eq_ptr[g as usize + 1]]);
    }
    debug_assert_eq!(fwd.len(), ni);
    Ok(fwd)
}

/// The node of each equation, its id compressed to 0..nn in order of first
/// appearance.
fn compressed_nodes(node_of: &[usize]) -> Vec<usize> {
    let mut id = vec![usize::MAX; node_of.iter().map(|&v| v + 1).max().unwrap_or(0)];
    let mut nn = 0;
    node_of
        .iter()
        .map(|&v| {
            if id[v] == usize::MAX {
                id[v] = nn;
                nn += 1;
            }
            id[v]
        })
        .collect()
}

/// The equations of each of the `nn` nodes, in CSR (pointers, equations).
fn equations_of_nodes(node: &[usize], nn: usize) -> (Vec<usize>, Vec<usize>) {
    let mut eq_ptr = vec![0usize; nn + 1];
    for &g in node {
        eq_ptr[g + 1] += 1;
    }
    for g in 0..nn {
        eq_ptr[g + 1] += eq_ptr[g];
    }
    let mut eqs = vec![0usize; node.len()];
    let mut fill = eq_ptr.clone();
    for (e, &g) in node.iter().enumerate() {
        eqs[fill[g]] = e;
        fill[g] += 1;
    }
    (eq_ptr, eqs)
}

/// The node graph of the interior block of `k` (the first `node.len()`
/// equations), in METIS's CSR (xadj, adjncy): both directions, no self
/// loops, no duplicates.
fn node_graph(
    k: &SymMatrix,
    node: &[usize],
    nn: usize,
) -> Result<(Vec<metis_sys::idx_t>, Vec<metis_sys::idx_t>), FactorError> {
    use metis_sys::idx_t;
    let ni = node.len();
    let mut adj: Vec<Vec<idx_t>> = vec![Vec::new(); nn];
    for c in 0..ni {
        let gc = node[c];
        for &r in &k.row_idx[k.col_ptr[c]..k.col_ptr[c + 1]] {
            if r < ni && node[r] != gc {
                adj[gc].push(node[r] as idx_t);
                adj[node[r]].push(gc as idx_t);
            }
        }
    }
    let mut xadj: Vec<idx_t> = Vec::with_capacity(nn + 1);
    let mut adjncy: Vec<idx_t> = Vec::new();
    xadj.push(0);
    for list in adj.iter_mut() {
        list.sort_unstable();
        list.dedup();
        adjncy.extend_from_slice(list);
        xadj.push(
            idx_t::try_from(adjncy.len())
                .map_err(|_| FactorError::Resource(String::from("node graph too large for METIS (32-bit indices)")))?,
        );
    }
    Ok((xadj, adjncy))
}

/// METIS_NodeND on a graph of `nn` vertices: `perm[new]` = old vertex.
fn metis_node_nd(
    xadj: &mut [metis_sys::idx_t],
    adjncy: &mut [metis_sys::idx_t],
    nn: usize,
) -> Result<Vec<metis_sys::idx_t>, FactorError> {
    use metis_sys::idx_t;
    let mut nvtxs = nn as idx_t;
    let mut perm: Vec<idx_t> = vec![0; nn];
    let mut iperm: Vec<idx_t> = vec![0; nn];
    let mut options = [0 as idx_t; metis_sys::METIS_NOPTIONS as usize];
    let _one = metis_lock();
    // SAFETY: the arrays have the lengths METIS reads (nvtxs + 1, xadj[nvtxs],
    // nvtxs, METIS_NOPTIONS) and outlive the call; METIS keeps no pointer.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        options[metis_sys::moptions_et_METIS_OPTION_NUMBERING as usize] = 0;
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(FactorError::Resource(format!("METIS_NodeND failed (status {status})")));
    }
    Ok(perm)
}
