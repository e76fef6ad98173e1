//! The steps of a commit on the file system, each safe to interrupt:
//!
//! - [`carry`]: the new directory gets a hard link (a copy where links are
//!   not possible, a new link for a symbolic one) of everything in the old
//!   one that the commit does not replace, subdirectories (the mesh cache)
//!   included;
//! - [`swap`]: the staging directory and the result directory trade places
//!   in one `renameat2(RENAME_EXCHANGE)` (Linux, ext4/xfs/btrfs/tmpfs);
//!   where the file system refuses it, in two renames through
//!   `.<name>.old-<run>`, whose interruption [`recover`] rolls back;
//! - [`settle`]: the old set, now in the staging directory's place, loses
//!   what the commit replaced and the links it made; anything else in it
//!   (a file a user saved there after the links were made) goes back into
//!   the result directory, so only files the manifest names are removed.
//!   A directory it cannot empty stays, hidden, for the next run's
//!   [`recover`] to settle again.

use std::ffi::OsStr;
use std::fs;
use std::io;
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};

use super::manifest::{Manifest, MANIFEST};
use super::target::Target;

/// Links or copies everything in `from` into the empty directory `to`,
/// except the top-level names `skip` accepts. Fifos, sockets and devices
/// are not carried: [`settle`] moves them back after the swap. An entry
/// that vanishes meanwhile is skipped.
pub fn carry(from: &Path, to: &Path, skip: &dyn Fn(&OsStr) -> bool) -> io::Result<()> {
    for e in fs::read_dir(from)? {
        let e = e?;
        let name = e.file_name();
        if !skip(&name) {
            carry_entry(&e.path(), &to.join(&name))?;
        }
    }
    Ok(())
}

fn carry_entry(src: &Path, dst: &Path) -> io::Result<()> {
    let meta = match fs::symlink_metadata(src) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(e),
    };
    let ft = meta.file_type();
    let done = if ft.is_dir() {
        fs::create_dir(dst)?;
        for e in fs::read_dir(src)? {
            let e = e?;
            carry_entry(&e.path(), &dst.join(e.file_name()))?;
        }
        fs::set_permissions(dst, meta.permissions())
    } else if ft.is_symlink() {
        fs::read_link(src).and_then(|to| std::os::unix::fs::symlink(to, dst))
    } else if ft.is_file() {
        fs::hard_link(src, dst).or_else(|_| fs::copy(src, dst).map(|_| ()))
    } else {
        Ok(())
    };
    match done {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        other => other,
    }
}

/// Puts the staging directory `stage` of run `run` in `target`'s place.
/// Returns where the old set now is (`None` when there was none).
pub fn swap(stage: &Path, target: &Target, run: &str) -> io::Result<Option<PathBuf>> {
    let out = &target.path;
    if fs::symlink_metadata(out).is_err() {
        match fs::rename(stage, out) {
            Ok(()) => return Ok(None),
            // made meanwhile (by someone not holding the lock): exchange
            Err(e) if matches!(e.raw_os_error(), Some(libc::EEXIST | libc::ENOTEMPTY)) => {}
            Err(e) => return Err(e),
        }
    }
    match exchange(stage, out) {
        Ok(()) => Ok(Some(stage.to_path_buf())),
        Err(e) if matches!(e.raw_os_error(), Some(libc::EINVAL | libc::ENOSYS | libc::EOPNOTSUPP)) => {
            // two renames: a kill between them leaves the old set aside,
            // which the next run's `recover` puts back
            let old = target.old_path(run);
            fs::rename(out, &old)?;
            if let Err(e) = fs::rename(stage, out) {
                let _ = fs::rename(&old, out);
                return Err(e);
            }
            Ok(Some(old))
        }
        Err(e) => Err(e),
    }
}

/// Swaps two directories in one step (Linux's renameat2).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| CString::new(p.as_os_str().as_bytes()).map_err(|_| io::Error::from_raw_os_error(libc::EINVAL));
    let (a, b) = (c(a)?, c(b)?);
    // SAFETY: two valid NUL-terminated paths, relative to nothing (absolute)
    let r = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if r == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> io::Result<()> {
    Err(io::Error::from_raw_os_error(libc::ENOSYS))
}

/// Empties the old set `old` after a swap into `out`: removes the
/// top-level files `replaced` accepts and every entry `out` holds the same
/// file of (a link [`carry`] made), recursing into directories both have;
/// moves anything else back into `out`, then removes `old` if it is empty.
/// Returns whether it is gone.
pub fn settle(old: &Path, out: &Path, replaced: &dyn Fn(&OsStr) -> bool) -> bool {
    if let Ok(entries) = fs::read_dir(old) {
        for e in entries.flatten() {
            let (path, there) = (e.path(), out.join(e.file_name()));
            let Ok(meta) = fs::symlink_metadata(&path) else { continue };
            let here = fs::symlink_metadata(&there).ok();
            let same = here.as_ref().is_some_and(|h| h.dev() == meta.dev() && h.ino() == meta.ino());
            if meta.is_dir() {
                if here.as_ref().is_some_and(|h| h.is_dir()) {
                    settle(&path, &there, &|_| false);
                } else if here.is_none() {
                    let _ = fs::rename(&path, &there);
                }
            } else if same || replaced(&e.file_name()) {
                let _ = fs::remove_file(&path);
            } else if here.as_ref().is_none_or(|h| !h.is_dir()) {
                // a file saved after the links were made: the newer one
                let _ = fs::rename(&path, &there);
            }
        }
    }
    fs::remove_dir(old).is_ok()
}

/// What a killed commit left beside `target`, made right (the caller holds
/// the lock, so no live run owns any of it): an old set aside after the
/// first of two renames goes back in place; an old set after a finished
/// swap is settled; a staging directory that never went in is removed.
pub fn recover(target: &Target) {
    let out = &target.path;
    for (path, run, old) in target.leftovers() {
        let current = Manifest::read(out);
        let committed = current.last.as_ref().filter(|l| l.run == run);
        if old && fs::symlink_metadata(out).is_err() {
            let _ = fs::rename(&path, out);
        } else if let Some(last) = committed {
            let before = Manifest::read(&path);
            let (was, now) = (before.files(&last.writer), current.files(&last.writer));
            settle(&path, out, &|n| n == MANIFEST || was.iter().chain(now).any(|f| OsStr::new(f) == n));
        } else if !old {
            let _ = fs::remove_dir_all(&path);
        }
    }
}

/// Flushes a directory's entries to disk.
pub fn sync_dir(dir: &Path) -> io::Result<()> {
    fs::File::open(dir)?.sync_all()
}
