//! The gmsh CLI itself, through the wrapper the driver uses
//! ([`gmsh::run_in`], gmsh working in a directory it is handed): its
//! version, the file it writes and where, the `.geo` commands it refuses,
//! its time limit, its errors quoted; and the MSH fixtures that the
//! reader's and the pictures' unit tests read (tests/fixtures/msh/, made
//! by its `make.sh`)
//! against what the installed gmsh writes now. What needs no gmsh run (the
//! cache key, the checks of a job) is unit-tested in src/mesh/gmsh.rs.

mod common;

use std::os::fd::AsFd;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use common::Case;
use subcontact::mesh::gmsh::{self, gmsh_version, GmshError, GmshJob, DEFAULT_TIMEOUT};
use subcontact::mesh::msh::read_msh;
use subcontact::mesh::Mesh;

/// Two unit squares side by side sharing the edge x = 1.
const TWO_RECT_GEO: &str = include_str!("fixtures/msh/two_rect.geo");

/// A first-order 2D job of `geo` into the case's `msh`.
fn job_in(case: &Case, geo: &Path, msh: &str) -> GmshJob {
    GmshJob {
        geo: geo.to_path_buf(),
        msh: case.dir.join(msh),
        dim: 2,
        order: 1,
        setnumber: Vec::new(),
        clscale: None,
        timeout: DEFAULT_TIMEOUT,
        allow_commands: false,
        cut: None,
    }
}

/// Meshes `job` into the directory of `job.msh`, as the driver does.
fn mesh(job: &GmshJob) -> Result<(), GmshError> {
    let parent = job.msh.parent().expect("the mesh's directory");
    let dir = std::fs::File::open(parent).expect("open the mesh's directory");
    gmsh::run_in(job, dir.as_fd())
}

/// The mesh of `dir/name`, or the reader's message with `dir` left out.
fn read_in(dir: &Path, name: &str) -> Result<Mesh, String> {
    read_msh(&dir.join(name)).map_err(|e| e.to_string().replace(&dir.display().to_string(), "DIR"))
}

fn dir_entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

#[test]
fn version_is_reported() {
    let v = gmsh_version().unwrap();
    assert!(v.starts_with('4'), "{v}");
    assert!(v.split('.').count() >= 2, "{v}");
}

/// gmsh writes the file of the job's name into the directory it is given,
/// as binary MSH 4.1, and a finer `lc` gives more nodes.
#[test]
fn gmsh_writes_into_its_directory_and_a_finer_lc_gives_more_nodes() {
    let case = Case::new("gmsh-cli-lc");
    let geo = case.write("two.geo", TWO_RECT_GEO);
    std::fs::create_dir_all(case.dir.join("out")).unwrap();
    let mut job = job_in(&case, &geo, "out/two.msh");
    job.setnumber = vec![("lc".into(), 0.25)];
    mesh(&job).unwrap();
    let fine = read_msh(&job.msh).unwrap();
    assert!(std::fs::read(&job.msh).unwrap().starts_with(b"$MeshFormat\n4.1 1 8\n"), "binary MSH 4.1 expected");
    job.setnumber = vec![("lc".into(), 0.5)];
    mesh(&job).unwrap();
    let coarse = read_msh(&job.msh).unwrap();
    assert!(fine.coords.len() > coarse.coords.len());
}

#[test]
fn commands_that_reach_outside_the_mesh_are_refused_unless_allowed() {
    let case = Case::new("gmsh-cli-commands");
    let text = format!("{TWO_RECT_GEO}\nSystemCall \"touch {}\";\n", case.dir.join("touched").display());
    let geo = case.write("two.geo", &text);
    let mut job = job_in(&case, &geo, "two.msh");
    let msg = mesh(&job).unwrap_err().to_string();
    assert!(msg.contains("SystemCall (line 15)") && msg.contains("--allow-geo-commands"), "{msg}");
    assert!(!case.dir.join("touched").exists() && !job.msh.exists());
    job.allow_commands = true;
    mesh(&job).unwrap();
    assert!(case.dir.join("touched").exists());
}

/// A .geo that never finishes ended only when killed (issue 32).
#[test]
fn gmsh_is_stopped_at_its_time_limit_with_what_it_started() {
    let case = Case::new("gmsh-cli-timeout");
    let geo = case.write("slow.geo", &format!("{TWO_RECT_GEO}\nSleep 30;\n"));
    let mut job = job_in(&case, &geo, "slow.msh");
    job.timeout = Duration::from_millis(700);
    let t = Instant::now();
    let e = mesh(&job).unwrap_err();
    let took = t.elapsed().as_secs_f64();
    assert!(matches!(e, GmshError::Timeout { .. }), "{e:?}");
    assert!(e.to_string().contains("within 0.7 s ([gmsh] timeout)"), "{e}");
    assert!((0.6..5.0).contains(&took), "stopped after {took} s");
    assert!(!job.msh.exists());
}

#[test]
fn gmsh_errors_are_quoted_and_leave_no_mesh() {
    let case = Case::new("gmsh-cli-bad");
    // A syntax error: gmsh 4.8.4 still writes a mesh (of what it read) and exits 1.
    let geo = case.write("syntax.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2;\n");
    let job = job_in(&case, &geo, "syntax.msh");
    let e = mesh(&job).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, GmshError::Failed { .. }), "{e:?}");
    assert!(msg.contains("syntax.geo") && msg.contains("syntax error"), "{msg}");
    assert!(!job.msh.exists());

    // A reference to a missing point: many repeated error lines, deduplicated.
    let geo = case.write("badline.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2};\nPhysical Curve(1) = {1};\n");
    let job = job_in(&case, &geo, "badline.msh");
    let msg = mesh(&job).unwrap_err().to_string();
    assert!(msg.contains("Unknown control point 2"), "{msg}");
    assert_eq!(msg.matches("Line with less than 2 control points").count(), 1, "{msg}");
    assert!(!msg.contains("error summary"), "{msg}");
    assert!(!job.msh.exists());

    let mut names = dir_entries(&case.dir);
    names.retain(|n| n.contains("tmp"));
    assert!(names.is_empty(), "temporary files left: {names:?}");
}

/// The fixtures of the reader's and the pictures' unit tests are what this
/// gmsh writes from their `.geo` files: `make.sh` run into a scratch
/// directory gives, file by file, the same mesh (or the same refusal) as
/// the committed file.
#[test]
fn the_msh_fixtures_are_what_gmsh_writes() {
    let case = Case::new("gmsh-cli-fixtures");
    let fixtures = common::repo_root().join("tests/fixtures/msh");
    let out = Command::new("sh").arg("make.sh").arg(&case.dir).current_dir(&fixtures).output().expect("run sh");
    assert!(out.status.success(), "make.sh: {}", String::from_utf8_lossy(&out.stderr));
    let names: Vec<String> = dir_entries(&fixtures).into_iter().filter(|n| n.ends_with(".msh")).collect();
    assert_eq!(names, dir_entries(&case.dir).into_iter().filter(|n| n.ends_with(".msh")).collect::<Vec<_>>());
    assert_eq!(names.len(), 50, "{names:?}");
    for name in &names {
        let committed = read_in(&fixtures, name);
        let fresh = read_in(&case.dir, name);
        assert_eq!(committed, fresh, "{name}");
    }
}
