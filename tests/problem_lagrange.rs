//! The Lagrange sub-problems of docs/theory.md §5: every metric's list, the unknown
//! counts of docs/theory.md §6, and start pairs whose configuration satisfies the
//! constraint.

use singdist::C64;
use singdist::mechanism::rpr;
use singdist::metric::{Metric, Part};
use singdist::pipeline::start_pair::find_start_pair;
use singdist::problem::{LagrangeProblem, ProblemId, SubProblem, subproblems_of};
use singdist::system::Evaluator;

fn metric(name: &str) -> Metric {
    name.parse().expect("valid metric name")
}

#[test]
fn each_metric_needs_the_subproblems_of_spec_a6() {
    let names = |m: &str| -> Vec<&'static str> {
        subproblems_of(metric(m)).iter().map(|k| k.name()).collect()
    };
    assert_eq!(names("plate/plate"), ["singularity", "all-collinear"]);
    assert_eq!(names("bars/plate"), ["singularity", "collinear-platform"]);
    assert_eq!(
        names("bars/bars"),
        ["singularity", "collinear-platform", "collinear-base"]
    );
    assert_eq!(
        names("bars/rigid"),
        ["singularity", "collinear-platform", "coincident-platform"]
    );
    assert_eq!(
        names("rigid/bars"),
        ["singularity", "collinear-base", "coincident-base"]
    );
    assert_eq!(names("rigid/rigid"), ["singularity", "all-collinear"]);
    assert_eq!(ProblemId::all().len(), 9 + 6 + 4 + 2);
    let id: ProblemId = "bars/rigid:collinear-platform".parse().unwrap();
    assert_eq!(id.file_stem(), "bars-rigid-collinear-platform");
    assert!("bars/rigid:collinear-base".parse::<ProblemId>().is_err());
    assert!("bars/rigid:nonsense".parse::<ProblemId>().is_err());
}

/// Unknown counts of docs/theory.md §6's table (and of our parameterisation of the others).
#[test]
fn unknown_counts_match_spec_a7() {
    for id in ProblemId::all() {
        let rigid_parts = [id.metric.platform, id.metric.base]
            .iter()
            .filter(|p| **p == Part::Rigid)
            .count();
        let expected = match id.subproblem {
            SubProblem::Singularity | SubProblem::CollinearPlatform | SubProblem::CollinearBase => {
                [13, 12, 11][rigid_parts]
            }
            // q, w, the free offsets, nu: plate/plate t2..t6; one rigid part: 3 free
            // offsets; rigid/rigid: t4, sigma and its multiplier rho.
            SubProblem::AllCollinear => [10, 8, 8][rigid_parts],
            SubProblem::CoincidentPlatform | SubProblem::CoincidentBase => 7,
        };
        let problem = LagrangeProblem::new(id).unwrap_or_else(|e| panic!("{id}: {e}"));
        assert_eq!(problem.evaluator().num_variables(), expected, "{id}");
        assert_eq!(problem.evaluator().num_equations(), expected, "{id}");
        // Shape constants per rigid part: (u, v, r2), or the line offsets (s2, s3).
        let per_rigid_part = if id.subproblem == SubProblem::AllCollinear {
            2
        } else {
            3
        };
        assert_eq!(
            problem.parameter_names().len(),
            12 + per_rigid_part
                * rigid_parts.min(match id.subproblem {
                    SubProblem::CoincidentPlatform | SubProblem::CoincidentBase => 1,
                    _ => 2,
                }),
            "{id}"
        );
    }
}

/// A start pair found by minimum-norm Gauss–Newton solves the system, and the
/// configuration it describes lies on the constraint variety (checked with the
/// independent numeric S, C_p, C_b of the mechanism module).
#[test]
fn start_pairs_lie_on_their_constraint_variety() {
    for id in ProblemId::all() {
        let Ok(problem) = LagrangeProblem::new(id) else {
            continue;
        };
        let pair = find_start_pair(problem.evaluator(), 11).unwrap_or_else(|e| panic!("{id}: {e}"));
        let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
        let mut f = vec![C64::new(0.0, 0.0); pair.x.len()];
        problem
            .evaluator()
            .evaluate(&pair.x, &pair.p, &mut work, &mut f);
        assert!(f.iter().all(|v| v.norm() < 1e-10), "{id}: residual");
        let k = problem.configuration(&pair.x, &pair.p, &mut work);
        let scale = k.iter().map(|v| v.norm()).fold(1.0, f64::max);
        let condition = match id.subproblem {
            SubProblem::Singularity => rpr::singularity_polynomial(&k),
            SubProblem::CollinearPlatform => rpr::collinearity_platform(&k),
            SubProblem::CollinearBase => rpr::collinearity_base(&k),
            SubProblem::AllCollinear => rpr::collinearity_platform(&k) + rpr::collinearity_base(&k),
            SubProblem::CoincidentPlatform => (k[6] - k[8]) + (k[9] - k[11]) * C64::new(0.0, 1.0),
            SubProblem::CoincidentBase => (k[0] - k[2]) + (k[3] - k[5]) * C64::new(0.0, 1.0),
        };
        assert!(
            condition.norm() < 1e-9 * scale.powi(4),
            "{id}: constraint {condition}"
        );
        // All-collinear with a rigid part: its anchors keep their signed offsets
        // (0, s2, s3) along the line, so |x2' - x1'|^2 = s2^2 and |x3' - x1'|^2 = s3^2
        // (complex squares: no conjugation).
        if id.subproblem == SubProblem::AllCollinear {
            let parameter = |name: &str| {
                let i = problem.parameter_names().iter().position(|n| n == name);
                i.map(|i| pair.p[i])
            };
            for (role, first) in [("base", 0), ("platform", 6)] {
                let (Some(s2), Some(s3)) = (
                    parameter(&format!("s2_{role}")),
                    parameter(&format!("s3_{role}")),
                ) else {
                    continue;
                };
                let square = |j: usize| {
                    let dx = k[first + 2 * j] - k[first];
                    let dy = k[first + 2 * j + 1] - k[first + 1];
                    dx * dx + dy * dy
                };
                assert!((square(1) - s2 * s2).norm() < 1e-9 * scale.powi(2), "{id}");
                assert!((square(2) - s3 * s3).norm() < 1e-9 * scale.powi(2), "{id}");
            }
        }
    }
}

/// The isotropic formulation (`(u, v) = (x + i y, x − i y)` per point) is the Cartesian
/// Lagrange system in other coordinates: at any point its equations are the chain rule
/// `∂Λ/∂u = (∂Λ/∂x − i ∂Λ/∂y)/√2`, `∂Λ/∂v = (∂Λ/∂x + i ∂Λ/∂y)/√2` of the Cartesian
/// ones (other equations equal), so every stored start solution converts to a solution,
/// with the same configuration K′.
#[test]
fn isotropic_systems_are_the_cartesian_ones_in_other_coordinates() {
    use singdist::pipeline::ab_initio::embedded_start_solutions;
    use singdist::problem::Coordinates;
    let half = C64::new(std::f64::consts::FRAC_1_SQRT_2, 0.0);
    let half_i = C64::new(0.0, std::f64::consts::FRAC_1_SQRT_2);
    let mut checked_solutions = 0;
    for id in ProblemId::all() {
        let cartesian = LagrangeProblem::new(id).unwrap();
        let isotropic = LagrangeProblem::new_in(id, Coordinates::Isotropic).unwrap();
        assert_eq!(isotropic.coordinates(), Coordinates::Isotropic);
        let n = cartesian.variable_names().len();
        assert_eq!(isotropic.variable_names().len(), n, "{id}");
        assert_eq!(
            isotropic.parameter_names(),
            cartesian.parameter_names(),
            "{id}"
        );
        // Which variables are the first coordinate of a point.
        let points: Vec<usize> = (0..n - 1)
            .filter(|&i| {
                let (a, b) = (
                    &isotropic.variable_names()[i],
                    &isotropic.variable_names()[i + 1],
                );
                a.ends_with('u') && b.ends_with('v') && a[..a.len() - 1] == b[..b.len() - 1]
            })
            .collect();
        assert!(!points.is_empty(), "{id}: no point variables");
        let m = cartesian.parameter_names().len();
        let x: Vec<C64> = (0..n)
            .map(|i| C64::new(0.3 + 0.17 * i as f64, -0.4 + 0.09 * (i * i) as f64))
            .collect();
        let p: Vec<C64> = (0..m)
            .map(|i| C64::new(1.1 - 0.13 * i as f64, 0.05 * i as f64))
            .collect();
        let y = isotropic.from_cartesian(&x);
        let back = isotropic.to_cartesian(&y);
        assert!(
            x.iter().zip(&back).all(|(a, b)| (a - b).norm() < 1e-14),
            "{id}"
        );
        let mut work =
            vec![C64::new(0.0, 0.0); cartesian.workspace_len().max(isotropic.workspace_len())];
        let mut fc = vec![C64::new(0.0, 0.0); n];
        let mut fi = vec![C64::new(0.0, 0.0); n];
        cartesian.evaluator().evaluate(&x, &p, &mut work, &mut fc);
        isotropic.evaluator().evaluate(&y, &p, &mut work, &mut fi);
        let mut expected = fc.clone();
        for &i in &points {
            expected[i] = half * fc[i] - half_i * fc[i + 1];
            expected[i + 1] = half * fc[i] + half_i * fc[i + 1];
        }
        let scale = 1.0 + fc.iter().map(|v| v.norm()).fold(0.0, f64::max);
        for (k, (a, b)) in fi.iter().zip(&expected).enumerate() {
            assert!(
                (a - b).norm() < 1e-12 * scale,
                "{id} equation {k}: {a} vs {b}"
            );
        }
        let kc = cartesian.configuration(&x, &p, &mut work);
        let ki = isotropic.configuration(&y, &p, &mut work);
        assert!(
            kc.iter()
                .zip(&ki)
                .all(|(a, b)| (a - b).norm() < 1e-12 * (1.0 + a.norm())),
            "{id}"
        );
        // Stored start solutions stay solutions.
        let Some(file) = embedded_start_solutions(id) else {
            continue;
        };
        let file = file.unwrap();
        let p0 = file.parameter_vector(isotropic.parameter_names()).unwrap();
        for solution in &file.solutions {
            isotropic.evaluator().evaluate(
                &isotropic.from_cartesian(solution),
                &p0,
                &mut work,
                &mut fi,
            );
            let size = 1.0 + solution.iter().map(|v| v.norm()).fold(0.0, f64::max);
            let residual = fi.iter().map(|v| v.norm()).fold(0.0, f64::max);
            assert!(residual < 1e-9 * size, "{id}: residual {residual:e}");
            checked_solutions += 1;
        }
    }
    assert!(
        checked_solutions > 600,
        "only {checked_solutions} start solutions checked"
    );
}

/// The Lagrange systems have real coefficients (in Cartesian coordinates), so
/// `F(x̄; p̄) = conj F(x; p)` with `x̄` the conjugate in the problem's coordinates
/// ([`LagrangeProblem::conjugate`]; in isotropic coordinates the equations are the
/// gradient in `(u, v)`, so `∂/∂u` and `∂/∂v` swap like the variables): at a real pose
/// the conjugate of a critical point is one. Checked at random complex points for
/// every sub-problem in both coordinate systems; in isotropic coordinates plain
/// entrywise conjugation must fail.
#[test]
fn conjugate_solutions_solve_the_conjugate_system() {
    use singdist::problem::Coordinates;
    for id in ProblemId::all() {
        for coordinates in [Coordinates::Cartesian, Coordinates::Isotropic] {
            let problem = LagrangeProblem::new_in(id, coordinates).unwrap();
            let (n, m) = (
                problem.variable_names().len(),
                problem.parameter_names().len(),
            );
            let x: Vec<C64> = (0..n)
                .map(|i| C64::new(0.3 + 0.17 * i as f64, -0.4 + 0.09 * (i * i) as f64))
                .collect();
            let p: Vec<C64> = (0..m)
                .map(|i| C64::new(1.1 - 0.13 * i as f64, 0.05 * i as f64 - 0.2))
                .collect();
            let conj = |v: &[C64]| v.iter().map(|z| z.conj()).collect::<Vec<_>>();
            let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
            let evaluate = |x: &[C64], p: &[C64], work: &mut [C64]| {
                let mut f = vec![C64::new(0.0, 0.0); n];
                problem.evaluator().evaluate(x, p, work, &mut f);
                f
            };
            let f = evaluate(&x, &p, &mut work);
            let scale = 1.0 + f.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            let g = evaluate(&problem.conjugate(&x), &conj(&p), &mut work);
            let error = problem
                .conjugate(&f)
                .iter()
                .zip(&g)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
            assert!(error < 1e-12 * scale, "{id} {coordinates:?}: {error:e}");
            if coordinates == Coordinates::Isotropic {
                let naive = evaluate(&conj(&x), &conj(&p), &mut work);
                let naive_error = problem
                    .conjugate(&f)
                    .iter()
                    .zip(&naive)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
                assert!(naive_error > 1e-6 * scale, "{id}: {naive_error:e}");
            }
        }
    }
}

/// The Fritz John form in a chart ([`Multipliers::Chart`]): every stored start
/// solution, converted (`λ₀ = 1/(c₀ + c·λ)`, multipliers scaled by `λ₀`), solves the
/// chart system with the same configuration K′, converts back to itself, and its
/// conjugate ([`LagrangeProblem::conjugate`], through the affine multipliers) solves
/// the conjugate system; the chart system is the affine one's gradient rows scaled by
/// `λ₀` (so a multiplier vector at infinity, `λ₀ = 0`, is a solution only where
/// `∇C`, `∇g` are dependent: a singular point of the constraint set).
#[test]
fn chart_multipliers_describe_the_same_critical_points() {
    use singdist::pipeline::ab_initio::embedded_start_solutions;
    use singdist::problem::{CHART_VARIABLE, Coordinates, Multipliers};
    let mut checked = 0;
    for id in ProblemId::all() {
        let Some(file) = embedded_start_solutions(id) else {
            continue;
        };
        let file = file.unwrap();
        let affine = LagrangeProblem::new_in(id, Coordinates::Isotropic).unwrap();
        let chart =
            LagrangeProblem::new_with(id, Coordinates::Isotropic, Multipliers::Chart).unwrap();
        let n = affine.variable_names().len();
        assert_eq!(chart.variable_names().len(), n + 1, "{id}");
        assert_eq!(chart.stored_solution_len(), n, "{id}");
        assert_eq!(chart.variable_names()[n], CHART_VARIABLE, "{id}");
        assert_eq!(chart.multipliers(), Multipliers::Chart);
        assert_eq!(chart.evaluator().homogenizing_variable(), Some(n), "{id}");
        assert_eq!(affine.evaluator().homogenizing_variable(), None, "{id}");
        let p = file.parameter_vector(chart.parameter_names()).unwrap();
        let conjugate_p: Vec<C64> = p.iter().map(|v| v.conj()).collect();
        let mut work = vec![C64::new(0.0, 0.0); chart.workspace_len().max(affine.workspace_len())];
        let mut f = vec![C64::new(0.0, 0.0); n + 1];
        for solution in &file.solutions {
            let x = chart.from_cartesian(solution);
            assert_eq!(x.len(), n + 1);
            let size = 1.0 + x.iter().map(|v| v.norm()).fold(0.0, f64::max);
            chart.evaluator().evaluate(&x, &p, &mut work, &mut f);
            let residual = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
            assert!(residual < 1e-9 * size, "{id}: chart residual {residual:e}");
            let back = chart.to_cartesian(&x);
            let scale = 1.0 + solution.iter().map(|v| v.norm()).fold(0.0, f64::max);
            assert!(
                back.iter()
                    .zip(solution)
                    .all(|(a, b)| (a - b).norm() < 1e-12 * scale),
                "{id}: round trip"
            );
            let y = affine.from_cartesian(solution);
            let (ka, kc) = (
                affine.configuration(&y, &p, &mut work),
                chart.configuration(&x, &p, &mut work),
            );
            assert!(
                ka.iter()
                    .zip(&kc)
                    .all(|(a, b)| (a - b).norm() < 1e-12 * scale),
                "{id}: configuration"
            );
            // The conjugate point solves the conjugate system (parameters conjugated).
            chart
                .evaluator()
                .evaluate(&chart.conjugate(&x), &conjugate_p, &mut work, &mut f);
            let residual = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
            assert!(
                residual < 1e-9 * size,
                "{id}: conjugate residual {residual:e}"
            );
            checked += 1;
        }
        // λ₀ = 0 with K′ a generic point is not a solution: the chart row alone
        // would be satisfiable, the gradient rows are not.
        let mut at_infinity = chart.from_cartesian(&file.solutions[0]);
        at_infinity[n] = C64::new(0.0, 0.0);
        chart
            .evaluator()
            .evaluate(&at_infinity, &p, &mut work, &mut f);
        assert!(
            f.iter().map(|v| v.norm()).fold(0.0, f64::max) > 1e-6,
            "{id}: λ₀ = 0 solved the chart system at a generic K′"
        );
    }
    assert!(checked > 600, "only {checked} start solutions checked");
}

/// On the stratum of a base on a line (`v_base = 0` a constant, [`Stratum`]) the
/// system is the generic one with `v_base = 0` substituted: the same unknowns, the
/// parameters without `v_base`, and at any point the same residuals as the generic
/// system at the same parameters with `v_base = 0`; a design off the line is refused.
#[test]
fn a_stratum_system_is_the_generic_one_with_v_fixed_at_zero() {
    use singdist::problem::{Coordinates, Multipliers, Stratum};
    let stratum = Stratum::from_name("collinear-base-anchors").unwrap();
    let mut rng_state = 7u64;
    let mut next = || {
        rng_state = rng_state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((rng_state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for name in ["rigid/rigid:singularity", "bars/rigid:coincident-platform"] {
        let id: ProblemId = name.parse().unwrap();
        let representation = (Coordinates::Cartesian, Multipliers::Affine);
        let generic = LagrangeProblem::new(id).unwrap();
        let on_line = LagrangeProblem::new_on(id, representation, stratum).unwrap();
        assert_eq!(on_line.stratum(), stratum);
        assert_eq!(on_line.variable_names(), generic.variable_names(), "{name}");
        let expected: Vec<&String> = generic
            .parameter_names()
            .iter()
            .filter(|p| *p != "v_base")
            .collect();
        let got: Vec<&String> = on_line.parameter_names().iter().collect();
        assert_eq!(got, expected, "{name}");
        let n = generic.variable_names().len();
        let x: Vec<C64> = (0..n).map(|_| C64::new(next(), next())).collect();
        let p: Vec<C64> = on_line
            .parameter_names()
            .iter()
            .map(|_| C64::new(next(), next()))
            .collect();
        let p_generic: Vec<C64> = generic
            .parameter_names()
            .iter()
            .map(
                |name| match on_line.parameter_names().iter().position(|q| q == name) {
                    Some(i) => p[i],
                    None => C64::new(0.0, 0.0),
                },
            )
            .collect();
        let mut work =
            vec![C64::new(0.0, 0.0); generic.workspace_len().max(on_line.workspace_len())];
        let mut f = vec![C64::new(0.0, 0.0); n];
        let mut g = vec![C64::new(0.0, 0.0); n];
        on_line.evaluator().evaluate(&x, &p, &mut work, &mut f);
        generic
            .evaluator()
            .evaluate(&x, &p_generic, &mut work, &mut g);
        for (a, b) in f.iter().zip(&g) {
            assert!(
                (a - b).norm() <= 1e-12 * (1.0 + b.norm()),
                "{name}: {a} vs {b}"
            );
        }
    }
    let off_line = rpr::Design::new(
        [[0.0, 0.0], [2.0, 0.0], [1.0, 1e-6]],
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
    )
    .unwrap();
    let id: ProblemId = "rigid/rigid:singularity".parse().unwrap();
    let representation = (Coordinates::Cartesian, Multipliers::Affine);
    assert!(LagrangeProblem::for_design_on(id, &off_line, representation, stratum).is_err());
    assert!(Stratum::of(id, &off_line).is_generic());
}
