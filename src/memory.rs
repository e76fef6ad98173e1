//! Memory, known before it runs out: what a run will need at its peak,
//! estimated before any factorisation, against what the process may use.
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
//!
//! What may be used ([`available`]): the least of MemAvailable
//! (/proc/meminfo), the cgroup's limit less its usage (cgroup v2
//! `memory.max` - `memory.current`, v1 `memory.limit_in_bytes` -
//! `memory.usage_in_bytes`) and the address-space limit (`ulimit -v`) less
//! the process's virtual size.
//!
//! An allocation that fails anyway ([`Guarded`], the binary's global
//! allocator) ends the process with one paragraph and exit status 1, not
//! Rust's `memory allocation of N bytes failed` and an abort (134). On
//! stable Rust the allocation error hook (`std::alloc::set_alloc_error_hook`)
//! is unstable, so the check sits in the allocator itself: a thin wrapper
//! of the system allocator that, when it returns null, writes a fixed
//! message with `write(2)` (nothing allocated) and leaves with `_exit(1)`.
//! Results are committed in one step after everything was computed, so a
//! run stopped there has written nothing (its hidden staging directory, if
//! the commit was under way, is removed by the next run).

use std::alloc::{GlobalAlloc, Layout, System};

use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, CholeskySymbolicParams, SymmetricOrdering};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::Side;

use crate::contact::system::InterfaceKind;
use crate::fem::sparse::{SymMatrix, NONE};
use crate::model::Model;
use crate::substructure::ordering::{self, Ordering};
use crate::substructure::{Condensation, Part};

/// What the terms leave out (allocator slack, the solvers' workspaces), as
/// a factor: measured peaks of block on block (tet10, 7.4e4 to 4.8e5
/// DOFs, dense and iterative interface) were 1.07-1.14 times the terms.
const MARGIN: f64 = 1.15;

/// The pictures' rasters and the result files' buffers, in bytes (64 MB
/// left a small iterative run's peak 2-3 % above the estimate).
const PICTURES: f64 = 72e6;

/// A run's estimated peak, in bytes, and its main terms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    /// The peak.
    pub total: f64,
    /// The parts' factors together.
    pub factors: f64,
    /// The interface matrices: every part's S and the interface system
    /// (dense, or the sparse interface's factor of the means).
    pub interface: f64,
}

/// What the process may still allocate, and the limit that says so.
#[derive(Clone, Debug, PartialEq)]
pub struct Available {
    pub bytes: f64,
    pub what: String,
}

/// A run whose estimated peak exceeds the memory available.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "{scene}: this run needs about {} of memory at its peak ({} DOFs, {} interface; {} for the factors of {parts} part(s){}), more than the {} available ({}). Make it smaller: {}--substructures K (smaller factors, K pieces per body), more MPI ranks (mpirun -np N, with the cargo feature mpi), or a coarser mesh (a larger lc in [gmsh] setnumber); or run it where there is more memory (--no-memory-check runs it anyway: the estimate errs high, but the system may stop the run)",
    human(need.total), dofs[0], dofs[1], human(need.factors),
    if need.interface > 0.0 { format!(", {} for the interface matrices", human(need.interface)) } else { String::new() },
    human(available.bytes), available.what,
    if need.interface > 0.0 { "--interface iterative (no dense interface matrices), " } else { "" }
)]
pub struct TooLarge {
    pub scene: String,
    pub need: Estimate,
    pub available: Available,
    /// DOFs in all and on the interface.
    pub dofs: [usize; 2],
    pub parts: usize,
}

/// Fails when `need` exceeds what is available.
pub fn check(scene: &str, need: Estimate, dofs: [usize; 2], parts: usize) -> Result<Available, TooLarge> {
    let available = available();
    if need.total > available.bytes {
        return Err(TooLarge { scene: scene.to_string(), need, available, dofs, parts });
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

/// What the process may still allocate: the least of the system's
/// available memory, its cgroup's room and its address-space room.
pub fn available() -> Available {
    let mut best = Available { bytes: f64::INFINITY, what: "no limit found".into() };
    let mut consider = |bytes: Option<f64>, what: &str| {
        if let Some(b) = bytes.filter(|b| *b < best.bytes) {
            best = Available { bytes: b.max(0.0), what: what.to_string() };
        }
    };
    consider(kb_line("/proc/meminfo", "MemAvailable:"), "MemAvailable in /proc/meminfo");
    for (limit, usage, what) in cgroups() {
        let (Some(l), Some(u)) = (number(&limit), number(&usage)) else { continue };
        consider(Some(l - u), &what);
    }
    if let (Some(limit), Some(size)) = (address_limit(), kb_line("/proc/self/status", "VmSize:")) {
        consider(Some(limit - size), "the address-space limit (ulimit -v) less this process's size");
    }
    best
}

/// The cgroup limit and usage files of this process: (limit, usage, name).
fn cgroups() -> Vec<(String, String, String)> {
    let Ok(text) = std::fs::read_to_string("/proc/self/cgroup") else { return Vec::new() };
    cgroups_in(std::path::Path::new("/sys/fs/cgroup"), &text)
}

/// The memory limit and usage files of the cgroups named in `proc_cgroup`
/// (the text of /proc/self/cgroup) under the cgroup mount `root`: each
/// cgroup's and every parent's up to the mount, in cgroup v2
/// (`memory.max`, `memory.current`) and v1 (`memory/memory.limit_in_bytes`,
/// `memory.usage_in_bytes`; Docker on v1 sets the limit on a parent). In a
/// cgroup namespace the mount is the process's own cgroup, which the
/// path from /proc does not name: the walk starts at the deepest part of
/// the path that exists.
fn cgroups_in(root: &std::path::Path, proc_cgroup: &str) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    for line in proc_cgroup.lines() {
        let mut f = line.splitn(3, ':');
        let (Some(_), Some(ctl), Some(path)) = (f.next(), f.next(), f.next()) else { continue };
        let (base, limit, usage) = if ctl.is_empty() {
            (root.to_path_buf(), "memory.max", "memory.current")
        } else if ctl.split(',').any(|c| c == "memory") {
            (root.join("memory"), "memory.limit_in_bytes", "memory.usage_in_bytes")
        } else {
            continue;
        };
        let mut p = base.join(path.trim_start_matches('/'));
        while !p.is_dir() && p != base && p.pop() {}
        loop {
            let (l, u) = (p.join(limit), p.join(usage));
            if l.exists() && !out.iter().any(|(x, _, _)| *x == l.display().to_string()) {
                let what = format!("the cgroup limit {} less its usage", l.display());
                out.push((l.display().to_string(), u.display().to_string(), what));
            }
            if p == base || !p.starts_with(&base) || !p.pop() {
                break;
            }
        }
    }
    out
}

/// The number in a file ("max" and absent files are no limit).
fn number(path: &str) -> Option<f64> {
    std::fs::read_to_string(path).ok()?.trim().parse::<f64>().ok()
}

/// Bytes of the `kB` value on the line of `file` that starts with `key`.
fn kb_line(file: &str, key: &str) -> Option<f64> {
    let text = std::fs::read_to_string(file).ok()?;
    let v: f64 = text.lines().find(|l| l.starts_with(key))?.split_whitespace().nth(1)?.parse().ok()?;
    Some(v * 1024.0)
}

/// This process's resident memory now, in bytes (0 where unknown).
pub fn resident() -> f64 {
    kb_line("/proc/self/status", "VmRSS:").unwrap_or(0.0)
}

/// The machine's memory, in bytes.
fn physical() -> f64 {
    kb_line("/proc/meminfo", "MemTotal:").unwrap_or(f64::INFINITY)
}

/// RLIMIT_AS, when set.
fn address_limit() -> Option<f64> {
    let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: getrlimit writes the struct it is given
    let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
    (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as f64)
}

/// Bytes as "1.2 GB" or "350 MB".
pub fn human(bytes: f64) -> String {
    if !bytes.is_finite() {
        "unlimited memory".to_string()
    } else if bytes >= 1e9 {
        format!("{:.1} GB", bytes / 1e9)
    } else {
        format!("{:.0} MB", (bytes / 1e6).max(1.0))
    }
}

/// The system allocator, ending the process with one paragraph and exit
/// status 1 when an allocation fails (see the module header).
pub struct Guarded;

// SAFETY: every call goes to the system allocator unchanged; on failure
// the process ends before anything sees the null pointer.
unsafe impl GlobalAlloc for Guarded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            out_of_memory(new_size);
        }
        p
    }
}

/// Writes the out-of-memory paragraph to stderr and exits 1, allocating nothing.
fn out_of_memory(size: usize) -> ! {
    let mut digits = [0u8; 20];
    let mut i = digits.len();
    let mut v = size;
    loop {
        i -= 1;
        digits[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    let parts: [&[u8]; 3] = [
        b"error: out of memory: an allocation of ",
        &digits[i..],
        b" bytes failed, so the run stopped; no result files were written (results are committed all at once, at the end). Give the run more memory, or make it smaller: --interface iterative (no dense interface matrices), --substructures K (smaller factors), more MPI ranks, or a coarser mesh (larger lc in [gmsh] setnumber)\n",
    ];
    for part in parts {
        // SAFETY: writes a valid buffer to stderr
        let _ = unsafe { libc::write(2, part.as_ptr().cast(), part.len()) };
    }
    // SAFETY: ends the process at once, running nothing that could allocate
    unsafe { libc::_exit(1) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Docker on cgroup v1 puts the limit on a parent of the process's
    /// cgroup; only the process's own was read (issue 32), so such a run
    /// was killed instead of refused.
    #[test]
    fn cgroup_limits_are_read_up_the_hierarchy_in_v1_and_v2() {
        let root = std::env::temp_dir().join(format!("subcontact-cgroup-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let put = |dir: &str, files: &[(&str, &str)]| {
            std::fs::create_dir_all(root.join(dir)).unwrap();
            for (f, v) in files {
                std::fs::write(root.join(dir).join(f), v).unwrap();
            }
        };
        let v1 =
            |l: &str, u: &str| [("memory.limit_in_bytes", l.to_string()), ("memory.usage_in_bytes", u.to_string())];
        for (dir, l, u) in [
            ("memory", "9223372036854771712", "5000000000"),
            ("memory/docker", "1000000000", "300000000"),
            ("memory/docker/abc", "9223372036854771712", "200000000"),
        ] {
            let files = v1(l, u);
            put(dir, &[(files[0].0, &files[0].1), (files[1].0, &files[1].1)]);
        }
        put("user.slice", &[("memory.max", "2000000000"), ("memory.current", "500000000")]);
        put("user.slice/run", &[("memory.max", "max"), ("memory.current", "100000000")]);
        let text = "4:memory:/docker/abc\n0::/user.slice/run\n";
        let found = cgroups_in(&root, text);
        let room = |l: &str, u: &str| number(l).zip(number(u)).map(|(l, u)| l - u);
        let rooms: Vec<Option<f64>> = found.iter().map(|(l, u, _)| room(l, u)).collect();
        assert_eq!(found.len(), 5, "{found:?}");
        assert!(rooms.contains(&Some(7e8)) && rooms.contains(&Some(1.5e9)), "{rooms:?}");
        // in a cgroup namespace the mount is the process's own cgroup
        let found = cgroups_in(&root, "4:memory:/not/here\n");
        assert_eq!(found.len(), 1, "{found:?}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
