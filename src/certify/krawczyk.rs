//! Krawczyk's test: a proof that a box contains exactly one solution of `F(x; p) = 0`.
//!
//! For a square system `F`, a centre `c`, a box `X ∋ c` and any invertible matrix `Y`
//! (here the floating-point inverse of `∂F/∂x(c)`), the Krawczyk operator is
//!
//! `K(X) = c − Y·F(c) + (I − Y·∂F/∂x(X))·(X − c)`,
//!
//! evaluated in interval arithmetic. If `K(X)` lies in the interior of `X`, then `X`
//! contains exactly one solution of `F = 0`, and it is nonsingular (Krawczyk,
//! "Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken", Computing
//! 1969; Moore, "A test for existence of solutions to nonlinear systems", SIAM J. Numer.
//! Anal. 1977; Rump, "Verification methods", Acta Numerica 2010, Thm. 8.1; complex
//! boxes as in Breiding, Rose, Timme, "Certifying zeros of polynomial systems using
//! interval arithmetic", ACM TOMS 2023).
//!
//! The product `(I − Y·∂F/∂x(X))·(X − c)` is replaced by the box `[−t, t]` (per real
//! and imaginary part) with `t ≥ |I − Y·J|·mag(X − c)` for every `J ∈ ∂F/∂x(X)`
//! ([`MidpointRadius::product_bound`]). The conclusion stands: for `x, x′ ∈ X`,
//! `F(x) − F(x′) = J̄·(x − x′)` with `J̄`, the mean of `∂F/∂x` over the segment, in the
//! convex box `∂F/∂x(X)`; so `x ↦ x − Y·F(x)` maps `X` into `c − Y·F(c) + [−t, t] ⊂ X`
//! (a fixed point by Brouwer's theorem), and inclusion in the interior gives
//! `P·rad(X − c) ≤ t < rad(X − c)` for the non-negative matrix `P ≥ |I − Y·J|` behind
//! `t` (in the real form of the complex matrices), so `ρ(P) < 1` (Perron–Frobenius):
//! `Y` and every `J` are nonsingular, the fixed point is a solution, and two solutions
//! would satisfy `|x − x′| ≤ P·|x − x′|`, so they coincide.
//!
//! **Realness.** When every coefficient of `F(·; p)` is real, the conjugate of a
//! solution is a solution. A box centred on a real point with a symmetric imaginary
//! part is closed under conjugation, so the unique solution it contains equals its own
//! conjugate: it is real. A box whose imaginary part excludes zero in some coordinate
//! contains no real point: its solution is not real.
//!
//! **Distinctness.** Two disjoint boxes that each contain exactly one solution contain
//! two different solutions; a pair of overlapping boxes is reported, since both may hold
//! the same solution.

use super::midrad::{MidpointRadius, negated_product};
use crate::C64;
use crate::homotopy::linalg::LuWorkspace;
use crate::homotopy::newton::max_norm;
use crate::homotopy::refine::same_point;
use crate::system::Evaluator;
use crate::system::compile::CompiledSystem;
use crate::system::double_double::ComplexDd;
use crate::system::interval::{ComplexInterval, Interval};
use crate::system::interval_dd::MidRadDd;
use serde::{Deserialize, Serialize};

/// What a certificate says about a solution's realness.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Realness {
    /// Proved real (a conjugation-closed box of a real system).
    Real,
    /// Proved not real (the box misses the real space).
    NonReal,
    /// Not decided (complex coefficients, or a box that meets the real space but is
    /// not closed under conjugation).
    Undecided,
}

/// A box proved to contain exactly one solution.
#[derive(Clone, Debug, PartialEq)]
pub struct RootBox {
    /// The box in which the solution is unique, one complex rectangle per unknown.
    pub bounds: Vec<ComplexInterval>,
    /// A tighter box (inside `bounds`) that contains the solution.
    pub enclosure: Vec<ComplexInterval>,
    /// Its centre (the refined approximation).
    pub center: Vec<C64>,
    /// Largest half-width of the enclosure over coordinates and parts.
    pub radius: f64,
    /// Realness of the solution in it.
    pub realness: Realness,
}

impl RootBox {
    /// Whether the two enclosures share a point (they may then hold the same
    /// solution; disjoint enclosures hold different ones).
    pub fn meets(&self, other: &RootBox) -> bool {
        self.enclosure
            .iter()
            .zip(&other.enclosure)
            .all(|(a, b)| a.meets(b))
    }

    /// The real box of a real solution (the enclosure's real parts).
    pub fn real_part(&self) -> Vec<Interval> {
        self.enclosure.iter().map(|b| b.re).collect()
    }
}

/// Rounds of ε-inflation before a point is given up.
const INFLATION_STEPS: usize = 12;
/// Newton steps that polish an approximation before it is tested (at most).
const POLISH_STEPS: usize = 3;
/// Relative Newton update below which polishing stops (the next update would be of
/// the order of its square times the condition: below the rounding error).
const POLISHED: f64 = 1e-10;
/// Newton steps of the double-double polish ([`Krawczyk::certify_extended`]) at most:
/// each gains about `−log₁₀(κ·u)` digits (at least 5 on the points it serves).
const EXTENDED_POLISH_STEPS: usize = 8;
/// Relative Newton update below which the double-double polish stops.
const EXTENDED_POLISHED: f64 = 1e-28;
/// Relative Newton update the double-double polish must reach, or stagnate below
/// (at condition κ its updates level off near `κ·u²`: about 10⁻²³ at κ ≈ 10¹⁰).
const EXTENDED_ACCURATE: f64 = 1e-18;

/// A reusable Krawczyk test for one square system at one parameter point.
pub struct Krawczyk<'a> {
    system: &'a CompiledSystem,
    parameters: Vec<C64>,
    parameter_boxes: Vec<ComplexInterval>,
    /// The parameter boxes with double-double midpoints, where known
    /// ([`Krawczyk::with_extended_parameters`]).
    extended_parameters: Option<Vec<MidRadDd>>,
    real_system: bool,
    /// First index of every isotropic pair `(u, v)` of unknowns (see
    /// [`Krawczyk::with_isotropic_pairs`]); empty for Cartesian unknowns.
    pairs: Vec<usize>,
    n: usize,
    work: Vec<C64>,
    lu: LuWorkspace,
    buffers: Buffers,
}

/// Scratch space of one test, sized once for the system (no allocation per point).
struct Buffers {
    f: Vec<C64>,
    jac: Vec<C64>,
    column: Vec<C64>,
    /// `Y = J(c)⁻¹` (row-major).
    inverse: Vec<C64>,
    f_box: Vec<ComplexInterval>,
    jac_box: Vec<ComplexInterval>,
    /// Bounds `[tᵣ, tᵢ]` of `|(I − Y·J(c + E))·e|`, `e ∈ E`, per row.
    spread: Vec<[f64; 2]>,
    step: Vec<ComplexInterval>,
    offsets: Vec<ComplexInterval>,
    trial: Vec<ComplexInterval>,
    bounds: Vec<ComplexInterval>,
    image: Vec<ComplexInterval>,
    product: MidpointRadius,
}

impl Buffers {
    fn new(n: usize) -> Self {
        let zero = C64::new(0.0, 0.0);
        let boxes = |len: usize| vec![ComplexInterval::default(); len];
        Buffers {
            f: vec![zero; n],
            jac: vec![zero; n * n],
            column: vec![zero; n],
            inverse: vec![zero; n * n],
            f_box: boxes(n),
            jac_box: boxes(n * n),
            spread: vec![[0.0; 2]; n],
            step: boxes(n),
            offsets: boxes(n),
            trial: boxes(n),
            bounds: boxes(n),
            image: boxes(n),
            product: MidpointRadius::new(n),
        }
    }
}

impl<'a> Krawczyk<'a> {
    /// The test for `system` at `parameters`. `None` unless the system is square.
    pub fn new(system: &'a CompiledSystem, parameters: &[C64]) -> Option<Self> {
        let boxes: Vec<ComplexInterval> = parameters
            .iter()
            .map(|&v| ComplexInterval::point(v))
            .collect();
        Self::with_parameter_boxes(system, parameters, &boxes)
    }

    /// The test for `system` at every parameter in the boxes `parameter_boxes` (a
    /// success proves a unique solution in the box for each of them); `parameters`, a
    /// point of the boxes, serves Newton's method and the preconditioner.
    pub fn with_parameter_boxes(
        system: &'a CompiledSystem,
        parameters: &[C64],
        parameter_boxes: &[ComplexInterval],
    ) -> Option<Self> {
        let n = system.num_variables();
        let m = system.num_parameters();
        if system.num_equations() != n || parameters.len() != m || parameter_boxes.len() != m {
            return None;
        }
        let real_parameters = parameter_boxes.iter().all(|b| b.im == Interval::point(0.0));
        Some(Krawczyk {
            system,
            parameters: parameters.to_vec(),
            parameter_boxes: parameter_boxes.to_vec(),
            extended_parameters: None,
            real_system: system.has_real_coefficients() && real_parameters,
            pairs: Vec::new(),
            n,
            work: system.new_workspace(),
            lu: LuWorkspace::new(n),
            buffers: Buffers::new(n),
        })
    }

    /// Declares unknowns `(x_i, x_{i+1})` for every `i` of `pairs` as isotropic
    /// coordinates `u = (x + iy)/√2`, `v = (x − iy)/√2` of a point of a system whose
    /// Cartesian form is real at real parameters `real`. Its solution set is then
    /// closed under `σ: (u, v) ↦ (v̄, ū)` (other unknowns conjugated), a real solution
    /// is a fixed point of σ, and boxes closed under σ decide realness as conjugation-
    /// closed boxes do for Cartesian unknowns.
    pub fn with_isotropic_pairs(mut self, pairs: &[usize], real: bool) -> Self {
        self.pairs = pairs.iter().copied().filter(|&i| i + 1 < self.n).collect();
        self.real_system = real;
        self
    }

    /// Gives the test the parameter boxes with double-double midpoints (enclosing the
    /// same parameters as the double boxes, far more tightly): a point that fails in
    /// double precision is then tested once more around a centre polished in
    /// double-double arithmetic (see [`Krawczyk::certify`]).
    pub fn with_extended_parameters(mut self, parameters: Vec<MidRadDd>) -> Self {
        if parameters.len() == self.parameters.len() {
            self.extended_parameters = Some(parameters);
        }
        self
    }

    /// `σ(x)`: conjugated, isotropic pairs swapped.
    fn involution(&self, x: &[C64]) -> Vec<C64> {
        (0..self.n)
            .map(|i| x[partner(&self.pairs, i)].conj())
            .collect()
    }

    /// Whether `x` is within `10⁻⁶·(1 + ‖x‖∞)` of its mirror image `σ(x)` (a real point
    /// to the tracker's accuracy; [`Krawczyk::certify`] then tries a σ-closed box).
    pub fn nearly_real(&self, x: &[C64]) -> bool {
        same_point(x, &self.involution(x), 1e-6)
    }

    /// Whether the system at these parameters has real coefficients (realness can
    /// then be decided).
    pub fn is_real_system(&self) -> bool {
        self.real_system
    }

    /// A box around `approximation` proved to contain exactly one solution, or `None`
    /// where no box of the tried sizes passes the test (a singular or not-yet-converged
    /// point, or one too ill-conditioned for double precision).
    pub fn certify(&mut self, approximation: &[C64]) -> Option<RootBox> {
        if approximation.len() != self.n || approximation.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let center = self.polish(approximation)?;
        let mirrored = self.involution(&center);
        if self.real_system && self.nearly_real(&center) {
            // The nearest fixed point of σ: (x + σ(x))/2.
            let real_center: Vec<C64> = center
                .iter()
                .zip(&mirrored)
                .map(|(a, b)| (a + b) * 0.5)
                .collect();
            if let Some(found) = self.certify_at(&real_center, true) {
                return Some(found);
            }
        }
        if let Some(found) = self.certify_at(&center, false) {
            return Some(found);
        }
        self.certify_extended(&center)
    }

    /// The test around a centre polished in double-double arithmetic, for a point that
    /// failed in double precision: where the condition number κ of the Jacobian is
    /// near `1/u`, a centre rounded to doubles is off by about `κ·u` and so is the
    /// enclosure of `F` at it, and no box the test can contract contains the solution.
    /// Here the centre `c = hi + lo` is a vector of double-doubles refined by Newton's
    /// method with residuals evaluated in double-double (the Jacobian in double);
    /// `F(c)` is enclosed over the parameters' double-double boxes
    /// ([`CompiledSystem::evaluate_interval_dd`]), and the boxes `c + E` are handled as
    /// their double hulls. The conclusion is the same as in double precision: `c + E`
    /// contains exactly one solution (the test holds for any centre and any `Y`).
    /// `None` without double-double parameter boxes, where a coefficient of the system
    /// is not recognised, or where the polish does not converge.
    fn certify_extended(&mut self, x: &[C64]) -> Option<RootBox> {
        let parameters = self.extended_parameters.clone()?;
        let n = self.n;
        let mut c: Vec<ComplexDd> = x.iter().map(|&v| ComplexDd::from_c64(v)).collect();
        let mut f = vec![MidRadDd::default(); n];
        let mut converged = false;
        let mut previous = f64::INFINITY;
        for _ in 0..EXTENDED_POLISH_STEPS {
            let rounded: Vec<C64> = c.iter().map(|v| v.to_c64()).collect();
            let Buffers {
                f: residual, jac, ..
            } = &mut self.buffers;
            self.system.evaluate_with_jacobian(
                &rounded,
                &self.parameters,
                &mut self.work,
                residual,
                jac,
            );
            if !self.lu.factor(jac) {
                return None;
            }
            let points: Vec<MidRadDd> = c.iter().map(|&v| MidRadDd::point(v)).collect();
            if !self
                .system
                .evaluate_interval_dd(&points, &parameters, &mut f)
            {
                return None;
            }
            for (r, v) in residual.iter_mut().zip(&f) {
                *r = v.midpoint().to_c64();
            }
            self.lu.solve_in_place(residual);
            let update = max_norm(residual) / (1.0 + max_norm(&rounded));
            if !update.is_finite() {
                return None;
            }
            for (ci, di) in c.iter_mut().zip(residual.iter()) {
                *ci = *ci - ComplexDd::from_c64(*di);
            }
            // Done when tiny, or when the updates stop shrinking below the accuracy
            // the test needs (rounding noise of the double-double residual).
            if update <= EXTENDED_POLISHED
                || (update <= EXTENDED_ACCURATE && update > 0.5 * previous)
            {
                converged = true;
                break;
            }
            previous = update;
        }
        if !converged {
            return None;
        }
        let rounded: Vec<C64> = c.iter().map(|v| v.to_c64()).collect();
        let attempts: &[bool] = if self.real_system && self.nearly_real(&rounded) {
            &[true, false]
        } else {
            &[false]
        };
        for &symmetric in attempts {
            let center: Vec<ComplexDd> = if symmetric {
                // (c + σ(c))/2 in double-double: exactly a fixed point of σ.
                let half = ComplexDd::from_c64(C64::new(0.5, 0.0));
                (0..n)
                    .map(|i| {
                        let p = c[partner(&self.pairs, i)];
                        let mirror = ComplexDd {
                            re: p.re,
                            im: -p.im,
                        };
                        (c[i] + mirror) * half
                    })
                    .collect()
            } else {
                c.clone()
            };
            let points: Vec<MidRadDd> = center.iter().map(|&v| MidRadDd::point(v)).collect();
            if !self
                .system
                .evaluate_interval_dd(&points, &parameters, &mut f)
            {
                return None;
            }
            for (b, v) in self.buffers.f_box.iter_mut().zip(&f) {
                *b = v.to_interval();
            }
            let hi: Vec<C64> = center.iter().map(|v| C64::new(v.re.hi, v.im.hi)).collect();
            let lo: Vec<C64> = center.iter().map(|v| C64::new(v.re.lo, v.im.lo)).collect();
            self.invert_factored();
            if let Some(found) = self.contract(&hi, Some(&lo), symmetric) {
                return Some(found);
            }
        }
        None
    }

    /// The certificate of the mirror image of a certified non-real root of a real
    /// system: with real coefficients `F(σ(x)) = 0` exactly when `F(x) = 0`
    /// (σ: complex conjugation, isotropic pairs swapped), so `σ(B)` contains exactly
    /// one solution, `σ(s)`, when `B` contains exactly one, `s`, and `σ(B)` misses
    /// the real points (the fixed points of σ) when `B` does. Certifies a conjugate
    /// partner without a second test. `None` for a system with complex coefficients
    /// and for a real root (its own mirror).
    pub fn mirror(&self, root: &RootBox) -> Option<RootBox> {
        if !self.real_system || root.realness == Realness::Real || root.bounds.len() != self.n {
            return None;
        }
        let image = |v: &[ComplexInterval]| -> Vec<ComplexInterval> {
            (0..self.n)
                .map(|i| conjugate(&v[partner(&self.pairs, i)]))
                .collect()
        };
        Some(RootBox {
            bounds: image(&root.bounds),
            enclosure: image(&root.enclosure),
            center: self.involution(&root.center),
            radius: root.radius,
            realness: root.realness,
        })
    }

    /// Newton's method from `x` in double precision for at most [`POLISH_STEPS`]
    /// updates, until one is below [`POLISHED`] relative; `None` if the Jacobian is
    /// singular or a value is not finite. `self.lu` then holds the factorisation at the
    /// iterate before the last update.
    ///
    /// The residual is the double one of the Jacobian evaluation (no double-double
    /// evaluation): the endpoints handed over are refined already, one update brings a
    /// point within about `κ·u` of the solution, and closer is of no use, since the box
    /// is at least as wide as the interval enclosure of `Y·F(c)`, itself about `κ·u`
    /// wide. Neither the centre nor `Y` has to be accurate for the proof.
    fn polish(&mut self, x: &[C64]) -> Option<Vec<C64>> {
        let mut x = x.to_vec();
        let Buffers { f, jac, .. } = &mut self.buffers;
        for _ in 0..POLISH_STEPS {
            self.system
                .evaluate_with_jacobian(&x, &self.parameters, &mut self.work, f, jac);
            if !self.lu.factor(jac) || f.iter().any(|v| !v.is_finite()) {
                return None;
            }
            self.lu.solve_in_place(f);
            let correction = max_norm(f) / (1.0 + max_norm(&x));
            if !correction.is_finite() {
                return None;
            }
            for (xi, di) in x.iter_mut().zip(f.iter()) {
                *xi -= di;
            }
            if correction <= POLISHED {
                break;
            }
        }
        x.iter().all(|v| v.is_finite()).then_some(x)
    }

    /// The Krawczyk test on boxes around `center` of growing size. With `symmetric`
    /// (a real centre of a real system) a success proves the solution real.
    ///
    /// `Y` is the inverse of the Jacobian factored by the last step of
    /// [`Krawczyk::polish`], at a point within one Newton update of `center`: the test
    /// is valid for any `Y`, and this one is `J(c)⁻¹` to the update's size.
    fn certify_at(&mut self, center: &[C64], symmetric: bool) -> Option<RootBox> {
        self.invert_factored();
        // F(c), enclosed by evaluating on the point box.
        let b = &mut self.buffers;
        for (x, &c) in b.bounds.iter_mut().zip(center) {
            *x = ComplexInterval::point(c);
        }
        self.system
            .evaluate_interval(&b.bounds, &self.parameter_boxes, &mut b.f_box);
        self.contract(center, None, symmetric)
    }

    /// `Y ≈ J⁻¹` from the factorisation in `self.lu`, column by column (row-major).
    fn invert_factored(&mut self) {
        let n = self.n;
        let b = &mut self.buffers;
        for j in 0..n {
            b.column.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
            b.column[j] = C64::new(1.0, 0.0);
            self.lu.solve_in_place(&mut b.column);
            for i in 0..n {
                b.inverse[i * n + j] = b.column[i];
            }
        }
    }

    /// The ε-inflation and the test itself for the centre `c = center + low` (`low`:
    /// the trailing parts of a double-double centre, none for a double one), with `Y`
    /// in the buffers' inverse and an enclosure of `F(c)` in their `f_box`.
    fn contract(
        &mut self,
        center: &[C64],
        low: Option<&[C64]>,
        symmetric: bool,
    ) -> Option<RootBox> {
        let b = &mut self.buffers;
        // The box around the exact centre: `hi + (lo + e)`, each sum rounded outwards.
        let around = |c: C64, i: usize, e: &ComplexInterval| match low {
            Some(low) => ComplexInterval::point(c) + (ComplexInterval::point(low[i]) + *e),
            None => ComplexInterval::point(c) + *e,
        };
        // A double-double centre is accurate far below a double's ulp: so may the box be.
        let floor_scale = if low.is_some() { f64::EPSILON } else { 1.0 };
        // z = −Y·F(c) encloses the Newton step; the ε-inflation iteration of Rump
        // ("Verification methods", §13.1) grows a box E around it until
        // z + (I − Y·J(c + E))·E lies inside E.
        if !negated_product(&b.inverse, &b.f_box, &mut b.step) {
            return None;
        }
        b.offsets.copy_from_slice(&b.step);
        for _ in 0..INFLATION_STEPS {
            for ((t, e), c) in b.trial.iter_mut().zip(&b.offsets).zip(center) {
                *t = inflate(e, c.norm() * floor_scale);
            }
            if symmetric {
                close_under_involution(&self.pairs, &mut b.trial);
            }
            for (i, ((x, &c), e)) in b.bounds.iter_mut().zip(center).zip(&b.trial).enumerate() {
                *x = around(c, i, e);
            }
            self.system.evaluate_interval_with_jacobian(
                &b.bounds,
                &self.parameter_boxes,
                &mut b.f_box,
                &mut b.jac_box,
            );
            // (I − Y·J(c + E))·E ⊂ [−t, t] per part (see the module documentation).
            if !b
                .product
                .product_bound(&b.inverse, &b.jac_box, &b.trial, &mut b.spread)
            {
                return None;
            }
            for ((k, z), t) in b.image.iter_mut().zip(&b.step).zip(&b.spread) {
                let centered = |t: f64| Interval { lo: -t, hi: t };
                *k = *z
                    + ComplexInterval {
                        re: centered(t[0]),
                        im: centered(t[1]),
                    };
            }
            if b.image.iter().any(|v| !v.is_bounded()) {
                return None;
            }
            if b.image
                .iter()
                .zip(&b.trial)
                .all(|(k, e)| k.strictly_inside(e))
            {
                let enclosure: Vec<ComplexInterval> = center
                    .iter()
                    .zip(&b.image)
                    .enumerate()
                    .map(|(i, (&c, k))| around(c, i, k))
                    .collect();
                let realness = if symmetric {
                    Realness::Real
                } else if self.real_system && misses_real_points(&self.pairs, &enclosure) {
                    Realness::NonReal
                } else {
                    Realness::Undecided
                };
                let radius = enclosure
                    .iter()
                    .fold(0.0f64, |r, b| r.max(b.re.width()).max(b.im.width()))
                    * 0.5;
                return Some(RootBox {
                    bounds: b.bounds.clone(),
                    enclosure,
                    center: center.to_vec(),
                    radius,
                    realness,
                });
            }
            b.offsets.copy_from_slice(&b.image);
        }
        None
    }
}

/// Partner of unknown `i` under σ (itself for a non-isotropic unknown), for the first
/// indices `pairs` of the isotropic pairs.
fn partner(pairs: &[usize], i: usize) -> usize {
    for &p in pairs {
        if i == p {
            return p + 1;
        }
        if i == p + 1 {
            return p;
        }
    }
    i
}

/// Enlarges offsets `e` around a σ-fixed centre so that the box is closed under σ:
/// `E_u ← E_u ∪ conj(E_v)`, `E_v ← conj(E_u)` per isotropic pair, and a symmetric
/// imaginary part for the other unknowns.
fn close_under_involution(pairs: &[usize], e: &mut [ComplexInterval]) {
    for i in 0..e.len() {
        let j = partner(pairs, i);
        if j == i {
            let m = e[i].im.magnitude();
            e[i].im = Interval { lo: -m, hi: m };
        } else if i < j {
            let mirrored = conjugate(&e[j]);
            let hull = ComplexInterval {
                re: hull(e[i].re, mirrored.re),
                im: hull(e[i].im, mirrored.im),
            };
            e[i] = hull;
            e[j] = conjugate(&hull);
        }
    }
}

/// Whether the box contains no fixed point of σ (no real solution can lie in it).
fn misses_real_points(pairs: &[usize], b: &[ComplexInterval]) -> bool {
    (0..b.len()).any(|i| {
        let j = partner(pairs, i);
        if j == i {
            !b[i].im.contains_zero()
        } else {
            !b[i].meets(&conjugate(&b[j]))
        }
    })
}

fn conjugate(z: &ComplexInterval) -> ComplexInterval {
    ComplexInterval {
        re: z.re,
        im: -z.im,
    }
}

fn hull(a: Interval, b: Interval) -> Interval {
    Interval {
        lo: a.lo.min(b.lo),
        hi: a.hi.max(b.hi),
    }
}

/// Rump's ε-inflation of an offset box `e` around a centre of modulus `scale`: each
/// part widened by a tenth of its width and a few ulps of the centre.
fn inflate(e: &ComplexInterval, scale: f64) -> ComplexInterval {
    let floor = 4.0 * f64::EPSILON * scale + f64::MIN_POSITIVE;
    let grow = |v: Interval| {
        let pad = 0.1 * v.width() + floor;
        Interval {
            lo: v.lo - pad,
            hi: v.hi + pad,
        }
        .widened()
    };
    ComplexInterval {
        re: grow(e.re),
        im: grow(e.im),
    }
}

/// The certificates of a list of approximate solutions.
#[derive(Clone, Debug, Default)]
pub struct CertifiedSolutions {
    /// Per input point: its box, or `None` where the test failed.
    pub boxes: Vec<Option<RootBox>>,
    /// Index pairs of certified boxes that overlap (possibly one solution twice).
    pub overlapping: Vec<(usize, usize)>,
}

impl CertifiedSolutions {
    /// Number of solutions proved distinct: certified boxes not overlapping an earlier
    /// certified box.
    pub fn distinct(&self) -> usize {
        let mut duplicate = vec![false; self.boxes.len()];
        for &(_, j) in &self.overlapping {
            duplicate[j] = true;
        }
        self.boxes
            .iter()
            .zip(&duplicate)
            .filter(|(b, d)| b.is_some() && !**d)
            .count()
    }

    /// Number of points whose test failed.
    pub fn uncertified(&self) -> usize {
        self.boxes.iter().filter(|b| b.is_none()).count()
    }

    /// Whether every point is certified and every pair of boxes is disjoint.
    pub fn all_distinct(&self) -> bool {
        self.uncertified() == 0 && self.overlapping.is_empty()
    }
}

/// Certifies every point of `solutions` as a solution of `system` at `parameters`,
/// and checks the boxes pairwise for overlap. `None` unless the system is square.
pub fn certify_solutions(
    system: &CompiledSystem,
    parameters: &[C64],
    solutions: &[Vec<C64>],
) -> Option<CertifiedSolutions> {
    let mut test = Krawczyk::new(system, parameters)?;
    let boxes: Vec<Option<RootBox>> = solutions.iter().map(|x| test.certify(x)).collect();
    let mut overlapping = Vec::new();
    for i in 0..boxes.len() {
        for j in i + 1..boxes.len() {
            if let (Some(a), Some(b)) = (&boxes[i], &boxes[j])
                && a.meets(b)
            {
                overlapping.push((i, j));
            }
        }
    }
    Some(CertifiedSolutions { boxes, overlapping })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::system::bertini;
    use crate::system::interval_dd::RealDd;

    /// Compiles `f1; f2` in `x, y` (Bertini input).
    fn compile(f1: &str, f2: &str) -> CompiledSystem {
        let text = format!(
            "INPUT\nvariable_group x, y;\nfunction f1, f2;\nf1 = {f1};\nf2 = {f2};\nEND;\n"
        );
        CompiledSystem::new(&bertini::read(&text).expect("system parses"))
    }

    #[test]
    fn circle_and_line_roots_are_real_and_distinct() {
        // x² + y² = 2, x = y: the roots (1, 1) and (−1, −1).
        let system = compile("x^2 + y^2 - 2", "x - y");
        let near = |a: f64| vec![C64::new(a + 1e-9, 1e-10), C64::new(a - 1e-9, 0.0)];
        let result = certify_solutions(&system, &[], &[near(1.0), near(-1.0)]).unwrap();
        assert!(result.all_distinct(), "{result:?}");
        assert_eq!(result.distinct(), 2);
        for b in result.boxes.iter().flatten() {
            assert_eq!(b.realness, Realness::Real);
            assert!(b.radius < 1e-12, "radius {}", b.radius);
        }
    }

    #[test]
    fn complex_roots_are_proved_non_real() {
        // x² + 1 = 0, y = x: roots ±i.
        let system = compile("x^2 + 1", "y - x");
        let i = C64::new(0.0, 1.0);
        let result = certify_solutions(&system, &[], &[vec![i, i], vec![-i, -i]]).unwrap();
        assert!(result.all_distinct());
        for b in result.boxes.iter().flatten() {
            assert_eq!(b.realness, Realness::NonReal);
        }
    }

    #[test]
    fn a_point_that_is_not_a_root_and_a_double_root_fail() {
        let system = compile("x^2 + y^2 - 2", "x - y");
        // Newton from a point between the roots lands on one of them; from exactly
        // the symmetric point the Jacobian is singular.
        let midpoint = vec![C64::new(0.0, 0.0), C64::new(0.0, 0.0)];
        let result = certify_solutions(&system, &[], &[midpoint]).unwrap();
        assert_eq!(result.uncertified(), 1);
        // A double root (x − 1)² = 0 is singular: no box passes.
        let double = compile("x^2 - 2*x + 1", "y");
        let near = vec![C64::new(1.0 + 1e-9, 0.0), C64::new(0.0, 0.0)];
        let result = certify_solutions(&double, &[], std::slice::from_ref(&near)).unwrap();
        assert_eq!(result.uncertified(), 1);
        // Nor in double-double: the polish stalls near the double root.
        let mut test = Krawczyk::new(&double, &[])
            .unwrap()
            .with_extended_parameters(Vec::new());
        assert!(test.extended_parameters.is_some());
        assert!(test.certify(&near).is_none());
    }

    #[test]
    fn the_mirror_of_a_non_real_root_certifies_its_conjugate() {
        // x² + 1 = 0, y = 2x: roots ±(i, 2i).
        let system = compile("x^2 + 1", "y - 2*x");
        let mut test = Krawczyk::new(&system, &[]).unwrap();
        let i = C64::new(0.0, 1.0);
        let root = test.certify(&[i, 2.0 * i]).expect("certified");
        let mirror = test
            .mirror(&root)
            .expect("a non-real root of a real system");
        assert_eq!(mirror.realness, Realness::NonReal);
        assert!(!mirror.meets(&root), "distinct from the original");
        let direct = test.certify(&[-i, -2.0 * i]).expect("certified");
        assert!(mirror.meets(&direct), "the mirror holds the conjugate root");
        assert!((mirror.center[1] - (-2.0 * i)).norm() < 1e-14);
        // A real root is its own mirror; a complex system has none.
        let real = compile("x^2 - 1", "y - x");
        let mut real_test = Krawczyk::new(&real, &[]).unwrap();
        let one = real_test
            .certify(&[C64::new(1.0, 0.0); 2])
            .expect("certified");
        assert!(real_test.mirror(&one).is_none());
        let complex = compile("x^2 + 1 + I*y", "y - x");
        let mut complex_test = Krawczyk::new(&complex, &[]).unwrap();
        if let Some(b) = complex_test.certify(&[i, i]) {
            assert!(complex_test.mirror(&b).is_none());
        }
    }

    /// `x² = p, y = x` for `p` in a box: near `p = 0.0025` the root `x = 0.05` is
    /// certified for a narrow box of `p`, but not for `p ∈ [0, 0.005]`, where the
    /// roots `±√p` meet at the fold `p = 0` and no box around 0.05 holds exactly one
    /// root for every `p` (this fails if `(I − Y·J(X))·(X − c)` is under-estimated).
    /// `x + y = 1`, `x + p y − q + x(x + y − 1) = 0` with `p = 1 + δ`, `q = 1 + δ/3`,
    /// `δ = 2⁻⁴⁰`: the root `(2/3, 1/3)` has condition number about `4/δ ≈ 4·10¹²`.
    /// `q` is not a double: its double box is an ulp wide, which moves `y` by
    /// `ulp/δ ≈ 2·10⁻⁴`, over which the Jacobian varies by about 10⁻³ (the quadratic
    /// term), and no box the test can contract in double precision holds the root for
    /// the whole parameter box.
    /// With `q` known in double-double (`1 + fl(δ/3)`, within `10⁻³⁰`) the
    /// double-double test proves the root, real, in a box far narrower than an ulp of
    /// `x`, and the box holds `(2/3, 1/3)`.
    #[test]
    fn an_ill_conditioned_root_is_certified_in_double_double_only() {
        let text = "INPUT\nvariable_group x, y;\nparameter p, q;\nfunction f1, f2;\n\
                    f1 = x + y - 1;\nf2 = x + p*y - q + x*(x + y - 1);\nEND;\n";
        let system = CompiledSystem::new(&bertini::read(text).expect("system parses"));
        let delta = 2f64.powi(-40);
        let third = delta / 3.0;
        let (p, q) = (1.0 + delta, 1.0 + third);
        let real = |v: Interval| ComplexInterval {
            re: v,
            im: Interval::point(0.0),
        };
        let boxes = [
            real(Interval::point(p)),
            real(Interval::point(1.0) + Interval::centered(third, 1e-30)),
        ];
        let parameters = [C64::new(p, 0.0), C64::new(q, 0.0)];
        let root = [C64::new(2.0 / 3.0, 0.0), C64::new(1.0 / 3.0, 0.0)];
        let mut double = Krawczyk::with_parameter_boxes(&system, &parameters, &boxes).unwrap();
        assert!(double.certify(&root).is_none(), "double precision cannot");
        let q_dd = RealDd {
            mid: crate::system::double_double::DoubleDouble { hi: 1.0, lo: third },
            rad: 1e-30,
        };
        let extended = vec![MidRadDd::real(RealDd::exact(p)), MidRadDd::real(q_dd)];
        let mut test = Krawczyk::with_parameter_boxes(&system, &parameters, &boxes)
            .unwrap()
            .with_extended_parameters(extended);
        let b = test.certify(&root).expect("double-double can");
        assert_eq!(b.realness, Realness::Real);
        for (e, v) in b.enclosure.iter().zip([2.0 / 3.0, 1.0 / 3.0]) {
            assert!(e.re.lo <= v && v <= e.re.hi, "{e:?}");
            assert!(e.re.width() < 1e-15, "{e:?}");
        }
        // From a start 10⁻³ off, Newton's method comes back to the same root.
        let off = [C64::new(2.0 / 3.0 + 1e-3, 0.0), C64::new(1.0 / 3.0, 0.0)];
        let moved = test.certify(&off).expect("Newton's method brings it back");
        assert!(moved.meets(&b));
    }

    #[test]
    fn a_parameter_box_reaching_the_fold_fails() {
        let text = "INPUT\nvariable_group x, y;\nparameter p;\nfunction f1, f2;\n\
                    f1 = x^2 - p;\nf2 = y - x;\nEND;\n";
        let system = CompiledSystem::new(&bertini::read(text).expect("system parses"));
        let p = C64::new(0.0025, 0.0);
        let root = [C64::new(0.05, 0.0); 2];
        let real = |lo: f64, hi: f64| ComplexInterval {
            re: Interval { lo, hi },
            im: Interval::point(0.0),
        };
        let narrow = [real(0.0025 - 1e-9, 0.0025 + 1e-9)];
        let mut test = Krawczyk::with_parameter_boxes(&system, &[p], &narrow).unwrap();
        let b = test
            .certify(&root)
            .expect("a narrow parameter box is certified");
        assert_eq!(b.realness, Realness::Real);
        let wide = [real(0.0, 0.005)];
        let mut test = Krawczyk::with_parameter_boxes(&system, &[p], &wide).unwrap();
        assert!(test.certify(&root).is_none());
    }

    #[test]
    fn the_same_root_twice_is_caught() {
        let system = compile("x^2 + y^2 - 2", "x - y");
        let a = vec![C64::new(1.0, 0.0), C64::new(1.0, 0.0)];
        let b = vec![C64::new(1.0 + 1e-12, 0.0), C64::new(1.0, 1e-13)];
        let result = certify_solutions(&system, &[], &[a, b]).unwrap();
        assert_eq!(result.uncertified(), 0);
        assert_eq!(result.overlapping, vec![(0, 1)]);
        assert_eq!(result.distinct(), 1);
    }
}
