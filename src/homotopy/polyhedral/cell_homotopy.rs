//! The polyhedral homotopy of one mixed cell.
//!
//! With the lifting ω, `Q̂_i(x, t) = Σ_{a ∈ A_i} c_{ia} x^a t^{ω_i(a)}` joins the binomial
//! systems at `t = 0` to the random-coefficient system `Q` at `t = 1`. For a mixed cell
//! with inner normal `(α, 1)` and `β_i = min_a (⟨a, α⟩ + ω_i(a))`, the substitution
//! `x = t^α y` and division of equation i by `t^{β_i}` give
//! `H_i(y, t) = Σ_a c_{ia} y^a t^{g_{ia}}`, `g_{ia} = ⟨a, α⟩ + ω_i(a) − β_i ≥ 0`, zero
//! exactly on the cell's pair: at `t = 0` it is the cell's binomial system, whose
//! `|det|` roots start as many paths; at `t = 1`, `y = x` is a root of `Q` (Huber and
//! Sturmfels, "A polyhedral method for solving sparse polynomial systems", Math.
//! Comp. 1995, §3; Verschelde, Verlinden and Cools, "Homotopies exploiting Newton
//! polytopes for solving sparse polynomial systems", SIAM J. Numer. Anal. 1994).
//! The roots of all cells are all the roots of `Q`, each once.
//!
//! The exponents are divided by the least positive one, `t = s^{1/g_min}`
//! (`H_i = Σ_a c_{ia} y^a s^{e_{ia}}`, `e = g / g_min`), so that the smallest power of
//! the path parameter is 1 and `∂H/∂s` is finite at `s = 0`, where the paths start.
//! Powers `s^e = exp(e log s)` use the principal logarithm (the tracker moves on
//! `[0, 1]` and on small circles around 1).

use super::random_system::RandomCoefficientSystem;
use crate::C64;
use crate::homotopy::Homotopy;

/// `H_i(y, s) = Σ_a c_{ia} y^a s^{e_{ia}}` of one mixed cell.
#[derive(Clone, Debug)]
pub struct CellHomotopy<'a> {
    system: &'a RandomCoefficientSystem,
    /// `e_{ia}` in term order.
    powers: Vec<f64>,
}

/// `(s^e, d(s^e)/ds)`, with `0^0 = 1`.
fn power_and_derivative(s: C64, log_s: C64, e: f64) -> (C64, C64) {
    let zero = C64::new(0.0, 0.0);
    let one = C64::new(1.0, 0.0);
    if e == 0.0 {
        return (one, zero);
    }
    if s == zero {
        return (zero, if e == 1.0 { one } else { zero });
    }
    if s.im == 0.0 && s.re > 0.0 {
        // The tracker's real segment: a real power.
        let value = s.re.powf(e);
        return (C64::new(value, 0.0), C64::new(value * e / s.re, 0.0));
    }
    let value = (log_s * e).exp();
    (value, value * e / s)
}

impl<'a> CellHomotopy<'a> {
    /// The homotopy of the cell with gaps `gaps` (`D·g_{ia}` in term order, any common
    /// positive factor D, at least one of them positive).
    pub fn new(system: &'a RandomCoefficientSystem, gaps: &[i128]) -> Self {
        assert_eq!(gaps.len(), system.terms().num_terms());
        let least = gaps.iter().copied().filter(|&g| g > 0).min().unwrap_or(1);
        let powers = gaps.iter().map(|&g| g as f64 / least as f64).collect();
        CellHomotopy { system, powers }
    }

    /// The exponents `e_{ia}` of s in term order.
    pub fn powers(&self) -> &[f64] {
        &self.powers
    }

    /// `h ← H`, and with `jac` the Jacobian, with `dh` the s-derivative.
    fn evaluate_all(
        &self,
        x: &[C64],
        s: C64,
        work: &mut [C64],
        h: &mut [C64],
        mut jac: Option<&mut [C64]>,
        mut dh: Option<&mut [C64]>,
    ) {
        let terms = self.system.terms();
        let n = terms.num_variables();
        let coefficients = self.system.coefficients();
        let log_s = if s == C64::new(0.0, 0.0) { s } else { s.ln() };
        let (table, scratch) = terms.tabulate(x, work);
        if let Some(jac) = jac.as_deref_mut() {
            jac.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        }
        for i in 0..n {
            let mut value = C64::new(0.0, 0.0);
            let mut derivative = C64::new(0.0, 0.0);
            for t in terms.equation(i) {
                let (power, power_derivative) = power_and_derivative(s, log_s, self.powers[t]);
                let c = coefficients[t];
                let monomial = match jac.as_deref_mut() {
                    Some(jac) => terms.value_and_gradient(
                        t,
                        table,
                        scratch,
                        c * power,
                        &mut jac[i * n..(i + 1) * n],
                    ),
                    None => terms.value(t, table),
                };
                value += c * power * monomial;
                derivative += c * power_derivative * monomial;
            }
            h[i] = value;
            if let Some(dh) = dh.as_deref_mut() {
                dh[i] = derivative;
            }
        }
    }
}

impl Homotopy for CellHomotopy<'_> {
    fn dimension(&self) -> usize {
        self.system.terms().num_variables()
    }

    fn workspace_len(&self) -> usize {
        self.dimension() + self.system.terms().workspace_len()
    }

    fn evaluate(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        self.evaluate_all(x, t, work, h, None, None);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
    ) {
        self.evaluate_all(x, t, work, h, Some(jac), None);
    }

    fn evaluate_time_derivative(&self, x: &[C64], t: C64, work: &mut [C64], dh: &mut [C64]) {
        let n = self.dimension();
        // H itself is not wanted: it goes to the head of the scratch.
        let (value, rest) = work.split_at_mut(n);
        self.evaluate_all(x, t, rest, value, None, Some(dh));
    }

    fn evaluate_with_jacobian_and_time_derivative(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
        dh: &mut [C64],
    ) {
        self.evaluate_all(x, t, work, h, Some(jac), Some(dh));
    }
}
