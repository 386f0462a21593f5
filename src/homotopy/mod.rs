//! Homotopy continuation: homotopies, predictor–corrector path tracking, endgame and
//! path classification, start systems, monodromy with trace test, and the parallel
//! `solve`.
//!
//! Read in this order: [`linalg`] (the LU of the hot loop), [`homotopies`] (what is
//! tracked), [`start`] (total-degree start systems), [`multihomogeneous`]
//! (multi-homogeneous start systems and the automatic choice), [`polyhedral`]
//! (polyhedral start systems with the mixed volume of paths), [`tracker`] (predictor, corrector,
//! step control, endgame, classification), [`solve`] (many paths in parallel, with
//! re-runs of failed paths), [`monodromy`] (solutions of parametric families from one
//! start pair, certified by a trace test).

pub mod chart;
pub mod conjugates;
mod divergence;
pub mod homotopies;
pub mod linalg;
pub mod monodromy;
pub mod multihomogeneous;
pub mod newton;
pub mod polyhedral;
pub mod refine;
pub mod solve;
pub mod start;
#[cfg(test)]
pub(crate) mod test_support;
pub mod tracker;

pub use homotopies::{
    Homotopy, ParameterHomotopy, ParameterPath, PathParameterHomotopy, PolylineParameterHomotopy,
    PolylinePath, StraightLineHomotopy,
};
pub use linalg::{DdLuWorkspace, LuWorkspace};
pub use monodromy::{
    ConstantShift, FiberCompletion, IncidenceSlice, MonodromyOptions, MonodromyResult,
    TraceCertificate, complete_fiber, monodromy_solve, solve_by_monodromy, trace_test,
};
pub use multihomogeneous::{
    MultiHomogeneousStartSystem, StartChoice, StartRequest, VariablePartition, choose_start_system,
    solve_multihomogeneous,
};
pub use newton::{NewtonBuffers, NewtonOptions, NewtonOutcome, NewtonStop, newton};
pub use polyhedral::{
    PolyhedralSolve, PolyhedralStartSystem, Supports, polyhedral_if_fewer_paths,
    solve_from_polyhedral_start, solve_polyhedral,
};
pub use refine::{
    Refinement, accuracy_at_condition, contains_point, distinct_nonsingular_roots, group_roots,
    newton_refine, same_point, same_root,
};
pub use solve::{
    HomotopyError, STALLED_NEAR_ROOTS, SolveOptions, SolveResult, SolveSummary,
    solve_parameter_homotopy, solve_total_degree, solve_with_homotopy,
};
pub use start::TotalDegreeStartSystem;
pub use tracker::{
    EndgameOptions, FailureReason, HOMOGENEOUS_ZERO, PathResult, PathStatus, PrecisionOptions,
    StepOptions, Tracker, TrackerOptions,
};
