//! Kinematic performance indices of a 3-RPR (docs/theory.md §9).

use nalgebra::Vector3;
use singdist::index::rpr::{
    CnVariant, DsAggregate, IndexOptions, Legs, SingularConic, SingularOrientations,
    compute_indices, control_number, incircle_radius, orientation_singularity_distance,
    position_singularity_distance, pressure_cosines, singular_orientations,
    singularity_free_cylinder_radius,
};
use singdist::index::rpr::{IndexVariants, RprIndices};
use singdist::mechanism::rpr::{Configuration, Design, Pose};
use singdist::random::{seeded, uniform};

fn design() -> Design {
    Design::new(
        [[0.0, 0.0], [10.0, 0.0], [4.0, 8.0]],
        [[0.0, 0.0], [3.0, 0.0], [1.0, 2.0]],
    )
    .unwrap()
}

fn pose() -> Pose {
    Pose::new(4.0, 3.0, 0.3)
}

fn close(value: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (value - expected).abs() <= tol,
        "{what}: {value} vs expected {expected}"
    );
}

#[test]
fn spec_test_vector() {
    let r = compute_indices(&design(), pose(), &IndexOptions::default());
    close(r.s, 125.29749, 1e-5, "S");
    close(r.m.unwrap(), 1.781467, 1e-6, "M");
    let cos = r.pressure_cosines.unwrap();
    for (c, e) in cos.iter().zip([0.787796, 0.883815, 0.918092]) {
        close(*c, e, 1e-6, "cos alpha");
    }
    close(r.ti.unwrap(), 0.787796, 1e-6, "TI");
    let cos_star = r.pressure_cosines_exchanged.unwrap();
    for (c, e) in cos_star.iter().zip([0.406690, 0.319097, 0.445024]) {
        close(*c, e, 1e-6, "cos alpha*");
    }
    close(r.mti.unwrap(), 0.319097, 1e-6, "MTI");
    close(r.ds.unwrap(), 0.787796 * 0.883815 * 0.918092, 1e-6, "DS");
    close(r.mds.unwrap(), 0.406690 * 0.319097 * 0.445024, 1e-6, "MDS");
    close(r.ir.unwrap(), 0.744749, 1e-6, "IR");
    close(r.lambda_min.unwrap(), 0.0399153, 1e-6, "lambda_min");
    close(r.lambda_max.unwrap(), 3.574523, 1e-6, "lambda_max");
    close(r.cn.unwrap(), 0.0111666, 1e-6, "CN");
    close(r.mcn.unwrap(), 0.528921, 1e-6, "MCN");
    let conic = SingularConic::at_orientation(&design(), 0.3);
    let expected = [-7.092485, 4.412386, -7.821077, 56.605541, 9.932048, 0.0];
    let got = [
        conic.cxx, conic.cxy, conic.cyy, conic.cx, conic.cy, conic.c0,
    ];
    for (g, e) in got.iter().zip(expected) {
        close(*g, e, 1e-6, "conic");
    }
    close(
        r.position_distance.unwrap(),
        2.589166,
        1e-6,
        "position distance",
    );
    let foot = r.position_foot.unwrap();
    close(foot[0], 2.43476, 1e-5, "foot x");
    close(foot[1], 5.06248, 1e-5, "foot y");
    match singular_orientations(&design(), 4.0, 3.0) {
        SingularOrientations::Finite(roots) => {
            assert_eq!(roots.len(), 2, "{roots:?}");
            close(roots[0], 3.111238, 1e-6, "orientation root 1");
            close(roots[1], 6.194301, 1e-6, "orientation root 2");
        }
        other => panic!("{other:?}"),
    }
    close(
        r.orientation_distance.unwrap(),
        0.388884,
        1e-6,
        "orientation distance",
    );
    close(
        r.orientation_distance_signed.unwrap(),
        0.388884,
        1e-6,
        "signed (S > 0)",
    );
    let cyl = singularity_free_cylinder_radius(&design(), 4.0, 3.0, [0.2, 0.4])
        .unwrap()
        .unwrap();
    close(cyl.radius, 2.54565, 1e-5, "cylinder radius");
    close(cyl.at_phi, 0.4, 1e-6, "cylinder phi");
}

fn random_design(rng: &mut singdist::random::SeededRng) -> Design {
    let mut p = [[0.0; 2]; 6];
    for q in p.iter_mut() {
        *q = [uniform(rng, -5.0, 5.0), uniform(rng, -5.0, 5.0)];
    }
    Design::new([p[0], p[1], p[2]], [p[3], p[4], p[5]]).unwrap()
}

fn random_pose(rng: &mut singdist::random::SeededRng) -> Pose {
    Pose::new(
        uniform(rng, -3.0, 3.0),
        uniform(rng, -3.0, 3.0),
        uniform(rng, -3.2, 3.2),
    )
}

/// Twist (v, ω) when leg i is driven alone at unit speed: J⁻¹ e_i.
fn twist(k: &Configuration, pose: Pose, leg: usize) -> Option<Vector3<f64>> {
    let legs = Legs::new(k)?;
    let j = legs.inverse_jacobian(&[pose.x, pose.y]);
    let mut e = Vector3::zeros();
    e[leg] = 1.0;
    j.lu().solve(&e)
}

#[test]
fn pressure_angles_equal_the_direct_velocity_computation() {
    let mut rng = seeded(21);
    for _ in 0..200 {
        let design = random_design(&mut rng);
        let pose = random_pose(&mut rng);
        let k = design.configuration(pose);
        let (Some(cos), Some(cos_star)) = (pressure_cosines(&k, false), pressure_cosines(&k, true))
        else {
            panic!("undefined at a random pose");
        };
        for i in 0..3 {
            let w = twist(&k, pose, i).unwrap();
            // Velocity of b_i (and of a_i relative to the platform): v + ω E(p − t).
            let velocity =
                |p: [f64; 2]| [w[0] - w[2] * (p[1] - pose.y), w[1] + w[2] * (p[0] - pose.x)];
            let vb = velocity(k.b[i]);
            let va = velocity(k.a[i]);
            // u_i · ḃ_i = 1, so |cos α_i| = 1/|ḃ_i|.
            let direct = 1.0 / vb[0].hypot(vb[1]);
            let direct_star = 1.0 / va[0].hypot(va[1]);
            assert!(
                (cos[i] - direct).abs() < 1e-8 * (1.0 + direct),
                "{} {}",
                cos[i],
                direct
            );
            assert!(
                (cos_star[i] - direct_star).abs() < 1e-8 * (1.0 + direct_star),
                "{} {}",
                cos_star[i],
                direct_star
            );
        }
    }
}

#[test]
fn conic_equals_s_on_a_grid() {
    let mut rng = seeded(22);
    for _ in 0..20 {
        let design = random_design(&mut rng);
        let phi = uniform(&mut rng, -3.2, 3.2);
        let conic = SingularConic::at_orientation(&design, phi);
        for ix in -5..=5 {
            for iy in -5..=5 {
                let (x, y) = (ix as f64 * 1.7, iy as f64 * 1.3);
                let s = design.configuration(Pose::new(x, y, phi)).singularity();
                let c = conic.value(&[x, y]);
                assert!((s - c).abs() < 1e-9 * (1.0 + s.abs()), "{s} vs {c}");
            }
        }
    }
}

#[test]
fn orientation_roots_make_s_vanish_and_match_sign_changes() {
    let mut rng = seeded(23);
    for _ in 0..100 {
        let design = random_design(&mut rng);
        let (x, y) = (uniform(&mut rng, -3.0, 3.0), uniform(&mut rng, -3.0, 3.0));
        let SingularOrientations::Finite(roots) = singular_orientations(&design, x, y) else {
            panic!("a random position is not singular at every orientation");
        };
        let s = |phi: f64| design.configuration(Pose::new(x, y, phi)).singularity();
        let scale = (0..64)
            .map(|j| s(j as f64 * 0.1).abs())
            .fold(0.0_f64, f64::max);
        for &r in &roots {
            assert!(s(r).abs() < 1e-9 * scale, "S({r}) = {}", s(r));
        }
        // Independent count: sign changes on a fine grid (odd-multiplicity roots).
        let n = 20000;
        let values: Vec<f64> = (0..=n)
            .map(|j| s(std::f64::consts::TAU * j as f64 / n as f64))
            .collect();
        let changes = (0..n).filter(|&j| values[j] * values[j + 1] < 0.0).count();
        assert_eq!(changes, roots.len(), "{roots:?}");
        assert!(roots.len() <= 6 && roots.len() % 2 == 0);
    }
}

#[test]
fn position_distance_matches_brute_force_over_rays() {
    let mut rng = seeded(24);
    let mut checked = 0;
    for _ in 0..60 {
        let design = random_design(&mut rng);
        let pose = random_pose(&mut rng);
        let conic = SingularConic::at_orientation(&design, pose.phi);
        let brute = (0..20000)
            .filter_map(|j| {
                let (sn, cs) = (std::f64::consts::TAU * j as f64 / 20000.0).sin_cos();
                // Q(p0 + r e) = A r² + B r + C.
                let p0 = [pose.x, pose.y];
                let c = conic.value(&p0);
                let q1 = conic.value(&[p0[0] + cs, p0[1] + sn]);
                let qm = conic.value(&[p0[0] - cs, p0[1] - sn]);
                let a = (q1 + qm - 2.0 * c) / 2.0;
                let b = (q1 - qm) / 2.0;
                let roots: Vec<f64> = if a.abs() < 1e-300 {
                    vec![-c / b]
                } else {
                    let disc = b * b - 4.0 * a * c;
                    if disc < 0.0 {
                        vec![]
                    } else {
                        vec![
                            (-b - disc.sqrt()) / (2.0 * a),
                            (-b + disc.sqrt()) / (2.0 * a),
                        ]
                    }
                };
                roots.into_iter().filter(|r| *r >= 0.0).reduce(f64::min)
            })
            .reduce(f64::min);
        let ours = position_singularity_distance(&design, pose).map(|p| p.distance);
        match (brute, ours) {
            (Some(b), Some(o)) => {
                assert!(o <= b + 1e-9 * (1.0 + b), "ours {o} > brute {b}");
                assert!(b - o < 1e-3 * (1.0 + b), "ours {o} << brute {b}");
                checked += 1;
            }
            (None, None) => {}
            other => panic!("{other:?}"),
        }
        let o = ours.unwrap_or(0.0);
        let s = design.configuration(pose).singularity();
        let signed = position_singularity_distance(&design, pose).map(|p| p.signed);
        if let Some(signed) = signed {
            assert_eq!(signed, o * s.signum());
        }
    }
    assert!(checked > 40);
}

/// The same manipulator seen from the platform: design with base and platform exchanged
/// at the inverse pose.
fn exchanged(design: &Design, pose: Pose) -> (Design, Pose) {
    let (s, c) = pose.phi.sin_cos();
    // Inverse pose: R(−φ), −R(−φ) t.
    let x = -(c * pose.x + s * pose.y);
    let y = -(-s * pose.x + c * pose.y);
    (design.exchanged(), Pose::new(x, y, -pose.phi))
}

fn moved(design: &Design, pose: Pose, angle: f64, t: [f64; 2]) -> (Design, Pose) {
    let (s, c) = angle.sin_cos();
    let g = |p: [f64; 2]| [t[0] + c * p[0] - s * p[1], t[1] + s * p[0] + c * p[1]];
    let base = design.base().map(g);
    let position = g([pose.x, pose.y]);
    (
        Design::new(base, *design.platform()).unwrap(),
        Pose::new(position[0], position[1], pose.phi + angle),
    )
}

#[test]
fn cn_and_mti_are_invariant_under_exchange_and_rigid_motion() {
    let mut rng = seeded(25);
    let options = IndexOptions::default();
    for _ in 0..100 {
        let design = random_design(&mut rng);
        let pose = random_pose(&mut rng);
        let r = compute_indices(&design, pose, &options);
        let (d2, p2) = exchanged(&design, pose);
        let (d3, p3) = moved(&design, pose, uniform(&mut rng, -3.0, 3.0), [2.0, -7.0]);
        // The exchanged configuration is congruent to K with a_i ↔ b_i.
        let k = design.configuration(pose);
        let k2 = d2.configuration(p2);
        for i in 0..3 {
            let dk = (k.b[i][0] - k.a[i][0]).hypot(k.b[i][1] - k.a[i][1]);
            let dk2 = (k2.b[i][0] - k2.a[i][0]).hypot(k2.b[i][1] - k2.a[i][1]);
            assert!((dk - dk2).abs() < 1e-9);
        }
        let rel = |a: f64, b: f64| (a - b).abs() <= 1e-7 * (a.abs() + b.abs() + 1e-12);
        for (other, what) in [
            (compute_indices(&d2, p2, &options), "exchange"),
            (compute_indices(&d3, p3, &options), "motion"),
        ] {
            assert!(rel(r.cn.unwrap(), other.cn.unwrap()), "CN {what}");
            assert!(rel(r.mcn.unwrap(), other.mcn.unwrap()), "MCN {what}");
            assert!(rel(r.mti.unwrap(), other.mti.unwrap()), "MTI {what}");
            assert!(rel(r.mds.unwrap(), other.mds.unwrap()), "MDS {what}");
            assert!(rel(r.m.unwrap(), other.m.unwrap()), "M {what}");
            assert!(rel(r.ir.unwrap(), other.ir.unwrap()), "IR {what}");
        }
        let moved_r = compute_indices(&d3, p3, &options);
        assert!(rel(r.ti.unwrap(), moved_r.ti.unwrap()));
        assert!(rel(r.s, moved_r.s));
        // Exchange swaps the viewpoints: TI ↔ TI*.
        let ex = compute_indices(&d2, p2, &options);
        assert!(rel(
            r.ti.unwrap(),
            min3(ex.pressure_cosines_exchanged.unwrap())
        ));
        assert!(rel(
            ex.ti.unwrap(),
            min3(r.pressure_cosines_exchanged.unwrap())
        ));
        if let (Some(a), Some(b)) = (r.position_distance, moved_r.position_distance) {
            assert!(
                (a - b).abs() < 1e-7 * (1.0 + a),
                "position distance {a} {b}"
            );
        }
    }
}

fn min3(c: [f64; 3]) -> f64 {
    c[0].min(c[1]).min(c[2])
}

#[test]
fn indices_vanish_at_a_singular_pose() {
    let design = design();
    let SingularOrientations::Finite(roots) = singular_orientations(&design, 4.0, 3.0) else {
        panic!()
    };
    let options = IndexOptions::default();
    for phi in roots {
        let r = compute_indices(&design, Pose::new(4.0, 3.0, phi), &options);
        assert!(r.s.abs() < 1e-9, "S = {}", r.s);
        for (name, value) in [
            ("M", r.m),
            ("IR", r.ir),
            ("TI", r.ti),
            ("DS", r.ds),
            ("MTI", r.mti),
            ("MDS", r.mds),
            ("CN", r.cn),
            ("MCN", r.mcn),
            ("orientation_distance", r.orientation_distance),
            ("position_distance", r.position_distance),
            ("cylinder_radius", r.cylinder_radius),
        ] {
            let v = value.unwrap_or_else(|| panic!("{name} undefined"));
            assert!(v.abs() < 1e-7, "{name} = {v}");
        }
    }
    // Distances grow from 0 on both sides and the signed ones change sign.
    let before = compute_indices(&design, Pose::new(4.0, 3.0, 3.0), &options);
    let after = compute_indices(&design, Pose::new(4.0, 3.0, 3.2), &options);
    let (b, a) = (
        before.position_distance_signed.unwrap(),
        after.position_distance_signed.unwrap(),
    );
    assert!(b * a < 0.0, "{b} {a}");
    let (b, a) = (
        before.orientation_distance_signed.unwrap(),
        after.orientation_distance_signed.unwrap(),
    );
    assert!(b * a < 0.0 && (b.abs() - 0.111238).abs() < 1e-6, "{b} {a}");
}

/// Independent incircle radius: vertices by intersection, r = 2·area / perimeter.
fn incircle_by_vertices(k: &Configuration) -> f64 {
    let line = |i: usize| {
        let (a, b) = (k.a[i], k.b[i]);
        [a[1] - b[1], b[0] - a[0], a[0] * b[1] - a[1] * b[0]]
    };
    let meet = |l: [f64; 3], m: [f64; 3]| {
        let w = l[0] * m[1] - l[1] * m[0];
        [
            (l[1] * m[2] - l[2] * m[1]) / w,
            (l[2] * m[0] - l[0] * m[2]) / w,
        ]
    };
    let t = [
        meet(line(0), line(1)),
        meet(line(1), line(2)),
        meet(line(2), line(0)),
    ];
    let area2 = ((t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
        - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]))
        .abs();
    let side = |i: usize, j: usize| (t[i][0] - t[j][0]).hypot(t[i][1] - t[j][1]);
    area2 / (side(0, 1) + side(1, 2) + side(2, 0))
}

#[test]
fn incircle_radius_matches_vertex_formula_and_is_continuous_at_parallel_legs() {
    let mut rng = seeded(26);
    for _ in 0..100 {
        let design = random_design(&mut rng);
        let k = design.configuration(random_pose(&mut rng));
        let ours = incircle_radius(&k).unwrap();
        let direct = incircle_by_vertices(&k);
        assert!(
            (ours - direct).abs() < 1e-7 * (1.0 + direct),
            "{ours} {direct}"
        );
    }
    // Legs 1 and 2 parallel (direction (0, 1)) at separation 4, leg 3 oblique.
    let parallel = |eps: f64| Configuration {
        a: [[0.0, 0.0], [4.0, 0.0], [-1.0, 1.0]],
        b: [[0.0, 3.0], [4.0 + eps, 3.0], [5.0, 2.0]],
    };
    assert!((incircle_radius(&parallel(0.0)).unwrap() - 2.0).abs() < 1e-12);
    for eps in [1e-3, -1e-3, 1e-6, -1e-6] {
        let r = incircle_radius(&parallel(eps)).unwrap();
        assert!((r - 2.0).abs() < 10.0 * eps.abs(), "eps {eps}: {r}");
        let direct = incircle_by_vertices(&parallel(eps));
        assert!((r - direct).abs() < 1e-6, "{r} {direct}");
    }
    // Three parallel legs: 0 (documented convention); concurrent legs: 0.
    let all_parallel = Configuration {
        a: [[0.0, 0.0], [4.0, 0.0], [-1.0, 1.0]],
        b: [[0.0, 3.0], [4.0, 3.0], [-1.0, 5.0]],
    };
    assert_eq!(incircle_radius(&all_parallel), Some(0.0));
    let concurrent = Configuration {
        a: [[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]],
        b: [[2.0, 2.0], [-1.0, 2.0], [2.0, -2.0]],
    };
    assert!(incircle_radius(&concurrent).unwrap() < 1e-12);
}

#[test]
fn cylinder_radius_is_the_minimum_over_the_range_and_zero_when_unbounded() {
    let design = design();
    let range = [0.2, 0.4];
    let cyl = singularity_free_cylinder_radius(&design, 4.0, 3.0, range)
        .unwrap()
        .unwrap();
    for j in 0..=200 {
        let phi = 0.2 + 0.2 * j as f64 / 200.0;
        let d = position_singularity_distance(&design, Pose::new(4.0, 3.0, phi))
            .unwrap()
            .distance;
        assert!(cyl.radius <= d + 1e-9, "{} > {d} at {phi}", cyl.radius);
    }
    let full = singularity_free_cylinder_radius(&design, 4.0, 3.0, [0.0, 7.0])
        .unwrap()
        .unwrap();
    assert_eq!(full.radius, 0.0);
    assert!(singularity_free_cylinder_radius(&design, 4.0, 3.0, [1.0, 0.0]).is_err());
    assert!(singularity_free_cylinder_radius(&design, 4.0, 3.0, [f64::NAN, 0.0]).is_err());
}

#[test]
fn options_variants_and_degenerate_outputs() {
    let design = design();
    let k = design.configuration(pose());
    let cos = pressure_cosines(&k, false).unwrap();
    for (variant, expected) in [
        ("product", cos[0] * cos[1] * cos[2]),
        ("geometric-mean", (cos[0] * cos[1] * cos[2]).cbrt()),
        ("arithmetic-mean", (cos[0] + cos[1] + cos[2]) / 3.0),
    ] {
        let ds: DsAggregate = variant.parse().unwrap();
        let options = IndexOptions {
            ds,
            ..IndexOptions::default()
        };
        let r = compute_indices(&design, pose(), &options);
        assert!((r.ds.unwrap() - expected).abs() < 1e-12);
        assert!(options.variants().ds.starts_with(variant));
        assert!(options.variants().ds.contains("reconstructed"));
    }
    let err = "median".parse::<DsAggregate>().unwrap_err().to_string();
    assert!(
        err.contains("median") && err.contains("geometric-mean"),
        "{err}"
    );
    let sqrt = control_number(&k, &[4.0, 3.0], CnVariant::SquareRoot).unwrap();
    assert!((sqrt.cn - 0.0111666f64.sqrt()).abs() < 1e-6);
    assert!("sqrt-lambda-ratio".parse::<CnVariant>().is_ok());
    // A leg of length 0 (b_1 = a_1 at the origin): undefined, never NaN.
    let r: RprIndices =
        compute_indices(&design, Pose::new(0.0, 0.0, 0.5), &IndexOptions::default());
    assert_eq!(r.m, None);
    assert_eq!(r.cn, None);
    assert_eq!(r.s, 0.0);
    let json = serde_json::to_string(&r).unwrap();
    assert!(
        !json.contains("NaN") && json.contains("\"M\":null"),
        "{json}"
    );
    let variants: IndexVariants = IndexOptions::default().variants();
    assert_eq!(variants.cn, "lambda_min/lambda_max");
    // At t = A_1 with P_1 = 0 leg 1 has length 0 for every φ: S ≡ 0 in φ and C_0 = 0.
    assert_eq!(
        singular_orientations(&design, 0.0, 0.0),
        SingularOrientations::All
    );
    let at_origin = orientation_singularity_distance(&design, Pose::new(0.0, 0.0, 1.0)).unwrap();
    assert_eq!(at_origin.distance, 0.0);
    let p = position_singularity_distance(&design, Pose::new(0.0, 0.0, 1.0)).unwrap();
    assert!(p.distance < 1e-12);
    let o = orientation_singularity_distance(&design, pose()).unwrap();
    assert!((o.nearest - 6.194301).abs() < 1e-6);
}

fn conic(c: [f64; 6]) -> SingularConic {
    SingularConic {
        cxx: c[0],
        cxy: c[1],
        cyy: c[2],
        cx: c[3],
        cy: c[4],
        c0: c[5],
    }
}

/// Degenerate branches of the Lagrange quartic: points on symmetry axes, circle centres,
/// line pairs, parabolas, lines, empty and vanishing conics.
#[test]
fn nearest_point_on_special_conics() {
    let cases: [([f64; 6], [f64; 2], Option<f64>); 9] = [
        // Circle x² + y² = 4 from its centre: every point is nearest.
        ([1.0, 0.0, 1.0, 0.0, 0.0, -4.0], [0.0, 0.0], Some(2.0)),
        // Ellipse x²/4 + y² = 1 from its centre: the minor axis (degenerate μ = 1/(2λ)).
        ([0.25, 0.0, 1.0, 0.0, 0.0, -1.0], [0.0, 0.0], Some(1.0)),
        // Same ellipse from (1, 0) on the major axis: d² = ¾x² − 2x + 2, minimal 2/3 at x = 4/3.
        (
            [0.25, 0.0, 1.0, 0.0, 0.0, -1.0],
            [1.0, 0.0],
            Some((2.0f64 / 3.0).sqrt()),
        ),
        // Line pair xy = 0 from (1, 2).
        ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], [1.0, 2.0], Some(1.0)),
        // Parabola y = x² from (0, 2): feet (±sqrt(1.5), 1.5).
        (
            [1.0, 0.0, 0.0, 0.0, -1.0, 0.0],
            [0.0, 2.0],
            Some(1.75f64.sqrt()),
        ),
        // Line 2x + y = 5 from the origin.
        (
            [0.0, 0.0, 0.0, 2.0, 1.0, -5.0],
            [0.0, 0.0],
            Some(5.0 / 5.0f64.sqrt()),
        ),
        // Empty conic x² + y² + 1 = 0.
        ([1.0, 0.0, 1.0, 0.0, 0.0, 1.0], [0.3, 0.1], None),
        // S ≡ 0: every position singular.
        ([0.0; 6], [0.3, 0.1], Some(0.0)),
        // Rotated hyperbola (x − 1)(y + 2) = 1 from its centre (1, −2): distance sqrt(2).
        (
            [0.0, 1.0, 0.0, 2.0, -1.0, -3.0],
            [1.0, -2.0],
            Some(2.0f64.sqrt()),
        ),
    ];
    for (coefficients, p0, expected) in cases {
        let got = conic(coefficients).nearest_point(&p0);
        match (got, expected) {
            (Some((d, foot)), Some(e)) => {
                assert!((d - e).abs() < 1e-9, "{coefficients:?}: {d} vs {e}");
                assert!(conic(coefficients).value(&foot).abs() < 1e-9);
            }
            (None, None) => {}
            other => panic!("{coefficients:?}: {other:?}"),
        }
    }
}
