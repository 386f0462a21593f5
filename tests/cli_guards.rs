//! Inputs that cannot poison a run, through the built binary: numbers beyond ±1e12 in
//! designs, motions and poses, too many poses, too many threads, unwritable or
//! unsupported output paths, failed writes, `solve` with failed paths, errors printed
//! once, and the `lost_paths` CSV column.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

struct Run {
    code: i32,
    stdout: String,
    stderr: String,
    elapsed: Duration,
}

fn run(args: &[&str]) -> Run {
    let started = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_singdist"))
        .args(args)
        .output()
        .expect("the binary runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        elapsed: started.elapsed(),
    }
}

/// A fresh temporary folder for one test, with the inputs it writes and the outputs it
/// names.
struct Scratch(PathBuf);

impl Scratch {
    fn new(test: &str) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("singdist-cli-guards-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        Scratch(dir)
    }

    /// The path of `name` inside the folder, as a command-line argument.
    fn path(&self, name: &str) -> String {
        self.0.join(name).display().to_string()
    }

    /// Writes `text` to `name` inside the folder; returns its path.
    fn write(&self, name: &str, text: &str) -> String {
        let path = self.path(name);
        std::fs::write(&path, text).expect("write temp file");
        path
    }
}

/// Exit code 1, one line on stderr (no panic, no Debug text) containing every needle.
fn assert_one_line_error(run: &Run, needles: &[&str]) {
    let stderr = &run.stderr;
    assert_eq!(run.code, 1, "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        stderr.trim().lines().count(),
        1,
        "one line expected: {stderr}"
    );
    assert!(!stderr.contains("Error("), "Debug text: {stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "`{needle}` missing in: {stderr}");
    }
}

/// Neither `out` nor `out.partial` exists.
fn assert_no_output(out: &str) {
    assert!(!Path::new(out).exists(), "{out} was written");
    assert!(
        !Path::new(&format!("{out}.partial")).exists(),
        "{out}.partial was left behind"
    );
}

const DESIGN: &str = r#"{"base": [[0,0],[10,0],[4,8]], "platform": [[0,0],[3,0],[1,2]]}"#;

#[test]
fn numbers_beyond_the_input_range_are_refused_with_file_field_and_index() {
    let dir = Scratch::new("range");
    let out = dir.path("out.csv");

    let poses = dir.write("poses.json", r#"{"poses": [[1e308,3,0.3],[4,3,0.3]]}"#);
    let r = run(&["curve", "--quiet", "--motion", &poses, "--out", &out]);
    assert_one_line_error(&r, &["poses.json: poses[0][0]: 1e308 is outside ±1e12"]);
    assert_no_output(&out);

    let design = dir.write(
        "design.json",
        r#"{"base": [[0,0],[1e308,0],[4,8]], "platform": [[0,0],[3,0],[1,2]]}"#,
    );
    let r = run(&["curve", "--quiet", "--design", &design, "--out", &out]);
    assert_one_line_error(&r, &["design.json: base[1].x: 1e308 is outside ±1e12"]);
    assert!(!r.stderr.contains("coincides"), "{}", r.stderr);
    assert_no_output(&out);

    // Finite coefficients whose motion leaves the range inside tau_range.
    let blow_up = dir.write(
        "blow_up.json",
        r#"{"tau_range": [0, 1e6], "x": {"polynomial": [4, 0, 0, 1]}, "y": {"polynomial": [3]}, "phi": {"polynomial": [0.3]}}"#,
    );
    let r = run(&[
        "indices", "--motion", &blow_up, "--poses", "5", "--out", &out,
    ]);
    assert_one_line_error(&r, &["blow_up.json: x(tau = ", "outside ±1e12"]);
    assert_no_output(&out);

    let r = run(&["distance", "--pose", "1e308,3,0.3"]);
    assert_one_line_error(&r, &["--pose: x: 1e308 is outside ±1e12"]);
    let r = run(&["indices", "--pose", "4,3,-1e13"]);
    assert_one_line_error(&r, &["--pose: phi: -1e13 is outside ±1e12"]);
    let r = run(&["prrr", "index", "--pose", "1e300,0,0"]);
    assert_one_line_error(&r, &["--pose", "1e300", "1e12"]);

    let rrr = dir.write(
        "rrr.json",
        r#"{"base": [[0,0],[1e13,0],[4,8]], "proximal": [1,1,1], "distal": [1,1,1], "platform": [[0,0],[1,0],[0,1]]}"#,
    );
    let r = run(&["rrr", "curve", "--design", &rrr, "--out", &out]);
    assert_one_line_error(&r, &["rrr.json: base[1].x: 1e13 is outside ±1e12"]);
    assert_no_output(&out);
    let r = run(&["rrr", "curve", "--motion", &poses, "--out", &out]);
    assert_one_line_error(&r, &["poses.json: poses[0][0]: 1e308 is outside ±1e12"]);
    assert_no_output(&out);
}

#[test]
fn errors_print_their_cause_once() {
    let dir = Scratch::new("once");
    let collapsed = dir.write(
        "collapsed.json",
        r#"{"base": [[0,0],[10,0],[4,8]], "platform": [[1,2],[1,2],[1,2]]}"#,
    );
    let r = run(&["curve", "--quiet", "--design", &collapsed]);
    assert_one_line_error(&r, &["collapsed.json: platform: collapsed to a point"]);
    assert_eq!(r.stderr.matches("collapsed").count(), 2, "{}", r.stderr);

    let rrr = dir.write(
        "rrr.json",
        r#"{"base": [[0,0],[10,0],[4,8]], "proximal": [1,-0.8,1], "distal": [1,1,1], "platform": [[0,0],[1,0],[0,1]]}"#,
    );
    let r = run(&["rrr", "curve", "--design", &rrr]);
    assert_one_line_error(&r, &["rrr.json: proximal[1] must be positive, got -0.8"]);
    assert_eq!(
        r.stderr.matches("must be positive").count(),
        1,
        "{}",
        r.stderr
    );

    let malformed = dir.write("malformed.json", "{\"poses\": [[0,0,");
    let r = run(&["curve", "--quiet", "--motion", &malformed]);
    assert_one_line_error(&r, &["malformed.json: malformed JSON"]);
    assert_eq!(r.stderr.matches("EOF").count(), 1, "{}", r.stderr);
}

#[test]
fn too_many_poses_are_refused_before_any_work() {
    for args in [
        vec!["indices", "--poses", "100000000"],
        vec!["curve", "--quiet", "--poses", "100000000"],
        // Streamed (CSV, JSON Lines) it runs; a JSON document holds every row.
        vec![
            "compare",
            "--quiet",
            "--poses",
            "20000",
            "--out",
            "compare.json",
        ],
        vec!["rrr", "curve", "--poses", "100000000"],
    ] {
        let r = run(&args);
        assert_one_line_error(&r, &["--poses", "memory"]);
        assert!(
            r.elapsed < Duration::from_secs(20),
            "{args:?}: {:?}",
            r.elapsed
        );
    }
}

#[test]
fn more_threads_than_cores_are_clamped_with_a_warning() {
    let r = run(&[
        "curve",
        "--quiet",
        "--threads",
        "10000",
        "--poses",
        "6",
        "--metric",
        "plate/plate",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stderr.contains("warning: --threads 10000"),
        "{}",
        r.stderr
    );
    assert!(r.stdout.contains("plate/plate"), "{}", r.stdout);
    assert!(r.elapsed < Duration::from_secs(120), "{:?}", r.elapsed);

    let r = run(&[
        "distance",
        "--pose",
        "4,3,0.3",
        "--metric",
        "plate/plate",
        "--threads",
        "0",
    ]);
    assert_one_line_error(&r, &["--threads: must be at least 1"]);
}

#[test]
fn solve_with_failed_paths_warns_and_exits_3() {
    let dir = Scratch::new("solve");
    // Coefficients of 1e300 overflow in every evaluation: every path fails. (Both
    // equations of that size: one alone would be normalised by `--scaling auto`.)
    let failing = dir.write(
        "failing.input",
        "INPUT\nvariable_group x,y;\nfunction f,g;\nf = 1e300*x^2 - 1e300;\ng = 1e300*y^2 - 1e300;\nEND;\n",
    );
    let r = run(&["solve", &failing, "--threads", "10000"]);
    assert_eq!(r.code, 3, "stdout: {} stderr: {}", r.stdout, r.stderr);
    assert!(
        r.stderr.contains("warning: --threads 10000"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("4 of 4 paths failed ("), "{}", r.stderr);
    assert!(r.stdout.contains("failed        4"), "{}", r.stdout);
    let r = run(&["solve", &failing, "--json"]);
    assert_eq!(r.code, 3, "{}", r.stderr);

    let fine = dir.write(
        "fine.input",
        "INPUT\nvariable_group x,y;\nfunction f,g;\nf = x^2 - 1;\ng = y^2 - 4;\nEND;\n",
    );
    let r = run(&["solve", &fine]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(!r.stderr.contains("warning"), "{}", r.stderr);
}

#[test]
fn output_paths_are_checked_before_computing() {
    let dir = Scratch::new("paths");
    let missing = dir.path("no-such-folder/x.csv");
    let svg = dir.path("one.svg");
    let (png, txt, pdf, rpng) = (
        dir.path("x.png"),
        dir.path("x.txt"),
        dir.path("i.pdf"),
        dir.path("r.png"),
    );
    // 20,000 poses would take minutes: a refusal within seconds comes before the work.
    let curve = |option: &str, out: &str| -> Vec<String> {
        [
            "curve",
            "--quiet",
            "--poses",
            "20000",
            "--metric",
            "plate/plate",
            option,
            out,
        ]
        .map(String::from)
        .to_vec()
    };
    let owned = |args: &[&str]| -> Vec<String> { args.iter().map(|a| a.to_string()).collect() };
    let cases: Vec<(Vec<String>, &str, Vec<&str>)> = vec![
        (curve("--plot", &png), &png, vec!["--plot", "x.png", "SVG"]),
        (
            curve("--out", &missing),
            &missing,
            vec!["--out", "no-such-folder", "does not exist"],
        ),
        (
            curve("--out", &txt),
            &txt,
            vec!["--out", "x.txt", ".jsonl or .csv"],
        ),
        (
            owned(&["indices", "--poses", "900000", "--plot", &pdf]),
            &pdf,
            vec!["--plot", "SVG"],
        ),
        (
            owned(&["indices", "--poses", "900000", "--plot-data", &missing]),
            &missing,
            vec!["--plot-data", "does not exist"],
        ),
        (
            owned(&["rrr", "curve", "--poses", "50000", "--plot", &rpng]),
            &rpng,
            vec!["--plot", "SVG"],
        ),
        (
            owned(&["curve", "--quiet", "--poses", "1", "--plot", &svg]),
            &svg,
            vec!["--plot", "at least 2 poses"],
        ),
        (
            owned(&["map", "--csv", &missing]),
            &missing,
            vec!["--csv", "does not exist"],
        ),
    ];
    for (args, out, needles) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let r = run(&args);
        assert_one_line_error(&r, &needles);
        assert!(
            r.elapsed < Duration::from_secs(20),
            "{args:?}: {:?}",
            r.elapsed
        );
        assert_no_output(out);
    }
}

#[test]
fn a_failed_write_names_its_partial_file() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    let dir = Scratch::new("full");
    let out = dir.0.join("full.csv");
    std::os::unix::fs::symlink("/dev/full", &out).expect("symlink");
    let out = out.display().to_string();
    let r = run(&[
        "curve",
        "--quiet",
        "--poses",
        "4",
        "--metric",
        "plate/plate",
        "--out",
        &out,
    ]);
    let partial = format!("{out}.partial");
    assert_one_line_error(&r, &["--out", "cannot write", &partial]);
    let lines = std::fs::read_to_string(&partial).expect("partial file kept");
    // The run log: a header record, the four poses' CSV rows, one window record.
    let rows = lines.lines().filter(|l| !l.starts_with("{\"record\":"));
    assert_eq!(rows.count(), 4, "{lines}");
    assert_eq!(lines.lines().count(), 6, "{lines}");
}

#[test]
fn csv_tables_carry_lost_paths_per_pose() {
    let dir = Scratch::new("csv");
    let out = dir.path("curve.csv");
    let design = dir.write("design.json", DESIGN);
    let r = run(&[
        "curve",
        "--quiet",
        "--design",
        &design,
        "--poses",
        "5",
        "--metric",
        "plate/plate",
        "--out",
        &out,
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&out).expect("CSV written");
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("tau,x,y,phi,S,plate/plate,lost_paths"),
        "{text}"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 5, "{text}");
    assert!(rows.iter().all(|row| row.ends_with(",0")), "{text}");
    assert!(!Path::new(&format!("{out}.partial")).exists());

    let out = dir.path("rrr.csv");
    let r = run(&["rrr", "curve", "--quiet", "--poses", "3", "--out", &out]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&out).expect("CSV written");
    let header = text.lines().next().unwrap_or_default();
    assert!(header.ends_with(",lost_paths"), "{header}");
    assert_eq!(text.lines().count(), 4, "{text}");
}
