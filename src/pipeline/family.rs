//! A parametrised family of polynomial systems over a motion, as the sweep engine
//! ([`super::sweep`]) sees it: the coefficient-parameter homotopy setting of Morgan
//! and Sommese (*Coefficient-parameter polynomial continuation*, Appl. Math. Comput.
//! 29, 1989), in the form of HomotopyContinuation.jl's parameter homotopies
//! (Breiding and Timme, *HomotopyContinuation.jl: a package for homotopy continuation
//! in Julia*, 2018): a family `F(x; p)` of square systems, a generic parameter
//! point with its solutions (the start set), and parameter points to track them to.
//!
//! A mechanism (3-RPR, 3-RRR) is an instance: its sub-problems are the family's
//! problems, all sharing one motion; the seed points are points of the complexified
//! motion (Kapilavai and Nawratil, *Singularity distance computations for 3-RPR
//! manipulators using extrinsic metrics*, Eqs. 65–66).

use crate::C64;
use crate::pipeline::sweep::ProjectiveTwin;
use crate::system::CompiledSystem;

/// A family of parametrised systems, one per problem, sharing one motion: what the
/// seed stage of the sweep engine (`seed_family`) needs.
pub trait Family: Sync {
    /// What identifies a seed point (besides its parameters), kept with the solutions
    /// that the poses start from.
    type Seed: Clone + Send;

    /// Number of problems (sub-problems of the mechanism).
    fn problems(&self) -> usize;

    /// Name of problem `problem` (in failure reports).
    fn name(&self, problem: usize) -> String;

    /// The compiled system `F(x; p)` of problem `problem`.
    fn system(&self, problem: usize) -> &CompiledSystem;

    /// The generic parameter point of problem `problem` and its solutions (the start
    /// set, in the system's coordinates): every finite isolated solution of a generic
    /// parameter, so their count is the family's generic count.
    fn generic_start(&self, problem: usize) -> (&[C64], &[Vec<C64>]);

    /// Independent seed point `point` (`0` the common one) of problem `problem` and
    /// its parameters.
    fn seed(&self, problem: usize, point: usize) -> (Self::Seed, Vec<C64>);

    /// Number of leading parameters that the motion moves (a detour perturbs only
    /// these; the rest, e.g. a rigid part's shape constants, are fixed by the design).
    fn moving_parameters(&self) -> usize;

    /// The random stream of detour `attempt` (`≥ 1`) of a route whose own stream is
    /// `stream`.
    fn detour_stream(&self, stream: u64, attempt: usize) -> u64 {
        stream + attempt as u64
    }

    /// Problem `problem` in a second formulation, where the paths a route sends to
    /// infinity or loses are checked once more (`None`: no twin).
    fn twin(&self, _problem: usize) -> Option<&dyn ProjectiveTwin> {
        None
    }
}

/// The scale `s` of a mechanism's normalised frame `K ↦ (K − c)/s` (3-RPR and 3-RRR
/// alike): the root of `mean_square_spread`, the mean squared distance of the
/// configuration's points from their centroid `c`; 1 if that is not a positive number
/// (designs are validated non-degenerate; the guard keeps the frame invertible anyway).
pub fn frame_scale(mean_square_spread: f64) -> f64 {
    let scale = mean_square_spread.sqrt();
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        1.0
    }
}
