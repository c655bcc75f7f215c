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
//! - `ch4_panel_f<f>` (Figs. 4.2–4.6): bed band between floor and ceiling, the section and the
//!   spectrum at each of the source's frequencies;
//! - `ch4_reconstruction` (Fig. 4.7): delay reconstructions of z_cm at the same frequencies.

use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use crate::analysis::regime::Regime;
use crate::analysis::spectrum::{power_spectrum, SpectrumOptions};
use crate::error::StudyError;
use crate::model::RunSummary;
use crate::plot::bed_motion::BedMotionFigure;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::frequency_panel::{FrequencyPanelFigure, ReconstructionGridFigure};
use crate::plot::lines::LinesFigure;
use crate::plot::poincare::PoincareFigure;
use crate::plot::reconstruction::ReconstructionFigure;
use crate::plot::regime_frf::{Exponents, RegimeFrfFigure};
use crate::plot::spectrum::SpectrumFigure;
use crate::plot::Series;
use rayon::prelude::*;

mod checks;
mod ensemble;

use checks::{checks_figure, Checks};
use ensemble::{ensemble_check, ensemble_figure};

use super::command::Command;
use super::dem_figures::softened_steel_set;
use super::pipeline::{
    scene_with, simulate_command, BundledScene, Ctx, FigureRecord, Recorded, SweepResult,
    DEM_B_SOFT,
};
use super::settings::{Chapter4Settings, DemSettings, Settings};
use crate::model::summary::DEFAULT_ANALYSIS_MAX_SAMPLES;
use crate::scene::keys::{
    DAMPER_SEED, EXCITATION_FREQUENCY, RUN_ANALYSIS_MAX_SAMPLES, RUN_DT_FRACTION, RUN_DURATION,
    RUN_PERIODS,
};
use crate::sweep::SweepPoints;

/// Scene B at Lz = 0.1225 m with softened grains and runs counted in periods
/// (`data/scenes/thesis_b_ch4.toml`).
pub const DEM_CH4: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_ch4.toml",
    text: include_str!("../../data/scenes/thesis_b_ch4.toml"),
};

/// The packing seed of [`DEM_CH4`] (the scene's default `damper.seed`).
const DEFAULT_SEED: u64 = 1;

/// Softening, time-step fraction and run length written in [`DEM_CH4`].
const SCENE_SOFTEN: f64 = 1000.0;
const SCENE_DT_FRACTION: f64 = 0.02;
const SCENE_PERIODS: f64 = 100.0;

/// Names of the chapter-4 figures (for `--only`).
pub const NAMES: [&str; 9] = [
    "ch4",
    "ch4_regime_frf",
    "ch4_ensemble",
    "ch4_checks",
    "ch4_bifurcation",
    "ch4_impacts",
    "ch4_run_length",
    "ch4_panels",
    "ch4_reconstruction",
];

/// One point of a chapter-4 sweep (from its typed summary).
#[derive(Debug, Clone, PartialEq)]
struct Point {
    f_hz: f64,
    amplitude_m: f64,
    regime: Option<Regime>,
    period: Option<f64>,
    /// The verdict with its qualifiers ("chaotic; phase-locked to the forcing (Λ₁ = 0.985);
    /// high-dimensional"); empty when not analysed.
    label: String,
    phase_locked: bool,
    locked_fraction: Option<f64>,
    /// W_n of the tight grouping, else the section's size (relative to the orbit).
    section_scatter: Option<f64>,
    chaos_dimension: Option<&'static str>,
    replica: Option<&'static str>,
    replica_saturation_rel: Option<f64>,
    replica_growth_per_s: Option<f64>,
    mle_per_s: Option<f64>,
    mle_stderr_per_s: Option<f64>,
    floor_impacts: f64,
    ceiling_impacts: f64,
}

impl Point {
    /// Regime and period ("periodic-3", "chaotic"): what the run-length and ensemble checks
    /// compare (the qualifiers are reported beside it).
    fn verdict(&self) -> String {
        match self.period {
            Some(p) if self.regime == Some(Regime::Periodic) => format!("periodic-{p}"),
            _ => self.regime_str().to_string(),
        }
    }

    /// The regime's name, empty when the point was not analysed (as in `sweep.csv`).
    fn regime_str(&self) -> &'static str {
        self.regime.map_or("", Regime::as_str)
    }
}

fn point(step: &str, dir: &str, p: &crate::sweep::SweepPoint) -> Result<Point, StudyError> {
    let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
    // a DEM figure of the point (NaN: written as null, read as missing)
    let extra = |key: &str, f: fn(&crate::model::DemExtras) -> f64| {
        p.summary
            .dem
            .as_ref()
            .map(f)
            .filter(|v| !v.is_nan())
            .ok_or_else(|| StudyError::step(step, format!("{dir}: point {}: no `{key}`", p.index)))
    };
    let a = p.summary.analysis.as_ref();
    let r = p.summary.replica.as_ref();
    Ok(Point {
        f_hz: p.summary.frequency_hz,
        amplitude_m: p.summary.amplitude_m,
        regime: a.map(|a| a.regime),
        period: finite(a.and_then(|a| a.period)),
        label: a.map(|a| a.verdict()).unwrap_or_default(),
        phase_locked: a.is_some_and(|a| a.phase_locked),
        locked_fraction: a.and_then(|a| a.phase_lock.map(|l| l.locked_fraction)),
        section_scatter: a
            .and_then(|a| a.section.as_ref())
            .map(|s| s.tight.as_ref().map_or(s.size, |g| g.scatter)),
        chaos_dimension: a.and_then(|a| a.chaos_dimension.map(|d| d.as_str())),
        replica: r.map(|r| r.outcome.as_str()),
        replica_saturation_rel: r.map(|r| r.saturation_rel),
        replica_growth_per_s: r.and_then(|r| r.growth_rate_per_s().map(|g| g.0)),
        mle_per_s: finite(a.and_then(|a| a.data_mle_per_s)),
        mle_stderr_per_s: finite(a.and_then(|a| a.data_mle_stderr_per_s)),
        floor_impacts: extra("bed_floor_impacts_per_cycle", |d| {
            d.bed_floor_impacts_per_cycle
        })?,
        ceiling_impacts: extra("bed_ceiling_impacts_per_cycle", |d| {
            d.bed_ceiling_impacts_per_cycle
        })?,
    })
}

fn points(step: &str, pts: &SweepPoints) -> Result<Vec<Point>, StudyError> {
    let mut out = pts
        .iter()
        .map(|p| point(step, &pts.dir, p))
        .collect::<Result<Vec<Point>, StudyError>>()?;
    out.sort_by(|a, b| a.f_hz.total_cmp(&b.f_hz));
    Ok(out)
}

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
fn ch4_set(d: &DemSettings, c: &Chapter4Settings, factor: f64) -> Vec<(&'static str, String)> {
    let mut set = Vec::new();
    if d.soften != SCENE_SOFTEN {
        set.extend(softened_steel_set(d.soften));
    }
    if d.dt_fraction != SCENE_DT_FRACTION {
        set.push((RUN_DT_FRACTION, d.dt_fraction.to_string()));
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
fn length_text(c: &Chapter4Settings, factor: f64) -> String {
    match c.duration_s {
        Some(s) => format!("{} s", factor * s),
        None => format!("{} periods", factor * c.periods),
    }
}

/// The run length in a directory name ("p200" or "d196.83").
fn length_dir(c: &Chapter4Settings, factor: f64) -> String {
    match c.duration_s {
        Some(s) => format!("d{}", factor * s),
        None => format!("p{}", factor * c.periods),
    }
}

fn sweep_dir(c: &Chapter4Settings, factor: f64) -> String {
    format!("dem_ch4_{}", length_dir(c, factor))
}

/// `--set` of the other shipped softened scene (`thesis_b_soft.toml`) at the mode's run
/// length: the chapter-4 scene's material and time step settings, and the run length always
/// written (that scene counts its runs in seconds).
fn other_scene_set(d: &DemSettings, c: &Chapter4Settings) -> Vec<(&'static str, String)> {
    let mut set = ch4_set(d, c, 1.0);
    if c.duration_s.is_none() && !set.iter().any(|(k, _)| *k == RUN_PERIODS) {
        set.push((RUN_PERIODS, c.periods.to_string()));
    }
    set
}

fn frequency_list(freqs: &[f64]) -> String {
    freqs
        .iter()
        .map(|f| f.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

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
    let base = sweep(1.0, &c.frequencies_hz)?;
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
        let seeds = c
            .ensemble_seeds
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join(",");
        let more = ctx.sweep(
            &format!("{}_seeds", sweep_dir(c, 1.0)),
            DEM_CH4,
            &ch4_set(d, c, 1.0),
            &[
                (DAMPER_SEED, seeds),
                (EXCITATION_FREQUENCY, frequency_list(&c.check_freqs_hz)),
            ],
            true,
        )?;
        Some(ensemble_check(&pts, &more)?)
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
    if want("ch4_panels") || want("ch4_reconstruction") {
        // one DEM run per panel, in parallel (each run is single-threaded and deterministic)
        let runs = c
            .panel_freqs_hz
            .par_iter()
            .map(|&f| panel_run(d, c, f))
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

/// What every figure of the study shares.
struct Info<'a, 'b> {
    ctx: &'a Ctx<'b>,
    c: &'a Chapter4Settings,
    sweep: &'a SweepResult,
    reductions: &'a [String],
}

impl Info<'_, '_> {
    /// The figure's record: the sweep's commands, then `plot`.
    fn record(
        &self,
        name: &str,
        caption: String,
        plot: Vec<Command>,
        size: (u32, u32),
    ) -> FigureRecord {
        FigureRecord {
            name: name.into(),
            caption,
            spec_item: "chapter 4: regimes of the DEM bed along f at Lz = 0.1225 m".into(),
            commands: [self.sweep.commands.clone(), plot].concat(),
            reductions: self.reductions.to_vec(),
            size_px: size,
        }
    }
}

fn opt_cell(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

fn regime_frf(
    info: &Info,
    pts: &[Point],
    ensemble: Option<&[(f64, String)]>,
) -> Result<FigureRecord, StudyError> {
    let name = "ch4_regime_frf";
    let header: Vec<&str> = ["frequency_hz", "amplitude_m", "regime", "period"]
        .into_iter()
        .chain(crate::sweep::VERDICT_COLUMNS)
        .chain([
            "mle_per_s",
            "mle_stderr_per_s",
            "impacts_per_cycle",
            "ensemble",
        ])
        .collect();
    let rows = pts.iter().map(|p| {
        vec![
            p.f_hz.to_string(),
            p.amplitude_m.to_string(),
            p.regime_str().to_string(),
            opt_cell(p.period),
            p.label.clone(),
            p.phase_locked.to_string(),
            opt_cell(p.locked_fraction),
            opt_cell(p.section_scatter),
            p.chaos_dimension.unwrap_or_default().to_string(),
            p.replica.unwrap_or_default().to_string(),
            opt_cell(p.replica_saturation_rel),
            opt_cell(p.replica_growth_per_s),
            opt_cell(p.mle_per_s),
            opt_cell(p.mle_stderr_per_s),
            (p.floor_impacts + p.ceiling_impacts).to_string(),
            ensemble
                .and_then(|e| e.iter().find(|(f, _)| *f == p.f_hz))
                .map_or(String::new(), |(_, words)| words.clone()),
        ]
    });
    info.ctx.write_table(name, &header, rows)?;
    let f: Vec<f64> = pts.iter().map(|p| p.f_hz).collect();
    let z: Vec<f64> = pts.iter().map(|p| p.amplitude_m).collect();
    let reg: Vec<Option<Regime>> = pts.iter().map(|p| p.regime).collect();
    let mle: Vec<Option<f64>> = pts.iter().map(|p| p.mle_per_s).collect();
    let se: Vec<Option<f64>> = pts.iter().map(|p| p.mle_stderr_per_s).collect();
    let locked: Vec<bool> = pts.iter().map(|p| p.phase_locked).collect();
    let growth: Vec<Option<f64>> = pts.iter().map(|p| p.replica_growth_per_s).collect();
    let period: Vec<Option<u32>> = pts
        .iter()
        .map(|p| p.period.filter(|x| *x >= 1.0).map(|x| x.round() as u32))
        .collect();
    let size = info.ctx.render(
        name,
        &RegimeFrfFigure {
            frequency_hz: &f,
            amplitude_m: &z,
            regime: &reg,
            period: Some(&period),
            data: Some(Exponents {
                per_s: &mle,
                stderr_per_s: Some(&se),
            }),
            model: None,
            phase_locked: Some(&locked),
            replica: Some(Exponents {
                per_s: &growth,
                stderr_per_s: None,
            }),
        },
    )?;
    Ok(info.record(
        name,
        format!(
            "DEM scene B (N = 250, Lz = 0.1225 m), {} per frequency: primary amplitude Z(f) \
             coloured by the regime of the grains' centre of mass — periodic-n only where the \
             exact section is n tight groups (≤ 5 % of the orbit on every axis), chaotic where \
             it is a cloud and two replicas started 1e-9 m apart separate to the cloud's size \
             (orange: chaos phase-locked to the forcing, Λ_p ≥ 0.9). Lower panel: the data \
             Lyapunov exponent of the section with its error bar and the replicas' growth rate \
             (1/s). Every column, with the section scatter and the replica outcome, is in \
             {name}.csv{}.",
            length_text(info.c, 1.0),
            if ensemble.is_some() {
                "; `ensemble` gives the verdicts of three initial packings"
            } else {
                ""
            }
        ),
        vec![Command::plot(
            "regime-frf",
            &info.sweep.csv,
            &info.ctx.path(&format!("{name}.png")),
        )],
        size,
    ))
}

fn bifurcation(info: &Info) -> Result<FigureRecord, StudyError> {
    let name = "ch4_bifurcation";
    let rows: Vec<(f64, f64, f64)> = (info.sweep.points.iter())
        .flat_map(|p| {
            let f = p.summary.frequency_hz;
            p.summary
                .strobe
                .iter()
                .map(move |s| (f, s.grain_z_m, s.box_z_m))
        })
        .collect();
    if rows.is_empty() {
        return Err(StudyError::step(name, "the sweep wrote no strobe.csv rows"));
    }
    let f: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let z: Vec<f64> = rows.iter().map(|r| r.1).collect();
    let b: Vec<f64> = rows.iter().map(|r| r.2).collect();
    let rel: Vec<f64> = z.iter().zip(&b).map(|(z, b)| z - b).collect();
    info.ctx.write_csv(
        name,
        &["frequency_hz", "grain_z_m", "box_z_m", "grain_z_rel_m"],
        &(0..f.len())
            .map(|i| vec![f[i], z[i], b[i], rel[i]])
            .collect::<Vec<_>>(),
    )?;
    let size = info.ctx.render(
        name,
        &BifurcationFigure {
            x: &f,
            z_m: &rel,
            x_label: "frequency f (Hz)".into(),
        },
    )?;
    Ok(info.record(
        name,
        "Same sweep: height of the grains' centre of mass above the floor, z_cm − z, at \
         t = kT over the analysis window (the exact section), versus f: one dot per period-1 \
         frequency, n dots for period n (their spread is the bed's granular noise)."
            .into(),
        vec![Command::plot(
            "bifurcation",
            &(info.sweep.csv.iter())
                .map(|p| p.with_file_name("strobe.csv"))
                .collect::<Vec<_>>(),
            &info.ctx.path(&format!("{name}.png")),
        )],
        size,
    ))
}

fn impacts(info: &Info, pts: &[Point]) -> Result<FigureRecord, StudyError> {
    let name = "ch4_impacts";
    let f: Vec<f64> = pts.iter().map(|p| p.f_hz).collect();
    let fl: Vec<f64> = pts.iter().map(|p| p.floor_impacts).collect();
    let ce: Vec<f64> = pts.iter().map(|p| p.ceiling_impacts).collect();
    let tot: Vec<f64> = fl.iter().zip(&ce).map(|(a, b)| a + b).collect();
    info.ctx.write_csv(
        name,
        &[
            "frequency_hz",
            "floor_impacts_per_cycle",
            "ceiling_impacts_per_cycle",
            "impacts_per_cycle",
        ],
        &(0..f.len())
            .map(|i| vec![f[i], fl[i], ce[i], tot[i]])
            .collect::<Vec<_>>(),
    )?;
    let size = info.ctx.render(
        name,
        &LinesFigure {
            series: vec![
                Series {
                    label: "bed on the floor",
                    x: &f,
                    y: &fl,
                },
                Series {
                    label: "bed on the ceiling",
                    x: &f,
                    y: &ce,
                },
                Series {
                    label: "total",
                    x: &f,
                    y: &tot,
                },
            ],
            x_label: "frequency f (Hz)".into(),
            y_label: "collective impacts per forcing cycle".into(),
            y_scale: 1.0,
            title: "Impacts of the bed as a whole per forcing cycle".into(),
            kind: "dem-impacts",
        },
    )?;
    Ok(info.record(
        name,
        "Same sweep: impacts of the bed as a whole on the floor and on the ceiling per forcing \
         cycle over the steady window (the centre of mass stopped by a wall that carries more \
         than half the bed's weight; see dem::bed_impacts)."
            .into(),
        vec![],
        size,
    ))
}

fn run_length(
    info: &Info,
    pts: &[Point],
    long: &SweepResult,
    long_pts: &[Point],
) -> Result<FigureRecord, StudyError> {
    let name = "ch4_run_length";
    let header = [
        "frequency_hz",
        "verdict",
        "verdict_doubled",
        "same_verdict",
        "amplitude_m",
        "amplitude_doubled_m",
        "amplitude_change_pct",
        "impacts_per_cycle",
        "impacts_per_cycle_doubled",
        "mle_per_s",
        "mle_per_s_doubled",
    ];
    let mut rows = Vec::new();
    let (mut same, mut worst) = (0usize, 0.0f64);
    let mut pairs = Vec::new();
    for p in pts {
        let Some(q) = long_pts.iter().find(|q| q.f_hz == p.f_hz) else {
            continue;
        };
        let change = 100.0 * (q.amplitude_m / p.amplitude_m - 1.0);
        worst = worst.max(change.abs());
        let agree = p.verdict() == q.verdict();
        same += usize::from(agree);
        rows.push(vec![
            p.f_hz.to_string(),
            p.verdict(),
            q.verdict(),
            agree.to_string(),
            p.amplitude_m.to_string(),
            q.amplitude_m.to_string(),
            format!("{change:.3}"),
            (p.floor_impacts + p.ceiling_impacts).to_string(),
            (q.floor_impacts + q.ceiling_impacts).to_string(),
            opt_cell(p.mle_per_s),
            opt_cell(q.mle_per_s),
        ]);
        pairs.push((p.f_hz, p.amplitude_m, q.amplitude_m));
    }
    info.ctx.write_table(name, &header, rows)?;
    let f: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    let a: Vec<f64> = pairs.iter().map(|p| p.1).collect();
    let b: Vec<f64> = pairs.iter().map(|p| p.2).collect();
    let (la, lb) = (
        length_text(info.c, 1.0),
        format!("{} (continued)", length_text(info.c, 2.0)),
    );
    let size = info.ctx.render(
        name,
        &LinesFigure {
            series: vec![
                Series {
                    label: &la,
                    x: &f,
                    y: &a,
                },
                Series {
                    label: &lb,
                    x: &f,
                    y: &b,
                },
            ],
            x_label: "frequency f (Hz)".into(),
            y_label: "primary amplitude Z (mm)".into(),
            y_scale: 1e3,
            title: "DEM frequency response at two run lengths".into(),
            kind: "dem-run-length",
        },
    )?;
    let mut rec = info.record(
        name,
        format!(
            "Run-length check: the sweep's runs continued to {} (the same trajectory: the \
             same time step, the first half bit for bit the shorter run): the verdict (regime \
             and period) is unchanged at {same} of {} frequencies and the amplitude changes by \
             at most {worst:.2} % (table in {name}.csv).",
            length_text(info.c, 2.0),
            pairs.len()
        ),
        vec![],
        size,
    );
    rec.commands.extend(long.commands.iter().cloned());
    Ok(rec)
}

/// One recorded chapter-4 run at a panel frequency.
struct PanelRun {
    f_hz: f64,
    summary: RunSummary,
    rec: Recorded,
    dt_s: f64,
    /// The run's `--set` (for its `pdamp simulate` command).
    set: Vec<(&'static str, String)>,
}

impl PanelRun {
    /// The verdict with its qualifiers.
    fn verdict(&self) -> String {
        self.summary
            .analysis
            .as_ref()
            .map_or_else(|| "not analysed".to_string(), |a| a.verdict())
    }

    /// The two-replica test's outcome in a few words ("replicas: sensitive, 9.7 % of the
    /// orbit").
    fn replica_words(&self) -> String {
        use crate::analysis::replica_test::ReplicaOutcome as O;
        match self.summary.replica.as_ref().map(|r| &r.outcome) {
            Some(O::Sensitive {
                saturation_rel_orbit,
            }) => format!(
                "replicas: sensitive, separating to {:.1} % of the orbit",
                100.0 * saturation_rel_orbit
            ),
            Some(O::Insensitive) => "replicas: insensitive".into(),
            Some(O::Inconclusive { .. }) => "replicas: inconclusive".into(),
            None => "no replica test".into(),
        }
    }
}

fn panel_run(d: &DemSettings, c: &Chapter4Settings, f: f64) -> Result<PanelRun, StudyError> {
    let step = format!("dem panel f{f}");
    let mut set = ch4_set(d, c, 1.0);
    set.push((EXCITATION_FREQUENCY, f.to_string()));
    let scene = scene_with(&step, DEM_CH4, &set)?;
    // the sweep's own analysis series (every analysis window / run.analysis_max_samples s
    // from the analysis start, ~170 samples a period here): the automatic time step is
    // snapped to that clock, so the panel is the sweep point's run, trajectory and verdict
    let opts = crate::setup::steady_series(&scene);
    let dt = opts.sample_interval_s.unwrap_or(scene.run.sample_interval);
    let mut rec = Recorded::default();
    let summary = crate::sweep::run_with_analysis(&scene, &mut rec, &opts, true)
        .map_err(|e| StudyError::step(&step, e))?;
    Ok(PanelRun {
        f_hz: f,
        summary,
        rec,
        dt_s: dt,
        set,
    })
}

fn panel(info: &Info, r: &PanelRun) -> Result<FigureRecord, StudyError> {
    let f = r.f_hz;
    let name = format!("ch4_panel_f{f}");
    let rec = &r.rec;
    let n = rec.time_s.len();
    let per_period = (1.0 / (f * r.dt_s)).round() as usize;
    let from = n.saturating_sub(4 * per_period);
    let w = |v: &[f64]| v[from.min(v.len())..].to_vec();
    let (t, floor, ceil, z, lo, hi) = (
        w(&rec.time_s),
        w(&rec.floor_z_m),
        w(&rec.ceiling_z_m),
        w(&rec.grain_z_m),
        w(&rec.grain_zmin_m),
        w(&rec.grain_zmax_m),
    );
    // one length unit across the panel: mm (the bed motion is drawn in mm)
    let sz: Vec<f64> = r.summary.strobe.iter().map(|p| 1e3 * p.grain_z_m).collect();
    let sv: Vec<f64> = r
        .summary
        .strobe
        .iter()
        .map(|p| 1e3 * p.grain_v_m_s)
        .collect();
    let sp = power_spectrum(
        &rec.grain_z_m,
        &SpectrumOptions {
            dt_s: Some(r.dt_s),
            ..Default::default()
        },
    )
    .map_err(|e| StudyError::step(&name, e))?;
    let keep: Vec<usize> = (0..sp.frequency.len())
        .filter(|&i| sp.frequency[i] > 0.0 && sp.frequency[i] <= 4.0 * f)
        .collect();
    let fx: Vec<f64> = keep.iter().map(|&i| sp.frequency[i]).collect();
    let pw_mm2: Vec<f64> = keep.iter().map(|&i| 1e6 * sp.power[i]).collect();
    info.ctx.write_csv(
        &format!("{name}_section"),
        &["cycle", "time_s", "grain_z_m", "grain_v_m_s", "box_z_m"],
        &r.summary
            .strobe
            .iter()
            .map(|p| {
                vec![
                    p.cycle as f64,
                    p.time_s,
                    p.grain_z_m,
                    p.grain_v_m_s,
                    p.box_z_m,
                ]
            })
            .collect::<Vec<_>>(),
    )?;
    let band = (!lo.is_empty() && lo.len() == t.len()).then_some((lo.as_slice(), hi.as_slice()));
    let fig = FrequencyPanelFigure {
        bed: BedMotionFigure {
            time_s: &t,
            floor_z_m: &floor,
            ceiling_z_m: &ceil,
            grain_z_m: &z,
            grain_band: band,
            grain_force_n: None,
        },
        section: PoincareFigure {
            x: &sz,
            y: &sv,
            x_label: "z_cm at t = kT (mm)".into(),
            y_label: "ż_cm at t = kT (mm/s)".into(),
        },
        spectrum: SpectrumFigure {
            frequency_hz: &fx,
            power: &pw_mm2,
            forcing_hz: Some(f),
            power_label: "power of z_cm (mm² per bin)".into(),
        },
    };
    let impacts = r.summary.impacts_per_cycle;
    let title = format!(
        "DEM scene B at {f} Hz: {}; {}; {impacts:.2} bed impacts per cycle",
        r.verdict(),
        r.replica_words()
    );
    let opts = crate::plot::FigureOptions {
        width: info.ctx.figure.width,
        height: (info.ctx.figure.height as f64 * 1.5) as u32,
        title: Some(title),
    };
    let path = info.ctx.path(&format!("{name}.png"));
    crate::plot::render(&fig, &path, &opts).map_err(|e| StudyError::step(&name, e))?;
    let mut rec = info.record(
        &name,
        format!(
            "DEM scene B (Lz = 0.1225 m) at {f} Hz, {}: the last four periods of the bed \
             (floor, ceiling, band from the lowest to the highest grain, z_cm), the exact \
             stroboscopic section (z_cm, ż_cm) at t = kT over the analysis window \
             ({} points; {name}_section.csv) and the spectrum of z_cm up to 4 f. Verdict: {}; \
             {}; {impacts:.2} collective impacts per cycle.",
            length_text(info.c, 1.0),
            sz.len(),
            r.verdict(),
            r.replica_words()
        ),
        vec![],
        (opts.width, opts.height),
    );
    // the run itself, into a directory, and the CLI's figures of its bed and section
    let dir = info.ctx.path(&format!("data/ch4_run_f{f}"));
    rec.commands = vec![
        simulate_command(DEM_CH4, &r.set, &dir),
        Command::plot(
            "bed-motion",
            &[dir.join("series.csv")],
            &dir.join("bed_motion.png"),
        ),
        Command::plot(
            "poincare",
            &[dir.join("strobe.csv")],
            &dir.join("poincare.png"),
        )
        .opt("x", "grain_z_m")
        .opt("y", "grain_v_m_s"),
    ];
    Ok(rec)
}

fn reconstruction(info: &Info, runs: &[PanelRun]) -> Result<FigureRecord, StudyError> {
    let name = "ch4_reconstruction";
    let mut series: Vec<(Vec<f64>, usize, f64, String)> = Vec::new();
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for r in runs {
        // 64 samples per period: the lag from the first minimum of the mutual information
        let dec = ((1.0 / (r.f_hz * 64.0 * r.dt_s)).round() as usize).max(1);
        let z: Vec<f64> = r.rec.grain_z_m.iter().step_by(dec).copied().collect();
        let mi = mutual_information(
            &z,
            &MutualInformationOptions {
                bins: 16,
                max_lag: 64,
            },
        )
        .map_err(|e| StudyError::step(name, e))?;
        let lag = mi.first_minimum.unwrap_or(16).max(1);
        let keep = z.len().min(20 * 64);
        let dt = r.dt_s * dec as f64;
        // the run into a directory, and its reconstruction at the same lag in its samples
        let dir = info.ctx.path(&format!("data/ch4_run_f{}", r.f_hz));
        commands.push(simulate_command(DEM_CH4, &r.set, &dir));
        commands.push(
            Command::plot(
                "reconstruction",
                &[dir.join("series.csv")],
                &dir.join("reconstruction.png"),
            )
            .opt("column", "grain_z_m")
            .opt("lag", lag * dec),
        );
        rows.push(vec![
            r.f_hz.to_string(),
            (lag as f64 * dt).to_string(),
            dec.to_string(),
        ]);
        series.push((
            z[z.len() - keep..].iter().map(|v| 1e3 * v).collect(),
            lag,
            dt,
            format!("{} Hz: {}", r.f_hz, r.verdict()),
        ));
    }
    info.ctx
        .write_table(name, &["frequency_hz", "lag_s", "decimation"], rows)?;
    let fig = ReconstructionGridFigure {
        cells: series
            .iter()
            .map(|(z, lag, dt, cap)| {
                (
                    ReconstructionFigure {
                        series: z,
                        lag: *lag,
                        dt_s: Some(*dt),
                        value_label: "z_cm (mm)".into(),
                    },
                    cap.clone(),
                )
            })
            .collect(),
        columns: 3,
    };
    let rows = runs.len().div_ceil(3).max(1) as f64;
    let opts = crate::plot::FigureOptions {
        width: info.ctx.figure.width * 3 / 2,
        height: (info.ctx.figure.height as f64 * 0.6 * rows) as u32,
        title: Some("Delay reconstructions (z_cm(t), z_cm(t + τ)) of the DEM bed".into()),
    };
    let path = info.ctx.path(&format!("{name}.png"));
    crate::plot::render(&fig, &path, &opts).map_err(|e| StudyError::step(name, e))?;
    let mut rec = info.record(
        name,
        format!(
            "Fig. 4.7: 2-D delay reconstructions of z_cm over the last 20 periods at {} Hz, τ \
             from the first minimum of the mutual information (lags in {name}.csv).",
            runs.iter()
                .map(|r| r.f_hz.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        vec![],
        (opts.width, opts.height),
    );
    rec.commands = commands;
    Ok(rec)
}
