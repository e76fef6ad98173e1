//! Shared helpers of the integration tests. Here: [`Case`], a scratch
//! directory per test case, with scenes written or copied into it and solved
//! there through the library's driver or the real binary; and the reading of
//! files, the repository's and the results' (text, JSON, CSV rows). By theme, beside it:
//!
//! - [`scenes`]: scene texts that several test files write (a repository
//!   scene with edits, two stacked blocks, Lamé's cylinder);
//! - [`slopes`]: two rock slopes with closed forms (Hoek & Bray's planar
//!   slide, Goodman & Bray's toppling block), their joints rigid or deforming;
//! - [`cli`]: the command line's contract for a failed run (one clean
//!   `error:` paragraph, no result files), and gmsh runs in a case;
//! - [`msh`]: an MSH 4.1 writer for meshes gmsh does not make;
//! - [`measure`]: what the tests measure on a solved run (rates, largest
//!   values, state counts, the difference to the bonded solve, contact forces).
#![allow(dead_code)]

pub mod cli;
pub mod measure;
pub mod msh;
pub mod scenes;
pub mod slopes;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use subcontact::driver::{self, ContactError, Run, RunOptions};

/// A scratch directory for one test case (recreated empty).
pub struct Case {
    pub dir: PathBuf,
}

impl Case {
    pub fn new(name: &str) -> Case {
        let dir = std::env::temp_dir().join("subcontact-tests").join(format!("{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch directory");
        Case { dir }
    }

    /// Writes a file of the case and returns its path.
    pub fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.dir.join(name);
        std::fs::write(&p, text).expect("write case file");
        p
    }

    /// Copies a file of the repository (e.g. "geo/cylinder.geo") into the case.
    pub fn copy(&self, repo_path: &str) -> PathBuf {
        let src = repo_root().join(repo_path);
        let dst = self.dir.join(src.file_name().expect("file name"));
        std::fs::copy(&src, &dst).expect("copy into case");
        dst
    }

    /// The results directory of a scene of this case.
    pub fn out(&self, scene: &str) -> PathBuf {
        self.dir.join("results").join(scene)
    }

    /// Solves a scene file of this case with the library driver.
    pub fn run(&self, scene: &Path) -> subcontact::Result<Run> {
        self.run_with(scene, false)
    }

    /// Solves with every contact bonded (the monolithic solve) or not.
    pub fn run_with(&self, scene: &Path, bonded: bool) -> subcontact::Result<Run> {
        let stem = scene.file_stem().expect("stem").to_string_lossy().to_string();
        let out = self.out(&format!("{stem}{}", if bonded { "-bonded" } else { "" }));
        driver::run(scene, &RunOptions { out: Some(out), bonded, ..Default::default() })
    }

    /// Solves a scene file of this case with the library driver, which must
    /// fail in the contact iteration: the typed error.
    pub fn contact_error(&self, scene: &Path) -> ContactError {
        let err = self.run(scene).err().unwrap_or_else(|| panic!("{}: the run must fail", scene.display()));
        match err.without_scene() {
            subcontact::Error::Contact(e) => *e,
            err => panic!("{}: a contact error, not: {err:#}", scene.display()),
        }
    }

    /// Runs the real binary in this case's directory.
    pub fn cli(&self, args: &[&str]) -> Output {
        Command::new(env!("CARGO_BIN_EXE_subcontact"))
            .args(args)
            .current_dir(&self.dir)
            .output()
            .expect("run subcontact")
    }

    /// Files in a directory (recursively), relative names, sorted.
    pub fn files_in(&self, dir: &Path) -> Vec<String> {
        let mut v = Vec::new();
        fn walk(base: &Path, d: &Path, v: &mut Vec<String>) {
            if let Ok(rd) = std::fs::read_dir(d) {
                for e in rd.flatten() {
                    let p = e.path();
                    if p.is_dir() {
                        walk(base, &p, v);
                    } else {
                        v.push(p.strip_prefix(base).unwrap_or(&p).display().to_string());
                    }
                }
            }
        }
        walk(dir, dir, &mut v);
        v.sort();
        v
    }
}

pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The text of a file, or a panic that names it.
pub fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The text of a repository file (e.g. "geo/cylinder.toml").
pub fn repo_text(repo_path: &str) -> String {
    read(&repo_root().join(repo_path))
}

/// A JSON file (summary.json), parsed.
pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap_or_else(|e| panic!("{}: not JSON: {e}", path.display()))
}

/// A JSON array of three numbers (a vector of summary.json).
pub fn json_vec3(v: &serde_json::Value) -> [f64; 3] {
    std::array::from_fn(|i| v[i].as_f64().unwrap_or_else(|| panic!("not three numbers: {v}")))
}

/// The rows of a CSV file of the results (no quoted fields), as maps from
/// the header's names.
pub fn csv_rows(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = read(path);
    let mut lines = text.lines();
    let head: Vec<String> = lines
        .next()
        .unwrap_or_else(|| panic!("{}: no header", path.display()))
        .split(',')
        .map(str::to_string)
        .collect();
    lines.map(|l| head.iter().cloned().zip(l.split(',').map(str::to_string)).collect()).collect()
}

/// A number of a CSV row of [`csv_rows`].
pub fn csv_num(row: &std::collections::HashMap<String, String>, key: &str) -> f64 {
    let v = row.get(key).unwrap_or_else(|| panic!("no column {key}"));
    v.parse().unwrap_or_else(|_| panic!("{key} = {v:?} is not a number"))
}
