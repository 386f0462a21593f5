//! `singdist system show` and `singdist system export`.

use std::process::Command;

fn singdist(args: &[&str]) -> (bool, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_singdist"))
        .args(args)
        .output()
        .expect("run singdist");
    (
        output.status.success(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn show_and_export_a_bertini_file() {
    let dir = std::env::temp_dir().join(format!("singdist_system_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("circle.input");
    std::fs::write(
        &input,
        "INPUT\nvariable_group x, y;\nparameter r;\nfunction f, g;\nf = x^2 + y^2 - r;\ng = x*y^2 - 1;\nEND;\n",
    )
    .unwrap();
    let path = input.to_str().unwrap();

    let (ok, stdout, _) = singdist(&["system", "show", path]);
    assert!(ok);
    assert!(stdout.contains("variables (2): x, y"), "{stdout}");
    assert!(stdout.contains("parameters (1): r"), "{stdout}");
    assert!(stdout.contains("degrees: 2, 3"), "{stdout}");
    assert!(stdout.contains("Bézout number: 6"), "{stdout}");

    let out = dir.join("circle.phc");
    let (ok, _, stderr) = singdist(&[
        "system",
        "export",
        path,
        "--to",
        "phc",
        "--set",
        "r=4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let phc = std::fs::read_to_string(&out).unwrap();
    assert_eq!(phc, "2\n1.0*x^2 + 1.0*y^2 - 4.0;\n1.0*x*y^2 - 1.0;\n");

    let (ok, _, stderr) = singdist(&["system", "export", path, "--to", "phc"]);
    assert!(!ok);
    assert!(stderr.contains("parameter `r`"), "{stderr}");

    let (ok, stdout, _) = singdist(&["system", "export", path, "--to", "bertini"]);
    assert!(ok);
    assert!(stdout.contains("parameter r;"), "{stdout}");

    std::fs::write(
        &input,
        "INPUT\nvariable_group x;\nfunction f;\nf = x + q;\nEND;\n",
    )
    .unwrap();
    let (ok, _, stderr) = singdist(&["system", "show", path]);
    assert!(!ok);
    assert!(
        stderr.contains("line 4, column 9: unknown symbol `q`"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
