//! Running a DEM scene: radii and initial bed (lattice or advancing front), settling under
//! gravity with the box held still, then the driven run with samples at a fixed interval.

use std::time::Instant;

use serde::Serialize;

use crate::contact::lanes::dot;
use crate::error::{ModelError, Quantity, SimError};
use crate::units::G;

use crate::model::{
    StrobePoint, DEFAULT_ANALYSIS_FRACTION, DEFAULT_SAMPLE_INTERVAL_S, DEFAULT_STEADY_FRACTION,
};
use crate::observe::{DemSampleState, ModelSample, Observer, Sample, SampleKind};

pub use super::bed::{initial_positions, initial_world, settle};
use super::bed::{release, settled_bed};
use super::bed_impacts::BedImpacts;
use super::energy::{balance, EnergyLedger};
use super::model::DemModel;
pub use super::stability::DtChoice;
use super::stability::{TimeStep, TimeStepScales, DEFAULT_DT_FRACTION};
use super::steady::{strobe_state, EnergyWatch, SteadyWindow, StrobeClock};
use super::world::{BoxDrive, ContactsPerGrain, DemWorld};

/// Relative ledger residual above which a run warns (stderr, `summary.json`) (1 %).
pub const LEDGER_WARNING_LIMIT: f64 = 0.01;

/// Run settings of a DEM simulation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemRunConfig {
    /// Driven duration after settling (s).
    pub duration_s: f64,
    /// Interval between samples (s).
    pub sample_interval_s: f64,
    /// Fraction of the run treated as steady state for per-cycle figures (default 0.1).
    pub steady_fraction: f64,
    /// Last fraction of the run recorded in the stroboscopic section (default 0.5, at least
    /// `steady_fraction`).
    pub analysis_fraction: f64,
    /// Time step.
    pub dt: DtChoice,
    /// dt / t_s with `DtChoice::Auto` (default [`DEFAULT_DT_FRACTION`]).
    pub dt_fraction: f64,
    /// Send samples to the observer (false: summary only).
    pub samples: bool,
    /// No samples before this time (s).
    pub sample_from_s: f64,
    /// Acceleration of gravity (m/s²), default [0, 0, −9.8].
    pub gravity_m_s2: [f64; 3],
    /// Book the energy ledger (default true; `run.energy_ledger`). Off: the step computes no
    /// dissipated powers, the per-cycle energies are absent, the samples' ledger columns and
    /// residual are 0, the summary's relative error is NaN (null in `summary.json`), and the
    /// stability check loses its energy-growth test.
    pub energy_ledger: bool,
    /// The primary's displacement along the drive axis at t = 0 (m, from the static
    /// equilibrium of M alone; `primary.initial_displacement`): the box and the settled bed
    /// in it are moved there before the drive starts. Default: the static equilibrium with
    /// the bed's weight, m_p g·d / K.
    pub initial_box_z_m: Option<f64>,
    /// The primary's velocity along the drive axis at t = 0 (m/s), the grains left at rest
    /// (`primary.initial_velocity`). Default 0.
    pub initial_box_v_m_s: Option<f64>,
    /// The rotating frame the damper sits on (centrifugal and Coriolis forces on the grains),
    /// if any.
    pub rotation: Option<crate::model::FrameRotation>,
}

impl Default for DemRunConfig {
    fn default() -> Self {
        DemRunConfig {
            duration_s: 1.0,
            sample_interval_s: DEFAULT_SAMPLE_INTERVAL_S,
            steady_fraction: DEFAULT_STEADY_FRACTION,
            analysis_fraction: DEFAULT_ANALYSIS_FRACTION,
            dt: DtChoice::Auto,
            dt_fraction: DEFAULT_DT_FRACTION,
            samples: true,
            sample_from_s: 0.0,
            gravity_m_s2: [0.0, 0.0, -G],
            energy_ledger: true,
            initial_box_z_m: None,
            initial_box_v_m_s: None,
            rotation: None,
        }
    }
}

/// A DEM sample with its DEM part unpacked (lab frame, SI units; energies cumulative since
/// the drive started), for callers that keep the samples of a DEM run
/// ([`DemSample::from_sample`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemSample {
    /// The sample (time, base, box, walls, z_cm, grain force).
    pub sample: Sample,
    /// Its [`ModelSample::Dem`] part: the grains' extent and the energy ledger.
    pub dem: DemSampleState,
}

impl DemSample {
    /// The DEM sample carried by `s`, if its model part is the DEM's.
    pub fn from_sample(s: &Sample) -> Option<DemSample> {
        let ModelSample::Dem(dem) = s.model else {
            return None;
        };
        Some(DemSample { sample: *s, dem })
    }
}

/// Keeps every DEM sample in memory (tests, small runs).
impl Observer for Vec<DemSample> {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.extend(DemSample::from_sample(s));
        Ok(())
    }
}

/// The stroboscopic point at `t_s`, interpolated linearly between the states `a` (before)
/// and `b` (after), each `(t, z_cm, v_cm, box_z, box_v)`.
pub(crate) fn interpolate_strobe(cycle: u64, t_s: f64, a: [f64; 5], b: [f64; 5]) -> StrobePoint {
    let span = b[0] - a[0];
    let w = if span > 0.0 {
        ((t_s - a[0]) / span).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let at = |k: usize| a[k] + w * (b[k] - a[k]);
    StrobePoint {
        cycle,
        time_s: t_s,
        grain_z_m: at(1),
        grain_v_m_s: at(2),
        box_z_m: at(3),
        box_v_m_s: at(4),
    }
}

/// Summary of a DEM run (`summary.json` keys).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemSummary {
    /// Half the peak-to-peak box displacement in the steady state (m).
    pub amplitude_m: f64,
    /// |E − E₀ − W_base + D| / max(W_base, D, |ΔE|) over the whole driven run (–).
    pub energy_balance_relative_error: f64,
    /// Collision dissipation per forcing cycle in the steady state (J).
    pub energy_collision_j_per_cycle: Option<f64>,
    /// Friction dissipation per cycle (J).
    pub energy_friction_j_per_cycle: Option<f64>,
    /// Dissipation in a bean bag's bonds per cycle (J); `None` without a bag.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_bag_j_per_cycle: Option<f64>,
    /// Viscous dissipation in C per cycle (J).
    pub energy_viscous_j_per_cycle: Option<f64>,
    /// Base work per cycle (J).
    pub energy_base_work_j_per_cycle: Option<f64>,
    /// Time steps of the driven run (settling excluded).
    pub steps: u64,
    /// Wall-clock time of the driven run (s).
    pub wall_time_s: f64,
    /// Grains × steps / wall time of the driven run (particle-steps/s).
    pub particle_steps_per_s: f64,
    /// Grains × steps / CPU time of the driven run (particle-steps per CPU-second; Linux
    /// `/proc/thread-self/stat`, 10 ms resolution; `None` elsewhere). On a loaded machine
    /// this is the fairer single-core figure.
    pub particle_steps_per_cpu_s: Option<f64>,
    /// Time step (s).
    pub dt_s: f64,
    /// Shortest Hertz contact time at the design impact speed (s).
    pub contact_time_s: f64,
    /// Shorter of the contacts' normal and tangential viscous times at the design impact
    /// speed (s) ([`super::stability::viscous_time`]); the step should stay below a quarter.
    pub viscous_time_s: f64,
    /// A warning when the time step is too long for the viscous time (see
    /// [`super::stability::TimeStepScales::viscous_warning`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_step_warning: Option<String>,
    /// A warning when the energy ledger's residual exceeds [`LEDGER_WARNING_LIMIT`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_balance_warning: Option<String>,
    /// Simulated settling time before the drive (s).
    pub settle_time_s: f64,
    /// Settling steps.
    pub settle_steps: u64,
    /// Neighbour-list builds during the driven run.
    pub neighbor_builds: u64,
    /// Contacts per grain, mean over the samples of the steady window (the last
    /// `steady_fraction` of the run; the run's last step is always a sample): candidate
    /// pairs, grain–grain pairs in contact (half the mean coordination number) and wall
    /// contacts.
    pub contacts_per_grain: ContactsPerGrain,
    /// Number of grains.
    pub grains: usize,
    /// Total grain mass m_p (kg).
    pub grain_mass_kg: f64,
    /// Settled bed height estimate 2 (z_cm − floor) (m).
    pub bed_height_m: f64,
    /// Settled volume fraction Σ V_i / (Lx Ly · bed height) (–).
    pub volume_fraction: f64,
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// Start of the steady-state window (s).
    pub steady_start_s: f64,
    /// Largest box position in the steady state (m).
    pub box_z_max_m: f64,
    /// Smallest box position in the steady state (m).
    pub box_z_min_m: f64,
    /// Whole-run ledger (J).
    #[serde(skip)]
    pub ledger: EnergyLedger,
    /// Stored mechanical energy when the drive started (J).
    #[serde(skip)]
    pub energy_start_j: f64,
    /// Stored mechanical energy at the end (J).
    #[serde(skip)]
    pub energy_end_j: f64,
    /// Collective impacts of the bed on the floor and the ceiling in the steady window
    /// ([`BedImpacts`]).
    #[serde(skip)]
    pub bed_impacts: BedImpacts,
    /// Forcing cycles of the steady window.
    pub cycles_steady: f64,
}

/// CPU time of the calling thread (s), from `/proc/thread-self/stat` (utime + stime, in
/// clock ticks of 1/100 s); `None` where unavailable.
pub fn thread_cpu_time_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    let f: Vec<&str> = s.rsplit(')').next()?.split_whitespace().collect();
    let utime: f64 = f.get(11)?.parse().ok()?;
    let stime: f64 = f.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// Runs a DEM damper: bed, settling, then `cfg.duration_s` of drive, with the time step the
/// rule chooses from `cfg.dt` and `cfg.dt_fraction` ([`TimeStep::choose`]) on the sample
/// clock of `cfg.sample_interval_s`. `obs` receives [`Observer::start`] with
/// [`SampleKind::Dem`], the samples, the stroboscopic points of the analysis window, the
/// particle snapshots and [`Observer::finish`]. A resolved scene runs
/// [`run_dem_with_step`] with the step it resolved.
///
/// # Errors
/// [`SimError::Model`] for a refused time step or run window; packing errors;
/// [`SimError::Unstable`] when the state turns non-finite, a grain leaves the box or energy
/// grows without input.
pub fn run_dem(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    obs: &mut dyn Observer,
) -> Result<DemSummary, SimError> {
    let step = TimeStep::choose(model, &drive, cfg.dt, cfg.dt_fraction)?;
    run_dem_with_step(model, drive, cfg, step, obs)
}

/// [`run_dem`] with the time step already resolved (`cfg.dt` and `cfg.dt_fraction` are not
/// read); `step` is put on the sample clock of `cfg.sample_interval_s`
/// ([`TimeStep::on_sample_clock`], nothing for a step already on it).
///
/// # Errors
/// As [`run_dem`].
pub fn run_dem_with_step(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    step: TimeStep,
    obs: &mut dyn Observer,
) -> Result<DemSummary, SimError> {
    run_dem_stepped(model, drive, cfg, step, obs, &mut |_| Ok(()))
}

/// [`run_dem_with_step`], calling `stepped` after every time step of the driven run with the
/// state the step reached (the two-replica test steps its perturbed copy there; the time
/// spent is left out of the run's wall and CPU times).
///
/// # Errors
/// As [`run_dem`]; the errors of `stepped`.
pub(crate) fn run_dem_stepped(
    model: &DemModel,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    step: TimeStep,
    obs: &mut dyn Observer,
    stepped: &mut dyn FnMut(&DemWorld) -> Result<(), SimError>,
) -> Result<DemSummary, SimError> {
    check_run_window(cfg)?;
    let step = step.on_sample_clock(cfg.sample_interval_s);
    let (dt, ts) = (step.dt_s, step.contact_time_s);
    let forces = (cfg.gravity_m_s2, cfg.rotation, cfg.energy_ledger);
    let (mut world, bed) = settled_bed(model, drive, forces, dt)?;
    release(&mut world, cfg.initial_box_z_m, cfg.initial_box_v_m_s);
    world.start_drive();
    // the radius of grain 0 (its slot, once the grains are stored along the curve)
    let slot0 = world.grain_ids().iter().position(|&g| g == 0).unwrap_or(0);
    let watch = EnergyWatch::new(&world, bed.mass_kg, G, world.radius[slot0]);
    let builds0 = world.neighbor_builds();
    let n_steps = (cfg.duration_s / dt).ceil() as u64;
    let window = |fraction: f64| ((1.0 - fraction) * n_steps as f64).floor() as u64;
    let mut steady = SteadyWindow::new(
        window(cfg.steady_fraction),
        bed.mass_kg,
        dot(cfg.gravity_m_s2, cfg.gravity_m_s2).sqrt(),
        drive.frequency_hz,
    );
    let clock = StrobeClock {
        from_step: window(cfg.analysis_fraction.max(cfg.steady_fraction)),
        frequency_hz: drive.frequency_hz,
    };
    let timing = drive_steps(
        &mut world,
        n_steps,
        Cadence::new(model, cfg, dt, drive.frequency_hz),
        (&watch, &mut steady, clock),
        obs,
        stepped,
    )?;
    let st = world.energy_state();
    let (_, rel) = if cfg.energy_ledger {
        balance(&st, &watch.start, &world.ledger)
    } else {
        (f64::NAN, f64::NAN)
    };
    let scales = TimeStepScales::of(model, &drive)?;
    let energy_balance_warning = (rel > LEDGER_WARNING_LIMIT).then(|| {
        format!(
            "the energy ledger does not close: residual {:.2} % of the flows (> {:.0} %); {}",
            100.0 * rel,
            100.0 * LEDGER_WARNING_LIMIT,
            scales
                .viscous_warning(dt)
                .unwrap_or_else(|| { "lower the time step and compare".to_string() })
        )
    });
    let per_cycle = |f| {
        steady
            .per_cycle(&world, drive.frequency_hz, f)
            .filter(|_| cfg.energy_ledger)
    };
    Ok(DemSummary {
        amplitude_m: 0.5 * (steady.z_max_m - steady.z_min_m),
        energy_balance_relative_error: rel,
        energy_collision_j_per_cycle: per_cycle(|l| l.collision_j),
        energy_friction_j_per_cycle: per_cycle(|l| l.friction_j),
        energy_bag_j_per_cycle: world
            .bag()
            .and_then(|_| per_cycle(|l: &crate::dem::EnergyLedger| l.bag_j)),
        energy_viscous_j_per_cycle: per_cycle(|l| l.viscous_j),
        energy_base_work_j_per_cycle: per_cycle(|l| l.base_work_j),
        steps: n_steps,
        wall_time_s: timing.wall_s,
        particle_steps_per_s: world.len() as f64 * n_steps as f64 / timing.wall_s,
        particle_steps_per_cpu_s: timing
            .cpu_s
            .map(|c| world.len() as f64 * n_steps as f64 / c),
        dt_s: dt,
        contact_time_s: ts,
        viscous_time_s: scales.viscous_time_s(),
        time_step_warning: scales.viscous_warning(dt),
        energy_balance_warning,
        settle_time_s: bed.settle_time_s,
        settle_steps: bed.settle_steps,
        neighbor_builds: world.neighbor_builds() - builds0,
        contacts_per_grain: steady.contacts_per_grain(&world),
        grains: world.len(),
        grain_mass_kg: bed.mass_kg,
        bed_height_m: bed.height_m,
        volume_fraction: bed.volume_fraction,
        frequency_hz: drive.frequency_hz,
        steady_start_s: steady.from_step as f64 * dt,
        box_z_max_m: steady.z_max_m,
        box_z_min_m: steady.z_min_m,
        ledger: world.ledger,
        energy_start_j: watch.start.total_j(),
        energy_end_j: st.total_j(),
        bed_impacts: steady.impacts,
        cycles_steady: steady.cycles(&world, drive.frequency_hz),
    })
}

/// Checks the run's lengths and fractions.
fn check_run_window(cfg: &DemRunConfig) -> Result<(), SimError> {
    for (q, v) in [
        (Quantity::Duration, cfg.duration_s),
        (Quantity::SampleInterval, cfg.sample_interval_s),
    ] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(ModelError::new(q, v, "must be > 0 (seconds)").into());
        }
    }
    if !(cfg.steady_fraction > 0.0 && cfg.steady_fraction <= 1.0) {
        return Err(ModelError::new(
            Quantity::SteadyFraction,
            cfg.steady_fraction,
            "must be in (0, 1]",
        )
        .into());
    }
    Ok(())
}

/// Every how many steps the driven run samples, snapshots and reports progress.
#[derive(Debug, Clone, Copy)]
struct Cadence {
    samples: bool,
    sample_from_s: f64,
    per_sample: u64,
    per_snapshot: Option<u64>,
    per_progress: u64,
    duration_s: f64,
}

impl Cadence {
    fn new(model: &DemModel, cfg: &DemRunConfig, dt: f64, frequency_hz: f64) -> Self {
        Cadence {
            samples: cfg.samples,
            sample_from_s: cfg.sample_from_s,
            per_sample: ((cfg.sample_interval_s / dt).round() as u64).max(1),
            per_snapshot: model
                .snapshot_interval_s
                .map(|s| ((s / dt).round() as u64).max(1)),
            per_progress: ((1.0 / frequency_hz.max(1e-3)) / dt).round().max(1.0) as u64,
            duration_s: cfg.duration_s,
        }
    }

    /// Whether the state `w` is inside the sampled part of the run.
    fn sampled(&self, w: &DemWorld) -> bool {
        self.samples && w.t >= self.sample_from_s - 0.5 * w.dt
    }
}

/// Wall and CPU seconds of the driven steps, without the observers' time.
struct Timing {
    wall_s: f64,
    cpu_s: Option<f64>,
}

/// Steps the driving world `n_steps` times: the strobe points of the analysis window, the
/// samples (each energy-checked), snapshots and progress go to `obs`; the steady window
/// takes every state (and counts the contacts at the samples); `stepped` sees every state
/// too.
fn drive_steps(
    world: &mut DemWorld,
    n_steps: u64,
    every: Cadence,
    (watch, steady, clock): (&EnergyWatch, &mut SteadyWindow, StrobeClock),
    obs: &mut dyn Observer,
    stepped: &mut dyn FnMut(&DemWorld) -> Result<(), SimError>,
) -> Result<Timing, SimError> {
    obs.start(SampleKind::Dem)?;
    if every.sampled(world) {
        obs.sample(&watch.sample(world))?;
    }
    if every.per_snapshot.is_some() {
        obs.snapshot(&world.grain_state())?;
    }
    let wall0 = Instant::now();
    let cpu0 = thread_cpu_time_s();
    let mut aside = 0.0;
    for k in 1..=n_steps {
        let strobe_before = clock.before_step(k, world);
        world.step();
        let c0 = Instant::now();
        stepped(world)?;
        aside += c0.elapsed().as_secs_f64();
        steady.observe(k, world);
        if let Some((cycle, before)) = strobe_before {
            let c0 = Instant::now();
            obs.strobe(&interpolate_strobe(
                cycle as u64,
                cycle / clock.frequency_hz,
                before,
                strobe_state(world),
            ))?;
            aside += c0.elapsed().as_secs_f64();
        }
        let do_sample = k % every.per_sample == 0 || k == n_steps;
        let do_snap = every.per_snapshot.is_some_and(|ps| k % ps == 0);
        let do_progress = k % every.per_progress == 0;
        if do_sample || do_snap || do_progress {
            let c0 = Instant::now();
            if do_sample {
                steady.count_contacts(k, world);
                let s = watch.checked_sample(world)?;
                if every.sampled(world) {
                    obs.sample(&s)?;
                }
            }
            if do_snap {
                obs.snapshot(&world.grain_state())?;
            }
            if do_progress {
                obs.progress(world.t, every.duration_s)?;
            }
            aside += c0.elapsed().as_secs_f64();
        }
    }
    let total = wall0.elapsed().as_secs_f64();
    let wall_s = (total - aside).max(1e-9);
    // the stepping's share of the thread's CPU time: `aside` is wall time, which a loaded
    // machine stretches, so it is removed as a fraction of the wall time, not subtracted
    let cpu_s = match (cpu0, thread_cpu_time_s()) {
        (Some(a), Some(b)) if b - a > 0.05 => Some((b - a) * wall_s / total.max(1e-9)),
        _ => None,
    };
    obs.finish()?;
    Ok(Timing { wall_s, cpu_s })
}
