//! Measuring child processes in the CLI tests.

use std::process::Command;
use std::time::Duration;

/// Whether peak memory can be read (Linux `/proc`); prints a note when it cannot.
pub fn memory_is_measurable() -> bool {
    let measurable = std::path::Path::new("/proc/self/status").exists();
    if !measurable {
        eprintln!("no /proc: skipped");
    }
    measurable
}

/// Peak resident memory (kB) of a child that ran `command` to its end: `VmHWM` read
/// from /proc while it runs (the last value seen before it exits). Panics if the child
/// fails.
pub fn peak_rss_kb(mut command: Command) -> u64 {
    let mut child = command.spawn().expect("spawn singdist");
    let status_path = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    loop {
        if let Ok(text) = std::fs::read_to_string(&status_path)
            && let Some(line) = text.lines().find(|l| l.starts_with("VmHWM:"))
        {
            let kb: u64 = line
                .split_whitespace()
                .nth(1)
                .and_then(|v| v.parse().ok())
                .unwrap_or(0);
            peak = peak.max(kb);
        }
        if let Some(status) = child.try_wait().expect("wait") {
            assert!(status.success(), "{command:?} failed: {status}");
            return peak;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Asserts that the peak memory of `command_for(poses)` does not grow with the number
/// of poses: 10,000 poses need at most 1.5 × the memory of 1,000. Returns whether it
/// was measured (see [`memory_is_measurable`]).
pub fn assert_memory_flat_in_poses(command_for: impl Fn(&str) -> Command) -> bool {
    if !memory_is_measurable() {
        return false;
    }
    let small = peak_rss_kb(command_for("1000"));
    let large = peak_rss_kb(command_for("10000"));
    assert!(small > 0 && large > 0, "{small} {large}");
    assert!(
        (large as f64) <= 1.5 * small as f64,
        "peak RSS {large} kB for 10,000 poses vs {small} kB for 1,000"
    );
    true
}
