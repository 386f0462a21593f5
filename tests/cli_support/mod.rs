//! Running the `singdist` binary in the CLI tests: one call and its output, the check
//! that it succeeded (showing its stderr otherwise), and a temporary folder per test.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary built for the tests.
pub fn binary() -> &'static str {
    env!("CARGO_BIN_EXE_singdist")
}

/// `singdist ARGS` run to its end.
pub fn singdist(args: &[&str]) -> Output {
    Command::new(binary())
        .args(args)
        .output()
        .expect("run singdist")
}

/// Panics with the run's stderr unless it exited with status 0.
pub fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `singdist ARGS`, which must succeed.
pub fn succeed(args: &[&str]) -> Output {
    let out = singdist(args);
    assert_success(&out);
    out
}

/// `TMP/singdist-TAG-PID`, created (left as it is if it exists).
pub fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("singdist-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    dir
}

/// `TMP/singdist-TAG-PID`, emptied.
pub fn fresh_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("singdist-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp folder");
    dir
}

/// The text of the file at `path` (panics naming it).
pub fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `singdist` with the arguments of `line`, split at white space (so no argument may
/// contain any; the folders of [`temp_dir`] have none).
pub fn singdist_line(line: &str) -> Output {
    singdist(&line.split_whitespace().collect::<Vec<_>>())
}

/// [`singdist_line`], which must succeed.
pub fn succeed_line(line: &str) -> Output {
    let out = singdist_line(line);
    assert_success(&out);
    out
}

/// The text of the element group `<g id="K" …> … </g>` (no nested groups inside).
pub fn group_of_k(svg: &str) -> &str {
    let start = svg.find(r#"<g id="K""#).expect("a group g#K");
    let end = start + svg[start..].find("</g>").expect("g#K is closed");
    &svg[start..end]
}
