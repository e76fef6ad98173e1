//! What several result files print that is costly to derive, derived
//! once a run and read by each of them.

use super::bearing::{self, FaceBearing};
use super::blocks::{self, Block};
use super::resultants::{self, Resultants};
use crate::results::Run;

/// The contact groups' and faces' resultants, the bearing of every group
/// and face (a window search about every pair: seconds on a joint set of
/// the 1,000-block cube, of 18,900 pairs) and the blocks (each one's
/// volume integrals: 0.3 s on the 86k tunnel), which the csv files,
/// summary.json and report.md all give.
pub struct Derived {
    resultants: Option<Resultants>,
    bearing: Option<Vec<FaceBearing>>,
    blocks: Option<Vec<Block>>,
}

impl Derived {
    /// Derives what the files share from `run`.
    pub fn of(run: &Run) -> Derived {
        let resultants = resultants::of_run(run);
        let bearing = resultants.as_ref().and_then(|r| bearing::of(run, r));
        Derived { resultants, bearing, blocks: blocks::of_run(run) }
    }

    /// The contact groups' and face pairs' resultants (None without contacts).
    pub fn resultants(&self) -> Option<&Resultants> {
        self.resultants.as_ref()
    }

    /// Every group's bearing, each followed by its faces' (None without contacts).
    pub fn bearing(&self) -> Option<&[FaceBearing]> {
        self.bearing.as_deref()
    }

    /// The blocks of the last load step (None without contacts).
    pub fn blocks(&self) -> Option<&[Block]> {
        self.blocks.as_deref()
    }
}
