//! Drawings of a 3-RPR configuration and its closest singular configurations, as SVG
//! text: the base triangle `a_1 a_2 a_3`, the platform triangle `b_1 b_2 b_3` and the
//! three legs `a_i b_i` of `K`, and per metric the closest singular configuration `K′`
//! overlaid (one colour and dash pattern per metric, the distance `D(K, K′)` in the
//! legend).
//!
//! A `K′` of the singularity sub-problem has concurrent or parallel leg lines
//! (`S(K′) = det[b_i − a_i | a_i × b_i] = 0`, Hunt, "Kinematic geometry of mechanisms",
//! 1978): the meeting point is marked, or an arrow shows the common direction. A `K′`
//! of a collinear sub-problem is drawn with the line its anchors lie on, one of a
//! coincident sub-problem with the point its anchors collapse to.
//!
//! Both axes use one scale (a drawing, not a chart), in the design's length unit.
//! Elements carry classes for tests and styling: `g#K`, `g.closest[data-metric]`,
//! `polygon.base`, `polygon.platform`, `line.leg`, `circle.meet`, `path.meet-direction`,
//! `line.degenerate-line`, `circle.degenerate-point`, `g#legend`.

pub use super::canvas::Extent;
use super::canvas::{
    Canvas, Legend, PointLabels, centroid, collinear_line, guide_attributes, joint_circle,
    leg_line, norm, sub, svg_document,
};
use super::leg_lines::mark_meeting;
pub use super::leg_lines::{LegMeeting, leg_meeting};
use super::scene::{
    K_LEGS, K_PLATFORM, MechanismScene, draw_skeleton, joint as anchor, open_overlay, scene_body,
};
use super::svg::{SeriesStyle, escape, metric_style, number, px, short};
use crate::mechanism::rpr::{Design, Pose};
use crate::pipeline::curve::PoseResult;
use std::fmt::Write;

/// One metric's closest singular configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosestOverlay {
    /// Metric name (`plate/plate`, …); chooses the colour and dash pattern.
    pub metric: String,
    /// `D(K, K′)`.
    pub distance: f64,
    /// Sub-problem attaining it (`singularity`, `collinear-platform`, …).
    pub subproblem: String,
    /// `K′ = (a_1′, a_2′, a_3′, b_1′, b_2′, b_3′)`, twelve coordinates.
    pub closest: [f64; 12],
}

/// What one drawing shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Title line above the drawing.
    pub title: String,
    /// The configuration `K` at the pose, twelve coordinates.
    pub configuration: [f64; 12],
    /// One overlay per metric.
    pub overlays: Vec<ClosestOverlay>,
    /// Name of the length unit for the axes and the legend.
    pub length_unit: String,
}

impl Scene {
    /// The scene of one computed pose: `K` of `design` at the pose and the closest
    /// configuration of each metric in `metrics` that has a result (in that order).
    pub fn of_pose(
        design: &Design,
        result: &PoseResult,
        metrics: &[String],
        length_unit: &str,
    ) -> Scene {
        let [x, y, phi] = result.pose;
        let configuration = design.configuration(Pose::new(x, y, phi)).to_array();
        let overlays = metrics
            .iter()
            .filter_map(|name| {
                result.metrics.get(name).map(|m| ClosestOverlay {
                    metric: name.clone(),
                    distance: m.distance,
                    subproblem: m.subproblem.clone(),
                    closest: m.closest,
                })
            })
            .collect();
        Scene {
            title: format!(
                "3-RPR at x = {}, y = {}, φ = {} rad; S(K) = {}",
                short(x),
                short(y),
                short(phi),
                short(result.singularity)
            ),
            configuration,
            overlays,
            length_unit: length_unit.into(),
        }
    }
}

fn configuration_extent(k: &[f64; 12]) -> Extent {
    Extent::of_points((0..6).map(|j| anchor(k, j)))
}

impl MechanismScene for Scene {
    fn labels(&self) -> (&str, &str) {
        (&self.title, &self.length_unit)
    }

    fn joints_extent(&self) -> Extent {
        let mut e = configuration_extent(&self.configuration);
        for overlay in &self.overlays {
            e = e.union(&configuration_extent(&overlay.closest));
        }
        e
    }

    fn leg_meetings(&self) -> Vec<LegMeeting> {
        self.overlays
            .iter()
            .filter(|o| o.subproblem == "singularity")
            .map(|o| leg_meeting(&o.closest))
            .collect()
    }

    fn draw_configuration(&self, out: &mut String, canvas: &Canvas) {
        let k = &self.configuration;
        out.push_str("<g id=\"K\" class=\"configuration\">\n");
        let base = r##" fill="#e8e8e8" stroke="#222" stroke-width="2.5""##;
        draw_skeleton(out, canvas, k, 3, legs, [base, K_PLATFORM, K_LEGS]);
        let mut labels = PointLabels::default();
        for (first, letter) in [(0, 'a'), (3, 'b')] {
            let points: Vec<[f64; 2]> = (first..first + 3).map(|j| anchor(k, j)).collect();
            let c = canvas.pixel(centroid(&points));
            for (i, p) in points.iter().enumerate() {
                let p = canvas.pixel(*p);
                joint_circle(out, "anchor", p);
                // The label sits outside the triangle, 18 px from the anchor.
                let text = format!("{letter}{}", i + 1);
                labels.place(out, "anchor-label", (p, sub(p, c)), &text);
            }
        }
        out.push_str("</g>\n");
    }

    fn draw_overlays(&self, out: &mut String, canvas: &Canvas, near: &Extent) {
        for overlay in &self.overlays {
            let style = metric_style(&overlay.metric);
            let k = &overlay.closest;
            let data = format!(
                r#"data-metric="{}" data-subproblem="{}""#,
                escape(&overlay.metric),
                escape(&overlay.subproblem)
            );
            open_overlay(out, canvas, k, 3, legs, style, &data);
            let thin = guide_attributes(style);
            let points =
                |range: std::ops::Range<usize>| range.map(|j| anchor(k, j)).collect::<Vec<_>>();
            match overlay.subproblem.as_str() {
                "singularity" => mark_meeting(
                    out,
                    canvas,
                    leg_meeting(k),
                    &points(3..6),
                    near,
                    (style, &thin),
                ),
                "collinear-platform" => collinear_line(out, canvas, &points(3..6), &thin),
                "collinear-base" => collinear_line(out, canvas, &points(0..3), &thin),
                "all-collinear" => collinear_line(out, canvas, &points(0..6), &thin),
                "coincident-platform" => {
                    degenerate_point(out, canvas, centroid(&points(3..6)), style)
                }
                "coincident-base" => degenerate_point(out, canvas, centroid(&points(0..3)), style),
                _ => {}
            }
            out.push_str("</g>\n");
        }
    }

    /// With a zoom inset on the platform region where the drawing shows it too small.
    fn svg(&self, extent: &Extent) -> String {
        let canvas = Canvas::new(extent);
        let mut body = scene_body(self, &canvas);
        let legend_bottom = legend(&mut body, &canvas, self);
        let mut height = canvas.height;
        let area = (
            canvas.left + canvas.plot_width + 24.0,
            legend_bottom + 34.0,
            320.0,
            250.0,
        );
        let zoom = zoom_canvas(&platform_extent(self), area);
        if zoom.scale >= ZOOM_AT_LEAST * canvas.scale {
            height = height.max(area.1 + area.3 + 16.0);
            zoom_inset(&mut body, self, &zoom, canvas.scale);
        }
        svg_document("rpr-drawing", canvas.width, height, &body)
    }
}

fn legs(out: &mut String, canvas: &Canvas, k: &[f64; 12], attributes: &str) {
    for i in 0..3 {
        let ends = (anchor(k, i), anchor(k, 3 + i));
        leg_line(out, canvas, "leg", i + 1, ends, attributes);
    }
}

/// The note on a `K′` that the legend prints under its distance.
fn overlay_note(overlay: &ClosestOverlay) -> String {
    let k = &overlay.closest;
    match overlay.subproblem.as_str() {
        "singularity" => leg_meeting(k)
            .describe("singular: leg lines")
            .unwrap_or_else(|| "leg lines undefined".into()),
        "collinear-platform" => "collinear platform: b1′, b2′, b3′ on one line".into(),
        "collinear-base" => "collinear base: a1′, a2′, a3′ on one line".into(),
        "all-collinear" => "all six anchors on one line".into(),
        "coincident-platform" => "coincident platform: b1′ = b2′ = b3′".into(),
        "coincident-base" => "coincident base: a1′ = a2′ = a3′".into(),
        other => other.to_string(),
    }
}

fn degenerate_point(out: &mut String, canvas: &Canvas, p: [f64; 2], style: SeriesStyle) {
    let _ = writeln!(
        out,
        r#"<circle class="degenerate-point" cx="{}" cy="{}" r="7" fill="none" stroke="{}" stroke-width="2.5"/>"#,
        px(canvas.x(p[0])),
        px(canvas.y(p[1])),
        style.colour
    );
}

/// Writes the legend right of the drawing; returns the y of its lower end.
fn legend(out: &mut String, canvas: &Canvas, scene: &Scene) -> f64 {
    let mut legend = Legend::open(out, canvas);
    legend.configuration(22.0);
    if !scene.overlays.is_empty() {
        legend.note("closest singular K′ per metric (platform/base),", "", 17.0);
        let unit = &scene.length_unit;
        legend.note(&format!("distance D(K, K′) in {unit}:"), "", 24.0);
    }
    for overlay in &scene.overlays {
        let style = metric_style(&overlay.metric);
        let note = overlay_note(overlay);
        legend.closest(
            &overlay.metric,
            &overlay.metric,
            style,
            (overlay.distance, ""),
            &note,
        );
    }
    legend.close()
}

/// A zoom inset is drawn when it enlarges the platform region at least this much.
const ZOOM_AT_LEAST: f64 = 2.0;

/// The box around the platform anchors of `K` and of each `K′` (and the leg lines'
/// meeting points near them): the region the zoom inset shows.
fn platform_extent(scene: &Scene) -> Extent {
    let mut e = Extent::empty();
    for k in std::iter::once(&scene.configuration).chain(scene.overlays.iter().map(|o| &o.closest))
    {
        for j in 3..6 {
            e.include(anchor(k, j));
        }
    }
    let (centre, size) = (e.centre(), e.size());
    for overlay in &scene.overlays {
        if overlay.subproblem == "singularity"
            && let LegMeeting::Point(p) = leg_meeting(&overlay.closest)
            && norm(sub(p, centre)) <= size
        {
            e.include(p);
        }
    }
    e
}

/// The canvas of the zoom inset: `zoom` with a 12 % margin (room for the anchor
/// labels) in the pixel rectangle `area`.
fn zoom_canvas(zoom: &Extent, area: (f64, f64, f64, f64)) -> Canvas {
    let margin = 0.12 * zoom.size();
    let padded = Extent {
        min: [zoom.min[0] - margin, zoom.min[1] - margin],
        max: [zoom.max[0] + margin, zoom.max[1] + margin],
    };
    Canvas::in_area(&padded, area)
}

/// The platform region of the scene enlarged on `canvas`; every
/// class of the inset is prefixed `zoom-` (and `g#K` becomes `g#K-zoom`) so the main
/// drawing's elements keep their meaning.
fn zoom_inset(out: &mut String, scene: &Scene, canvas: &Canvas, main_scale: f64) {
    let mut inset = String::new();
    let (l, t, w, h) = canvas.frame();
    let _ = writeln!(
        inset,
        r##"<text x="{}" y="{}" font-size="13" fill="#444">zoom on the platform (× {}, same units)</text><rect class="frame" x="{}" y="{}" width="{}" height="{}" fill="#fff" stroke="#888"/><clipPath id="zoom-area"><rect x="{3}" y="{4}" width="{5}" height="{6}"/></clipPath><g clip-path="url(#zoom-area)">"##,
        px(l),
        px(t - 8.0),
        number(canvas.scale / main_scale, 1),
        px(l),
        px(t),
        px(w),
        px(h)
    );
    scene.draw_configuration(&mut inset, canvas);
    scene.draw_overlays(&mut inset, canvas, &platform_extent(scene));
    inset.push_str("</g>\n");
    out.push_str("<g class=\"zoom\">\n");
    out.push_str(
        &inset
            .replace("class=\"", "class=\"zoom-")
            .replace("id=\"K\"", "id=\"K-zoom\""),
    );
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::scene::scene_extent;

    #[test]
    fn parallel_leg_lines_are_drawn_as_an_arrow() {
        let k = [0.0, 0.0, 10.0, 0.0, 4.0, 8.0, 4.0, 3.0, 7.0, 3.0, 5.0, 5.0];
        // Three vertical legs: parallel leg lines, no meeting point.
        let parallel = [0.0, 0.0, 3.0, 0.0, 1.0, 2.0, 0.0, 3.0, 3.0, 5.0, 1.0, 7.0];
        let scene = Scene {
            title: "parallel legs".into(),
            configuration: k,
            overlays: vec![ClosestOverlay {
                metric: "plate/plate".into(),
                distance: 3.0,
                subproblem: "singularity".into(),
                closest: parallel,
            }],
            length_unit: "m".into(),
        };
        let svg = scene.svg(&scene_extent(&scene));
        assert_eq!(svg.matches(r#"class="meet-direction""#).count(), 1);
        assert_eq!(svg.matches(r#"<circle class="meet""#).count(), 0);
        assert!(
            svg.contains("leg lines parallel, along (0.000, 1.000)"),
            "{svg}"
        );
        std::fs::write(std::env::temp_dir().join("singdist-parallel-legs.svg"), svg).ok();
    }

    #[test]
    fn drawing_has_three_legs_two_triangles_and_one_overlay_per_metric() {
        let k = [0.0, 0.0, 10.0, 0.0, 4.0, 8.0, 4.0, 3.0, 7.0, 3.0, 5.0, 5.0];
        let mut singular = k;
        singular[6] = 4.2;
        let scene = Scene {
            title: "test".into(),
            configuration: k,
            overlays: vec![
                ClosestOverlay {
                    metric: "plate/plate".into(),
                    distance: 0.2,
                    subproblem: "singularity".into(),
                    closest: singular,
                },
                ClosestOverlay {
                    metric: "bars/rigid".into(),
                    distance: 1.5,
                    subproblem: "coincident-platform".into(),
                    closest: [0.0, 0.0, 10.0, 0.0, 4.0, 8.0, 5.0, 4.0, 5.0, 4.0, 5.0, 4.0],
                },
            ],
            length_unit: "m".into(),
        };
        let svg = scene.svg(&scene_extent(&scene));
        assert_eq!(svg.matches(r#"<g id="K""#).count(), 1);
        assert_eq!(svg.matches(r#"class="leg""#).count(), 3 * 3);
        assert_eq!(svg.matches(r#"class="base""#).count(), 3);
        assert_eq!(svg.matches(r#"class="platform""#).count(), 3);
        assert_eq!(svg.matches(r#"<g class="closest""#).count(), 2);
        assert_eq!(svg.matches(r#"class="degenerate-point""#).count(), 1);
        // The platform is not small enough for a zoom inset to help.
        assert_eq!(svg.matches(r#"<g class="zoom">"#).count(), 0);
        // A platform a tenth of the base's size gets one, with classes of its own.
        let mut small = scene.clone();
        small.configuration = [0.0, 0.0, 10.0, 0.0, 4.0, 8.0, 4.0, 3.0, 4.3, 3.0, 4.1, 3.2];
        for overlay in &mut small.overlays {
            overlay.closest[6..].copy_from_slice(&small.configuration[6..]);
        }
        let svg = small.svg(&scene_extent(&small));
        assert_eq!(svg.matches(r#"<g class="zoom">"#).count(), 1);
        assert_eq!(svg.matches(r#"<g id="K-zoom""#).count(), 1);
        assert_eq!(svg.matches(r#"<g class="zoom-closest""#).count(), 2);
        assert_eq!(svg.matches(r#"<g class="closest""#).count(), 2);
        for label in ["a1", "a2", "a3", "b1", "b2", "b3"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label}");
        }
    }

    #[test]
    fn labels_of_coincident_anchors_do_not_overprint() {
        // a1 = a2 = (0, 0).
        let k = [0.0, 0.0, 0.0, 0.0, 4.0, 8.0, 3.0, 2.0, 5.0, 2.0, 4.0, 4.0];
        let scene = Scene {
            title: "coincident".into(),
            configuration: k,
            overlays: vec![],
            length_unit: "m".into(),
        };
        let svg = scene.svg(&scene_extent(&scene));
        let centre = |label: &str| -> [f64; 2] {
            let end = svg.find(&format!(">{label}</text>")).expect(label);
            let start = svg[..end].rfind("<text").expect("text element");
            let number = |name: &str| -> f64 {
                let from = start + svg[start..].find(&format!(" {name}=\"")).unwrap() + 4;
                svg[from..from + svg[from..].find('"').unwrap()]
                    .parse()
                    .unwrap()
            };
            [number("x"), number("y")]
        };
        let (a1, a2) = (centre("a1"), centre("a2"));
        assert!(
            (a1[0] - a2[0]).abs() >= 22.0 || (a1[1] - a2[1]).abs() >= 16.0,
            "{a1:?} {a2:?}"
        );
    }
}
