//! A result directory is a transaction (issue 20): the real binary, killed
//! at random instants of real runs, leaves the old set of results or the
//! new one, whole, every time; two runs into one `--out` at once both
//! finish and leave one whole set (or both scenes' sets); a run removes only
//! the files it wrote before, never a user's file or another scene's
//! results; a commit that fails leaves the earlier results as they were.
//!
//! The scene is the dam (three load steps: 14 result files, ~0.5 s a run);
//! its two variants A and B differ in gravity, so that every result file
//! but summary.json and report.md (timings) differs between them and is
//! the same, byte for byte, from one run of the same variant to the next.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::scenes::edited;
use common::{json, Case};

const MANIFEST: &str = ".subcontact-manifest.json";

/// The dam scene of variant `v` ("A" or "B"), its title naming it.
fn dam(v: &str) -> String {
    let g = if v == "A" { "-9.81" } else { "-9.5" };
    edited(
        "geo/dam.toml",
        &[
            ("title = \"Gravity dam", &format!("title = \"Variant {v}: gravity dam")),
            ("gravity = [0.0, -9.81]", &format!("gravity = [0.0, {g}]")),
        ],
    )
}

fn solve(case: &Case, scene: &str, out: &str) -> std::process::Output {
    let o = case.cli(&["solve", scene, "--out", out, "--quiet"]);
    assert!(o.status.success(), "{scene}: {}", String::from_utf8_lossy(&o.stderr));
    o
}

/// The result files of writer `dam` in `dir` (the manifest's list) with
/// their bytes; panics unless every listed file is there.
fn results(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let m = json(&dir.join(MANIFEST));
    let list = m["writers"]["dam"]
        .as_array()
        .unwrap_or_else(|| panic!("{}: the manifest lists no dam files: {m}", dir.display()));
    list.iter()
        .map(|f| {
            let f = f.as_str().expect("a name");
            (
                f.to_string(),
                std::fs::read(dir.join(f))
                    .unwrap_or_else(|e| panic!("{}: listed file {f} is missing: {e}", dir.display())),
            )
        })
        .collect()
}

/// Which variant's whole set `dir` holds, checked against the reference
/// sets: the same files, every file but the timed ones identical to that
/// variant's, and summary.json and report.md naming it.
fn whole_set(dir: &Path, refs: &[(&str, BTreeMap<String, Vec<u8>>)]) -> Result<String, String> {
    let got = results(dir);
    for (v, r) in refs {
        if got.keys().ne(r.keys()) {
            return Err(format!(
                "files {:?}, expected {:?}",
                got.keys().collect::<Vec<_>>(),
                r.keys().collect::<Vec<_>>()
            ));
        }
        let timed = ["summary.json", "report.md"];
        if got.iter().all(|(f, b)| timed.contains(&f.as_str()) || r[f] == *b) {
            let title = json(&dir.join("summary.json"))["title"].as_str().unwrap_or("").to_string();
            let report = String::from_utf8_lossy(&got["report.md"]).into_owned();
            let name = format!("Variant {v}:");
            return if title.starts_with(&name) && report.contains(&name) {
                Ok(v.to_string())
            } else {
                Err(format!("variant {v}'s files with summary title {title:?}"))
            };
        }
    }
    let mixed: Vec<String> = got
        .iter()
        .map(|(f, b)| format!("{f}: {}", refs.iter().find(|(_, r)| r[f] == *b).map_or("neither", |(v, _)| v)))
        .collect();
    Err(format!("a mixed set: {mixed:?}"))
}

/// xorshift64*: random instants without a dependency; the seed is printed.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) % n.max(1)
    }
}

/// Files a user keeps in the result directory, which every run must leave
/// as they are: notes, names that start with the scene's name (another
/// scene's results, a photo, a sketch), and a folder of 300 pictures.
fn user_files(out: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    std::fs::create_dir_all(out.join("photos")).expect("photos");
    let mut files: Vec<(PathBuf, Vec<u8>)> =
        ["notes.txt", "dam3d.vtu", "dam3d_contact.vtu", "dam_site_photo.png", "dam_sketch.svg"]
            .iter()
            .map(|f| (out.join(f), format!("user's {f}").into_bytes()))
            .collect();
    files.extend((0..300).map(|i| (out.join(format!("photos/p{i:03}.png")), vec![i as u8; 100])));
    for (p, b) in &files {
        std::fs::write(p, b).expect("user file");
    }
    files
}

fn user_files_intact(files: &[(PathBuf, Vec<u8>)]) {
    for (p, b) in files {
        assert_eq!(std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())), *b, "{}", p.display());
    }
}

#[test]
fn a_run_killed_at_random_instants_leaves_the_old_or_the_new_results_whole() {
    let case = Case::new("tx-kill");
    case.copy("geo/dam.geo");
    let mut refs = Vec::new();
    for v in ["A", "B"] {
        case.write("dam.toml", &dam(v));
        solve(&case, "dam.toml", &format!("ref{v}"));
        refs.push((v, results(&case.dir.join(format!("ref{v}")))));
    }
    assert_ne!(refs[0].1["dam.vtu"], refs[1].1["dam.vtu"], "the variants differ");
    let out = case.dir.join("out");
    case.write("dam.toml", &dam("A"));
    solve(&case, "dam.toml", "out");
    let user = user_files(&out);
    // how long a run takes here, with the mesh cached
    let t = Instant::now();
    solve(&case, "dam.toml", "out");
    let run_ms = t.elapsed().as_millis() as u64;

    let seed =
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(1, |d| d.as_nanos() as u64) | 1;
    eprintln!("kill test: a run takes {run_ms} ms; seed {seed}");
    let mut rng = Rng(seed);
    let mut last = "A".to_string();
    let mut tally: BTreeMap<&str, usize> = BTreeMap::new();
    for k in 0..30 {
        let v = if k % 2 == 0 { "B" } else { "A" };
        case.write("dam.toml", &dam(v));
        // instants over the whole run, more of them where it writes
        let at = if k % 3 == 0 { rng.below(run_ms) } else { run_ms / 2 + rng.below(run_ms) };
        let mut child = Command::new(env!("CARGO_BIN_EXE_subcontact"))
            .args(["solve", "dam.toml", "--out", "out", "--quiet"])
            .current_dir(&case.dir)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn");
        std::thread::sleep(Duration::from_millis(at));
        let finished = child.try_wait().expect("wait").is_some_and(|s| s.success());
        let _ = child.kill();
        let _ = child.wait();
        let found = whole_set(&out, &refs).unwrap_or_else(|e| panic!("kill {k} at {at} ms (seed {seed}): {e}"));
        assert!(found == last || found == v, "kill {k}: variant {found}, neither the old {last} nor the new {v}");
        if finished {
            assert_eq!(found, v, "kill {k}: the run had finished");
        }
        *tally.entry(if found == v { "new" } else { "old" }).or_default() += 1;
        user_files_intact(&user);
        last = found;
    }
    eprintln!("kill test: {tally:?}");
    // the next run settles whatever the kills left beside the directory
    solve(&case, "dam.toml", "out");
    user_files_intact(&user);
    let beside: Vec<String> = std::fs::read_dir(&case.dir)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".out."))
        .collect();
    assert_eq!(beside, [".out.lock"], "staging directories left");
}

#[test]
fn two_runs_into_one_directory_at_once_leave_one_whole_set() {
    let case = Case::new("tx-two");
    for v in ["A", "B"] {
        std::fs::create_dir_all(case.dir.join(v)).expect("dir");
        std::fs::copy(common::repo_root().join("geo/dam.geo"), case.dir.join(v).join("dam.geo")).expect("geo");
        std::fs::write(case.dir.join(v).join("dam.toml"), dam(v)).expect("scene");
        solve(&case, &format!("{v}/dam.toml"), &format!("ref{v}"));
    }
    let refs: Vec<(&str, BTreeMap<String, Vec<u8>>)> =
        ["A", "B"].iter().map(|v| (*v, results(&case.dir.join(format!("ref{v}"))))).collect();
    let user = user_files(&case.dir.join("shared"));
    for trial in 0..6 {
        let children: Vec<_> = ["A", "B"]
            .iter()
            .map(|v| {
                Command::new(env!("CARGO_BIN_EXE_subcontact"))
                    .args(["solve", &format!("{v}/dam.toml"), "--out", "shared", "--quiet"])
                    .current_dir(&case.dir)
                    .stdout(Stdio::null())
                    .stderr(Stdio::piped())
                    .spawn()
                    .expect("spawn")
            })
            .collect();
        for c in children {
            let o = c.wait_with_output().expect("wait");
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "trial {trial}: {stderr}");
            assert!(stderr.lines().all(|l| l.contains("waiting for another run")), "trial {trial}: {stderr}");
        }
        whole_set(&case.dir.join("shared"), &refs).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
        user_files_intact(&user);
    }
}

#[test]
fn another_scenes_results_and_a_users_files_stay_and_a_failed_commit_changes_nothing() {
    let case = Case::new("tx-others");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    // another scene, whose name starts with this one's, into the same folder
    case.write("dam_b.toml", &dam("B"));
    solve(&case, "dam_b.toml", "shared");
    let theirs: Vec<String> = json(&case.dir.join("shared").join(MANIFEST))["writers"]["dam_b"]
        .as_array()
        .expect("dam_b's files")
        .iter()
        .map(|f| f.as_str().unwrap_or("").to_string())
        .collect();
    let user = user_files(&case.dir.join("shared"));
    solve(&case, "dam.toml", "shared");
    solve(&case, "dam.toml", "shared");
    user_files_intact(&user);
    let m = json(&case.dir.join("shared").join(MANIFEST));
    // dam_b keeps its own files; those of common names (contact.csv, the
    // pictures, summary.json) are dam's now
    let still: Vec<&str> =
        m["writers"]["dam_b"].as_array().expect("dam_b's files").iter().filter_map(|f| f.as_str()).collect();
    assert!(still.contains(&"dam_b.vtu") && still.contains(&"dam_b_contact_step003.vtu"), "{still:?}");
    for f in &theirs {
        assert!(case.dir.join("shared").join(f).is_file(), "{f} of the other scene was removed");
    }

    // summary.json replaced by a directory: the commit fails, nothing changes
    let shared = case.dir.join("shared");
    let before = results(&shared);
    std::fs::remove_file(shared.join("summary.json")).expect("remove");
    std::fs::create_dir_all(shared.join("summary.json/inside")).expect("dir in the way");
    let o = case.cli(&["solve", "dam.toml", "--out", "shared", "--quiet"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("summary.json") && stderr.contains("in the way"), "{stderr}");
    for (f, b) in &before {
        if f != "summary.json" {
            assert_eq!(std::fs::read(shared.join(f)).ok().as_ref(), Some(b), "{f} changed by a failed run");
        }
    }
    user_files_intact(&user);
}

/// `subcontact solve dam.toml 2>&1 | head -1`: the reader leaves after
/// the first line; the run goes on silently, writes its results and exits
/// 0 (before, `failed printing to stdout: Broken pipe`, exit 101).
#[test]
fn a_pipe_whose_reader_leaves_silences_the_run_but_does_not_stop_it() {
    use std::io::BufRead;
    let case = Case::new("tx-pipe");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    for args in [&["solve", "dam.toml", "--out", "out"][..], &["check", "dam.toml"][..], &["--help"][..]] {
        let (reader, writer) = std::io::pipe().expect("pipe");
        let mut child = Command::new(env!("CARGO_BIN_EXE_subcontact"))
            .args(args)
            .current_dir(&case.dir)
            .stdout(writer.try_clone().expect("clone"))
            .stderr(writer)
            .spawn()
            .expect("spawn");
        let mut first = String::new();
        std::io::BufReader::new(reader).read_line(&mut first).expect("a first line");
        // the reader is gone now: every later write meets a broken pipe
        let status = child.wait().expect("wait");
        assert!(status.success(), "{args:?}: {status:?} after {first:?}");
    }
    let refs = [("A", results(&case.dir.join("out")))];
    whole_set(&case.dir.join("out"), &refs).expect("the results of the piped run");
    assert!(json(&case.dir.join("out/summary.json"))["contact"]["converged"].as_bool().unwrap_or(false));
}
