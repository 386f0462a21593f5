//! docs/theory.md §11.3 redundancy resolution: trajectories, quintic profile, objective,
//! optimiser.

mod optimize_support;
use optimize_support::small_genetic_options;
use singdist::analysis::redundancy::{
    Aggregate, RedundancyError, RedundancyProblem, Scheme, TaskIndex, Trajectory, quintic, resolve,
};
use singdist::mechanism::prrr::{PrrrDesign, WorkingMode};
use singdist::optimize::{GeneticOptions, LocalOptions};

/// The problem of `design` with every working mode `+`.
fn problem_of(
    design: PrrrDesign,
    (trajectory, scheme, index, aggregate): (Trajectory, Scheme, TaskIndex, Aggregate),
    samples: usize,
) -> Result<RedundancyProblem, RedundancyError> {
    RedundancyProblem::new(
        design,
        trajectory,
        scheme,
        index,
        aggregate,
        [WorkingMode::Plus; 3],
        samples,
    )
}

/// The problem of Farias Filho et al.'s design, 41 samples.
fn problem(
    trajectory: Trajectory,
    scheme: Scheme,
    index: TaskIndex,
    aggregate: Aggregate,
) -> RedundancyProblem {
    let task = (trajectory, scheme, index, aggregate);
    problem_of(PrrrDesign::farias2021(), task, 41).unwrap()
}

/// The error message of parsing `text` as a `T`.
fn parse_error<T: std::str::FromStr>(text: &str) -> String
where
    T::Err: std::fmt::Display,
{
    text.parse::<T>().err().expect("a parse error").to_string()
}

fn small_ga(seed: u64) -> GeneticOptions {
    small_genetic_options(16, 8, seed)
}

#[test]
fn trajectories_match_spec_d3() {
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    let p = Trajectory::Line.pose_at(0.0);
    assert!(close(p.x, -0.02) && close(p.y, -0.09) && close(p.alpha, 0.2));
    let p = Trajectory::Line.pose_at(1.0);
    assert!(close(p.x, 0.02) && close(p.y, 0.09) && close(p.alpha, 0.0));
    for s in [0.0, 0.13, 0.5, 1.0] {
        let p = Trajectory::Circle.pose_at(s);
        assert!(close(p.x.hypot(p.y), 0.05) && close(p.alpha, 0.5));
    }
    let p = Trajectory::Circle.pose_at(0.0);
    assert!(close(p.x, 0.0) && close(p.y, 0.05));
    let p = Trajectory::Spiral.pose_at(0.0);
    assert!(close(p.x, 0.0) && close(p.y, 0.01));
    let p = Trajectory::Spiral.pose_at(1.0);
    assert!(close(p.x, 0.0) && close(p.y, 0.05), "{p:?}");
    // Radius grows linearly with the turn parameter.
    let p = Trajectory::Spiral.pose_at(0.5 + 1.0 / 24.0);
    assert!(close(p.x.hypot(p.y), 0.01 + 0.04 / 6.0 * 3.25));
    for (s, x, y) in [
        (0.0, -0.06, -0.06),
        (0.25, 0.06, -0.06),
        (0.5, 0.06, 0.06),
        (0.75, -0.06, 0.06),
        (1.0, -0.06, -0.06),
        (0.125, 0.0, -0.06),
    ] {
        let p = Trajectory::Square.pose_at(s);
        assert!(
            close(p.x, x) && close(p.y, y) && close(p.alpha, 0.3),
            "{s}: {p:?}"
        );
    }
}

#[test]
fn quintic_profile_has_zero_end_derivatives() {
    assert_eq!(quintic(0.0), 0.0);
    assert!((quintic(1.0) - 1.0).abs() < 1e-15);
    assert!((quintic(0.5) - 0.5).abs() < 1e-15);
    let h = 1e-4;
    for s in [0.0, 1.0] {
        let d1 = (quintic(s + h) - quintic(s - h)) / (2.0 * h);
        let d2 = (quintic(s + h) - 2.0 * quintic(s) + quintic(s - h)) / (h * h);
        assert!(d1.abs() < 1e-6 && d2.abs() < 1e-3, "{s}: {d1} {d2}");
    }
    // Continuous positioning with δ_o = δ_f equals prepositioning.
    let [pre, cont] = [Scheme::Prepositioning, Scheme::Continuous]
        .map(|scheme| problem(Trajectory::Circle, scheme, TaskIndex::Nsir, Aggregate::Mean));
    let d = [0.03, -0.05, 0.01];
    let dd = [0.03, -0.05, 0.01, 0.03, -0.05, 0.01];
    assert!((pre.objective(&d) - cont.objective(&dd)).abs() < 1e-15);
    assert_eq!(
        cont.delta_at(&[0.0, 0.0, 0.0, 0.1, 0.2, -0.1], 40),
        [0.1, 0.2, -0.1]
    );
}

#[test]
fn objective_is_mean_or_min_and_zero_when_unreachable() {
    let [mean, min] = [Aggregate::Mean, Aggregate::Min].map(|aggregate| {
        problem(
            Trajectory::Square,
            Scheme::Prepositioning,
            TaskIndex::Lci,
            aggregate,
        )
    });
    let d = [0.01, 0.02, -0.01];
    let stats = mean.stats(TaskIndex::Lci, &d);
    assert!((mean.objective(&d) - stats.mean).abs() < 1e-15);
    assert!((min.objective(&d) - stats.min).abs() < 1e-15);
    assert!(stats.min <= stats.mean && stats.mean <= stats.max && stats.max <= 1.0);
    // Guides moved out of reach (a = 0.6 > h + 0.1 + l1 + l2): every sample unreachable, F = 0.
    let mut far_design = PrrrDesign::farias2021();
    far_design.a = 0.6;
    for aggregate in [Aggregate::Mean, Aggregate::Min] {
        let task = (
            Trajectory::Square,
            Scheme::Prepositioning,
            TaskIndex::Nsir,
            aggregate,
        );
        let p = problem_of(far_design.clone(), task, 41).unwrap();
        assert_eq!(p.unreachable_samples(&d), 41);
        assert_eq!(p.objective(&d), 0.0);
    }
    // Partly unreachable (a = 0.42): unreachable samples contribute exactly 0 to the mean.
    let mut edge = PrrrDesign::farias2021();
    edge.a = 0.42;
    let task = (
        Trajectory::Square,
        Scheme::Prepositioning,
        TaskIndex::Nsir,
        Aggregate::Mean,
    );
    let p = problem_of(edge, task, 41).unwrap();
    let zero = [0.0; 3];
    let unreachable = p.unreachable_samples(&zero);
    assert!(unreachable > 0 && unreachable < 41, "{unreachable}");
    let reachable_sum: f64 = (0..41).map(|k| p.index_at(TaskIndex::Nsir, &zero, k)).sum();
    assert!((p.objective(&zero) - reachable_sum / 41.0).abs() < 1e-15);
    // A wrong variable count is rejected as −∞, never a panic.
    assert_eq!(mean.objective(&[0.0; 2]), f64::NEG_INFINITY);
}

/// The acceptance test of docs/theory.md §11.3: the optimised objective is at least the
/// one at δ = 0 and at 20 random feasible δ; the run repeats exactly for a fixed seed.
#[test]
fn optimised_objective_beats_zero_and_random_inputs_and_is_reproducible() {
    let local = LocalOptions {
        max_iterations: 20,
        ..LocalOptions::default()
    };
    let mut rng = singdist::random::seeded(99);
    for (trajectory, scheme, index) in [
        (Trajectory::Line, Scheme::Prepositioning, TaskIndex::Lci),
        (Trajectory::Circle, Scheme::Continuous, TaskIndex::Nsir),
        (Trajectory::Square, Scheme::Prepositioning, TaskIndex::Nsir),
        (Trajectory::Spiral, Scheme::Continuous, TaskIndex::Lci),
    ] {
        let p = problem(trajectory, scheme, index, Aggregate::Mean);
        let r = resolve(&p, &small_ga(5), &local, 1).unwrap();
        assert!(
            r.objective >= r.objective_at_zero,
            "{trajectory:?}: {} < {}",
            r.objective,
            r.objective_at_zero
        );
        assert!((p.objective(&r.variables) - r.objective).abs() < 1e-12);
        let bounds = p.bounds();
        for v in &r.variables {
            assert!(*v >= bounds[0].0 && *v <= bounds[0].1);
        }
        let mut feasible = 0;
        while feasible < 20 {
            let x: Vec<f64> = bounds
                .iter()
                .map(|&(lo, hi)| singdist::random::uniform(&mut rng, lo, hi))
                .collect();
            if p.unreachable_samples(&x) > 0 {
                continue;
            }
            feasible += 1;
            let f = p.objective(&x);
            assert!(
                r.objective >= f,
                "{trajectory:?} {scheme:?} {index:?}: optimum {} < random {f} at {x:?}",
                r.objective
            );
        }
        // Stats of the optimised index agree with the objective.
        let s = match index {
            TaskIndex::Lci => r.lci,
            TaskIndex::Nsir => r.nsir,
        };
        assert!((s.mean - r.objective).abs() < 1e-12);
        // The profile reproduces the statistics and the δ bounds.
        let profile = p.profile(&r.variables);
        assert_eq!(profile.len(), 41);
        let mean_nsir = profile.iter().map(|q| q.nsir.unwrap_or(0.0)).sum::<f64>() / 41.0;
        assert!((mean_nsir - r.nsir.mean).abs() < 1e-12);
        assert_eq!(profile[40].pose, trajectory.pose_at(1.0));
        // Reproducible.
        let again = resolve(&p, &small_ga(5), &local, 1).unwrap();
        assert_eq!(again.variables, r.variables);
        assert_eq!(again.genetic.history, r.genetic.history);
    }
}

#[test]
fn names_parse_and_bad_names_are_errors() {
    assert_eq!("spiral".parse::<Trajectory>().unwrap(), Trajectory::Spiral);
    assert_eq!("Continuous".parse::<Scheme>().unwrap(), Scheme::Continuous);
    assert_eq!("nsir".parse::<TaskIndex>().unwrap(), TaskIndex::Nsir);
    assert!(parse_error::<Trajectory>("zigzag").contains("trajectory"));
    assert!(parse_error::<Scheme>("x").contains("scheme"));
    assert!(parse_error::<TaskIndex>("gci").contains("index"));
    assert!("median".parse::<Aggregate>().is_err());
    let task = (
        Trajectory::Line,
        Scheme::Continuous,
        TaskIndex::Lci,
        Aggregate::Mean,
    );
    let bad = problem_of(PrrrDesign::farias2021(), task, 1);
    assert!(bad.unwrap_err().to_string().contains("samples"));
}
