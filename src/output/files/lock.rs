//! The lock of a result directory: `<parent>/.<name>.lock`, held with
//! `flock` (std's `File::lock`) while a run writes the mesh cache inside
//! the directory or commits its results. Another run that wants the same
//! directory waits for it, after saying which process it waits for (the
//! holder writes its pid into the file). The kernel releases the lock when
//! its holder exits or is killed, so a lock is never stale; the file itself
//! stays (removing a lock file races with the next process that opens it).
//!
//! The lock lives beside the directory, not in it: a commit replaces the
//! directory itself (see the module above), which would take a lock inside
//! it along.

use std::fs::{self, File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

use super::target::Target;
use super::OutputError;

/// A held lock on a result directory; released when dropped.
#[derive(Debug)]
pub struct Lock {
    file: File,
    target: Target,
}

impl Lock {
    /// Locks the result directory `dir` (created with its parents if need
    /// be, so that it has a place for the lock), waiting while another
    /// process holds it; `waiting` gets one line saying whom it waits for
    /// before the wait starts.
    pub fn acquire(dir: &Path, waiting: &mut dyn FnMut(&str)) -> Result<Lock, OutputError> {
        let target = Target::resolve(dir)?;
        let path = target.lock_path();
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|source| OutputError::Lock { path: path.clone(), source })?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                waiting(&format!("waiting for another run{} writing into {}", holder(&path), target.path.display()));
                file.lock().map_err(|source| OutputError::Lock { path: path.clone(), source })?;
            }
            Err(TryLockError::Error(source)) => return Err(OutputError::Lock { path, source }),
        }
        let mut lock = Lock { file, target };
        lock.mark();
        Ok(lock)
    }

    /// The directory this lock holds.
    pub fn dir(&self) -> &Path {
        &self.target.path
    }

    pub(super) fn target(&self) -> &Target {
        &self.target
    }

    /// Writes this process's id into the lock file, for the next waiter's
    /// message (best effort: the lock is the flock, not the text).
    fn mark(&mut self) {
        let _ = self
            .file
            .set_len(0)
            .and_then(|()| self.file.rewind())
            .and_then(|()| writeln!(self.file, "{}", std::process::id()));
    }
}

/// " (process N)" from the lock file's text, or nothing.
fn holder(path: &PathBuf) -> String {
    let mut text = String::new();
    let _ = fs::File::open(path).and_then(|mut f| f.read_to_string(&mut text));
    match text.trim().parse::<u32>() {
        Ok(pid) => format!(" (process {pid})"),
        Err(_) => String::new(),
    }
}
