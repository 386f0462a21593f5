//! The drawing surface of a manipulator drawing: a world box shown at one scale on
//! both axes (a drawing, not a chart) in a pixel rectangle, `pixel = left + (x −
//! x_min)·scale` across and `top + height − (y − y_min)·scale` down, with its framed,
//! ticked axes in the design's length unit, and the SVG primitives every drawing uses
//! (lines, polygons, joints, labels, arrows, degenerate lines), the document frame and
//! the legend column to the right of the drawing.

use super::svg::{SeriesStyle, escape, number, px, stroke_attributes, tick_label, ticks};
use std::fmt::Write;

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

    /// The smallest box containing every point of `points` (non-finite ones ignored).
    pub fn of_points(points: impl IntoIterator<Item = [f64; 2]>) -> Self {
        let mut e = Extent::empty();
        for p in points {
            e.include(p);
        }
        e
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

/// `p − q`.
pub(crate) fn sub(p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    [p[0] - q[0], p[1] - q[1]]
}

/// `|p|`.
pub(crate) fn norm(p: [f64; 2]) -> f64 {
    p[0].hypot(p[1])
}

/// The mean of `points`.
pub(crate) fn centroid(points: &[[f64; 2]]) -> [f64; 2] {
    let n = points.len().max(1) as f64;
    [
        points.iter().map(|p| p[0]).sum::<f64>() / n,
        points.iter().map(|p| p[1]).sum::<f64>() / n,
    ]
}

/// Pixel layout of a drawing (opaque outside the crate: the surface the
/// [`super::scene::MechanismScene`] drawings draw on).
pub struct Canvas {
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
    pub(crate) fn in_area(
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

    /// The plot area `(left, top, width, height)` in pixels.
    pub(crate) fn frame(&self) -> (f64, f64, f64, f64) {
        (self.left, self.top, self.plot_width, self.plot_height)
    }

    /// The pixel position of a world point.
    pub(crate) fn pixel(&self, p: [f64; 2]) -> [f64; 2] {
        [self.x(p[0]), self.y(p[1])]
    }

    pub(crate) fn point(&self, p: [f64; 2]) -> String {
        format!("{},{}", px(self.x(p[0])), px(self.y(p[1])))
    }
}

/// A `<line>` of class `class` from world point `p` to `q`.
pub(crate) fn line(
    out: &mut String,
    canvas: &Canvas,
    class: &str,
    p: [f64; 2],
    q: [f64; 2],
    attributes: &str,
) {
    let ends = line_ends(canvas, p, q);
    let _ = writeln!(out, r#"<line class="{class}" {ends}{attributes}/>"#);
}

/// The attributes `x1="…" y1="…" x2="…" y2="…"` of a line from world point `p` to `q`.
fn line_ends(canvas: &Canvas, p: [f64; 2], q: [f64; 2]) -> String {
    format!(
        r#"x1="{}" y1="{}" x2="{}" y2="{}""#,
        px(canvas.x(p[0])),
        px(canvas.y(p[1])),
        px(canvas.x(q[0])),
        px(canvas.y(q[1]))
    )
}

/// A `<line>` of class `class` and leg number `leg` (`data-leg`) from `p` to `q`.
pub(crate) fn leg_line(
    out: &mut String,
    canvas: &Canvas,
    class: &str,
    leg: usize,
    (p, q): ([f64; 2], [f64; 2]),
    attributes: &str,
) {
    let ends = line_ends(canvas, p, q);
    let _ = writeln!(
        out,
        r#"<line class="{class}" data-leg="{leg}" {ends}{attributes}/>"#
    );
}

/// A closed `<polygon>` of class `class` through the world points `points`.
pub(crate) fn polygon(
    out: &mut String,
    canvas: &Canvas,
    points: impl IntoIterator<Item = [f64; 2]>,
    class: &str,
    attributes: &str,
) {
    let points: Vec<String> = points.into_iter().map(|p| canvas.point(p)).collect();
    let _ = writeln!(
        out,
        r#"<polygon class="{class}" points="{}"{attributes}/>"#,
        points.join(" ")
    );
}

/// A revolute joint: a white circle of radius 4 px at pixel position `p`.
pub(crate) fn joint_circle(out: &mut String, class: &str, p: [f64; 2]) {
    let _ = writeln!(
        out,
        r##"<circle class="{class}" cx="{}" cy="{}" r="4" fill="#fff" stroke="#222" stroke-width="1.5"/>"##,
        px(p[0]),
        px(p[1])
    );
}

/// Distance in pixels from a point to the centre of its label.
const LABEL_OFFSET: f64 = 18.0;

/// An italic label centred at pixel position `centre` (white halo, so lines under
/// it do not hide it).
fn label_at(out: &mut String, class: &str, centre: [f64; 2], text: &str) {
    let _ = writeln!(
        out,
        r##"<text class="{class}" x="{}" y="{}" font-size="15" font-style="italic" text-anchor="middle" dominant-baseline="central" stroke="#fff" stroke-width="4" paint-order="stroke">{text}</text>"##,
        px(centre[0]),
        px(centre[1]),
    );
}

/// Two label centres closer than this across and up (px) would overprint.
const LABEL_CLEARANCE: [f64; 2] = [22.0, 16.0];

/// Point labels of one drawing, placed so that none overprints an earlier one.
#[derive(Default)]
pub(crate) struct PointLabels {
    placed: Vec<[f64; 2]>,
}

impl PointLabels {
    /// Writes a label 18 px from pixel position `at` in the pixel direction `away`
    /// unless that overprints an earlier label (coincident points, e.g. two anchors at
    /// one place); then at the first free place among the direction turned by ±60°,
    /// ±120°, 180° at 18 px, then the same at 34 px. A zero direction means "above".
    pub(crate) fn place(
        &mut self,
        out: &mut String,
        class: &str,
        (at, away): ([f64; 2], [f64; 2]),
        text: &str,
    ) {
        let n = norm(away);
        let d = if n > 1e-9 {
            [away[0] / n, away[1] / n]
        } else {
            [0.0, -1.0]
        };
        let preferred = [
            at[0] + LABEL_OFFSET * away[0] / n.max(1e-9),
            at[1] + LABEL_OFFSET * away[1] / n.max(1e-9),
        ];
        let free = |c: &[f64; 2]| {
            self.placed.iter().all(|q| {
                (q[0] - c[0]).abs() >= LABEL_CLEARANCE[0]
                    || (q[1] - c[1]).abs() >= LABEL_CLEARANCE[1]
            })
        };
        let centre = if n > 1e-9 && free(&preferred) {
            preferred
        } else {
            let turns = [0.0f64, 60.0, -60.0, 120.0, -120.0, 180.0];
            [LABEL_OFFSET, 34.0]
                .iter()
                .flat_map(|r| turns.iter().map(move |t| (*r, t.to_radians())))
                .map(|(r, t)| {
                    let (sin, cos) = t.sin_cos();
                    let turned = [d[0] * cos - d[1] * sin, d[0] * sin + d[1] * cos];
                    [at[0] + r * turned[0], at[1] + r * turned[1]]
                })
                .find(|c| free(c))
                .unwrap_or(preferred)
        };
        label_at(out, class, centre, text);
        self.placed.push(centre);
    }
}

/// Thin dotted guide lines (leg lines to their meeting point, degenerate lines) in the
/// colour of `style`.
pub(crate) fn guide_attributes(style: SeriesStyle) -> String {
    format!(
        r#" stroke="{}" stroke-width="1.5" stroke-dasharray="2 3" fill="none""#,
        style.colour
    )
}

/// A 70 px arrow from world point `from` along the world direction `direction`.
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

/// The frame, grid, ticks and axis titles `x (unit)`, `y (unit)` of `canvas`.
pub(crate) fn axes(out: &mut String, canvas: &Canvas, unit: &str) {
    let (l, t, w, h) = canvas.frame();
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

/// The start of a drawing's body: white background, `title`, the axes, and the opened
/// group clipped to the plot area (close it with `</g>`).
pub(crate) fn open_drawing(canvas: &Canvas, title: &str, unit: &str) -> String {
    let mut body = String::new();
    let _ = writeln!(
        body,
        r##"<rect width="100%" height="100%" fill="#fff"/><text class="title" x="{}" y="26" font-size="17">{}</text>"##,
        px(canvas.left),
        escape(title)
    );
    axes(&mut body, canvas, unit);
    let _ = writeln!(
        body,
        r#"<clipPath id="plot-area"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#plot-area)">"#,
        px(canvas.left),
        px(canvas.top),
        px(canvas.plot_width),
        px(canvas.plot_height)
    );
    body
}

/// `body` wrapped in an `<svg class="{class}">` document of `width × height` pixels.
pub(crate) fn svg_document(class: &str, width: f64, height: f64, body: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="{class}" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif">"#,
        px(width),
        px(height)
    );
    out.push_str(body);
    out.push_str("</svg>\n");
    out
}

/// The legend column right of a drawing (`g#legend`), written top to bottom.
pub(crate) struct Legend<'a> {
    out: &'a mut String,
    x: f64,
    /// Where the next line goes.
    pub(crate) y: f64,
}

impl<'a> Legend<'a> {
    /// Opens the legend 24 px right of the plot area of `canvas`.
    pub(crate) fn open(out: &'a mut String, canvas: &Canvas) -> Self {
        out.push_str("<g id=\"legend\" font-size=\"13\">\n");
        Legend {
            out,
            x: canvas.left + canvas.plot_width + 24.0,
            y: canvas.top + 8.0,
        }
    }

    /// The entry of the drawn configuration `K` (a thick dark line), at the current
    /// line; moves down `advance` px.
    pub(crate) fn configuration(&mut self, advance: f64) {
        let (x, y) = (self.x, self.y);
        let _ = writeln!(
            self.out,
            r##"<g class="legend-entry"><line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="#222" stroke-width="4"/><text x="{3}" y="{1}" dominant-baseline="central">K: the manipulator at the pose</text></g>"##,
            px(x),
            px(y),
            px(x + 34.0),
            px(x + 42.0)
        );
        self.y += advance;
    }

    /// A grey line of text (with extra `attributes`, e.g. a font size); moves down
    /// `advance` px.
    pub(crate) fn note(&mut self, text: &str, attributes: &str, advance: f64) {
        let _ = writeln!(
            self.out,
            r##"<text x="{}" y="{}" dominant-baseline="central" fill="#444"{attributes}>{}</text>"##,
            px(self.x),
            px(self.y),
            escape(text)
        );
        self.y += advance;
    }

    /// The entry of one closest singular configuration: its line style, `name` in bold,
    /// `D = distance` and `suffix`, and `note` under it; `key` is its `data-metric`.
    pub(crate) fn closest(
        &mut self,
        key: &str,
        name: &str,
        style: SeriesStyle,
        (distance, suffix): (f64, &str),
        note: &str,
    ) {
        let (x, y) = (self.x, self.y);
        let _ = writeln!(
            self.out,
            r##"<g class="legend-entry" data-metric="{m}"><line x1="{0}" y1="{1}" x2="{2}" y2="{1}"{3}/><text x="{4}" y="{1}" dominant-baseline="central"><tspan font-weight="bold">{name}</tspan>   D = {5}{suffix}</text><text x="{4}" y="{6}" dominant-baseline="central" fill="#444" font-size="12">{7}</text></g>"##,
            px(x),
            px(y),
            px(x + 34.0),
            stroke_attributes(style, 2.5),
            px(x + 42.0),
            number(distance, 4),
            px(y + 16.0),
            escape(note),
            m = escape(key),
            name = escape(name),
        );
        self.y += 40.0;
    }

    /// Closes the legend; returns the y of its lower end.
    pub(crate) fn close(self) -> f64 {
        self.out.push_str("</g>\n");
        self.y
    }
}
