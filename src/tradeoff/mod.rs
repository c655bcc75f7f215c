//! Speed against accuracy (SPEC §2–§4): measure what each cheaper setting of a DEM scene
//! costs and how wrong it is against the most accurate affordable reference, find the Pareto
//! front, and let `[damper] kind = "auto"` pick the cheapest model that meets a scene's
//! `[outputs]`.
//!
//! Pipeline: [`ladder`] (the settings) → [`measure`] (one run, timed inside) → [`metrics`]
//! (errors of Z, dissipation, M_ef/C_ef, regime, Lyapunov exponent) → [`study`] (all runs in
//! parallel, each single-threaded) → [`pareto`] → [`table`] (CSV) → [`auto`] (model choice).

pub mod auto;
pub mod ladder;
pub mod measure;
pub mod metrics;
pub mod pareto;
pub mod study;
pub mod table;

pub use auto::{choose, AutoChoice};
pub use ladder::{settings_ladder, Axis, Case, Change, LadderOptions, Setting};
pub use study::{run_study, Study, StudyOptions};
