//! Conditioning maps of the 3RRR and the 3-PRRR over the workspace (docs/theory.md §11.4;
//! Fontes et al. §3–4).
//!
//! The (x, y) workspace is gridded at a fixed orientation α. For the 3RRR (δ = 0) each node
//! has one configuration (fixed working modes) and the map shows its LCI (default
//! `1/κ(Ā)`, Fontes et al. Eq. 15). For the 3-PRRR each δ_i takes `k` equally spaced levels in
//! `[δ_min, δ_max]`; all `k³` combinations are evaluated and the node shows the best index,
//! with the arg-max δ stored (Fontes et al. Figs. 4–5; ties keep the first combination in
//! lexicographic order). Unreachable nodes are `None` (blank in the images). Working modes
//! are fixed (default σ = (+,+,+)) or searched per node with δ ([`ModeSelection::Best`]).
//!
//! Speed: the inverse kinematics of a leg depends only on its own δ_i, so each node first
//! computes the 3·k leg solutions (rows of Ā and B̄), then assembles the k³ matrices.
//! Nodes are evaluated in parallel with results in grid order (deterministic).

use crate::index::prrr::{LciVariant, lci_from_parts};
use crate::mechanism::prrr::{
    Pose, PrrrDesign, PrrrError, Robot, WorkingMode, a_row, b_prismatic, b_revolute,
};
use nalgebra::Matrix3;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::io::Write;
use thiserror::Error;

/// Errors of the map module.
#[derive(Debug, Error)]
pub enum MapError {
    /// Invalid design.
    #[error(transparent)]
    Design(#[from] PrrrError),
    /// Invalid grid option.
    #[error("map option `{field}`: {reason}")]
    InvalidOption {
        /// Option name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// Writing CSV or SVG failed.
    #[error("writing {what}: {reason}")]
    Output {
        /// Which output.
        what: &'static str,
        /// Underlying error.
        reason: String,
    },
}

/// Largest grid accepted by [`conditioning_map`] (nodes).
pub const MAX_NODES: usize = 4_000_000;
/// Largest number of δ levels k accepted (k³ combinations per node).
pub const MAX_DELTA_LEVELS: usize = 200;

/// Options of [`conditioning_map`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MapOptions {
    /// 3RRR or 3-PRRR.
    pub robot: Robot,
    /// Fixed orientation α (rad), default 0.
    pub alpha: f64,
    /// x extent of the grid (m).
    pub x_range: (f64, f64),
    /// y extent of the grid (m).
    pub y_range: (f64, f64),
    /// Grid nodes along x (≥ 2).
    pub nx: usize,
    /// Grid nodes along y (≥ 2).
    pub ny: usize,
    /// Levels k of each δ_i for the 3-PRRR (≥ 1; 1 means δ = midpoint of the stroke).
    pub delta_levels: usize,
    /// Working modes: fixed (the same at every node) or the best per node.
    pub modes: ModeSelection,
    /// Index mapped: `1/κ(Ā)` (Fontes et al., default) or `1/κ(Ā⁻¹B̄)`.
    pub variant: LciVariant,
}

impl Default for MapOptions {
    /// 3-PRRR, α = 0, x ∈ [−0.4, 0.4], y ∈ [−0.25, 0.45] (the whole 3-PRRR workspace of
    /// both presets) with 161×141 nodes (5 mm), k = 11, σ = (+,+,+), `1/κ(Ā)`.
    fn default() -> Self {
        Self {
            robot: Robot::ThreePrrr,
            alpha: 0.0,
            x_range: (-0.4, 0.4),
            y_range: (-0.25, 0.45),
            nx: 161,
            ny: 141,
            delta_levels: 11,
            modes: ModeSelection::Fixed([WorkingMode::Plus; 3]),
            variant: LciVariant::DirectA,
        }
    }
}

/// Working modes used by a map.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum ModeSelection {
    /// The same σ at every node (docs/theory.md §11.4 default; Fontes et al. does not
    /// state its modes).
    Fixed([WorkingMode; 3]),
    /// Each leg's σ is searched with its δ levels: the node shows the best of `(2k)³`
    /// configurations (for the 3RRR: the best of the 8 assembly modes).
    Best,
}

impl ModeSelection {
    fn per_leg(self, leg: usize) -> &'static [WorkingMode] {
        const PLUS: &[WorkingMode] = &[WorkingMode::Plus];
        const MINUS: &[WorkingMode] = &[WorkingMode::Minus];
        const BOTH: &[WorkingMode] = &[WorkingMode::Plus, WorkingMode::Minus];
        match self {
            ModeSelection::Fixed(m) => match m[leg] {
                WorkingMode::Plus => PLUS,
                WorkingMode::Minus => MINUS,
            },
            ModeSelection::Best => BOTH,
        }
    }
}

/// A computed conditioning map. Node `(ix, iy)` is at `(xs[ix], ys[iy])`, stored at `iy·nx + ix`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ConditioningMap {
    /// Options used.
    pub options: MapOptions,
    /// Node x coordinates.
    pub xs: Vec<f64>,
    /// Node y coordinates.
    pub ys: Vec<f64>,
    /// Best index per node, `None` when unreachable for every δ combination.
    pub values: Vec<Option<f64>>,
    /// Arg-max δ per node (3RRR: zeros).
    pub best_delta: Vec<Option<[f64; 3]>>,
    /// Working modes of the arg-max configuration per node.
    pub best_modes: Vec<Option<[WorkingMode; 3]>>,
}

impl ConditioningMap {
    /// Number of reachable nodes.
    pub fn reachable_nodes(&self) -> usize {
        self.values.iter().flatten().count()
    }

    /// Smallest value over reachable nodes (`None` if none is reachable).
    pub fn min_value(&self) -> Option<f64> {
        self.values.iter().flatten().copied().reduce(f64::min)
    }

    /// Largest value over reachable nodes.
    pub fn max_value(&self) -> Option<f64> {
        self.values.iter().flatten().copied().reduce(f64::max)
    }

    /// Number of nodes with value ≥ `threshold`.
    pub fn nodes_at_least(&self, threshold: f64) -> usize {
        self.values
            .iter()
            .flatten()
            .filter(|&&v| v >= threshold)
            .count()
    }

    /// Area of one grid cell (m²): node counts times this give areas.
    pub fn cell_area(&self) -> f64 {
        let o = &self.options;
        (o.x_range.1 - o.x_range.0) / (o.nx - 1) as f64 * (o.y_range.1 - o.y_range.0)
            / (o.ny - 1) as f64
    }

    /// Number of unreachable holes: 4-connected components of unreachable nodes that do not
    /// touch the border of the grid (Fontes et al.: the 3RRR's three unreachable circles).
    pub fn unreachable_holes(&self) -> usize {
        let (nx, ny) = (self.xs.len(), self.ys.len());
        let mut label = vec![false; nx * ny];
        let mut holes = 0;
        let mut stack = Vec::new();
        for start in 0..nx * ny {
            if self.values[start].is_some() || label[start] {
                continue;
            }
            label[start] = true;
            stack.push(start);
            let mut touches_border = false;
            while let Some(k) = stack.pop() {
                let (ix, iy) = (k % nx, k / nx);
                if ix == 0 || iy == 0 || ix == nx - 1 || iy == ny - 1 {
                    touches_border = true;
                }
                let mut visit = |j: usize| {
                    if self.values[j].is_none() && !label[j] {
                        label[j] = true;
                        stack.push(j);
                    }
                };
                if ix > 0 {
                    visit(k - 1);
                }
                if ix + 1 < nx {
                    visit(k + 1);
                }
                if iy > 0 {
                    visit(k - nx);
                }
                if iy + 1 < ny {
                    visit(k + nx);
                }
            }
            if !touches_border {
                holes += 1;
            }
        }
        holes
    }

    /// Value at node `(ix, iy)`.
    pub fn value(&self, ix: usize, iy: usize) -> Option<f64> {
        self.values[iy * self.xs.len() + ix]
    }

    /// Write the map as CSV: `x,y,value,delta1,delta2,delta3` (empty fields when unreachable).
    pub fn write_csv<W: Write>(&self, writer: W) -> Result<(), MapError> {
        let err = |e: csv::Error| MapError::Output {
            what: "CSV",
            reason: e.to_string(),
        };
        let mut w = csv::Writer::from_writer(writer);
        w.write_record([
            "x",
            "y",
            self.options.variant.key(),
            "delta1",
            "delta2",
            "delta3",
        ])
        .map_err(err)?;
        for (iy, &y) in self.ys.iter().enumerate() {
            for (ix, &x) in self.xs.iter().enumerate() {
                let k = iy * self.xs.len() + ix;
                let field = |v: Option<f64>| v.map(|v| format!("{v:.9}")).unwrap_or_default();
                let d = self.best_delta[k];
                w.write_record([
                    format!("{x:.6}"),
                    format!("{y:.6}"),
                    field(self.values[k]),
                    field(d.map(|d| d[0])),
                    field(d.map(|d| d[1])),
                    field(d.map(|d| d[2])),
                ])
                .map_err(err)?;
            }
        }
        w.flush().map_err(|e| MapError::Output {
            what: "CSV",
            reason: e.to_string(),
        })
    }

    /// Draw the map as an SVG heat map (plotters): the index in [0, 1]; for the 3-PRRR also
    /// the three arg-max δ maps (Fontes et al. Fig. 5). Unreachable nodes stay blank (white).
    pub fn write_svg(&self, path: &std::path::Path, stroke: (f64, f64)) -> Result<(), MapError> {
        draw_svg(self, path, stroke).map_err(|reason| MapError::Output {
            what: "SVG",
            reason,
        })
    }
}

/// Equally spaced values from `lo` to `hi` (`n ≥ 2`), or the midpoint for `n = 1`.
fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![0.5 * (lo + hi)];
    }
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

/// One leg's contribution: row of Ā and the homogenised entries of its row of B̄.
#[derive(Clone, Copy)]
struct LegRow {
    a_bar: [f64; 3],
    b_bar: [f64; 2],
}

/// Solve leg `leg` alone at `pose` with input δ and form its rows with the same
/// functions as [`crate::mechanism::prrr::PrrrConfiguration`] (bit-identical values).
fn leg_row(
    design: &PrrrDesign,
    leg: usize,
    pose: &Pose,
    delta: f64,
    mode: WorkingMode,
) -> Option<LegRow> {
    let s = design.solve_leg(leg, pose, delta, mode).ok()?;
    let mut a_bar = a_row(&s.elbow, &s.platform, pose);
    a_bar[2] /= design.characteristic_length;
    Some(LegRow {
        a_bar,
        b_bar: [
            b_revolute(&s.base, &s.elbow, &s.platform),
            design.pitch / (2.0 * PI) * b_prismatic(&s.elbow, &s.platform, design.gamma[leg]),
        ],
    })
}

/// Index of three assembled leg rows.
fn index_of_rows(rows: [&LegRow; 3], robot: Robot, variant: LciVariant) -> f64 {
    let a = Matrix3::from_fn(|i, j| rows[i].a_bar[j]);
    lci_from_parts(
        &a,
        &[rows[0].b_bar, rows[1].b_bar, rows[2].b_bar],
        robot,
        variant,
    )
}

/// Compute a conditioning map (docs/theory.md §11.4).
pub fn conditioning_map(
    design: &PrrrDesign,
    options: &MapOptions,
) -> Result<ConditioningMap, MapError> {
    design.validate()?;
    let bad = |field: &'static str, reason: String| Err(MapError::InvalidOption { field, reason });
    for (field, (lo, hi)) in [("x_range", options.x_range), ("y_range", options.y_range)] {
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return bad(field, format!("[{lo}, {hi}] must be finite with min < max"));
        }
    }
    if options.nx < 2 || options.ny < 2 {
        return bad(
            "nx/ny",
            format!("{}×{} grid: at least 2×2 nodes", options.nx, options.ny),
        );
    }
    if !options.alpha.is_finite() {
        return bad("alpha", format!("{} must be finite", options.alpha));
    }
    if options.nx.saturating_mul(options.ny) > MAX_NODES {
        return bad(
            "nx/ny",
            format!(
                "{}×{} grid exceeds {MAX_NODES} nodes",
                options.nx, options.ny
            ),
        );
    }
    if options.delta_levels == 0 || options.delta_levels > MAX_DELTA_LEVELS {
        return bad(
            "delta_levels",
            format!("{} not in 1..={MAX_DELTA_LEVELS}", options.delta_levels),
        );
    }
    let xs = linspace(options.x_range.0, options.x_range.1, options.nx);
    let ys = linspace(options.y_range.0, options.y_range.1, options.ny);
    let levels = match options.robot {
        Robot::ThreeRrr => vec![0.0],
        Robot::ThreePrrr => linspace(
            design.delta_range.0,
            design.delta_range.1,
            options.delta_levels,
        ),
    };
    // Candidates of each leg: (δ level, working mode).
    let candidates: Vec<Vec<(f64, WorkingMode)>> = (0..3)
        .map(|leg| {
            levels
                .iter()
                .flat_map(|&d| options.modes.per_leg(leg).iter().map(move |&m| (d, m)))
                .collect()
        })
        .collect();
    let m = candidates[0].len();
    type Node = (Option<f64>, Option<[f64; 3]>, Option<[WorkingMode; 3]>);
    let nodes: Vec<Node> = (0..options.nx * options.ny)
        .into_par_iter()
        .map_init(
            || vec![None::<LegRow>; 3 * m],
            |rows, node| {
                let pose = Pose::new(xs[node % options.nx], ys[node / options.nx], options.alpha);
                for (leg, list) in candidates.iter().enumerate() {
                    for (j, &(delta, mode)) in list.iter().enumerate() {
                        rows[leg * m + j] = leg_row(design, leg, &pose, delta, mode);
                    }
                }
                let mut best: Option<(f64, [usize; 3])> = None;
                for j0 in 0..m {
                    let Some(r0) = &rows[j0] else { continue };
                    for j1 in 0..m {
                        let Some(r1) = &rows[m + j1] else { continue };
                        for j2 in 0..m {
                            let Some(r2) = &rows[2 * m + j2] else {
                                continue;
                            };
                            let value = index_of_rows([r0, r1, r2], options.robot, options.variant);
                            if best.is_none_or(|(b, _)| value > b) {
                                best = Some((value, [j0, j1, j2]));
                            }
                        }
                    }
                }
                match best {
                    Some((value, j)) => (
                        Some(value),
                        Some([0, 1, 2].map(|leg| candidates[leg][j[leg]].0)),
                        Some([0, 1, 2].map(|leg| candidates[leg][j[leg]].1)),
                    ),
                    None => (None, None, None),
                }
            },
        )
        .collect();
    let mut values = Vec::with_capacity(nodes.len());
    let mut best_delta = Vec::with_capacity(nodes.len());
    let mut best_modes = Vec::with_capacity(nodes.len());
    for (v, d, w) in nodes {
        values.push(v);
        best_delta.push(d);
        best_modes.push(w);
    }
    Ok(ConditioningMap {
        options: options.clone(),
        xs,
        ys,
        values,
        best_delta,
        best_modes,
    })
}

/// Viridis-like colour for `t ∈ [0, 1]` (piecewise-linear through five anchor colours).
fn colour(t: f64) -> plotters::style::RGBColor {
    const ANCHORS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let position = t * 4.0;
    let i = (position.floor() as usize).min(3);
    let f = position - i as f64;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    plotters::style::RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The x and y ranges that show `x` and `y` at one scale (a metre is as long across as
/// up) in a plot area of `pixels = (width, height)`: the range with the larger scale is
/// widened about its centre, `scale = min(width / Δx, height / Δy)`.
fn equal_scale_view(x: (f64, f64), y: (f64, f64), pixels: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let scale = (pixels.0 / (x.1 - x.0)).min(pixels.1 / (y.1 - y.0));
    let widen = |(lo, hi): (f64, f64), length: f64| {
        let (centre, half) = (0.5 * (lo + hi), 0.5 * length / scale);
        (centre - half, centre + half)
    };
    (widen(x, pixels.0), widen(y, pixels.1))
}

/// Width in pixels of a map panel's colour-bar column: the bar (about 24 px), its tick
/// marks and its tick labels.
const COLOUR_BAR_WIDTH: u32 = 100;

fn draw_svg(
    map: &ConditioningMap,
    path: &std::path::Path,
    stroke: (f64, f64),
) -> Result<(), String> {
    use plotters::prelude::*;
    let o = &map.options;
    // Title, colour-bar caption, value of node k, colour range.
    type Panel<'a> = (
        String,
        String,
        Box<dyn Fn(usize) -> Option<f64> + 'a>,
        (f64, f64),
    );
    let panels: Vec<Panel> = {
        let mut p: Vec<Panel> = vec![(
            format!(
                "{} {} (alpha = {:.3} rad), min {:.3}",
                match o.robot {
                    Robot::ThreeRrr => "3RRR",
                    Robot::ThreePrrr => "3PRRR",
                },
                o.variant.formula(),
                o.alpha,
                map.min_value().unwrap_or(f64::NAN)
            ),
            o.variant.formula().to_string(),
            Box::new(|k| map.values[k]),
            (0.0, 1.0),
        )];
        if o.robot == Robot::ThreePrrr {
            for leg in 0..3 {
                p.push((
                    format!("arg-max delta{} (m)", leg + 1),
                    format!("δ{} (m)", leg + 1),
                    Box::new(move |k| map.best_delta[k].map(|d| d[leg])),
                    stroke,
                ));
            }
        }
        p
    };
    let columns = if panels.len() > 1 { 2 } else { 1 };
    let rows = panels.len().div_ceil(columns);
    let (width, height) = (580u32, 540u32);
    let root =
        SVGBackend::new(path, (width * columns as u32, height * rows as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let areas = root.split_evenly((rows, columns));
    let dx = (o.x_range.1 - o.x_range.0) / (o.nx - 1) as f64;
    let dy = (o.y_range.1 - o.y_range.0) / (o.ny - 1) as f64;
    // plotters writes font sizes divided by 1.24: 17 is 13.7 px, 18 is 14.5 px.
    let (labels, descriptions, titles) = (17, 18, 18);
    for ((title, caption, value, (lo, hi)), area) in panels.iter().zip(&areas) {
        // The map on the left, its colour bar (with the labels right of it) on the
        // right.
        let (main, bar) = area.split_horizontally(width - COLOUR_BAR_WIDTH);
        let main = main
            .titled(title, ("sans-serif", titles))
            .map_err(|e| e.to_string())?;
        // Room under the x tick labels for the axis title, and left of the y tick
        // labels for the rotated one.
        let (margin, x_labels, y_labels) = (8u32, 52u32, 66u32);
        let (plot_width, plot_height) = main.dim_in_pixel();
        let (x_view, y_view) = equal_scale_view(
            (o.x_range.0 - dx / 2.0, o.x_range.1 + dx / 2.0),
            (o.y_range.0 - dy / 2.0, o.y_range.1 + dy / 2.0),
            (
                plot_width.saturating_sub(2 * margin + y_labels).max(1) as f64,
                plot_height.saturating_sub(2 * margin + x_labels).max(1) as f64,
            ),
        );
        let mut chart = ChartBuilder::on(&main)
            .margin(margin)
            .margin_right(22)
            .x_label_area_size(x_labels)
            .y_label_area_size(y_labels)
            .build_cartesian_2d(x_view.0..x_view.1, y_view.0..y_view.1)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(7)
            .y_labels(9)
            .x_desc("x (m)")
            .y_desc("y (m)")
            .label_style(("sans-serif", labels))
            .axis_desc_style(("sans-serif", descriptions))
            .x_label_formatter(&|v| crate::io::svg::plain(*v, 3))
            .y_label_formatter(&|v| crate::io::svg::plain(*v, 3))
            .draw()
            .map_err(|e| e.to_string())?;
        let span = if hi > lo { hi - lo } else { 1.0 };
        chart
            .draw_series((0..map.values.len()).filter_map(|k| {
                let v = value(k)?;
                let (x, y) = (map.xs[k % o.nx], map.ys[k / o.nx]);
                Some(Rectangle::new(
                    [(x - dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)],
                    colour((v - lo) / span).filled(),
                ))
            }))
            .map_err(|e| e.to_string())?;
        // Colour bar: its caption above it, its tick labels 10 px right of it.
        bar.draw_text(
            caption,
            &("sans-serif", labels).into_text_style(&bar),
            (6, 34),
        )
        .map_err(|e| e.to_string())?;
        let mut legend = ChartBuilder::on(&bar)
            .margin_top(60)
            .margin_bottom(70)
            .margin_left(6)
            .margin_right(4)
            .right_y_label_area_size(COLOUR_BAR_WIDTH - 40)
            .build_cartesian_2d(0.0..1.0, *lo..*hi)
            .map_err(|e| e.to_string())?;
        legend
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(6)
            .set_tick_mark_size(LabelAreaPosition::Right, 5)
            .label_style(("sans-serif", labels))
            .y_label_formatter(&|v| crate::io::svg::plain(*v, 3))
            .draw()
            .map_err(|e| e.to_string())?;
        let steps = 100;
        legend
            .draw_series((0..steps).map(|i| {
                let a = lo + span * i as f64 / steps as f64;
                let b = lo + span * (i + 1) as f64 / steps as f64;
                Rectangle::new(
                    [(0.0, a), (1.0, b)],
                    colour(i as f64 / (steps - 1) as f64).filled(),
                )
            }))
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::equal_scale_view;

    #[test]
    fn map_view_has_one_scale_on_both_axes() {
        let ((x0, x1), (y0, y1)) = equal_scale_view((-0.4, 0.4), (-0.25, 0.45), (369.0, 430.0));
        let (sx, sy) = (369.0 / (x1 - x0), 430.0 / (y1 - y0));
        assert!((sx - sy).abs() < 1e-9 * sx, "{sx} vs {sy}");
        // The data stay inside the view, which is centred on them.
        assert!(x0 <= -0.4 && x1 >= 0.4 && y0 <= -0.25 && y1 >= 0.45);
        assert!((x0 + x1).abs() < 1e-12 && (y0 + y1 - 0.2).abs() < 1e-12);
    }
}
