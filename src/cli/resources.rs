//! Resource bounds checked before any work: the worker-thread count and the number of
//! poses a command may hold in memory.

use super::args::ThreadsArg;
use anyhow::{Context, Result, bail};

/// Most poses of one motion: streamed runs (`curve`, `indices`, `compare`, `rrr
/// curve` to CSV, JSON Lines or stdout) still sample the whole motion in memory (tens
/// of bytes per pose); a table kept whole (a `.json` document, a plot) holds every row
/// until the run ends (≈ 1 KB per pose for the indices table), about 1 GB here.
pub const MAX_POSES: usize = 1_000_000;

/// Most pose × metric pairs of one metric-distance run kept whole (`curve`, `compare`,
/// `indices --with-metrics` to a `.json` document or a plot; streamed runs hold one
/// window): every pose keeps the critical points of each metric until the run ends (≈ 30 KB per pair measured: 250 MB for 9,000 poses of one metric), so
/// 100,000 pairs need about 3 GB (e.g. 100,000 poses of one metric or 11,111 of all
/// nine).
pub const MAX_METRIC_POSES: usize = 100_000;

/// Most poses of a 3-RRR curve kept whole (`.json`, `--plot`, `--html`; streamed runs
/// hold one window): each pose keeps its four sub-problems' results until the run ends (≈ 7 KB per pose measured: 9 MB peak for 300 poses, 16 MB for
/// 1,200), so 100,000 poses need about 0.7 GB.
pub const MAX_RRR_POSES: usize = 100_000;

/// Cores of the machine ([`std::thread::available_parallelism`], 1 if unknown).
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The `--threads` value to use: `None` stays `None` (all cores); 0 is an error; more
/// than the machine's cores is clamped to the cores with a one-line warning (more
/// workers than cores only add contention: `curve --threads 2000` took 265 s instead
/// of 1.4 s).
pub fn thread_count(threads: ThreadsArg) -> Result<Option<usize>> {
    match threads.requested() {
        None => Ok(None),
        Some(0) => bail!("--threads: must be at least 1"),
        Some(1) => Ok(Some(1)),
        Some(n) => {
            let cores = available_cores();
            if n > cores {
                eprintln!(
                    "singdist: warning: --threads {n} is more than the {cores} cores of this machine; using {cores}"
                );
                Ok(Some(cores))
            } else {
                Ok(Some(n))
            }
        }
    }
}

/// Runs `f` on a rayon pool of the `--threads` workers (checked by [`thread_count`])
/// or on the global pool.
pub fn with_threads<T: Send>(threads: ThreadsArg, f: impl FnOnce() -> T + Send) -> Result<T> {
    match thread_count(threads)? {
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .context("--threads: cannot start the worker pool")?;
            Ok(pool.install(f))
        }
        None => Ok(f()),
    }
}

/// Refuses more than `limit` poses before any work; `what` names the limit's reason.
pub fn check_pose_count(poses: usize, limit: usize, what: &str) -> Result<()> {
    if poses > limit {
        bail!(
            "--poses: {poses} poses are more than the {limit} this command holds in memory ({what}); use fewer poses or split the motion"
        );
    }
    Ok(())
}

/// Refuses more than [`MAX_METRIC_POSES`] pose × metric pairs before any work.
pub fn check_metric_pose_count(poses: usize, metrics: usize) -> Result<()> {
    let pairs = poses.saturating_mul(metrics);
    if pairs > MAX_METRIC_POSES {
        bail!(
            "--poses: {poses} poses × {metrics} metric(s) = {pairs} pose-metric pairs are more than the {MAX_METRIC_POSES} a run holds in memory (each pose keeps its critical points until the end, ≈ 30 KB per pair); use fewer poses or metrics"
        );
    }
    Ok(())
}
