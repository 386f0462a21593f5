//! Certified singularity distances at one pose of a 3-RPR.
//!
//! For one sub-problem (a Lagrange system `∇Λ = 0` of Cartesian unknowns) at the
//! configuration `K` (twelve doubles) of a pose:
//!
//! The unknowns may be Cartesian or isotropic (`u = (x + iy)/√2`, `v = (x − iy)/√2`
//! per point, in which points far out along isotropic lines stay well-conditioned);
//! realness is then decided under `(u, v) ↦ (v̄, ū)` ([`Krawczyk::with_isotropic_pairs`]).
//!
//! 1. the parameters are enclosed in intervals: the normalised configuration
//!    `(K − c)/s` of the similarity the pipeline works in (any `c`, `s` are a valid
//!    choice, since every sub-problem is equivariant under similarities), and the rigid
//!    parts' shape constants `u = (w·e)/|e|²`, `v = (w·Ee)/|e|²`, `r² = |e|²`
//!    (`e = p₂ − p₁`, `w = p₃ − p₁`) computed from the design's anchors;
//! 2. every computed critical point is certified by [`super::krawczyk`] for every
//!    parameter in those boxes (unique solution in its box, distinct from the others,
//!    real or not); where fewer points were computed than the generic count, so that
//!    completeness cannot be proved whatever is certified, only the real points are
//!    tested, in the order of their `D`, until one (the minimiser) is certified;
//! 3. for each certified real one, `D(K, K′)` is enclosed by evaluating the
//!    configuration map `K′(x; p)` and the metric over the boxes: `D = s·D((K − c)/s,
//!    K′_normalised)`;
//! 4. the sub-problem is **complete** when as many distinct solutions are certified as
//!    the family's generic count and every one's realness is decided: then no other
//!    isolated critical point exists (Morgan, Sommese, "Coefficient-parameter
//!    polynomial continuation", Appl. Math. Comput. 1989: no parameter has more
//!    isolated solutions than the generic number), and the smallest enclosure is the
//!    sub-problem's minimum over its isolated critical points.
//!
//! The statement is about the configuration `K` and the anchors exactly as the
//! doubles given; the rounding of `cos φ`, `sin φ` in computing `K` from a pose is not
//! part of it.

use super::krawczyk::{Krawczyk, Realness, RootBox};
use crate::C64;
use crate::homotopy::refine::same_point;
use crate::mechanism::rpr::Design;
use crate::metric::Metric;
use crate::problem::LagrangeProblem;
use crate::system::interval::{ComplexInterval, Interval};
use crate::system::interval_dd::{MidRadDd, RealDd};
use serde::{Deserialize, Serialize};

/// The similarity `K ↦ (K − c)/s` in which a sub-problem's system is solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// `c`.
    pub center: [f64; 2],
    /// `s > 0`.
    pub scale: f64,
}

/// What was proved about one sub-problem at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubproblemCertificate {
    /// The family's generic number of critical points (the start file's count).
    pub expected: usize,
    /// Critical points proved to be distinct exact solutions.
    pub certified: usize,
    /// Of those, proved real.
    pub real: usize,
    /// Of those, whose realness is not decided.
    pub undecided: usize,
    /// Computed points that failed the test (singular, or too ill-conditioned).
    pub uncertified: usize,
    /// Computed points not put to the test: where fewer points were computed than
    /// `expected`, completeness cannot be proved, and only the real points are tested,
    /// in the order of their `D`, until one is certified (the minimiser).
    #[serde(skip_serializing_if = "is_zero", default)]
    pub untested: usize,
    /// `certified == expected` with every realness decided: no other isolated
    /// critical point exists.
    pub complete: bool,
    /// Enclosure `[lo, hi]` of the smallest `D` over the certified real points.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub distance: Option<[f64; 2]>,
}

fn is_zero(v: &usize) -> bool {
    *v == 0
}

/// The real arithmetic the parameters are enclosed in: double intervals
/// ([`Interval`]), or double-double midpoints with radii ([`RealDd`]).
trait Enclosure:
    Copy + std::ops::Add<Output = Self> + std::ops::Sub<Output = Self> + std::ops::Mul<Output = Self>
{
    /// The complex box of a real enclosure.
    type Complex;
    fn exact(v: f64) -> Self;
    fn recip(self) -> Option<Self>;
    fn sqrt(self) -> Option<Self>;
    fn complex(self) -> Self::Complex;
}

impl Enclosure for Interval {
    type Complex = ComplexInterval;
    fn exact(v: f64) -> Self {
        Interval::point(v)
    }
    fn complex(self) -> ComplexInterval {
        ComplexInterval {
            re: self,
            im: Interval::point(0.0),
        }
    }
    fn recip(self) -> Option<Self> {
        Interval::recip(&self)
    }
    fn sqrt(self) -> Option<Self> {
        Interval::sqrt(&self)
    }
}

impl Enclosure for RealDd {
    type Complex = MidRadDd;
    fn exact(v: f64) -> Self {
        RealDd::exact(v)
    }
    fn complex(self) -> MidRadDd {
        MidRadDd::real(self)
    }
    fn recip(self) -> Option<Self> {
        RealDd::recip(self)
    }
    fn sqrt(self) -> Option<Self> {
        RealDd::sqrt(self)
    }
}

/// Shape constants `(u, v, r²)` of a rigid part from its anchors, enclosed.
fn shape_enclosure<T: Enclosure>(p: &[[f64; 2]; 3]) -> Option<(T, T, T)> {
    let point = |q: [f64; 2]| [T::exact(q[0]), T::exact(q[1])];
    let [p1, p2, p3] = [point(p[0]), point(p[1]), point(p[2])];
    let e = [p2[0] - p1[0], p2[1] - p1[1]];
    let w = [p3[0] - p1[0], p3[1] - p1[1]];
    let r2 = e[0] * e[0] + e[1] * e[1];
    let inverse = r2.recip()?;
    // E e = (−e_y, e_x).
    let u = (w[0] * e[0] + w[1] * e[1]) * inverse;
    let v = (w[1] * e[0] - w[0] * e[1]) * inverse;
    Some((u, v, r2))
}

/// The parameters of `problem` at configuration `k` of `design` in `frame`, enclosed:
/// `(K − c)/s`, then the shape constants in the frame's units (see
/// [`LagrangeProblem::parameters_in_units`]). `None` if a shape is degenerate.
fn parameter_values<T: Enclosure>(
    problem: &LagrangeProblem,
    design: &Design,
    k: &[f64; 12],
    frame: Frame,
) -> Option<Vec<T>> {
    let inverse_scale = T::exact(frame.scale).recip()?;
    let mut out: Vec<T> = (0..12)
        .map(|i| (T::exact(k[i]) - T::exact(frame.center[i % 2])) * inverse_scale)
        .collect();
    let base = shape_enclosure::<T>(design.base())?;
    let platform = shape_enclosure::<T>(design.platform())?;
    for name in &problem.parameter_names()[12..] {
        let (u, v, r2) = if name.ends_with("_base") {
            base
        } else {
            platform
        };
        let length = r2.sqrt()? * inverse_scale;
        let value = if name.starts_with("s2_") {
            length
        } else if name.starts_with("s3_") {
            u * length
        } else if name.starts_with("u_") {
            u
        } else if name.starts_with("v_") {
            v
        } else {
            r2 * inverse_scale * inverse_scale
        };
        out.push(value);
    }
    Some(out)
}

/// The parameter boxes of `problem` at configuration `k` of `design` in `frame`:
/// [`ComplexInterval`]s computed in double interval arithmetic (`T = Interval`), or
/// boxes with double-double midpoints computed in [`RealDd`] arithmetic (`T = RealDd`,
/// for the double-double test of ill-conditioned points). `None` if a shape is
/// degenerate.
fn parameter_enclosure<T: Enclosure>(
    problem: &LagrangeProblem,
    design: &Design,
    k: &[f64; 12],
    frame: Frame,
) -> Option<Vec<T::Complex>> {
    let values = parameter_values::<T>(problem, design, k, frame)?;
    Some(values.into_iter().map(T::complex).collect())
}

/// The enclosure of `D(K, K′)` of the real solution in `root`.
fn distance_enclosure(
    problem: &LagrangeProblem,
    metric: Metric,
    root: &RootBox,
    parameters: &[ComplexInterval],
    frame: Frame,
) -> Option<Interval> {
    // The solution lies in the enclosure and its K′ is real: the real parts of the
    // configuration map's enclosure contain it (in Cartesian or isotropic unknowns).
    let k_prime = problem
        .configuration_enclosure(&root.enclosure, parameters)
        .map(|v| v.re);
    let k: [Interval; 12] = std::array::from_fn(|i| parameters[i].re);
    let squared = metric.distance_sq(&k, &k_prime);
    let d = squared.sqrt()? * Interval::point(frame.scale);
    d.is_bounded().then_some(d)
}

/// Certifies the computed critical points `solutions` (unknowns of `problem`, Cartesian
/// or isotropic, in the normalised `frame`) of one sub-problem of `metric` at the
/// configuration `k` of `design`; `expected` is the family's generic count.
pub fn certify_subproblem(
    problem: &LagrangeProblem,
    metric: Metric,
    (design, k): (&Design, &[f64; 12]),
    frame: Frame,
    solutions: &[Vec<C64>],
    expected: usize,
) -> SubproblemCertificate {
    let failed = SubproblemCertificate {
        expected,
        certified: 0,
        real: 0,
        undecided: 0,
        uncertified: solutions.len(),
        untested: 0,
        complete: false,
        distance: None,
    };
    let Some(parameter_boxes) = parameter_enclosure::<Interval>(problem, design, k, frame) else {
        return failed;
    };
    let midpoints: Vec<C64> = parameter_boxes.iter().map(|b| b.midpoint()).collect();
    let Some(test) =
        Krawczyk::with_parameter_boxes(problem.evaluator(), &midpoints, &parameter_boxes)
    else {
        return failed;
    };
    // The parameter boxes are real: the Cartesian system is real, and so is the
    // isotropic one under (u, v) ↦ (v̄, ū).
    let mut test = test.with_isotropic_pairs(&problem.isotropic_pairs(), true);
    if let Some(extended) = parameter_enclosure::<RealDd>(problem, design, k, frame) {
        test = test.with_extended_parameters(extended);
    }
    // Fewer points than the generic count: no certificate can be complete, and only
    // the minimiser matters. The real points are tested in the order of their `D`
    // (computed in double at the parameters' midpoints) until one is certified.
    let minimiser_only = solutions.len() < expected;
    let order: Vec<usize> = if minimiser_only {
        let mut work = vec![C64::new(0.0, 0.0); problem.workspace_len()];
        let mut real: Vec<(f64, usize)> = solutions
            .iter()
            .enumerate()
            .filter(|(_, x)| test.nearly_real(x))
            .map(|(i, x)| {
                let k_prime = problem
                    .configuration(x, &midpoints, &mut work)
                    .map(|v| v.re);
                let k: [f64; 12] = std::array::from_fn(|i| midpoints[i].re);
                (metric.distance_sq(&k, &k_prime), i)
            })
            .collect();
        real.sort_by(|a, b| a.0.total_cmp(&b.0));
        real.into_iter().map(|(_, i)| i).collect()
    } else {
        (0..solutions.len()).collect()
    };
    // A conjugate partner of a certified non-real point is certified by the mirror
    // image of its box ([`Krawczyk::mirror`]) instead of a second test.
    let mut mirrors: Vec<RootBox> = Vec::new();
    let mut boxes: Vec<Option<RootBox>> = Vec::with_capacity(solutions.len());
    for x in order.iter().map(|&i| &solutions[i]) {
        if let Some(at) = mirrors.iter().position(|m| approximates(x, &m.center)) {
            boxes.push(Some(mirrors.swap_remove(at)));
            continue;
        }
        let certified = test.certify(x);
        if let Some(mirror) = certified.as_ref().and_then(|b| test.mirror(b)) {
            mirrors.push(mirror);
        }
        let found = minimiser_only
            && certified.as_ref().is_some_and(|b| {
                b.realness == Realness::Real
                    && distance_enclosure(problem, metric, b, &parameter_boxes, frame).is_some()
            });
        boxes.push(certified);
        if found {
            break;
        }
    }
    let untested = solutions.len() - boxes.len();
    // Keep the first of every group of overlapping enclosures.
    let mut kept: Vec<&RootBox> = Vec::new();
    let mut uncertified = 0;
    for b in &boxes {
        match b {
            None => uncertified += 1,
            Some(b) => {
                if kept.iter().all(|k| !k.meets(b)) {
                    kept.push(b);
                }
            }
        }
    }
    let real: Vec<&RootBox> = kept
        .iter()
        .copied()
        .filter(|b| b.realness == Realness::Real)
        .collect();
    let undecided = kept
        .iter()
        .filter(|b| b.realness == Realness::Undecided)
        .count();
    let mut distance: Option<Interval> = None;
    let mut enclosed_all = true;
    for root in &real {
        match distance_enclosure(problem, metric, root, &parameter_boxes, frame) {
            Some(d) => {
                distance = Some(match distance {
                    None => d,
                    Some(m) => Interval {
                        lo: m.lo.min(d.lo),
                        hi: m.hi.min(d.hi),
                    },
                })
            }
            None => enclosed_all = false,
        }
    }
    SubproblemCertificate {
        expected,
        certified: kept.len(),
        real: real.len(),
        undecided,
        uncertified,
        untested,
        complete: kept.len() == expected && undecided == 0 && enclosed_all,
        distance: distance.map(|d| [d.lo, d.hi]),
    }
}

/// Whether the computed point `x` is the certified centre `center` to within
/// `10⁻⁶·(1 + ‖center‖∞)` (the same solution: the certified box around `center`
/// stands for it; a wrong match can only leave a solution uncounted, never add one).
fn approximates(x: &[C64], center: &[C64]) -> bool {
    x.len() == center.len() && same_point(center, x, 1e-6)
}

/// How much of a metric's distance at a pose is proved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CertifiedStatus {
    /// Every sub-problem complete: the distance is the certified global minimum over
    /// the isolated critical points, enclosed in `distance`.
    GlobalMinimum,
    /// The reported minimiser is a certified real critical point with its `D` enclosed,
    /// but some sub-problem is not complete.
    MinimiserOnly,
    /// Nothing about the reported distance is proved.
    None,
}

/// What was proved about one metric's distance at one pose.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MetricCertificate {
    /// The status.
    pub status: CertifiedStatus,
    /// Why it is not stronger (empty for a global minimum).
    #[serde(skip_serializing_if = "String::is_empty", default)]
    pub reason: String,
    /// Enclosure `[lo, hi]` of the certified value (global minimum or minimiser's `D`).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub distance: Option<[f64; 2]>,
}

/// Relative slack allowed between the reported distance (computed in double from the
/// tracked point) and the enclosure (from the polished, certified one).
const REPORTED_SLACK: f64 = 1e-9;

fn contains(enclosure: [f64; 2], value: f64) -> bool {
    let slack = REPORTED_SLACK * value.abs().max(1e-300);
    enclosure[0] - slack <= value && value <= enclosure[1] + slack
}

/// Combines the sub-problems' certificates of one metric (`None` for a sub-problem
/// without one, e.g. solved in closed form) into the metric's: `reported` is the
/// distance the pipeline reports and `reported_subproblem` the sub-problem attaining it.
pub fn combine(
    subproblems: &[(String, Option<&SubproblemCertificate>)],
    reported: f64,
    reported_subproblem: &str,
) -> MetricCertificate {
    let mut missing = Vec::new();
    let mut enclosure: Option<[f64; 2]> = None;
    for (name, certificate) in subproblems {
        match certificate {
            None => missing.push(format!("{name}: not certified (closed form)")),
            Some(c) => {
                if !c.complete {
                    missing.push(format!(
                        "{name}: {} of {} critical points certified{}{}",
                        c.certified,
                        c.expected,
                        if c.undecided > 0 {
                            format!(", {} of undecided realness", c.undecided)
                        } else {
                            String::new()
                        },
                        if c.untested > 0 {
                            format!(
                                ", {} more found and not tested (fewer than {} found)",
                                c.untested, c.expected
                            )
                        } else {
                            String::new()
                        }
                    ));
                }
                if let Some(d) = c.distance {
                    enclosure = Some(match enclosure {
                        None => d,
                        Some(e) => [e[0].min(d[0]), e[1].min(d[1])],
                    });
                }
            }
        }
    }
    let minimiser = subproblems
        .iter()
        .find(|(name, _)| name == reported_subproblem)
        .and_then(|(_, c)| c.and_then(|c| c.distance))
        .filter(|d| contains(*d, reported));
    if missing.is_empty() {
        return match enclosure {
            Some(e) if contains(e, reported) => MetricCertificate {
                status: CertifiedStatus::GlobalMinimum,
                reason: String::new(),
                distance: Some(e),
            },
            Some(e) => MetricCertificate {
                status: CertifiedStatus::None,
                reason: format!(
                    "the reported distance {reported:e} is outside the certified minimum [{:e}, {:e}]",
                    e[0], e[1]
                ),
                distance: Some(e),
            },
            None => MetricCertificate {
                status: CertifiedStatus::None,
                reason: "no real critical point certified".to_string(),
                distance: None,
            },
        };
    }
    let reason = format!("completeness not certified: {}", missing.join("; "));
    match minimiser {
        Some(d) => MetricCertificate {
            status: CertifiedStatus::MinimiserOnly,
            reason,
            distance: Some(d),
        },
        None => MetricCertificate {
            status: CertifiedStatus::None,
            reason,
            distance: None,
        },
    }
}
