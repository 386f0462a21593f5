//! Where the three leg lines of a configuration meet, and how a drawing marks it. A
//! configuration `K′` is singular when its leg lines `a_i + t (b_i − a_i)` are
//! concurrent or parallel (`S(K′) = det[b_i − a_i | a_i × b_i] = 0`, Hunt, "Kinematic
//! geometry of mechanisms", 1978); for a 3-RRR the same holds for the distal-link lines
//! `B_i C_i` (Gosselin and Angeles, "Singularity analysis of closed-loop kinematic
//! chains", 1990). A meeting point near the drawing is marked with the leg lines drawn
//! to it; a far one, or a common direction, becomes an arrow.

use super::canvas::{Canvas, Extent, arrow, centroid, line, norm, sub};
use super::scene::joint as anchor;
use super::svg::{SeriesStyle, number, px};
use std::fmt::Write;

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

fn cross(p: [f64; 2], q: [f64; 2]) -> f64 {
    p[0] * q[1] - p[1] * q[0]
}

impl LegMeeting {
    /// `"{lines} meet at (x, y)"` or `"{lines} parallel, along (dx, dy)"` (three
    /// decimals); `None` when undefined.
    pub fn describe(&self, lines: &str) -> Option<String> {
        match self {
            LegMeeting::Point(p) => Some(format!(
                "{lines} meet at ({}, {})",
                number(p[0], 3),
                number(p[1], 3)
            )),
            LegMeeting::Direction(d) => Some(format!(
                "{lines} parallel, along ({}, {})",
                number(d[0], 3),
                number(d[1], 3)
            )),
            LegMeeting::Undefined => None,
        }
    }
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

/// Marks `meeting` of the leg lines ending at the platform points `platform`: a
/// meeting point within [`NEAR_MEETING`] sizes of `near` as a dot with dotted lines
/// (`guide` attributes) from each platform point to it; a farther one as an arrow from
/// the platform's centroid towards it; parallel lines as an arrow along them.
pub(crate) fn mark_meeting(
    out: &mut String,
    canvas: &Canvas,
    meeting: LegMeeting,
    platform: &[[f64; 2]],
    near: &Extent,
    (style, guide): (SeriesStyle, &str),
) {
    match meeting {
        LegMeeting::Point(p) if norm(sub(p, near.centre())) <= NEAR_MEETING * near.size() => {
            for b in platform {
                line(out, canvas, "leg-line", *b, p, guide);
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
            let c = centroid(platform);
            let d = sub(p, c);
            let n = norm(d).max(1e-300);
            arrow(out, canvas, c, [d[0] / n, d[1] / n], style);
        }
        LegMeeting::Direction(d) => arrow(out, canvas, centroid(platform), d, style),
        LegMeeting::Undefined => {}
    }
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
}
