//! Speed against accuracy (SPEC §2–§4): how wrong and how cheap every shortcut of a DEM scene
//! is against a converged reference, measured on stored sweep points, and the Pareto fronts.
//! The shortcuts themselves and `[damper] kind = "auto"`, which reads the table written here,
//! live beneath the resolve step in [`crate::choice`].
//!
//! Pipeline: [`crate::choice::ladder`](mod@crate::choice::ladder) (the settings, each one change to the reference scene) → [`plan`]
//! (frequencies, where points live) → [`compute`] (the missing points, as resumable sweeps)
//! → [`observed`] (each rung's stored point at each frequency, or why there is none) →
//! [`study`](mod@study) (errors, resonance, M_ef/C_ef, verdicts, cost; [`metrics`], [`pareto`]) →
//! [`table`] (`tradeoff.csv`, `tradeoff_settings.csv`; read back by
//! [`crate::choice::measured`] for `auto`) →
//! [`report`] (`TRADEOFF.md`: what to use for what).

pub mod compute;
pub mod metrics;
pub mod observed;
pub mod pareto;
pub mod plan;
pub mod report;
pub mod study;
pub mod table;

pub use plan::StudyPlan;
pub use study::{study, Study};
