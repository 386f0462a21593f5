//! Seeded, reproducible randomness.
//!
//! Every random choice in singdist takes an explicit `u64` seed and draws from
//! ChaCha8, whose stream is fixed across platforms and library versions, so a run
//! repeats bit for bit. Parallel code derives one independent stream per task with
//! [`stream`] (seed, task index), never from a shared generator, so results do not
//! depend on the thread count or scheduling.

use crate::C64;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The generator used everywhere.
pub type SeededRng = ChaCha8Rng;

/// Generator for a given seed.
pub fn seeded(seed: u64) -> SeededRng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// Independent generator for task `index` of a run with `seed` (ChaCha stream selection).
pub fn stream(seed: u64, index: u64) -> SeededRng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    rng
}

/// Uniform real number in `[lo, hi)`.
pub fn uniform(rng: &mut SeededRng, lo: f64, hi: f64) -> f64 {
    let u = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    lo + (hi - lo) * u
}

/// Standard normal sample (Box–Muller).
pub fn normal(rng: &mut SeededRng) -> f64 {
    let u1 = uniform(rng, f64::MIN_POSITIVE, 1.0);
    let u2 = uniform(rng, 0.0, 1.0);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Complex number with independent standard normal real and imaginary parts
/// (the usual "generic" complex choice of numerical algebraic geometry).
pub fn complex_normal(rng: &mut SeededRng) -> C64 {
    C64::new(normal(rng), normal(rng))
}

/// Complex number uniformly distributed on the unit circle, e.g. the γ of a
/// straight-line homotopy `(1−t)·γ·G + t·F`.
pub fn unit_complex(rng: &mut SeededRng) -> C64 {
    C64::from_polar(1.0, uniform(rng, 0.0, std::f64::consts::TAU))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_stream_and_streams_differ() {
        let a: Vec<u64> = (0..4).map(|_| seeded(7).next_u64()).collect();
        assert!(a.iter().all(|&v| v == a[0]));
        let mut s0 = stream(7, 0);
        let mut s1 = stream(7, 1);
        assert_ne!(s0.next_u64(), s1.next_u64());
        let z = unit_complex(&mut seeded(3));
        assert!((z.norm() - 1.0).abs() < 1e-15);
    }
}
