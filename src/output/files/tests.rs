//! The transaction on a result directory: what a commit writes, keeps and
//! removes, what a failed one leaves (the old set, untouched), what a
//! killed one leaves once the next run recovers, and the lock.

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
    assert_eq!(listing(&root), vec![".plain-file.lock", "plain-file"]);
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
    assert!(listing(root.parent().unwrap()).iter().all(|n| !n.contains(".stage-")), "no staging directory is left");
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
    fs::create_dir_all(t.stage_path("1-1")).unwrap();
    fs::write(t.stage_path("1-1").join("s.vtu"), b"half").unwrap();
    // killed between the two renames of a two-step swap: the old set aside
    fs::rename(&dir, t.old_path("2-2")).unwrap();
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
