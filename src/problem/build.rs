//! Construction of each sub-problem's Lagrange system with the system builder.

use super::{ProblemId, Stratum, SubProblem};
use crate::C64;
use crate::algebra::{Cartesian, Isotropic, Plane, Point};
use crate::mechanism::rpr::{self, Design};
use crate::metric::Part;
use crate::system::interval::ComplexInterval;
use crate::system::{CompiledSystem, Evaluator, Expr, ParametricSystem, System};

/// Errors of the problem layer.
#[derive(Debug, thiserror::Error)]
pub enum ProblemError {
    /// A name that is not a metric, sub-problem or problem.
    #[error("unknown name `{name}`; valid: {valid}")]
    UnknownName {
        /// What was given.
        name: String,
        /// What would have been accepted.
        valid: String,
    },
    /// A sub-problem that the metric does not need (docs/theory.md §5).
    #[error("problem `{problem}` is not part of its metric; that metric needs: {needed}")]
    NotNeeded {
        /// The problem name given.
        problem: String,
        /// The sub-problems the metric needs.
        needed: String,
    },
    /// The sub-problem does not exist for this design (e.g. all-collinear with a
    /// rigid part whose anchors are not collinear).
    #[error("problem `{problem}` is not applicable: {reason}")]
    NotApplicable {
        /// The problem name.
        problem: String,
        /// Why.
        reason: String,
    },
    /// The system builder rejected the Lagrangian (a bug, reported rather than hidden).
    #[error("building the system of `{problem}` failed: {message}")]
    Build {
        /// The problem name.
        problem: String,
        /// The builder's message.
        message: String,
    },
}

/// Names of the twelve coordinates of a configuration, in the order of docs/theory.md §1.1:
/// `a1x a1y a2x a2y a3x a3y b1x b1y b2x b2y b3x b3y`.
pub const COORDINATE_NAMES: [&str; 12] = [
    "a1x", "a1y", "a2x", "a2y", "a3x", "a3y", "b1x", "b1y", "b2x", "b2y", "b3x", "b3y",
];

/// Names of the parameters holding the given configuration K (fixed frame).
pub const CONFIGURATION_PARAMETER_NAMES: [&str; 12] = [
    "A1x", "A1y", "A2x", "A2y", "A3x", "A3y", "B1x", "B1y", "B2x", "B2y", "B3x", "B3y",
];

/// The coordinates of a problem's unknown points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Coordinates {
    /// `(x, y)`: variables `a1x a1y …` (the stored start solutions use these).
    #[default]
    Cartesian,
    /// `(u, v) = ((x + i y)/√2, (x − i y)/√2)` ([`crate::algebra::Isotropic`]): variables
    /// `a1u a1v …`. The same critical points (multipliers unchanged), with the ones far
    /// out along isotropic lines well-conditioned; the curve pipeline tracks in these.
    Isotropic,
}

impl Coordinates {
    /// The suffixes of a point's two coordinate names.
    fn suffixes(self) -> [char; 2] {
        match self {
            Coordinates::Cartesian => ['x', 'y'],
            Coordinates::Isotropic => ['u', 'v'],
        }
    }
}

/// How the Lagrange multipliers are represented among the unknowns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Multipliers {
    /// `(λ, μ, …)` themselves: `∇D² − λ ∇C − Σ μ ∇g = 0` (the stored start solutions
    /// use these).
    #[default]
    Affine,
    /// Homogeneous multipliers `[λ₀ : λ : μ : …]` in a random affine chart
    /// `c₀ λ₀ + c·(λ, μ, …) = 1` (the Fritz John form of the Lagrange conditions,
    /// `λ₀ ∇D² − λ ∇C − Σ μ ∇g = 0`; one more unknown `lambda0` and the chart
    /// equation): a critical point whose multipliers are huge — `K′` close to a
    /// singular point of the constraint set, where `∇C` nearly vanishes — has
    /// `λ₀ = 1/(c₀ + c·(λ, μ))` small instead of multipliers near a pole, so its path
    /// stays bounded and the endgame does not mistake it for a path to infinity.
    /// Points with `λ₀ = 0` are not critical points of the Lagrangian but singular
    /// points of the constraint set (covered by the other sub-problems).
    Chart,
}

/// Coefficients `(c₀, c₁, c₂, …)` of the chart of [`Multipliers::Chart`]: fixed
/// complex numbers of modulus 1 at unrelated angles. Complex, so that the real
/// multiplier vectors the chart misses (`c₀ + c·λ = 0`: two real equations) form a set
/// of codimension 2 — none at all for the one multiplier of most sub-problems —
/// instead of a real hyperplane that real critical points could lie near.
const CHART_COEFFICIENTS: [(f64, f64); 4] = [
    (0.8090169943749475, 0.5877852522924731),
    (-0.4539904997395468, 0.8910065241883679),
    (0.2079116908177593, -0.9781476007338057),
    (-0.9135454576426009, -0.4067366430758002),
];

fn chart_coefficient(i: usize) -> C64 {
    let (re, im) = CHART_COEFFICIENTS[i % CHART_COEFFICIENTS.len()];
    C64::new(re, im)
}

/// A sub-problem's compiled Lagrange system `∇Λ = 0` together with the map from a
/// solution back to the configuration `K′` it describes.
#[derive(Clone)]
pub struct LagrangeProblem {
    id: ProblemId,
    coordinates: Coordinates,
    multipliers: Multipliers,
    /// The stratum posed on: rigid parts on a line have `v = 0` fixed.
    stratum: Stratum,
    /// Index of the first multiplier among the unknowns (the multipliers, and
    /// `lambda0` last for [`Multipliers::Chart`], end the list).
    first_multiplier: usize,
    /// Index of the first coordinate of every point among the variables.
    point_variables: Vec<usize>,
    /// `∇Λ = 0`, symbolic and compiled.
    equations: ParametricSystem,
    /// `K′(x; p)`: twelve coordinates as functions of the unknowns and parameters.
    configuration_map: CompiledSystem,
}

/// The system `∇Λ = 0` with its names ([`ParametricSystem`]'s accessors).
impl std::ops::Deref for LagrangeProblem {
    type Target = ParametricSystem;
    fn deref(&self) -> &ParametricSystem {
        &self.equations
    }
}

impl std::fmt::Debug for LagrangeProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LagrangeProblem")
            .field("id", &self.id.name())
            .field("variables", &self.variable_names())
            .field("parameters", &self.parameter_names())
            .finish()
    }
}

/// The name of `λ₀`, the multiplier of `D²` in the Fritz John form ([`Multipliers::Chart`]).
pub const CHART_VARIABLE: &str = "lambda0";

fn var(name: &str) -> Expr {
    Expr::variable(name)
}

fn par(name: &str) -> Expr {
    Expr::parameter(name)
}

/// The unknown points of one part (base or platform) and the constraint of a rigid part.
struct PartUnknowns {
    points: [Point<Expr>; 3],
    variables: Vec<String>,
    parameters: Vec<String>,
    /// `g = |x₂′ − x₁′|² − r²` and its multiplier's name, for a rigid part.
    rigidity: Option<(Expr, String)>,
}

fn part_unknowns<P: Plane<Expr>>(
    part: Part,
    prefix: char,
    role: &str,
    [sx, sy]: [char; 2],
    stratum: Stratum,
) -> PartUnknowns {
    let coordinate = |k: usize, c: char| format!("{prefix}{k}{c}");
    let point = |k: usize| [var(&coordinate(k, sx)), var(&coordinate(k, sy))];
    match part {
        Part::Rigid => {
            let (p1, p2) = (point(1), point(2));
            let (u, v, r2) = (
                format!("u_{role}"),
                format!("v_{role}"),
                format!("r2_{role}"),
            );
            // On a line (the stratum fixes v = 0): v is no parameter.
            let (v, parameters) = if stratum.fixes(role) {
                (Expr::from(0.0), vec![u.clone(), r2.clone()])
            } else {
                (par(&v), vec![u.clone(), v, r2.clone()])
            };
            let p3 = rpr::reconstruct_third_point_in::<P, _>(&p1, &p2, par(&u), v);
            let g = rpr::rigidity_constraint_in::<P, _>(&p1, &p2, par(&r2));
            PartUnknowns {
                points: [p1, p2, p3],
                variables: (1..=2)
                    .flat_map(|k| [coordinate(k, sx), coordinate(k, sy)])
                    .collect(),
                parameters,
                rigidity: Some((g, format!("mu_{role}"))),
            }
        }
        Part::Plate | Part::Bars => PartUnknowns {
            points: [point(1), point(2), point(3)],
            variables: (1..=3)
                .flat_map(|k| [coordinate(k, sx), coordinate(k, sy)])
                .collect(),
            parameters: Vec::new(),
            rigidity: None,
        },
    }
}

/// Applies `convert` to each of the six points of a configuration.
fn map_points(k: &[Expr; 12], convert: impl Fn(&Point<Expr>) -> Point<Expr>) -> [Expr; 12] {
    let mut out = k.clone();
    for j in (0..12).step_by(2) {
        [out[j], out[j + 1]] = convert(&[k[j].clone(), k[j + 1].clone()]);
    }
    out
}

fn flatten(base: &[Point<Expr>; 3], platform: &[Point<Expr>; 3]) -> [Expr; 12] {
    let mut out: Vec<Expr> = Vec::with_capacity(12);
    for p in base.iter().chain(platform.iter()) {
        out.push(p[0].clone());
        out.push(p[1].clone());
    }
    out.try_into()
        .unwrap_or_else(|_| unreachable!("six points have twelve coordinates"))
}

/// A rigid part's anchors count as collinear (all-collinear sub-problem applicable,
/// docs/theory.md §5.3) when `|v| ≤ COLLINEAR_ANCHOR_TOLERANCE`, with `v` the dimensionless
/// offset of anchor 3 from the line of anchors 1, 2 (docs/theory.md §4: distance / `|e|`).
pub const COLLINEAR_ANCHOR_TOLERANCE: f64 = 1e-9;

/// Offsets along the common line of the six points of the all-collinear sub-problem
/// (docs/theory.md §5.3), in the order `a₁ a₂ a₃ b₁ b₂ b₃` (`None` = 0, point 1 is `q`).
struct LineOffsets {
    offsets: Vec<Option<Expr>>,
    variables: Vec<String>,
    parameters: Vec<String>,
    /// `σ² − 1` and its multiplier `rho` (rigid/rigid: orientation of the platform).
    orientation: Option<(Expr, String)>,
}

/// Offsets `c_k` of the all-collinear parameterisation `x_k′ = q + c_k w`, `w·w = 1`
/// (Kapilavai and Nawratil, Eq. 56; docs/theory.md §5.3), with `c_{a₁} = 0` (the gauge:
/// `q = a₁′`):
///
/// - a `plate` part: free offsets (`t2 t3` for the base, `t4 t5 t6` for the platform);
/// - a `rigid` part whose anchors are collinear (docs/theory.md §4 with `v = 0`:
///   `x₃ = x₁ + u (x₂ − x₁)`): a proper motion keeps them on one line at fixed signed
///   distances, so its offsets are known up to a common shift: `(0, s₂, s₃)` for the
///   base (the base fixes the direction of `w`), `(t4, t4 + s₂, t4 + s₃)` for the
///   platform, with `s₂ = |e|`, `s₃ = u·|e|` (parameters `s2_base s3_base`,
///   `s2_platform s3_platform`). When the base is rigid as well, `w` is already
///   oriented by the base and the platform may point either way along the line:
///   `(t4, t4 + σ s₂, t4 + σ s₃)` with an unknown `σ`, `σ² = 1` (multiplier `rho`);
///   every critical point of the Lagrangian then has `σ = ±1` and is a critical point
///   of that orientation's problem (`rho` absorbs `∂Λ/∂σ`).
fn all_collinear_offsets(platform: Part, base: Part) -> LineOffsets {
    let mut variables = Vec::new();
    let mut parameters = Vec::new();
    let mut orientation = None;
    let mut offsets: Vec<Option<Expr>> = vec![None];
    if base == Part::Rigid {
        parameters.extend(["s2_base", "s3_base"].map(String::from));
        offsets.extend([Some(par("s2_base")), Some(par("s3_base"))]);
    } else {
        variables.extend(["t2", "t3"].map(String::from));
        offsets.extend([Some(var("t2")), Some(var("t3"))]);
    }
    if platform == Part::Rigid {
        parameters.extend(["s2_platform", "s3_platform"].map(String::from));
        variables.push("t4".to_string());
        let sign = if base == Part::Rigid {
            variables.push("sigma".to_string());
            orientation = Some((
                var("sigma") * var("sigma") - Expr::from(1.0),
                "rho".to_string(),
            ));
            var("sigma")
        } else {
            Expr::from(1.0)
        };
        offsets.push(Some(var("t4")));
        for s in ["s2_platform", "s3_platform"] {
            offsets.push(Some(var("t4") + sign.clone() * par(s)));
        }
    } else {
        for k in 4..=6 {
            let t = format!("t{k}");
            offsets.push(Some(var(&t)));
            variables.push(t);
        }
    }
    LineOffsets {
        offsets,
        variables,
        parameters,
        orientation,
    }
}

/// Whether the anchors of a rigid part with shape `shape` are collinear
/// ([`COLLINEAR_ANCHOR_TOLERANCE`]).
pub fn anchors_collinear(shape: &rpr::RigidShape) -> bool {
    shape.v.abs() <= COLLINEAR_ANCHOR_TOLERANCE
}

impl LagrangeProblem {
    /// Whether sub-problem `id` exists for `design` (docs/theory.md §5.3): all-collinear
    /// with a rigid part needs that part's anchors to be collinear
    /// ([`COLLINEAR_ANCHOR_TOLERANCE`]); every other sub-problem always applies.
    pub fn check_applicable(id: ProblemId, design: &Design) -> Result<(), ProblemError> {
        if id.subproblem != SubProblem::AllCollinear {
            return Ok(());
        }
        for (part, role, shape) in [
            (id.metric.base, "base", design.base_shape()),
            (id.metric.platform, "platform", design.platform_shape()),
        ] {
            if part == Part::Rigid && !anchors_collinear(&shape) {
                return Err(ProblemError::NotApplicable {
                    problem: id.name(),
                    reason: format!(
                        "all six points on one line needs the rigid {role}'s anchors to be \
                         collinear (Kapilavai and Nawratil, Thm 3; docs/theory.md §5.3); \
                         here anchor 3 is off the line of anchors 1, 2 \
                         by v = {:.3e} |e| (tolerance {COLLINEAR_ANCHOR_TOLERANCE:e})",
                        shape.v
                    ),
                });
            }
        }
        Ok(())
    }

    /// [`LagrangeProblem::new`] for a sub-problem that applies to `design`
    /// ([`LagrangeProblem::check_applicable`]; `NotApplicable` otherwise).
    pub fn for_design(id: ProblemId, design: &Design) -> Result<Self, ProblemError> {
        Self::for_design_in(id, design, Coordinates::Cartesian)
    }

    /// [`LagrangeProblem::for_design`] with the unknown points in `coordinates`.
    pub fn for_design_in(
        id: ProblemId,
        design: &Design,
        coordinates: Coordinates,
    ) -> Result<Self, ProblemError> {
        Self::check_applicable(id, design)?;
        Self::new_in(id, coordinates)
    }

    /// Builds and compiles the Lagrange system of `id` (docs/theory.md §5).
    ///
    /// Variables: the unknown coordinates of K′ (a rigid part lists only its first two
    /// points), then the multipliers (`lambda`, `mu_base`, `mu_platform`), or for
    /// all-collinear `qx qy wx wy`, the free offsets (`t2 t3` of a plate base, `t4 t5 t6`
    /// of a plate platform, `t4` of a rigid platform, `sigma` for rigid/rigid), `nu`
    /// (and `rho` for rigid/rigid) (point 1 is q; see `all_collinear_offsets`), for
    /// coincident points `qx qy` + the rigid part's coordinates + its multiplier.
    /// Parameters: `A1x … B3y`, then `u_base v_base r2_base` and/or `u_platform
    /// v_platform r2_platform`; for all-collinear the line offsets `s2_base s3_base`
    /// and/or `s2_platform s3_platform` of collinear rigid anchors instead.
    ///
    /// Every sub-problem is built for any design; whether it applies to a given design
    /// is [`LagrangeProblem::check_applicable`].
    pub fn new(id: ProblemId) -> Result<Self, ProblemError> {
        Self::new_in(id, Coordinates::Cartesian)
    }

    /// [`LagrangeProblem::new`] with the unknown points in `coordinates` (the
    /// parameters, the multipliers and [`LagrangeProblem::configuration`] stay
    /// Cartesian; [`LagrangeProblem::from_cartesian`] converts solutions).
    pub fn new_in(id: ProblemId, coordinates: Coordinates) -> Result<Self, ProblemError> {
        Self::new_with(id, coordinates, Multipliers::Affine)
    }

    /// [`LagrangeProblem::new_in`] with the multipliers represented as `multipliers`
    /// ([`LagrangeProblem::from_cartesian`] and [`LagrangeProblem::to_cartesian`]
    /// convert solutions from and to affine multipliers).
    pub fn new_with(
        id: ProblemId,
        coordinates: Coordinates,
        multipliers: Multipliers,
    ) -> Result<Self, ProblemError> {
        Self::new_on(id, (coordinates, multipliers), Stratum::GENERIC)
    }

    /// [`LagrangeProblem::new_with`] posed on `stratum`: each rigid part it puts on a
    /// line has `v = 0` as a constant of the system instead of the parameter `v_base` /
    /// `v_platform` ([`Stratum`]).
    pub fn new_on(
        id: ProblemId,
        (coordinates, multipliers): (Coordinates, Multipliers),
        stratum: Stratum,
    ) -> Result<Self, ProblemError> {
        match coordinates {
            Coordinates::Cartesian => {
                Self::build::<Cartesian>(id, coordinates, multipliers, stratum)
            }
            Coordinates::Isotropic => {
                Self::build::<Isotropic>(id, coordinates, multipliers, stratum)
            }
        }
    }

    /// [`LagrangeProblem::new_on`] for a sub-problem that applies to `design`, on a
    /// stratum `design` lies on (the generic one, or one whose every part on a line is
    /// on a line in `design` too, [`Stratum::of`]; otherwise an error).
    pub fn for_design_on(
        id: ProblemId,
        design: &Design,
        representation: (Coordinates, Multipliers),
        stratum: Stratum,
    ) -> Result<Self, ProblemError> {
        Self::check_applicable(id, design)?;
        let on_design = Stratum::of(id, design);
        if (stratum.collinear_base && !on_design.collinear_base)
            || (stratum.collinear_platform && !on_design.collinear_platform)
        {
            return Err(ProblemError::Build {
                problem: id.name(),
                message: format!(
                    "the design is not on the stratum {} (a rigid part's anchors are not \
                     collinear)",
                    stratum.name().unwrap_or("generic")
                ),
            });
        }
        Self::new_on(id, representation, stratum)
    }

    fn build<P: Plane<Expr>>(
        id: ProblemId,
        coordinates: Coordinates,
        multipliers: Multipliers,
        stratum: Stratum,
    ) -> Result<Self, ProblemError> {
        let metric = id.metric;
        let suffixes = coordinates.suffixes();
        let [sx, sy] = suffixes;
        let given_cartesian: [Expr; 12] =
            std::array::from_fn(|i| par(CONFIGURATION_PARAMETER_NAMES[i]));
        let given = map_points(&given_cartesian, P::from_cartesian);
        let mut parameters: Vec<String> = CONFIGURATION_PARAMETER_NAMES
            .iter()
            .map(|s| s.to_string())
            .collect();
        let mut variables: Vec<String> = Vec::new();
        let mut constraints: Vec<(Expr, String)> = Vec::new();

        let configuration: [Expr; 12] = match id.subproblem {
            SubProblem::Singularity | SubProblem::CollinearPlatform | SubProblem::CollinearBase => {
                let base = part_unknowns::<P>(metric.base, 'a', "base", suffixes, stratum);
                let platform =
                    part_unknowns::<P>(metric.platform, 'b', "platform", suffixes, stratum);
                variables.extend(base.variables.iter().cloned());
                variables.extend(platform.variables.iter().cloned());
                let k_prime = flatten(&base.points, &platform.points);
                let condition = match id.subproblem {
                    SubProblem::Singularity => rpr::singularity_polynomial_in::<P, _>(&k_prime),
                    SubProblem::CollinearPlatform => {
                        rpr::collinearity_platform_in::<P, _>(&k_prime)
                    }
                    _ => rpr::collinearity_base_in::<P, _>(&k_prime),
                };
                constraints.push((condition, "lambda".to_string()));
                for part in [base, platform] {
                    parameters.extend(part.parameters);
                    constraints.extend(part.rigidity);
                }
                k_prime
            }
            SubProblem::AllCollinear => {
                // Paper Eq. 56: the first point is q itself, the others q + c_k w
                // (fixing c_1 = 0 removes the slide of q along the line). See
                // `all_collinear_offsets` for the offsets c_k of a rigid part.
                let names = [
                    format!("q{sx}"),
                    format!("q{sy}"),
                    format!("w{sx}"),
                    format!("w{sy}"),
                ];
                let q = [var(&names[0]), var(&names[1])];
                let w = [var(&names[2]), var(&names[3])];
                variables.extend(names);
                let offsets = all_collinear_offsets(metric.platform, metric.base);
                variables.extend(offsets.variables);
                parameters.extend(offsets.parameters);
                let points: Vec<Point<Expr>> = offsets
                    .offsets
                    .into_iter()
                    .map(|offset| match offset {
                        None => q.clone(),
                        Some(c) => [
                            q[0].clone() + c.clone() * w[0].clone(),
                            q[1].clone() + c * w[1].clone(),
                        ],
                    })
                    .collect();
                let norm = P::dot(&w, &w) - Expr::from(1.0);
                constraints.push((norm, "nu".to_string()));
                constraints.extend(offsets.orientation);
                let base = [points[0].clone(), points[1].clone(), points[2].clone()];
                let platform = [points[3].clone(), points[4].clone(), points[5].clone()];
                flatten(&base, &platform)
            }
            SubProblem::CoincidentPlatform | SubProblem::CoincidentBase => {
                let names = [format!("q{sx}"), format!("q{sy}")];
                let q = [var(&names[0]), var(&names[1])];
                variables.extend(names);
                let coincident = [q.clone(), q.clone(), q];
                let (base, platform) = if id.subproblem == SubProblem::CoincidentPlatform {
                    let base = part_unknowns::<P>(Part::Rigid, 'a', "base", suffixes, stratum);
                    variables.extend(base.variables.iter().cloned());
                    parameters.extend(base.parameters.iter().cloned());
                    constraints.extend(base.rigidity.clone());
                    (base.points, coincident)
                } else {
                    let platform =
                        part_unknowns::<P>(Part::Rigid, 'b', "platform", suffixes, stratum);
                    variables.extend(platform.variables.iter().cloned());
                    parameters.extend(platform.parameters.iter().cloned());
                    constraints.extend(platform.rigidity.clone());
                    (coincident, platform.points)
                };
                flatten(&base, &platform)
            }
        };

        let mut lagrangian = metric.distance_sq_in::<P, Expr>(&given, &configuration);
        if multipliers == Multipliers::Chart {
            lagrangian = var(CHART_VARIABLE) * lagrangian;
        }
        let first_multiplier = variables.len();
        for (constraint, multiplier) in constraints {
            lagrangian -= var(&multiplier) * constraint;
            variables.push(multiplier);
        }
        let build_error = |e: &dyn std::fmt::Display| ProblemError::Build {
            problem: id.name(),
            message: e.to_string(),
        };
        // ∂Λ/∂(x, λ, μ); for the chart λ₀ is not differentiated by (declared as a
        // parameter here, an unknown below).
        let mut symbols = parameters.clone();
        if multipliers == Multipliers::Chart {
            symbols.push(CHART_VARIABLE.to_string());
        }
        let mut system = System::lagrange(&lagrangian, variables.clone(), symbols)
            .map_err(|e| build_error(&e))?;
        if multipliers == Multipliers::Chart {
            // Λ = λ₀ D² − λ C − Σ μ g, and the chart c₀ λ₀ + Σ c_i λ_i − 1 = 0
            // (not ∂Λ/∂λ₀ = D²).
            variables.push(CHART_VARIABLE.to_string());
            let mut chart =
                Expr::constant(chart_coefficient(0)) * var(CHART_VARIABLE) - Expr::from(1.0);
            for (i, name) in variables[first_multiplier..variables.len() - 1]
                .iter()
                .enumerate()
            {
                chart += Expr::constant(chart_coefficient(i + 1)) * var(name);
            }
            let mut equations = system.equations().to_vec();
            equations.push(chart);
            system = System::new(variables.clone(), parameters.clone(), equations)
                .and_then(|s| s.with_homogenizing_variable(CHART_VARIABLE))
                .map_err(|e| build_error(&e))?;
        }
        let point_variables = (0..variables.len().saturating_sub(1))
            .filter(|&i| {
                let (first, second) = (&variables[i], &variables[i + 1]);
                first
                    .strip_suffix(sx)
                    .is_some_and(|stem| !stem.is_empty() && second.strip_suffix(sy) == Some(stem))
            })
            .collect();
        let configuration = map_points(&configuration, P::to_cartesian);
        let configuration_map = System::new(variables, parameters, configuration.to_vec())
            .map_err(|e| build_error(&e))?;
        Ok(LagrangeProblem {
            id,
            coordinates,
            multipliers,
            stratum,
            first_multiplier,
            point_variables,
            equations: ParametricSystem::new(system),
            configuration_map: configuration_map.compile(),
        })
    }

    /// Which metric and sub-problem this is.
    pub fn id(&self) -> ProblemId {
        self.id
    }

    /// The coordinates of the unknown points.
    pub fn coordinates(&self) -> Coordinates {
        self.coordinates
    }

    /// How the multipliers are represented.
    pub fn multipliers(&self) -> Multipliers {
        self.multipliers
    }

    /// The stratum the system is posed on ([`Stratum`]).
    pub fn stratum(&self) -> Stratum {
        self.stratum
    }

    /// Index of the first Lagrange multiplier among the unknowns: the unknowns before
    /// it describe `K′` (points, line offsets, orientation).
    pub fn first_multiplier(&self) -> usize {
        self.first_multiplier
    }

    /// The solution `x` (Cartesian variables `a1x a1y …` and affine multipliers, as in
    /// the stored start solutions) in this problem's unknowns: `(u, v) = ((x + i y)/√2,
    /// (x − i y)/√2)` per point for [`Coordinates::Isotropic`]; for
    /// [`Multipliers::Chart`] `λ₀ = 1/(c₀ + c·λ)` appended and every multiplier `λ_i`
    /// replaced by `λ₀ λ_i`.
    pub fn from_cartesian(&self, x: &[C64]) -> Vec<C64> {
        let mut out = self.convert_points(x, crate::algebra::to_isotropic);
        if self.multipliers == Multipliers::Chart {
            let multipliers = &mut out[self.first_multiplier.min(x.len())..];
            let denominator = multipliers
                .iter()
                .enumerate()
                .fold(chart_coefficient(0), |sum, (i, m)| {
                    sum + chart_coefficient(i + 1) * m
                });
            let lambda0 = denominator.inv();
            for m in multipliers.iter_mut() {
                *m *= lambda0;
            }
            out.push(lambda0);
        }
        out
    }

    /// The inverse of [`LagrangeProblem::from_cartesian`]: `x = (u + v)/√2`,
    /// `y = −i (u − v)/√2` per point, and for [`Multipliers::Chart`] the multipliers
    /// `λ_i / λ₀` (`lambda0`, the last unknown, dropped; not finite where `λ₀ = 0`).
    pub fn to_cartesian(&self, x: &[C64]) -> Vec<C64> {
        let mut out = self.convert_points(x, crate::algebra::to_cartesian);
        if self.multipliers == Multipliers::Chart
            && let Some(lambda0) = out.pop()
        {
            let scale = lambda0.inv();
            for m in out[self.first_multiplier.min(x.len())..].iter_mut() {
                *m *= scale;
            }
        }
        out
    }

    /// The number of entries of a solution with Cartesian points and affine multipliers
    /// (as stored in start files): one fewer than the unknowns for
    /// [`Multipliers::Chart`].
    pub fn stored_solution_len(&self) -> usize {
        let len = self.variable_names().len();
        match self.multipliers {
            Multipliers::Chart => len - 1,
            Multipliers::Affine => len,
        }
    }

    /// First index of every point's coordinate pair `(u, v)` among the unknowns when
    /// they are [`Coordinates::Isotropic`] (empty for Cartesian ones): what
    /// certification needs to decide realness (`(u, v) ↦ (v̄, ū)`).
    pub fn isotropic_pairs(&self) -> Vec<usize> {
        match self.coordinates {
            Coordinates::Isotropic => self.point_variables.clone(),
            Coordinates::Cartesian => Vec::new(),
        }
    }

    /// The complex conjugate solution: for real parameters the system has real
    /// coefficients in Cartesian coordinates, so with `x` also `x̄` is a solution. In
    /// this problem's coordinates: every entry conjugated, and for
    /// [`Coordinates::Isotropic`] the two coordinates of each point swapped
    /// (`(u, v) ↦ (v̄, ū)`, since `ū = (x̄ − iȳ)/√2`).
    pub fn conjugate(&self, x: &[C64]) -> Vec<C64> {
        if self.multipliers == Multipliers::Chart {
            // The chart's coefficients are complex: conjugate the Cartesian point and
            // its affine multipliers, whose system has real coefficients.
            let cartesian: Vec<C64> = self.to_cartesian(x).iter().map(|v| v.conj()).collect();
            return self.from_cartesian(&cartesian);
        }
        let mut out: Vec<C64> = x.iter().map(|v| v.conj()).collect();
        if self.coordinates == Coordinates::Isotropic {
            for &i in &self.point_variables {
                if i + 1 < out.len() {
                    out.swap(i, i + 1);
                }
            }
        }
        out
    }

    fn convert_points(&self, x: &[C64], convert: fn(&Point<C64>) -> Point<C64>) -> Vec<C64> {
        let mut out = x.to_vec();
        if self.coordinates == Coordinates::Isotropic {
            for &i in &self.point_variables {
                if i + 1 < out.len() {
                    [out[i], out[i + 1]] = convert(&[x[i], x[i + 1]]);
                }
            }
        }
        out
    }

    /// Parameter vector for the given configuration `k` (twelve coordinates, possibly
    /// complex) of `design`: `k` followed by the rigid parts' shape constants
    /// `(u, v, r²)` of docs/theory.md §4, computed from the design's base and platform
    /// anchors (all-collinear: the line offsets `s₂ = |e|`, `s₃ = u·|e|`).
    pub fn parameters_for(&self, design: &Design, k: &[C64; 12]) -> Vec<C64> {
        self.parameters_in_units(design, k, 1.0)
    }

    /// [`LagrangeProblem::parameters_for`] with lengths measured in units of `unit`:
    /// `k` is taken as given (already in those units) and the design's shape constants
    /// are converted (`r² / unit²`, offsets `s / unit`; `u, v` are dimensionless). The
    /// curve pipeline works in a normalised frame this way.
    pub fn parameters_in_units(&self, design: &Design, k: &[C64; 12], unit: f64) -> Vec<C64> {
        let mut out: Vec<C64> = k.to_vec();
        for name in &self.parameter_names()[12..] {
            let shape = if name.ends_with("_base") {
                design.base_shape()
            } else {
                design.platform_shape()
            };
            let value = if name.starts_with("s2_") {
                shape.r2.sqrt() / unit
            } else if name.starts_with("s3_") {
                shape.u * shape.r2.sqrt() / unit
            } else if name.starts_with("u_") {
                shape.u
            } else if name.starts_with("v_") {
                shape.v
            } else {
                shape.r2 / (unit * unit)
            };
            out.push(C64::new(value, 0.0));
        }
        out
    }

    /// `K′` described by the solution `x` at parameters `p` (twelve coordinates).
    pub fn configuration(&self, x: &[C64], p: &[C64], work: &mut [C64]) -> [C64; 12] {
        let mut out = [C64::new(0.0, 0.0); 12];
        self.configuration_map.evaluate(x, p, work, &mut out);
        out
    }

    /// [`LagrangeProblem::configuration`] over boxes: twelve rectangles that contain
    /// `K′(ξ; π)` for every `ξ ∈ x`, `π ∈ p` (interval arithmetic, outward rounding).
    pub fn configuration_enclosure(
        &self,
        x: &[ComplexInterval],
        p: &[ComplexInterval],
    ) -> [ComplexInterval; 12] {
        let mut out = [ComplexInterval::default(); 12];
        let mut jacobian = vec![ComplexInterval::default(); 12 * x.len()];
        self.configuration_map
            .evaluate_interval_with_jacobian(x, p, &mut out, &mut jacobian);
        out
    }

    /// Scratch length sufficient for both the system and the configuration map.
    pub fn workspace_len(&self) -> usize {
        self.evaluator()
            .workspace_len()
            .max(self.configuration_map.workspace_len())
    }
}
