//! Classic kinematic performance indices (docs/theory.md §9 and §11), for comparison with
//! metric singularity distances.

pub mod actuation;
pub mod map;
pub mod polynomial;
pub mod prrr;
pub mod rpr;
