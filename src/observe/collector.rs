//! In-memory collectors: the steady-state grain series (input of the nonlinear analysis), the
//! stroboscopic points, and the samples figures draw ([`Recorded`]).

use super::{ModelSample, Observer, Sample};
use crate::error::SimError;
use crate::model::StrobePoint;

/// Keeps `grain_z_m` of the samples with `time_s ≥ from_s` (the steady state).
#[derive(Debug, Clone, Default)]
pub struct SteadyCollector {
    /// First time kept (s).
    pub from_s: f64,
    /// Sample times (s).
    pub time_s: Vec<f64>,
    /// Grain position / centre of mass (m).
    pub grain_z_m: Vec<f64>,
    /// Box position (m).
    pub box_z_m: Vec<f64>,
}

impl SteadyCollector {
    /// Collect samples from `from_s` on.
    pub fn new(from_s: f64) -> Self {
        SteadyCollector {
            from_s,
            ..Default::default()
        }
    }

    /// Sampling interval of the collected series (s), if at least two samples.
    pub fn dt_s(&self) -> Option<f64> {
        (self.time_s.len() >= 2).then(|| self.time_s[1] - self.time_s[0])
    }
}

impl Observer for SteadyCollector {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        if s.time_s >= self.from_s {
            self.time_s.push(s.time_s);
            self.grain_z_m.push(s.grain_z_m);
            self.box_z_m.push(s.box_z_m);
        }
        Ok(())
    }
}

/// Keeps the stroboscopic points of a run (what `strobe.csv` and the section analysis read).
#[derive(Debug, Clone, Default)]
pub struct StrobeCollector {
    /// The points, in time order.
    pub points: Vec<StrobePoint>,
}

impl Observer for StrobeCollector {
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }
    fn strobe(&mut self, p: &StrobePoint) -> Result<(), SimError> {
        self.points.push(*p);
        Ok(())
    }
}

/// The samples of one run kept in memory (the columns of `series.csv` that figures use).
#[derive(Debug, Clone, Default)]
pub struct Recorded {
    /// `time_s`.
    pub time_s: Vec<f64>,
    /// `box_z_m`.
    pub box_z_m: Vec<f64>,
    /// `floor_z_m`.
    pub floor_z_m: Vec<f64>,
    /// `ceiling_z_m`.
    pub ceiling_z_m: Vec<f64>,
    /// `grain_z_m` (particle or z_cm).
    pub grain_z_m: Vec<f64>,
    /// `grain_zmin_m` (DEM only).
    pub grain_zmin_m: Vec<f64>,
    /// `grain_zmax_m` (DEM only).
    pub grain_zmax_m: Vec<f64>,
    /// `grain_force_n`.
    pub grain_force_n: Vec<f64>,
}

impl Observer for Recorded {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.time_s.push(s.time_s);
        self.box_z_m.push(s.box_z_m);
        self.floor_z_m.push(s.floor_z_m);
        self.ceiling_z_m.push(s.ceiling_z_m);
        self.grain_z_m.push(s.grain_z_m);
        self.grain_force_n.push(s.grain_force_n);
        if let ModelSample::Dem(d) = s.model {
            self.grain_zmin_m.push(d.grain_zmin_m);
            self.grain_zmax_m.push(d.grain_zmax_m);
        }
        Ok(())
    }
}
