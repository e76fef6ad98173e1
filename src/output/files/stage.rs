//! A run's staging directory, `<parent>/.<name>.stage-<run>`: made when the
//! run starts (under the directory's lock, briefly), then filled without
//! the lock: gmsh meshes into its `mesh/` (or the cached mesh of the
//! result directory is linked there, when its key matches), and at the end
//! [`Stage::commit`] adds the result files and the manifest, links what
//! stays of the old set, and swaps it in (see the module above). A run
//! holds a `flock` on its staging directory while it lives, so another
//! run's recovery tells it from one a killed run left; a stage that is
//! dropped without a commit is removed.
//!
//! Before the run does any work, [`Stage::begin`] checks that the result
//! directory can be kept as it is through the swap: no mount point inside
//! it, `mesh` a plain directory, and (for a user other than root) every
//! directory of the user's and every file linkable, since the new set
//! holds the same files under directories made anew with the old ones'
//! owner, group, mode and extended attributes.

use std::ffi::{OsStr, OsString};
use std::io::Read;
use std::path::{Path, PathBuf};

use rustix::fs::FileType;

use super::at::{kind, Dir};
use super::lock::Lock;
use super::manifest::{Manifest, MANIFEST};
use super::output_error::OutputError;
use super::target::Target;
use super::{swap, Staged};

/// The mesh cache's directory inside a result directory.
pub const MESH_DIR: &str = "mesh";

/// A run's staging directory, removed when dropped uncommitted.
#[derive(Debug)]
pub struct Stage {
    target: Target,
    run: String,
    name: OsString,
    dir: Dir,
    /// Files put into the stage before the commit (the mesh), relative.
    early: Vec<String>,
    /// Swapped in: nothing of it is removed when it is dropped.
    committed: bool,
}

impl Stage {
    /// Makes the staging directory of a run into `out`, after tidying
    /// what killed runs left and checking that `out` can be kept as it is.
    pub fn begin(out: &Path, waiting: &mut dyn FnMut(&str)) -> Result<Stage, OutputError> {
        let lock = Lock::on(Target::resolve(out)?, waiting)?;
        Stage::under(&lock)
    }

    /// The same, under a lock the caller holds.
    pub fn under(lock: &Lock) -> Result<Stage, OutputError> {
        let target = lock.target().try_clone()?;
        swap::recover(&target);
        if let Some(out) = open_out(&target)? {
            keepable(&out)?;
        }
        let run = format!(
            "{}-{}",
            std::process::id(),
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
        );
        let name = target.stage_name(&run);
        let path = target.beside_path(&name);
        let dir = target.parent.mkdir(&name, 0o777).map_err(|source| OutputError::CreateDir { path, source })?;
        let _ = dir.try_flock();
        Ok(Stage { target, run, name, dir, early: Vec::new(), committed: false })
    }

    /// Refuses, before the run does any work, a symbolic link or a
    /// directory where `writer` wrote a result file the last time (the
    /// manifest's names), which the commit would refuse only after the
    /// whole solve.
    pub fn refuse_in_the_way(&self, writer: &str) -> Result<(), OutputError> {
        let Some(out) = open_out(&self.target)? else { return Ok(()) };
        let manifest = Manifest::read_at(&out);
        refuse_at(&out, manifest.files(writer).iter().map(String::as_str).filter(|n| !n.contains('/')))
    }

    /// The result directory.
    pub fn out(&self) -> &Path {
        &self.target.path
    }

    /// The staging directory's `mesh/`, made on first use: gmsh's
    /// working directory.
    pub fn mesh_dir(&self) -> Result<Dir, OutputError> {
        let m = OsStr::new(MESH_DIR);
        let made = match self.dir.open(m) {
            Ok(Some(d)) => Ok(d),
            Ok(None) => self.dir.mkdir(m, 0o777),
            Err(e) => Err(e),
        };
        made.map_err(|source| OutputError::CreateDir { path: self.out().join(MESH_DIR), source })
    }

    /// Takes the cached mesh `file` of the result directory into the
    /// stage when its key file (`<file>.key`) holds `key`; whether it did.
    pub fn reuse_mesh(&mut self, file: &str, key: &str) -> bool {
        let key_file = format!("{file}.key");
        let Ok(Some(out)) = open_out(&self.target) else { return false };
        let Ok(Some(cache)) = out.open(OsStr::new(MESH_DIR)) else { return false };
        let mut text = String::new();
        let read = cache.read_file(OsStr::new(&key_file)).and_then(|mut f| f.read_to_string(&mut text));
        if read.is_err() || text != key {
            return false;
        }
        let Ok(mesh) = self.mesh_dir() else { return false };
        let mut files = vec![file.to_string(), key_file.clone()];
        // what the mesher kept beside the mesh (the joints' cut report)
        files.extend(MESH_COMPANIONS.iter().map(|c| format!("{file}{c}")).filter(|f| is_file(&cache, f)));
        let linked = files.iter().all(|f| cache.link(OsStr::new(f), &mesh, OsStr::new(f)).is_ok());
        // the key read is the key linked (a commit may have replaced it)
        let mut again = String::new();
        let same = mesh.read_file(OsStr::new(&key_file)).and_then(|mut f| f.read_to_string(&mut again)).is_ok()
            && again == key;
        if linked && same && is_file(&mesh, file) {
            self.early.extend(files.iter().map(|f| format!("{MESH_DIR}/{f}")));
            return true;
        }
        let _ = self.dir.remove_tree(OsStr::new(MESH_DIR));
        false
    }

    /// Records the mesh `file` gmsh wrote into [`Stage::mesh_dir`], with
    /// its key file, as this run's cache.
    pub fn keep_mesh(&mut self, file: &str, key: &str) -> Result<(), OutputError> {
        let key_file = format!("{file}.key");
        let mesh = self.mesh_dir()?;
        mesh.create(OsStr::new(&key_file), key.as_bytes())
            .map_err(|source| OutputError::Write { path: self.out().join(MESH_DIR).join(&key_file), source })?;
        self.early.extend([format!("{MESH_DIR}/{file}"), format!("{MESH_DIR}/{key_file}")]);
        let companions = MESH_COMPANIONS.iter().map(|c| format!("{file}{c}")).filter(|f| is_file(&mesh, f));
        self.early.extend(companions.map(|f| format!("{MESH_DIR}/{f}")).collect::<Vec<_>>());
        Ok(())
    }

    /// Reads a file of the stage (the mesh), by its path relative to it.
    pub fn read(&self, rel: &str) -> std::io::Result<Vec<u8>> {
        let (dir, file) = match rel.rsplit_once('/') {
            Some((d, f)) => (self.dir.open(OsStr::new(d))?.ok_or(std::io::ErrorKind::NotFound)?, f),
            None => (self.dir.open(OsStr::new("."))?.ok_or(std::io::ErrorKind::NotFound)?, rel),
        };
        let mut bytes = Vec::new();
        dir.read_file(OsStr::new(file))?.read_to_end(&mut bytes)?;
        Ok(bytes)
    }

    /// Where a file of the stage is, for another process to read it
    /// before the commit (MPI ranks).
    pub fn path_of(&self, rel: &str) -> PathBuf {
        self.target.beside_path(&self.name).join(rel)
    }

    /// Whether the stage holds anything yet (a mesh).
    pub fn has_files(&self) -> bool {
        !self.early.is_empty()
    }

    /// Locks the directory (`waiting` told when another run holds it) and
    /// commits `files` with the stage.
    pub fn commit(self, files: Staged, waiting: &mut dyn FnMut(&str)) -> Result<Vec<PathBuf>, OutputError> {
        let lock = Lock::on(self.target.try_clone()?, waiting)?;
        self.commit_locked(files, &lock)
    }

    /// Commits under a lock the caller holds on this directory. Returns the
    /// paths of the files written, in the order they were added; on any
    /// error the directory is as it was.
    pub fn commit_locked(mut self, files: Staged, lock: &Lock) -> Result<Vec<PathBuf>, OutputError> {
        files.check_names()?;
        let t = lock.target();
        swap::recover(t);
        let out = open_out(t)?;
        if let Some(out) = &out {
            in_the_way(out, &files, !self.early.is_empty())?;
        }
        let old = out.as_ref().map(Manifest::read_at).unwrap_or_default();
        let names: Vec<String> = files.names().chain(self.early.iter().cloned()).collect();
        let manifest = old.after(&self.run, &files.writer, &names, files.keep);
        let was: &[String] = if files.keep { &[] } else { old.files(&files.writer) };
        let replaced = |r: &Path| r == Path::new(MANIFEST) || names.iter().chain(was).any(|f| Path::new(f) == r);

        self.fill(&files, out.as_ref(), &replaced, &manifest)?;
        let old_set = swap::swap(t, &self.name, &self.run).map_err(|source| OutputError::Rename {
            from: t.beside_path(&self.name),
            to: t.path.clone(),
            source,
        })?;
        // committed: the rest only tidies
        let _ = t.parent.sync();
        self.committed = true;
        if let (Some(old_name), Ok(Some(now))) = (old_set, t.parent.open(&t.name)) {
            if let Ok(Some(old_dir)) = t.parent.open(&old_name) {
                swap::settle(&old_dir, &now, Path::new(""), &replaced);
                let _ = t.parent.rmdir(&old_name);
            }
        }
        Ok(files.names().map(|n| files.dir.join(n)).collect())
    }

    /// The new set in the stage: the files, the manifest, what stays of
    /// `out`, and `out`'s owner, mode and attributes.
    fn fill(
        &self,
        files: &Staged,
        out: Option<&Dir>,
        replaced: swap::Replaced,
        manifest: &Manifest,
    ) -> Result<(), OutputError> {
        let manifest = manifest.bytes();
        for (name, bytes) in files.files.iter().map(|(n, b)| (n.as_str(), b)).chain([(MANIFEST, &manifest)]) {
            self.dir
                .create(OsStr::new(name), bytes)
                .map_err(|source| OutputError::Write { path: files.dir.join(name), source })?;
        }
        if let Some(out) = out {
            swap::carry(out, &self.dir, Path::new(""), replaced)?;
            self.dir.copy_meta(out).map_err(|source| OutputError::Carry { from: out.path.clone(), source })?;
        }
        self.dir.sync().map_err(|source| OutputError::Write { path: self.target.beside_path(&self.name), source })
    }
}

impl Drop for Stage {
    fn drop(&mut self) {
        if !self.committed {
            let _ = self.target.parent.remove_tree(&self.name);
        }
    }
}

/// Files a mesher may keep beside the mesh `<file>`, as `<file><suffix>`:
/// cached, reused and committed with it.
const MESH_COMPANIONS: &[&str] = &[".cut.json"];

fn is_file(d: &Dir, name: &str) -> bool {
    d.stat(OsStr::new(name)).ok().flatten().is_some_and(|s| kind(&s) == FileType::RegularFile)
}

/// The result directory, opened, or `None` when it does not exist yet.
fn open_out(t: &Target) -> Result<Option<Dir>, OutputError> {
    t.parent.open(&t.name).map_err(|source| match source.raw_os_error() {
        Some(libc::ELOOP | libc::ENOTDIR) => OutputError::InvalidDir {
            path: t.path.clone(),
            why: "it is no longer a directory (a file or a symbolic link took its place)".into(),
        },
        _ => OutputError::CreateDir { path: t.path.clone(), source },
    })
}

/// A directory or a symbolic link where the commit writes a file, or a
/// `mesh` that is not a plain directory, refuses the commit.
fn in_the_way(out: &Dir, files: &Staged, mesh: bool) -> Result<(), OutputError> {
    refuse_at(out, files.files.iter().map(|(n, _)| n.as_str()))?;
    if mesh {
        mesh_is_plain(out)?;
    }
    Ok(())
}

/// A directory or a symbolic link at one of `names` in `out`.
fn refuse_at<'a>(out: &Dir, names: impl Iterator<Item = &'a str>) -> Result<(), OutputError> {
    for name in names {
        match out.stat(OsStr::new(name)) {
            Ok(Some(st)) if kind(&st) == FileType::Directory => {
                return Err(OutputError::InTheWay { path: out.path.join(name) })
            }
            Ok(Some(st)) if kind(&st) == FileType::Symlink => {
                return Err(OutputError::NotOurs { path: out.path.join(name), what: "a symbolic link" })
            }
            _ => {}
        }
    }
    Ok(())
}

fn mesh_is_plain(out: &Dir) -> Result<(), OutputError> {
    match out.stat(OsStr::new(MESH_DIR)) {
        Ok(Some(st)) if kind(&st) == FileType::Symlink => {
            Err(OutputError::NotOurs { path: out.path.join(MESH_DIR), what: "a symbolic link" })
        }
        Ok(Some(st)) if kind(&st) != FileType::Directory => {
            Err(OutputError::NotOurs { path: out.path.join(MESH_DIR), what: "not a directory" })
        }
        _ => Ok(()),
    }
}

/// Whether the result directory `out` can be kept as it is through a
/// swap: no mount point in it, `mesh` a plain directory, and, for a user
/// other than root, directories the user can give their owner and group
/// to, and files the user may link (see the module header).
fn keepable(out: &Dir) -> Result<(), OutputError> {
    mesh_is_plain(out)?;
    let euid = rustix::process::geteuid();
    let groups = if euid.is_root() {
        Vec::new()
    } else {
        let mut g: Vec<u32> = rustix::process::getgroups().unwrap_or_default().iter().map(|g| g.as_raw()).collect();
        g.push(rustix::process::getegid().as_raw());
        g
    };
    walk_keepable(out, euid.is_root(), euid.as_raw(), &groups, 0)
}

fn walk_keepable(dir: &Dir, root: bool, uid: u32, groups: &[u32], depth: usize) -> Result<(), OutputError> {
    let cannot = |path: PathBuf, why: String| Err(OutputError::CannotKeep { path, why });
    if !root {
        let st = dir.own().map_err(|source| OutputError::Carry { from: dir.path.clone(), source })?;
        if st.st_uid != uid || !groups.contains(&st.st_gid) {
            return cannot(
                dir.path.clone(),
                format!("the directory belongs to user {} and group {}, which a run by another user cannot give back to a directory made anew", st.st_uid, st.st_gid),
            );
        }
    }
    let names = dir.names().map_err(|source| OutputError::Carry { from: dir.path.clone(), source })?;
    for name in names {
        let Ok(Some(st)) = dir.stat(&name) else { continue };
        match kind(&st) {
            FileType::Directory => {
                if dir.is_mount_point(&name) {
                    return Err(OutputError::MountPoint { path: dir.path.join(&name) });
                }
                if depth < 64 {
                    if let Ok(Some(sub)) = dir.open(&name) {
                        walk_keepable(&sub, root, uid, groups, depth + 1)?;
                    }
                }
            }
            FileType::RegularFile
                if !root && st.st_uid != uid && st.st_mode & 0o006 != 0o006 && st.st_mode & 0o060 != 0o060 =>
            {
                return cannot(
                    dir.path.join(&name),
                    format!(
                        "the file belongs to user {}, and the system lets only its owner link it into the new set",
                        st.st_uid
                    ),
                );
            }
            _ => {}
        }
    }
    Ok(())
}
