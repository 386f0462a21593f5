//! Helpers shared by the benchmarks: thread pools and one timed run.
#![allow(dead_code)]

use std::time::Instant;

/// A rayon pool of `threads` threads (the benchmarks fix the thread count).
pub fn thread_pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

/// The result of `run` and its wall time in seconds.
pub fn timed<T>(run: impl FnOnce() -> T) -> (T, f64) {
    let started = Instant::now();
    let result = run();
    (result, started.elapsed().as_secs_f64())
}

/// A PHCpack input text parsed into a system, or `None` after printing why system
/// `name` is skipped (one row of a benchmark table).
pub fn parse_phc(name: &str, text: &str) -> Option<singdist::system::System> {
    match singdist::system::phc::read(text) {
        Ok(system) => Some(system),
        Err(e) => {
            println!("{name:<12} skipped: {e}");
            None
        }
    }
}
