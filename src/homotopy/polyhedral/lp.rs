//! Feasibility of a system of linear inequalities `M z ≥ r`, `z ∈ R^d` free, by the
//! simplex method on a dense tableau.
//!
//! The free unknowns are split `z = z⁺ − z⁻` (`z^± ≥ 0`), giving the standard form
//! `A u ≤ b`, `u ≥ 0` with `A = −[M, −M]`, `b = −r`. When `b ≥ 0` the origin is
//! feasible; otherwise the auxiliary problem `max −x₀` subject to `A u − x₀ ≤ b`,
//! `u, x₀ ≥ 0` starts from the basis made feasible by one pivot on the row of the
//! least `b_i`, and the system is feasible iff the optimum is `x₀ = 0` (the phase one
//! of the two-phase simplex method; Dantzig's largest-coefficient rule, falling back
//! to Bland's smallest-index rule after a run of degenerate pivots so the method
//! cannot cycle). This is the feasibility test of the mixed-cell enumeration
//! (Li, "Numerical solution of polynomial systems by homotopy continuation
//! methods", Handbook of Numerical Analysis XI, 2003, §4): the data are small integers,
//! so double precision with a relative tolerance decides it, and the test errs on the
//! side of "feasible" (a cell is then rejected by the exact test of
//! [`super::cells`]).

/// Relative tolerance of the tableau (pivots, ratio tests, the final `x₀`).
const TOLERANCE: f64 = 1e-9;
/// Degenerate pivots in a row after which Bland's rule is used.
const DEGENERATE_RUN: usize = 32;

/// A reusable dense tableau for [`Feasibility::feasible`].
#[derive(Clone, Debug, Default)]
pub struct Feasibility {
    /// Row-major `rows × (columns + 1)`: the coefficients of the nonbasic variables and
    /// the right-hand side last.
    tableau: Vec<f64>,
    /// Objective coefficients of the nonbasic variables and its constant last.
    objective: Vec<f64>,
    /// Variable index of each nonbasic column.
    nonbasic: Vec<usize>,
    /// Variable index of each basic row.
    basic: Vec<usize>,
}

impl Feasibility {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether some `z ∈ R^d` satisfies `Σ_j rows[i·d + j] z_j ≥ rhs[i]` for every row
    /// `i` (`rows` row-major, `rhs.len()` rows of `d` entries).
    pub fn feasible(&mut self, d: usize, rows: &[f64], rhs: &[f64]) -> bool {
        let m = rhs.len();
        debug_assert_eq!(rows.len(), m * d);
        let scale = rows.iter().chain(rhs).fold(1.0f64, |s, v| s.max(v.abs()));
        let eps = TOLERANCE * scale;
        // b = −r; the origin is feasible when b ≥ 0.
        let (least, least_b) =
            rhs.iter()
                .enumerate()
                .map(|(i, r)| (i, -r))
                .fold(
                    (usize::MAX, 0.0),
                    |acc, (i, b)| if b < acc.1 { (i, b) } else { acc },
                );
        if least == usize::MAX || least_b >= -eps {
            return true;
        }
        // Variables: 0..d = z⁺, d..2d = z⁻, 2d = x₀, 2d+1.. = slacks of the rows.
        let columns = 2 * d + 1;
        let width = columns + 1;
        self.tableau.clear();
        self.tableau.resize(m * width, 0.0);
        for i in 0..m {
            let row = &mut self.tableau[i * width..(i + 1) * width];
            for j in 0..d {
                let a = -rows[i * d + j];
                row[j] = a;
                row[d + j] = -a;
            }
            row[2 * d] = -1.0;
            row[columns] = -rhs[i];
        }
        self.objective.clear();
        self.objective.resize(width, 0.0);
        self.objective[2 * d] = -1.0;
        self.nonbasic.clear();
        self.nonbasic.extend(0..columns);
        self.basic.clear();
        self.basic.extend((0..m).map(|i| columns + i));
        // x₀ enters on the row of the least b: the basis becomes feasible.
        self.pivot(least, 2 * d, width);
        let mut degenerate = 0usize;
        for _ in 0..(50 * (m + columns)).max(1000) {
            if self.objective[columns] >= -eps {
                return true;
            }
            let bland = degenerate >= DEGENERATE_RUN;
            let Some(entering) = self.entering(columns, eps, bland) else {
                return self.objective[columns] >= -eps;
            };
            let Some(leaving) = self.leaving(entering, m, width, eps) else {
                // Unbounded in the auxiliary problem cannot happen (−x₀ ≤ 0); treat as
                // feasible, the cautious answer.
                return true;
            };
            let before = self.objective[columns];
            self.pivot(leaving, entering, width);
            if (self.objective[columns] - before).abs() <= eps {
                degenerate += 1;
            } else {
                degenerate = 0;
            }
        }
        // Iteration limit: the cautious answer.
        true
    }

    /// Entering column: largest positive reduced cost, or with `bland` the positive
    /// one of smallest variable index.
    fn entering(&self, columns: usize, eps: f64, bland: bool) -> Option<usize> {
        let mut best: Option<usize> = None;
        for j in 0..columns {
            let c = self.objective[j];
            if c <= eps {
                continue;
            }
            best = match best {
                None => Some(j),
                Some(b) if bland && self.nonbasic[j] < self.nonbasic[b] => Some(j),
                Some(b) if !bland && c > self.objective[b] => Some(j),
                keep => keep,
            };
        }
        best
    }

    /// Leaving row of the minimum-ratio test (ties: smallest basic variable index).
    fn leaving(&self, entering: usize, m: usize, width: usize, eps: f64) -> Option<usize> {
        let columns = width - 1;
        let mut best: Option<(usize, f64)> = None;
        for i in 0..m {
            let a = self.tableau[i * width + entering];
            if a <= eps {
                continue;
            }
            let ratio = self.tableau[i * width + columns] / a;
            best = match best {
                None => Some((i, ratio)),
                Some((b, r)) => {
                    if ratio < r - eps
                        || ((ratio - r).abs() <= eps && self.basic[i] < self.basic[b])
                    {
                        Some((i, ratio))
                    } else {
                        Some((b, r))
                    }
                }
            };
        }
        best.map(|(i, _)| i)
    }

    /// Exchanges basic variable of row `r` with nonbasic column `c`.
    fn pivot(&mut self, r: usize, c: usize, width: usize) {
        let m = self.basic.len();
        let p = self.tableau[r * width + c];
        {
            let row = &mut self.tableau[r * width..(r + 1) * width];
            for (j, v) in row.iter_mut().enumerate() {
                if j == c {
                    *v = 1.0 / p;
                } else {
                    *v /= p;
                }
            }
        }
        let (before, rest) = self.tableau.split_at_mut(r * width);
        let (pivot_row, after) = rest.split_at_mut(width);
        let eliminate = |row: &mut [f64]| {
            let f = row[c];
            if f == 0.0 {
                return;
            }
            for (j, v) in row.iter_mut().enumerate() {
                if j == c {
                    *v = -f * pivot_row[c];
                } else {
                    *v -= f * pivot_row[j];
                }
            }
        };
        before.chunks_mut(width).for_each(eliminate);
        after.chunks_mut(width).for_each(eliminate);
        // The objective row keeps its constant with the opposite sign convention:
        // objective = Σ c_j x_j + v, so the constant moves with +.
        let f = self.objective[c];
        if f != 0.0 {
            for j in 0..width {
                if j == c {
                    self.objective[j] = -f * pivot_row[c];
                } else if j == width - 1 {
                    self.objective[j] += f * pivot_row[j];
                } else {
                    self.objective[j] -= f * pivot_row[j];
                }
            }
        }
        debug_assert!(r < m);
        std::mem::swap(&mut self.basic[r], &mut self.nonbasic[c]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feasible_and_infeasible_systems() {
        let mut lp = Feasibility::new();
        // z ≥ 1, z ≤ 2 (−z ≥ −2): feasible.
        assert!(lp.feasible(1, &[1.0, -1.0], &[1.0, -2.0]));
        // z ≥ 2, z ≤ 1: infeasible.
        assert!(!lp.feasible(1, &[1.0, -1.0], &[2.0, -1.0]));
        // x + y ≥ 3, x ≤ 1, y ≤ 1: infeasible; with y ≤ 2: feasible (the point (1, 2)).
        let rows = [1.0, 1.0, -1.0, 0.0, 0.0, -1.0];
        assert!(!lp.feasible(2, &rows, &[3.0, -1.0, -1.0]));
        assert!(lp.feasible(2, &rows, &[3.0, -1.0, -2.0]));
        // Negative coordinates are allowed: x ≤ −5, x + y ≥ 1 and y ≤ 7 is met by
        // (−5, 6); with y ≤ −3 instead, y ≥ 1 − x ≥ 6 contradicts it.
        let rows = [-1.0, 0.0, 1.0, 1.0, 0.0, -1.0];
        assert!(lp.feasible(2, &rows, &[5.0, 1.0, -7.0]));
        assert!(!lp.feasible(2, &rows, &[5.0, 1.0, 3.0]));
        // x ≤ −5, y ≥ x + 1, y ≤ −4.5 is met by (−6, −5): unbounded below, feasible.
        let rows = [-1.0, 0.0, -1.0, 1.0, 0.0, -1.0];
        assert!(lp.feasible(2, &rows, &[5.0, 1.0, 4.5]));
    }
}
