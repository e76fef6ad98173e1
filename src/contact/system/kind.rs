//! How the interface system is solved, decided once per run
//! ([`InterfaceKind::choose`], from `[solver] interface`), and everything
//! that follows from it: how the parts are condensed, which [`Solver`] is
//! built, what the interface matrices cost in memory and the name the
//! results give it. A new way of solving the interface is one more
//! [`Solver`] file and one more variant here.

use super::dense::Dense;
use super::iterative::{Iterative, Remote};
use super::layout::Layout;
use super::reduce::NotHeld;
use super::solver::{Solver, Springs};
use super::sparse::Sparse;
use super::w_columns;
use crate::contact::mobility::PartModes;
use crate::contact::options::InterfaceSolver;
use crate::model::Model;
use crate::substructure::{Condensation, OperatorRef, Part};

/// Interface DOFs summed over the parts (a joint counted once per side)
/// from which `[solver] interface = "auto"` solves the interface
/// iteratively (the `--help` of `InterfaceSolver::Auto` says the number
/// too). Measured (docs/bench3d.md, 2 threads): below it the dense
/// interface is 1.2-2.4 times faster (6,534 interface DOFs: 8.0 s against
/// 18.6 s; 11,790: 32.1 s against 39.3 s, but 4.1 GB against 1.5 GB); at
/// 24,426 the iterative one takes 229 s and 15.5 GB against 552 s and 21.9
/// GB; a column cut into 4 pieces (41,550 summed) 98 s and 4.7 GB against
/// 115 s and 16.5 GB, into 8 pieces (94,905) 94 s and 3.2 GB where the
/// dense interface ran out of 24 GB.
pub const ITERATIVE_FROM: usize = 20_000;

/// The interface solver of a run: `[solver] interface` with `auto` decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InterfaceKind {
    /// Each part's dense S; the interface reduced to the contact unknowns
    /// once and factorised densely at every iteration ([`Dense`]).
    Dense,
    /// Each part's dense S; the interface means factorised once, sparse,
    /// and each state set solved by GMRES ([`Sparse`]).
    Sparse,
    /// No S formed: S applied through the parts' interior factors, GMRES
    /// ([`Iterative`]).
    Iterative,
}

/// From how many parts, each with at most [`BLOCKY_PART_INTERFACE`]
/// interface DOFs, `interface = "auto"` takes the sparse interface.
const BLOCKY_PARTS: usize = 16;
const BLOCKY_PART_INTERFACE: usize = 6_000;

/// The sparse interface's factor holds about this times nm^(4/3) values.
const SPARSE_FILL: f64 = 50.0;

impl InterfaceKind {
    /// The kind `[solver] interface` names for these `parts`. Auto takes
    /// the sparse interface for many small parts, the iterative one from
    /// [`ITERATIVE_FROM`] interface DOFs (summed over the parts), else the
    /// dense one.
    pub fn choose(choice: InterfaceSolver, parts: &[Part], nd: usize) -> InterfaceKind {
        let interface_dofs: usize = parts.iter().map(|p| p.interface.len() * nd).sum();
        match choice {
            InterfaceSolver::Iterative => InterfaceKind::Iterative,
            InterfaceSolver::Sparse => InterfaceKind::Sparse,
            InterfaceSolver::Dense => InterfaceKind::Dense,
            InterfaceSolver::Auto if blocky(parts, nd) => InterfaceKind::Sparse,
            InterfaceSolver::Auto if interface_dofs >= ITERATIVE_FROM => InterfaceKind::Iterative,
            InterfaceSolver::Auto => InterfaceKind::Dense,
        }
    }

    /// The name `[solver] interface` gives it (and the results).
    pub fn name(self) -> &'static str {
        match self {
            InterfaceKind::Dense => "dense",
            InterfaceKind::Sparse => "sparse",
            InterfaceKind::Iterative => "iterative",
        }
    }

    /// How the parts are condensed for it: a dense S, or S applied.
    pub fn condensation(self) -> Condensation {
        match self {
            InterfaceKind::Dense | InterfaceKind::Sparse => Condensation::Dense,
            InterfaceKind::Iterative => Condensation::Applied,
        }
    }

    /// What the run says of it before the parts are condensed, if anything.
    pub fn note(self, interface_dofs: usize) -> Option<String> {
        (self == InterfaceKind::Iterative).then(|| {
            format!("{interface_dofs} interface DOFs over the parts: no S formed, the interface solved by GMRES through the parts' interior factors")
        })
    }

    /// Its solver of the condensed `parts` (`springs`: where its solves
    /// put springs on every pair, [`Sparse::new`]).
    pub(super) fn build<'a>(
        self,
        model: &Model,
        layout: &Layout,
        parts: &[OperatorRef],
        rigid: &[PartModes],
        remote: Option<&'a dyn Remote>,
        (threads, springs): (usize, Springs),
    ) -> Result<Box<dyn Solver + 'a>, NotHeld> {
        Ok(match self {
            InterfaceKind::Dense => Box::new(Dense::new(layout, parts)?),
            InterfaceKind::Sparse => Box::new(Sparse::new(model, layout, parts, (threads, springs))?),
            InterfaceKind::Iterative => Box::new(Iterative::build(model, layout, parts, rigid, remote, threads)),
        })
    }

    /// The interface system's own matrices in bytes when this rank
    /// `solves` the interface of `interface_dofs` DOFs, and the peak while
    /// it is built from the parts' S (`schur` bytes) beside the factors
    /// `kept`: (matrices, peak).
    pub fn memory(self, interface_dofs: usize, solves: bool, schur: f64, kept: f64) -> (f64, f64) {
        let nm = interface_dofs as f64 / 2.0;
        match self {
            // the means' sparse factor: 50 nm^(4/3) values in 3D, measured on
            // the jointed cubes of make bench-blocks (nm = 3.6e4: 5.4e7, 7.1e4: 1.5e8).
            // Their peaks (VmHWM) against the estimate: 64 blocks of 5^3
            // hex20 4.62 GB (3.5 GB without K_mm and the scratch, now 4.7),
            // 512 blocks 1.95 (1.7, now 2.9), 1,000 blocks 5.14 (3.8, now 6.5).
            // The factor is now kept in single precision (4.05, 1.68 and 4.43
            // GB measured); 8 bytes a value stays, for K_mm that single
            // precision cannot hold, factorised in double. Each S is also
            // copied into the pairs' frames while W is assembled; the sparse
            // interface then holds the bonded model over the means and the
            // parts' interiors (`means_whole`: the parts' own stiffness,
            // sparse, where a clique of means per part took 0.7 schur) and
            // factorises it, the factorisation's scratch beside the factor
            // (up to 0.8 of it): on the 86k tunnel 34.5 million values
            // against this term's 50 million (72.8 with the cliques).
            // During the contact iteration it keeps W's columns beside the
            // factor and the parts' S in the pairs' frames (at most
            // [`w_columns::most_bytes`]: 128 MB, or every column of W)
            InterfaceKind::Sparse if solves => {
                let w = 8.0 * SPARSE_FILL * nm.powf(4.0 / 3.0);
                let columns = w_columns::most_bytes(interface_dofs / 2) as f64;
                (w + columns, (kept + 3.0 * schur + 2.0 * w).max(kept + schur + w + columns))
            }
            InterfaceKind::Dense if solves => {
                let w = 3.0 * 8.0 * nm.powi(2);
                (w, kept + 2.0 * schur + w)
            }
            _ => (0.0, kept + 2.0 * schur + 0.0),
        }
    }
}

/// Whether the parts are many and small, as the blocks of a rock mass:
/// then the sparse interface pays (see [`super::sparse`]).
fn blocky(parts: &[Part], nd: usize) -> bool {
    parts.len() >= BLOCKY_PARTS && parts.iter().all(|p| p.interface.len() * nd <= BLOCKY_PART_INTERFACE)
}

#[cfg(test)]
mod tests {
    use super::{w_columns, InterfaceKind, SPARSE_FILL};

    /// The sparse interface's matrices are K_mm's factor and W's columns:
    /// every column of W (4 bytes an entry) on a small interface, 128 MB
    /// on a large one; the iteration's peak holds them beside the factor.
    #[test]
    fn the_sparse_interface_counts_the_columns_of_w() {
        for (dofs, columns) in [(2_000usize, 4.0 * 1000.0 * 1000.0), (200_000, 128.0 * 1024.0 * 1024.0)] {
            let factor = 8.0 * SPARSE_FILL * (dofs as f64 / 2.0).powf(4.0 / 3.0);
            let (matrices, peak) = InterfaceKind::Sparse.memory(dofs, true, 0.0, 0.0);
            assert!((matrices - factor - columns).abs() <= 1e-9 * matrices, "{dofs}: {matrices} {factor}");
            assert!(peak >= factor + columns && peak >= 2.0 * factor, "{dofs}: {peak}");
            assert_eq!(w_columns::most_bytes(dofs / 2) as f64, columns);
        }
        // a rank that does not solve the interface keeps no columns
        assert_eq!(InterfaceKind::Sparse.memory(2_000, false, 0.0, 0.0).0, 0.0);
    }
}
