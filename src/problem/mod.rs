//! The Lagrangian sub-problems of every metric (SPEC A.6), built with [`crate::system`].
