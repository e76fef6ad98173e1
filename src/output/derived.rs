//! What several result files print that is costly to derive, derived
//! once a run and read by each of them.

use super::bearing::{self, FaceBearing};
use crate::results::Run;

/// The bearing of every contact group and face (a window search about
/// every pair: seconds on a joint set of the 1,000-block cube, of 18,900
/// pairs), which bearing.csv, summary.json and report.md all give.
pub struct Derived {
    bearing: Option<Vec<FaceBearing>>,
}

impl Derived {
    /// Derives what the files share from `run`.
    pub fn of(run: &Run) -> Derived {
        Derived { bearing: bearing::of_run(run) }
    }

    /// Every group's bearing, each followed by its faces' (None without contacts).
    pub fn bearing(&self) -> Option<&[FaceBearing]> {
        self.bearing.as_deref()
    }
}
