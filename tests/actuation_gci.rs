//! GCI of the 3-RRR actuation schemes (Ramana Babu et al., Eq. 20): range, agreement with an
//! independent brute-force recomputation (finite-difference Jacobians of the IK, eigenvalues
//! of JᵀJ), symmetry of the symmetric design, determinism, loci, and the GA design optimisation.

#![allow(clippy::needless_range_loop)] // matrix loops read best with indices

use nalgebra::{Matrix3, SymmetricEigen};
use singdist::analysis::actuation_design::{DesignProblem, optimize_design};
use singdist::index::actuation::{
    ConditionNorm, GciDomain, GciOptions, PsiModel, Scheme, WorkspaceGrid, active_joints, gci,
    local_inverse_condition, plot_loci_svg, singularity_loci,
};
use singdist::mechanism::rrr::{POSITIVE_MODES, RrrDesign, RrrPose};
use singdist::optimize::GeneticOptions;

fn wrap(angle: f64) -> f64 {
    angle.sin().atan2(angle.cos())
}

/// Independent 1/κ: J = dq/dx by central differences of the IK, κ from the eigenvalues of JᵀJ
/// (2-norm) or from traces (weighted Frobenius). `None` when unreachable (or a neighbour is).
fn brute_inverse_condition(
    design: &RrrDesign,
    pose: RrrPose,
    scheme: Scheme,
    model: PsiModel,
    norm: ConditionNorm,
) -> Option<f64> {
    design.try_inverse_kinematics(&pose, &POSITIVE_MODES)?;
    let h = 1e-7;
    let mut j = Matrix3::zeros();
    for k in 0..3 {
        let mut plus = pose;
        let mut minus = pose;
        let (p, m) = match k {
            0 => (&mut plus.x, &mut minus.x),
            1 => (&mut plus.y, &mut minus.y),
            _ => (&mut plus.phi, &mut minus.phi),
        };
        *p += h;
        *m -= h;
        let qp = active_joints(
            &design.try_inverse_kinematics(&plus, &POSITIVE_MODES)?,
            scheme,
            model,
        );
        let qm = active_joints(
            &design.try_inverse_kinematics(&minus, &POSITIVE_MODES)?,
            scheme,
            model,
        );
        for leg in 0..3 {
            j[(leg, k)] = wrap(qp[leg] - qm[leg]) / (2.0 * h);
        }
    }
    Some(match norm {
        ConditionNorm::Spectral => {
            let eig = SymmetricEigen::new(j.transpose() * j).eigenvalues;
            (eig.min().max(0.0) / eig.max()).sqrt()
        }
        ConditionNorm::WeightedFrobenius => {
            let inv = j.try_inverse()?;
            3.0 / ((j * j.transpose()).trace() * (inv * inv.transpose()).trace()).sqrt()
        }
    })
}

#[test]
fn gci_equals_brute_force_mean_on_a_tiny_grid() {
    let design = RrrDesign::symmetric(5.0, 1.3, 3.0, 3.5).unwrap();
    let grid = WorkspaceGrid::square(3.0, 9);
    for (scheme_number, model, norm, phi) in [
        (1, PsiModel::Seed, ConditionNorm::Spectral, 0.0),
        (2, PsiModel::Seed, ConditionNorm::Spectral, 0.35),
        (4, PsiModel::RelativeElbow, ConditionNorm::Spectral, 0.35),
        (7, PsiModel::Seed, ConditionNorm::WeightedFrobenius, -0.2),
    ] {
        let scheme = Scheme::from_number(scheme_number).unwrap();
        let options = GciOptions {
            model,
            norm,
            ..GciOptions::default()
        };
        let result = gci(&design, scheme, phi, &grid, &options).unwrap();
        let mut sum = 0.0;
        let mut reachable = 0;
        for j in 0..grid.ny {
            for i in 0..grid.nx {
                let pose = RrrPose::new(grid.x(i), grid.y(j), phi);
                if let Some(value) = brute_inverse_condition(&design, pose, scheme, model, norm) {
                    sum += value;
                    reachable += 1;
                }
            }
        }
        assert_eq!(result.reachable_nodes, reachable, "scheme {scheme}");
        assert!(
            reachable > 10 && reachable < grid.len(),
            "grid must straddle the boundary"
        );
        let brute = sum / reachable as f64;
        assert!(
            (result.gci - brute).abs() < 1e-5,
            "scheme {scheme}: gci {} vs brute force {brute}",
            result.gci
        );
        assert!((0.0..=1.0).contains(&result.gci) && result.gci > 0.0);
        assert!(
            (result.mean_grid * result.total_nodes as f64
                - result.mean_reachable * result.reachable_nodes as f64)
                .abs()
                < 1e-9
        );
        let grid_domain = gci(
            &design,
            scheme,
            phi,
            &grid,
            &GciOptions {
                domain: GciDomain::Grid,
                ..options
            },
        )
        .unwrap();
        assert!((grid_domain.gci - sum / grid.len() as f64).abs() < 1e-5);
    }
}

#[test]
fn symmetric_design_maps_scheme_3_to_scheme_5_under_a_third_turn() {
    // Rotating the whole robot by 120° maps leg i to leg i+1 at the same orientation φ, so
    // θθψ at (P, φ) is ψθθ at (R·P, φ) and θψψ at (P, φ) is ψθψ at (R·P, φ).
    let design = RrrDesign::symmetric(5.0, 1.4, 2.9, 3.6).unwrap();
    let options = GciOptions::default();
    let (s, c) = (2.0 * std::f64::consts::PI / 3.0).sin_cos();
    let mut compared = 0;
    for (from, to) in [(3, 5), (5, 4), (6, 8), (1, 1), (2, 2)] {
        let (from, to) = (
            Scheme::from_number(from).unwrap(),
            Scheme::from_number(to).unwrap(),
        );
        for k in 0..20 {
            let (x, y, phi) = (
                -2.0 + 0.21 * k as f64,
                1.5 - 0.17 * k as f64,
                0.05 * k as f64,
            );
            let rotated = RrrPose::new(c * x - s * y, s * x + c * y, phi);
            let a = local_inverse_condition(&design, &RrrPose::new(x, y, phi), from, &options);
            let b = local_inverse_condition(&design, &rotated, to, &options);
            assert_eq!(a.is_some(), b.is_some());
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a - b).abs() < 1e-10, "{from} -> {to}: {a} vs {b}");
                compared += 1;
            }
        }
    }
    assert!(compared > 50);
    // ... and θθψ is not equivalent to θψψ.
    let pose = RrrPose::new(0.4, 0.3, 0.2);
    let a = local_inverse_condition(&design, &pose, Scheme::from_number(3).unwrap(), &options);
    let b = local_inverse_condition(&design, &pose, Scheme::from_number(6).unwrap(), &options);
    assert!((a.unwrap() - b.unwrap()).abs() > 1e-3);
}

#[test]
fn gci_is_deterministic_across_thread_counts_and_rejects_bad_grids() {
    let design = RrrDesign::symmetric(5.0, 1.5, 3.0, 3.5).unwrap();
    let grid = WorkspaceGrid::square(5.0, 33);
    let scheme = Scheme::from_number(6).unwrap();
    let options = GciOptions::default();
    let many = gci(&design, scheme, 0.2, &grid, &options).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = pool.install(|| gci(&design, scheme, 0.2, &grid, &options).unwrap());
    assert_eq!(many, one);
    let mut bad = grid;
    bad.nx = 1;
    let err = gci(&design, scheme, 0.0, &bad, &options).unwrap_err();
    assert!(err.to_string().contains("grid.nx"), "{err}");
    bad = grid;
    bad.y_max = f64::NAN;
    let err = gci(&design, scheme, 0.0, &bad, &options).unwrap_err();
    assert!(err.to_string().contains("grid.y_max"), "{err}");
    let err = gci(&design, scheme, f64::NAN, &grid, &options).unwrap_err();
    assert!(err.to_string().contains("orientation"), "{err}");
}

#[test]
fn loci_lie_on_leg_boundaries_and_plot_is_written() {
    let design = RrrDesign::symmetric(5.0, 1.5, 3.0, 3.5).unwrap();
    let grid = WorkspaceGrid::square(5.0, 41);
    let spacing = 10.0 / 40.0;
    let phi = 20f64.to_radians();
    let mut maps = Vec::new();
    for scheme in [
        Scheme::from_number(1).unwrap(),
        Scheme::from_number(2).unwrap(),
    ] {
        let map =
            singularity_loci(&design, scheme, phi, &grid, &POSITIVE_MODES, PsiModel::Seed).unwrap();
        assert!(!map.type_i.is_empty());
        let pose_of = |x: f64, y: f64| RrrPose::new(x, y, phi);
        for &(x, y) in &map.type_i {
            let c = design.platform_joints(&pose_of(x, y));
            let gap = (0..3)
                .map(|leg| {
                    let d = (c[leg] - design.base()[leg]).norm();
                    let (b, cc) = (design.proximal()[leg], design.distal()[leg]);
                    (d - (b + cc)).abs().min((d - (b - cc).abs()).abs())
                })
                .fold(f64::INFINITY, f64::min);
            assert!(
                gap <= spacing,
                "Type I point ({x}, {y}) is {gap} from every leg boundary"
            );
        }
        assert_eq!(
            map.reachable.iter().filter(|r| **r).count(),
            gci(&design, scheme, phi, &grid, &GciOptions::default())
                .unwrap()
                .reachable_nodes
        );
        maps.push(map);
    }
    // ψψψ has a Type II locus crossing the workspace at φ = 20° in this geometry.
    assert!(!maps[1].type_ii.is_empty());
    let path = std::env::temp_dir().join(format!("singdist_loci_test_{}.svg", std::process::id()));
    plot_loci_svg(&path, &maps, 2).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("<svg") && text.contains("scheme 2"));
    std::fs::remove_file(&path).ok();
}

#[test]
fn ga_design_optimisation_is_reproducible_feasible_and_not_worse_than_the_start() {
    let scheme = Scheme::from_number(3).unwrap();
    let problem = DesignProblem::example(scheme, 0.0, 11);
    let initial = [1.5, 3.0, 3.5];
    let ga = GeneticOptions {
        population: 10,
        generations: 4,
        seed: 17,
        ..GeneticOptions::default()
    };
    let first = optimize_design(&problem, initial, &ga).unwrap();
    let second = optimize_design(&problem, initial, &ga).unwrap();
    assert_eq!(first, second, "same seed, same optimum");
    assert!(first.objective >= first.initial_objective);
    assert!((first.initial_objective - problem.objective(&initial)).abs() < 1e-15);
    let [a, b, c] = first.design_vector;
    assert!(a + b + c <= problem.size_limit + 1e-12);
    for (k, &(lo, hi)) in problem.bounds.iter().enumerate() {
        assert!((lo..=hi).contains(&first.design_vector[k]));
    }
    assert!(
        (first.gci.gci - first.objective).abs() < 1e-15,
        "objective = GCI at the optimum"
    );
    assert_eq!(first.history.len(), 5);
    assert!(first.history.windows(2).all(|w| w[1] >= w[0]));
    // An infeasible start is rejected, naming the field.
    let err = optimize_design(&problem, [3.0, 4.0, 4.0], &ga).unwrap_err();
    assert!(err.to_string().contains("initial"), "{err}");
}

#[test]
fn relative_elbow_psi_psi_psi_is_architecturally_singular_at_zero_orientation() {
    // Similar, equally oriented base and platform triangles: lines O_iC_i concurrent at
    // R·P/(R − a) for every P when φ = 0, so the relative-elbow ψψψ has GCI 0 there only.
    let design = RrrDesign::symmetric(5.0, 1.5, 3.0, 3.5).unwrap();
    let grid = WorkspaceGrid::square(5.0, 21);
    let scheme = Scheme::from_number(2).unwrap();
    let relative = GciOptions {
        model: PsiModel::RelativeElbow,
        ..GciOptions::default()
    };
    let at_zero = gci(&design, scheme, 0.0, &grid, &relative).unwrap();
    assert!(at_zero.reachable_nodes > 50);
    assert!(at_zero.gci < 1e-8, "{}", at_zero.gci);
    assert!(gci(&design, scheme, 0.3, &grid, &relative).unwrap().gci > 0.05);
    assert!(
        gci(&design, scheme, 0.0, &grid, &GciOptions::default())
            .unwrap()
            .gci
            > 0.05
    );
}

#[test]
fn isosceles_legs_make_seed_psi_scheme_equal_theta_scheme_in_the_other_mode() {
    // With |O_iB_i| = |B_iC_i| the mirrored elbow (other working mode) swaps the directions of
    // b_i and c_i, so the paper-model ψψψ rows in mode σ are the θθθ rows in mode −σ (and
    // the J_q diagonals agree): equal 1/κ pose by pose.
    let design = RrrDesign::symmetric(5.0, 1.2, 3.0, 3.0).unwrap();
    let psi = Scheme::from_number(2).unwrap();
    let theta = Scheme::from_number(1).unwrap();
    let plus = GciOptions::default();
    let minus = GciOptions {
        modes: [singdist::mechanism::rrr::ElbowMode::Negative; 3],
        ..GciOptions::default()
    };
    let mut compared = 0;
    for k in 0..40 {
        let pose = RrrPose::new(
            -2.0 + 0.1 * k as f64,
            1.0 - 0.07 * k as f64,
            0.3 - 0.02 * k as f64,
        );
        let a = local_inverse_condition(&design, &pose, psi, &plus);
        let b = local_inverse_condition(&design, &pose, theta, &minus);
        if let (Some(a), Some(b)) = (a, b) {
            assert!((a - b).abs() < 1e-10, "pose {k}: {a} vs {b}");
            compared += 1;
        }
    }
    assert!(compared > 20);
    // Not an identity of the θθθ scheme in the same mode.
    let pose = RrrPose::new(0.5, -0.4, 0.3);
    let a = local_inverse_condition(&design, &pose, psi, &plus).unwrap();
    let b = local_inverse_condition(&design, &pose, theta, &plus).unwrap();
    assert!((a - b).abs() > 1e-3);
}
