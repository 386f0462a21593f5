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
//! The exponents are divided by the least positive one (`e = g / g_min`, so the least
//! positive power is 1) and the path is followed in logarithmic time: the tracker's
//! parameter `τ ∈ [0, 1]` stands for `t = exp(−L(1 − τ))` with [`LOG_RANGE`] `= L`,
//! so `t^e = exp(−eL(1 − τ))`. At `τ = 0` every term off the cell's pair is below
//! `e^{−L} ≈ 2·10⁻¹⁶` relative, so the binomial roots are the path's start to rounding
//! level; a term of power e switches on near `1 − τ ≈ 1/(eL)`, so terms of different
//! powers come in one after another over `[0, 1]` instead of crowding at `t = 0` (where
//! fractional powers have unbounded derivatives) and near `t = 1` (where high powers
//! switch on abruptly). `exp` is entire, so complex `τ` (the endgame's circles) needs no
//! branch of the logarithm. This is the logarithmic parametrisation used for
//! polyhedral homotopies by HomotopyContinuation.jl (Breiding and Timme,
//! "HomotopyContinuation.jl: a package for homotopy continuation in Julia", ICMS 2018).

use super::random_system::RandomCoefficientSystem;
use crate::C64;
use crate::homotopy::Homotopy;
use crate::system::Evaluator;

/// `H_i(y, τ) = Σ_a c_{ia} y^a exp(−e_{ia}L(1 − τ))` of one mixed cell.
#[derive(Clone, Debug)]
pub struct CellHomotopy<'a> {
    system: &'a RandomCoefficientSystem,
    /// `e_{ia}` in term order.
    powers: Vec<f64>,
}

/// Workspace entries ahead of the parameters: the homotopy and the `τ` they were
/// filled for ([`CellHomotopy::parameters`]).
const CACHE_SLOTS: usize = 2;

/// `L`: the path parameter `τ ∈ [0, 1]` stands for `t = exp(−L(1 − τ))`.
pub const LOG_RANGE: f64 = 36.0;

/// `(t^e, d(t^e)/dτ)` at `t = exp(−L(1 − τ))`: `(exp(−eL(1 − τ)), eL·t^e)`.
fn power_and_derivative(tau: C64, e: f64) -> (C64, C64) {
    if e == 0.0 {
        return (C64::new(1.0, 0.0), C64::new(0.0, 0.0));
    }
    let rate = e * LOG_RANGE;
    let value = if tau.im == 0.0 {
        C64::new((-rate * (1.0 - tau.re)).exp(), 0.0)
    } else {
        ((C64::new(1.0, 0.0) - tau) * -rate).exp()
    };
    (value, value * rate)
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

    /// Splits the workspace into the term family's parameters `c ⊙ t^e`, their
    /// τ-derivatives `c ⊙ eL·t^e` (filled at `tau`), and the family's scratch.
    ///
    /// The first [`CACHE_SLOTS`] entries remember for which homotopy and which `tau`
    /// the parameters were last filled: a predictor–corrector step evaluates several
    /// times at one `τ` (the two midpoint stages of Runge–Kutta, the last stage and
    /// the corrector's iterations), and each filling costs one `exp` per term.
    fn parameters<'w>(
        &self,
        tau: C64,
        work: &'w mut [C64],
    ) -> (&'w [C64], &'w [C64], &'w mut [C64]) {
        let count = self.powers.len();
        let (cache, work) = work.split_at_mut(CACHE_SLOTS);
        let (values, rest) = work.split_at_mut(count);
        let (derivatives, scratch) = rest.split_at_mut(count);
        // Which homotopy filled the parameters: the address of its powers, and their
        // number (a fresh, zeroed workspace matches no homotopy).
        let owner = C64::new(self.powers.as_ptr() as usize as f64, count as f64 + 1.0);
        let at = |z: C64| (z.re.to_bits(), z.im.to_bits());
        if at(cache[0]) == at(owner) && at(cache[1]) == at(tau) {
            return (values, derivatives, scratch);
        }
        cache[0] = owner;
        cache[1] = tau;
        let coefficients = self.system.coefficients();
        for t in 0..count {
            let (power, power_derivative) = power_and_derivative(tau, self.powers[t]);
            values[t] = coefficients[t] * power;
            derivatives[t] = coefficients[t] * power_derivative;
        }
        (values, derivatives, scratch)
    }
}

impl Homotopy for CellHomotopy<'_> {
    fn dimension(&self) -> usize {
        self.system.terms().num_variables()
    }

    fn workspace_len(&self) -> usize {
        CACHE_SLOTS + 2 * self.powers.len() + self.system.family().workspace_len()
    }

    fn evaluate(&self, x: &[C64], t: C64, work: &mut [C64], h: &mut [C64]) {
        let (values, _, scratch) = self.parameters(t, work);
        self.system.family().evaluate(x, values, scratch, h);
    }

    fn evaluate_with_jacobian(
        &self,
        x: &[C64],
        t: C64,
        work: &mut [C64],
        h: &mut [C64],
        jac: &mut [C64],
    ) {
        let (values, _, scratch) = self.parameters(t, work);
        self.system
            .family()
            .evaluate_with_jacobian(x, values, scratch, h, jac);
    }

    fn evaluate_time_derivative(&self, x: &[C64], t: C64, work: &mut [C64], dh: &mut [C64]) {
        // G is linear in its parameters: ∂H/∂τ = G(x; c ⊙ eL·t^e).
        let (_, derivatives, scratch) = self.parameters(t, work);
        self.system.family().evaluate(x, derivatives, scratch, dh);
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
        let (values, derivatives, scratch) = self.parameters(t, work);
        let family = self.system.family();
        family.evaluate_with_jacobian(x, values, scratch, h, jac);
        family.evaluate(x, derivatives, scratch, dh);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::polyhedral::{PolyhedralStartSystem, Supports};

    /// `x²y + 3xy² − 1`, `x³ − y + 2` style supports: two equations, mixed volume > 1.
    fn start_system() -> PolyhedralStartSystem {
        let supports = Supports::new(
            2,
            vec![
                vec![vec![2, 1], vec![1, 2], vec![0, 0]],
                vec![vec![3, 0], vec![0, 1], vec![0, 0], vec![1, 1]],
            ],
        );
        PolyhedralStartSystem::new(&supports, 11).unwrap()
    }

    /// The remembered parameters are those of the homotopy and the `τ` asked for: two
    /// cells evaluated in turn on one workspace, at one `τ` and then another, give what
    /// each gives on a fresh workspace.
    #[test]
    fn a_shared_workspace_gives_what_a_fresh_one_gives() {
        let start = start_system();
        let cells: Vec<_> = (0..start.subdivision().cells.len())
            .map(|c| start.cell_homotopy(c))
            .collect();
        assert!(cells.len() >= 2, "{} cells", cells.len());
        let n = cells[0].dimension();
        let len = cells.iter().map(|h| h.workspace_len()).max().unwrap();
        let x = vec![C64::new(0.7, -0.3); n];
        let fresh = |h: &CellHomotopy, tau: C64| {
            let mut work = vec![C64::new(0.0, 0.0); len];
            let mut value = vec![C64::new(0.0, 0.0); n];
            h.evaluate(&x, tau, &mut work, &mut value);
            value
        };
        let mut shared = vec![C64::new(0.0, 0.0); len];
        for tau in [C64::new(0.0, 0.0), C64::new(0.6, 0.0), C64::new(0.6, 0.1)] {
            for h in cells.iter().chain(cells.iter().rev()) {
                let mut value = vec![C64::new(0.0, 0.0); n];
                h.evaluate(&x, tau, &mut shared, &mut value);
                assert_eq!(value, fresh(h, tau), "τ = {tau}");
            }
        }
    }

    #[test]
    fn start_points_are_roots_at_log_time_zero_and_derivatives_match_differences() {
        let start = start_system();
        let mut checked = 0;
        for index in 0..start.mixed_volume() as u64 {
            let (c, _) = start.locate(index);
            let h = start.cell_homotopy(c);
            let n = h.dimension();
            let mut work = vec![C64::new(0.0, 0.0); h.workspace_len()];
            let mut y = vec![C64::new(0.0, 0.0); n];
            start.start_solution(index, &mut y);
            let mut value = vec![C64::new(0.0, 0.0); n];
            h.evaluate(&y, C64::new(0.0, 0.0), &mut work, &mut value);
            let scale = 1.0 + y.iter().map(|v| v.norm()).fold(0.0, f64::max);
            for v in &value {
                assert!(v.norm() < 1e-12 * scale.powi(4), "residual {v} at τ = 0");
            }
            // Derivatives at an interior complex point against central differences.
            let tau = C64::new(0.8, 0.01);
            let x: Vec<C64> = y.iter().map(|v| v * C64::new(1.1, -0.2)).collect();
            let (mut jac, mut dh) = (vec![C64::new(0.0, 0.0); n * n], vec![C64::new(0.0, 0.0); n]);
            h.evaluate_with_jacobian_and_time_derivative(
                &x, tau, &mut work, &mut value, &mut jac, &mut dh,
            );
            let step = 1e-6;
            let (mut plus, mut minus) = (vec![C64::new(0.0, 0.0); n], vec![C64::new(0.0, 0.0); n]);
            h.evaluate(&x, tau + step, &mut work, &mut plus);
            h.evaluate(&x, tau - step, &mut work, &mut minus);
            for i in 0..n {
                let difference = (plus[i] - minus[i]) / (2.0 * step);
                assert!((difference - dh[i]).norm() <= 1e-5 * (1.0 + dh[i].norm()));
            }
            for j in 0..n {
                let mut shifted = x.clone();
                shifted[j] += step;
                h.evaluate(&shifted, tau, &mut work, &mut plus);
                shifted[j] -= 2.0 * step;
                h.evaluate(&shifted, tau, &mut work, &mut minus);
                for i in 0..n {
                    let difference = (plus[i] - minus[i]) / (2.0 * step);
                    let exact = jac[i * n + j];
                    assert!((difference - exact).norm() <= 1e-5 * (1.0 + exact.norm()));
                }
            }
            checked += 1;
        }
        assert!(checked >= 2, "mixed volume {}", start.mixed_volume());
    }
}
