//! A curve solved window by window: the seed stage (and the self-check's) once, then
//! consecutive windows of [`CurveOptions::window_poses`] poses, each final before the
//! next starts, so that a caller can write a window's results and drop them. Memory is
//! bounded by one window, not by the number of poses; a run can start at any window
//! (to resume an interrupted one) and gets the same results there.

use super::*;

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
#[derive(Clone, Debug, PartialEq)]
pub struct CurveWindow {
    /// Index of the window.
    pub index: usize,
    /// Its poses, in order.
    pub poses: Vec<PoseResult>,
    /// Critical points continued at its poses (its share of
    /// [`CurveResult::paths_tracked`]).
    pub paths_tracked: usize,
    /// Its self-check (first, last and each metric's closest pose of the window).
    pub self_check: Option<SelfCheck>,
}

/// The pose index ranges `[first, last)` of the windows of `n` poses, `window_poses`
/// each (the last one shorter).
pub fn window_ranges(n: usize, window_poses: usize) -> Vec<std::ops::Range<usize>> {
    let size = window_poses.max(1);
    (0..n.div_ceil(size))
        .map(|w| w * size..((w + 1) * size).min(n))
        .collect()
}

/// A curve being computed window by window (see the module documentation).
pub struct CurveRun<'a> {
    design: &'a Design,
    motion: &'a Motion,
    metrics: &'a [Metric],
    options: &'a CurveOptions,
    samples: Vec<SampledPose>,
    windows: Vec<std::ops::Range<usize>>,
    stage: SeedStage,
    check: Option<(SeedStage, CurveOptions)>,
    provider: StartProvider<'a>,
}

impl<'a> CurveRun<'a> {
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
        let mut stage = seed_stage(design, motion, metrics, options, provider)?;
        let first = samples.first().map(|s| s.pose);
        let probe = |id: ProblemId| {
            first.and_then(|pose| local_seed::seed_count_at(design, pose, id, options, provider))
        };
        let check = if options.self_check {
            let context = (design, motion, metrics);
            let (mut check_stage, check_options) =
                self_check::check_stage(context, options, provider, &stage.probes)?;
            reconcile_seed_counts(&mut stage, &mut check_stage, probe);
            Some((check_stage, check_options))
        } else {
            // Without the self-check a count below the generic one is still checked by
            // the self-check's independent seed stage, for those metrics alone: two
            // seed points of one stage can agree on too few (see
            // `reconcile_seed_counts`), and nothing else would notice.
            let short: Vec<Metric> = metrics
                .iter()
                .copied()
                .filter(|&metric| {
                    stage.problems.iter().any(|p| {
                        p.id.metric == metric && p.at_seed.start_count < p.at_seed.generic_count
                    })
                })
                .collect();
            if !short.is_empty() {
                let context = (design, motion, &short[..]);
                let (mut count_stage, _) =
                    self_check::check_stage(context, options, provider, &stage.probes)?;
                reconcile_seed_counts(&mut stage, &mut count_stage, probe);
            }
            None
        };
        Ok(CurveRun {
            design,
            motion,
            metrics,
            options,
            windows: window_ranges(samples.len(), options.window_poses),
            samples,
            stage,
            check,
            provider,
        })
    }

    /// The run's pose-independent results.
    pub fn header(&self) -> CurveHeader {
        CurveHeader {
            metric_names: self.metrics.iter().map(Metric::name).collect(),
            seed: self.options.seed,
            tau_star: match self.stage.seed.point {
                MotionPoint::Tau(t) => Some([t.re, t.im]),
                MotionPoint::Pose(_) => None,
            },
            not_applicable: self.stage.not_applicable.clone(),
            seed_failures: self.stage.failures.clone(),
            seed_paths_tracked: self.stage.paths_tracked,
            poses: self.samples.len(),
            windows: self.windows.len(),
        }
    }

    /// The sampled poses of the run.
    pub fn samples(&self) -> &[SampledPose] {
        &self.samples
    }

    /// The pose range of window `index`.
    pub fn window_range(&self, index: usize) -> std::ops::Range<usize> {
        self.windows[index].clone()
    }

    /// Solves window `index` completely: its chains in parallel (stage 2), the rescue
    /// of its poses that lost paths from complete neighbours in the window (stage 3b),
    /// then from a seed stage at the pose itself (stage 3c), its self-check. `on_pose`
    /// is called as poses complete (progress).
    pub fn solve_window(
        &self,
        index: usize,
        on_pose: &(dyn Fn(&PoseResult) + Sync),
    ) -> CurveWindow {
        let range = self.windows[index].clone();
        let (stage, design, motion, metrics, options) = (
            &self.stage,
            self.design,
            self.motion,
            self.metrics,
            self.options,
        );
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
        let self_check = self.check.as_ref().map(|(check_stage, check_options)| {
            self_check::check_poses(
                (check_stage, check_options),
                (design, motion, metrics),
                samples,
                &mut results,
            )
        });
        CurveWindow {
            index,
            paths_tracked: results.iter().map(|r| r.paths_tracked).sum(),
            poses: results,
            self_check,
        }
    }
}

/// The whole curve of `header` from its windows in order.
pub fn collect_curve(header: CurveHeader, windows: Vec<CurveWindow>) -> CurveResult {
    let mut failures = header.seed_failures.clone();
    let mut paths_tracked = header.seed_paths_tracked;
    let mut self_check: Option<SelfCheck> = None;
    let mut poses = Vec::with_capacity(header.poses);
    for window in windows {
        paths_tracked += window.paths_tracked;
        if let Some(check) = &window.self_check {
            match &mut self_check {
                Some(total) => total.merge(check),
                None => self_check = Some(check.clone()),
            }
        }
        failures.extend(window.poses.iter().flat_map(|r| r.failures.iter().cloned()));
        poses.extend(window.poses);
    }
    CurveResult {
        metric_names: header.metric_names,
        seed: header.seed,
        tau_star: header.tau_star,
        not_applicable: header.not_applicable,
        poses,
        failures,
        paths_tracked,
        self_check,
    }
}
