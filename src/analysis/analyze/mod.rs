//! The whole analysis chain with automatic choices and a regime verdict (SPEC §4):
//! spectrum and lines → recurrence → mutual information (lag) → false nearest neighbours
//! (dimension) → Kantz (exponent, automatic scaling region) → stroboscopic section (with a
//! forcing frequency) → 0–1 test → [`crate::analysis::regime::classify`]. The verdict's
//! evidence is Kantz's; for an autonomous series judged chaotic whose mean crossings return at
//! nearly constant times (a phase-coherent flow such as Rössler's), the exponent's value is
//! that of the first-return map ([`crate::analysis::return_map_lyapunov`]), with Kantz's
//! value kept in the evidence and the notes.
//!
//! [`analyze_series`] is the library entry point used by `pdamp analyze`, the simulators'
//! `summary.json` and the sweeps. It never panics on user data: estimators that cannot run on a
//! given series leave their evidence empty and add a note; only non-finite data, a series
//! shorter than [`MIN_SAMPLES`] or inconsistent options are errors.
//!
//! One file per part: the options and the report (re-exported here), the
//! evidence of each estimator, the chain on a series and the forced-run path.

mod chain;
mod evidence;
mod forced;
mod report;

pub use chain::analyze_series;
pub use forced::{analyze_forced, ForcedRun};
pub use report::{
    AnalysisReport, AnalyzeOptions, KantzFitReport, LineReport, MAX_ABS_VALUE, MIN_SAMPLES,
};
