//! Local constrained refinement: projected BFGS ascent with finite-difference gradients.
//!
//! Farias Filho et al. (2021) refine the GA's best individual with SQP. Our constraints
//! are bounds only, for which SQP reduces to maximising a quadratic model over the box;
//! we use the compact active-set form of that idea (as in L-BFGS-B, without the limited
//! memory):
//!
//! 1. variables are scaled to `u_j = (x_j − lo_j)/(hi_j − lo_j) ∈ [0, 1]` (zero-width
//!    intervals are frozen);
//! 2. the gradient `g` is a central difference of step `gradient_step` (one-sided at a bound);
//! 3. a variable is *active* when it sits on a bound and `g` points out of the box; the
//!    ascent direction is `d = H g` on the free variables (`H` the BFGS approximation of
//!    the inverse of the negative Hessian), `d_j = 0` on the active ones;
//! 4. the step `u⁺ = P(u + t d)` (P the projection on the box) is accepted by the projected
//!    Armijo rule `f(u⁺) ≥ f(u) + c₁ gᵀ(u⁺ − u)`, halving t; on failure H is reset to the
//!    identity once before stopping;
//! 5. BFGS update of H with `s = u⁺ − u`, `y = g(u) − g(u⁺)` when `sᵀy > 0`.
//!
//! Stops when the projected gradient's ∞-norm falls below `tolerance`, when no ascent step
//! is found, or after `max_iterations`. The returned value is never below the start value.
//! No dependency was added: the crates with bounded local solvers (`cobyla`: derivative-free;
//! `argmin`: no bound constraints for its quasi-Newton methods) do not fit better.

use super::{OptimizeError, sanitize, validate_bounds};

/// Options of [`local_maximize`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LocalOptions {
    /// Maximum number of quasi-Newton iterations.
    pub max_iterations: usize,
    /// Finite-difference step in scaled units (fraction of each variable's range).
    pub gradient_step: f64,
    /// Stop when the projected gradient's ∞-norm (scaled units) is below this.
    pub tolerance: f64,
    /// Longest first trial step, ∞-norm in scaled units.
    pub max_step: f64,
}

impl Default for LocalOptions {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            gradient_step: 1e-6,
            tolerance: 1e-8,
            max_step: 0.25,
        }
    }
}

/// Result of [`local_maximize`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LocalResult {
    /// Best point found.
    pub best: Vec<f64>,
    /// Objective at `best` (≥ objective at the start point).
    pub best_value: f64,
    /// Iterations performed.
    pub iterations: usize,
    /// Objective evaluations.
    pub evaluations: usize,
    /// True when the projected-gradient test was met.
    pub converged: bool,
}

/// Maximise `objective` over the box from `start` by projected BFGS (module doc).
pub fn local_maximize<F>(
    objective: F,
    bounds: &[(f64, f64)],
    start: &[f64],
    options: &LocalOptions,
) -> Result<LocalResult, OptimizeError>
where
    F: Fn(&[f64]) -> f64,
{
    validate_bounds(bounds)?;
    let n = bounds.len();
    if start.len() != n || start.iter().any(|v| !v.is_finite()) {
        return Err(OptimizeError::InvalidStart {
            field: "start",
            reason: format!("must have {n} finite values"),
        });
    }
    let bad = |field: &'static str, value: f64| OptimizeError::InvalidOption {
        field,
        reason: format!("{value} must be finite and > 0"),
    };
    if !(options.gradient_step.is_finite() && options.gradient_step > 0.0) {
        return Err(bad("gradient_step", options.gradient_step));
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(bad("tolerance", options.tolerance));
    }
    if !(options.max_step.is_finite() && options.max_step > 0.0) {
        return Err(bad("max_step", options.max_step));
    }

    let mut scaled = Scaled {
        bounds,
        range: bounds.iter().map(|&(lo, hi)| hi - lo).collect(),
        point: vec![0.0; n],
        probe: vec![0.0; n],
        evaluations: 0,
        step: options.gradient_step,
    };
    let mut u: Vec<f64> = (0..n)
        .map(|j| {
            if scaled.frozen(j) {
                0.0
            } else {
                ((start[j] - bounds[j].0) / scaled.range[j]).clamp(0.0, 1.0)
            }
        })
        .collect();
    let mut value = scaled.eval(&objective, &u);
    let mut gradient = vec![0.0; n];
    let mut new_gradient = vec![0.0; n];
    let mut direction = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut active = vec![false; n];
    let mut h_inv = identity(n);
    let mut iterations = 0;
    let mut converged = false;
    if value.is_finite() {
        scaled.gradient(&objective, &u, value, &mut gradient);
    }

    while value.is_finite() && iterations < options.max_iterations {
        iterations += 1;
        // Active set and projected gradient.
        for j in 0..n {
            active[j] = scaled.frozen(j)
                || (u[j] <= 0.0 && gradient[j] < 0.0)
                || (u[j] >= 1.0 && gradient[j] > 0.0);
        }
        let projected_norm = (0..n)
            .filter(|&j| !active[j])
            .map(|j| gradient[j].abs())
            .fold(0.0, f64::max);
        if projected_norm < options.tolerance {
            converged = true;
            break;
        }
        let mut accepted = false;
        for attempt in 0..2 {
            if attempt == 1 {
                h_inv = identity(n);
            }
            for j in 0..n {
                direction[j] = if active[j] {
                    0.0
                } else {
                    (0..n)
                        .filter(|&k| !active[k])
                        .map(|k| h_inv[j * n + k] * gradient[k])
                        .sum()
                };
            }
            let slope: f64 = (0..n).map(|j| direction[j] * gradient[j]).sum();
            if slope.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                h_inv = identity(n);
                continue;
            }
            let longest = direction.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            let mut t = if longest > options.max_step {
                options.max_step / longest
            } else {
                1.0
            };
            for _ in 0..40 {
                for j in 0..n {
                    trial[j] = (u[j] + t * direction[j]).clamp(0.0, 1.0);
                }
                let gain: f64 = (0..n).map(|j| gradient[j] * (trial[j] - u[j])).sum();
                let trial_value = scaled.eval(&objective, &trial);
                if trial_value > value && trial_value >= value + 1e-4 * gain {
                    accepted = true;
                    scaled.gradient(&objective, &trial, trial_value, &mut new_gradient);
                    bfgs_update(&mut h_inv, &u, &trial, &gradient, &new_gradient, n);
                    u.copy_from_slice(&trial);
                    gradient.copy_from_slice(&new_gradient);
                    value = trial_value;
                    break;
                }
                t *= 0.5;
            }
            if accepted {
                break;
            }
        }
        if !accepted {
            break;
        }
    }
    let best: Vec<f64> = (0..n)
        .map(|j| bounds[j].0 + u[j] * scaled.range[j])
        .collect();
    Ok(LocalResult {
        best,
        best_value: value,
        iterations,
        evaluations: scaled.evaluations,
        converged,
    })
}

/// Objective in scaled coordinates `u ∈ [0,1]ⁿ`, with evaluation buffers and counter.
struct Scaled<'a> {
    bounds: &'a [(f64, f64)],
    range: Vec<f64>,
    point: Vec<f64>,
    probe: Vec<f64>,
    evaluations: usize,
    step: f64,
}

impl Scaled<'_> {
    fn frozen(&self, j: usize) -> bool {
        self.range[j] <= 0.0
    }

    fn eval<F: Fn(&[f64]) -> f64>(&mut self, objective: &F, u: &[f64]) -> f64 {
        for (j, x) in self.point.iter_mut().enumerate() {
            *x = self.bounds[j].0 + u[j] * self.range[j];
        }
        self.evaluations += 1;
        sanitize(objective(&self.point))
    }

    /// Central differences (one-sided on a bound) of step `self.step` in scaled units.
    fn gradient<F: Fn(&[f64]) -> f64>(
        &mut self,
        objective: &F,
        u: &[f64],
        value: f64,
        out: &mut [f64],
    ) {
        let mut probe = std::mem::take(&mut self.probe);
        probe.copy_from_slice(u);
        for j in 0..u.len() {
            if self.frozen(j) {
                out[j] = 0.0;
                continue;
            }
            let up = (u[j] + self.step).min(1.0);
            let down = (u[j] - self.step).max(0.0);
            probe[j] = up;
            let f_up = if up > u[j] {
                self.eval(objective, &probe)
            } else {
                value
            };
            probe[j] = down;
            let f_down = if down < u[j] {
                self.eval(objective, &probe)
            } else {
                value
            };
            probe[j] = u[j];
            let g = (f_up - f_down) / (up - down);
            out[j] = if g.is_finite() { g } else { 0.0 };
        }
        self.probe = probe;
    }
}

fn identity(n: usize) -> Vec<f64> {
    let mut m = vec![0.0; n * n];
    for j in 0..n {
        m[j * n + j] = 1.0;
    }
    m
}

/// BFGS update of the inverse-Hessian approximation of `−f` (row-major `n×n`):
/// `H ← (I − ρ s yᵀ) H (I − ρ y sᵀ) + ρ s sᵀ`, `s = u⁺ − u`, `y = g − g⁺`, `ρ = 1/(yᵀs)`;
/// skipped when the curvature `yᵀs` is not positive.
fn bfgs_update(h: &mut [f64], u: &[f64], u_new: &[f64], g: &[f64], g_new: &[f64], n: usize) {
    let s: Vec<f64> = (0..n).map(|j| u_new[j] - u[j]).collect();
    let y: Vec<f64> = (0..n).map(|j| g[j] - g_new[j]).collect();
    let sy: f64 = (0..n).map(|j| s[j] * y[j]).sum();
    let s_norm: f64 = s.iter().map(|v| v * v).sum::<f64>().sqrt();
    let y_norm: f64 = y.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !sy.is_finite() || sy <= 1e-12 * s_norm * y_norm {
        return;
    }
    let rho = 1.0 / sy;
    let hy: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|k| h[i * n + k] * y[k]).sum())
        .collect();
    let yhy: f64 = (0..n).map(|i| y[i] * hy[i]).sum();
    for i in 0..n {
        for k in 0..n {
            h[i * n + k] +=
                -rho * (hy[i] * s[k] + s[i] * hy[k]) + (rho * rho * yhy + rho) * s[i] * s[k];
        }
    }
}
