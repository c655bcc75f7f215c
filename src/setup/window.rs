//! The run windows and the sampling a scene's `run` keys set (s): what the engine's setups
//! and the runners take from the scene.

use crate::model::{RunOptions, RunWindow};
use crate::scene::Scene;

/// The run windows of a scene (s): duration, steady-state start, analysis start.
pub fn window(scene: &Scene) -> RunWindow {
    RunWindow {
        duration_s: scene.duration_s(),
        steady_start_s: scene.steady_start_s(),
        analysis_start_s: scene.analysis_start_s(),
    }
}

/// Samples every `run.sample_interval` from t = 0 (what `pdamp simulate` writes).
pub fn full_series(scene: &Scene) -> RunOptions {
    RunOptions::full_series(scene.run.sample_interval)
}

/// Samples of the analysis window only (`run.analysis_fraction`), decimated so that at most
/// `run.analysis_max_samples` are produced (input of the nonlinear analysis).
pub fn steady_series(scene: &Scene) -> RunOptions {
    RunOptions::steady_series(
        &window(scene),
        scene.run.sample_interval,
        scene.run.analysis_max_samples,
    )
}
