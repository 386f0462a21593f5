//! Symbolic expressions over the complex numbers in named symbols.
//!
//! An [`Expr`] is an immutable DAG of reference-counted nodes: cloning is a pointer copy
//! and shared subexpressions stay shared (the compiler in [`super::compile`] exploits
//! that and additionally merges structurally equal subexpressions). Every constructor
//! simplifies locally: constants are folded, `0 + a = a`, `1 · a = a`, `0 · a = 0`,
//! `−(−a) = a`, `a^0 = 1`, `a^1 = a`, so that exact derivatives do not fill up with
//! zeros and ones.
//!
//! Whether a symbol is an unknown or a parameter is decided by the [`super::System`]
//! that lists it; [`Expr::variable`] and [`Expr::parameter`] build the same kind of
//! node and exist to make the intent of the caller readable.

use crate::C64;
use crate::algebra::Ring;
use std::collections::HashMap;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use std::sync::Arc;

/// A polynomial expression in named symbols with complex coefficients.
#[derive(Clone)]
pub struct Expr(Arc<Node>);

pub(crate) struct Node {
    pub(crate) kind: Kind,
    hash: u64,
}

/// The node kinds of the expression DAG.
pub(crate) enum Kind {
    Constant(C64),
    Symbol(Arc<str>),
    Add(Expr, Expr),
    Sub(Expr, Expr),
    Mul(Expr, Expr),
    Neg(Expr),
    Pow(Expr, u32),
}

const ZERO: C64 = C64::new(0.0, 0.0);
const ONE: C64 = C64::new(1.0, 0.0);

fn structural_hash(kind: &Kind) -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    match kind {
        Kind::Constant(c) => {
            0u8.hash(&mut hasher);
            c.re.to_bits().hash(&mut hasher);
            c.im.to_bits().hash(&mut hasher);
        }
        Kind::Symbol(name) => {
            1u8.hash(&mut hasher);
            name.hash(&mut hasher);
        }
        Kind::Add(a, b) => {
            2u8.hash(&mut hasher);
            a.0.hash.hash(&mut hasher);
            b.0.hash.hash(&mut hasher);
        }
        Kind::Sub(a, b) => {
            3u8.hash(&mut hasher);
            a.0.hash.hash(&mut hasher);
            b.0.hash.hash(&mut hasher);
        }
        Kind::Mul(a, b) => {
            4u8.hash(&mut hasher);
            a.0.hash.hash(&mut hasher);
            b.0.hash.hash(&mut hasher);
        }
        Kind::Neg(a) => {
            5u8.hash(&mut hasher);
            a.0.hash.hash(&mut hasher);
        }
        Kind::Pow(a, n) => {
            6u8.hash(&mut hasher);
            a.0.hash.hash(&mut hasher);
            n.hash(&mut hasher);
        }
    }
    hasher.finish()
}

impl Expr {
    fn from_kind(kind: Kind) -> Expr {
        let hash = structural_hash(&kind);
        Expr(Arc::new(Node { kind, hash }))
    }

    pub(crate) fn kind(&self) -> &Kind {
        &self.0.kind
    }

    /// Identity of the node (address), for memoisation over the DAG.
    pub(crate) fn node_id(&self) -> usize {
        Arc::as_ptr(&self.0) as usize
    }

    /// The named unknown `name`.
    pub fn variable(name: impl AsRef<str>) -> Expr {
        Expr::from_kind(Kind::Symbol(Arc::from(name.as_ref())))
    }

    /// The named parameter `name` (same node kind as a variable; the role is given by
    /// the [`super::System`] that lists the name).
    pub fn parameter(name: impl AsRef<str>) -> Expr {
        Expr::variable(name)
    }

    /// The complex constant `value`.
    pub fn constant(value: C64) -> Expr {
        Expr::from_kind(Kind::Constant(value))
    }

    /// The constant 0.
    pub fn zero() -> Expr {
        Expr::constant(ZERO)
    }

    /// The constant 1.
    pub fn one() -> Expr {
        Expr::constant(ONE)
    }

    /// `Some(c)` if this expression is the constant `c`.
    pub fn as_constant(&self) -> Option<C64> {
        match self.kind() {
            Kind::Constant(c) => Some(*c),
            _ => None,
        }
    }

    /// `Some(name)` if this expression is a single symbol.
    pub fn as_symbol(&self) -> Option<&str> {
        match self.kind() {
            Kind::Symbol(name) => Some(name),
            _ => None,
        }
    }

    /// True for the constant 0.
    pub fn is_zero(&self) -> bool {
        self.as_constant() == Some(ZERO)
    }

    /// True for the constant 1.
    pub fn is_one(&self) -> bool {
        self.as_constant() == Some(ONE)
    }

    /// `self^exponent` (exponent 0 gives 1, also for `0^0`).
    pub fn pow(&self, exponent: u32) -> Expr {
        match (exponent, self.kind()) {
            (0, _) => Expr::one(),
            (1, _) => self.clone(),
            (_, Kind::Constant(c)) => Expr::constant(c.powu(exponent)),
            (_, Kind::Pow(base, inner)) if inner.checked_mul(exponent).is_some() => {
                base.pow(inner * exponent)
            }
            _ => Expr::from_kind(Kind::Pow(self.clone(), exponent)),
        }
    }

    /// The exact partial derivative `∂self/∂symbol` (sum, product, power and chain
    /// rules), simplified by the local rules of the constructors. Shared subexpressions
    /// are differentiated once.
    pub fn differentiate(&self, symbol: &str) -> Expr {
        let mut memo = HashMap::new();
        self.differentiate_memo(symbol, &mut memo)
    }

    pub(crate) fn differentiate_memo(&self, symbol: &str, memo: &mut HashMap<usize, Expr>) -> Expr {
        if let Some(done) = memo.get(&self.node_id()) {
            return done.clone();
        }
        let derivative = match self.kind() {
            Kind::Constant(_) => Expr::zero(),
            Kind::Symbol(name) => {
                if &**name == symbol {
                    Expr::one()
                } else {
                    Expr::zero()
                }
            }
            Kind::Add(a, b) => {
                a.differentiate_memo(symbol, memo) + b.differentiate_memo(symbol, memo)
            }
            Kind::Sub(a, b) => {
                a.differentiate_memo(symbol, memo) - b.differentiate_memo(symbol, memo)
            }
            Kind::Mul(a, b) => {
                let da = a.differentiate_memo(symbol, memo);
                let db = b.differentiate_memo(symbol, memo);
                da * b + a * db
            }
            Kind::Neg(a) => -a.differentiate_memo(symbol, memo),
            Kind::Pow(a, n) => {
                let da = a.differentiate_memo(symbol, memo);
                if da.is_zero() {
                    Expr::zero()
                } else {
                    Expr::from(*n as f64) * a.pow(n - 1) * da
                }
            }
        };
        memo.insert(self.node_id(), derivative.clone());
        derivative
    }

    /// Naive evaluation: walks the DAG (each shared node once) and looks symbols up with
    /// `lookup`. Returns `Err(name)` for the first symbol `lookup` does not know.
    pub fn evaluate<F>(&self, lookup: F) -> Result<C64, String>
    where
        F: Fn(&str) -> Option<C64>,
    {
        let mut memo = HashMap::new();
        self.evaluate_memo(&lookup, &mut memo)
    }

    /// Naive evaluation with symbol values from a map (see [`Expr::evaluate`]).
    pub fn evaluate_map(&self, values: &HashMap<String, C64>) -> Result<C64, String> {
        self.evaluate(|name| values.get(name).copied())
    }

    pub(crate) fn evaluate_memo<F>(
        &self,
        lookup: &F,
        memo: &mut HashMap<usize, C64>,
    ) -> Result<C64, String>
    where
        F: Fn(&str) -> Option<C64>,
    {
        if let Some(value) = memo.get(&self.node_id()) {
            return Ok(*value);
        }
        let value = match self.kind() {
            Kind::Constant(c) => *c,
            Kind::Symbol(name) => lookup(name).ok_or_else(|| name.to_string())?,
            Kind::Add(a, b) => a.evaluate_memo(lookup, memo)? + b.evaluate_memo(lookup, memo)?,
            Kind::Sub(a, b) => a.evaluate_memo(lookup, memo)? - b.evaluate_memo(lookup, memo)?,
            Kind::Mul(a, b) => a.evaluate_memo(lookup, memo)? * b.evaluate_memo(lookup, memo)?,
            Kind::Neg(a) => -a.evaluate_memo(lookup, memo)?,
            Kind::Pow(a, n) => a.evaluate_memo(lookup, memo)?.powu(*n),
        };
        memo.insert(self.node_id(), value);
        Ok(value)
    }

    /// The distinct symbol names occurring in the expression, in order of first
    /// occurrence (depth first, left to right).
    pub fn symbols(&self) -> Vec<String> {
        let mut seen_nodes = std::collections::HashSet::new();
        let mut seen_names = std::collections::HashSet::new();
        let mut names = Vec::new();
        let mut stack = vec![self.clone()];
        while let Some(e) = stack.pop() {
            if !seen_nodes.insert(e.node_id()) {
                continue;
            }
            match e.kind() {
                Kind::Constant(_) => {}
                Kind::Symbol(name) => {
                    if seen_names.insert(name.clone()) {
                        names.push(name.to_string());
                    }
                }
                Kind::Add(a, b) | Kind::Sub(a, b) | Kind::Mul(a, b) => {
                    stack.push(b.clone());
                    stack.push(a.clone());
                }
                Kind::Neg(a) | Kind::Pow(a, _) => stack.push(a.clone()),
            }
        }
        names
    }

    /// Replaces symbols by expressions (`map(name)` returns the replacement, `None`
    /// keeps the symbol), rebuilding with the simplifying constructors.
    pub fn substitute<F>(&self, map: &F) -> Expr
    where
        F: Fn(&str) -> Option<Expr>,
    {
        let mut memo = HashMap::new();
        self.substitute_memo(map, &mut memo)
    }

    fn substitute_memo<F>(&self, map: &F, memo: &mut HashMap<usize, Expr>) -> Expr
    where
        F: Fn(&str) -> Option<Expr>,
    {
        if let Some(done) = memo.get(&self.node_id()) {
            return done.clone();
        }
        let result = match self.kind() {
            Kind::Constant(_) => self.clone(),
            Kind::Symbol(name) => map(name).unwrap_or_else(|| self.clone()),
            Kind::Add(a, b) => a.substitute_memo(map, memo) + b.substitute_memo(map, memo),
            Kind::Sub(a, b) => a.substitute_memo(map, memo) - b.substitute_memo(map, memo),
            Kind::Mul(a, b) => a.substitute_memo(map, memo) * b.substitute_memo(map, memo),
            Kind::Neg(a) => -a.substitute_memo(map, memo),
            Kind::Pow(a, n) => a.substitute_memo(map, memo).pow(*n),
        };
        memo.insert(self.node_id(), result.clone());
        result
    }

    /// `Σ terms`, combined as a balanced binary tree (depth `⌈log₂ len⌉`, so that
    /// long sums do not make deep recursions). The empty sum is 0.
    pub fn balanced_sum(terms: Vec<Expr>) -> Expr {
        balanced(terms, &add).unwrap_or_else(Expr::zero)
    }

    /// `Π factors`, combined as a balanced binary tree. The empty product is 1.
    pub fn balanced_product(factors: Vec<Expr>) -> Expr {
        balanced(factors, &mul).unwrap_or_else(Expr::one)
    }

    /// Number of distinct nodes of the DAG.
    pub fn node_count(&self) -> usize {
        let mut seen = std::collections::HashSet::new();
        let mut stack = vec![self.clone()];
        while let Some(e) = stack.pop() {
            if !seen.insert(e.node_id()) {
                continue;
            }
            match e.kind() {
                Kind::Constant(_) | Kind::Symbol(_) => {}
                Kind::Add(a, b) | Kind::Sub(a, b) | Kind::Mul(a, b) => {
                    stack.push(a.clone());
                    stack.push(b.clone());
                }
                Kind::Neg(a) | Kind::Pow(a, _) => stack.push(a.clone()),
            }
        }
        seen.len()
    }
}

fn balanced(mut items: Vec<Expr>, combine: &dyn Fn(&Expr, &Expr) -> Expr) -> Option<Expr> {
    while items.len() > 1 {
        let mut next = Vec::with_capacity(items.len().div_ceil(2));
        let mut iter = items.chunks_exact(2);
        for pair in &mut iter {
            next.push(combine(&pair[0], &pair[1]));
        }
        next.extend(iter.remainder().iter().cloned());
        items = next;
    }
    items.pop()
}

fn add(a: &Expr, b: &Expr) -> Expr {
    match (a.kind(), b.kind()) {
        (Kind::Constant(x), Kind::Constant(y)) => Expr::constant(x + y),
        _ if a.is_zero() => b.clone(),
        _ if b.is_zero() => a.clone(),
        (_, Kind::Neg(c)) => sub(a, c),
        (Kind::Neg(c), _) => sub(b, c),
        _ => Expr::from_kind(Kind::Add(a.clone(), b.clone())),
    }
}

fn sub(a: &Expr, b: &Expr) -> Expr {
    match (a.kind(), b.kind()) {
        (Kind::Constant(x), Kind::Constant(y)) => Expr::constant(x - y),
        _ if b.is_zero() => a.clone(),
        _ if a.is_zero() => neg(b),
        (_, Kind::Neg(c)) => add(a, c),
        _ => Expr::from_kind(Kind::Sub(a.clone(), b.clone())),
    }
}

fn mul(a: &Expr, b: &Expr) -> Expr {
    match (a.kind(), b.kind()) {
        (Kind::Constant(x), Kind::Constant(y)) => Expr::constant(x * y),
        _ if a.is_zero() || b.is_zero() => Expr::zero(),
        _ if a.is_one() => b.clone(),
        _ if b.is_one() => a.clone(),
        (Kind::Constant(x), _) if *x == -ONE => neg(b),
        (_, Kind::Constant(y)) if *y == -ONE => neg(a),
        // c₁·(c₂·e) = (c₁c₂)·e
        (Kind::Constant(x), Kind::Mul(c, e)) if c.as_constant().is_some() => {
            mul(&Expr::constant(x * c.as_constant().unwrap_or(ONE)), e)
        }
        (Kind::Mul(c, e), Kind::Constant(y)) if c.as_constant().is_some() => {
            mul(&Expr::constant(y * c.as_constant().unwrap_or(ONE)), e)
        }
        (Kind::Neg(x), Kind::Neg(y)) => mul(x, y),
        (Kind::Neg(x), _) => neg(&mul(x, b)),
        (_, Kind::Neg(y)) => neg(&mul(a, y)),
        // Constants first, so that `c · e` and `e · c` look alike.
        (_, Kind::Constant(_)) => Expr::from_kind(Kind::Mul(b.clone(), a.clone())),
        _ if a.0.hash == b.0.hash && a == b => a.pow(2),
        _ => Expr::from_kind(Kind::Mul(a.clone(), b.clone())),
    }
}

fn neg(a: &Expr) -> Expr {
    match a.kind() {
        Kind::Constant(x) => Expr::constant(-x),
        Kind::Neg(inner) => inner.clone(),
        Kind::Sub(x, y) => Expr::from_kind(Kind::Sub(y.clone(), x.clone())),
        _ => Expr::from_kind(Kind::Neg(a.clone())),
    }
}

impl PartialEq for Expr {
    /// Structural equality (same tree up to sharing).
    fn eq(&self, other: &Expr) -> bool {
        if Arc::ptr_eq(&self.0, &other.0) {
            return true;
        }
        if self.0.hash != other.0.hash {
            return false;
        }
        match (self.kind(), other.kind()) {
            (Kind::Constant(x), Kind::Constant(y)) => {
                x.re.to_bits() == y.re.to_bits() && x.im.to_bits() == y.im.to_bits()
            }
            (Kind::Symbol(x), Kind::Symbol(y)) => x == y,
            (Kind::Add(a, b), Kind::Add(c, d))
            | (Kind::Sub(a, b), Kind::Sub(c, d))
            | (Kind::Mul(a, b), Kind::Mul(c, d)) => a == c && b == d,
            (Kind::Neg(a), Kind::Neg(c)) => a == c,
            (Kind::Pow(a, n), Kind::Pow(c, m)) => n == m && a == c,
            _ => false,
        }
    }
}

impl Eq for Expr {}

impl Hash for Expr {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.0.hash.hash(state);
    }
}

impl From<f64> for Expr {
    fn from(value: f64) -> Expr {
        Expr::constant(C64::new(value, 0.0))
    }
}

impl From<C64> for Expr {
    fn from(value: C64) -> Expr {
        Expr::constant(value)
    }
}

impl From<&Expr> for Expr {
    fn from(value: &Expr) -> Expr {
        value.clone()
    }
}

impl Ring for Expr {
    fn from_f64(value: f64) -> Expr {
        Expr::from(value)
    }
}

impl crate::algebra::ComplexRing for Expr {
    fn imaginary_unit() -> Expr {
        Expr::constant(C64::new(0.0, 1.0))
    }
}

macro_rules! binary_operator {
    ($trait:ident, $method:ident, $function:ident) => {
        impl $trait<Expr> for Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                $function(&self, &rhs)
            }
        }
        impl $trait<&Expr> for Expr {
            type Output = Expr;
            fn $method(self, rhs: &Expr) -> Expr {
                $function(&self, rhs)
            }
        }
        impl $trait<Expr> for &Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                $function(self, &rhs)
            }
        }
        impl $trait<&Expr> for &Expr {
            type Output = Expr;
            fn $method(self, rhs: &Expr) -> Expr {
                $function(self, rhs)
            }
        }
        binary_operator!(@scalar $trait, $method, $function, f64);
        binary_operator!(@scalar $trait, $method, $function, C64);
    };
    (@scalar $trait:ident, $method:ident, $function:ident, $scalar:ty) => {
        impl $trait<$scalar> for Expr {
            type Output = Expr;
            fn $method(self, rhs: $scalar) -> Expr {
                $function(&self, &Expr::from(rhs))
            }
        }
        impl $trait<$scalar> for &Expr {
            type Output = Expr;
            fn $method(self, rhs: $scalar) -> Expr {
                $function(self, &Expr::from(rhs))
            }
        }
        impl $trait<Expr> for $scalar {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr {
                $function(&Expr::from(self), &rhs)
            }
        }
        impl $trait<&Expr> for $scalar {
            type Output = Expr;
            fn $method(self, rhs: &Expr) -> Expr {
                $function(&Expr::from(self), rhs)
            }
        }
    };
}

binary_operator!(Add, add, add);
binary_operator!(Sub, sub, sub);
binary_operator!(Mul, mul, mul);

impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        neg(&self)
    }
}

impl Neg for &Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        neg(self)
    }
}

impl<T: Into<Expr>> AddAssign<T> for Expr {
    fn add_assign(&mut self, rhs: T) {
        *self = add(self, &rhs.into());
    }
}

impl<T: Into<Expr>> SubAssign<T> for Expr {
    fn sub_assign(&mut self, rhs: T) {
        *self = sub(self, &rhs.into());
    }
}

impl<T: Into<Expr>> MulAssign<T> for Expr {
    fn mul_assign(&mut self, rhs: T) {
        *self = mul(self, &rhs.into());
    }
}

/// `Trait` (`Sum` or `Product`) over owned and borrowed expressions by the balanced
/// fold `balanced` ([`Expr::balanced_sum`], [`Expr::balanced_product`]).
macro_rules! balanced_fold {
    ($trait:ident, $method:ident, $balanced:ident) => {
        impl std::iter::$trait for Expr {
            fn $method<I: Iterator<Item = Expr>>(iter: I) -> Expr {
                Expr::$balanced(iter.collect())
            }
        }

        impl<'a> std::iter::$trait<&'a Expr> for Expr {
            fn $method<I: Iterator<Item = &'a Expr>>(iter: I) -> Expr {
                Expr::$balanced(iter.cloned().collect())
            }
        }
    };
}

balanced_fold!(Sum, sum, balanced_sum);
balanced_fold!(Product, product, balanced_product);

/// Formats a complex constant so that it reads back exactly (shortest round-trip
/// decimal of each part), with `imaginary_unit` as the name of `i`.
pub(crate) fn format_constant(c: C64, imaginary_unit: &str) -> String {
    let real = |v: f64| format!("{v:?}");
    if c.im == 0.0 {
        if c.re.is_sign_negative() {
            format!("({})", real(c.re))
        } else {
            real(c.re)
        }
    } else if c.re == 0.0 {
        format!("({}*{imaginary_unit})", real(c.im))
    } else {
        let sign = if c.im.is_sign_negative() { "-" } else { "+" };
        format!(
            "({}{sign}{}*{imaginary_unit})",
            real(c.re),
            real(c.im.abs())
        )
    }
}

/// Precedence levels for printing: sum < product < unary minus < power < atom.
pub(crate) fn write_expr(
    e: &Expr,
    out: &mut String,
    imaginary_unit: &str,
    names: &HashMap<usize, String>,
) {
    write_at(e, out, imaginary_unit, names, 0);
}

fn precedence(e: &Expr, names: &HashMap<usize, String>) -> u8 {
    if names.contains_key(&e.node_id()) {
        return 4;
    }
    match e.kind() {
        Kind::Constant(_) => 4,
        Kind::Symbol(_) => 4,
        Kind::Add(..) | Kind::Sub(..) => 0,
        Kind::Mul(..) => 1,
        Kind::Neg(_) => 2,
        Kind::Pow(..) => 3,
    }
}

fn write_at(
    e: &Expr,
    out: &mut String,
    imaginary_unit: &str,
    names: &HashMap<usize, String>,
    context: u8,
) {
    let own = precedence(e, names);
    let parenthesise = own < context;
    if parenthesise {
        out.push('(');
    }
    if let Some(name) = names.get(&e.node_id()) {
        out.push_str(name);
    } else {
        match e.kind() {
            Kind::Constant(c) => out.push_str(&format_constant(*c, imaginary_unit)),
            Kind::Symbol(name) => out.push_str(name),
            Kind::Add(a, b) => {
                write_at(a, out, imaginary_unit, names, 0);
                out.push_str(" + ");
                write_at(b, out, imaginary_unit, names, 1);
            }
            Kind::Sub(a, b) => {
                write_at(a, out, imaginary_unit, names, 0);
                out.push_str(" - ");
                write_at(b, out, imaginary_unit, names, 1);
            }
            Kind::Mul(a, b) => {
                write_at(a, out, imaginary_unit, names, 1);
                out.push('*');
                write_at(b, out, imaginary_unit, names, 3);
            }
            Kind::Neg(a) => {
                out.push('-');
                write_at(a, out, imaginary_unit, names, 3);
            }
            Kind::Pow(a, n) => {
                write_at(a, out, imaginary_unit, names, 4);
                out.push('^');
                out.push_str(&n.to_string());
            }
        }
    }
    if parenthesise {
        out.push(')');
    }
}

impl fmt::Display for Expr {
    /// Bertini-style infix text (`I` is the imaginary unit).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        write_expr(self, &mut out, "I", &HashMap::new());
        f.write_str(&out)
    }
}

impl fmt::Debug for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Expr {
        Expr::variable("x")
    }

    #[test]
    fn constructors_simplify_locally() {
        assert_eq!(x() + 0.0, x());
        assert_eq!(0.0 + x(), x());
        assert!((x() * 0.0).is_zero());
        assert_eq!(1.0 * x(), x());
        assert_eq!(-(-x()), x());
        assert_eq!(x() * x(), x().pow(2));
        assert_eq!(x().pow(2).pow(3), x().pow(6));
        assert_eq!(x().pow(1), x());
        assert!(x().pow(0).is_one());
        assert_eq!(
            (Expr::from(2.0) * 3.0).as_constant(),
            Some(C64::new(6.0, 0.0))
        );
        // c₁·(c₂·x) folds the constants; x·c puts the constant first.
        assert_eq!(2.0 * (3.0 * x()), 6.0 * x());
        assert_eq!(x() * 2.0, 2.0 * x());
        // a + (−b) is a − b, −(a − b) is b − a.
        let y = Expr::variable("y");
        assert_eq!(x() + (-&y), x() - &y);
        assert_eq!(-(x() - &y), &y - x());
        assert_ne!(x() - &y, &y - x());
    }

    #[test]
    fn display_parenthesises_by_precedence() {
        let y = Expr::variable("y");
        assert_eq!((x() + &y).pow(2).to_string(), "(x + y)^2");
        assert_eq!((x() - (&y - 1.0)).to_string(), "x - (y - 1.0)");
        assert_eq!((x() * -(&y)).to_string(), "-(x*y)");
        assert_eq!((x() * (&y + 1.0)).to_string(), "x*(y + 1.0)");
        assert_eq!(
            Expr::constant(C64::new(-1.5, 0.0)).pow(3).to_string(),
            "(-3.375)"
        );
        assert_eq!((x() + C64::new(0.5, -2.0)).to_string(), "x + (0.5-2.0*I)");
        assert_eq!((x() * -2.0).to_string(), "(-2.0)*x");
    }

    #[test]
    fn shared_subexpressions_are_evaluated_once_and_counted_once() {
        let s = (x() + 1.0).pow(3);
        let e = &s * &s + &s;
        // s·s becomes s², whose node shares s: nodes {e, s², s, x + 1, x, 1}.
        assert_eq!(e.node_count(), 6);
        let value = e.evaluate(|_| Some(C64::new(1.0, 0.0))).unwrap();
        assert_eq!(value, C64::new(64.0 + 8.0, 0.0));
        assert_eq!(e.evaluate(|_| None), Err("x".to_string()));
        assert_eq!(e.symbols(), vec!["x".to_string()]);
    }

    #[test]
    fn substitution_rebuilds_with_simplification() {
        let y = Expr::variable("y");
        let e = x() * &y + &y;
        let replaced = e.substitute(&|name| (name == "y").then(Expr::zero));
        assert!(replaced.is_zero());
    }
}
