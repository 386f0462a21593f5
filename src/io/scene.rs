//! What the 3-RPR and 3-RRR drawings ([`super::draw`], [`super::rrr_draw`]) share: a
//! configuration `K` drawn with each closest singular configuration `K′` overlaid, in
//! a view that holds every joint and the leg lines' meeting points near them, and the
//! flat coordinate arrays (`x` of point `j` at `2j`, `y` at `2j + 1`) both draw from.

use super::canvas::{Canvas, Extent, norm, open_drawing, polygon, sub};
use super::leg_lines::{LegMeeting, NEAR_MEETING};
use super::svg::{SeriesStyle, stroke_attributes};
use std::fmt::Write;

/// A drawing of a configuration `K` and its closest singular configurations `K′`.
pub trait MechanismScene {
    /// The title line above the drawing and the name of the length unit (axes and
    /// legend).
    fn labels(&self) -> (&str, &str);
    /// The box around every joint of `K` and of each `K′`.
    fn joints_extent(&self) -> Extent;
    /// Where the leg lines of each `K′` singular by concurrent or parallel leg lines
    /// meet (3-RRR: the distal-link lines).
    fn leg_meetings(&self) -> Vec<LegMeeting>;
    /// Draws `K`.
    fn draw_configuration(&self, out: &mut String, canvas: &Canvas);
    /// Draws every `K′`; leg-line meeting points within `near` are marked as points.
    fn draw_overlays(&self, out: &mut String, canvas: &Canvas, near: &Extent);
    /// The scene as a standalone SVG document showing `extent` (pass
    /// [`scene_extent`] for one drawing, or the union over several scenes for frames
    /// that share a view).
    fn svg(&self, extent: &Extent) -> String;
}

/// The box the scene's drawing must show: every joint of `K` and of each `K′`, and
/// the leg lines' meeting points that lie near them.
pub fn scene_extent(scene: &impl MechanismScene) -> Extent {
    let mut e = scene.joints_extent();
    let (centre, size) = (e.centre(), e.size());
    for meeting in scene.leg_meetings() {
        if let LegMeeting::Point(p) = meeting
            && norm(sub(p, centre)) <= NEAR_MEETING * size
        {
            e.include(p);
        }
    }
    e
}

/// The drawing's SVG body on `canvas`: title and axes, `K`, every `K′`, with the
/// plot group closed (the legend and the document frame are the caller's).
pub fn scene_body(scene: &impl MechanismScene, canvas: &Canvas) -> String {
    let (title, length_unit) = scene.labels();
    let mut body = open_drawing(canvas, title, length_unit);
    scene.draw_configuration(&mut body, canvas);
    scene.draw_overlays(&mut body, canvas, &scene.joints_extent());
    body.push_str("</g>\n");
    body
}

/// Point `j` of a flat coordinate array `k`.
pub fn joint<const N: usize>(k: &[f64; N], j: usize) -> [f64; 2] {
    [k[2 * j], k[2 * j + 1]]
}

/// SVG attributes of `K`'s platform triangle (both drawings).
pub const K_PLATFORM: &str =
    r##" fill="#c8c8c8" fill-opacity="0.8" stroke="#222" stroke-width="2.5""##;

/// SVG attributes of `K`'s legs (3-RRR: links), both drawings.
pub const K_LEGS: &str = r##" stroke="#222" stroke-width="4" stroke-linecap="round""##;

/// How a configuration's legs (3-RRR: proximal and distal links) are drawn: `k`
/// with the given SVG attributes.
pub type DrawLegs<const N: usize> = fn(&mut String, &Canvas, &[f64; N], &str);

/// The skeleton of a configuration `k` in both drawings: the base triangle (points
/// `0..3`), the platform triangle (points `platform..platform + 3`) and the legs,
/// with the SVG `attributes` of each, in that order (`K′`: one stroke for all three).
pub fn draw_skeleton<const N: usize>(
    out: &mut String,
    canvas: &Canvas,
    k: &[f64; N],
    platform: usize,
    legs: DrawLegs<N>,
    attributes: [&str; 3],
) {
    for (first, class, attributes) in [
        (0, "base", attributes[0]),
        (platform, "platform", attributes[1]),
    ] {
        polygon(
            out,
            canvas,
            (first..first + 3).map(|j| joint(k, j)),
            class,
            attributes,
        );
    }
    legs(out, canvas, k, attributes[2]);
}

/// Opens the group of one `K′` (`<g class="closest"` with its `data` attributes,
/// already escaped) and draws its skeleton ([`draw_skeleton`]) in `style`; the caller
/// marks what makes it singular and closes the group.
pub fn open_overlay<const N: usize>(
    out: &mut String,
    canvas: &Canvas,
    k: &[f64; N],
    platform: usize,
    legs: DrawLegs<N>,
    style: SeriesStyle,
    data: &str,
) {
    let _ = writeln!(out, r#"<g class="closest" {data}>"#);
    let stroke = stroke_attributes(style, 1.8);
    draw_skeleton(out, canvas, k, platform, legs, [&stroke; 3]);
}
