//! Where a result directory really is: its parent (absolute, symbolic
//! links resolved, created if missing), opened once as a directory handle
//! that every later step works through, and its name there; and the
//! hidden names beside it that a commit uses: `.<name>.lock`, the staging
//! directories `.<name>.stage-<run>` and, where the file system cannot swap
//! two directories in one step, `.<name>.old-<run>`.

use std::ffi::{OsStr, OsString};
use std::fs;
use std::path::{Path, PathBuf};

use super::at::Dir;
use super::output_error::OutputError;

/// A result directory, resolved, with its parent open.
#[derive(Debug)]
pub struct Target {
    /// The directory's parent, opened (its path absolute and canonical).
    pub parent: Dir,
    /// Its name in the parent.
    pub name: OsString,
    /// `parent/name`, for messages.
    pub path: PathBuf,
}

const STAGE: &str = ".stage-";
const OLD: &str = ".old-";

impl Target {
    /// Resolves `dir`: a symbolic link to a directory is followed (the
    /// results go where it points, the link stays), the parent is created
    /// when missing and must be writable (the new set is built there).
    /// `/`, a file, and a link to nothing are refused.
    pub fn resolve(dir: &Path) -> Result<Target, OutputError> {
        let invalid = |why: String| OutputError::InvalidDir { path: dir.to_path_buf(), why };
        let abs = std::path::absolute(dir).map_err(|e| invalid(e.to_string()))?;
        let real = match fs::canonicalize(&abs) {
            Ok(p) if p.is_dir() => p,
            Ok(_) => return Err(invalid("it is a file, not a directory".into())),
            Err(_) => {
                if let Ok(to) = fs::read_link(&abs) {
                    return Err(invalid(format!(
                        "it is a symbolic link to {}, which does not exist: create that directory or remove the link",
                        to.display()
                    )));
                }
                let (Some(parent), Some(name)) = (abs.parent(), abs.file_name()) else {
                    return Err(invalid("it has no parent directory to stage the results in".into()));
                };
                fs::create_dir_all(parent)
                    .map_err(|source| OutputError::CreateDir { path: parent.to_path_buf(), source })?;
                let parent = fs::canonicalize(parent)
                    .map_err(|source| OutputError::CreateDir { path: parent.to_path_buf(), source })?;
                parent.join(name)
            }
        };
        let (Some(parent), Some(name)) = (real.parent(), real.file_name()) else {
            return Err(invalid("it has no parent directory to stage the results in".into()));
        };
        let opened = Dir::open_path(parent).map_err(|source| OutputError::CreateDir { path: parent.into(), source })?;
        if let Err(e) =
            rustix::fs::accessat(opened.fd(), ".", rustix::fs::Access::WRITE_OK, rustix::fs::AtFlags::EACCESS)
        {
            return Err(invalid(format!(
                "its parent {} is not writable ({e}): a run builds its new set of results beside the directory and swaps it in, in one step, so that a run stopped at any instant leaves the old set or the new one. Make {} writable, or give an --out inside a directory you can write",
                parent.display(),
                parent.display()
            )));
        }
        Ok(Target { parent: opened, name: name.to_os_string(), path: real.clone() })
    }

    /// A second handle on the same parent.
    pub fn try_clone(&self) -> Result<Target, OutputError> {
        let parent = self
            .parent
            .try_clone()
            .map_err(|source| OutputError::CreateDir { path: self.parent.path.clone(), source })?;
        Ok(Target { parent, name: self.name.clone(), path: self.path.clone() })
    }

    fn beside(&self, what: &str) -> OsString {
        let mut n = OsString::from(".");
        n.push(&self.name);
        n.push(what);
        n
    }

    /// The lock's name in the parent.
    pub fn lock_name(&self) -> OsString {
        self.beside(".lock")
    }

    /// The name in the parent of run `run`'s staging directory.
    pub fn stage_name(&self, run: &str) -> OsString {
        self.beside(&format!("{STAGE}{run}"))
    }

    /// Where the old directory waits during a two-step swap.
    pub fn old_name(&self, run: &str) -> OsString {
        self.beside(&format!("{OLD}{run}"))
    }

    /// A name in the parent as a path, for messages.
    pub fn beside_path(&self, name: &OsStr) -> PathBuf {
        self.parent.path.join(name)
    }

    /// Staging and old directories beside this one that some run left:
    /// (name in the parent, run, whether it is an `old` one).
    pub fn leftovers(&self) -> Vec<(OsString, String, bool)> {
        let Ok(names) = self.parent.names() else { return Vec::new() };
        let prefix = format!(".{}", self.name.to_string_lossy());
        names
            .into_iter()
            .filter_map(|n| {
                let s = n.to_str()?;
                let rest = s.strip_prefix(&prefix)?;
                let (run, old) = match (rest.strip_prefix(STAGE), rest.strip_prefix(OLD)) {
                    (Some(r), _) => (r.to_string(), false),
                    (_, Some(r)) => (r.to_string(), true),
                    _ => return None,
                };
                let st = self.parent.stat(&n).ok()??;
                (super::at::kind(&st) == rustix::fs::FileType::Directory).then_some((n, run, old))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_is_followed_a_missing_parent_made_and_a_dangling_link_refused() {
        let root = std::env::temp_dir().join(format!("subcontact-target-{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        let t = Target::resolve(&root.join("a/b/out")).unwrap();
        assert!(root.join("a/b").is_dir());
        assert_eq!(t.name, "out");
        assert_eq!(t.beside_path(&t.lock_name()), fs::canonicalize(root.join("a/b")).unwrap().join(".out.lock"));
        fs::create_dir_all(root.join("real")).unwrap();
        std::os::unix::fs::symlink(root.join("real"), root.join("link")).unwrap();
        let t = Target::resolve(&root.join("link")).unwrap();
        assert_eq!(t.name, "real");
        assert!(Target::resolve(Path::new("/")).is_err());
        std::os::unix::fs::symlink(root.join("nowhere"), root.join("dangling")).unwrap();
        let e = Target::resolve(&root.join("dangling")).unwrap_err().to_string();
        assert!(e.contains("symbolic link") && e.contains("nowhere") && e.contains("does not exist"), "{e}");
        fs::create_dir_all(t.beside_path(&t.stage_name("1-2"))).unwrap();
        fs::create_dir_all(t.beside_path(&t.old_name("3-4"))).unwrap();
        fs::write(t.parent.path.join(".real.stage-file"), b"").unwrap();
        let left: Vec<(String, bool)> = t.leftovers().into_iter().map(|(_, r, o)| (r, o)).collect();
        assert_eq!(left, vec![("3-4".to_string(), true), ("1-2".to_string(), false)]);
        fs::remove_dir_all(&root).unwrap();
    }
}
