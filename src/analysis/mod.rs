//! Mechanism studies that combine kinematic indices with the generic optimisers: the layer
//! above [`crate::index`] and [`crate::optimize`], so that neither of those depends on the
//! other (`analysis → {index, optimize, mechanism}`).
//!
//! * [`redundancy`]: redundancy resolution of the 3-PRRR along a task, maximising LCI or NSIR
//!   (docs/theory.md §11.3; Farias Filho et al. (2021) §4).
//! * [`actuation_design`]: GA optimisation of the 3-RRR design vector `(a, b, c)` for the GCI
//!   of one actuation scheme (docs/theory.md §11.5; Ramana Babu et al. §V.B).

pub mod actuation_design;
pub mod redundancy;
