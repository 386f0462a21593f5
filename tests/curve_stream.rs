//! `singdist curve` streamed window by window: peak memory independent of the number
//! of poses, `--resume` after a kill equal byte for byte to an uninterrupted run, and
//! resumes with other arguments refused.

mod cli_support;
mod process_support;
use cli_support::{binary, fresh_dir, read};
use process_support::assert_memory_flat_in_poses;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn folder(name: &str) -> PathBuf {
    fresh_dir(&format!("stream-{name}"))
}

/// `curve --quiet --metric plate/plate --threads 1` with `extra` arguments.
fn curve(extra: &[&str]) -> Command {
    let mut command = Command::new(binary());
    command.args([
        "curve",
        "--quiet",
        "--metric",
        "plate/plate",
        "--threads",
        "1",
    ]);
    command.args(extra);
    command.stdout(Stdio::null()).stderr(Stdio::piped());
    command
}

/// With windows of 500 poses, 10 × the poses need (almost) no more memory. Before
/// streaming, every pose kept its critical points to the end: 57 MB peak for 2,000
/// poses of `plate/plate` against 14 MB now.
#[test]
fn peak_memory_does_not_grow_with_the_number_of_poses() {
    let dir = folder("memory");
    assert_memory_flat_in_poses(|poses| {
        let out = dir.join(format!("m{poses}.csv")).display().to_string();
        curve(&["--poses", poses, "--window", "500", "--out", &out])
    });
}

/// Lines of `path`, which must exist.
/// Windows recorded in a run log.
fn windows_in(path: &Path) -> usize {
    std::fs::read_to_string(path)
        .map(|t| t.matches("{\"record\":\"window\"").count())
        .unwrap_or(0)
}

#[test]
fn resume_after_a_kill_equals_the_uninterrupted_run() {
    let dir = folder("resume");
    let args = |out: &str| -> Vec<String> {
        [
            "--poses", "2000", "--window", "100", "--seed", "3", "--out", out,
        ]
        .map(String::from)
        .to_vec()
    };
    for ext in ["csv", "jsonl"] {
        let whole = dir.join(format!("whole.{ext}")).display().to_string();
        let status = curve(&args(&whole).iter().map(String::as_str).collect::<Vec<_>>())
            .status()
            .expect("run");
        assert!(status.success());

        let cut = dir.join(format!("cut.{ext}"));
        let cut_name = cut.display().to_string();
        let partial = PathBuf::from(format!("{cut_name}.partial"));
        let cut_args = args(&cut_name);
        let cut_args: Vec<&str> = cut_args.iter().map(String::as_str).collect();
        let mut child = curve(&cut_args).spawn().expect("spawn");
        let started = Instant::now();
        while windows_in(&partial) < 2 && child.try_wait().expect("wait").is_none() {
            assert!(
                started.elapsed() < Duration::from_secs(120),
                "no window written"
            );
            std::thread::sleep(Duration::from_millis(2));
        }
        let _ = child.kill();
        let _ = child.wait();
        if !cut.exists() {
            let done = windows_in(&partial);
            assert!((2..20).contains(&done), "{done} windows before the kill");
            let mut resumed = cut_args.clone();
            resumed.push("--resume");
            let output = curve(&resumed).output().expect("resume");
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(output.status.success(), "{stderr}");
        }
        assert_eq!(read(&cut), read(Path::new(&whole)), "{ext}");
        assert!(!partial.exists());
    }
}

#[test]
fn a_resume_with_other_arguments_is_refused() {
    let dir = folder("refuse");
    let jsonl = dir.join("run.jsonl").display().to_string();
    let status = curve(&["--poses", "40", "--window", "20", "--out", &jsonl])
        .status()
        .expect("run");
    assert!(status.success());
    // A log interrupted before its first window: the header record only.
    let header = read(Path::new(&jsonl))
        .lines()
        .next()
        .unwrap_or_default()
        .to_string()
        + "\n";
    assert!(header.starts_with("{\"record\":\"header\""), "{header}");
    let out = dir.join("run.csv").display().to_string();
    let partial = format!("{out}.partial");
    let resume = |extra: &[&str]| {
        let mut args = vec!["--window", "20", "--out", &out, "--resume"];
        args.extend_from_slice(extra);
        curve(&args).output().expect("run")
    };
    let refused = |extra: &[&str], needles: &[&str]| {
        let output = resume(extra);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{extra:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        for needle in needles {
            assert!(stderr.contains(needle), "`{needle}` missing: {stderr}");
        }
    };
    // Without a log the run starts afresh, with a note.
    let output = resume(&["--poses", "40"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && stderr.contains("starting from the first window"),
        "{stderr}"
    );
    std::fs::write(&partial, "").expect("partial");
    refused(&["--poses", "40"], &["--resume", "no complete header"]);
    std::fs::write(&partial, &header).expect("partial");
    refused(
        &["--poses", "41"],
        &["--resume", "poses (40 there, 41 now)"],
    );
    refused(
        &["--poses", "40", "--seed", "2"],
        &["seed (1 there, 2 now)"],
    );
    refused(
        &["--poses", "40", "--metric", "bars/bars"],
        &["metric", "plate/plate"],
    );
    // The same arguments continue it.
    let output = resume(&["--poses", "40"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(!Path::new(&partial).exists());
    assert_eq!(read(Path::new(&out)).lines().count(), 41);
}
