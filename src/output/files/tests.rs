//! The transaction on a result directory: what a commit writes, keeps and
//! removes, what a failed one leaves (the old set, untouched), what a
//! killed one leaves once the next run recovers, and the lock.

use std::fs;
use std::os::unix::fs::MetadataExt;

use super::*;

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("subcontact-files-{}-{tag}", std::process::id()));
    let _ = fs::remove_dir_all(&d);
    d
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

fn commit(dir: &Path, writer: &str, files: &[(&str, &[u8])]) -> Result<Vec<PathBuf>, OutputError> {
    let mut s = Staged::new(dir, writer);
    for (n, b) in files {
        s.add(n, b.to_vec());
    }
    s.commit()
}

#[test]
fn commit_writes_all_files_and_a_rerun_removes_only_its_own_old_ones() {
    let root = scratch("all");
    let dir = root.join("nested/results");
    let mut s = Staged::new(&dir, "a");
    s.add("a.vtu", b"first".to_vec());
    s.add("b.vtu", b"second".to_vec());
    s.add("series.pvd", b"third".to_vec());
    s.add("a.vtu", b"replaced".to_vec());
    let paths = s.commit().unwrap();
    assert_eq!(paths, vec![dir.join("a.vtu"), dir.join("b.vtu"), dir.join("series.pvd")]);
    assert_eq!(fs::read(dir.join("a.vtu")).unwrap(), b"replaced");
    assert_eq!(listing(&dir), vec![MANIFEST, "a.vtu", "b.vtu", "series.pvd"]);
    assert_eq!(Manifest::read(&dir).files("a"), ["a.vtu", "b.vtu", "series.pvd"]);

    // a user's file and another writer's files stay; writer a's old files go
    fs::write(dir.join("a_notes.vtu"), b"mine").unwrap();
    commit(&dir, "other", &[("other.vtu", b"o")]).unwrap();
    commit(&dir, "a", &[("b.vtu", b"new")]).unwrap();
    assert_eq!(fs::read(dir.join("b.vtu")).unwrap(), b"new");
    assert_eq!(listing(&dir), vec![MANIFEST, "a_notes.vtu", "b.vtu", "other.vtu"]);
    assert_eq!(fs::read(dir.join("a_notes.vtu")).unwrap(), b"mine");
    // nothing is left beside the directory but its lock
    assert_eq!(listing(dir.parent().unwrap()), vec![".results.lock", "results"]);
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn files_that_stay_are_the_same_files_subdirectories_and_links_included() {
    let root = scratch("same");
    let dir = root.join("out");
    fs::create_dir_all(dir.join("mesh")).unwrap();
    fs::write(dir.join("mesh/s.msh"), b"mesh").unwrap();
    fs::write(dir.join("photo.png"), b"png").unwrap();
    std::os::unix::fs::symlink("photo.png", dir.join("link.png")).unwrap();
    let ino = |p: &Path| fs::metadata(p).unwrap().ino();
    let (mesh, photo) = (ino(&dir.join("mesh/s.msh")), ino(&dir.join("photo.png")));
    commit(&dir, "s", &[("s.vtu", b"v"), ("photo2.png", b"p")]).unwrap();
    assert_eq!(ino(&dir.join("mesh/s.msh")), mesh);
    assert_eq!(ino(&dir.join("photo.png")), photo);
    assert_eq!(fs::read_link(dir.join("link.png")).unwrap(), Path::new("photo.png"));
    assert_eq!(listing(&dir), vec![MANIFEST, "link.png", "mesh", "photo.png", "photo2.png", "s.vtu"]);
    // a file of a name the run writes is replaced, whoever wrote it
    fs::write(dir.join("contact.csv"), b"user's").unwrap();
    commit(&dir, "s", &[("contact.csv", b"ours")]).unwrap();
    assert_eq!(fs::read(dir.join("contact.csv")).unwrap(), b"ours");
    assert_eq!(listing(&dir), vec![MANIFEST, "contact.csv", "link.png", "mesh", "photo.png"]);
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn amend_keeps_the_writers_other_files() {
    let root = scratch("amend");
    commit(&root, "s", &[("s.vtu", b"v"), ("report.md", b"r")]).unwrap();
    let mut s = Staged::amend(&root, "s");
    s.add("report.md", b"r + tables".to_vec());
    s.commit().unwrap();
    assert_eq!(listing(&root), vec![MANIFEST, "report.md", "s.vtu"]);
    assert_eq!(Manifest::read(&root).files("s"), ["s.vtu", "report.md"]);
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn impossible_directory_is_an_error_and_leaves_nothing() {
    let root = scratch("impossible");
    fs::create_dir_all(&root).unwrap();
    let file = root.join("plain-file");
    fs::write(&file, b"x").unwrap();
    for dir in [file.join("results"), file.clone()] {
        let err = commit(&dir, "s", &[("a.vtu", b"a")]).unwrap_err();
        assert!(err.to_string().contains(&file.display().to_string()), "{err}");
    }
    assert_eq!(fs::read(&file).unwrap(), b"x");
    assert_eq!(listing(&root), vec!["plain-file"]);
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_failed_commit_leaves_the_old_set_as_it_was() {
    let root = scratch("failed");
    commit(&root, "s", &[("a.vtu", b"old a"), ("b.vtu", b"old b")]).unwrap();
    let before = listing(&root);
    // a directory in the way of a result file
    fs::create_dir_all(root.join("c.vtu/keep")).unwrap();
    let err = commit(&root, "s", &[("a.vtu", b"a"), ("c.vtu", b"c")]).unwrap_err();
    assert!(matches!(err, OutputError::InTheWay { .. }), "{err:?}");
    assert!(err.to_string().contains(&root.join("c.vtu").display().to_string()), "{err}");
    fs::remove_dir_all(root.join("c.vtu")).unwrap();
    // a name too long for the file system, after the first file is written
    let long = "x".repeat(300);
    let err = commit(&root, "s", &[("a.vtu", b"a"), (&long, b"b")]).unwrap_err();
    assert!(matches!(err, OutputError::Write { .. }), "{err:?}");
    assert!(err.to_string().contains(&long), "{err}");
    assert_eq!(listing(&root), before);
    assert_eq!(fs::read(root.join("a.vtu")).unwrap(), b"old a");
    // (only this set's own: the temporary directory is shared with every other run)
    let own = format!(".{}.stage-", root.file_name().unwrap().to_string_lossy());
    assert!(listing(root.parent().unwrap()).iter().all(|n| !n.starts_with(&own)), "no staging directory is left");
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn names_must_be_plain() {
    let root = scratch("names");
    for bad in ["", ".", "..", "a/b.vtu", "../x.vtu", "a\\b", "nul\0", MANIFEST] {
        let err = commit(&root, "s", &[("good.vtu", b"g"), (bad, b"b")]).unwrap_err();
        assert!(matches!(err, OutputError::InvalidName { .. }), "{bad:?}: {err:?}");
        assert!(!root.exists(), "{bad:?}");
    }
}

#[test]
fn empty_commit_creates_the_directory() {
    let root = scratch("empty");
    assert!(Staged::new(&root, "s").commit().unwrap().is_empty());
    assert!(root.is_dir());
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn what_a_killed_commit_left_is_made_right_by_the_next() {
    let root = scratch("recover");
    let dir = root.join("out");
    commit(&dir, "s", &[("s.vtu", b"old")]).unwrap();
    let t = target::Target::resolve(&dir).unwrap();
    // killed while staging: a staging directory that never went in
    let stage = t.beside_path(&t.stage_name("1-1"));
    fs::create_dir_all(&stage).unwrap();
    fs::write(stage.join("s.vtu"), b"half").unwrap();
    // killed between the two renames of a two-step swap: the old set aside
    fs::rename(&dir, t.beside_path(&t.old_name("2-2"))).unwrap();
    commit(&root.join("elsewhere"), "s", &[]).unwrap();
    assert!(!dir.exists(), "another directory's commit leaves this one alone");
    commit(&dir, "s", &[("s.vtu", b"new")]).unwrap();
    assert_eq!(fs::read(dir.join("s.vtu")).unwrap(), b"new");
    assert_eq!(listing(&root), vec![".elsewhere.lock", ".out.lock", "elsewhere", "out"]);
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_second_commit_waits_for_the_lock_and_says_so() {
    let root = scratch("lock");
    let held = Lock::acquire(&root, &mut |_| panic!("nobody holds it")).unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    let dir = root.clone();
    let other = std::thread::spawn(move || {
        let mut said = Vec::new();
        let r = Staged::new(&dir, "s").commit_with(&mut |m| {
            said.push(m.to_string());
            let _ = tx.send(());
        });
        (r.map(|_| ()), said)
    });
    rx.recv().unwrap();
    assert!(!root.exists(), "the waiting commit writes nothing");
    drop(held);
    let (r, said) = other.join().unwrap();
    r.unwrap();
    assert_eq!(said.len(), 1);
    assert!(
        said[0].contains(&format!("(process {})", std::process::id())) && said[0].contains("waiting for another run"),
        "{said:?}"
    );
    assert!(root.join(MANIFEST).is_file());
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn error_is_send_sync() {
    fn f<T: Send + Sync + 'static + std::error::Error>() {}
    f::<OutputError>();
}

/// Killed while the old set was being emptied (issue 32): the old code
/// removed the old set's manifest first, and the next run put the old
/// scene's leftovers (a third load step of a 3-step run) back beside a
/// 2-step run's results, outside any manifest. The old manifest now goes
/// last, and recovery removes what it lists.
#[test]
fn a_kill_while_the_old_set_is_emptied_resurrects_nothing() {
    let root = scratch("resurrect");
    let dir = root.join("out");
    commit(&dir, "s", &[("s_step1.vtu", b"1"), ("s_step2.vtu", b"2"), ("s_step3.vtu", b"3")]).unwrap();
    fs::write(dir.join("notes.txt"), b"mine").unwrap();
    let t = target::Target::resolve(&dir).unwrap();
    // the state after the swap of a 2-step run "R", before the old set is emptied
    let old = Manifest::read(&dir);
    let new = old.after("R", "s", &["s_step1.vtu".into(), "s_step2.vtu".into()], false);
    let stage = t.beside_path(&t.stage_name("R"));
    fs::create_dir_all(&stage).unwrap();
    for f in ["s_step1.vtu", "s_step2.vtu"] {
        fs::write(stage.join(f), b"new").unwrap();
    }
    fs::hard_link(dir.join("notes.txt"), stage.join("notes.txt")).unwrap();
    fs::write(stage.join(MANIFEST), new.bytes()).unwrap();
    fs::rename(&dir, root.join("swapping")).unwrap();
    fs::rename(&stage, &dir).unwrap();
    fs::rename(root.join("swapping"), &stage).unwrap();
    // killed after the old set lost its first file
    fs::remove_file(stage.join("s_step1.vtu")).unwrap();
    commit(&dir, "other", &[("o.csv", b"o")]).unwrap();
    assert_eq!(listing(&dir), vec![MANIFEST, "notes.txt", "o.csv", "s_step1.vtu", "s_step2.vtu"]);
    assert_eq!(fs::read(dir.join("s_step2.vtu")).unwrap(), b"new");
    assert_eq!(listing(&root), vec![".out.lock", "out"]);
    fs::remove_dir_all(&root).unwrap();
}

/// The lock file was opened following links and truncated (issue 32): a
/// root-owned 0600 file was reduced to a pid through a link of its name.
#[test]
fn the_lock_follows_no_link_and_writes_nothing() {
    let root = scratch("lock-link");
    fs::create_dir_all(&root).unwrap();
    let victim = root.join("victim");
    fs::write(&victim, b"precious").unwrap();
    fs::set_permissions(&victim, std::os::unix::fs::PermissionsExt::from_mode(0o600)).unwrap();
    std::os::unix::fs::symlink(&victim, root.join(".out.lock")).unwrap();
    let err = commit(&root.join("out"), "s", &[("a.vtu", b"a")]).unwrap_err();
    assert!(err.to_string().contains("symbolic link") && err.to_string().contains(".out.lock"), "{err}");
    assert_eq!(fs::read(&victim).unwrap(), b"precious");
    assert!(!root.join("out").exists());
    // a lock file that is there already is used as it is, never truncated
    fs::remove_file(root.join(".out.lock")).unwrap();
    fs::write(root.join(".out.lock"), b"someone's text").unwrap();
    commit(&root.join("out"), "s", &[("a.vtu", b"a")]).unwrap();
    assert_eq!(fs::read(root.join(".out.lock")).unwrap(), b"someone's text");
    fs::remove_dir_all(&root).unwrap();
}

/// A link named `mesh` in the result directory was followed: the run
/// rewrote the mesh cache wherever it pointed (issue 32).
#[test]
fn a_link_where_the_mesh_cache_or_a_result_goes_is_refused() {
    let root = scratch("mesh-link");
    let elsewhere = root.join("elsewhere");
    fs::create_dir_all(&elsewhere).unwrap();
    fs::write(elsewhere.join("s.msh"), b"not yours").unwrap();
    let dir = root.join("out");
    commit(&dir, "s", &[("s.vtu", b"v")]).unwrap();
    std::os::unix::fs::symlink(&elsewhere, dir.join(MESH_DIR)).unwrap();
    let err = Stage::begin(&dir, &mut |_| {}).unwrap_err();
    assert!(matches!(err, OutputError::NotOurs { .. }), "{err:?}");
    assert!(err.to_string().contains("out/mesh") && err.to_string().contains("symbolic link"), "{err}");
    fs::remove_file(dir.join(MESH_DIR)).unwrap();
    fs::remove_file(dir.join("s.vtu")).unwrap();
    std::os::unix::fs::symlink(elsewhere.join("s.msh"), dir.join("s.vtu")).unwrap();
    let err = commit(&dir, "s", &[("s.vtu", b"v")]).unwrap_err();
    assert!(matches!(err, OutputError::NotOurs { .. }), "{err:?}");
    assert_eq!(fs::read(elsewhere.join("s.msh")).unwrap(), b"not yours");
    fs::remove_dir_all(&root).unwrap();
}

/// Every run re-created `--out` and its subdirectories: owner, group,
/// mode and attributes were lost (issue 32: run with sudo into a user's
/// 700 home, the user was locked out). They are kept now; as root, the
/// owner and group too.
#[test]
fn directories_keep_their_owner_mode_and_attributes() {
    let root = scratch("meta");
    let dir = root.join("out");
    fs::create_dir_all(dir.join("photos/old")).unwrap();
    fs::write(dir.join("photos/old/p.png"), b"p").unwrap();
    let set_xattr = |p: &Path| {
        let d = at::Dir::open_path(p).unwrap();
        rustix::fs::fsetxattr(d.fd(), "user.project", b"dam", rustix::fs::XattrFlags::empty()).is_ok()
    };
    let xattrs = set_xattr(&dir) && set_xattr(&dir.join("photos"));
    let root_user = rustix::process::geteuid().is_root();
    if root_user {
        std::os::unix::fs::chown(&dir, Some(65534), Some(65534)).unwrap();
        std::os::unix::fs::chown(dir.join("photos"), Some(65534), Some(100)).unwrap();
    }
    let mode = |p: &Path, m: u32| fs::set_permissions(p, std::os::unix::fs::PermissionsExt::from_mode(m)).unwrap();
    mode(&dir, 0o2750);
    mode(&dir.join("photos/old"), 0o555);
    let meta = |p: &Path| {
        let m = fs::metadata(p).unwrap();
        let x = at::Dir::open_path(p).ok().and_then(|d| {
            let mut b = [0u8; 16];
            rustix::fs::fgetxattr(d.fd(), "user.project", &mut b[..]).ok().map(|n| b[..n].to_vec())
        });
        (m.uid(), m.gid(), m.mode() & 0o7777, x)
    };
    let before: Vec<_> = ["", "photos", "photos/old"].iter().map(|s| meta(&dir.join(s))).collect();
    commit(&dir, "s", &[("s.vtu", b"v")]).unwrap();
    commit(&dir, "s", &[("s.vtu", b"w")]).unwrap();
    let after: Vec<_> = ["", "photos", "photos/old"].iter().map(|s| meta(&dir.join(s))).collect();
    assert_eq!(after, before, "xattrs tried: {xattrs}, as root: {root_user}");
    assert_eq!(fs::read(dir.join("photos/old/p.png")).unwrap(), b"p");
    // a read-only subdirectory leaves no staging directory behind
    assert_eq!(listing(&root), vec![".out.lock", "out"]);
    mode(&dir.join("photos/old"), 0o755);
    fs::remove_dir_all(&root).unwrap();
}
