//! Small helpers for writing SVG as text: escaping, number formatting, "nice" axis
//! ticks (steps 1, 2 or 5 × 10^k) whose labels never read "-0", and the colour and
//! dash style of each of the nine 3-RPR metrics (the same in every picture).

use crate::metric::Metric;
use std::fmt::Write;

/// Escapes `&`, `<`, `>` and `"` for SVG/HTML text and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// A pixel coordinate with two decimals (enough for a 1000 px picture).
pub fn px(v: f64) -> String {
    let text = format!("{v:.2}");
    let trimmed = text.trim_end_matches('0').trim_end_matches('.');
    if trimmed == "-0" {
        "0".into()
    } else {
        trimmed.into()
    }
}

/// `value` with `decimals` digits after the point; a value that rounds to zero
/// prints as `0`-padded zero without a minus sign.
pub fn number(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_string()
    } else {
        text
    }
}

/// `value` to four significant digits without trailing zeros (`4`, `0.3`, `125.3`,
/// `1.234e-5`); zero prints as `0`.
pub fn short(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return if value.is_finite() {
            "0".into()
        } else {
            value.to_string()
        };
    }
    let exponent = value.abs().log10().floor() as i32;
    if !(-3..6).contains(&exponent) {
        return format!("{value:.3e}");
    }
    let decimals = (3 - exponent).max(0) as usize;
    let text = number(value, decimals);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// `value` with at most `decimals` digits after the point, trailing zeros dropped and
/// zero as `0` (for axis labels of plotters charts, whose tick values may be ±1e-17).
pub fn plain(value: f64, decimals: usize) -> String {
    let text = number(value, decimals);
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    if text == "-0" { "0".into() } else { text }
}

/// Label of an axis tick: `number(value, decimals)`, and plain `0` for zero.
pub fn tick_label(value: f64, decimals: usize) -> String {
    let text = number(value, decimals);
    if text.chars().all(|c| c == '0' || c == '.') {
        "0".into()
    } else {
        text
    }
}

/// Axis ticks covering `[lo, hi]`: about `target` values at a step of 1, 2 or 5 ×
/// 10^k, and the number of decimals their labels need.
pub fn ticks(lo: f64, hi: f64, target: usize) -> (Vec<f64>, usize) {
    let span = (hi - lo).abs().max(1e-12);
    let raw = span / target.max(1) as f64;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * magnitude);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let first = (lo.min(hi) / step).ceil() as i64;
    let last = (lo.max(hi) / step).floor() as i64;
    let values = (first..=last).map(|k| k as f64 * step).collect();
    (values, decimals)
}

/// Colour and dash pattern of one plotted series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SeriesStyle {
    /// CSS colour.
    pub colour: &'static str,
    /// `stroke-dasharray` value (empty: solid).
    pub dash: &'static str,
}

/// Nine colours distinguishable on white (after Wong, "Points of view: Color
/// blindness", Nature Methods 2011, extended by three darker tones).
pub const COLOURS: [&str; 9] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#8C564B", "#999933",
    "#882255",
];

/// Nine dash patterns, paired with [`COLOURS`] so that colour and dash both differ.
pub const DASHES: [&str; 9] = [
    "",
    "7 3",
    "2 2",
    "9 3 2 3",
    "12 4",
    "4 4",
    "1 3",
    "10 2 2 2 2 2",
    "6 2 1 2",
];

/// Style of the `k`-th series (cycling after nine).
pub fn series_style(k: usize) -> SeriesStyle {
    SeriesStyle {
        colour: COLOURS[k % COLOURS.len()],
        dash: DASHES[k % DASHES.len()],
    }
}

/// Style of a 3-RPR metric by its name (its place in [`Metric::all`]), so a metric
/// looks the same in every picture; unknown names get the last style.
pub fn metric_style(name: &str) -> SeriesStyle {
    let k = Metric::all()
        .iter()
        .position(|m| m.name() == name)
        .unwrap_or(COLOURS.len() - 1);
    series_style(k)
}

/// ` stroke="…" stroke-dasharray="…"` attributes of a style.
pub fn stroke_attributes(style: SeriesStyle, width: f64) -> String {
    let mut out = format!(
        r#" stroke="{}" stroke-width="{}" fill="none""#,
        style.colour,
        px(width)
    );
    if !style.dash.is_empty() {
        let _ = write!(out, r#" stroke-dasharray="{}""#, style.dash);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_tick_has_no_minus_sign() {
        let (values, decimals) = ticks(-0.31, 0.29, 6);
        let labels: Vec<String> = values.iter().map(|v| tick_label(*v, decimals)).collect();
        assert!(labels.contains(&"0".to_string()), "{labels:?}");
        assert!(labels.contains(&"-0.3".to_string()), "{labels:?}");
        assert_eq!(number(-1e-17, 2), "0.00");
        assert_eq!(number(-0.5, 1), "-0.5");
    }

    #[test]
    fn short_numbers_drop_trailing_zeros() {
        assert_eq!(short(4.0), "4");
        assert_eq!(short(0.3), "0.3");
        assert_eq!(short(125.2974914), "125.3");
        assert_eq!(short(-0.0859123), "-0.08591");
        assert_eq!(short(0.0), "0");
        assert_eq!(plain(-2.7e-17, 3), "0");
        assert_eq!(plain(-0.25, 3), "-0.25");
    }

    #[test]
    fn ticks_use_one_two_five_steps() {
        let (values, decimals) = ticks(0.0, 10.0, 5);
        assert_eq!(values, vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!(decimals, 0);
        let (values, decimals) = ticks(-0.26, 0.12, 5);
        assert_eq!(decimals, 1);
        assert_eq!(values.len(), 4);
    }

    #[test]
    fn every_metric_has_its_own_colour_and_dash() {
        let styles: Vec<SeriesStyle> = Metric::all()
            .iter()
            .map(|m| metric_style(&m.name()))
            .collect();
        for i in 0..styles.len() {
            for j in 0..i {
                assert_ne!(styles[i].colour, styles[j].colour);
                assert_ne!(styles[i].dash, styles[j].dash);
            }
        }
    }
}
