//! The common types of the library in one import, for programs that use `pdamp` as a library:
//!
//! ```
//! use pdamp::prelude::*;
//! let scene = Scene::from_toml(include_str!("../data/scenes/thesis_b_impact.toml")).unwrap();
//! let resolved: Resolved = scene.resolve().unwrap();
//! assert!(matches!(resolved.setup, Setup::Impact(_)));
//! ```
//!
//! - scenes and the resolve step: [`Scene`], [`SceneSource`], [`parse_assignment`],
//!   [`Resolved`], [`Setup`], [`ImpactSetup`], [`DemSetup`];
//! - running: [`run_scene`], [`run_with_analysis`], [`run_resolved`], [`simulate`] with
//!   [`RunOptions`] ([`full_series`], [`steady_series`]) → [`RunSummary`]; sweeps:
//!   [`run_sweep`], [`SweepSpec`], [`Vary`];
//! - observers: [`Observer`], [`Sample`], [`ModelSample`], [`Tee`], [`NullObserver`],
//!   [`CsvRecorder`], [`SteadyCollector`], [`StrobeCollector`], [`SnapshotWriter`];
//! - analysis: [`analyze_series`], [`AnalyzeOptions`], [`AnalysisReport`], [`Regime`], the
//!   delay and the FRF fit ([`mutual_information`], [`first_zero_lag`], [`fit_frf`],
//!   [`fit_frf_groups`]);
//! - figures: [`render`], [`Figure`], [`FigureOptions`]; files: [`read_series`],
//!   [`SeriesReadOptions`], [`Column`], [`atomic_write`], [`RunDir`];
//! - errors: [`SceneError`], [`SimError`], [`AnalysisError`], [`DataError`], [`PlotError`].

pub use crate::analysis::analyze::{analyze_series, AnalysisReport, AnalyzeOptions};
pub use crate::analysis::autocorrelation::first_zero_lag;
pub use crate::analysis::frf_fit::{fit_frf, fit_frf_groups, FrfFit, FrfFitOptions};
pub use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
pub use crate::analysis::regime::Regime;
pub use crate::error::{AnalysisError, DataError, PlotError, SceneError, SimError};
pub use crate::impact::ImpactSetup;
pub use crate::io::{atomic_write, read_series, Column, RunDir, SeriesReadOptions};
pub use crate::model::{PrimarySystem, RunOptions, RunSummary, StrobePoint};
pub use crate::observe::{
    CsvRecorder, ModelSample, NullObserver, Observer, Sample, SnapshotWriter, SteadyCollector,
    StrobeCollector, Tee,
};
pub use crate::plot::{render, Figure, FigureOptions};
pub use crate::scene::{parse_assignment, Scene, SceneSource};
pub use crate::setup::{full_series, simulate, steady_series, DemSetup, Resolved, Setup};
pub use crate::sweep::run::{run_resolved, run_scene, run_with_analysis};
pub use crate::sweep::{run_sweep, SweepSpec, Vary};
