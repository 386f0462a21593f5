//! Actuation schemes of the planar 3-RRR: Jacobians, singularity types, singularity loci and the
//! global conditioning index GCI (docs/theory.md §11.5; Ramana Babu et al. §III–V).
//!
//! # Jacobians (Ramana Babu et al. Eqs. 16–18)
//!
//! With the vectors of the configuration ([`RrrConfiguration`])
//! `b_i = B_i − O_i`, `c_i = C_i − B_i`, `a_i = P − C_i` and the twist `ẋ = (ẋ_P, ẏ_P, φ̇)`,
//! every scheme satisfies the velocity relation **`J_x ẋ = J_q q̇`** with a diagonal `J_q`:
//!
//! | active joint of leg i | `J_x` row i | `J_q` diagonal i | `q_i` |
//! |---|---|---|---|
//! | θ (base joint) | `[c_ix, c_iy, a_iy c_ix − a_ix c_iy]` | `b_i × c_i` | `θ_i = atan2(b_i)` |
//! | ψ, [`PsiModel::Seed`] | `[b_ix, b_iy, a_iy b_ix − a_ix b_iy]` | `−b_i × c_i` | `ψ_i = atan2(c_i)` (absolute) |
//! | ψ, [`PsiModel::RelativeElbow`] | `[d_ix, d_iy, a_iy d_ix − a_ix d_iy]`, `d_i = C_i − O_i` | `−b_i × c_i` | `ψ_i − θ_i` (elbow joint angle) |
//!
//! Derivation (checked by finite differences of the inverse kinematics in
//! `tests/actuation_jacobians.rs`): `C_i = P − a_i` with `ȧ_i = φ̇ E a_i`. A θ-actuated leg keeps
//! `|C_i − B_i|² = c²`: differentiating gives `c_i·(Ṗ − φ̇ E a_i − θ̇_i E b_i) = 0`, i.e. the θ
//! row above. The ψ matrices of Ramana Babu et al. keep `|B_i − O_i|² = b²` with
//! `B_i = C_i − c_i` and the *absolute* distal angle ψ_i as input; the physical elbow
//! motor drives the *relative* angle `ψ_i − θ_i`, which fixes
//! `|C_i − O_i|² = b² + c² + 2bc cos(ψ_i − θ_i)` and gives the `d_i` row (its Type II:
//! lines `O_iC_i` concurrent, as the paper's text says, while its matrices give Type II
//! when the lines through `C_i` parallel to `O_iB_i` are concurrent). All the paper's
//! matrices `J_x1..8`, `J_q1..8` agree with this table. Typos found and fixed: the
//! listing of `q̇_6` reads `[ψ̇_1 θ̇_2 ψ̇_3]` (that is `q̇_8`) while Table I and `J_x6`,
//! `J_q6` give θ_1 ψ_2 ψ_3; the denominator of Eq. 15 reads `e_2i − e_2i` for
//! `e_3i − e_2i`; Eq. 12 has `2a y_oi sin ψ_i` for `2c y_oi sin ψ_i`.
//!
//! # Singularities (Ramana Babu et al. §III.B)
//! Type I: `det J_q = 0` (some leg has `O_i, B_i, C_i` aligned; identical for all schemes).
//! Type II: `det J_x = 0`. Type III: both.
//!
//! Two facts of the symmetric family ([`RrrDesign::symmetric`]) worth knowing when reading a
//! GCI table: (1) a rotation of the whole robot by 120° maps leg i to leg i+1 at the *same*
//! orientation φ, so θθψ, θψθ, ψθθ (schemes 3–5) have equal GCIs on a 120°-invariant region,
//! and so have θψψ, ψψθ, ψθψ (6–8); on the square grid they differ only by discretisation
//! (Table II of Ramana Babu et al., where they differ by up to 20 %, therefore cannot
//! come from a symmetric design with symmetric limits and grid). (2) With the
//! relative-elbow model, ψψψ is singular at *every* position when φ = 0: base and
//! platform triangles are similar and equally oriented, so the lines `O_iC_i` all pass
//! through `R·P/(R − a)` (the architecture singularity of the similar-triangle 3-RPR);
//! its GCI at φ = 0 is 0. (3) With isosceles legs (`b = c`) the paper-model ψψψ in
//! working mode σ equals θθθ in mode −σ pose by pose (the mirrored elbow swaps the
//! directions of `b_i` and `c_i`); at φ = 0 the mirror symmetry of the design then gives
//! equal GCIs for θθθ and ψψψ in the same mode.
//!
//! # GCI (Ramana Babu et al. Eq. 20)
//! `GCI = ∫_W (1/κ) dw / ∫_W dw`, discretised as the mean of `1/κ(J)`, `J = J_q⁻¹ J_x`, over
//! the nodes of an (x, y) grid at constant orientation. **Choice** ([`GciDomain`]): by default
//! the mean runs over the *reachable* nodes only (the paper's `∫_W dw` is the workspace
//! area); [`GciDomain::Grid`] divides by all grid nodes (unreachable nodes count 0),
//! which is the objective the design optimisation uses by default because the
//! reachable-only mean rewards shrinking the workspace. Singular nodes count 0 in both.
//!
//! # Findings on the example geometry ([`ExampleGeometry`], `singdist schemes`)
//!
//! Paper model ([`PsiModel::Seed`]), 81×81 grid, reachable mean, 2-norm: at φ = 0 θθθ
//! 0.2901 > ψψψ 0.2152 > {θθψ, θψθ, ψθθ} 0.1485 > {θψψ, ψψθ, ψθψ} 0.1347; at φ = 20° θθθ
//! 0.2420 > {3, 4, 5} 0.2099 > ψψψ 0.1980 > {6, 7, 8} 0.1582. So between 0° and 20° the
//! best scheme does **not** change here; over a wider range it does (θθθ for φ ∈ [−10°,
//! 20°] and 50°–60°, the {3, 4, 5} class at 25°, ψψψ at 30°–40° and at −20°), and between
//! 0° and 20° it does change for other link lengths (e.g. (a, b, c) = (2, 2.5, 3.5): θθθ
//! → θψθ class) and with the relative-elbow model (θθθ at 0°, ψψψ 0.2984 at 20°). The
//! paper's qualitative claim holds in general, but not for every geometry at its two
//! orientations. GA optima (grid-mean objective, λ = 9.3) push `b, c` to their upper
//! bound 4 and make `a + b + c ≤ λ` active (a = 1.3) for most schemes, like Table IV of
//! Ramana Babu et al.; θθθ is the best optimised scheme at both orientations, as in their
//! Table IV. With the reachable-only mean as objective the GA degenerates to tiny
//! workspaces with GCI → 1, which is why the GA uses the grid mean by default.

use crate::choice::UnknownChoice;
use crate::mechanism::rrr::{
    ElbowMode, Point, RrrConfiguration, RrrDesign, RrrError, RrrPose, WorkingModes, det3,
};
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;
use std::fmt;
use std::path::Path;
use std::str::FromStr;
use thiserror::Error;

/// Errors of the actuation-scheme analysis; each names the field at fault.
#[derive(Debug, Error)]
pub enum ActuationError {
    /// A scheme number outside 1..=8.
    #[error("scheme number must be 1..=8, got {0}")]
    SchemeNumber(i64),
    /// An unknown scheme name.
    #[error(
        "unknown actuation scheme `{0}` (use 1..8, a Greek name like θθψ or an ASCII name like ttp)"
    )]
    UnknownScheme(String),
    /// An unknown option value (norm, domain, ψ model).
    #[error(transparent)]
    UnknownChoice(#[from] UnknownChoice),
    /// A grid or option field out of range.
    #[error("invalid {field}: {reason}")]
    InvalidField {
        /// Field name, e.g. `grid.nx`.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// The design or pose is invalid.
    #[error(transparent)]
    Design(#[from] RrrError),
    /// The SVG plot could not be written.
    #[error("plot {path}: {message}")]
    Plot {
        /// Output file.
        path: String,
        /// Backend message.
        message: String,
    },
}

/// Active joint of one leg.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Actuator {
    /// The base joint (angle θ_i of the proximal link).
    Theta,
    /// The elbow joint (ψ_i; see [`PsiModel`]).
    Psi,
}

named_choices! {
    option "psi model", error ActuationError, default Seed;
    /// Which elbow input a ψ-actuated leg has (docs/theory.md §11.5 **Choice**).
    #[derive(Hash)]
    pub enum PsiModel {
        /// The matrices of Ramana Babu et al.: input = absolute distal angle
        /// `ψ_i = atan2(C_i − B_i)`.
        Seed = "seed" | "absolute",
        /// Physical elbow motor: input = relative angle `ψ_i − θ_i`; `J_x` row built on
        /// `d_i = C_i − O_i`.
        RelativeElbow = "relative" | "relative-elbow" | "elbow",
    }
}

/// One of the eight non-redundant actuation schemes of Ramana Babu et al. Table I.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Scheme {
    number: u8,
}

const SCHEME_TABLE: [[Actuator; 3]; 8] = {
    use Actuator::{Psi as P, Theta as T};
    [
        [T, T, T],
        [P, P, P],
        [T, T, P],
        [T, P, T],
        [P, T, T],
        [T, P, P],
        [P, P, T],
        [P, T, P],
    ]
};

impl Scheme {
    /// Scheme by its number 1..=8 (Ramana Babu et al. Table I: θθθ, ψψψ, θθψ, θψθ, ψθθ, θψψ, ψψθ, ψθψ).
    pub fn from_number(number: i64) -> Result<Self, ActuationError> {
        if (1..=8).contains(&number) {
            Ok(Self {
                number: number as u8,
            })
        } else {
            Err(ActuationError::SchemeNumber(number))
        }
    }

    /// All eight schemes in table order.
    pub fn all() -> [Scheme; 8] {
        [1, 2, 3, 4, 5, 6, 7, 8].map(|number| Scheme { number })
    }

    /// Number 1..=8.
    pub fn number(self) -> u8 {
        self.number
    }

    /// Active joint of each leg.
    pub fn actuators(self) -> [Actuator; 3] {
        SCHEME_TABLE[usize::from(self.number - 1)]
    }

    /// Greek name, e.g. `θθψ`.
    pub fn name(self) -> String {
        self.actuators()
            .iter()
            .map(|a| match a {
                Actuator::Theta => 'θ',
                Actuator::Psi => 'ψ',
            })
            .collect()
    }

    /// ASCII name, e.g. `ttp` (t = θ, p = ψ).
    pub fn ascii_name(self) -> String {
        self.actuators()
            .iter()
            .map(|a| match a {
                Actuator::Theta => 't',
                Actuator::Psi => 'p',
            })
            .collect()
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.number, self.name())
    }
}

impl FromStr for Scheme {
    type Err = ActuationError;
    /// Accepts `1`..`8`, Greek names (`θθψ`) and ASCII names (`ttp`, case-insensitive).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let trimmed = s.trim();
        if let Ok(number) = trimmed.parse::<i64>() {
            return Self::from_number(number);
        }
        let lower = trimmed.to_lowercase();
        Self::all()
            .into_iter()
            .find(|scheme| scheme.name() == lower || scheme.ascii_name() == lower)
            .ok_or_else(|| ActuationError::UnknownScheme(s.to_string()))
    }
}

fn cross(u: Point, v: Point) -> f64 {
    u.x * v.y - u.y * v.x
}

/// The Jacobians of one scheme at one configuration: `J_x ẋ = J_q q̇`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActuationJacobians {
    /// Direct-kinematics matrix `J_x` (rows per leg, see the module table).
    pub jx: Matrix3<f64>,
    /// Diagonal of the inverse-kinematics matrix `J_q`.
    pub jq: Vector3<f64>,
}

/// Row of `J_x` for a leg whose constraint line passes through `C_i` with direction `u`:
/// `[u_x, u_y, a_y u_x − a_x u_y]`, `a = P − C_i`.
fn line_row(u: Point, a: Point) -> [f64; 3] {
    [u.x, u.y, a.y * u.x - a.x * u.y]
}

/// `J_x` and `J_q` of `scheme` at `config` (Ramana Babu et al. Eqs. 16–18, module table).
pub fn jacobians(config: &RrrConfiguration, scheme: Scheme, model: PsiModel) -> ActuationJacobians {
    let mut jx = Matrix3::zeros();
    let mut jq = Vector3::zeros();
    for (leg, actuator) in scheme.actuators().into_iter().enumerate() {
        let b = config.proximal_vector(leg);
        let c = config.distal_vector(leg);
        let a = config.platform_vector(leg);
        let (row, diag) = match (actuator, model) {
            (Actuator::Theta, _) => (line_row(c, a), cross(b, c)),
            (Actuator::Psi, PsiModel::Seed) => (line_row(b, a), -cross(b, c)),
            (Actuator::Psi, PsiModel::RelativeElbow) => (line_row(b + c, a), -cross(b, c)),
        };
        for (k, value) in row.into_iter().enumerate() {
            jx[(leg, k)] = value;
        }
        jq[leg] = diag;
    }
    ActuationJacobians { jx, jq }
}

/// Active joint coordinates `q` of `scheme` at `config` (θ_i, absolute ψ_i, or `ψ_i − θ_i`
/// wrapped to (−π, π], per the module table).
pub fn active_joints(config: &RrrConfiguration, scheme: Scheme, model: PsiModel) -> [f64; 3] {
    let mut q = [0.0; 3];
    for (leg, actuator) in scheme.actuators().into_iter().enumerate() {
        q[leg] = match (actuator, model) {
            (Actuator::Theta, _) => config.theta(leg),
            (Actuator::Psi, PsiModel::Seed) => config.psi(leg),
            (Actuator::Psi, PsiModel::RelativeElbow) => {
                let b = config.proximal_vector(leg);
                let c = config.distal_vector(leg);
                cross(b, c).atan2(b.dot(&c))
            }
        };
    }
    q
}

named_choices! {
    option "norm", error ActuationError, default Spectral;
    /// Matrix norm used in the condition number `κ = ‖J‖ ‖J⁻¹‖` (Ramana Babu et al. Eq. 19).
    pub enum ConditionNorm {
        /// 2-norm: `κ = σ_max/σ_min` (default).
        Spectral = "2-norm" | "2" | "two" | "spectral",
        /// Weighted Frobenius norm `‖A‖ = sqrt(tr(A Aᵀ)/3)` (Gosselin–Angeles), `κ ≥ 1`.
        WeightedFrobenius = "weighted-frobenius" | "frobenius" | "f",
    }
}

impl ActuationJacobians {
    /// `det J_x` (Type II when zero).
    pub fn det_jx(&self) -> f64 {
        self.jx.determinant()
    }

    /// `det J_q = Π J_q,ii` (Type I when zero).
    pub fn det_jq(&self) -> f64 {
        self.jq.iter().product()
    }

    /// `J = J_q⁻¹ J_x` (maps ẋ to q̇), `None` when `J_q` is singular.
    pub fn kinematic_jacobian(&self) -> Option<Matrix3<f64>> {
        if self.jq.iter().any(|d| *d == 0.0 || !d.is_finite()) {
            return None;
        }
        let mut j = self.jx;
        for leg in 0..3 {
            for k in 0..3 {
                j[(leg, k)] /= self.jq[leg];
            }
        }
        Some(j)
    }

    /// Local conditioning index `1/κ(J)` ∈ [0, 1], `J = J_q⁻¹ J_x` with column 3 divided by
    /// `length_scale` when given (homogenisation; Ramana Babu et al. use none). 0 at
    /// singularities.
    pub fn inverse_condition(&self, norm: ConditionNorm, length_scale: Option<f64>) -> f64 {
        let Some(mut j) = self.kinematic_jacobian() else {
            return 0.0;
        };
        if let Some(length) = length_scale {
            for leg in 0..3 {
                j[(leg, 2)] /= length;
            }
        }
        let value = match norm {
            ConditionNorm::Spectral => {
                let sv = j.singular_values();
                let max = sv.max();
                if max > 0.0 { sv.min() / max } else { 0.0 }
            }
            ConditionNorm::WeightedFrobenius => match j.try_inverse() {
                Some(inverse) => {
                    let n = (j.norm_squared() / 3.0).sqrt();
                    let n_inv = (inverse.norm_squared() / 3.0).sqrt();
                    1.0 / (n * n_inv)
                }
                None => 0.0,
            },
        };
        if value.is_finite() {
            value.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// Singularity type at a configuration (Ramana Babu et al. §III.B).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SingularityType {
    /// Neither Jacobian singular.
    Regular,
    /// `det J_q = 0` only.
    TypeI,
    /// `det J_x = 0` only.
    TypeII,
    /// Both.
    TypeIII,
}

/// Tolerances of [`classify`]; both measures are dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularityTolerance {
    /// Type I when some `|b_i × c_i| / (|b_i||c_i|)` (= |sin| of the elbow angle) is below.
    pub leg: f64,
    /// Type II when [`normalized_det_jx`] is below in absolute value.
    pub parallel: f64,
}

impl Default for SingularityTolerance {
    fn default() -> Self {
        Self {
            leg: 1e-9,
            parallel: 1e-9,
        }
    }
}

/// Dimensionless `det J_x`: each row divided by the norm of its direction part, the determinant
/// divided by `length` (e.g. [`RrrDesign::platform_length`]). Zero iff Type II.
pub fn normalized_det_jx(jac: &ActuationJacobians, length: f64) -> f64 {
    let mut rows = [[0.0; 3]; 3];
    for (leg, row) in rows.iter_mut().enumerate() {
        let n = jac.jx[(leg, 0)].hypot(jac.jx[(leg, 1)]);
        let n = if n > 0.0 { n } else { 1.0 };
        for (k, value) in row.iter_mut().enumerate() {
            *value = jac.jx[(leg, k)] / n;
        }
    }
    det3(&rows) / length
}

/// Minimum over legs of `|b_i × c_i| / (|b_i||c_i|)` (0 at a Type I singularity).
pub fn leg_singularity_measure(config: &RrrConfiguration) -> f64 {
    (0..3)
        .map(|leg| {
            let b = config.proximal_vector(leg);
            let c = config.distal_vector(leg);
            cross(b, c).abs() / (b.norm() * c.norm())
        })
        .fold(f64::INFINITY, f64::min)
}

/// Singularity type of `scheme` at `config` with tolerances `tol`.
pub fn classify(
    design: &RrrDesign,
    config: &RrrConfiguration,
    scheme: Scheme,
    model: PsiModel,
    tol: SingularityTolerance,
) -> SingularityType {
    let jac = jacobians(config, scheme, model);
    let type_i = leg_singularity_measure(config) < tol.leg;
    let type_ii = normalized_det_jx(&jac, design.platform_length()).abs() < tol.parallel;
    match (type_i, type_ii) {
        (false, false) => SingularityType::Regular,
        (true, false) => SingularityType::TypeI,
        (false, true) => SingularityType::TypeII,
        (true, true) => SingularityType::TypeIII,
    }
}

/// Rectangular (x, y) grid of nodes at constant orientation, `nx × ny` nodes including the
/// edges, row-major with x fastest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkspaceGrid {
    /// Smallest x.
    pub x_min: f64,
    /// Largest x.
    pub x_max: f64,
    /// Smallest y.
    pub y_min: f64,
    /// Largest y.
    pub y_max: f64,
    /// Nodes along x (≥ 2).
    pub nx: usize,
    /// Nodes along y (≥ 2).
    pub ny: usize,
}

impl WorkspaceGrid {
    /// Square grid `[−half_width, half_width]²` with `n × n` nodes.
    pub fn square(half_width: f64, n: usize) -> Self {
        Self {
            x_min: -half_width,
            x_max: half_width,
            y_min: -half_width,
            y_max: half_width,
            nx: n,
            ny: n,
        }
    }

    /// Checks finiteness, ordering and node counts, naming the field.
    pub fn validate(&self) -> Result<(), ActuationError> {
        for (field, value) in [
            ("grid.x_min", self.x_min),
            ("grid.x_max", self.x_max),
            ("grid.y_min", self.y_min),
            ("grid.y_max", self.y_max),
        ] {
            if !value.is_finite() {
                return Err(ActuationError::InvalidField {
                    field: field.to_string(),
                    reason: format!("must be finite, got {value}"),
                });
            }
        }
        if self.x_max <= self.x_min || self.y_max <= self.y_min {
            return Err(ActuationError::InvalidField {
                field: "grid bounds".to_string(),
                reason: "need x_min < x_max and y_min < y_max".to_string(),
            });
        }
        for (field, n) in [("grid.nx", self.nx), ("grid.ny", self.ny)] {
            if !(2..=100_000).contains(&n) {
                return Err(ActuationError::InvalidField {
                    field: field.to_string(),
                    reason: format!("must be in 2..=100000, got {n}"),
                });
            }
        }
        Ok(())
    }

    /// x of column `i`.
    pub fn x(&self, i: usize) -> f64 {
        self.x_min + (self.x_max - self.x_min) * i as f64 / (self.nx - 1) as f64
    }

    /// y of row `j`.
    pub fn y(&self, j: usize) -> f64 {
        self.y_min + (self.y_max - self.y_min) * j as f64 / (self.ny - 1) as f64
    }

    /// Total node count.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True when the grid has no node (never for a validated grid).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

named_choices! {
    option "gci domain", error ActuationError, default Reachable;
    /// Which nodes the GCI mean runs over (module documentation, **Choice**).
    pub enum GciDomain {
        /// Mean over reachable nodes (Ramana Babu et al., Eq. 20, `∫_W dw` = workspace).
        /// Default for analysis.
        Reachable = "reachable" | "workspace",
        /// Mean over all grid nodes, unreachable nodes counting 0 (fixed task region).
        Grid = "grid" | "task",
    }
}

/// Options of [`gci`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GciOptions {
    /// Working modes of the legs (default: the positive modes of Ramana Babu et al.).
    pub modes: WorkingModes,
    /// ψ-actuation model.
    pub model: PsiModel,
    /// Matrix norm of κ.
    pub norm: ConditionNorm,
    /// Domain of the mean.
    pub domain: GciDomain,
    /// Optional homogenising length dividing the φ̇ column of J (seed: none).
    pub length_scale: Option<f64>,
}

impl Default for GciOptions {
    fn default() -> Self {
        Self {
            modes: [ElbowMode::Positive; 3],
            model: PsiModel::Seed,
            norm: ConditionNorm::Spectral,
            domain: GciDomain::Reachable,
            length_scale: None,
        }
    }
}

/// Result of [`gci`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GciResult {
    /// The GCI per the chosen domain (0 when no node is reachable).
    pub gci: f64,
    /// Mean of 1/κ over reachable nodes.
    pub mean_reachable: f64,
    /// Mean of 1/κ over all nodes (unreachable = 0).
    pub mean_grid: f64,
    /// Reachable nodes.
    pub reachable_nodes: usize,
    /// Reachable nodes at which `J` is exactly singular (1/κ = 0).
    pub singular_nodes: usize,
    /// All nodes.
    pub total_nodes: usize,
}

/// Local conditioning `1/κ(J)` at `pose`, `None` when unreachable.
pub fn local_inverse_condition(
    design: &RrrDesign,
    pose: &RrrPose,
    scheme: Scheme,
    options: &GciOptions,
) -> Option<f64> {
    let config = design.try_inverse_kinematics(pose, &options.modes)?;
    let jac = jacobians(&config, scheme, options.model);
    Some(jac.inverse_condition(options.norm, options.length_scale))
}

/// GCI of `scheme` at orientation `phi` over `grid` (Ramana Babu et al. Eq. 20, module documentation).
/// Rows are evaluated in parallel and summed in row order: deterministic for any thread count.
pub fn gci(
    design: &RrrDesign,
    scheme: Scheme,
    phi: f64,
    grid: &WorkspaceGrid,
    options: &GciOptions,
) -> Result<GciResult, ActuationError> {
    grid.validate()?;
    if !phi.is_finite() {
        return Err(ActuationError::InvalidField {
            field: "orientation".to_string(),
            reason: format!("must be finite, got {phi}"),
        });
    }
    if let Some(length) = options.length_scale
        && !(length.is_finite() && length > 0.0)
    {
        return Err(ActuationError::InvalidField {
            field: "length_scale".to_string(),
            reason: format!("must be positive and finite, got {length}"),
        });
    }
    let rows: Vec<(f64, usize, usize)> = (0..grid.ny)
        .into_par_iter()
        .map(|j| {
            let y = grid.y(j);
            let mut sum = 0.0;
            let mut reachable = 0;
            let mut singular = 0;
            for i in 0..grid.nx {
                let pose = RrrPose::new(grid.x(i), y, phi);
                if let Some(value) = local_inverse_condition(design, &pose, scheme, options) {
                    reachable += 1;
                    if value == 0.0 {
                        singular += 1;
                    }
                    sum += value;
                }
            }
            (sum, reachable, singular)
        })
        .collect();
    let (sum, reachable, singular) = rows.iter().fold((0.0, 0, 0), |acc, r| {
        (acc.0 + r.0, acc.1 + r.1, acc.2 + r.2)
    });
    let total = grid.len();
    let mean_reachable = if reachable > 0 {
        sum / reachable as f64
    } else {
        0.0
    };
    let mean_grid = sum / total as f64;
    Ok(GciResult {
        gci: match options.domain {
            GciDomain::Reachable => mean_reachable,
            GciDomain::Grid => mean_grid,
        },
        mean_reachable,
        mean_grid,
        reachable_nodes: reachable,
        singular_nodes: singular,
        total_nodes: total,
    })
}

/// Singularity loci of one scheme at constant orientation, detected as sign changes between
/// neighbouring grid nodes (Ramana Babu et al. §IV, Figs. 6–21).
///
/// Type I loci: sign changes of `Π_i (|d_i|² − (b_i+c_i)²)(|d_i|² − (b_i−c_i)²)`,
/// `d_i = C_i − O_i`, which vanishes exactly where some leg is stretched or folded, i.e. where
/// `det J_q = 0` in either working mode (with fixed modes, `det J_q` keeps its sign inside the
/// workspace and these loci are the workspace boundary; crossings between two unreachable
/// nodes, i.e. annulus boundaries of single legs outside the workspace, are not drawn).
/// Type II loci: sign changes of
/// `det J_x` between two reachable neighbours. Unreachable nodes are blank.
#[derive(Debug, Clone, PartialEq)]
pub struct LociMap {
    /// Scheme.
    pub scheme: Scheme,
    /// Orientation φ (radians).
    pub phi: f64,
    /// Grid.
    pub grid: WorkspaceGrid,
    /// Reachability per node (row-major, x fastest).
    pub reachable: Vec<bool>,
    /// `det J_x` per node (`None` when unreachable).
    pub det_jx: Vec<Option<f64>>,
    /// Midpoints of grid edges, at least one end reachable, across which the Type I function
    /// changes sign.
    pub type_i: Vec<(f64, f64)>,
    /// Midpoints of grid edges across which `det J_x` changes sign.
    pub type_ii: Vec<(f64, f64)>,
}

/// Leg-stretch function of the loci (see [`LociMap`]).
fn leg_stretch_function(design: &RrrDesign, pose: &RrrPose) -> f64 {
    let platform = design.platform_joints(pose);
    (0..3)
        .map(|leg| {
            let d2 = (platform[leg] - design.base()[leg]).norm_squared();
            let (b, c) = (design.proximal()[leg], design.distal()[leg]);
            (d2 - (b + c) * (b + c)) * (d2 - (b - c) * (b - c))
        })
        .product()
}

/// Computes the [`LociMap`] of `scheme` at orientation `phi` on `grid`.
pub fn singularity_loci(
    design: &RrrDesign,
    scheme: Scheme,
    phi: f64,
    grid: &WorkspaceGrid,
    modes: &WorkingModes,
    model: PsiModel,
) -> Result<LociMap, ActuationError> {
    grid.validate()?;
    let nodes: Vec<(Option<f64>, f64)> = (0..grid.len())
        .into_par_iter()
        .map(|k| {
            let pose = RrrPose::new(grid.x(k % grid.nx), grid.y(k / grid.nx), phi);
            let det = design
                .try_inverse_kinematics(&pose, modes)
                .map(|config| jacobians(&config, scheme, model).det_jx());
            (det, leg_stretch_function(design, &pose))
        })
        .collect();
    let mut type_i = Vec::new();
    let mut type_ii = Vec::new();
    let mut visit = |k: usize, m: usize| {
        let (xa, ya) = (grid.x(k % grid.nx), grid.y(k / grid.nx));
        let (xb, yb) = (grid.x(m % grid.nx), grid.y(m / grid.nx));
        let mid = (0.5 * (xa + xb), 0.5 * (ya + yb));
        let touches_workspace = nodes[k].0.is_some() || nodes[m].0.is_some();
        if touches_workspace && nodes[k].1.signum() != nodes[m].1.signum() {
            type_i.push(mid);
        }
        if let (Some(da), Some(db)) = (nodes[k].0, nodes[m].0)
            && da.signum() != db.signum()
        {
            type_ii.push(mid);
        }
    };
    for j in 0..grid.ny {
        for i in 0..grid.nx {
            let k = j * grid.nx + i;
            if i + 1 < grid.nx {
                visit(k, k + 1);
            }
            if j + 1 < grid.ny {
                visit(k, k + grid.nx);
            }
        }
    }
    Ok(LociMap {
        scheme,
        phi,
        grid: *grid,
        reachable: nodes.iter().map(|n| n.0.is_some()).collect(),
        det_jx: nodes.iter().map(|n| n.0).collect(),
        type_i,
        type_ii,
    })
}

/// Writes the loci maps as one SVG, `columns` panels per row: reachable nodes light grey,
/// Type I loci blue, Type II loci red, unreachable blank.
pub fn plot_loci_svg(path: &Path, maps: &[LociMap], columns: usize) -> Result<(), ActuationError> {
    use plotters::prelude::*;
    let plot_error = |message: String| ActuationError::Plot {
        path: path.display().to_string(),
        message,
    };
    if maps.is_empty() || columns == 0 {
        return Err(plot_error("nothing to plot".to_string()));
    }
    let columns = columns.min(maps.len());
    let rows = maps.len().div_ceil(columns);
    let panel = 300u32;
    let root = SVGBackend::new(path, (panel * columns as u32, panel * rows as u32 + 40))
        .into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(e.to_string()))?;
    let grey = RGBColor(215, 215, 215);
    // Colour key across the top, inside the figure.
    let (key, body) = root.split_vertically(40);
    let entries: [(RGBColor, &str); 3] = [
        (grey, "reachable"),
        (BLUE, "Type I loci: det J_q = 0 (a leg O_i B_i C_i aligned)"),
        (RED, "Type II loci: det J_x = 0 (parallel singularity)"),
    ];
    let mut x = 10;
    for (colour, text) in entries {
        key.draw(&Rectangle::new([(x, 13), (x + 16, 29)], colour.filled()))
            .map_err(|e| plot_error(e.to_string()))?;
        key.draw(&Text::new(text, (x + 22, 14), ("sans-serif", 15)))
            .map_err(|e| plot_error(e.to_string()))?;
        x += 30 + 8 * text.len() as i32;
    }
    let areas = body.split_evenly((rows, columns));
    for (map, area) in maps.iter().zip(areas.iter()) {
        let g = &map.grid;
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!(
                    "scheme {} {}  phi = {:.1} deg",
                    map.scheme.number(),
                    map.scheme.name(),
                    map.phi.to_degrees()
                ),
                ("sans-serif", 17),
            )
            .margin(6)
            .x_label_area_size(42)
            .y_label_area_size(50)
            .build_cartesian_2d(g.x_min..g.x_max, g.y_min..g.y_max)
            .map_err(|e| plot_error(e.to_string()))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(5)
            .y_labels(5)
            .x_desc("x (design length unit)")
            .y_desc("y (design length unit)")
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 15))
            .x_label_formatter(&|v| crate::io::svg::plain(*v, 2))
            .y_label_formatter(&|v| crate::io::svg::plain(*v, 2))
            .draw()
            .map_err(|e| plot_error(e.to_string()))?;
        let hx = 0.5 * (g.x_max - g.x_min) / (g.nx - 1) as f64;
        let hy = 0.5 * (g.y_max - g.y_min) / (g.ny - 1) as f64;
        // Reachable area as one rectangle per run of reachable nodes in a row.
        let mut runs = Vec::new();
        for j in 0..g.ny {
            let mut start: Option<usize> = None;
            for i in 0..=g.nx {
                let reachable = i < g.nx && map.reachable[j * g.nx + i];
                match (reachable, start) {
                    (true, None) => start = Some(i),
                    (false, Some(s)) => {
                        runs.push(Rectangle::new(
                            [(g.x(s) - hx, g.y(j) - hy), (g.x(i - 1) + hx, g.y(j) + hy)],
                            grey.filled(),
                        ));
                        start = None;
                    }
                    _ => {}
                }
            }
        }
        chart
            .draw_series(runs)
            .map_err(|e| plot_error(e.to_string()))?;
        for (points, colour) in [(&map.type_i, BLUE), (&map.type_ii, RED)] {
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&(x, y)| Circle::new((x, y), 1, colour.filled())),
                )
                .map_err(|e| plot_error(e.to_string()))?;
        }
    }
    root.present().map_err(|e| plot_error(e.to_string()))?;
    Ok(())
}

/// Example geometry of this crate for Ramana Babu et al. (the paper does not give its base geometry, joint
/// limits or grid): symmetric family of [`RrrDesign::symmetric`] with base radius 5, default
/// design `(a, b, c) = (1.5, 3.0, 3.5)` (platform circumradius, proximal, distal), size limit
/// `a + b + c ≤ λ = 9.3` (Ramana Babu et al., Table IV), bounds `a ∈ [1, 3]`,
/// `b, c ∈ [1, 4]` (the paper's optima sit at `a = 1.3` and `b, c ≤ 4`), no joint limits,
/// and the square grid `[−5, 5]²` at constant orientation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExampleGeometry {
    /// Base circumradius R.
    pub base_radius: f64,
    /// `a` of Ramana Babu et al.: platform circumradius.
    pub platform_radius: f64,
    /// `b` of Ramana Babu et al.: proximal link `|O_iB_i|`.
    pub proximal: f64,
    /// `c` of Ramana Babu et al.: distal link `|B_iC_i|`.
    pub distal: f64,
}

impl Default for ExampleGeometry {
    fn default() -> Self {
        Self {
            base_radius: 5.0,
            platform_radius: 1.5,
            proximal: 3.0,
            distal: 3.5,
        }
    }
}

impl ExampleGeometry {
    /// The symmetric design of this geometry.
    pub fn design(&self) -> Result<RrrDesign, ActuationError> {
        Ok(RrrDesign::symmetric(
            self.base_radius,
            self.platform_radius,
            self.proximal,
            self.distal,
        )?)
    }

    /// The design vector `(a, b, c)` of Ramana Babu et al.
    pub fn design_vector(&self) -> [f64; 3] {
        [self.platform_radius, self.proximal, self.distal]
    }
}
