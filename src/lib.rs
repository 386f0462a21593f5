//! # singdist
//!
//! How far is a planar parallel manipulator from its nearest singularity, and which
//! singular configuration is that, at every pose of a motion?
//!
//! The crate reads as the data flows (see `ARCHITECTURE.md` of the project):
//!
//! 1. [`system`]: polynomial systems with variables and parameters, symbolic
//!    differentiation, compiled straight-line evaluation, Bertini/PHCpack formats.
//! 2. [`homotopy`]: homotopies, the predictor–corrector path tracker, endgame,
//!    start systems, monodromy with trace test, parallel `solve`.
//! 3. [`mechanism`]: 3-RPR, 3-RRR and 3-PRRR designs, poses, motions, configurations.
//! 4. [`metric`]: extrinsic distances between configurations (the nine metrics).
//! 5. [`problem`]: the Lagrangian sub-problems of every metric, built with [`system`].
//! 6. [`pipeline`]: ab-initio, user homotopy, parameter homotopy, post-processing.
//! 7. [`index`]: classic kinematic performance indices (for comparison).
//! 8. [`optimize`]: genetic algorithm and local constrained refinement.
//! 9. [`io`]: serde types of input and output files, CSV/JSON/SVG writers.
//! 10. [`reference`]: an independent yardstick for the pipeline: many-start local
//!     minimisation of the singularity distances, and a matrix of test designs.
//! 11. [`certify`]: Krawczyk certificates in interval arithmetic that critical points
//!     are exact, distinct and real, and that a sub-problem's set of them is complete.
//!
//! Arrows point one way: `pipeline → problem → {metric, mechanism, system}`,
//! `pipeline → homotopy → system`. Nothing numerical depends on [`io`].

pub mod algebra;
pub mod certify;
pub mod homotopy;
pub mod index;
pub mod io;
pub mod mechanism;
pub mod metric;
pub mod optimize;
pub mod pipeline;
pub mod problem;
pub mod random;
pub mod reference;
pub mod system;

/// Complex double, the scalar of every numerical routine.
pub type C64 = num_complex::Complex64;

/// `|z| = √(re² + im²)` without the overflow guard of [`num_complex::Complex::norm`]
/// (`hypot`, several times slower; it was 10 % of a curve run's profile). Exact to
/// rounding for `|z| < 1e150`, which covers every finite point the tracker keeps.
#[inline(always)]
pub fn modulus(z: C64) -> f64 {
    z.norm_sqr().sqrt()
}
