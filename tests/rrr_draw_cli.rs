//! `singdist rrr draw`: the SVG shows the 3-RRR (two triangles, six links, nine labelled
//! joints) and one closest singular configuration per kind (parallel, legs 1–3), with
//! the distances `singdist rrr curve` reports at that pose.

mod cli_support;
use cli_support::{group_of_k, singdist, temp_dir};

fn temp(name: &str) -> String {
    temp_dir("rrr-draw-cli").join(name).display().to_string()
}

#[test]
fn drawing_shows_the_robot_and_each_closest_singular_configuration() {
    let out = temp("pose.svg");
    let run = singdist(&["rrr", "draw", "--pose", "0.15,0.4,0", "--out", &out]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let svg = std::fs::read_to_string(&out).expect("the SVG is written");
    let k = group_of_k(&svg);
    assert_eq!(k.matches(r#"class="leg proximal""#).count(), 3);
    assert_eq!(k.matches(r#"class="leg distal""#).count(), 3);
    assert_eq!(k.matches(r#"<polygon class="base""#).count(), 1);
    assert_eq!(k.matches(r#"<polygon class="platform""#).count(), 1);
    for label in ["O1", "O2", "O3", "B1", "B2", "B3", "C1", "C2", "C3"] {
        assert!(
            k.contains(&format!(">{label}</text>")),
            "joint label {label}"
        );
    }
    for kind in ["parallel", "leg1", "leg2", "leg3"] {
        assert_eq!(
            svg.matches(&format!(r#"<g class="closest" data-metric="{kind}""#))
                .count(),
            1,
            "{kind}"
        );
    }
    assert_eq!(svg.matches(r#"<polygon class="platform""#).count(), 5);
    // Each leg-singular K′ shows the line its leg lies on.
    assert_eq!(svg.matches(r#"class="degenerate-line""#).count(), 3);

    // The legend's distances are those of `rrr curve` at the same pose.
    let motion = temp("pose.json");
    std::fs::write(&motion, r#"{"poses": [[0.15, 0.4, 0]]}"#).expect("motion file");
    let table = temp("pose.csv");
    let run = singdist(&[
        "rrr", "curve", "--motion", &motion, "--out", &table, "--quiet",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let csv = std::fs::read_to_string(&table).expect("CSV written");
    let row: Vec<&str> = csv.lines().nth(1).expect("one pose").split(',').collect();
    for cell in &row[4..8] {
        let d: f64 = cell.parse().expect("a distance");
        let text = format!("D = {:.4}", d.abs());
        assert!(svg.contains(&text), "{text} in the legend");
    }
}

#[test]
fn unreachable_pose_and_wrong_extension_are_one_line_errors() {
    let out = temp("far.svg");
    let run = singdist(&["rrr", "draw", "--pose", "5,5,0", "--out", &out]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("--pose"), "{stderr}");
    assert!(!std::path::Path::new(&out).exists());
    let run = singdist(&[
        "rrr",
        "draw",
        "--pose",
        "0.15,0.4,0",
        "--out",
        &temp("x.png"),
    ]);
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("--out"));
}
