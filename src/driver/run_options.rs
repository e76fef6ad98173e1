//! Options of a run beyond the scene: where results go, how the work is
//! split, what is printed.

use std::path::PathBuf;

use crate::contact::InterfaceSolver;
use crate::scene::Scene;

/// Options of a run beyond the scene.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    pub out: Option<PathBuf>,
    /// Pieces each part is cut into (overrides `[solver] substructures`).
    pub substructures: Option<usize>,
    /// Parts condensed at once on each rank (default: the cores per rank).
    pub threads: Option<usize>,
    /// How the interface is solved (overrides `[solver] interface`).
    pub interface: Option<InterfaceSolver>,
    /// Treat every contact as bonded (shared nodes): the monolithic solve.
    pub bonded: bool,
    /// Print stage progress on stderr.
    pub verbose: bool,
    /// Compute everything but write no result files (benchmarks).
    pub skip_output: bool,
    /// Run even when the estimated peak memory exceeds what is available.
    pub ignore_memory_estimate: bool,
    /// Let the .geo run programs and write files (SystemCall, Save, ...).
    pub allow_geo_commands: bool,
}

impl RunOptions {
    /// Where the results of `scene` go: `out`, or `results/<scene name>`.
    pub fn out_dir(&self, scene: &Scene) -> PathBuf {
        self.out.clone().unwrap_or_else(|| PathBuf::from("results").join(&scene.name))
    }
}
