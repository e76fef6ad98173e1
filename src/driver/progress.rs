//! Lines on stderr: a stage's progress when the run is verbose, and what
//! a run says whatever `--quiet` asks (a wait for another run).

use super::run_options::RunOptions;

pub(super) fn progress(opts: &RunOptions, msg: &str) {
    if opts.verbose {
        say(msg);
    }
}

/// A line on stderr, whatever `--quiet` says (a wait for another run); a
/// closed stderr (a pipe whose reader left) is no reason to stop a run.
pub(super) fn say(msg: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "subcontact: {msg}");
}
