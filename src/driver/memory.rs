//! What the machine has and what this process used, read from /proc
//! (Linux; elsewhere the machine is never short and the peak unknown): the
//! memory [`super::condense`] keeps the parts' factors within, and each
//! rank's peak that [`super::stats`] reports.

/// The machine's memory in bytes (Linux; `u64::MAX` elsewhere: never short).
pub(super) fn physical_memory() -> u64 {
    meminfo("/proc/meminfo", "MemTotal:").map_or(u64::MAX, |kb| kb * 1024)
}

/// Peak resident memory of this process in bytes (Linux; 0 elsewhere).
pub(super) fn peak_memory() -> u64 {
    meminfo("/proc/self/status", "VmHWM:").map_or(0, |kb| kb * 1024)
}

/// The value in kB of the line of `file` that starts with `key`.
fn meminfo(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    text.lines()
        .find(|l| l.starts_with(key))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse::<u64>().ok())
}
