//! The 3-PRRR kinematically redundant planar parallel manipulator, and the 3RRR as its
//! special case δ = 0 (docs/theory.md §11.1; Farias Filho et al. (2021) §2, Fontes et al.
//! §2).
//!
//! Leg i (i = 1, 2, 3): an active prismatic joint moves the base joint along a guide,
//! `A_i = a e(λ_i) + δ_i e(γ_i)`; the active revolute joint at `A_i` turns the link
//! `A_iB_i` (length `l_1`, angle θ_i); the passive link `B_iC_i` (length `l_2`, angle β_i)
//! reaches the platform joint `C_i = D + h e(α + φ_i)`, with `D = (x, y)` and orientation α
//! the pose. Fontes et al. use `φ_i = λ_i` (our default); Farias Filho et al. (2021) write
//! `C_i = D − h e(α + η_i)`, i.e. `φ_i = η_i + π` ([`PrrrDesign::with_seed000_platform`]).
//!
//! Velocity equation (docs/theory.md §11.1): `A Ẋ = B Θ̇`, `Ẋ = (ẋ, ẏ, α̇)`,
//! `Θ̇ = (θ̇_1..3, δ̇_1..3)`, `A_i = [l_2 cos β_i, l_2 sin β_i, l_2 h sin(β_i − α − φ_i)]`,
//! `B = [diag(l_1 l_2 sin(β_k − θ_k)) | diag(l_2 cos(β_k − γ_k))]` (3RRR: first three columns).
//! Direct singularity: `det A = 0`; inverse singularity: `rank B < 3`.
//! Homogenisation: `Ā` divides the third column of A by `L_c`, `B̄` multiplies the prismatic
//! columns by `p/(2π)` (pitch p per turn).

use crate::mechanism::{MAX_INPUT_MAGNITUDE, within_input_range};
use nalgebra::{Matrix3, SMatrix};
use std::f64::consts::PI;
use thiserror::Error;

/// 3×6 matrix (the inverse-kinematics Jacobian B of the 3-PRRR).
pub type Matrix3x6 = SMatrix<f64, 3, 6>;

/// Errors of the 3-PRRR model: invalid designs and inputs name the field; unreachable
/// poses name the leg.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PrrrError {
    /// A design parameter is out of range (non-finite, non-positive, empty interval).
    #[error("design field `{field}`: {reason}")]
    InvalidDesign {
        /// Field name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// A pose, δ or working-mode input is invalid.
    #[error("input `{field}`: {reason}")]
    InvalidInput {
        /// Field name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Unknown preset name.
    #[error("unknown 3-PRRR preset `{0}` (known: farias2021, fontes2017)")]
    UnknownPreset(String),
    /// Leg `leg` (1-based) cannot reach its platform joint: the acos argument of the
    /// inverse kinematics is outside [−1, 1] (or the leg's base and platform joints coincide).
    #[error("leg {leg} cannot reach the pose (acos argument {argument})")]
    Unreachable {
        /// 1-based leg number.
        leg: usize,
        /// The acos argument `(μ²+ρ²+l_1²−l_2²)/(2 l_1 √(μ²+ρ²))`.
        argument: f64,
    },
}

/// Which robot: the redundant 3-PRRR (six actuators) or the non-redundant 3RRR
/// (prismatic joints locked at δ = 0, three actuators).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Robot {
    /// Non-redundant 3RRR: δ = 0, B is the first three columns.
    #[serde(rename = "3rrr")]
    ThreeRrr,
    /// Kinematically redundant 3-PRRR.
    #[serde(rename = "3prrr")]
    ThreePrrr,
}

impl std::str::FromStr for Robot {
    type Err = PrrrError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "3rrr" | "rrr" => Ok(Robot::ThreeRrr),
            "3prrr" | "prrr" => Ok(Robot::ThreePrrr),
            other => Err(PrrrError::InvalidInput {
                field: "robot",
                reason: format!("unknown robot `{other}` (3rrr or 3prrr)"),
            }),
        }
    }
}

/// Elbow working mode σ_i of one leg: the sign in front of the acos of the inverse kinematics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum WorkingMode {
    /// σ = +1.
    Plus,
    /// σ = −1.
    Minus,
}

impl WorkingMode {
    /// σ as ±1.
    pub fn sign(self) -> f64 {
        match self {
            WorkingMode::Plus => 1.0,
            WorkingMode::Minus => -1.0,
        }
    }
}

/// Parse three working modes written `+,-,+` (also `+1,-1,+1`, `p,m,p`).
pub fn parse_modes(text: &str) -> Result<[WorkingMode; 3], PrrrError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(PrrrError::InvalidInput {
            field: "modes",
            reason: format!("expected three comma-separated signs, got `{text}`"),
        });
    }
    let mut modes = [WorkingMode::Plus; 3];
    for (mode, part) in modes.iter_mut().zip(&parts) {
        *mode = match *part {
            "+" | "+1" | "1" | "p" | "plus" => WorkingMode::Plus,
            "-" | "-1" | "m" | "minus" => WorkingMode::Minus,
            other => {
                return Err(PrrrError::InvalidInput {
                    field: "modes",
                    reason: format!("`{other}` is not + or -"),
                });
            }
        };
    }
    Ok(modes)
}

/// End-effector pose: platform centre `D = (x, y)` in metres and orientation α in radians.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Pose {
    /// x of D (m).
    pub x: f64,
    /// y of D (m).
    pub y: f64,
    /// Orientation α (rad).
    pub alpha: f64,
}

impl Pose {
    /// Pose from its three coordinates.
    pub fn new(x: f64, y: f64, alpha: f64) -> Self {
        Self { x, y, alpha }
    }
}

/// Geometry of a 3-PRRR (docs/theory.md §11.1 table), SI units.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PrrrDesign {
    /// Distance from the centre to the mid-stroke of each prismatic guide, `a` (m).
    pub a: f64,
    /// Distance from the platform centre D to each platform joint C_i, `h` (m).
    pub h: f64,
    /// Length of the active link `A_iB_i` (m).
    pub l1: f64,
    /// Length of the passive link `B_iC_i` (m).
    pub l2: f64,
    /// Angular positions λ_i of the guides' mid-strokes (rad).
    pub lambda: [f64; 3],
    /// Guide directions γ_i (rad).
    pub gamma: [f64; 3],
    /// Platform joint angles φ_i: `C_i = D + h e(α + φ_i)` (rad).
    pub platform_angles: [f64; 3],
    /// Stroke of the prismatic joints `[δ_min, δ_max]` (m).
    pub delta_range: (f64, f64),
    /// Screw pitch p (m per turn): prismatic columns of B̄ are multiplied by p/(2π).
    pub pitch: f64,
    /// Characteristic length `L_c` dividing the rotational column of Ā (m), `√2·h` in
    /// both papers.
    pub characteristic_length: f64,
}

impl PrrrDesign {
    /// Farias Filho et al. (2021), Table 1: a = 0.260, h = 0.0597,
    /// l_1 = 0.191, l_2 = 0.232, λ = (π/2, 11π/6, 7π/6), γ = (π, π/3, 5π/3),
    /// δ ∈ [−0.230, 0.230], p = 0.010 m/turn, L_c = √2 h; platform in Fontes et al.'s
    /// convention `C_i = D + h e(α + λ_i)` (docs/theory.md §11.1 **Choice**).
    pub fn farias2021() -> Self {
        let h = 0.0597;
        let lambda = [PI / 2.0, 11.0 * PI / 6.0, 7.0 * PI / 6.0];
        Self {
            a: 0.260,
            h,
            l1: 0.191,
            l2: 0.232,
            lambda,
            gamma: [PI, PI / 3.0, 5.0 * PI / 3.0],
            platform_angles: lambda,
            delta_range: (-0.230, 0.230),
            pitch: 0.010,
            characteristic_length: 2f64.sqrt() * h,
        }
    }

    /// Fontes et al., §4: a = 0.260, h = 0.060, l_1 = 0.191,
    /// l_2 = 0.232, δ ∈ [−0.3, 0.3], L_c = √2 h; angles and pitch (not given in Fontes et al.)
    /// as in Farias Filho et al. (2021).
    pub fn fontes2017() -> Self {
        let h = 0.060;
        Self {
            h,
            delta_range: (-0.3, 0.3),
            characteristic_length: 2f64.sqrt() * h,
            ..Self::farias2021()
        }
    }

    /// Preset by name: `farias2021` (Farias Filho et al. (2021)) or `fontes2017` (Fontes et al.).
    pub fn preset(name: &str) -> Result<Self, PrrrError> {
        match name.trim().to_ascii_lowercase().as_str() {
            "farias2021" => Ok(Self::farias2021()),
            "fontes2017" => Ok(Self::fontes2017()),
            _ => Err(PrrrError::UnknownPreset(name.to_string())),
        }
    }

    /// The platform convention of Farias Filho et al. (2021), `C_i = D − h e(α + η_i)`,
    /// i.e. `φ_i = η_i + π`.
    pub fn with_seed000_platform(mut self, eta: [f64; 3]) -> Self {
        self.platform_angles = eta.map(|e| e + PI);
        self
    }

    /// Check every field: lengths finite and > 0, angles finite, `δ_min < δ_max` finite.
    pub fn validate(&self) -> Result<(), PrrrError> {
        let positive = [
            ("a", self.a),
            ("h", self.h),
            ("l1", self.l1),
            ("l2", self.l2),
            ("pitch", self.pitch),
            ("characteristic_length", self.characteristic_length),
        ];
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(PrrrError::InvalidDesign {
                    field,
                    reason: format!("{value} must be finite and > 0"),
                });
            }
        }
        let angles = [
            ("lambda", self.lambda),
            ("gamma", self.gamma),
            ("platform_angles", self.platform_angles),
        ];
        for (field, values) in angles {
            if values.iter().any(|v| !v.is_finite()) {
                let list: Vec<String> = values.iter().map(f64::to_string).collect();
                return Err(PrrrError::InvalidDesign {
                    field,
                    reason: format!("[{}] must be finite", list.join(", ")),
                });
            }
        }
        let (lo, hi) = self.delta_range;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(PrrrError::InvalidDesign {
                field: "delta_range",
                reason: format!("[{lo}, {hi}] must be finite with min < max"),
            });
        }
        Ok(())
    }

    /// Base joint `A_i = a e(λ_i) + δ_i e(γ_i)` (leg index 0..3).
    pub fn base_joint(&self, leg: usize, delta: f64) -> [f64; 2] {
        let (sl, cl) = self.lambda[leg].sin_cos();
        let (sg, cg) = self.gamma[leg].sin_cos();
        [self.a * cl + delta * cg, self.a * sl + delta * sg]
    }

    /// Platform joint `C_i = D + h e(α + φ_i)` (leg index 0..3).
    pub fn platform_joint(&self, leg: usize, pose: &Pose) -> [f64; 2] {
        let (s, c) = (pose.alpha + self.platform_angles[leg]).sin_cos();
        [pose.x + self.h * c, pose.y + self.h * s]
    }

    /// Inverse kinematics of leg `leg` (0..3) alone: it depends only on that leg's δ and σ
    /// (formulas of [`PrrrDesign::inverse_kinematics`]). Unreachable (or non-finite input)
    /// gives [`PrrrError::Unreachable`], never NaN.
    pub fn solve_leg(
        &self,
        leg: usize,
        pose: &Pose,
        delta: f64,
        mode: WorkingMode,
    ) -> Result<LegSolution, PrrrError> {
        let a = self.base_joint(leg, delta);
        let c = self.platform_joint(leg, pose);
        let (mu, rho) = (c[0] - a[0], c[1] - a[1]);
        let reach = mu.hypot(rho);
        let argument =
            (reach * reach + self.l1 * self.l1 - self.l2 * self.l2) / (2.0 * self.l1 * reach);
        if !(argument.is_finite() && (-1.0..=1.0).contains(&argument)) {
            return Err(PrrrError::Unreachable {
                leg: leg + 1,
                argument,
            });
        }
        let theta = rho.atan2(mu) + mode.sign() * argument.acos();
        let (st, ct) = theta.sin_cos();
        let b = [a[0] + self.l1 * ct, a[1] + self.l1 * st];
        Ok(LegSolution {
            base: a,
            elbow: b,
            platform: c,
            theta,
            beta: (c[1] - b[1]).atan2(c[0] - b[0]),
        })
    }

    /// Inverse kinematics with explicit working modes (docs/theory.md §11.1):
    /// `(μ_i, ρ_i) = C_i − A_i`, `θ_i = atan2(ρ_i, μ_i) + σ_i acos((μ_i²+ρ_i²+l_1²−l_2²)/(2 l_1 √(μ_i²+ρ_i²)))`,
    /// `B_i = A_i + l_1 e(θ_i)`, `β_i = atan2(C_i − B_i)`.
    /// Errors: [`PrrrError::Unreachable`] when the acos argument leaves [−1, 1];
    /// [`PrrrError::InvalidInput`] for a non-finite pose or δ, or one beyond
    /// ±[`MAX_INPUT_MAGNITUDE`]. Never returns NaN. Allocation-free.
    pub fn inverse_kinematics(
        &self,
        pose: &Pose,
        delta: &[f64; 3],
        modes: &[WorkingMode; 3],
    ) -> Result<PrrrConfiguration, PrrrError> {
        let inputs = [
            ("pose", "x", pose.x),
            ("pose", "y", pose.y),
            ("pose", "alpha", pose.alpha),
            ("delta", "[0]", delta[0]),
            ("delta", "[1]", delta[1]),
            ("delta", "[2]", delta[2]),
        ];
        for (field, part, value) in inputs {
            if !within_input_range(value) {
                return Err(PrrrError::InvalidInput {
                    field,
                    reason: format!(
                        "{part} = {value:e} must be finite and within ±{MAX_INPUT_MAGNITUDE:e}"
                    ),
                });
            }
        }
        let mut configuration = PrrrConfiguration {
            pose: *pose,
            delta: *delta,
            modes: *modes,
            base: [[0.0; 2]; 3],
            elbow: [[0.0; 2]; 3],
            platform: [[0.0; 2]; 3],
            theta: [0.0; 3],
            beta: [0.0; 3],
        };
        for leg in 0..3 {
            let solution = self.solve_leg(leg, pose, delta[leg], modes[leg])?;
            configuration.base[leg] = solution.base;
            configuration.elbow[leg] = solution.elbow;
            configuration.platform[leg] = solution.platform;
            configuration.theta[leg] = solution.theta;
            configuration.beta[leg] = solution.beta;
        }
        Ok(configuration)
    }
}

/// Inverse kinematics of one leg: joint points and angles.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LegSolution {
    /// Base joint A_i.
    pub base: [f64; 2],
    /// Elbow B_i.
    pub elbow: [f64; 2],
    /// Platform joint C_i.
    pub platform: [f64; 2],
    /// θ_i (rad).
    pub theta: f64,
    /// β_i (rad).
    pub beta: f64,
}

/// Row i of A from joint points, `[C_i − B_i, (C_i − D) × (C_i − B_i)]`
/// (= `[l_2 cos β_i, l_2 sin β_i, l_2 h sin(β_i − α − φ_i)]`, trigonometry-free).
pub fn a_row(elbow: &[f64; 2], platform: &[f64; 2], pose: &Pose) -> [f64; 3] {
    let passive = [platform[0] - elbow[0], platform[1] - elbow[1]];
    let arm = [platform[0] - pose.x, platform[1] - pose.y];
    [
        passive[0],
        passive[1],
        arm[0] * passive[1] - arm[1] * passive[0],
    ]
}

/// `b_kk = l_1 l_2 sin(β_k − θ_k) = (B_k − A_k) × (C_k − B_k)`.
pub fn b_revolute(base: &[f64; 2], elbow: &[f64; 2], platform: &[f64; 2]) -> f64 {
    let active = [elbow[0] - base[0], elbow[1] - base[1]];
    let passive = [platform[0] - elbow[0], platform[1] - elbow[1]];
    active[0] * passive[1] - active[1] * passive[0]
}

/// `b_k,k+3 = l_2 cos(β_k − γ_k) = (C_k − B_k) · e(γ_k)` (unhomogenised).
pub fn b_prismatic(elbow: &[f64; 2], platform: &[f64; 2], gamma: f64) -> f64 {
    let (sg, cg) = gamma.sin_cos();
    (platform[0] - elbow[0]) * cg + (platform[1] - elbow[1]) * sg
}

/// One assembly of the 3-PRRR: pose, redundant inputs δ, working modes, joint points and angles.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PrrrConfiguration {
    /// End-effector pose.
    pub pose: Pose,
    /// Prismatic inputs δ_i (m).
    pub delta: [f64; 3],
    /// Working modes σ_i.
    pub modes: [WorkingMode; 3],
    /// Base joints A_i.
    pub base: [[f64; 2]; 3],
    /// Elbows B_i.
    pub elbow: [[f64; 2]; 3],
    /// Platform joints C_i.
    pub platform: [[f64; 2]; 3],
    /// Active angles θ_i (rad).
    pub theta: [f64; 3],
    /// Passive link angles β_i (rad).
    pub beta: [f64; 3],
}

impl PrrrConfiguration {
    /// `b_kk = l_1 l_2 sin(β_k − θ_k)`, evaluated as `(B_k − A_k) × (C_k − B_k)`.
    pub fn b_revolute(&self, k: usize) -> f64 {
        b_revolute(&self.base[k], &self.elbow[k], &self.platform[k])
    }

    /// `b_k,k+3 = l_2 cos(β_k − γ_k) = (C_k − B_k) · e(γ_k)` (unhomogenised).
    pub fn b_prismatic(&self, design: &PrrrDesign, k: usize) -> f64 {
        b_prismatic(&self.elbow[k], &self.platform[k], design.gamma[k])
    }

    /// Direct-kinematics matrix A (docs/theory.md §11.1; Fontes et al. Eq. 12):
    /// row i `[l_2 cos β_i, l_2 sin β_i, l_2 h sin(β_i − α − φ_i)]`, evaluated from the joint
    /// points as `[C_i − B_i, (C_i − D) × (C_i − B_i)]`.
    pub fn matrix_a(&self, _design: &PrrrDesign) -> Matrix3<f64> {
        let mut a = Matrix3::zeros();
        for i in 0..3 {
            let row = a_row(&self.elbow[i], &self.platform[i], &self.pose);
            for j in 0..3 {
                a[(i, j)] = row[j];
            }
        }
        a
    }

    /// Homogenised `Ā`: A with its third column divided by `L_c` (Fontes et al. Eq. 14).
    pub fn matrix_a_bar(&self, design: &PrrrDesign) -> Matrix3<f64> {
        let mut a = self.matrix_a(design);
        for i in 0..3 {
            a[(i, 2)] /= design.characteristic_length;
        }
        a
    }

    /// Inverse-kinematics matrix B (3×6; docs/theory.md §11.1; Farias Filho et al. (2021)
    /// Eq. 9): `b_kk = l_1 l_2 sin(β_k − θ_k)`, `b_k,k+3 = l_2 cos(β_k − γ_k)`.
    pub fn matrix_b(&self, design: &PrrrDesign) -> Matrix3x6 {
        let mut b = Matrix3x6::zeros();
        for k in 0..3 {
            b[(k, k)] = self.b_revolute(k);
            b[(k, k + 3)] = self.b_prismatic(design, k);
        }
        b
    }

    /// Homogenised `B̄`: prismatic columns of B multiplied by `p/(2π)` (Farias Filho et al. (2021) §3.1).
    pub fn matrix_b_bar(&self, design: &PrrrDesign) -> Matrix3x6 {
        let mut b = self.matrix_b(design);
        let scale = design.pitch / (2.0 * PI);
        for k in 0..3 {
            b[(k, k + 3)] *= scale;
        }
        b
    }

    /// B of the 3RRR: the three revolute columns `diag(l_1 l_2 sin(β_k − θ_k))`.
    pub fn matrix_b_rrr(&self, _design: &PrrrDesign) -> Matrix3<f64> {
        Matrix3::from_diagonal(&nalgebra::Vector3::from_fn(|k, _| self.b_revolute(k)))
    }

    /// Dimensionless direct-singularity measure `det Ā / l_2³` (0 ⇔ `det A = 0`, lines
    /// `B_iC_i` concurrent or parallel).
    pub fn direct_singularity_measure(&self, design: &PrrrDesign) -> f64 {
        self.matrix_a_bar(design).determinant() / design.l2.powi(3)
    }

    /// Dimensionless inverse-singularity measure in [0, 1]: for the 3-PRRR
    /// `√(Π_k(b̄_kk² + b̄_k,k+3²)) / √((l_1²l_2² + l_2²(p/2π)²)³)` (= ξ of docs/theory.md
    /// §11.2, 0 ⇔ rank B < 3); for the 3RRR `Π_k |sin(β_k − θ_k)|` (0 ⇔ a leg is
    /// stretched or folded).
    pub fn inverse_singularity_measure(&self, design: &PrrrDesign, robot: Robot) -> f64 {
        match robot {
            Robot::ThreePrrr => {
                let s = design.pitch / (2.0 * PI);
                let row_max =
                    design.l1 * design.l1 * design.l2 * design.l2 + design.l2 * design.l2 * s * s;
                let mut product = 1.0;
                for k in 0..3 {
                    let bkk = self.b_revolute(k);
                    let bkp = s * self.b_prismatic(design, k);
                    product *= (bkk * bkk + bkp * bkp) / row_max;
                }
                product.sqrt()
            }
            Robot::ThreeRrr => (0..3)
                .map(|k| (self.b_revolute(k) / (design.l1 * design.l2)).abs())
                .product(),
        }
    }

    /// Direct (parallel) singularity test: `|det Ā| / l_2³ ≤ tolerance`.
    pub fn is_direct_singular(&self, design: &PrrrDesign, tolerance: f64) -> bool {
        self.direct_singularity_measure(design).abs() <= tolerance
    }

    /// Inverse (serial) singularity test: inverse-singularity measure ≤ tolerance.
    pub fn is_inverse_singular(&self, design: &PrrrDesign, robot: Robot, tolerance: f64) -> bool {
        self.inverse_singularity_measure(design, robot) <= tolerance
    }
}
