//! Running one setting at one frequency, single-threaded, with its wall time measured inside
//! the run, and reducing the run to the quantities whose errors the trade-off reports.

use std::time::Instant;

use crate::dem::{BoxDrive, DemRunConfig, DtChoice};
use crate::error::{SceneError, SimError};
use crate::model::PrimarySystem;
use crate::model::RunOptions;
use crate::observe::{ModelSample, Observer, Sample};
use crate::scene::{Damper, ImpactParams, Run, Scene};

use super::ladder::Case;

/// Output sampling of the measured runs (s): fine enough that the sampled peak of a 30 Hz
/// sine is within 0.03 % of the true one (1 − cos(π f Δt)).
pub const SAMPLE_INTERVAL_S: f64 = 2.5e-4;

/// The primary system and base motion of a scene (what every setting shares).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rig {
    /// The primary system M, K, C.
    pub primary: PrimarySystem,
    /// Base amplitude U (m).
    pub amplitude_m: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
}

impl Rig {
    /// The rig of a scene with a `[primary]`.
    ///
    /// # Errors
    /// `primary` missing: the trade-off measures the primary's response.
    pub fn of_scene(scene: &Scene) -> Result<Rig, SceneError> {
        let p = scene.primary.as_ref().ok_or_else(|| SceneError::Missing {
            field: "primary".into(),
            hint: "the trade-off compares the primary's response Z; add a [primary] table".into(),
        })?;
        Ok(Rig {
            primary: p.system(),
            amplitude_m: scene.excitation.amplitude,
            gravity: scene.gravity,
        })
    }

    /// The DEM drive at `frequency_hz`.
    pub fn drive(&self, frequency_hz: f64) -> BoxDrive {
        BoxDrive {
            primary: Some(self.primary),
            amplitude_m: self.amplitude_m,
            frequency_hz,
        }
    }
}

/// The recorded part of a run: box position, grain position, cumulative grain dissipation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trace {
    /// Sample times (s).
    pub time_s: Vec<f64>,
    /// Box position z (m).
    pub box_z_m: Vec<f64>,
    /// Particle position or grains' centre of mass (m).
    pub grain_z_m: Vec<f64>,
    /// Cumulative energy dissipated by the grains (collisions + friction) (J); empty for the
    /// impact model (its per-cycle loss comes from the run summary).
    pub dissipated_j: Vec<f64>,
    /// Cumulative collision (normal damping) loss (J), DEM only.
    pub collision_j: Vec<f64>,
}

impl Observer for Trace {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.time_s.push(s.time_s);
        self.box_z_m.push(s.box_z_m);
        self.grain_z_m.push(s.grain_z_m);
        if let ModelSample::Dem(d) = s.model {
            self.dissipated_j.push(d.e_collision_j + d.e_friction_j);
            self.collision_j.push(d.e_collision_j);
        }
        Ok(())
    }
}

/// A finished run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutput {
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// Wall-clock time of the driven run (s), measured inside the (single-threaded) run:
    /// the cost of the simulated duration (DEM: bed building and settling excluded, as they
    /// can be shared between frequencies; sampling excluded).
    pub wall_time_s: f64,
    /// Wall-clock time of the whole run, bed building and settling included (s).
    pub total_wall_time_s: f64,
    /// Time steps of the driven run (DEM) or events (impact model).
    pub steps: u64,
    /// The recorded series.
    pub trace: Trace,
    /// Grain dissipation per cycle from the model's own summary (J) (impact model).
    pub summary_dissipation_j_per_cycle: Option<f64>,
    /// Total grain mass (kg).
    pub grain_mass_kg: f64,
    /// Settled bed height (m) (DEM).
    pub bed_height_m: Option<f64>,
    /// Time step (s) (DEM).
    pub dt_s: Option<f64>,
}

/// Runs a DEM case at `frequency_hz` on `rig`.
///
/// # Errors
/// The simulator's errors (e.g. a time step refused by the stability guard).
pub fn run_dem_case(case: &Case, rig: &Rig, frequency_hz: f64) -> Result<RunOutput, SimError> {
    let params = case.effective_params();
    let cfg = DemRunConfig {
        duration_s: case.duration_s,
        sample_interval_s: SAMPLE_INTERVAL_S,
        steady_fraction: case.steady_fraction,
        dt: DtChoice::Auto,
        dt_fraction: case.dt_fraction,
        gravity_m_s2: rig.gravity,
        ..DemRunConfig::default()
    };
    let mut trace = Trace::default();
    let clock = Instant::now();
    let s = crate::setup::dem::run_params(&params, rig.drive(frequency_hz), &cfg, &mut trace)?;
    let wall = clock.elapsed().as_secs_f64();
    Ok(RunOutput {
        frequency_hz,
        wall_time_s: s.wall_time_s,
        total_wall_time_s: wall,
        steps: s.steps,
        trace,
        summary_dissipation_j_per_cycle: None,
        grain_mass_kg: s.grain_mass_kg,
        bed_height_m: Some(s.bed_height_m),
        dt_s: Some(s.dt_s),
    })
}

/// The one-particle scene equivalent to a bed: mass m_p, gap = Lz − bed height, restitution e.
pub fn one_particle_scene(
    rig: &Rig,
    frequency_hz: f64,
    mass_kg: f64,
    gap_m: f64,
    e: f64,
    duration_s: f64,
    steady_fraction: f64,
) -> Scene {
    let mut run = Run::with_duration(duration_s);
    run.steady_fraction = steady_fraction;
    run.sample_interval = SAMPLE_INTERVAL_S;
    Scene {
        gravity: rig.gravity,
        primary: Some(crate::scene::Primary::new(
            rig.primary.mass_kg,
            rig.primary.stiffness_n_m,
            rig.primary.damping_n_s_m,
        )),
        excitation: crate::scene::Excitation {
            amplitude: rig.amplitude_m,
            frequency: frequency_hz,
        },
        damper: Damper::Impact(ImpactParams {
            mass: mass_kg,
            gap: gap_m.max(0.0),
            restitution: e,
            initial_height: 0.0,
            initial_velocity: 0.0,
        }),
        run,
        outputs: Default::default(),
    }
}

/// Runs the one-particle impact model (SPEC §3) for `scene`.
///
/// # Errors
/// The impact model's errors.
pub fn run_impact_scene(scene: &Scene) -> Result<RunOutput, SimError> {
    let mut trace = Trace::default();
    let opts = RunOptions {
        sample_interval_s: Some(SAMPLE_INTERVAL_S),
        sample_from_s: 0.0,
    };
    let clock = Instant::now();
    let s = crate::impact::simulate(&scene.resolve_impact()?, &mut trace, &opts)
        .map_err(crate::setup::keyed)?;
    let wall = clock.elapsed().as_secs_f64();
    Ok(RunOutput {
        frequency_hz: scene.frequency_hz(),
        wall_time_s: wall,
        total_wall_time_s: wall,
        steps: s.events_total,
        trace,
        summary_dissipation_j_per_cycle: Some(s.energy_impact_j_per_cycle),
        grain_mass_kg: scene.attached_mass_kg(),
        bed_height_m: None,
        dt_s: None,
    })
}

/// What the errors are measured on, for one run and one steady window.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// Steady amplitude of the primary Z = (max z − min z)/2 (m).
    pub amplitude_m: f64,
    /// Energy dissipated by the grains per forcing cycle (J).
    pub dissipation_j_per_cycle: f64,
    /// Collision share of it (J), DEM only.
    pub collision_j_per_cycle: Option<f64>,
    /// Steady-state grain series z (m) and its sampling interval (s).
    pub grain_z_m: Vec<f64>,
    /// Sampling interval of `grain_z_m` (s).
    pub sample_dt_s: f64,
}

/// Reduces a run to an [`Observation`] over its last `steady_fraction`.
///
/// # Errors
/// [`SimError::Output`] when the window holds fewer than 2 samples.
pub fn observe(out: &RunOutput, steady_fraction: f64) -> Result<Observation, SimError> {
    let t = &out.trace;
    let n = t.time_s.len();
    let t_end = t.time_s.last().copied().unwrap_or(0.0);
    let t0 = t_end * (1.0 - steady_fraction);
    let i0 = t.time_s.iter().position(|&x| x >= t0 - 1e-12).unwrap_or(n);
    if n < 2 || n - i0 < 2 {
        return Err(SimError::Output(format!(
            "steady window of {steady_fraction} × {t_end} s holds fewer than 2 samples"
        )));
    }
    let (lo, hi) = crate::analysis::min_max(&t.box_z_m[i0..]);
    let cycles = (t_end - t.time_s[i0]) * out.frequency_hz;
    let per_cycle = |v: &[f64]| (v[n - 1] - v[i0]) / cycles;
    let dissipation = match out.summary_dissipation_j_per_cycle {
        Some(d) => d,
        None if t.dissipated_j.len() == n => per_cycle(&t.dissipated_j),
        None => f64::NAN,
    };
    Ok(Observation {
        amplitude_m: 0.5 * (hi - lo),
        dissipation_j_per_cycle: dissipation,
        collision_j_per_cycle: (t.collision_j.len() == n).then(|| per_cycle(&t.collision_j)),
        grain_z_m: t.grain_z_m[i0..].to_vec(),
        sample_dt_s: t.time_s[1] - t.time_s[0],
    })
}
