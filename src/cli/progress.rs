//! Progress bar observer (indicatif), hidden when stderr is not a terminal (CI, pipes) or
//! with `-q`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use pdamp::error::SimError;
use pdamp::observe::{Observer, Sample};
use std::io::IsTerminal;

/// Shows simulated time against the run's duration.
pub struct ProgressObserver {
    bar: ProgressBar,
}

impl ProgressObserver {
    /// A bar for a run of `duration_s` seconds; hidden unless stderr is a terminal.
    pub fn new(duration_s: f64, message: &str) -> Self {
        let bar = ProgressBar::with_draw_target(Some(1000), draw_target());
        bar.set_style(
            ProgressStyle::with_template(
                "{msg} [{elapsed_precise}] {wide_bar} {percent}% (eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.set_message(format!("{message} ({duration_s:.3} s simulated)"));
        ProgressObserver { bar }
    }
}

/// The draw target: stderr when it is a terminal and notes are on (not `-q`), hidden
/// otherwise.
pub fn draw_target() -> ProgressDrawTarget {
    if std::io::stderr().is_terminal() && tracing::enabled!(tracing::Level::INFO) {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    }
}

impl Observer for ProgressObserver {
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }
    fn progress(&mut self, t: f64, d: f64) -> Result<(), SimError> {
        if d > 0.0 {
            self.bar
                .set_position(((t / d).clamp(0.0, 1.0) * 1000.0) as u64);
        }
        Ok(())
    }
    fn finish(&mut self) -> Result<(), SimError> {
        self.bar.finish_and_clear();
        Ok(())
    }
}
