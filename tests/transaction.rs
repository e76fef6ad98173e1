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
            continue;
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
    if refs.iter().all(|(_, r)| got.keys().ne(r.keys())) {
        return Err(format!(
            "files {:?}, expected those of one variant: {:?}",
            got.keys().collect::<Vec<_>>(),
            refs.iter().map(|(_, r)| r.keys().collect::<Vec<_>>()).collect::<Vec<_>>()
        ));
    }
    let mixed: Vec<String> = got
        .iter()
        .map(|(f, b)| format!("{f}: {}", refs.iter().find(|(_, r)| r.get(f) == Some(b)).map_or("neither", |(v, _)| v)))
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

/// Nothing but the lock beside the result directory `out` of the case.
fn nothing_beside(case: &Case) {
    let beside: Vec<String> = std::fs::read_dir(&case.dir)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".out."))
        .collect();
    assert_eq!(beside, [".out.lock"], "staging directories left");
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
    nothing_beside(&case);
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

/// The system calls of a commit that change the file system or order it;
/// a kill is injected at each of them in turn.
const COMMIT_CALLS: &str =
    "openat,mkdirat,linkat,unlinkat,renameat2,fsync,fchown,fchmod,fsetxattr,symlinkat,flock,getdents64";

/// A system call: its name, and its occurrence among that name's calls.
type Call = (String, usize);

/// The commit's system calls in one run of `scene` into `out` (the main
/// thread's, from the second opening of the lock on: the first makes the
/// stage when the run starts): (name, its occurrence among that name's
/// calls since the process started), for `strace -e inject=NAME:when=N`.
fn commit_calls(case: &Case, scene: &str, out: &str) -> Vec<Call> {
    let log = case.dir.join("strace.log");
    let o = Command::new("strace")
        .args(["-qq", "-o"])
        .arg(&log)
        .args([
            "-e",
            &format!("trace={COMMIT_CALLS}"),
            env!("CARGO_BIN_EXE_subcontact"),
            "solve",
            scene,
            "--out",
            out,
            "--quiet",
        ])
        .current_dir(&case.dir)
        .output()
        .expect("strace (the Makefile's test and stress targets install it: apt-get install strace)");
    assert!(o.status.success(), "traced run: {}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&log).expect("strace log");
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut calls = Vec::new();
    let mut locks = 0;
    for line in text.lines().filter(|l| !l.starts_with("<...") && !l.starts_with("+++") && !l.starts_with("---")) {
        let Some(name) = line.split('(').next().filter(|n| COMMIT_CALLS.split(',').any(|c| c == *n)) else { continue };
        let n = seen.entry(name.to_string()).or_default();
        *n += 1;
        if name == "openat" && line.contains(&format!(".{out}.lock\"")) {
            locks += 1;
        }
        if locks >= 2 {
            calls.push((name.to_string(), *n));
        }
    }
    assert!(calls.len() > 20, "the commit's calls: {calls:?}");
    calls
}

/// Files in `dir` that no manifest lists and that are not the user's:
/// what a kill left for ever (issue 32: the old scene's `dam_step003.vtu`
/// beside a 2-step run's results).
fn stale(dir: &Path, user: &[(PathBuf, Vec<u8>)]) -> Vec<String> {
    let m = json(&dir.join(MANIFEST));
    let listed: Vec<String> = m["writers"]
        .as_object()
        .map(|w| {
            w.values()
                .flat_map(|v| v.as_array().cloned().unwrap_or_default())
                .filter_map(|f| f.as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    let mut found = Vec::new();
    let mut walk = vec![PathBuf::new()];
    while let Some(rel) = walk.pop() {
        for e in std::fs::read_dir(dir.join(&rel)).expect("dir").flatten() {
            let r = rel.join(e.file_name());
            let s = r.to_string_lossy().into_owned();
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                walk.push(r);
            } else if s != MANIFEST && !listed.contains(&s) && !user.iter().any(|(p, _)| *p == dir.join(&r)) {
                found.push(s);
            }
        }
    }
    found
}

/// Kills runs at the commit's system calls `which` picks (indices into
/// the traced commit), alternating a 3-step and a 2-step scene, and checks
/// after each: a whole set, old or new; the user's files as they were; no
/// stale file; nothing but the lock beside the directory once a run ends.
fn kill_at_calls(tag: &str, which: &dyn Fn(usize, &[Call]) -> bool) {
    let case = Case::new(tag);
    case.copy("geo/dam.geo");
    let variant = |v: &str| {
        let three = dam(v);
        if v == "A" {
            three
        } else {
            three
                .replace("load_steps = 3", "load_steps = 2")
                .replace("factors = [0.0, 0.5, 1.0]", "factors = [0.0, 1.0]")
                .replace("gravity_factors = [1.0, 1.0, 1.0]", "gravity_factors = [1.0, 1.0]")
        }
    };
    let mut refs = Vec::new();
    for v in ["A", "B"] {
        case.write("dam.toml", &variant(v));
        solve(&case, "dam.toml", &format!("ref{v}"));
        refs.push((v, results(&case.dir.join(format!("ref{v}")))));
    }
    assert_ne!(refs[0].1.len(), refs[1].1.len(), "the variants write different files: {:?}", refs[1].1.keys());
    let out = case.dir.join("out");
    case.write("dam.toml", &variant("A"));
    solve(&case, "dam.toml", "out");
    std::fs::create_dir_all(out.join("photos")).expect("photos");
    let user: Vec<(PathBuf, Vec<u8>)> = ["notes.txt", "dam_site_photo.png", "photos/p1.png", "photos/p2.png"]
        .iter()
        .map(|f| (out.join(f), format!("user's {f}").into_bytes()))
        .collect();
    for (p, b) in &user {
        std::fs::write(p, b).expect("user file");
    }
    case.write("dam.toml", &variant("B"));
    let calls = commit_calls(&case, "dam.toml", "out");
    let mut tally: BTreeMap<&str, usize> = BTreeMap::new();
    for (k, (name, n)) in calls.iter().enumerate().filter(|(k, _)| which(*k, &calls)) {
        // an ordinary run of A settles what the last kill left (checked),
        // so that the killed run of B makes the traced run's calls
        case.write("dam.toml", &variant("A"));
        solve(&case, "dam.toml", "out");
        assert_eq!(whole_set(&out, &refs).as_deref(), Ok("A"), "the run after the kill before call {k}");
        let left = stale(&out, &user);
        assert!(left.is_empty(), "the run after the kill before call {k}: stale files {left:?}");
        case.write("dam.toml", &variant("B"));
        let o = Command::new("strace")
            .args(["-qq", "-o", "/dev/null", "-e", &format!("inject={name}:signal=KILL:when={n}")])
            .args([env!("CARGO_BIN_EXE_subcontact"), "solve", "dam.toml", "--out", "out", "--quiet"])
            .current_dir(&case.dir)
            .output()
            .expect("strace");
        let at = format!("killed at call {k} of the commit ({name} #{n}, exit {:?})", o.status.code());
        let found = whole_set(&out, &refs).unwrap_or_else(|e| panic!("{at}: {e}"));
        user_files_intact(&user);
        let left = stale(&out, &user);
        assert!(left.is_empty(), "{at}: stale files {left:?}");
        *tally.entry(if found == "B" { "new" } else { "old" }).or_default() += 1;
    }
    eprintln!("kill at system calls: {} calls in the commit, {tally:?}", calls.len());
    solve(&case, "dam.toml", "out");
    user_files_intact(&user);
    assert!(stale(&out, &user).is_empty());
    nothing_beside(&case);
}

/// A few kill points of the commit: its first call, around the swap (the
/// commit point) and its last; `make stress` kills at every one.
#[test]
fn a_run_killed_at_system_calls_of_its_commit_leaves_a_whole_set_and_nothing_stale() {
    kill_at_calls("tx-calls", &|k, calls| {
        let swap = calls.iter().position(|(n, _)| n == "renameat2").unwrap_or(0);
        k == 0 || (swap.saturating_sub(1)..=swap + 3).contains(&k) || k + 1 == calls.len()
    });
}

#[test]
#[ignore = "make stress: a kill at every system call of the commit, a few minutes"]
fn a_run_killed_at_every_system_call_of_its_commit_leaves_a_whole_set_and_nothing_stale() {
    kill_at_calls("tx-every-call", &|_, _| true);
}

/// The first line of the dam scene's failure, run into `out`.
fn fails(case: &Case, out: &str) -> String {
    let o = case.cli(&["solve", "dam.toml", "--out", out, "--quiet"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Issue 32: a link named `mesh` inside --out was followed (the cache
/// deleted and rewritten where it pointed); the lock was opened through a
/// link and truncated; a dangling-link --out said "File exists". None of
/// these touches anything now, and each says what it found, before any work.
#[test]
fn nothing_outside_the_result_directory_is_touched_through_a_link() {
    let case = Case::new("tx-links");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    let victim = case.dir.join("victim");
    std::fs::create_dir_all(&victim).expect("victim");
    for f in ["dam.msh", "dam.msh.key", "precious"] {
        std::fs::write(victim.join(f), format!("someone else's {f}")).expect("victim file");
    }
    let untouched = || {
        for f in ["dam.msh", "dam.msh.key", "precious"] {
            assert_eq!(std::fs::read_to_string(victim.join(f)).expect("victim file"), format!("someone else's {f}"));
        }
    };
    std::fs::create_dir_all(case.dir.join("out")).expect("out");
    std::os::unix::fs::symlink(&victim, case.dir.join("out/mesh")).expect("link");
    let msg = fails(&case, "out");
    assert!(msg.contains("out/mesh") && msg.contains("symbolic link"), "{msg}");
    untouched();
    std::fs::remove_file(case.dir.join("out/mesh")).expect("unlink");
    std::fs::remove_file(case.dir.join(".out.lock")).expect("the lock of the refused run");
    std::os::unix::fs::symlink(victim.join("precious"), case.dir.join(".out.lock")).expect("link");
    let msg = fails(&case, "out");
    assert!(msg.contains(".out.lock") && msg.contains("symbolic link"), "{msg}");
    untouched();
    std::os::unix::fs::symlink(case.dir.join("nowhere"), case.dir.join("dangling")).expect("link");
    let msg = fails(&case, "dangling");
    assert!(msg.contains("symbolic link") && msg.contains("does not exist") && !msg.contains("File exists"), "{msg}");
}

/// A link where the last run wrote a result file (contact.csv) was
/// refused only when the results were written, after the whole solve (a
/// long run lost for a link); it is refused before any work now, and what
/// it points at stays as it was.
#[test]
fn a_link_where_a_result_file_goes_is_refused_before_the_solve() {
    let case = Case::new("tx-link-early");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    solve(&case, "dam.toml", "out");
    let victim = case.dir.join("victim.csv");
    std::fs::write(&victim, "someone else's").expect("victim");
    std::fs::remove_file(case.dir.join("out/contact.csv")).expect("unlink");
    std::os::unix::fs::symlink(&victim, case.dir.join("out/contact.csv")).expect("link");
    let o = case.cli(&["solve", "dam.toml", "--out", "out"]);
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("out/contact.csv") && msg.contains("symbolic link"), "{msg}");
    assert!(!msg.contains("DOFs") && !msg.contains("contact iteration"), "refused after work: {msg}");
    assert_eq!(std::fs::read_to_string(&victim).expect("victim"), "someone else's");
}

/// Issue 32: a .geo that never finished blocked every later run into its
/// --out (gmsh meshed under the directory's lock, with no time limit).
/// Now gmsh meshes outside the lock, and stops at `[gmsh] timeout`.
#[test]
fn a_never_ending_geo_ends_at_its_time_limit_and_blocks_no_other_run() {
    let case = Case::new("tx-timeout");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    let geo = std::fs::read_to_string(case.dir.join("dam.geo")).expect("geo");
    std::fs::create_dir_all(case.dir.join("slow")).expect("slow");
    std::fs::write(case.dir.join("slow/dam.geo"), format!("{geo}\nSleep 600;\n")).expect("slow geo");
    std::fs::write(case.dir.join("slow/dam.toml"), dam("A").replace("[gmsh]", "[gmsh]\ntimeout = 8")).expect("scene");
    let t = Instant::now();
    let slow = Command::new(env!("CARGO_BIN_EXE_subcontact"))
        .args(["solve", "slow/dam.toml", "--out", "out", "--quiet"])
        .current_dir(&case.dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    std::thread::sleep(Duration::from_millis(500));
    // another run into the same directory meanwhile: not held up
    let o = case.cli(&["solve", "dam.toml", "--out", "out", "--quiet"]);
    let other = t.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("waiting"), "{}", String::from_utf8_lossy(&o.stderr));
    let o = slow.wait_with_output().expect("wait");
    let took = t.elapsed().as_secs_f64();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("within 8 s ([gmsh] timeout)") && msg.contains("slow/dam.geo"), "{msg}");
    assert!(other < 8.0 && (8.0..20.0).contains(&took), "the other run ended at {other} s, the slow one at {took} s");
    // gmsh is gone with what it started, and left nothing in the results
    let ps = Command::new("pgrep").args(["-f", "slow/dam.geo"]).output().expect("pgrep");
    assert!(ps.stdout.is_empty(), "gmsh still runs: {}", String::from_utf8_lossy(&ps.stdout));
    results(&case.dir.join("out"));
    nothing_beside(&case);
}

/// Issue 32: run as root into another user's 700 directory, the run made
/// it anew as root's (the user was locked out); a writable --out in a
/// read-only parent failed only after the whole solve; a mount point
/// inside --out ended up hidden in a stage. As root here (the test says
/// so and checks what it can otherwise).
#[test]
fn the_result_directory_keeps_its_owner_and_what_cannot_be_kept_is_refused_first() {
    let case = Case::new("tx-owner");
    case.copy("geo/dam.geo");
    case.write("dam.toml", &dam("A"));
    let out = case.dir.join("home/out");
    std::fs::create_dir_all(&out).expect("out");
    std::fs::write(out.join("notes.txt"), b"mine").expect("notes");
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    // the case's directory is this process's: its owner says who runs
    let root = std::fs::metadata(&case.dir).expect("meta").uid() == 0;
    if root {
        std::os::unix::fs::chown(&out, Some(65534), Some(65534)).expect("chown");
    }
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o700)).expect("chmod");
    let before = std::fs::metadata(&out).expect("meta");
    solve(&case, "dam.toml", "home/out");
    let after = std::fs::metadata(&out).expect("meta");
    assert_eq!(
        (after.uid(), after.gid(), after.mode()),
        (before.uid(), before.gid(), before.mode()),
        "as root: {root}"
    );
    assert_eq!(std::fs::read(out.join("notes.txt")).expect("notes"), b"mine");
    if !root {
        eprintln!("not root: the read-only parent and the mount point are not tried");
        return;
    }
    // a read-only parent (immutable even for root): refused before any work
    let home = case.dir.join("home");
    let t = Instant::now();
    assert!(Command::new("chattr").args(["+i"]).arg(&home).status().is_ok_and(|s| s.success()), "chattr +i");
    let o = case.cli(&["solve", "dam.toml", "--out", "home/out", "--quiet"]);
    let _ = Command::new("chattr").args(["-i"]).arg(&home).status();
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(msg.contains("home") && msg.contains("not writable") && msg.contains("an --out inside"), "{msg}");
    assert!(t.elapsed().as_secs_f64() < 1.0, "refused after {:?}", t.elapsed());
    // a mount point inside --out: refused, left where it is
    std::fs::create_dir_all(out.join("data")).expect("data");
    let mounted =
        Command::new("mount").args(["-t", "tmpfs", "none"]).arg(out.join("data")).status().is_ok_and(|s| s.success());
    if mounted {
        std::fs::write(out.join("data/inside"), b"on the mount").expect("write on the mount");
        let o = case.cli(&["solve", "dam.toml", "--out", "home/out", "--quiet"]);
        let msg = String::from_utf8_lossy(&o.stderr).into_owned();
        let still = std::fs::read(out.join("data/inside"));
        let _ = Command::new("umount").arg(out.join("data")).status();
        assert_eq!(o.status.code(), Some(1), "{msg}");
        assert!(msg.contains("data") && msg.contains("mount point"), "{msg}");
        assert_eq!(still.expect("the mount stays in place"), b"on the mount");
    } else {
        eprintln!("mount -t tmpfs is not allowed here: the mount point is not tried");
    }
}
