//! Test designs and helpers shared by the 3-RRR tests.
// Each test crate that includes this module uses part of it.
#![allow(dead_code)]

use singdist::mechanism::rpr::{Motion, MotionCoordinate};
use singdist::mechanism::rrr::*;
use singdist::pipeline::rrr::curve::{
    RrrCurveOptions, RrrCurveResult, compute_rrr_curve_at, default_rrr_start_solutions,
};

/// The curve of `trajectory` at the motion parameters `taus` with the default options
/// and start solutions.
pub fn curve_at(trajectory: &RrrTrajectory, taus: &[f64]) -> RrrCurveResult {
    compute_rrr_curve_at(
        trajectory,
        taus,
        &RrrCurveOptions::default(),
        &default_rrr_start_solutions,
    )
    .expect("curve")
}

/// The valid design with base joints `base`, link lengths `(proximal, distal)` and
/// platform joints `platform` (moving frame), points given as `[x, y]`.
pub fn design_of(
    base: [[f64; 2]; 3],
    (proximal, distal): ([f64; 3], [f64; 3]),
    platform: [[f64; 2]; 3],
) -> RrrDesign {
    let point = |[x, y]: [f64; 2]| Point::new(x, y);
    RrrDesign::new(base.map(point), proximal, distal, platform.map(point)).expect("design")
}

/// The working mode of each leg with base joints `bases`, elbows `elbows` and platform
/// joints `platform` (all in the fixed frame): the sign of `(B − O) × (C − B)`.
pub fn modes_of(bases: &[Point; 3], elbows: &[Point; 3], platform: &[Point; 3]) -> WorkingModes {
    [0, 1, 2].map(|i| {
        let b = elbows[i] - bases[i];
        let c = platform[i] - elbows[i];
        if b.x * c.y - b.y * c.x > 0.0 {
            ElbowMode::Positive
        } else {
            ElbowMode::Negative
        }
    })
}

/// Three design classes: the built-in example (equal links, a leg folding through its
/// base joint), an asymmetric design with unequal links, and a symmetric design with
/// unequal links and an oscillating orientation.
pub fn trajectories() -> Vec<RrrTrajectory> {
    let asymmetric = design_of(
        [[0.0, 0.0], [2.0, 0.2], [0.8, 1.9]],
        ([1.0, 0.9, 1.1], [0.9, 1.2, 1.0]),
        [[-0.2, -0.15], [0.3, -0.1], [0.05, 0.3]],
    );
    let symmetric = RrrDesign::symmetric(1.0, 0.3, 0.6, 0.7).expect("design");
    let mut oscillating = circular_translation(Point::new(0.05, 0.0), 0.1, 0.0, [0.0, 6.0]);
    if let Motion::Analytic(m) = &mut oscillating {
        m.phi = MotionCoordinate {
            polynomial: vec![0.1],
            cosines: vec![[0.3, 1.0, 0.0].into()],
        };
    }
    vec![
        example_trajectory(),
        RrrTrajectory::new(
            asymmetric,
            [
                ElbowMode::Positive,
                ElbowMode::Negative,
                ElbowMode::Positive,
            ],
            circular_translation(Point::new(1.0, 0.7), 0.1, 0.2, [0.0, 6.0]),
        )
        .expect("trajectory"),
        RrrTrajectory::new(symmetric, POSITIVE_MODES, oscillating).expect("trajectory"),
    ]
}
