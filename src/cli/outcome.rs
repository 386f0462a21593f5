//! How a command ends: its exit code and, for an error, the one-line message on stderr.
//! The one place that decides exit codes: commands return an [`Outcome`] or an error,
//! and `main` turns that into the process's [`ExitCode`].
//!
//! Exit codes: 0 = complete; 1 = error (bad input, unwritable output, a stored file
//! failing its checks, …; nothing computed is claimed); 2 = invalid command line (from
//! the argument parser, which exits by itself); 3 = the run finished but some homotopy
//! paths were lost (warning on stderr, the failures listed in the output), or
//! `certify` found a distance of the file contradicted by a certified critical point.

use std::process::ExitCode;

/// Exit code of an error.
pub const EXIT_ERROR: u8 = 1;

/// Exit code of a run that completed but lost paths (results may miss critical points).
pub const EXIT_PATH_FAILURES: u8 = 3;

/// What a completed command reports through its exit code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Everything asked for was computed.
    Complete,
    /// The results were written, but some paths were lost (already warned about).
    PathsLost,
    /// `certify`: a distance of the re-checked file is contradicted (already listed).
    Contradicted,
}

impl Outcome {
    /// [`Outcome::PathsLost`] when `lost`, else [`Outcome::Complete`].
    pub fn paths_lost_if(lost: bool) -> Self {
        if lost {
            Outcome::PathsLost
        } else {
            Outcome::Complete
        }
    }

    /// The process exit code.
    pub fn exit_code(self) -> ExitCode {
        match self {
            Outcome::Complete => ExitCode::SUCCESS,
            Outcome::PathsLost | Outcome::Contradicted => ExitCode::from(EXIT_PATH_FAILURES),
        }
    }
}

/// The exit code of a command's result; an error is printed first, as one line on
/// stderr (`singdist: error: …`).
pub fn exit_code_of(result: anyhow::Result<Outcome>) -> ExitCode {
    match result {
        Ok(outcome) => outcome.exit_code(),
        Err(error) => {
            eprintln!("singdist: error: {}", one_line_message(&error));
            ExitCode::from(EXIT_ERROR)
        }
    }
}

/// The error and its causes as one line, `context: cause: cause`, where a cause whose
/// text the message already contains is left out. (Error types that print their source
/// in their own message, as `thiserror`'s `#[error("{path}: {source}")]` does, would
/// otherwise show it twice.)
pub fn one_line_message(error: &anyhow::Error) -> String {
    let mut message = error.to_string();
    for cause in error.chain().skip(1) {
        let text = cause.to_string();
        if !message.contains(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
    }
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("inner field: bad value")]
    struct Inner;

    #[derive(Debug, thiserror::Error)]
    #[error("file.json: {source}")]
    struct Outer {
        source: Inner,
    }

    #[test]
    fn a_cause_already_in_the_message_is_printed_once() {
        let error = anyhow::Error::new(Outer { source: Inner });
        assert_eq!(
            one_line_message(&error),
            "file.json: inner field: bad value"
        );
        let error = anyhow::Error::new(Inner).context("--design");
        assert_eq!(one_line_message(&error), "--design: inner field: bad value");
        let error = anyhow::anyhow!("line one\nline two");
        assert_eq!(one_line_message(&error), "line one line two");
    }
}
