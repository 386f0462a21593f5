//! The 3-RRR instance of the sweep engine: its sub-problems (the parallel singularity
//! and the three leg singularities, Kapilavai and Nawratil, *Singularity distance
//! computations for 3-RPR manipulators using extrinsic metrics*, §6.3) in a
//! normalised frame, their seed stage, chains, self-check, windows and ab-initio
//! start files.

pub mod ab_initio;
pub mod chain;
pub mod curve;
mod motion_route;
pub mod seed;
pub mod self_check;
pub mod window;
