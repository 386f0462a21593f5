//! 3-RPR model: design validation, singularity polynomial (docs/theory.md §1.3), rigid
//! shapes (docs/theory.md §4), motions and the built-in example, design/motion files.

use nalgebra::Matrix3;
use singdist::C64;
use singdist::io::{load_design, load_motion};
use singdist::mechanism::InputNumberError;
use singdist::mechanism::rpr::{
    Design, Motion, Pose, PoseList, RprError, collinearity_base, collinearity_platform,
    example_design, example_motion, reconstruct_third_point, rigid_shape, singularity_polynomial,
};
use singdist::random::{seeded, uniform};

fn test_design() -> Design {
    Design::new(
        [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    )
    .unwrap()
}

#[test]
fn spec_test_vector_configuration_and_s() {
    let k = test_design().configuration(Pose::new(4.0, 3.0, 0.3));
    let expected_b = [[4.0, 3.0], [6.866009, 3.886561], [4.364296, 5.206193]];
    for (b, expected) in k.b.iter().zip(expected_b) {
        assert!((b[0] - expected[0]).abs() < 1e-6 && (b[1] - expected[1]).abs() < 1e-6);
    }
    assert!((k.singularity() - 125.29749).abs() < 1e-5);
    let arr = k.to_array();
    assert_eq!(arr[0..6], [0.0, 0.0, 10.0, 0.0, 4.0, 8.0]);
    assert_eq!(singdist::mechanism::rpr::Configuration::from_array(&arr), k);
}

/// Independent computation: S = l1 l2 l3 det J with J rows [u_i, (b_i − t) × u_i].
#[test]
fn s_equals_leg_lengths_times_det_inverse_jacobian() {
    let mut rng = seeded(11);
    for _ in 0..200 {
        let mut pts = [[0.0; 2]; 6];
        for p in pts.iter_mut() {
            *p = [uniform(&mut rng, -5.0, 5.0), uniform(&mut rng, -5.0, 5.0)];
        }
        let design = Design::new([pts[0], pts[1], pts[2]], [pts[3], pts[4], pts[5]]).unwrap();
        let pose = Pose::new(
            uniform(&mut rng, -3.0, 3.0),
            uniform(&mut rng, -3.0, 3.0),
            uniform(&mut rng, -3.2, 3.2),
        );
        let k = design.configuration(pose);
        let mut j = Matrix3::zeros();
        let mut lengths = 1.0;
        for i in 0..3 {
            let d = [k.b[i][0] - k.a[i][0], k.b[i][1] - k.a[i][1]];
            let l = d[0].hypot(d[1]);
            lengths *= l;
            let u = [d[0] / l, d[1] / l];
            let r = [k.b[i][0] - pose.x, k.b[i][1] - pose.y];
            j[(i, 0)] = u[0];
            j[(i, 1)] = u[1];
            j[(i, 2)] = r[0] * u[1] - r[1] * u[0];
        }
        let s = k.singularity();
        let direct = lengths * j.determinant();
        assert!(
            (s - direct).abs() <= 1e-9 * (1.0 + s.abs()),
            "S = {s}, l1l2l3 det J = {direct}"
        );
    }
}

#[test]
fn s_sign_follows_permutation_parity_under_relabelling() {
    let mut rng = seeded(12);
    let perms: [([usize; 3], f64); 6] = [
        ([0, 1, 2], 1.0),
        ([1, 2, 0], 1.0),
        ([2, 0, 1], 1.0),
        ([1, 0, 2], -1.0),
        ([0, 2, 1], -1.0),
        ([2, 1, 0], -1.0),
    ];
    for _ in 0..50 {
        let k: [f64; 12] = std::array::from_fn(|_| uniform(&mut rng, -4.0, 4.0));
        let s = singularity_polynomial(&k);
        for (perm, sign) in perms {
            let mut q = [0.0; 12];
            for (new, &old) in perm.iter().enumerate() {
                q[2 * new] = k[2 * old];
                q[2 * new + 1] = k[2 * old + 1];
                q[6 + 2 * new] = k[6 + 2 * old];
                q[6 + 2 * new + 1] = k[6 + 2 * old + 1];
            }
            let sp = singularity_polynomial(&q);
            assert!((sp - sign * s).abs() < 1e-9 * (1.0 + s.abs()), "{perm:?}");
        }
    }
}

#[test]
fn s_vanishes_for_concurrent_and_parallel_legs() {
    // Legs through the common point (1, 1).
    let k = [0.0, 0.0, 3.0, 0.0, 0.0, 4.0, 2.0, 2.0, -1.0, 2.0, 2.0, -2.0];
    assert!(singularity_polynomial(&k).abs() < 1e-12);
    // Three parallel legs (direction (1, 2)).
    let k = [0.0, 0.0, 1.0, 0.0, 5.0, 1.0, 1.0, 2.0, 3.0, 4.0, 4.0, -1.0];
    assert!(singularity_polynomial(&k).abs() < 1e-12);
    // A generic configuration is not singular.
    let k = [0.0, 0.0, 1.0, 0.0, 5.0, 1.0, 1.0, 2.0, 3.0, 4.0, 4.0, 1.0];
    assert!(singularity_polynomial(&k).abs() > 1e-3);
}

#[test]
fn collinearity_is_twice_the_signed_area() {
    let k = [0.0, 0.0, 4.0, 0.0, 0.0, 3.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0];
    assert!((collinearity_base(&k) - 12.0).abs() < 1e-12);
    assert!(collinearity_platform(&k).abs() < 1e-12);
}

#[test]
fn complex_configuration_matches_real_and_is_analytic() {
    let design = test_design();
    let pose = Pose::new(1.5, -0.5, 0.7);
    let real = design.configuration(pose).to_array();
    let complex =
        design.configuration_complex(C64::new(1.5, 0.0), C64::new(-0.5, 0.0), C64::new(0.7, 0.0));
    for j in 0..12 {
        assert!((complex[j] - real[j]).norm() < 1e-14);
    }
    // At complex φ the platform stays congruent in the complex sense: |b2 − b1|² (bilinear) = |P2 − P1|².
    let k =
        design.configuration_complex(C64::new(0.3, 1.1), C64::new(-2.0, 0.4), C64::new(0.5, -0.8));
    let dx = k[8] - k[6];
    let dy = k[9] - k[7];
    assert!((dx * dx + dy * dy - 9.0).norm() < 1e-12);
}

#[test]
fn rigid_shape_reconstructs_third_point_after_rigid_motion() {
    let mut rng = seeded(13);
    for _ in 0..50 {
        let p: [[f64; 2]; 3] =
            std::array::from_fn(|_| [uniform(&mut rng, -3.0, 3.0), uniform(&mut rng, -3.0, 3.0)]);
        let shape = rigid_shape(&p[0], &p[1], &p[2]);
        let (s, c) = uniform(&mut rng, -3.0, 3.0).sin_cos();
        let t = [uniform(&mut rng, -3.0, 3.0), uniform(&mut rng, -3.0, 3.0)];
        let m = |q: [f64; 2]| [t[0] + c * q[0] - s * q[1], t[1] + s * q[0] + c * q[1]];
        let q3 = reconstruct_third_point(&m(p[0]), &m(p[1]), shape.u, shape.v);
        let e = m(p[2]);
        assert!((q3[0] - e[0]).abs() < 1e-10 && (q3[1] - e[1]).abs() < 1e-10);
        let d = [p[1][0] - p[0][0], p[1][1] - p[0][1]];
        assert!((shape.r2 - (d[0] * d[0] + d[1] * d[1])).abs() < 1e-12);
    }
}

#[test]
fn design_validation_names_the_field() {
    let base = [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]];
    // Two coincident anchors are a legitimate robot (Kapilavai and Nawratil, Lemma 2).
    assert!(Design::new(base, [[0.0, 0.0], [0.0, 0.0], [1.0, 2.0]]).is_ok());
    let err = Design::new(
        [[0.0, 0.0], [10.0, f64::NAN], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    )
    .unwrap_err();
    assert!(
        matches!(err, RprError::Number(InputNumberError::NotFinite { ref field, .. }) if field == "base[1].y")
    );
    assert!(err.to_string().contains("base[1].y"));
    // A base collapsed to a point.
    let err = Design::new([[1.0, 1.0]; 3], [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]]).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("base: collapsed to a point (all three anchors coincide)"),
        "{err}"
    );
    // Three distinct but collinear anchors are a valid design.
    assert!(Design::new([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], base).is_ok());
}

#[test]
fn example_motion_crosses_the_singularity_variety_exactly_twice() {
    let design = example_design();
    let motion = example_motion();
    motion.validate().unwrap();
    let samples = motion.sample(20001);
    assert_eq!(samples.len(), 20001);
    assert_eq!(samples[0].tau, -1.0);
    assert_eq!(samples[20000].tau, 4.5);
    let values: Vec<f64> = samples
        .iter()
        .map(|s| design.configuration(s.pose).singularity())
        .collect();
    let crossings: Vec<f64> = (0..values.len() - 1)
        .filter(|&j| values[j] * values[j + 1] < 0.0)
        .map(|j| samples[j].tau)
        .collect();
    assert_eq!(crossings.len(), 2, "{crossings:?}");
    assert!((crossings[0] + 0.086).abs() < 0.01 && (crossings[1] - 3.107).abs() < 0.01);
    // Apart from the crossings S stays clear of 0: no tangential touching.
    let far: f64 = samples
        .iter()
        .zip(&values)
        .filter(|(s, _)| crossings.iter().all(|c| (s.tau - c).abs() > 0.1))
        .map(|(_, v)| v.abs())
        .fold(f64::INFINITY, f64::min);
    assert!(far > 1.0, "{far}");
}

#[test]
fn example_files_equal_the_built_in_example() {
    let root = env!("CARGO_MANIFEST_DIR");
    let design = load_design(format!("{root}/systems/rpr_example_design.json")).unwrap();
    assert_eq!(design, example_design());
    let motion = load_motion(format!("{root}/systems/rpr_example_motion.json")).unwrap();
    assert_eq!(motion, example_motion());
}

#[test]
fn motion_evaluates_at_complex_tau_consistently() {
    let motion = example_motion();
    for tau in [-1.0, 0.0, 1.3, 4.5] {
        let real = motion.pose(tau).unwrap();
        let complex = motion.pose_complex(C64::new(tau, 0.0)).unwrap();
        assert!((complex[0] - real.x).norm() < 1e-14);
        assert!((complex[1] - real.y).norm() < 1e-14);
        assert!((complex[2] - real.phi).norm() < 1e-14);
    }
    // Analytic continuation: sin(τ) at τ = i is i sinh(1).
    let z = motion.pose_complex(C64::new(0.0, 1.0)).unwrap();
    assert!((z[0] - C64::new(4.0, 1f64.sinh())).norm() < 1e-12);
    let list = Motion::Poses(PoseList {
        poses: vec![Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.0, 0.1)],
    });
    assert!(list.pose_complex(C64::new(0.5, 0.1)).is_none());
    assert_eq!(list.sample(100).len(), 2);
    // Serde round trip of both forms.
    for m in [motion, list] {
        let text = serde_json::to_string(&m).unwrap();
        let back: Motion = serde_json::from_str(&text).unwrap();
        assert_eq!(back, m);
    }
}

fn write_temp(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("singdist-rpr-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn file_errors_name_file_and_field() {
    // The message of loading a file as a design or as a motion.
    type Loader = fn(&std::path::Path) -> String;
    let design: Loader = |path| load_design(path).unwrap_err().to_string();
    let motion: Loader = |path| load_motion(path).unwrap_err().to_string();
    let cases: [(Loader, &str, &str, &str); 11] = [
        (
            design,
            "malformed.json",
            "{\"base\": [[0,0],",
            "malformed JSON",
        ),
        (
            design,
            "missing.json",
            "{\"base\": [[0,0],[1,0],[0,1]]}",
            "platform: missing field",
        ),
        (
            design,
            "short.json",
            "{\"base\": [[0,0],[1,0],[0,1]], \"platform\": [[0,0],[1,0,3],[0,1]]}",
            "platform[1]: expected an array of 2 numbers, got 3 elements",
        ),
        (
            design,
            "two.json",
            "{\"base\": [[0,0],[1,0]], \"platform\": [[0,0],[1,0],[0,1]]}",
            "base: expected 3 anchors",
        ),
        (
            design,
            "string.json",
            "{\"base\": [[0,0],[1,\"x\"],[0,1]], \"platform\": [[0,0],[1,0],[0,1]]}",
            "base[1][1]: expected a number, got a string",
        ),
        (
            design,
            "nan.json",
            "{\"base\": [[0,0],[1,NaN],[0,1]], \"platform\": [[0,0],[1,0],[0,1]]}",
            "malformed JSON",
        ),
        (
            design,
            "collapsed.json",
            "{\"base\": [[0,0],[1,0],[0,1]], \"platform\": [[2,1],[2,1],[2,1]]}",
            "platform: collapsed to a point",
        ),
        (
            motion,
            "m1.json",
            "{\"poses\": [[0,0,0],[1,2]]}",
            "poses[1]: expected an array of 3",
        ),
        (
            motion,
            "m2.json",
            "{\"poses\": []}",
            "poses: the pose list is empty",
        ),
        (
            motion,
            "m3.json",
            "{\"tau_range\": [1, 0], \"x\": {}, \"y\": {}, \"phi\": {}}",
            "tau_range: must be two finite numbers",
        ),
        (
            motion,
            "m4.json",
            "{\"tau_range\": [0, 1], \"x\": {\"cosines\": [[1, 2]]}, \"y\": {}, \"phi\": {}}",
            "x.cosines[0]: expected an array of 3 numbers",
        ),
    ];
    for (load, name, text, expected) in cases {
        let err = load(&write_temp(name, text));
        assert!(
            err.contains(name) && err.contains(expected),
            "{name}: {err}"
        );
    }
    let err = load_design("/nonexistent/d.json").unwrap_err().to_string();
    assert!(err.contains("/nonexistent/d.json: cannot read"), "{err}");
}

/// The generic formulas give the same numbers in f64 and C64 (the ring the seeds of the
/// parameter homotopy live in), and S at a complex pose is the complex continuation.
#[test]
fn generic_formulas_agree_between_real_and_complex_rings() {
    use singdist::metric::Metric;
    let mut rng = seeded(14);
    for _ in 0..20 {
        let k: [f64; 12] = std::array::from_fn(|_| uniform(&mut rng, -4.0, 4.0));
        let k2: [f64; 12] = std::array::from_fn(|_| uniform(&mut rng, -4.0, 4.0));
        let kc = k.map(|v| C64::new(v, 0.0));
        let k2c = k2.map(|v| C64::new(v, 0.0));
        assert!((singularity_polynomial(&kc) - singularity_polynomial(&k)).norm() < 1e-9);
        assert!((collinearity_platform(&kc) - collinearity_platform(&k)).norm() < 1e-12);
        for metric in Metric::all() {
            let real = metric.distance_sq(&k, &k2);
            assert!((metric.distance_sq(&kc, &k2c) - real).norm() < 1e-12 * (1.0 + real));
        }
    }
    // Complex pose: S(K(τ)) along the analytic motion is holomorphic, so its value at
    // τ + ih matches the Taylor expansion from real τ to first order.
    let design = example_design();
    let motion = example_motion();
    let s_at = |tau: C64| {
        let [x, y, phi] = motion.pose_complex(tau).unwrap();
        singularity_polynomial(&design.configuration_complex(x, y, phi))
    };
    let tau = 1.0;
    let h = 1e-5;
    let derivative = (s_at(C64::new(tau + h, 0.0)) - s_at(C64::new(tau - h, 0.0))) / (2.0 * h);
    let predicted = s_at(C64::new(tau, 0.0)) + C64::new(0.0, h) * derivative;
    assert!((s_at(C64::new(tau, h)) - predicted).norm() < 1e-6 * (1.0 + derivative.norm()));
}

#[test]
fn conditioned_labelling_takes_the_longest_reference_edge() {
    // Base anchors 1 and 2 coincide, platform anchors 2 and 3 nearly do.
    let design = Design::new(
        [[0.0, 0.0], [0.0, 0.0], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [3.0, 1e-4]],
    )
    .unwrap();
    for (rigid_base, rigid_platform) in [(true, false), (false, true), (true, true)] {
        let labels = design.conditioned_labelling(rigid_base, rigid_platform);
        let relabelled = design.relabelled(labels);
        for (i, &user) in labels.iter().enumerate() {
            assert_eq!(relabelled.base()[i], design.base()[user]);
            assert_eq!(relabelled.platform()[i], design.platform()[user]);
        }
        let edge =
            |p: &[[f64; 2]; 3]| ((p[1][0] - p[0][0]).powi(2) + (p[1][1] - p[0][1]).powi(2)).sqrt();
        if rigid_base {
            assert!(edge(relabelled.base()) >= 8.0, "{labels:?}");
            let shape = relabelled.base_shape();
            assert!(shape.u.is_finite() && shape.v.is_finite() && shape.r2 > 0.0);
        }
        if rigid_platform {
            assert!(edge(relabelled.platform()) >= 1.5, "{labels:?}");
        }
    }
    // No rigid part, or a well-conditioned user labelling: the identity.
    assert_eq!(design.conditioned_labelling(false, false), [0, 1, 2]);
    let example = Design::new(
        [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    )
    .unwrap();
    assert_eq!(example.conditioned_labelling(true, true), [0, 1, 2]);
    // A collapsed part is rejected with a clear message.
    let err = Design::new(design.base().to_owned(), [[1.0, 1.0]; 3]).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("platform: collapsed to a point"),
        "{err}"
    );
}

/// Design and motion files are read exactly as written: every number's shortest
/// round-trip decimal (as `{:?}` and serde print it) parses back to the same double.
/// The default `serde_json` float parser may be one unit in the last place off, and on
/// a base with two anchors 10⁻⁴ apart such a difference in the design, a pose or a
/// stored start solution changed a curve's run time from 4.9 s to 7.5 s.
#[test]
fn design_and_motion_files_are_read_to_the_last_bit() {
    let (x, y) = (-0.18453416024607766_f64, 0.9491201413076239_f64);
    let design = write_temp(
        "exact_design.json",
        &format!(
            r#"{{"base": [[{x:?}, {y:?}], [1.0, 0.0], [0.3, 1.1]], "platform": [[0.0, 0.0], [0.5, 0.0], [0.2, 0.4]]}}"#
        ),
    );
    let motion = write_temp(
        "exact_motion.json",
        &format!(r#"{{"poses": [[{x:?}, {y:?}, -0.2316706902576993]]}}"#),
    );
    let loaded = load_design(&design).unwrap();
    assert_eq!(loaded.base()[0][0].to_bits(), x.to_bits());
    assert_eq!(loaded.base()[0][1].to_bits(), y.to_bits());
    let Motion::Poses(list) = load_motion(&motion).unwrap() else {
        panic!("a pose list");
    };
    assert_eq!(list.poses[0].x.to_bits(), x.to_bits());
    assert_eq!(list.poses[0].y.to_bits(), y.to_bits());
}
