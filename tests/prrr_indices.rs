//! docs/theory.md §11.1–§11.2: inverse kinematics, A and B against finite differences,
//! singularity tests, LCI and NSIR test vectors.
#![allow(clippy::needless_range_loop)]

use singdist::index::prrr::{LciVariant, all_indices, incircle_radius_of_lines, lci, nsir};
use singdist::mechanism::prrr::{Pose, PrrrDesign, PrrrError, Robot, WorkingMode, parse_modes};

const PLUS: WorkingMode = WorkingMode::Plus;
const MINUS: WorkingMode = WorkingMode::Minus;

#[test]
fn spec_d2_test_vector() {
    let design = PrrrDesign::farias2021();
    let pose = Pose::new(0.0, 0.0, 0.0);
    let indices_with = |modes: [WorkingMode; 3]| {
        let c = design.inverse_kinematics(&pose, &[0.0; 3], &modes).unwrap();
        let idx = all_indices(&design, &c, Robot::ThreePrrr);
        println!("{idx:?}");
        idx
    };
    let close = |value: f64, expected: f64| {
        assert!((value - expected).abs() < 1e-6, "{value} vs {expected}");
    };
    let idx = indices_with([PLUS; 3]);
    close(idx.lci_inv_a_b, 0.785952);
    close(idx.r_norm, 0.785952);
    close(idx.xi, 0.559922);
    close(idx.nsir, 0.440072);
    let idx = indices_with([PLUS, MINUS, PLUS]);
    close(idx.lci_inv_a_b, 0.253256);
    close(idx.nsir, 0.305006);
}

/// Random inverse-kinematics inputs, drawn in this order: a pose with `x, y` uniform in
/// `[−r, r]` and `φ` in `[−φ_max, φ_max]`, actuator offsets uniform in `[−d, d]`, and
/// each leg's working mode `+` or `−` with probability ½.
fn random_inputs(
    rng: &mut singdist::random::SeededRng,
    r: f64,
    phi_max: f64,
    d: f64,
) -> (Pose, [f64; 3], [WorkingMode; 3]) {
    let mut u = |lo: f64, hi: f64| singdist::random::uniform(rng, lo, hi);
    let pose = Pose::new(u(-r, r), u(-r, r), u(-phi_max, phi_max));
    let delta = [u(-d, d), u(-d, d), u(-d, d)];
    let modes = [0, 1, 2].map(|_| if u(0.0, 1.0) < 0.5 { PLUS } else { MINUS });
    (pose, delta, modes)
}

fn wrap(angle: f64) -> f64 {
    let t = angle.rem_euclid(std::f64::consts::TAU);
    if t > std::f64::consts::PI {
        t - std::f64::consts::TAU
    } else {
        t
    }
}

/// `A Ẋ = B Θ̇` checked column by column against central differences of the inverse kinematics.
#[test]
fn a_and_b_agree_with_finite_differences_of_inverse_kinematics() {
    let mut rng = singdist::random::seeded(2024);
    let mut checked = 0;
    for design in [PrrrDesign::farias2021(), PrrrDesign::fontes2017()] {
        for _ in 0..200 {
            let (pose, delta, modes) = random_inputs(&mut rng, 0.1, 0.6, 0.2);
            let Ok(c) = design.inverse_kinematics(&pose, &delta, &modes) else {
                continue;
            };
            let a = c.matrix_a(&design);
            let b = c.matrix_b(&design);
            let eps = 1e-7;
            let mut ok = true;
            // Pose derivatives: A e_j = B_θ ∂θ/∂X_j.
            let mut dtheta = [[0.0; 3]; 3];
            for j in 0..3 {
                let mut plus = pose;
                let mut minus = pose;
                match j {
                    0 => {
                        plus.x += eps;
                        minus.x -= eps;
                    }
                    1 => {
                        plus.y += eps;
                        minus.y -= eps;
                    }
                    _ => {
                        plus.alpha += eps;
                        minus.alpha -= eps;
                    }
                }
                let (Ok(cp), Ok(cm)) = (
                    design.inverse_kinematics(&plus, &delta, &modes),
                    design.inverse_kinematics(&minus, &delta, &modes),
                ) else {
                    ok = false;
                    break;
                };
                for k in 0..3 {
                    dtheta[k][j] = wrap(cp.theta[k] - cm.theta[k]) / (2.0 * eps);
                }
            }
            if !ok {
                continue;
            }
            for k in 0..3 {
                for j in 0..3 {
                    let predicted = b[(k, k)] * dtheta[k][j];
                    let scale = 1.0 + a[(k, j)].abs() + predicted.abs();
                    assert!(
                        (a[(k, j)] - predicted).abs() < 1e-5 * scale,
                        "A[{k},{j}] = {} vs FD {} at {pose:?} {delta:?}",
                        a[(k, j)],
                        predicted
                    );
                }
            }
            // δ derivatives at fixed pose: b_kk ∂θ_k/∂δ_k + b_k,k+3 = 0, other legs unchanged.
            for k in 0..3 {
                let mut dp = delta;
                let mut dm = delta;
                dp[k] += eps;
                dm[k] -= eps;
                let (Ok(cp), Ok(cm)) = (
                    design.inverse_kinematics(&pose, &dp, &modes),
                    design.inverse_kinematics(&pose, &dm, &modes),
                ) else {
                    continue;
                };
                let d = wrap(cp.theta[k] - cm.theta[k]) / (2.0 * eps);
                let residual = b[(k, k)] * d + b[(k, k + 3)];
                assert!(
                    residual.abs() < 1e-5 * (1.0 + b[(k, k + 3)].abs()),
                    "leg {k}: {residual}"
                );
                for other in (0..3).filter(|&o| o != k) {
                    assert_eq!(cp.theta[other], cm.theta[other]);
                }
            }
            // IK consistency: |B_i − A_i| = l1, |C_i − B_i| = l2.
            for k in 0..3 {
                let d1 = (c.elbow[k][0] - c.base[k][0]).hypot(c.elbow[k][1] - c.base[k][1]);
                let d2 = (c.platform[k][0] - c.elbow[k][0]).hypot(c.platform[k][1] - c.elbow[k][1]);
                assert!((d1 - design.l1).abs() < 1e-12 && (d2 - design.l2).abs() < 1e-12);
            }
            checked += 1;
        }
    }
    assert!(checked > 150, "only {checked} reachable samples checked");
}

/// Bisection on x for a sign change of det Ā gives a direct singularity: the lines B_iC_i
/// become concurrent (incircle → 0, computed geometrically) and both LCIs vanish.
#[test]
fn direct_singularity_test_fires_on_constructed_singular_pose() {
    let design = PrrrDesign::farias2021();
    let delta = [0.0; 3];
    let mut found = 0;
    for modes in [
        [PLUS, MINUS, PLUS],
        [MINUS, MINUS, MINUS],
        [PLUS, PLUS, MINUS],
        [MINUS, PLUS, PLUS],
    ] {
        let det_at = |x: f64| {
            design
                .inverse_kinematics(&Pose::new(x, 0.03, 0.2), &delta, &modes)
                .ok()
                .map(|c| c.direct_singularity_measure(&design))
        };
        let xs: Vec<f64> = (0..=200).map(|i| -0.2 + 0.4 * i as f64 / 200.0).collect();
        for w in xs.windows(2) {
            let (Some(d0), Some(d1)) = (det_at(w[0]), det_at(w[1])) else {
                continue;
            };
            if d0 * d1 >= 0.0 {
                continue;
            }
            let (mut lo, mut hi, mut dlo) = (w[0], w[1], d0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                let Some(dm) = det_at(mid) else { break };
                if dm * dlo > 0.0 {
                    lo = mid;
                    dlo = dm;
                } else {
                    hi = mid;
                }
            }
            let pose = Pose::new(0.5 * (lo + hi), 0.03, 0.2);
            let c = design.inverse_kinematics(&pose, &delta, &modes).unwrap();
            assert!(
                c.is_direct_singular(&design, 1e-12),
                "{}",
                c.direct_singularity_measure(&design)
            );
            let n = nsir(&design, &c, Robot::ThreePrrr);
            assert!(n.r_norm < 1e-8, "lines not concurrent: r_norm {}", n.r_norm);
            assert!(lci(&design, &c, Robot::ThreePrrr, LciVariant::InverseAB) < 1e-8);
            assert!(lci(&design, &c, Robot::ThreePrrr, LciVariant::DirectA) < 1e-8);
            // A nearby regular pose is not flagged.
            let near = design
                .inverse_kinematics(&Pose::new(w[0], 0.03, 0.2), &delta, &modes)
                .unwrap();
            assert!(!near.is_direct_singular(&design, 1e-12));
            found += 1;
        }
    }
    assert!(found >= 1, "no direct singularity found along the scan");
}

/// Leg 1 fully stretched perpendicular to its guide: rank B < 3 for the 3-PRRR; a stretched
/// leg is an inverse singularity of the 3RRR.
#[test]
fn inverse_singularity_test_fires_on_constructed_singular_poses() {
    let design = PrrrDesign::farias2021();
    let reach = (design.l1 + design.l2) * (1.0 - 1e-13);
    let alpha: f64 = 0.1;
    // Guide 1 is the line a e(λ_1) + t e(γ_1); its unit normal is n = (−sin γ_1, cos γ_1).
    let g = design.gamma[0];
    let normal = [-g.sin(), g.cos()];
    let a1 = design.base_joint(0, 0.02);
    // C_1 = A_1 + reach n (leg along the normal, i.e. perpendicular to the guide).
    let c1 = [a1[0] + reach * normal[0], a1[1] + reach * normal[1]];
    let phi = alpha + design.platform_angles[0];
    let pose = Pose::new(
        c1[0] - design.h * phi.cos(),
        c1[1] - design.h * phi.sin(),
        alpha,
    );
    let mut hit = false;
    let levels: Vec<f64> = (0..=20).map(|i| -0.23 + 0.023 * i as f64).collect();
    'outer: for &d2 in &levels {
        for &d3 in &levels {
            let Ok(c) = design.inverse_kinematics(&pose, &[0.02, d2, d3], &[PLUS; 3]) else {
                continue;
            };
            assert!(
                c.is_inverse_singular(&design, Robot::ThreePrrr, 1e-5),
                "{}",
                c.inverse_singularity_measure(&design, Robot::ThreePrrr)
            );
            let b = c.matrix_b(&design);
            assert!(b[(0, 0)].abs() < 1e-6 && b[(0, 3)].abs() < 1e-6);
            assert!(nsir(&design, &c, Robot::ThreePrrr).nsir < 1e-5);
            assert!(lci(&design, &c, Robot::ThreePrrr, LciVariant::InverseAB) < 1e-5);
            // Moving δ_1 leaves the singularity.
            if let Ok(off) = design.inverse_kinematics(&pose, &[0.0, d2, d3], &[PLUS; 3]) {
                assert!(!off.is_inverse_singular(&design, Robot::ThreePrrr, 1e-3));
            }
            hit = true;
            break 'outer;
        }
    }
    assert!(hit, "no reachable completion of the singular leg");

    // 3RRR: stretch leg 2 (δ = 0) in some direction where the other legs reach the pose.
    let a2 = design.base_joint(1, 0.0);
    let phi = design.platform_angles[1];
    let mut rrr_hits = 0;
    for step in 0..64 {
        let psi = step as f64 * std::f64::consts::TAU / 64.0;
        let c2 = [a2[0] + reach * psi.cos(), a2[1] + reach * psi.sin()];
        let pose = Pose::new(
            c2[0] - design.h * phi.cos(),
            c2[1] - design.h * phi.sin(),
            0.0,
        );
        let Ok(c) = design.inverse_kinematics(&pose, &[0.0; 3], &[PLUS; 3]) else {
            continue;
        };
        assert!(c.is_inverse_singular(&design, Robot::ThreeRrr, 1e-5));
        assert!(lci(&design, &c, Robot::ThreeRrr, LciVariant::InverseAB) < 1e-5);
        rrr_hits += 1;
    }
    assert!(rrr_hits > 0, "no reachable stretched-leg pose of the 3RRR");
}

#[test]
fn incircle_matches_known_triangles_and_degenerate_rules() {
    // 3-4-5 right triangle (0,0), (4,0), (0,3): inradius (3+4−5)/2 = 1.
    let p = [[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]];
    let q = [[4.0, 0.0], [0.0, 3.0], [0.0, 0.0]];
    assert!((incircle_radius_of_lines(&p, &q) - 1.0).abs() < 1e-14);
    // Orientation and choice of points on the lines do not matter.
    let q2 = [[8.0, 0.0], [-4.0, 6.0], [0.0, -7.0]];
    assert!((incircle_radius_of_lines(&q2, &p) - 1.0).abs() < 1e-13);
    // Concurrent lines: 0.
    let p = [[0.0, 0.0]; 3];
    let q = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
    assert!(incircle_radius_of_lines(&p, &q).abs() < 1e-15);
    // Two parallel lines 2 apart, third transversal: d/2 = 1 (continuous limit).
    let p = [[0.0, 0.0], [0.0, 2.0], [0.0, 0.0]];
    let q = [[1.0, 0.0], [-3.0, 2.0], [1.0, 5.0]];
    assert!((incircle_radius_of_lines(&p, &q) - 1.0).abs() < 1e-14);
    let nearly = [[1.0, 0.0], [-3.0, 2.0 + 1e-9], [1.0, 5.0]];
    assert!((incircle_radius_of_lines(&p, &nearly) - 1.0).abs() < 1e-6);
    // Three parallel lines: 0.
    let q = [[1.0, 0.0], [1.0, 2.0], [1.0, 7.0]];
    let p = [[0.0, 0.0], [0.0, 2.0], [0.0, 7.0]];
    assert_eq!(incircle_radius_of_lines(&p, &q), 0.0);
}

#[test]
fn bad_input_gives_named_errors_not_nan() {
    let design = PrrrDesign::farias2021();
    let far = design.inverse_kinematics(&Pose::new(1.0, 0.0, 0.0), &[0.0; 3], &[PLUS; 3]);
    assert!(matches!(far, Err(PrrrError::Unreachable { .. })));
    let nan = design.inverse_kinematics(&Pose::new(f64::NAN, 0.0, 0.0), &[0.0; 3], &[PLUS; 3]);
    assert!(matches!(
        nan,
        Err(PrrrError::InvalidInput { field: "pose", .. })
    ));
    let nan = design.inverse_kinematics(
        &Pose::new(0.0, 0.0, 0.0),
        &[0.0, f64::INFINITY, 0.0],
        &[PLUS; 3],
    );
    assert!(matches!(
        nan,
        Err(PrrrError::InvalidInput { field: "delta", .. })
    ));
    assert_eq!(parse_modes("+,-,+").unwrap(), [PLUS, MINUS, PLUS]);
    assert_eq!(parse_modes("+1, -1, -1").unwrap(), [PLUS, MINUS, MINUS]);
    assert!(parse_modes("+,+").is_err());
    assert!(
        parse_modes("+,x,+")
            .unwrap_err()
            .to_string()
            .contains("modes")
    );
    assert!(matches!(
        PrrrDesign::preset("nope"),
        Err(PrrrError::UnknownPreset(_))
    ));
    assert_eq!(PrrrDesign::preset("Fontes2017").unwrap().h, 0.060);
    let mut bad = PrrrDesign::farias2021();
    bad.l2 = -1.0;
    assert!(bad.validate().unwrap_err().to_string().contains("l2"));
    let mut bad = PrrrDesign::farias2021();
    bad.delta_range = (0.1, -0.1);
    assert!(
        bad.validate()
            .unwrap_err()
            .to_string()
            .contains("delta_range")
    );
    assert!(PrrrDesign::farias2021().validate().is_ok());
}

/// The platform convention of Farias Filho et al. (2021) `C_i = D − h e(α + η_i)` equals
/// ours with φ_i = η_i + π, and the indices are invariant under a rigid rotation of the
/// whole robot about the origin.
#[test]
fn platform_convention_and_rotation_invariance() {
    let design = PrrrDesign::farias2021();
    let alt = PrrrDesign::farias2021()
        .with_seed000_platform(design.lambda.map(|l| l - std::f64::consts::PI));
    let pose = Pose::new(0.01, -0.02, 0.1);
    let c1 = design
        .inverse_kinematics(&pose, &[0.01, 0.02, -0.03], &[PLUS; 3])
        .unwrap();
    let c2 = alt
        .inverse_kinematics(&pose, &[0.01, 0.02, -0.03], &[PLUS; 3])
        .unwrap();
    let i1 = all_indices(&design, &c1, Robot::ThreePrrr);
    let i2 = all_indices(&alt, &c2, Robot::ThreePrrr);
    assert!((i1.nsir - i2.nsir).abs() < 1e-12 && (i1.lci_inv_a_b - i2.lci_inv_a_b).abs() < 1e-12);
    // Rotate everything by ψ: λ, γ, φ unchanged in the body, pose rotated.
    let psi: f64 = 0.7;
    let mut rotated = design.clone();
    rotated.lambda = design.lambda.map(|l| l + psi);
    rotated.gamma = design.gamma.map(|g| g + psi);
    rotated.platform_angles = design.platform_angles.map(|l| l + psi);
    let (s, c) = psi.sin_cos();
    let rpose = Pose::new(c * pose.x - s * pose.y, s * pose.x + c * pose.y, pose.alpha);
    let c3 = rotated
        .inverse_kinematics(&rpose, &[0.01, 0.02, -0.03], &[PLUS; 3])
        .unwrap();
    let i3 = all_indices(&rotated, &c3, Robot::ThreePrrr);
    assert!((i1.nsir - i3.nsir).abs() < 1e-12, "{} {}", i1.nsir, i3.nsir);
    assert!((i1.lci_a - i3.lci_a).abs() < 1e-12);
    assert!((i1.lci_inv_a_b - i3.lci_inv_a_b).abs() < 1e-12);
}

/// The fast LCI (row-scaled Ā, closed-form Gram eigenvalues) equals the literal formula
/// (Ā⁻¹, product with B̄, SVD) on random configurations, and the symmetric eigenvalue solver
/// matches the characteristic invariants.
#[test]
fn fast_lci_equals_reference_formula() {
    use singdist::index::prrr::{
        inverse_condition_3x3, inverse_condition_svd_3x3, lci_reference, symmetric_eigenvalues_3x3,
    };
    let design = PrrrDesign::fontes2017();
    let mut rng = singdist::random::seeded(5);
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for _ in 0..3000 {
        let (pose, delta, modes) = random_inputs(&mut rng, 0.2, 1.0, 0.3);
        let Ok(c) = design.inverse_kinematics(&pose, &delta, &modes) else {
            continue;
        };
        for robot in [Robot::ThreePrrr, Robot::ThreeRrr] {
            for variant in [LciVariant::InverseAB, LciVariant::DirectA] {
                let fast = lci(&design, &c, robot, variant);
                let reference = lci_reference(&design, &c, robot, variant);
                worst = worst.max((fast - reference).abs());
                assert!(
                    (fast - reference).abs() < 1e-9,
                    "{robot:?} {variant:?}: {fast} vs {reference}"
                );
            }
        }
        let m = c.matrix_a_bar(&design);
        assert!((inverse_condition_3x3(&m) - inverse_condition_svd_3x3(&m)).abs() < 1e-9);
        let g = m * m.transpose();
        let e = symmetric_eigenvalues_3x3(&g);
        assert!(e[0] <= e[1] && e[1] <= e[2]);
        let scale = e[2].abs().max(1e-300);
        assert!(((e[0] + e[1] + e[2]) - g.trace()).abs() < 1e-12 * scale);
        assert!((e[0] * e[1] * e[2] - g.determinant()).abs() < 1e-9 * scale * scale * scale);
        checked += 1;
    }
    assert!(checked > 500, "{checked}");
    println!("worst |fast − reference| = {worst:e} over {checked} configurations");
}
