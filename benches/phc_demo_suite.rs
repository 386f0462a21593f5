//! PHCpack's demo systems solved side by side by `singdist solve --threads 1` and
//! `phc -b -t1`, every root of both refined by Newton's method against the original
//! polynomials to decide the true number of distinct nonsingular roots.
//!
//! Usage (after `cargo build --release`):
//!
//! ```text
//! cargo bench --bench phc_demo_suite -- [--dir DIR] [--max-degree N] [--timeout S]
//!     [--only NAME,NAME] [--seed SEED] [--singdist PATH] [--start START] [--keep DIR]
//! ```
//!
//! `--keep DIR` writes the converted files (`NAME.input` for singdist, `NAME.phc` for
//! PHCpack) and both solvers' outputs to `DIR` and keeps them there.
//!
//! `START` (or the environment variable `SINGDIST_START`) is passed to
//! `singdist solve --start` (`total-degree`, `multi-homogeneous`, `auto`,
//! `polyhedral`); without it singdist uses its default.
//!
//! `DIR` defaults to `/usr/share/doc/phcpack/examples` (Debian package `phcpack`, files
//! possibly gzipped); systems of total degree above `N` (default 1000) are skipped; each
//! solver run is killed after `S` seconds (default 120). Skips cleanly when `phc` is not
//! installed. Per system the table gives the Bézout number, singdist's counts (paths
//! tracked, paths reported nonsingular, distinct nonsingular roots after refinement, singular, at
//! infinity, failed), PHCpack's distinct nonsingular roots, those of the solution list
//! the demo file itself ships (`THE SOLUTIONS`, computed by PHCpack's authors, often
//! in extended precision; `-` where the file has none), the union of all three (the
//! true count unless all miss a root), who is right, and the phc/singdist time ratio.
//! On `discret3s` the file's list holds 128 roots (norms up to 1.2·10⁵) where both
//! solvers' runs stop short of them.

mod bench_support;
use serde_json::Value;
use singdist::C64;
use singdist::homotopy::{accuracy_at_condition, group_roots, newton_refine};
use singdist::system::scaling::Scaling;
use singdist::system::{CompiledSystem, System, bertini, phc};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// Newton stops at corrections below this (relative).
const NEWTON_TOLERANCE: f64 = 1e-13;
/// Condition number below which a converged Newton limit is a nonsingular root.
const NONSINGULAR_CONDITION: f64 = 1e11;
/// Two refined nonsingular roots closer than this (relative, plus `10·κ·ε`, how far a
/// root at condition κ moves when the coefficients are rounded) are the same root.
const SAME_ROOT_TOLERANCE: f64 = 1e-10;

/// Six characters standing for the distinct-root count until it is known.
const DISTINCT_MARK: &str = "<dist>";

struct Arguments {
    dir: PathBuf,
    max_degree: u128,
    timeout: f64,
    only: Vec<String>,
    seed: Option<u64>,
    singdist: PathBuf,
    start: Option<String>,
    keep: Option<PathBuf>,
}

fn arguments() -> Arguments {
    let mut a = Arguments {
        dir: PathBuf::from("/usr/share/doc/phcpack/examples"),
        max_degree: 1000,
        timeout: 120.0,
        only: Vec::new(),
        seed: None,
        singdist: PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/release/singdist"),
        start: std::env::var("SINGDIST_START").ok(),
        keep: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || {
            args.next()
                .unwrap_or_else(|| panic!("{flag} needs a value"))
        };
        match flag.as_str() {
            "--dir" => a.dir = PathBuf::from(value()),
            "--max-degree" => a.max_degree = value().parse().expect("--max-degree: integer"),
            "--timeout" => a.timeout = value().parse().expect("--timeout: seconds"),
            "--only" => a.only = value().split(',').map(str::to_string).collect(),
            "--seed" => a.seed = Some(value().parse().expect("--seed: integer")),
            "--singdist" => a.singdist = PathBuf::from(value()),
            "--start" => a.start = Some(value()),
            "--keep" => a.keep = Some(PathBuf::from(value())),
            "--bench" => {}
            other => panic!("unknown argument {other}"),
        }
    }
    a
}

/// The text of a demo file (gunzipped if needed).
fn read_demo(path: &Path) -> Option<String> {
    if path.extension().is_some_and(|e| e == "gz") {
        let out = Command::new("gzip").arg("-dc").arg(path).output().ok()?;
        return String::from_utf8(out.stdout).ok();
    }
    std::fs::read_to_string(path).ok()
}

/// The system part of a PHCpack file: the counts line and the first `n` polynomials
/// (each ended by `;`), dropping titles, root counts and solution lists after them.
fn system_text(text: &str) -> Option<String> {
    let trimmed = text.trim_start();
    let first_line = trimmed.lines().next()?;
    let n: usize = first_line.split_whitespace().next()?.parse().ok()?;
    let rest = &trimmed[first_line.len()..];
    let mut end = 0;
    for _ in 0..n {
        end += rest[end..].find(';')? + 1;
    }
    Some(format!("{first_line}{}\n", &rest[..end]))
}

/// Runs of a solver shorter than this are repeated (see [`run_timed`]).
const SHORT_RUN: f64 = 0.2;
/// At most this many runs of one solver on one system.
const MAX_RUNS: usize = 5;

/// Runs `command` once with a timeout: (wall seconds, exit code, stdout), exit code
/// `None` when killed by the timeout. The bench blocks in `wait` (a watchdog thread
/// kills the child at the timeout), so the measured time ends when the child exits:
/// polling `try_wait` added up to a millisecond to every run, a quarter of the
/// smallest systems' solve time.
fn run_once(command: &mut Command, timeout: f64) -> (f64, Option<i32>, String) {
    let started = Instant::now();
    let mut child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("cannot start a solver");
    let mut stdout = child.stdout.take().expect("piped stdout");
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = std::io::Read::read_to_string(&mut stdout, &mut text);
        text
    });
    let pid = child.id().to_string();
    let (done, exited) = std::sync::mpsc::channel::<()>();
    let watchdog = std::thread::spawn(move || {
        let limit = std::time::Duration::from_secs_f64(timeout);
        if exited.recv_timeout(limit).is_err() {
            let _ = Command::new("kill").args(["-9", &pid]).status();
            return true;
        }
        false
    });
    let status = child.wait().expect("wait for a solver");
    let seconds = started.elapsed().as_secs_f64();
    let _ = done.send(());
    let killed = watchdog.join().unwrap_or(false);
    let text = reader.join().unwrap_or_default();
    if killed {
        return (timeout, None, String::new());
    }
    (seconds, status.code(), text)
}

/// Runs a solver like [`run_once`]; a run shorter than [`SHORT_RUN`] is repeated (at
/// most [`MAX_RUNS`] runs, at most `SHORT_RUN` seconds in all) and the median wall
/// time reported, as benchmark tools do: one run of a few milliseconds varies by
/// 30 % or more with the page cache and the scheduler. The repeats run `repeat()`'s
/// command (PHCpack's on copies of its files, so that the first run's output stays
/// what is verified). Exit code and output are the first run's.
fn run_timed(
    command: &mut Command,
    timeout: f64,
    repeat: &dyn Fn() -> Command,
) -> (f64, Option<i32>, String) {
    let first = run_once(command, timeout);
    if first.1.is_none() || first.0 >= SHORT_RUN {
        return first;
    }
    let mut times = vec![first.0];
    while times.len() < MAX_RUNS && times.iter().sum::<f64>() < SHORT_RUN {
        times.push(run_once(&mut repeat(), timeout).0);
    }
    (median(&mut times), first.1, first.2)
}

/// Distinct nonsingular roots among approximate roots, after Newton refinement:
/// (number of distinct roots, the refined representatives with their accuracy).
fn distinct_nonsingular(
    system: &CompiledSystem,
    points: &[Vec<C64>],
) -> (usize, Vec<(Vec<C64>, f64)>) {
    let refined: Vec<(Vec<C64>, f64)> = points
        .iter()
        .map(|x| newton_refine(system, x, &[], NEWTON_TOLERANCE, 60))
        .filter(|r| r.is_nonsingular(NONSINGULAR_CONDITION))
        .map(|r| {
            let accuracy = accuracy_at_condition(r.condition);
            (r.point, accuracy)
        })
        .collect();
    let groups = group_roots(&refined, SAME_ROOT_TOLERANCE);
    let representatives: Vec<(Vec<C64>, f64)> = groups
        .iter()
        .enumerate()
        .filter(|&(i, &g)| i == g)
        .map(|(i, _)| refined[i].clone())
        .collect();
    (representatives.len(), representatives)
}

fn json_point(value: &Value) -> Vec<C64> {
    value
        .as_array()
        .map(|coordinates| {
            coordinates
                .iter()
                .map(|c| {
                    C64::new(
                        c[0].as_f64().unwrap_or(f64::NAN),
                        c[1].as_f64().unwrap_or(f64::NAN),
                    )
                })
                .collect()
        })
        .unwrap_or_default()
}

/// The points of a PHCpack solution list with coordinates in the order `names`.
fn in_order(solutions: &[phc::PhcSolution], names: &[String]) -> Vec<Vec<C64>> {
    solutions
        .iter()
        .map(|s| {
            names
                .iter()
                .map(|n| s.value(n).unwrap_or_default())
                .collect()
        })
        .collect()
}

struct Row {
    name: String,
    bezout: u128,
    line: String,
    ratio: Option<f64>,
    verdict: &'static str,
}

fn solve_one(
    args: &Arguments,
    name: &str,
    system: &System,
    input: &str,
    listed: &[phc::PhcSolution],
    work: &Path,
) -> Row {
    let bezout = system.bezout_number();
    let mut row = Row {
        name: name.to_string(),
        bezout,
        line: String::new(),
        ratio: None,
        verdict: "error",
    };
    let bertini_text = match bertini::write(system) {
        Ok(t) => t,
        Err(e) => {
            row.line = format!("cannot write Bertini input: {e}");
            return row;
        }
    };
    let bertini_file = work.join(format!("{name}.input"));
    let phc_file = work.join(format!("{name}.phc"));
    let phc_out = work.join(format!("{name}.phc.out"));
    std::fs::write(&bertini_file, bertini_text).expect("write the Bertini file");
    std::fs::write(&phc_file, input).expect("write the PHCpack file");
    let _ = std::fs::remove_file(&phc_out);

    let mut ours = Command::new(&args.singdist);
    ours.arg("solve")
        .arg(&bertini_file)
        .args(["--threads", "1", "--json"]);
    if let Some(seed) = args.seed {
        ours.args(["--seed", &seed.to_string()]);
    }
    if let Some(start) = &args.start {
        ours.args(["--start", start]);
    }
    let our_arguments: Vec<std::ffi::OsString> = ours.get_args().map(Into::into).collect();
    let our_repeat = || {
        let mut c = Command::new(&args.singdist);
        c.args(&our_arguments);
        c
    };
    let (our_time, our_code, our_out) = run_timed(&mut ours, args.timeout, &our_repeat);
    let mut theirs = Command::new("phc");
    theirs.arg("-b").arg("-t1").arg(&phc_file).arg(&phc_out);
    let phc_repeat = || {
        let file = work.join(format!("{name}.repeat.phc"));
        let out = work.join(format!("{name}.repeat.phc.out"));
        std::fs::write(&file, input).expect("write the PHCpack file");
        let _ = std::fs::remove_file(&out);
        let mut c = Command::new("phc");
        c.arg("-b").arg("-t1").arg(file).arg(out);
        c
    };
    let (phc_time, phc_code, _) = run_timed(&mut theirs, args.timeout, &phc_repeat);
    for extension in ["repeat.phc", "repeat.phc.out"] {
        let _ = std::fs::remove_file(work.join(format!("{name}.{extension}")));
    }

    // Roots are verified where the system is balanced: a badly scaled one (coordinates
    // of 10⁻¹¹, coefficients of 10⁻¹⁵) in its least-squares scaling, so that Newton's
    // convergence, the condition number and the same-root test are judged in
    // coordinates of comparable size (the same for both solvers); a system whose
    // equations differ widely in size with its equations normalised.
    let scaling = Scaling::automatic(system);
    let compiled = match &scaling {
        Some(s) => s.apply(system).compile(),
        None => system.compile(),
    };
    let balanced = |points: Vec<Vec<C64>>| -> Vec<Vec<C64>> {
        match &scaling {
            Some(s) => points.iter().map(|x| s.scale(x)).collect(),
            None => points,
        }
    };
    let names = system.variables();
    // singdist: finite endpoints (nonsingular and singular) in its variable order.
    let ours_json: Option<Value> = our_code
        .filter(|&c| c == 0 || c == 3)
        .and_then(|_| serde_json::from_str(&our_out).ok());
    let (ours_summary, our_points, our_reported) = match &ours_json {
        Some(v) => {
            let order: Vec<String> = v["variables"]
                .as_array()
                .map(|a| {
                    a.iter()
                        .filter_map(|s| s.as_str().map(String::from))
                        .collect()
                })
                .unwrap_or_default();
            let permutation: Vec<usize> = names
                .iter()
                .map(|n| order.iter().position(|o| o == n).unwrap_or(0))
                .collect();
            let solutions = v["solutions"].as_array().cloned().unwrap_or_default();
            let points: Vec<Vec<C64>> = solutions
                .iter()
                .map(|s| {
                    let x = json_point(&s["coordinates"]);
                    permutation
                        .iter()
                        .map(|&k| x.get(k).copied().unwrap_or_default())
                        .collect()
                })
                .collect();
            let s = &v["summary"];
            let count = |field: &str| s[field].as_u64().unwrap_or(0);
            let summary = format!(
                "{:>6} {:>6} {:>6} {:>5} {:>6} {:>6}",
                count("paths"),
                count("nonsingular"),
                DISTINCT_MARK,
                count("singular"),
                count("at_infinity"),
                count("failed")
            );
            (
                Some(summary),
                points,
                s["nonsingular"].as_u64().unwrap_or(0),
            )
        }
        None => (None, Vec::new(), 0),
    };
    // PHCpack: every solution of its final list (`phc -b` appends it to its input file;
    // the output file holds the intermediate lists).
    let phc_points: Option<Vec<Vec<C64>>> = phc_code.map(|_| {
        let text = std::fs::read_to_string(&phc_file).unwrap_or_default();
        in_order(&phc::read_last_solutions(&text), names)
    });
    let (our_distinct, our_roots) = distinct_nonsingular(&compiled, &balanced(our_points));
    let (phc_distinct, phc_roots) = match phc_points.clone() {
        Some(p) => distinct_nonsingular(&compiled, &balanced(p)),
        None => (0, Vec::new()),
    };
    // The demo file's own solution list, in the system's variable order.
    let listed_points = in_order(listed, names);
    let (listed_distinct, listed_roots) = distinct_nonsingular(&compiled, &balanced(listed_points));
    let union: Vec<(Vec<C64>, f64)> = our_roots
        .into_iter()
        .chain(phc_roots)
        .chain(listed_roots)
        .collect();
    let groups = group_roots(&union, SAME_ROOT_TOLERANCE);
    let true_count = groups.iter().enumerate().filter(|&(i, &g)| i == g).count();

    let ours_text = match &ours_summary {
        Some(s) => s.replacen(DISTINCT_MARK, &format!("{our_distinct:>6}"), 1),
        None => format!(
            "{:>41}",
            if our_code.is_none() {
                "timeout"
            } else {
                "error"
            }
        ),
    };
    let phc_text = if phc_points.is_some() {
        format!("{phc_distinct:>6}")
    } else {
        format!("{:>6}", "timeout")
    };
    row.verdict = match (ours_summary.is_some(), phc_points.is_some()) {
        (true, true) if our_distinct == true_count && phc_distinct == true_count => {
            if our_reported as usize == our_distinct {
                "agree"
            } else {
                "agree*"
            }
        }
        (true, _) if our_distinct == true_count => "singdist",
        (_, true) if phc_distinct == true_count => "phc",
        (true, true) => "neither",
        _ => "timeout",
    };
    if ours_summary.is_some() && phc_points.is_some() {
        row.ratio = Some(phc_time / our_time.max(1e-3));
    }
    let listed_text = if listed.is_empty() {
        format!("{:>6}", "-")
    } else {
        format!("{listed_distinct:>6}")
    };
    row.line = format!(
        "{ours_text} {phc_text} {listed_text} {true_count:>6} {:>9} {our_time:>9.3} {phc_time:>9.3} {:>8}",
        row.verdict,
        row.ratio.map_or("-".into(), |r| format!("{r:.2}"))
    );
    row
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

fn main() {
    let args = arguments();
    if !phc::available() {
        println!("phc_demo_suite: phc (PHCpack) not found; skipping");
        return;
    }
    assert!(
        args.singdist.exists(),
        "{} not built; run `cargo build --release` first",
        args.singdist.display()
    );
    let Ok(entries) = std::fs::read_dir(&args.dir) else {
        println!("phc_demo_suite: {} not found; skipping", args.dir.display());
        return;
    };
    let mut files: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.sort();
    let work = args.keep.clone().unwrap_or_else(|| {
        std::env::temp_dir().join(format!("phc_demo_suite.{}", std::process::id()))
    });
    std::fs::create_dir_all(&work).expect("create the work directory");
    println!(
        "{:<12} {:>6} {:>6} {:>6} {:>6} {:>5} {:>6} {:>6} {:>6} {:>6} {:>6} {:>9} {:>9} {:>9} {:>8}",
        "system",
        "bezout",
        "paths",
        "ns",
        "dist",
        "sing",
        "inf",
        "fail",
        "phc",
        "file",
        "true",
        "right",
        "t_ours",
        "t_phc",
        "phc/ours"
    );
    let mut rows = Vec::new();
    for path in files {
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .trim_end_matches(".gz")
            .to_string();
        if !args.only.is_empty() && !args.only.contains(&name) {
            continue;
        }
        let Some(text) = read_demo(&path) else {
            continue;
        };
        let Some(input) = system_text(&text) else {
            continue;
        };
        let Some(system) = bench_support::parse_phc(&name, &input) else {
            continue;
        };
        if system.num_equations() != system.variables().len() {
            continue;
        }
        let bezout = system.bezout_number();
        if bezout > args.max_degree {
            continue;
        }
        let listed = phc::read_last_solutions(&text);
        let row = solve_one(&args, &name, &system, &input, &listed, &work);
        println!("{:<12} {:>6} {}", row.name, row.bezout, row.line);
        rows.push(row);
    }
    if args.keep.is_none() {
        let _ = std::fs::remove_dir_all(&work);
    }
    let count = |v: &str| rows.iter().filter(|r| r.verdict == v).count();
    println!(
        "\n{} systems: agree {} (+{} where singdist's reported nonsingular count differs from its refined distinct count), only singdist right {}, only phc right {}, neither {}, timeout/error {}",
        rows.len(),
        count("agree"),
        count("agree*"),
        count("singdist"),
        count("phc"),
        count("neither"),
        count("timeout") + count("error")
    );
    let mut ratios: Vec<f64> = rows.iter().filter_map(|r| r.ratio).collect();
    if !ratios.is_empty() {
        let geometric = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
        println!(
            "phc/singdist time ratio over {} systems: geometric mean {geometric:.2}, median {:.2}",
            ratios.len(),
            median(&mut ratios)
        );
    }
}
