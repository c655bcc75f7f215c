//! Exit status of `pdamp`: one code per failure kind, so that scripts can tell a mistyped
//! option from a bad input file, an unstable simulation or a full disk.
//!
//! | code | kind | examples |
//! |---|---|---|
//! | 0 | success (also: standard output closed early, `pdamp embed … \| head -1`) | |
//! | 1 | other failure | a study's qualitative check failed, sweep points failed |
//! | 2 | usage | unknown option, option value out of range (clap's own code) |
//! | 3 | input | scene key refused, series file unreadable as numbers, incomplete run directory |
//! | 4 | numerical instability | the state became non-finite or energy grew without input |
//! | 5 | I/O | a file cannot be read or written (missing, permission, disk full) |

use pdamp::error::{
    AnalysisError, DataError, ModelError, PlotError, SceneError, SimError, StudyError,
};

/// The failure kinds and their exit codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Kind {
    /// Any failure not classified below.
    Other = 1,
    /// The command line asks for something impossible (also clap's parse errors).
    Usage = 2,
    /// An input (scene, series, table, run directory) is refused.
    Input = 3,
    /// The simulation became unstable.
    Unstable = 4,
    /// A file could not be read or written.
    Io = 5,
}

/// Some points of a sweep failed (the others are written; a rerun retries the failed ones):
/// exit code 1, as the points' failures may be of different kinds.
#[derive(Debug, thiserror::Error)]
#[error("{failed} of {points} sweep points failed (rerun to retry them)")]
pub struct PointsFailed {
    /// Points that failed.
    pub failed: usize,
    /// Points in the sweep.
    pub points: usize,
}

/// The exit code of `err`: the kind of the outermost typed error in its chain; an error
/// with no typed cause (an option checked by the CLI itself) is a usage error.
pub fn code(err: &anyhow::Error) -> Kind {
    err.chain().find_map(kind_of).unwrap_or(Kind::Usage)
}

/// The kind of one error of a chain, if it is one of the typed errors.
fn kind_of(e: &(dyn std::error::Error + 'static)) -> Option<Kind> {
    if let Some(e) = e.downcast_ref::<SimError>() {
        return Some(match e {
            SimError::Unstable { .. } => Kind::Unstable,
            SimError::Output(_) => Kind::Io,
            SimError::Scene(_) | SimError::Model(_) | SimError::Unavailable(_) => Kind::Input,
            SimError::Interrupted(_) => Kind::Other,
        });
    }
    if let Some(e) = e.downcast_ref::<DataError>() {
        return Some(match e {
            DataError::Io { .. } => Kind::Io,
            DataError::Malformed { .. } | DataError::Incomplete { .. } => Kind::Input,
        });
    }
    if let Some(e) = e.downcast_ref::<PlotError>() {
        return Some(match e {
            PlotError::Draw { .. } => Kind::Io,
            PlotError::BadData { .. } | PlotError::Format { .. } => Kind::Input,
        });
    }
    if let Some(e) = e.downcast_ref::<StudyError>() {
        return Some(match e {
            StudyError::Output { .. } => Kind::Io,
            StudyError::Step { .. } | StudyError::Check(_) => Kind::Other,
        });
    }
    if e.is::<SceneError>() || e.is::<ModelError>() || e.is::<AnalysisError>() {
        return Some(Kind::Input);
    }
    if e.is::<PointsFailed>() {
        return Some(Kind::Other);
    }
    if e.is::<std::io::Error>() {
        return Some(Kind::Io);
    }
    None
}

/// The error and its causes joined by `: `, leaving out a cause whose text the message
/// already ends with (a data error that prints its I/O source would otherwise say it twice).
pub fn message(err: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if msg.is_empty() {
            msg = text;
        } else if !msg.ends_with(&text) {
            msg.push_str(": ");
            msg.push_str(&text);
        }
    }
    msg
}

/// Whether `err` is a write to a closed pipe (the reader of our output has gone).
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| {
        e.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
            || e.downcast_ref::<serde_json::Error>()
                .and_then(|j| j.io_error_kind())
                .is_some_and(|k| k == std::io::ErrorKind::BrokenPipe)
    })
}

/// `println!` to a closed pipe panics ("failed printing to stdout: Broken pipe"): exit
/// quietly with status 0 instead, as `head`'s other writers do; other panics are reported
/// as before.
pub fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let msg = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.contains("failed printing to stdout") && msg.contains("Broken pipe") {
            std::process::exit(0);
        }
        default(info);
    }));
}
