//! The 3-RRR's seed → pose route along its complexified motion, as the 3-RPR's
//! (docs/theory.md §8.3): the parameters follow the configuration `K(τ)` of the
//! analytic motion from the seed's complex `τ*` to the pose's real `τ` (a straight
//! segment in the τ-plane), plus the seed's random perturbation fading linearly to
//! zero, instead of the straight segment between the two configurations.
//!
//! The elbows of `K(τ)` come from inverse kinematics, `B = O + k d + g (d_y, −d_x)`
//! with `g² = b²/L² − k²` (see [`RrrDesign::configuration_complex_on_branch`]): at a
//! complex τ the sign of the square root is a choice, and the route must make it
//! continuously. The branch is followed on [`BRANCH_SAMPLES`] points of the segment,
//! each root taken nearest the linear extrapolation of the previous two; a path
//! point between samples takes the root nearest the interpolated one. The route is
//! only used where that continuation is unambiguous, starts at the seed's parameters
//! and ends at the pose's (the working modes of the pose: the continuation can end
//! on the other elbow posture when the segment winds around a leg singularity);
//! otherwise the caller takes the straight segment.
//!
//! [`RrrDesign::configuration_complex_on_branch`]: crate::mechanism::rrr::RrrDesign::configuration_complex_on_branch

use super::seed::RrrFrame;
use crate::C64;
use crate::homotopy::{ParameterPath, PolylinePath};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrTrajectory};

/// Points on the τ segment at which the square-root branch is followed.
pub const BRANCH_SAMPLES: usize = 64;

/// A root is taken only when it is at most this fraction of the distance of the other
/// root from the extrapolated one (otherwise the branch is ambiguous there).
const BRANCH_MARGIN: f64 = 0.5;

/// Largest difference (relative to `1 + ‖p‖∞`) between the route's ends and the seed's
/// and pose's parameters.
const END_TOLERANCE: f64 = 1e-10;

/// The route of the module documentation.
#[derive(Clone)]
pub(crate) struct MotionRoute<'a> {
    trajectory: &'a RrrTrajectory,
    frame: RrrFrame,
    /// `τ*` and the pose's `τ`.
    from: C64,
    to: C64,
    /// The seed's parameters minus the frame's `K(τ*)`: added with weight `1 − t`.
    offset: [C64; CONFIGURATION_LEN],
    /// The signed elbow heights `g` at `t = k / BRANCH_SAMPLES`.
    heights: Vec<[C64; 3]>,
}

impl<'a> MotionRoute<'a> {
    /// The route from the seed's parameters `source` at `τ*` (`tau_star`) to the pose's
    /// parameters `target` at `tau`, all in `frame`; `None` where the branch cannot be
    /// followed unambiguously or the continuation does not end at `target`.
    pub fn new(
        trajectory: &'a RrrTrajectory,
        frame: RrrFrame,
        (tau_star, source): (C64, &[C64]),
        (tau, target): (f64, &[C64]),
    ) -> Option<Self> {
        let motion = trajectory.motion();
        let design = trajectory.design();
        let to = C64::new(tau, 0.0);
        let pose_at = |s: f64| motion.pose_complex(tau_star + (to - tau_star) * s);
        // The seed's branch: σ times the principal root, as the seed configuration.
        let modes = trajectory.modes_at(tau_star.re);
        let sigma = std::array::from_fn(|leg| C64::new(modes[leg].sign(), 0.0));
        let zero = [C64::new(0.0, 0.0); 3];
        let (k0, _, first) = design.configuration_complex_on_branch(pose_at(0.0)?, zero, &sigma);
        let k0 = frame.apply_complex(&k0);
        let offset: [C64; CONFIGURATION_LEN] = std::array::from_fn(|i| source[i] - k0[i]);
        let mut heights = vec![first];
        for k in 1..=BRANCH_SAMPLES {
            let s = k as f64 / BRANCH_SAMPLES as f64;
            let reference: [C64; 3] = match heights.len() {
                1 => heights[0],
                n => std::array::from_fn(|leg| heights[n - 1][leg] * 2.0 - heights[n - 2][leg]),
            };
            let (_, _, g) = design.configuration_complex_on_branch(pose_at(s)?, zero, &reference);
            let clear = (0..3).all(|leg| {
                (g[leg] - reference[leg]).norm() <= BRANCH_MARGIN * (g[leg] + reference[leg]).norm()
            });
            if !clear {
                return None;
            }
            heights.push(g);
        }
        let route = MotionRoute {
            trajectory,
            frame,
            from: tau_star,
            to,
            offset,
            heights,
        };
        let close = |a: &[C64], b: &[C64]| {
            let scale = 1.0 + b.iter().fold(0.0f64, |m, v| m.max(v.norm()));
            a.iter()
                .zip(b)
                .all(|(x, y)| (x - y).norm() <= END_TOLERANCE * scale)
        };
        let mut p = vec![C64::new(0.0, 0.0); CONFIGURATION_LEN];
        route.point(C64::new(1.0, 0.0), &mut p);
        close(&p, target).then_some(route)
    }

    /// The heights interpolated at `Re t` (clamped to the segment).
    fn reference(&self, t: C64) -> [C64; 3] {
        let u = t.re.clamp(0.0, 1.0) * BRANCH_SAMPLES as f64;
        let k = (u.floor() as usize).min(BRANCH_SAMPLES - 1);
        let w = u - k as f64;
        let (a, b) = (&self.heights[k], &self.heights[k + 1]);
        std::array::from_fn(|leg| a[leg] * (1.0 - w) + b[leg] * w)
    }
}

impl ParameterPath for MotionRoute<'_> {
    fn len(&self) -> usize {
        CONFIGURATION_LEN
    }

    fn point(&self, t: C64, p: &mut [C64]) {
        let mut dp = [C64::new(0.0, 0.0); CONFIGURATION_LEN];
        self.point_and_velocity(t, p, &mut dp);
    }

    /// `p(t) = frame(K(τ(t))) + (1 − t)·offset`, `τ(t) = τ* + t (τ − τ*)`, and
    /// `p′(t) = K′(τ) (τ − τ*) / s − offset`.
    fn point_and_velocity(&self, t: C64, p: &mut [C64], dp: &mut [C64]) {
        let motion = self.trajectory.motion();
        let dtau = self.to - self.from;
        let tau = self.from + dtau * t;
        let (Some(pose), Some(velocity)) = (
            motion.pose_complex(tau),
            motion.pose_derivative_complex(tau),
        ) else {
            p.fill(C64::new(f64::NAN, f64::NAN));
            dp.fill(C64::new(f64::NAN, f64::NAN));
            return;
        };
        let velocity = velocity.map(|v| v * dtau);
        let design = self.trajectory.design();
        let (k, dk, _) = design.configuration_complex_on_branch(pose, velocity, &self.reference(t));
        let k = self.frame.apply_complex(&k);
        let fade = C64::new(1.0, 0.0) - t;
        let scale = self.frame.scale();
        for i in 0..CONFIGURATION_LEN {
            p[i] = k[i] + self.offset[i] * fade;
            dp[i] = dk[i] / scale - self.offset[i];
        }
    }
}

/// A seed → pose route: along the motion, or a polyline (the straight segment, or a
/// detour).
#[derive(Clone)]
pub(crate) enum SeedRoute<'a> {
    /// Along the complexified motion ([`MotionRoute`]).
    Motion(Box<MotionRoute<'a>>),
    /// Straight segments between parameter points.
    Polyline(PolylinePath),
}

impl SeedRoute<'_> {
    fn route(&self) -> &dyn ParameterPath {
        match self {
            SeedRoute::Motion(route) => route.as_ref(),
            SeedRoute::Polyline(route) => route,
        }
    }
}

impl ParameterPath for SeedRoute<'_> {
    fn len(&self) -> usize {
        self.route().len()
    }

    fn point(&self, t: C64, p: &mut [C64]) {
        self.route().point(t, p);
    }

    fn point_and_velocity(&self, t: C64, p: &mut [C64], dp: &mut [C64]) {
        self.route().point_and_velocity(t, p, dp);
    }

    fn breakpoints(&self) -> &[f64] {
        self.route().breakpoints()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::rrr::example_trajectory;
    use crate::pipeline::rrr::curve::{configuration_at, target_parameters};
    use crate::pipeline::rrr::seed::trajectory_frame;

    /// The route starts at the seed's parameters, ends at the pose's, and its velocity
    /// is the derivative of its points (central differences in complex t).
    #[test]
    fn the_route_joins_seed_and_pose_and_its_velocity_is_its_derivative() {
        let trajectory = example_trajectory();
        let frame = trajectory_frame(&trajectory).unwrap();
        let tau_star = C64::new(1.3, 0.4);
        let k_star = frame.apply_complex(&trajectory.configuration_complex(tau_star).unwrap());
        let source: Vec<C64> = k_star
            .iter()
            .enumerate()
            .map(|(i, v)| v + C64::new(0.01 * i as f64, -0.02))
            .collect();
        let (_, k) = configuration_at(&trajectory, 0, 0.9).unwrap();
        let target = target_parameters(&frame, &k.to_array());
        let route = MotionRoute::new(&trajectory, frame, (tau_star, &source), (0.9, &target))
            .expect("an unambiguous branch");
        let gap = |a: &[C64], b: &[C64]| {
            let pairs = a.iter().zip(b);
            pairs.fold(0.0f64, |m, (x, y)| m.max((x - y).norm()))
        };
        let mut p = vec![C64::new(0.0, 0.0); CONFIGURATION_LEN];
        route.point(C64::new(0.0, 0.0), &mut p);
        assert!(gap(&p, &source) < 1e-13, "{}", gap(&p, &source));
        route.point(C64::new(1.0, 0.0), &mut p);
        assert!(gap(&p, &target) < 1e-12, "{}", gap(&p, &target));
        let (mut dp, mut plus, mut minus) = (p.clone(), p.clone(), p.clone());
        for t in [C64::new(0.3, 0.0), C64::new(0.71, 0.05)] {
            route.point_and_velocity(t, &mut p, &mut dp);
            let h = 1e-6;
            route.point(t + h, &mut plus);
            route.point(t - h, &mut minus);
            for i in 0..CONFIGURATION_LEN {
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                assert!(
                    (fd - dp[i]).norm() < 1e-6 * (1.0 + dp[i].norm()),
                    "{i}: {fd} vs {}",
                    dp[i]
                );
            }
        }
    }
}
