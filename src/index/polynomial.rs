//! Roots of real univariate polynomials, for the indices that reduce to one: the
//! half-angle polynomial of `S(φ)` at a fixed position and the quartic of the
//! position singularity distance.

use crate::C64;
use std::f64::consts::TAU;

/// Trims leading coefficients (ascending order) below `relative · max |c|`.
pub(crate) fn trimmed(coefficients: &[f64], relative: f64) -> Vec<f64> {
    let max = coefficients.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    let mut out = coefficients.to_vec();
    while out.len() > 1 && out.last().is_some_and(|c| c.abs() <= relative * max) {
        out.pop();
    }
    out
}

fn horner(coefficients: &[f64], z: C64) -> (C64, C64) {
    let mut p = C64::new(0.0, 0.0);
    let mut dp = C64::new(0.0, 0.0);
    for &c in coefficients.iter().rev() {
        dp = dp * z + p;
        p = p * z + c;
    }
    (p, dp)
}

/// All complex roots of a real polynomial (ascending coefficients, leading coefficient
/// nonzero) by the Aberth–Ehrlich iteration (simultaneous Newton with repulsion),
/// capped at 500 sweeps. Non-finite coefficients give no roots.
pub fn polynomial_roots(coefficients: &[f64]) -> Vec<C64> {
    let n = coefficients.len().saturating_sub(1);
    if n == 0 || coefficients.iter().any(|c| !c.is_finite()) || coefficients[n] == 0.0 {
        return Vec::new();
    }
    let lead = coefficients[n];
    // Cauchy-type bound for the initial circle.
    let radius = 1.0
        + coefficients[..n]
            .iter()
            .fold(0.0_f64, |m, c| m.max((c / lead).abs()));
    let radius = radius.min(1e12);
    let mut z: Vec<C64> = (0..n)
        .map(|k| C64::from_polar(0.5 * radius, TAU * k as f64 / n as f64 + 0.4))
        .collect();
    let mut converged = vec![false; n];
    for _ in 0..500 {
        for k in 0..n {
            if converged[k] {
                continue;
            }
            let (p, dp) = horner(coefficients, z[k]);
            // Rounding-error bound of Horner's scheme: |p| at this level is a root.
            let bound: f64 = coefficients
                .iter()
                .rev()
                .fold(0.0, |acc, c| acc * z[k].norm() + c.abs());
            if p.norm() <= 4.0 * f64::EPSILON * bound {
                converged[k] = true;
                continue;
            }
            let ratio = p / dp;
            let repulsion: C64 = (0..n)
                .filter(|&j| j != k)
                .map(|j| {
                    let d = z[k] - z[j];
                    if d.norm() == 0.0 {
                        C64::new(0.0, 0.0)
                    } else {
                        d.inv()
                    }
                })
                .sum();
            let step = ratio / (C64::new(1.0, 0.0) - ratio * repulsion);
            if step.is_finite() {
                z[k] -= step;
                if step.norm() <= 1e-15 * (1.0 + z[k].norm()) {
                    converged[k] = true;
                }
            }
        }
        if converged.iter().all(|&c| c) {
            break;
        }
    }
    z
}
