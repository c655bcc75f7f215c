//! The chapter-4 runs' settings: the bundled scene [`DEM_CH4`] and what it writes, the
//! `--set` of a run at the mode's (or a multiple of its) length, the other shipped softened
//! scene's `--set`, and the run length in words and in directory names.

use crate::model::summary::DEFAULT_ANALYSIS_MAX_SAMPLES;
use crate::scene::keys::{RUN_ANALYSIS_MAX_SAMPLES, RUN_DT_FRACTION, RUN_DURATION, RUN_PERIODS};
use crate::study::dem_figures::softened_steel_set;
use crate::study::pipeline::BundledScene;
use crate::study::settings::{Chapter4Settings, DemSettings, CH4_SLOWER_DT_FRACTION};

/// Scene B at Lz = 0.1225 m with softened grains and runs counted in periods
/// (`data/scenes/thesis_b_ch4.toml`).
pub const DEM_CH4: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_ch4.toml",
    text: include_str!("../../../data/scenes/thesis_b_ch4.toml"),
};

/// The packing seed of [`DEM_CH4`] (the scene's default `damper.seed`).
pub(super) const DEFAULT_SEED: u64 = 1;

/// Softening, time-step fraction and run length written in [`DEM_CH4`] (its step, t_s/50, is
/// the one the quick study's t_s/20 is checked against).
pub(super) const SCENE_SOFTEN: f64 = 1000.0;
pub(super) const SCENE_DT_FRACTION: f64 = CH4_SLOWER_DT_FRACTION;
pub(super) const SCENE_PERIODS: f64 = 100.0;

/// `--set` of a chapter-4 run: material and time step when they differ from the scene file,
/// and the run length (`factor` × the mode's).
///
/// A longer run (`factor` ≠ 1) also takes `factor` × the analysed series' sample count, so
/// that its analysis sample clock — analysis window / `run.analysis_max_samples` — is the
/// mode's run's. The automatic time step is snapped to that clock, so the longer run takes the
/// same time step and continues the mode's run's trajectory bit for bit (a doubled run on its
/// own clock takes a time step a fraction of a per cent off: another trajectory, which in a
/// multistable bed can end on another attractor — what the ensemble of starts checks, not the
/// run length).
pub(super) fn ch4_set(
    d: &DemSettings,
    c: &Chapter4Settings,
    factor: f64,
) -> Vec<(&'static str, String)> {
    let mut set = Vec::new();
    if d.soften != SCENE_SOFTEN {
        set.extend(softened_steel_set(d.soften));
    }
    if c.dt_fraction != SCENE_DT_FRACTION {
        set.push((RUN_DT_FRACTION, c.dt_fraction.to_string()));
    }
    match c.duration_s {
        Some(s) => set.push((RUN_DURATION, (factor * s).to_string())),
        None if factor * c.periods != SCENE_PERIODS => {
            set.push((RUN_PERIODS, (factor * c.periods).to_string()));
        }
        None => {}
    }
    if factor != 1.0 {
        let samples = factor * DEFAULT_ANALYSIS_MAX_SAMPLES as f64;
        set.push((RUN_ANALYSIS_MAX_SAMPLES, samples.to_string()));
    }
    set
}

/// The run length in words ("100 periods" or "196.83 s").
pub(super) fn length_text(c: &Chapter4Settings, factor: f64) -> String {
    match c.duration_s {
        Some(s) => format!("{} s", factor * s),
        None => format!("{} periods", factor * c.periods),
    }
}

/// The run length in a directory name ("p200" or "d196.83"), and the time step when it is
/// not the scene file's ("p200_dt20" at t_s/20).
pub(super) fn length_dir(c: &Chapter4Settings, factor: f64) -> String {
    let length = match c.duration_s {
        Some(s) => format!("d{}", factor * s),
        None => format!("p{}", factor * c.periods),
    };
    match c.dt_fraction == SCENE_DT_FRACTION {
        true => length,
        false => format!("{length}_dt{}", 1.0 / c.dt_fraction),
    }
}

/// The settings of the time-step check's runs: the study's at `slower_dt_fraction`, `None`
/// without the check.
pub(super) fn slower_step(c: &Chapter4Settings) -> Option<Chapter4Settings> {
    c.slower_dt_fraction.map(|dt| Chapter4Settings {
        dt_fraction: dt,
        slower_dt_fraction: None,
        ..c.clone()
    })
}

pub(super) fn sweep_dir(c: &Chapter4Settings, factor: f64) -> String {
    format!("dem_ch4_{}", length_dir(c, factor))
}

/// `--set` of the other shipped softened scene (`thesis_b_soft.toml`) at the mode's run
/// length: the chapter-4 scene's material and time step settings, and the run length always
/// written (that scene counts its runs in seconds).
pub(super) fn other_scene_set(
    d: &DemSettings,
    c: &Chapter4Settings,
) -> Vec<(&'static str, String)> {
    let mut set = ch4_set(d, c, 1.0);
    if c.duration_s.is_none() && !set.iter().any(|(k, _)| *k == RUN_PERIODS) {
        set.push((RUN_PERIODS, c.periods.to_string()));
    }
    set
}

pub(super) fn frequency_list(freqs: &[f64]) -> String {
    freqs
        .iter()
        .map(|f| f.to_string())
        .collect::<Vec<_>>()
        .join(",")
}
