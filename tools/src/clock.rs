//! The clock the tools time with, and the machine they ran on.
//!
//! Times are the calling thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`), not wall time: a
//! time ratio between two parts of one run then does not count the moments another
//! process had the core. Every table of times prints [`cpu_model`] beside it: times
//! differ from machine to machine (instruction counts under callgrind are the gate,
//! docs/PERFORMANCE.md).

use std::time::Duration;

/// The calling thread's CPU time since it started.
#[cfg(unix)]
pub fn thread_cpu() -> Duration {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `ts` is a valid, writable timespec; clock_gettime writes only into it.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "CLOCK_THREAD_CPUTIME_ID is available on every supported Unix");
    Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32)
}

/// Elsewhere (the tools run on Linux; this keeps them building): wall time since the
/// first call.
#[cfg(not(unix))]
pub fn thread_cpu() -> Duration {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed()
}

/// The thread CPU time `f` takes, and its result.
pub fn time<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let t0 = thread_cpu();
    let out = f();
    (out, thread_cpu().saturating_sub(t0))
}

/// The CPU's model as the system names it (`/proc/cpuinfo`'s `model name`; on Arm
/// boards, which have none, the implementer and part numbers), or `unknown CPU`.
pub fn cpu_model() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let field = |key: &str| {
        info.lines()
            .filter_map(|l| l.split_once(':'))
            .find(|(k, _)| k.trim() == key)
            .map(|(_, v)| v.trim().to_string())
    };
    if let Some(name) = field("model name") {
        return name;
    }
    match (field("CPU implementer"), field("CPU part")) {
        (Some(i), Some(p)) => format!("Arm CPU implementer {i} part {p}"),
        _ => "unknown CPU".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thread clock counts this thread's work: a busy loop advances it, and it never
    /// goes back.
    #[test]
    fn the_thread_clock_counts_work() {
        let (sum, spent) = time(|| (0..20_000_000u64).fold(0u64, |a, x| std::hint::black_box(a ^ x)));
        assert!(sum < u64::MAX);
        assert!(spent > Duration::ZERO, "{spent:?}");
        let (a, b) = (thread_cpu(), thread_cpu());
        assert!(b >= a);
    }

    #[test]
    fn the_cpu_model_names_something() {
        assert!(!cpu_model().is_empty());
    }
}
