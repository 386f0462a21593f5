//! Actuation schemes (Ramana Babu, Ramachandra Raju, Ramji): J_x and J_q against finite differences of the
//! inverse kinematics for all eight schemes and both ψ models, scheme names, and singularity
//! classification on constructed singular configurations.

#![allow(clippy::needless_range_loop)] // matrix loops read best with indices

use singdist::index::actuation::{
    Actuator, PsiModel, Scheme, SingularityTolerance, SingularityType, active_joints, classify,
    jacobians, leg_singularity_measure,
};
use singdist::mechanism::rrr::{
    ElbowMode, POSITIVE_MODES, Point, RrrConfiguration, RrrDesign, RrrPose, WorkingModes,
};
use singdist::random::{seeded, uniform};

mod rrr_support;
use rrr_support::{design_of, modes_of};

fn wrap(angle: f64) -> f64 {
    angle.sin().atan2(angle.cos())
}

/// dq/dx by central differences of the inverse kinematics (column k = ∂q/∂x_k).
fn fd_joint_jacobian(
    design: &RrrDesign,
    pose: &RrrPose,
    modes: &WorkingModes,
    scheme: Scheme,
    model: PsiModel,
) -> [[f64; 3]; 3] {
    let h = 1e-6;
    let mut d = [[0.0; 3]; 3];
    for k in 0..3 {
        let mut plus = *pose;
        let mut minus = *pose;
        match k {
            0 => {
                plus.x += h;
                minus.x -= h
            }
            1 => {
                plus.y += h;
                minus.y -= h
            }
            _ => {
                plus.phi += h;
                minus.phi -= h
            }
        }
        let qp = active_joints(
            &design.inverse_kinematics(&plus, modes).unwrap(),
            scheme,
            model,
        );
        let qm = active_joints(
            &design.inverse_kinematics(&minus, modes).unwrap(),
            scheme,
            model,
        );
        for leg in 0..3 {
            d[leg][k] = wrap(qp[leg] - qm[leg]) / (2.0 * h);
        }
    }
    d
}

#[test]
fn jacobians_match_finite_differences_for_all_schemes_and_models() {
    let mut rng = seeded(11);
    let designs = [
        RrrDesign::symmetric(5.0, 1.3, 3.0, 3.5).unwrap(),
        design_of(
            [[-4.0, -2.0], [4.5, -1.5], [0.5, 4.2]],
            ([2.6, 3.1, 2.8], [3.3, 2.7, 3.0]),
            [[-0.9, -0.4], [1.1, -0.3], [0.2, 0.8]],
        ),
    ];
    let mut checked = 0;
    for design in &designs {
        let mut found = 0;
        while found < 12 {
            let pose = RrrPose::new(
                uniform(&mut rng, -2.5, 2.5),
                uniform(&mut rng, -2.5, 2.5),
                uniform(&mut rng, -0.6, 0.6),
            );
            let modes: WorkingModes = [0, 1, 2].map(|_| {
                if uniform(&mut rng, 0.0, 1.0) < 0.5 {
                    ElbowMode::Positive
                } else {
                    ElbowMode::Negative
                }
            });
            let Some(config) = design.try_inverse_kinematics(&pose, &modes) else {
                continue;
            };
            if leg_singularity_measure(&config) < 0.05 {
                continue;
            }
            found += 1;
            for scheme in Scheme::all() {
                for model in [PsiModel::Seed, PsiModel::RelativeElbow] {
                    let jac = jacobians(&config, scheme, model);
                    let d = fd_joint_jacobian(design, &pose, &modes, scheme, model);
                    // J_x ẋ = J_q q̇ for every ẋ ⇔ J_x = diag(J_q) · dq/dx.
                    for leg in 0..3 {
                        for k in 0..3 {
                            let lhs = jac.jx[(leg, k)];
                            let rhs = jac.jq[leg] * d[leg][k];
                            let scale = 1.0 + lhs.abs();
                            assert!(
                                (lhs - rhs).abs() < 1e-6 * scale,
                                "scheme {scheme} model {model:?} leg {leg} col {k}: J_x = {lhs}, J_q·dq/dx = {rhs}"
                            );
                        }
                    }
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 2 * 12 * 8 * 2);
}

#[test]
fn schemes_by_number_and_name() {
    let names = ["θθθ", "ψψψ", "θθψ", "θψθ", "ψθθ", "θψψ", "ψψθ", "ψθψ"];
    for (k, scheme) in Scheme::all().into_iter().enumerate() {
        assert_eq!(scheme.number() as usize, k + 1);
        assert_eq!(scheme.name(), names[k]);
        assert_eq!(names[k].parse::<Scheme>().unwrap(), scheme);
        assert_eq!(
            scheme
                .ascii_name()
                .to_uppercase()
                .parse::<Scheme>()
                .unwrap(),
            scheme
        );
        assert_eq!((k + 1).to_string().parse::<Scheme>().unwrap(), scheme);
    }
    assert_eq!(
        Scheme::from_number(6).unwrap().actuators(),
        [Actuator::Theta, Actuator::Psi, Actuator::Psi]
    );
    assert!("9".parse::<Scheme>().is_err());
    assert!("0".parse::<Scheme>().is_err());
    let unknown = "tpx".parse::<Scheme>().expect_err("an unknown scheme");
    assert!(unknown.to_string().contains("tpx"));
}

/// Design whose configuration at pose (0, 0, 0) is exactly (bases, elbows, platform).
fn design_through(
    bases: [Point; 3],
    elbows: [Point; 3],
    platform: [Point; 3],
) -> (RrrDesign, RrrConfiguration) {
    let proximal = [0, 1, 2].map(|i| (elbows[i] - bases[i]).norm());
    let distal = [0, 1, 2].map(|i| (platform[i] - elbows[i]).norm());
    let design = RrrDesign::new(bases, proximal, distal, platform).unwrap();
    let modes = modes_of(&bases, &elbows, &platform);
    let config = design
        .inverse_kinematics(&RrrPose::new(0.0, 0.0, 0.0), &modes)
        .unwrap();
    for i in 0..3 {
        assert!((config.elbow[i] - elbows[i]).norm() < 1e-9);
    }
    (design, config)
}

fn rotate(u: Point, angle: f64) -> Point {
    let (s, c) = angle.sin_cos();
    Point::new(c * u.x - s * u.y, s * u.x + c * u.y)
}

const PLATFORM: [Point; 3] = [
    Point::new(-1.0, -0.6),
    Point::new(1.2, -0.5),
    Point::new(0.1, 1.1),
];

#[test]
fn type_ii_fires_on_concurrent_lines_for_each_model_and_not_generically() {
    let tol = SingularityTolerance {
        leg: 1e-7,
        parallel: 1e-7,
    };
    let q = Point::new(0.3, 0.2);
    let radial = PLATFORM.map(|c| (c - q).normalize());
    let theta_scheme = Scheme::from_number(1).unwrap();
    let psi_scheme = Scheme::from_number(2).unwrap();
    // The design through (bases, elbows, PLATFORM): each (scheme, model) classifies its
    // configuration as the given type; returns the configuration.
    let expect =
        |bases: [Point; 3], elbows: [Point; 3], cases: &[(Scheme, PsiModel, SingularityType)]| {
            let (design, config) = design_through(bases, elbows, PLATFORM);
            for &(scheme, model, expected) in cases {
                assert_eq!(
                    classify(&design, &config, scheme, model, tol),
                    expected,
                    "scheme {scheme} {model:?}"
                );
            }
            config
        };

    // θθθ: distal lines B_iC_i through Q.
    let elbows = [0, 1, 2].map(|i| PLATFORM[i] + 2.0 * radial[i]);
    let bases = [0, 1, 2].map(|i| elbows[i] + 1.7 * rotate(radial[i], 1.1));
    let config = expect(
        bases,
        elbows,
        &[
            (theta_scheme, PsiModel::Seed, SingularityType::TypeII),
            (psi_scheme, PsiModel::Seed, SingularityType::Regular),
        ],
    );
    let jac = jacobians(&config, theta_scheme, PsiModel::Seed);
    assert!(jac.det_jx().abs() < 1e-12);

    // Type III: same concurrent distal lines, and leg 0 stretched (O_0 on the line B_0C_0).
    let mut stretched_bases = bases;
    stretched_bases[0] = elbows[0] + 1.7 * radial[0];
    expect(
        stretched_bases,
        elbows,
        &[(theta_scheme, PsiModel::Seed, SingularityType::TypeIII)],
    );

    // ψψψ, seed model: the lines through C_i parallel to O_iB_i pass through Q.
    let elbows = [0, 1, 2].map(|i| PLATFORM[i] + 2.0 * rotate(radial[i], 0.9));
    let bases = [0, 1, 2].map(|i| elbows[i] - 1.6 * radial[i]);
    expect(
        bases,
        elbows,
        &[
            (psi_scheme, PsiModel::Seed, SingularityType::TypeII),
            (theta_scheme, PsiModel::Seed, SingularityType::Regular),
            (
                psi_scheme,
                PsiModel::RelativeElbow,
                SingularityType::Regular,
            ),
        ],
    );

    // ψψψ, relative-elbow model: lines O_iC_i through Q (the text of Ramana Babu et al.,
    // Fig. 5).
    let bases = [0, 1, 2].map(|i| PLATFORM[i] + 3.5 * radial[i]);
    let elbows = [0, 1, 2].map(|i| bases[i] + 2.0 * rotate(-radial[i], 0.7));
    expect(
        bases,
        elbows,
        &[
            (psi_scheme, PsiModel::RelativeElbow, SingularityType::TypeII),
            (psi_scheme, PsiModel::Seed, SingularityType::Regular),
        ],
    );

    // Generic pose of the example design: regular for all schemes and both models.
    let design = RrrDesign::symmetric(5.0, 1.3, 3.0, 3.5).unwrap();
    let config = design
        .inverse_kinematics(&RrrPose::new(0.31, -0.27, 0.1), &POSITIVE_MODES)
        .unwrap();
    for scheme in Scheme::all() {
        for model in [PsiModel::Seed, PsiModel::RelativeElbow] {
            assert_eq!(
                classify(&design, &config, scheme, model, tol),
                SingularityType::Regular,
                "scheme {scheme} {model:?}"
            );
        }
    }
}

#[test]
fn type_i_fires_on_a_stretched_leg_for_every_scheme() {
    let tol = SingularityTolerance {
        leg: 1e-7,
        parallel: 1e-7,
    };
    let (r, a, b, c) = (5.0, 1.0, 2.0, 2.5);
    let design = RrrDesign::symmetric(r, a, b, c).unwrap();
    let config = design
        .inverse_kinematics(&RrrPose::new(0.0, r - a - b - c, 0.0), &POSITIVE_MODES)
        .unwrap();
    for scheme in Scheme::all() {
        let jac = jacobians(&config, scheme, PsiModel::Seed);
        assert!(jac.det_jq().abs() < 1e-9);
        let kind = classify(&design, &config, scheme, PsiModel::Seed, tol);
        assert!(
            matches!(kind, SingularityType::TypeI | SingularityType::TypeIII),
            "scheme {scheme}: {kind:?}"
        );
        assert!(jac.inverse_condition(Default::default(), None) < 1e-12);
    }
    // Slightly inside the workspace: no longer Type I at this tolerance.
    let config = design
        .inverse_kinematics(
            &RrrPose::new(0.0, r - a - b - c + 0.05, 0.0),
            &POSITIVE_MODES,
        )
        .unwrap();
    let kind = classify(
        &design,
        &config,
        Scheme::from_number(1).unwrap(),
        PsiModel::Seed,
        tol,
    );
    assert!(!matches!(
        kind,
        SingularityType::TypeI | SingularityType::TypeIII
    ));
}
