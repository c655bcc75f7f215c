//! Speed against accuracy (SPEC §2–§4): how wrong and how cheap every shortcut of a DEM scene
//! is against a converged reference, measured on stored sweep points; the Pareto fronts; and
//! `[damper] kind = "auto"`, which picks the cheapest setting that meets a scene's `[outputs]`.
//!
//! Pipeline: [`ladder`](mod@ladder) (the settings, each one change to the reference scene) → [`plan`]
//! (frequencies, where points live) → [`compute`] (the missing points, as resumable sweeps)
//! → [`observed`] (each rung's stored point at each frequency, or why there is none) →
//! [`study`](mod@study) (errors, resonance, M_ef/C_ef, verdicts, cost; [`metrics`], [`pareto`]) →
//! [`table`] (`tradeoff.csv`, `tradeoff_settings.csv`) → [`auto`] (model choice) →
//! [`report`] (`TRADEOFF.md`: what to use for what).

pub mod auto;
pub mod compute;
pub mod ladder;
pub mod metrics;
pub mod observed;
pub mod pareto;
pub mod plan;
pub mod report;
pub mod study;
pub mod table;

pub use auto::{choose, AutoChoice};
pub use ladder::{ladder, Axis, Change, Rung};
pub use plan::StudyPlan;
pub use study::{study, Study};
