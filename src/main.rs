//! The `subcontact` binary: parse the command line, run, print the error
//! chain and exit non-zero on failure.

use std::process::ExitCode;

use clap::Parser;
use subcontact::cli::{Cli, Command};
use subcontact::{commands, driver::RunOptions};

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Solve { scene, out, bonded, quiet } => {
            commands::solve(&scene, &RunOptions { out, bonded, verbose: !quiet })
        }
        Command::Check { scene } => commands::check(&scene),
        Command::Paper { fine, paper, quiet } => commands::paper(&fine, &paper, !quiet),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
