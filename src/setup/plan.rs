//! What a run will cost, checked before it starts: the derived quantities of a resolved scene
//! (natural frequency, damping ratio, duration, time step, number of steps, samples and
//! snapshot files, fill fraction, output size, estimated run time), each finite and within
//! a stated bound.
//!
//! [`crate::scene::Scene::resolve`] checks the bounds that do not depend on what is written
//! ([`RunPlan::new`] with no samples); `pdamp simulate` and `pdamp check-scene` build the plan
//! of the full series and refuse an output estimate above `--max-output`
//! ([`RunPlan::check_output`]). Both print the same figures.
//!
//! Bounds (a run beyond them would not finish or would fill the disk):
//! - natural frequency f0 and damping ratio ξ of the primary: finite;
//! - duration: finite and > 0, at least one sample interval;
//! - integration steps ≤ [`MAX_STEPS`]; samples ≤ [`MAX_SAMPLES`]; snapshot files ≤
//!   [`MAX_SNAPSHOT_FILES`];
//! - the DEM's grains fit its box by the scene's packing (the packing is built here); what
//!   the DEM needs in memory (grains, neighbour list, the packer's grid) is judged by one check,
//!   the memory estimate of [`super::dem::check_memory`], when the model is resolved;
//! - output ≤ `--max-output` (default [`DEFAULT_MAX_OUTPUT_BYTES`]).

use crate::error::SceneError;
use crate::model::RunOptions;
use crate::scene::keys;

use super::dem::DemSetup;
use super::keys::scene_error;
use super::{Resolved, Setup};

/// Most integration steps (event-driven steps, or DEM steps including settling) of one run.
pub const MAX_STEPS: f64 = 1e11;
/// Most samples of one run (rows of `series.csv`).
pub const MAX_SAMPLES: f64 = 1e10;
/// Most snapshot files of one run.
pub const MAX_SNAPSHOT_FILES: f64 = 1e5;
/// Default limit of a run's output (bytes): 4 GB.
pub const DEFAULT_MAX_OUTPUT_BYTES: f64 = 4e9;

/// Speed of the event-driven model used for the run-time estimate (steps per second; measured:
/// `pdamp simulate data/scenes/thesis_b_impact.toml --set run.periods=2000 --set
/// run.sample_interval=0.1 --no-analysis` takes 0.05 s for ~3.2e4 steps, events included).
const IMPACT_STEPS_PER_S: f64 = 1e6;
/// Cost of one written sample (s; measured: the same run with the default sampling writes
/// 1.3e6 rows in 2.2 s).
const SAMPLE_COST_S: f64 = 1.7e-6;
/// Speed of the DEM used for the run-time estimate (grain-steps per second; measured:
/// `pdamp simulate data/scenes/thesis_b_soft.toml --set run.duration=0.2` reports
/// `particle_steps_per_s` = 2.0e7 in its summary).
const DEM_GRAIN_STEPS_PER_S: f64 = 2e7;
/// Bytes per number in `series.csv` (shortest round-trip formatting and a comma; measured 16
/// for the impact model's rows, 20 for the DEM's).
const BYTES_PER_NUMBER: f64 = 20.0;
/// Bytes per grain in one CSV snapshot row (measured ≈ 200 on scene B's soft bed).
const BYTES_PER_GRAIN_CSV: f64 = 200.0;
/// Bytes per grain in one VTK XML snapshot (`grains_NNNNNN.vtp`, five arrays; measured ≈ 350).
const BYTES_PER_GRAIN_VTP: f64 = 350.0;

/// The derived figures of one run (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct RunPlan {
    /// Driven duration (s).
    pub duration_s: f64,
    /// Integration step (s): the DEM's dt, the event-driven model's largest step.
    pub dt_s: f64,
    /// Hertz contact time t_s (s) of the DEM's grains; `None` for the event-driven model.
    pub contact_time_s: Option<f64>,
    /// Integration steps (for the DEM: with the longest settling, `damper.settle_time`).
    pub steps: f64,
    /// Samples written (rows of `series.csv`).
    pub samples: f64,
    /// Snapshot files written.
    pub snapshot_files: f64,
    /// Solid volume fraction of the bed in the box (DEM), grains over box volume.
    pub fill_fraction: Option<f64>,
    /// Estimated output size (bytes).
    pub output_bytes: f64,
    /// Estimated run time on one core (s).
    pub run_time_s: f64,
    /// Sample interval of the written series (s; the scene's when no samples).
    pub sample_interval_s: f64,
}

impl RunPlan {
    /// The plan of `resolved` run with the sampling of `opts`, refused beyond the bounds of
    /// the module documentation (all but the output size).
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the scene key that sets the refused quantity and the
    /// bound.
    pub fn new(resolved: &Resolved, opts: &RunOptions) -> Result<RunPlan, SceneError> {
        let scene = &resolved.scene;
        if let Some(p) = &scene.primary {
            let (f0, xi) = (p.natural_frequency_hz(), p.damping_ratio());
            if !f0.is_finite() || !xi.is_finite() {
                return Err(SceneError::invalid(
                    "primary.mass",
                    format!("{:e}", p.mass),
                    format!(
                        "gives natural frequency f0 = {f0:e} Hz and damping ratio ξ = {xi:e}: both \
                         must be finite; check primary.mass and primary.stiffness (kg, N/m)"
                    ),
                ));
            }
        }
        let duration_s = scene.duration_s();
        let (duration_key, duration_value) = match scene.run.periods {
            Some(n) => (keys::RUN_PERIODS, format!("{n:e}")),
            None => (keys::RUN_DURATION, format!("{duration_s:e} s")),
        };
        if !(duration_s.is_finite() && duration_s > 0.0) {
            return Err(SceneError::invalid(
                duration_key,
                &duration_value,
                format!(
                    "gives a duration of {duration_s:e} s (excitation.frequency = {:e} Hz); the \
                     run's duration must be finite and > 0",
                    scene.frequency_hz()
                ),
            ));
        }
        let dt_sample = scene.run.sample_interval;
        if duration_s < dt_sample {
            return Err(SceneError::invalid(
                duration_key,
                &duration_value,
                format!(
                    "gives a duration of {duration_s:e} s, shorter than one sample interval \
                     (run.sample_interval = {dt_sample:e} s): lengthen the run"
                ),
            ));
        }
        let samples = match opts.sample_interval_s {
            Some(d) => ((duration_s - opts.sample_from_s).max(0.0) / d).floor() + 1.0,
            None => 0.0,
        };
        let mut plan = match &resolved.setup {
            Setup::Impact(_) => impact_plan(resolved, duration_s),
            Setup::Dem(d) => dem_plan(d, duration_s)?,
        };
        plan.samples = samples;
        plan.sample_interval_s = opts.sample_interval_s.unwrap_or(dt_sample);
        let kind = match &resolved.setup {
            Setup::Dem(_) => crate::observe::SampleKind::Dem,
            Setup::Impact(i) if i.particle.is_some() => crate::observe::SampleKind::Impact,
            Setup::Impact(_) => crate::observe::SampleKind::Primary,
        };
        // series.csv: the fixed columns, the model's, grain_force_n
        let columns = (crate::observe::FIXED_COLUMNS.len() + kind.columns().len() + 1) as f64;
        plan.output_bytes += samples * columns * BYTES_PER_NUMBER;
        plan.run_time_s += samples * SAMPLE_COST_S;
        let (step_key, step_value) = match &resolved.setup {
            Setup::Dem(_) => ("run.dt", format!("{:e} s", plan.dt_s)),
            Setup::Impact(_) => (duration_key, duration_value.clone()),
        };
        let what = format!(
            "integration steps of dt = {:.3e} s{}",
            plan.dt_s,
            match &resolved.setup {
                Setup::Dem(_) => " (the DEM's step, from the contact time)".to_string(),
                Setup::Impact(_) => format!(
                    " (1/16 of the shorter of the forcing period and the primary's natural \
                     period, f0 = {:.3e} Hz: check primary.mass and primary.stiffness)",
                    scene
                        .primary
                        .as_ref()
                        .map_or(0.0, |p| p.natural_frequency_hz())
                ),
            }
        );
        bound(plan.steps, MAX_STEPS, step_key, step_value, &what)?;
        bound(
            samples,
            MAX_SAMPLES,
            keys::RUN_SAMPLE_INTERVAL,
            format!("{:e} s", opts.sample_interval_s.unwrap_or(dt_sample)),
            "samples",
        )?;
        let every = match &scene.damper {
            crate::scene::Damper::Dem(p) => p.snapshot_interval.unwrap_or(0.0),
            _ => 0.0,
        };
        bound(
            plan.snapshot_files,
            MAX_SNAPSHOT_FILES,
            "damper.snapshot_interval",
            format!("{every:e} s"),
            "snapshot files",
        )?;
        Ok(plan)
    }

    /// Refuses an output estimate above `max_bytes`, with the estimate and the way out.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming `run.sample_interval` (the usual lever).
    pub fn check_output(&self, max_bytes: f64) -> Result<(), SceneError> {
        if self.output_bytes > max_bytes {
            return Err(SceneError::invalid(
                keys::RUN_SAMPLE_INTERVAL,
                format!("{:e} s", self.sample_interval_s),
                format!(
                    "the run would write about {} ({:.3e} samples, {:.0} snapshot files), above \
                     the limit of {}: raise run.sample_interval, shorten the run, or pass \
                     --max-output {:.0e} to accept it",
                    human_bytes(self.output_bytes),
                    self.samples,
                    self.snapshot_files,
                    human_bytes(max_bytes),
                    (self.output_bytes * 1.1).max(1.0)
                ),
            ));
        }
        Ok(())
    }

    /// The figures as printed by `check-scene` and `simulate` (one line).
    pub fn describe(&self) -> String {
        let ts = self.contact_time_s.map_or(String::new(), |t| {
            format!("t_s = {t:.3e} s (dt = t_s/{:.0}), ", t / self.dt_s)
        });
        let fill = self
            .fill_fraction
            .map_or(String::new(), |f| format!(", fill fraction {f:.3}"));
        // dt in full (the shortest text that reads back to the same number): the step the
        // run takes, to the last bit
        format!(
            "{ts}dt = {:e} s, {:.3e} steps, {:.3e} samples, {:.0} snapshot files{fill}; \
             output ≈ {}, run time ≈ {} on one core (rough)",
            self.dt_s,
            self.steps,
            self.samples,
            self.snapshot_files,
            human_bytes(self.output_bytes),
            human_seconds(self.run_time_s)
        )
    }
}

/// The event-driven model: steps of at most 1/16 of the shorter of the forcing and the
/// primary's natural period (`crate::impact`'s step).
fn impact_plan(resolved: &Resolved, duration_s: f64) -> RunPlan {
    let scene = &resolved.scene;
    let f0 = scene
        .primary
        .as_ref()
        .map_or(0.0, |p| p.natural_frequency_hz());
    let f_max = scene.frequency_hz().max(f0);
    let dt_s = 1.0 / (16.0 * f_max);
    let steps = duration_s / dt_s;
    RunPlan {
        duration_s,
        dt_s,
        contact_time_s: None,
        steps,
        samples: 0.0,
        snapshot_files: 0.0,
        fill_fraction: None,
        output_bytes: 0.0,
        run_time_s: steps / IMPACT_STEPS_PER_S,
        sample_interval_s: 0.0,
    }
}

/// The DEM: the step every run of the scene takes ([`super::DemSetup::time_step`], on the
/// scene's step clock [`super::dem::step_clock_s`]), settling and drive steps, the packing
/// built once to check that the grains fit.
fn dem_plan(d: &DemSetup, duration_s: f64) -> Result<RunPlan, SceneError> {
    let step = d.time_step;
    let (dt_s, ts) = (step.dt_s, step.contact_time_s);
    if !(dt_s > 0.0 && dt_s.is_finite() && ts.is_finite()) {
        return Err(SceneError::invalid(
            keys::DAMPER_YOUNGS_MODULUS,
            format!("{:e} Pa", d.model.grains.material.youngs_modulus),
            format!(
                "gives a Hertz contact time t_s = {ts:e} s and time step {dt_s:e} s: both must be \
                 finite and > 0; check damper.youngs_modulus, damper.density and damper.radius"
            ),
        ));
    }
    // memory (grains, neighbour list, the packer's grid) was judged once, by the memory
    // estimate, when the model was resolved (`super::dem::dem_model`)
    crate::dem::initial_positions(&d.model).map_err(scene_error)?;
    let n = d.model.grains.radius_m.len() as f64;
    let steps = (duration_s + d.model.settle_time_s) / dt_s;
    let [lx, ly, lz] = d.model.box_size_m;
    let solid: f64 = d
        .model
        .grains
        .radius_m
        .iter()
        .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3))
        .sum();
    // per snapshot: the CSV file and/or the grains' and the box's .vtp (plus the two .pvd
    // series once); bytes per grain of each snapshot
    let (snapshot_files, snapshot_bytes_per_grain) =
        match (d.model.snapshot_interval_s, &d.snapshots) {
            (Some(every), Some((_, format))) => {
                use crate::scene::dem::SnapshotFormat;
                let count = (duration_s / every).floor() + 1.0;
                let (files, series, bytes) = match format {
                    SnapshotFormat::Csv => (1.0, 0.0, BYTES_PER_GRAIN_CSV),
                    SnapshotFormat::Vtk => (2.0, 2.0, BYTES_PER_GRAIN_VTP),
                    SnapshotFormat::Both => (3.0, 2.0, BYTES_PER_GRAIN_CSV + BYTES_PER_GRAIN_VTP),
                };
                (files * count + series, bytes * count)
            }
            _ => (0.0, 0.0),
        };
    Ok(RunPlan {
        duration_s,
        dt_s,
        contact_time_s: Some(ts),
        steps,
        samples: 0.0,
        snapshot_files,
        fill_fraction: Some(solid / d.model.container.volume_m3([lx, ly, lz])),
        output_bytes: snapshot_bytes_per_grain * n,
        run_time_s: steps * n.max(1.0) / DEM_GRAIN_STEPS_PER_S,
        sample_interval_s: 0.0,
    })
}

/// Refuses a count that is not finite or above `max`, naming `key`.
fn bound(count: f64, max: f64, key: &str, value: String, what: &str) -> Result<(), SceneError> {
    if count.is_finite() && count <= max {
        return Ok(());
    }
    Err(SceneError::invalid(
        key,
        value,
        format!(
            "the run would take {count:.3e} {what}, above the bound of {max:.0e}: this run \
             would not finish (or fill the disk); change {key} or shorten the run"
        ),
    ))
}

/// `1.2 GB`, `340 kB`, …
fn human_bytes(b: f64) -> String {
    if !b.is_finite() {
        return format!("{b} B");
    }
    let units = [(1e12, "TB"), (1e9, "GB"), (1e6, "MB"), (1e3, "kB")];
    units
        .iter()
        .find(|(u, _)| b >= *u)
        .map_or(format!("{b:.0} B"), |(u, name)| {
            format!("{:.1} {name}", b / u)
        })
}

/// `3.2 s`, `4.1 min`, `2.5 h`, `3.1 days`.
fn human_seconds(s: f64) -> String {
    match s {
        s if !s.is_finite() => format!("{s} s"),
        s if s < 120.0 => format!("{s:.1} s"),
        s if s < 7200.0 => format!("{:.1} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.1} h", s / 3600.0),
        s => format!("{:.1} days", s / 86400.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_times_read_well() {
        assert_eq!(human_bytes(1.07e11), "107.0 GB");
        assert_eq!(human_bytes(512.0), "512 B");
        assert_eq!(human_seconds(30.0), "30.0 s");
        assert_eq!(human_seconds(86400.0 * 3.0), "3.0 days");
    }

    #[test]
    fn bounds_refuse_infinite_and_large_counts() {
        let v = || "1e-3 s".to_string();
        assert!(bound(10.0, 100.0, "k", v(), "steps").is_ok());
        let e = bound(f64::INFINITY, 100.0, "run.dt", v(), "steps").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("run.dt = 1e-3 s: the run would take inf steps"),
            "{e}"
        );
        assert!(bound(f64::NAN, 100.0, "k", v(), "steps").is_err());
        assert!(bound(101.0, 100.0, "k", v(), "steps").is_err());
    }
}
