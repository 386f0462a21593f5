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
//!
//! [`Feasibility`] solves each system from scratch (the lower edges of the supports);
//! [`Incremental`] keeps a feasible tableau that grows by rows and is repaired from
//! its previous basis (the warm start of the depth-first mixed-cell search).

/// Relative tolerance of the tableau (pivots, ratio tests, the final `x₀`).
pub(crate) const TOLERANCE: f64 = 1e-9;
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
        exchange(&mut self.tableau, width, r, c);
        let pivot_row = &self.tableau[r * width..(r + 1) * width];
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

/// An incrementally grown system `M z ≥ r`, `z ∈ R^d` free, kept as a feasible simplex
/// tableau, so that the depth-first mixed-cell search tests a child (its parent's rows
/// plus one support's) from its parent's basis instead of from scratch — the warm
/// start of the dynamic enumeration of Mizutani, Takeda and Kojima ("Dynamic
/// enumeration of all mixed cells", Discrete Comput. Geom. 2007) and of MixedVol (Gao,
/// Li and Wu, "MixedVol: a software package for mixed-volume computation", ACM Trans.
/// Math. Softw. 2005).
///
/// Every row adds a slack `s = ⟨m, z⟩ − r ≥ 0`, expressed in the current nonbasic
/// variables. A free unknown still nonbasic enters the basis on the first row where
/// it has a nonzero coefficient (that row is then tight, so still feasible) and never
/// leaves it: its row takes no part in the ratio tests, and the columns are the `d`
/// nonbasic variables (slacks, or free unknowns whose column is zero). Rows made
/// infeasible are repaired one at a time without artificial variables: the simplex
/// method maximizes the violated row's slack while the ratio test keeps the feasible
/// rows feasible, until the slack leaves the basis at zero (repaired) or no nonbasic
/// variable increases it, which proves the system infeasible (the row reads
/// `s = s̄ − Σ t_c x_c` with `s̄ < 0 ≤ t_c` and nonnegative `x_c`) — the first violated
/// row that cannot be repaired ends the test early. Dantzig's rule, falling back to
/// Bland's after a run of degenerate pivots. Like [`Feasibility`] the test errs on the
/// side of "feasible".
#[derive(Debug, Default)]
pub struct Incremental {
    /// Number of free unknowns d.
    d: usize,
    /// Number of nonbasic columns (d less the equalities fixed by
    /// [`Incremental::fix_last`]).
    columns: usize,
    /// Absolute tolerance of the values (right-hand sides, ratios).
    eps: f64,
    /// Absolute tolerance of the coefficients.
    coefficient_eps: f64,
    /// Row-major `rows × (d + 1)`: the row's basic variable plus `Σ_c t_c x_c` equals
    /// the last entry; the columns are the nonbasic variables.
    tableau: Vec<f64>,
    /// Variable of each nonbasic column (`0..d` the free unknowns, `d + k` the slack
    /// of row k).
    nonbasic: Vec<usize>,
    /// Variable of each row's basic variable.
    basic: Vec<usize>,
    /// Row of each basic free unknown (`usize::MAX` while nonbasic).
    free_rows: Vec<usize>,
}

impl Clone for Incremental {
    fn clone(&self) -> Self {
        Incremental {
            d: self.d,
            columns: self.columns,
            eps: self.eps,
            coefficient_eps: self.coefficient_eps,
            tableau: self.tableau.clone(),
            nonbasic: self.nonbasic.clone(),
            basic: self.basic.clone(),
            free_rows: self.free_rows.clone(),
        }
    }

    /// Reuses the allocations (the search copies a parent's system for every child).
    fn clone_from(&mut self, source: &Self) {
        self.d = source.d;
        self.columns = source.columns;
        self.eps = source.eps;
        self.coefficient_eps = source.coefficient_eps;
        self.tableau.clone_from(&source.tableau);
        self.nonbasic.clone_from(&source.nonbasic);
        self.basic.clone_from(&source.basic);
        self.free_rows.clone_from(&source.free_rows);
    }
}

impl Incremental {
    /// The empty system in `d` unknowns (the origin is feasible), tolerances `eps` for
    /// values and `coefficient_eps` for coefficients.
    pub fn new(d: usize, eps: f64, coefficient_eps: f64) -> Self {
        Incremental {
            d,
            columns: d,
            eps,
            coefficient_eps,
            tableau: Vec::new(),
            nonbasic: (0..d).collect(),
            basic: Vec::new(),
            free_rows: vec![usize::MAX; d],
        }
    }

    /// Empties the system (keeping the allocations).
    pub fn reset(&mut self) {
        self.tableau.clear();
        self.basic.clear();
        self.nonbasic.clear();
        self.nonbasic.extend(0..self.d);
        self.columns = self.d;
        self.free_rows.clear();
        self.free_rows.resize(self.d, usize::MAX);
    }

    /// Appends the rows `Σ_j rows[i·d + j] z_j ≥ rhs[i]` (not yet repaired).
    pub fn push(&mut self, rows: &[f64], rhs: &[f64]) {
        let d = self.d;
        let columns = self.columns;
        let width = columns + 1;
        for (k, &r) in rhs.iter().enumerate() {
            let m = &rows[k * d..(k + 1) * d];
            let start = self.tableau.len();
            let new = self.basic.len();
            self.tableau.resize(start + width, 0.0);
            // s − ⟨m, z⟩ = −r, the basic unknowns substituted by their rows.
            self.tableau[start + columns] = -r;
            for (c, &v) in self.nonbasic.iter().enumerate() {
                if v < d {
                    self.tableau[start + c] -= m[v];
                }
            }
            for (v, &i) in self.free_rows.iter().enumerate() {
                if i == usize::MAX || m[v] == 0.0 {
                    continue;
                }
                let a = -m[v];
                let (old, row) = self.tableau.split_at_mut(start);
                for (t, s) in row.iter_mut().zip(&old[i * width..(i + 1) * width]) {
                    *t -= a * s;
                }
            }
            self.basic.push(d + new);
            // A nonbasic free unknown with a nonzero coefficient enters on this row.
            let mut best: Option<(usize, f64)> = None;
            for (c, &v) in self.nonbasic.iter().enumerate() {
                let t = self.tableau[start + c].abs();
                if v < d && t > self.coefficient_eps && best.is_none_or(|(_, b)| t > b) {
                    best = Some((c, t));
                }
            }
            if let Some((c, _)) = best {
                self.free_rows[self.nonbasic[c]] = new;
                self.pivot(new, c);
            }
        }
    }

    /// Repairs the violated rows; whether the system is feasible (within the
    /// tolerance). After `false` the tableau is no longer a basis of the system.
    pub fn repair(&mut self) -> bool {
        let d = self.d;
        let columns = self.columns;
        let width = columns + 1;
        let m = self.basic.len();
        let (eps, ceps) = (self.eps, self.coefficient_eps);
        let mut budget = (50 * (m + d)).max(1000);
        loop {
            let Some(r) =
                (0..m).find(|&i| self.basic[i] >= d && self.tableau[i * width + columns] < -eps)
            else {
                return true;
            };
            let mut degenerate = 0usize;
            while self.tableau[r * width + columns] < -eps {
                if budget == 0 {
                    // Iteration limit: the cautious answer.
                    return true;
                }
                budget -= 1;
                let row = &self.tableau[r * width..(r + 1) * width];
                let bland = degenerate >= DEGENERATE_RUN;
                let mut entering: Option<usize> = None;
                for c in 0..columns {
                    let t = row[c];
                    if t >= -ceps || self.nonbasic[c] < d {
                        continue;
                    }
                    entering = match entering {
                        None => Some(c),
                        Some(b) if bland && self.nonbasic[c] < self.nonbasic[b] => Some(c),
                        Some(b) if !bland && t < row[b] => Some(c),
                        keep => keep,
                    };
                }
                let Some(c) = entering else {
                    return false;
                };
                let mut best = r;
                let mut best_ratio = row[columns] / row[c];
                for i in 0..m {
                    if i == r || self.basic[i] < d {
                        continue;
                    }
                    let t = self.tableau[i * width + c];
                    let v = self.tableau[i * width + columns];
                    if t <= ceps || v < -eps {
                        continue;
                    }
                    let ratio = v.max(0.0) / t;
                    if ratio < best_ratio - eps
                        || ((ratio - best_ratio).abs() <= eps
                            && best != r
                            && self.basic[i] < self.basic[best])
                    {
                        best = i;
                        best_ratio = ratio;
                    }
                }
                if best_ratio <= eps {
                    degenerate += 1;
                } else {
                    degenerate = 0;
                }
                self.pivot(best, c);
            }
        }
    }

    /// Fixes the slack of the last row at zero for good (the row closing an equality,
    /// after a successful [`Incremental::repair`]): made nonbasic (a pivot on its row,
    /// whose value is zero, keeps every row feasible), its column is dropped, so the
    /// tableau narrows by one column per equality (the dimension of the feasible set).
    /// Nothing happens when the slack's row has no usable pivot.
    pub fn fix_last(&mut self) {
        let m = self.basic.len();
        if m == 0 {
            return;
        }
        let label = self.d + m - 1;
        let width = self.columns + 1;
        let c = match self.nonbasic.iter().position(|&v| v == label) {
            Some(c) => c,
            None => {
                let Some(r) = self.basic.iter().position(|&v| v == label) else {
                    return;
                };
                let row = &self.tableau[r * width..(r + 1) * width];
                let mut best: Option<(usize, f64)> = None;
                for (c, (t, &v)) in row[..self.columns].iter().zip(&self.nonbasic).enumerate() {
                    let t = t.abs();
                    if v >= self.d && t > self.coefficient_eps && best.is_none_or(|(_, b)| t > b) {
                        best = Some((c, t));
                    }
                }
                let Some((c, _)) = best else {
                    return;
                };
                self.pivot(r, c);
                c
            }
        };
        // Drop column c.
        let mut write = 0;
        for i in 0..m {
            for j in 0..width {
                if j != c {
                    self.tableau[write] = self.tableau[i * width + j];
                    write += 1;
                }
            }
        }
        self.tableau.truncate(write);
        self.nonbasic.remove(c);
        self.columns -= 1;
    }

    /// Exchanges the basic variable of row `r` with nonbasic column `c`.
    fn pivot(&mut self, r: usize, c: usize) {
        exchange(&mut self.tableau, self.columns + 1, r, c);
        std::mem::swap(&mut self.basic[r], &mut self.nonbasic[c]);
    }
}

/// The exchange step of the simplex method on the constraint rows of a row-major
/// `tableau` of `width` columns: the basic variable of row `r` leaves and nonbasic
/// column `c` enters. With pivot `p = T[r][c]`, row `r` becomes `T[r]/p` with
/// `T[r][c] = 1/p`, and every other row `i` with `f = T[i][c] ≠ 0` becomes
/// `T[i] − f·T[r]` (the new row `r`) with `T[i][c] = −f/p`.
fn exchange(tableau: &mut [f64], width: usize, r: usize, c: usize) {
    let p = tableau[r * width + c];
    {
        let row = &mut tableau[r * width..(r + 1) * width];
        for v in row.iter_mut() {
            *v /= p;
        }
        row[c] = 1.0 / p;
    }
    let (before, rest) = tableau.split_at_mut(r * width);
    let (pivot_row, after) = rest.split_at_mut(width);
    let eliminate = |row: &mut [f64]| {
        let f = row[c];
        if f == 0.0 {
            return;
        }
        for (v, q) in row.iter_mut().zip(pivot_row.iter()) {
            *v -= f * q;
        }
        row[c] = -f * pivot_row[c];
    };
    before.chunks_mut(width).for_each(eliminate);
    after.chunks_mut(width).for_each(eliminate);
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

    /// The incremental test agrees with the test from scratch on random systems grown
    /// a few rows at a time, every prefix checked (feasible ones keep their tableau).
    #[test]
    fn incremental_agrees_with_the_test_from_scratch() {
        use rand::Rng;
        let mut rng = crate::random::stream(5, 0);
        let mut lp = Feasibility::new();
        let (mut feasible, mut infeasible) = (0, 0);
        for trial in 0..400 {
            let d = 1 + trial % 4;
            let mut system = Incremental::new(d, 1e-6, 1e-9);
            let mut rows = Vec::new();
            let mut rhs = Vec::new();
            for _ in 0..6 {
                let k = 1 + (rng.next_u64() % 3) as usize;
                let start = rhs.len();
                for _ in 0..k {
                    rows.extend((0..d).map(|_| (rng.next_u64() % 7) as f64 - 3.0));
                    rhs.push((rng.next_u64() % 9) as f64 - 6.0);
                }
                // Every other batch ends with an equality (its last row negated), whose
                // slack is fixed after the repair, as the mixed-cell search does.
                let equality = trial % 2 == 1;
                if equality {
                    let last: Vec<f64> = rows[rows.len() - d..].iter().map(|v| -v).collect();
                    rows.extend(last);
                    rhs.push(-rhs[rhs.len() - 1]);
                }
                system.push(&rows[start * d..], &rhs[start..]);
                let expected = lp.feasible(d, &rows, &rhs);
                assert_eq!(system.repair(), expected, "trial {trial}: {rows:?} {rhs:?}");
                if expected && equality {
                    system.fix_last();
                }
                if !expected {
                    infeasible += 1;
                    break;
                }
                feasible += 1;
            }
        }
        assert!(
            feasible > 200 && infeasible > 100,
            "{feasible} {infeasible}"
        );
    }
}
