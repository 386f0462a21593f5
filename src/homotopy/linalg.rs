//! Dense complex linear algebra for the tracker's hot loop.
//!
//! Every predictor stage and Newton iteration solves `J Δ = b` with the n × n Jacobian
//! `J = ∂H/∂x` (n = 11..19 for singdist's problems). At that size a plain LU
//! factorisation with partial pivoting (`P J = L U`, Golub & Van Loan Alg. 3.4.1) on a
//! preallocated row-major buffer beats general-purpose libraries, whose per-call set-up
//! dominates (see `benches/tracker_linalg.rs`: this LU against nalgebra and faer. With
//! the AVX2 row update (`subtract_scaled_row_avx2`) factor + solve took
//! 0.87/1.26/1.77/2.45 µs for n = 11/13/16/19, against 1.33/1.83/3.45/3.60 µs for
//! faer's allocation-free `lu_in_place` in the same run; nalgebra was slower still.
//! Delegating n ≥ 18 to faer was tried and lost its edge to the layout copies, and a
//! split real/imaginary layout was slower than interleaved complex entries for rows
//! this short, so this loop is used for every n).
//!
//! Besides solving, the workspace offers
//! - the adjoint solve `Jᴴ y = b` from the same factors,
//! - a 1-norm condition estimate `κ₁(J) ≈ ‖J‖₁ ‖J⁻¹‖₁` by Hager's method in Higham's
//!   complex form (Higham, *Accuracy and Stability of Numerical Algorithms*, Alg. 15.4),
//! - mixed-precision iterative refinement: the residual `b − J Δ` is accumulated in
//!   double-double arithmetic (error-free `TwoSum`/`TwoProduct`, Dekker 1971), which
//!   recovers a backward-stable solution on ill-conditioned stretches of a path where
//!   the plain double solve loses digits.
//!
//! Nothing here allocates after [`LuWorkspace::new`].

use crate::C64;
use crate::system::double_double::{ComplexDd, DoubleDouble};

/// `t ← t − f·u` entrywise (rows of equal length), products as num-complex forms
/// them: `f·u = (f_re u_re − f_im u_im, f_re u_im + f_im u_re)`.
#[inline(always)]
fn subtract_scaled_row(target: &mut [C64], row: &[C64], f: C64) {
    for (t, &u) in target.iter_mut().zip(row) {
        *t -= f * u;
    }
}

/// [`subtract_scaled_row`] with AVX2 intrinsics, two complex entries per 256-bit
/// register: `u·f_re` and `swap(u)·f_im` combined by one `addsub` give
/// `(u_re f_re − u_im f_im, u_im f_re + u_re f_im)`, the same products and sums as
/// num-complex's `f·u` (no fused operations), so results are bit-identical.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn subtract_scaled_row_avx2(target: &mut [C64], row: &[C64], f: C64) {
    use std::arch::x86_64::{
        _mm256_addsub_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_permute_pd, _mm256_set1_pd,
        _mm256_storeu_pd, _mm256_sub_pd,
    };
    let len = target.len().min(row.len());
    let t = target.as_mut_ptr() as *mut f64;
    let u = row.as_ptr() as *const f64;
    let f_re = _mm256_set1_pd(f.re);
    let f_im = _mm256_set1_pd(f.im);
    let mut j = 0;
    while j + 2 <= len {
        // SAFETY: entries j and j + 1 are in bounds of both slices (j + 2 ≤ len), and
        // `Complex<f64>` is `repr(C)`: `(re, im)` pairs of contiguous f64.
        unsafe {
            let uv = _mm256_loadu_pd(u.add(2 * j));
            let swapped = _mm256_permute_pd(uv, 0b0101);
            let product = _mm256_addsub_pd(_mm256_mul_pd(uv, f_re), _mm256_mul_pd(swapped, f_im));
            let tv = _mm256_loadu_pd(t.add(2 * j));
            _mm256_storeu_pd(t.add(2 * j), _mm256_sub_pd(tv, product));
        }
        j += 2;
    }
    if j < len {
        target[j] -= f * row[j];
    }
}

/// Preallocated LU factorisation `P A = L U` of an n × n complex matrix (row-major).
#[derive(Clone, Debug)]
pub struct LuWorkspace {
    n: usize,
    /// Copy of the factored matrix `A` (needed for residuals and refinement).
    matrix: Vec<C64>,
    /// `L` (unit lower, strictly below the diagonal) and `U` (upper) packed together.
    factors: Vec<C64>,
    /// Row `i` of `P A` is row `permutation[i]` of `A`.
    permutation: Vec<usize>,
    scratch: Vec<C64>,
    scratch_b: Vec<C64>,
    matrix_norm1: f64,
    singular: bool,
}

impl LuWorkspace {
    /// Workspace for n × n matrices.
    pub fn new(n: usize) -> Self {
        LuWorkspace {
            n,
            matrix: vec![C64::new(0.0, 0.0); n * n],
            factors: vec![C64::new(0.0, 0.0); n * n],
            permutation: (0..n).collect(),
            scratch: vec![C64::new(0.0, 0.0); n],
            scratch_b: vec![C64::new(0.0, 0.0); n],
            matrix_norm1: 0.0,
            singular: true,
        }
    }

    /// Dimension n.
    pub fn dimension(&self) -> usize {
        self.n
    }

    /// Factors the row-major matrix `a` (copied). Returns `false` if a pivot is exactly
    /// zero or not finite (the matrix is numerically singular); solves are then invalid.
    pub fn factor(&mut self, a: &[C64]) -> bool {
        #[cfg(target_arch = "x86_64")]
        if crate::system::double_double::has_avx2_fma() {
            // SAFETY: the CPU supports AVX2 and FMA (checked at run time just above).
            return unsafe { self.factor_with_avx2(a) };
        }
        self.factor_generic(a)
    }

    /// [`LuWorkspace::factor`] compiled with AVX2, with the row updates in
    /// [`subtract_scaled_row_avx2`] (two complex entries per instruction; the same
    /// products and sums, so the same rounding).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn factor_with_avx2(&mut self, a: &[C64]) -> bool {
        // SAFETY: this function runs only where the CPU supports AVX2.
        self.factor_with(a, |target, row, f| unsafe {
            subtract_scaled_row_avx2(target, row, f)
        })
    }

    fn factor_generic(&mut self, a: &[C64]) -> bool {
        self.factor_with(a, subtract_scaled_row)
    }

    /// `P A = L U` by rows (right-looking), with `update(t, u, f)` doing `t ← t − f·u`.
    #[inline(always)]
    fn factor_with(&mut self, a: &[C64], update: impl Fn(&mut [C64], &[C64], C64)) -> bool {
        let n = self.n;
        debug_assert_eq!(a.len(), n * n);
        self.matrix.copy_from_slice(a);
        self.factors.copy_from_slice(a);
        self.matrix_norm1 = f64::NAN;
        for (i, p) in self.permutation.iter_mut().enumerate() {
            *p = i;
        }
        let lu = &mut self.factors;
        for k in 0..n {
            // Pivot: largest |entry|² in column k at or below the diagonal.
            let mut pivot_row = k;
            let mut pivot_size = lu[k * n + k].norm_sqr();
            for i in k + 1..n {
                let size = lu[i * n + k].norm_sqr();
                if size > pivot_size {
                    pivot_size = size;
                    pivot_row = i;
                }
            }
            if pivot_size == 0.0 || !pivot_size.is_finite() {
                self.singular = true;
                return false;
            }
            if pivot_row != k {
                for j in 0..n {
                    lu.swap(k * n + j, pivot_row * n + j);
                }
                self.permutation.swap(k, pivot_row);
            }
            let inverse_pivot = lu[k * n + k].inv();
            for i in k + 1..n {
                let factor = lu[i * n + k] * inverse_pivot;
                lu[i * n + k] = factor;
                if factor.re != 0.0 || factor.im != 0.0 {
                    let (upper, lower) = lu.split_at_mut(i * n);
                    update(
                        &mut lower[k + 1..n],
                        &upper[k * n + k + 1..k * n + n],
                        factor,
                    );
                }
            }
        }
        self.singular = false;
        true
    }

    /// Whether the last factorisation failed.
    pub fn is_singular(&self) -> bool {
        self.singular
    }

    /// `‖A‖₁` (maximal column sum of moduli) of the last factored matrix, computed on
    /// first use after each factorisation (the hot loop never needs it).
    pub fn matrix_norm1(&mut self) -> f64 {
        if self.matrix_norm1.is_nan() {
            let n = self.n;
            let mut norm1: f64 = 0.0;
            for j in 0..n {
                let column: f64 = (0..n).map(|i| crate::modulus(self.matrix[i * n + j])).sum();
                norm1 = norm1.max(column);
            }
            self.matrix_norm1 = norm1;
        }
        self.matrix_norm1
    }

    /// Solves `A x = b` in place (`b` becomes `x`).
    pub fn solve_in_place(&mut self, b: &mut [C64]) {
        #[cfg(target_arch = "x86_64")]
        if crate::system::double_double::has_avx2_fma() {
            // SAFETY: the CPU supports AVX2 and FMA (checked at run time just above).
            unsafe { self.solve_with_avx2(b) };
            return;
        }
        self.solve_generic(b)
    }

    /// [`LuWorkspace::solve_in_place`] compiled with AVX2 (same operations, same
    /// rounding).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn solve_with_avx2(&mut self, b: &mut [C64]) {
        self.solve_generic(b)
    }

    #[inline(always)]
    fn solve_generic(&mut self, b: &mut [C64]) {
        let n = self.n;
        let lu = &self.factors;
        let y = &mut self.scratch;
        for i in 0..n {
            y[i] = b[self.permutation[i]];
        }
        for i in 0..n {
            let mut sum = y[i];
            let row = &lu[i * n..i * n + i];
            for (l, yj) in row.iter().zip(y.iter()) {
                sum -= l * yj;
            }
            y[i] = sum;
        }
        for i in (0..n).rev() {
            let row = &lu[i * n..i * n + n];
            let mut sum = y[i];
            for (u, yj) in row[i + 1..].iter().zip(&y[i + 1..]) {
                sum -= u * yj;
            }
            y[i] = sum / row[i];
        }
        b.copy_from_slice(y);
    }

    /// Solves `Aᴴ x = b` in place, with `A = Pᵀ L U` so `Aᴴ = Uᴴ Lᴴ P`.
    pub fn solve_adjoint_in_place(&mut self, b: &mut [C64]) {
        let n = self.n;
        let lu = &self.factors;
        let z = &mut self.scratch;
        z.copy_from_slice(b);
        // Uᴴ z = b (forward substitution with the conjugate transpose of U).
        for i in 0..n {
            let mut sum = z[i];
            for j in 0..i {
                sum -= lu[j * n + i].conj() * z[j];
            }
            z[i] = sum / lu[i * n + i].conj();
        }
        // Lᴴ w = z (backward, unit diagonal).
        for i in (0..n).rev() {
            let mut sum = z[i];
            for j in i + 1..n {
                sum -= lu[j * n + i].conj() * z[j];
            }
            z[i] = sum;
        }
        // P x = w.
        for i in 0..n {
            b[self.permutation[i]] = z[i];
        }
    }

    /// Estimate of `‖A⁻¹‖₁` (Hager–Higham, at most five solve pairs; a lower bound that is
    /// almost always within a factor 3 of the truth).
    pub fn inverse_norm1_estimate(&mut self) -> f64 {
        let n = self.n;
        if self.singular {
            return f64::INFINITY;
        }
        if n == 0 {
            return 0.0;
        }
        let mut x = std::mem::take(&mut self.scratch_b);
        let fill = C64::new(1.0 / n as f64, 0.0);
        x.iter_mut().for_each(|v| *v = fill);
        let mut estimate = 0.0;
        let mut previous_index = usize::MAX;
        for iteration in 0..5 {
            self.solve_in_place(&mut x);
            let norm: f64 = x.iter().map(|v| crate::modulus(*v)).sum();
            if iteration > 0 && norm <= estimate {
                estimate = estimate.max(norm);
                break;
            }
            estimate = norm;
            for v in x.iter_mut() {
                let r = crate::modulus(*v);
                *v = if r > 0.0 { *v / r } else { C64::new(1.0, 0.0) };
            }
            self.solve_adjoint_in_place(&mut x);
            let mut best = 0;
            let mut best_size = -1.0;
            for (j, v) in x.iter().enumerate() {
                let size = crate::modulus(*v);
                if size > best_size {
                    best_size = size;
                    best = j;
                }
            }
            if best == previous_index {
                break;
            }
            previous_index = best;
            x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
            x[best] = C64::new(1.0, 0.0);
        }
        self.scratch_b = x;
        if estimate.is_finite() {
            estimate
        } else {
            f64::INFINITY
        }
    }

    /// Estimate of the 1-norm condition number `κ₁(A) = ‖A‖₁ ‖A⁻¹‖₁`.
    pub fn condition_estimate(&mut self) -> f64 {
        self.matrix_norm1() * self.inverse_norm1_estimate()
    }

    /// One step of mixed-precision iterative refinement of a solution `x` of `A x = b`:
    /// `r ← b − A x` accumulated in double-double, `x ← x + A⁻¹ r`.
    pub fn refine(&mut self, b: &[C64], x: &mut [C64]) {
        let n = self.n;
        let mut r = std::mem::take(&mut self.scratch_b);
        for i in 0..n {
            let mut re = DoubleDouble::from_f64(b[i].re);
            let mut im = DoubleDouble::from_f64(b[i].im);
            let row = &self.matrix[i * n..i * n + n];
            for (a, xj) in row.iter().zip(x.iter()) {
                re.add_product(-a.re, xj.re);
                re.add_product(a.im, xj.im);
                im.add_product(-a.re, xj.im);
                im.add_product(-a.im, xj.re);
            }
            r[i] = C64::new(re.value(), im.value());
        }
        self.solve_in_place(&mut r);
        for (xi, ri) in x.iter_mut().zip(r.iter()) {
            *xi += ri;
        }
        self.scratch_b = r;
    }
}

/// LU factorisation with partial pivoting in double-double arithmetic, for matrices
/// known beyond double precision (`A = A_hi + A_lo`, e.g. a Jacobian evaluated in
/// double-double). Solutions are accurate to about `κ(A)·10⁻³²` relative, where the
/// double-precision [`LuWorkspace`] gives `κ(A)·10⁻¹⁶`: the tracker's velocities and
/// Newton updates at points with `κ` up to ~10²⁵ (huge critical points near infinity).
pub struct DdLuWorkspace {
    n: usize,
    /// Row-major factors: unit lower L below the diagonal, U on and above it.
    factors: Vec<ComplexDd>,
    /// `1 / U_kk`.
    inverse_diagonal: Vec<ComplexDd>,
    /// Row permutation: row k of PA is row `permutation[k]` of A.
    permutation: Vec<usize>,
    scratch: Vec<ComplexDd>,
}

impl DdLuWorkspace {
    /// Workspace for n × n matrices.
    pub fn new(n: usize) -> Self {
        DdLuWorkspace {
            n,
            factors: vec![ComplexDd::default(); n * n],
            inverse_diagonal: vec![ComplexDd::default(); n],
            permutation: (0..n).collect(),
            scratch: vec![ComplexDd::default(); n],
        }
    }

    /// Factors `hi + lo` (row-major); `false` if a pivot is exactly zero or not finite.
    /// (Runs a copy compiled with the `fma` target feature where the CPU has it.)
    pub fn factor(&mut self, hi: &[C64], lo: &[C64]) -> bool {
        #[cfg(target_arch = "x86_64")]
        if crate::system::double_double::has_fma() {
            // SAFETY: the CPU supports FMA (checked at run time just above).
            return unsafe { self.factor_with_fma(hi, lo) };
        }
        self.factor_generic(hi, lo)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "fma")]
    fn factor_with_fma(&mut self, hi: &[C64], lo: &[C64]) -> bool {
        self.factor_generic(hi, lo)
    }

    #[inline(always)]
    fn factor_generic(&mut self, hi: &[C64], lo: &[C64]) -> bool {
        let n = self.n;
        for (f, (h, l)) in self.factors.iter_mut().zip(hi.iter().zip(lo)) {
            *f = ComplexDd::from_parts(*h, *l);
        }
        for (k, p) in self.permutation.iter_mut().enumerate() {
            *p = k;
        }
        for k in 0..n {
            let mut pivot_row = k;
            let mut pivot_size = 0.0f64;
            for i in k..n {
                let size = self.factors[i * n + k].to_c64().norm();
                if size > pivot_size {
                    pivot_size = size;
                    pivot_row = i;
                }
            }
            if !(pivot_size > 0.0 && pivot_size.is_finite()) {
                return false;
            }
            if pivot_row != k {
                for j in 0..n {
                    self.factors.swap(k * n + j, pivot_row * n + j);
                }
                self.permutation.swap(k, pivot_row);
            }
            let inverse = self.factors[k * n + k].recip();
            self.inverse_diagonal[k] = inverse;
            for i in k + 1..n {
                let multiplier = self.factors[i * n + k] * inverse;
                self.factors[i * n + k] = multiplier;
                for j in k + 1..n {
                    self.factors[i * n + j] =
                        self.factors[i * n + j].minus_product(multiplier, self.factors[k * n + j]);
                }
            }
        }
        true
    }

    /// `x ← A⁻¹ b` with the last factorisation (`b` and the result in double).
    pub fn solve_in_place(&mut self, b: &mut [C64]) {
        #[cfg(target_arch = "x86_64")]
        if crate::system::double_double::has_fma() {
            // SAFETY: the CPU supports FMA (checked at run time just above).
            unsafe { self.solve_with_fma(b) };
            return;
        }
        self.solve_generic(b);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "fma")]
    fn solve_with_fma(&mut self, b: &mut [C64]) {
        self.solve_generic(b);
    }

    #[inline(always)]
    fn solve_generic(&mut self, b: &mut [C64]) {
        let n = self.n;
        for (k, s) in self.scratch.iter_mut().enumerate() {
            *s = ComplexDd::from_c64(b[self.permutation[k]]);
        }
        for i in 0..n {
            let mut sum = self.scratch[i];
            for j in 0..i {
                sum = sum.minus_product(self.factors[i * n + j], self.scratch[j]);
            }
            self.scratch[i] = sum;
        }
        for i in (0..n).rev() {
            let mut sum = self.scratch[i];
            for j in i + 1..n {
                sum = sum.minus_product(self.factors[i * n + j], self.scratch[j]);
            }
            self.scratch[i] = sum * self.inverse_diagonal[i];
        }
        for (x, s) in b.iter_mut().zip(&self.scratch) {
            *x = s.to_c64();
        }
    }
}

#[cfg(test)]
mod tests {
    /// The AVX2 copies of factor and solve (chosen at run time) round exactly as the
    /// baseline code: bit-identical factors and solutions.
    #[test]
    fn dispatched_lu_matches_the_baseline_bit_for_bit() {
        let n = 13;
        let mut rng = crate::random::seeded(7);
        let a: Vec<C64> = (0..n * n)
            .map(|_| crate::random::complex_normal(&mut rng))
            .collect();
        let b: Vec<C64> = (0..n)
            .map(|_| crate::random::complex_normal(&mut rng))
            .collect();
        let (mut dispatched, mut baseline) = (LuWorkspace::new(n), LuWorkspace::new(n));
        assert!(dispatched.factor(&a) && baseline.factor_generic(&a));
        assert_eq!(dispatched.factors, baseline.factors);
        let (mut x, mut y) = (b.clone(), b);
        dispatched.solve_in_place(&mut x);
        baseline.solve_generic(&mut y);
        assert_eq!(x, y);
    }

    use super::*;
    use crate::random::{complex_normal, seeded};

    fn random_matrix(n: usize, seed: u64) -> Vec<C64> {
        let mut rng = seeded(seed);
        (0..n * n).map(|_| complex_normal(&mut rng)).collect()
    }

    fn multiply(a: &[C64], x: &[C64]) -> Vec<C64> {
        let n = x.len();
        (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect()
    }

    /// Blocks `[[a, a+1], [a−1, a]]` (determinant 1, κ ≈ 4a²) with integer entries and
    /// right-hand sides, so the system is exact in double: with a = 10⁷ (κ ≈ 10¹⁴) the
    /// double-double LU recovers the solution to double accuracy, the double LU only to
    /// about κ·ε.
    #[test]
    fn double_double_lu_solves_ill_conditioned_systems_to_double_accuracy() {
        let n = 6;
        let a = 1e7;
        let mut matrix = vec![C64::new(0.0, 0.0); n * n];
        let x_true: Vec<C64> = (0..n)
            .map(|i| C64::new(1.0 + i as f64, 2.0 - i as f64))
            .collect();
        for block in 0..n / 2 {
            let (r, c) = (2 * block, 2 * block);
            let unit = [C64::new(1.0, 0.0), C64::new(0.0, 1.0), C64::new(-1.0, 0.0)][block];
            matrix[r * n + c] = unit * a;
            matrix[r * n + c + 1] = unit * (a + 1.0);
            matrix[(r + 1) * n + c] = unit * (a - 1.0);
            matrix[(r + 1) * n + c + 1] = unit * a;
        }
        let b: Vec<C64> = (0..n)
            .map(|i| (0..n).map(|j| matrix[i * n + j] * x_true[j]).sum())
            .collect();
        let error = |x: &[C64]| {
            x.iter()
                .zip(&x_true)
                .fold(0.0f64, |m, (u, v)| m.max((u - v).norm()))
        };
        let mut lu = LuWorkspace::new(n);
        assert!(lu.factor(&matrix));
        assert!(lu.condition_estimate() > 1e13);
        let mut x_double = b.clone();
        lu.solve_in_place(&mut x_double);
        let mut dd = DdLuWorkspace::new(n);
        assert!(dd.factor(&matrix, &vec![C64::new(0.0, 0.0); n * n]));
        let mut x_dd = b.clone();
        dd.solve_in_place(&mut x_dd);
        assert!(
            error(&x_dd) < 1e-12,
            "double-double LU error {:e}",
            error(&x_dd)
        );
        assert!(
            error(&x_double) > 1e-6,
            "double LU error {:e}",
            error(&x_double)
        );
    }

    #[test]
    fn solve_and_adjoint_solve_reproduce_right_hand_sides() {
        for n in [1, 2, 5, 11, 13, 16, 19, 24] {
            let a = random_matrix(n, n as u64);
            let mut lu = LuWorkspace::new(n);
            assert!(lu.factor(&a));
            let x_true: Vec<C64> = (0..n).map(|i| C64::new(i as f64, 1.0 - i as f64)).collect();
            let mut b = multiply(&a, &x_true);
            lu.solve_in_place(&mut b);
            for (u, v) in b.iter().zip(&x_true) {
                assert!((u - v).norm() < 1e-10, "n = {n}");
            }
            // adjoint
            let ah: Vec<C64> = (0..n * n).map(|k| a[(k % n) * n + k / n].conj()).collect();
            let mut c = multiply(&ah, &x_true);
            lu.solve_adjoint_in_place(&mut c);
            for (u, v) in c.iter().zip(&x_true) {
                assert!((u - v).norm() < 1e-10, "adjoint n = {n}");
            }
        }
    }

    #[test]
    fn condition_estimate_tracks_a_known_condition_number() {
        // Diagonal matrix: κ₁ = max|d| / min|d| exactly.
        let n = 6;
        let mut a = vec![C64::new(0.0, 0.0); n * n];
        for i in 0..n {
            a[i * n + i] = C64::new(10f64.powi(i as i32), 0.0);
        }
        let mut lu = LuWorkspace::new(n);
        assert!(lu.factor(&a));
        let kappa = lu.condition_estimate();
        assert!((kappa / 1e5 - 1.0).abs() < 1e-12, "{kappa}");
        // Singular matrix is detected.
        let zero = vec![C64::new(0.0, 0.0); n * n];
        assert!(!lu.factor(&zero));
    }

    #[test]
    fn double_double_refinement_improves_an_ill_conditioned_solve() {
        // Hilbert-like complex matrix, κ ≈ 1e13.
        let n = 10;
        let a: Vec<C64> = (0..n * n)
            .map(|k| C64::new(1.0 / ((k / n + k % n + 1) as f64), 0.0))
            .collect();
        let x_true: Vec<C64> = (0..n).map(|i| C64::new(1.0, i as f64 * 0.1)).collect();
        let b = multiply(&a, &x_true);
        let mut lu = LuWorkspace::new(n);
        assert!(lu.factor(&a));
        let mut x = b.clone();
        lu.solve_in_place(&mut x);
        let residual = |x: &[C64]| -> f64 {
            multiply(&a, x)
                .iter()
                .zip(&b)
                .map(|(u, v)| (u - v).norm())
                .fold(0.0, f64::max)
        };
        let before = residual(&x);
        lu.refine(&b, &mut x);
        lu.refine(&b, &mut x);
        let after = residual(&x);
        assert!(after <= before, "{after} > {before}");
        assert!(after < 1e-14, "{after}");
    }
}
