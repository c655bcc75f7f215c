//! Which model a scene needs: the ladder of shortcuts from a DEM reference (each one change:
//! time step, stiffness, contact law, rotations, friction, grain count, the one-particle model,
//! run length, analysis window), the measured speed–accuracy table read back, and
//! `[damper] kind = "auto"`, which picks the cheapest measured setting that meets a scene's
//! `[outputs]`.
//!
//! This sits beneath the resolve step ([`crate::setup`] calls [`choose`] for an `auto`
//! damper) and above the scene and the engines; the study that measures the table
//! ([`crate::tradeoff`]) builds its rungs from [`ladder`](mod@ladder) and writes the table
//! that [`measured`] reads.

pub mod auto;
pub mod ladder;
pub mod measured;

pub use auto::{choose, AutoChoice};
pub use ladder::{ladder, Axis, Change, Rung};
pub use measured::{read_settings, MeasuredSetting};
