//! The polyhedral start system: the random-coefficient system `Q` on the supports
//! (with the origin added, so that roots with zero coordinates are counted), a generic
//! random lifting, its mixed cells, and per cell the binomial start system and the
//! cell homotopy (Huber and Sturmfels, "A polyhedral method for solving sparse
//! polynomial systems", Math. Comp. 1995; Li and Wang, "The BKK root count in C^n",
//! Math. Comp. 1996).
//!
//! Path `index` is decoded by the cells' cumulative volumes into (cell, root of the
//! cell's binomial system), so any subset of paths is generated independently.

use super::binomial::{BinomialError, BinomialSystem};
use super::cell_homotopy::CellHomotopy;
use super::cells::{CellError, MixedSubdivision, mixed_cells_bounded};
use super::random_system::RandomCoefficientSystem;
use super::supports::{Supports, random_lifting};
use crate::C64;

/// Lifting values are drawn from `0..LIFTING_RANGE`: wide enough that ties (a
/// non-generic lifting, redrawn with the whole enumeration) are rare — at `2^10`
/// virasoro needed 5 liftings and katsura8's cells lost 4 paths — and small enough
/// that the exact `i128` arithmetic of the cells cannot overflow for the supports
/// met in practice (an overflow is reported, not wrapped). The cell homotopies are
/// tracked in logarithmic time, so the size of the powers costs few steps.
pub const LIFTING_RANGE: u64 = 1 << 22;
/// Liftings tried before giving up on genericity.
const MAX_LIFTINGS: u64 = 16;
/// Random streams of the seed: liftings use `LIFTING_STREAM + attempt`.
const COEFFICIENT_STREAM: u64 = 0x901f;
const LIFTING_STREAM: u64 = 0x9020;

/// Errors building a polyhedral start system.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PolyhedralError {
    /// The mixed-cell enumeration failed.
    #[error(transparent)]
    Cells(#[from] CellError),
    /// A binomial start system could not be solved.
    #[error(transparent)]
    Binomial(#[from] BinomialError),
    /// The mixed volume is zero: no isolated roots in `C^n`.
    #[error("the mixed volume is zero")]
    ZeroMixedVolume,
}

/// Everything a polyhedral homotopy run needs.
#[derive(Clone, Debug)]
pub struct PolyhedralStartSystem {
    supports: Supports,
    system: RandomCoefficientSystem,
    subdivision: MixedSubdivision,
    binomials: Vec<BinomialSystem>,
    /// Cumulative volumes: cell c owns paths `offsets[c]..offsets[c + 1]`.
    offsets: Vec<u64>,
    liftings_tried: u64,
    /// The seed of the random choices (for [`PolyhedralStartSystem::relifted`]).
    seed: u64,
}

impl PolyhedralStartSystem {
    /// The start system of the system with supports `supports` (the origin is added to
    /// each), random choices from `seed`.
    pub fn new(supports: &Supports, seed: u64) -> Result<Self, PolyhedralError> {
        Self::within_budget(supports, seed, usize::MAX)
    }

    /// [`PolyhedralStartSystem::new`], giving up with [`CellError::OverBudget`] when the
    /// mixed-cell search of a lifting passes `max_lp_tests` LP feasibility tests.
    pub fn within_budget(
        supports: &Supports,
        seed: u64,
        max_lp_tests: usize,
    ) -> Result<Self, PolyhedralError> {
        Self::within_bounds(supports, seed, max_lp_tests, u128::MAX)
    }

    /// [`PolyhedralStartSystem::within_budget`], giving up with
    /// [`CellError::OverVolume`] too once the mixed cells found have a total volume
    /// above `max_volume`.
    pub fn within_bounds(
        supports: &Supports,
        seed: u64,
        max_lp_tests: usize,
        max_volume: u128,
    ) -> Result<Self, PolyhedralError> {
        let supports = supports.with_origin();
        let system = RandomCoefficientSystem::new(&supports, seed, COEFFICIENT_STREAM);
        Self::lifted(
            supports,
            system,
            seed,
            LIFTING_STREAM,
            (max_lp_tests, max_volume),
        )
    }

    /// The same random-coefficient system `Q` with the mixed cells of a fresh random
    /// lifting (lifting number `relifting`, from 1, of this seed): its cell homotopies
    /// reach the same roots of `Q` along other paths, so roots of `Q` that the first
    /// stage lost on one lifting can be found on another.
    pub fn relifted(&self, relifting: u64) -> Result<Self, PolyhedralError> {
        Self::lifted(
            self.supports.clone(),
            self.system.clone(),
            self.seed,
            LIFTING_STREAM + relifting * MAX_LIFTINGS,
            (usize::MAX, u128::MAX),
        )
    }

    /// The start system of `Q` = `system` on `supports` (the origin added) with the
    /// first generic lifting of the seed's streams `first_stream`, `first_stream + 1`, …
    /// within `(max_lp_tests, max_volume)` ([`mixed_cells_bounded`]).
    fn lifted(
        supports: Supports,
        system: RandomCoefficientSystem,
        seed: u64,
        first_stream: u64,
        (max_lp_tests, max_volume): (usize, u128),
    ) -> Result<Self, PolyhedralError> {
        let mut attempt = 0;
        let subdivision = loop {
            let lifting = random_lifting(&supports, seed, first_stream + attempt, LIFTING_RANGE);
            attempt += 1;
            match mixed_cells_bounded(&supports, &lifting, max_lp_tests, max_volume) {
                Err(CellError::NonGenericLifting) if attempt < MAX_LIFTINGS => continue,
                other => break other?,
            }
        };
        if subdivision.mixed_volume == 0 {
            return Err(PolyhedralError::ZeroMixedVolume);
        }
        let n = supports.num_variables();
        let terms = system.terms();
        let coefficients = system.coefficients();
        let mut binomials = Vec::with_capacity(subdivision.cells.len());
        let mut offsets = vec![0u64];
        for cell in &subdivision.cells {
            let mut exponents = Vec::with_capacity(n * n);
            let mut rhs = Vec::with_capacity(n);
            for (i, &(p, q)) in cell.pairs.iter().enumerate() {
                let points = supports.support(i);
                exponents.extend(points[q].iter().zip(&points[p]).map(|(a, b)| a - b));
                let first = terms.equation(i).start;
                rhs.push(-coefficients[first + p] / coefficients[first + q]);
            }
            let binomial = BinomialSystem::new(n, &exponents, &rhs)?;
            debug_assert_eq!(binomial.solution_count(), Some(cell.volume));
            offsets.push(offsets.last().copied().unwrap_or(0) + cell.volume);
            binomials.push(binomial);
        }
        Ok(PolyhedralStartSystem {
            supports,
            system,
            subdivision,
            binomials,
            offsets,
            liftings_tried: attempt,
            seed,
        })
    }

    /// The supports with the origin added.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// The random-coefficient system `Q` (the start system of the second stage).
    pub fn system(&self) -> &RandomCoefficientSystem {
        &self.system
    }

    /// The mixed cells.
    pub fn subdivision(&self) -> &MixedSubdivision {
        &self.subdivision
    }

    /// The mixed volume of the supports with the origin: the number of paths.
    pub fn mixed_volume(&self) -> u128 {
        self.subdivision.mixed_volume
    }

    /// Number of liftings drawn (more than one when one was not generic).
    pub fn liftings_tried(&self) -> u64 {
        self.liftings_tried
    }

    /// The homotopy of cell c.
    pub fn cell_homotopy(&self, c: usize) -> CellHomotopy<'_> {
        CellHomotopy::new(&self.system, &self.subdivision.cells[c].gaps)
    }

    /// Cell of path `index` and the index of its root in the cell.
    pub fn locate(&self, index: u64) -> (usize, u64) {
        let c = self.offsets.partition_point(|&o| o <= index) - 1;
        (c, index - self.offsets[c])
    }

    /// Start point of path `index` (a root of its cell's binomial system) into `y`.
    pub fn start_solution(&self, index: u64, y: &mut [C64]) {
        let (c, k) = self.locate(index);
        self.binomials[c].solution(k, y);
    }
}
