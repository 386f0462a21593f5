//! Bad inputs of `singdist curve` / `distance`: one-line errors naming the file and
//! field, exit code 1, never a panic.

use std::process::Command;

fn run(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_singdist"))
        .args(args)
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn write(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("singdist-pipeline-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write temp file");
    path.display().to_string()
}

fn assert_one_line_error(code: i32, stderr: &str, needles: &[&str]) {
    assert_eq!(code, 1, "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        stderr.trim().lines().count(),
        1,
        "one line expected: {stderr}"
    );
    for needle in needles {
        assert!(stderr.contains(needle), "`{needle}` missing in: {stderr}");
    }
}

#[test]
fn bad_inputs_give_one_line_errors() {
    let malformed = write("malformed.json", "{\"base\": [[0,0],[1,0]");
    let (code, err) = run(&["curve", "--quiet", "--design", &malformed]);
    assert_one_line_error(code, &err, &["malformed.json", "JSON"]);

    let missing = write("missing.json", "{\"base\": [[0,0],[10,0],[4,8]]}");
    let (code, err) = run(&["curve", "--quiet", "--design", &missing]);
    assert_one_line_error(code, &err, &["missing.json", "platform"]);

    let degenerate = write(
        "degenerate.json",
        "{\"base\": [[1,1],[1,1],[1,1]], \"platform\": [[0,0],[3,0],[1,2]]}",
    );
    let (code, err) = run(&["curve", "--quiet", "--design", &degenerate]);
    assert_one_line_error(code, &err, &["degenerate.json", "base"]);

    let (code, err) = run(&["curve", "--quiet", "--metric", "plate/wood"]);
    assert_one_line_error(code, &err, &["--metric", "plate/wood"]);

    let (code, err) = run(&["curve", "--quiet", "--poses", "0"]);
    assert_one_line_error(code, &err, &["poses"]);

    let (code, err) = run(&["curve", "--quiet", "--chain", "0"]);
    assert_one_line_error(code, &err, &["--chain"]);

    let bad_motion = write("motion.json", "{\"tau_range\": [1, 0], \"x\": 1}");
    let (code, err) = run(&["curve", "--quiet", "--motion", &bad_motion]);
    assert_one_line_error(code, &err, &["motion.json"]);

    let (code, err) = run(&["distance", "--pose", "1,2"]);
    assert_one_line_error(code, &err, &["--pose"]);
    let (code, err) = run(&["distance", "--pose", "1,nan,0"]);
    assert_one_line_error(code, &err, &["--pose", "y"]);
}
