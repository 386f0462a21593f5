//! Classic kinematic performance indices (SPEC Parts B and D), for comparison with metric singularity distances.

pub mod actuation;
pub mod map;
pub mod prrr;
pub mod rpr;
