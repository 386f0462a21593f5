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
            let certificate = certification::certify_subproblem(
                &seeded.problem,
                seeded.id.metric,
                (&seeded.design, k),
                stage.normalization.frame(),
                endpoints,
                seeded.generic_count,
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
