//! Where the rows of the `indices` / `compare` motion table go as its windows of poses
//! complete: CSV on stdout, or `FILE.csv` / `FILE.jsonl` written to `FILE.partial`
//! (renamed to `FILE` at the end), each window written and then dropped so that memory
//! does not grow with the number of poses; for a `.json` document or a plot every row
//! is also kept.

use super::indices::{CurveSummary, Row, csv_rows, headers, jsonl_header, row_json};
use super::output::{PartialFile, extension};
use anyhow::{Context, Result, anyhow};
use singdist::index::rpr::IndexOptions;
use std::io::Write;
use std::path::Path;

/// The format of the motion table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TableFormat {
    /// CSV on stdout (no `--out`).
    Stdout,
    /// `.csv`.
    Csv,
    /// `.jsonl`: a header record, one object per pose, a closing summary record.
    JsonLines,
    /// `.json`: one document, written at the end (every row kept in memory).
    Json,
}

impl TableFormat {
    /// The format of `--out` (by its extension; checked before).
    pub fn of(out: Option<&Path>) -> Self {
        match out.map(|p| extension(p).unwrap_or_default()) {
            None => TableFormat::Stdout,
            Some(e) if e == "csv" => TableFormat::Csv,
            Some(e) if e == "jsonl" => TableFormat::JsonLines,
            Some(_) => TableFormat::Json,
        }
    }
}

/// The receiver of the table's rows, window by window.
pub struct RowSink<'a> {
    format: TableFormat,
    out: Option<&'a Path>,
    options: &'a IndexOptions,
    metric_names: &'a [String],
    partial: Option<PartialFile>,
    /// Every row so far, when an output needs them all.
    kept: Option<Vec<Row>>,
    poses: usize,
}

fn stdout_write(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| anyhow!("stdout: cannot write: {e}"))
}

impl<'a> RowSink<'a> {
    /// A sink writing `format` (to `out` unless [`TableFormat::Stdout`]); with `keep`
    /// it also keeps every row.
    pub fn new(
        (format, out): (TableFormat, Option<&'a Path>),
        (options, metric_names): (&'a IndexOptions, &'a [String]),
        keep: bool,
    ) -> Self {
        RowSink {
            format,
            out,
            options,
            metric_names,
            partial: None,
            kept: keep.then(Vec::new),
            poses: 0,
        }
    }

    fn append(&self, text: &str) -> Result<()> {
        match &self.partial {
            Some(partial) => partial.append(text),
            None if self.format == TableFormat::Stdout => stdout_write(text),
            None => Ok(()),
        }
    }

    /// Before the first row: the CSV header or the JSON Lines header record (with the
    /// metric computation's facts, if any); creates `FILE.partial`.
    pub fn start(&mut self, curve: Option<&CurveSummary>) -> Result<()> {
        let text = match self.format {
            TableFormat::Stdout | TableFormat::Csv => {
                let mut writer = csv::Writer::from_writer(Vec::new());
                writer.write_record(headers(self.options, self.metric_names))?;
                String::from_utf8(writer.into_inner().context("writing CSV")?)?
            }
            TableFormat::JsonLines => {
                let header = jsonl_header(self.options, self.metric_names, curve)?;
                serde_json::to_string(&header)? + "\n"
            }
            TableFormat::Json => return Ok(()),
        };
        if let (Some(out), TableFormat::Csv | TableFormat::JsonLines) = (self.out, self.format) {
            self.partial = Some(PartialFile::create("--out", out)?);
        }
        self.append(&text)
    }

    /// Writes the rows of one window (and keeps them if asked to).
    pub fn write(&mut self, rows: Vec<Row>) -> Result<()> {
        let text = match self.format {
            TableFormat::Stdout | TableFormat::Csv => csv_rows(&rows, self.metric_names)?,
            TableFormat::JsonLines => {
                let mut text = String::new();
                for row in &rows {
                    text.push_str(&serde_json::to_string(&row_json(row, self.metric_names)?)?);
                    text.push('\n');
                }
                text
            }
            TableFormat::Json => String::new(),
        };
        self.append(&text)?;
        self.poses += rows.len();
        if let Some(kept) = &mut self.kept {
            kept.extend(rows);
        }
        Ok(())
    }

    /// After the last row: the JSON Lines summary record (poses, every lost path of
    /// the metric computation); `FILE.partial` becomes `FILE`. Returns the kept rows.
    pub fn finish(mut self, curve: Option<&CurveSummary>) -> Result<Option<Vec<Row>>> {
        if self.format == TableFormat::JsonLines {
            let mut summary = serde_json::json!({"record": "summary", "poses": self.poses});
            if let Some(curve) = curve {
                summary["metric_failures"] = serde_json::to_value(&curve.failures)?;
            }
            if let Err(error) = self.append(&(serde_json::to_string(&summary)? + "\n")) {
                return Err(self.fail(error));
            }
        }
        if let (Some(partial), Some(out)) = (self.partial.take(), self.out)
            && let Err(e) = std::fs::rename(partial.path(), out)
        {
            partial.finish();
            return Err(anyhow!("--out: {}: cannot write: {e}", out.display()));
        }
        Ok(self.kept)
    }

    /// The run failed: `FILE.partial` is removed.
    pub fn fail(mut self, error: anyhow::Error) -> anyhow::Error {
        if let Some(partial) = self.partial.take() {
            partial.finish();
        }
        error
    }
}
