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
//! pairs of lower edges of two supports that share an inner normal (filled as the
//! search reaches an edge), and a depth-first search that adds one lower edge per
//! support. The candidates of every support not yet chosen are the lower edges related
//! to all chosen ones (bit-set intersections); a choice leaving some support without
//! candidates is pruned, the support with the fewest candidates is branched on next,
//! and every partial choice whose inequalities (all points of the supports chosen so
//! far) and equalities (the chosen pairs) are infeasible is pruned (the relation table
//! and the pruning follow the scheme of Li, Handbook, §4.3, and of Verschelde,
//! Verlinden and Cools, "Homotopies exploiting Newton polytopes for solving sparse
//! polynomial systems", SIAM J. Numer. Anal. 1994).
//!
//! The LPs of the search are warm-started ([`super::lp::Incremental`]), as in the
//! dynamic enumeration of Mizutani, Takeda and Kojima ("Dynamic enumeration of all
//! mixed cells", Discrete Comput. Geom. 2007) and in MixedVol (Gao, Li and Wu,
//! "MixedVol: a software package for mixed-volume computation", ACM Trans. Math.
//! Softw. 2005): every depth keeps the feasible tableau of its partial choice, and a
//! child adds the rows of one support to a copy of it. A child's test is split in two:
//! the 1-point test (the rows "`p` is lowest in `Â_i`", shared by every edge `{p, q}`
//! of the branching support: an infeasible point prunes all its edges at once), then
//! the one row closing the equality of `{p, q}`, whose slack then leaves the tableau
//! (one column fewer per depth). The relation tests of an edge are
//! warm-started from the edge's own tableau in the same way, and an infeasible row
//! ends a test at once. Every test is one LP test of the budget. The order of the
//! search, hence the cells and their order, are those of the tests from scratch.
//!
//! Every complete choice is then checked exactly: `α` by Cramer's
//! rule in `i128` (fraction-free Bareiss determinants), and the gaps
//! `⟨a − p_i, α⟩ + ω_i(a) − ω_i(p_i)` must be positive off the pair. A zero gap means
//! the lifting is not generic ([`CellError::NonGenericLifting`]); the caller draws
//! another one.

use super::lp::{Feasibility, Incremental, TOLERANCE};
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
    /// The cells found so far have a larger volume than the caller allowed.
    #[error("the mixed volume exceeds {0}")]
    OverVolume(u128),
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
    mixed_cells_bounded(supports, lifting, max_lp_tests, u128::MAX)
}

/// [`mixed_cells_within`], giving up with [`CellError::OverVolume`] too once the
/// cells found so far have a total volume above `max_volume` (a caller that takes the
/// polyhedral start system only below some mixed volume need not finish the search:
/// `katsura8`'s 242,050 LP tests, 0.39 s, decided nothing its first cells do not).
pub fn mixed_cells_bounded(
    supports: &Supports,
    lifting: &[Vec<i64>],
    max_lp_tests: usize,
    max_volume: u128,
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
        volume: 0,
        max_volume,
        edges: Vec::new(),
        edge_offset: Vec::new(),
        words: 0,
        relation: Vec::new(),
        known: Vec::new(),
        stack: Vec::new(),
        points: Vec::new(),
        related: Default::default(),
    };
    let scale = supports
        .equations()
        .iter()
        .flatten()
        .flatten()
        .chain(lifting.iter().flatten())
        .fold(1i64, |s, v| s.max(v.abs()));
    let eps = TOLERANCE * 2.0 * scale as f64;
    let coefficient_scale = supports
        .equations()
        .iter()
        .flatten()
        .flatten()
        .fold(1i64, |s, v| s.max(v.abs()));
    let coefficient_eps = TOLERANCE * 2.0 * coefficient_scale as f64;
    search.stack = vec![Incremental::new(n, eps, coefficient_eps); n + 1];
    search.points = vec![Incremental::new(n, eps, coefficient_eps); n];
    let empty = Incremental::new(n, eps, coefficient_eps);
    search.related = (empty.clone(), empty.clone(), empty);
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

/// The bits of word k that lie in `lo..hi`.
fn range_mask(k: usize, lo: usize, hi: usize) -> u64 {
    let mut mask = !0u64;
    if k == lo / 64 {
        mask &= !0u64 << (lo % 64);
    }
    if k == (hi - 1) / 64 {
        mask &= !0u64 >> (63 - (hi - 1) % 64);
    }
    mask
}

/// Number of bits set in `lo..hi`.
fn count_bits(bits: &[u64], lo: usize, hi: usize) -> usize {
    if lo >= hi {
        return 0;
    }
    let (first, last) = (lo / 64, (hi - 1) / 64);
    let low_mask = !0u64 << (lo % 64);
    let high_mask = !0u64 >> (63 - (hi - 1) % 64);
    if first == last {
        return (bits[first] & low_mask & high_mask).count_ones() as usize;
    }
    let mut total = (bits[first] & low_mask).count_ones() + (bits[last] & high_mask).count_ones();
    for w in &bits[first + 1..last] {
        total += w.count_ones();
    }
    total as usize
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
    /// Total volume of `cells`.
    volume: u128,
    /// [`CellError::OverVolume`] past this total volume.
    max_volume: u128,
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
    /// Per depth the warm-started system of the chosen supports.
    stack: Vec<Incremental>,
    /// Per depth the parent's system with the 1-point rows of the branching support.
    points: Vec<Incremental>,
    /// The relation tests' systems: one edge, with a point of the other support, with
    /// its edge.
    related: (Incremental, Incremental, Incremental),
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
        let w = self.words;
        let known = &self.known[u * w..(u + 1) * w];
        let (lo, hi) = (self.edge_offset[j], self.edge_offset[j + 1]);
        if lo == hi
            || (lo / 64..=(hi - 1) / 64)
                .all(|k| candidates[k] & !known[k] & range_mask(k, lo, hi) == 0)
        {
            return;
        }
        let d = self.n;
        let saved = self.rhs.len();
        self.push_rows(i, self.edges[i][e]);
        let base = self.rhs.len();
        // The edge's own system, warm start of every test.
        self.related.0.reset();
        self.related
            .0
            .push(&self.rows[saved * d..], &self.rhs[saved..]);
        self.lp_tests += 1;
        let edge_feasible = self.related.0.repair();
        let mut point = usize::MAX;
        let mut point_feasible = false;
        for f in 0..self.edges[j].len() {
            let v = self.edge_offset[j] + f;
            if !has_bit(candidates, v) || has_bit(&self.known[u * w..(u + 1) * w], v) {
                continue;
            }
            set_bit(&mut self.known[u * w..(u + 1) * w], v);
            set_bit(&mut self.known[v * w..(v + 1) * w], u);
            if !edge_feasible {
                continue;
            }
            let edge = self.edges[j][f];
            self.push_rows(j, edge);
            let last = self.rhs.len() - 1;
            if edge.0 != point {
                point = edge.0;
                self.related.1.clone_from(&self.related.0);
                self.related
                    .1
                    .push(&self.rows[base * d..last * d], &self.rhs[base..last]);
                self.lp_tests += 1;
                point_feasible = self.related.1.repair();
            }
            if point_feasible {
                self.related.2.clone_from(&self.related.1);
                self.related
                    .2
                    .push(&self.rows[last * d..], &self.rhs[last..]);
                self.lp_tests += 1;
                if self.related.2.repair() {
                    set_bit(&mut self.relation[u * w..(u + 1) * w], v);
                    set_bit(&mut self.relation[v * w..(v + 1) * w], u);
                }
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
        let count = |i: usize| count_bits(candidates, self.edge_offset[i], self.edge_offset[i + 1]);
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
        let mut point = usize::MAX;
        let mut point_feasible = false;
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
            if remaining
                .iter()
                .any(|&j| count_bits(&child, self.edge_offset[j], self.edge_offset[j + 1]) == 0)
            {
                continue;
            }
            if self.lp_tests > self.max_lp_tests {
                return Err(CellError::OverBudget(self.max_lp_tests));
            }
            let edge = self.edges[i][e];
            self.push_rows(i, edge);
            let depth = self.n - remaining.len() - 1;
            let d = self.n;
            let last = self.rhs.len() - 1;
            if edge.0 != point {
                // The 1-point test: can p be on the lower face of support i?
                point = edge.0;
                let lp = &mut self.points[depth];
                lp.clone_from(&self.stack[depth]);
                lp.push(&self.rows[rows * d..last * d], &self.rhs[rows..last]);
                if !first {
                    self.lp_tests += 1;
                }
                point_feasible = lp.repair();
            }
            if point_feasible {
                let lp = &mut self.stack[depth + 1];
                lp.clone_from(&self.points[depth]);
                lp.push(&self.rows[last * d..], &self.rhs[last..]);
                if !first {
                    self.lp_tests += 1;
                }
                if lp.repair() {
                    // The equality of the pair closes one dimension for good.
                    lp.fix_last();
                    self.chosen[i] = edge;
                    self.descend(remaining, &child)?;
                }
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
        let volume = u64::try_from(d).map_err(|_| CellError::Overflow)?;
        self.cells.push(MixedCell {
            pairs: self.chosen.clone(),
            normal,
            volume,
            gaps,
        });
        self.volume += u128::from(volume);
        if self.volume > self.max_volume {
            return Err(CellError::OverVolume(self.max_volume));
        }
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
    fn a_search_past_its_volume_bound_gives_up() {
        let s = dense_quadrics();
        let lifting = random_lifting(&s, 1, 0, 1 << 12);
        let full = mixed_cells(&s, &lifting).unwrap();
        assert_eq!(full.mixed_volume, 4);
        assert_eq!(
            mixed_cells_bounded(&s, &lifting, usize::MAX, 3),
            Err(CellError::OverVolume(3))
        );
        assert_eq!(mixed_cells_bounded(&s, &lifting, usize::MAX, 4), Ok(full));
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

    /// All exponent vectors in `n` unknowns of total degree at most `degree`.
    fn dense(n: usize, degree: i64) -> Vec<Vec<i64>> {
        let mut all = vec![vec![]];
        for _ in 0..n {
            all = all
                .into_iter()
                .flat_map(|p: Vec<i64>| {
                    (0..=degree).map(move |e| {
                        let mut q = p.clone();
                        q.push(e);
                        q
                    })
                })
                .filter(|q| q.iter().sum::<i64>() <= degree)
                .collect();
        }
        all
    }

    /// cyclic-n: `Σ_i Π_{j<k} x_{i+j}` for k = 1 … n − 1 and `x_0 ⋯ x_{n−1} − 1`.
    fn cyclic(n: usize) -> Supports {
        let mut equations = Vec::new();
        for k in 1..n {
            equations.push(
                (0..n)
                    .map(|i| {
                        let mut a = vec![0i64; n];
                        for j in 0..k {
                            a[(i + j) % n] = 1;
                        }
                        a
                    })
                    .collect(),
            );
        }
        equations.push(vec![vec![1i64; n], vec![0; n]]);
        Supports::new(n, equations)
    }

    /// katsura-n in `x_0 … x_n`: `x_0 + 2 Σ x_i − 1` and for m = 0 … n − 1
    /// `Σ_{l=−n..n} x_{|l|} x_{|m−l|} − x_m` (`x_i = 0` for i > n).
    fn katsura(n: usize) -> Supports {
        let v = n + 1;
        let unit = |i: usize| {
            let mut a = vec![0i64; v];
            a[i] = 1;
            a
        };
        let mut linear: Vec<Vec<i64>> = (0..v).map(unit).collect();
        linear.push(vec![0; v]);
        let mut equations = vec![linear];
        for m in 0..n as i64 {
            let mut points = vec![unit(m as usize)];
            for l in -(n as i64)..=n as i64 {
                let (a, b) = (l.unsigned_abs() as usize, (m - l).unsigned_abs() as usize);
                if a <= n && b <= n {
                    let mut p = vec![0i64; v];
                    p[a] += 1;
                    p[b] += 1;
                    points.push(p);
                }
            }
            equations.push(points);
        }
        Supports::new(v, equations)
    }

    #[test]
    fn mixed_volumes_of_known_systems() {
        // Bernstein's bound of cyclic-5 is its 70 isolated roots.
        assert_eq!(mv(&cyclic(5), 3), 70);
        assert_eq!(mv(&cyclic(4).with_origin(), 3), 16);
        // katsura-n: the Bézout number 2^n in C^n (fewer in the torus: its quadrics
        // lack constant terms).
        for n in 3..=5 {
            assert_eq!(mv(&katsura(n).with_origin(), 5), 1 << n, "katsura{n}");
            assert!(mv(&katsura(n), 4) < 1 << n, "katsura{n}");
        }
        // Dense supports: the Bézout number 2 · 3 · 2.
        let s = Supports::new(3, vec![dense(3, 2), dense(3, 3), dense(3, 2)]);
        assert_eq!(mv(&s, 6), 12);
    }

    /// The mixed cells by brute force: every choice of one pair per support whose
    /// exact inner normal makes the pairs the lower faces.
    fn brute_force(supports: &Supports, lifting: &[Vec<i64>]) -> Result<Vec<MixedCell>, CellError> {
        let n = supports.num_variables();
        let mut cells = Vec::new();
        let pairs: Vec<Vec<(usize, usize)>> = (0..n)
            .map(|i| {
                let m = supports.support(i).len();
                (0..m)
                    .flat_map(|p| (p + 1..m).map(move |q| (p, q)))
                    .collect()
            })
            .collect();
        let mut index = vec![0usize; n];
        'choices: loop {
            let chosen: Vec<(usize, usize)> = (0..n).map(|i| pairs[i][index[i]]).collect();
            let mut matrix = vec![0i128; n * n];
            let mut rhs = vec![0i128; n];
            for (i, &(p, q)) in chosen.iter().enumerate() {
                let points = supports.support(i);
                for j in 0..n {
                    matrix[i * n + j] = (points[q][j] - points[p][j]) as i128;
                }
                rhs[i] = (lifting[i][p] - lifting[i][q]) as i128;
            }
            let det = bareiss_determinant(&matrix, n)?;
            if det != 0 {
                let mut normal = vec![0i128; n];
                for (j, nj) in normal.iter_mut().enumerate() {
                    let mut replaced = matrix.clone();
                    for i in 0..n {
                        replaced[i * n + j] = rhs[i];
                    }
                    *nj = bareiss_determinant(&replaced, n)? * det.signum();
                }
                let d = det.abs();
                let mut gaps = Vec::new();
                for (i, &(p, q)) in chosen.iter().enumerate() {
                    let points = supports.support(i);
                    for (k, a) in points.iter().enumerate() {
                        let g = (0..n)
                            .map(|j| (a[j] - points[p][j]) as i128 * normal[j])
                            .sum::<i128>()
                            + (lifting[i][k] - lifting[i][p]) as i128 * d;
                        gaps.push((g, k == p || k == q));
                    }
                }
                if gaps.iter().all(|&(g, _)| g >= 0) {
                    if gaps.iter().any(|&(g, on_pair)| g == 0 && !on_pair) {
                        return Err(CellError::NonGenericLifting);
                    }
                    cells.push(MixedCell {
                        pairs: chosen,
                        normal,
                        volume: d as u64,
                        gaps: gaps.into_iter().map(|(g, _)| g).collect(),
                    });
                }
            }
            for i in 0..n {
                index[i] += 1;
                if index[i] < pairs[i].len() {
                    continue 'choices;
                }
                index[i] = 0;
            }
            break;
        }
        Ok(cells)
    }

    /// The warm-started search finds exactly the cells of the brute force, on small
    /// random supports (and their mixed volume), for many liftings.
    #[test]
    fn the_search_finds_the_cells_of_the_brute_force() {
        use rand::Rng;
        let mut rng = crate::random::stream(11, 0);
        let mut compared = 0;
        for trial in 0..60u64 {
            let n = 2 + (trial % 3) as usize;
            let supports = Supports::new(
                n,
                (0..n)
                    .map(|_| {
                        let m = 3 + (rng.next_u64() % 3) as usize;
                        (0..m)
                            .map(|_| (0..n).map(|_| (rng.next_u64() % 4) as i64).collect())
                            .collect()
                    })
                    .collect(),
            );
            if (0..n).any(|i| supports.support(i).len() < 2) {
                continue;
            }
            // Small liftings make ties, and so the non-generic case, likely too.
            let range = if trial % 2 == 0 { 1 << 12 } else { 8 };
            let lifting = random_lifting(&supports, trial, 1, range);
            let expected = brute_force(&supports, &lifting);
            let found = mixed_cells(&supports, &lifting);
            match (expected, found) {
                (Ok(mut expected), Ok(found)) => {
                    let volume: u128 = expected.iter().map(|c| c.volume as u128).sum();
                    assert_eq!(found.mixed_volume, volume, "trial {trial}");
                    let mut cells = found.cells.clone();
                    cells.sort_by(|a, b| a.pairs.cmp(&b.pairs));
                    expected.sort_by(|a, b| a.pairs.cmp(&b.pairs));
                    assert_eq!(cells, expected, "trial {trial}");
                    compared += 1;
                }
                (Err(CellError::NonGenericLifting), _) => {}
                // A tie the brute force skips (dependent pairs on a common lower face).
                (_, Err(CellError::NonGenericLifting)) if range == 8 => {}
                (expected, found) => panic!("trial {trial}: {expected:?} against {found:?}"),
            }
        }
        assert!(compared >= 40, "{compared} comparisons");
    }

    #[test]
    fn the_search_is_deterministic() {
        let s = katsura(4).with_origin();
        let lifting = random_lifting(&s, 9, 0, 1 << 22);
        let a = mixed_cells(&s, &lifting).unwrap();
        let b = mixed_cells(&s, &lifting).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.mixed_volume, 16);
    }
}
