//! Observers: the simulators emit samples to an [`Observer`]; CSV recorders, progress bars and
//! in-memory collectors are observers attached by the caller (no prints, no globals).

pub mod collector;
pub mod csv_recorder;
pub mod progress;

pub use collector::SteadyCollector;
pub use csv_recorder::CsvRecorder;
pub use progress::ProgressObserver;

use crate::error::SimError;

/// The fixed columns of `series.csv`, in order; model-specific columns follow, then
/// `grain_force_n` (see [`Sample`]).
pub const FIXED_COLUMNS: [&str; 7] = [
    "time_s",
    "base_u_m",
    "box_z_m",
    "box_v_m_s",
    "floor_z_m",
    "ceiling_z_m",
    "grain_z_m",
];

/// One output sample of a run (lab frame, z up, origin at the static equilibrium of M alone).
#[derive(Debug, Clone, Copy)]
pub struct Sample<'a> {
    /// Time t (s).
    pub time_s: f64,
    /// Base displacement u(t) (m).
    pub base_u_m: f64,
    /// Box (primary mass) position z (m).
    pub box_z_m: f64,
    /// Box velocity z' (m/s).
    pub box_v_m_s: f64,
    /// Floor position (m).
    pub floor_z_m: f64,
    /// Ceiling position (m); `inf` without ceiling.
    pub ceiling_z_m: f64,
    /// Particle position (impact model) or the grains' centre of mass (DEM) (m).
    pub grain_z_m: f64,
    /// Model-specific values, in the order of the names given to [`Observer::start`].
    pub extra: &'a [f64],
    /// Vertical force of the grains on the box (N); impulses at impacts are not included.
    pub grain_force_n: f64,
}

/// Receives the samples of a run.
pub trait Observer {
    /// Called once before the first sample with the names of the model-specific columns.
    ///
    /// # Errors
    /// [`SimError::Output`] if the observer cannot start (e.g. cannot create its file).
    fn start(&mut self, _extra_columns: &[&str]) -> Result<(), SimError> {
        Ok(())
    }
    /// Called for every sample, in time order.
    ///
    /// # Errors
    /// [`SimError::Output`] if the sample cannot be recorded.
    fn sample(&mut self, s: &Sample<'_>) -> Result<(), SimError>;
    /// Progress report: simulated time `t_s` out of `duration_s`. Called at most every few
    /// forcing periods.
    fn progress(&mut self, _t_s: f64, _duration_s: f64) {}
    /// Called once after the last sample.
    ///
    /// # Errors
    /// [`SimError::Output`] if buffered output cannot be flushed.
    fn finish(&mut self) -> Result<(), SimError> {
        Ok(())
    }
}

/// An observer that ignores everything (for runs that only need the summary).
#[derive(Debug, Default, Clone, Copy)]
pub struct NullObserver;

impl Observer for NullObserver {
    fn sample(&mut self, _s: &Sample<'_>) -> Result<(), SimError> {
        Ok(())
    }
}

/// Forwards everything to several observers, in order.
pub struct Tee<'a> {
    /// The observers.
    pub observers: Vec<&'a mut dyn Observer>,
}

impl Observer for Tee<'_> {
    fn start(&mut self, extra: &[&str]) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.start(extra))
    }
    fn sample(&mut self, s: &Sample<'_>) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.sample(s))
    }
    fn progress(&mut self, t: f64, d: f64) {
        self.observers.iter_mut().for_each(|o| o.progress(t, d))
    }
    fn finish(&mut self) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.finish())
    }
}

/// Format a number for CSV output: shortest round-trip representation, in scientific notation
/// for very small or large magnitudes (`3.1e-13` rather than `0.00000000000031`).
pub fn fmt_num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
