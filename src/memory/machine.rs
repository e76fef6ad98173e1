//! The machine's memory as this process sees it, read from /proc and the
//! cgroup files (Linux; elsewhere nothing is short and the peak unknown):
//! the machine's size, this process's resident memory now and at its
//! peak, and what it may still allocate.
//!
//! What may be used ([`available`]): the least of MemAvailable
//! (/proc/meminfo), the cgroup's limit less its usage (cgroup v2
//! `memory.max` - `memory.current`, v1 `memory.limit_in_bytes` -
//! `memory.usage_in_bytes`) and the address-space limit (`ulimit -v`) less
//! the process's virtual size.

/// What the process may still allocate, and the limit that says so.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Available {
    pub bytes: f64,
    pub what: String,
}

/// What the process may still allocate: the least of the system's
/// available memory, its cgroup's room and its address-space room.
pub fn available() -> Available {
    let mut best = Available { bytes: f64::INFINITY, what: "no limit found".into() };
    let mut consider = |bytes: Option<f64>, what: &str| {
        if let Some(b) = bytes.filter(|b| *b < best.bytes) {
            best = Available { bytes: b.max(0.0), what: what.to_string() };
        }
    };
    consider(kb_line("/proc/meminfo", "MemAvailable:"), "MemAvailable in /proc/meminfo");
    for (limit, usage, what) in cgroups() {
        let (Some(l), Some(u)) = (number(&limit), number(&usage)) else { continue };
        consider(Some(l - u), &what);
    }
    if let (Some(limit), Some(size)) = (address_limit(), kb_line("/proc/self/status", "VmSize:")) {
        consider(Some(limit - size), "the address-space limit (ulimit -v) less this process's size");
    }
    best
}

/// The cgroup limit and usage files of this process: (limit, usage, name).
fn cgroups() -> Vec<(String, String, String)> {
    let Ok(text) = std::fs::read_to_string("/proc/self/cgroup") else { return Vec::new() };
    cgroups_in(std::path::Path::new("/sys/fs/cgroup"), &text)
}

/// The memory limit and usage files of the cgroups named in `proc_cgroup`
/// (the text of /proc/self/cgroup) under the cgroup mount `root`: each
/// cgroup's and every parent's up to the mount, in cgroup v2
/// (`memory.max`, `memory.current`) and v1 (`memory/memory.limit_in_bytes`,
/// `memory.usage_in_bytes`; Docker on v1 sets the limit on a parent). In a
/// cgroup namespace the mount is the process's own cgroup, which the
/// path from /proc does not name: the walk starts at the deepest part of
/// the path that exists.
fn cgroups_in(root: &std::path::Path, proc_cgroup: &str) -> Vec<(String, String, String)> {
    let mut out = Vec::new();
    for line in proc_cgroup.lines() {
        let mut f = line.splitn(3, ':');
        let (Some(_), Some(ctl), Some(path)) = (f.next(), f.next(), f.next()) else { continue };
        let (base, limit, usage) = if ctl.is_empty() {
            (root.to_path_buf(), "memory.max", "memory.current")
        } else if ctl.split(',').any(|c| c == "memory") {
            (root.join("memory"), "memory.limit_in_bytes", "memory.usage_in_bytes")
        } else {
            continue;
        };
        let mut p = base.join(path.trim_start_matches('/'));
        while !p.is_dir() && p != base && p.pop() {}
        loop {
            let (l, u) = (p.join(limit), p.join(usage));
            if l.exists() && !out.iter().any(|(x, _, _)| *x == l.display().to_string()) {
                let what = format!("the cgroup limit {} less its usage", l.display());
                out.push((l.display().to_string(), u.display().to_string(), what));
            }
            if p == base || !p.starts_with(&base) || !p.pop() {
                break;
            }
        }
    }
    out
}

/// The number in a file ("max" and absent files are no limit).
fn number(path: &str) -> Option<f64> {
    std::fs::read_to_string(path).ok()?.trim().parse::<f64>().ok()
}

/// Bytes of the `kB` value on the line of `file` that starts with `key`.
fn kb_line(file: &str, key: &str) -> Option<f64> {
    let text = std::fs::read_to_string(file).ok()?;
    let v: f64 = text.lines().find(|l| l.starts_with(key))?.split_whitespace().nth(1)?.parse().ok()?;
    Some(v * 1024.0)
}

/// This process's resident memory now, in bytes (0 where unknown).
pub fn resident() -> f64 {
    kb_line("/proc/self/status", "VmRSS:").unwrap_or(0.0)
}

/// Returns the heap's free memory to the system where the allocator can
/// (glibc's `malloc_trim`), so that [`resident`] counts what the process
/// holds, not what it held: a run solved again after a first attempt
/// (the driver's fallback) is estimated from its own needs.
pub fn give_back() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only releases free heap pages; it reads and
    // writes no memory of ours.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// The machine's memory, in bytes (infinite where unknown: never short).
pub fn physical() -> f64 {
    kb_line("/proc/meminfo", "MemTotal:").unwrap_or(f64::INFINITY)
}

/// This process's peak resident memory, in bytes (0 where unknown).
pub fn peak() -> u64 {
    kb_line("/proc/self/status", "VmHWM:").map_or(0, |b| b as u64)
}

/// RLIMIT_AS, when set.
fn address_limit() -> Option<f64> {
    let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: getrlimit writes the struct it is given
    let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
    (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as f64)
}

/// Bytes as "1.2 GB" or "350 MB".
pub fn human(bytes: f64) -> String {
    if !bytes.is_finite() {
        "unlimited memory".to_string()
    } else if bytes >= 1e9 {
        format!("{:.1} GB", bytes / 1e9)
    } else {
        format!("{:.0} MB", (bytes / 1e6).max(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Docker on cgroup v1 puts the limit on a parent of the process's
    /// cgroup; only the process's own was read (issue 32), so such a run
    /// was killed instead of refused.
    #[test]
    fn cgroup_limits_are_read_up_the_hierarchy_in_v1_and_v2() {
        let root = std::env::temp_dir().join(format!("subcontact-cgroup-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let put = |dir: &str, files: &[(&str, &str)]| {
            std::fs::create_dir_all(root.join(dir)).unwrap();
            for (f, v) in files {
                std::fs::write(root.join(dir).join(f), v).unwrap();
            }
        };
        let v1 =
            |l: &str, u: &str| [("memory.limit_in_bytes", l.to_string()), ("memory.usage_in_bytes", u.to_string())];
        for (dir, l, u) in [
            ("memory", "9223372036854771712", "5000000000"),
            ("memory/docker", "1000000000", "300000000"),
            ("memory/docker/abc", "9223372036854771712", "200000000"),
        ] {
            let files = v1(l, u);
            put(dir, &[(files[0].0, &files[0].1), (files[1].0, &files[1].1)]);
        }
        put("user.slice", &[("memory.max", "2000000000"), ("memory.current", "500000000")]);
        put("user.slice/run", &[("memory.max", "max"), ("memory.current", "100000000")]);
        let text = "4:memory:/docker/abc\n0::/user.slice/run\n";
        let found = cgroups_in(&root, text);
        let room = |l: &str, u: &str| number(l).zip(number(u)).map(|(l, u)| l - u);
        let rooms: Vec<Option<f64>> = found.iter().map(|(l, u, _)| room(l, u)).collect();
        assert_eq!(found.len(), 5, "{found:?}");
        assert!(rooms.contains(&Some(7e8)) && rooms.contains(&Some(1.5e9)), "{rooms:?}");
        // in a cgroup namespace the mount is the process's own cgroup
        let found = cgroups_in(&root, "4:memory:/not/here\n");
        assert_eq!(found.len(), 1, "{found:?}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
