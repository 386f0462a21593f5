//! Bertini input files (subset): reading and writing.
//!
//! Supported: an optional `CONFIG … END;` section (skipped), an `INPUT … END;` section
//! (the keywords may be omitted), declarations `variable_group`, `variable` (read as
//! ordinary affine unknowns), `function`, `constant`, `parameter` (parameters without
//! definitions, as in Bertini's parameter-homotopy mode; their values are given at
//! evaluation time), definitions `name = expression;` (an undeclared name defines a
//! subfunction, usable in later definitions), `+ - * / ^ ( )` with division only by
//! numeric constants, `I` (imaginary unit), `Pi`, numbers like `1.5e-3`, `%` comments.
//! Names must be defined before they are used. Equations are the functions in the
//! order of their declaration.
//!
//! Files written here declare parameters with `parameter` and no definition: Bertini
//! itself runs such a file in its parameter-homotopy mode (`ParameterHomotopy: 1` or
//! `2` in CONFIG, with the parameter values in its parameter files); substitute values
//! first ([`System::with_parameter_values`]) for a plain Bertini run.

use crate::C64;
use crate::system::expr::{Expr, Kind, format_constant, write_expr};
use crate::system::parse::{ParseError, ParseErrorKind, Resolved, Token, TokenCursor, tokenize};
use crate::system::{System, SystemError};
use std::collections::{HashMap, HashSet};

/// Errors of writing a system as Bertini input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BertiniWriteError {
    /// A symbol name Bertini cannot read.
    #[error(
        "the symbol name `{0}` is not a valid Bertini identifier (letters, digits, `_`, not starting with a digit, not `I` or `Pi`)"
    )]
    InvalidName(String),
    /// A NaN or infinite coefficient.
    #[error("the system contains a non-finite coefficient")]
    NonFiniteConstant,
}

#[derive(Clone)]
enum Entry {
    Variable,
    Parameter,
    Constant(Option<Expr>),
    Function(Option<Expr>),
    Subfunction(Expr),
}

const RESERVED: [&str; 2] = ["I", "Pi"];

fn keyword(token: &Token, word: &str) -> bool {
    matches!(token, Token::Name(n) if n.eq_ignore_ascii_case(word))
}

/// Reads a system from Bertini input text (see the module documentation for the
/// subset). Errors name the line and column; malformed text never panics.
pub fn read(text: &str) -> Result<System, ParseError> {
    let mut cursor = TokenCursor::new(tokenize(text)?);
    // Optional CONFIG section: skipped up to `END;`.
    if keyword(&cursor.peek().token, "CONFIG") {
        cursor.advance();
        loop {
            match &cursor.peek().token {
                Token::EndOfInput => {
                    return Err(cursor.error_here(ParseErrorKind::Unexpected {
                        found: "end of input".into(),
                        expected: "`END;` closing the CONFIG section".into(),
                    }));
                }
                t if keyword(t, "END") && cursor.peek_at(1).token == Token::Semicolon => {
                    cursor.advance();
                    cursor.advance();
                    break;
                }
                _ => {
                    cursor.advance();
                }
            }
        }
    }
    let has_input = keyword(&cursor.peek().token, "INPUT");
    if has_input {
        cursor.advance();
    }

    let mut entries: HashMap<String, Entry> = HashMap::new();
    let mut declared_at: HashMap<String, (usize, usize)> = HashMap::new();
    let mut variables: Vec<String> = Vec::new();
    let mut parameters: Vec<String> = Vec::new();
    let mut functions: Vec<String> = Vec::new();
    let mut constants: Vec<String> = Vec::new();
    // Where the statements end (the `END` of INPUT, or the end of the text).
    let mut end_position: Option<(usize, usize)> = None;

    loop {
        let at = cursor.peek().clone();
        let word = match &at.token {
            Token::EndOfInput => {
                if has_input {
                    return Err(cursor.unexpected("`END;` closing the INPUT section"));
                }
                break;
            }
            Token::Name(word) => word.clone(),
            _ => return Err(cursor.unexpected("a declaration or a definition `name = …;`")),
        };
        if word.eq_ignore_ascii_case("END") && cursor.peek_at(1).token != Token::Equals {
            end_position = Some((at.line, at.column));
            cursor.advance();
            cursor.expect_semicolon()?;
            if cursor.peek().token != Token::EndOfInput {
                return Err(cursor.unexpected("end of input after `END;`"));
            }
            break;
        }
        let declaration = match word.as_str() {
            "variable_group" | "variable" => Some(Entry::Variable),
            "parameter" => Some(Entry::Parameter),
            "function" => Some(Entry::Function(None)),
            "constant" => Some(Entry::Constant(None)),
            "hom_variable_group" | "pathvariable" | "random" | "random_real" | "subfunction"
                if cursor.peek_at(1).token != Token::Equals =>
            {
                return Err(cursor.error_here(ParseErrorKind::Unsupported(format!(
                    "the declaration `{word}`"
                ))));
            }
            _ => None,
        };
        if let Some(kind) = declaration {
            cursor.advance();
            loop {
                let name_at = cursor.peek().clone();
                let name = match &name_at.token {
                    Token::Name(name) => name.clone(),
                    _ => return Err(cursor.unexpected("a name")),
                };
                if RESERVED.contains(&name.as_str()) || entries.contains_key(&name) {
                    return Err(cursor.error_here(ParseErrorKind::Redeclared(name)));
                }
                cursor.advance();
                match kind {
                    Entry::Variable => variables.push(name.clone()),
                    Entry::Parameter => parameters.push(name.clone()),
                    Entry::Function(_) => functions.push(name.clone()),
                    Entry::Constant(_) => constants.push(name.clone()),
                    Entry::Subfunction(_) => {}
                }
                entries.insert(name.clone(), kind.clone());
                declared_at.insert(name, (name_at.line, name_at.column));
                if cursor.peek().token == Token::Comma {
                    cursor.advance();
                } else {
                    break;
                }
            }
            cursor.expect_semicolon()?;
            continue;
        }

        // A definition `name = expression;`.
        cursor.advance();
        if cursor.peek().token != Token::Equals {
            return Err(cursor.unexpected("`=` (a definition) after the name"));
        }
        let not_assignable = |reason: &'static str| ParseError {
            line: at.line,
            column: at.column,
            kind: ParseErrorKind::NotAssignable {
                name: word.clone(),
                reason,
            },
        };
        match entries.get(&word) {
            Some(Entry::Variable) => return Err(not_assignable("it is a variable")),
            Some(Entry::Parameter) => {
                return Err(not_assignable(
                    "it is a parameter (its values are given at evaluation time; use `constant` for a fixed value)",
                ));
            }
            Some(Entry::Function(Some(_)))
            | Some(Entry::Constant(Some(_)))
            | Some(Entry::Subfunction(_)) => {
                return Err(ParseError {
                    line: at.line,
                    column: at.column,
                    kind: ParseErrorKind::Redefined(word),
                });
            }
            _ if RESERVED.contains(&word.as_str()) => {
                return Err(not_assignable("it is a reserved name"));
            }
            _ => {}
        }
        cursor.advance();
        let value = {
            let resolve = |name: &str| -> Resolved {
                match name {
                    "I" => return Resolved::Value(Expr::constant(C64::new(0.0, 1.0))),
                    "Pi" => return Resolved::Value(Expr::from(std::f64::consts::PI)),
                    _ => {}
                }
                match entries.get(name) {
                    None => Resolved::Unknown,
                    Some(Entry::Variable) | Some(Entry::Parameter) => {
                        Resolved::Value(Expr::variable(name))
                    }
                    Some(Entry::Constant(Some(e)))
                    | Some(Entry::Function(Some(e)))
                    | Some(Entry::Subfunction(e)) => Resolved::Value(e.clone()),
                    Some(Entry::Constant(None)) => Resolved::Invalid(ParseErrorKind::Undefined {
                        what: "constant",
                        name: name.to_string(),
                    }),
                    Some(Entry::Function(None)) => Resolved::Invalid(ParseErrorKind::Undefined {
                        what: "function",
                        name: name.to_string(),
                    }),
                }
            };
            cursor.expression(&resolve)?
        };
        cursor.expect_semicolon()?;
        let entry = match entries.get(&word) {
            Some(Entry::Constant(None)) => {
                if value.as_constant().is_none() {
                    return Err(ParseError {
                        line: at.line,
                        column: at.column,
                        kind: ParseErrorKind::NonConstantDefinition(word),
                    });
                }
                Entry::Constant(Some(value))
            }
            Some(Entry::Function(None)) => Entry::Function(Some(value)),
            _ => Entry::Subfunction(value),
        };
        entries.insert(word, entry);
    }

    let (end_line, end_column) = end_position.unwrap_or_else(|| {
        let last = cursor.peek();
        (last.line, last.column)
    });
    for (what, list) in [("function", &functions), ("constant", &constants)] {
        for name in list {
            if let Some(Entry::Function(None)) | Some(Entry::Constant(None)) = entries.get(name) {
                let (line, column) = declared_at
                    .get(name)
                    .copied()
                    .unwrap_or((end_line, end_column));
                return Err(ParseError {
                    line,
                    column,
                    kind: ParseErrorKind::Undefined {
                        what,
                        name: name.clone(),
                    },
                });
            }
        }
    }
    let at_end = |kind: ParseErrorKind| ParseError {
        line: end_line,
        column: end_column,
        kind,
    };
    if functions.is_empty() {
        return Err(at_end(ParseErrorKind::EmptySystem));
    }
    let equations: Vec<Expr> = functions
        .iter()
        .filter_map(|f| match entries.get(f) {
            Some(Entry::Function(Some(e))) => Some(e.clone()),
            _ => None,
        })
        .collect();
    System::new(&variables, &parameters, equations).map_err(|error| match error {
        SystemError::EmptySystem => at_end(ParseErrorKind::EmptySystem),
        other => at_end(ParseErrorKind::InvalidSystem(other.to_string())),
    })
}

/// True for names Bertini (and our reader) accept as identifiers.
pub fn is_valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    match chars.next() {
        Some(c) if c.is_ascii_alphabetic() || c == '_' => {}
        _ => return false,
    }
    chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !RESERVED.contains(&name)
        && !["END", "INPUT", "CONFIG"]
            .iter()
            .any(|k| k.eq_ignore_ascii_case(name))
        && ![
            "variable_group",
            "variable",
            "function",
            "constant",
            "parameter",
            "hom_variable_group",
            "pathvariable",
            "random",
            "random_real",
            "subfunction",
        ]
        .contains(&name)
}

/// A prefix such that `prefix0, prefix1, …` clash with no name in `taken`.
fn fresh_prefix(base: &str, taken: &HashSet<&str>) -> String {
    let mut prefix = base.to_string();
    while taken.iter().any(|name| {
        name.strip_prefix(prefix.as_str())
            .is_some_and(|rest| !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit()))
    }) {
        prefix.push('_');
    }
    prefix
}

/// Writes `system` as Bertini input. Subexpressions shared in the expression DAG
/// become subfunctions, so the text stays proportional to the DAG (not to the expanded
/// tree). Parameters are declared with `parameter` (Bertini's parameter-homotopy mode).
pub fn write(system: &System) -> Result<String, BertiniWriteError> {
    for name in system.variables().iter().chain(system.parameters()) {
        if !is_valid_name(name) {
            return Err(BertiniWriteError::InvalidName(name.clone()));
        }
    }
    // Use counts over the DAG and a post-order of its nodes.
    let mut uses: HashMap<usize, usize> = HashMap::new();
    let mut order: Vec<Expr> = Vec::new();
    let mut visited: HashSet<usize> = HashSet::new();
    for equation in system.equations() {
        let mut stack: Vec<(Expr, bool)> = vec![(equation.clone(), false)];
        *uses.entry(equation.node_id()).or_insert(0) += 1;
        while let Some((e, children_done)) = stack.pop() {
            if children_done {
                order.push(e);
                continue;
            }
            if !visited.insert(e.node_id()) {
                continue;
            }
            if let Kind::Constant(c) = e.kind()
                && !(c.re.is_finite() && c.im.is_finite())
            {
                return Err(BertiniWriteError::NonFiniteConstant);
            }
            stack.push((e.clone(), true));
            let children: Vec<Expr> = match e.kind() {
                Kind::Add(a, b) | Kind::Sub(a, b) | Kind::Mul(a, b) => vec![a.clone(), b.clone()],
                Kind::Neg(a) | Kind::Pow(a, _) => vec![a.clone()],
                Kind::Constant(_) | Kind::Symbol(_) => vec![],
            };
            for child in children.into_iter().rev() {
                *uses.entry(child.node_id()).or_insert(0) += 1;
                stack.push((child, false));
            }
        }
    }
    let taken: HashSet<&str> = system
        .variables()
        .iter()
        .chain(system.parameters())
        .map(|s| s.as_str())
        .collect();
    let function_prefix = fresh_prefix("f", &taken);
    let subfunction_prefix = fresh_prefix("s", &taken);

    let mut out = String::new();
    out.push_str(&format!(
        "% Polynomial system written by singdist: {} variables, {} parameters, {} equations.\n",
        system.variables().len(),
        system.parameters().len(),
        system.num_equations()
    ));
    out.push_str("INPUT\n");
    out.push_str(&format!(
        "variable_group {};\n",
        system.variables().join(", ")
    ));
    if !system.parameters().is_empty() {
        out.push_str(&format!("parameter {};\n", system.parameters().join(", ")));
    }
    let function_names: Vec<String> = (1..=system.num_equations())
        .map(|i| format!("{function_prefix}{i}"))
        .collect();
    out.push_str(&format!("function {};\n", function_names.join(", ")));

    let equation_ids: HashSet<usize> = system.equations().iter().map(|e| e.node_id()).collect();
    let mut names: HashMap<usize, String> = HashMap::new();
    let mut count = 0usize;
    for e in &order {
        let shared = uses.get(&e.node_id()).copied().unwrap_or(0) > 1;
        let trivial = matches!(e.kind(), Kind::Constant(_) | Kind::Symbol(_));
        if shared && !trivial && !equation_ids.contains(&e.node_id()) {
            let name = format!("{subfunction_prefix}{count}");
            count += 1;
            let mut text = String::new();
            write_expr(e, &mut text, "I", &names);
            out.push_str(&format!("{name} = {text};\n"));
            names.insert(e.node_id(), name);
        }
    }
    for (name, equation) in function_names.iter().zip(system.equations()) {
        let mut text = String::new();
        if let Some(shared) = names.get(&equation.node_id()) {
            text.push_str(shared);
        } else if let Some(c) = equation.as_constant() {
            text.push_str(&format_constant(c, "I"));
        } else {
            write_expr(equation, &mut text, "I", &names);
        }
        out.push_str(&format!("{name} = {text};\n"));
    }
    out.push_str("END;\n");
    Ok(out)
}

/// Reads a numeric constant written as a Bertini expression, e.g. `1.5`, `-2e-3`,
/// `0.5 + 2*I` (for parameter values given on the command line).
pub fn read_constant(text: &str) -> Result<C64, ParseError> {
    let mut cursor = TokenCursor::new(tokenize(text)?);
    let resolve = |name: &str| match name {
        "I" => Resolved::Value(Expr::constant(C64::new(0.0, 1.0))),
        "Pi" => Resolved::Value(Expr::from(std::f64::consts::PI)),
        _ => Resolved::Unknown,
    };
    let value = cursor.expression(&resolve)?;
    if cursor.peek().token != Token::EndOfInput {
        return Err(cursor.unexpected("end of the number"));
    }
    value
        .as_constant()
        .ok_or_else(|| cursor.error_here(ParseErrorKind::InvalidNumber(text.to_string())))
}
