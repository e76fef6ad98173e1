//! A run's peak memory, estimated before any factorisation, and the check
//! of it against what the machine lets the process use ([`check`]).
//!
//! The estimate ([`estimate`]) orders each part's node graph as the
//! factorisation will (AMD, or METIS nested dissection for large 3D parts,
//! [`crate::substructure::ordering`]) with its interface last, and takes
//! the supernodal symbolic factorisation's fill: `nnz(L) ≈ nd² nnz(L_nodes)`
//! values of 8 bytes. Then, in bytes, with `n_c` a part's interface DOFs
//! and `N` the interface system's unknowns (about half the interface DOFs:
//! a pair's two nodes give one relative displacement):
//!
//! ```text
//! condensing  = Σ factors + Σ 8 n_c²                (every S until the interface takes it)
//!             + threads · max(24 nnz(K) + 8 n_c²)   (parts being assembled and condensed)
//! interface   = [Σ factors] + 2 Σ 8 n_c² + 3 · 8 N²  (S and S in the pairs' frames, W, the
//!                                                    state set's matrix and its factor;
//!                                                    factors freed above 30 % of the memory)
//!               (sparse interface: the means' factor, and W's columns, min(128 MB, 4 N²),
//!                beside it in the contact iteration: [`InterfaceKind::memory`])
//! peak        = now + 1.15 max(condensing, interface) + results + 72 MB
//! ```
//!
//! `now` is the resident memory when the estimate is made (the model),
//! `results` the displacements, stresses and files of the load steps, and
//! 72 MB the pictures (measured: a run of 2.7e3 DOFs, 18 MB before its
//! output, peaked at 81 MB while drawing them). The factor 1.15 is what the terms miss (measured:
//! peaks 1.07-1.14 times the terms on block on block, 7.4e4 to 4.8e5 DOFs;
//! the factors alone within 2 %). With
//! the iterative interface there is no S and no W: the interiors' factors
//! and the results.

use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, SymmetricOrdering};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::Side;

use crate::contact::system::InterfaceKind;
use crate::fem::sparse::{SymMatrix, NONE};
use crate::model::Model;
use crate::substructure::ordering::{self, Ordering};
use crate::substructure::{Condensation, Part};

use super::machine::{available, human, physical, resident, Available};

/// What the terms leave out (allocator slack, the solvers' workspaces), as
/// a factor: measured peaks of block on block (tet10, 7.4e4 to 4.8e5
/// DOFs, dense and iterative interface) were 1.07-1.14 times the terms.
const MARGIN: f64 = 1.15;

/// The pictures' rasters and the result files' buffers, in bytes (64 MB
/// left a small iterative run's peak 2-3 % above the estimate).
const PICTURES: f64 = 72e6;

/// A run's estimated peak, in bytes, and its main terms.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Estimate {
    /// The peak.
    pub total: f64,
    /// The parts' factors together.
    pub factors: f64,
    /// The interface matrices: every part's S and the interface system
    /// (dense, or the sparse interface's factor of the means).
    pub interface: f64,
}

/// A run whose estimated peak exceeds the memory available (the driver
/// puts the scene file's name in front of the message).
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
#[error(
    "this run needs about {} of memory at its peak ({} DOFs, {} interface; {} for the factors of {parts} part(s){}), more than the {} available ({}). Make it smaller: {}--substructures K (smaller factors, K pieces per body), more MPI ranks (mpirun -np N, with the cargo feature mpi), or a coarser mesh (a larger lc in [gmsh] setnumber); or run it where there is more memory (--no-memory-check runs it anyway: the estimate errs high, but the system may stop the run)",
    human(need.total), dofs[0], dofs[1], human(need.factors),
    if need.interface > 0.0 { format!(", {} for the interface matrices", human(need.interface)) } else { String::new() },
    human(available.bytes), available.what,
    if need.interface > 0.0 { "--interface iterative (no dense interface matrices), " } else { "" }
)]
pub struct TooLarge {
    pub need: Estimate,
    pub available: Available,
    /// DOFs in all and on the interface.
    pub dofs: [usize; 2],
    pub parts: usize,
}

/// Fails when `need` exceeds what is available.
pub fn check(need: Estimate, dofs: [usize; 2], parts: usize) -> Result<Available, TooLarge> {
    let available = available();
    if need.total > available.bytes {
        return Err(TooLarge { need, available, dofs, parts });
    }
    Ok(available)
}

/// Estimates the peak memory of condensing `parts` (this rank's) for the
/// interface `kind`, `threads` at a time, the
/// interface of `interface_dofs` DOFs solved here when `solves_interface`,
/// over `steps` load steps.
pub fn estimate(
    model: &Model,
    parts: &[&Part],
    kind: InterfaceKind,
    threads: usize,
    solves_interface: bool,
    interface_dofs: usize,
    steps: usize,
) -> Estimate {
    let nd = model.nd as f64;
    let mut factors = 0.0;
    let mut schur = 0.0;
    let mut busiest: f64 = 0.0;
    let how = kind.condensation();
    for part in parts {
        let (fill, k_nnz, nc) = part_fill(model, part, how);
        let nc = nc as f64 * nd;
        let s = if how == Condensation::Dense { 8.0 * nc * nc } else { 0.0 };
        factors += 8.0 * fill * nd * nd;
        schur += s;
        busiest = busiest.max(24.0 * k_nnz * nd * nd + s);
    }
    let condensing = factors + schur + threads.clamp(1, parts.len().max(1)) as f64 * busiest;
    let kept = if factors > 0.3 * physical() { 0.0 } else { factors };
    let (w, interface) = kind.memory(interface_dofs, solves_interface, schur, kept);
    // displacements, stresses (6 per body node) and the files, per step
    let results = (steps.max(1) as f64 + 1.0) * model.n_nodes() as f64 * 8.0 * (nd + 6.0 + 8.0);
    Estimate {
        total: resident() + MARGIN * condensing.max(interface) + results + PICTURES,
        factors,
        interface: schur + w,
    }
}

/// A part's node graph ordered as the factorisation orders its equations,
/// interface last for the dense S: (values of the supernodal factor of the
/// node graph, nonzeros of its lower triangle, interface nodes).
fn part_fill(model: &Model, part: &Part, how: Condensation) -> (f64, f64, usize) {
    let nd = model.nd;
    let free = |n: usize| (0..nd).any(|c| model.prescribed[n * nd + c].is_none());
    let nodes = part.nodes(model);
    let mut is_iface = vec![false; nodes.len()];
    for &n in &part.interface {
        if let Ok(i) = nodes.binary_search(&n) {
            is_iface[i] = true;
        }
    }
    // interior nodes with a free component first, then the interface
    let mut local = vec![NONE; nodes.len()];
    let mut next = 0;
    let mut ni_eq = 0;
    for (i, &n) in nodes.iter().enumerate() {
        if !is_iface[i] && free(n) {
            local[i] = next;
            next += 1;
            ni_eq += (0..nd).filter(|&c| model.prescribed[n * nd + c].is_none()).count();
        }
    }
    let ni = next;
    let nc = part.interface.len();
    if how == Condensation::Dense {
        for i in 0..nodes.len() {
            if is_iface[i] {
                local[i] = next;
                next += 1;
            }
        }
    }
    let n = next;
    let cells: Vec<Vec<usize>> = (part.cells.iter())
        .map(|&(b, c)| model.bodies[b].cells[c].nodes.iter().filter_map(|x| nodes.binary_search(x).ok()).collect())
        .collect();
    let graph = SymMatrix::pattern(n, 1, &local, cells.iter().map(|c| c.as_slice()));
    let k_nnz = graph.row_idx.len() as f64;
    let identity: Vec<usize> = (0..ni).collect();
    let Ok(mut fwd) = ordering::interior(&graph, ni, &identity, Ordering::choose(ni_eq, nd)) else {
        return (dense_guess(n), k_nnz, nc);
    };
    fwd.extend(ni..n);
    let mut inv = vec![0; n];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
    let a = SymbolicSparseColMatRef::new_checked(n, n, &graph.col_ptr, None, &graph.row_idx);
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    let fill = factorize_symbolic_cholesky(a, Side::Lower, SymmetricOrdering::Custom(perm), params)
        .map_or(dense_guess(n), |s| s.len_val() as f64);
    (fill, k_nnz, nc)
}

/// A dense lower triangle: what a factor of n unknowns holds at most.
fn dense_guess(n: usize) -> f64 {
    n as f64 * (n as f64 + 1.0) / 2.0
}
