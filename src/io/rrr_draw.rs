//! Drawings of a 3-RRR configuration and its closest singular configurations, as SVG
//! text: the base joints `O_i`, elbows `B_i` and platform joints `C_i` of `K`, the base
//! and platform triangles, the proximal links `O_i B_i` and distal links `B_i C_i`, and
//! per singularity kind the closest singular configuration `K′` of the all-deformable
//! metric overlaid (one colour and dash pattern per kind, `D(K, K′)` in the legend).
//!
//! A parallel-singular `K′` has concurrent or parallel distal-link lines `B_i′C_i′`
//! (`det[C_i − B_i | B_i × C_i] = 0`, Gosselin and Angeles, "Singularity analysis of
//! closed-loop kinematic chains", 1990): their meeting point is marked, or an arrow
//! shows their common direction. A leg-`i`-singular `K′` has `O_i′, B_i′, C_i′` on one
//! line (the leg stretched out or folded back): that line is drawn.
//!
//! Both axes use one scale, in the design's length unit. Elements carry classes for
//! tests and styling: `g#K`, `g.closest[data-metric]` (`parallel`, `leg1`, `leg2`,
//! `leg3`), `polygon.base`, `polygon.platform`, `line.leg.proximal`, `line.leg.distal`,
//! `circle.meet`, `path.meet-direction`, `line.degenerate-line`, `g#legend`.

use super::canvas::{
    Canvas, Extent, Legend, PointLabels, centroid, collinear_line, guide_attributes, joint_circle,
    leg_line, norm, sub, svg_document,
};
use super::leg_lines::{LegMeeting, leg_meeting, mark_meeting};
use super::scene::{
    K_LEGS, K_PLATFORM, MechanismScene, draw_skeleton, joint, open_overlay, scene_body,
};
use super::svg::{SeriesStyle, escape, px, series_style, short};
use crate::mechanism::rrr::{CONFIGURATION_LEN, RrrConfiguration};
use crate::pipeline::rrr::curve::RrrPoseResult;
use std::fmt::Write;

/// The sub-problems in drawing order, with their legend names.
pub const RRR_SUBPROBLEMS: [(&str, &str); 4] = [
    ("parallel", "parallel singularity"),
    ("leg1", "leg 1 singularity"),
    ("leg2", "leg 2 singularity"),
    ("leg3", "leg 3 singularity"),
];

/// Style of a 3-RRR sub-problem (`parallel`, `leg1`, …) by its place in
/// [`RRR_SUBPROBLEMS`], the same in the drawing and the report's chart.
pub fn rrr_style(name: &str) -> SeriesStyle {
    series_style(
        RRR_SUBPROBLEMS
            .iter()
            .position(|(n, _)| *n == name)
            .unwrap_or(RRR_SUBPROBLEMS.len()),
    )
}

/// One sub-problem's closest singular configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct RrrOverlay {
    /// Sub-problem (`parallel`, `leg1`, `leg2`, `leg3`).
    pub subproblem: String,
    /// `D(K, K′)`.
    pub distance: f64,
    /// `K′`, the 18 coordinates `O1x … C3y`.
    pub closest: [f64; CONFIGURATION_LEN],
}

/// What one 3-RRR drawing shows.
#[derive(Clone, Debug, PartialEq)]
pub struct RrrScene {
    /// Title line above the drawing.
    pub title: String,
    /// `K`, the 18 coordinates `O1x … C3y`.
    pub configuration: [f64; CONFIGURATION_LEN],
    /// One overlay per sub-problem with a result.
    pub overlays: Vec<RrrOverlay>,
    /// The sub-problem nearest to `K` (marked in the legend).
    pub nearest: Option<String>,
    /// Name of the length unit for the axes and the legend.
    pub length_unit: String,
}

impl RrrScene {
    /// The scene of one computed pose: `K` (the configuration at the pose) and the
    /// closest configuration of every sub-problem that has one.
    pub fn of_pose(
        configuration: &RrrConfiguration,
        result: &RrrPoseResult,
        length_unit: &str,
    ) -> RrrScene {
        let overlays = RRR_SUBPROBLEMS
            .iter()
            .filter_map(|(name, _)| {
                let sub = result.subproblems.get(*name)?;
                Some(RrrOverlay {
                    subproblem: name.to_string(),
                    distance: sub.distance?,
                    closest: sub.closest?,
                })
            })
            .collect();
        let [x, y, phi] = result.pose;
        RrrScene {
            title: format!(
                "3-RRR at x = {}, y = {}, φ = {} rad; working modes {}",
                short(x),
                short(y),
                short(phi),
                result
                    .working_modes
                    .iter()
                    .map(|m| if *m < 0 { "−" } else { "+" })
                    .collect::<Vec<_>>()
                    .join("")
            ),
            configuration: configuration.to_array(),
            overlays,
            nearest: result.nearest.clone(),
            length_unit: length_unit.into(),
        }
    }
}

/// The 12-vector `(B_1, B_2, B_3, C_1, C_2, C_3)` of the distal links, in the layout
/// of [`leg_meeting`].
fn distal_links(k: &[f64; CONFIGURATION_LEN]) -> [f64; 12] {
    std::array::from_fn(|j| k[6 + j])
}

fn configuration_extent(k: &[f64; CONFIGURATION_LEN]) -> Extent {
    Extent::of_points((0..9).map(|j| joint(k, j)))
}

/// Joints of an 18-vector: `O_1 … O_3` = 0…2, `B_i` = 3…5, `C_i` = 6…8.
impl MechanismScene for RrrScene {
    fn labels(&self) -> (&str, &str) {
        (&self.title, &self.length_unit)
    }

    fn joints_extent(&self) -> Extent {
        self.overlays
            .iter()
            .map(|o| configuration_extent(&o.closest))
            .fold(configuration_extent(&self.configuration), |a, b| {
                a.union(&b)
            })
    }

    fn leg_meetings(&self) -> Vec<LegMeeting> {
        self.overlays
            .iter()
            .filter(|o| o.subproblem == "parallel")
            .map(|o| leg_meeting(&distal_links(&o.closest)))
            .collect()
    }

    fn draw_configuration(&self, out: &mut String, canvas: &Canvas) {
        let k = &self.configuration;
        out.push_str("<g id=\"K\" class=\"configuration\">\n");
        let base = r##" fill="#eeeeee" stroke="#999" stroke-width="1.5" stroke-dasharray="6 4""##;
        draw_skeleton(out, canvas, k, 6, links, [base, K_PLATFORM, K_LEGS]);
        let pixel = |p: [f64; 2]| canvas.pixel(p);
        let centre = |first: usize| {
            pixel(centroid(
                &(first..first + 3).map(|j| joint(k, j)).collect::<Vec<_>>(),
            ))
        };
        let mut labels = PointLabels::default();
        for i in 0..3 {
            let (o, b, c) = (
                pixel(joint(k, i)),
                pixel(joint(k, 3 + i)),
                pixel(joint(k, 6 + i)),
            );
            let _ = writeln!(
                out,
                r##"<rect class="joint base-joint" x="{}" y="{}" width="10" height="10" fill="#fff" stroke="#222" stroke-width="1.5"/>"##,
                px(o[0] - 5.0),
                px(o[1] - 5.0)
            );
            for p in [b, c] {
                joint_circle(out, "joint", p);
            }
            // O_i and C_i labels outside their triangles, B_i's beside its elbow, away
            // from the midpoint of O_i and C_i.
            let class = "joint-label";
            labels.place(out, class, (o, sub(o, centre(0))), &format!("O{}", i + 1));
            labels.place(out, class, (c, sub(c, centre(6))), &format!("C{}", i + 1));
            let mid = [0.5 * (o[0] + c[0]), 0.5 * (o[1] + c[1])];
            let away = sub(b, mid);
            let away = if norm(away) > 1.0 {
                away
            } else {
                [-(c[1] - o[1]), c[0] - o[0]]
            };
            labels.place(out, class, (b, away), &format!("B{}", i + 1));
        }
        out.push_str("</g>\n");
    }

    fn draw_overlays(&self, out: &mut String, canvas: &Canvas, near: &Extent) {
        for overlay in &self.overlays {
            let style = rrr_style(&overlay.subproblem);
            let k = &overlay.closest;
            let data = format!(r#"data-metric="{}""#, escape(&overlay.subproblem));
            open_overlay(out, canvas, k, 6, links, style, &data);
            let thin = guide_attributes(style);
            if overlay.subproblem == "parallel" {
                let platform: Vec<[f64; 2]> = (6..9).map(|j| joint(k, j)).collect();
                let meeting = leg_meeting(&distal_links(k));
                mark_meeting(out, canvas, meeting, &platform, near, (style, &thin));
            } else if let Some(i) = overlay
                .subproblem
                .trim_start_matches("leg")
                .parse::<usize>()
                .ok()
                .filter(|i| (1..=3).contains(i))
            {
                let leg = [joint(k, i - 1), joint(k, 2 + i), joint(k, 5 + i)];
                collinear_line(out, canvas, &leg, &thin);
            }
            out.push_str("</g>\n");
        }
    }

    fn svg(&self, extent: &Extent) -> String {
        let canvas = Canvas::new(extent);
        let mut body = scene_body(self, &canvas);
        legend(&mut body, &canvas, self);
        svg_document("rrr-drawing", canvas.width, canvas.height, &body)
    }
}

fn links(out: &mut String, canvas: &Canvas, k: &[f64; CONFIGURATION_LEN], attributes: &str) {
    for i in 0..3 {
        for (kind, from, to) in [("proximal", i, 3 + i), ("distal", 3 + i, 6 + i)] {
            let ends = (joint(k, from), joint(k, to));
            leg_line(out, canvas, &format!("leg {kind}"), i + 1, ends, attributes);
        }
    }
}

/// The note on a `K′` that the legend prints under its distance.
fn overlay_note(overlay: &RrrOverlay) -> String {
    match overlay.subproblem.as_str() {
        "parallel" => leg_meeting(&distal_links(&overlay.closest))
            .describe("distal-link lines B′C′")
            .unwrap_or_else(|| "distal-link lines undefined".into()),
        leg => {
            let i = leg.trim_start_matches("leg");
            format!("O{i}′, B{i}′, C{i}′ collinear (leg {i} stretched or folded)")
        }
    }
}

/// Writes the legend right of the drawing.
fn legend(out: &mut String, canvas: &Canvas, scene: &RrrScene) {
    let mut legend = Legend::open(out, canvas);
    legend.configuration(20.0);
    legend.note(
        "□ base joints O, ○ elbows B and platform joints C",
        r#" font-size="12""#,
        22.0,
    );
    if !scene.overlays.is_empty() {
        let unit = &scene.length_unit;
        legend.note("closest singular K′ of each kind (every joint", "", 17.0);
        legend.note(&format!("may move); D(K, K′) in {unit},"), "", 17.0);
        legend.note("D² = mean squared distance of the 8 bodies:", "", 24.0);
    }
    for overlay in &scene.overlays {
        let style = rrr_style(&overlay.subproblem);
        let name = RRR_SUBPROBLEMS
            .iter()
            .find(|(n, _)| *n == overlay.subproblem)
            .map_or(overlay.subproblem.as_str(), |(_, title)| title);
        let nearest = if scene.nearest.as_deref() == Some(overlay.subproblem.as_str()) {
            " (nearest)"
        } else {
            ""
        };
        let note = overlay_note(overlay);
        legend.closest(
            &overlay.subproblem,
            name,
            style,
            (overlay.distance, nearest),
            &note,
        );
    }
    legend.close();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::scene::scene_extent;

    /// A 3-RRR with legs along the axes; leg 1's K′ stretched out along y.
    fn scene() -> RrrScene {
        let k = [
            0.0, 1.0, -0.87, -0.5, 0.87, -0.5, 0.5, 0.6, -0.7, 0.3, 0.2, -0.8, 0.0, 0.4, -0.35,
            -0.2, 0.35, -0.2,
        ];
        let mut stretched = k;
        stretched[6..8].copy_from_slice(&[0.0, 0.7]);
        // Distal links through (0, 0): B_i = 2 C_i.
        let mut concurrent = k;
        for i in 0..3 {
            concurrent[6 + 2 * i] = 2.0 * k[12 + 2 * i];
            concurrent[7 + 2 * i] = 2.0 * k[13 + 2 * i];
        }
        RrrScene {
            title: "test".into(),
            configuration: k,
            overlays: vec![
                RrrOverlay {
                    subproblem: "parallel".into(),
                    distance: 0.5,
                    closest: concurrent,
                },
                RrrOverlay {
                    subproblem: "leg1".into(),
                    distance: 0.2,
                    closest: stretched,
                },
            ],
            nearest: Some("leg1".into()),
            length_unit: "m".into(),
        }
    }

    #[test]
    fn drawing_has_six_links_two_triangles_and_one_overlay_per_kind() {
        let scene = scene();
        let svg = scene.svg(&scene_extent(&scene));
        assert_eq!(svg.matches(r#"<g id="K""#).count(), 1);
        assert_eq!(svg.matches(r#"class="leg proximal""#).count(), 3 * 3);
        assert_eq!(svg.matches(r#"class="leg distal""#).count(), 3 * 3);
        assert_eq!(svg.matches(r#"<polygon class="platform""#).count(), 3);
        assert_eq!(svg.matches(r#"<polygon class="base""#).count(), 3);
        assert_eq!(svg.matches(r#"<g class="closest""#).count(), 2);
        assert_eq!(svg.matches(r#"<circle class="meet""#).count(), 1);
        assert_eq!(svg.matches(r#"class="degenerate-line""#).count(), 1);
        assert!(svg.contains("meet at (0.000, 0.000)"), "{svg}");
        assert!(svg.contains("D = 0.2000 (nearest)"), "{svg}");
        for label in ["O1", "O2", "O3", "B1", "B2", "B3", "C1", "C2", "C3"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label}");
        }
    }
}
