//! Result files are written all together or not at all, as one
//! transaction on the result directory (SQLite's promise, for a directory):
//! after a kill at any instant, the directory holds the old set of results
//! or the new one, whole; and nothing outside it is ever written,
//! truncated or removed.
//!
//! A run's [`Stage`] is made when the run starts, beside the directory,
//! `<parent>/.<name>.stage-<run>` (`<run>` = process id and time); gmsh
//! meshes into it, outside the lock. [`Staged`] keeps a run's result files
//! in memory; [`Stage::commit`]:
//!
//! 1. locks the directory ([`lock`]: `<parent>/.<name>.lock`; a second run
//!    into the same directory waits, saying for whom) and makes right what
//!    a killed commit left ([`swap::recover`]);
//! 2. writes the new files and the [`manifest`] into the stage, each
//!    flushed to disk, then hard links to everything of the old directory
//!    that stays ([`swap::carry`]), and gives the stage the old
//!    directory's owner, group, mode and extended attributes;
//! 3. swaps the two directories in one step (`renameat2` with
//!    `RENAME_EXCHANGE`): this is the commit point;
//! 4. empties the old set, now in the staging directory's place, of what
//!    the manifests say this writer wrote and of the links, its manifest
//!    last, and removes it ([`swap::settle`]).
//!
//! Every step works through directory handles the run opened itself
//! ([`at`]): a symbolic link planted in the result directory or beside it
//! is never followed, and one where a result file, the mesh cache or the
//! lock goes is refused.
//!
//! Why a whole-directory swap and not a journal of renames per file: a
//! journal makes the set whole only once the next run has replayed it, and
//! a person opening the results in ParaView after a kill never runs one.
//! The price is that the directory is a new one after every run: whatever
//! else lives in it must be carried over, and is. Files the tool did not
//! write (a user's notes, another scene's results, other scenes' meshes)
//! are hard-linked into the new directory, so they are the same files,
//! never copied or lost; subdirectories are made anew with the owner,
//! group, mode and attributes of the old ones; a file saved into the
//! directory while a commit runs is moved back after the swap. What cannot
//! be kept that way (a mount point inside the directory; for a user other
//! than root, another user's directory or file) is refused before the run
//! does any work. A file of the name a run writes is replaced, whoever
//! wrote it; nothing else is ever removed. A shell whose working directory
//! is the result directory sees the old one until it changes directory
//! again (`cd .`).
//!
//! [`OutputError`] is the error of the whole `output` module.

pub mod at;
pub mod lock;
pub mod manifest;
mod output_error;
mod stage;
mod swap;
mod target;

pub use lock::Lock;
pub use manifest::{Manifest, MANIFEST};
pub use output_error::OutputError;
pub use stage::{Stage, MESH_DIR};

use std::path::{Path, PathBuf};

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

    /// Makes a stage, locks the directory (`waiting` told when another run
    /// holds it) and commits.
    pub fn commit_with(self, waiting: &mut dyn FnMut(&str)) -> Result<Vec<PathBuf>, OutputError> {
        self.check_names()?;
        Stage::begin(&self.dir, waiting)?.commit(self, waiting)
    }

    /// Commits under a lock the caller holds on this directory (to read and
    /// write it in one transaction). Returns the paths of the files
    /// written, in the order they were added; on any error the directory
    /// is as it was.
    pub fn commit_locked(self, lock: &Lock) -> Result<Vec<PathBuf>, OutputError> {
        self.check_names()?;
        Stage::under(lock)?.commit_locked(self, lock)
    }

    /// The names of the staged files, in the order they were added.
    fn names(&self) -> impl Iterator<Item = String> + '_ {
        self.files.iter().map(|(n, _)| n.clone())
    }

    fn check_names(&self) -> Result<(), OutputError> {
        match self.files.iter().find(|(n, _)| !is_plain_name(n)) {
            Some((name, _)) => Err(OutputError::InvalidName { dir: self.dir.clone(), name: name.clone() }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests;
