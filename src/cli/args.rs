//! The option groups several commands share, each a `#[command(flatten)]` struct, so
//! every shared option is declared once with one help text: the design and its motion,
//! one pose, the metrics, the output table and its plot, the HTML report, the worker
//! threads and seed, and the 3-RRR working modes. What a command does with
//! an option beyond this help is in the command's own `--help` text.

use super::values::{parse_metrics, parse_pose};
use anyhow::Result;
use clap::Args;
use singdist::mechanism::rpr::Pose;
use singdist::metric::Metric;
use std::path::{Path, PathBuf};

/// `--design`: the manipulator.
#[derive(Args, Debug)]
pub struct DesignArg {
    /// Design file (JSON: a 3-RPR's `{"base": [[x,y],…], "platform": [[x,y],…]}`, a
    /// 3-RRR's `{"base", "proximal", "distal", "platform", "working_modes"}`); default:
    /// the built-in example (`systems/rpr_example_design.json`, for `rrr` commands
    /// `systems/rrr_example_design.json`). Lengths are in its unit.
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
}

impl DesignArg {
    /// The design file, `None` for the built-in example.
    pub fn path(&self) -> Option<&Path> {
        self.design.as_deref()
    }
}

/// The options of a command along a motion (`curve`, `indices`, `compare`, `rrr
/// curve`): `--design`, `--motion` and `--poses`, the output table and plot, threads
/// and seed, `--quiet`.
#[derive(Args, Debug)]
pub struct MotionRunArgs {
    #[command(flatten)]
    pub design: DesignArg,
    /// Motion file (analytic motion or explicit pose list); default: the built-in
    /// example (`systems/rpr_example_motion.json`, for `rrr` commands the circular
    /// translation `systems/rrr_example_motion.json`).
    #[arg(long, value_name = "FILE")]
    pub motion: Option<PathBuf>,
    /// Number of poses evenly spaced in τ (pose lists are used as given), at most
    /// 1,000,000. Streamed outputs (`.csv`, `.jsonl`, the table on stdout) hold one
    /// window of 1000 poses at a time; a `.json` document, `--plot`, `--plot-data` and
    /// `--html` hold every pose (at most 100,000 poses × metrics, or 100,000 poses of a
    /// 3-RRR).
    #[arg(long, value_name = "N", default_value_t = 90)]
    pub poses: usize,
    #[command(flatten)]
    pub output: TableOutputArgs,
    #[command(flatten)]
    pub run: RunArgs,
    /// No progress bar and no timing line on stderr.
    #[arg(long)]
    pub quiet: bool,
}

impl MotionRunArgs {
    /// The design file, `None` for the built-in example.
    pub fn design(&self) -> Option<&Path> {
        self.design.path()
    }

    /// The motion file, `None` for the built-in example.
    pub fn motion(&self) -> Option<&Path> {
        self.motion.as_deref()
    }
}

/// `--pose`: one pose of the platform.
#[derive(Args, Debug)]
pub struct PoseArg {
    /// The pose `x,y,phi`: platform position (design length unit) and orientation φ
    /// (radians).
    #[arg(long, value_name = "X,Y,PHI", allow_hyphen_values = true)]
    pose: String,
}

impl PoseArg {
    /// The pose, each number checked (errors name `--pose` and the component).
    pub fn parse(&self) -> Result<Pose> {
        parse_pose(&self.pose)
    }
}

/// `--metric`: the extrinsic metrics of the 3-RPR distances.
#[derive(Args, Debug)]
pub struct MetricsArg {
    /// Metrics: `all`, or names `PLATFORM/BASE` with each part `plate`, `bars` or
    /// `rigid`, like `plate/plate bars/rigid` (space or comma separated).
    #[arg(long, value_name = "NAME", num_args = 1.., default_value = "all")]
    metric: Vec<String>,
}

impl MetricsArg {
    /// The metrics, in the order given, each once.
    pub fn parse(&self) -> Result<Vec<Metric>> {
        parse_metrics(&self.metric)
    }
}

/// `--out`, `--plot`: the results table and its plot.
#[derive(Args, Debug)]
pub struct TableOutputArgs {
    /// Output table; its extension chooses the format among those the command writes
    /// (`.csv`, `.jsonl` JSON Lines, `.json` one document: see the command's help).
    /// Checked, like `--plot`, before any work; streamed outputs are written to
    /// `FILE.partial` while running and renamed to FILE at the end.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// SVG plot of the results (what it shows: see the command's help).
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// `--html`: the self-contained report of a motion.
#[derive(Args, Debug)]
pub struct HtmlReportArg {
    /// Self-contained HTML report: the signed distances against τ with a slider on τ,
    /// and the drawing of the manipulator K and its closest singular configurations K′
    /// at the chosen τ (no network access needed to view it).
    #[arg(long, value_name = "FILE.html")]
    pub html: Option<PathBuf>,
}

/// `--threads`: the worker pool.
#[derive(Args, Debug, Clone, Copy)]
pub struct ThreadsArg {
    /// Worker threads (default: all cores; more than the cores is clamped to them).
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
}

impl ThreadsArg {
    /// The `--threads` value as given, `None` for all cores (checked by
    /// [`thread_count`](super::resources::thread_count)).
    pub fn requested(self) -> Option<usize> {
        self.threads
    }
}

/// `--threads`, `--seed`: how the homotopy commands run.
#[derive(Args, Debug, Clone, Copy)]
pub struct RunArgs {
    #[command(flatten)]
    pub threads: ThreadsArg,
    /// Seed of every random choice (results are identical for any thread count).
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
}

/// `--modes`: the 3-RRR working modes.
#[derive(Args, Debug)]
pub struct ModesArg {
    /// Working modes (elbow postures) of the three legs (at the start of the motion),
    /// e.g. `+,-,+` (or `1,-1,1`); overrides the design file's `working_modes`.
    #[arg(long, value_name = "S1,S2,S3", allow_hyphen_values = true)]
    modes: Option<String>,
}

impl ModesArg {
    /// The `--modes` text, `None` for the design's own modes.
    pub fn text(&self) -> Option<&str> {
        self.modes.as_deref()
    }
}
