//! Where a result directory really is: its parent (absolute, symbolic
//! links resolved, created if missing) and its name there, and the hidden
//! names beside it that a commit uses: `.<name>.lock`, the staging
//! directories `.<name>.stage-<run>` and, where the file system cannot swap
//! two directories in one step, `.<name>.old-<run>`.

use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};

use super::OutputError;

/// A result directory, resolved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Target {
    /// The directory's parent, absolute and canonical.
    pub parent: PathBuf,
    /// Its name in the parent.
    pub name: OsString,
    /// `parent/name`.
    pub path: PathBuf,
}

const STAGE: &str = ".stage-";
const OLD: &str = ".old-";

impl Target {
    /// Resolves `dir`: a symbolic link to a directory is followed (the
    /// results go where it points, the link stays), the parent is created
    /// when missing. `/` has no parent to stage in and is refused.
    pub fn resolve(dir: &Path) -> Result<Target, OutputError> {
        let invalid = |why: &str| OutputError::InvalidDir { path: dir.to_path_buf(), why: why.to_string() };
        let abs = std::path::absolute(dir).map_err(|e| invalid(&e.to_string()))?;
        // a directory that exists (or a link to one): its canonical path
        let real = match fs::canonicalize(&abs) {
            Ok(p) => p,
            Err(_) => {
                let (Some(parent), Some(name)) = (abs.parent(), abs.file_name()) else {
                    return Err(invalid("it has no parent directory to stage the results in"));
                };
                fs::create_dir_all(parent)
                    .map_err(|source| OutputError::CreateDir { path: parent.to_path_buf(), source })?;
                let parent = fs::canonicalize(parent)
                    .map_err(|source| OutputError::CreateDir { path: parent.to_path_buf(), source })?;
                parent.join(name)
            }
        };
        match (real.parent(), real.file_name()) {
            (Some(parent), Some(name)) => {
                Ok(Target { parent: parent.to_path_buf(), name: name.to_os_string(), path: real.clone() })
            }
            _ => Err(invalid("it has no parent directory to stage the results in")),
        }
    }

    fn beside(&self, what: &str) -> PathBuf {
        let mut n = OsString::from(".");
        n.push(&self.name);
        n.push(what);
        self.parent.join(n)
    }

    pub fn lock_path(&self) -> PathBuf {
        self.beside(".lock")
    }

    /// The staging directory of run `run`.
    pub fn stage_path(&self, run: &str) -> PathBuf {
        self.beside(&format!("{STAGE}{run}"))
    }

    /// Where the old directory waits during a two-step swap.
    pub fn old_path(&self, run: &str) -> PathBuf {
        self.beside(&format!("{OLD}{run}"))
    }

    /// Staging and old directories beside this one that some run left:
    /// (path, run, whether it is an `old` one).
    pub fn leftovers(&self) -> Vec<(PathBuf, String, bool)> {
        let Ok(entries) = fs::read_dir(&self.parent) else { return Vec::new() };
        let prefix = format!(".{}", self.name.to_string_lossy());
        let mut found: Vec<(PathBuf, String, bool)> = entries
            .flatten()
            .filter_map(|e| {
                let n = e.file_name().into_string().ok()?;
                let rest = n.strip_prefix(&prefix)?;
                let (run, old) = match (rest.strip_prefix(STAGE), rest.strip_prefix(OLD)) {
                    (Some(r), _) => (r, false),
                    (_, Some(r)) => (r, true),
                    _ => return None,
                };
                e.file_type().ok()?.is_dir().then(|| (e.path(), run.to_string(), old))
            })
            .collect();
        found.sort();
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_is_followed_and_a_missing_parent_made() {
        let root = std::env::temp_dir().join(format!("subcontact-target-{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        let t = Target::resolve(&root.join("a/b/out")).unwrap();
        assert!(root.join("a/b").is_dir());
        assert_eq!(t.name, "out");
        assert_eq!(t.lock_path(), fs::canonicalize(root.join("a/b")).unwrap().join(".out.lock"));
        fs::create_dir_all(root.join("real")).unwrap();
        std::os::unix::fs::symlink(root.join("real"), root.join("link")).unwrap();
        let t = Target::resolve(&root.join("link")).unwrap();
        assert_eq!(t.name, "real");
        assert!(Target::resolve(Path::new("/")).is_err());
        fs::create_dir_all(t.stage_path("1-2")).unwrap();
        fs::create_dir_all(t.old_path("3-4")).unwrap();
        fs::write(t.parent.join(".real.stage-file"), b"").unwrap();
        let left: Vec<(String, bool)> = t.leftovers().into_iter().map(|(_, r, o)| (r, o)).collect();
        assert_eq!(left, vec![("3-4".to_string(), true), ("1-2".to_string(), false)]);
        fs::remove_dir_all(&root).unwrap();
    }
}
