//! `singdist indices` / `compare` streamed window by window: peak memory independent of
//! the number of poses, the CSV unchanged (a stored table and the `curve` command's
//! distances across a window boundary), JSON Lines and the JSON document agreeing.

mod cli_support;
mod process_support;
use cli_support::{binary, fresh_dir, read};
use process_support::assert_memory_flat_in_poses;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn folder(name: &str) -> PathBuf {
    fresh_dir(&format!("istream-{name}"))
}

fn singdist(args: &[&str]) -> Command {
    let mut command = Command::new(binary());
    command
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    command
}

fn run(args: &[&str]) {
    let output = singdist(args).output().expect("run singdist");
    assert!(
        output.status.success(),
        "singdist {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// 10 × the poses need (almost) no more memory. Before streaming, every row stayed in
/// memory to the end: 7.5 MB peak for 1,000 poses, 14 MB for 10,000, 82 MB for
/// 100,000.
#[test]
fn peak_memory_does_not_grow_with_the_number_of_poses() {
    let dir = folder("memory");
    let measured = assert_memory_flat_in_poses(|poses| {
        let out = dir.join(format!("i{poses}.csv")).display().to_string();
        singdist(&["indices", "--threads", "1", "--poses", poses, "--out", &out])
    });
    if !measured {
        return;
    }
    let rows = read(&dir.join("i10000.csv")).lines().count();
    assert_eq!(rows, 10_001, "header + one row per pose");
}

/// The CSV of a small run with metric distances equals, byte for byte, the one
/// written before the table was streamed (stored in tests/data), on stdout too.
#[test]
fn csv_equals_the_stored_table() {
    let dir = folder("stored");
    let out = dir.join("t.csv");
    let args = [
        "indices",
        "--quiet",
        "--with-metrics",
        "plate/plate",
        "bars/rigid",
        "--poses",
        "12",
    ];
    let mut with_out = args.to_vec();
    with_out.extend(["--out", out.to_str().expect("path")]);
    run(&with_out);
    let stored = read(Path::new("tests/data/indices_two_metrics_12_poses.csv"));
    assert_eq!(read(&out), stored);
    assert!(!dir.join("t.csv.partial").exists(), "partial file left");
    let stdout = Command::new(binary()).args(args).output().expect("run");
    assert!(stdout.status.success());
    assert_eq!(String::from_utf8_lossy(&stdout.stdout), stored);
}

/// Across a window boundary (1,100 poses: windows of 1,000 and 100) the metric columns
/// are the `curve` command's signed distances at the same τ, and the `.jsonl` and
/// `.json` outputs hold the same poses as the CSV.
#[test]
fn metric_columns_equal_curve_across_windows() {
    let dir = folder("curve");
    let path = |name: &str| dir.join(name).display().to_string();
    let common = ["--quiet", "--poses", "1100", "--threads", "2"];
    let mut curve = vec!["curve", "--metric", "plate/plate", "--out"];
    let curve_out = path("c.csv");
    curve.push(&curve_out);
    curve.extend(common);
    run(&curve);
    let (csv_out, jsonl_out, json_out) = (path("i.csv"), path("i.jsonl"), path("i.json"));
    for out in [&csv_out, &jsonl_out, &json_out] {
        let mut args = vec!["indices", "--with-metrics", "plate/plate", "--out", out];
        args.extend(common);
        run(&args);
    }
    let table = read(Path::new(&csv_out));
    let curve = read(Path::new(&curve_out));
    // The last two columns: `plate/plate_signed`, `metric_failures`.
    let head = table.lines().next().expect("header");
    assert!(
        head.ends_with(",plate/plate_signed,metric_failures"),
        "{head}"
    );
    let rows: Vec<&str> = table.lines().skip(1).collect();
    let curve_rows: Vec<&str> = curve.lines().skip(1).collect();
    assert_eq!(rows.len(), 1100);
    assert_eq!(curve_rows.len(), 1100);
    for (j, (row, c)) in rows.iter().zip(&curve_rows).enumerate() {
        let cells: Vec<&str> = row.split(',').collect();
        let c: Vec<&str> = c.split(',').collect();
        assert_eq!(cells[0], c[0], "tau of pose {j}");
        let signed: f64 = c[5].parse().expect("curve distance");
        let column = cells.len() - 2;
        assert_eq!(cells[column], format!("{signed:.12e}"), "pose {j}");
    }
    // JSON Lines: header, one object per pose, summary; the document: the same poses.
    let lines = read(Path::new(&jsonl_out));
    let lines: Vec<serde_json::Value> = lines
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON line"))
        .collect();
    assert_eq!(lines.len(), 1102);
    assert_eq!(lines[0]["record"], "header");
    assert_eq!(lines[1101]["record"], "summary");
    assert_eq!(lines[1101]["poses"], 1100);
    let document: serde_json::Value =
        serde_json::from_str(&read(Path::new(&json_out))).expect("JSON document");
    let poses = document["poses"].as_array().expect("poses");
    assert_eq!(poses.len(), 1100);
    for (j, pose) in poses.iter().enumerate() {
        assert_eq!(pose, &lines[j + 1], "pose {j}");
    }
}
