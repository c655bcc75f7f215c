//! Adapter from a [`Scene`] with `damper.kind = "dem"` to [`run_dem`]: the dispatch arm of
//! `pdamp simulate` / `sweep` (series columns and `summary.json` keys of the shared contract).

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::error::SimError;
use crate::model::{EnergyTotals, RunOptions, RunSummary, StrobePoint};
use crate::observe::{Observer, Sample};
use crate::scene::dem::{DemParams, SnapshotFormat};
use crate::scene::{Damper, DtSpec, Scene};

use super::replica::{run_replica, ReplicaOptions};
use super::run::{run_dem, DemObserver, DemRunConfig, DemSample, DtChoice};
use super::snapshot::{write_csv, write_vtk};
use super::world::{BoxDrive, DemWorld, PrimarySystem};

/// Model-specific columns of `series.csv` for the DEM, after `grain_z_m`.
pub const DEM_EXTRA_COLUMNS: [&str; 11] = [
    "grain_zmin_m",
    "grain_zmax_m",
    "e_collision_j",
    "e_friction_j",
    "e_viscous_j",
    "e_base_work_j",
    "e_kinetic_j",
    "e_potential_j",
    "e_elastic_j",
    "e_primary_j",
    "e_balance_residual_j",
];

struct Forward<'a> {
    obs: &'a mut dyn Observer,
    snapshot_dir: Option<PathBuf>,
    format: SnapshotFormat,
    snapshots: usize,
}

impl DemObserver for Forward<'_> {
    fn sample(&mut self, s: &DemSample) -> Result<(), SimError> {
        let extra = [
            s.grain_zmin_m,
            s.grain_zmax_m,
            s.e_collision_j,
            s.e_friction_j,
            s.e_viscous_j,
            s.e_base_work_j,
            s.e_kinetic_j,
            s.e_potential_j,
            s.e_elastic_j,
            s.e_primary_j,
            s.e_balance_residual_j,
        ];
        self.obs.sample(&Sample {
            time_s: s.time_s,
            base_u_m: s.base_u_m,
            box_z_m: s.box_z_m,
            box_v_m_s: s.box_v_m_s,
            floor_z_m: s.floor_z_m,
            ceiling_z_m: s.ceiling_z_m,
            grain_z_m: s.grain_z_m,
            extra: &extra,
            grain_force_n: s.grain_force_n,
        })
    }

    fn snapshot(&mut self, world: &DemWorld) -> Result<(), SimError> {
        let Some(dir) = &self.snapshot_dir else {
            return Ok(());
        };
        let io =
            |e: std::io::Error| SimError::Output(format!("snapshot in {}: {e}", dir.display()));
        std::fs::create_dir_all(dir).map_err(io)?;
        let stem = format!("grains_{:06}", self.snapshots);
        if matches!(self.format, SnapshotFormat::Csv | SnapshotFormat::Both) {
            write_csv(world, &dir.join(format!("{stem}.csv"))).map_err(io)?;
        }
        if matches!(self.format, SnapshotFormat::Vtk | SnapshotFormat::Both) {
            write_vtk(world, &dir.join(format!("{stem}.vtk"))).map_err(io)?;
        }
        self.snapshots += 1;
        Ok(())
    }

    fn progress(&mut self, t_s: f64, duration_s: f64) {
        self.obs.progress(t_s, duration_s);
    }
}

/// Runs a DEM scene: samples go to `obs` (columns of the shared contract plus
/// [`DEM_EXTRA_COLUMNS`]), the summary follows `summary.json`'s keys; the DEM's own figures
/// (`energy_collision_j_per_cycle`, `energy_friction_j_per_cycle`, `steps`, `wall_time_s`,
/// `particle_steps_per_s`, `dt_s`, `contact_time_s`, `volume_fraction`, …) are in `extra`.
/// Without `[primary]` the box moves kinematically with the base. With `run.replica` the
/// two-replica test ([`super::replica`]) runs alongside and its report is in `replica`.
///
/// # Errors
/// [`SimError::Unavailable`] if the damper is not `dem`; scene and stability errors of
/// [`run_dem`]; output errors of the observer.
pub fn simulate(
    scene: &Scene,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<RunSummary, SimError> {
    let (params, drive, cfg) = resolve(scene, opts)?;
    obs.start(&DEM_EXTRA_COLUMNS)?;
    let mut fwd = Forward {
        obs,
        snapshot_dir: params.snapshot_interval.map(|_| {
            PathBuf::from(
                params
                    .snapshot_dir
                    .clone()
                    .unwrap_or_else(|| "snapshots".into()),
            )
        }),
        format: params.snapshot_format,
        snapshots: 0,
    };
    // `run.replica`: replica B perturbed at the start of the analysis window
    let (s, replica) = match scene.run.replica {
        Some(delta_m) => {
            let opts = ReplicaOptions::at_analysis_start(&cfg, delta_m);
            let (s, r) = run_replica(params, drive, &cfg, &opts, &mut fwd)?;
            (s, Some(r))
        }
        None => (run_dem(params, drive, &cfg, &mut fwd)?, None),
    };
    fwd.obs.finish()?;
    let cycles = (scene.duration_s() - s.steady_start_s) * scene.excitation.frequency;
    let l = s.ledger;
    let mut extra = BTreeMap::new();
    let opt = |v: Option<f64>| v.unwrap_or(f64::NAN);
    for (k, v) in [
        (
            "energy_collision_j_per_cycle",
            opt(s.energy_collision_j_per_cycle),
        ),
        (
            "energy_friction_j_per_cycle",
            opt(s.energy_friction_j_per_cycle),
        ),
        (
            "bed_floor_impacts_per_cycle",
            s.bed_impacts.floor as f64 / s.cycles_steady,
        ),
        (
            "bed_ceiling_impacts_per_cycle",
            s.bed_impacts.ceiling as f64 / s.cycles_steady,
        ),
        ("steps", s.steps as f64),
        ("wall_time_s", s.wall_time_s),
        ("particle_steps_per_s", s.particle_steps_per_s),
        ("particle_steps_per_cpu_s", opt(s.particle_steps_per_cpu_s)),
        ("dt_s", s.dt_s),
        ("contact_time_s", s.contact_time_s),
        ("settle_time_s", s.settle_time_s),
        ("settle_steps", s.settle_steps as f64),
        ("neighbor_builds", s.neighbor_builds as f64),
        ("grains", s.grains as f64),
        ("grain_mass_kg", s.grain_mass_kg),
        ("bed_height_m", s.bed_height_m),
        ("volume_fraction", s.volume_fraction),
    ] {
        extra.insert(k.to_string(), v);
    }
    Ok(RunSummary {
        model: "dem".into(),
        frequency_hz: scene.excitation.frequency,
        duration_s: scene.duration_s(),
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
        extra,
        strobe: s
            .strobe
            .iter()
            .map(|r| StrobePoint {
                cycle: r.cycle,
                time_s: r.time_s,
                grain_z_m: r.grain_z_m,
                box_z_m: r.box_z_m,
                grain_v_m_s: r.grain_v_m_s,
                box_v_m_s: r.box_v_m_s,
            })
            .collect(),
        analysis: None,
        analysis_error: None,
        replica,
    })
}

/// The inputs of [`run_dem`] (and of the two-replica test,
/// [`super::replica::run_replica`]) that a DEM scene and the run options resolve to.
///
/// # Errors
/// [`SimError::Unavailable`] if the damper is not `dem`.
pub fn resolve<'a>(
    scene: &'a Scene,
    opts: &RunOptions,
) -> Result<(&'a DemParams, BoxDrive, DemRunConfig), SimError> {
    let Damper::Dem(params) = &scene.damper else {
        return Err(SimError::Unavailable(
            "the DEM model runs only damper.kind = \"dem\"".into(),
        ));
    };
    let drive = BoxDrive {
        primary: scene.primary.as_ref().map(|p| PrimarySystem {
            mass_kg: p.mass,
            stiffness_n_m: p.stiffness,
            damping_n_s_m: p.damping_n_s_m(),
        }),
        amplitude_m: scene.excitation.amplitude,
        frequency_hz: scene.excitation.frequency,
    };
    let cfg = DemRunConfig {
        duration_s: scene.duration_s(),
        sample_interval_s: opts.sample_interval_s.unwrap_or(scene.run.sample_interval),
        steady_fraction: scene.run.steady_fraction,
        analysis_fraction: scene.run.analysis_fraction,
        dt: match scene.run.dt {
            Some(DtSpec::Seconds(s)) => DtChoice::Seconds(s),
            _ => DtChoice::Auto,
        },
        dt_fraction: scene.run.dt_fraction,
        samples: opts.sample_interval_s.is_some(),
        sample_from_s: opts.sample_from_s,
        gravity_m_s2: scene.gravity,
    };
    Ok((params, drive, cfg))
}
