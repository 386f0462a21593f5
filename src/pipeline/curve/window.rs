//! The 3-RPR curve as an instance of the sweep engine ([`CurveFamily`], a
//! [`SweptFamily`]; the run is a [`Sweep`] of it), solved window by window: the seed
//! stage (and the self-check's) once, then
//! consecutive windows of [`CurveOptions::window_poses`] poses, each final before the
//! next starts, so that a caller can write a window's results and drop them. Memory is
//! bounded by one window, not by the number of poses; a run can start at any window
//! (to resume an interrupted one) and gets the same results there.

use super::*;
use crate::pipeline::sweep::{PoseRange, Sweep, SweepWindow, SweptFamily, merge_windows};

/// What a run knows after its seed stage, before any pose: the part of
/// [`CurveResult`] that does not depend on the poses.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurveHeader {
    /// The metrics computed, by name.
    pub metric_names: Vec<String>,
    /// Seed of the run.
    pub seed: u64,
    /// `[Re τ*, Im τ*]` of the seed (analytic motions).
    pub tau_star: Option<[f64; 2]>,
    /// Sub-problems not applicable to this design.
    pub not_applicable: Vec<String>,
    /// Paths lost at the seed (they affect every pose).
    pub seed_failures: Vec<PathFailure>,
    /// Paths tracked by the seed stage.
    pub seed_paths_tracked: usize,
    /// Number of poses of the run.
    pub poses: usize,
    /// Number of windows.
    pub windows: usize,
}

/// One window's final results.
pub type CurveWindow = SweepWindow<PoseResult>;

/// A 3-RPR curve as the sweep engine sees it ([`SweptFamily`]): the design, the
/// motion, the metrics, the options, the sampled poses and the start-solution
/// provider.
pub struct CurveFamily<'a> {
    design: &'a Design,
    motion: &'a Motion,
    metrics: &'a [Metric],
    options: &'a CurveOptions,
    samples: Vec<SampledPose>,
    provider: StartProvider<'a>,
}

/// A 3-RPR curve being computed window by window (see the module documentation).
pub type CurveRun<'a> = Sweep<CurveFamily<'a>>;

impl<'a> Sweep<CurveFamily<'a>> {
    /// Samples the motion and runs the seed stage (and the self-check's).
    pub fn new(
        (design, motion, metrics): (&'a Design, &'a Motion, &'a [Metric]),
        poses: usize,
        options: &'a CurveOptions,
        provider: StartProvider<'a>,
    ) -> Result<Self, PipelineError> {
        if options.window_poses == 0 {
            return Err(PipelineError::Option {
                field: "window_poses",
                reason: "must be at least 1".into(),
            });
        }
        let samples = sample_motion(motion, poses)?;
        let family = CurveFamily {
            design,
            motion,
            metrics,
            options,
            samples,
            provider,
        };
        Sweep::start(family, options.window_poses, options.self_check)
    }

    /// The run's pose-independent results.
    pub fn header(&self) -> CurveHeader {
        let (family, stage) = (self.family(), self.stage());
        CurveHeader {
            metric_names: family.metrics.iter().map(Metric::name).collect(),
            seed: family.options.seed,
            tau_star: match stage.seed.point {
                MotionPoint::Tau(t) => Some([t.re, t.im]),
                MotionPoint::Pose(_) => None,
            },
            not_applicable: stage.not_applicable.clone(),
            seed_failures: stage.failures.clone(),
            seed_paths_tracked: stage.paths_tracked,
            poses: family.samples.len(),
            windows: self.windows().len(),
        }
    }

    /// The sampled poses of the run.
    pub fn samples(&self) -> &[SampledPose] {
        &self.family().samples
    }
}

impl SweptFamily for CurveFamily<'_> {
    type Stage = SeedStage;
    type Check = (SeedStage, CurveOptions);
    type Pose = PoseResult;
    type Error = PipelineError;

    fn pose_count(&self) -> usize {
        self.samples.len()
    }

    fn seed_stage(&self) -> Result<SeedStage, PipelineError> {
        seed_stage(
            self.design,
            self.motion,
            self.metrics,
            self.options,
            self.provider,
        )
    }

    /// Every metric's stage, or only those of the metrics with a sub-problem whose
    /// seed count is below its generic count.
    fn check_stage(
        &self,
        stage: &SeedStage,
        all: bool,
    ) -> Result<Option<(SeedStage, CurveOptions)>, PipelineError> {
        let metrics: Vec<Metric> = self
            .metrics
            .iter()
            .copied()
            .filter(|&metric| {
                all || stage.problems.iter().any(|p| {
                    p.id.metric == metric && p.at_seed.start_count < p.at_seed.generic_count
                })
            })
            .collect();
        if metrics.is_empty() {
            return Ok(None);
        }
        let context = (self.design, self.motion, &metrics[..]);
        self_check::check_stage(context, self.options, self.provider, &stage.probes).map(Some)
    }

    /// The 3-RPR reconciliation of the seed counts, probing a disputed count at the
    /// first pose.
    fn reconcile(&self, stage: &mut SeedStage, (check, _): &mut (SeedStage, CurveOptions)) {
        let first = self.samples.first().map(|s| s.pose);
        let (design, options, provider) = (self.design, self.options, self.provider);
        let probe = |id: ProblemId| {
            first.and_then(|pose| local_seed::seed_count_at(design, pose, id, options, provider))
        };
        reconcile_seed_counts(stage, check, probe);
    }

    /// The poses' chains in parallel (stage 2), the rescue of the poses that lost
    /// paths from complete neighbours in the range (stage 3b), then from a seed stage
    /// at the pose itself (stage 3c).
    fn solve_poses(
        &self,
        stage: &SeedStage,
        PoseRange { range, on_pose }: PoseRange<'_, PoseResult>,
    ) -> Result<Vec<PoseResult>, PipelineError> {
        let (design, motion, metrics, options) =
            (self.design, self.motion, self.metrics, self.options);
        let context = SolveContext {
            stage,
            motion,
            options,
        };
        let samples = &self.samples;
        let blocks = chain_blocks(
            design,
            (motion, samples),
            (range.start, range.end),
            options.chain_length,
            stage.normalization,
        );
        let mut solved: Vec<(PoseResult, Vec<ProblemAtPose>)> = blocks
            .par_iter()
            .flat_map_iter(|chain| {
                solve_chain(
                    context,
                    (design, metrics),
                    samples,
                    (range.clone(), chain),
                    on_pose,
                )
            })
            .collect();
        // In pose order (a pose list's chains run in nearest-neighbour order).
        solved.sort_by_key(|(result, _)| result.index);
        let (mut results, mut work): (Vec<PoseResult>, Vec<Vec<ProblemAtPose>>) =
            solved.into_iter().unzip();
        let window_samples = &samples[range.clone()];
        let rescued = rescue_from_neighbours(context, (range.start, window_samples), &mut work);
        for local in rescued {
            let j = range.start + local;
            let k = design.configuration(samples[j].pose).to_array();
            let entries = work[local].iter().map(|p| p.entry.clone()).collect();
            results[local] = assemble_pose(stage, metrics, j, samples[j], &k, entries, options);
            on_pose(&results[local]);
        }
        drop(work);
        // Stage 3c: what is still lost, from a seed stage at the pose itself.
        let context = (design, metrics);
        let provider = self.provider;
        for local in
            local_seed::rescue_by_local_seed(context, samples, &mut results, options, provider)
        {
            on_pose(&results[local]);
        }
        Ok(results)
    }

    fn check_poses(
        &self,
        _stage: &SeedStage,
        (check_stage, check_options): &(SeedStage, CurveOptions),
        poses: &mut [PoseResult],
    ) -> Result<SelfCheck, PipelineError> {
        Ok(self_check::check_poses(
            (check_stage, check_options),
            (self.design, self.motion, self.metrics),
            &self.samples,
            poses,
        ))
    }

    fn paths_tracked(pose: &PoseResult) -> usize {
        pose.paths_tracked
    }
}

/// The whole curve of `header` from its windows in order.
pub fn collect_curve(header: CurveHeader, windows: Vec<CurveWindow>) -> CurveResult {
    let mut failures = header.seed_failures.clone();
    for window in &windows {
        failures.extend(window.poses.iter().flat_map(|r| r.failures.iter().cloned()));
    }
    let (poses, self_check, paths_tracked) = merge_windows(windows);
    CurveResult {
        metric_names: header.metric_names,
        seed: header.seed,
        tau_star: header.tau_star,
        not_applicable: header.not_applicable,
        poses,
        failures,
        paths_tracked: header.seed_paths_tracked + paths_tracked,
        self_check,
    }
}
