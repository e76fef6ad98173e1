//! Command line: `subcontact solve | safety | bench | check | paper`.

use std::path::PathBuf;

use crate::contact::InterfaceSolver;
use clap::{Parser, Subcommand};

/// Contact between elastic bodies by the substructure interface method.
///
/// Write a gmsh .geo with physical groups (bodies, contact curves/surfaces,
/// supports, loads) and a scene .toml next to it (materials, contacts,
/// supports, loads); `subcontact solve scene.toml` meshes it with the gmsh
/// CLI, condenses every body onto its contact interface once, iterates the
/// contact states (stick / slip / open) on the small interface system and
/// writes results for ParaView.
#[derive(Parser, Debug)]
#[command(name = "subcontact", version, about, long_about, after_help = EXAMPLES)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

const EXAMPLES: &str = "Examples:
  subcontact solve geo/cylinder.toml              results in results/cylinder/
  subcontact solve geo/cylinder.toml --out /tmp/c  results elsewhere
  subcontact safety geo/dam.toml                  the load steps, then the factor of safety against
                                                  sliding by strength reduction of the contacts
  subcontact check geo/cylinder.toml              validate scene, mesh and model; solve nothing
  subcontact bench geo/cylinder.toml --orders 1,2 --levels 5 --start 0.4
                                                  run time against error, results/cylinder/bench.*
  subcontact paper geo/cylinder.toml geo/cylinder_paper.toml
                                                  the paper's Tables 1 and 2 side by side

Results: <name>.vtu (bodies: displacement, stress, von_mises), <name>_contact.vtu
(interfaces: status 0 open / 1 slip / 2 stick, sigma_n, tau, gap, slip), contact.csv,
probes.csv, summary.json (sizes, timings, errors, contact states), report.md.";

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve a scene and write its results (default directory `results/<scene name>`).
    Solve {
        #[command(flatten)]
        run: RunArgs,
        /// Ignore the `[[contacts]]`: bodies meeting at a shared curve/surface are bonded (one monolithic solve).
        #[arg(long)]
        bonded: bool,
    },
    /// The factor of safety against sliding: solve the load steps, then divide the strength of
    /// the contacts (f = tan(phi), c, f_t) by F, raised step by step from the last step's state
    /// until equilibrium is lost, and bisect F to the tolerance. Options from the scene's
    /// `[safety]` table (reduce, contacts, step, tolerance, max_factor), else the defaults: all
    /// three on every contact, steps of 0.1, tolerance 1e-3 x F, up to F = 10. `solve` runs the
    /// same search on a scene with a `[safety]` table. Results as `solve`'s, plus safety.csv (the
    /// trials), the last state that holds (`<name>_safety*.vtu`, safety_contact.csv, safety_*.png)
    /// and F in summary.json ("safety") and report.md. A scene that already fails at F = 1 is
    /// unsafe as given: F is sought below 1, and the run fails naming the blocks that slide.
    Safety {
        #[command(flatten)]
        run: RunArgs,
    },
    /// Run time against error: mesh the scene at successive refinements for each element order,
    /// solve each (with contact, and bonded as the floor of one linear solve), and write
    /// bench.csv, bench.md (table, fitted convergence rates) and bench.svg to `results/<name>/`.
    Bench {
        scene: PathBuf,
        /// Number of refinement levels per order.
        #[arg(long, default_value_t = 4)]
        levels: usize,
        /// Element orders, comma separated.
        #[arg(long, value_delimiter = ',', default_value = "1,2")]
        orders: Vec<usize>,
        /// Refinement ratio between levels (the element size is divided by it).
        #[arg(long, default_value_t = 2.0)]
        ratio: f64,
        /// Element size (the scene's setnumber parameter, or clscale) of level 0; default the scene's.
        #[arg(long)]
        start: Option<f64>,
        /// Skip levels estimated above this many DOFs.
        #[arg(long, default_value_t = 3_000_000)]
        max_dofs: usize,
        /// Do not time the bonded monolithic solve of each mesh.
        #[arg(long)]
        no_monolithic: bool,
        /// Directory for bench.csv/md/svg (default `results/<scene name>`).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Validate a scene, its mesh and its model (groups, pairs, supports) without solving.
    Check {
        scene: PathBuf,
        /// Let the .geo run programs and write files (see solve --allow-geo-commands).
        #[arg(long)]
        allow_geo_commands: bool,
    },
    /// Solve the fine and the paper-mesh cylinder scenes and print the paper's Tables 1 and 2
    /// side by side with both (also written to the fine scene's report.md).
    Paper {
        /// The default (fine) cylinder scene.
        fine: PathBuf,
        /// The paper's 30-hexahedron scene.
        paper: PathBuf,
        #[arg(long, short)]
        quiet: bool,
    },
}

/// Why a count given on the command line is not one.
#[derive(Debug, thiserror::Error)]
enum CountError {
    #[error("must be at least 1")]
    Zero,
    #[error("{0:?} is not a whole number")]
    NotWhole(String),
}

/// A count of at least 1 (pieces, threads).
fn at_least_one(s: &str) -> Result<usize, CountError> {
    match s.parse::<usize>() {
        Ok(0) => Err(CountError::Zero),
        Ok(n) => Ok(n),
        Err(_) => Err(CountError::NotWhole(s.to_string())),
    }
}

/// The spellings of `--interface`, those of `[solver] interface`.
const INTERFACE_SOLVERS: [&str; 4] = ["auto", "dense", "iterative", "sparse"];

/// `--interface`: one of [`INTERFACE_SOLVERS`], read as the scene reads
/// `[solver] interface` (the kernel's enum knows no command line).
fn interface_solver() -> impl clap::builder::TypedValueParser<Value = InterfaceSolver> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(INTERFACE_SOLVERS).map(|s| scene_spelling(&s).unwrap_or_default())
}

/// The interface solver the scene file spells `s`.
fn scene_spelling(s: &str) -> Option<InterfaceSolver> {
    use serde::de::{value, Deserialize, IntoDeserializer};
    let d: value::StrDeserializer<value::Error> = s.into_deserializer();
    InterfaceSolver::deserialize(d).ok()
}

/// What `solve` and `safety` take alike: the scene, where the results go,
/// and how the run is spread and solved.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// The scene file (TOML), next to its .geo or .msh.
    pub scene: PathBuf,
    /// Directory for the results.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print no progress.
    #[arg(long, short)]
    pub quiet: bool,
    /// Cut every part (bodies joined by shared nodes) into K substructures with METIS,
    /// joined by bonded interfaces: the answer is the uncut one, but each piece is
    /// factorised alone (in its own thread or MPI rank). Overrides `[solver] substructures`.
    #[arg(long, value_name = "K", value_parser = at_least_one)]
    pub substructures: Option<usize>,
    /// Parts condensed at once (default: the machine's cores, divided among MPI ranks).
    #[arg(long, value_name = "N", value_parser = at_least_one)]
    pub threads: Option<usize>,
    /// How the interface system is solved: dense (S formed, the interface reduced and
    /// factorised densely), sparse (the interface means factorised once, sparse, GMRES in the
    /// free relative displacements: many small blocks), iterative (S applied through the
    /// parts' interior factors, GMRES) or auto (sparse from 16 blocks of at most 6,000
    /// interface DOFs, dense below 20,000 interface DOFs, iterative above). Overrides
    /// `[solver] interface`.
    #[arg(long, value_parser = interface_solver())]
    pub interface: Option<InterfaceSolver>,
    /// Run even when the estimated peak memory exceeds the memory available
    /// (the estimate errs high; the run may still be stopped by the system).
    #[arg(long)]
    pub no_memory_check: bool,
    /// Let the .geo run programs and write files: SystemCall, NonBlockingSystemCall,
    /// OnelabRun, Save, Print, CreateDir, SendToServer, Printf(...) > "file". Refused
    /// otherwise: a .geo is a program, and these reach outside the mesh with your rights.
    #[arg(long)]
    pub allow_geo_commands: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_interface_spelling_of_the_command_line_is_one_of_the_scene() {
        let read: Vec<_> = INTERFACE_SOLVERS.iter().map(|s| scene_spelling(s)).collect();
        use InterfaceSolver::*;
        assert_eq!(read, [Some(Auto), Some(Dense), Some(Iterative), Some(Sparse)]);
        assert_eq!(scene_spelling("fast"), None);
        let cli = Cli::try_parse_from(["subcontact", "solve", "s.toml", "--interface", "sparse"]).expect("parses");
        let Command::Solve { run, .. } = cli.command else { panic!("solve") };
        assert_eq!(run.interface, Some(Sparse));
        assert!(Cli::try_parse_from(["subcontact", "solve", "s.toml", "--interface", "fast"]).is_err());
    }
}
