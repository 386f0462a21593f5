//! The `singdist prrr` and `singdist map` commands end to end (small sizes).

mod cli_support;
use cli_support::{assert_success, read, singdist, succeed_line, temp_dir};

#[test]
fn prrr_index_json_reports_spec_test_vector() {
    let out = singdist(&[
        "prrr", "index", "--pose", "0,0,0", "--delta", "0,0,0", "--modes", "+,-,+", "--json",
    ]);
    assert_success(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((v["lci"].as_f64().unwrap() - 0.253256).abs() < 1e-6);
    assert!((v["nsir"].as_f64().unwrap() - 0.305006).abs() < 1e-6);
    assert_eq!(v["lci_variant"], "1/κ(Ā⁻¹B̄)");
    assert!(v["lci_a"].is_number() && v["r_norm"].is_number() && v["xi"].is_number());
}

#[test]
fn prrr_index_errors_are_one_line_and_named() {
    let out = singdist(&["prrr", "index", "--pose", "1,0,0"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot reach"));
    let out = singdist(&["prrr", "index", "--pose", "0,0", "--json"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--pose"));
    let out = singdist(&["prrr", "index", "--pose", "0,0,0", "--preset", "nope"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("nope"));
    let out = singdist(&[
        "prrr", "index", "--pose", "0,0,0", "--delta", "-0.1,0,0", "--robot", "3rrr",
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("--delta"));
}

#[test]
fn resolve_writes_table_and_map_writes_files() {
    let dir = temp_dir("prrr-cli");
    let csv = dir.join("r.csv");
    let out = succeed_line(&format!(
        "prrr resolve --trajectory circle --scheme all --index nsir --population 8 \
         --generations 3 --samples 21 --timing-repetitions 1 --seed 3 --out {}",
        csv.display()
    ));
    let text = read(&csv);
    assert_eq!(text.lines().count(), 3, "{text}");
    assert_eq!(String::from_utf8_lossy(&out.stdout), text);
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    for row in reader.deserialize::<std::collections::HashMap<String, String>>() {
        let row = row.unwrap();
        let f: f64 = row["objective"].parse().unwrap();
        let f0: f64 = row["objective_at_delta0"].parse().unwrap();
        assert!(f >= f0, "{row:?}");
    }
    let svg = dir.join("m.svg");
    let map_csv = dir.join("m.csv");
    let out = succeed_line(&format!(
        "map --robot 3rrr --x-range=-0.25,0.25 --y-range=-0.25,0.25 --step 0.05 \
         --out {} --csv {} --json",
        svg.display(),
        map_csv.display()
    ));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["nodes"], 121);
    assert!(read(&svg).contains("<svg"));
    assert_eq!(read(&map_csv).lines().count(), 122);
    let out = singdist(&["map", "--robot", "4rrr"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("robot"));
    std::fs::remove_dir_all(&dir).ok();
}
