//! Resolving a scene with damper `dem` to the DEM's [`DemSetup`] — the grains drawn from
//! their distribution with their masses, the contact model selected by the scene's enums,
//! the box drive and the run settings — and running it (series columns and `summary.json`
//! keys of the shared contract).

use std::path::PathBuf;

use crate::dem::model::{DemModel, Grains, Packing};
use crate::dem::replica::{run_replica_deferred, DeferredReplica, ReplicaOptions, DEFAULT_DELTA_M};
use crate::dem::run::{run_dem, run_dem_with_step, DemRunConfig, DtChoice};
use crate::dem::stability::TimeStep;
use crate::error::{SceneError, SimError};
use crate::model::{BoxDrive, DemExtras, EnergyTotals, RunOptions, RunSummary, RunWindow};
use crate::observe::{Observer, SnapshotWriter, StrobeCollector, Tee};
use crate::scene::dem::{DemParams, PackingKind, SnapshotFormat};
use crate::scene::run::ReplicaChoice;
use crate::scene::{Damper, DtSpec, Scene};

use super::keys::{keyed, scene_error};
use super::window::window;

mod contact;
mod memory;

pub use contact::{
    contact_model, hertz_kk_gamma_n, hertz_kk_gamma_s, DEFAULT_RESTITUTION_SPEED,
    GAMMA_S_PER_GAMMA_N,
};
pub use memory::{check_memory, memory_estimate, MemoryEstimate, PACKING_BYTES_PER_CELL};

/// A resolved DEM scene: the damper, its drive, gravity, the run settings and outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct DemSetup {
    /// The resolved damper (grains, contact model, box, bed).
    pub model: DemModel,
    /// The box drive (primary + base motion, or a kinematic box).
    pub drive: BoxDrive,
    /// Acceleration of gravity (m/s²), `[0, 0, −g]` unless `environment.gravity` says
    /// otherwise.
    pub gravity_m_s2: [f64; 3],
    /// Duration, steady-state and analysis windows (s).
    pub window: RunWindow,
    /// Fraction of the run treated as steady state (–).
    pub steady_fraction: f64,
    /// Last fraction of the run recorded in the stroboscopic section (–).
    pub analysis_fraction: f64,
    /// Output sampling interval of `series.csv` (s).
    pub sample_interval_s: f64,
    /// Time step as the scene asks for it: automatic or explicit (`run.dt`).
    pub dt: DtChoice,
    /// dt / t_s with an automatic step (–) (`run.dt_fraction`).
    pub dt_fraction: f64,
    /// The time step the rule chose for `dt` and `dt_fraction`, once, here (checked against
    /// the contact time) and put on the scene's step clock ([`step_clock_s`]): every run of
    /// the scene takes this step, whatever it samples — `pdamp simulate` (every
    /// `run.sample_interval`), a sweep point (the analysis window's samples, or none) and
    /// `check-scene`'s plan, which prints it.
    pub time_step: TimeStep,
    /// Snapshot directory and format, when snapshots are written.
    pub snapshots: Option<(PathBuf, SnapshotFormat)>,
    /// When the two-replica test runs (`run.replica`); see [`simulate_for_verdict`].
    pub replica: ReplicaChoice,
    /// Book the energy ledger (`run.energy_ledger`).
    pub energy_ledger: bool,
    /// `primary.initial_displacement` (m), see [`DemRunConfig::initial_box_z_m`].
    pub initial_box_z_m: Option<f64>,
    /// `primary.initial_velocity` (m/s).
    pub initial_box_v_m_s: Option<f64>,
    /// `environment.rotation`: the rotating frame, its axis placed from the container's centre
    /// at rest (m).
    pub rotation: Option<crate::model::FrameRotation>,
}

impl DemSetup {
    /// The sample clock of a run with the sampling of `opts` (s): its interval, or
    /// `run.sample_interval` for a run without samples.
    pub fn sample_interval_for(&self, opts: &RunOptions) -> f64 {
        opts.sample_interval_s.unwrap_or(self.sample_interval_s)
    }

    /// The engine's run settings for the sampling of `opts`.
    pub fn config(&self, opts: &RunOptions) -> DemRunConfig {
        DemRunConfig {
            duration_s: self.window.duration_s,
            sample_interval_s: self.sample_interval_for(opts),
            steady_fraction: self.steady_fraction,
            analysis_fraction: self.analysis_fraction,
            dt: self.dt,
            dt_fraction: self.dt_fraction,
            samples: opts.sample_interval_s.is_some(),
            sample_from_s: opts.sample_from_s,
            gravity_m_s2: self.gravity_m_s2,
            energy_ledger: self.energy_ledger,
            initial_box_z_m: self.initial_box_z_m,
            initial_box_v_m_s: self.initial_box_v_m_s,
            rotation: self.rotation,
        }
    }
}

/// The scene's step clock (s): the interval of the analysis window's samples
/// ([`super::steady_series`]: `run.sample_interval`, or the analysis window divided by
/// `run.analysis_max_samples` when that is longer). An automatic step is shortened to the
/// nearest whole fraction of it ([`TimeStep::on_sample_clock`]), so that the analysed samples
/// fall on time steps; a run sampling more often (`pdamp simulate`'s `series.csv` every
/// `run.sample_interval`) samples every whole number of steps nearest its interval, and
/// writes each sample's exact time.
///
/// One clock for every run of the scene is what makes `pdamp simulate` and a sweep point of
/// the same scene take the same step and the same trajectory.
pub fn step_clock_s(scene: &Scene) -> f64 {
    super::steady_series(scene)
        .sample_interval_s
        .unwrap_or(scene.run.sample_interval)
}

/// The DEM's setup of a validated scene with damper `dem`. The time step is checked against
/// the contact time here, so that a refused `run.dt` is reported before any output.
///
/// # Errors
/// [`SceneError`] naming the key: a damper other than `dem`, invalid grains or laws, a
/// refused time step.
pub fn dem_setup(scene: &Scene) -> Result<DemSetup, SceneError> {
    let Damper::Dem(params) = &scene.damper else {
        return Err(SceneError::invalid(
            "damper.kind",
            scene.damper.kind(),
            "the DEM model runs only damper.kind = \"dem\"",
        ));
    };
    let model = dem_model(params)?;
    let drive = super::drive::box_drive(scene);
    let dt = match scene.run.dt {
        Some(DtSpec::Seconds(s)) => DtChoice::Seconds(s),
        _ => DtChoice::Auto,
    };
    // the one rule, applied once: the step chosen against the contact time, put on the
    // scene's step clock (`step_clock_s`) whatever a run then samples
    let time_step = TimeStep::choose(&model, &drive, dt, scene.run.dt_fraction)
        .map_err(scene_error)?
        .on_sample_clock(step_clock_s(scene));
    Ok(DemSetup {
        model,
        drive,
        gravity_m_s2: scene.gravity_vector(),
        window: window(scene),
        steady_fraction: scene.run.steady_fraction,
        analysis_fraction: scene.run.analysis_fraction,
        sample_interval_s: scene.run.sample_interval,
        dt,
        dt_fraction: scene.run.dt_fraction,
        time_step,
        snapshots: params.snapshot_interval.map(|_| {
            (
                PathBuf::from(
                    params
                        .snapshot_dir
                        .clone()
                        .unwrap_or_else(|| "snapshots".into()),
                ),
                params.snapshot_format,
            )
        }),
        replica: scene.run.replica,
        energy_ledger: scene.run.energy_ledger,
        initial_box_z_m: scene.primary.as_ref().and_then(|p| p.initial_displacement),
        initial_box_v_m_s: scene.primary.as_ref().and_then(|p| p.initial_velocity),
        rotation: scene
            .environment
            .rotation
            .as_ref()
            .map(|r| r.frame(params.r#box.map(|l| 0.5 * l))),
    })
}

/// The resolved DEM damper of `params`: validated once, radii drawn from their distribution
/// (seeded by `damper.seed`) with their masses, the contact model of `damper.contact`.
///
/// # Errors
/// [`SceneError`] naming the key (see [`DemParams::validate`]).
pub fn dem_model(params: &DemParams) -> Result<DemModel, SceneError> {
    params.validate()?;
    let dist = params.radius_distribution()?;
    check_memory(
        &memory_estimate(params, dist.r_max()),
        crate::dem::world::available_memory_bytes(),
    )?;
    let radii = dist.sample_n(params.count, params.seed);
    let grains = Grains::new(
        radii,
        params.density,
        params.grain_material(),
        (dist.r_min(), dist.r_max()),
    );
    let model = DemModel {
        box_size_m: params.r#box,
        container: params.container_shape(),
        grains,
        contact: contact_model(params)?,
        rotations: params.rotations,
        orientations: params.orientations,
        neighbor_skin_m: params.neighbor_skin,
        packing: match params.packing {
            PackingKind::Lattice => Packing::Lattice { seed: params.seed },
            PackingKind::AdvancingFront => Packing::AdvancingFront,
        },
        settle_time_s: params.settle_time.unwrap_or(1.0),
        snapshot_interval_s: params.snapshot_interval,
        bag: match &params.bag {
            Some(b) => Some(
                crate::dem::bag::bag_mesh(b.geometry(params.r#box, dist.r_min()), b.film_model())
                    .map_err(scene_error)?,
            ),
            None => None,
        },
    };
    // the linear law's parameters (e, Y) and the contact time are checked once, here
    crate::dem::stability::contact_time(&model, 1.0).map_err(scene_error)?;
    Ok(model)
}

/// Runs the DEM for `params` on `drive` with the engine settings `cfg` (the scene-level
/// entry of tests, benchmarks and the trade-off study): resolves the damper
/// ([`dem_model`]) and names refused quantities by their scene keys.
///
/// # Errors
/// As [`dem_model`] and [`run_dem`], keyed.
pub fn run_params(
    params: &DemParams,
    drive: BoxDrive,
    cfg: &DemRunConfig,
    obs: &mut dyn Observer,
) -> Result<crate::dem::DemSummary, SimError> {
    let model = dem_model(params)?;
    run_dem(&model, drive, cfg, obs).map_err(keyed)
}

/// Runs a DEM scene: samples go to `obs` (model part [`crate::observe::ModelSample::Dem`]),
/// snapshots to a [`SnapshotWriter`], the stroboscopic points to the summary; the summary follows `summary.json`'s keys; the DEM's own figures
/// (`energy_collision_j_per_cycle`, `energy_friction_j_per_cycle`, `steps`, `wall_time_s`,
/// `particle_steps_per_s`, `dt_s`, `contact_time_s`, `volume_fraction`, …) are in `dem`
/// ([`DemExtras`]), the run's warnings in `warnings`.
/// Without `[primary]` the box moves kinematically with the base. With `run.replica` the
/// two-replica test ([`crate::dem::replica`]) runs alongside and its report is in `replica`.
///
/// # Errors
/// The errors of [`run_dem`] (engine quantities, mapped to keys by [`super::simulate`]);
/// output errors of the observer.
pub fn simulate(
    setup: &DemSetup,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<RunSummary, SimError> {
    let replica = match setup.replica.delta_m(false) {
        Some(d) => ReplicaRun::Now(d),
        None => ReplicaRun::Off,
    };
    let (mut s, deferred) = simulate_with(setup, obs, opts, replica)?;
    s.replica = deferred.map(DeferredReplica::complete);
    Ok(s)
}

/// [`simulate`] for a run analysed for a regime verdict: the two-replica test's replica B is
/// cloned at the analysis start but left unstepped when `run.replica` is left out (the
/// default: the caller completes it only if the verdict needs it, [`DeferredReplica`]), run
/// in full when `run.replica` sets it, not at all when it is `false`.
///
/// # Errors
/// As [`simulate`].
pub fn simulate_for_verdict(
    setup: &DemSetup,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<(RunSummary, Option<DeferredReplica>), SimError> {
    let replica = match setup.replica {
        ReplicaChoice::WithVerdict => ReplicaRun::Deferred(DEFAULT_DELTA_M),
        ReplicaChoice::Delta(d) => ReplicaRun::Now(d),
        ReplicaChoice::Off => ReplicaRun::Off,
    };
    let (mut s, deferred) = simulate_with(setup, obs, opts, replica)?;
    if let ReplicaRun::Now(_) = replica {
        s.replica = deferred.map(DeferredReplica::complete);
        return Ok((s, None));
    }
    Ok((s, deferred))
}

/// Whether and when a run's two-replica test runs.
#[derive(Debug, Clone, Copy)]
enum ReplicaRun {
    Off,
    /// With this δ0 (m), completed by the caller.
    Now(f64),
    /// With this δ0 (m), left for the caller to complete or not.
    Deferred(f64),
}

/// The run, with replica B cloned when `replica` asks for the test (not stepped: the
/// summary's `replica` is left empty for the caller).
fn simulate_with(
    setup: &DemSetup,
    obs: &mut dyn Observer,
    opts: &RunOptions,
    replica: ReplicaRun,
) -> Result<(RunSummary, Option<DeferredReplica>), SimError> {
    let (drive, cfg, step) = (setup.drive, setup.config(opts), setup.time_step);
    let mut snapshots = setup.snapshots.as_ref().map(|(dir, format)| {
        SnapshotWriter::new(
            dir.clone(),
            matches!(format, SnapshotFormat::Csv | SnapshotFormat::Both),
            matches!(format, SnapshotFormat::Vtk | SnapshotFormat::Both),
        )
    });
    let mut strobe = StrobeCollector::default();
    let mut observers: Vec<&mut dyn Observer> = vec![obs, &mut strobe];
    if let Some(w) = snapshots.as_mut() {
        observers.push(w);
    }
    let mut fwd = Tee { observers };
    // `run.replica`: replica B perturbed at the start of the analysis window
    let (s, deferred) = match replica {
        ReplicaRun::Now(delta_m) | ReplicaRun::Deferred(delta_m) => {
            let opts = ReplicaOptions::at_analysis_start(&cfg, delta_m);
            let (s, r) = run_replica_deferred(&setup.model, drive, &cfg, step, &opts, &mut fwd)?;
            (s, Some(r))
        }
        ReplicaRun::Off => (
            run_dem_with_step(&setup.model, drive, &cfg, step, &mut fwd)?,
            None,
        ),
    };
    drop(fwd);
    // what the run warns about goes back to the caller (the CLI prints `warning: …`)
    let warnings = [&s.time_step_warning, &s.energy_balance_warning]
        .into_iter()
        .flatten()
        .cloned()
        .collect();
    let cycles = (cfg.duration_s - s.steady_start_s) * drive.frequency_hz;
    let l = s.ledger;
    let opt = |v: Option<f64>| v.unwrap_or(f64::NAN);
    let dem = DemExtras {
        energy_collision_j_per_cycle: opt(s.energy_collision_j_per_cycle),
        energy_friction_j_per_cycle: opt(s.energy_friction_j_per_cycle),
        energy_bag_j_per_cycle: s.energy_bag_j_per_cycle,
        bed_floor_impacts_per_cycle: s.bed_impacts.floor as f64 / s.cycles_steady,
        bed_ceiling_impacts_per_cycle: s.bed_impacts.ceiling as f64 / s.cycles_steady,
        steps: s.steps as f64,
        wall_time_s: s.wall_time_s,
        particle_steps_per_s: s.particle_steps_per_s,
        // a machine figure, left out when the thread's CPU time was not measurable (a JSON
        // null would make the point unreadable)
        particle_steps_per_cpu_s: s.particle_steps_per_cpu_s,
        dt_s: s.dt_s,
        contact_time_s: s.contact_time_s,
        viscous_time_s: s.viscous_time_s,
        // 1 when the ledger's residual exceeds 1 % (the run also warns)
        energy_balance_warning: f64::from(u8::from(s.energy_balance_warning.is_some())),
        settle_time_s: s.settle_time_s,
        settle_steps: s.settle_steps as f64,
        neighbor_builds: s.neighbor_builds as f64,
        // contacts per grain, mean over the steady window's samples (cost of a step: see
        // bench/README.md)
        candidate_pairs_per_grain: s.contacts_per_grain.candidate_pairs,
        pair_contacts_per_grain: s.contacts_per_grain.pair_contacts,
        wall_contacts_per_grain: s.contacts_per_grain.wall_contacts,
        grains: s.grains as f64,
        grain_mass_kg: s.grain_mass_kg,
        bed_height_m: s.bed_height_m,
        volume_fraction: s.volume_fraction,
    };
    let summary = RunSummary {
        model: "dem".into(),
        frequency_hz: drive.frequency_hz,
        duration_s: cfg.duration_s,
        steady_start_s: s.steady_start_s,
        cycles_steady: cycles,
        amplitude_m: s.amplitude_m,
        box_z_max_m: s.box_z_max_m,
        box_z_min_m: s.box_z_min_m,
        reference_amplitude_m: drive.reference_amplitude_m(),
        energy_input_j_per_cycle: opt(s.energy_base_work_j_per_cycle),
        energy_viscous_j_per_cycle: opt(s.energy_viscous_j_per_cycle),
        energy_impact_j_per_cycle: opt(s.energy_collision_j_per_cycle)
            + opt(s.energy_friction_j_per_cycle),
        // collective bed–floor and bed–ceiling impacts (dem::bed_impacts)
        impacts_per_cycle: if s.cycles_steady > 0.0 {
            s.bed_impacts.total() as f64 / s.cycles_steady
        } else {
            f64::NAN
        },
        energy_balance_relative_error: Some(s.energy_balance_relative_error),
        energy_totals: EnergyTotals {
            base_work_j: l.base_work_j,
            viscous_j: l.viscous_j,
            impact_j: l.collision_j + l.friction_j,
            initial_mechanical_j: s.energy_start_j,
            final_mechanical_j: s.energy_end_j,
        },
        impacts_total: s.bed_impacts.total(),
        events_total: 0,
        dem: Some(dem),
        warnings,
        strobe: strobe.points,
        analysis: None,
        analysis_error: None,
        replica: None,
        decay: None,
    };
    Ok((summary, deferred))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dem::run::run_dem_stepped;
    use crate::dem::stability::choose_dt;

    /// The fraction these tests were written for (the default was 1/50 then).
    const DT_FRACTION: f64 = 1.0 / 50.0;
    use crate::dem::world::ContactsPerGrain;

    #[test]
    fn explicit_dt_above_limit_is_rejected_with_the_limit() {
        let p = dem_model(&DemParams::thesis_b()).unwrap();
        let d = BoxDrive {
            primary: None,
            amplitude_m: 4.5e-3,
            frequency_hz: 15.0,
            force_n: 0.0,
            direction: [0.0, 0.0, 1.0],
        };
        let (dt, ts) = choose_dt(&p, &d, None, DT_FRACTION).unwrap();
        assert!((dt - ts / 50.0).abs() < 1e-20);
        // steel, R = 3 mm, v ≈ 1.55 m/s (free fall over 0.1225 m): t_s ≈ 1.5e-5 s
        assert!(ts > 5e-6 && ts < 5e-5, "{ts}");
        let e = choose_dt(&p, &d, Some(1e-4), DT_FRACTION).unwrap_err();
        // the engine speaks of the time step; the resolve step names the key
        assert!(
            e.to_string().contains("time step") && e.to_string().contains("t_s/20"),
            "{e}"
        );
        let e = super::super::keys::scene_error(e).to_string();
        assert!(e.contains("run.dt") && e.contains("t_s/20"), "{e}");
        assert!(choose_dt(&p, &d, Some(ts / 30.0), DT_FRACTION).is_ok());
    }

    // (an engine figure, tested here because the engine's own tests may not build a scene)
    #[test]
    fn contacts_per_grain_are_their_mean_over_the_steady_window_samples() {
        let mut p = DemParams::thesis_b_softened(1000.0);
        p.count = 200;
        p.settle_time = Some(0.05);
        let model = dem_model(&p).unwrap();
        let drive = BoxDrive {
            primary: None,
            amplitude_m: 4.5e-3,
            frequency_hz: 15.0,
            force_n: 0.0,
            direction: [0.0, 0.0, 1.0],
        };
        let (dt, _) = choose_dt(&model, &drive, None, DT_FRACTION).unwrap();
        let per_sample = 25;
        let cfg = DemRunConfig {
            duration_s: 1000.0 * dt,
            sample_interval_s: per_sample as f64 * dt,
            steady_fraction: 0.5,
            dt: DtChoice::Seconds(dt),
            samples: false,
            ..DemRunConfig::default()
        };
        // the counts after every driven step, taken here apart from the run's own count
        let mut seen = Vec::new();
        let step = TimeStep::choose(&model, &drive, cfg.dt, cfg.dt_fraction).unwrap();
        let summary = run_dem_stepped(&model, drive, &cfg, step, &mut Vec::new(), &mut |w| {
            seen.push(ContactsPerGrain::of(w.contact_counts(), w.len()));
            Ok(())
        })
        .unwrap();
        let steps = summary.steps;
        assert_eq!(seen.len() as u64, steps);
        // the samples of the window: every `per_sample` steps from the window's start, and the
        // last step
        let from = ((1.0 - cfg.steady_fraction) * steps as f64).floor() as u64;
        let picked: Vec<ContactsPerGrain> = (from.max(1)..=steps)
            .filter(|&k| k % per_sample == 0 || k == steps)
            .map(|k| seen[k as usize - 1])
            .collect();
        assert!(picked.len() >= 10, "{} samples", picked.len());
        let n = picked.len() as f64;
        let mean = |f: fn(&ContactsPerGrain) -> f64| picked.iter().map(f).sum::<f64>() / n;
        let got = summary.contacts_per_grain;
        for (name, f) in [
            (
                "candidate pairs",
                (|c: &ContactsPerGrain| c.candidate_pairs) as fn(&_) -> f64,
            ),
            ("pair contacts", |c| c.pair_contacts),
            ("wall contacts", |c| c.wall_contacts),
        ] {
            let (want, g) = (mean(f), f(&got));
            assert!(
                (g - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{name}: {g} against the mean {want}"
            );
        }
        // the vibrated bed's counts move within the window, so the mean is not the last state
        let last = seen[steps as usize - 1];
        assert!(
            picked.iter().any(|c| c.pair_contacts != last.pair_contacts),
            "contacts did not change in the window"
        );
        assert!(got.pair_contacts > 0.0 && got.wall_contacts > 0.0);
    }
}
