//! Singularity-avoidance indices of the 3-PRRR and 3RRR (docs/theory.md §11.2): LCI in
//! two named variants and the normalised scaled incircle radius NSIR (Farias Filho et al.
//! (2021) Eqs. 11–26).
//!
//! * `1/κ(Ā⁻¹B̄)` ([`LciVariant::InverseAB`], Farias Filho et al. (2021) Eqs. 10–12): the reciprocal condition
//!   number of the homogenised Jacobian `J̄ = Ā⁻¹ B̄` (3×6 for the 3-PRRR, 3×3 for the 3RRR),
//!   κ = σ_max/σ_min. 0 when Ā is singular.
//! * `1/κ(Ā)` ([`LciVariant::DirectA`], Fontes et al. Eqs. 14–15): the same for `Ā` alone.
//! * NSIR (Farias Filho et al. (2021) Eqs. 13–26): `r_norm = r/h` with r the incircle radius of the triangle
//!   formed by the three lines `B_iC_i`; `ξ = √(Π_k(b̄_kk² + b̄_k,k+3²)) / √((l_1²l_2² + l_2²(p/2π)²)³)`
//!   (3RRR: `Π_k |sin(β_k − θ_k)|`, i.e. p = 0); `NSIR = ξ · r_norm`.
//!
//! Every function here is allocation-free (fixed-size nalgebra matrices).
//! LCI uses a closed-form 3×3 route (see [`lci`]); [`lci_reference`] keeps the literal formula.

use crate::mechanism::prrr::{PrrrConfiguration, PrrrDesign, Robot};
use nalgebra::Matrix3;

/// The two LCI variants of docs/theory.md §11.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LciVariant {
    /// `1/κ(Ā⁻¹B̄)`, Farias Filho et al. (2021) (default for redundancy resolution).
    #[serde(rename = "lci_inv_a_b")]
    InverseAB,
    /// `1/κ(Ā)`, Fontes et al. (conditioning maps).
    #[serde(rename = "lci_a")]
    DirectA,
}

impl LciVariant {
    /// Stable name used in tables and JSON: `lci_inv_a_b` or `lci_a`.
    pub fn key(self) -> &'static str {
        match self {
            LciVariant::InverseAB => "lci_inv_a_b",
            LciVariant::DirectA => "lci_a",
        }
    }

    /// Formula as printed in output: `1/κ(Ā⁻¹B̄)` or `1/κ(Ā)`.
    pub fn formula(self) -> &'static str {
        match self {
            LciVariant::InverseAB => "1/κ(Ā⁻¹B̄)",
            LciVariant::DirectA => "1/κ(Ā)",
        }
    }
}

/// Reciprocal condition number `σ_min/σ_max` of a 3×3 matrix (0 if singular or non-finite).
///
/// Fast path: the eigenvalues λ of the symmetric Gram matrix `M Mᵀ` in closed form
/// (trigonometric solution of the characteristic cubic), `1/κ = √(λ_min/λ_max)`. Squaring
/// loses relative accuracy when `λ_min/λ_max` approaches the rounding unit, so below
/// `1/κ = 10⁻⁵` the value is recomputed from an SVD (nalgebra) — the result agrees with the
/// SVD everywhere to about 1e-10 absolute.
pub fn inverse_condition_3x3(m: &Matrix3<f64>) -> f64 {
    let gram = m * m.transpose();
    let [low, _, high] = symmetric_eigenvalues_3x3(&gram);
    let r = low / high;
    if r.is_finite() && r > 1e-10 {
        r.sqrt().min(1.0)
    } else {
        inverse_condition_svd_3x3(m)
    }
}

/// Reference `σ_min/σ_max` of a 3×3 matrix from nalgebra's SVD.
pub fn inverse_condition_svd_3x3(m: &Matrix3<f64>) -> f64 {
    let sv = m.singular_values();
    ratio(sv.min(), sv.max())
}

/// Eigenvalues of a symmetric 3×3 matrix, ascending (closed form: with `q = tr/3`,
/// `p = √(‖M − qI‖²_F/6)`, `r = det((M − qI)/p)/2`, `φ = acos(r)/3`:
/// `λ_max = q + 2p cos φ`, `λ_min = q + 2p cos(φ + 2π/3)`, `λ_mid = 3q − λ_max − λ_min`).
pub fn symmetric_eigenvalues_3x3(m: &Matrix3<f64>) -> [f64; 3] {
    let off = m[(0, 1)] * m[(0, 1)] + m[(0, 2)] * m[(0, 2)] + m[(1, 2)] * m[(1, 2)];
    let q = (m[(0, 0)] + m[(1, 1)] + m[(2, 2)]) / 3.0;
    let d = [m[(0, 0)] - q, m[(1, 1)] - q, m[(2, 2)] - q];
    let p2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * off;
    if p2 <= 0.0 || !p2.is_finite() {
        let mut e = [m[(0, 0)], m[(1, 1)], m[(2, 2)]];
        e.sort_by(f64::total_cmp);
        return e;
    }
    let p = (p2 / 6.0).sqrt();
    let mut b = *m;
    for i in 0..3 {
        b[(i, i)] -= q;
    }
    let r = (b.determinant() / (p * p * p) / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let high = q + 2.0 * p * phi.cos();
    let low = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    [low, 3.0 * q - high - low, high]
}

fn ratio(min: f64, max: f64) -> f64 {
    let r = min / max;
    if r.is_finite() {
        r.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// LCI of a configuration, variant `variant`, for the 3-PRRR (`J̄` 3×6) or the 3RRR (`J̄` 3×3).
///
/// `1/κ(Ā⁻¹B̄)` is computed without inverting Ā: the rows of B̄ have disjoint supports, so
/// `B̄ = D^{1/2} Q` with `D = diag(‖b̄_k‖²)` and Q with orthonormal rows, hence
/// `σ(Ā⁻¹B̄) = 1/σ(D^{−1/2} Ā)` and `1/κ(Ā⁻¹B̄) = 1/κ(diag(1/‖b̄_k‖) Ā)`; 0 when a row of B̄
/// vanishes (inverse singularity). [`lci_reference`] is the literal formula.
pub fn lci(
    design: &PrrrDesign,
    configuration: &PrrrConfiguration,
    robot: Robot,
    variant: LciVariant,
) -> f64 {
    let scale = design.pitch / (2.0 * std::f64::consts::PI);
    let b_bar_rows = [0, 1, 2].map(|k| {
        [
            configuration.b_revolute(k),
            scale * configuration.b_prismatic(design, k),
        ]
    });
    lci_from_parts(
        &configuration.matrix_a_bar(design),
        &b_bar_rows,
        robot,
        variant,
    )
}

/// LCI from `Ā` and the rows of `B̄` given as `(b̄_kk, b̄_k,k+3)` (the prismatic entry is
/// ignored for the 3RRR); the shared kernel of [`lci`] and the conditioning maps.
pub fn lci_from_parts(
    a_bar: &Matrix3<f64>,
    b_bar_rows: &[[f64; 2]; 3],
    robot: Robot,
    variant: LciVariant,
) -> f64 {
    match variant {
        LciVariant::DirectA => inverse_condition_3x3(a_bar),
        LciVariant::InverseAB => {
            let mut scaled = *a_bar;
            for (k, row) in b_bar_rows.iter().enumerate() {
                let norm = match robot {
                    Robot::ThreePrrr => row[0].hypot(row[1]),
                    Robot::ThreeRrr => row[0].abs(),
                };
                if norm.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                    return 0.0;
                }
                for j in 0..3 {
                    scaled[(k, j)] /= norm;
                }
            }
            inverse_condition_3x3(&scaled)
        }
    }
}

/// LCI by the literal formulas of docs/theory.md §11.2 (`Ā⁻¹`, the product with B̄,
/// nalgebra SVD): the reference against which [`lci`] is tested.
pub fn lci_reference(
    design: &PrrrDesign,
    configuration: &PrrrConfiguration,
    robot: Robot,
    variant: LciVariant,
) -> f64 {
    let a_bar = configuration.matrix_a_bar(design);
    match variant {
        LciVariant::DirectA => inverse_condition_svd_3x3(&a_bar),
        LciVariant::InverseAB => {
            let Some(a_inverse) = a_bar.try_inverse() else {
                return 0.0;
            };
            match robot {
                Robot::ThreePrrr => {
                    let sv = (a_inverse * configuration.matrix_b_bar(design)).singular_values();
                    ratio(sv.min(), sv.max())
                }
                Robot::ThreeRrr => {
                    inverse_condition_svd_3x3(&(a_inverse * configuration.matrix_b_rrr(design)))
                }
            }
        }
    }
}

/// The three factors of NSIR (Farias Filho et al. (2021) Eqs. 21–26).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Nsir {
    /// Incircle radius r of the lines `B_iC_i` (m).
    pub incircle_radius: f64,
    /// `r_norm = r / h` (closeness to direct singularities).
    pub r_norm: f64,
    /// ξ (closeness to inverse singularities), in [0, 1].
    pub xi: f64,
    /// `NSIR = ξ · r_norm`.
    pub nsir: f64,
}

/// NSIR of a configuration (docs/theory.md §11.2).
pub fn nsir(design: &PrrrDesign, configuration: &PrrrConfiguration, robot: Robot) -> Nsir {
    let r = incircle_radius_of_lines(&configuration.elbow, &configuration.platform);
    let r_norm = r / design.h;
    let xi = configuration.inverse_singularity_measure(design, robot);
    Nsir {
        incircle_radius: r,
        r_norm,
        xi,
        nsir: xi * r_norm,
    }
}

/// Incircle radius of the triangle formed by the three lines through `p[i]` and `q[i]`
/// (docs/theory.md §9, IR; Farias Filho et al. (2021) Eqs. 16–21): lines in homogeneous
/// form `L_i = (p_i,1) × (q_i,1)`, vertices `T_1 = L_1×L_2`, `T_2 = L_2×L_3`,
/// `T_3 = L_3×L_1`, `r = |det[T_k,1]| / (t_1+t_2+t_3)`. Concurrent lines give 0.
/// **Choice** (docs/theory.md §9): two parallel lines at separation d (third not
/// parallel) give the continuous limit d/2; three parallel lines give 0; a degenerate
/// line (p_i = q_i) gives 0.
pub fn incircle_radius_of_lines(p: &[[f64; 2]; 3], q: &[[f64; 2]; 3]) -> f64 {
    // Normalised lines n·x + c = 0 with |n| = 1.
    let mut lines = [[0.0f64; 3]; 3];
    for i in 0..3 {
        let l = [
            p[i][1] - q[i][1],
            q[i][0] - p[i][0],
            p[i][0] * q[i][1] - p[i][1] * q[i][0],
        ];
        let norm = l[0].hypot(l[1]);
        if norm.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return 0.0;
        }
        lines[i] = [l[0] / norm, l[1] / norm, l[2] / norm];
    }
    const PARALLEL: f64 = 1e-12;
    let pairs = [(0usize, 1usize), (1, 2), (2, 0)];
    let mut vertices = [[0.0f64; 2]; 3];
    let mut parallel_pair = None;
    let mut parallel_count = 0;
    for (k, &(i, j)) in pairs.iter().enumerate() {
        let (li, lj) = (lines[i], lines[j]);
        let w = li[0] * lj[1] - li[1] * lj[0];
        if w.abs() < PARALLEL {
            parallel_count += 1;
            parallel_pair = Some((i, j));
            continue;
        }
        let x = li[1] * lj[2] - li[2] * lj[1];
        let y = li[2] * lj[0] - li[0] * lj[2];
        vertices[k] = [x / w, y / w];
    }
    match (parallel_count, parallel_pair) {
        (0, _) => {
            let [t1, t2, t3] = vertices;
            let det = t1[0] * (t2[1] - t3[1]) + t2[0] * (t3[1] - t1[1]) + t3[0] * (t1[1] - t2[1]);
            let perimeter = (t2[0] - t1[0]).hypot(t2[1] - t1[1])
                + (t3[0] - t2[0]).hypot(t3[1] - t2[1])
                + (t1[0] - t3[0]).hypot(t1[1] - t3[1]);
            let r = det.abs() / perimeter;
            if r.is_finite() { r } else { 0.0 }
        }
        (1, Some((i, j))) => {
            let (li, lj) = (lines[i], lines[j]);
            let same_direction = li[0] * lj[0] + li[1] * lj[1];
            (li[2] - same_direction.signum() * lj[2]).abs() / 2.0
        }
        _ => 0.0,
    }
}

/// Every index of one configuration (for tables and the `prrr index` command).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PrrrIndices {
    /// `1/κ(Ā⁻¹B̄)` (Farias Filho et al. (2021)).
    pub lci_inv_a_b: f64,
    /// `1/κ(Ā)` (Fontes et al.).
    pub lci_a: f64,
    /// Incircle radius r (m).
    pub incircle_radius: f64,
    /// r / h.
    pub r_norm: f64,
    /// ξ.
    pub xi: f64,
    /// NSIR = ξ r_norm.
    pub nsir: f64,
    /// `det Ā / l_2³` (0 at direct singularities).
    pub direct_singularity_measure: f64,
}

/// Compute [`PrrrIndices`] of a configuration.
pub fn all_indices(
    design: &PrrrDesign,
    configuration: &PrrrConfiguration,
    robot: Robot,
) -> PrrrIndices {
    let n = nsir(design, configuration, robot);
    PrrrIndices {
        lci_inv_a_b: lci(design, configuration, robot, LciVariant::InverseAB),
        lci_a: lci(design, configuration, robot, LciVariant::DirectA),
        incircle_radius: n.incircle_radius,
        r_norm: n.r_norm,
        xi: n.xi,
        nsir: n.nsir,
        direct_singularity_measure: configuration.direct_singularity_measure(design),
    }
}
