//! `singdist draw`: the SVG shows the manipulator (two triangles, three legs, six
//! labelled anchors) and one closest singular configuration per metric, with the
//! distances `singdist distance --json` reports; degenerate K′ are marked as such.

mod cli_support;
use cli_support::{assert_success, group_of_k, singdist, temp_dir};

fn temp(name: &str) -> String {
    temp_dir("draw-cli").join(name).display().to_string()
}

#[test]
fn drawing_shows_the_robot_and_each_metrics_closest_configuration() {
    let out = temp("all.svg");
    let run = singdist(&["draw", "--pose", "4,3,0.3", "--out", &out]);
    assert_success(&run);
    let svg = std::fs::read_to_string(&out).expect("the SVG is written");
    let k = group_of_k(&svg);
    assert_eq!(k.matches(r#"class="leg""#).count(), 3);
    assert_eq!(k.matches(r#"<polygon class="base""#).count(), 1);
    assert_eq!(k.matches(r#"<polygon class="platform""#).count(), 1);
    for label in ["a1", "a2", "a3", "b1", "b2", "b3"] {
        assert!(
            k.contains(&format!(">{label}</text>")),
            "anchor label {label}"
        );
    }
    assert_eq!(svg.matches(r#"<g class="closest""#).count(), 9);
    assert_eq!(svg.matches(r#"<polygon class="platform""#).count(), 10);
    assert_eq!(svg.matches(r#"class="leg""#).count(), 30);
    // Every K' of this pose is on the singularity: its leg lines meet in the picture.
    assert_eq!(svg.matches(r#"<circle class="meet""#).count(), 9);
    // The legend sits to the right of the drawing area (x > 670 px).
    let legend = &svg[svg.find(r#"<g id="legend""#).expect("legend")..];
    let first_x: f64 = legend
        .split("x1=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .and_then(|s| s.parse().ok())
        .expect("legend x");
    assert!(first_x > 670.0, "legend at x = {first_x}");

    let json = singdist(&["distance", "--pose", "4,3,0.3", "--json"]);
    assert!(json.status.success());
    let value: serde_json::Value = serde_json::from_slice(&json.stdout).expect("JSON");
    let metrics = value["metrics"].as_object().expect("metrics");
    assert_eq!(metrics.len(), 9);
    for (name, m) in metrics {
        let d = m["distance"].as_f64().expect("distance");
        let entry = format!("{name}</tspan>   D = {d:.4}");
        assert!(legend.contains(&entry), "legend lacks `{entry}`");
        assert!(svg.contains(&format!(
            r#"<g class="closest" data-metric="{name}" data-subproblem="singularity">"#
        )));
    }
}

#[test]
fn collinear_closest_configuration_is_drawn_with_its_line() {
    let out = temp("collinear.svg");
    let run = singdist(&[
        "draw",
        "--pose",
        "3,2,-1",
        "--metric",
        "bars/bars",
        "plate/plate",
        "--out",
        &out,
    ]);
    assert_success(&run);
    let svg = std::fs::read_to_string(&out).expect("the SVG is written");
    assert_eq!(svg.matches(r#"<g class="closest""#).count(), 2);
    assert!(svg.contains(r#"data-metric="bars/bars" data-subproblem="collinear-platform""#));
    assert_eq!(svg.matches(r#"class="degenerate-line""#).count(), 1);
    assert_eq!(svg.matches(r#"<circle class="meet""#).count(), 1);
}

#[test]
fn bad_draw_arguments_give_one_line_errors() {
    for (args, needle) in [
        (vec!["draw", "--pose", "4,3", "--out", "x.svg"], "--pose"),
        (
            vec!["draw", "--pose", "4,3,0.3", "--out", "x.png"],
            "--out: x.png",
        ),
        (
            vec![
                "draw",
                "--pose",
                "4,3,0.3",
                "--metric",
                "plate/glass",
                "--out",
                "x.svg",
            ],
            "--metric",
        ),
    ] {
        let run = singdist(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(needle), "`{needle}` missing in {stderr}");
    }
}

#[test]
fn distance_labels_the_closest_configuration_by_point() {
    let run = singdist(&["distance", "--pose", "4,3,0.3", "--metric", "plate/plate"]);
    assert!(run.status.success());
    let stdout = String::from_utf8_lossy(&run.stdout);
    let line = stdout
        .lines()
        .find(|l| l.contains("closest K'"))
        .expect("a closest K' line");
    let mut at = 0;
    for label in ["a1 (", "a2 (", "a3 (", "b1 (", "b2 (", "b3 ("] {
        let found = line[at..]
            .find(label)
            .unwrap_or_else(|| panic!("{label} missing or out of order in {line}"));
        at += found + label.len();
    }
}
