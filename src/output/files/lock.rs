//! The lock of a result directory: `<parent>/.<name>.lock`, held with
//! `flock` while a run makes its staging directory, commits its results or
//! tidies what a killed run left. Another run that wants the same
//! directory waits for it, after saying which process it waits for (read
//! from the kernel's table of locks, `/proc/locks`). The kernel releases
//! the lock when its holder exits or is killed, so a lock is never stale;
//! the file itself stays (removing a lock file races with the next process
//! that opens it).
//!
//! The lock file is opened relative to the parent's handle, created when
//! missing, never followed when it is a symbolic link (`O_NOFOLLOW`),
//! never truncated and never written: whoever can write the parent cannot
//! make a run write a file elsewhere by planting a link of that name. A
//! name that is not a plain file (a link, a fifo, a device) is refused.
//!
//! The lock lives beside the directory, not in it: a commit replaces the
//! directory itself (see the module above), which would take a lock inside
//! it along.

use std::fs::{File, TryLockError};
use std::os::unix::fs::MetadataExt;
use std::path::Path;

use rustix::fs::{FileType, Mode, OFlags};

use super::output_error::OutputError;
use super::target::Target;

/// A held lock on a result directory; released when dropped.
#[derive(Debug)]
pub struct Lock {
    /// Held open: the flock lasts as long as it.
    _file: File,
    target: Target,
}

impl Lock {
    /// Locks the result directory `dir` (its parent created if need be,
    /// so that it has a place for the lock), waiting while another process
    /// holds it; `waiting` gets one line saying whom it waits for before
    /// the wait starts.
    pub fn acquire(dir: &Path, waiting: &mut dyn FnMut(&str)) -> Result<Lock, OutputError> {
        Lock::on(Target::resolve(dir)?, waiting)
    }

    /// Locks the resolved directory `target`.
    pub(super) fn on(target: Target, waiting: &mut dyn FnMut(&str)) -> Result<Lock, OutputError> {
        let path = target.beside_path(&target.lock_name());
        let lock_err = |source: std::io::Error| OutputError::Lock { path: path.clone(), source };
        let flags = OFlags::RDONLY | OFlags::CREATE | OFlags::NOFOLLOW | OFlags::NONBLOCK | OFlags::CLOEXEC;
        let fd = match rustix::fs::openat(
            target.parent.fd(),
            target.lock_name().as_os_str(),
            flags,
            Mode::from_raw_mode(0o644),
        ) {
            Ok(fd) => fd,
            Err(rustix::io::Errno::LOOP) => return Err(not_plain(&path, "a symbolic link")),
            Err(e) => return Err(lock_err(e.into())),
        };
        let file = File::from(fd);
        let meta = file.metadata().map_err(lock_err)?;
        if FileType::from_raw_mode(meta.mode()) != FileType::RegularFile {
            return Err(not_plain(&path, "not a plain file"));
        }
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                waiting(&format!(
                    "waiting for another run{} writing into {}",
                    holder(meta.dev(), meta.ino()),
                    target.path.display()
                ));
                file.lock().map_err(lock_err)?;
            }
            Err(TryLockError::Error(source)) => return Err(lock_err(source)),
        }
        Ok(Lock { _file: file, target })
    }

    /// The directory this lock holds.
    pub fn dir(&self) -> &Path {
        &self.target.path
    }

    pub(super) fn target(&self) -> &Target {
        &self.target
    }
}

fn not_plain(path: &Path, what: &str) -> OutputError {
    OutputError::Lock {
        path: path.to_path_buf(),
        source: std::io::Error::other(format!(
            "it is {what}; a run only ever uses a plain file of its own there, so remove it (or give another --out)"
        )),
    }
}

/// " (process N)" for the process holding a `flock` on the file (`dev`,
/// `ino`), from `/proc/locks`, or nothing.
fn holder(dev: u64, ino: u64) -> String {
    let Ok(text) = std::fs::read_to_string("/proc/locks") else { return String::new() };
    let (major, minor) = (rustix::fs::major(dev), rustix::fs::minor(dev));
    let want = format!("{major:02x}:{minor:02x}:{ino}");
    text.lines()
        .filter(|l| l.contains("FLOCK") && !l.contains("->"))
        .find_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            let at = f.iter().position(|w| w.ends_with(&format!(":{ino}")))?;
            let same = f[at].eq_ignore_ascii_case(&want) || same_dev(f[at], major, minor);
            same.then(|| f.get(at.checked_sub(1)?)?.parse::<u32>().ok()).flatten()
        })
        .map_or(String::new(), |pid| format!(" (process {pid})"))
}

/// Whether "MAJ:MIN:INO" (hex device numbers) names device `major:minor`.
fn same_dev(field: &str, major: u32, minor: u32) -> bool {
    let mut p = field.split(':');
    let hex = |s: Option<&str>| s.and_then(|s| u32::from_str_radix(s, 16).ok());
    hex(p.next()) == Some(major) && hex(p.next()) == Some(minor)
}
