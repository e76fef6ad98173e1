//! The steps of a commit on the file system, each safe to interrupt, all
//! through directory handles ([`super::at`]):
//!
//! - [`carry`]: the new directory gets a hard link of every file of the
//!   old one that the commit does not replace, the same symbolic links,
//!   and its subdirectories (the mesh cache, a user's folders) made anew
//!   with the owner, group, mode and extended attributes of the old ones;
//! - [`swap`]: the staging directory and the result directory trade places
//!   in one `renameat2(RENAME_EXCHANGE)` (Linux, ext4/xfs/btrfs/tmpfs);
//!   where the file system refuses it, in two renames through
//!   `.<name>.old-<run>`, whose interruption [`recover`] rolls back;
//! - [`settle`]: the old set, now in the staging directory's place, loses
//!   what the commit replaced and the links it made; anything else in it
//!   (a file a user saved there after the links were made) goes back into
//!   the result directory, so only files the manifests name are removed.
//!   The old set's manifest goes last: until the old set is empty, it says
//!   which of its files were the writer's, and a run killed while settling
//!   is settled again by the next one ([`recover`]) with the same answer.

use std::ffi::{OsStr, OsString};
use std::io;
use std::path::Path;

use rustix::fs::FileType;

use super::at::{kind, Dir};
use super::manifest::{Manifest, MANIFEST};
use super::output_error::OutputError;
use super::target::Target;

/// Whether a path relative to the result directory is replaced by the commit.
pub type Replaced<'a> = &'a dyn Fn(&Path) -> bool;

/// Links everything in `from` (at `rel` inside the result directory) into
/// `to`, except what `skip` accepts and names `to` already has (the new
/// files); subdirectories are made anew like the old ones and filled the
/// same way. Fifos, sockets and devices are not carried: [`settle`] moves
/// them back after the swap. An entry that vanishes meanwhile is skipped;
/// a mount point is refused (it cannot move with the directory).
pub fn carry(from: &Dir, to: &Dir, rel: &Path, skip: Replaced) -> Result<(), OutputError> {
    let fail = |name: &OsStr, source: io::Error| OutputError::Carry { from: from.path.join(name), source };
    for name in from.names().map_err(|e| fail(OsStr::new(""), e))? {
        let r = rel.join(&name);
        if skip(&r) || to.stat(&name).map_err(|e| fail(&name, e))?.is_some() && !is_dir(to, &name) {
            continue;
        }
        let Some(st) = from.stat(&name).map_err(|e| fail(&name, e))? else { continue };
        let done = match kind(&st) {
            FileType::Directory => {
                if from.is_mount_point(&name) {
                    return Err(OutputError::MountPoint { path: from.path.join(&name) });
                }
                let Some(sub) = from.open(&name).map_err(|e| fail(&name, e))? else { continue };
                let made = match to.open(&name).map_err(|e| fail(&name, e))? {
                    Some(d) => d,
                    None => to.mkdir(&name, 0o700).map_err(|e| fail(&name, e))?,
                };
                carry(&sub, &made, &r, skip)?;
                made.copy_meta(&sub)
            }
            FileType::Symlink => from.copy_symlink(&name, to, &name),
            FileType::RegularFile => from.link(&name, to, &name),
            _ => Ok(()),
        };
        match done {
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(fail(&name, e)),
            Ok(()) => {}
        }
    }
    Ok(())
}

fn is_dir(d: &Dir, name: &OsStr) -> bool {
    d.stat(name).ok().flatten().is_some_and(|s| kind(&s) == FileType::Directory)
}

/// Puts the staging directory `stage` (a name in the parent) of run `run`
/// in `target`'s place. Returns the name in the parent where the old set
/// now is (`None` when there was none).
pub fn swap(target: &Target, stage: &OsStr, run: &str) -> io::Result<Option<OsString>> {
    let p = &target.parent;
    if p.stat(&target.name)?.is_none() {
        match p.rename(stage, p, &target.name, false) {
            Ok(()) => return Ok(None),
            // made meanwhile (by someone not holding the lock): exchange
            Err(e) if matches!(e.raw_os_error(), Some(libc::EEXIST | libc::ENOTEMPTY)) => {}
            Err(e) => return Err(e),
        }
    }
    match p.rename(stage, p, &target.name, true) {
        Ok(()) => Ok(Some(stage.to_os_string())),
        Err(e) if matches!(e.raw_os_error(), Some(libc::EINVAL | libc::ENOSYS | libc::EOPNOTSUPP)) => {
            // two renames: a kill between them leaves the old set aside,
            // which the next run's `recover` puts back
            let old = target.old_name(run);
            p.rename(&target.name, p, &old, false)?;
            if let Err(e) = p.rename(stage, p, &target.name, false) {
                let _ = p.rename(&old, p, &target.name, false);
                return Err(e);
            }
            Ok(Some(old))
        }
        Err(e) => Err(e),
    }
}

/// Empties the old set `old` (at `rel`) after a swap into `out`: removes
/// what `replaced` accepts and every entry `out` holds the same file of (a
/// link [`carry`] made), recursing into directories both have; moves
/// anything else back into `out`; the manifest last. Directories emptied
/// are removed; the caller removes `old` itself.
pub fn settle(old: &Dir, out: &Dir, rel: &Path, replaced: Replaced) {
    writable(old);
    let Ok(names) = old.names() else { return };
    let top = rel.as_os_str().is_empty();
    for name in names.iter().filter(|n| !(top && n.as_os_str() == MANIFEST)) {
        let r = rel.join(name);
        let Ok(Some(st)) = old.stat(name) else { continue };
        let here = out.stat(name).ok().flatten();
        let same = here.as_ref().is_some_and(|h| (h.st_dev, h.st_ino) == (st.st_dev, st.st_ino));
        let here_dir = here.as_ref().is_some_and(|h| kind(h) == FileType::Directory);
        if kind(&st) == FileType::Directory {
            if here_dir {
                if let (Ok(Some(o)), Ok(Some(n))) = (old.open(name), out.open(name)) {
                    settle(&o, &n, &r, replaced);
                    let _ = old.rmdir(name);
                }
            } else if here.is_none() {
                let _ = old.rename(name, out, name, false);
            }
        } else if same || replaced(&r) {
            let _ = old.unlink(name);
        } else if !here_dir {
            // a file saved after the links were made: the newer one
            let _ = old.replace(name, out, name);
        }
    }
    if top {
        let _ = old.unlink(OsStr::new(MANIFEST));
    }
}

/// Lets this process empty a directory of its own that is read-only.
fn writable(d: &Dir) {
    if let Ok(st) = d.own() {
        if st.st_mode & 0o200 == 0 && st.st_uid == rustix::process::geteuid().as_raw() {
            let _ = rustix::fs::fchmod(d.fd(), rustix::fs::Mode::from_raw_mode((st.st_mode | 0o700) & 0o7777));
        }
    }
}

/// What a killed commit left beside `target`, made right (the caller holds
/// the lock, so no live run commits): an old set aside after the first of
/// two renames goes back in place; an old set after a finished swap is
/// settled; a staging directory that never went in is removed, unless its
/// run is alive (it holds a `flock` on it while it meshes and solves).
pub fn recover(target: &Target) {
    let p = &target.parent;
    for (name, run, old) in target.leftovers() {
        let Ok(Some(left)) = p.open(&name) else { continue };
        if !old && !left.try_flock().unwrap_or(false) {
            continue;
        }
        let out = p.open(&target.name).ok().flatten();
        let current = out.as_ref().map(Manifest::read_at).unwrap_or_default();
        let committed = current.last.as_ref().filter(|l| l.run == run);
        if old && out.is_none() {
            let _ = p.rename(&name, p, &target.name, false);
        } else if let (Some(last), Some(out)) = (committed, &out) {
            let before = Manifest::read_at(&left);
            let (was, now) = (before.files(&last.writer), current.files(&last.writer));
            let replaced = |r: &Path| r == Path::new(MANIFEST) || was.iter().chain(now).any(|f| Path::new(f) == r);
            settle(&left, out, Path::new(""), &replaced);
            let _ = p.rmdir(&name);
        } else if !old {
            let _ = p.remove_tree(&name);
        }
    }
}
