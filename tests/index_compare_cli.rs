//! `singdist indices --with-metrics` / `singdist compare` end to end:
//! the metric columns are those of `singdist curve` for the same poses and seed, they
//! vanish at a singular pose, the plotted data are scaled into [0, 1], the single-pose
//! JSON carries the metric distances of `singdist distance`, and lost paths give exit
//! code 3 exactly when the output lists them.

use singdist::mechanism::rpr::{example_design, example_motion};
use singdist::pipeline::bisection::bisect_sign_change;
use std::collections::HashMap;
use std::process::Output;

mod cli_support;
use cli_support::{singdist, singdist_line, temp_dir};

fn temp(name: &str) -> String {
    temp_dir("compare-cli").join(name).display().to_string()
}

/// Exit code 0, or 3 (lost paths) with the warning on stderr.
fn completed(out: &Output) -> i32 {
    let code = out.status.code().unwrap_or(-1);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(code == 0 || code == 3, "exit {code}: {err}");
    assert_eq!(code == 3, err.contains("lost paths"), "exit {code}: {err}");
    code
}

/// Columns of a CSV file by header name.
fn read_csv(path: &str) -> (Vec<String>, HashMap<String, Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let headers: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let mut columns: HashMap<String, Vec<String>> = HashMap::new();
    for record in reader.records() {
        let record = record.unwrap();
        for (name, value) in headers.iter().zip(record.iter()) {
            columns.entry(name.clone()).or_default().push(value.into());
        }
    }
    (headers, columns)
}

fn numbers(values: &[String]) -> Vec<f64> {
    values
        .iter()
        .map(|v| v.parse().unwrap_or_else(|_| panic!("not a number: {v}")))
        .collect()
}

/// τ of the example motion's first singular pose (S changes sign near −0.086), by
/// bisection to machine precision.
fn singular_tau() -> f64 {
    let design = example_design();
    let motion = example_motion();
    let s = |tau: f64| {
        design
            .configuration(motion.pose(tau).unwrap())
            .singularity()
    };
    assert!(s(-0.5) * s(0.5) < 0.0);
    bisect_sign_change((-0.5, 0.5), s(-0.5), |tau| Some(s(tau)))
}

#[test]
fn metric_columns_match_curve_vanish_at_the_singular_pose_and_plot_data_are_scaled() {
    let motion = example_motion();
    let tau_singular = singular_tau();
    let taus = [-1.0, -0.5, tau_singular, 0.6, 1.7, 2.8, 4.2];
    let poses: Vec<[f64; 3]> = taus
        .iter()
        .map(|&t| {
            let p = motion.pose(t).unwrap();
            [p.x, p.y, p.phi]
        })
        .collect();
    let motion_path = temp("poses.json");
    std::fs::write(
        &motion_path,
        serde_json::json!({ "poses": poses }).to_string(),
    )
    .unwrap();

    let table = temp("compare.csv");
    let data = temp("compare_plot.csv");
    let svg = temp("compare.svg");
    let out = singdist_line(&format!(
        "indices --motion {motion_path} --with-metrics plate/plate --seed 3 --quiet \
         --out {table} --plot {svg} --plot-data {data}"
    ));
    let code = completed(&out);
    let curve_table = temp("curve.csv");
    let out = singdist_line(&format!(
        "curve --motion {motion_path} --metric plate/plate --seed 3 --quiet --out {curve_table}"
    ));
    assert_eq!(completed(&out), code, "same computation, same losses");

    let (headers, columns) = read_csv(&table);
    for name in ["S", "plate/plate", "plate/plate_signed", "metric_failures"] {
        assert!(
            headers.iter().any(|h| h == name),
            "{name} missing: {headers:?}"
        );
    }
    let failures = &columns["metric_failures"];
    assert_eq!(code == 3, failures.iter().any(|f| !f.is_empty()));
    let (_, reference) = read_csv(&curve_table);
    assert_eq!(columns["tau"], reference["tau"], "same pose sampling");
    let distance = numbers(&columns["plate/plate"]);
    let signed = numbers(&columns["plate/plate_signed"]);
    let expected = numbers(&reference["plate/plate"]);
    let s = numbers(&columns["S"]);
    assert_eq!(distance.len(), taus.len());
    for j in 0..taus.len() {
        let tolerance = 1e-11 * (1.0 + expected[j].abs());
        assert!(
            (signed[j] - expected[j]).abs() <= tolerance,
            "pose {j}: {} vs curve {}",
            signed[j],
            expected[j]
        );
        assert!((distance[j] - expected[j].abs()).abs() <= tolerance);
        if s[j] != 0.0 && distance[j] > 0.0 {
            assert_eq!(signed[j].signum(), s[j].signum(), "pose {j}: sign of S");
        }
    }
    // Pose 2 is singular (S = 0 up to rounding): the distance vanishes (docs/theory.md §7).
    assert!(s[2].abs() < 1e-9, "S = {}", s[2]);
    assert!(
        distance[2] < 1e-6,
        "distance at the singular pose {}",
        distance[2]
    );
    assert!(
        distance
            .iter()
            .enumerate()
            .all(|(j, &d)| j == 2 || d > 1e-3)
    );

    // Plot data: every curve divided by its maximum along the motion.
    let (plot_headers, plot_columns) = read_csv(&data);
    assert!(
        plot_headers
            .iter()
            .any(|h| h.starts_with("D plate/plate / "))
    );
    assert!(plot_headers.iter().any(|h| h.starts_with("|S| / ")));
    for header in plot_headers.iter().filter(|h| *h != "tau") {
        let values: Vec<f64> = plot_columns[header]
            .iter()
            .filter(|v| *v != "undefined")
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(
            values.iter().all(|v| (0.0..=1.0).contains(v)),
            "{header}: {values:?}"
        );
        let max = values.iter().fold(0.0f64, |m, v| m.max(*v));
        assert!(
            max == 0.0 || (max - 1.0).abs() < 1e-12,
            "{header}: max {max}"
        );
    }
    let scaled = numbers(
        &plot_columns[plot_headers
            .iter()
            .find(|h| h.starts_with("D plate/plate / "))
            .unwrap()],
    );
    let max = distance.iter().fold(0.0f64, |m, v| m.max(*v));
    for (a, d) in scaled.iter().zip(&distance) {
        assert!((a - d / max).abs() < 1e-11);
    }
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains(">plate/plate (max ") && svg.contains("divided by its maximum"));
    // Small multiples: the metric distances have a panel of their own; every panel
    // marks the two singular poses.
    assert!(svg.contains(">metric distances D(K, K′)"));
    let panels = svg.matches(r#"<g class="panel""#).count();
    assert!(panels >= 2, "{panels} panels");
    assert_eq!(svg.matches(r#"class="marker""#).count(), 2 * panels);
}

#[test]
fn single_pose_json_and_compare_json_table_carry_the_metric_distances() {
    let out = singdist(&[
        "indices",
        "--pose",
        "4,3,0.3",
        "--json",
        "--with-metrics",
        "plate/plate",
        "--quiet",
    ]);
    let code = completed(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((v["S"].as_f64().unwrap() - 125.29749).abs() < 1e-4);
    let ours = &v["metrics"]["plate/plate"];
    assert_eq!(
        code == 3,
        !v["metric_failures"].as_array().unwrap().is_empty()
    );
    let out = singdist(&[
        "distance",
        "--pose",
        "4,3,0.3",
        "--json",
        "--metric",
        "plate/plate",
    ]);
    assert_eq!(completed(&out), code);
    let reference: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let theirs = &reference["metrics"]["plate/plate"];
    for key in ["distance", "signed_distance"] {
        let (a, b) = (ours[key].as_f64().unwrap(), theirs[key].as_f64().unwrap());
        assert!(a > 0.0 && a == b, "{key}: {a} vs distance {b}");
    }
    assert_eq!(ours["subproblem"], theirs["subproblem"]);

    // `compare` = `indices --with-metrics all` unless metrics are named.
    let json = temp("compare.json");
    let out = singdist(&[
        "compare",
        "--poses",
        "3",
        "--with-metrics",
        "plate/plate",
        "--quiet",
        "--out",
        &json,
    ]);
    let code = completed(&out);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["metric_names"], serde_json::json!(["plate/plate"]));
    let poses = v["poses"].as_array().unwrap();
    assert_eq!(poses.len(), 3);
    for pose in poses {
        let m = &pose["metrics"]["plate/plate"];
        let d = m["distance"].as_f64().unwrap();
        assert!(d > 0.0);
        assert_eq!(
            m["signed_distance"].as_f64().unwrap(),
            d * pose["S"].as_f64().unwrap().signum()
        );
    }
    assert_eq!(
        code == 3,
        !v["metric_failures"].as_array().unwrap().is_empty()
    );

    let out = singdist(&["indices", "--with-metrics", "plate/wood", "--poses", "3"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--with-metrics") && err.contains("wood"),
        "{err}"
    );
}
