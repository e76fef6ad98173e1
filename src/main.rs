//! The `subcontact` binary: parse the command line, run, print the error
//! chain and exit non-zero on failure. Built with the cargo feature `mpi`
//! and started by `mpirun -np N`, `solve` spreads the parts over the ranks;
//! rank 0 prints and writes, the other ranks stay silent (also on failure,
//! which every rank shares).

use std::process::ExitCode;

use clap::Parser;
use subcontact::cli::{Cli, Command, RunArgs};
use subcontact::parallel::{Comm, Serial};
use subcontact::{commands, driver::RunOptions};

/// The system allocator, but an allocation that fails ends the run with
/// one paragraph and exit status 1 instead of an abort (subcontact::memory).
#[global_allocator]
static ALLOCATOR: subcontact::memory::Guarded = subcontact::memory::Guarded;

fn main() -> ExitCode {
    let cli = Cli::parse();
    #[cfg(feature = "mpi")]
    let mpi = subcontact::parallel::Mpi::init();
    #[cfg(feature = "mpi")]
    let comm: &dyn Comm = match &mpi {
        Some(m) => m,
        None => &Serial,
    };
    #[cfg(not(feature = "mpi"))]
    let comm: &dyn Comm = &Serial;
    let root = comm.rank() == 0;
    let result = match cli.command {
        Command::Solve { run, bonded } => {
            let (scene, opts) = options(run);
            commands::solve(&scene, &RunOptions { bonded, ..opts }, comm)
        }
        Command::Safety { run } => {
            let (scene, opts) = options(run);
            commands::safety(&scene, &opts, comm)
        }
        // the other commands run on rank 0 alone
        _ if !root => Ok(()),
        Command::Check { scene, allow_geo_commands } => commands::check(&scene, allow_geo_commands),
        Command::Bench { scene, levels, orders, ratio, start, max_dofs, no_monolithic, out } => commands::bench(
            &scene,
            &subcontact::bench::BenchOptions {
                levels,
                orders,
                ratio,
                start,
                max_dofs,
                monolithic: !no_monolithic,
                out,
            },
        ),
        Command::Paper { fine, paper, quiet } => commands::paper(&fine, &paper, !quiet),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            if root {
                // a closed stderr (a pipe whose reader left) ends quietly
                use std::io::Write;
                let _ = writeln!(std::io::stderr(), "error: {}", chain(&anyhow::Error::from(e)));
            }
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes as one line, `outer: inner: ...`, leaving out a
/// cause whose text the message before it already quotes (several library
/// errors put their source into their own message).
fn chain(e: &anyhow::Error) -> String {
    let mut msg = e.to_string();
    let mut last = msg.clone();
    for cause in e.chain().skip(1) {
        let text = cause.to_string();
        if !last.contains(&text) {
            msg += ": ";
            msg += &text;
        }
        last = text;
    }
    msg
}

/// The scene and the run's options from `solve`'s and `safety`'s arguments.
fn options(a: RunArgs) -> (std::path::PathBuf, RunOptions) {
    let opts = RunOptions {
        out: a.out,
        verbose: !a.quiet,
        substructures: a.substructures,
        threads: a.threads,
        interface: a.interface,
        ignore_memory_estimate: a.no_memory_check,
        allow_geo_commands: a.allow_geo_commands,
        ..Default::default()
    };
    (a.scene, opts)
}
