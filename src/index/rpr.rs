//! Kinematic performance indices of a 3-RPR (docs/theory.md §9; Kapilavai and Nawratil,
//! §1.1, §6.1–6.2).
//!
//! Notation: leg vectors `d_i = b_i − a_i`, lengths `l_i`, unit directions `u_i`, leg
//! lines `L_i` through `a_i, b_i`, platform reference point `t = (x, y)`. The inverse
//! Jacobian J has rows `[u_ix, u_iy, (b_i − t) × u_i]`, so that `J · (ṫ, φ̇) = l̇`.
//!
//! Every index is either a number or `None` ("undefined", e.g. a leg of length 0 has no
//! line); no function returns NaN. Every **Choice** of docs/theory.md §9 is an option
//! with the documented default ([`IndexOptions`]) and is named in the output
//! ([`IndexVariants`]).

use super::polynomial::{polynomial_roots, trimmed};
use crate::C64;
use crate::algebra::{Point, cross, difference, dot};
use crate::choice::UnknownChoice;
use crate::mechanism::rpr::{Configuration, Design, Pose, rotate_quarter};
use nalgebra::{Matrix3, Matrix6x3};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};
use thiserror::Error;

/// Errors of index options.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum IndexError {
    /// Unknown option value.
    #[error(transparent)]
    UnknownChoice(#[from] UnknownChoice),
    /// An orientation range that is not `lo ≤ hi`, both finite.
    #[error("orientation range: expected finite lo <= hi, got [{lo}, {hi}]")]
    BadRange {
        /// Start.
        lo: f64,
        /// End.
        hi: f64,
    },
}

// ---------------------------------------------------------------------------------
// Options
// ---------------------------------------------------------------------------------

named_choices! {
    option "DS aggregate", error IndexError, serde "kebab-case", default Product;
    /// How DS combines the three pressure-angle cosines (docs/theory.md §9, **Choice**; the
    /// original formula of Gómez et al. was not available to us, so DS is *reconstructed*).
    pub enum DsAggregate {
        /// `DS = Π_i |cos α_i|` (default).
        Product = "product",
        /// `DS = (Π_i |cos α_i|)^{1/3}`.
        GeometricMean = "geometric-mean",
        /// `DS = (Σ_i |cos α_i|) / 3`.
        ArithmeticMean = "arithmetic-mean",
    }
}

impl DsAggregate {
    /// Aggregates three cosines.
    pub fn apply(self, c: [f64; 3]) -> f64 {
        let c = c.map(f64::abs);
        match self {
            DsAggregate::Product => c[0] * c[1] * c[2],
            DsAggregate::GeometricMean => (c[0] * c[1] * c[2]).cbrt(),
            DsAggregate::ArithmeticMean => (c[0] + c[1] + c[2]) / 3.0,
        }
    }
}

named_choices! {
    option "CN variant", error IndexError, serde "kebab-case", default Ratio;
    /// Which control number (docs/theory.md §9, **Choice**).
    pub enum CnVariant {
        /// `CN = λ_min / λ_max` (default; Nawratil's control number).
        Ratio = "lambda-ratio",
        /// `CN = sqrt(λ_min / λ_max)` (inverse condition number of G).
        SquareRoot = "sqrt-lambda-ratio",
    }
}

/// Default half width (radians) of the orientation range of the singularity-free
/// cylinder around the current φ (**Choice**: the motion of Kapilavai and Nawratil has no
/// orientation limits, where the radius is 0; a bounded range needs a value).
pub const DEFAULT_CYLINDER_HALF_WIDTH: f64 = 0.1;

/// Options of [`compute_indices`]; `Default` gives the documented defaults.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IndexOptions {
    /// DS aggregate (default product).
    pub ds: DsAggregate,
    /// CN variant (default λ_min/λ_max).
    pub cn: CnVariant,
    /// Orientation range of the singularity-free cylinder: `[φ − w, φ + w]` (default
    /// w = [`DEFAULT_CYLINDER_HALF_WIDTH`]).
    pub cylinder_half_width: f64,
}

impl Default for IndexOptions {
    fn default() -> Self {
        IndexOptions {
            ds: DsAggregate::Product,
            cn: CnVariant::Ratio,
            cylinder_half_width: DEFAULT_CYLINDER_HALF_WIDTH,
        }
    }
}

/// The variants used for an output, spelled out (written next to the values).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IndexVariants {
    /// E.g. `product (reconstructed: the formula of Gómez et al. was lost)`.
    #[serde(rename = "DS")]
    pub ds: String,
    /// MDS uses the same aggregate as DS.
    #[serde(rename = "MDS")]
    pub mds: String,
    /// E.g. `lambda_min/lambda_max`.
    #[serde(rename = "CN")]
    pub cn: String,
    /// IR convention at parallel legs.
    #[serde(rename = "IR")]
    pub ir: String,
    /// MTI definition.
    #[serde(rename = "MTI")]
    pub mti: String,
    /// Orientation range of the cylinder radius.
    pub cylinder_radius: String,
}

impl IndexOptions {
    /// The variant descriptions of these options.
    pub fn variants(&self) -> IndexVariants {
        IndexVariants {
            ds: format!(
                "{} of |cos alpha_i| (reconstructed: the original formula of Gomez et al. was lost)",
                self.ds.name()
            ),
            mds: format!("min(DS, DS*) with DS = {}", self.ds.name()),
            cn: match self.cn {
                CnVariant::Ratio => "lambda_min/lambda_max".into(),
                CnVariant::SquareRoot => "sqrt(lambda_min/lambda_max)".into(),
            },
            ir: "continuous: two parallel legs at separation d give d/2, three parallel give 0"
                .into(),
            mti: "min(TI, TI*)".into(),
            cylinder_radius: format!(
                "phi in [phi - {w}, phi + {w}]",
                w = self.cylinder_half_width
            ),
        }
    }
}

// ---------------------------------------------------------------------------------
// Leg geometry
// ---------------------------------------------------------------------------------

/// Relative tolerance for degenerate geometry (zero-length legs, parallel lines).
const GEOMETRY_TOLERANCE: f64 = 1e-12;

/// Leg lines of a configuration: anchors, unit directions and lengths.
#[derive(Debug, Clone, Copy)]
pub struct Legs {
    /// Base anchors `a_i`.
    pub a: [Point<f64>; 3],
    /// Platform anchors `b_i`.
    pub b: [Point<f64>; 3],
    /// Unit leg directions `u_i = (b_i − a_i)/l_i`.
    pub u: [Point<f64>; 3],
    /// Leg lengths `l_i`.
    pub l: [f64; 3],
}

impl Legs {
    /// Leg lines of K; `None` if a leg has (relative) length 0 and hence no line.
    pub fn new(k: &Configuration) -> Option<Legs> {
        let scale =
            k.a.iter()
                .chain(k.b.iter())
                .flatten()
                .fold(1.0_f64, |m, v| m.max(v.abs()));
        let mut u = [[0.0; 2]; 3];
        let mut l = [0.0; 3];
        for i in 0..3 {
            let d = difference(&k.a[i], &k.b[i]);
            l[i] = d[0].hypot(d[1]);
            if l[i].is_nan() || l[i] <= GEOMETRY_TOLERANCE * scale {
                return None;
            }
            u[i] = [d[0] / l[i], d[1] / l[i]];
        }
        Some(Legs {
            a: k.a,
            b: k.b,
            u,
            l,
        })
    }

    /// Base and platform exchanged (the viewpoint of the platform).
    fn exchanged(&self) -> Legs {
        Legs {
            a: self.b,
            b: self.a,
            u: self.u.map(|u| [-u[0], -u[1]]),
            l: self.l,
        }
    }

    /// Normalised homogeneous line `(n, −n·a_i)` with unit normal `n = E u_i`.
    fn line(&self, i: usize) -> [f64; 3] {
        let n = rotate_quarter(&self.u[i]);
        [n[0], n[1], -dot(&n, &self.a[i])]
    }

    /// Inverse Jacobian with reference point t: rows `[u_i, (b_i − t) × u_i]`.
    pub fn inverse_jacobian(&self, t: &Point<f64>) -> Matrix3<f64> {
        let mut j = Matrix3::zeros();
        for i in 0..3 {
            let r = difference(t, &self.b[i]);
            j[(i, 0)] = self.u[i][0];
            j[(i, 1)] = self.u[i][1];
            j[(i, 2)] = cross(&r, &self.u[i]);
        }
        j
    }
}

/// Manipulability `M = |det J| = |S| / (l_1 l_2 l_3)` (docs/theory.md §9; Yoshikawa).
pub fn manipulability(k: &Configuration) -> Option<f64> {
    let legs = Legs::new(k)?;
    Some(k.singularity().abs() / (legs.l[0] * legs.l[1] * legs.l[2]))
}

/// Incircle radius of the triangle of the leg lines (docs/theory.md §9, Ebrahimi et al.).
///
/// With normalised lines `L̂_i = (n_i, c_i)` (`|n_i| = 1`) and `w_ij = n_i × n_j`
/// (the sine of the angle between two lines), `r = 2·Area/Perimeter` becomes
///
/// `IR = |det(L̂_1, L̂_2, L̂_3)| / (|w_12| + |w_23| + |w_31|)`,
///
/// equal to `|det[T_k, 1]| / (t_1 + t_2 + t_3)` of docs/theory.md §9 for a proper
/// triangle, 0 for concurrent lines, and continuous at parallel lines (**Choice**): two
/// parallel legs at separation d give d/2 (the limit), three parallel legs give 0.
pub fn incircle_radius(k: &Configuration) -> Option<f64> {
    let legs = Legs::new(k)?;
    let lines = [legs.line(0), legs.line(1), legs.line(2)];
    let det = crate::algebra::det3(&lines).abs();
    let w = |i: usize, j: usize| (lines[i][0] * lines[j][1] - lines[i][1] * lines[j][0]).abs();
    let denominator = w(0, 1) + w(1, 2) + w(2, 0);
    if denominator <= GEOMETRY_TOLERANCE {
        return Some(0.0);
    }
    Some(det / denominator)
}

/// Pressure-angle cosines `|cos α_i|` (docs/theory.md §9, Takeda & Funabashi): with legs
/// j, k locked the platform rotates about `Q_i = L_j ∩ L_k`, so
/// `cos α_i = dist(Q_i, L_i) / |b_i − Q_i|`; if `L_j ∥ L_k` the platform translates
/// and `cos α_i = |u_i · E u_j|`. With `exchanged` the base is seen moving relative to
/// the platform: `cos α_i* = dist(Q_i, L_i) / |a_i − Q_i|`.
///
/// `None` if a leg has length 0 or the moving anchor coincides with `Q_i` (then the
/// three lines are concurrent at that anchor and the angle is 0/0).
pub fn pressure_cosines(k: &Configuration, exchanged: bool) -> Option<[f64; 3]> {
    let legs = Legs::new(k)?;
    let legs = if exchanged { legs.exchanged() } else { legs };
    let scale =
        k.a.iter()
            .chain(k.b.iter())
            .flatten()
            .fold(1.0_f64, |m, v| m.max(v.abs()));
    let mut out = [0.0; 3];
    for (i, cosine) in out.iter_mut().enumerate() {
        let (j, m) = ((i + 1) % 3, (i + 2) % 3);
        let sine = cross(&legs.u[j], &legs.u[m]);
        if sine.abs() <= GEOMETRY_TOLERANCE {
            *cosine = dot(&legs.u[i], &rotate_quarter(&legs.u[j])).abs();
            continue;
        }
        // Q = a_j + s u_j with (a_j + s u_j − a_m) × u_m = 0.
        let s = cross(&difference(&legs.a[j], &legs.a[m]), &legs.u[m]) / sine;
        let q = [
            legs.a[j][0] + s * legs.u[j][0],
            legs.a[j][1] + s * legs.u[j][1],
        ];
        let to_anchor = difference(&q, &legs.b[i]);
        let r = to_anchor[0].hypot(to_anchor[1]);
        if r.is_nan() || r <= GEOMETRY_TOLERANCE * scale {
            return None;
        }
        *cosine = cross(&to_anchor, &legs.u[i]).abs() / r;
    }
    Some(out)
}

/// Eigenvalues `(λ_min, λ_max)` of `GᵀG`, `G = K J⁻¹` the map from actuator rates to
/// the six passive joint rates (docs/theory.md §9, Nawratil's control number), and the
/// derived CN and MCN.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ControlNumber {
    /// `λ_min(GᵀG)`; `None` at a singularity (G unbounded).
    pub lambda_min: Option<f64>,
    /// `λ_max(GᵀG)`; `None` at a singularity.
    pub lambda_max: Option<f64>,
    /// CN in the requested variant (0 at singularities, the limit).
    pub cn: f64,
    /// `MCN = 1/sqrt(λ_max)` (units of length; 0 at singularities, the limit).
    pub mcn: f64,
}

/// Control number (docs/theory.md §9). Base joint rate `ψ̇_i = (E u_i)·ḃ_i / l_i`,
/// platform joint rate `ψ̇_i − φ̇`, `ḃ_i = ṫ + φ̇ E(b_i − t)`; `G = K J⁻¹`. Computed as
/// `G = K adj(J) / det J`, so CN (a ratio) and `MCN = |det J| / sqrt(λ_max(H))`,
/// `H = (K adj J)ᵀ(K adj J)`, stay continuous through singularities where they are 0.
///
/// `None` if a leg has length 0 or `adj J = 0` (J of rank ≤ 1).
pub fn control_number(
    k: &Configuration,
    t: &Point<f64>,
    variant: CnVariant,
) -> Option<ControlNumber> {
    let legs = Legs::new(k)?;
    let j = legs.inverse_jacobian(t);
    let det = j.determinant();
    // adj(J) = transpose of the cofactor matrix.
    let mut adj = Matrix3::zeros();
    for r in 0..3 {
        for c in 0..3 {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            adj[(c, r)] = j[(r1, c1)] * j[(r2, c2)] - j[(r1, c2)] * j[(r2, c1)];
        }
    }
    let mut kmat = Matrix6x3::zeros();
    for i in 0..3 {
        let n = rotate_quarter(&legs.u[i]);
        let r = difference(t, &legs.b[i]);
        let er = rotate_quarter(&r);
        let row = [n[0] / legs.l[i], n[1] / legs.l[i], dot(&n, &er) / legs.l[i]];
        for c in 0..3 {
            kmat[(i, c)] = row[c];
            kmat[(3 + i, c)] = row[c];
        }
        kmat[(3 + i, 2)] -= 1.0;
    }
    let g_scaled = kmat * adj;
    let h = g_scaled.transpose() * g_scaled;
    let eig = h.symmetric_eigen().eigenvalues;
    let h_max = eig.max();
    let h_min = eig.min().max(0.0);
    if h_max.is_nan() || h_max <= 0.0 || !h_max.is_finite() {
        return None;
    }
    let ratio = h_min / h_max;
    let det2 = det * det;
    let singular = det2 <= f64::MIN_POSITIVE;
    Some(ControlNumber {
        lambda_min: (!singular).then(|| h_min / det2),
        lambda_max: (!singular).then(|| h_max / det2),
        cn: match variant {
            CnVariant::Ratio => ratio,
            CnVariant::SquareRoot => ratio.sqrt(),
        },
        mcn: det.abs() / h_max.sqrt(),
    })
}

// ---------------------------------------------------------------------------------
// Orientation singularity distance
// ---------------------------------------------------------------------------------

/// `S(φ)` at a fixed position as a trigonometric polynomial of degree ≤ 3 about an
/// origin φ0: `S(φ0 + ψ) = a_0 + Σ_{k=1..3} (a_k cos kψ + b_k sin kψ)`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct TrigCubic {
    origin: f64,
    a: [f64; 4],
    b: [f64; 4],
}

impl TrigCubic {
    /// Exact interpolation from 7 equally spaced samples (discrete Fourier transform).
    fn fit(design: &Design, x: f64, y: f64, origin: f64) -> TrigCubic {
        let mut a = [0.0; 4];
        let mut b = [0.0; 4];
        for j in 0..7 {
            let psi = TAU * j as f64 / 7.0;
            let s = design
                .configuration(Pose::new(x, y, origin + psi))
                .singularity();
            a[0] += s / 7.0;
            for kk in 1..4 {
                let (sn, cs) = (kk as f64 * psi).sin_cos();
                a[kk] += 2.0 * s * cs / 7.0;
                b[kk] += 2.0 * s * sn / 7.0;
            }
        }
        TrigCubic { origin, a, b }
    }

    fn value_and_derivative(&self, psi: f64) -> (f64, f64) {
        let mut v = self.a[0];
        let mut d = 0.0;
        for k in 1..4 {
            let (sn, cs) = (k as f64 * psi).sin_cos();
            v += self.a[k] * cs + self.b[k] * sn;
            d += k as f64 * (-self.a[k] * sn + self.b[k] * cs);
        }
        (v, d)
    }

    fn scale(&self) -> f64 {
        self.a.iter().chain(self.b.iter()).map(|c| c.abs()).sum()
    }

    /// Coefficients (ascending) of `(1 + t²)³ S(φ0 + 2 atan t)`, a real polynomial of
    /// degree ≤ 6 (`e^{iψ} = (1 + it)² / (1 + t²)`).
    fn half_angle_polynomial(&self) -> [f64; 7] {
        let mul = |p: &[C64], q: &[C64]| {
            let mut out = vec![C64::new(0.0, 0.0); p.len() + q.len() - 1];
            for (i, x) in p.iter().enumerate() {
                for (j, y) in q.iter().enumerate() {
                    out[i + j] += x * y;
                }
            }
            out
        };
        let one_plus_it = [C64::new(1.0, 0.0), C64::new(0.0, 1.0)];
        let one_plus_t2 = [C64::new(1.0, 0.0), C64::new(0.0, 0.0), C64::new(1.0, 0.0)];
        let mut out = [0.0; 7];
        for k in 0..4 {
            let mut p = vec![C64::new(1.0, 0.0)];
            for _ in 0..2 * k {
                p = mul(&p, &one_plus_it);
            }
            for _ in 0..3 - k {
                p = mul(&p, &one_plus_t2);
            }
            for (j, c) in p.iter().enumerate() {
                out[j] += self.a[k] * c.re + if k > 0 { self.b[k] * c.im } else { 0.0 };
            }
        }
        out
    }
}

/// The singular orientations at a fixed position (docs/theory.md §9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum SingularOrientations {
    /// Every orientation is singular (S ≡ 0 at this position).
    All,
    /// The finitely many (≤ 6) singular orientations in `[0, 2π)`, ascending.
    Finite(Vec<f64>),
}

/// All real φ ∈ [0, 2π) with `S(x, y, φ) = 0` (docs/theory.md §9): S(φ) is a trigonometric
/// polynomial of degree ≤ 3; its roots are those of a degree-6 polynomial in
/// `t = tan((φ − φ0)/2)` (φ0 chosen so that `t = ∞` is not a root), polished by Newton's
/// method on S(φ) itself.
pub fn singular_orientations(design: &Design, x: f64, y: f64) -> SingularOrientations {
    // Put t = ∞ (ψ = π) at the sample where |S| is largest, which is not a root.
    let probe = TrigCubic::fit(design, x, y, 0.0);
    let (mut best, mut best_value) = (0.0, -1.0);
    for j in 0..7 {
        let psi = TAU * j as f64 / 7.0;
        let v = probe.value_and_derivative(psi).0.abs();
        if v > best_value {
            best = psi;
            best_value = v;
        }
    }
    let trig = TrigCubic::fit(design, x, y, best - PI);
    let scale = trig.scale();
    if scale.is_nan() || scale <= 0.0 || best_value <= 1e-14 * design.length_scale().powi(4) {
        return SingularOrientations::All;
    }
    let poly = trimmed(&trig.half_angle_polynomial(), 1e-14);
    let mut roots: Vec<f64> = Vec::new();
    for t in polynomial_roots(&poly) {
        if t.im.abs() > 1e-6 * (1.0 + t.re.abs()) {
            continue;
        }
        let mut psi = 2.0 * t.re.atan();
        for _ in 0..8 {
            let (v, d) = trig.value_and_derivative(psi);
            if d == 0.0 {
                break;
            }
            let step = v / d;
            if step.abs() > 0.1 {
                break;
            }
            psi -= step;
        }
        if trig.value_and_derivative(psi).0.abs() > 1e-9 * scale {
            continue;
        }
        let phi = (trig.origin + psi).rem_euclid(TAU);
        let phi = if phi >= TAU { 0.0 } else { phi };
        if roots.iter().all(|r| angular_distance(*r, phi) > 1e-9) {
            roots.push(phi);
        }
    }
    roots.sort_by(f64::total_cmp);
    SingularOrientations::Finite(roots)
}

/// `|φ_1 − φ_2|` measured on the circle, in `[0, π]`.
pub fn angular_distance(phi1: f64, phi2: f64) -> f64 {
    let d = (phi1 - phi2).rem_euclid(TAU);
    d.min(TAU - d)
}

/// Nearest singular orientation at the pose's position (docs/theory.md §9; Mao et al.).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OrientationDistance {
    /// Angular distance (radians) from φ to the nearest singular orientation.
    pub distance: f64,
    /// The same, with the sign of S at the pose.
    pub signed: f64,
    /// The nearest singular orientation, in `[0, 2π)` (φ itself if S ≡ 0).
    pub nearest: f64,
}

/// Orientation singularity distance; `None` if no orientation at this position is
/// singular (the platform can turn fully round).
pub fn orientation_singularity_distance(
    design: &Design,
    pose: Pose,
) -> Option<OrientationDistance> {
    let sign = signum(design.configuration(pose).singularity());
    match singular_orientations(design, pose.x, pose.y) {
        SingularOrientations::All => Some(OrientationDistance {
            distance: 0.0,
            signed: 0.0,
            nearest: pose.phi.rem_euclid(TAU),
        }),
        SingularOrientations::Finite(roots) => roots
            .iter()
            .map(|&r| (angular_distance(r, pose.phi), r))
            .min_by(|p, q| p.0.total_cmp(&q.0))
            .map(|(distance, nearest)| OrientationDistance {
                distance,
                signed: sign * distance,
                nearest,
            }),
    }
}

fn signum(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

// ---------------------------------------------------------------------------------
// Position singularity distance
// ---------------------------------------------------------------------------------

/// The conic of singular positions at fixed φ (docs/theory.md §9):
/// `S(x, y, φ) = C_xx x² + C_xy xy + C_yy y² + C_x x + C_y y + C_0` (S is quadratic in
/// the translation because the cubic terms have two equal columns).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SingularConic {
    /// `C_xx`.
    pub cxx: f64,
    /// `C_xy`.
    pub cxy: f64,
    /// `C_yy`.
    pub cyy: f64,
    /// `C_x`.
    pub cx: f64,
    /// `C_y`.
    pub cy: f64,
    /// `C_0`.
    pub c0: f64,
}

impl SingularConic {
    /// Fit from six evaluations of S at `(0,0), (±h,0), (0,±h), (h,h)` with h the design's
    /// length scale (exact up to rounding, since S is quadratic in (x, y)).
    pub fn at_orientation(design: &Design, phi: f64) -> SingularConic {
        let h = design.length_scale();
        let s = |x: f64, y: f64| design.configuration(Pose::new(x, y, phi)).singularity();
        let c0 = s(0.0, 0.0);
        let (sxp, sxm, syp, sym, sxy) = (s(h, 0.0), s(-h, 0.0), s(0.0, h), s(0.0, -h), s(h, h));
        let cx = (sxp - sxm) / (2.0 * h);
        let cy = (syp - sym) / (2.0 * h);
        let cxx = (sxp + sxm - 2.0 * c0) / (2.0 * h * h);
        let cyy = (syp + sym - 2.0 * c0) / (2.0 * h * h);
        let cxy = (sxy - c0 - cx * h - cy * h - cxx * h * h - cyy * h * h) / (h * h);
        SingularConic {
            cxx,
            cxy,
            cyy,
            cx,
            cy,
            c0,
        }
    }

    /// Value at (x, y).
    pub fn value(&self, p: &Point<f64>) -> f64 {
        let [x, y] = *p;
        self.cxx * x * x + self.cxy * x * y + self.cyy * y * y + self.cx * x + self.cy * y + self.c0
    }

    fn gradient(&self, p: &Point<f64>) -> Point<f64> {
        let [x, y] = *p;
        [
            2.0 * self.cxx * x + self.cxy * y + self.cx,
            self.cxy * x + 2.0 * self.cyy * y + self.cy,
        ]
    }

    /// Nearest point of the conic to `p0`: all critical points of `|p − p0|²` on the
    /// conic. In the eigenframe of the quadratic part, centred at p0,
    /// `Q = λ_1 z_1² + λ_2 z_2² + β_1 z_1 + β_2 z_2 + c`, the Lagrange condition
    /// `z = μ ∇Q` gives `z_i = μ β_i / (1 − 2μλ_i)` and a quartic in μ; the degenerate
    /// branches `μ = 1/(2λ_i)` (where `z_i` is free) and the centre are added; every
    /// candidate is projected onto the conic by Newton steps. Returns
    /// `(distance, foot)`, or `None` if the conic has no real point. If S vanishes for
    /// every position (`Q ≡ 0`), the distance is 0 at p0.
    pub fn nearest_point(&self, p0: &Point<f64>) -> Option<(f64, Point<f64>)> {
        let coefficient_scale = [self.cxx, self.cxy, self.cyy, self.cx, self.cy, self.c0]
            .iter()
            .map(|c| c.abs())
            .fold(0.0_f64, f64::max);
        if !coefficient_scale.is_finite() {
            return None;
        }
        if coefficient_scale == 0.0 {
            return Some((0.0, *p0));
        }
        // Symmetric 2×2 eigen decomposition of [[cxx, cxy/2], [cxy/2, cyy]].
        let (p, q, r) = (self.cxx, self.cxy / 2.0, self.cyy);
        let mean = (p + r) / 2.0;
        let radius = (((p - r) / 2.0).powi(2) + q * q).sqrt();
        let lambda = [mean + radius, mean - radius];
        let angle = 0.5 * (2.0 * q).atan2(p - r);
        let (sn, cs) = angle.sin_cos();
        let axes = [[cs, sn], [-sn, cs]];
        let g = self.gradient(p0);
        let beta = [dot(&axes[0], &g), dot(&axes[1], &g)];
        let c = self.value(p0);
        let to_plane = |z: [f64; 2]| {
            [
                p0[0] + z[0] * axes[0][0] + z[1] * axes[1][0],
                p0[1] + z[0] * axes[0][1] + z[1] * axes[1][1],
            ]
        };
        let tiny = 1e-14 * coefficient_scale;

        let mut candidates: Vec<Point<f64>> = Vec::new();
        // Quartic in μ: Σ_i λ_i μ² β_i² Π_{j≠i}(1−2μλ_j)² + β_i² μ (1−2μλ_i) Π_{j≠i}(1−2μλ_j)² + c Π(1−2μλ_j)².
        let lin = |l: f64| vec![1.0, -2.0 * l];
        let mul = |a: &[f64], b: &[f64]| {
            let mut out = vec![0.0; a.len() + b.len() - 1];
            for (i, x) in a.iter().enumerate() {
                for (j, y) in b.iter().enumerate() {
                    out[i + j] += x * y;
                }
            }
            out
        };
        let add = |acc: &mut Vec<f64>, term: &[f64]| {
            if acc.len() < term.len() {
                acc.resize(term.len(), 0.0);
            }
            for (a, t) in acc.iter_mut().zip(term) {
                *a += t;
            }
        };
        let mut quartic = vec![0.0; 5];
        for i in 0..2 {
            let other = 1 - i;
            let other_sq = mul(&lin(lambda[other]), &lin(lambda[other]));
            let t1 = mul(&[0.0, 0.0, lambda[i] * beta[i] * beta[i]], &other_sq);
            let t2 = mul(&mul(&[0.0, beta[i] * beta[i]], &lin(lambda[i])), &other_sq);
            add(&mut quartic, &t1);
            add(&mut quartic, &t2);
        }
        let all_sq = mul(
            &mul(&lin(lambda[0]), &lin(lambda[0])),
            &mul(&lin(lambda[1]), &lin(lambda[1])),
        );
        add(
            &mut quartic,
            &all_sq.iter().map(|v| c * v).collect::<Vec<_>>(),
        );
        let quartic = trimmed(&quartic, 1e-13);
        for mu in polynomial_roots(&quartic) {
            if mu.im.abs() > 1e-3 * (1.0 + mu.re.abs()) {
                continue;
            }
            let mu = mu.re;
            let mut z = [0.0; 2];
            let mut ok = true;
            for i in 0..2 {
                let denominator = 1.0 - 2.0 * mu * lambda[i];
                if denominator.abs() < 1e-14 {
                    ok = false;
                    break;
                }
                z[i] = mu * beta[i] / denominator;
            }
            if ok {
                candidates.push(to_plane(z));
            }
        }
        // Degenerate branches μ = 1/(2λ_i): z_i free, z_j fixed.
        for i in 0..2 {
            if lambda[i].abs() <= tiny {
                continue;
            }
            let j = 1 - i;
            let mu = 1.0 / (2.0 * lambda[i]);
            let denominator = 1.0 - 2.0 * mu * lambda[j];
            let zj = if denominator.abs() > 1e-12 {
                mu * beta[j] / denominator
            } else {
                0.0
            };
            // λ_i z_i² + β_i z_i + (λ_j z_j² + β_j z_j + c) = 0.
            let rest = lambda[j] * zj * zj + beta[j] * zj + c;
            let disc = beta[i] * beta[i] - 4.0 * lambda[i] * rest;
            if disc >= 0.0 {
                for sign in [-1.0, 1.0] {
                    let zi = (-beta[i] + sign * disc.sqrt()) / (2.0 * lambda[i]);
                    let mut z = [0.0; 2];
                    z[i] = zi;
                    z[j] = zj;
                    candidates.push(to_plane(z));
                }
            }
        }
        // The centre (a double point when the conic is a pair of crossing lines).
        if lambda[0].abs() > tiny && lambda[1].abs() > tiny {
            candidates.push(to_plane([
                -beta[0] / (2.0 * lambda[0]),
                -beta[1] / (2.0 * lambda[1]),
            ]));
        }
        let mut best: Option<(f64, Point<f64>)> = None;
        for mut point in candidates {
            for _ in 0..30 {
                let v = self.value(&point);
                let grad = self.gradient(&point);
                let g2 = dot(&grad, &grad);
                if v == 0.0 || g2.is_nan() || g2 <= 0.0 {
                    break;
                }
                let step = [v * grad[0] / g2, v * grad[1] / g2];
                point = [point[0] - step[0], point[1] - step[1]];
                if step[0].hypot(step[1]) <= 1e-15 * (1.0 + point[0].hypot(point[1])) {
                    break;
                }
            }
            let reach = 1.0 + point[0].abs().max(point[1].abs());
            let residual = self.value(&point).abs();
            if residual.is_nan() || residual > 1e-10 * coefficient_scale * reach * reach {
                continue;
            }
            let d = difference(p0, &point);
            let distance = d[0].hypot(d[1]);
            if best.is_none_or(|(b, _)| distance < b) {
                best = Some((distance, point));
            }
        }
        best
    }
}

/// Nearest singular position at the pose's orientation (docs/theory.md §9; Nag et al.).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PositionDistance {
    /// Distance from (x, y) to the conic of singular positions.
    pub distance: f64,
    /// The same, with the sign of S at the pose.
    pub signed: f64,
    /// The nearest singular position (foot point).
    pub foot: Point<f64>,
}

/// Position singularity distance; `None` if no position is singular at this φ.
pub fn position_singularity_distance(design: &Design, pose: Pose) -> Option<PositionDistance> {
    let conic = SingularConic::at_orientation(design, pose.phi);
    let sign = signum(design.configuration(pose).singularity());
    conic
        .nearest_point(&[pose.x, pose.y])
        .map(|(distance, foot)| PositionDistance {
            distance,
            signed: sign * distance,
            foot,
        })
}

/// Radius of the singularity-free cylinder (Li, Gosselin & Richard 2006; Kapilavai and
/// Nawratil, Eq. 4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CylinderRadius {
    /// `min_{φ ∈ [lo, hi]}` position singularity distance at (x, y).
    pub radius: f64,
    /// An orientation where the minimum is attained.
    pub at_phi: f64,
}

/// `min` over φ ∈ `[lo, hi]` of the position singularity distance at (x, y)
/// (docs/theory.md §9). It is 0 if some φ in the range is a singular orientation at (x,
/// y) (always the case for an unbounded range unless the position admits no singular
/// orientation). Otherwise: 33 samples, then golden-section refinement around the best one.
/// `Ok(None)` if no orientation in the range has a singular position.
pub fn singularity_free_cylinder_radius(
    design: &Design,
    x: f64,
    y: f64,
    range: [f64; 2],
) -> Result<Option<CylinderRadius>, IndexError> {
    let [lo, hi] = range;
    if !lo.is_finite() || !hi.is_finite() || lo > hi {
        return Err(IndexError::BadRange { lo, hi });
    }
    match singular_orientations(design, x, y) {
        SingularOrientations::All => {
            return Ok(Some(CylinderRadius {
                radius: 0.0,
                at_phi: lo,
            }));
        }
        SingularOrientations::Finite(roots) => {
            for r in roots {
                let k = ((lo - r) / TAU).ceil();
                let phi = r + k * TAU;
                if phi <= hi {
                    return Ok(Some(CylinderRadius {
                        radius: 0.0,
                        at_phi: phi,
                    }));
                }
            }
        }
    }
    let f = |phi: f64| {
        position_singularity_distance(design, Pose::new(x, y, phi))
            .map_or(f64::INFINITY, |d| d.distance)
    };
    if lo == hi {
        let radius = f(lo);
        return Ok(radius
            .is_finite()
            .then_some(CylinderRadius { radius, at_phi: lo }));
    }
    const SAMPLES: usize = 33;
    let phis: Vec<f64> = (0..SAMPLES)
        .map(|j| lo + (hi - lo) * j as f64 / (SAMPLES - 1) as f64)
        .collect();
    let values: Vec<f64> = phis.iter().map(|&p| f(p)).collect();
    let (best, &best_value) = values
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .unwrap_or((0, &f64::INFINITY));
    if !best_value.is_finite() {
        return Ok(None);
    }
    let (mut a, mut b) = (
        phis[best.saturating_sub(1)],
        phis[(best + 1).min(SAMPLES - 1)],
    );
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..50 {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d);
        }
    }
    let mut result = CylinderRadius {
        radius: best_value,
        at_phi: phis[best],
    };
    for (phi, value) in [(c, fc), (d, fd)] {
        if value < result.radius {
            result = CylinderRadius {
                radius: value,
                at_phi: phi,
            };
        }
    }
    Ok(Some(result))
}

// ---------------------------------------------------------------------------------
// All indices at a pose
// ---------------------------------------------------------------------------------

/// Every index of docs/theory.md §9 at one pose; `None` = undefined (never NaN).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RprIndices {
    /// The pose.
    pub pose: Pose,
    /// Manipulability `|det J|`.
    #[serde(rename = "M")]
    pub m: Option<f64>,
    /// The singularity polynomial S (signed).
    #[serde(rename = "S")]
    pub s: f64,
    /// Incircle radius.
    #[serde(rename = "IR")]
    pub ir: Option<f64>,
    /// Transmission index `min_i |cos α_i|`.
    #[serde(rename = "TI")]
    pub ti: Option<f64>,
    /// DS (reconstructed; aggregate in [`IndexVariants`]).
    #[serde(rename = "DS")]
    pub ds: Option<f64>,
    /// `min(TI, TI*)`.
    #[serde(rename = "MTI")]
    pub mti: Option<f64>,
    /// `min(DS, DS*)`.
    #[serde(rename = "MDS")]
    pub mds: Option<f64>,
    /// Control number (variant in [`IndexVariants`]).
    #[serde(rename = "CN")]
    pub cn: Option<f64>,
    /// `1/sqrt(λ_max)`.
    #[serde(rename = "MCN")]
    pub mcn: Option<f64>,
    /// Unsigned orientation singularity distance (radians); `None`: no singular orientation.
    pub orientation_distance: Option<f64>,
    /// Signed orientation singularity distance (sign of S).
    pub orientation_distance_signed: Option<f64>,
    /// Unsigned position singularity distance; `None`: no singular position at this φ.
    pub position_distance: Option<f64>,
    /// Signed position singularity distance (sign of S).
    pub position_distance_signed: Option<f64>,
    /// Nearest singular position.
    pub position_foot: Option<Point<f64>>,
    /// Singularity-free cylinder radius over `[φ − w, φ + w]`.
    pub cylinder_radius: Option<f64>,
    /// Pressure-angle cosines `|cos α_i|` (platform viewpoint).
    pub pressure_cosines: Option<[f64; 3]>,
    /// Pressure-angle cosines `|cos α_i*|` (base viewpoint).
    pub pressure_cosines_exchanged: Option<[f64; 3]>,
    /// `λ_min(GᵀG)`.
    pub lambda_min: Option<f64>,
    /// `λ_max(GᵀG)`.
    pub lambda_max: Option<f64>,
}

fn min3(c: [f64; 3]) -> f64 {
    c[0].min(c[1]).min(c[2])
}

/// All indices of docs/theory.md §9 at `pose`.
pub fn compute_indices(design: &Design, pose: Pose, options: &IndexOptions) -> RprIndices {
    let k = design.configuration(pose);
    let cos = pressure_cosines(&k, false);
    let cos_star = pressure_cosines(&k, true);
    let cn = control_number(&k, &[pose.x, pose.y], options.cn);
    let orientation = orientation_singularity_distance(design, pose);
    let position = position_singularity_distance(design, pose);
    let w = options.cylinder_half_width.abs();
    let cylinder =
        singularity_free_cylinder_radius(design, pose.x, pose.y, [pose.phi - w, pose.phi + w])
            .ok()
            .flatten();
    let both = |f: &dyn Fn([f64; 3]) -> f64| match (cos, cos_star) {
        (Some(c), Some(cs)) => Some(f(c).min(f(cs))),
        _ => None,
    };
    RprIndices {
        pose,
        m: manipulability(&k),
        s: k.singularity(),
        ir: incircle_radius(&k),
        ti: cos.map(min3),
        ds: cos.map(|c| options.ds.apply(c)),
        mti: both(&min3),
        mds: both(&|c| options.ds.apply(c)),
        cn: cn.map(|c| c.cn),
        mcn: cn.map(|c| c.mcn),
        orientation_distance: orientation.map(|o| o.distance),
        orientation_distance_signed: orientation.map(|o| o.signed),
        position_distance: position.map(|p| p.distance),
        position_distance_signed: position.map(|p| p.signed),
        position_foot: position.map(|p| p.foot),
        cylinder_radius: cylinder.map(|c| c.radius),
        pressure_cosines: cos,
        pressure_cosines_exchanged: cos_star,
        lambda_min: cn.and_then(|c| c.lambda_min),
        lambda_max: cn.and_then(|c| c.lambda_max),
    }
}

/// Names of the scalar index columns of a motion table, in output order.
pub const INDEX_COLUMN_NAMES: [&str; 14] = [
    "M",
    "S",
    "IR",
    "TI",
    "DS",
    "MTI",
    "MDS",
    "CN",
    "MCN",
    "orientation_distance",
    "orientation_distance_signed",
    "position_distance",
    "position_distance_signed",
    "cylinder_radius",
];

/// The scalar index columns of a motion table ([`INDEX_COLUMN_NAMES`]) with their values.
pub fn index_columns(indices: &RprIndices) -> [(&'static str, Option<f64>); 14] {
    let values = [
        indices.m,
        Some(indices.s),
        indices.ir,
        indices.ti,
        indices.ds,
        indices.mti,
        indices.mds,
        indices.cn,
        indices.mcn,
        indices.orientation_distance,
        indices.orientation_distance_signed,
        indices.position_distance,
        indices.position_distance_signed,
        indices.cylinder_radius,
    ];
    std::array::from_fn(|j| (INDEX_COLUMN_NAMES[j], values[j]))
}
