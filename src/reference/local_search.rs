//! Reference singularity distances of a 3-RPR by many-start local constrained
//! minimisation of `D²(K, K′)`, independent of the homotopy pipeline.
//!
//! For each metric and each of its constraint sets (the singularity variety
//! `S(K′) = 0`, the collinear platform `C_p(K′) = 0` or base `C_b(K′) = 0`, all six
//! points on one line, three coincident platform or base points; Kapilavai and Nawratil,
//! *Singularity distance computations for 3-RPR manipulators using extrinsic metrics*,
//! docs/theory.md §5), the
//! configuration `K′` is written in unknowns `x` that make every structural condition
//! hold exactly:
//!
//! - a deformable part (plate or bars) has its three points free (6 unknowns);
//! - a rigid part is moved by a proper Euclidean motion `(t_x, t_y, θ)` applied to its
//!   own anchors, `p_i′ = c + t + R(θ)(p_i − c)` about their centroid `c`, so it stays
//!   congruent to rounding;
//! - on one line `{c n(α) + t n(α)^⊥}` every deformable point has its own abscissa
//!   `t`; a rigid part with collinear anchors has `t_k = s + τ_k`, `τ_k` its anchors'
//!   abscissae (both orientations are covered by `α ∈ [0, 2π)`);
//! - coincident points are one free point `q`.
//!
//! The remaining equality (`S = 0` or `C = 0`, one scalar) is enforced by an augmented
//! Lagrangian `f − λh + ρh²/2` (Nocedal and Wright, *Numerical Optimization*, 2nd ed.,
//! Springer 2006, §17.3) whose inner minimisation is Newton's method on the
//! eigenvalue-modified Hessian with an Armijo line search (ibid. §3.4); each local
//! minimiser is then polished by Newton's method on the KKT system
//! `∇f − λ∇h = 0, h = 0` (pseudo-inverse steps, so positive-dimensional minimum sets
//! do no harm). Derivatives are exact ([`super::jet`]), computed from
//! [`Metric::distance_sq`] and the crate's polynomials themselves.
//!
//! Starts: `K` itself (projected onto the constraint by the first iterations), then
//! seeded random perturbations at relative scales 0.01 … 3 of the configuration's
//! size. Everything is computed in the similarity frame `K ↦ (K − centroid)/rms
//! radius` and mapped back; the reported distance and feasibility are recomputed from
//! the reported `K′` in the caller's frame.

use super::jet::{Jet, MAX_VARIABLES, Real};
use crate::algebra::Point;
use crate::mechanism::rpr::{
    Design, collinearity_base, collinearity_platform, singularity_polynomial,
};
use crate::metric::{Metric, Part};
use crate::problem::{SubProblem, subproblems_of};
use crate::random;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use serde::Serialize;

/// A constraint set of the singularity distance: one of the pipeline's sub-problems
/// ([`SubProblem`], with its name), so that the reference search and the pipeline
/// minimise over the same sets ([`subproblems_of`] gives those of a metric).
pub type Constraint = SubProblem;

/// Anchors count as collinear when twice their triangle's area is at most this times
/// the square of its longest edge.
pub const COLLINEAR_ANCHORS: f64 = 1e-9;

/// A local minimiser counts as feasible when [`Feasibility::worst`] is at most this.
pub const FEASIBILITY_TOLERANCE: f64 = 1e-10;

/// Knobs of the reference search.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Number of local minimisations per constraint set (the first from `K` itself).
    pub starts: usize,
    /// Seed of the random starts.
    pub seed: u64,
    /// Relative scales of the random perturbations, used in turn.
    pub scales: Vec<f64>,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            starts: 200,
            seed: 1,
            scales: vec![0.01, 0.03, 0.1, 0.3, 1.0, 3.0],
        }
    }
}

/// How well a configuration `K′` satisfies a constraint set, in units of the size `ℓ`
/// of `K` (root-mean-square distance of its six points from their centroid).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Feasibility {
    /// For `h = S, C_p, C_b`: the first-order distance to `h = 0`,
    /// `|h(K′)| / (‖∇h(K′)‖ ℓ)`; for all-collinear: the largest distance of a point
    /// from the points' total-least-squares line over `ℓ`; for coincident points:
    /// their largest distance over `ℓ`.
    pub constraint: f64,
    /// Rigid parts: the largest change of a pairwise anchor distance over `ℓ`, and of
    /// the signed area over `ℓ²` (a reflection is not a proper motion); 0 without
    /// rigid parts.
    pub rigidity: f64,
}

impl Feasibility {
    /// The larger of the two residuals.
    pub fn worst(&self) -> f64 {
        self.constraint.max(self.rigidity)
    }
}

/// A verified local minimiser of one constraint set.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LocalMinimum {
    /// `D(K, K′)`, recomputed from `K′` by [`Metric::distance`].
    pub distance: f64,
    /// `K′` (caller's frame).
    pub closest: [f64; 12],
    /// Recomputed from `K′`.
    pub feasibility: Feasibility,
    /// Norm of the gradient of the Lagrangian in the normalised unknowns.
    pub stationarity: f64,
}

/// The reference result of one constraint set.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SubproblemReference {
    /// Which constraint set.
    pub constraint: Constraint,
    /// The smallest distance over the feasible local minimisers (`None` if no start
    /// ended feasible).
    pub best: Option<LocalMinimum>,
    /// Starts run.
    pub starts: usize,
    /// Starts that ended feasible and stationary (gradient of the Lagrangian ≤ 1e-6).
    pub converged: usize,
    /// Feasible ends within `1e-9` (relative) of the best distance.
    pub hits: usize,
    /// Distinct distances (relative gap > `1e-7`) among the stationary feasible ends.
    pub distinct_minima: usize,
}

/// The reference singularity distance of one metric at one configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MetricReference {
    /// The metric (serialised by name).
    #[serde(serialize_with = "serialize_metric")]
    pub metric: Metric,
    /// The minimum over the constraint sets (`∞` if none had a feasible end).
    pub distance: f64,
    /// The constraint set attaining it.
    pub constraint: Constraint,
    /// `K′` attaining it.
    pub closest: [f64; 12],
    /// Every applicable constraint set of the metric.
    pub subproblems: Vec<SubproblemReference>,
    /// Constraint sets that do not apply to this design (all-collinear with a rigid
    /// part whose anchors are not collinear).
    pub not_applicable: Vec<Constraint>,
}

fn serialize_metric<S: serde::Serializer>(metric: &Metric, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&metric.name())
}

impl MetricReference {
    /// The result of one constraint set, if it applies.
    pub fn subproblem(&self, constraint: Constraint) -> Option<&SubproblemReference> {
        self.subproblems.iter().find(|s| s.constraint == constraint)
    }
}

// ---------------------------------------------------------------------------------
// Geometry helpers
// ---------------------------------------------------------------------------------

fn points(k: &[f64; 12], first: usize) -> [Point<f64>; 3] {
    [0, 1, 2].map(|i| [k[first + 2 * i], k[first + 2 * i + 1]])
}

fn centroid(p: &[Point<f64>]) -> Point<f64> {
    let n = p.len() as f64;
    [
        p.iter().map(|q| q[0]).sum::<f64>() / n,
        p.iter().map(|q| q[1]).sum::<f64>() / n,
    ]
}

fn cross(u: Point<f64>, v: Point<f64>) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

fn sub(p: Point<f64>, q: Point<f64>) -> Point<f64> {
    [p[0] - q[0], p[1] - q[1]]
}

fn norm(p: Point<f64>) -> f64 {
    p[0].hypot(p[1])
}

/// Twice the signed area of the triangle `p_1 p_2 p_3`.
fn signed_area(p: &[Point<f64>; 3]) -> f64 {
    cross(sub(p[1], p[0]), sub(p[2], p[0]))
}

/// Whether three anchors are collinear ([`COLLINEAR_ANCHORS`]).
pub fn anchors_collinear(p: &[Point<f64>; 3]) -> bool {
    let longest = [(0, 1), (1, 2), (2, 0)]
        .iter()
        .map(|&(i, j)| norm(sub(p[i], p[j])))
        .fold(0.0, f64::max);
    signed_area(p).abs() <= COLLINEAR_ANCHORS * longest * longest
}

/// Total-least-squares line of points: centroid and unit normal (eigenvector of the
/// scatter matrix with the smaller eigenvalue).
fn tls_line(p: &[Point<f64>]) -> (Point<f64>, Point<f64>) {
    let c = centroid(p);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for q in p {
        let d = sub(*q, c);
        sxx += d[0] * d[0];
        sxy += d[0] * d[1];
        syy += d[1] * d[1];
    }
    // Direction of the larger eigenvalue: angle ψ with tan 2ψ = 2 sxy / (sxx − syy).
    let psi = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    (c, [-psi.sin(), psi.cos()])
}

/// The orthogonal projections of points onto their total-least-squares line.
pub fn pedal_points(p: &[Point<f64>; 3]) -> [Point<f64>; 3] {
    let (c, n) = tls_line(p);
    p.map(|q| {
        let d = sub(q, c);
        let off = d[0] * n[0] + d[1] * n[1];
        [q[0] - off * n[0], q[1] - off * n[1]]
    })
}

/// Size `ℓ` of a configuration: root-mean-square distance of its six points from
/// their centroid (1 if they coincide).
pub fn configuration_size(k: &[f64; 12]) -> f64 {
    let all: Vec<Point<f64>> = (0..6).map(|i| [k[2 * i], k[2 * i + 1]]).collect();
    let c = centroid(&all);
    let r = (all.iter().map(|p| norm(sub(*p, c)).powi(2)).sum::<f64>() / 6.0).sqrt();
    if r > 0.0 && r.is_finite() { r } else { 1.0 }
}

fn gradient_norm_12(h: impl Fn(&[Jet; 12]) -> Jet, k: &[f64; 12]) -> (f64, f64) {
    let jets: [Jet; 12] = std::array::from_fn(|i| Jet::variable(k[i], i));
    let value = h(&jets);
    let g = value.gradient.iter().map(|v| v * v).sum::<f64>().sqrt();
    (value.value, g)
}

/// Feasibility of `k_prime` for `constraint` under `metric`, relative to `k` (the
/// rigid parts of `metric` must be congruent, properly, to those of `k`).
pub fn feasibility(
    k: &[f64; 12],
    metric: Metric,
    constraint: Constraint,
    k_prime: &[f64; 12],
) -> Feasibility {
    let size = configuration_size(k);
    let first_order = |(value, g): (f64, f64)| {
        if value == 0.0 {
            0.0
        } else if g > 0.0 {
            value.abs() / (g * size)
        } else {
            f64::INFINITY
        }
    };
    let a = points(k_prime, 0);
    let b = points(k_prime, 6);
    let spread = |p: &[Point<f64>; 3]| {
        [(0, 1), (1, 2), (2, 0)]
            .iter()
            .map(|&(i, j)| norm(sub(p[i], p[j])))
            .fold(0.0, f64::max)
            / size
    };
    let constraint_residual = match constraint {
        Constraint::Singularity => first_order(gradient_norm_12(singularity_polynomial, k_prime)),
        Constraint::CollinearPlatform => {
            first_order(gradient_norm_12(collinearity_platform, k_prime))
        }
        Constraint::CollinearBase => first_order(gradient_norm_12(collinearity_base, k_prime)),
        Constraint::AllCollinear => {
            let all: Vec<Point<f64>> = a.iter().chain(b.iter()).copied().collect();
            let (c, n) = tls_line(&all);
            all.iter()
                .map(|p| {
                    let d = sub(*p, c);
                    (d[0] * n[0] + d[1] * n[1]).abs()
                })
                .fold(0.0, f64::max)
                / size
        }
        Constraint::CoincidentPlatform => spread(&b),
        Constraint::CoincidentBase => spread(&a),
    };
    let rigid_error = |p: &[Point<f64>; 3], q: &[Point<f64>; 3]| {
        let edges = [(0, 1), (1, 2), (2, 0)]
            .iter()
            .map(|&(i, j)| (norm(sub(p[i], p[j])) - norm(sub(q[i], q[j]))).abs())
            .fold(0.0, f64::max)
            / size;
        edges.max((signed_area(p) - signed_area(q)).abs() / (size * size))
    };
    let mut rigidity: f64 = 0.0;
    if metric.base == Part::Rigid {
        rigidity = rigidity.max(rigid_error(&points(k, 0), &a));
    }
    if metric.platform == Part::Rigid {
        rigidity = rigidity.max(rigid_error(&points(k, 6), &b));
    }
    Feasibility {
        constraint: constraint_residual,
        rigidity,
    }
}

// ---------------------------------------------------------------------------------
// Parametrisations
// ---------------------------------------------------------------------------------

/// How one part's points depend on the unknowns.
#[derive(Clone, Copy, Debug)]
enum PartParameters {
    /// Three free points: 6 unknowns.
    Free,
    /// Proper motion of the given points about their centroid: `(t_x, t_y, θ)`.
    Rigid {
        centre: Point<f64>,
        relative: [Point<f64>; 3],
    },
    /// On the common line, free abscissae: 3 unknowns.
    LineFree,
    /// On the common line, rigid with abscissae `τ_k`: 1 unknown `s`.
    LineRigid { abscissae: [f64; 3] },
    /// All three points equal one free point: 2 unknowns.
    Coincident,
}

impl PartParameters {
    fn count(&self) -> usize {
        match self {
            PartParameters::Free => 6,
            PartParameters::Rigid { .. } => 3,
            PartParameters::LineFree => 3,
            PartParameters::LineRigid { .. } => 1,
            PartParameters::Coincident => 2,
        }
    }

    fn rigid(p: &[Point<f64>; 3]) -> Self {
        let centre = centroid(p);
        PartParameters::Rigid {
            centre,
            relative: p.map(|q| sub(q, centre)),
        }
    }

    fn line_rigid(p: &[Point<f64>; 3]) -> Self {
        let (i, j) = [(0, 1), (1, 2), (2, 0)]
            .into_iter()
            .max_by(|&(i, j), &(k, l)| norm(sub(p[i], p[j])).total_cmp(&norm(sub(p[k], p[l]))))
            .unwrap_or((0, 1));
        let d = sub(p[j], p[i]);
        let length = norm(d);
        let d = if length > 0.0 {
            [d[0] / length, d[1] / length]
        } else {
            [1.0, 0.0]
        };
        let c = centroid(p);
        PartParameters::LineRigid {
            abscissae: p.map(|q| {
                let r = sub(q, c);
                r[0] * d[0] + r[1] * d[1]
            }),
        }
    }

    /// The three points from this part's unknowns `x` (and, on a line, the line's
    /// offset `c`, normal `n` and direction `n^⊥`).
    fn points<T: Real>(&self, x: &[T], line: Option<(T, [T; 2], [T; 2])>) -> [[T; 2]; 3] {
        let c = |v: f64| T::from_f64(v);
        match self {
            PartParameters::Free => [0, 1, 2].map(|i| [x[2 * i], x[2 * i + 1]]),
            PartParameters::Rigid { centre, relative } => {
                let (s, co) = (x[2].sin(), x[2].cos());
                relative.map(|r| {
                    [
                        c(centre[0]) + x[0] + co * c(r[0]) - s * c(r[1]),
                        c(centre[1]) + x[1] + s * c(r[0]) + co * c(r[1]),
                    ]
                })
            }
            PartParameters::LineFree | PartParameters::LineRigid { .. } => {
                let (offset, n, t) = line.expect("line parameters for a part on a line");
                let abscissa = |k: usize| match self {
                    PartParameters::LineRigid { abscissae } => x[0] + c(abscissae[k]),
                    _ => x[k],
                };
                [0, 1, 2].map(|k| {
                    let a = abscissa(k);
                    [offset * n[0] + a * t[0], offset * n[1] + a * t[1]]
                })
            }
            PartParameters::Coincident => [[x[0], x[1]]; 3],
        }
    }

    /// The unknowns reproducing the points `p` exactly (line parts: their
    /// projections on the line `(offset, n)`).
    fn identity(&self, p: &[Point<f64>; 3], line: Option<(f64, Point<f64>)>) -> Vec<f64> {
        match self {
            PartParameters::Free => p.iter().flat_map(|q| q.iter().copied()).collect(),
            PartParameters::Rigid { .. } => vec![0.0; 3],
            PartParameters::LineFree | PartParameters::LineRigid { .. } => {
                let (_, n) = line.unwrap_or((0.0, [0.0, 1.0]));
                let t = [-n[1], n[0]];
                let abscissae: Vec<f64> = p.iter().map(|q| q[0] * t[0] + q[1] * t[1]).collect();
                match self {
                    PartParameters::LineRigid { abscissae: tau } => {
                        vec![(0..3).map(|k| abscissae[k] - tau[k]).sum::<f64>() / 3.0]
                    }
                    _ => abscissae,
                }
            }
            PartParameters::Coincident => centroid(p).to_vec(),
        }
    }

    /// Random perturbation of the unknowns at relative scale `scale`.
    fn perturb(&self, x: &mut [f64], scale: f64, rng: &mut random::SeededRng) {
        match self {
            PartParameters::Rigid { .. } => {
                x[0] += scale * random::normal(rng);
                x[1] += scale * random::normal(rng);
                x[2] = if scale >= 1.0 {
                    random::uniform(rng, -std::f64::consts::PI, std::f64::consts::PI)
                } else {
                    x[2] + scale * std::f64::consts::PI * random::normal(rng)
                };
            }
            _ => {
                for v in x.iter_mut() {
                    *v += scale * random::normal(rng);
                }
            }
        }
    }
}

/// One constrained minimisation problem in the normalised frame.
struct Problem {
    metric: Metric,
    constraint: Constraint,
    /// `K` normalised, as constants.
    k: [f64; 12],
    k_jets: [Jet; 12],
    base: PartParameters,
    platform: PartParameters,
    /// Whether the unknowns start with a line `(α, offset)`.
    on_line: bool,
    /// `1/‖∇h(K)‖` (so `h` has unit gradient near `K`).
    h_scale: f64,
    count: usize,
}

/// Evaluation with exact derivatives.
struct Evaluation {
    gf: DVector<f64>,
    hf: DMatrix<f64>,
    h: f64,
    gh: DVector<f64>,
    hh: DMatrix<f64>,
}

fn jet_parts(jet: &Jet, n: usize) -> (DVector<f64>, DMatrix<f64>) {
    let g = DVector::from_fn(n, |i, _| jet.gradient[i]);
    let h = DMatrix::from_fn(n, n, |i, j| jet.hessian_entry(i, j));
    (g, h)
}

impl Problem {
    fn new(design_k: &[f64; 12], metric: Metric, constraint: Constraint) -> Option<Problem> {
        let a = points(design_k, 0);
        let b = points(design_k, 6);
        let line_part = |part: Part, p: &[Point<f64>; 3]| match part {
            Part::Rigid if anchors_collinear(p) => Some(PartParameters::line_rigid(p)),
            Part::Rigid => None,
            _ => Some(PartParameters::LineFree),
        };
        let free_part = |part: Part, p: &[Point<f64>; 3]| match part {
            Part::Rigid => PartParameters::rigid(p),
            _ => PartParameters::Free,
        };
        let (base, platform, on_line) = match constraint {
            Constraint::Singularity | Constraint::CollinearPlatform | Constraint::CollinearBase => {
                (
                    free_part(metric.base, &a),
                    free_part(metric.platform, &b),
                    false,
                )
            }
            Constraint::AllCollinear => (
                line_part(metric.base, &a)?,
                line_part(metric.platform, &b)?,
                true,
            ),
            Constraint::CoincidentPlatform => (
                free_part(metric.base, &a),
                PartParameters::Coincident,
                false,
            ),
            Constraint::CoincidentBase => (
                PartParameters::Coincident,
                free_part(metric.platform, &b),
                false,
            ),
        };
        let count = base.count() + platform.count() + if on_line { 2 } else { 0 };
        debug_assert!(count <= MAX_VARIABLES);
        let mut problem = Problem {
            metric,
            constraint,
            k: *design_k,
            k_jets: design_k.map(Jet::constant),
            base,
            platform,
            on_line,
            h_scale: 1.0,
            count,
        };
        let (_, g) = match constraint {
            Constraint::Singularity => gradient_norm_12(singularity_polynomial, design_k),
            Constraint::CollinearPlatform => gradient_norm_12(collinearity_platform, design_k),
            Constraint::CollinearBase => gradient_norm_12(collinearity_base, design_k),
            _ => (0.0, 1.0),
        };
        problem.h_scale = if g > 1e-8 { 1.0 / g } else { 1.0 };
        Some(problem)
    }

    fn constrained(&self) -> bool {
        matches!(
            self.constraint,
            Constraint::Singularity | Constraint::CollinearPlatform | Constraint::CollinearBase
        )
    }

    /// `K′` from the unknowns.
    fn configuration<T: Real>(&self, x: &[T]) -> [T; 12] {
        let (line, rest) = if self.on_line {
            let (alpha, offset) = (x[0], x[1]);
            let n = [alpha.cos(), alpha.sin()];
            let t = [-n[1], n[0]];
            (Some((offset, n, t)), &x[2..])
        } else {
            (None, x)
        };
        let nb = self.base.count();
        let a = self.base.points(&rest[..nb], line);
        let b = self.platform.points(&rest[nb..], line);
        [
            a[0][0], a[0][1], a[1][0], a[1][1], a[2][0], a[2][1], b[0][0], b[0][1], b[1][0],
            b[1][1], b[2][0], b[2][1],
        ]
    }

    fn constraint_value<T: Real>(&self, k_prime: &[T; 12]) -> T {
        let value = match self.constraint {
            Constraint::Singularity => singularity_polynomial(k_prime),
            Constraint::CollinearPlatform => collinearity_platform(k_prime),
            Constraint::CollinearBase => collinearity_base(k_prime),
            _ => return T::from_f64(0.0),
        };
        value * T::from_f64(self.h_scale)
    }

    /// `(f, h)` at `x` (values only).
    fn values(&self, x: &[f64]) -> (f64, f64) {
        let kp = self.configuration(x);
        (
            self.metric.distance_sq(&self.k, &kp),
            self.constraint_value(&kp),
        )
    }

    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let jets: Vec<Jet> = x
            .iter()
            .enumerate()
            .map(|(i, &v)| Jet::variable(v, i))
            .collect();
        let kp = self.configuration(&jets);
        let f = self.metric.distance_sq(&self.k_jets, &kp);
        let h = self.constraint_value(&kp);
        let (gf, hf) = jet_parts(&f, self.count);
        let (gh, hh) = jet_parts(&h, self.count);
        Evaluation {
            gf,
            hf,
            h: h.value,
            gh,
            hh,
        }
    }

    /// The unknowns reproducing `K` (projected onto the line for all-collinear).
    fn identity(&self) -> Vec<f64> {
        let a = points(&self.k, 0);
        let b = points(&self.k, 6);
        let mut x = Vec::with_capacity(self.count);
        let line = if self.on_line {
            let all: Vec<Point<f64>> = a.iter().chain(b.iter()).copied().collect();
            let (c, n) = tls_line(&all);
            let offset = c[0] * n[0] + c[1] * n[1];
            x.push(n[1].atan2(n[0]));
            x.push(offset);
            Some((offset, n))
        } else {
            None
        };
        x.extend(self.base.identity(&a, line));
        x.extend(self.platform.identity(&b, line));
        x
    }

    /// Start `index`: `K` itself for 0, else a seeded random perturbation.
    fn start(&self, index: usize, options: &ReferenceOptions) -> Vec<f64> {
        let mut x = self.identity();
        if index == 0 {
            return x;
        }
        let mut rng = random::stream(options.seed, index as u64);
        let scale = options.scales[index % options.scales.len().max(1)];
        let mut offset = 0;
        if self.on_line {
            x[0] = random::uniform(&mut rng, 0.0, std::f64::consts::TAU);
            let n = [x[0].cos(), x[0].sin()];
            let a = points(&self.k, 0);
            let b = points(&self.k, 6);
            let all: Vec<Point<f64>> = a.iter().chain(b.iter()).copied().collect();
            let c = centroid(&all);
            x[1] = c[0] * n[0] + c[1] * n[1] + scale * random::normal(&mut rng);
            let nb = self.base.count();
            let xa = self.base.identity(&a, Some((x[1], n)));
            let xb = self.platform.identity(&b, Some((x[1], n)));
            x[2..2 + nb].copy_from_slice(&xa);
            x[2 + nb..].copy_from_slice(&xb);
            offset = 2;
        }
        let nb = self.base.count();
        self.base
            .perturb(&mut x[offset..offset + nb], scale, &mut rng);
        self.platform
            .perturb(&mut x[offset + nb..], scale, &mut rng);
        x
    }
}

// ---------------------------------------------------------------------------------
// The local solver
// ---------------------------------------------------------------------------------

/// Newton's method on `φ = f − λh + ρh²/2` with the eigenvalue-modified Hessian and an
/// Armijo line search; returns the final point.
fn inner_newton(problem: &Problem, mut x: Vec<f64>, lambda: f64, rho: f64) -> Vec<f64> {
    let merit = |x: &[f64]| {
        let (f, h) = problem.values(x);
        f - lambda * h + 0.5 * rho * h * h
    };
    let mut phi = merit(&x);
    for _ in 0..200 {
        let e = problem.evaluate(&x);
        let mu = lambda - rho * e.h;
        let g = &e.gf - &e.gh * mu;
        if g.norm() <= 1e-13 {
            break;
        }
        let hess = &e.hf - &e.hh * mu + &e.gh * e.gh.transpose() * rho;
        let eigen = hess.symmetric_eigen();
        let largest = eigen.eigenvalues.amax().max(1e-300);
        let floor = 1e-10 * largest.max(1.0);
        let mut d = DVector::zeros(problem.count);
        for (k, &ev) in eigen.eigenvalues.iter().enumerate() {
            let v = eigen.eigenvectors.column(k);
            d -= v * (v.dot(&g) / ev.abs().max(floor));
        }
        let length = d.norm();
        if length > 3.0 {
            d *= 3.0 / length;
        }
        let slope = g.dot(&d);
        if slope >= 0.0 {
            break;
        }
        let mut t = 1.0;
        let mut accepted = None;
        for _ in 0..60 {
            let trial: Vec<f64> = x.iter().zip(d.iter()).map(|(a, b)| a + t * b).collect();
            let value = merit(&trial);
            if value <= phi + 1e-4 * t * slope {
                accepted = Some((trial, value));
                break;
            }
            t *= 0.5;
        }
        let Some((trial, value)) = accepted else {
            break;
        };
        let moved = t * length;
        x = trial;
        let decrease = phi - value;
        phi = value;
        if moved <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max))
            || decrease <= 1e-17 * (1.0 + phi.abs()) && g.norm() < 1e-9
        {
            break;
        }
    }
    x
}

/// Newton's method on the KKT system (`∇f − λ∇h = 0`, `h = 0`; just `∇f = 0`
/// without a constraint) with pseudo-inverse steps; returns the point with the
/// smallest KKT residual met, its multiplier and that residual.
fn polish(problem: &Problem, x0: Vec<f64>, lambda0: f64) -> (Vec<f64>, f64, f64) {
    let n = problem.count;
    let constrained = problem.constrained();
    let residual = |e: &Evaluation, lambda: f64| {
        let g = &e.gf - &e.gh * lambda;
        (g.norm_squared() + e.h * e.h).sqrt()
    };
    let (mut x, mut lambda) = (x0, lambda0);
    let mut e = problem.evaluate(&x);
    let mut best = (x.clone(), lambda, residual(&e, lambda));
    for _ in 0..30 {
        let m = if constrained { n + 1 } else { n };
        let mut jac = DMatrix::zeros(m, m);
        let mut rhs = DVector::zeros(m);
        let g = &e.gf - &e.gh * lambda;
        let hl = &e.hf - &e.hh * lambda;
        jac.view_mut((0, 0), (n, n)).copy_from(&hl);
        rhs.rows_mut(0, n).copy_from(&(-g));
        if constrained {
            for i in 0..n {
                jac[(i, n)] = -e.gh[i];
                jac[(n, i)] = e.gh[i];
            }
            rhs[n] = -e.h;
        }
        let svd = jac.svd(true, true);
        let threshold = 1e-13 * svd.singular_values.max();
        let Ok(step) = svd.solve(&rhs, threshold) else {
            break;
        };
        for (xi, s) in x.iter_mut().zip(step.iter()) {
            *xi += s;
        }
        if constrained {
            lambda += step[n];
        }
        e = problem.evaluate(&x);
        let r = residual(&e, lambda);
        let previous = best.2;
        if r < best.2 {
            best = (x.clone(), lambda, r);
        }
        // Quadratic convergence has ended at the rounding level.
        if r <= 1e-15 || (r > 0.25 * previous && r < 1e-9) {
            break;
        }
    }
    best
}

/// One local minimisation from `x0`: augmented Lagrangian, then KKT polish. Returns
/// the unknowns and the norm of the Lagrangian's gradient.
fn local_minimisation(problem: &Problem, x0: Vec<f64>) -> (Vec<f64>, f64) {
    let mut x = x0;
    let mut lambda = 0.0;
    if problem.constrained() {
        let mut rho = 10.0;
        let mut previous = f64::INFINITY;
        for _ in 0..40 {
            x = inner_newton(problem, x, lambda, rho);
            let (_, h) = problem.values(&x);
            // Newton's method on the KKT system takes it from here.
            if h.abs() <= 1e-12 {
                break;
            }
            lambda -= rho * h;
            if h.abs() > 0.25 * previous {
                rho = (rho * 10.0).min(1e12);
            }
            previous = h.abs();
        }
    } else {
        x = inner_newton(problem, x, 0.0, 0.0);
    }
    let before = problem.values(&x);
    let (polished, _, residual) = polish(problem, x.clone(), lambda);
    let after = problem.values(&polished);
    // Keep the polished point unless it left the minimiser's neighbourhood.
    if after.0 <= before.0 * (1.0 + 1e-6) + 1e-14 {
        (polished, residual)
    } else {
        let e = problem.evaluate(&x);
        (x, (&e.gf - &e.gh * lambda).norm())
    }
}

/// The similarity frame `K ↦ (K − c)/ℓ`.
struct Frame {
    centre: Point<f64>,
    size: f64,
}

impl Frame {
    fn of(k: &[f64; 12]) -> Frame {
        let all: Vec<Point<f64>> = (0..6).map(|i| [k[2 * i], k[2 * i + 1]]).collect();
        Frame {
            centre: centroid(&all),
            size: configuration_size(k),
        }
    }
    fn apply(&self, k: &[f64; 12]) -> [f64; 12] {
        std::array::from_fn(|i| (k[i] - self.centre[i % 2]) / self.size)
    }
    fn restore(&self, k: &[f64; 12]) -> [f64; 12] {
        std::array::from_fn(|i| self.centre[i % 2] + self.size * k[i])
    }
}

/// Reference minimum of one constraint set (`None`: not applicable to this design).
pub fn reference_subproblem(
    k: &[f64; 12],
    metric: Metric,
    constraint: Constraint,
    options: &ReferenceOptions,
) -> Option<SubproblemReference> {
    let frame = Frame::of(k);
    let problem = Problem::new(&frame.apply(k), metric, constraint)?;
    let ends: Vec<LocalMinimum> = (0..options.starts.max(1))
        .into_par_iter()
        .map(|index| {
            let (x, stationarity) = local_minimisation(&problem, problem.start(index, options));
            let closest = frame.restore(&problem.configuration(&x));
            LocalMinimum {
                distance: metric.distance(k, &closest),
                closest,
                feasibility: feasibility(k, metric, constraint, &closest),
                stationarity,
            }
        })
        .collect();
    let feasible: Vec<&LocalMinimum> = ends
        .iter()
        .filter(|e| e.feasibility.worst() <= FEASIBILITY_TOLERANCE && e.distance.is_finite())
        .collect();
    let best = feasible
        .iter()
        .min_by(|a, b| a.distance.total_cmp(&b.distance))
        .map(|e| (*e).clone());
    let converged: Vec<f64> = feasible
        .iter()
        .filter(|e| e.stationarity <= 1e-6)
        .map(|e| e.distance)
        .collect();
    let hits = match &best {
        Some(b) => feasible
            .iter()
            .filter(|e| e.distance <= b.distance * (1.0 + 1e-9) + 1e-15 * frame.size)
            .count(),
        None => 0,
    };
    let mut sorted = converged.clone();
    sorted.sort_by(f64::total_cmp);
    let distinct_minima = sorted
        .windows(2)
        .filter(|w| w[1] - w[0] > 1e-7 * w[1].abs().max(1e-12 * frame.size))
        .count()
        + usize::from(!sorted.is_empty());
    Some(SubproblemReference {
        constraint,
        best,
        starts: ends.len(),
        converged: converged.len(),
        hits,
        distinct_minima,
    })
}

/// Reference singularity distance of `metric` at the configuration `k` of `design`
/// (`k` as [`crate::mechanism::rpr::Configuration::to_array`]): the minimum over the
/// metric's constraint sets, each by [`ReferenceOptions::starts`] local
/// minimisations.
pub fn reference_distance(
    design: &Design,
    k: &[f64; 12],
    metric: Metric,
    options: &ReferenceOptions,
) -> MetricReference {
    let mut subproblems = Vec::new();
    let mut not_applicable = Vec::new();
    for constraint in subproblems_of(metric) {
        if constraint == Constraint::AllCollinear && !all_collinear_applies(design, metric) {
            not_applicable.push(constraint);
            continue;
        }
        match reference_subproblem(k, metric, constraint, options) {
            Some(s) => subproblems.push(s),
            None => not_applicable.push(constraint),
        }
    }
    let attained = subproblems
        .iter()
        .filter_map(|s| s.best.as_ref().map(|b| (s.constraint, b)))
        .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance));
    let (distance, constraint, closest) = match attained {
        Some((c, b)) => (b.distance, c, b.closest),
        None => (f64::INFINITY, Constraint::Singularity, *k),
    };
    MetricReference {
        metric,
        distance,
        constraint,
        closest,
        subproblems,
        not_applicable,
    }
}

/// Whether all six points on one line is a constraint set of `metric` for `design`:
/// every rigid part must have collinear anchors.
pub fn all_collinear_applies(design: &Design, metric: Metric) -> bool {
    (metric.base != Part::Rigid || anchors_collinear(design.base()))
        && (metric.platform != Part::Rigid || anchors_collinear(design.platform()))
}

/// [`reference_distance`] for several metrics, in parallel.
pub fn reference_distances(
    design: &Design,
    k: &[f64; 12],
    metrics: &[Metric],
    options: &ReferenceOptions,
) -> Vec<MetricReference> {
    metrics
        .par_iter()
        .map(|&metric| reference_distance(design, k, metric, options))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Constraints serialise as their variant names, as before they were the
    /// pipeline's sub-problems.
    #[test]
    fn constraints_serialise_by_variant_name() {
        let names: Vec<String> = subproblems_of(Metric::new(Part::Bars, Part::Rigid))
            .into_iter()
            .map(|c: Constraint| serde_json::to_string(&c).unwrap())
            .collect();
        assert_eq!(
            names,
            [
                "\"Singularity\"",
                "\"CollinearPlatform\"",
                "\"CoincidentPlatform\""
            ]
        );
    }
}
