//! Mixed cells of a fine mixed subdivision induced by a lifting, and the mixed volume.
//!
//! Lift every point `a ∈ A_i` to `â = (a, ω_i(a)) ∈ Z^{n+1}`. A mixed cell is a choice
//! of one pair `{p_i, q_i} ⊂ A_i` per support with an inner normal `(α, 1)`,
//! `α ∈ Q^n`, on which the pair is exactly the lower face of `Â_i`:
//! `⟨a, α⟩ + ω_i(a) ≥ ⟨p_i, α⟩ + ω_i(p_i)` for every `a ∈ A_i`, with equality exactly
//! at `p_i` and `q_i`. For a generic lifting the mixed cells of the induced regular
//! fine mixed subdivision are exactly these, and their volumes
//! `|det(q_1 − p_1, …, q_n − p_n)|` add up to the mixed volume `MV(A_1, …, A_n)`
//! (Huber and Sturmfels, "A polyhedral method for solving sparse polynomial systems",
//! Math. Comp. 1995, Thm 2.4; Li, "Numerical solution of polynomial systems by
//! homotopy continuation methods", Handbook of Numerical Analysis XI, 2003, §3–4).
//!
//! Enumeration: first the lower edges of every lifted support (pairs `{p, q}` that are
//! a lower face of `Â_i` alone, one LP feasibility test each), the relation table of
//! pairs of lower edges of two supports that share an inner normal (one LP each,
//! filled as the search reaches an edge), and a depth-first search that adds one lower edge per support. The
//! candidates of every support not yet chosen are the lower edges related to all
//! chosen ones (bit-set intersections); a choice leaving some support without
//! candidates is pruned, the support with the fewest candidates is branched on next,
//! and every partial choice whose inequalities (all points of the supports chosen so
//! far) and equalities (the chosen pairs) are infeasible is pruned ([`super::lp`];
//! the relation table and the pruning follow the scheme of Li, Handbook, §4.3, and of
//! Verschelde, Verlinden and Cools, "Homotopies exploiting Newton polytopes for
//! solving sparse polynomial systems", SIAM J. Numer. Anal. 1994). Every complete choice is then checked exactly: `α` by Cramer's
//! rule in `i128` (fraction-free Bareiss determinants), and the gaps
//! `⟨a − p_i, α⟩ + ω_i(a) − ω_i(p_i)` must be positive off the pair. A zero gap means
//! the lifting is not generic ([`CellError::NonGenericLifting`]); the caller draws
//! another one.

use super::lp::Feasibility;
use super::supports::Supports;

/// Errors of the mixed-cell enumeration.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CellError {
    /// The number of supports differs from the number of unknowns.
    #[error("{supports} supports in {variables} unknowns; mixed cells need a square system")]
    NotSquare {
        /// Number of supports.
        supports: usize,
        /// Number of unknowns.
        variables: usize,
    },
    /// A support has fewer than two points (a monomial equation has no roots in the
    /// torus and no mixed cell).
    #[error("the support of equation {0} has fewer than two points")]
    DegenerateSupport(usize),
    /// A cell's inner normal attains the minimum at a third point of some support.
    #[error("the lifting is not generic")]
    NonGenericLifting,
    /// An exact determinant overflowed `i128`.
    #[error("an exact determinant overflowed")]
    Overflow,
    /// The enumeration needed more LP feasibility tests than it was allowed.
    #[error("the mixed-cell search passed its budget of {0} LP tests")]
    OverBudget(usize),
}

/// One mixed cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MixedCell {
    /// Per equation the indices `(p_i, q_i)` of the pair in support i.
    pub pairs: Vec<(usize, usize)>,
    /// `D·α` (the inner normal's numerators), with `D = volume > 0`.
    pub normal: Vec<i128>,
    /// `|det(q_1 − p_1, …, q_n − p_n)|`, also the common denominator of `α`.
    pub volume: u64,
    /// `D·(⟨a − p_i, α⟩ + ω_i(a) − ω_i(p_i)) ≥ 0` for every point of every support,
    /// equations in order, points in support order (zero exactly at the pair).
    pub gaps: Vec<i128>,
}

/// The mixed cells of a lifting and their total volume.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MixedSubdivision {
    /// The cells.
    pub cells: Vec<MixedCell>,
    /// Σ volumes: the mixed volume.
    pub mixed_volume: u128,
    /// LP feasibility tests run.
    pub lp_tests: usize,
}

/// The mixed cells of `supports` lifted by `lifting` (`lifting[i][k]` lifts point k of
/// support i).
pub fn mixed_cells(
    supports: &Supports,
    lifting: &[Vec<i64>],
) -> Result<MixedSubdivision, CellError> {
    mixed_cells_within(supports, lifting, usize::MAX)
}

/// [`mixed_cells`], giving up with [`CellError::OverBudget`] once the search has run
/// more than `max_lp_tests` LP feasibility tests (so a caller choosing between start
/// systems can bound what the polyhedral one costs to find out).
pub fn mixed_cells_within(
    supports: &Supports,
    lifting: &[Vec<i64>],
    max_lp_tests: usize,
) -> Result<MixedSubdivision, CellError> {
    let n = supports.num_variables();
    if supports.num_equations() != n {
        return Err(CellError::NotSquare {
            supports: supports.num_equations(),
            variables: n,
        });
    }
    for i in 0..n {
        if supports.support(i).len() < 2 {
            return Err(CellError::DegenerateSupport(i));
        }
    }
    let mut search = Search {
        supports,
        lifting,
        n,
        lp: Feasibility::new(),
        rows: Vec::new(),
        rhs: Vec::new(),
        chosen: vec![(0, 0); n],
        cells: Vec::new(),
        lp_tests: 0,
        max_lp_tests,
        edges: Vec::new(),
        edge_offset: Vec::new(),
        words: 0,
        relation: Vec::new(),
        known: Vec::new(),
    };
    search.edges = (0..n).map(|i| search.lower_edges(i)).collect();
    search.relation_table();
    let mut candidates = vec![0u64; search.words];
    for i in 0..n {
        for e in 0..search.edges[i].len() {
            set_bit(&mut candidates, search.edge_offset[i] + e);
        }
    }
    let mut remaining: Vec<usize> = (0..n).collect();
    search.descend(&mut remaining, &candidates)?;
    let mixed_volume = search.cells.iter().map(|c| c.volume as u128).sum();
    Ok(MixedSubdivision {
        cells: search.cells,
        mixed_volume,
        lp_tests: search.lp_tests,
    })
}

fn set_bit(bits: &mut [u64], k: usize) {
    bits[k / 64] |= 1 << (k % 64);
}

fn has_bit(bits: &[u64], k: usize) -> bool {
    bits[k / 64] >> (k % 64) & 1 == 1
}

/// State of the depth-first search.
struct Search<'a> {
    supports: &'a Supports,
    lifting: &'a [Vec<i64>],
    n: usize,
    lp: Feasibility,
    /// The inequality rows of the current partial choice (row-major, n per row).
    rows: Vec<f64>,
    rhs: Vec<f64>,
    chosen: Vec<(usize, usize)>,
    cells: Vec<MixedCell>,
    lp_tests: usize,
    /// [`CellError::OverBudget`] past this many LP tests.
    max_lp_tests: usize,
    /// Lower edges of each support.
    edges: Vec<Vec<(usize, usize)>>,
    /// Global number of the first edge of each support.
    edge_offset: Vec<usize>,
    /// Words of a bit set over all edges.
    words: usize,
    /// Row-major bit sets: bit f of row e is set when edges e and f (of different
    /// supports) are lower edges for a common inner normal.
    relation: Vec<u64>,
    /// Bit sets like `relation`: the pairs already decided.
    known: Vec<u64>,
}

impl Search<'_> {
    /// Appends the rows of pair `(p, q)` of support i: `⟨a − p, α⟩ ≥ ω(p) − ω(a)` for
    /// all a, and `⟨p − q, α⟩ ≥ ω(q) − ω(p)` (with the row of `a = q`, the equality).
    fn push_rows(&mut self, i: usize, (p, q): (usize, usize)) {
        let points = self.supports.support(i);
        let w = &self.lifting[i];
        for (k, a) in points.iter().enumerate() {
            if k == p {
                continue;
            }
            self.rows
                .extend(a.iter().zip(&points[p]).map(|(x, y)| (x - y) as f64));
            self.rhs.push((w[p] - w[k]) as f64);
        }
        self.rows.extend(
            points[p]
                .iter()
                .zip(&points[q])
                .map(|(x, y)| (x - y) as f64),
        );
        self.rhs.push((w[q] - w[p]) as f64);
    }

    fn truncate(&mut self, rows: usize) {
        self.rows.truncate(rows * self.n);
        self.rhs.truncate(rows);
    }

    fn feasible(&mut self) -> bool {
        self.lp_tests += 1;
        self.lp.feasible(self.n, &self.rows, &self.rhs)
    }

    /// The pairs of support i that are a lower edge of its lifting.
    fn lower_edges(&mut self, i: usize) -> Vec<(usize, usize)> {
        let m = self.supports.support(i).len();
        let mut edges = Vec::new();
        for p in 0..m {
            for q in p + 1..m {
                self.truncate(0);
                self.push_rows(i, (p, q));
                if self.feasible() {
                    edges.push((p, q));
                }
            }
        }
        self.truncate(0);
        edges
    }

    /// Sizes of the relation table (decided lazily by [`Search::relate`]).
    fn relation_table(&mut self) {
        let n = self.n;
        self.edge_offset = Vec::with_capacity(n + 1);
        let mut total = 0;
        for i in 0..n {
            self.edge_offset.push(total);
            total += self.edges[i].len();
        }
        self.edge_offset.push(total);
        self.words = total.div_ceil(64);
        self.relation = vec![0u64; total * self.words];
        self.known = vec![0u64; total * self.words];
    }

    /// Decides the relation of edge `e` of support i with every lower edge of support j
    /// that is still a candidate (one LP per pair not yet decided): edges the search has
    /// already excluded need no test, since the child's candidates are an intersection
    /// with `candidates`.
    fn relate(&mut self, i: usize, e: usize, j: usize, candidates: &[u64]) {
        let u = self.edge_offset[i] + e;
        let saved = self.rhs.len();
        self.push_rows(i, self.edges[i][e]);
        let base = self.rhs.len();
        let w = self.words;
        for f in 0..self.edges[j].len() {
            let v = self.edge_offset[j] + f;
            if !has_bit(candidates, v) || has_bit(&self.known[u * w..(u + 1) * w], v) {
                continue;
            }
            set_bit(&mut self.known[u * w..(u + 1) * w], v);
            set_bit(&mut self.known[v * w..(v + 1) * w], u);
            self.push_rows(j, self.edges[j][f]);
            // Only the two supports' rows: the LP starts after the caller's rows.
            self.lp_tests += 1;
            let d = self.n;
            if self
                .lp
                .feasible(d, &self.rows[saved * d..], &self.rhs[saved..])
            {
                set_bit(&mut self.relation[u * w..(u + 1) * w], v);
                set_bit(&mut self.relation[v * w..(v + 1) * w], u);
            }
            self.truncate(base);
        }
        self.truncate(saved);
    }

    /// Depth-first search over the supports in `remaining` with the candidate edges
    /// `candidates` (a bit set over all edges, compatible with every chosen edge):
    /// the support with the fewest candidates is branched on next.
    fn descend(&mut self, remaining: &mut Vec<usize>, candidates: &[u64]) -> Result<(), CellError> {
        if remaining.is_empty() {
            return self.leaf();
        }
        if self.lp_tests > self.max_lp_tests {
            return Err(CellError::OverBudget(self.max_lp_tests));
        }
        let count = |i: usize| {
            (0..self.edges[i].len())
                .filter(|&e| has_bit(candidates, self.edge_offset[i] + e))
                .count()
        };
        let (position, _) = remaining
            .iter()
            .enumerate()
            .map(|(k, &i)| (k, count(i)))
            .min_by_key(|&(_, c)| c)
            .unwrap_or((0, 0));
        let i = remaining.swap_remove(position);
        let rows = self.rhs.len();
        let first = self.rhs.is_empty();
        let mut child = vec![0u64; self.words];
        for e in 0..self.edges[i].len() {
            let u = self.edge_offset[i] + e;
            if !has_bit(candidates, u) {
                continue;
            }
            for &j in remaining.iter() {
                self.relate(i, e, j, candidates);
            }
            let w = self.words;
            for (c, (a, b)) in child
                .iter_mut()
                .zip(candidates.iter().zip(&self.relation[u * w..(u + 1) * w]))
            {
                *c = a & b;
            }
            if remaining.iter().any(|&j| {
                (0..self.edges[j].len()).all(|f| !has_bit(&child, self.edge_offset[j] + f))
            }) {
                continue;
            }
            if self.lp_tests > self.max_lp_tests {
                return Err(CellError::OverBudget(self.max_lp_tests));
            }
            let edge = self.edges[i][e];
            self.push_rows(i, edge);
            if first || self.feasible() {
                self.chosen[i] = edge;
                self.descend(remaining, &child)?;
            }
            self.truncate(rows);
        }
        remaining.push(i);
        let last = remaining.len() - 1;
        remaining.swap(position, last);
        Ok(())
    }

    /// Exact test of a complete choice; records the cell.
    fn leaf(&mut self) -> Result<(), CellError> {
        let n = self.n;
        let mut matrix = vec![0i128; n * n];
        let mut rhs = vec![0i128; n];
        for i in 0..n {
            let (p, q) = self.chosen[i];
            let points = self.supports.support(i);
            for j in 0..n {
                matrix[i * n + j] = (points[q][j] - points[p][j]) as i128;
            }
            rhs[i] = (self.lifting[i][p] - self.lifting[i][q]) as i128;
        }
        let det = bareiss_determinant(&matrix, n)?;
        if det == 0 {
            return Err(CellError::NonGenericLifting);
        }
        let mut normal = vec![0i128; n];
        let mut replaced = matrix.clone();
        for (j, nj) in normal.iter_mut().enumerate() {
            for i in 0..n {
                replaced[i * n + j] = rhs[i];
            }
            *nj = bareiss_determinant(&replaced, n)?;
            for i in 0..n {
                replaced[i * n + j] = matrix[i * n + j];
            }
        }
        let d = det.abs();
        if det < 0 {
            normal.iter_mut().for_each(|v| *v = -*v);
        }
        let mut gaps = Vec::new();
        for i in 0..n {
            let (p, q) = self.chosen[i];
            let points = self.supports.support(i);
            let w = &self.lifting[i];
            for (k, a) in points.iter().enumerate() {
                let mut g = 0i128;
                for j in 0..n {
                    let term = ((a[j] - points[p][j]) as i128)
                        .checked_mul(normal[j])
                        .ok_or(CellError::Overflow)?;
                    g = g.checked_add(term).ok_or(CellError::Overflow)?;
                }
                g = ((w[k] - w[p]) as i128)
                    .checked_mul(d)
                    .and_then(|v| v.checked_add(g))
                    .ok_or(CellError::Overflow)?;
                let on_pair = k == p || k == q;
                if on_pair && g != 0 {
                    return Err(CellError::Overflow);
                }
                if !on_pair && g == 0 {
                    return Err(CellError::NonGenericLifting);
                }
                if g < 0 {
                    // Not a lower face: the LP's tolerance let it through.
                    return Ok(());
                }
                gaps.push(g);
            }
        }
        self.cells.push(MixedCell {
            pairs: self.chosen.clone(),
            normal,
            volume: u64::try_from(d).map_err(|_| CellError::Overflow)?,
            gaps,
        });
        Ok(())
    }
}

/// Determinant of the n × n integer matrix `a` (row-major) by fraction-free Bareiss
/// elimination with row pivoting, overflow-checked.
pub fn bareiss_determinant(a: &[i128], n: usize) -> Result<i128, CellError> {
    let mut m = a.to_vec();
    let mut sign = 1i128;
    let mut previous = 1i128;
    for k in 0..n {
        if m[k * n + k] == 0 {
            let Some(r) = (k + 1..n).find(|&r| m[r * n + k] != 0) else {
                return Ok(0);
            };
            for j in 0..n {
                m.swap(k * n + j, r * n + j);
            }
            sign = -sign;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                let v = m[i * n + j]
                    .checked_mul(m[k * n + k])
                    .and_then(|x| {
                        m[i * n + k]
                            .checked_mul(m[k * n + j])
                            .and_then(|y| x.checked_sub(y))
                    })
                    .ok_or(CellError::Overflow)?;
                m[i * n + j] = v / previous;
            }
            m[i * n + k] = 0;
        }
        previous = m[k * n + k];
    }
    Ok(sign * m[(n - 1) * n + (n - 1)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homotopy::polyhedral::supports::random_lifting;

    fn mv(supports: &Supports, seed: u64) -> u128 {
        for stream in 0.. {
            let lifting = random_lifting(supports, seed, stream, 1 << 12);
            match mixed_cells(supports, &lifting) {
                Ok(s) => return s.mixed_volume,
                Err(CellError::NonGenericLifting) => continue,
                Err(e) => panic!("{e}"),
            }
        }
        unreachable!()
    }

    /// Two dense quadrics in two unknowns.
    fn dense_quadrics() -> Supports {
        let dense: Vec<Vec<i64>> = vec![
            vec![0, 0],
            vec![1, 0],
            vec![0, 1],
            vec![2, 0],
            vec![1, 1],
            vec![0, 2],
        ];
        Supports::new(2, vec![dense.clone(), dense])
    }

    #[test]
    fn determinants() {
        assert_eq!(bareiss_determinant(&[2, 1, 1, 3], 2), Ok(5));
        assert_eq!(bareiss_determinant(&[0, 1, 1, 0], 2), Ok(-1));
        assert_eq!(
            bareiss_determinant(&[1, 2, 3, 4, 5, 6, 7, 8, 10], 3),
            Ok(-3)
        );
        assert_eq!(bareiss_determinant(&[1, 2, 2, 4], 2), Ok(0));
    }

    #[test]
    fn mixed_volume_of_dense_quadrics_is_the_bezout_number() {
        // MV = 4, the Bézout number.
        let s = dense_quadrics();
        assert_eq!(mv(&s, 1), 4);
        assert_eq!(mv(&s, 2), 4);
    }

    #[test]
    fn a_search_past_its_lp_budget_gives_up() {
        let s = dense_quadrics();
        let lifting = random_lifting(&s, 1, 0, 1 << 12);
        let full = mixed_cells(&s, &lifting).unwrap();
        assert_eq!(
            mixed_cells_within(&s, &lifting, full.lp_tests / 2),
            Err(CellError::OverBudget(full.lp_tests / 2))
        );
        assert_eq!(mixed_cells_within(&s, &lifting, full.lp_tests), Ok(full));
    }

    #[test]
    fn mixed_volume_of_a_sparse_system() {
        // a x y + b x + c y + d = 0 twice (bilinear): MV = 2, total degree 4.
        let bilinear = vec![vec![0, 0], vec![1, 0], vec![0, 1], vec![1, 1]];
        let s = Supports::new(2, vec![bilinear.clone(), bilinear]);
        assert_eq!(mv(&s, 5), 2);
        // x³y + 1, x + y²: binomials, MV = |det((3, 1), (1, −2))| = 7.
        let s = Supports::new(
            2,
            vec![vec![vec![3, 1], vec![0, 0]], vec![vec![1, 0], vec![0, 2]]],
        );
        assert_eq!(mv(&s, 5), 7);
    }
}
