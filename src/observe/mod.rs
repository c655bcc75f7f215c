//! Observers: the simulators emit samples to an [`Observer`]; CSV recorders, snapshot writers and
//! in-memory collectors are observers attached by the caller (no prints, no globals); the
//! progress bar of the `pdamp` binary is one too (it lives in the CLI, not in the library).

pub mod collector;
pub mod csv_recorder;
pub mod snapshot;
pub mod vtk_xml;

pub use collector::{Recorded, SteadyCollector, StrobeCollector};
pub use csv_recorder::CsvRecorder;
pub use snapshot::SnapshotWriter;

use crate::error::SimError;
use crate::model::StrobePoint;

/// The fixed columns of `series.csv`, in order; the model's columns
/// ([`SampleKind::columns`]) follow, then `grain_force_n` (see [`Sample`]).
pub const FIXED_COLUMNS: [&str; 7] = [
    "time_s",
    "base_u_m",
    "box_z_m",
    "box_v_m_s",
    "floor_z_m",
    "ceiling_z_m",
    "grain_z_m",
];

/// Columns of the impact model's part of a sample ([`ModelSample::Impact`]).
pub const IMPACT_COLUMNS: [&str; 2] = ["grain_v_m_s", "contact"];

/// Columns of the DEM's part of a sample ([`DemSampleState`]).
pub const DEM_COLUMNS: [&str; 11] = [
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

/// Which model produced a run's samples: fixes the model part of every [`Sample`] and the
/// columns of `series.csv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleKind {
    /// The primary alone (no particle): no model columns.
    Primary,
    /// The event-driven impact model: [`IMPACT_COLUMNS`].
    Impact,
    /// The DEM: [`DEM_COLUMNS`].
    Dem,
}

impl SampleKind {
    /// The model's columns of `series.csv`, after `grain_z_m`.
    pub fn columns(self) -> &'static [&'static str] {
        match self {
            SampleKind::Primary => &[],
            SampleKind::Impact => &IMPACT_COLUMNS,
            SampleKind::Dem => &DEM_COLUMNS,
        }
    }
}

/// The DEM's part of a sample: the grains' vertical extent and the energy ledger (J,
/// cumulative since the drive started; SPEC (2.6.1)–(2.6.6)).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DemSampleState {
    /// Lowest grain centre (m).
    pub grain_zmin_m: f64,
    /// Highest grain centre (m).
    pub grain_zmax_m: f64,
    /// Energy dissipated by normal damping (J).
    pub e_collision_j: f64,
    /// Energy dissipated by friction (J).
    pub e_friction_j: f64,
    /// Energy dissipated in the primary's damper C (J).
    pub e_viscous_j: f64,
    /// Work done by the base (J).
    pub e_base_work_j: f64,
    /// Grains' kinetic energy, translational + rotational (J).
    pub e_kinetic_j: f64,
    /// Grains' gravitational potential energy relative to the start (J).
    pub e_potential_j: f64,
    /// Elastic energy in contacts (J).
    pub e_elastic_j: f64,
    /// Energy of the primary: ½ M z'² + ½ K (z − u)² (J).
    pub e_primary_j: f64,
    /// Ledger residual E − E₀ − W_base + D (J); ≈ 0.
    pub e_balance_residual_j: f64,
}

impl DemSampleState {
    /// The values in the order of [`DEM_COLUMNS`].
    pub fn values(&self) -> [f64; 11] {
        [
            self.grain_zmin_m,
            self.grain_zmax_m,
            self.e_collision_j,
            self.e_friction_j,
            self.e_viscous_j,
            self.e_base_work_j,
            self.e_kinetic_j,
            self.e_potential_j,
            self.e_elastic_j,
            self.e_primary_j,
            self.e_balance_residual_j,
        ]
    }
}

/// The model-specific part of a sample, typed (no named extra columns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModelSample {
    /// The primary alone: nothing more.
    Primary,
    /// The impact model's particle.
    Impact {
        /// Exact particle velocity w (m/s, lab frame) from the closed form.
        grain_v_m_s: f64,
        /// Contact code: 0 flight, 1 on the floor, 2 at the ceiling, 3 clamped.
        contact: f64,
    },
    /// The DEM's grains and energy ledger.
    Dem(DemSampleState),
}

impl ModelSample {
    /// Which kind of model part this is.
    pub fn kind(&self) -> SampleKind {
        match self {
            ModelSample::Primary => SampleKind::Primary,
            ModelSample::Impact { .. } => SampleKind::Impact,
            ModelSample::Dem(_) => SampleKind::Dem,
        }
    }

    /// Calls `f` with the values in the order of [`SampleKind::columns`].
    pub fn for_each_value(&self, mut f: impl FnMut(f64)) {
        match self {
            ModelSample::Primary => {}
            ModelSample::Impact {
                grain_v_m_s,
                contact,
            } => {
                f(*grain_v_m_s);
                f(*contact);
            }
            ModelSample::Dem(d) => d.values().into_iter().for_each(f),
        }
    }
}

/// One output sample of a run (lab frame, z up, origin at the static equilibrium of M alone).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
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
    /// The model's own part.
    pub model: ModelSample,
    /// Vertical force of the grains on the box (N); impulses at impacts are not included.
    pub grain_force_n: f64,
}

impl Sample {
    /// The values of the fixed columns, in the order of [`FIXED_COLUMNS`].
    pub fn fixed_values(&self) -> [f64; 7] {
        [
            self.time_s,
            self.base_u_m,
            self.box_z_m,
            self.box_v_m_s,
            self.floor_z_m,
            self.ceiling_z_m,
            self.grain_z_m,
        ]
    }
}

/// The grains' state at one instant, for particle snapshots (borrowed from the DEM world).
#[derive(Debug, Clone, Copy)]
pub struct GrainState<'a> {
    /// Time since the drive started (s).
    pub time_s: f64,
    /// Centres (m).
    pub pos: &'a [[f64; 3]],
    /// Velocities (m/s).
    pub vel: &'a [[f64; 3]],
    /// Angular velocities (rad/s).
    pub omega: &'a [[f64; 3]],
    /// Radii (m).
    pub radius: &'a [f64],
    /// Orientations, when tracked.
    pub orientation: Option<&'a [nalgebra::UnitQuaternion<f64>]>,
    /// Total force on each grain at the last force evaluation (N).
    pub force: &'a [[f64; 3]],
    /// Inner size of the container [Lx, Ly, Lz] (m).
    pub box_size: [f64; 3],
    /// The container's corner (its floor, x = y = 0) (m): walls at origin + {0, L} on each
    /// axis.
    pub box_origin: [f64; 3],
    /// The cavity's shape inside the box (a box, or a cylinder inscribed in it).
    pub container: crate::model::Container,
}

/// Receives what a run emits: its samples, stroboscopic points, particle snapshots and
/// progress (one contract for every simulator; CSV recorders, collectors, snapshot writers
/// and progress bars are observers attached by the caller).
pub trait Observer {
    /// Called once before the first sample with the kind of the model part of the samples.
    ///
    /// # Errors
    /// [`SimError::Output`] if the observer cannot start (e.g. cannot create its file).
    fn start(&mut self, _kind: SampleKind) -> Result<(), SimError> {
        Ok(())
    }
    /// Called for every sample, in time order.
    ///
    /// # Errors
    /// [`SimError::Output`] if the sample cannot be recorded.
    fn sample(&mut self, s: &Sample) -> Result<(), SimError>;
    /// One stroboscopic point: the exact state at t = n/f over the analysis window (default:
    /// ignored).
    ///
    /// # Errors
    /// [`SimError::Output`] if the point cannot be recorded.
    fn strobe(&mut self, _p: &StrobePoint) -> Result<(), SimError> {
        Ok(())
    }
    /// A particle snapshot at `damper.snapshot_interval` (DEM; default: ignored).
    ///
    /// # Errors
    /// [`SimError::Output`] if the snapshot cannot be written.
    fn snapshot(&mut self, _g: &GrainState<'_>) -> Result<(), SimError> {
        Ok(())
    }
    /// Progress report: simulated time `t_s` out of `duration_s`. Called about once per
    /// forcing period, samples or none, so that an observer can stop a run there.
    ///
    /// # Errors
    /// Any error ends the run with it (e.g. an interrupt the caller asked for: the Python
    /// binding returns one after a Ctrl-C).
    fn progress(&mut self, _t_s: f64, _duration_s: f64) -> Result<(), SimError> {
        Ok(())
    }
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
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }
}

/// Forwards everything to several observers, in order.
pub struct Tee<'a> {
    /// The observers.
    pub observers: Vec<&'a mut dyn Observer>,
}

impl Observer for Tee<'_> {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.start(kind))
    }
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.sample(s))
    }
    fn strobe(&mut self, p: &StrobePoint) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.strobe(p))
    }
    fn snapshot(&mut self, g: &GrainState<'_>) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.snapshot(g))
    }
    fn progress(&mut self, t: f64, d: f64) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.progress(t, d))
    }
    fn finish(&mut self) -> Result<(), SimError> {
        self.observers.iter_mut().try_for_each(|o| o.finish())
    }
}

/// Format a number for CSV output: shortest round-trip representation, in scientific notation
/// for very small or large magnitudes (`3.1e-13` rather than `0.00000000000031`).
pub fn fmt_num(x: f64) -> String {
    let mut s = String::new();
    crate::files::csv_out::push_num(&mut s, x);
    s
}
