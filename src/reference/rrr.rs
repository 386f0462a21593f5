//! Reference 3-RRR singularity distances by many-start local solution of the
//! constrained problem `min D²(K, K′)` subject to `C(K′) = 0` (the parallel or a leg
//! polynomial), independent of the homotopy pipeline.
//!
//! `D²(K, K + d) = dᵀ M d` is a positive definite quadratic form (the all-deformable
//! metric is a sum of squared point distances); the constraint involves only some
//! coordinates `y` of `K′` (a leg problem: `O_i, B_i, C_i`; the parallel problem: the
//! elbows and platform joints), so the others are eliminated in closed form: their
//! optimum for given `y` is linear in `y`, and the cost becomes
//! `f(y) = (y − y_K)ᵀ S (y − y_K)` with `S = M_yy − M_yz M_zz⁻¹ M_zy` the Schur
//! complement. From each start (`K`'s coordinates plus seeded normal noise at relative
//! scales 0.02 … 1), Gauss–Newton steps reach `C = 0`, then Newton's method on the KKT
//! system `∇f − λ∇C = 0, C = 0` (Nocedal and Wright, *Numerical Optimization*, 2nd ed.,
//! Springer 2006, §18.1) converges to a critical point; exact derivatives of `C` come
//! from [`super::jet`]. Every converged point is feasible, so the smallest `D` found is
//! an upper bound on the distance.

use super::jet::{Jet, MAX_VARIABLES};
use crate::mechanism::rrr::{CONFIGURATION_LEN, distance_sq};
use crate::problem::rrr::RrrSubProblem;
use crate::random;
use nalgebra::{DMatrix, DVector};

/// The coordinates of `K′` that the constraint of `kind` involves.
fn constrained_coordinates(kind: RrrSubProblem) -> Vec<usize> {
    match kind {
        RrrSubProblem::Parallel => (6..CONFIGURATION_LEN).collect(),
        RrrSubProblem::Leg(i) => [0, 6, 12]
            .iter()
            .flat_map(|&first| [first + 2 * i, first + 2 * i + 1])
            .collect(),
    }
}

/// `M` of `D²(K, K + d) = dᵀ M d` (constant; by polarisation).
fn metric_matrix(k: &[f64; CONFIGURATION_LEN]) -> DMatrix<f64> {
    let q = |d: &[f64; CONFIGURATION_LEN]| {
        let moved: [f64; CONFIGURATION_LEN] = std::array::from_fn(|j| k[j] + d[j]);
        distance_sq(k, &moved)
    };
    let unit = |j: usize| -> [f64; CONFIGURATION_LEN] {
        std::array::from_fn(|i| if i == j { 1.0 } else { 0.0 })
    };
    DMatrix::from_fn(CONFIGURATION_LEN, CONFIGURATION_LEN, |j, l| {
        let both: [f64; CONFIGURATION_LEN] = std::array::from_fn(|i| unit(j)[i] + unit(l)[i]);
        0.5 * (q(&both) - q(&unit(j)) - q(&unit(l)))
    })
}

/// The reduced problem of one sub-problem at one configuration.
struct Reduced {
    kind: RrrSubProblem,
    k: [f64; CONFIGURATION_LEN],
    coordinates: Vec<usize>,
    schur: DMatrix<f64>,
}

impl Reduced {
    fn new(kind: RrrSubProblem, k: &[f64; CONFIGURATION_LEN]) -> Option<Self> {
        let coordinates = constrained_coordinates(kind);
        let others: Vec<usize> = (0..CONFIGURATION_LEN)
            .filter(|j| !coordinates.contains(j))
            .collect();
        let m = metric_matrix(k);
        let pick = |rows: &[usize], columns: &[usize]| {
            DMatrix::from_fn(rows.len(), columns.len(), |a, b| m[(rows[a], columns[b])])
        };
        let myy = pick(&coordinates, &coordinates);
        let myz = pick(&coordinates, &others);
        let mzz = pick(&others, &others);
        let schur = if others.is_empty() {
            myy
        } else {
            let inverse = mzz.try_inverse()?;
            &myy - &myz * inverse * myz.transpose()
        };
        Some(Reduced {
            kind,
            k: *k,
            coordinates,
            schur,
        })
    }

    /// `C` with its gradient and Hessian in the reduced coordinates.
    fn constraint(&self, y: &[f64]) -> (f64, DVector<f64>, DMatrix<f64>) {
        let n = self.coordinates.len();
        let mut jets = self.k.map(Jet::constant);
        for (a, &j) in self.coordinates.iter().enumerate() {
            jets[j] = Jet::variable(y[a], a);
        }
        let c = self.kind.constraint(&jets);
        (
            c.value,
            DVector::from_fn(n, |a, _| c.gradient[a]),
            DMatrix::from_fn(n, n, |a, b| c.hessian_entry(a, b)),
        )
    }

    fn y_of_k(&self) -> DVector<f64> {
        DVector::from_fn(self.coordinates.len(), |a, _| self.k[self.coordinates[a]])
    }

    /// `D = √f(y)`.
    fn distance(&self, y: &DVector<f64>) -> f64 {
        let d = y - self.y_of_k();
        d.dot(&(&self.schur * &d)).max(0.0).sqrt()
    }

    /// From `y`: Gauss–Newton onto `C = 0`, then Newton on the KKT system. `Some(D)` at
    /// a converged feasible critical point.
    fn solve_from(&self, mut y: DVector<f64>, size: f64) -> Option<f64> {
        let n = self.coordinates.len();
        for _ in 0..50 {
            let (c, g, _) = self.constraint(y.as_slice());
            if c.abs() <= 1e-14 * size.powi(self.degree()) {
                break;
            }
            let gg = g.norm_squared();
            if gg <= 1e-300 {
                return None;
            }
            y -= &g * (c / gg);
        }
        let y_k = self.y_of_k();
        let (_, g, _) = self.constraint(y.as_slice());
        let grad_f = &self.schur * (&y - &y_k) * 2.0;
        let mut lambda = grad_f.dot(&g) / g.norm_squared().max(1e-300);
        for _ in 0..60 {
            let (c, g, h) = self.constraint(y.as_slice());
            let grad_f = &self.schur * (&y - &y_k) * 2.0;
            let residual = &grad_f - &g * lambda;
            let scale = size.powi(self.degree());
            if residual.norm() <= 1e-13 * size && c.abs() <= 1e-13 * scale {
                return Some(self.distance(&y));
            }
            let mut jac = DMatrix::zeros(n + 1, n + 1);
            jac.view_mut((0, 0), (n, n))
                .copy_from(&(&self.schur * 2.0 - &h * lambda));
            let mut rhs = DVector::zeros(n + 1);
            for a in 0..n {
                jac[(a, n)] = -g[a];
                jac[(n, a)] = g[a];
                rhs[a] = -residual[a];
            }
            rhs[n] = -c;
            let step = jac.lu().solve(&rhs)?;
            let length = step.rows(0, n).norm();
            let damping = if length > size { size / length } else { 1.0 };
            y += step.rows(0, n) * damping;
            lambda += step[n] * damping;
            if !y.iter().all(|v| v.is_finite()) {
                return None;
            }
        }
        None
    }

    fn degree(&self) -> i32 {
        match self.kind {
            RrrSubProblem::Parallel => 4,
            RrrSubProblem::Leg(_) => 2,
        }
    }
}

/// The smallest `D(K, K′)` over the critical points reached from `starts` seeded random
/// starts (module documentation), `None` if none converged. `MAX_VARIABLES` bounds the
/// reduced coordinates (12 for the parallel problem, 6 for a leg).
pub fn reference_distance(
    kind: RrrSubProblem,
    k: &[f64; CONFIGURATION_LEN],
    starts: usize,
    seed: u64,
) -> Option<f64> {
    let reduced = Reduced::new(kind, k)?;
    debug_assert!(reduced.coordinates.len() <= MAX_VARIABLES);
    let y_k = reduced.y_of_k();
    // Spread of the coordinates (noise scale), and their magnitude (tolerances: the
    // constraints are not centred).
    let spread_of_k = {
        let mean = y_k.mean();
        (y_k.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / y_k.len() as f64)
            .sqrt()
            .max(1e-300)
    };
    let size = y_k.amax().max(spread_of_k);
    let mut rng = random::seeded(seed);
    let mut best: Option<f64> = None;
    for start in 0..starts {
        let spread = [0.02, 0.1, 0.3, 1.0][start % 4] * spread_of_k;
        let y0 = DVector::from_fn(y_k.len(), |a, _| y_k[a] + spread * random::normal(&mut rng));
        if let Some(d) = reduced.solve_from(y0, size) {
            best = Some(best.map_or(d, |b: f64| b.min(d)));
        }
    }
    best
}
