//! Running the gmsh CLI to turn a `.geo` into an MSH 4.1 mesh, with a cache.
//!
//! [`mesh`] runs
//! `gmsh <geo> -<dim> -order <order> [-setnumber k v]... [-clscale s] -format msh41 -bin -o <tmp>`
//! and renames `<tmp>` to the wanted `.msh`, so a failed or interrupted gmsh never
//! leaves a `.msh` behind. Next to the mesh, `<msh>.key` holds a hash (64-bit
//! FNV-1a) of the `.geo` bytes and of every argument; while the `.msh` exists and
//! its key matches, gmsh is not run again. Files that the `.geo` pulls in with
//! `Include` or `Merge` are not part of the key.
//!
//! gmsh's output is captured, never shown. gmsh 4.8.4 may write a mesh and exit
//! 0 after reporting errors, so any `Error` line counts as a failure. Parameters
//! reach the `.geo` through `-setnumber NAME VALUE`, which overrides
//! `DefineConstant[ NAME = {default, Name "..."} ];` (it also sets gmsh options
//! such as `Mesh.SecondOrderIncomplete`).

use std::io;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Why a mesh could not be made.
#[derive(Debug, thiserror::Error)]
pub enum GmshError {
    #[error("geometry file `{}` does not exist: check the scene's path to the .geo", geo.display())]
    GeoMissing { geo: PathBuf },

    #[error("the gmsh CLI was not found: install it with `apt-get install -y gmsh` (or `make deps`)")]
    NotInstalled,

    #[error("cannot run gmsh: {source}")]
    Spawn {
        #[source]
        source: io::Error,
    },

    #[error("gmsh failed on `{}` ({status}):\n{errors}\nfix the .geo (open it in the gmsh GUI to see the problem)", geo.display())]
    Failed { geo: PathBuf, status: String, errors: String },

    #[error("gmsh wrote no mesh for `{}` although it reported no error:\n{output}", geo.display())]
    NoOutput { geo: PathBuf, output: String },

    #[error("invalid gmsh job for `{}`: {detail}", geo.display())]
    BadJob { geo: PathBuf, detail: String },

    #[error("{what} `{}`: {source}", path.display())]
    Io {
        what: &'static str,
        path: PathBuf,
        #[source]
        source: io::Error,
    },

    #[error("`gmsh --version` printed no version (output: {output:?})")]
    Version { output: String },
}

/// What to mesh and how.
#[derive(Clone, Debug, PartialEq)]
pub struct GmshJob {
    /// The gmsh geometry script.
    pub geo: PathBuf,
    /// Where the mesh goes (its directory is created); `<msh>.key` goes beside it.
    pub msh: PathBuf,
    /// 2 or 3.
    pub dim: usize,
    /// 1 or 2.
    pub order: usize,
    /// `-setnumber NAME VALUE` for each pair, in order.
    pub setnumber: Vec<(String, f64)>,
    /// `-clscale s`: global factor on mesh sizes.
    pub clscale: Option<f64>,
}

/// Whether [`mesh`] ran gmsh or found an up-to-date mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Meshed {
    Generated,
    Cached,
}

/// Runs `gmsh <geo> -<dim> -order <order> [-setnumber k v]... [-clscale s] -format msh41 -bin -o <msh>` unless <msh> exists
/// and its key file (<msh>.key: a hash of the .geo bytes and of every argument) matches, writing to a temporary
/// file first and renaming, so a failed or interrupted gmsh never leaves a .msh behind. Creates the parent directory.
pub fn mesh(job: &GmshJob) -> Result<Meshed, GmshError> {
    mesh_with(job, true)
}

/// The installed gmsh's version, e.g. `4.8.4`.
pub fn gmsh_version() -> Result<String, GmshError> {
    let out = Command::new("gmsh").arg("--version").stdin(Stdio::null()).output().map_err(spawn_error)?;
    // gmsh 4.8.4 prints its version on stderr.
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let version = text
        .split_whitespace()
        .find(|w| w.chars().next().is_some_and(|c| c.is_ascii_digit()) && w.contains('.'))
        .map(str::to_string);
    match version {
        Some(v) if out.status.success() => Ok(v),
        _ => Err(GmshError::Version { output: text.trim().to_string() }),
    }
}

fn spawn_error(e: io::Error) -> GmshError {
    if e.kind() == io::ErrorKind::NotFound {
        GmshError::NotInstalled
    } else {
        GmshError::Spawn { source: e }
    }
}

/// The arguments after `gmsh`, for output file `out`.
fn gmsh_args(job: &GmshJob, binary: bool, out: &Path) -> Vec<std::ffi::OsString> {
    let mut args: Vec<std::ffi::OsString> =
        vec![job.geo.clone().into(), format!("-{}", job.dim).into(), "-order".into(), job.order.to_string().into()];
    for (name, value) in &job.setnumber {
        args.push("-setnumber".into());
        args.push(name.into());
        args.push(value.to_string().into());
    }
    if let Some(s) = job.clscale {
        args.push("-clscale".into());
        args.push(s.to_string().into());
    }
    args.push("-format".into());
    args.push("msh41".into());
    if binary {
        args.push("-bin".into());
    }
    args.push("-o".into());
    args.push(out.into());
    args
}

fn check_job(job: &GmshJob) -> Result<(), GmshError> {
    let bad = |detail: String| Err(GmshError::BadJob { geo: job.geo.clone(), detail });
    if !(job.dim == 2 || job.dim == 3) {
        return bad(format!("dimension {} (must be 2 or 3)", job.dim));
    }
    if !(job.order == 1 || job.order == 2) {
        return bad(format!("order {} (must be 1 or 2)", job.order));
    }
    for (name, value) in &job.setnumber {
        if name.is_empty() || name.starts_with('-') || name.chars().any(char::is_whitespace) {
            return bad(format!("parameter name {name:?} (must be a gmsh name such as `lc`)"));
        }
        if !value.is_finite() {
            return bad(format!("parameter `{name}` = {value} (must be a finite number)"));
        }
    }
    if let Some(s) = job.clscale {
        if !(s.is_finite() && s > 0.0) {
            return bad(format!("clscale {s} (must be a positive number)"));
        }
    }
    if job.msh.file_name().is_none() {
        return bad(format!("mesh path `{}` has no file name", job.msh.display()));
    }
    Ok(())
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    /// Length-prefixed, so that consecutive fields cannot run into each other.
    fn field(&mut self, b: &[u8]) {
        self.bytes(&(b.len() as u64).to_le_bytes());
        self.bytes(b);
    }
}

/// The key file's content: hash, then the command for people reading it.
fn job_key(geo_bytes: &[u8], args: &[std::ffi::OsString]) -> String {
    let mut h = Fnv::new();
    h.field(b"subcontact gmsh key 1");
    h.field(geo_bytes);
    for a in args {
        h.field(a.as_encoded_bytes());
    }
    let cmd: Vec<String> = args.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    format!("{:016x}\ngmsh {}\n", h.0, cmd.join(" "))
}

fn key_path(msh: &Path) -> PathBuf {
    let mut s = msh.as_os_str().to_owned();
    s.push(".key");
    PathBuf::from(s)
}

/// A fresh name beside `msh` for gmsh to write into.
fn temp_path(msh: &Path, what: &str) -> PathBuf {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let nanos =
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.subsec_nanos()).unwrap_or(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = msh.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let file = format!(".{name}.{}-{n}-{nanos}.tmp.{what}", std::process::id());
    msh.with_file_name(file)
}

/// gmsh's error lines (consecutive repeats and the summary box dropped), at most 15.
fn error_lines(output: &str) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for line in output.lines() {
        let Some(rest) = line.strip_prefix("Error") else {
            continue;
        };
        let msg = rest.trim_start().trim_start_matches(':').trim();
        let count_line = msg.split_once(' ').is_some_and(|(n, what)| {
            n.chars().all(|c| c.is_ascii_digit()) && matches!(what, "warning" | "warnings" | "error" | "errors")
        });
        let boxed = msg.is_empty()
            || msg.starts_with("---")
            || msg == "Mesh generation error summary"
            || msg == "Check the full log for details"
            || count_line;
        if boxed || lines.iter().any(|l| l == msg) {
            continue;
        }
        lines.push(msg.to_string());
    }
    lines.truncate(15);
    lines
}

/// The last `n` lines of `output`, for failures without `Error` lines.
fn tail(output: &str, n: usize) -> String {
    let lines: Vec<&str> = output.lines().filter(|l| !l.trim().is_empty()).collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// [`mesh`], with a choice of binary or ASCII output (the tests use both).
pub(crate) fn mesh_with(job: &GmshJob, binary: bool) -> Result<Meshed, GmshError> {
    mesh_impl(job, binary, "gmsh")
}

fn mesh_impl(job: &GmshJob, binary: bool, program: &str) -> Result<Meshed, GmshError> {
    check_job(job)?;
    let geo_bytes = match std::fs::read(&job.geo) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Err(GmshError::GeoMissing { geo: job.geo.clone() }),
        Err(e) => return Err(GmshError::Io { what: "cannot read", path: job.geo.clone(), source: e }),
    };
    let key = job_key(&geo_bytes, &gmsh_args(job, binary, &job.msh));
    let key_file = key_path(&job.msh);
    if job.msh.is_file() && std::fs::read_to_string(&key_file).is_ok_and(|k| k == key) {
        return Ok(Meshed::Cached);
    }

    if let Some(dir) = job.msh.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| GmshError::Io {
            what: "cannot create directory",
            path: dir.to_path_buf(),
            source: e,
        })?;
    }
    // The old key and mesh go first: whatever happens next, no .msh is left
    // that does not match the .geo and arguments.
    for old in [&key_file, &job.msh] {
        match std::fs::remove_file(old) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => {
                return Err(GmshError::Io { what: "cannot remove", path: old.clone(), source: e })
            }
            _ => {}
        }
    }

    let tmp = temp_path(&job.msh, "msh");
    let result = run_gmsh(job, binary, &tmp, program);
    let result = result.and_then(|()| {
        std::fs::rename(&tmp, &job.msh).map_err(|e| GmshError::Io {
            what: "cannot rename the new mesh to",
            path: job.msh.clone(),
            source: e,
        })
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result?;

    let tmp_key = temp_path(&job.msh, "key");
    let written = std::fs::write(&tmp_key, &key).and_then(|()| std::fs::rename(&tmp_key, &key_file));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp_key);
        return Err(GmshError::Io { what: "cannot write", path: key_file, source: e });
    }
    Ok(Meshed::Generated)
}

/// Runs gmsh writing to `out`; Ok only if gmsh succeeded, reported no error and wrote `out`.
fn run_gmsh(job: &GmshJob, binary: bool, out: &Path, program: &str) -> Result<(), GmshError> {
    let output =
        Command::new(program).args(gmsh_args(job, binary, out)).stdin(Stdio::null()).output().map_err(spawn_error)?;
    let text = format!("{}\n{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    let errors = error_lines(&text);
    if !output.status.success() || !errors.is_empty() {
        let status = match output.status.code() {
            Some(c) => format!("exit status {c}"),
            None => "killed by a signal".to_string(),
        };
        let errors = if errors.is_empty() { tail(&text, 10) } else { errors.join("\n") };
        let errors = errors.lines().map(|l| format!("  {l}")).collect::<Vec<_>>().join("\n");
        return Err(GmshError::Failed { geo: job.geo.clone(), status, errors });
    }
    if !out.is_file() {
        return Err(GmshError::NoOutput { geo: job.geo.clone(), output: tail(&text, 10) });
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A fresh directory under the system temp dir, removed when the test passes.
    pub(crate) struct TestDir(pub PathBuf);

    impl TestDir {
        pub(crate) fn new(name: &str) -> Self {
            use std::sync::atomic::{AtomicU64, Ordering};
            static N: AtomicU64 = AtomicU64::new(0);
            let nanos =
                std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos()).unwrap_or(0);
            let dir = std::env::temp_dir().join(format!(
                "subcontact-mesh-test-{name}-{}-{}-{nanos}",
                std::process::id(),
                N.fetch_add(1, Ordering::Relaxed)
            ));
            std::fs::create_dir_all(&dir).unwrap();
            TestDir(dir)
        }

        pub(crate) fn write(&self, name: &str, text: &str) -> PathBuf {
            let p = self.0.join(name);
            std::fs::write(&p, text).unwrap();
            p
        }

        pub(crate) fn job(&self, geo: &Path, msh: &str, dim: usize, order: usize) -> GmshJob {
            GmshJob { geo: geo.to_path_buf(), msh: self.0.join(msh), dim, order, setnumber: Vec::new(), clscale: None }
        }
    }

    impl Drop for TestDir {
        fn drop(&mut self) {
            if !std::thread::panicking() {
                let _ = std::fs::remove_dir_all(&self.0);
            }
        }
    }

    /// Two unit squares side by side sharing the edge x = 1.
    pub(crate) const TWO_RECT_GEO: &str = r#"
DefineConstant[ lc = {0.5, Name "lc"} ];
Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc}; Point(3) = {2, 0, 0, lc};
Point(4) = {2, 1, 0, lc}; Point(5) = {1, 1, 0, lc}; Point(6) = {0, 1, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Physical Surface("left") = {1};
Physical Surface("right") = {2};
Physical Curve("shared") = {7};
Physical Curve("bottom") = {1, 2};
Physical Point("corner") = {1};
"#;

    /// A unit cube of n-1 x n-1 x n-1 hexahedra (transfinite, recombined, extruded).
    pub(crate) const BOX_GEO: &str = r#"
DefineConstant[ n = {3, Name "n"} ];
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n; Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{n - 1}; Recombine; };
Physical Volume("box") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
"#;

    /// A unit square of recombined (quadrangle) transfinite cells.
    pub(crate) const QUAD_GEO: &str = r#"
DefineConstant[ n = {3, Name "n"} ];
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("square") = {1};
Physical Curve("edges") = {1, 2};
"#;

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

    #[test]
    fn cache_reuses_and_regenerates() {
        let dir = TestDir::new("cache");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        // Also checks that the parent directory is created.
        let mut job = dir.job(&geo, "out/sub/two.msh", 2, 1);
        job.setnumber = vec![("lc".into(), 0.5)];
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        let first = std::fs::read(&job.msh).unwrap();
        assert!(first.starts_with(b"$MeshFormat\n4.1 1 8\n"), "binary MSH 4.1 expected");
        let key = std::fs::read_to_string(key_path(&job.msh)).unwrap();
        assert!(key.contains("-setnumber lc 0.5"), "{key}");
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);

        // A changed parameter regenerates, and the mesh follows it.
        job.setnumber = vec![("lc".into(), 0.25)];
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        let finer = super::super::msh::read_msh(&job.msh).unwrap();
        job.setnumber = vec![("lc".into(), 0.5)];
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        let coarse = super::super::msh::read_msh(&job.msh).unwrap();
        assert!(finer.coords.len() > coarse.coords.len());
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);

        // Other arguments are part of the key too.
        job.clscale = Some(0.5);
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);
        job.order = 2;
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        assert_eq!(mesh_with(&job, false).unwrap(), Meshed::Generated);
        assert_eq!(mesh_with(&job, false).unwrap(), Meshed::Cached);
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);

        // So are the .geo's bytes.
        dir.write("two.geo", &TWO_RECT_GEO.replace("{2, 0, 0, lc}", "{3, 0, 0, lc}"));
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);

        // A missing key, or a missing mesh, regenerates.
        std::fs::remove_file(key_path(&job.msh)).unwrap();
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        std::fs::remove_file(&job.msh).unwrap();
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        assert_eq!(mesh(&job).unwrap(), Meshed::Cached);

        // No temporary file is left behind.
        assert_eq!(dir_entries(&dir.0.join("out/sub")), vec!["two.msh", "two.msh.key"]);
    }

    #[test]
    fn missing_geo_is_reported() {
        let dir = TestDir::new("nogeo");
        let job = dir.job(&dir.0.join("nothere.geo"), "x.msh", 2, 1);
        let e = mesh(&job).unwrap_err();
        assert!(matches!(e, GmshError::GeoMissing { .. }), "{e:?}");
        let msg = e.to_string();
        assert!(msg.contains("nothere.geo") && msg.contains("does not exist"), "{msg}");
        assert!(!job.msh.exists());
    }

    #[test]
    fn missing_gmsh_is_reported() {
        let dir = TestDir::new("nogmsh");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        let job = dir.job(&geo, "x.msh", 2, 1);
        let e = mesh_impl(&job, true, "gmsh-not-installed-subcontact-test").unwrap_err();
        assert!(matches!(e, GmshError::NotInstalled), "{e:?}");
        assert_eq!(
            e.to_string(),
            "the gmsh CLI was not found: install it with `apt-get install -y gmsh` (or `make deps`)"
        );
        assert!(!job.msh.exists());
    }

    #[test]
    fn gmsh_errors_are_quoted_and_leave_no_mesh() {
        let dir = TestDir::new("bad");
        // A syntax error: gmsh 4.8.4 still writes a mesh (of what it read) and exits 1.
        let geo = dir.write("syntax.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2;\n");
        let job = dir.job(&geo, "syntax.msh", 2, 1);
        let e = mesh(&job).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, GmshError::Failed { .. }), "{e:?}");
        assert!(msg.contains("syntax.geo") && msg.contains("syntax error"), "{msg}");
        assert!(!job.msh.exists());

        // A reference to a missing point: many repeated error lines, deduplicated.
        let geo = dir.write("badline.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2};\nPhysical Curve(1) = {1};\n");
        let job = dir.job(&geo, "badline.msh", 2, 1);
        let msg = mesh(&job).unwrap_err().to_string();
        assert!(msg.contains("Unknown control point 2"), "{msg}");
        assert_eq!(msg.matches("Line with less than 2 control points").count(), 1, "{msg}");
        assert!(!msg.contains("error summary"), "{msg}");
        assert!(!job.msh.exists());

        // A failure replaces an older good mesh: none is left that does not match the .geo.
        let good = dir.write("good.geo", TWO_RECT_GEO);
        let mut job = dir.job(&good, "reuse.msh", 2, 1);
        assert_eq!(mesh(&job).unwrap(), Meshed::Generated);
        job.geo = geo;
        assert!(mesh(&job).is_err());
        assert!(!job.msh.exists());
        assert!(!key_path(&job.msh).exists());

        let mut names = dir_entries(&dir.0);
        names.retain(|n| n.contains("tmp"));
        assert!(names.is_empty(), "temporary files left: {names:?}");
    }

    #[test]
    fn bad_jobs_are_refused() {
        let dir = TestDir::new("badjob");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        let mut job = dir.job(&geo, "x.msh", 4, 1);
        assert!(matches!(mesh(&job), Err(GmshError::BadJob { .. })));
        job.dim = 2;
        job.order = 3;
        assert!(matches!(mesh(&job), Err(GmshError::BadJob { .. })));
        job.order = 1;
        job.setnumber = vec![("lc".into(), f64::NAN)];
        assert!(matches!(mesh(&job), Err(GmshError::BadJob { .. })));
        job.setnumber = vec![("".into(), 1.0)];
        assert!(matches!(mesh(&job), Err(GmshError::BadJob { .. })));
        job.setnumber = vec![];
        job.clscale = Some(0.0);
        assert!(matches!(mesh(&job), Err(GmshError::BadJob { .. })));
    }

    #[test]
    fn error_lines_skip_the_summary_box() {
        let out = "Info : x\nError   : a\nError   : ------\nError   : Mesh generation error summary\n\
                   Error   :     0 warnings\nError   :     2 errors\nError   : a\nError   : b 3 errors\n";
        assert_eq!(error_lines(out), vec!["a".to_string(), "b 3 errors".to_string()]);
    }
}
