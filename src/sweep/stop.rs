//! Stopping a running sweep from another thread: the Python binding turns a Ctrl-C into
//! [`request`] (a sweep runs its points on worker threads, where Python's signal handler
//! cannot be asked). The point being computed ends at its next progress report (about once
//! per forcing period) with [`SimError::Interrupted`] and writes no file; the points not
//! started are not started; the finished points stay on disk, so a rerun resumes.
//!
//! The request is process-wide, as a signal is: every sweep running in the process stops.
//! A sweep clears it when it starts.

use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::SimError;
use crate::observe::{Observer, Sample};

static STOP: AtomicBool = AtomicBool::new(false);

/// Asks every running sweep of this process to stop.
pub fn request() {
    STOP.store(true, Ordering::SeqCst);
}

/// Whether a stop was asked for since the last sweep started.
pub fn requested() -> bool {
    STOP.load(Ordering::SeqCst)
}

/// Clears an earlier request (a sweep starting).
pub(super) fn clear() {
    STOP.store(false, Ordering::SeqCst);
}

/// The error of a point stopped by a request.
pub(super) fn interrupted() -> SimError {
    SimError::Interrupted("the sweep was asked to stop; a rerun resumes it".into())
}

/// An observer that ends a point's run at its next progress report once a stop is asked for.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct StopCheck;

impl Observer for StopCheck {
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }

    fn progress(&mut self, _t_s: f64, _duration_s: f64) -> Result<(), SimError> {
        if requested() {
            return Err(interrupted());
        }
        Ok(())
    }
}
