//! `singdist certify FILE`: a saved `curve` result re-solved with another seed and
//! certified; a distance changed in the file is caught (exit 3), a broken file is a
//! one-line error naming the field.

use std::path::{Path, PathBuf};

mod cli_support;
use cli_support::{assert_success, fresh_dir, singdist};

fn folder(name: &str) -> PathBuf {
    fresh_dir(&format!("certify-{name}"))
}

/// A three-pose `plate/plate` run of the built-in example written to `out`.
fn small_run(out: &Path) {
    let out = out.to_str().unwrap();
    let args = [
        "curve",
        "--quiet",
        "--poses",
        "3",
        "--metric",
        "plate/plate",
    ];
    let run = singdist(&[&args[..], &["--threads", "1", "--out", out]].concat());
    assert_success(&run);
}

/// [`small_run`] written to `dir/name` and certified, which must succeed: the file and
/// the certificate's stdout.
fn certified_small_run(dir: &Path, name: &str) -> (PathBuf, String) {
    let file = dir.join(name);
    small_run(&file);
    let (code, stdout, stderr) = certify(&file);
    assert_eq!(code, 0, "{stdout}{stderr}");
    (file, stdout)
}

fn certify(file: &Path) -> (i32, String, String) {
    let run = singdist(&["certify", file.to_str().unwrap(), "--threads", "1"]);
    (
        run.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&run.stdout).into_owned(),
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}

/// The document with pose `pose`'s `plate/plate` distance multiplied by `factor`.
fn tampered(file: &Path, pose: usize, factor: f64, out: &Path) {
    let mut doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let d = &mut doc["poses"][pose]["metrics"]["plate/plate"]["distance"];
    *d = serde_json::json!(d.as_f64().unwrap() * factor);
    std::fs::write(out, doc.to_string()).unwrap();
}

#[test]
fn a_saved_run_is_certified_and_a_changed_distance_is_caught() {
    let dir = folder("document");
    let (file, stdout) = certified_small_run(&dir, "run.json");
    assert!(
        stdout.contains("3 poses, 3 distances re-checked (seed 7920): 3 certified global minima"),
        "{stdout}"
    );
    // The certificate of the file with pose `pose`'s distance times `factor`, which
    // must exit with code 3.
    let contradicted = |pose: usize, factor: f64| {
        let changed = dir.join(format!("changed-{pose}.json"));
        tampered(&file, pose, factor, &changed);
        let (code, stdout, _) = certify(&changed);
        assert_eq!(code, 3, "{stdout}");
        stdout
    };
    // A distance 0.1 % too large: a certified real critical point is closer.
    let stdout = contradicted(1, 1.001);
    assert!(
        stdout.contains("CONTRADICTED pose 1 plate/plate"),
        "{stdout}"
    );
    assert!(stdout.contains("2 certified global minima (G)"), "{stdout}");
    // 0.1 % too small: below the certified global minimum.
    let stdout = contradicted(2, 0.999);
    assert!(
        stdout.contains("below the certified global minimum"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn logs_are_read_and_broken_files_are_one_line_errors() {
    let dir = folder("log");
    let (_, stdout) = certified_small_run(&dir, "run.jsonl");
    assert!(stdout.contains("3 certified global minima"), "{stdout}");
    let broken = dir.join("broken.json");
    std::fs::write(
        &broken,
        r#"{"metric_names": ["plate/plate"], "seed": 1, "poses": [{"index": 0, "pose": [1, 2], "metrics": {}}]}"#,
    )
    .unwrap();
    let (code, _, stderr) = certify(&broken);
    assert_eq!(code, 1);
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("broken.json: poses[0].pose"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}
