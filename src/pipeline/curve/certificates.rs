//! Certificates of the (pose, sub-problem) results a curve keeps, computed once each
//! and only for the results that end up in the output.
//!
//! A tracked result carries its finite endpoints as a [`PendingCertificate`]; the
//! Krawczyk test ([`certification::certify_subproblem`]) runs when the pose is first
//! assembled, and the certificate is then shared by every later assembly of the same
//! result (the rescue pass re-assembles poses). Attempts that are replaced (a
//! pose-to-pose route that lost paths, a rescue that did not improve) and the
//! self-check's re-solved poses (unless they replace a result) are never certified.

use super::*;
use crate::problem::COORDINATE_NAMES;
use std::sync::{Arc, Mutex};

/// The endpoints of one (pose, sub-problem) result until certified, then the
/// certificate (shared between clones of the result).
#[derive(Clone, Debug)]
pub struct PendingCertificate(Arc<Mutex<Pending>>);

#[derive(Debug)]
enum Pending {
    /// Finite endpoints (normalised frame) at configuration `k` of the sub-problem's
    /// design.
    Endpoints(Vec<Vec<C64>>, [f64; 12]),
    Done(SubproblemCertificate),
}

impl PendingCertificate {
    /// A certificate to compute of `endpoints` at configuration `k`.
    pub fn new(endpoints: Vec<Vec<C64>>, k: [f64; 12]) -> Self {
        PendingCertificate(Arc::new(Mutex::new(Pending::Endpoints(endpoints, k))))
    }

    /// The certificate of the endpoints of sub-problem `seeded` against its generic
    /// count (computed on the first call).
    pub fn get(&self, stage: &SeedStage, seeded: &SeededProblem) -> SubproblemCertificate {
        let mut state = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Pending::Endpoints(endpoints, k) = &*state {
            let endpoints: Vec<Vec<C64>> = endpoints.iter().map(|x| seeded.to_affine(x)).collect();
            let certificate = certification::certify_subproblem(
                seeded.affine_problem(),
                seeded.id.metric,
                (&seeded.design, k),
                stage.normalization.frame(),
                &endpoints,
                seeded.at_seed.generic_count,
            );
            *state = Pending::Done(certificate);
        }
        match &*state {
            Pending::Done(certificate) => certificate.clone(),
            Pending::Endpoints(..) => unreachable!("certified just above"),
        }
    }
}

/// Moves the sub-problems' certificates of metric `name` into `result` and combines
/// them into the metric's ([`certification::combine`]).
pub(super) fn attach_certificates(
    name: &str,
    result: &mut MetricDistance,
    certificates: &mut BTreeMap<(String, String), SubproblemCertificate>,
) {
    for (subproblem, distance) in result.subproblems.iter_mut() {
        distance.certificate = certificates.remove(&(name.to_string(), subproblem.clone()));
    }
    let parts: Vec<(String, Option<&SubproblemCertificate>)> = result
        .subproblems
        .iter()
        .map(|(sub, d)| (sub.clone(), d.certificate.as_ref()))
        .collect();
    result.certificate = Some(certification::combine(
        &parts,
        result.distance,
        &result.subproblem,
    ));
}

/// The certificate of a sub-problem solved in closed form at the real configuration
/// `k` (user's labels, original frame): both critical points of
/// [`pedal::critical_points`], with the multiplier that makes them stationary
/// ([`with_multiplier`]), put to Krawczyk's test in the normalised frame against the
/// family's generic count. `None` where the closed form does not apply.
pub(super) fn closed_form_certificate(
    stage: &SeedStage,
    id: ProblemId,
    system: &ClosedFormSystem,
    k: &[f64; 12],
) -> Option<SubproblemCertificate> {
    let k_normalized = stage.normalization.apply(&to_real(k));
    let configurations = pedal::critical_points(id, &k_normalized.map(|v| v.re))?;
    let parameters = normalized_parameters(
        &system.problem,
        &system.design,
        &k_normalized,
        stage.normalization,
    );
    let solutions: Vec<Vec<C64>> = configurations
        .iter()
        .filter_map(|c| with_multiplier(&system.problem, c, &parameters))
        .collect();
    Some(certification::certify_subproblem(
        &system.problem,
        id.metric,
        (&system.design, k),
        stage.normalization.frame(),
        &solutions,
        system.generic_count,
    ))
}

/// The solution vector `(K′, λ)` of a Lagrange system with unknowns `a1x … b3y lambda`
/// (one constraint `C`, no rigid part) at the configuration `K′`: with
/// `F(K′, λ) = ∇D² − λ ∇C` on the coordinate rows, `∇C = F(K′, 0) − F(K′, 1)` and `λ`
/// the least-squares solution of `∇D² = λ ∇C`. `None` for systems of another shape
/// or where `∇C` vanishes.
pub(super) fn with_multiplier(
    problem: &LagrangeProblem,
    configuration: &[f64; 12],
    parameters: &[C64],
) -> Option<Vec<C64>> {
    let names = problem.variable_names();
    if names.len() != 13 || names[..12] != COORDINATE_NAMES[..] {
        return None;
    }
    let mut x: Vec<C64> = configuration.iter().map(|&v| C64::new(v, 0.0)).collect();
    x.push(C64::new(0.0, 0.0));
    let system = problem.evaluator();
    let mut work = vec![C64::new(0.0, 0.0); system.workspace_len()];
    let mut at_zero = vec![C64::new(0.0, 0.0); 13];
    let mut at_one = vec![C64::new(0.0, 0.0); 13];
    system.evaluate(&x, parameters, &mut work, &mut at_zero);
    x[12] = C64::new(1.0, 0.0);
    system.evaluate(&x, parameters, &mut work, &mut at_one);
    let (mut numerator, mut denominator) = (C64::new(0.0, 0.0), 0.0);
    for i in 0..12 {
        let gradient_c = at_zero[i] - at_one[i];
        numerator += gradient_c.conj() * at_zero[i];
        denominator += gradient_c.norm_sqr();
    }
    if denominator.is_nan() || denominator <= 0.0 {
        return None;
    }
    x[12] = numerator / denominator;
    Some(x)
}
