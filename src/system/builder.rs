//! [`System`]: a list of polynomial equations `F(x; p) = 0` with named unknowns `x`
//! and named parameters `p`.

use crate::C64;
use crate::system::compile::CompiledSystem;
use crate::system::expr::Expr;
use crate::system::sparse::{self, SparsePolynomial};
use std::collections::{HashMap, HashSet};

/// Errors of building or using a [`System`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SystemError {
    /// An equation uses a name that is neither a variable nor a parameter.
    #[error(
        "equation {equation} uses the symbol `{symbol}`, which is neither a variable nor a parameter"
    )]
    UnknownSymbol {
        /// The unknown name.
        symbol: String,
        /// Index of the equation (0-based).
        equation: usize,
    },
    /// A name is listed twice (as variables, parameters, or both).
    #[error("the symbol `{0}` is declared more than once")]
    DuplicateSymbol(String),
    /// No equations.
    #[error("the system has no equations")]
    EmptySystem,
    /// No unknowns.
    #[error("the system has no variables")]
    NoVariables,
    /// A symbol name that is empty.
    #[error("a symbol name is empty")]
    EmptyName,
    /// An assignment of parameter values lacks a parameter.
    #[error("no value given for the parameter `{0}`")]
    MissingParameterValue(String),
    /// A value given for a name that is not a parameter.
    #[error("`{0}` is not a parameter of the system")]
    NotAParameter(String),
}

/// A polynomial system `F(x; p) = 0`: equations in the unknowns `variables` with
/// coefficients that are polynomials in `parameters`.
#[derive(Clone, Debug)]
pub struct System {
    variables: Vec<String>,
    parameters: Vec<String>,
    equations: Vec<Expr>,
    /// The unknown that homogenises some of the others ([`System::homogenizing`]).
    homogenizing: Option<usize>,
}

fn names(list: impl IntoIterator<Item = impl AsRef<str>>) -> Vec<String> {
    list.into_iter().map(|s| s.as_ref().to_string()).collect()
}

impl System {
    /// The system `equations = 0` in the unknowns `variables` with parameters
    /// `parameters`. Errors: a symbol of an equation that is in neither list, a name
    /// listed twice, no equations, no variables.
    pub fn new(
        variables: impl IntoIterator<Item = impl AsRef<str>>,
        parameters: impl IntoIterator<Item = impl AsRef<str>>,
        equations: Vec<Expr>,
    ) -> Result<System, SystemError> {
        let variables = names(variables);
        let parameters = names(parameters);
        if equations.is_empty() {
            return Err(SystemError::EmptySystem);
        }
        if variables.is_empty() {
            return Err(SystemError::NoVariables);
        }
        let mut declared = HashSet::new();
        for name in variables.iter().chain(parameters.iter()) {
            if name.is_empty() {
                return Err(SystemError::EmptyName);
            }
            if !declared.insert(name.as_str()) {
                return Err(SystemError::DuplicateSymbol(name.clone()));
            }
        }
        for (equation, f) in equations.iter().enumerate() {
            if let Some(symbol) = f
                .symbols()
                .into_iter()
                .find(|s| !declared.contains(s.as_str()))
            {
                return Err(SystemError::UnknownSymbol { symbol, equation });
            }
        }
        Ok(System {
            variables,
            parameters,
            equations,
            homogenizing: None,
        })
    }

    /// Declares unknown `variable` the homogenising coordinate of the system's affine
    /// chart: a solution with `variable = 0` lies at infinity of the affine system it
    /// was homogenised from (e.g. `λ₀` of the Fritz John form of Lagrange conditions),
    /// so the tracker classifies such an endpoint at infinity
    /// ([`crate::homotopy::Homotopy::homogenizing_variable`]). Error: no such unknown.
    pub fn with_homogenizing_variable(mut self, variable: &str) -> Result<System, SystemError> {
        let index = self
            .variables
            .iter()
            .position(|v| v == variable)
            .ok_or_else(|| SystemError::UnknownSymbol {
                symbol: variable.to_string(),
                equation: 0,
            })?;
        self.homogenizing = Some(index);
        Ok(self)
    }

    /// The homogenising unknown, if any ([`System::with_homogenizing_variable`]).
    pub fn homogenizing(&self) -> Option<usize> {
        self.homogenizing
    }

    /// The Lagrange system `∇_variables Λ = 0` of a Lagrangian `Λ` (the variable list
    /// includes the multipliers, so the system is square: one equation `∂Λ/∂v` per
    /// variable `v`, in the order of `variables`); see docs/theory.md §5.
    pub fn lagrange(
        lagrangian: &Expr,
        variables: impl IntoIterator<Item = impl AsRef<str>>,
        parameters: impl IntoIterator<Item = impl AsRef<str>>,
    ) -> Result<System, SystemError> {
        let variables = names(variables);
        let mut memo = HashMap::new();
        let equations = variables
            .iter()
            .map(|v| {
                memo.clear();
                lagrangian.differentiate_memo(v, &mut memo)
            })
            .collect();
        System::new(variables, parameters, equations)
    }

    /// Names of the unknowns, in the order of `x`.
    pub fn variables(&self) -> &[String] {
        &self.variables
    }

    /// Names of the parameters, in the order of `p`.
    pub fn parameters(&self) -> &[String] {
        &self.parameters
    }

    /// The equations `f_i` of `F = 0`.
    pub fn equations(&self) -> &[Expr] {
        &self.equations
    }

    /// Number of equations.
    pub fn num_equations(&self) -> usize {
        self.equations.len()
    }

    /// Variables followed by parameters (the symbol order of [`System::expand`]).
    pub fn symbols(&self) -> Vec<String> {
        self.variables
            .iter()
            .chain(self.parameters.iter())
            .cloned()
            .collect()
    }

    /// Each equation expanded into a sparse polynomial over [`System::symbols`]
    /// (variables, then parameters).
    pub fn expand(&self) -> Result<Vec<SparsePolynomial>, sparse::ExpansionError> {
        let symbols = self.symbols();
        self.equations
            .iter()
            .map(|f| sparse::expand(f, &symbols))
            .collect()
    }

    /// Total degree of each equation in the variables (parameters count as
    /// coefficients). Exact (from the expanded polynomial) when the expansion stays
    /// below [`sparse::MAX_TERMS`] terms, otherwise the structural upper bound. The zero
    /// polynomial has degree 0.
    pub fn degrees(&self) -> Vec<u64> {
        let n = self.variables.len();
        let symbols = self.symbols();
        let variable_set: HashSet<&str> = self.variables.iter().map(|s| s.as_str()).collect();
        self.equations
            .iter()
            .map(|f| match sparse::expand(f, &symbols) {
                Ok(polynomial) => polynomial.degree_in(|i| i < n).unwrap_or(0),
                Err(_) => sparse::degree_bound(f, &|s| variable_set.contains(s)),
            })
            .collect()
    }

    /// [`System::degrees`] from the system's expansion ([`System::expand`]), when the
    /// caller has it already.
    pub fn degrees_of_expansion(&self, expansion: &[SparsePolynomial]) -> Vec<u64> {
        let n = self.variables.len();
        expansion
            .iter()
            .map(|polynomial| polynomial.degree_in(|i| i < n).unwrap_or(0))
            .collect()
    }

    /// Bézout number `Π deg f_i` (saturating at `u128::MAX`): the number of isolated
    /// solutions in projective space of a generic system with these degrees, an upper
    /// bound of the finite isolated solutions of a square system.
    pub fn bezout_number(&self) -> u128 {
        self.degrees()
            .iter()
            .fold(1u128, |acc, &d| acc.saturating_mul(d as u128))
    }

    /// `F(x; p)` by walking the expressions (slow reference evaluator).
    ///
    /// # Panics
    /// If `x` or `p` do not have one value per variable / parameter (a programming
    /// error: the lengths are fixed by the system).
    pub fn evaluate_naive(&self, x: &[C64], p: &[C64]) -> Vec<C64> {
        assert_eq!(x.len(), self.variables.len(), "one value per variable");
        assert_eq!(p.len(), self.parameters.len(), "one value per parameter");
        let values: HashMap<&str, C64> = self
            .variables
            .iter()
            .map(|s| s.as_str())
            .zip(x.iter().copied())
            .chain(
                self.parameters
                    .iter()
                    .map(|s| s.as_str())
                    .zip(p.iter().copied()),
            )
            .collect();
        let lookup = |name: &str| values.get(name).copied();
        let mut memo = HashMap::new();
        self.equations
            .iter()
            .map(|f| {
                f.evaluate_memo(&lookup, &mut memo)
                    .unwrap_or(C64::new(f64::NAN, f64::NAN))
            })
            .collect()
    }

    /// `∂F/∂x` (row-major) by differentiating and walking the expressions (slow
    /// reference evaluator).
    pub fn jacobian_naive(&self, x: &[C64], p: &[C64]) -> Vec<C64> {
        self.derivative_naive(&self.variables, x, p)
    }

    /// `∂F/∂p` (row-major) by differentiating and walking the expressions.
    pub fn parameter_jacobian_naive(&self, x: &[C64], p: &[C64]) -> Vec<C64> {
        self.derivative_naive(&self.parameters, x, p)
    }

    fn derivative_naive(&self, wrt: &[String], x: &[C64], p: &[C64]) -> Vec<C64> {
        let columns: Vec<System> = wrt
            .iter()
            .map(|s| System {
                variables: self.variables.clone(),
                parameters: self.parameters.clone(),
                equations: self.equations.iter().map(|f| f.differentiate(s)).collect(),
                homogenizing: self.homogenizing,
            })
            .collect();
        let values: Vec<Vec<C64>> = columns.iter().map(|c| c.evaluate_naive(x, p)).collect();
        let mut out = Vec::with_capacity(self.equations.len() * wrt.len());
        for i in 0..self.equations.len() {
            for column in &values {
                out.push(column[i]);
            }
        }
        out
    }

    /// The system with the parameters replaced by numbers (`values` by parameter name;
    /// every parameter needs a value). The result has no parameters.
    pub fn with_parameter_values(&self, values: &[(String, C64)]) -> Result<System, SystemError> {
        let map: HashMap<&str, C64> = values.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        for (name, _) in values {
            if !self.parameters.contains(name) {
                return Err(SystemError::NotAParameter(name.clone()));
            }
        }
        for name in &self.parameters {
            if !map.contains_key(name.as_str()) {
                return Err(SystemError::MissingParameterValue(name.clone()));
            }
        }
        let substitute = |name: &str| map.get(name).map(|&v| Expr::constant(v));
        Ok(System {
            variables: self.variables.clone(),
            parameters: Vec::new(),
            equations: self
                .equations
                .iter()
                .map(|f| f.substitute(&substitute))
                .collect(),
            homogenizing: self.homogenizing,
        })
    }

    /// Compiles the system to straight-line programs for fast evaluation of F, ∂F/∂x,
    /// ∂F/∂p and (∂F/∂p)·dp (see [`crate::system::compile`]).
    pub fn compile(&self) -> CompiledSystem {
        CompiledSystem::new(self)
    }
}
