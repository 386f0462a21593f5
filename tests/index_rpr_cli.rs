//! `singdist indices` end to end: single-pose JSON, motion table, plot, errors.

mod cli_support;
use cli_support::{assert_success, read, singdist, singdist_line, succeed_line, temp_dir};

fn temp(name: &str) -> std::path::PathBuf {
    temp_dir("indices-cli").join(name)
}

#[test]
fn single_pose_json_has_every_key_and_the_test_vector_values() {
    let out = singdist(&["indices", "--pose", "4,3,0.3", "--json"]);
    assert_success(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let expected = [
        ("M", 1.781467),
        ("S", 125.29749),
        ("IR", 0.744749),
        ("TI", 0.787796),
        ("MTI", 0.319097),
        ("CN", 0.0111666),
        ("MCN", 0.528921),
        ("orientation_distance", 0.388884),
        ("position_distance", 2.589166),
    ];
    for (key, value) in expected {
        let got = v[key].as_f64().unwrap_or_else(|| panic!("missing {key}"));
        assert!((got - value).abs() < 1e-5, "{key}: {got}");
    }
    for key in [
        "DS",
        "MDS",
        "orientation_distance_signed",
        "position_distance_signed",
    ] {
        assert!(v[key].is_number(), "{key}");
    }
    assert!(
        v["variants"]["DS"]
            .as_str()
            .unwrap()
            .contains("reconstructed")
    );
}

#[test]
fn motion_table_plot_and_errors() {
    let csv_path = temp("indices.csv");
    let svg_path = temp("indices.svg");
    succeed_line(&format!(
        "indices --poses 40 --out {} --plot {}",
        csv_path.display(),
        svg_path.display()
    ));
    let text = read(&csv_path);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 41);
    assert!(
        lines[0].starts_with("tau,x,y,phi,M,S,IR,TI,"),
        "{}",
        lines[0]
    );
    assert!(lines[0].contains("DS(product,reconstructed)"));
    assert!(!text.to_ascii_lowercase().contains("nan"));
    // S changes sign exactly twice along the example motion.
    let s: Vec<f64> = lines[1..]
        .iter()
        .map(|l| l.split(',').nth(5).unwrap().parse().unwrap())
        .collect();
    assert_eq!(s.windows(2).filter(|w| w[0] * w[1] < 0.0).count(), 2);
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    // Small multiples: every panel marks both singular poses and names them once in
    // its legend, at the τ that `curve` reports (roots of S along the motion, not
    // interpolated between the 40 samples).
    let panels = svg.matches(r#"<g class="panel""#).count();
    assert!(panels >= 3, "{panels} panels");
    assert_eq!(svg.matches(r#"class="marker""#).count(), 2 * panels);
    let curve = singdist_line("curve --poses 3 --metric plate/plate --quiet");
    let stdout = String::from_utf8_lossy(&curve.stdout);
    let roots: Vec<f64> = stdout
        .rsplit("singular poses at tau = ")
        .next()
        .unwrap()
        .trim()
        .split(", ")
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(roots.len(), 2, "{stdout}");
    let legend = format!(
        "singular pose, S = 0 (τ = {:.4}, {:.4})",
        roots[0], roots[1]
    );
    assert_eq!(svg.matches(&legend).count(), panels, "`{legend}` per panel");

    let json_path = temp("indices.json");
    succeed_line(&format!("indices --poses 5 --out {}", json_path.display()));
    let v: serde_json::Value = serde_json::from_str(&read(&json_path)).unwrap();
    assert_eq!(v["poses"].as_array().unwrap().len(), 5);

    let bad = temp("bad_design.json");
    std::fs::write(
        &bad,
        "{\"base\": [[0,0],[1,0]], \"platform\": [[0,0],[1,0],[0,1]]}",
    )
    .unwrap();
    let out = singdist(&[
        "indices",
        "--design",
        bad.to_str().unwrap(),
        "--pose",
        "1,1,0",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad_design.json") && err.contains("base"),
        "{err}"
    );
    let out = singdist(&["indices", "--out", temp("x.txt").to_str().unwrap()]);
    assert!(!out.status.success());
}
