//! Running the gmsh CLI to turn a `.geo` into an MSH 4.1 mesh.
//!
//! [`run_in`] runs
//! `gmsh <geo> -<dim> -order <order> [-setnumber k v]... [-clscale s] -format msh41 -bin -o <file>`
//! in a directory it is handed as an open handle (gmsh's working
//! directory: the run's staging directory, so a failed or interrupted gmsh
//! leaves nothing in the results). gmsh runs in its own process group,
//! killed when this process dies (`PR_SET_PDEATHSIG`) and, with everything
//! it started, when it takes longer than the job's time limit.
//!
//! [`cache_key`] is what the mesh cache compares: a hash (64-bit FNV-1a) of
//! the `.geo` bytes and of every argument, with the command for people
//! reading it. Files that the `.geo` pulls in with `Include` or `Merge` are
//! not part of the key. Before that, the job is checked against what the
//! `.geo` says ([`super::geo`]): every `setnumber` name must be a
//! `DefineConstant` of the `.geo` (or a gmsh option, `Mesh.X`), since gmsh
//! silently ignores any other; and commands that run programs or write
//! files are refused unless the job allows them.
//!
//! gmsh's output is captured, never shown. gmsh 4.8.4 may write a mesh and exit
//! 0 after reporting errors, so any `Error` line counts as a failure. Parameters
//! reach the `.geo` through `-setnumber NAME VALUE`, which overrides
//! `DefineConstant[ NAME = {default, Name "..."} ];` (it also sets gmsh options
//! such as `Mesh.SecondOrderIncomplete`).

use std::io::{self, Read};
use std::os::fd::{AsRawFd, BorrowedFd};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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

    #[error("gmsh did not finish meshing `{}` within {seconds} s ([gmsh] timeout) and was stopped: coarsen the mesh (a larger size in [gmsh] setnumber), look for a loop in the .geo that never ends, or raise [gmsh] timeout", geo.display())]
    Timeout { geo: PathBuf, seconds: f64 },

    #[error("[gmsh] setnumber names `{name}`, which `{}` does not define: gmsh would ignore it and mesh with the .geo's own values. {}", geo.display(), defined_names(defined))]
    UnknownParameter { geo: PathBuf, name: String, defined: Vec<String> },

    #[error("`{}` runs commands that reach outside the mesh: {}. A .geo is a program: these run other programs through the shell or write files wherever the script says, with your rights. Remove them from the .geo, or pass --allow-geo-commands if you trust it", geo.display(), commands.join(", "))]
    Commands { geo: PathBuf, commands: Vec<String> },

    #[error("`gmsh --version` printed no version (output: {output:?})")]
    Version { output: String },

    #[error(transparent)]
    Joints(#[from] super::joints::JointError),
}

fn defined_names(defined: &[String]) -> String {
    if defined.is_empty() {
        "The .geo defines no parameters: add `DefineConstant[ NAME = {value, Name \"...\"} ];` to it for each name to set".into()
    } else {
        format!(
            "The .geo defines (by DefineConstant): {}; use one of those, or add a DefineConstant for the name",
            defined.join(", ")
        )
    }
}

/// What to mesh and how.
#[derive(Clone, Debug, PartialEq)]
pub struct GmshJob {
    /// The gmsh geometry script.
    pub geo: PathBuf,
    /// The mesh's path once committed (for messages); gmsh writes a file
    /// of its name into the directory [`run_in`] is given.
    pub msh: PathBuf,
    /// 2 or 3.
    pub dim: usize,
    /// 1 or 2.
    pub order: usize,
    /// `-setnumber NAME VALUE` for each pair, in order.
    pub setnumber: Vec<(String, f64)>,
    /// `-clscale s`: global factor on mesh sizes.
    pub clscale: Option<f64>,
    /// How long gmsh may take.
    pub timeout: Duration,
    /// Whether the .geo may run programs and write files.
    pub allow_commands: bool,
    /// Joints that cut the bodies: then gmsh runs through its API
    /// ([`super::joints`]) instead of the CLI, and the joints are part of the key.
    pub cut: Option<super::joints::CutJob>,
}

/// gmsh's time limit when the scene sets none.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(600);

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
fn gmsh_args(job: &GmshJob, geo: &Path, binary: bool, out: &Path) -> Vec<std::ffi::OsString> {
    let mut args: Vec<std::ffi::OsString> =
        vec![geo.into(), format!("-{}", job.dim).into(), "-order".into(), job.order.to_string().into()];
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
    if job.timeout.is_zero() {
        return bad("time limit 0 (must be a positive number of seconds)".into());
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

/// The mesh cache's key of `job`: a hash of the `.geo` bytes and of every
/// argument, then the command for people reading it. Checks the job and
/// the `.geo` first (see the module header).
pub fn cache_key(job: &GmshJob) -> Result<String, GmshError> {
    key_with(job, true)
}

fn key_with(job: &GmshJob, binary: bool) -> Result<String, GmshError> {
    check_job(job)?;
    let geo_bytes = match std::fs::read(&job.geo) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Err(GmshError::GeoMissing { geo: job.geo.clone() }),
        Err(e) => return Err(GmshError::Io { what: "cannot read", path: job.geo.clone(), source: e }),
    };
    check_geo(job, &String::from_utf8_lossy(&geo_bytes))?;
    let mut h = Fnv::new();
    h.field(b"subcontact gmsh key 2");
    h.field(&geo_bytes);
    let args = gmsh_args(job, &job.geo, binary, out_name(job)?);
    for a in &args {
        h.field(a.as_encoded_bytes());
    }
    if let Some(c) = &job.cut {
        h.field(c.key_text().as_bytes());
    }
    let cmd: Vec<String> = args.iter().map(|a| a.to_string_lossy().into_owned()).collect();
    Ok(format!("{:016x}\ngmsh {}\n", h.0, cmd.join(" ")))
}

/// The job against what its `.geo` defines and runs.
fn check_geo(job: &GmshJob, text: &str) -> Result<(), GmshError> {
    let found = super::geo::scan(&job.geo, text);
    if !job.allow_commands && !found.commands.is_empty() {
        let commands = found
            .commands
            .iter()
            .map(|(f, line, c)| {
                let file = if *f == job.geo { String::new() } else { format!("{}, ", f.display()) };
                format!("{c} ({file}line {line})")
            })
            .collect();
        return Err(GmshError::Commands { geo: job.geo.clone(), commands });
    }
    // a name with a dot is a gmsh option (Mesh.SecondOrderIncomplete), which gmsh checks
    match job.setnumber.iter().find(|(n, _)| !n.contains('.') && !found.constants.contains(n)) {
        Some((name, _)) => {
            Err(GmshError::UnknownParameter { geo: job.geo.clone(), name: name.clone(), defined: found.constants })
        }
        None => Ok(()),
    }
}

/// The file name gmsh writes.
fn out_name(job: &GmshJob) -> Result<&Path, GmshError> {
    job.msh.file_name().map(Path::new).ok_or_else(|| GmshError::BadJob {
        geo: job.geo.clone(),
        detail: format!("mesh path `{}` has no file name", job.msh.display()),
    })
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

/// Meshes `job` into the directory `dir` (gmsh's working directory; the
/// file is named as `job.msh`), after the checks of [`cache_key`].
pub fn run_in(job: &GmshJob, dir: BorrowedFd<'_>) -> Result<(), GmshError> {
    key_with(job, true)?;
    match &job.cut {
        None => run_gmsh(job, true, dir, "gmsh"),
        Some(cut) => run_cut(job, cut, dir),
    }
}

/// Cuts the bodies by the joints and meshes through gmsh's API (in this
/// process, so without [`GmshJob::timeout`]), writing the mesh and the
/// cut's report ([`super::joints::report_path`]) into `dir`.
fn run_cut(job: &GmshJob, cut: &super::joints::CutJob, dir: BorrowedFd<'_>) -> Result<(), GmshError> {
    let out = out_name(job)?;
    let report = super::joints::report_path(out);
    // gmsh's API takes paths: the directory handle's own, which stays the
    // directory it was opened on
    let at = |f: &Path| Path::new(&format!("/proc/self/fd/{}", dir.as_raw_fd())).join(f);
    let args = super::joints::MeshArgs {
        geo: &job.geo,
        dim: job.dim,
        order: job.order,
        setnumber: &job.setnumber,
        clscale: job.clscale,
    };
    let ran = super::joints::mesh(&args, cut, &at(out), &at(&report));
    if ran.is_err() {
        for f in [out, report.as_path()] {
            let _ = rustix::fs::unlinkat(dir, f, rustix::fs::AtFlags::empty());
        }
    }
    Ok(ran?)
}

/// Meshes `job` into `job.msh`'s directory with `program` as the gmsh CLI
/// (the unit tests name one that is not installed).
#[cfg(test)]
fn mesh_impl(job: &GmshJob, binary: bool, program: &str) -> Result<(), GmshError> {
    key_with(job, binary)?;
    let parent = job.msh.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let dir = std::fs::File::open(parent).map_err(|e| GmshError::Io {
        what: "cannot open",
        path: parent.into(),
        source: e,
    })?;
    run_gmsh(job, binary, std::os::fd::AsFd::as_fd(&dir), program)
}

/// Runs gmsh in `dir`; Ok only if gmsh succeeded in time, reported no
/// error and wrote its file.
fn run_gmsh(job: &GmshJob, binary: bool, dir: BorrowedFd<'_>, program: &str) -> Result<(), GmshError> {
    let out = out_name(job)?;
    let ran = gmsh_in(job, binary, dir, program, out);
    if ran.is_err() {
        // gmsh 4.8.4 writes a mesh of what it read even after errors
        let _ = rustix::fs::unlinkat(dir, out, rustix::fs::AtFlags::empty());
    }
    ran
}

fn gmsh_in(job: &GmshJob, binary: bool, dir: BorrowedFd<'_>, program: &str, out: &Path) -> Result<(), GmshError> {
    let geo = std::path::absolute(&job.geo).unwrap_or_else(|_| job.geo.clone());
    let mut cmd = Command::new(program);
    cmd.args(gmsh_args(job, &geo, binary, out))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .process_group(0);
    let (raw, parent) = (dir.as_raw_fd(), rustix::process::getpid());
    // SAFETY: between fork and exec only system calls (fchdir, prctl,
    // getppid), which allocate nothing; `raw` is open in the child until exec
    unsafe {
        cmd.pre_exec(move || {
            rustix::process::fchdir(BorrowedFd::borrow_raw(raw))?;
            rustix::process::set_parent_process_death_signal(Some(rustix::process::Signal::KILL))?;
            if rustix::process::getppid() != Some(parent) {
                return Err(io::Error::other("the parent is gone"));
            }
            Ok(())
        });
    }
    let mut child = cmd.spawn().map_err(spawn_error)?;
    let readers = [child.stdout.take().map(drain), child.stderr.take().map(drain)];
    let finished = wait_until(&mut child, Instant::now() + job.timeout);
    // gmsh and anything it started: gone (a child holding the pipes open
    // would keep the readers waiting)
    if let Some(pid) = rustix::process::Pid::from_raw(child.id() as i32) {
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    let status = match finished {
        Some(s) => s,
        None => {
            let _ = child.wait();
            return Err(GmshError::Timeout { geo: job.geo.clone(), seconds: job.timeout.as_secs_f64() });
        }
    };
    let text: String = readers.into_iter().flatten().map(|r| r.join().unwrap_or_default() + "\n").collect();
    let errors = error_lines(&text);
    if !status.success() || !errors.is_empty() {
        let status = match status.code() {
            Some(c) => format!("exit status {c}"),
            None => "killed by a signal".to_string(),
        };
        let errors = if errors.is_empty() { tail(&text, 10) } else { errors.join("\n") };
        let errors = errors.lines().map(|l| format!("  {l}")).collect::<Vec<_>>().join("\n");
        return Err(GmshError::Failed { geo: job.geo.clone(), status, errors });
    }
    let wrote = rustix::fs::statat(dir, out, rustix::fs::AtFlags::SYMLINK_NOFOLLOW)
        .is_ok_and(|st| rustix::fs::FileType::from_raw_mode(st.st_mode) == rustix::fs::FileType::RegularFile);
    if !wrote {
        return Err(GmshError::NoOutput { geo: job.geo.clone(), output: tail(&text, 10) });
    }
    Ok(())
}

/// A thread reading a pipe to its end, lossily as text.
fn drain(mut r: impl Read + Send + 'static) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = r.read_to_end(&mut b);
        String::from_utf8_lossy(&b).into_owned()
    })
}

/// The child's exit status, or `None` when `deadline` passed first.
fn wait_until(child: &mut std::process::Child, deadline: Instant) -> Option<std::process::ExitStatus> {
    let mut pause = Duration::from_millis(2);
    loop {
        match child.try_wait() {
            Ok(Some(s)) => return Some(s),
            Ok(None) if Instant::now() < deadline => {}
            _ => return None,
        }
        std::thread::sleep(pause.min(deadline.saturating_duration_since(Instant::now())));
        pause = (pause * 2).min(Duration::from_millis(50));
    }
}

#[cfg(test)]
mod tests {
    //! What needs no gmsh run: the cache key, the checks of the job and the
    //! `.geo`, a missing gmsh, gmsh's error lines. gmsh itself runs in
    //! tests/gmsh_cli.rs.

    use super::*;

    /// Two unit squares side by side sharing the edge x = 1.
    const TWO_RECT_GEO: &str = include_str!("../../tests/fixtures/msh/two_rect.geo");

    /// A fresh directory under the system temp dir, removed when the test passes.
    struct TestDir(PathBuf);

    impl TestDir {
        fn new(name: &str) -> Self {
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

        fn write(&self, name: &str, text: &str) -> PathBuf {
            let p = self.0.join(name);
            std::fs::write(&p, text).unwrap();
            p
        }

        fn job(&self, geo: &Path, msh: &str, dim: usize, order: usize) -> GmshJob {
            GmshJob {
                geo: geo.to_path_buf(),
                msh: self.0.join(msh),
                dim,
                order,
                setnumber: Vec::new(),
                clscale: None,
                timeout: DEFAULT_TIMEOUT,
                allow_commands: false,
                cut: None,
            }
        }
    }

    impl Drop for TestDir {
        fn drop(&mut self) {
            if !std::thread::panicking() {
                let _ = std::fs::remove_dir_all(&self.0);
            }
        }
    }

    #[test]
    fn the_key_follows_every_argument_and_the_geo() {
        let dir = TestDir::new("key");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        let mut job = dir.job(&geo, "out/two.msh", 2, 1);
        job.setnumber = vec![("lc".into(), 0.5)];
        let first = cache_key(&job).unwrap();
        assert!(first.contains("-setnumber lc 0.5") && first.contains("-o two.msh"), "{first}");
        assert_eq!(cache_key(&job).unwrap(), first);
        let mut keys = vec![first];
        job.setnumber = vec![("lc".into(), 0.25)];
        keys.push(cache_key(&job).unwrap());
        job.clscale = Some(0.5);
        keys.push(cache_key(&job).unwrap());
        job.order = 2;
        keys.push(cache_key(&job).unwrap());
        keys.push(key_with(&job, false).unwrap());
        dir.write("two.geo", &TWO_RECT_GEO.replace("{2, 0, 0, lc}", "{3, 0, 0, lc}"));
        keys.push(cache_key(&job).unwrap());
        let mut unique = keys.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), keys.len(), "{keys:?}");
    }

    /// A misspelt parameter was meshed at the .geo's own size (issue 32:
    /// `lcc = 0.02` gave 1,576 DOFs instead of 34,448, exit 0).
    #[test]
    fn a_parameter_the_geo_does_not_define_is_refused_naming_those_it_does() {
        let dir = TestDir::new("param");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        let mut job = dir.job(&geo, "two.msh", 2, 1);
        job.setnumber = vec![("lcc".into(), 0.02)];
        let e = cache_key(&job).unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, GmshError::UnknownParameter { .. }), "{e:?}");
        assert!(msg.contains("`lcc`") && msg.contains("two.geo") && msg.contains("DefineConstant): lc"), "{msg}");
        // gmsh options pass (gmsh checks them)
        job.setnumber = vec![("lc".into(), 0.5), ("Mesh.SecondOrderIncomplete".into(), 1.0)];
        cache_key(&job).unwrap();
    }

    #[test]
    fn missing_geo_is_reported() {
        let dir = TestDir::new("nogeo");
        let job = dir.job(&dir.0.join("nothere.geo"), "x.msh", 2, 1);
        let e = mesh_impl(&job, true, "gmsh").unwrap_err();
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
    fn bad_jobs_are_refused() {
        let dir = TestDir::new("badjob");
        let geo = dir.write("two.geo", TWO_RECT_GEO);
        let mut job = dir.job(&geo, "x.msh", 4, 1);
        assert!(matches!(mesh_impl(&job, true, "gmsh"), Err(GmshError::BadJob { .. })));
        job.dim = 2;
        job.order = 3;
        assert!(matches!(mesh_impl(&job, true, "gmsh"), Err(GmshError::BadJob { .. })));
        job.order = 1;
        job.setnumber = vec![("lc".into(), f64::NAN)];
        assert!(matches!(mesh_impl(&job, true, "gmsh"), Err(GmshError::BadJob { .. })));
        job.setnumber = vec![("".into(), 1.0)];
        assert!(matches!(mesh_impl(&job, true, "gmsh"), Err(GmshError::BadJob { .. })));
        job.setnumber = vec![];
        job.clscale = Some(0.0);
        assert!(matches!(mesh_impl(&job, true, "gmsh"), Err(GmshError::BadJob { .. })));
    }

    #[test]
    fn error_lines_skip_the_summary_box() {
        let out = "Info : x\nError   : a\nError   : ------\nError   : Mesh generation error summary\n\
                   Error   :     0 warnings\nError   :     2 errors\nError   : a\nError   : b 3 errors\n";
        assert_eq!(error_lines(out), vec!["a".to_string(), "b 3 errors".to_string()]);
    }
}
