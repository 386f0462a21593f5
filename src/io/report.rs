//! Self-contained HTML report of a curve (3-RPR or 3-RRR): the distance curves
//! against the motion parameter τ (an SVG chart), a slider on τ, and the drawing of
//! `K` with every metric's (3-RRR: every singularity kind's) closest singular
//! configuration `K′` at the selected τ, redrawn as the slider moves. Everything is in
//! the one file: the data as JSON, one pre-rendered drawing per pose
//! ([`MechanismScene::svg`] of a 3-RPR or 3-RRR scene, all with one view
//! so the robot does not jump), and a short hand-written script; no network access is
//! needed.
//!
//! Opened with the URL hash `#test`, the page moves the slider from the first to the
//! last pose on load and writes what changed (and any script error) as JSON into
//! `<pre id="test-result">`, for headless browser tests.

use super::chart::{PlotFrame, TickStyle, grid_and_ticks};
use super::draw::{Extent, Scene};
use super::rrr_draw::{RrrScene, rrr_style};
use super::scene::{MechanismScene, scene_extent};
use super::svg::{SeriesStyle, escape, metric_style, px, short, stroke_attributes};
use crate::mechanism::rpr::Design;
use crate::mechanism::rrr::RrrConfiguration;
use crate::pipeline::curve::CurveResult;
use crate::pipeline::rrr::curve::{RrrCurveResult, RrrPoseResult};
use serde::Serialize;
use std::fmt::Write;

/// One curve of the chart: a value per pose (`None` where undefined).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReportCurve {
    /// Legend text.
    pub label: String,
    /// Colour and dash pattern.
    #[serde(skip)]
    pub style: SeriesStyle,
    /// Value at each pose.
    pub values: Vec<Option<f64>>,
}

/// What a report shows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// Page and chart title.
    pub title: String,
    /// One line under the title saying what the quantities are.
    pub description: String,
    /// Title of the value axis (with its unit).
    pub y_title: String,
    /// τ of each pose.
    pub tau: Vec<f64>,
    /// `[x, y, φ]` of each pose.
    pub poses: Vec<[f64; 3]>,
    /// The curves.
    pub curves: Vec<ReportCurve>,
    /// Singular parameter values with the label of their marker (`S = 0`, …), marked
    /// on the chart.
    pub singular: Vec<(f64, String)>,
    /// One SVG drawing per pose.
    pub frames: Vec<String>,
}

/// How the report chart's ticks look.
const REPORT_TICKS: TickStyle = TickStyle {
    font_size: 12.0,
    counts: (8, 7),
    tau_label_drop: 16.0,
    zero_line: "#999",
};

/// Chart geometry in pixels.
const CHART: (f64, f64, f64, f64, f64, f64) = (640.0, 400.0, 72.0, 16.0, 548.0, 320.0);

/// A report of signed distances (in the design's length unit) along a motion, both
/// mechanisms' kind: `(title, description)`, `(τ, [x, y, φ])` of each pose, and the
/// scene at each pose, all drawn in the one view that holds them (the frames the
/// slider switches between, so the robot does not jump).
fn signed_distance_report<S: MechanismScene>(
    (title, description): (&str, &str),
    poses: Vec<(f64, [f64; 3])>,
    scenes: &[S],
    curves: Vec<ReportCurve>,
    singular: Vec<(f64, String)>,
) -> Report {
    let view = scenes
        .iter()
        .map(scene_extent)
        .fold(Extent::empty(), |a, b| a.union(&b));
    Report {
        title: title.into(),
        description: description.into(),
        y_title: "signed distance D (design length unit)".into(),
        tau: poses.iter().map(|p| p.0).collect(),
        poses: poses.iter().map(|p| p.1).collect(),
        curves,
        singular,
        frames: scenes.iter().map(|scene| scene.svg(&view)).collect(),
    }
}

/// The report of a 3-RPR curve: signed distance of each metric in `metrics` against
/// τ, and per pose the drawing of `K` and each metric's `K′`.
pub fn rpr_report(
    design: &Design,
    result: &CurveResult,
    metrics: &[String],
    singular: &[f64],
) -> Report {
    let scenes: Vec<Scene> = result
        .poses
        .iter()
        .map(|p| {
            let mut scene = Scene::of_pose(design, p, metrics, "design length unit");
            scene.title = format!("τ = {}: {}", short(p.tau), scene.title);
            scene
        })
        .collect();
    let curves = metrics
        .iter()
        .map(|name| ReportCurve {
            label: name.clone(),
            style: metric_style(name),
            values: result
                .poses
                .iter()
                .map(|p| p.metrics.get(name).map(|m| m.signed_distance))
                .collect(),
        })
        .collect();
    signed_distance_report(
        (
            "3-RPR distance to the nearest singularity along the motion",
            "D(K, K′): distance from the configuration K to the closest singular configuration K′ under each metric (platform part / base part: plate, bars or rigid), signed with S(K), the singularity polynomial (S = 0: leg lines concurrent or parallel); τ: the motion parameter.",
        ),
        result.poses.iter().map(|p| (p.tau, p.pose)).collect(),
        &scenes,
        curves,
        singular.iter().map(|&t| (t, "S = 0".to_string())).collect(),
    )
}

/// The report of a 3-RRR curve: the signed distances to the parallel and the three
/// leg singularities against τ, and per pose the drawing of `K` and each kind's
/// closest singular `K′`. `configurations` holds `K` at each pose of `result`.
pub fn rrr_report(configurations: &[RrrConfiguration], result: &RrrCurveResult) -> Report {
    let scenes: Vec<RrrScene> = result
        .poses
        .iter()
        .zip(configurations)
        .map(|(p, k)| {
            let mut scene = RrrScene::of_pose(k, p, "design length unit");
            scene.title = format!("τ = {}: {}", short(p.tau), scene.title);
            scene
        })
        .collect();
    type Getter = fn(&RrrPoseResult) -> Option<f64>;
    let getters: [(&str, Getter); 4] = [
        ("parallel", |p| p.parallel),
        ("leg1", |p| p.leg1),
        ("leg2", |p| p.leg2),
        ("leg3", |p| p.leg3),
    ];
    let curves = getters
        .iter()
        .map(|(name, get)| ReportCurve {
            label: name.to_string(),
            style: rrr_style(name),
            values: result.poses.iter().map(get).collect(),
        })
        .collect();
    let mut singular: Vec<(f64, String)> = result
        .parallel_singular_parameters
        .iter()
        .map(|&t| (t, "parallel singular".to_string()))
        .collect();
    for (leg, taus) in result.leg_singular_parameters.iter().enumerate() {
        singular.extend(
            taus.iter()
                .map(|&t| (t, format!("leg {} singular", leg + 1))),
        );
    }
    singular.sort_by(|a, b| a.0.total_cmp(&b.0));
    signed_distance_report(
        (
            "3-RRR distance to the parallel and leg singularities along the motion",
            "D(K, K′): distance from the configuration K to the closest singular configuration K′ of each kind under the all-deformable metric (base, platform and six links may all move); parallel: the distal-link lines B′C′ concurrent or parallel, legN: O′, B′, C′ of leg N collinear; each curve signed with its determinant at K; τ: the motion parameter.",
        ),
        result.poses.iter().map(|p| (p.tau, p.pose)).collect(),
        &scenes,
        curves,
        singular,
    )
}

fn chart_svg(report: &Report) -> String {
    let (width, height, left, top, w, h) = CHART;
    let t0 = report.tau.first().copied().unwrap_or(0.0);
    let t1 = report.tau.last().copied().unwrap_or(1.0);
    let (t0, t1) = if t1 > t0 {
        (t0, t1)
    } else {
        (t0 - 0.5, t0 + 0.5)
    };
    let values = report
        .curves
        .iter()
        .flat_map(|c| c.values.iter().flatten().copied());
    let (lo, hi) = values.fold((0.0f64, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.05 * (hi - lo).max(1e-9);
    let (lo, hi) = (lo - pad, hi + pad);
    let x = |t: f64| left + (t - t0) / (t1 - t0) * w;
    let y = |v: f64| top + h - (v - lo) / (hi - lo) * h;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" id="chart" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" data-left="{2}" data-width="{3}" data-t0="{4}" data-t1="{5}">"#,
        px(width),
        px(height),
        px(left),
        px(w),
        t0,
        t1
    );
    let _ = writeln!(
        out,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#fff" stroke="#888"/>"##,
        px(left),
        px(top),
        px(w),
        px(h)
    );
    let frame = PlotFrame {
        left,
        top,
        width: w,
        height: h,
    };
    grid_and_ticks(&mut out, &frame, ((t0, t1), (lo, hi)), &REPORT_TICKS);
    for (tau, _) in &report.singular {
        let _ = writeln!(
            out,
            r##"<line class="singular" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#444" stroke-dasharray="3 3"/>"##,
            px(x(*tau)),
            px(top),
            px(top + h),
        );
    }
    for curve in &report.curves {
        let style_attributes = stroke_attributes(curve.style, 2.0);
        let mut segment: Vec<String> = Vec::new();
        let flush = |segment: &mut Vec<String>, out: &mut String| {
            if segment.len() > 1 {
                let _ = writeln!(
                    out,
                    r#"<polyline class="curve" data-label="{}" points="{}"{style_attributes}/>"#,
                    escape(&curve.label),
                    segment.join(" ")
                );
            }
            segment.clear();
        };
        for (t, v) in report.tau.iter().zip(&curve.values) {
            match v {
                Some(v) => segment.push(format!("{},{}", px(x(*t)), px(y(*v)))),
                None => flush(&mut segment, &mut out),
            }
        }
        flush(&mut segment, &mut out);
    }
    for (k, (tau, label)) in report.singular.iter().enumerate() {
        // Over the curves, with a white halo; right of their line, or left of it in
        // the chart's right half; stacked in three rows so neighbours do not overprint.
        let right_half = x(*tau) > left + 0.5 * w;
        let _ = writeln!(
            out,
            r##"<text class="singular-label" x="{}" y="{}" font-size="11" fill="#444" stroke="#fff" stroke-width="3" paint-order="stroke" text-anchor="{}">{} at τ = {}</text>"##,
            px(x(*tau) + if right_half { -4.0 } else { 4.0 }),
            px(top + 12.0 + 13.0 * (k % 3) as f64),
            if right_half { "end" } else { "start" },
            escape(label),
            super::svg::number(*tau, 4)
        );
    }
    let _ = writeln!(
        out,
        r##"<line id="cursor" x1="{0}" y1="{1}" x2="{0}" y2="{2}" stroke="#c00" stroke-width="2"/>"##,
        px(left),
        px(top),
        px(top + h)
    );
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" font-size="13" text-anchor="middle">motion parameter τ</text>"#,
        px(left + 0.5 * w),
        px(top + h + 36.0)
    );
    let _ = writeln!(
        out,
        r#"<text x="{0}" y="{1}" font-size="13" text-anchor="middle" transform="rotate(-90 {0} {1})">{2}</text>"#,
        px(18.0),
        px(top + 0.5 * h),
        escape(&report.y_title)
    );
    out.push_str("</svg>\n");
    out
}

fn legend_html(report: &Report) -> String {
    let mut out = String::from("<ul id=\"chart-legend\">\n");
    for curve in &report.curves {
        let _ = writeln!(
            out,
            r#"<li><label><input type="checkbox" checked data-label="{1}"><svg width="36" height="10"><line x1="0" y1="5" x2="36" y2="5"{0}/></svg> {1}</label></li>"#,
            stroke_attributes(curve.style, 2.5),
            escape(&curve.label)
        );
    }
    out.push_str("</ul>\n");
    out
}

const STYLE: &str = "body{font-family:sans-serif;margin:16px;color:#222}h1{font-size:20px;margin:0 0 4px}p.description{max-width:1100px;font-size:14px;color:#444}#layout{display:grid;grid-template-columns:640px minmax(0,1fr);gap:16px;align-items:start}@media (max-width:1100px){#layout{grid-template-columns:minmax(0,1fr)}}#chart{cursor:crosshair}#chart-legend{list-style:none;padding:0;margin:4px 0;display:flex;flex-wrap:wrap;gap:4px 14px;max-width:640px;font-size:13px}#controls{margin:8px 0;font-size:14px}#tau-slider{width:548px;margin-left:72px}#readout{font-size:13px;border-collapse:collapse}#readout td{padding:1px 8px;border-bottom:1px solid #eee}#drawing svg{width:100%;max-width:1040px;height:auto}";

/// The script: slider and chart clicks select a pose; the cursor and the drawing follow.
const SCRIPT: &str = r#"(function () {
  var data = JSON.parse(document.getElementById('report-data').textContent);
  var slider = document.getElementById('tau-slider');
  var drawing = document.getElementById('drawing');
  var chart = document.getElementById('chart');
  var cursor = document.getElementById('cursor');
  var readout = document.getElementById('readout');
  var left = +chart.dataset.left, width = +chart.dataset.width;
  var t0 = +chart.dataset.t0, t1 = +chart.dataset.t1;
  function fmt(v) { return v === null ? '–' : (Math.abs(v) < 5e-13 ? '0' : v.toPrecision(5)); }
  function show(i) {
    slider.value = i;
    var x = left + (data.tau[i] - t0) / (t1 - t0) * width;
    cursor.setAttribute('x1', x);
    cursor.setAttribute('x2', x);
    drawing.innerHTML = data.frames[i];
    var p = data.poses[i];
    var rows = '<tr><td>τ</td><td>' + fmt(data.tau[i]) + '</td></tr>' +
      '<tr><td>pose x, y, φ (rad)</td><td>' + fmt(p[0]) + ', ' + fmt(p[1]) + ', ' + fmt(p[2]) + '</td></tr>';
    data.curves.forEach(function (c) {
      rows += '<tr><td>' + c.label + '</td><td>' + fmt(c.values[i]) + '</td></tr>';
    });
    readout.innerHTML = rows;
    applyVisibility();
  }
  var hidden = {};
  function applyVisibility() {
    drawing.querySelectorAll('g.closest, g.zoom-closest').forEach(function (g) {
      g.style.display = hidden[g.getAttribute('data-metric')] ? 'none' : '';
    });
    chart.querySelectorAll('polyline.curve').forEach(function (line) {
      line.style.display = hidden[line.getAttribute('data-label')] ? 'none' : '';
    });
  }
  document.querySelectorAll('#chart-legend input').forEach(function (box) {
    box.addEventListener('change', function () {
      hidden[box.getAttribute('data-label')] = !box.checked;
      applyVisibility();
    });
  });
  slider.addEventListener('input', function () { show(+slider.value); });
  chart.addEventListener('click', function (event) {
    var box = chart.getBoundingClientRect();
    var px = (event.clientX - box.left) * (chart.viewBox.baseVal.width / box.width);
    var tau = t0 + (px - left) / width * (t1 - t0), best = 0;
    data.tau.forEach(function (t, k) { if (Math.abs(t - tau) < Math.abs(data.tau[best] - tau)) best = k; });
    show(best);
  });
  show(0);
  if (location.hash === '#test') {
    var before = drawing.innerHTML, cursorBefore = cursor.getAttribute('x1');
    slider.value = data.tau.length - 1;
    slider.dispatchEvent(new Event('input'));
    var box = document.querySelector('#chart-legend input');
    box.checked = false;
    box.dispatchEvent(new Event('change'));
    var visible = 0;
    drawing.querySelectorAll('g.closest').forEach(function (g) { if (g.style.display !== 'none') visible += 1; });
    var result = {
      visible_after_untick: visible,
      poses: data.tau.length,
      slider: +slider.value,
      drawing_changed: drawing.innerHTML !== before,
      cursor_moved: cursor.getAttribute('x1') !== cursorBefore,
      closest_drawn: drawing.querySelectorAll('g.closest').length,
      legs_of_k: drawing.querySelectorAll('#K line.leg').length,
      errors: window.reportErrors
    };
    document.getElementById('test-result').textContent = JSON.stringify(result);
  }
})();"#;

/// Collects script errors and `console.error` calls for the `#test` mode.
const ERROR_TRAP: &str = "window.reportErrors=[];window.addEventListener('error',function(e){window.reportErrors.push(String(e.message))});(function(){var f=console.error;console.error=function(){window.reportErrors.push(Array.prototype.join.call(arguments,' '));f.apply(console,arguments)}})();";

/// The report as one HTML page.
pub fn report_html(report: &Report) -> String {
    let data = serde_json::json!({
        "tau": report.tau,
        "poses": report.poses,
        "curves": report.curves,
        "frames": report.frames,
    });
    // `</` inside a script element would end it; `<\/` is the same JSON string.
    let data = data.to_string().replace("</", "<\\/");
    let last = report.tau.len().saturating_sub(1);
    format!(
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>{STYLE}</style>
<script>{ERROR_TRAP}</script>
</head>
<body>
<h1>{title}</h1>
<p class="description">{description} Move the slider or click the chart to choose τ; untick a curve to hide it and its K′.</p>
<div id="layout">
<div>
{chart}<div id="controls"><input id="tau-slider" type="range" min="0" max="{last}" step="1" value="0" aria-label="pose along the motion"></div>
{legend}<table id="readout"></table>
</div>
<div id="drawing"></div>
</div>
<pre id="test-result"></pre>
<script type="application/json" id="report-data">{data}</script>
<script>{SCRIPT}</script>
</body>
</html>
"#,
        title = escape(&report.title),
        description = escape(&report.description),
        chart = chart_svg(report),
        legend = legend_html(report),
    )
}
