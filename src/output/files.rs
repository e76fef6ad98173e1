//! Result files are written all together or not at all.
//!
//! [`Staged`] keeps a set of files in memory; [`Staged::commit`] writes each
//! one to a hidden temporary (`.<name>.tmp`, flushed to disk) in the target
//! directory and only then renames them all into place. If anything fails,
//! whatever this commit wrote — temporaries, files already renamed, and
//! directories it created — is removed again, so a failed run never leaves a
//! half-written or mismatched set of results. (A file of the same name that
//! existed before and was already replaced by this commit cannot come back.)
//!
//! [`OutputError`] is the error of the whole `output` module.

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
    #[error("invalid result file name {name:?} in {}: it must be a plain file name", dir.display())]
    InvalidName { dir: PathBuf, name: String },
    #[error(
        "{location} field `{field}` has {len} values, expected {} ({n_comp} per {location} × {count} {location}s)",
        *n_comp as u128 * *count as u128
    )]
    FieldLength {
        location: &'static str,
        field: String,
        n_comp: usize,
        count: usize,
        len: usize,
    },
    #[error("{location} field `{field}` has no components")]
    NoComponents {
        location: &'static str,
        field: String,
    },
    #[error("cell {index} (gmsh element {tag}, {kind}) has {actual} nodes, expected {expected}")]
    CellNodes {
        index: usize,
        tag: u64,
        kind: &'static str,
        expected: usize,
        actual: usize,
    },
    #[error("cell {index} (gmsh element {tag}) refers to node {node}, but there are only {n_points} points")]
    NodeOutOfRange {
        index: usize,
        tag: u64,
        node: usize,
        n_points: usize,
    },
    #[error("too many {what} for a VTU file: {count}")]
    TooLarge { what: &'static str, count: usize },
    #[error("cannot encode the VTU data: {0}")]
    Vtk(String),
}

/// A set of result files kept in memory until `commit`.
#[derive(Clone)]
pub struct Staged {
    dir: PathBuf,
    files: Vec<(String, Vec<u8>)>,
}

/// Names and sizes only: the contents may be large.
impl std::fmt::Debug for Staged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Staged")
            .field("dir", &self.dir)
            .field(
                "files",
                &self
                    .files
                    .iter()
                    .map(|(n, b)| (n, b.len()))
                    .collect::<Vec<_>>(),
            )
            .finish()
    }
}

/// A plain file name: not empty, not `.`/`..`, no separator, no NUL.
fn is_plain_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\', '\0'])
        && Path::new(name).file_name().and_then(|n| n.to_str()) == Some(name)
}

impl Staged {
    /// An empty set of files for `dir` (nothing is touched until `commit`).
    pub fn new(dir: &Path) -> Self {
        Staged {
            dir: dir.to_path_buf(),
            files: Vec::new(),
        }
    }

    /// Stages file `name` (a plain file name inside the directory). Adding a
    /// name again replaces its bytes and keeps its first position.
    pub fn add(&mut self, name: &str, bytes: Vec<u8>) {
        match self.files.iter_mut().find(|(n, _)| n == name) {
            Some((_, b)) => *b = bytes,
            None => self.files.push((name.to_string(), bytes)),
        }
    }

    /// Creates dir, writes each file as `.<name>.tmp` then renames all into place; on any error removes what this
    /// commit already wrote (temporaries and renamed files) and returns the error naming the path.
    ///
    /// Returns the paths of the files written, in the order they were added.
    pub fn commit(self) -> Result<Vec<PathBuf>, OutputError> {
        let Staged { dir, files } = self;
        if let Some((name, _)) = files.iter().find(|(n, _)| !is_plain_name(n)) {
            return Err(OutputError::InvalidName {
                dir,
                name: name.clone(),
            });
        }

        // The directories that do not exist yet, deepest first, to remove
        // again if the commit fails.
        let mut created: Vec<PathBuf> = Vec::new();
        let mut p = Some(dir.as_path());
        while let Some(d) = p {
            if d.as_os_str().is_empty() || fs::symlink_metadata(d).is_ok() {
                break;
            }
            created.push(d.to_path_buf());
            p = d.parent();
        }
        if let Err(source) = fs::create_dir_all(&dir) {
            remove_dirs(&created);
            return Err(OutputError::CreateDir { path: dir, source });
        }

        let mut temps: Vec<PathBuf> = Vec::with_capacity(files.len());
        let mut renamed: Vec<PathBuf> = Vec::with_capacity(files.len());
        let result = write_all(&dir, &files, &mut temps, &mut renamed);
        match result {
            Ok(()) => Ok(renamed),
            Err(e) => {
                for p in temps.iter().chain(&renamed) {
                    let _ = fs::remove_file(p);
                }
                remove_dirs(&created);
                Err(e)
            }
        }
    }
}

/// Removes the given directories, deepest first, if they are empty.
fn remove_dirs(dirs: &[PathBuf]) {
    for d in dirs {
        let _ = fs::remove_dir(d);
    }
}

/// Writes all temporaries, then renames them. `temps` holds the temporaries
/// that exist, `renamed` the files already in place.
fn write_all(
    dir: &Path,
    files: &[(String, Vec<u8>)],
    temps: &mut Vec<PathBuf>,
    renamed: &mut Vec<PathBuf>,
) -> Result<(), OutputError> {
    for (name, bytes) in files {
        let tmp = dir.join(format!(".{name}.tmp"));
        let mut f = fs::File::create(&tmp).map_err(|source| OutputError::Write {
            path: tmp.clone(),
            source,
        })?;
        temps.push(tmp.clone());
        f.write_all(bytes)
            .and_then(|()| f.sync_all())
            .map_err(|source| OutputError::Write { path: tmp, source })?;
    }
    // Rename in order; `temps` and `files` line up.
    let staged: Vec<PathBuf> = std::mem::take(temps);
    let mut pending = staged.into_iter();
    for (name, _) in files {
        let Some(tmp) = pending.next() else { break };
        let target = dir.join(name);
        if let Err(source) = fs::rename(&tmp, &target) {
            temps.push(tmp.clone());
            temps.extend(pending);
            return Err(OutputError::Rename {
                from: tmp,
                to: target,
                source,
            });
        }
        renamed.push(target);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("subcontact-files-{}-{tag}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        d
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn commit_writes_all_files() {
        let root = scratch("all");
        let dir = root.join("nested/results");
        let mut s = Staged::new(&dir);
        s.add("a.vtu", b"first".to_vec());
        s.add("b.vtu", b"second".to_vec());
        s.add("series.pvd", b"third".to_vec());
        s.add("a.vtu", b"replaced".to_vec());
        let paths = s.commit().unwrap();
        assert_eq!(
            paths,
            vec![dir.join("a.vtu"), dir.join("b.vtu"), dir.join("series.pvd")]
        );
        assert_eq!(fs::read(dir.join("a.vtu")).unwrap(), b"replaced");
        assert_eq!(fs::read(dir.join("b.vtu")).unwrap(), b"second");
        assert_eq!(fs::read(dir.join("series.pvd")).unwrap(), b"third");
        assert_eq!(listing(&dir), vec!["a.vtu", "b.vtu", "series.pvd"]);

        // A second commit overwrites.
        let mut s = Staged::new(&dir);
        s.add("b.vtu", b"new".to_vec());
        s.commit().unwrap();
        assert_eq!(fs::read(dir.join("b.vtu")).unwrap(), b"new");
        assert_eq!(listing(&dir), vec!["a.vtu", "b.vtu", "series.pvd"]);
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn impossible_directory_is_an_error_and_leaves_nothing() {
        let root = scratch("impossible");
        fs::create_dir_all(&root).unwrap();
        let file = root.join("plain-file");
        fs::write(&file, b"x").unwrap();
        let dir = file.join("results");
        let mut s = Staged::new(&dir);
        s.add("a.vtu", b"a".to_vec());
        s.add("b.vtu", b"b".to_vec());
        let err = s.commit().unwrap_err();
        assert!(matches!(err, OutputError::CreateDir { .. }), "{err:?}");
        assert!(
            err.to_string().contains(&dir.display().to_string()),
            "{err}"
        );
        assert_eq!(listing(&root), vec!["plain-file"]);
        assert_eq!(fs::read(&file).unwrap(), b"x");
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn failed_rename_removes_everything_this_commit_wrote() {
        let root = scratch("rename");
        // b.vtu is in the way as a non-empty directory: renaming onto it fails
        // after a.vtu is already in place.
        fs::create_dir_all(root.join("b.vtu/keep")).unwrap();
        let mut s = Staged::new(&root);
        s.add("a.vtu", b"a".to_vec());
        s.add("b.vtu", b"b".to_vec());
        s.add("c.vtu", b"c".to_vec());
        let err = s.commit().unwrap_err();
        assert!(matches!(err, OutputError::Rename { .. }), "{err:?}");
        assert!(
            err.to_string()
                .contains(&root.join("b.vtu").display().to_string()),
            "{err}"
        );
        assert_eq!(listing(&root), vec!["b.vtu"]);
        assert_eq!(listing(&root.join("b.vtu")), vec!["keep"]);
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn failed_write_removes_temporaries() {
        let root = scratch("write");
        fs::create_dir_all(root.join(".c.vtu.tmp")).unwrap();
        let mut s = Staged::new(&root);
        s.add("a.vtu", b"a".to_vec());
        s.add("b.vtu", b"b".to_vec());
        s.add("c.vtu", b"c".to_vec());
        let err = s.commit().unwrap_err();
        assert!(matches!(err, OutputError::Write { .. }), "{err:?}");
        assert!(err.to_string().contains(".c.vtu.tmp"), "{err}");
        assert_eq!(listing(&root), vec![".c.vtu.tmp"]);
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn failure_removes_the_directories_it_created() {
        let root = scratch("created");
        fs::create_dir_all(&root).unwrap();
        // The name is fine but its temporary name is too long for the file system.
        let long = "x".repeat(252);
        let mut s = Staged::new(&root.join("new/deeper"));
        s.add("a.vtu", b"a".to_vec());
        s.add(&long, b"b".to_vec());
        let err = s.commit().unwrap_err();
        assert!(err.to_string().contains(&long), "{err}");
        assert!(listing(&root).is_empty(), "{:?}", listing(&root));
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn names_must_be_plain() {
        let root = scratch("names");
        for bad in ["", ".", "..", "a/b.vtu", "../x.vtu", "a\\b", "nul\0"] {
            let mut s = Staged::new(&root);
            s.add("good.vtu", b"g".to_vec());
            s.add(bad, b"b".to_vec());
            let err = s.commit().unwrap_err();
            assert!(
                matches!(err, OutputError::InvalidName { .. }),
                "{bad:?}: {err:?}"
            );
            assert!(!root.exists(), "{bad:?}");
        }
    }

    #[test]
    fn empty_commit_creates_the_directory() {
        let root = scratch("empty");
        assert!(Staged::new(&root).commit().unwrap().is_empty());
        assert!(root.is_dir());
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn error_is_send_sync() {
        fn f<T: Send + Sync + 'static + std::error::Error>() {}
        f::<OutputError>();
    }
}
