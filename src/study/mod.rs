//! Studies: pipelines of sweeps, fits and figures built from the library's pieces.
//!
//! [`reproduce::reproduce`] regenerates the figure set of SPEC §7 (`pdamp reproduce`): the
//! orchestrator (`reproduce.rs`) calls one file per figure family (`impact_frf`, `impact_gap`,
//! `impact_series`, `impact_regimes`, `dem_figures`, `chapter4`, `saeki`, `els`), which share `pipeline`
//! (sweeps and runs) and `kit` (scene B's values, fits, shared drawings); `readme` writes
//! `OUT/README.md` from the [`ReproduceReport`], whose commands are
//! [`command::Command`]s built from the sweeps and runs that were made. Imports go one way: orchestrator → families →
//! kit → pipeline.

mod bean_bag;
pub mod chapter4;
pub mod check;
pub mod command;
pub mod dem_figures;
mod els;
mod impact_frf;
mod impact_gap;
mod impact_regimes;
mod impact_series;
pub mod kit;
pub mod options;
pub mod pipeline;
pub mod readme;
pub mod reproduce;
mod saeki;
pub mod settings;

pub use check::{check_effective, EffectiveRow, QualitativeCheck};
pub use options::{ReproduceOptions, ReproduceReport};
pub use reproduce::reproduce;
pub use settings::{Mode, Settings};
