//! The run log of `singdist curve --out FILE`: `FILE.partial`, JSON Lines written window
//! by window as the run goes, from which the final `FILE` is made and an interrupted
//! run is resumed.
//!
//! Lines, in order: one `{"record":"header",…}` (the arguments that determine the
//! results, and what the seed stage found), then per window its poses (one line each,
//! in pose order: a [`PoseResult`] object, or for a `.csv` output its CSV row) followed
//! by one `{"record":"window",…}` line (its failures, its share of the paths tracked,
//! its self-check). A window is written in one piece after it is final, so a killed run
//! leaves complete windows and at most one truncated line, which a resume discards. A
//! resume reads only the records, never the pose lines, so the final file does not
//! depend on reading numbers back: a `.jsonl` output is the log with a closing
//! `{"record":"summary",…}` line (every failure, the total paths tracked, the whole
//! self-check), a `.csv` output its pose lines under the CSV header.

use super::failures::lost_paths;
use super::output::PartialFile;
use anyhow::{Context, Result, anyhow, bail};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use singdist::metric::Metric;
use singdist::pipeline::curve::{CurveHeader, CurveWindow, PathFailure, PoseResult, SelfCheck};
use std::io::{BufRead, Write};
use std::path::Path;

/// Version of the log's layout; a log of another version is not resumed.
const LOG_FORMAT: u32 = 1;

/// One line of the log that is not a pose.
#[derive(Debug, Serialize, Deserialize)]
#[serde(tag = "record", rename_all = "snake_case")]
enum Record {
    Header {
        format: u32,
        /// `(name, value)` of every argument the results depend on.
        arguments: Vec<(String, Value)>,
        #[serde(flatten)]
        header: CurveHeader,
    },
    Window {
        window: usize,
        first_pose: usize,
        end_pose: usize,
        failures: Vec<PathFailure>,
        paths_tracked: usize,
        self_check: Option<SelfCheck>,
        /// The bits of the self-check's worst relative difference (JSON numbers are
        /// not read back bit for bit).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        worst_bits: Option<u64>,
    },
    Summary {
        failures: Vec<PathFailure>,
        paths_tracked: usize,
        self_check: Option<SelfCheck>,
    },
}

/// Whether a log line is a record (header, window, summary) rather than a pose.
fn is_record(line: &str) -> bool {
    line.starts_with("{\"record\":")
}

/// The totals of the windows so far: what the closing summary reports.
#[derive(Debug, Default)]
pub struct Totals {
    /// Windows complete.
    pub windows: usize,
    /// Poses complete.
    pub poses: usize,
    /// Paths lost at the poses so far (in pose order).
    pub failures: Vec<PathFailure>,
    /// Paths tracked at the poses so far.
    pub paths_tracked: usize,
    /// The self-checks of the windows so far, merged.
    pub self_check: Option<SelfCheck>,
}

impl Totals {
    fn add(&mut self, paths_tracked: usize, self_check: Option<&SelfCheck>, poses: usize) {
        self.windows += 1;
        self.poses += poses;
        self.paths_tracked += paths_tracked;
        if let Some(check) = self_check {
            match &mut self.self_check {
                Some(total) => total.merge(check),
                None => self.self_check = Some(check.clone()),
            }
        }
    }
}

/// How the pose lines of a log are written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PoseLines {
    /// One [`PoseResult`] JSON object per pose (`.jsonl`, `.json`).
    Json,
    /// One CSV row per pose (`.csv`).
    Csv,
}

/// The open log of a run.
pub struct RunLog {
    partial: PartialFile,
    header: CurveHeader,
    lines: PoseLines,
    metrics: Vec<Metric>,
    /// The windows written so far.
    pub totals: Totals,
}

fn to_line<T: Serialize>(value: &T) -> Result<String> {
    serde_json::to_string(value).context("serialising the run log")
}

/// A value for a message: compact JSON, long ones shortened.
fn shown(value: &Value) -> String {
    let text = value.to_string();
    if text.chars().count() > 60 {
        let head: String = text.chars().take(57).collect();
        format!("{head}…")
    } else {
        text
    }
}

/// The argument fingerprint and seed-stage results a log starts with.
pub type LogHeader = (Vec<(String, Value)>, CurveHeader);

impl RunLog {
    /// Starts the log of `out` afresh (truncating an old one) with its header line.
    pub fn create(
        out: &Path,
        (arguments, header): LogHeader,
        lines: PoseLines,
        metrics: &[Metric],
    ) -> Result<Self> {
        let partial = PartialFile::create("--out", out)?;
        let record = Record::Header {
            format: LOG_FORMAT,
            arguments,
            header: header.clone(),
        };
        partial.append(&(to_line(&record)? + "\n"))?;
        Ok(RunLog {
            partial,
            header,
            lines,
            metrics: metrics.to_vec(),
            totals: Totals::default(),
        })
    }

    /// Opens the log of an interrupted run of `out` to continue it: its header must
    /// have been written with the same `arguments` (else the error names the first
    /// that differs) and the same seed-stage results; everything after its last
    /// complete window is cut off. `tau_of(j)` is the τ of pose `j` (a failure's τ is
    /// taken from there, not read back).
    pub fn resume(
        out: &Path,
        (arguments, header): LogHeader,
        (lines, metrics): (PoseLines, &[Metric]),
        tau_of: &dyn Fn(usize) -> Option<f64>,
    ) -> Result<Self> {
        let path = PartialFile::path_for(out);
        let shown_path = path.display().to_string();
        let file = std::fs::File::open(&path)
            .map_err(|e| anyhow!("--resume: {shown_path}: cannot read: {e}"))?;
        let mut reader = std::io::BufReader::new(file);
        let mut line = String::new();
        let (mut offset, mut kept, mut number) = (0u64, 0u64, 0usize);
        let mut totals = Totals::default();
        let mut header_seen = false;
        let mut pose_lines = 0usize;
        loop {
            line.clear();
            let read = reader
                .read_line(&mut line)
                .with_context(|| format!("--resume: {shown_path}: cannot read"))?;
            if read == 0 || !line.ends_with('\n') {
                // The end, or a last line cut off by the interruption.
                break;
            }
            number += 1;
            offset += read as u64;
            let text = line.trim_end();
            let at = || format!("--resume: {shown_path}: line {number}");
            if !header_seen {
                let Ok(Record::Header {
                    format,
                    arguments: written,
                    header: written_header,
                }) = serde_json::from_str::<Record>(text)
                else {
                    bail!("{}: not the header of a singdist curve run log", at());
                };
                if format != LOG_FORMAT {
                    bail!(
                        "{}: run log format {format}, this singdist writes {LOG_FORMAT}; run without --resume to start again",
                        at()
                    );
                }
                compare_arguments(&shown_path, &written, &as_read_back(&arguments)?)?;
                if written_header != as_read_back(&header)? {
                    bail!(
                        "--resume: {shown_path}: its seed stage differs from this run's (another singdist version?); run without --resume to start again"
                    );
                }
                header_seen = true;
                kept = offset;
                continue;
            }
            if !is_record(text) {
                pose_lines += 1;
                continue;
            }
            match serde_json::from_str::<Record>(text) {
                Ok(Record::Window {
                    window,
                    first_pose,
                    end_pose,
                    mut failures,
                    paths_tracked,
                    mut self_check,
                    worst_bits,
                }) => {
                    let count = end_pose.saturating_sub(first_pose);
                    if window != totals.windows
                        || first_pose != totals.poses
                        || pose_lines != count
                        || failures_out_of(&failures, first_pose, end_pose)
                    {
                        bail!(
                            "{}: window {window} does not continue the windows before it; run without --resume to start again",
                            at()
                        );
                    }
                    for failure in &mut failures {
                        failure.tau = failure.pose_index.and_then(tau_of);
                    }
                    if let (Some(check), Some(bits)) = (&mut self_check, worst_bits) {
                        check.worst_relative_difference = f64::from_bits(bits);
                    }
                    totals.add(paths_tracked, self_check.as_ref(), count);
                    totals.failures.append(&mut failures);
                    pose_lines = 0;
                    kept = offset;
                }
                // A summary: the run had finished writing its log.
                Ok(Record::Summary { .. }) => break,
                _ => bail!("{}: not a record of a singdist curve run log", at()),
            }
        }
        if !header_seen {
            bail!(
                "--resume: {shown_path}: no complete header line (nothing to resume); run without --resume"
            );
        }
        drop(reader);
        Ok(RunLog {
            partial: PartialFile::reopen("--out", out, kept)?,
            header,
            lines,
            metrics: metrics.to_vec(),
            totals,
        })
    }

    /// Appends a final window (its poses, then its record) in one write.
    pub fn write_window(&mut self, window: &CurveWindow) -> Result<()> {
        let mut text = String::new();
        match self.lines {
            PoseLines::Json => {
                for pose in &window.poses {
                    text.push_str(&to_line(pose)?);
                    text.push('\n');
                }
            }
            PoseLines::Csv => {
                let mut writer = csv::Writer::from_writer(Vec::new());
                for pose in &window.poses {
                    let row = csv_row(pose, &self.metrics, &self.header.seed_failures);
                    writer.write_record(row)?;
                }
                let bytes = writer.into_inner().context("writing CSV")?;
                text.push_str(&String::from_utf8_lossy(&bytes));
            }
        }
        let failures: Vec<PathFailure> = window
            .poses
            .iter()
            .flat_map(|p| p.failures.iter().cloned())
            .collect();
        let (first_pose, end_pose) = (self.totals.poses, self.totals.poses + window.poses.len());
        let record = Record::Window {
            window: window.index,
            first_pose,
            end_pose,
            failures: failures.clone(),
            paths_tracked: window.paths_tracked,
            self_check: window.self_check.clone(),
            worst_bits: window
                .self_check
                .as_ref()
                .map(|c| c.worst_relative_difference.to_bits()),
        };
        text.push_str(&to_line(&record)?);
        text.push('\n');
        self.partial.append(&text)?;
        let check = window.self_check.as_ref();
        self.totals
            .add(window.paths_tracked, check, window.poses.len());
        self.totals.failures.extend(failures);
        Ok(())
    }

    /// Every failure of the run so far: the seed stage's, then the poses'.
    pub fn failures(&self) -> Vec<PathFailure> {
        let mut all = self.header.seed_failures.clone();
        all.extend(self.totals.failures.iter().cloned());
        all
    }

    /// Total paths tracked so far (seed stage included).
    pub fn paths_tracked(&self) -> usize {
        self.header.seed_paths_tracked + self.totals.paths_tracked
    }

    /// The log is complete: `.jsonl` gets the summary line and becomes `out`.
    pub fn finish_jsonl(self, out: &Path) -> Result<()> {
        let record = Record::Summary {
            failures: self.failures(),
            paths_tracked: self.paths_tracked(),
            self_check: self.totals.self_check.clone(),
        };
        let line = to_line(&record)? + "\n";
        let partial = self.partial;
        if let Err(error) = partial.append(&line) {
            return Err(partial.abandon(error));
        }
        partial.rename_to("--out", out)
    }

    /// The log is complete: `.csv` is its pose lines under the CSV header; the log
    /// goes.
    pub fn finish_csv(self, out: &Path) -> Result<()> {
        let partial = self.partial;
        match write_csv_from_log(partial.path(), out, &self.metrics) {
            Ok(()) => {
                partial.finish();
                Ok(())
            }
            Err(error) => {
                let _ = std::fs::remove_file(out);
                Err(partial.abandon(error))
            }
        }
    }

    /// The run failed: the log is kept (and named) if it holds results.
    pub fn abandon(self, error: anyhow::Error) -> anyhow::Error {
        self.partial.abandon(error)
    }

    /// The output is written otherwise (`.json`): the log goes.
    pub fn remove(self) {
        self.partial.finish();
    }
}

/// `value` as read back from its JSON text: what a log written by an identical run
/// holds, number for number (JSON numbers are not read back bit for bit, but the
/// same text is always read back the same).
fn as_read_back<T: Serialize + serde::de::DeserializeOwned>(value: &T) -> Result<T> {
    Ok(serde_json::from_str(&to_line(value)?)?)
}

fn failures_out_of(failures: &[PathFailure], first: usize, end: usize) -> bool {
    failures
        .iter()
        .any(|f| f.pose_index.is_some_and(|j| j < first || j >= end))
}

/// Refuses a resume whose arguments differ from the log's, naming the first difference.
fn compare_arguments(
    path: &str,
    written: &[(String, Value)],
    now: &[(String, Value)],
) -> Result<()> {
    for (name, value) in now {
        match written.iter().find(|(n, _)| n == name) {
            Some((_, old)) if old == value => {}
            Some((_, old)) => bail!(
                "--resume: {path} was written with another {name} ({} there, {} now); run without --resume to start again",
                shown(old),
                shown(value)
            ),
            None => bail!("--resume: {path} has no {name}; run without --resume to start again"),
        }
    }
    if let Some((name, _)) = written
        .iter()
        .find(|(n, _)| !now.iter().any(|(m, _)| m == n))
    {
        bail!(
            "--resume: {path} was written with an argument {name} this run does not have; run without --resume to start again"
        );
    }
    Ok(())
}

/// One CSV row of a pose: `tau, x, y, phi, S`, the signed distance of each metric
/// (empty where none), `lost_paths` (the pose's and the seed's lost paths).
pub fn csv_row(pose: &PoseResult, metrics: &[Metric], all_failures: &[PathFailure]) -> Vec<String> {
    let mut row: Vec<String> = vec![
        pose.tau.to_string(),
        pose.pose[0].to_string(),
        pose.pose[1].to_string(),
        pose.pose[2].to_string(),
        pose.singularity.to_string(),
    ];
    for metric in metrics {
        row.push(
            pose.metrics
                .get(&metric.name())
                .map(|m| m.signed_distance.to_string())
                .unwrap_or_default(),
        );
    }
    row.push(lost_paths(&pose.failures, all_failures).to_string());
    row
}

/// The CSV header: `tau, x, y, phi, S`, the metric names, `lost_paths`.
pub fn csv_header(metrics: &[Metric]) -> Vec<String> {
    let mut header: Vec<String> = ["tau", "x", "y", "phi", "S"].map(String::from).to_vec();
    header.extend(metrics.iter().map(Metric::name));
    header.push("lost_paths".into());
    header
}

/// Writes the CSV table of the log at `log` to `out`: the header row, then the log's
/// pose lines as they are, one line at a time.
fn write_csv_from_log(log: &Path, out: &Path, metrics: &[Metric]) -> Result<()> {
    let cannot = |e: &dyn std::fmt::Display| anyhow!("--out: {}: cannot write: {e}", out.display());
    let file = std::fs::File::create(out).map_err(|e| cannot(&e))?;
    let mut writer = std::io::BufWriter::new(file);
    let mut header = csv::Writer::from_writer(Vec::new());
    header.write_record(csv_header(metrics))?;
    let header = header.into_inner().context("writing CSV")?;
    writer.write_all(&header).map_err(|e| cannot(&e))?;
    let mut reader = std::io::BufReader::new(
        std::fs::File::open(log).with_context(|| format!("{}: cannot read", log.display()))?,
    );
    let mut line = String::new();
    loop {
        line.clear();
        if reader.read_line(&mut line)? == 0 {
            break;
        }
        if !is_record(&line) {
            writer.write_all(line.as_bytes()).map_err(|e| cannot(&e))?;
        }
    }
    writer.flush().map_err(|e| cannot(&e))?;
    Ok(())
}
