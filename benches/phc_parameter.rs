//! PHCpack side by side on this job's parameter homotopy (Paramotopy-style: every pose
//! from one solved seed). For each singularity sub-problem of the selected metrics on
//! the built-in example, the seed's finite critical points are tracked to one real pose
//! (default: pose 45 of 90) by
//! - PHCpack's coefficient-parameter continuation (`phc -p`, "complex homotopy with
//!   random gamma constant", hardware double precision) in one natural parameter `s`:
//!   the Lagrange system on the segment `p(s) = p_seed + s (p_pose − p_seed)`, from
//!   `s = 0` to `s = 1`;
//! - singdist's parameter homotopy along the straight parameter segment
//!   ([`solve_parameter_homotopy`], the curve's tracker settings, 1 thread);
//!
//! both from the same start solutions (Cartesian coordinates, the curve's normalised
//! frame). It prints, per sub-problem, the finite endpoints each found (PHCpack's: those
//! with residual ≤ 10⁻⁸), whether PHCpack's are among singdist's, and the best of 3
//! wall times (PHCpack: the whole process, reading and writing its files included;
//! singdist: the library call).
//!
//! `cargo bench --bench phc_parameter`; skips cleanly when `phc` is not on PATH
//! (`apt-get update && apt-get install -y phcpack`). `SINGDIST_BENCH_METRICS`
//! (default `plate/plate,rigid/rigid`) and `SINGDIST_BENCH_POSE` (default 45) select
//! the work.

use singdist::C64;
use singdist::homotopy::{PathStatus, SolveOptions, solve_parameter_homotopy};
use singdist::mechanism::rpr::{example_design, example_motion};
use singdist::metric::Metric;
use singdist::pipeline::curve::{
    CurveOptions, default_start_solutions, pose_parameters, sample_motion, seed_stage,
};
use singdist::problem::{Coordinates, SubProblem};
use singdist::system::{Expr, System, phc};
use std::process::{Command, Stdio};
use std::time::Instant;

fn best_of_3(mut run: impl FnMut()) -> f64 {
    (0..3)
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    if std::env::args().any(|a| a == "--list") {
        return;
    }
    if !phc::available() {
        println!("phc_parameter: phc (PHCpack) not found; skipping");
        return;
    }
    let list = std::env::var("SINGDIST_BENCH_METRICS")
        .unwrap_or_else(|_| "plate/plate,rigid/rigid".into());
    let fail = |message: String| -> ! {
        eprintln!("phc_parameter: {message}");
        std::process::exit(2)
    };
    let metrics =
        Metric::parse_list(&list).unwrap_or_else(|e| fail(format!("SINGDIST_BENCH_METRICS: {e}")));
    let pose_index: usize = match std::env::var("SINGDIST_BENCH_POSE") {
        Ok(v) => v.parse().unwrap_or_else(|_| {
            fail(format!(
                "SINGDIST_BENCH_POSE: `{v}` is not a pose index (0..89)"
            ))
        }),
        Err(_) => 45,
    };
    if pose_index >= 90 {
        fail(format!(
            "SINGDIST_BENCH_POSE: {pose_index} is not a pose index (0..89)"
        ));
    }
    let design = example_design();
    let motion = example_motion();
    let options = CurveOptions {
        coordinates: Coordinates::Cartesian,
        ..CurveOptions::default()
    };
    let stage = seed_stage(
        &design,
        &motion,
        &metrics,
        &options,
        &default_start_solutions,
    )
    .expect("seed stage");
    let samples = sample_motion(&motion, 90).expect("samples");
    let sample = samples[pose_index];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("thread pool");
    let work = std::env::temp_dir().join(format!("singdist-phc-parameter-{}", std::process::id()));
    std::fs::create_dir_all(&work).expect("scratch directory");
    println!(
        "pose {} (tau = {:.4}), seed tau* from the curve's seed stage, Cartesian coordinates, 1 thread",
        pose_index, sample.tau
    );
    for seeded in stage
        .problems
        .iter()
        .filter(|s| s.id.subproblem == SubProblem::Singularity)
    {
        let system = seeded.problem.system();
        let start = &seeded.at_seed.parameters;
        let target = pose_parameters(&stage, seeded, sample.pose);
        // singdist: the straight parameter segment, the curve's tracker settings.
        let solve_options = SolveOptions {
            tracker: options.tracker.clone(),
            ..SolveOptions::default()
        };
        let run = || {
            solve_parameter_homotopy(
                seeded.problem.evaluator(),
                &seeded.at_seed.solutions,
                start,
                &target,
                &solve_options,
            )
            .expect("parameter homotopy")
        };
        let ours = pool.install(run);
        let our_points = ours.finite_endpoints();
        let our_seconds = best_of_3(|| {
            pool.install(run);
        });
        // PHCpack: the same straight parameter segment as one natural parameter `s`,
        // `p(s) = p_seed + s (p_pose − p_seed)` (n equations in n + 1 unknowns). Its
        // coefficient-parameter continuation with several parameters fails on more
        // than 3 (PHCpack 2.4.86: `Define_Parameters` sorts the parameter indices with
        // a selection sort that scans from the second entry on every pass, which
        // leaves 4 or more indices unsorted, and `Substitute` fails an index check).
        let segment = |name: &str| -> Option<Expr> {
            let i = system.parameters().iter().position(|p| p == name)?;
            let constant = |v: C64| Expr::constant(v);
            Some(constant(start[i]) + constant(target[i] - start[i]) * Expr::variable("s"))
        };
        let equations: Vec<Expr> = system
            .equations()
            .iter()
            .map(|f| f.substitute(&segment))
            .collect();
        let mut unknowns: Vec<String> = system.variables().to_vec();
        unknowns.push("s".into());
        let open = System::new(&unknowns, Vec::<String>::new(), equations)
            .expect("the system on the parameter segment");
        let text = phc::write(&open, &[]).expect("PHCpack input");
        // PHCpack numbers the unknowns in order of first appearance, as `phc::read`.
        let order: Vec<String> = phc::read(&text)
            .expect("PHCpack input reads back")
            .variables()
            .to_vec();
        let starts: Vec<Vec<C64>> = seeded
            .at_seed
            .solutions
            .iter()
            .map(|x| {
                order
                    .iter()
                    .map(|name| match unknowns.iter().position(|u| u == name) {
                        Some(i) if i < x.len() => x[i],
                        _ => C64::new(0.0, 0.0),
                    })
                    .collect()
            })
            .collect();
        let stem = seeded.id.file_stem();
        let input = work.join(format!("{stem}.phc"));
        let solutions = work.join(format!("{stem}.sols"));
        let output = work.join(format!("{stem}.out"));
        std::fs::write(&input, &text).expect("write PHCpack input");
        std::fs::write(&solutions, phc::write_solutions(&order, &starts)).expect("write solutions");
        // The dialogue of `phc -p` for coefficient-parameter continuation: random-γ
        // homotopy, double precision, the files, the parameter `s` (and a yes), its
        // target value 1 (real and imaginary part, one number a line), then the default
        // tracker settings and no intermediate output.
        let answers = format!(
            "1\n0\n{}\n{}\ns\ny\n1.0\n0.0\n0\n0\n",
            solutions.display(),
            output.display()
        );
        let run_phc = || {
            let _ = std::fs::remove_file(&output);
            let mut child = Command::new("phc")
                .arg("-p")
                .arg(&input)
                .stdin(Stdio::piped())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .expect("phc starts");
            use std::io::Write as _;
            child
                .stdin
                .take()
                .expect("stdin")
                .write_all(answers.as_bytes())
                .expect("phc reads its answers");
            child.wait().expect("phc finishes");
        };
        let phc_seconds = best_of_3(run_phc);
        let out = std::fs::read_to_string(&output).unwrap_or_default();
        let found = phc::read_last_solutions(&out);
        let n = system.variables().len();
        let finite: Vec<Vec<C64>> = found
            .iter()
            .filter(|s| s.diagnostic("res").is_some_and(|r| r <= 1e-8))
            .map(|s| {
                system
                    .variables()
                    .iter()
                    .map(|name| s.value(name).unwrap_or(C64::new(f64::NAN, 0.0)))
                    .collect::<Vec<C64>>()
            })
            .filter(|x: &Vec<C64>| x.len() == n && x.iter().all(|v| v.re.is_finite()))
            .collect();
        let matched = finite
            .iter()
            .filter(|x| {
                our_points.iter().any(|y| {
                    let scale = 1.0 + y.iter().fold(0.0f64, |m, v| m.max(v.norm()));
                    x.iter().zip(y).all(|(a, b)| (a - b).norm() <= 1e-6 * scale)
                })
            })
            .count();
        let nonsingular = ours
            .paths
            .iter()
            .filter(|p| p.status == PathStatus::Nonsingular)
            .count();
        println!(
            "{}: {} start points; singdist {} finite ({} nonsingular) in {:.3} s; \
             phc -p {} of {} endpoints with residual <= 1e-8, {} of them among singdist's, \
             in {:.3} s; phc/singdist = {:.1}",
            seeded.id.name(),
            seeded.at_seed.solutions.len(),
            our_points.len(),
            nonsingular,
            our_seconds,
            finite.len(),
            found.len(),
            matched,
            phc_seconds,
            phc_seconds / our_seconds
        );
    }
    if std::env::var_os("SINGDIST_BENCH_KEEP").is_some() {
        println!("files kept in {}", work.display());
    } else {
        let _ = std::fs::remove_dir_all(&work);
    }
}
