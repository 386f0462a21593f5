use super::*;
use crate::mechanism::rpr::{example_design, example_motion};

/// The predictors are exact on their model functions at any nodes: a quadratic
/// per coordinate for [`extrapolate`], a Möbius function (a simple pole at
/// `s = 2.5` and `s = −4`) for [`extrapolate_moebius`], which the quadratic misses.
#[test]
fn predictors_reproduce_their_model_functions() {
    let quadratic = |s: f64| {
        [
            C64::new(1.0 - 2.0 * s + 0.5 * s * s, s),
            C64::new(3.0, -s * s),
        ]
    };
    let moebius = |s: f64| {
        [
            C64::new(2.0 + 3.0 * s, 1.0) / (1.0 - 0.4 * s),
            C64::new(-1.0, 0.5 * s) / C64::new(1.0 + 0.25 * s, 0.1 * s),
        ]
    };
    let nodes_of = |at: &[f64; 3], values: &[[C64; 2]; 3]| -> Vec<(f64, Vec<C64>)> {
        at.iter()
            .zip(values)
            .map(|(&t, v)| (t, v.to_vec()))
            .collect()
    };
    for nodes_at in [[0.0, -1.0, -2.0], [0.5, 0.0, -1.0], [0.75, 0.5, 0.0]] {
        for s in [1.0, 0.875] {
            let mut out = [C64::new(0.0, 0.0); 2];
            let owned = nodes_of(&nodes_at, &nodes_at.map(quadratic));
            let nodes: Vec<Node<'_>> = owned.iter().map(|(t, v)| (*t, &v[..])).collect();
            extrapolate(&nodes, s, &mut out);
            let exact = quadratic(s);
            assert!(
                (0..2).all(|i| (out[i] - exact[i]).norm() < 1e-12),
                "{out:?} vs {exact:?}"
            );
            let owned = nodes_of(&nodes_at, &nodes_at.map(moebius));
            let nodes: Vec<Node<'_>> = owned.iter().map(|(t, v)| (*t, &v[..])).collect();
            extrapolate_moebius(&nodes, s, &mut out);
            let exact = moebius(s);
            assert!(
                (0..2).all(|i| (out[i] - exact[i]).norm() < 1e-10),
                "{out:?} vs {exact:?}"
            );
            extrapolate(&nodes, s, &mut out);
            assert!(
                (out[0] - exact[0]).norm() > 1e-3,
                "the quadratic should miss the pole"
            );
        }
    }
}

/// `MotionPath::point_and_velocity` is the derivative of `MotionPath::point`
/// (central differences in complex t), on every segment of a detoured path.
#[test]
fn motion_path_velocity_matches_finite_differences() {
    let design = example_design();
    let motion = example_motion();
    let seed = seed_point(&design, &motion, 3);
    let k0 = design
        .configuration(motion.pose(0.3).expect("pose"))
        .to_array();
    let normalization = Normalization::of(&to_real(&k0));
    let target = MotionPoint::Tau(C64::new(1.7, 0.0));
    let mut rng = random::stream(3, 99);
    let waypoints = vec![seed.point, target.perturbed(0.5, &mut rng), target];
    let path = MotionPath::new(
        &design,
        &motion,
        waypoints,
        seed.perturbation,
        normalization,
        vec![C64::new(0.4, 0.1); 6],
    );
    let m = path.len();
    let (mut p, mut dp, mut plus, mut minus) = (
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
        vec![C64::new(0.0, 0.0); m],
    );
    for t in [0.1, 0.37, 0.62, 0.9] {
        for direction in [C64::new(1.0, 0.0), C64::new(0.0, 1.0)] {
            let t = C64::new(t, 0.0);
            let h = direction * 1e-6;
            path.point_and_velocity(t, &mut p, &mut dp);
            path.point(t + h, &mut plus);
            path.point(t - h, &mut minus);
            for i in 0..m {
                let fd = (plus[i] - minus[i]) / (h * 2.0);
                assert!(
                    (fd - dp[i]).norm() <= 1e-6 * (1.0 + dp[i].norm()),
                    "t = {t}, i = {i}: {fd} vs {}",
                    dp[i]
                );
            }
        }
    }
}
