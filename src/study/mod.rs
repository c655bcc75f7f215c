//! Studies: pipelines of sweeps, fits and figures built from the library's pieces.
//!
//! [`reproduce::reproduce`] regenerates the figure set of SPEC §7 (`pdamp reproduce`).

pub mod chapter4;
pub mod check;
pub mod dem_figures;
pub mod pipeline;
pub mod readme;
pub mod reproduce;
pub mod settings;

pub use check::{check_effective, EffectiveRow, QualitativeCheck};
pub use reproduce::{reproduce, ReproduceOptions, ReproduceReport};
pub use settings::{Mode, Settings};
