//! Shared helpers of the integration tests: a scratch directory per case,
//! scenes written into it, runs through the real gmsh CLI and the library's
//! driver, or through the real binary.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use subcontact::driver::{self, Run, RunOptions};

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
    pub fn run(&self, scene: &Path) -> anyhow::Result<Run> {
        self.run_with(scene, false)
    }

    /// Solves with every contact bonded (the monolithic solve) or not.
    pub fn run_with(&self, scene: &Path, bonded: bool) -> anyhow::Result<Run> {
        let stem = scene.file_stem().expect("stem").to_string_lossy().to_string();
        let out = self.out(&format!("{stem}{}", if bonded { "-bonded" } else { "" }));
        driver::run(scene, &RunOptions { out: Some(out), bonded, ..Default::default() })
    }

    /// Runs the real binary in this case's directory.
    pub fn cli(&self, args: &[&str]) -> Output {
        Command::new(env!("CARGO_BIN_EXE_subcontact")).args(args).current_dir(&self.dir).output().expect("run subcontact")
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

/// Least-squares slope of log(y) against log(x).
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}
