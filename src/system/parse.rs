//! Tokenizer and expression parser shared by the Bertini and PHCpack readers.
//!
//! Grammar (usual precedence, `^` binds tightest, unary minus below `^` so that
//! `-x^2 = -(x^2)`):
//!
//! ```text
//! sum     = product { ("+" | "-") product }
//! product = unary { ("*" | "/") unary }
//! unary   = ("-" | "+") unary | power
//! power   = atom [ ("^" | "**") exponent ]        exponent: non-negative integer literal,
//! atom    = number | name | "(" sum ")"                      optionally in parentheses
//! ```
//!
//! Division is accepted only by a non-zero constant (a polynomial stays a polynomial).
//! Every error carries the line and column (1-based) where it was detected; the parser
//! never panics and bounds its recursion depth.

use crate::C64;
use crate::system::expr::Expr;

/// Deepest nesting of parentheses / unary operators the parser accepts.
pub const MAX_NESTING: usize = 200;

/// What went wrong while reading a system file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParseErrorKind {
    /// A name that was not declared or defined before its use.
    #[error("unknown symbol `{0}`")]
    UnknownSymbol(String),
    /// A statement not closed by `;`.
    #[error("missing `;` (found {0})")]
    MissingSemicolon(String),
    /// `^` followed by something other than a non-negative integer.
    #[error("the exponent must be a non-negative integer below 2^32 (found {0})")]
    NonIntegerExponent(String),
    /// No equations.
    #[error("the system has no equations (declare them with `function` and define them)")]
    EmptySystem,
    /// A declared function or constant that is never defined.
    #[error("the {what} `{name}` is declared but never defined")]
    Undefined {
        /// `function` or `constant`.
        what: &'static str,
        /// Its name.
        name: String,
    },
    /// A token that does not fit the grammar here.
    #[error("unexpected {found}, expected {expected}")]
    Unexpected {
        /// Description of the token found.
        found: String,
        /// What the grammar allows here.
        expected: String,
    },
    /// A character that starts no token.
    #[error("invalid character `{0}`")]
    InvalidCharacter(char),
    /// A malformed number.
    #[error("invalid number `{0}`")]
    InvalidNumber(String),
    /// A name declared twice.
    #[error("`{0}` is already declared")]
    Redeclared(String),
    /// A name defined twice.
    #[error("`{0}` is already defined")]
    Redefined(String),
    /// A definition of a name that cannot be defined.
    #[error("`{name}` cannot be defined: {reason}")]
    NotAssignable {
        /// The name.
        name: String,
        /// Why.
        reason: &'static str,
    },
    /// A construct of the format outside the supported subset.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// Too many nested parentheses or unary operators.
    #[error("expression nested deeper than {MAX_NESTING} levels")]
    TooDeeplyNested,
    /// A constant defined by a non-constant expression.
    #[error("the constant `{0}` must be defined by a numeric expression")]
    NonConstantDefinition(String),
    /// Division by something other than a non-zero constant.
    #[error("division is only allowed by a non-zero numeric constant")]
    InvalidDivision,
    /// The statements are fine but do not form a valid system.
    #[error("{0}")]
    InvalidSystem(String),
}

/// An error of a system file, with its position.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}, column {column}: {kind}")]
pub struct ParseError {
    /// Line, 1-based.
    pub line: usize,
    /// Column (in characters), 1-based.
    pub column: usize,
    /// What went wrong.
    pub kind: ParseErrorKind,
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Token {
    Name(String),
    Number(f64, String),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LeftParen,
    RightParen,
    Comma,
    Semicolon,
    Equals,
    Other(char),
    EndOfInput,
}

impl Token {
    pub(crate) fn describe(&self) -> String {
        match self {
            Token::Name(n) => format!("`{n}`"),
            Token::Number(_, text) => format!("number `{text}`"),
            Token::Plus => "`+`".into(),
            Token::Minus => "`-`".into(),
            Token::Star => "`*`".into(),
            Token::Slash => "`/`".into(),
            Token::Caret => "`^`".into(),
            Token::LeftParen => "`(`".into(),
            Token::RightParen => "`)`".into(),
            Token::Comma => "`,`".into(),
            Token::Semicolon => "`;`".into(),
            Token::Equals => "`=`".into(),
            Token::Other(c) => format!("`{c}`"),
            Token::EndOfInput => "end of input".into(),
        }
    }
}

/// A token with the position of its first character and of the character after it.
#[derive(Clone, Debug)]
pub(crate) struct Spanned {
    pub token: Token,
    pub line: usize,
    pub column: usize,
    pub end_line: usize,
    pub end_column: usize,
}

/// Splits `text` into tokens; `%` starts a comment to the end of the line. Unknown
/// characters become [`Token::Other`] so that free-form sections (Bertini's CONFIG)
/// can be skipped.
pub(crate) fn tokenize(text: &str) -> Result<Vec<Spanned>, ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let (mut i, mut line, mut column) = (0usize, 1usize, 1usize);
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            i += 1;
            line += 1;
            column = 1;
            continue;
        }
        if c.is_whitespace() {
            i += 1;
            column += 1;
            continue;
        }
        if c == '%' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            continue;
        }
        let (start_line, start_column) = (line, column);
        let start = i;
        let token = if c.is_ascii_alphabetic() || c == '_' {
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            Token::Name(chars[start..i].iter().collect())
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let text: String = chars[start..i].iter().collect();
            match text.parse::<f64>() {
                Ok(value) if value.is_finite() => Token::Number(value, text),
                _ => {
                    return Err(ParseError {
                        line: start_line,
                        column: start_column,
                        kind: ParseErrorKind::InvalidNumber(text),
                    });
                }
            }
        } else {
            i += 1;
            match c {
                '+' => Token::Plus,
                '-' => Token::Minus,
                '*' if chars.get(i) == Some(&'*') => {
                    i += 1;
                    Token::Caret
                }
                '*' => Token::Star,
                '/' => Token::Slash,
                '^' => Token::Caret,
                '(' => Token::LeftParen,
                ')' => Token::RightParen,
                ',' => Token::Comma,
                ';' => Token::Semicolon,
                '=' => Token::Equals,
                other => Token::Other(other),
            }
        };
        column += i - start;
        tokens.push(Spanned {
            token,
            line: start_line,
            column: start_column,
            end_line: line,
            end_column: column,
        });
    }
    tokens.push(Spanned {
        token: Token::EndOfInput,
        line,
        column,
        end_line: line,
        end_column: column,
    });
    Ok(tokens)
}

/// How a name inside an expression is resolved.
pub(crate) enum Resolved {
    Value(Expr),
    Unknown,
    /// Known but not usable here; the message says why.
    Invalid(ParseErrorKind),
}

/// Maps a name inside an expression to its value (see [`Resolved`]).
type Resolver<'r> = &'r dyn Fn(&str) -> Resolved;

/// A cursor over tokens with the expression grammar.
pub(crate) struct TokenCursor {
    pub tokens: Vec<Spanned>,
    pub position: usize,
}

impl TokenCursor {
    pub fn new(tokens: Vec<Spanned>) -> TokenCursor {
        TokenCursor {
            tokens,
            position: 0,
        }
    }

    pub fn peek(&self) -> &Spanned {
        let last = self.tokens.len() - 1;
        &self.tokens[self.position.min(last)]
    }

    pub fn peek_at(&self, offset: usize) -> &Spanned {
        let last = self.tokens.len() - 1;
        &self.tokens[(self.position + offset).min(last)]
    }

    pub fn advance(&mut self) -> Spanned {
        let token = self.peek().clone();
        if self.position < self.tokens.len() - 1 {
            self.position += 1;
        }
        token
    }

    /// End position of the previous token (where a missing `;` belongs).
    pub fn previous_end(&self) -> (usize, usize) {
        if self.position == 0 {
            (1, 1)
        } else {
            let t = &self.tokens[self.position - 1];
            (t.end_line, t.end_column)
        }
    }

    pub fn error_here(&self, kind: ParseErrorKind) -> ParseError {
        let t = self.peek();
        ParseError {
            line: t.line,
            column: t.column,
            kind,
        }
    }

    pub fn unexpected(&self, expected: &str) -> ParseError {
        let found = self.peek().token.describe();
        self.error_here(ParseErrorKind::Unexpected {
            found,
            expected: expected.to_string(),
        })
    }

    /// Expects `;` after a statement.
    pub fn expect_semicolon(&mut self) -> Result<(), ParseError> {
        if self.peek().token == Token::Semicolon {
            self.advance();
            return Ok(());
        }
        let (line, column) = self.previous_end();
        Err(ParseError {
            line,
            column,
            kind: ParseErrorKind::MissingSemicolon(self.peek().token.describe()),
        })
    }

    /// Parses a sum; `resolve` maps names to expressions.
    pub fn expression(&mut self, resolve: Resolver) -> Result<Expr, ParseError> {
        self.sum(resolve, 0)
    }

    fn sum(&mut self, resolve: Resolver, depth: usize) -> Result<Expr, ParseError> {
        // Terms are combined as a balanced tree so that long sums stay shallow.
        let mut terms = vec![self.product(resolve, depth)?];
        while matches!(self.peek().token, Token::Plus | Token::Minus) {
            let negative = self.advance().token == Token::Minus;
            let term = self.product(resolve, depth)?;
            terms.push(if negative { -term } else { term });
        }
        Ok(Expr::balanced_sum(terms))
    }

    fn product(&mut self, resolve: Resolver, depth: usize) -> Result<Expr, ParseError> {
        let mut factors = vec![self.unary(resolve, depth)?];
        loop {
            match self.peek().token {
                Token::Star => {
                    self.advance();
                    factors.push(self.unary(resolve, depth)?);
                }
                Token::Slash => {
                    let at = self.advance();
                    let divisor = self.unary(resolve, depth)?;
                    match divisor.as_constant() {
                        Some(c) if c != C64::new(0.0, 0.0) => {
                            factors.push(Expr::constant(C64::new(1.0, 0.0) / c));
                        }
                        _ => {
                            return Err(ParseError {
                                line: at.line,
                                column: at.column,
                                kind: ParseErrorKind::InvalidDivision,
                            });
                        }
                    }
                }
                _ => return Ok(Expr::balanced_product(factors)),
            }
        }
    }

    fn unary(&mut self, resolve: Resolver, depth: usize) -> Result<Expr, ParseError> {
        if depth > MAX_NESTING {
            return Err(self.error_here(ParseErrorKind::TooDeeplyNested));
        }
        match self.peek().token {
            Token::Minus => {
                self.advance();
                Ok(-self.unary(resolve, depth + 1)?)
            }
            Token::Plus => {
                self.advance();
                self.unary(resolve, depth + 1)
            }
            _ => self.power(resolve, depth),
        }
    }

    fn power(&mut self, resolve: Resolver, depth: usize) -> Result<Expr, ParseError> {
        let mut base = self.atom(resolve, depth)?;
        while self.peek().token == Token::Caret {
            self.advance();
            let exponent = self.exponent()?;
            base = base.pow(exponent);
        }
        Ok(base)
    }

    fn exponent(&mut self) -> Result<u32, ParseError> {
        let parenthesised = self.peek().token == Token::LeftParen;
        if parenthesised {
            self.advance();
        }
        let at = self.peek().clone();
        let value = match &at.token {
            Token::Number(value, _)
                if value.fract() == 0.0 && *value >= 0.0 && *value <= u32::MAX as f64 =>
            {
                *value as u32
            }
            other => {
                return Err(ParseError {
                    line: at.line,
                    column: at.column,
                    kind: ParseErrorKind::NonIntegerExponent(other.describe()),
                });
            }
        };
        self.advance();
        if parenthesised {
            if self.peek().token != Token::RightParen {
                return Err(self.unexpected("`)` closing the exponent"));
            }
            self.advance();
        }
        Ok(value)
    }

    fn atom(&mut self, resolve: Resolver, depth: usize) -> Result<Expr, ParseError> {
        let at = self.peek().clone();
        match &at.token {
            Token::Number(value, _) => {
                self.advance();
                Ok(Expr::from(*value))
            }
            Token::LeftParen => {
                if depth >= MAX_NESTING {
                    return Err(self.error_here(ParseErrorKind::TooDeeplyNested));
                }
                self.advance();
                let inner = self.sum(resolve, depth + 1)?;
                if self.peek().token != Token::RightParen {
                    return Err(self.unexpected("`)`"));
                }
                self.advance();
                Ok(inner)
            }
            Token::Name(name) => {
                if self.peek_at(1).token == Token::LeftParen {
                    return Err(self.error_here(ParseErrorKind::Unsupported(format!(
                        "function call `{name}(…)` (only polynomial expressions are supported)"
                    ))));
                }
                let kind = match resolve(name) {
                    Resolved::Value(e) => {
                        self.advance();
                        return Ok(e);
                    }
                    Resolved::Unknown => ParseErrorKind::UnknownSymbol(name.clone()),
                    Resolved::Invalid(kind) => kind,
                };
                Err(ParseError {
                    line: at.line,
                    column: at.column,
                    kind,
                })
            }
            _ => Err(self.unexpected("a number, a name or `(`")),
        }
    }
}
