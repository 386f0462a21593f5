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

use super::svg::{
    SeriesStyle, escape, metric_style, number, px, short, stroke_attributes, tick_label, ticks,
};
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

/// An axis-aligned box in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extent {
    /// Lower-left corner.
    pub min: [f64; 2],
    /// Upper-right corner.
    pub max: [f64; 2],
}

impl Extent {
    /// The empty box (contains nothing until a point is included).
    pub fn empty() -> Self {
        Extent {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        }
    }

    /// Grows the box to contain `p` (non-finite points are ignored).
    pub fn include(&mut self, p: [f64; 2]) {
        if p[0].is_finite() && p[1].is_finite() {
            for ((lo, hi), v) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
                *lo = lo.min(v);
                *hi = hi.max(v);
            }
        }
    }

    /// The smallest box containing both.
    pub fn union(&self, other: &Extent) -> Extent {
        let mut out = *self;
        out.include(other.min);
        out.include(other.max);
        out
    }

    pub(crate) fn centre(&self) -> [f64; 2] {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
        ]
    }

    pub(crate) fn size(&self) -> f64 {
        (self.max[0] - self.min[0])
            .max(self.max[1] - self.min[1])
            .max(1e-12)
    }
}

/// Where the three leg lines `a_i + t (b_i − a_i)` of a configuration meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LegMeeting {
    /// A common point.
    Point([f64; 2]),
    /// Parallel legs: their common unit direction.
    Direction([f64; 2]),
    /// Fewer than two legs of non-zero length.
    Undefined,
}

fn anchor(k: &[f64; 12], j: usize) -> [f64; 2] {
    [k[2 * j], k[2 * j + 1]]
}

pub(crate) fn sub(p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    [p[0] - q[0], p[1] - q[1]]
}

fn cross(p: [f64; 2], q: [f64; 2]) -> f64 {
    p[0] * q[1] - p[1] * q[0]
}

pub(crate) fn norm(p: [f64; 2]) -> f64 {
    p[0].hypot(p[1])
}

/// Sine of the angle below which two leg lines count as parallel.
const PARALLEL_SINE: f64 = 1e-3;

/// Meeting point of the leg lines of `k`: the intersection of the two legs whose unit
/// directions `d_i, d_j` have the largest `|d_i × d_j|`,
/// `a_i + (((a_j − a_i) × d_j) / (d_i × d_j)) d_i`; their common direction when every
/// such sine is below 10⁻³.
pub fn leg_meeting(k: &[f64; 12]) -> LegMeeting {
    let scale = (0..6).map(|j| norm(anchor(k, j))).fold(1.0, f64::max);
    let legs: Vec<([f64; 2], [f64; 2])> = (0..3)
        .filter_map(|i| {
            let a = anchor(k, i);
            let d = sub(anchor(k, 3 + i), a);
            let length = norm(d);
            (length > 1e-9 * scale).then(|| (a, [d[0] / length, d[1] / length]))
        })
        .collect();
    if legs.len() < 2 {
        return LegMeeting::Undefined;
    }
    let mut best = (0, 1, 0.0f64);
    for i in 0..legs.len() {
        for j in i + 1..legs.len() {
            let s = cross(legs[i].1, legs[j].1);
            if s.abs() > best.2.abs() {
                best = (i, j, s);
            }
        }
    }
    let (i, j, s) = best;
    if s.abs() < PARALLEL_SINE {
        let d0 = legs[0].1;
        let mut sum = [0.0, 0.0];
        for (_, d) in &legs {
            let sign = if d[0] * d0[0] + d[1] * d0[1] < 0.0 {
                -1.0
            } else {
                1.0
            };
            sum = [sum[0] + sign * d[0], sum[1] + sign * d[1]];
        }
        let n = norm(sum);
        return LegMeeting::Direction([sum[0] / n, sum[1] / n]);
    }
    let (ai, di) = legs[i];
    let (aj, dj) = legs[j];
    let t = cross(sub(aj, ai), dj) / s;
    LegMeeting::Point([ai[0] + t * di[0], ai[1] + t * di[1]])
}

/// How far (in units of the configurations' own size) a meeting point may lie from
/// their centre and still be drawn as a point; farther ones become an arrow.
pub(crate) const NEAR_MEETING: f64 = 1.5;

fn configuration_extent(k: &[f64; 12]) -> Extent {
    let mut e = Extent::empty();
    for j in 0..6 {
        e.include(anchor(k, j));
    }
    e
}

/// The box around every anchor of `K` and of each `K′`.
fn anchors_extent(scene: &Scene) -> Extent {
    let mut e = configuration_extent(&scene.configuration);
    for overlay in &scene.overlays {
        e = e.union(&configuration_extent(&overlay.closest));
    }
    e
}

/// The box the scene's drawing must show: every anchor of `K` and of each `K′`, and
/// the leg lines' meeting points that lie near them.
pub fn scene_extent(scene: &Scene) -> Extent {
    let mut e = anchors_extent(scene);
    let (centre, size) = (e.centre(), e.size());
    for overlay in &scene.overlays {
        if overlay.subproblem == "singularity"
            && let LegMeeting::Point(p) = leg_meeting(&overlay.closest)
            && norm(sub(p, centre)) <= NEAR_MEETING * size
        {
            e.include(p);
        }
    }
    e
}

/// Pixel layout of a drawing.
pub(crate) struct Canvas {
    pub(crate) width: f64,
    pub(crate) height: f64,
    pub(crate) left: f64,
    pub(crate) top: f64,
    pub(crate) plot_width: f64,
    pub(crate) plot_height: f64,
    /// World box shown (already widened to the plot area's aspect ratio).
    pub(crate) view: Extent,
    pub(crate) scale: f64,
}

impl Canvas {
    pub(crate) fn new(extent: &Extent) -> Self {
        Canvas::in_area(extent, (70.0, 48.0, 600.0, 560.0))
    }

    /// `extent` (padded by 6 %) shown at one scale in the pixel rectangle
    /// `(left, top, width, height)`.
    fn in_area(
        extent: &Extent,
        (left, top, plot_width, plot_height): (f64, f64, f64, f64),
    ) -> Self {
        let pad = 0.06 * extent.size();
        let (w, h) = (
            extent.max[0] - extent.min[0] + 2.0 * pad,
            extent.max[1] - extent.min[1] + 2.0 * pad,
        );
        let scale = (plot_width / w.max(1e-12)).min(plot_height / h.max(1e-12));
        let (half_w, half_h) = (0.5 * plot_width / scale, 0.5 * plot_height / scale);
        let c = extent.centre();
        Canvas {
            width: 1040.0,
            height: 660.0,
            left,
            top,
            plot_width,
            plot_height,
            view: Extent {
                min: [c[0] - half_w, c[1] - half_h],
                max: [c[0] + half_w, c[1] + half_h],
            },
            scale,
        }
    }

    pub(crate) fn x(&self, x: f64) -> f64 {
        self.left + (x - self.view.min[0]) * self.scale
    }

    pub(crate) fn y(&self, y: f64) -> f64 {
        self.top + self.plot_height - (y - self.view.min[1]) * self.scale
    }

    pub(crate) fn point(&self, p: [f64; 2]) -> String {
        format!("{},{}", px(self.x(p[0])), px(self.y(p[1])))
    }
}

fn triangle(
    out: &mut String,
    canvas: &Canvas,
    k: &[f64; 12],
    first: usize,
    class: &str,
    attributes: &str,
) {
    let points: Vec<String> = (first..first + 3)
        .map(|j| canvas.point(anchor(k, j)))
        .collect();
    let _ = writeln!(
        out,
        r#"<polygon class="{class}" points="{}"{attributes}/>"#,
        points.join(" ")
    );
}

fn legs(out: &mut String, canvas: &Canvas, k: &[f64; 12], attributes: &str) {
    for i in 0..3 {
        let (a, b) = (anchor(k, i), anchor(k, 3 + i));
        let _ = writeln!(
            out,
            r#"<line class="leg" data-leg="{}" x1="{}" y1="{}" x2="{}" y2="{}"{attributes}/>"#,
            i + 1,
            px(canvas.x(a[0])),
            px(canvas.y(a[1])),
            px(canvas.x(b[0])),
            px(canvas.y(b[1]))
        );
    }
}

pub(crate) fn line(
    out: &mut String,
    canvas: &Canvas,
    class: &str,
    p: [f64; 2],
    q: [f64; 2],
    attributes: &str,
) {
    let _ = writeln!(
        out,
        r#"<line class="{class}" x1="{}" y1="{}" x2="{}" y2="{}"{attributes}/>"#,
        px(canvas.x(p[0])),
        px(canvas.y(p[1])),
        px(canvas.x(q[0])),
        px(canvas.y(q[1]))
    );
}

fn draw_configuration(out: &mut String, canvas: &Canvas, k: &[f64; 12]) {
    out.push_str("<g id=\"K\" class=\"configuration\">\n");
    triangle(
        out,
        canvas,
        k,
        0,
        "base",
        r##" fill="#e8e8e8" stroke="#222" stroke-width="2.5""##,
    );
    triangle(
        out,
        canvas,
        k,
        3,
        "platform",
        r##" fill="#c8c8c8" fill-opacity="0.8" stroke="#222" stroke-width="2.5""##,
    );
    legs(
        out,
        canvas,
        k,
        r##" stroke="#222" stroke-width="4" stroke-linecap="round""##,
    );
    for (first, letter) in [(0, 'a'), (3, 'b')] {
        let c = [
            (0..3).map(|j| anchor(k, first + j)[0]).sum::<f64>() / 3.0,
            (0..3).map(|j| anchor(k, first + j)[1]).sum::<f64>() / 3.0,
        ];
        for i in 0..3 {
            let p = anchor(k, first + i);
            let (x, y) = (canvas.x(p[0]), canvas.y(p[1]));
            let _ = writeln!(
                out,
                r##"<circle class="anchor" cx="{}" cy="{}" r="4" fill="#fff" stroke="#222" stroke-width="1.5"/>"##,
                px(x),
                px(y)
            );
            // The label sits outside the triangle, 16 px from the anchor.
            let away = sub([x, y], [canvas.x(c[0]), canvas.y(c[1])]);
            let n = norm(away).max(1e-9);
            let _ = writeln!(
                out,
                r##"<text class="anchor-label" x="{}" y="{}" font-size="15" font-style="italic" text-anchor="middle" dominant-baseline="central" stroke="#fff" stroke-width="4" paint-order="stroke">{letter}{}</text>"##,
                px(x + 18.0 * away[0] / n),
                px(y + 18.0 * away[1] / n),
                i + 1
            );
        }
    }
    out.push_str("</g>\n");
}

/// The note on a `K′` that the legend prints under its distance.
fn overlay_note(overlay: &ClosestOverlay) -> String {
    let k = &overlay.closest;
    match overlay.subproblem.as_str() {
        "singularity" => match leg_meeting(k) {
            LegMeeting::Point(p) => format!(
                "singular: leg lines meet at ({}, {})",
                number(p[0], 3),
                number(p[1], 3)
            ),
            LegMeeting::Direction(d) => format!(
                "singular: leg lines parallel, along ({}, {})",
                number(d[0], 3),
                number(d[1], 3)
            ),
            LegMeeting::Undefined => "leg lines undefined".into(),
        },
        "collinear-platform" => "collinear platform: b1′, b2′, b3′ on one line".into(),
        "collinear-base" => "collinear base: a1′, a2′, a3′ on one line".into(),
        "all-collinear" => "all six anchors on one line".into(),
        "coincident-platform" => "coincident platform: b1′ = b2′ = b3′".into(),
        "coincident-base" => "coincident base: a1′ = a2′ = a3′".into(),
        other => other.to_string(),
    }
}

pub(crate) fn arrow(
    out: &mut String,
    canvas: &Canvas,
    from: [f64; 2],
    direction: [f64; 2],
    style: SeriesStyle,
) {
    let length = 70.0;
    let (x0, y0) = (canvas.x(from[0]), canvas.y(from[1]));
    let (dx, dy) = (direction[0], -direction[1]);
    let (x1, y1) = (x0 + length * dx, y0 + length * dy);
    let (hx, hy) = (-dy, dx);
    let head = format!(
        "M{} {} L{} {} M{} {} L{} {}",
        px(x1),
        px(y1),
        px(x1 - 10.0 * dx + 5.0 * hx),
        px(y1 - 10.0 * dy + 5.0 * hy),
        px(x1),
        px(y1),
        px(x1 - 10.0 * dx - 5.0 * hx),
        px(y1 - 10.0 * dy - 5.0 * hy)
    );
    let _ = writeln!(
        out,
        r#"<path class="meet-direction" d="M{} {} L{} {} {head}" stroke="{}" stroke-width="2" fill="none"/>"#,
        px(x0),
        px(y0),
        px(x1),
        px(y1),
        style.colour
    );
}

fn draw_overlay(out: &mut String, canvas: &Canvas, overlay: &ClosestOverlay, near: &Extent) {
    let style = metric_style(&overlay.metric);
    let k = &overlay.closest;
    let _ = writeln!(
        out,
        r#"<g class="closest" data-metric="{}" data-subproblem="{}">"#,
        escape(&overlay.metric),
        escape(&overlay.subproblem)
    );
    let stroke = stroke_attributes(style, 1.8);
    triangle(out, canvas, k, 0, "base", &stroke);
    triangle(out, canvas, k, 3, "platform", &stroke);
    legs(out, canvas, k, &stroke);
    let thin = format!(
        r#" stroke="{}" stroke-width="1.5" stroke-dasharray="2 3" fill="none""#,
        style.colour
    );
    let points = |range: std::ops::Range<usize>| range.map(|j| anchor(k, j)).collect::<Vec<_>>();
    match overlay.subproblem.as_str() {
        "singularity" => match leg_meeting(k) {
            LegMeeting::Point(p) if norm(sub(p, near.centre())) <= NEAR_MEETING * near.size() => {
                for i in 0..3 {
                    line(out, canvas, "leg-line", anchor(k, 3 + i), p, &thin);
                }
                let _ = writeln!(
                    out,
                    r##"<circle class="meet" cx="{}" cy="{}" r="5" fill="{}" stroke="#fff" stroke-width="1"/>"##,
                    px(canvas.x(p[0])),
                    px(canvas.y(p[1])),
                    style.colour
                );
            }
            LegMeeting::Point(p) => {
                let c = centroid(&points(3..6));
                let d = sub(p, c);
                let n = norm(d).max(1e-300);
                arrow(out, canvas, c, [d[0] / n, d[1] / n], style);
            }
            LegMeeting::Direction(d) => arrow(out, canvas, centroid(&points(3..6)), d, style),
            LegMeeting::Undefined => {}
        },
        "collinear-platform" => collinear_line(out, canvas, &points(3..6), &thin),
        "collinear-base" => collinear_line(out, canvas, &points(0..3), &thin),
        "all-collinear" => collinear_line(out, canvas, &points(0..6), &thin),
        "coincident-platform" => degenerate_point(out, canvas, centroid(&points(3..6)), style),
        "coincident-base" => degenerate_point(out, canvas, centroid(&points(0..3)), style),
        _ => {}
    }
    out.push_str("</g>\n");
}

pub(crate) fn centroid(points: &[[f64; 2]]) -> [f64; 2] {
    let n = points.len().max(1) as f64;
    [
        points.iter().map(|p| p[0]).sum::<f64>() / n,
        points.iter().map(|p| p[1]).sum::<f64>() / n,
    ]
}

/// The line through collinear points, drawn between the two farthest apart and 15 %
/// beyond them.
pub(crate) fn collinear_line(
    out: &mut String,
    canvas: &Canvas,
    points: &[[f64; 2]],
    attributes: &str,
) {
    let mut ends = (points[0], points[0], 0.0);
    for (i, p) in points.iter().enumerate() {
        for q in &points[i + 1..] {
            let d = norm(sub(*p, *q));
            if d > ends.2 {
                ends = (*p, *q, d);
            }
        }
    }
    let (p, q, _) = ends;
    let d = sub(q, p);
    let from = [p[0] - 0.15 * d[0], p[1] - 0.15 * d[1]];
    let to = [q[0] + 0.15 * d[0], q[1] + 0.15 * d[1]];
    line(out, canvas, "degenerate-line", from, to, attributes);
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

pub(crate) fn axes(out: &mut String, canvas: &Canvas, unit: &str) {
    let (l, t, w, h) = (
        canvas.left,
        canvas.top,
        canvas.plot_width,
        canvas.plot_height,
    );
    let _ = writeln!(
        out,
        r##"<rect class="frame" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#888" stroke-width="1"/>"##,
        px(l),
        px(t),
        px(w),
        px(h)
    );
    let (xs, dx) = ticks(canvas.view.min[0], canvas.view.max[0], 8);
    for v in xs {
        let x = canvas.x(v);
        let _ = writeln!(
            out,
            r##"<line x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#eee"/><line x1="{0}" y1="{2}" x2="{0}" y2="{3}" stroke="#888"/><text x="{0}" y="{4}" font-size="13" text-anchor="middle">{5}</text>"##,
            px(x),
            px(t),
            px(t + h),
            px(t + h + 5.0),
            px(t + h + 20.0),
            tick_label(v, dx)
        );
    }
    let (ys, dy) = ticks(canvas.view.min[1], canvas.view.max[1], 8);
    for v in ys {
        let y = canvas.y(v);
        let _ = writeln!(
            out,
            r##"<line x1="{1}" y1="{0}" x2="{2}" y2="{0}" stroke="#eee"/><line x1="{3}" y1="{0}" x2="{1}" y2="{0}" stroke="#888"/><text x="{4}" y="{0}" font-size="13" text-anchor="end" dominant-baseline="central">{5}</text>"##,
            px(y),
            px(l),
            px(l + w),
            px(l - 5.0),
            px(l - 8.0),
            tick_label(v, dy)
        );
    }
    let unit = escape(unit);
    let _ = writeln!(
        out,
        r#"<text class="axis-title" x="{}" y="{}" font-size="14" text-anchor="middle">x ({unit})</text>"#,
        px(l + 0.5 * w),
        px(t + h + 42.0)
    );
    let _ = writeln!(
        out,
        r#"<text class="axis-title" x="{0}" y="{1}" font-size="14" text-anchor="middle" transform="rotate(-90 {0} {1})">y ({unit})</text>"#,
        px(l - 50.0),
        px(t + 0.5 * h)
    );
}

/// Writes the legend right of the drawing; returns the y of its lower end.
fn legend(out: &mut String, canvas: &Canvas, scene: &Scene) -> f64 {
    let x = canvas.left + canvas.plot_width + 24.0;
    let mut y = canvas.top + 8.0;
    out.push_str("<g id=\"legend\" font-size=\"13\">\n");
    let _ = writeln!(
        out,
        r##"<g class="legend-entry"><line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#222" stroke-width="4"/><text x="{3}" y="{1}" dominant-baseline="central">K: the manipulator at the pose</text></g>"##,
        px(x),
        px(y),
        px(x + 34.0),
        px(x + 42.0)
    );
    y += 22.0;
    if !scene.overlays.is_empty() {
        let _ = writeln!(
            out,
            r##"<text x="{}" y="{}" dominant-baseline="central" fill="#444">closest singular K′ per metric (platform/base),</text>"##,
            px(x),
            px(y)
        );
        y += 17.0;
        let _ = writeln!(
            out,
            r##"<text x="{}" y="{}" dominant-baseline="central" fill="#444">distance D(K, K′) in {}:</text>"##,
            px(x),
            px(y),
            escape(&scene.length_unit)
        );
        y += 24.0;
    }
    for overlay in &scene.overlays {
        let style = metric_style(&overlay.metric);
        let _ = writeln!(
            out,
            r##"<g class="legend-entry" data-metric="{m}"><line x1="{0}" y1="{1}" x2="{2}" y2="{1}"{3}/><text x="{4}" y="{1}" dominant-baseline="central"><tspan font-weight="bold">{m}</tspan>   D = {5}</text><text x="{4}" y="{6}" dominant-baseline="central" fill="#444" font-size="12">{7}</text></g>"##,
            px(x),
            px(y),
            px(x + 34.0),
            stroke_attributes(style, 2.5),
            px(x + 42.0),
            number(overlay.distance, 4),
            px(y + 16.0),
            escape(&overlay_note(overlay)),
            m = escape(&overlay.metric),
        );
        y += 40.0;
    }
    out.push_str("</g>\n");
    y
}

/// The scene as a standalone SVG document showing `extent` (pass
/// [`scene_extent`] for one drawing, or the union over several scenes for frames that
/// share a view).
pub fn scene_svg(scene: &Scene, extent: &Extent) -> String {
    let canvas = Canvas::new(extent);
    let mut body = String::new();
    let _ = writeln!(
        body,
        r##"<rect width="100%" height="100%" fill="#fff"/><text class="title" x="{}" y="26" font-size="17">{}</text>"##,
        px(canvas.left),
        escape(&scene.title)
    );
    axes(&mut body, &canvas, &scene.length_unit);
    let _ = writeln!(
        body,
        r#"<clipPath id="plot-area"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#plot-area)">"#,
        px(canvas.left),
        px(canvas.top),
        px(canvas.plot_width),
        px(canvas.plot_height)
    );
    draw_configuration(&mut body, &canvas, &scene.configuration);
    let near = anchors_extent(scene);
    for overlay in &scene.overlays {
        draw_overlay(&mut body, &canvas, overlay, &near);
    }
    body.push_str("</g>\n");
    let legend_bottom = legend(&mut body, &canvas, scene);
    let mut height = canvas.height;
    let area = (
        canvas.left + canvas.plot_width + 24.0,
        legend_bottom + 34.0,
        320.0,
        250.0,
    );
    let zoom = zoom_canvas(&platform_extent(scene), area);
    if zoom.scale >= ZOOM_AT_LEAST * canvas.scale {
        height = height.max(area.1 + area.3 + 16.0);
        zoom_inset(&mut body, scene, &zoom, canvas.scale);
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="rpr-drawing" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif">"#,
        px(canvas.width),
        px(height)
    );
    out.push_str(&body);
    out.push_str("</svg>\n");
    out
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
    let (l, t, w, h) = (
        canvas.left,
        canvas.top,
        canvas.plot_width,
        canvas.plot_height,
    );
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
    draw_configuration(&mut inset, canvas, &scene.configuration);
    let near = platform_extent(scene);
    for overlay in &scene.overlays {
        draw_overlay(&mut inset, canvas, overlay, &near);
    }
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

    #[test]
    fn concurrent_legs_meet_at_their_common_point() {
        // Three legs through (1, 1).
        let k = [0.0, 0.0, 2.0, 0.0, 0.0, 2.0, 0.5, 0.5, 1.5, 0.5, 0.5, 1.5];
        match leg_meeting(&k) {
            LegMeeting::Point(p) => {
                assert!(
                    (p[0] - 1.0).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12,
                    "{p:?}"
                )
            }
            other => panic!("expected a point, got {other:?}"),
        }
    }

    #[test]
    fn parallel_legs_give_their_direction() {
        let k = [0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0];
        match leg_meeting(&k) {
            LegMeeting::Direction(d) => assert!(d[0].abs() < 1e-12 && (d[1] - 1.0).abs() < 1e-12),
            other => panic!("expected a direction, got {other:?}"),
        }
    }

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
        let svg = scene_svg(&scene, &scene_extent(&scene));
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
        let svg = scene_svg(&scene, &scene_extent(&scene));
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
        let svg = scene_svg(&small, &scene_extent(&small));
        assert_eq!(svg.matches(r#"<g class="zoom">"#).count(), 1);
        assert_eq!(svg.matches(r#"<g id="K-zoom""#).count(), 1);
        assert_eq!(svg.matches(r#"<g class="zoom-closest""#).count(), 2);
        assert_eq!(svg.matches(r#"<g class="closest""#).count(), 2);
        for label in ["a1", "a2", "a3", "b1", "b2", "b3"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label}");
        }
    }
}
