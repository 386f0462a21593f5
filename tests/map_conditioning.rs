//! Conditioning maps: brute-force agreement and Fontes et al.'s claims on a moderate grid.

use singdist::index::map::{MapOptions, ModeSelection, conditioning_map};
use singdist::index::prrr::{LciVariant, lci};
use singdist::mechanism::prrr::{Pose, PrrrDesign, Robot, WorkingMode};

fn options(robot: Robot, modes: ModeSelection) -> MapOptions {
    MapOptions {
        robot,
        x_range: (-0.4, 0.4),
        y_range: (-0.25, 0.45),
        nx: 33,
        ny: 29,
        delta_levels: 5,
        modes,
        ..MapOptions::default()
    }
}

const FIXED: ModeSelection = ModeSelection::Fixed([WorkingMode::Plus; 3]);

/// The factorised search (leg rows assembled k³ times) equals a brute-force loop over full
/// inverse kinematics and `1/κ(Ā)` from the mechanism module.
#[test]
fn map_matches_brute_force_search_at_sample_nodes() {
    let design = PrrrDesign::fontes2017();
    for variant in [LciVariant::DirectA, LciVariant::InverseAB] {
        let o = MapOptions {
            nx: 7,
            ny: 7,
            variant,
            ..options(Robot::ThreePrrr, FIXED)
        };
        let map = conditioning_map(&design, &o).unwrap();
        let levels: Vec<f64> = (0..5).map(|i| -0.3 + 0.15 * i as f64).collect();
        for iy in 0..7 {
            for ix in 0..7 {
                let pose = Pose::new(map.xs[ix], map.ys[iy], 0.0);
                let mut best: Option<(f64, [f64; 3])> = None;
                for &d0 in &levels {
                    for &d1 in &levels {
                        for &d2 in &levels {
                            let Ok(c) = design.inverse_kinematics(
                                &pose,
                                &[d0, d1, d2],
                                &[WorkingMode::Plus; 3],
                            ) else {
                                continue;
                            };
                            let v = lci(&design, &c, Robot::ThreePrrr, variant);
                            if best.is_none_or(|(b, _)| v > b) {
                                best = Some((v, [d0, d1, d2]));
                            }
                        }
                    }
                }
                match (best, map.value(ix, iy)) {
                    (None, None) => {}
                    (Some((v, d)), Some(m)) => {
                        assert!((v - m).abs() < 1e-12, "{pose:?}: brute {v} map {m}");
                        let md = map.best_delta[iy * 7 + ix].unwrap();
                        for j in 0..3 {
                            assert!(
                                (md[j] - d[j]).abs() < 1e-12,
                                "{pose:?}: arg-max {md:?} vs {d:?}"
                            );
                        }
                    }
                    (b, m) => panic!("{pose:?}: reachability differs, brute {b:?}, map {m:?}"),
                }
            }
        }
    }
}

/// δ = 0 is one of the (odd) k levels, so the 3-PRRR map dominates the 3RRR map node by node.
#[test]
fn redundant_map_dominates_non_redundant_map() {
    let design = PrrrDesign::fontes2017();
    let rrr = conditioning_map(&design, &options(Robot::ThreeRrr, FIXED)).unwrap();
    let prrr = conditioning_map(&design, &options(Robot::ThreePrrr, FIXED)).unwrap();
    let mut compared = 0;
    for (r, p) in rrr.values.iter().zip(&prrr.values) {
        if let Some(r) = r {
            let p = p.expect("a node reachable by the 3RRR is reachable by the 3PRRR");
            assert!(p >= *r - 1e-15);
            compared += 1;
        }
    }
    assert!(compared > 100);
    assert!(rrr.best_delta.iter().flatten().all(|d| *d == [0.0; 3]));
    // Deterministic.
    let again = conditioning_map(&design, &options(Robot::ThreePrrr, FIXED)).unwrap();
    assert_eq!(again, prrr);
}

/// The claims of Fontes et al., §4, checked on the computed maps (fontes2017, α = 0, 25
/// mm grid over the whole 3-PRRR workspace).
#[test]
fn seed001_claims_hold_on_the_maps() {
    let design = PrrrDesign::fontes2017();
    let rrr = conditioning_map(&design, &options(Robot::ThreeRrr, FIXED)).unwrap();
    let prrr = conditioning_map(&design, &options(Robot::ThreePrrr, ModeSelection::Best)).unwrap();
    let prrr_fixed = conditioning_map(&design, &options(Robot::ThreePrrr, FIXED)).unwrap();
    // 3RRR: three unreachable circles inside the workspace, below 0.8 over most of it.
    assert_eq!(rrr.unreachable_holes(), 3);
    assert!((rrr.nodes_at_least(0.8) as f64) < 0.2 * rrr.reachable_nodes() as f64);
    // 3PRRR: no unreachable holes; no value below 0.2 (with the working modes searched too).
    assert_eq!(prrr.unreachable_holes(), 0);
    assert_eq!(prrr_fixed.unreachable_holes(), 0);
    let min = prrr.min_value().unwrap();
    assert!(min >= 0.2, "3PRRR minimum {min}");
    // Larger workspace and a much larger area above 0.8.
    assert!(prrr.reachable_nodes() > rrr.reachable_nodes());
    let (high_p, high_r) = (prrr.nodes_at_least(0.8), rrr.nodes_at_least(0.8));
    assert!(
        high_p >= 5 * high_r.max(1),
        "≥0.8 nodes: 3PRRR {high_p}, 3RRR {high_r}"
    );
    assert!(prrr_fixed.nodes_at_least(0.8) >= 5 * high_r.max(1));
    // The ≥0.8 region is central: it contains the origin (node (16, 10) is (0, 0)).
    assert!(prrr.xs[16].abs() < 1e-12 && prrr.ys[10].abs() < 1e-12);
    assert!(prrr.value(16, 10).unwrap() >= 0.8);
    // Its area is of the order of the 3RRR workspace (seed: "the same size"); we measure ≥ 1/3.
    assert!(
        3 * high_p >= rrr.reachable_nodes(),
        "{high_p} vs {}",
        rrr.reachable_nodes()
    );
}

#[test]
fn outputs_and_bad_options() {
    let design = PrrrDesign::fontes2017();
    let o = MapOptions {
        nx: 9,
        ny: 9,
        ..options(Robot::ThreePrrr, FIXED)
    };
    let map = conditioning_map(&design, &o).unwrap();
    let mut csv = Vec::new();
    map.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    assert_eq!(text.lines().count(), 82);
    assert!(text.starts_with("x,y,lci_a,delta1,delta2,delta3"));
    let dir = std::env::temp_dir().join(format!("singdist_map_test_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("map.svg");
    map.write_svg(&path, design.delta_range).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.contains("<svg") && svg.contains("<rect"));
    std::fs::remove_dir_all(&dir).ok();

    let refused = |bad: MapOptions, field: &str| {
        let message = conditioning_map(&design, &bad).unwrap_err().to_string();
        assert!(message.contains(field), "{field}: {message}");
    };
    refused(MapOptions { nx: 1, ..o.clone() }, "nx");
    let x_range = (0.1, -0.1);
    refused(
        MapOptions {
            x_range,
            ..o.clone()
        },
        "x_range",
    );
    refused(
        MapOptions {
            delta_levels: 0,
            ..o.clone()
        },
        "delta_levels",
    );
    refused(
        MapOptions {
            alpha: f64::NAN,
            ..o
        },
        "alpha",
    );
}
