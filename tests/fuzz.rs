//! Fuzzing (issue 20): the MSH reader, the scene parser and a whole
//! `check` (scene, mesh, model, memory estimate) on mutated inputs must
//! never panic or hang: every input ends in Ok or in an error. And the
//! commit of result files (issue 32): a fuzzed sequence of commits, kills
//! at random instants of them and foreign files loses no data.
//!
//! A mutation loop of our own, not cargo-fuzz: cargo-fuzz needs a nightly
//! toolchain (sanitizer flags) and this project builds on stable only; the
//! loop needs no dependency. It starts from real inputs (the repository's
//! scenes and the meshes gmsh makes of them, ASCII and binary) and mutates
//! them as a careless editor or a damaged disk would: lines deleted,
//! duplicated or swapped, numbers replaced by edge values (nan, inf, -0,
//! 1e308, huge integers), strings emptied or swapped, bytes flipped, files
//! truncated. Each input runs in a thread under a watchdog (10 s); a panic
//! or a hang fails the test and saves the input in `target/fuzz-found/`.
//!
//! `make test` runs each target for a few seconds (`FUZZ_SECONDS`, default
//! 4); `make fuzz` for minutes. Inputs it found once are replayed from
//! tests/fuzz/ every time.

mod common;

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use common::Case;
use subcontact::mesh::msh::read_msh;
use subcontact::model::Model;
use subcontact::scene::Scene;

/// xorshift64*.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const EDGE: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-0.0",
    "0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "99999999999999999999",
    "4294967297",
    "18446744073709551616",
    "0.5",
    "\"\"",
    "\"x\"",
    "[]",
    "[1e308, nan]",
    "{}",
    "true",
];

/// A text mutated 1-4 times.
fn mutate_text(rng: &mut Rng, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(4) {
        if lines.is_empty() {
            break;
        }
        let i = rng.below(lines.len());
        match rng.below(7) {
            0 => {
                lines.remove(i);
            }
            1 => {
                let l = lines[i].clone();
                lines.insert(rng.below(lines.len()), l);
            }
            2 => {
                let j = rng.below(lines.len());
                lines.swap(i, j);
            }
            3 | 4 => {
                // a number token replaced by an edge value
                let words: Vec<String> =
                    lines[i].split_inclusive([' ', ',', '[', ']', '=']).map(str::to_string).collect();
                let nums: Vec<usize> = (0..words.len())
                    .filter(|&k| words[k].trim_matches([' ', ',', '[', ']', '=']).parse::<f64>().is_ok())
                    .collect();
                if !nums.is_empty() {
                    let k = nums[rng.below(nums.len())];
                    let tail: String = words[k].chars().filter(|c| [' ', ',', '[', ']', '='].contains(c)).collect();
                    let mut w = words.clone();
                    w[k] = format!("{}{tail}", EDGE[rng.below(EDGE.len())]);
                    lines[i] = w.concat();
                }
            }
            5 => {
                // a quoted string emptied or replaced by another line's
                if let (Some(a), Some(b)) = (lines[i].find('"'), lines[i].rfind('"')) {
                    if b > a {
                        let other = lines[rng.below(lines.len())].clone();
                        let repl = other.split('"').nth(1).unwrap_or("").to_string();
                        lines[i] = format!("{}\"{repl}\"{}", &lines[i][..a], &lines[i][b + 1..]);
                    }
                }
            }
            _ => {
                let cut = rng.below(lines[i].len() + 1);
                let mut l = lines[i].clone();
                while !l.is_char_boundary(cut.min(l.len())) {
                    l.pop();
                }
                l.truncate(cut.min(l.len()));
                lines[i] = l;
            }
        }
    }
    let mut s = lines.join("\n");
    s.push('\n');
    s
}

/// Bytes mutated 1-8 times: flips, overwritten words, a cut.
fn mutate_bytes(rng: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for _ in 0..1 + rng.below(8) {
        if b.is_empty() {
            break;
        }
        let i = rng.below(b.len());
        match rng.below(4) {
            0 => b[i] ^= 1 << rng.below(8),
            1 => b[i] = rng.next() as u8,
            2 => {
                let word: [u8; 8] =
                    [u64::MAX, 0, 1 << 31, 1 << 63, u32::MAX as u64, rng.next()][rng.below(6)].to_le_bytes();
                for (k, w) in word.iter().enumerate().take(b.len() - i) {
                    b[i + k] = *w;
                }
            }
            _ => b.truncate(i),
        }
    }
    b
}

/// Runs `f` on `input` in a thread under a watchdog; a panic or a hang
/// saves the input and fails.
fn guarded(target: &str, input: &Path, f: impl FnOnce() + Send + 'static) {
    let (tx, rx) = mpsc::channel();
    let worker = std::thread::spawn(move || {
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
        let _ = tx.send(r.is_ok());
    });
    let outcome = rx.recv_timeout(Duration::from_secs(10));
    if !matches!(outcome, Ok(true)) {
        let keep = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-found").join(target);
        std::fs::create_dir_all(&keep).expect("fuzz-found");
        let saved = keep.join(input.file_name().expect("name"));
        let _ = std::fs::copy(input, &saved);
        panic!(
            "{target}: {} on the input saved as {}",
            if outcome.is_err() { "a hang (10 s)" } else { "a panic" },
            saved.display()
        );
    }
    let _ = worker.join();
}

fn seconds() -> f64 {
    std::env::var("FUZZ_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(4.0)
}

fn seed() -> u64 {
    std::env::var("FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or_else(|| {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(1, |d| d.as_nanos() as u64) | 1
    })
}

/// The repository's scenes meshed (cached in the case) and rewritten to
/// read their .msh: (scene name, scene text, mesh path).
fn seeds(case: &Case) -> Vec<(String, String, PathBuf)> {
    let mut out = Vec::new();
    for (name, edits) in
        [("cylinder", vec![]), ("dam", vec![]), ("blocks3d", vec![("lc = 0.1,", "lc = 0.25,")]), ("footing", vec![])]
    {
        case.copy(&format!("geo/{name}.geo"));
        let text = common::scenes::edited(&format!("geo/{name}.toml"), &edits);
        let path = case.write(&format!("{name}.toml"), &text);
        let scene = Scene::load(&path).expect("seed scene");
        let (_, msh, _) =
            subcontact::driver::load_mesh(&scene, &case.dir.join(format!("mesh-{name}")), false).expect("seed mesh");
        let text = text.replace(&format!("mesh = \"{name}.geo\""), &format!("mesh = \"{}\"", msh.display()));
        out.push((name.to_string(), text, msh));
    }
    out
}

/// The whole of `check` in this process: scene, mesh, model, parts, memory.
fn check(path: &Path, out: &Path) {
    let Ok(scene) = Scene::load(path) else { return };
    let Ok((mesh, _, _)) = subcontact::driver::load_mesh(&scene, out, false) else { return };
    let Ok(model) = Model::build(&mesh, &scene.model_spec()) else { return };
    let parts = subcontact::substructure::cut(
        &model,
        subcontact::substructure::parts(&model),
        scene.solver.substructures.min(4),
    );
    let dofs = subcontact::substructure::parts::dof_counts(&model, &parts);
    let kind = subcontact::contact::system::InterfaceKind::choose(scene.solver.interface, &parts, model.nd);
    let _ = subcontact::memory::estimate(
        &model,
        &parts.iter().collect::<Vec<_>>(),
        kind,
        1,
        true,
        dofs.interface,
        scene.solver.load_steps,
    );
    let _ = subcontact::model::warnings::warnings(&model);
}

/// Replays tests/fuzz/<target>/* and then mutates for FUZZ_SECONDS.
fn run(target: &str, mut one: impl FnMut(&mut Rng, usize)) {
    let s = seed();
    eprintln!("fuzz {target}: seed {s} (FUZZ_SEED={s} repeats it), {} s", seconds());
    let mut rng = Rng(s);
    let t = Instant::now();
    let mut n = 0;
    while t.elapsed().as_secs_f64() < seconds() {
        one(&mut rng, n);
        n += 1;
    }
    eprintln!("fuzz {target}: {n} inputs, no panic, no hang");
}

fn replay(target: &str, f: impl Fn(&Path)) {
    let dir = common::repo_root().join("tests/fuzz").join(target);
    for e in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
        f(&e.path());
    }
}

#[test]
fn msh_reader_never_panics_or_hangs() {
    let case = Case::new("fuzz-msh");
    let meshes: Vec<Vec<u8>> = seeds(&case).iter().map(|(_, _, m)| std::fs::read(m).expect("seed mesh")).collect();
    // an ASCII one too: gmsh writes binary
    let ascii = case.dir.join("ascii.msh");
    common::msh::write_msh41(
        &ascii,
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[common::msh::MshGroup { name: "b".into(), dim: 2, gmsh_type: 2, cells: vec![vec![0, 1, 2]] }],
    );
    let ascii = std::fs::read_to_string(&ascii).expect("ascii");
    replay("msh", |p| {
        let p = p.to_path_buf();
        guarded("msh", &p.clone(), move || {
            let _ = read_msh(&p);
        })
    });
    run("msh", |rng, n| {
        let bytes = if rng.below(3) == 0 {
            mutate_text(rng, &ascii).into_bytes()
        } else {
            {
                let m = rng.below(meshes.len());
                mutate_bytes(rng, &meshes[m])
            }
        };
        let p = case.dir.join(format!("input-{n}.msh"));
        std::fs::write(&p, bytes).expect("input");
        let q = p.clone();
        guarded("msh", &p, move || {
            let _ = read_msh(&q);
        });
        let _ = std::fs::remove_file(&p);
    });
}

#[test]
fn scene_parser_never_panics_or_hangs() {
    let case = Case::new("fuzz-scene");
    let scenes: Vec<String> = seeds(&case).into_iter().map(|(_, t, _)| t).collect();
    replay("scene", |p| {
        let p = p.to_path_buf();
        guarded("scene", &p.clone(), move || {
            let _ = Scene::load(&p);
        })
    });
    run("scene", |rng, n| {
        let p = case.dir.join(format!("input-{n}.toml"));
        let k = rng.below(scenes.len());
        std::fs::write(&p, mutate_text(rng, &scenes[k])).expect("input");
        let q = p.clone();
        guarded("scene", &p, move || {
            let _ = Scene::load(&q);
        });
        let _ = std::fs::remove_file(&p);
    });
}

#[test]
fn check_of_mutated_scenes_never_panics_or_hangs() {
    let case = Case::new("fuzz-check");
    let seeds = seeds(&case);
    let out = case.dir.join("out");
    replay("check", |p| {
        let (p, o) = (p.to_path_buf(), out.clone());
        guarded("check", &p.clone(), move || check(&p, &o))
    });
    run("check", |rng, n| {
        let (_, text, _) = &seeds[rng.below(seeds.len())];
        let p = case.dir.join(format!("input-{n}.toml"));
        std::fs::write(&p, mutate_text(rng, text)).expect("input");
        let (q, o) = (p.clone(), out.clone());
        guarded("check", &p, move || check(&q, &o));
        let _ = std::fs::remove_file(&p);
    });
}

/// One commit of `writer`'s files (generation `generation`) into `dir`, in
/// a forked child that this process kills after `kill_after` (or lets
/// finish when `None`).
fn forked_commit(dir: &Path, writer: &str, names: &[String], generation: u64, kill_after: Option<Duration>) {
    let mut staged = subcontact::output::files::Staged::new(dir, writer);
    for n in names {
        staged.add(n, format!("{writer}-{generation}").into_bytes());
    }
    // SAFETY: the child only commits and leaves with _exit
    let pid = unsafe { libc::fork() };
    assert!(pid >= 0, "fork");
    if pid == 0 {
        let ok = staged.commit().is_ok();
        // SAFETY: ends the child at once
        unsafe { libc::_exit(if ok { 0 } else { 1 }) };
    }
    if let Some(t) = kill_after {
        std::thread::sleep(t);
        // SAFETY: signals our own child
        unsafe { libc::kill(pid, libc::SIGKILL) };
    }
    let mut status = 0;
    // SAFETY: waits for our own child
    unsafe { libc::waitpid(pid, &mut status, 0) };
}

/// What a result directory must hold after any sequence of commits,
/// kills and foreign files: each writer's listed files all there and of
/// one generation, every foreign file as it was written, nothing else.
fn commit_invariants(dir: &Path, foreign: &std::collections::BTreeMap<String, Vec<u8>>) -> Result<(), String> {
    let m = common::json(&dir.join(".subcontact-manifest.json"));
    let mut listed = Vec::new();
    for (w, files) in m["writers"].as_object().cloned().unwrap_or_default() {
        let mut generations = std::collections::BTreeSet::new();
        for f in files.as_array().cloned().unwrap_or_default() {
            let f = f.as_str().unwrap_or("").to_string();
            let text = std::fs::read_to_string(dir.join(&f)).map_err(|e| format!("{w}'s {f}: {e}"))?;
            generations.insert(text);
            listed.push(f);
        }
        if generations.len() > 1 || generations.iter().any(|g| !g.starts_with(&format!("{w}-"))) {
            return Err(format!("{w}'s files are of several runs: {generations:?}"));
        }
    }
    for (f, bytes) in foreign {
        if std::fs::read(dir.join(f)).ok().as_ref() != Some(bytes) {
            return Err(format!("the foreign file {f} changed or vanished"));
        }
    }
    let mut walk = vec![PathBuf::new()];
    while let Some(rel) = walk.pop() {
        for e in std::fs::read_dir(dir.join(&rel)).map_err(|e| e.to_string())?.flatten() {
            let r = rel.join(e.file_name()).to_string_lossy().into_owned();
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                walk.push(PathBuf::from(r));
            } else if r != ".subcontact-manifest.json" && !listed.contains(&r) && !foreign.contains_key(&r) {
                return Err(format!("stale file {r}"));
            }
        }
    }
    Ok(())
}

/// The commit path (issue 32): a fuzzed sequence of runs of two writers
/// (each a random set of names, some shared), kills at random instants of
/// their commits, and foreign files added between them; after each step
/// the directory holds whole sets, every foreign file, nothing stale.
#[test]
fn the_commit_path_loses_no_data_under_kills_and_foreign_files() {
    let case = Case::new("fuzz-commit");
    let dir = case.dir.join("out");
    let mut foreign = std::collections::BTreeMap::new();
    let mut generation = 0;
    run("commit", |rng, n| {
        match rng.below(4) {
            0 => {
                let f = if rng.below(2) == 0 {
                    format!("user_{}.txt", rng.below(6))
                } else {
                    format!("photos/p{}.png", rng.below(6))
                };
                if dir.is_dir() {
                    std::fs::create_dir_all(dir.join("photos")).expect("photos");
                    let bytes = format!("user {n}").into_bytes();
                    std::fs::write(dir.join(&f), &bytes).expect("foreign file");
                    foreign.insert(f, bytes);
                }
            }
            _ => {
                let writer = ["a", "b"][rng.below(2)];
                let mut names: Vec<String> = (0..rng.below(6)).map(|i| format!("{writer}_{i}.vtu")).collect();
                if rng.below(2) == 0 {
                    names.push("shared.csv".into());
                }
                generation += 1;
                let kill = (rng.below(3) > 0).then(|| Duration::from_micros(rng.below(3000) as u64));
                forked_commit(&dir, writer, &names, generation, kill);
            }
        }
        if dir.is_dir() {
            if let Err(e) = commit_invariants(&dir, &foreign) {
                panic!("step {n}: {e}");
            }
        }
    });
    // a last commit that finishes settles whatever the kills left beside it
    forked_commit(&dir, "a", &["a_0.vtu".into()], generation + 1, None);
    commit_invariants(&dir, &foreign).unwrap_or_else(|e| panic!("after the last commit: {e}"));
    let beside: Vec<String> = std::fs::read_dir(&case.dir)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".out."))
        .collect();
    assert_eq!(beside, [".out.lock"], "staging directories left");
}
