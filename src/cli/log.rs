//! `-v` / `-q`: how much `pdamp` says on standard error.
//!
//! Results go to standard output (or files); notes, warnings and progress bars go to standard
//! error as `tracing` events — the CLI's own and the library's. The level:
//!
//! | flags | shows |
//! |---|---|
//! | `-qq` | errors only |
//! | `-q` | warnings and errors (no notes, no progress bars) |
//! | (none) | notes (what was read, chosen, written), warnings, progress bars on a terminal |
//! | `-v` | also the library's debug events (resolved scene, time step, analysis choices) |
//! | `-vv` | also trace events |

use std::fmt;

use tracing::{Event, Level, Subscriber};
use tracing_subscriber::fmt::format::Writer;
use tracing_subscriber::fmt::{FmtContext, FormatEvent, FormatFields};
use tracing_subscriber::registry::LookupSpan;

/// The level of `-v` given `verbose` times and `-q` given `quiet` times.
pub fn level(verbose: u8, quiet: u8) -> Level {
    match i16::from(verbose) - i16::from(quiet) {
        i16::MIN..=-2 => Level::ERROR,
        -1 => Level::WARN,
        0 => Level::INFO,
        1 => Level::DEBUG,
        _ => Level::TRACE,
    }
}

/// Installs the standard-error printer for `level` (once, at start-up).
pub fn init(level: Level) {
    let _ = tracing_subscriber::fmt()
        .with_max_level(level)
        .with_writer(std::io::stderr)
        .event_format(Plain)
        .try_init();
}

/// Notes print as plain lines, as they always have; warnings and errors say so; debug and
/// trace events name the module they come from.
struct Plain;

impl<S, N> FormatEvent<S, N> for Plain
where
    S: Subscriber + for<'a> LookupSpan<'a>,
    N: for<'a> FormatFields<'a> + 'static,
{
    fn format_event(
        &self,
        ctx: &FmtContext<'_, S, N>,
        mut writer: Writer<'_>,
        event: &Event<'_>,
    ) -> fmt::Result {
        let meta = event.metadata();
        match *meta.level() {
            Level::ERROR => write!(writer, "error: ")?,
            Level::WARN => write!(writer, "warning: ")?,
            Level::INFO => {}
            _ => write!(writer, "[{}] ", meta.target())?,
        }
        ctx.field_format().format_fields(writer.by_ref(), event)?;
        writeln!(writer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_map_to_levels() {
        assert_eq!(level(0, 0), Level::INFO);
        assert_eq!(level(0, 1), Level::WARN);
        assert_eq!(level(0, 2), Level::ERROR);
        assert_eq!(level(0, 9), Level::ERROR);
        assert_eq!(level(1, 0), Level::DEBUG);
        assert_eq!(level(3, 0), Level::TRACE);
        assert_eq!(level(1, 1), Level::INFO);
    }
}
