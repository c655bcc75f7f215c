//! Equations of the primary system, no time stepping: the linear single-degree-of-freedom
//! system under harmonic base excitation (2.1.2), its closed-form solution between events and
//! its analytic steady-state amplitude (2.1.21); and what every run reports ([`summary`]).

pub mod container;
pub mod dem_extras;
pub mod primary;
pub mod rotation;
pub mod summary;

/// Revision of the simulators' physics: which trajectories this build computes. Every stored
/// sweep point carries the revision that made it (`points/<i>.json`, field `physics`; points
/// written before the field existed are revision 1), and a sweep refuses to resume over points
/// of another revision rather than mix two physics in one table. Raise it with any change that
/// moves a trajectory's bits — `tests/cached_points_reproduce.rs` recomputes committed points
/// and says when that happened.
pub const PHYSICS_REVISION: u32 = 1;

pub use container::{Container, Cylinder};
pub use dem_extras::DemExtras;
pub use primary::{base_motion, Anchor, BoxDrive, PrimarySystem, Sdof};
pub use rotation::FrameRotation;
pub use summary::{
    EnergyTotals, RunAnalysis, RunOptions, RunSummary, RunWindow, StrobePoint,
    DEFAULT_ANALYSIS_FRACTION, DEFAULT_SAMPLE_INTERVAL_S, DEFAULT_STEADY_FRACTION,
};
