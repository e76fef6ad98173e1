//! Result files are written all together or not at all, as one
//! transaction on the result directory (SQLite's promise, for a directory):
//! after a kill at any instant, the directory holds the old set of results
//! or the new one, whole.
//!
//! [`Staged`] keeps a run's files in memory; [`Staged::commit`]:
//!
//! 1. locks the directory ([`lock`]: `<parent>/.<name>.lock`; a second run
//!    into the same directory waits, saying for whom) and makes right what
//!    a killed commit left ([`swap::recover`]);
//! 2. builds the new directory beside it, `<parent>/.<name>.stage-<run>`
//!    (`<run>` = process id and time): hard links to everything of the old
//!    directory that stays ([`swap::carry`]), then the new files and the
//!    [`manifest`], each flushed to disk;
//! 3. swaps the two directories in one step (`renameat2` with
//!    `RENAME_EXCHANGE`): this is the commit point;
//! 4. empties the old set, now in the staging directory's place, of what
//!    the manifest says this writer wrote before and of the links, and
//!    removes it ([`swap::settle`]).
//!
//! Why a whole-directory swap and not a journal of renames per file: a
//! journal makes the set whole only once the next run has replayed it, and
//! a person opening the results in ParaView after a kill never runs one.
//! The price is that the directory is a new one after every run: whatever
//! else lives in it must be carried over, and is. Files the tool did not
//! write (a user's notes, another scene's results, the mesh cache `mesh/`)
//! are hard-linked into the new directory, so they are the same files,
//! never copied or lost; a file saved into the directory while a commit
//! runs is moved back after the swap. A file of the name a run writes is
//! replaced, whoever wrote it; nothing else is ever removed. A shell whose
//! working directory is the result directory sees the old one until it
//! changes directory again (`cd .`).
//!
//! [`OutputError`] is the error of the whole `output` module.

pub mod lock;
pub mod manifest;
mod swap;
mod target;

pub use lock::Lock;
pub use manifest::{Manifest, MANIFEST};

use std::ffi::OsStr;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// What went wrong while building or writing result files. Messages name the
/// file, field or cell concerned and the cause.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot create result directory {}: {source}", path.display())]
    CreateDir {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write result file {}: {source}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot move {} into place as {}: {source}", from.display(), to.display())]
    Rename {
        from: PathBuf,
        to: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot lock the result directory ({}): {source}", path.display())]
    Lock {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write results into {}: {why}; choose another --out", path.display())]
    InvalidDir { path: PathBuf, why: String },
    #[error("cannot write result file {}: a directory of that name is in the way; move it elsewhere", path.display())]
    InTheWay { path: PathBuf },
    #[error("cannot carry the files of {} into the new set of results: {source}", from.display())]
    Carry {
        from: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("invalid result file name {name:?} in {}: it must be a plain file name", dir.display())]
    InvalidName { dir: PathBuf, name: String },
    #[error(
        "{location} field `{field}` has {len} values, expected {} ({n_comp} per {location} × {count} {location}s)",
        *n_comp as u128 * *count as u128
    )]
    FieldLength { location: &'static str, field: String, n_comp: usize, count: usize, len: usize },
    #[error("{location} field `{field}` has no components")]
    NoComponents { location: &'static str, field: String },
    #[error("cell {index} (gmsh element {tag}, {kind}) has {actual} nodes, expected {expected}")]
    CellNodes { index: usize, tag: u64, kind: &'static str, expected: usize, actual: usize },
    #[error("cell {index} (gmsh element {tag}) refers to node {node}, but there are only {n_points} points")]
    NodeOutOfRange { index: usize, tag: u64, node: usize, n_points: usize },
    #[error("too many {what} for a VTU file: {count}")]
    TooLarge { what: &'static str, count: usize },
    #[error("cannot encode the VTU data: {0}")]
    Vtk(String),
}

/// A set of result files kept in memory until `commit`.
#[derive(Clone)]
pub struct Staged {
    dir: PathBuf,
    writer: String,
    keep: bool,
    files: Vec<(String, Vec<u8>)>,
}

/// Names and sizes only: the contents may be large.
impl std::fmt::Debug for Staged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Staged")
            .field("dir", &self.dir)
            .field("writer", &self.writer)
            .field("files", &self.files.iter().map(|(n, b)| (n, b.len())).collect::<Vec<_>>())
            .finish()
    }
}

/// A plain file name: not empty, not `.`/`..`, no separator, no NUL, not
/// the manifest.
fn is_plain_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && name != MANIFEST
        && !name.contains(['/', '\\', '\0'])
        && Path::new(name).file_name().and_then(|n| n.to_str()) == Some(name)
}

impl Staged {
    /// An empty set of files that `writer` (a scene's name, `bench`) puts
    /// into `dir`, replacing all that it wrote there before (nothing is
    /// touched until `commit`).
    pub fn new(dir: &Path, writer: &str) -> Self {
        Staged { dir: dir.to_path_buf(), writer: writer.to_string(), keep: false, files: Vec::new() }
    }

    /// The same, but what `writer` wrote before and does not write again stays.
    pub fn amend(dir: &Path, writer: &str) -> Self {
        Staged { keep: true, ..Staged::new(dir, writer) }
    }

    /// Stages file `name` (a plain file name inside the directory). Adding a
    /// name again replaces its bytes and keeps its first position.
    pub fn add(&mut self, name: &str, bytes: Vec<u8>) {
        match self.files.iter_mut().find(|(n, _)| n == name) {
            Some((_, b)) => *b = bytes,
            None => self.files.push((name.to_string(), bytes)),
        }
    }

    /// Locks the directory (waiting for another run, silently) and commits.
    pub fn commit(self) -> Result<Vec<PathBuf>, OutputError> {
        self.commit_with(&mut |_| {})
    }

    /// Locks the directory, `waiting` told when another run holds it, and commits.
    pub fn commit_with(self, waiting: &mut dyn FnMut(&str)) -> Result<Vec<PathBuf>, OutputError> {
        self.check_names()?;
        let lock = Lock::acquire(&self.dir, waiting)?;
        self.commit_locked(&lock)
    }

    /// Commits under a lock the caller holds on this directory (to read and
    /// write it in one transaction). Returns the paths of the files
    /// written, in the order they were added; on any error the directory
    /// is as it was.
    pub fn commit_locked(self, lock: &Lock) -> Result<Vec<PathBuf>, OutputError> {
        self.check_names()?;
        let target = lock.target();
        swap::recover(target);
        let out = &target.path;
        let exists = match fs::symlink_metadata(out) {
            Ok(m) if m.is_dir() => true,
            Ok(_) => {
                return Err(OutputError::InvalidDir { path: out.clone(), why: "it is a file, not a directory".into() })
            }
            Err(_) => false,
        };
        for (name, _) in &self.files {
            let p = out.join(name);
            if fs::symlink_metadata(&p).is_ok_and(|m| m.is_dir()) {
                return Err(OutputError::InTheWay { path: p });
            }
        }
        let run = format!(
            "{}-{}",
            std::process::id(),
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
        );
        let old = Manifest::read(out);
        let names: Vec<String> = self.files.iter().map(|(n, _)| n.clone()).collect();
        let manifest = old.after(&run, &self.writer, &names, self.keep);
        let was: &[String] = if self.keep { &[] } else { old.files(&self.writer) };
        let replaced = |n: &OsStr| n == MANIFEST || names.iter().chain(was).any(|f| OsStr::new(f) == n);

        let stage = target.stage_path(&run);
        fs::create_dir(&stage).map_err(|source| OutputError::CreateDir { path: stage.clone(), source })?;
        let swapped = self.fill(&stage, exists.then_some(out.as_path()), &replaced, &manifest).and_then(|()| {
            swap::swap(&stage, target, &run).map_err(|source| OutputError::Rename {
                from: stage.clone(),
                to: out.clone(),
                source,
            })
        });
        let old_set = match swapped {
            Ok(old_set) => old_set,
            Err(e) => {
                let _ = fs::remove_dir_all(&stage);
                return Err(e);
            }
        };
        // committed: the rest only tidies
        let _ = swap::sync_dir(&target.parent);
        if let Some(old_set) = old_set {
            swap::settle(&old_set, out, &replaced);
        }
        Ok(names.iter().map(|n| self.dir.join(n)).collect())
    }

    fn check_names(&self) -> Result<(), OutputError> {
        match self.files.iter().find(|(n, _)| !is_plain_name(n)) {
            Some((name, _)) => Err(OutputError::InvalidName { dir: self.dir.clone(), name: name.clone() }),
            None => Ok(()),
        }
    }

    /// The new set in `stage`: what stays of `out`, the files, the manifest.
    fn fill(
        &self,
        stage: &Path,
        out: Option<&Path>,
        replaced: &dyn Fn(&OsStr) -> bool,
        manifest: &Manifest,
    ) -> Result<(), OutputError> {
        if let Some(out) = out {
            swap::carry(out, stage, replaced)
                .map_err(|source| OutputError::Carry { from: out.to_path_buf(), source })?;
            if let Ok(m) = fs::metadata(out) {
                let _ = fs::set_permissions(stage, m.permissions());
            }
        }
        let manifest = manifest.bytes();
        for (name, bytes) in self.files.iter().map(|(n, b)| (n.as_str(), b)).chain([(MANIFEST, &manifest)]) {
            let path = stage.join(name);
            let write = || -> std::io::Result<()> {
                let mut f = fs::OpenOptions::new().write(true).create_new(true).open(&path)?;
                f.write_all(bytes)?;
                f.sync_all()
            };
            write().map_err(|source| OutputError::Write { path: self.dir.join(name), source })?;
        }
        swap::sync_dir(stage).map_err(|source| OutputError::Write { path: stage.to_path_buf(), source })
    }
}

#[cfg(test)]
mod tests;
