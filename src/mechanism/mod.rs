//! Planar parallel manipulators: 3-RPR, 3-RRR and 3-PRRR designs, poses, motions, configurations, inverse kinematics and Jacobians.

pub mod rpr;

pub mod prrr;
pub mod rrr;
