//! Expansion of expressions into sparse polynomials (monomial → coefficient), used for
//! exact degrees, Bézout numbers and the PHCpack export.

use crate::C64;
use crate::system::expr::{Expr, Kind};
use std::collections::{BTreeMap, HashMap};

/// Largest number of terms an expansion may reach before it is abandoned.
pub const MAX_TERMS: usize = 200_000;

/// A polynomial `Σ c_α s^α` over an ordered list of symbols; the key is the exponent
/// vector α (one entry per symbol). Terms with a zero coefficient are never stored.
#[derive(Clone, Debug, PartialEq)]
pub struct SparsePolynomial {
    /// Monomial exponent vector → coefficient.
    pub terms: BTreeMap<Vec<u32>, C64>,
}

/// Why an expansion failed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ExpansionError {
    /// A symbol outside the given symbol list.
    #[error("unknown symbol `{0}`")]
    UnknownSymbol(String),
    /// The expansion exceeded [`MAX_TERMS`] terms or an exponent overflowed `u32`.
    #[error(
        "the expanded polynomial is too large (more than {MAX_TERMS} terms or degree above 2^32)"
    )]
    TooLarge,
}

impl SparsePolynomial {
    fn constant(value: C64, num_symbols: usize) -> SparsePolynomial {
        let mut terms = BTreeMap::new();
        if value != C64::new(0.0, 0.0) {
            terms.insert(vec![0; num_symbols], value);
        }
        SparsePolynomial { terms }
    }

    fn add_scaled(&self, other: &SparsePolynomial, scale: f64) -> SparsePolynomial {
        let mut terms = self.terms.clone();
        for (monomial, &c) in &other.terms {
            let entry = terms.entry(monomial.clone()).or_insert(C64::new(0.0, 0.0));
            *entry += c * scale;
            if *entry == C64::new(0.0, 0.0) {
                terms.remove(monomial);
            }
        }
        SparsePolynomial { terms }
    }

    fn multiply(&self, other: &SparsePolynomial) -> Result<SparsePolynomial, ExpansionError> {
        if self.terms.len().saturating_mul(other.terms.len()) > MAX_TERMS * 8 {
            return Err(ExpansionError::TooLarge);
        }
        let mut terms: BTreeMap<Vec<u32>, C64> = BTreeMap::new();
        for (ma, &ca) in &self.terms {
            for (mb, &cb) in &other.terms {
                let mut monomial = Vec::with_capacity(ma.len());
                for (ea, eb) in ma.iter().zip(mb) {
                    monomial.push(ea.checked_add(*eb).ok_or(ExpansionError::TooLarge)?);
                }
                *terms.entry(monomial).or_insert(C64::new(0.0, 0.0)) += ca * cb;
            }
        }
        terms.retain(|_, c| *c != C64::new(0.0, 0.0));
        if terms.len() > MAX_TERMS {
            return Err(ExpansionError::TooLarge);
        }
        Ok(SparsePolynomial { terms })
    }

    fn power(&self, exponent: u32, num_symbols: usize) -> Result<SparsePolynomial, ExpansionError> {
        if self.terms.len() == 1 {
            // A monomial: multiply the exponents.
            let (monomial, &c) = self.terms.iter().next().ok_or(ExpansionError::TooLarge)?;
            let mut powered = Vec::with_capacity(monomial.len());
            for e in monomial {
                powered.push(e.checked_mul(exponent).ok_or(ExpansionError::TooLarge)?);
            }
            let mut terms = BTreeMap::new();
            let value = c.powu(exponent);
            if value != C64::new(0.0, 0.0) {
                terms.insert(powered, value);
            }
            return Ok(SparsePolynomial { terms });
        }
        let mut result = SparsePolynomial::constant(C64::new(1.0, 0.0), num_symbols);
        let mut base = self.clone();
        let mut e = exponent;
        while e > 0 {
            if e & 1 == 1 {
                result = result.multiply(&base)?;
            }
            e >>= 1;
            if e > 0 {
                base = base.multiply(&base)?;
            }
        }
        Ok(result)
    }

    /// Total degree in the symbols whose indices satisfy `counted`; `None` for the zero
    /// polynomial.
    pub fn degree_in(&self, counted: impl Fn(usize) -> bool) -> Option<u64> {
        self.terms
            .keys()
            .map(|m| {
                m.iter()
                    .enumerate()
                    .filter(|(i, _)| counted(*i))
                    .map(|(_, &e)| e as u64)
                    .sum()
            })
            .max()
    }
}

/// Expands `e` over `symbols` (every symbol of `e` must be in the list).
pub fn expand(e: &Expr, symbols: &[String]) -> Result<SparsePolynomial, ExpansionError> {
    let index: HashMap<&str, usize> = symbols
        .iter()
        .enumerate()
        .map(|(i, s)| (s.as_str(), i))
        .collect();
    let mut memo = HashMap::new();
    expand_memo(e, &index, symbols.len(), &mut memo)
}

fn expand_memo(
    e: &Expr,
    index: &HashMap<&str, usize>,
    num_symbols: usize,
    memo: &mut HashMap<usize, SparsePolynomial>,
) -> Result<SparsePolynomial, ExpansionError> {
    if let Some(done) = memo.get(&e.node_id()) {
        return Ok(done.clone());
    }
    let result = match e.kind() {
        Kind::Constant(c) => SparsePolynomial::constant(*c, num_symbols),
        Kind::Symbol(name) => {
            let i = *index
                .get(&**name)
                .ok_or_else(|| ExpansionError::UnknownSymbol(name.to_string()))?;
            let mut monomial = vec![0; num_symbols];
            monomial[i] = 1;
            let mut terms = BTreeMap::new();
            terms.insert(monomial, C64::new(1.0, 0.0));
            SparsePolynomial { terms }
        }
        Kind::Add(a, b) => expand_memo(a, index, num_symbols, memo)?
            .add_scaled(&expand_memo(b, index, num_symbols, memo)?, 1.0),
        Kind::Sub(a, b) => expand_memo(a, index, num_symbols, memo)?
            .add_scaled(&expand_memo(b, index, num_symbols, memo)?, -1.0),
        Kind::Mul(a, b) => expand_memo(a, index, num_symbols, memo)?.multiply(&expand_memo(
            b,
            index,
            num_symbols,
            memo,
        )?)?,
        Kind::Neg(a) => SparsePolynomial::constant(C64::new(0.0, 0.0), num_symbols)
            .add_scaled(&expand_memo(a, index, num_symbols, memo)?, -1.0),
        Kind::Pow(a, n) => expand_memo(a, index, num_symbols, memo)?.power(*n, num_symbols)?,
    };
    if result.terms.len() > MAX_TERMS {
        return Err(ExpansionError::TooLarge);
    }
    memo.insert(e.node_id(), result.clone());
    Ok(result)
}

/// Upper bound of the total degree of `e` in the symbols for which `counted` holds,
/// read off the expression structure (no expansion, so cancellations are not seen).
pub fn degree_bound(e: &Expr, counted: &dyn Fn(&str) -> bool) -> u64 {
    let mut memo = HashMap::new();
    degree_bound_memo(e, counted, &mut memo)
}

fn degree_bound_memo(
    e: &Expr,
    counted: &dyn Fn(&str) -> bool,
    memo: &mut HashMap<usize, u64>,
) -> u64 {
    if let Some(&d) = memo.get(&e.node_id()) {
        return d;
    }
    let d = match e.kind() {
        Kind::Constant(_) => 0,
        Kind::Symbol(name) => u64::from(counted(name)),
        Kind::Add(a, b) | Kind::Sub(a, b) => {
            degree_bound_memo(a, counted, memo).max(degree_bound_memo(b, counted, memo))
        }
        Kind::Mul(a, b) => {
            degree_bound_memo(a, counted, memo).saturating_add(degree_bound_memo(b, counted, memo))
        }
        Kind::Neg(a) => degree_bound_memo(a, counted, memo),
        Kind::Pow(a, n) => degree_bound_memo(a, counted, memo).saturating_mul(*n as u64),
    };
    memo.insert(e.node_id(), d);
    d
}
