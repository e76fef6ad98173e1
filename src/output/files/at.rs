//! Every file operation of a commit, relative to a directory handle the
//! run opened itself ([`Dir`]), never through a path that someone else
//! could turn into a symbolic link meanwhile: `openat` with `O_NOFOLLOW`
//! (and `O_DIRECTORY` for directories), `mkdirat`, `linkat`, `unlinkat`,
//! `renameat2` (`RENAME_EXCHANGE` for the swap), `fstatat` with
//! `AT_SYMLINK_NOFOLLOW`, and the owner, mode and extended attributes of a
//! directory copied through its handle (`fchown`, `fchmod`, `fsetxattr`).
//! A name that is a symbolic link where a directory or file of ours is
//! expected is an error (`ELOOP`, `ENOTDIR`), never followed.
//!
//! Why rustix and not cap-std: the commit needs Linux's `renameat2` with
//! `RENAME_EXCHANGE`, `linkat` between two handles, `statx`'s mount-root
//! attribute and the extended attributes, which rustix exposes one to one
//! as safe functions over `OwnedFd`, where cap-std's portable `Dir` offers
//! none of the four; and the commit is a dozen system calls whose order is
//! the whole point (the crash recovery), best written as those calls.

use std::ffi::{OsStr, OsString};
use std::io;
use std::os::fd::{AsFd, OwnedFd};
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::path::{Path, PathBuf};

use rustix::fs::{self as rfs, AtFlags, FileType, Mode, OFlags, RenameFlags, Stat};

/// A directory opened by the run, with the path it was opened as (for
/// messages only: nothing is ever opened through `path`).
#[derive(Debug)]
pub struct Dir {
    fd: OwnedFd,
    pub path: PathBuf,
}

/// What a name in a directory is, not following a symbolic link.
pub fn kind(st: &Stat) -> FileType {
    FileType::from_raw_mode(st.st_mode)
}

fn err(e: rustix::io::Errno) -> io::Error {
    io::Error::from_raw_os_error(e.raw_os_error())
}

const DIR_FLAGS: OFlags = OFlags::DIRECTORY.union(OFlags::NOFOLLOW).union(OFlags::CLOEXEC).union(OFlags::RDONLY);

impl Dir {
    /// Opens the directory at `path` (a path the user gave: followed).
    pub fn open_path(path: &Path) -> io::Result<Dir> {
        let fd = rfs::open(path, OFlags::DIRECTORY | OFlags::CLOEXEC | OFlags::RDONLY, Mode::empty()).map_err(err)?;
        Ok(Dir { fd, path: path.to_path_buf() })
    }

    /// A second handle on this directory.
    pub fn try_clone(&self) -> io::Result<Dir> {
        Ok(Dir { fd: self.fd.try_clone()?, path: self.path.clone() })
    }

    /// The subdirectory `name`, or `None` when there is none; a symbolic
    /// link or a file of that name is an error.
    pub fn open(&self, name: &OsStr) -> io::Result<Option<Dir>> {
        match rfs::openat(&self.fd, name, DIR_FLAGS, Mode::empty()) {
            Ok(fd) => Ok(Some(Dir { fd, path: self.path.join(name) })),
            Err(rustix::io::Errno::NOENT) => Ok(None),
            Err(e) => Err(err(e)),
        }
    }

    /// Makes the subdirectory `name` (it must not exist) and opens it.
    pub fn mkdir(&self, name: &OsStr, mode: u32) -> io::Result<Dir> {
        rfs::mkdirat(&self.fd, name, Mode::from_raw_mode(mode)).map_err(err)?;
        self.open(name)?.ok_or_else(|| io::Error::from(io::ErrorKind::NotFound))
    }

    /// What `name` is (not following a link), or `None` when it is absent.
    pub fn stat(&self, name: &OsStr) -> io::Result<Option<Stat>> {
        match rfs::statat(&self.fd, name, AtFlags::SYMLINK_NOFOLLOW) {
            Ok(s) => Ok(Some(s)),
            Err(rustix::io::Errno::NOENT) => Ok(None),
            Err(e) => Err(err(e)),
        }
    }

    /// This directory's own status.
    pub fn own(&self) -> io::Result<Stat> {
        rfs::fstat(&self.fd).map_err(err)
    }

    /// Whether `name` is the root of a mount (a mount point inside the directory).
    pub fn is_mount_point(&self, name: &OsStr) -> bool {
        rfs::statx(&self.fd, name, AtFlags::SYMLINK_NOFOLLOW, rfs::StatxFlags::BASIC_STATS).is_ok_and(|s| {
            s.stx_attributes_mask.contains(rfs::StatxAttributes::MOUNT_ROOT)
                && s.stx_attributes.contains(rfs::StatxAttributes::MOUNT_ROOT)
        })
    }

    /// The names in this directory (not `.` and `..`), sorted.
    pub fn names(&self) -> io::Result<Vec<OsString>> {
        let mut names = Vec::new();
        for e in rfs::Dir::read_from(&self.fd).map_err(err)? {
            let e = e.map_err(err)?;
            let n = e.file_name().to_bytes();
            if n != b"." && n != b".." {
                names.push(OsString::from_vec(n.to_vec()));
            }
        }
        names.sort();
        Ok(names)
    }

    /// Creates file `name` (it must not exist; a link of that name is not
    /// followed) with `bytes`, flushed to disk.
    pub fn create(&self, name: &OsStr, bytes: &[u8]) -> io::Result<()> {
        let flags = OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::NOFOLLOW | OFlags::CLOEXEC;
        let fd = rfs::openat(&self.fd, name, flags, Mode::from_raw_mode(0o644)).map_err(err)?;
        let mut file = std::fs::File::from(fd);
        io::Write::write_all(&mut file, bytes)?;
        file.sync_all()
    }

    /// Opens file `name` for reading, not following a link.
    pub fn read_file(&self, name: &OsStr) -> io::Result<std::fs::File> {
        let fd = rfs::openat(&self.fd, name, OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::CLOEXEC, Mode::empty())
            .map_err(err)?;
        Ok(std::fs::File::from(fd))
    }

    /// A second link `to/to_name` of the file `name` (not following a link).
    pub fn link(&self, name: &OsStr, to: &Dir, to_name: &OsStr) -> io::Result<()> {
        rfs::linkat(&self.fd, name, &to.fd, to_name, AtFlags::empty()).map_err(err)
    }

    /// The symbolic link `to/to_name` with the same text as link `name`.
    pub fn copy_symlink(&self, name: &OsStr, to: &Dir, to_name: &OsStr) -> io::Result<()> {
        let text = rfs::readlinkat(&self.fd, name, Vec::new()).map_err(err)?;
        rfs::symlinkat(text.as_c_str(), &to.fd, to_name).map_err(err)
    }

    /// Removes file (or link) `name`.
    pub fn unlink(&self, name: &OsStr) -> io::Result<()> {
        rfs::unlinkat(&self.fd, name, AtFlags::empty()).map_err(err)
    }

    /// Removes the empty directory `name`.
    pub fn rmdir(&self, name: &OsStr) -> io::Result<()> {
        rfs::unlinkat(&self.fd, name, AtFlags::REMOVEDIR).map_err(err)
    }

    /// Moves `name` to `to/to_name`; with `exchange`, the two trade places.
    pub fn rename(&self, name: &OsStr, to: &Dir, to_name: &OsStr, exchange: bool) -> io::Result<()> {
        let flags = if exchange { RenameFlags::EXCHANGE } else { RenameFlags::NOREPLACE };
        rfs::renameat_with(&self.fd, name, &to.fd, to_name, flags).map_err(err)
    }

    /// Moves `name` to `to/to_name`, replacing a file there.
    pub fn replace(&self, name: &OsStr, to: &Dir, to_name: &OsStr) -> io::Result<()> {
        rfs::renameat(&self.fd, name, &to.fd, to_name).map_err(err)
    }

    /// Removes `name` and, when it is a directory, everything in it; links
    /// are removed, never followed; an absent `name` is no error.
    pub fn remove_tree(&self, name: &OsStr) -> io::Result<()> {
        match self.stat(name)? {
            None => Ok(()),
            Some(st) if kind(&st) == FileType::Directory => {
                if let Some(sub) = self.open(name)? {
                    for n in sub.names()? {
                        sub.remove_tree(&n)?;
                    }
                }
                self.rmdir(name)
            }
            Some(_) => self.unlink(name),
        }
    }

    /// Flushes this directory's entries to disk.
    pub fn sync(&self) -> io::Result<()> {
        rfs::fsync(&self.fd).map_err(err)
    }

    /// Takes `flock` on this directory: exclusive, without waiting.
    /// `Ok(false)` when another open handle holds it.
    pub fn try_flock(&self) -> io::Result<bool> {
        match rfs::flock(&self.fd, rfs::FlockOperation::NonBlockingLockExclusive) {
            Ok(()) => Ok(true),
            Err(rustix::io::Errno::WOULDBLOCK) => Ok(false),
            Err(e) => Err(err(e)),
        }
    }

    /// Gives this directory the owner, group, mode and extended attributes
    /// of `like` (an ACL is an extended attribute). The owner first: a
    /// change of owner clears the set-id bits that the mode then restores.
    pub fn copy_meta(&self, like: &Dir) -> io::Result<()> {
        let (st, now) = (like.own()?, self.own()?);
        if (st.st_uid, st.st_gid) != (now.st_uid, now.st_gid) {
            let ids = (rfs::Uid::from_raw(st.st_uid), rfs::Gid::from_raw(st.st_gid));
            rfs::fchown(&self.fd, Some(ids.0), Some(ids.1)).map_err(err)?;
        }
        for name in xattr_names(&like.fd)? {
            let value = xattr(&like.fd, &name)?;
            rfs::fsetxattr(&self.fd, name.as_slice(), &value, rfs::XattrFlags::empty()).map_err(err)?;
        }
        rfs::fchmod(&self.fd, Mode::from_raw_mode(st.st_mode & 0o7777)).map_err(err)
    }

    /// The handle, for a child process's working directory.
    pub fn fd(&self) -> std::os::fd::BorrowedFd<'_> {
        self.fd.as_fd()
    }
}

/// The names of a file's extended attributes.
fn xattr_names(fd: &OwnedFd) -> io::Result<Vec<Vec<u8>>> {
    let mut buf = vec![0u8; 1024];
    loop {
        match rfs::flistxattr(fd, &mut buf[..]) {
            Ok(n) => return Ok(buf[..n].split(|&b| b == 0).filter(|s| !s.is_empty()).map(<[u8]>::to_vec).collect()),
            Err(rustix::io::Errno::RANGE) if buf.len() < 1 << 24 => buf.resize(buf.len() * 4, 0),
            Err(rustix::io::Errno::NOTSUP) => return Ok(Vec::new()),
            Err(e) => return Err(err(e)),
        }
    }
}

/// The value of a file's extended attribute `name`.
fn xattr(fd: &OwnedFd, name: &[u8]) -> io::Result<Vec<u8>> {
    let mut buf = vec![0u8; 256];
    loop {
        match rfs::fgetxattr(fd, name, &mut buf[..]) {
            Ok(n) => {
                buf.truncate(n);
                return Ok(buf);
            }
            Err(rustix::io::Errno::RANGE) if buf.len() < 1 << 24 => buf.resize(buf.len() * 4, 0),
            Err(e) => return Err(err(e)),
        }
    }
}

/// `name` as bytes, for comparisons with manifest entries.
pub fn bytes(name: &OsStr) -> &[u8] {
    name.as_bytes()
}
