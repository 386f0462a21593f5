//! Bertini input: reading, writing, round trips and error positions.

mod system_support;

use proptest::prelude::*;
use singdist::C64;
use singdist::random::seeded;
use singdist::system::{Expr, ParseErrorKind, System, bertini};
use system_support::*;

fn assert_same_values(a: &System, b: &System, seed: u64) {
    assert_eq!(a.variables(), b.variables());
    assert_eq!(a.parameters(), b.parameters());
    assert_eq!(a.num_equations(), b.num_equations());
    let mut rng = seeded(seed);
    for _ in 0..5 {
        let x = random_point(&mut rng, a.variables().len());
        let p = random_point(&mut rng, a.parameters().len());
        let error = relative_error(&b.evaluate_naive(&x, &p), &a.evaluate_naive(&x, &p));
        assert!(error < 1e-13, "round trip changed the values: {error:e}");
    }
}

#[test]
fn reads_a_documented_example() {
    let text = "% a comment
CONFIG
  TrackType: 0;   % anything goes here
  MPType: 2;
END;
INPUT
  variable_group x, y;
  parameter p;
  constant c;
  function f1, f2;
  c = 1.5e-1 + 2*I;
  s = x^2 - p;          % a subfunction
  f1 = s*s + c*y;
  f2 = -x^3 + y/2 - 1;
END;
";
    let system = bertini::read(text).expect("valid file");
    assert_eq!(system.variables(), ["x", "y"]);
    assert_eq!(system.parameters(), ["p"]);
    assert_eq!(system.degrees(), vec![4, 3]);
    assert_eq!(system.bezout_number(), 12);
    let (x, y, p) = (C64::new(0.3, -1.2), C64::new(2.0, 0.5), C64::new(-0.7, 0.1));
    let c = C64::new(0.15, 2.0);
    let f = system.evaluate_naive(&[x, y], &[p]);
    let expected = [
        (x * x - p) * (x * x - p) + c * y,
        -x * x * x + y / 2.0 - 1.0,
    ];
    assert!(relative_error(&f, &expected) < 1e-15);
}

#[test]
fn round_trip_of_random_systems() {
    let mut rng = seeded(41);
    let variables: Vec<String> = (0..3).map(|i| format!("x{i}")).collect();
    let parameters: Vec<String> = vec!["q".to_string()];
    let symbols: Vec<String> = variables.iter().chain(&parameters).cloned().collect();
    for trial in 0..30 {
        let shared = random_expression(&mut rng, &symbols, 3);
        let equations: Vec<Expr> = (0..3)
            .map(|_| random_expression(&mut rng, &symbols, 4) * &shared - &shared)
            .collect();
        let system = System::new(&variables, &parameters, equations).unwrap();
        let text = bertini::write(&system).unwrap();
        let back = bertini::read(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_same_values(&system, &back, 300 + trial);
        // The shared factor is written once, as a subfunction.
        assert!(
            text.contains("s0 = ")
                || shared.as_constant().is_some()
                || shared.as_symbol().is_some()
        );
    }
}

#[test]
fn round_trip_of_the_plate_plate_lagrange_system() {
    let system = plate_plate_system();
    let text = bertini::write(&system).unwrap();
    let back = bertini::read(&text).unwrap();
    assert_same_values(&system, &back, 9);
    assert_eq!(back.degrees(), system.degrees());
    // 12 gradient equations of D² − λS have degree 4 (λ times cubic), ∂/∂λ gives −S.
    assert_eq!(system.degrees(), [vec![4; 12], vec![4]].concat());
}

fn error_of(text: &str) -> (usize, usize, ParseErrorKind) {
    match bertini::read(text) {
        Ok(_) => panic!("should fail:\n{text}"),
        Err(e) => {
            // The message names the position.
            let message = e.to_string();
            assert!(message.starts_with(&format!("line {}, column {}", e.line, e.column)));
            (e.line, e.column, e.kind)
        }
    }
}

#[test]
fn unknown_symbol_is_reported_at_its_position() {
    let (line, column, kind) =
        error_of("INPUT\nvariable_group x;\nfunction f;\nf = x + zz*2;\nEND;\n");
    assert_eq!((line, column), (4, 9));
    assert_eq!(kind, ParseErrorKind::UnknownSymbol("zz".into()));
}

#[test]
fn missing_semicolon_is_reported_after_the_statement() {
    let (line, column, kind) =
        error_of("INPUT\nvariable_group x, y;\nfunction f, g;\nf = x + y\ng = x;\nEND;\n");
    assert_eq!((line, column), (4, 10));
    assert!(matches!(kind, ParseErrorKind::MissingSemicolon(_)));
    let (line, _, kind) = error_of("INPUT\nvariable_group x\nfunction f;\nf = x;\nEND;\n");
    assert_eq!(line, 2);
    assert!(matches!(kind, ParseErrorKind::MissingSemicolon(_)));
}

#[test]
fn non_integer_exponent_is_rejected() {
    for (text, column) in [
        (
            "INPUT\nvariable_group x;\nfunction f;\nf = x^2.5;\nEND;\n",
            7,
        ),
        (
            "INPUT\nvariable_group x;\nfunction f;\nf = x^-1;\nEND;\n",
            7,
        ),
        ("INPUT\nvariable_group x;\nfunction f;\nf = x^x;\nEND;\n", 7),
    ] {
        let (line, col, kind) = error_of(text);
        assert_eq!((line, col), (4, column), "{text}");
        assert!(
            matches!(kind, ParseErrorKind::NonIntegerExponent(_)),
            "{kind:?}"
        );
    }
    // Integral exponents, also written 2.0 or (3), are fine.
    let system = bertini::read("variable_group x;\nfunction f;\nf = x^2.0*x^(3);\n").unwrap();
    assert_eq!(system.degrees(), vec![5]);
}

#[test]
fn empty_system_and_undefined_function_are_errors() {
    let (line, _, kind) = error_of("INPUT\nvariable_group x;\nEND;\n");
    assert_eq!(line, 3);
    assert_eq!(kind, ParseErrorKind::EmptySystem);
    let (line, column, kind) = error_of("INPUT\nvariable_group x;\nfunction f, g;\nf = x;\nEND;\n");
    assert_eq!((line, column), (3, 13));
    assert_eq!(
        kind,
        ParseErrorKind::Undefined {
            what: "function",
            name: "g".into()
        }
    );
    let (_, _, kind) = error_of("");
    assert_eq!(kind, ParseErrorKind::EmptySystem);
}

#[test]
fn other_malformed_inputs_are_errors() {
    for text in [
        "INPUT\nvariable_group x;\nfunction f;\nf = sin(x);\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = x/x;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = x;\nf = x;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nx = 2;\nEND;\n",
        "INPUT\nvariable_group x, x;\nfunction f;\nf = x;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = (x + 1;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = x $ 2;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = x;\n",
        "CONFIG\nMPType: 2;\n",
        "INPUT\nvariable_group x;\nconstant c;\nfunction f;\nc = x;\nf = c;\nEND;\n",
        "INPUT\nvariable_group x;\nparameter p;\nfunction f;\np = 2;\nf = x;\nEND;\n",
        "INPUT\nvariable_group x;\nfunction f;\nf = 1.2.3*x;\nEND;\n",
        "INPUT\nfunction f;\nf = 2;\nEND;\n",
    ] {
        let (line, column, _) = error_of(text);
        assert!(line >= 1 && column >= 1);
    }
    let deep = format!(
        "variable_group x;\nfunction f;\nf = {}x{};\n",
        "(".repeat(5000),
        ")".repeat(5000)
    );
    assert_eq!(error_of(&deep).2, ParseErrorKind::TooDeeplyNested);
}

#[test]
fn constants_and_parameter_values_on_the_command_line() {
    assert_eq!(
        bertini::read_constant("0.5 + 2*I").unwrap(),
        C64::new(0.5, 2.0)
    );
    assert_eq!(
        bertini::read_constant("-3e-2").unwrap(),
        C64::new(-0.03, 0.0)
    );
    assert!(bertini::read_constant("x").is_err());
    assert!(bertini::read_constant("1 +").is_err());
}

const ALPHABET: &[&str] = &[
    "x",
    "y",
    "p",
    "f",
    "g",
    "c",
    "=",
    ";",
    ",",
    "+",
    "-",
    "*",
    "/",
    "^",
    "(",
    ")",
    "2",
    "1.5e-3",
    " ",
    "\n",
    "%",
    "I",
    "END",
    "INPUT",
    "CONFIG",
    "variable_group",
    "function",
    "parameter",
    "constant",
    ":",
    "$",
    "3.",
    ".",
    "e",
    "ß",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn random_garbage_never_panics(text in "\\PC{0,80}") {
        let _ = bertini::read(&text);
    }

    #[test]
    fn random_token_soup_never_panics(pieces in prop::collection::vec(0..ALPHABET.len(), 0..60)) {
        let body: String = pieces.iter().map(|&i| ALPHABET[i]).collect::<Vec<_>>().join(" ");
        let _ = bertini::read(&body);
        let text = format!("INPUT\nvariable_group x, y;\nparameter p;\nfunction f;\n{body}\nEND;\n");
        if let Err(e) = bertini::read(&text) {
            prop_assert!(e.line >= 1 && e.column >= 1);
        }
        let _ = singdist::system::phc::read(&body);
    }
}

#[test]
fn long_sums_and_products_are_read_without_deep_recursion() {
    // 30 000 terms: a left-deep tree would overflow the stack of the recursive walkers.
    let terms: Vec<String> = (0..30_000).map(|i| format!("{}*x", i % 7)).collect();
    let factors = vec!["x"; 2000].join("*");
    let text = format!(
        "variable_group x;\nfunction f, g;\nf = {} - 1;\ng = {factors};\n",
        terms.join(" + ")
    );
    let system = bertini::read(&text).unwrap();
    let coefficient: f64 = (0..30_000).map(|i| (i % 7) as f64).sum();
    let x = C64::from_polar(1.0, 0.3);
    let f = system.evaluate_naive(&[x], &[]);
    assert!((f[0] - (coefficient * x - 1.0)).norm() < 1e-9 * coefficient);
    assert!((f[1] - x.powu(2000)).norm() < 1e-12);
    assert_eq!(system.degrees(), vec![1, 2000]);
    let compiled = system.compile();
    let mut work = compiled.new_workspace();
    let mut out = vec![C64::new(0.0, 0.0); 2];
    let mut jac = vec![C64::new(0.0, 0.0); 2];
    use singdist::system::Evaluator;
    compiled.evaluate_with_jacobian(&[x], &[], &mut work, &mut out, &mut jac);
    assert!((jac[0] - coefficient).norm() < 1e-9 * coefficient);
    assert!((jac[1] - 2000.0 * x.powu(1999)).norm() < 1e-9 * jac[1].norm());
}
