//! The source's chapter-4 study (Sánchez 2012 ch. 4): the regimes of scene B's DEM bed along
//! the forcing frequency at the optimal container height Lz = 0.1225 m.
//!
//! - `ch4_regime_frf` (Fig. 4.1): the DEM frequency response coloured by the regime of the
//!   grains' centre of mass, with the data Lyapunov exponent and its error bar;
//! - `ch4_bifurcation`: z_cm strobed once per period (the exact section) versus f;
//! - `ch4_impacts`: collective bed–floor and bed–ceiling impacts per cycle versus f
//!   ([`crate::dem::bed_impacts`]), so that "two impacts per period" can be read off;
//! - `ch4_checks` (with `--ch4-checks`): every frequency from three starts, continued to twice
//!   the length, and with the other shipped softened scene, verdict by verdict
//!   (`chapter4/checks.rs`);
//! - `ch4_run_length`: the check frequencies again with every run continued to twice its
//!   length (the same trajectory, see `ch4_set`), verdict by verdict and amplitude by
//!   amplitude (the quick mode's run length is only trusted where doubling it changes
//!   nothing);
//! - `ch4_time_step` (with `--ch4-checks`): every frequency again at t_s/50, the step the
//!   quick study's t_s/20 stands in for, verdict by verdict and amplitude by amplitude beside
//!   the spread of the three starts;
//! - `ch4_panel_f<f>` (Figs. 4.2–4.6): bed band between floor and ceiling, the section and the
//!   spectrum at each of the source's frequencies;
//! - `ch4_reconstruction` (Fig. 4.7): delay reconstructions of z_cm at the same frequencies.
//!
//! This file holds the study's steps (`all`); the parts are in `chapter4/`: the runs'
//! settings (`runs.rs`), the sweep points (`points.rs`), what every figure shares
//! (`record.rs`), the figures along f (`frequency.rs`), the run-length and time-step checks
//! (`compare.rs`), the panel runs and their figures (`panels.rs`), the checks
//! (`checks.rs`) and the ensemble of starts (`ensemble.rs`).

use rayon::prelude::*;

mod checks;
mod compare;
mod ensemble;
mod frequency;
mod panels;
mod points;
mod record;
mod runs;

use checks::{checks_figure, Checks};
use compare::{run_length, time_step};
use ensemble::{ensemble_check, ensemble_figure};
use frequency::{bifurcation, impacts, regime_frf};
use panels::{panel, panel_of_point, panel_points, panel_run, reconstruction};
use points::{opt_cell, point, points, Point};
use record::Info;
use runs::DEFAULT_SEED;
pub use runs::DEM_CH4;
use runs::{
    ch4_set, frequency_list, length_dir, length_text, other_scene_set, slower_step, sweep_dir,
};

use super::pipeline::{Ctx, FigureRecord, SweepResult, DEM_B_SOFT};
use super::settings::{Chapter4Settings, DemSettings, Settings};
use crate::error::StudyError;
use crate::scene::keys::{DAMPER_SEED, EXCITATION_FREQUENCY};
use crate::sweep::KeptRun;

/// Names of the chapter-4 figures (for `--only`).
pub const NAMES: [&str; 10] = [
    "ch4",
    "ch4_regime_frf",
    "ch4_ensemble",
    "ch4_checks",
    "ch4_bifurcation",
    "ch4_impacts",
    "ch4_run_length",
    "ch4_time_step",
    "ch4_panels",
    "ch4_reconstruction",
];

/// What the chapter-4 study produced.
#[derive(Debug, Clone)]
pub struct Chapter4Output {
    /// The figures.
    pub figures: Vec<FigureRecord>,
    /// The regime sweep at the mode's run length (also the DEM curve of `frf.png`: its runs
    /// are long enough that doubling them moves the amplitudes by a few per cent, see
    /// `ch4_run_length`).
    pub sweep: SweepResult,
}

/// Runs the chapter-4 sweeps and panels and draws its figures (those `want` selects).
///
/// # Errors
/// [`StudyError`] naming the sweep, run or figure that failed.
pub fn all(
    ctx: &Ctx,
    s: &Settings,
    d: &DemSettings,
    c: &Chapter4Settings,
    want: &dyn Fn(&str) -> bool,
) -> Result<Chapter4Output, StudyError> {
    let mut figures = Vec::new();
    let reductions = s.reductions(&["dem_material", "dem_ch4"]);
    let sweep = |factor: f64, freqs: &[f64]| {
        ctx.sweep(
            &sweep_dir(c, factor),
            DEM_CH4,
            &ch4_set(d, c, factor),
            &[(EXCITATION_FREQUENCY, frequency_list(freqs))],
            true,
        )
    };
    // the panels draw their sweep points' runs: kept from the sweep when it runs them now
    let panels = want("ch4_panels") || want("ch4_reconstruction");
    let keep: Vec<usize> = match panels {
        true => panel_points(&c.frequencies_hz, &c.panel_freqs_hz),
        false => Vec::new(),
    };
    let (base, kept) = ctx.sweep_keeping(
        &sweep_dir(c, 1.0),
        DEM_CH4,
        &ch4_set(d, c, 1.0),
        &[(EXCITATION_FREQUENCY, frequency_list(&c.frequencies_hz))],
        true,
        &keep,
    )?;
    let pts = points("ch4_regime_frf", &base.points)?;
    let info = Info {
        ctx,
        c,
        sweep: &base,
        reductions: &reductions,
    };
    // the ensemble check: the check frequencies from further initial packings
    let checks = want("ch4_checks");
    let ensemble = if !c.ensemble_seeds.is_empty()
        && !c.check_freqs_hz.is_empty()
        && (want("ch4_ensemble") || want("ch4_regime_frf") || checks)
    {
        Some(ensemble_check(&pts, &seeds_sweep(ctx, d, c)?)?)
    } else {
        None
    };
    if want("ch4_regime_frf") {
        let words = ensemble.as_ref().map(|e| e.words.as_slice());
        figures.push(regime_frf(&info, &pts, words)?);
    }
    if let (true, Some(e)) = (want("ch4_ensemble"), &ensemble) {
        figures.push(ensemble_figure(&info, e)?);
    }
    if want("ch4_bifurcation") {
        figures.push(bifurcation(&info)?);
    }
    if want("ch4_impacts") {
        figures.push(impacts(&info, &pts)?);
    }
    let long = if !c.doubling_freqs_hz.is_empty() && (want("ch4_run_length") || checks) {
        let long = sweep(2.0, &c.doubling_freqs_hz)?;
        let long_pts = points("ch4_run_length", &long.points)?;
        if want("ch4_run_length") {
            figures.push(run_length(&info, &pts, &long, &long_pts)?);
        }
        Some((long, long_pts))
    } else {
        None
    };
    if let (true, Some(e), Some((long, long_pts))) = (checks, &ensemble, &long) {
        if !c.recipe_freqs_hz.is_empty() {
            let other = ctx.sweep(
                &format!("dem_soft_{}", length_dir(c, 1.0)),
                DEM_B_SOFT,
                &other_scene_set(d, c),
                &[(EXCITATION_FREQUENCY, frequency_list(&c.recipe_freqs_hz))],
                true,
            )?;
            let other_pts = points("ch4_checks", &other.points)?;
            let ch = Checks {
                base: &pts,
                starts: &e.runs,
                ensemble_words: &e.words,
                doubled: long_pts,
                other_scene: &other_pts,
                lengths: (length_text(c, 1.0), length_text(c, 2.0)),
                sweeps: [long, &other],
            };
            figures.push(checks_figure(&info, &ch)?);
        }
    }
    if let (true, Some(sc)) = (want("ch4_time_step"), slower_step(c)) {
        let slow = ctx.sweep(
            &sweep_dir(&sc, 1.0),
            DEM_CH4,
            &ch4_set(d, &sc, 1.0),
            &[(EXCITATION_FREQUENCY, frequency_list(&c.frequencies_hz))],
            true,
        )?;
        let slow_pts = points("ch4_time_step", &slow.points)?;
        // the slower step's own starts, where the study ran its ensemble
        let slow_ensemble = match &ensemble {
            Some(_) => Some(ensemble_check(&slow_pts, &seeds_sweep(ctx, d, &sc)?)?),
            None => None,
        };
        figures.push(time_step(
            &info,
            &pts,
            (&slow, &slow_pts, sc.dt_fraction),
            ensemble.as_ref().map(|e| (e, slow_ensemble.as_ref())),
        )?);
    }
    if panels {
        // the sweep's own runs where it kept them, else one DEM run per panel, in parallel
        // (each run is single-threaded and deterministic: the same run as the sweep point's)
        let mut kept: Vec<Option<KeptRun>> = kept.into_iter().map(Some).collect();
        let mut take = |f: f64| {
            let i = c.frequencies_hz.iter().position(|&x| x == f)?;
            let k = kept
                .iter_mut()
                .find(|k| k.as_ref().is_some_and(|k| k.point == i))?;
            k.take()
        };
        let from_sweep: Vec<(f64, Option<KeptRun>)> =
            c.panel_freqs_hz.iter().map(|&f| (f, take(f))).collect();
        let runs = from_sweep
            .into_par_iter()
            .map(|(f, k)| match k {
                Some(k) => panel_of_point(d, c, f, k),
                None => panel_run(d, c, f),
            })
            .collect::<Result<Vec<_>, _>>()?;
        if want("ch4_panels") {
            for r in &runs {
                figures.push(panel(&info, r)?);
            }
        }
        if want("ch4_reconstruction") {
            figures.push(reconstruction(&info, &runs)?);
        }
    }
    Ok(Chapter4Output {
        figures,
        sweep: base,
    })
}

/// The ensemble check's further starts (`ensemble_seeds`) at the check frequencies, with `c`'s
/// time step and run length.
fn seeds_sweep(
    ctx: &Ctx,
    d: &DemSettings,
    c: &Chapter4Settings,
) -> Result<SweepResult, StudyError> {
    let seeds = c
        .ensemble_seeds
        .iter()
        .map(|s| s.to_string())
        .collect::<Vec<_>>()
        .join(",");
    ctx.sweep(
        &format!("{}_seeds", sweep_dir(c, 1.0)),
        DEM_CH4,
        &ch4_set(d, c, 1.0),
        &[
            (DAMPER_SEED, seeds),
            (EXCITATION_FREQUENCY, frequency_list(&c.check_freqs_hz)),
        ],
        true,
    )
}
