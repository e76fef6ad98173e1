//! Command line: `subcontact solve | check | paper`.

use std::path::PathBuf;

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
  subcontact check geo/cylinder.toml              validate scene, mesh and model; solve nothing
  subcontact paper geo/cylinder.toml geo/cylinder_paper.toml
                                                  the paper's Tables 1 and 2 side by side

Results: <name>.vtu (bodies: displacement, stress, von_mises), <name>_contact.vtu
(interfaces: status 0 open / 1 slip / 2 stick, sigma_n, tau, gap, slip), contact.csv,
probes.csv, summary.json (sizes, timings, errors, contact states), report.md.";

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve a scene and write its results (default directory results/<scene name>).
    Solve {
        /// The scene file (TOML), next to its .geo or .msh.
        scene: PathBuf,
        /// Directory for the results.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Ignore the [[contacts]]: bodies meeting at a shared curve/surface are bonded (one monolithic solve).
        #[arg(long)]
        bonded: bool,
        /// Print no progress.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Validate a scene, its mesh and its model (groups, pairs, supports) without solving.
    Check {
        scene: PathBuf,
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
