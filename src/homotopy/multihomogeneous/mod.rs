//! Multi-homogeneous start systems: fewer paths than the total degree on systems whose
//! unknowns fall into groups of low degree (eigenvalue problems, bilinear and
//! multilinear systems, kinematic chains).
//!
//! [`bezout`] computes the m-homogeneous Bézout number of a variable partition,
//! [`partition`] searches the partition of least Bézout number, [`start`] builds the
//! linear-product start system with that many solutions, and [`choose_start_system`]
//! picks it over the total-degree start system only when it tracks strictly fewer
//! paths; [`solve_multihomogeneous`] tracks its paths with
//! [`super::solve::solve_with_homotopy`] (Morgan & Sommese, "A homotopy for solving
//! general polynomial systems that respects m-homogeneous structures", 1987).

pub mod bezout;
pub mod partition;
pub mod start;

pub use bezout::{
    BezoutError, BezoutTable, MonomialSupports, VariablePartition, multihomogeneous_bezout_number,
};
pub use partition::{PartitionChoice, PartitionSearchOptions, SearchMethod, best_partition};
pub use start::MultiHomogeneousStartSystem;

use super::solve::{
    HomotopyError, SolveOptions, SolveResult, check_length, check_square, check_target_parameters,
    solve_from_start_system,
};
use crate::C64;
use crate::system::Evaluator;

/// Most paths a solve run tracks.
const MAX_PATHS: u128 = 1 << 32;

/// Which start system `solve` uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartRequest {
    /// The multi-homogeneous start system of the best partition found when its Bézout
    /// number is strictly below the total degree, the total-degree one otherwise.
    Auto,
    /// The total-degree start system.
    TotalDegree,
    /// The multi-homogeneous start system of the best partition found (the one-group
    /// partition, a linear-product form of the total degree, when nothing beats it).
    MultiHomogeneous,
}

/// The start system chosen for a system.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StartChoice {
    /// Total degree; `search` holds the partition search when one ran.
    TotalDegree {
        /// Π d_i.
        paths: u128,
        /// The partition search (`None` when not run or the supports were unavailable).
        search: Option<PartitionChoice>,
    },
    /// Multi-homogeneous with the searched partition.
    MultiHomogeneous {
        /// The partition search; its `bezout_number` is the number of paths.
        search: PartitionChoice,
        /// The degree matrix of the partition (row-major, equations × groups).
        degrees: Vec<u32>,
    },
}

impl StartChoice {
    /// Paths the start system has.
    pub fn paths(&self) -> u128 {
        match self {
            StartChoice::TotalDegree { paths, .. } => *paths,
            StartChoice::MultiHomogeneous { search, .. } => search.bezout_number,
        }
    }
}

/// The total-degree Bézout number `Π d_i` (saturating at `u128::MAX`).
pub fn total_degree_paths(degrees: &[u32]) -> u128 {
    degrees
        .iter()
        .try_fold(1u128, |acc, &d| acc.checked_mul(d as u128))
        .unwrap_or(u128::MAX)
}

/// Chooses the start system for a square system with total degrees `degrees` and
/// monomial supports `supports` (`None` when the equations could not be expanded:
/// then only the total degree is available, and `MultiHomogeneous` is an error).
pub fn choose_start_system(
    degrees: &[u32],
    supports: Option<&MonomialSupports>,
    request: StartRequest,
    search_options: &PartitionSearchOptions,
) -> Result<StartChoice, HomotopyError> {
    let total = total_degree_paths(degrees);
    if request == StartRequest::TotalDegree {
        return Ok(StartChoice::TotalDegree {
            paths: total,
            search: None,
        });
    }
    let search = supports.and_then(|s| best_partition(s, search_options));
    match (request, search) {
        (StartRequest::MultiHomogeneous, None) => Err(HomotopyError::InvalidDegrees(
            "no multi-homogeneous structure: the equations could not be expanded".into(),
        )),
        (StartRequest::MultiHomogeneous, Some(search)) => {
            let degrees = supports
                .map(|s| s.degrees(&search.partition))
                .unwrap_or_default();
            Ok(StartChoice::MultiHomogeneous { search, degrees })
        }
        (_, Some(search)) if search.bezout_number < total => {
            let degrees = supports
                .map(|s| s.degrees(&search.partition))
                .unwrap_or_default();
            Ok(StartChoice::MultiHomogeneous { search, degrees })
        }
        (_, search) => Ok(StartChoice::TotalDegree {
            paths: total,
            search,
        }),
    }
}

/// Solves `F(x; p) = 0` (parameters fixed at `target_parameters`) with the homotopy
/// `(1 − t)·γ·G + t·F`, `G` the multi-homogeneous start system of `partition` and
/// `degrees` (row-major equations × groups, each at least the degree of the equation
/// in the group), γ and `G`'s coefficients random from `options.seed`. Tracks the
/// m-homogeneous Bézout number of paths in parallel, deterministically.
pub fn solve_multihomogeneous<F: Evaluator + ?Sized>(
    system: &F,
    partition: &VariablePartition,
    degrees: &[u32],
    target_parameters: &[C64],
    options: &SolveOptions,
) -> Result<SolveResult, HomotopyError> {
    check_square(system)?;
    let n = system.num_variables();
    check_length("partition", n, partition.num_variables())?;
    let m = partition.num_groups();
    check_length("degrees", n * m, degrees.len())?;
    check_target_parameters(system, target_parameters)?;
    if let Some(i) = (0..n).find(|&i| degrees[i * m..(i + 1) * m].iter().all(|&d| d == 0)) {
        return Err(HomotopyError::InvalidDegrees(format!(
            "equation {i} has degree 0 in every group"
        )));
    }
    let start = MultiHomogeneousStartSystem::new(partition.clone(), degrees.to_vec(), options.seed)
        .map_err(|e| HomotopyError::InvalidDegrees(e.to_string()))?;
    let count = start.path_count();
    if count > MAX_PATHS {
        return Err(HomotopyError::InvalidDegrees(
            "multi-homogeneous Bézout number too large".into(),
        ));
    }
    Ok(solve_from_start_system(
        &start,
        system,
        count as usize,
        |index, x| {
            start.start_solution(index as u128, x);
        },
        target_parameters,
        options,
        // A monomial's total degree is the sum of its group degrees.
        &(0..n)
            .map(|i| degrees[i * m..(i + 1) * m].iter().sum())
            .collect::<Vec<u32>>(),
    ))
}
