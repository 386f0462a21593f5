//! The nine extrinsic metrics (docs/theory.md §2, §3): axioms, invariance, hand-computed
//! values, summand counts and names.

use proptest::prelude::*;
use singdist::metric::{Metric, MetricError, Part, segment_distance_sq, triangle_distance_sq};

fn moved(k: &[f64; 12], angle: f64, t: [f64; 2]) -> [f64; 12] {
    let (s, c) = angle.sin_cos();
    let mut out = [0.0; 12];
    for j in 0..6 {
        let (x, y) = (k[2 * j], k[2 * j + 1]);
        out[2 * j] = t[0] + c * x - s * y;
        out[2 * j + 1] = t[1] + s * x + c * y;
    }
    out
}

fn configuration() -> impl Strategy<Value = [f64; 12]> {
    proptest::array::uniform12(-10.0f64..10.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn axioms_and_euclidean_invariance(
        k in configuration(),
        k2 in configuration(),
        angle in -3.2f64..3.2,
        tx in -20.0f64..20.0,
        ty in -20.0f64..20.0,
    ) {
        for metric in Metric::all() {
            prop_assert!(metric.distance(&k, &k) == 0.0);
            let d = metric.distance(&k, &k2);
            let d_back = metric.distance(&k2, &k);
            prop_assert!((d - d_back).abs() <= 1e-12 * (1.0 + d));
            let moved_d = metric.distance(&moved(&k, angle, [tx, ty]), &moved(&k2, angle, [tx, ty]));
            prop_assert!((d - moved_d).abs() <= 1e-9 * (1.0 + d), "{} {} {}", metric, d, moved_d);
            // D² is a sum of nonnegative terms: positive for distinct configurations.
            if metric.platform != Part::Rigid && metric.base != Part::Rigid {
                prop_assert!(d > 0.0);
            }
        }
    }

    /// seg² and tri² are mean squared distances: compare with numerical quadrature.
    #[test]
    fn segment_and_triangle_are_mean_squared_point_distances(
        p in proptest::array::uniform6(-5.0f64..5.0),
        q in proptest::array::uniform6(-5.0f64..5.0),
    ) {
        let pt = |v: &[f64; 6], i: usize| [v[2 * i], v[2 * i + 1]];
        let n = 400;
        let mut seg = 0.0;
        for j in 0..n {
            let s = (j as f64 + 0.5) / n as f64;
            let dx = (1.0 - s) * (q[0] - p[0]) + s * (q[2] - p[2]);
            let dy = (1.0 - s) * (q[1] - p[1]) + s * (q[3] - p[3]);
            seg += (dx * dx + dy * dy) / n as f64;
        }
        let exact = segment_distance_sq([&pt(&p, 0), &pt(&p, 1)], [&pt(&q, 0), &pt(&q, 1)]);
        prop_assert!((seg - exact).abs() < 1e-4 * (1.0 + exact));
        // Triangle: the displacement is affine, so its squared norm is quadratic and the
        // edge-midpoint rule integrates it exactly.
        let d = |i: usize| [q[2 * i] - p[2 * i], q[2 * i + 1] - p[2 * i + 1]];
        let mid = |i: usize, j: usize| {
            let (a, b) = (d(i), d(j));
            let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            m[0] * m[0] + m[1] * m[1]
        };
        let quad = (mid(0, 1) + mid(1, 2) + mid(2, 0)) / 3.0;
        let tri = triangle_distance_sq(
            [&pt(&p, 0), &pt(&p, 1), &pt(&p, 2)],
            [&pt(&q, 0), &pt(&q, 1), &pt(&q, 2)],
        );
        prop_assert!((quad - tri).abs() < 1e-10 * (1.0 + tri));
    }
}

#[test]
fn hand_computed_values() {
    // K: a = (0,0),(1,0),(0,1); b = (0,2),(1,2),(0,3). K′: b_1 moved by (1, 0).
    let k = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 2.0, 1.0, 2.0, 0.0, 3.0];
    let mut k2 = k;
    k2[6] += 1.0;
    // Leg 1: (0 + 1 + 0)/3 = 1/3. Platform plate: 1/6. Total 1/2, n = 5.
    let plate = Metric::new(Part::Plate, Part::Plate);
    assert!((plate.distance_sq(&k, &k2) - 0.1).abs() < 1e-15);
    // bars/bars: leg 1/3, platform edges 12 and 31 each 1/3: (1/3 + 2/3)/9.
    let bars = Metric::new(Part::Bars, Part::Bars);
    assert!((bars.distance_sq(&k, &k2) - 1.0 / 9.0).abs() < 1e-15);
    // rigid/rigid: only the legs, n = 3.
    let rigid = Metric::new(Part::Rigid, Part::Rigid);
    assert!((rigid.distance_sq(&k, &k2) - 1.0 / 9.0).abs() < 1e-15);
    // bars/plate: (1/3 + 2/3 + 0)/7.
    let m = Metric::new(Part::Bars, Part::Plate);
    assert!((m.distance(&k, &k2) - (1.0f64 / 7.0).sqrt()).abs() < 1e-15);
    assert_eq!(plate.summands(&k, &k2).len(), 5);
}

#[test]
fn number_of_summands_per_metric() {
    let expected = [
        ("plate/plate", 5),
        ("plate/bars", 7),
        ("plate/rigid", 4),
        ("bars/plate", 7),
        ("bars/bars", 9),
        ("bars/rigid", 6),
        ("rigid/plate", 4),
        ("rigid/bars", 6),
        ("rigid/rigid", 3),
    ];
    let k = [0.5; 12];
    for (metric, (name, n)) in Metric::all().iter().zip(expected) {
        assert_eq!(metric.name(), name);
        assert_eq!(metric.number_of_summands(), n, "{name}");
        assert_eq!(metric.summands(&k, &k).len(), n, "{name}");
    }
}

#[test]
fn names_round_trip_and_errors_list_valid_names() {
    for metric in Metric::all() {
        let parsed: Metric = metric.name().parse().unwrap();
        assert_eq!(parsed, metric);
        assert_eq!(metric.to_string(), metric.name());
    }
    assert_eq!(Metric::parse_list("all").unwrap().len(), 9);
    assert_eq!(
        Metric::parse_list("bars/rigid, plate/plate,bars/rigid").unwrap(),
        vec![
            Metric::new(Part::Bars, Part::Rigid),
            Metric::new(Part::Plate, Part::Plate)
        ]
    );
    let err = "plate/steel".parse::<Metric>().unwrap_err();
    let text = err.to_string();
    assert!(text.contains("plate/steel"), "{text}");
    for metric in Metric::all() {
        assert!(text.contains(&metric.name()), "{text}");
    }
    assert!(matches!(
        Metric::parse_list("plate"),
        Err(MetricError::UnknownMetric { .. })
    ));
    assert_eq!(Metric::parse_list(" , "), Err(MetricError::EmptyList));
}
