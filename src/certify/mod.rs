//! Certification: proofs, in interval arithmetic, that computed critical points are
//! exact solutions, distinct, and real or not.
//!
//! [`krawczyk`] proves that a box around an approximate solution contains exactly one
//! solution of a square polynomial system (Krawczyk's test, with realness decided by
//! conjugation-closed boxes). [`distance`] applies it to the Lagrange systems of the
//! singularity-distance sub-problems: every critical point of a sub-problem at a pose
//! is certified, the distance `D(K, K′)` of each certified real one is enclosed in an
//! interval, and when as many distinct solutions are certified as the family's generic
//! root count, no other isolated critical point exists (the number of isolated
//! solutions at any parameter is at most the generic number: Morgan, Sommese,
//! "Coefficient-parameter polynomial continuation", Appl. Math. Comput. 1989).

pub mod distance;
pub mod krawczyk;
pub mod midrad;
