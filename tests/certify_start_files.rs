//! Krawczyk certificates of the shipped start solutions: at the start file's (complex,
//! generic) parameters every stored critical point of every sub-problem, on the generic
//! stratum and on every stratum with a shipped file (rigid parts on a line), is proved
//! to be an exact solution in its own box, and the boxes are pairwise disjoint, so the
//! file holds as many distinct solutions as it claims.

use singdist::C64;
use singdist::certify::krawczyk::{Realness, certify_solutions};
use singdist::pipeline::curve::default_start_solutions;
use singdist::problem::{Coordinates, LagrangeProblem};
use singdist::problem::{ProblemId, Stratum};

/// The start file of `problem` and its parameter point, in the problem's order.
fn start_point(
    problem: &LagrangeProblem,
) -> (
    std::sync::Arc<singdist::pipeline::start_file::StartSolutions>,
    Vec<C64>,
) {
    let start = default_start_solutions(problem.id(), problem.stratum()).expect("start file");
    assert_eq!(
        start.parameters.len(),
        problem.parameter_names().len(),
        "{}",
        start.problem
    );
    let parameters = problem
        .parameter_names()
        .iter()
        .map(|name| start.parameters[name])
        .collect();
    (start, parameters)
}

#[test]
fn every_start_solution_is_certified_and_distinct() {
    let mut report = Vec::new();
    let mut failed = Vec::new();
    let mut problems = Vec::new();
    for id in ProblemId::all() {
        problems.extend(LagrangeProblem::new(id));
        for stratum in Stratum::special(id) {
            if default_start_solutions(id, stratum).is_ok() {
                let representation = (Coordinates::Cartesian, Default::default());
                problems.push(LagrangeProblem::new_on(id, representation, stratum).unwrap());
            }
        }
    }
    let on_strata = problems
        .iter()
        .filter(|p| !p.stratum().is_generic())
        .count();
    assert!(on_strata >= 6, "{on_strata} start files on special strata");
    for problem in &problems {
        let id = problem.id();
        let (start, parameters) = start_point(problem);
        assert_eq!(start.variables, problem.variable_names(), "{}", id.name());
        assert_eq!(start.stratum, problem.stratum(), "{}", start.problem);
        let result = certify_solutions(problem.evaluator(), &parameters, &start.solutions)
            .expect("square system");
        let widest = result
            .boxes
            .iter()
            .flatten()
            .fold(0.0f64, |m, b| m.max(b.radius));
        // Complex parameters: realness is not decided.
        assert!(
            result
                .boxes
                .iter()
                .flatten()
                .all(|b| b.realness != Realness::Real),
            "{}",
            id.name()
        );
        report.push(format!(
            "{}: {} of {} certified, {} overlapping pairs, widest box {:.1e}",
            start.problem,
            result.distinct(),
            start.solutions.len(),
            result.overlapping.len(),
            widest
        ));
        if !result.all_distinct() || result.distinct() != start.solutions.len() {
            failed.push(report.last().unwrap().clone());
            for (k, b) in result.boxes.iter().enumerate() {
                if b.is_none() {
                    let norm = start.solutions[k]
                        .iter()
                        .fold(0.0f64, |m, v| m.max(v.norm()));
                    failed.push(format!("  solution {k} uncertified, |x|∞ = {norm:.2e}"));
                }
            }
        }
    }
    println!("{}", report.join("\n"));
    assert!(failed.is_empty(), "{}", failed.join("\n"));
    assert!(report.len() >= 9, "too few sub-problems: {report:?}");
}

#[test]
fn configuration_enclosure_contains_the_configuration() {
    use singdist::system::interval::ComplexInterval;
    for id in ProblemId::all() {
        for coordinates in [Coordinates::Cartesian, Coordinates::Isotropic] {
            let Ok(problem) = LagrangeProblem::new_in(id, coordinates) else {
                continue;
            };
            let (start, parameters) = start_point(&problem);
            let x = &problem.from_cartesian(&start.solutions[0]);
            let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
            let k_prime = problem.configuration(x, &parameters, &mut work);
            let boxes: Vec<ComplexInterval> =
                x.iter().map(|&v| ComplexInterval::point(v)).collect();
            let p: Vec<ComplexInterval> = parameters
                .iter()
                .map(|&v| ComplexInterval::point(v))
                .collect();
            let enclosure = problem.configuration_enclosure(&boxes, &p);
            for (value, b) in k_prime.iter().zip(&enclosure) {
                assert!(
                    b.re.lo <= value.re
                        && value.re <= b.re.hi
                        && b.im.lo <= value.im
                        && value.im <= b.im.hi,
                    "{} {coordinates:?}: {value} not in {b:?}",
                    id.name()
                );
            }
        }
    }
}

#[test]
fn interval_metric_encloses_the_metric() {
    use singdist::metric::Metric;
    use singdist::system::interval::Interval;
    let k: [f64; 12] = std::array::from_fn(|i| (i as f64 * 0.37).sin());
    let kp: [f64; 12] = std::array::from_fn(|i| (i as f64 * 0.91).cos());
    for metric in Metric::all() {
        let d2 = metric.distance_sq(&k, &kp);
        let ki = k.map(Interval::point);
        let kpi = kp.map(Interval::point);
        let e = metric.distance_sq(&ki, &kpi);
        assert!(
            e.lo <= d2 && d2 <= e.hi,
            "{}: {d2} not in {e:?}",
            metric.name()
        );
    }
}

#[test]
fn interval_values_enclose_sampled_values_and_agree_with_the_jacobian_tape() {
    use singdist::system::Evaluator;
    use singdist::system::interval::ComplexInterval;
    for id in ProblemId::all() {
        let Ok(problem) = LagrangeProblem::new(id) else {
            continue;
        };
        let start = default_start_solutions(id, Stratum::GENERIC).expect("start file");
        let parameters: Vec<C64> = problem
            .parameter_names()
            .iter()
            .map(|name| start.parameters[name])
            .collect();
        let system = problem.evaluator();
        let (n, m) = (system.num_variables(), system.num_equations());
        let center = &start.solutions[0];
        let radius = 1e-3;
        let x = ComplexInterval::boxes(center, radius);
        let p: Vec<ComplexInterval> = parameters
            .iter()
            .map(|&v| ComplexInterval::point(v))
            .collect();
        let mut values = vec![ComplexInterval::default(); m];
        system.evaluate_interval(&x, &p, &mut values);
        let mut both = vec![ComplexInterval::default(); m];
        let mut jac = vec![ComplexInterval::default(); m * n];
        system.evaluate_interval_with_jacobian(&x, &p, &mut both, &mut jac);
        let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); m];
        for sample in 0..8 {
            // Corners and inner points of the box.
            let t = [-1.0, 1.0, 0.5, -0.25, 0.9, -0.9, 0.0, 0.3][sample];
            let point: Vec<C64> = center
                .iter()
                .enumerate()
                .map(|(i, &c)| {
                    c + C64::new(t, if i % 2 == 0 { -t } else { t * 0.5 }) * radius * 0.999
                })
                .collect();
            system.evaluate(&point, &parameters, &mut work, &mut f);
            for i in 0..m {
                for (b, what) in [(&values[i], "values"), (&both[i], "values+jacobian")] {
                    let tol = 1e-9 * (1.0 + f[i].norm());
                    assert!(
                        b.re.lo - tol <= f[i].re
                            && f[i].re <= b.re.hi + tol
                            && b.im.lo - tol <= f[i].im
                            && f[i].im <= b.im.hi + tol,
                        "{}: {what} F_{i} = {} not in {b:?}",
                        id.name(),
                        f[i]
                    );
                }
            }
        }
    }
}
