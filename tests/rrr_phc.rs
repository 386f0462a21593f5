//! Independent check of a 3-RRR start-solution file with PHCpack (`phc -b`: root counts,
//! polyhedral homotopy, filtering): the finite solutions PHCpack finds at the file's source
//! parameters are exactly the stored ones. Skips cleanly (with a message) when `phc` is
//! not on PATH.
use singdist::C64;
use singdist::pipeline::rrr::ab_initio::rrr_start_solutions;
use singdist::problem::rrr::{RrrProblem, RrrSubProblem};
use singdist::system::phc;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs `phc -b` on `input`, killing it after `limit`; returns the input file afterwards
/// (with PHCpack's appended solution list), `None` if it did not finish.
fn run_phc(input: &std::path::Path, output: &std::path::Path, limit: Duration) -> Option<String> {
    let mut child = Command::new("phc")
        .arg("-b")
        .arg(input)
        .arg(output)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .ok()?;
    let started = Instant::now();
    loop {
        if let Ok(Some(_)) = child.try_wait() {
            return std::fs::read_to_string(input).ok();
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Leg 2: PHCpack's finite regular solutions at the stored source parameters are exactly
/// the two stored solutions (the generic root count of a leg problem is 2, see
/// `systems/rrr_example_README.md`).
#[test]
fn phc_blackbox_confirms_the_leg_count() {
    if !phc::available() {
        eprintln!("skipped: `phc` (PHCpack) is not on PATH");
        return;
    }
    let kind = RrrSubProblem::Leg(1);
    let problem = RrrProblem::new(kind).unwrap();
    let start = rrr_start_solutions(&problem).unwrap();
    let values = start.parameter_vector(problem.parameter_names()).unwrap();
    let named: Vec<(String, C64)> = problem
        .parameter_names()
        .iter()
        .cloned()
        .zip(values)
        .collect();
    let text = phc::write(problem.system(), &named).unwrap();
    let directory = std::env::temp_dir().join(format!("singdist-rrr-phc-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let input = directory.join("leg2.phc");
    let output = directory.join("leg2.out");
    std::fs::write(&input, text).unwrap();
    let Some(result) = run_phc(&input, &output, Duration::from_secs(240)) else {
        let _ = std::fs::remove_dir_all(&directory);
        panic!("phc -b did not finish within 240 s");
    };
    let solutions = phc::read_last_solutions(&result);
    assert!(
        !solutions.is_empty(),
        "no solution list appended to {}: {} bytes",
        input.display(),
        result.len()
    );
    let _ = std::fs::remove_dir_all(&directory);
    for s in &solutions {
        // Inverse condition number of the Jacobian: far from singular.
        let rco = s.diagnostic("rco").unwrap_or(0.0);
        assert!(rco > 1e-10, "{}", s.closing);
    }
    let finite: Vec<Vec<C64>> = solutions
        .iter()
        .map(|s| {
            problem
                .variable_names()
                .iter()
                .map(|name| {
                    s.values
                        .iter()
                        .find(|(n, _)| n == name)
                        .map(|(_, v)| *v)
                        .unwrap_or_else(|| panic!("phc solution without `{name}`"))
                })
                .collect()
        })
        .collect();
    let close = |a: &[C64], b: &[C64]| {
        let scale = 1.0 + a.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        a.iter().zip(b).all(|(x, y)| (x - y).norm() <= 1e-6 * scale)
    };
    println!(
        "phc: {} finite solutions; stored {}",
        finite.len(),
        start.solutions.len()
    );
    assert_eq!(finite.len(), start.solutions.len());
    for x in &finite {
        assert!(
            start.solutions.iter().any(|y| close(x, y)),
            "a phc solution is not stored: {x:?}"
        );
    }
    for y in &start.solutions {
        assert!(finite.iter().any(|x| close(x, y)));
    }
}
