//! `singdist schemes` end to end on tiny grids: table files, plot, errors, GA reproducibility.

mod cli_support;
use cli_support::{assert_success, read, singdist, succeed_line, temp_dir};

fn temp(name: &str) -> std::path::PathBuf {
    temp_dir("schemes-cli").join(name)
}

#[test]
fn table_json_csv_and_plot_are_written() {
    let json = temp("t.json");
    let csv = temp("t.csv");
    let svg = temp("t.svg");
    let out = succeed_line(&format!(
        "schemes --grid 21 --out {} --plot {}",
        json.display(),
        svg.display()
    ));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("Ramana Babu et al.'s claim"), "{stdout}");
    let rows: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(rows.len(), 16, "8 schemes x 2 orientations");
    for row in &rows {
        let g = row["gci"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&g));
        assert!(row["reachable_nodes"].as_u64().unwrap() > 0);
    }
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    succeed_line(&format!(
        "schemes --grid 11 --orientation -20 --scheme θψψ --out {}",
        csv.display()
    ));
    let text = read(&csv);
    assert_eq!(text.lines().count(), 2, "{text}");
    assert!(
        text.lines().nth(1).unwrap().starts_with("-20.0,6,θψψ"),
        "{text}"
    );
    for path in [json, csv, svg] {
        std::fs::remove_file(path).ok();
    }
}

#[test]
fn bad_input_gives_a_named_error() {
    for (args, needle) in [
        (vec!["schemes", "--scheme", "9"], "1..=8"),
        (vec!["schemes", "--grid", "1"], "grid.nx"),
        (vec!["schemes", "--distal=-1"], "distal"),
        (vec!["schemes", "--modes", "+x+"], "--modes"),
        (vec!["schemes", "--norm", "max"], "norm"),
        (
            vec!["schemes", "--grid", "5", "--out", "/tmp/x.txt"],
            "extension",
        ),
    ] {
        let out = singdist(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
}

#[test]
fn optimisation_is_reproducible_for_a_seed() {
    let args = [
        "schemes",
        "--optimize",
        "--scheme",
        "1",
        "--orientation",
        "0",
        "--grid",
        "11",
        "--optimize-grid",
        "9",
        "--population",
        "6",
        "--generations",
        "2",
        "--seed",
        "5",
    ];
    let first = singdist(&args);
    let second = singdist(&args);
    assert_success(&first);
    assert_eq!(first.stdout, second.stdout);
    assert!(String::from_utf8_lossy(&first.stdout).contains("optimised objective"));
}
