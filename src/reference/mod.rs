//! An independent reference for the 3-RPR singularity distances, sharing no code with
//! the homotopy pipeline: many-start local constrained minimisation of `D²(K, K′)`
//! ([`local_search`]), exact derivatives by second-order forward differentiation
//! ([`jet`]), and a matrix of test designs of every class a user builds
//! ([`designs`]); the 3-RRR analogue ([`rrr`]).
//!
//! A local search gives an upper bound on the distance (every reported `K′` is a
//! verified feasible configuration); with enough well-spread starts it finds the
//! global minimum, so a homotopy distance above it has missed a critical point.

pub mod designs;
pub mod jet;
pub mod local_search;
pub mod rrr;
