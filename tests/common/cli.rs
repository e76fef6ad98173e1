//! The command line's contract for a failed run (DESIGN.md §4, "Command
//! line"): exit status 1 and one paragraph `error: ...` on stderr, no panic
//! or backtrace, nothing on stdout, and no result file in the results
//! directory (the mesh cache, `mesh/*.msh` and `.msh.key`, is an input and
//! may stay). And the gmsh CLI run in a case's directory, for meshes the
//! driver does not make itself.

use std::path::Path;
use std::process::{Command, Output};

use super::Case;

/// Runs `subcontact solve SCENE --out OUT --quiet` in the case and checks
/// the failure is clean (see [`clean_failure`]); returns the message.
pub fn solve_fails(case: &Case, scene: &str, out: &str) -> String {
    let output = case.cli(&["solve", scene, "--out", out, "--quiet"]);
    clean_failure(case, &output, &case.dir.join(out))
}

/// Exit status 1, stderr one paragraph starting with `error: `, no panic or
/// backtrace, empty stdout, and nothing but mesh caches (`[<name>/]mesh/*.msh`,
/// `.msh.key`, `.msh.cut.json`, the manifest that lists them, and the locks `.<name>.lock`
/// beside them) in `results`. Returns the message, trimmed.
pub fn clean_failure(case: &Case, out: &Output, results: &Path) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(1),
        "expected exit status 1 (a user error), got {:?}; stderr:\n{stderr}",
        out.status
    );
    assert!(stderr.starts_with("error: "), "stderr must start with `error: `:\n{stderr}");
    let msg = stderr.trim().to_string();
    assert!(!msg.contains("\n\n"), "the message must be one paragraph:\n{stderr}");
    for bad in ["panicked", "backtrace", "RUST_BACKTRACE", "thread '"] {
        assert!(!msg.contains(bad), "stderr shows a panic or backtrace ({bad:?}):\n{stderr}");
    }
    assert!(stdout.trim().is_empty(), "a failed --quiet run printed on stdout:\n{stdout}");
    let files = case.files_in(results);
    let results_written: Vec<&String> = files.iter().filter(|f| !mesh_cache(results, f)).collect();
    assert!(
        results_written.is_empty(),
        "a failed run left files in {}: {results_written:?}\n(stderr: {msg})",
        results.display()
    );
    msg
}

/// Whether `f` (relative to `dir`) is part of a mesh cache: `mesh/*.msh`,
/// its key, a manifest listing nothing but those, or a lock.
pub fn mesh_cache(dir: &Path, f: &str) -> bool {
    let mesh = |f: &str| {
        (f.starts_with("mesh/") || f.contains("/mesh/"))
            && [".msh", ".msh.key", ".msh.cut.json"].iter().any(|e| f.ends_with(e))
    };
    let name = f.rsplit('/').next().unwrap_or(f);
    if name == ".subcontact-manifest.json" {
        let m = super::json(&dir.join(f));
        let writers = m["writers"].as_object().cloned().unwrap_or_default();
        return writers
            .values()
            .flat_map(|v| v.as_array().cloned().unwrap_or_default())
            .all(|v| v.as_str().is_some_and(mesh));
    }
    // the lock beside a result directory
    mesh(f) || (name.starts_with('.') && name.ends_with(".lock"))
}

/// Asserts that `msg` contains every one of `needles`.
pub fn says(msg: &str, needles: &[&str]) {
    for n in needles {
        assert!(msg.contains(n), "the message lacks {n:?}:\n{msg}");
    }
}

/// Runs `gmsh ARGS` in the case directory, failing the test if gmsh does.
pub fn gmsh<S: AsRef<str>>(case: &Case, args: &[S]) {
    let args: Vec<&str> = args.iter().map(|a| a.as_ref()).collect();
    let out =
        Command::new("gmsh").args(&args).current_dir(&case.dir).output().expect("gmsh CLI (apt-get install gmsh)");
    assert!(
        out.status.success(),
        "gmsh {} failed: {}{}",
        args.join(" "),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}
