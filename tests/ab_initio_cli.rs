//! `singdist ab-initio --verify` through the built binary: without `--problem` it
//! re-checks every stored start-solution file (3-RPR and 3-RRR), names each problem
//! with its verdict, and a file that is unreadable or fails its checks ends the run
//! with exit code 1 and a one-line error.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const START_FOLDER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/supplementary/start");

fn singdist(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_singdist"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// The `problem` field of every stored start file, e.g. `bars/rigid:collinear-platform`
/// or `rrr:leg1`.
fn stored_problems() -> Vec<String> {
    let mut problems: Vec<String> = std::fs::read_dir(START_FOLDER)
        .expect("supplementary/start")
        .map(|entry| entry.expect("a folder entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "json"))
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("a start file");
            let file: serde_json::Value = serde_json::from_str(&text).expect("JSON");
            file["problem"]
                .as_str()
                .expect("a problem name")
                .to_string()
        })
        .collect();
    problems.sort();
    problems
}

/// The verdict on `problem`'s line of the output (its first word, without a trailing
/// colon, is the problem's name; the verdict is the line's last word).
fn verdict<'a>(stdout: &'a str, problem: &str) -> Option<&'a str> {
    stdout
        .lines()
        .find(|line| {
            line.split_whitespace()
                .next()
                .map(|w| w.trim_end_matches(':'))
                == Some(problem)
        })
        .and_then(|line| line.split_whitespace().last())
}

/// A fresh temporary copy of the stored start files.
fn copy_of_start_folder(test: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("singdist-ab-initio-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    for entry in std::fs::read_dir(START_FOLDER).expect("supplementary/start") {
        let path = entry.expect("a folder entry").path();
        std::fs::copy(&path, dir.join(path.file_name().expect("a file name"))).expect("copy");
    }
    dir
}

#[test]
fn verify_without_a_problem_checks_every_stored_file() {
    let problems = stored_problems();
    assert!(problems.len() >= 25, "{problems:?}");
    assert!(
        problems.iter().any(|p| p.starts_with("rrr:")),
        "{problems:?}"
    );
    let out = singdist(&["ab-initio", "--verify"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    for problem in &problems {
        assert_eq!(verdict(&stdout, problem), Some("ok"), "{problem}: {stdout}");
    }
}

#[test]
fn a_broken_or_failing_stored_file_is_an_error_naming_it() {
    let dir = copy_of_start_folder("broken");
    let folder = dir.display().to_string();

    let leg = dir.join("rrr-leg1.json");
    std::fs::write(&leg, "{\"problem\": \"rrr:leg1\"").expect("write");
    let out = singdist(&["ab-initio", "--verify", "--dir", &folder]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains(&leg.display().to_string()), "{stderr}");

    // A solution moved off its solution set: the file's line says FAILED, the run fails.
    let original = std::fs::read_to_string(Path::new(START_FOLDER).join("rrr-leg1.json"))
        .expect("a start file");
    let mut file: serde_json::Value = serde_json::from_str(&original).expect("JSON");
    file["solutions"][0][0][0] = serde_json::json!(12.5);
    std::fs::write(&leg, file.to_string()).expect("write");
    let out = singdist(&["ab-initio", "--verify", "--dir", &folder]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(verdict(&stdout, "rrr:leg1"), Some("FAILED"), "{stdout}");
    assert_eq!(verdict(&stdout, "rrr:leg2"), Some("ok"), "{stdout}");
    assert!(
        stderr.contains("1 problem(s) failed their checks"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
