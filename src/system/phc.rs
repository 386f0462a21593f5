//! PHCpack input files: expanded polynomials with numeric coefficients.
//!
//! Layout written: a first line with the number of equations (followed by the number
//! of unknowns when the system is not square), then one polynomial per equation, each
//! ended by `;`, terms `c*x^2*y` with `^` for powers and `i` for the imaginary unit.
//! PHCpack has no parameters: every parameter needs a value, substituted before the
//! expansion.

use crate::C64;
use crate::system::parse::{ParseError, ParseErrorKind, Resolved, Token, TokenCursor, tokenize};
use crate::system::sparse::ExpansionError;
use crate::system::{Expr, System, SystemError};
use std::cell::RefCell;

/// Errors of writing a system as PHCpack input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PhcWriteError {
    /// A parameter without a value, or a value for an unknown parameter.
    #[error("PHCpack input needs a numeric value for every parameter")]
    Parameters(#[from] SystemError),
    /// A variable name PHCpack cannot read.
    #[error(
        "the variable name `{0}` is not valid in PHCpack input (letters, digits and `_`, starting with a letter; not `i`, `I`, `e` or `E`)"
    )]
    InvalidName(String),
    /// The expansion is too large.
    #[error(transparent)]
    Expansion(#[from] ExpansionError),
    /// A NaN or infinite coefficient.
    #[error("the system contains a non-finite coefficient")]
    NonFiniteConstant,
}

fn is_valid_phc_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !["i", "I", "e", "E"].contains(&name)
}

fn format_real(v: f64) -> String {
    format!("{v:?}")
}

/// The signed coefficient text of a term: `(" + ", "2.5")`, `(" - ", "2.5")` or
/// `(" + ", "(1.0+2.0*i)")`.
fn coefficient_text(c: C64) -> (&'static str, String) {
    if c.im == 0.0 {
        if c.re.is_sign_negative() {
            (" - ", format_real(-c.re))
        } else {
            (" + ", format_real(c.re))
        }
    } else if c.re == 0.0 {
        if c.im.is_sign_negative() {
            (" - ", format!("{}*i", format_real(-c.im)))
        } else {
            (" + ", format!("{}*i", format_real(c.im)))
        }
    } else {
        let sign = if c.im.is_sign_negative() { "-" } else { "+" };
        (
            " + ",
            format!("({}{sign}{}*i)", format_real(c.re), format_real(c.im.abs())),
        )
    }
}

/// Writes `system` as PHCpack input; `parameter_values` gives a value to every
/// parameter (by name).
pub fn write(system: &System, parameter_values: &[(String, C64)]) -> Result<String, PhcWriteError> {
    let numeric = system.with_parameter_values(parameter_values)?;
    for name in numeric.variables() {
        if !is_valid_phc_name(name) {
            return Err(PhcWriteError::InvalidName(name.clone()));
        }
    }
    let polynomials = numeric.expand()?;
    let n = numeric.variables().len();
    let k = numeric.num_equations();
    let mut out = if k == n {
        format!("{k}\n")
    } else {
        format!("{k} {n}\n")
    };
    for polynomial in &polynomials {
        let mut line = String::new();
        let mut terms_on_line = 0;
        // Graded lexicographic order, highest degree first.
        let mut terms: Vec<(&Vec<u32>, &C64)> = polynomial.terms.iter().collect();
        terms.sort_by_key(|(m, _)| {
            std::cmp::Reverse((m.iter().map(|&e| e as u64).sum::<u64>(), (*m).clone()))
        });
        for (monomial, &c) in terms {
            if !(c.re.is_finite() && c.im.is_finite()) {
                return Err(PhcWriteError::NonFiniteConstant);
            }
            let (sign, coefficient) = coefficient_text(c);
            if line.is_empty() {
                line.push_str(if sign == " - " { "-" } else { "" });
            } else {
                line.push_str(sign);
            }
            line.push_str(&coefficient);
            for (name, &e) in numeric.variables().iter().zip(monomial) {
                match e {
                    0 => {}
                    1 => line.push_str(&format!("*{name}")),
                    e => line.push_str(&format!("*{name}^{e}")),
                }
            }
            terms_on_line += 1;
            if terms_on_line == 4 {
                line.push_str("\n ");
                terms_on_line = 0;
            }
        }
        if polynomial.terms.is_empty() {
            line.push('0');
        }
        out.push_str(line.trim_end());
        out.push_str(";\n");
    }
    Ok(out)
}

/// The counts line and the first `n` polynomials of PHCpack input (`n` from the counts
/// line): what PHCpack itself reads. Titles, root counts and the solution lists `phc`
/// appends to its input files come after them. The whole text when the counts line or
/// the `n` semicolons are missing (the parser then reports the error).
fn system_part(text: &str) -> &str {
    let start = text.len() - text.trim_start().len();
    let first_line = text[start..].lines().next().unwrap_or("");
    let Some(n) = first_line
        .split_whitespace()
        .next()
        .and_then(|w| w.parse::<usize>().ok())
    else {
        return text;
    };
    let mut end = start + first_line.len();
    for _ in 0..n {
        match text[end..].find(';') {
            Some(k) => end += k + 1,
            None => return text,
        }
    }
    &text[..end]
}

/// Reads PHCpack input text: the counts line, then the polynomials separated by `;`;
/// text after the last polynomial (a title, a solution list) is ignored, as PHCpack
/// does. The unknowns are the names in order of first appearance; `i` and `I` are the
/// imaginary unit.
pub fn read(text: &str) -> Result<System, ParseError> {
    let mut cursor = TokenCursor::new(tokenize(system_part(text))?);
    let count = |cursor: &mut TokenCursor| -> Result<Option<usize>, ParseError> {
        match cursor.peek().token {
            Token::Number(v, _) if v.fract() == 0.0 && (0.0..1e9).contains(&v) => {
                cursor.advance();
                Ok(Some(v as usize))
            }
            _ => Ok(None),
        }
    };
    let equations_count =
        count(&mut cursor)?.ok_or_else(|| cursor.unexpected("the number of equations"))?;
    let first_line = cursor.tokens.first().map(|t| t.line).unwrap_or(1);
    let variables_count = if cursor.peek().line == first_line {
        count(&mut cursor)?
    } else {
        None
    };
    let names: RefCell<Vec<String>> = RefCell::new(Vec::new());
    let resolve = |name: &str| -> Resolved {
        if name == "i" || name == "I" {
            return Resolved::Value(Expr::constant(C64::new(0.0, 1.0)));
        }
        let mut names = names.borrow_mut();
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
        Resolved::Value(Expr::variable(name))
    };
    let mut equations = Vec::new();
    for _ in 0..equations_count {
        equations.push(cursor.expression(&resolve)?);
        cursor.expect_semicolon()?;
    }
    if cursor.peek().token != Token::EndOfInput {
        return Err(cursor.unexpected("end of input after the polynomials"));
    }
    let names = names.into_inner();
    let at_end = |kind: ParseErrorKind| cursor.error_here(kind);
    if let Some(n) = variables_count
        && names.len() > n
    {
        return Err(at_end(ParseErrorKind::InvalidSystem(format!(
            "{} unknowns appear but the header declares {n}",
            names.len()
        ))));
    }
    System::new(&names, [""; 0], equations).map_err(|error| match error {
        SystemError::EmptySystem => at_end(ParseErrorKind::EmptySystem),
        other => at_end(ParseErrorKind::InvalidSystem(other.to_string())),
    })
}

/// Whether PHCpack's `phc` runs here (on `PATH`): cross-checks and side-by-side
/// timings skip cleanly without it (`apt-get install phcpack` provides it).
pub fn available() -> bool {
    std::process::Command::new("phc")
        .arg("--version")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok()
}

/// One solution of a PHCpack solution list: the coordinates by name, in the order
/// listed, and the closing diagnostics line (`== err : … = rco : … = res : … ==`).
#[derive(Clone, Debug, PartialEq)]
pub struct PhcSolution {
    /// `(name, value)` per unknown.
    pub values: Vec<(String, C64)>,
    /// The closing line, as PHCpack wrote it.
    pub closing: String,
}

impl PhcSolution {
    /// A diagnostic of the closing line by its label: `err` (last Newton correction),
    /// `rco` (estimated inverse condition number) or `res` (residual).
    pub fn diagnostic(&self, label: &str) -> Option<f64> {
        self.closing
            .split(&format!("{label} :"))
            .nth(1)?
            .split_whitespace()
            .next()?
            .parse()
            .ok()
    }

    /// The value of unknown `name`.
    pub fn value(&self, name: &str) -> Option<C64> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }
}

/// The solutions of the last `THE SOLUTIONS` list in a PHCpack file (`phc -b` appends
/// its final list to the input file; `phc -p` ends its output file with the list at
/// the target parameters). Each solution block runs from `the solution for t :` to its
/// closing line; lines `name : re im` give the coordinates.
pub fn read_last_solutions(text: &str) -> Vec<PhcSolution> {
    let Some(start) = text.rfind("THE SOLUTIONS") else {
        return Vec::new();
    };
    text[start..]
        .split("the solution for t :")
        .skip(1)
        .filter_map(|block| {
            let mut values = Vec::new();
            for line in block.lines().map(str::trim) {
                if line.starts_with("==") {
                    return Some(PhcSolution {
                        values,
                        closing: line.to_string(),
                    });
                }
                let Some((name, numbers)) = line.split_once(':') else {
                    continue;
                };
                let parts: Option<Vec<f64>> =
                    numbers.split_whitespace().map(|v| v.parse().ok()).collect();
                if let Some([re, im]) = parts.as_deref() {
                    values.push((name.trim().to_string(), C64::new(*re, *im)));
                }
            }
            None
        })
        .collect()
}

/// A PHCpack solution list (start solutions for `phc -p`): `count dimension`, a
/// banner, then per solution `t : 0 0`, `m : 1`, one `name : re im` line per unknown in
/// the order of `names` (PHCpack reads them by position: give them in the order of its
/// symbol table, i.e. of first appearance in the system file, as [`read`] numbers the
/// unknowns) and a closing line.
pub fn write_solutions(names: &[String], solutions: &[Vec<C64>]) -> String {
    use std::fmt::Write as _;
    let mut out = format!("{} {}\n{}\n", solutions.len(), names.len(), "=".repeat(59));
    for (i, x) in solutions.iter().enumerate() {
        let _ = writeln!(
            out,
            "solution {} :\nt :  0.0E+00   0.0E+00\nm : 1\nthe solution for t :",
            i + 1
        );
        for (name, v) in names.iter().zip(x) {
            let _ = writeln!(out, " {name} : {:.16E} {:.16E}", v.re, v.im);
        }
        out.push_str("== err :  0.000E+00 = rco :  1.000E+00 = res :  0.000E+00 ==\n");
    }
    out
}

#[cfg(test)]
mod solution_list_tests {
    use super::*;

    /// A written solution list reads back exactly (values to the last bit, the
    /// diagnostics of the closing line), after a `THE SOLUTIONS` heading.
    #[test]
    fn solution_lists_round_trip() {
        let names = vec!["x".to_string(), "lambda".to_string()];
        let solutions = vec![
            vec![C64::new(1.0 / 3.0, -2.5e-17), C64::new(-7.25e8, 0.1)],
            vec![C64::new(f64::MIN_POSITIVE, 1.0), C64::new(0.0, -0.0)],
        ];
        let text = format!(
            "2\nx;\nlambda;\n\nTHE SOLUTIONS :\n{}",
            write_solutions(&names, &solutions)
        );
        let read = read_last_solutions(&text);
        assert_eq!(read.len(), 2);
        for (s, x) in read.iter().zip(&solutions) {
            assert_eq!(s.value("x"), Some(x[0]));
            assert_eq!(s.value("lambda"), Some(x[1]));
            assert_eq!(s.value("y"), None);
            assert_eq!(s.diagnostic("rco"), Some(1.0));
            assert_eq!(s.diagnostic("res"), Some(0.0));
        }
        assert!(read_last_solutions("no list here").is_empty());
    }
}
