//! `singdist solve` end to end: text summary, JSON schema, monodromy, bad input.

mod cli_support;
use cli_support::{assert_success, singdist, temp_dir};
mod demo_support;
use demo_support::{SYSTEMS, demo_file};

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let path = temp_dir("homotopy-cli").join(name);
    std::fs::write(&path, text).unwrap();
    path
}

const CIRCLE_HYPERBOLA: &str =
    "INPUT\nvariable_group x, y;\nfunction f, g;\nf = x^2 + y^2 - 1;\ng = x*y - 0.25;\nEND;\n";

#[test]
fn text_summary_counts_the_four_real_intersections() {
    let file = write("ch.input", CIRCLE_HYPERBOLA);
    let out = singdist(&["solve", file.to_str().unwrap(), "--threads", "1"]);
    assert_success(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    for line in [
        "paths         4",
        "nonsingular   4",
        "at infinity   0",
        "failed        0",
        "real          4",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
}

#[test]
fn json_output_has_summary_and_solutions_as_re_im_pairs() {
    let file = write("ch2.input", CIRCLE_HYPERBOLA);
    let out = singdist(&["solve", file.to_str().unwrap(), "--json", "--seed", "3"]);
    assert!(out.status.success());
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["summary"]["nonsingular"], 4);
    let solutions = value["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 4);
    for s in solutions {
        let c = s["coordinates"].as_array().unwrap();
        let x = c[0][0].as_f64().unwrap();
        let y = c[1][0].as_f64().unwrap();
        assert!((x * x + y * y - 1.0).abs() < 1e-12 && (x * y - 0.25).abs() < 1e-12);
        assert!(c[0][1].as_f64().unwrap().abs() < 1e-12);
        assert_eq!(s["status"], "nonsingular");
        assert!(s["residual"].as_f64().unwrap() < 1e-14);
        assert!(s["condition"].as_f64().unwrap() >= 1.0);
    }
}

#[test]
fn monodromy_mode_agrees_and_reports_a_small_trace_residual() {
    let file = write("ch3.input", CIRCLE_HYPERBOLA);
    let out = singdist(&["solve", file.to_str().unwrap(), "--monodromy", "--json"]);
    assert!(out.status.success());
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["summary"]["nonsingular"], 4);
    assert!(value["trace_residual"].as_f64().unwrap() < 1e-8);
}

#[test]
fn bad_files_and_unset_parameters_are_errors() {
    let missing = singdist(&["solve", "/definitely/not/here.input"]);
    assert_eq!(missing.status.code(), Some(1));
    let bad = write("bad.input", "variable_group x;\nfunction f;\nf = x^2 - ;\n");
    let out = singdist(&["solve", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line"));
    let param = write(
        "p.input",
        "variable_group x;\nparameter a;\nfunction f;\nf = x^2 - a;\n",
    );
    let out = singdist(&["solve", param.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--set"));
    let out = singdist(&["solve", param.to_str().unwrap(), "--set", "a=4", "--json"]);
    assert_success(&out);
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["summary"]["nonsingular"], 2);
}

/// `xy + x − 1 = 0, xy − y + 2 = 0`: roots `x = 2 ± √3, y = 3 − x`; 2-homogeneous
/// Bézout number 2 in `{x} {y}` against the total degree 4.
const BILINEAR: &str =
    "INPUT\nvariable_group x, y;\nfunction f, g;\nf = x*y + x - 1;\ng = x*y - y + 2;\nEND;\n";

#[test]
fn start_option_reports_the_start_system_and_its_paths() {
    let file = write("bilinear.input", BILINEAR);
    let path = file.to_str().unwrap();
    let out = singdist(&["solve", path, "--start", "auto", "--json"]);
    assert!(out.status.success());
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let start = &value["start_system"];
    assert_eq!(start["name"], "multi-homogeneous");
    assert_eq!(start["partition"], serde_json::json!([["x"], ["y"]]));
    assert_eq!(
        (
            start["paths"].as_u64(),
            start["total_degree_paths"].as_u64()
        ),
        (Some(2), Some(4))
    );
    assert_eq!(value["summary"]["paths"], 2);
    assert_eq!(value["summary"]["nonsingular"], 2);
    let mut xs: Vec<f64> = value["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["coordinates"][0][0].as_f64().unwrap())
        .collect();
    xs.sort_by(f64::total_cmp);
    let r = 3f64.sqrt();
    assert!((xs[0] - (2.0 - r)).abs() < 1e-12 && (xs[1] - (2.0 + r)).abs() < 1e-12);

    // The default takes the polyhedral start system: mixed volume 2, half the total
    // degree 4.
    let out = singdist(&["solve", path, "--json"]);
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["start_system"]["name"], "polyhedral");
    assert_eq!(value["summary"]["paths"], 2);
    assert_eq!(value["summary"]["nonsingular"], 2);
    let out = singdist(&["solve", path, "--json", "--start", "total-degree"]);
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["start_system"]["name"], "total-degree");
    assert_eq!(value["summary"]["paths"], 4);
    assert_eq!(value["summary"]["nonsingular"], 2);

    let out = singdist(&["solve", path, "--threads", "1", "--start", "auto"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("start system  multi-homogeneous {x} {y}\nstart paths   2 (total degree 4)"),
        "{text}"
    );
    // Nothing beats the total degree 4 of the circle and the hyperbola.
    let file = write("ch4.input", CIRCLE_HYPERBOLA);
    let out = singdist(&["solve", file.to_str().unwrap(), "--start", "auto"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains(
            "start system  total-degree\nstart paths   4 (total degree 4, best multi-homogeneous 4)"
        ),
        "{text}"
    );
    // Polyhedral: the mixed volume of the triangles {xy, x, 1} and {xy, y, 1} is
    // area(P₁ + P₂) − area(P₁) − area(P₂) = 3 − 1/2 − 1/2 = 2 paths, both roots.
    let value = solve_json(&[path, "--start", "polyhedral"]);
    let start = &value["start_system"];
    assert_eq!(start["name"], "polyhedral");
    assert_eq!(
        (start["paths"].as_u64(), start["mixed_volume"].as_u64()),
        (Some(2), Some(2))
    );
    assert_eq!(value["summary"]["paths"], 2);
    assert_eq!(value["summary"]["nonsingular"], 2);
    assert_eq!(value["summary"]["failed"], 0);
    let out = singdist(&["solve", path, "--monodromy", "--start", "auto"]);
    assert!(!out.status.success(), "--monodromy and --start conflict");
}

/// `--start auto` takes the polyhedral start system where the mixed volume is at most
/// half of the best Bézout number (chemequ: 16 paths against a total degree of 108),
/// and keeps the total degree where it is not (katsura-6: mixed volume 64 = 2⁶).
#[test]
fn automatic_start_takes_the_polyhedral_system_where_it_halves_the_paths() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/demo_systems");
    let value = solve_json(&[&format!("{dir}/chemequ.input"), "--start", "auto"]);
    assert_eq!(value["start_system"]["name"], "polyhedral");
    assert_eq!(value["start_system"]["mixed_volume"], 16);
    assert_eq!(value["summary"]["paths"], 16);
    assert_eq!(value["summary"]["nonsingular"], 16);
    assert_eq!(value["summary"]["failed"], 0);
    let value = solve_json(&[&format!("{dir}/katsura6.input"), "--start", "auto"]);
    assert_eq!(value["start_system"]["name"], "total-degree");
    assert_eq!(value["summary"]["nonsingular"], 64);
}

/// PHCpack's `comb3000` unscaled (`--scaling never`; total degree 96, mixed volume
/// 16; coordinates down to 10⁻¹¹): the default start takes the polyhedral system,
/// whose paths run into what look like singular roots and 8–12 of them fail (their
/// stalled endgames do not settle there: equilibrated, the Jacobian is well
/// conditioned, 7.5–7·10⁷, so these are nonsingular roots, not singular points); the
/// total-degree run, which accounts for all 96 paths, is reported instead, with the
/// polyhedral run named as superseded.
#[test]
fn default_start_falls_back_to_the_total_degree_where_polyhedral_paths_fail() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/demo_systems");
    let file = format!("{dir}/comb3000.input");
    let value = solve_json(&[&file, "--threads", "1", "--scaling", "never"]);
    let start = &value["start_system"];
    assert_eq!(start["name"], "total-degree", "{start}");
    assert_eq!(start["superseded"]["name"], "polyhedral", "{start}");
    assert_eq!(start["superseded"]["paths"], 16, "{start}");
    assert!(start["superseded"]["failed"].as_u64() > Some(0), "{start}");
    assert_eq!(value["summary"]["paths"], 96);
    assert_eq!(value["summary"]["failed"], 0);
    // Asked for, the polyhedral run is reported as it is, failures included (exit 3).
    let out = singdist(&[
        "solve",
        &file,
        "--start",
        "polyhedral",
        "--scaling",
        "never",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(3));
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["start_system"]["name"], "polyhedral");
    assert!(value["start_system"].get("superseded").is_none());
}

/// PHCpack's `cassou` (mixed volume 24, 10 nonsingular roots): at seed 19 the
/// polyhedral run loses two paths (they diverge before the endgame; it still finds
/// the 10 roots); the default start then solves again from a fresh random lifting,
/// which loses none, instead of running the 1,344 total-degree paths, and names the
/// first run as superseded.
#[test]
fn a_polyhedral_run_that_lost_a_path_is_run_again_from_a_fresh_lifting() {
    let file = demo_file("cassou");
    let value = solve_json(&[&file, "--threads", "1", "--seed", "19"]);
    let start = &value["start_system"];
    assert_eq!(start["name"], "polyhedral", "{start}");
    assert_eq!(start["superseded"]["name"], "polyhedral", "{start}");
    assert!(start["superseded"]["failed"].as_u64() > Some(0), "{start}");
    let summary = &value["summary"];
    assert_eq!(summary["paths"], 24, "{summary}");
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["nonsingular"], 10, "{summary}");
    // Asked for, the polyhedral run of that seed is reported as it is (exit 3).
    let (code, _) = polyhedral_json(&file, "19");
    assert_eq!(code, Some(3));
}

/// PHCpack's `cassou` at seed 1: two polyhedral paths to its singular roots fail in
/// affine space; tracked again from their start in a random projective chart, they
/// end at those singular roots (3 roots, 6 paths), and the run is complete without a
/// second lifting (`recovered_in_chart` counts them; without that route they stay
/// failed, out of steps, and the run exits with code 3).
#[test]
fn failed_paths_tracked_in_a_projective_chart_reach_their_singular_roots() {
    let file = demo_file("cassou");
    let (code, value) = polyhedral_json(&file, "1");
    assert_eq!(code, Some(0));
    let summary = &value["summary"];
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["recovered_in_chart"], 2, "{summary}");
    assert_eq!(summary["nonsingular"], 10, "{summary}");
    assert_eq!(summary["singular"], 3, "{summary}");
    assert_eq!(summary["singular_paths"], 6, "{summary}");
    assert_eq!(summary["at_infinity"], 8, "{summary}");
}

/// PHCpack's `des22_24` (mixed volume 42): the random start system of the polyhedral
/// homotopy has roots of norm 3·10⁴, and at seeds 2 and 13 second-stage paths pass
/// norms of 10⁸ before `t = 0.03`, where the affine tracker stops
/// (`DivergedBeforeEndgame`). In a projective chart they stay finite and reach the
/// system's roots: all 41 nonsingular roots and the singular one, no path failed.
#[test]
fn second_stage_paths_that_run_far_out_are_followed_in_a_projective_chart() {
    let file = demo_file("des22_24");
    for seed in ["2", "13"] {
        let (code, value) = polyhedral_json(&file, seed);
        let summary = &value["summary"];
        assert_eq!(code, Some(0), "seed {seed}: {summary}");
        assert_eq!(summary["paths"], 42, "seed {seed}: {summary}");
        assert_eq!(summary["failed"], 0, "seed {seed}: {summary}");
        assert!(
            summary["recovered_in_chart"].as_u64() > Some(0),
            "seed {seed}: {summary}"
        );
        assert_eq!(summary["nonsingular"], 41, "seed {seed}: {summary}");
        assert_eq!(summary["singular"], 1, "seed {seed}: {summary}");
    }
}

/// PHCpack's `cassou` at the default seed: two roots of the random-coefficient start
/// system differ only in the sign of a coordinate of size 3·10⁻³ while another is
/// 2·10³, at condition 1.4·10⁹. Their Newton limits are accurate to 10⁻¹³, but the
/// same-root test allowed `10·κ·ε` relative to the largest coordinate (8·10⁻³) and
/// merged them: stage one reported a lost path and the run was repeated twice over
/// (three liftings, then a second polyhedral run). Now the first run is complete.
#[test]
fn start_roots_apart_in_a_small_coordinate_are_two_roots() {
    let value = solve_json(&[&demo_file("cassou"), "--threads", "1"]);
    let start = &value["start_system"];
    assert!(start.get("superseded").is_none(), "{start}");
    assert_eq!(value["summary"]["failed"], 0, "{value}");
    assert_eq!(value["summary"]["nonsingular"], 10, "{value}");
}

/// PHCpack's `fourbar` (96 polyhedral paths, 36 nonsingular roots): paths that end on
/// its positive-dimensional solution sets close their Cauchy loops after one turn at
/// every radius while the estimate drifts along the set; two of them per run used to
/// fail when the step size reached the resolution of `t` near `s = 10⁻¹⁰`. They end
/// at their last estimate (singular: its Jacobian equilibrated has condition
/// 5·10¹¹–2·10¹²), and no path fails, for two seeds. (Seed 2 still loses three paths,
/// to path jumps: two paths reaching one nonsingular root.)
#[test]
fn paths_to_a_positive_dimensional_set_settle_at_their_last_estimate() {
    let file = demo_file("fourbar");
    for seed in ["1", "24301"] {
        let value = solve_json(&[&file, "--start", "polyhedral", "--seed", seed]);
        let summary = &value["summary"];
        assert_eq!(summary["failed"], 0, "seed {seed}: {summary}");
        assert_eq!(summary["nonsingular"], 36, "seed {seed}: {summary}");
    }
}

/// PHCpack's `stewgou40` (a Stewart–Gough platform with 40 real postures): the
/// default start takes the polyhedral system (1,536 paths against a total degree of
/// 4,096). One root, of condition 4·10⁵, ended its path labelled singular and
/// Newton's corrections stalled at 1.01·10⁻¹³ relative, just above the promotion's
/// tolerance: it is nonsingular, and all 40 roots are reported so.
#[test]
fn a_root_whose_newton_corrections_stall_at_rounding_level_is_nonsingular() {
    let value = solve_json(&[&demo_file("stewgou40"), "--threads", "2"]);
    assert_eq!(value["start_system"]["name"], "polyhedral");
    let summary = &value["summary"];
    assert_eq!(summary["nonsingular"], 40, "{summary}");
    assert_eq!(summary["singular"], 0, "{summary}");
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["real"], 40, "{summary}");
}

/// PHCpack's `rbpl24` (a parallel robot, 40 roots of which 24 real): its equations'
/// sizes range from 6·10⁴ to 10¹⁴ while the coefficients within each equation are
/// well balanced, so the least-squares scaling is not worth a change of coordinates.
/// Unnormalised, the large equations dominate the homotopy from `t ≈ 0` and every
/// path fails there (`--scaling never`, exit 3); the
/// default normalises the equations alone and finds all 40, every one verified.
#[test]
fn equations_of_very_different_sizes_are_normalised() {
    let file = demo_file("rbpl24");
    let value = solve_json(&[&file, "--threads", "2"]);
    let scaling = &value["scaling"];
    assert!(
        scaling["variable_exponents"]
            .as_array()
            .unwrap()
            .iter()
            .all(|d| d == 0),
        "{scaling}"
    );
    let summary = &value["summary"];
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["nonsingular"], 40, "{summary}");
    assert_eq!(summary["real"], 24, "{summary}");
    let out = singdist(&["solve", &file, "--scaling", "never", "--json"]);
    assert_eq!(out.status.code(), Some(3));
    let value: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(value["summary"]["nonsingular"], 0, "{}", value["summary"]);
}

/// The distinct nonsingular roots of a `solve --json` output, checked in the scaled
/// coordinates the output names (`y_j = 2^{−d_j} x_j`): each a nonsingular root of
/// the scaled system (Newton's method converging, residual below `1e-9` of the largest
/// monomial's size), and no two within `1e-6` of each other there. Returns their number.
fn verified_distinct_roots(file: &str, value: &serde_json::Value) -> usize {
    use singdist::C64;
    use singdist::homotopy::newton_refine;
    use singdist::system::bertini;
    use singdist::system::scaling::Scaling;
    let system = bertini::read(&std::fs::read_to_string(file).unwrap()).unwrap();
    let exponents: Vec<i32> = value["scaling"]["variable_exponents"]
        .as_array()
        .expect("a scaled run")
        .iter()
        .map(|d| d.as_i64().unwrap() as i32)
        .collect();
    let scaling = Scaling::least_squares(&system).unwrap();
    // The output's exponents are the least-squares ones, the system scaled by them.
    assert_eq!(scaling.variables, exponents);
    let scaled = scaling.apply(&system).compile();
    let degree = system.degrees().into_iter().max().unwrap() as i32;
    let mut roots: Vec<Vec<C64>> = Vec::new();
    for solution in value["solutions"].as_array().unwrap() {
        if solution["status"] != "nonsingular" {
            continue;
        }
        let x: Vec<C64> = solution["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|z| C64::new(z[0].as_f64().unwrap(), z[1].as_f64().unwrap()))
            .collect();
        let refined = newton_refine(&scaled, &scaling.scale(&x), &[], 1e-13, 20);
        assert!(refined.is_nonsingular(1e12), "{file}: {refined:?}");
        let y = refined.point.clone();
        let size = y.iter().fold(1.0f64, |m, v| m.max(v.norm()));
        // Relative to the largest monomial's size.
        assert!(
            refined.residual < 1e-9 * size.powi(degree),
            "{file}: {refined:?}"
        );
        let close = |r: &Vec<C64>| r.iter().zip(&y).all(|(a, b)| (a - b).norm() <= 1e-6 * size);
        assert!(!roots.iter().any(close), "{file}: a root twice");
        roots.push(y);
    }
    roots.len()
}

/// Badly scaled systems are solved in their least-squares scaling: `comb3000`
/// (Morgan's combustion model A, coordinates from 10⁻¹¹ to 10⁻⁵) has 16 nonsingular
/// roots, which the unscaled run above takes for singular ones; `pb601es` has 18
/// (the mixed volume), three of them about 10⁶ times larger in the scaled coordinates
/// than the others, which the endgame's norm cap sends to infinity and the random
/// projective chart recovers. Two seeds; every root verified and distinct.
#[test]
fn badly_scaled_systems_are_solved_completely_in_their_scaling() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/demo_systems");
    for (stem, roots) in [("comb3000", 16), ("pb601es", 18)] {
        let file = format!("{dir}/{stem}.input");
        for seed in ["1", "24301"] {
            let value = solve_json(&[&file, "--seed", seed]);
            let summary = &value["summary"];
            assert_eq!(summary["failed"], 0, "{stem} {seed}: {summary}");
            assert_eq!(summary["nonsingular"], roots, "{stem} {seed}: {summary}");
            assert_eq!(
                verified_distinct_roots(&file, &value),
                roots,
                "{stem} {seed}"
            );
        }
        // Unscaled, the same start system misses roots or fails paths.
        let unscaled = singdist(&["solve", &file, "--scaling", "never", "--json"]);
        let value: serde_json::Value = serde_json::from_slice(&unscaled.stdout).unwrap();
        assert!(
            value["summary"]["nonsingular"].as_u64() < Some(roots as u64),
            "{stem}: {}",
            value["summary"]
        );
    }
}

/// PHCpack's `des22_24`: its mixed cells take 34,000–46,000 LP tests over seeds,
/// within the default start's budget for 256 total-degree paths (20,000 + 100 per
/// path), so the default tracks its 42 polyhedral paths: 41 nonsingular roots and
/// the singular one, no failed path, for two seeds.
#[test]
fn the_default_start_of_des22_24_is_its_polyhedral_one() {
    for (seed, value) in solved_completely(&demo_file("des22_24"), &["24301", "7"], 41) {
        let start = &value["start_system"];
        assert_eq!(start["name"], "polyhedral", "{seed}: {start}");
        assert_eq!(start["paths"], 42, "{seed}: {start}");
        assert_eq!(
            value["summary"]["singular"], 1,
            "{seed}: {}",
            value["summary"]
        );
    }
}

/// PHCpack's `cohn3` at seed 1 (mixed volume 269, 130 nonsingular roots): two
/// polyhedral paths fail in affine space. Tracked from their start in random
/// projective charts they end at infinity in two charts each (`at_infinity_in_charts`),
/// so no path is failed and every root is found; one chart alone would not be enough
/// evidence (a chart route can stray). (`reimer5`'s 8 such paths at two seeds now reach
/// infinity in affine space, their residuals evaluated in extended precision.)
#[test]
fn failed_paths_at_infinity_in_two_charts_are_at_infinity() {
    let file = demo_file("cohn3");
    for (seed, value) in solved_completely(&file, &["1"], 130) {
        let summary = &value["summary"];
        assert!(
            summary["at_infinity_in_charts"].as_u64() > Some(0),
            "{seed}: {summary}"
        );
    }
    // The text summary says where those paths were settled.
    let out = singdist(&["solve", &file, "--threads", "2", "--seed", "1"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.lines()
            .any(|l| l.starts_with("charts") && l.contains("ended at infinity in two")),
        "{text}"
    );
}

/// PHCpack's `discret3s` at seed 7: Cauchy loops whose radius enclosed two nearby
/// nonsingular roots closed after two turns at the roots' mean (residual 4.5·10⁻⁶
/// relative), which was reported as a double root reached by two paths, twice, with
/// no failed path and roots missing. No singular endpoint of winding number 2 or more
/// may now have a residual above 10⁻⁸ relative to `1 + ‖x‖∞`, and all 128 roots are
/// found.
#[test]
fn a_loop_around_two_roots_is_not_a_double_root() {
    let value = solve_json(&[&demo_file("discret3s"), "--seed", "7", "--threads", "2"]);
    for solution in value["solutions"].as_array().unwrap() {
        if solution["status"] != "singular" || solution["winding_number"].as_u64() < Some(2) {
            continue;
        }
        let size = solution["coordinates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|z| z[0].as_f64().unwrap().hypot(z[1].as_f64().unwrap()))
            .fold(1.0f64, |m, v| m.max(1.0 + v));
        let residual = solution["residual"].as_f64().unwrap();
        assert!(residual <= 1e-8 * size, "{solution}");
    }
    assert_eq!(value["summary"]["nonsingular"], 128, "{}", value["summary"]);
}

/// Moderately badly scaled: PHCpack's `cohn2` (coefficients from 1 to 3·10⁶, a
/// spread of 2^5.7 on average that the least-squares scaling brings to 2^1.3) is
/// solved in its scaling by default, with its 18 nonsingular roots verified and
/// distinct and no failed path, for two seeds.
#[test]
fn a_moderately_badly_scaled_system_is_solved_in_its_scaling() {
    let file = demo_file("cohn2");
    for (seed, value) in solved_completely(&file, &["1", "24301"], 18) {
        let exponents = &value["scaling"]["variable_exponents"];
        assert!(
            exponents.as_array().unwrap().iter().any(|d| d != 0),
            "{seed}: {exponents}"
        );
        assert_eq!(verified_distinct_roots(&file, &value), 18, "{seed}");
    }
}

/// PHCpack's `pb601` as distributed (coefficients from 1 to 10¹⁶): three of its 18
/// roots (modulus 26 against 10⁻³ for the rest) lie beyond the endgame's norm cap,
/// and their paths are re-tracked in random projective charts. At the default seed the
/// first chart sends two paths to one root, and at seed 17 to a root already known
/// (17 roots with a warning before); further charts for the paths left unconfirmed
/// find the 18th root at every seed, each root verified and distinct.
#[test]
fn roots_beyond_the_norm_cap_are_found_in_further_charts() {
    let file = demo_file("pb601");
    for seed in ["24301", "17", "1"] {
        let value = solve_json(&[&file, "--seed", seed, "--threads", "1"]);
        let summary = &value["summary"];
        assert_eq!(summary["nonsingular"], 18, "seed {seed}: {summary}");
        assert_eq!(summary["failed"], 0, "seed {seed}: {summary}");
        assert_eq!(
            summary["unconfirmed_at_infinity"], 0,
            "seed {seed}: {summary}"
        );
        assert_eq!(verified_distinct_roots(&file, &value), 18, "seed {seed}");
    }
}

/// PHCpack's `butcher8`: 15 of its 24 polyhedral paths go to infinity, and the
/// endgame's norm cap classifies 4 of them there without evidence from their
/// valuations. Re-tracked in a random projective chart, each reaches the hyperplane at
/// infinity (its homogenising coordinate of 10⁻⁹–10⁻¹⁰ at `t ≈ 1 − 10⁻⁴` after 400
/// steps, the former budget, which left 3 of them unconfirmed with a warning): all
/// confirmed, and the 5 roots reported.
#[test]
fn paths_at_infinity_by_the_norm_cap_are_confirmed_in_a_projective_chart() {
    let value = solve_json(&[&demo_file("butcher8"), "--threads", "1"]);
    let summary = &value["summary"];
    assert_eq!(summary["nonsingular"], 5, "{summary}");
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["rechecked_at_infinity"], 4, "{summary}");
    assert_eq!(summary["unconfirmed_at_infinity"], 0, "{summary}");
}

/// PHCpack's `fbrfive4` (four-bar linkage through five points): 36 nonsingular roots
/// among 56 polyhedral paths, the others ending at singular points where Cauchy loops
/// do not close (10,000–18,000 steps a path, and 3 failed paths, before the endgame
/// settled on the direct finish's singular endpoint). Every root found, no path
/// failed, and no path takes more than 5,000 steps.
#[test]
fn paths_to_singular_points_settle_without_failing() {
    let file = demo_file("fbrfive4");
    for seed in ["1", "24301"] {
        let value = solve_json(&[&file, "--seed", seed, "--threads", "2"]);
        let summary = &value["summary"];
        assert_eq!(summary["failed"], 0, "seed {seed}: {summary}");
        assert_eq!(summary["nonsingular"], 36, "seed {seed}: {summary}");
        let longest = value["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["steps"].as_u64().unwrap())
            .max()
            .unwrap();
        assert!(longest < 5_000, "seed {seed}: a path took {longest} steps");
    }
}

/// PHCpack's `redcyc7` (reduced cyclic 7-roots): 132 nonsingular roots among 228
/// polyhedral paths, most others ending at singular roots of winding numbers 5 and 10.
/// At the first endgame radius the Cauchy loops of some paths enclose more than their
/// own branch point and do not close within the winding bound; a path left where such
/// a loop stopped went on along another path's sheet and ended on a root that path
/// reached too (7 paths lost as jumped, and a 3.5 s total-degree fallback). Every root
/// is found by the polyhedral run and no path fails.
#[test]
fn a_loop_that_does_not_close_leaves_no_path_on_another_sheet() {
    let value = solve_json(&[&demo_file("redcyc7"), "--threads", "2"]);
    let summary = &value["summary"];
    assert_eq!(summary["failed"], 0, "{summary}");
    assert_eq!(summary["nonsingular"], 132, "{summary}");
    assert_eq!(value["start_system"]["name"], "polyhedral", "{value}");
}

/// `singdist solve ARGS --json`, which must succeed, as parsed JSON.
fn solve_json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["solve"];
    all.extend_from_slice(args);
    all.push("--json");
    let out = singdist(&all);
    assert_success(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// `solve --start polyhedral --seed SEED --threads 1 --json` of `file`: the exit code
/// and the output.
fn polyhedral_json(file: &str, seed: &str) -> (Option<i32>, serde_json::Value) {
    let out = singdist(&[
        "solve",
        file,
        "--start",
        "polyhedral",
        "--seed",
        seed,
        "--threads",
        "1",
        "--json",
    ]);
    let value = serde_json::from_slice(&out.stdout).unwrap();
    (out.status.code(), value)
}

/// `solve --json --seed SEED --threads 2` of `file` for each of `seeds`, each checked
/// complete (no failed path) with `roots` nonsingular roots; the outputs, seed first.
fn solved_completely(
    file: &str,
    seeds: &[&'static str],
    roots: u64,
) -> Vec<(&'static str, serde_json::Value)> {
    seeds
        .iter()
        .map(|&seed| {
            let value = solve_json(&[file, "--seed", seed, "--threads", "2"]);
            let summary = &value["summary"];
            assert_eq!(summary["failed"], 0, "{file}, seed {seed}: {summary}");
            assert_eq!(
                summary["nonsingular"], roots,
                "{file}, seed {seed}: {summary}"
            );
            (seed, value)
        })
        .collect()
}

/// The default start system on the committed demo systems (verified counts of distinct
/// nonsingular roots, see `homotopy_demo_suite.rs`), for two seeds: no failed path,
/// every root once, whichever start system the default takes.
#[test]
fn default_start_solves_the_demo_systems_completely_for_two_seeds() {
    // eco8 too: its total-degree homotopy loses paths, the polyhedral one does not.
    let systems = SYSTEMS.iter().copied().chain([("eco8", 64)]);
    for (stem, roots) in systems {
        let file = demo_file(stem);
        for seed in ["24301", "7"] {
            let value = solve_json(&[&file, "--seed", seed, "--threads", "2"]);
            let summary = &value["summary"];
            let start = &value["start_system"]["name"];
            assert_eq!(
                summary["failed"], 0,
                "{stem}, seed {seed}, {start}: {summary}"
            );
            assert_eq!(
                summary["nonsingular"], roots,
                "{stem}, seed {seed}, {start}: {summary}"
            );
        }
    }
}
