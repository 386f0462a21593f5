//! Extrinsic metrics on the configuration space of a 3-RPR (docs/theory.md §2–§4):
//! segment and triangle distances, the nine interpretations `PLATFORM/BASE`, and D(K, K′).
//!
//! A configuration is the 12-vector `K = (a_1, a_2, a_3, b_1, b_2, b_3)` of
//! [`crate::mechanism::rpr::Configuration::to_array`]. Every formula is generic over
//! [`crate::algebra::Ring`], so the Lagrangians of the distance problems are built
//! symbolically from exactly the code that evaluates distances numerically.

use crate::algebra::{Cartesian, Plane, Point, Ring, difference};
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// Errors of metric names.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MetricError {
    /// A metric name that is not one of the nine.
    #[error(
        "unknown metric `{name}`: expected PLATFORM/BASE with each of plate, bars, rigid (one of {valid}), or `all`"
    )]
    UnknownMetric {
        /// The name given.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// An empty metric list.
    #[error("empty metric list: give `all` or names like `plate/plate,bars/rigid`")]
    EmptyList,
}

/// Mean squared distance of corresponding points of two oriented segments
/// `p_1 p_2` and `p_1′ p_2′` (Kapilavai and Nawratil, Eq. 8; docs/theory.md §2): with
/// `d_k = p_k′ − p_k`,
///
/// `seg² = (|d_1|² + |d_2|² + d_1·d_2) / 3`.
pub fn segment_distance_sq<T: Ring>(p: [&Point<T>; 2], q: [&Point<T>; 2]) -> T {
    segment_distance_sq_in::<Cartesian, T>(p, q)
}

/// [`segment_distance_sq`] with the points in the coordinates `P`.
pub fn segment_distance_sq_in<P: Plane<T>, T: Ring>(p: [&Point<T>; 2], q: [&Point<T>; 2]) -> T {
    let d1 = difference(p[0], q[0]);
    let d2 = difference(p[1], q[1]);
    (P::dot(&d1, &d1) + P::dot(&d2, &d2) + P::dot(&d1, &d2)) * T::from_f64(1.0 / 3.0)
}

/// Mean squared distance of corresponding points of two triangles under the affine
/// correspondence (Kapilavai and Nawratil, Eq. 9; docs/theory.md §2): with
/// `d_k = p_k′ − p_k`,
///
/// `tri² = (|d_1|² + |d_2|² + |d_3|² + d_1·d_2 + d_1·d_3 + d_2·d_3) / 6`.
pub fn triangle_distance_sq<T: Ring>(p: [&Point<T>; 3], q: [&Point<T>; 3]) -> T {
    triangle_distance_sq_in::<Cartesian, T>(p, q)
}

/// [`triangle_distance_sq`] with the points in the coordinates `P`.
pub fn triangle_distance_sq_in<P: Plane<T>, T: Ring>(p: [&Point<T>; 3], q: [&Point<T>; 3]) -> T {
    let d1 = difference(p[0], q[0]);
    let d2 = difference(p[1], q[1]);
    let d3 = difference(p[2], q[2]);
    (P::dot(&d1, &d1)
        + P::dot(&d2, &d2)
        + P::dot(&d3, &d3)
        + P::dot(&d1, &d2)
        + P::dot(&d1, &d3)
        + P::dot(&d2, &d3))
        * T::from_f64(1.0 / 6.0)
}

/// How a part (platform or base) is modelled (docs/theory.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    /// ▲ deformable triangular plate: one summand `tri²`.
    Plate,
    /// △ pin-jointed triangle of three deformable bars: three summands `seg²`.
    Bars,
    /// Undeformable: no summand; in K′ it may only move by a proper Euclidean motion.
    Rigid,
}

impl Part {
    /// All three part models.
    pub const ALL: [Part; 3] = [Part::Plate, Part::Bars, Part::Rigid];

    /// `plate`, `bars` or `rigid`.
    pub fn name(self) -> &'static str {
        match self {
            Part::Plate => "plate",
            Part::Bars => "bars",
            Part::Rigid => "rigid",
        }
    }

    /// Number of summands this part contributes to D² (1, 3, 0).
    pub fn number_of_summands(self) -> usize {
        match self {
            Part::Plate => 1,
            Part::Bars => 3,
            Part::Rigid => 0,
        }
    }

    fn from_name(name: &str) -> Option<Part> {
        Part::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Calls `sink` with each summand of this part for points `p` (in K) and `q` (in K′).
    fn each_summand<P: Plane<T>, T: Ring>(
        self,
        p: [&Point<T>; 3],
        q: [&Point<T>; 3],
        sink: &mut impl FnMut(T),
    ) {
        match self {
            Part::Plate => sink(triangle_distance_sq_in::<P, T>(p, q)),
            Part::Bars => {
                for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                    sink(segment_distance_sq_in::<P, T>([p[i], p[j]], [q[i], q[j]]));
                }
            }
            Part::Rigid => {}
        }
    }
}

/// One of the nine extrinsic metrics `PLATFORM/BASE` (Kapilavai and Nawratil, §1.4, Eqs.
/// 10–22; docs/theory.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Metric {
    /// Model of the platform.
    pub platform: Part,
    /// Model of the base.
    pub base: Part,
}

fn point<T: Ring>(k: &[T; 12], j: usize) -> Point<T> {
    [k[j].clone(), k[j + 1].clone()]
}

impl Metric {
    /// Metric with the given platform and base models.
    pub fn new(platform: Part, base: Part) -> Self {
        Metric { platform, base }
    }

    /// The nine metrics, platform-major: plate/plate, plate/bars, plate/rigid, bars/plate, ….
    pub fn all() -> [Metric; 9] {
        let mut out = [Metric::new(Part::Plate, Part::Plate); 9];
        for (i, platform) in Part::ALL.into_iter().enumerate() {
            for (j, base) in Part::ALL.into_iter().enumerate() {
                out[3 * i + j] = Metric::new(platform, base);
            }
        }
        out
    }

    /// `PLATFORM/BASE`, e.g. `bars/rigid`.
    pub fn name(&self) -> String {
        format!("{}/{}", self.platform.name(), self.base.name())
    }

    /// Parses `all` or a comma-separated list of names (`plate/plate,bars/rigid`);
    /// duplicates are removed, order kept.
    pub fn parse_list(list: &str) -> Result<Vec<Metric>, MetricError> {
        let list = list.trim();
        if list.eq_ignore_ascii_case("all") {
            return Ok(Metric::all().to_vec());
        }
        let mut out: Vec<Metric> = Vec::new();
        for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let metric: Metric = name.parse()?;
            if !out.contains(&metric) {
                out.push(metric);
            }
        }
        if out.is_empty() {
            return Err(MetricError::EmptyList);
        }
        Ok(out)
    }

    /// `n = 3 + (#platform summands) + (#base summands)` (docs/theory.md §3): the three
    /// legs always contribute three summands.
    pub fn number_of_summands(&self) -> usize {
        3 + self.platform.number_of_summands() + self.base.number_of_summands()
    }

    /// Calls `sink` with each unnormalised summand of D²(K, K′) (docs/theory.md §3), in
    /// order: the three leg terms `seg²(a_i b_i, a_i′ b_i′)`, then the platform's (`tri²`
    /// of `b_1 b_2 b_3` for a plate, `seg²` of its edges 12, 23, 31 for bars), then the
    /// base's likewise. Rigid parts contribute nothing: the caller guarantees K′ moved
    /// them rigidly. `D² = (Σ summands) / n`. Allocation-free.
    pub fn for_each_summand<T: Ring>(&self, k: &[T; 12], k_prime: &[T; 12], sink: impl FnMut(T)) {
        self.for_each_summand_in::<Cartesian, T>(k, k_prime, sink)
    }

    /// [`Metric::for_each_summand`] with the points of `k` and `k_prime` in the
    /// coordinates `P`.
    pub fn for_each_summand_in<P: Plane<T>, T: Ring>(
        &self,
        k: &[T; 12],
        k_prime: &[T; 12],
        mut sink: impl FnMut(T),
    ) {
        let a: [Point<T>; 3] = [point(k, 0), point(k, 2), point(k, 4)];
        let b: [Point<T>; 3] = [point(k, 6), point(k, 8), point(k, 10)];
        let a2: [Point<T>; 3] = [point(k_prime, 0), point(k_prime, 2), point(k_prime, 4)];
        let b2: [Point<T>; 3] = [point(k_prime, 6), point(k_prime, 8), point(k_prime, 10)];
        for i in 0..3 {
            sink(segment_distance_sq_in::<P, T>(
                [&a[i], &b[i]],
                [&a2[i], &b2[i]],
            ));
        }
        self.platform.each_summand::<P, T>(
            [&b[0], &b[1], &b[2]],
            [&b2[0], &b2[1], &b2[2]],
            &mut sink,
        );
        self.base
            .each_summand::<P, T>([&a[0], &a[1], &a[2]], [&a2[0], &a2[1], &a2[2]], &mut sink);
    }

    /// The unnormalised summands of D²(K, K′) as a vector (see
    /// [`Metric::for_each_summand`] for the order); handy for building Lagrangians.
    pub fn summands<T: Ring>(&self, k: &[T; 12], k_prime: &[T; 12]) -> Vec<T> {
        let mut out = Vec::with_capacity(self.number_of_summands());
        self.for_each_summand(k, k_prime, |t| out.push(t));
        out
    }

    /// `D²(K, K′) = (Σ summands) / n` (docs/theory.md §3), generic over the ring;
    /// allocation-free.
    pub fn distance_sq<T: Ring>(&self, k: &[T; 12], k_prime: &[T; 12]) -> T {
        self.distance_sq_in::<Cartesian, T>(k, k_prime)
    }

    /// [`Metric::distance_sq`] with the points of `k` and `k_prime` in the coordinates
    /// `P`.
    pub fn distance_sq_in<P: Plane<T>, T: Ring>(&self, k: &[T; 12], k_prime: &[T; 12]) -> T {
        let n = self.number_of_summands() as f64;
        let mut total: Option<T> = None;
        self.for_each_summand_in::<P, T>(k, k_prime, |t| {
            total = Some(match total.take() {
                Some(acc) => acc + t,
                None => t,
            })
        });
        total.unwrap_or_else(|| T::from_f64(0.0)) * T::from_f64(1.0 / n)
    }

    /// `D(K, K′)`, the square root of [`Metric::distance_sq`], for real configurations.
    pub fn distance(&self, k: &[f64; 12], k_prime: &[f64; 12]) -> f64 {
        self.distance_sq(k, k_prime).max(0.0).sqrt()
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name())
    }
}

impl FromStr for Metric {
    type Err = MetricError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let unknown = || MetricError::UnknownMetric {
            name: s.to_string(),
            valid: Metric::all()
                .iter()
                .map(Metric::name)
                .collect::<Vec<_>>()
                .join(", "),
        };
        let lower = s.trim().to_ascii_lowercase();
        let (platform, base) = lower.split_once('/').ok_or_else(unknown)?;
        let platform = Part::from_name(platform.trim()).ok_or_else(unknown)?;
        let base = Part::from_name(base.trim()).ok_or_else(unknown)?;
        Ok(Metric::new(platform, base))
    }
}
