//! The figure set of SPEC §7 for scene B (Sánchez 2012 §3.2), headless: sweeps through
//! [`crate::sweep`] (resumable, under `OUT/data/`), fits of (2.1.21), figures through
//! [`crate::plot`], and `OUT/README.md` saying which command made each figure and how it
//! departs from the source's parameters.
//!
//! Order: impact-model sweeps (cheap) → their figures → DEM sweeps and figures (if the DEM
//! model is in this build and the mode includes them) → the README.

use std::path::PathBuf;

use crate::analysis::frf_fit::{fit_frf_groups, FrfFitOptions, FrfGroupFit};
use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use crate::analysis::spectrum::{power_spectrum, SpectrumOptions};
use crate::error::StudyError;
use crate::model::PrimarySystem;
use crate::plot::bed_motion::BedMotionFigure;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::effective::EffectiveFigure;
use crate::plot::energy::energy_figure;
use crate::plot::frf::{FrfFigure, FrfReference};
use crate::plot::lines::LinesFigure;
use crate::plot::poincare::PoincareFigure;
use crate::plot::reconstruction::ReconstructionFigure;
use crate::plot::regime_frf::{Exponents, RegimeFrfFigure};
use crate::plot::regime_map::RegimeMapFigure;
use crate::plot::resonance::{resonance_amplitudes, resonance_figure};
use crate::plot::spectrum::SpectrumFigure;
use crate::plot::{FigureOptions, Series};
use crate::scene::keys::{
    DAMPER_GAP, DAMPER_RESTITUTION, EXCITATION_FREQUENCY, RUN_DURATION, RUN_PERIODS,
};
use crate::sweep::SweepPoints;

use super::check::EffectiveRow;
use super::dem_figures;
use super::pipeline::{
    record_run, record_run_summary, scene_with, simulate_command, Ctx, FigureRecord, SweepResult,
    IMPACT_B,
};
use super::settings::{Mode, Settings, SCENE_B_GAP_M};

/// Scene B's primary system and grains (SPEC §6): M, m_p, K, C, U.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneB {
    /// The primary system M, K, C.
    pub primary: PrimarySystem,
    /// Grain mass m_p (kg).
    pub particle_mass_kg: f64,
    /// Base amplitude U (m).
    pub base_amplitude_m: f64,
}

/// Scene B's values (Sánchez 2012 §3.2).
pub const SCENE_B: SceneB = SceneB {
    primary: PrimarySystem {
        mass_kg: 2.37,
        stiffness_n_m: 21500.0,
        damping_n_s_m: 7.6,
    },
    particle_mass_kg: 0.227,
    base_amplitude_m: 4.5e-3,
};

impl SceneB {
    /// The FRF reference curves for M and M + m_p.
    pub fn reference(&self) -> FrfReference {
        FrfReference {
            primary: self.primary,
            particle_mass_kg: Some(self.particle_mass_kg),
            base_amplitude_m: self.base_amplitude_m,
        }
    }
}

/// Options of [`reproduce`].
#[derive(Debug, Clone)]
pub struct ReproduceOptions {
    /// Work per figure.
    pub settings: Settings,
    /// Output directory: figures, `README.md`, sweeps under `data/`.
    pub out: PathBuf,
    /// Size of every PNG (default 1024 × 768).
    pub figure: FigureOptions,
    /// Skip the DEM figures even if the mode includes them.
    pub skip_dem: bool,
    /// Make only these figures (names as in [`ReproduceReport::figures`]; a name also selects
    /// `name_*`, e.g. `poincare` → `poincare_f10`, `bed_motion` → `bed_motion_dem`); empty:
    /// all, and write `OUT/README.md`.
    pub only: Vec<String>,
}

impl ReproduceOptions {
    /// The settings of `mode`, writing into `out`.
    pub fn new(mode: Mode, out: impl Into<PathBuf>) -> Self {
        ReproduceOptions {
            settings: Settings::for_mode(mode),
            out: out.into(),
            figure: FigureOptions::default(),
            skip_dem: false,
            only: Vec::new(),
        }
    }

    /// The README written into `out`: `README.md` for the whole set, `README.<only>.md`
    /// (names joined by `+`) for a selection, so that a partial run never overwrites the
    /// whole set's README.
    pub fn readme_name(&self) -> String {
        if self.only.is_empty() {
            "README.md".into()
        } else {
            format!("README.{}.md", self.only.join("+"))
        }
    }

    /// Whether figure `name` is selected by [`ReproduceOptions::only`].
    pub fn wants(&self, name: &str) -> bool {
        self.only.is_empty()
            || self.only.iter().any(|o| {
                name == o
                    || name.starts_with(&format!("{o}_"))
                    || o.starts_with(&format!("{name}_"))
            })
    }
}

/// What [`reproduce`] made.
#[derive(Debug, Clone)]
pub struct ReproduceReport {
    /// Every figure written, in order.
    pub figures: Vec<FigureRecord>,
    /// The impact model's effective mass and damping per gap (e = 0), sorted by gap.
    pub effective: Vec<EffectiveRow>,
    /// The DEM's effective mass and damping per container height (N of the source), if run.
    pub effective_dem: Vec<EffectiveRow>,
    /// Parts left out, with the reason (e.g. the DEM model not in this build).
    pub skipped: Vec<String>,
    /// Wall time (s).
    pub elapsed_s: f64,
}

/// Regenerates the figure set of SPEC §7 into `opts.out`.
///
/// `progress` receives one line per stage. Sweeps are resumable: rerunning into the same
/// directory reuses the finished points.
///
/// # Errors
/// [`StudyError`] naming the stage that failed.
pub fn reproduce(
    opts: &ReproduceOptions,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<ReproduceReport, StudyError> {
    let started = std::time::Instant::now();
    std::fs::create_dir_all(opts.out.join("data")).map_err(|e| StudyError::Output {
        path: opts.out.display().to_string(),
        message: e.to_string(),
    })?;
    let ctx = Ctx {
        out: opts.out.clone(),
        figure: opts.figure.clone(),
        progress,
    };
    let s = &opts.settings;
    let want = |name: &str| opts.wants(name);
    let mut figures = Vec::new();
    let mut skipped = Vec::new();
    let mut effective = Vec::new();

    // ---- impact model (SPEC §3) ----
    let need_frf = want("frf") || want("energy_vs_frequency");
    let frf_e0 = need_frf
        .then(|| impact_frf_sweep(&ctx, s, 0.0))
        .transpose()?;
    let frf_e8 = want("frf")
        .then(|| impact_frf_sweep(&ctx, s, 0.8))
        .transpose()?;
    let need_grid = want("effective") || want("zres_vs_gap") || want("energy_vs_gap");
    if need_grid {
        let grid_e0 = impact_gap_grid(&ctx, s, 0.0)?;
        let (rec, rows) = effective_figure(&ctx, s, &grid_e0)?;
        effective = rows;
        if want("effective") {
            figures.push(rec);
        }
        if want("zres_vs_gap") || want("energy_vs_gap") {
            let grid_e8 = impact_gap_grid(&ctx, s, 0.8)?;
            if want("zres_vs_gap") {
                figures.push(zres_vs_gap(&ctx, s, &grid_e0, &grid_e8)?);
            }
            if want("energy_vs_gap") {
                figures.push(energy_vs_gap(&ctx, s, &grid_e0, &grid_e8)?);
            }
        }
    }
    if want("zres_vs_restitution") {
        figures.push(zres_vs_restitution(&ctx, s)?);
    }
    if let (true, Some(e0)) = (want("energy_vs_frequency"), &frf_e0) {
        figures.push(energy_vs_frequency(&ctx, s, e0)?);
    }
    if want("bed_motion") {
        figures.push(bed_motion_impact(&ctx, s)?);
    }
    if want("poincare") || want("spectrum") || want("reconstruction") {
        for &f in &s.series_freqs_hz {
            figures.extend(per_frequency(&ctx, s, f)?);
        }
    }
    if want("regime_frf") || want("bifurcation") {
        let regime = ctx.sweep(
            "impact_regimes_e0.8",
            IMPACT_B,
            &[
                (DAMPER_RESTITUTION, "0.8".into()),
                (RUN_DURATION, s.regime_duration_s.to_string()),
            ],
            &[(EXCITATION_FREQUENCY, s.regime_freq.vary())],
            true,
        )?;
        if want("regime_frf") {
            figures.push(regime_frf(&ctx, s, &regime)?);
        }
        if want("bifurcation") {
            figures.push(bifurcation(&ctx, s, &regime)?);
        }
    }
    if want("regime_map") {
        figures.push(regime_map(&ctx, s)?);
    }

    // ---- DEM (SPEC §2) ----
    let mut dem_frf: Option<SweepResult> = None;
    let mut effective_dem = Vec::new();
    let dem_wanted = dem_figures::NAMES.iter().any(|n| want(n)) || want("frf");
    match (&s.dem, opts.skip_dem, dem_wanted) {
        (_, _, false) => {}
        (None, _, _) => skipped.push(format!(
            "DEM figures: not part of {} mode (use --quick or --full)",
            s.mode.as_str()
        )),
        (Some(_), true, _) => skipped.push("DEM figures: --no-dem".into()),
        (Some(d), false, _) => match dem_figures::available() {
            Err(why) => skipped.push(format!("DEM figures: {why}")),
            Ok(()) => {
                let out = dem_figures::all(&ctx, s, d)?;
                figures.extend(out.figures);
                effective_dem = out.effective;
                dem_frf = Some(out.frf);
            }
        },
    }
    // ---- the source's chapter 4 (DEM regimes along f) ----
    let ch4_wanted = super::chapter4::NAMES.iter().any(|n| want(n));
    match (
        s.dem
            .as_ref()
            .and_then(|d| d.chapter4.as_ref().map(|c| (d, c))),
        ch4_wanted,
    ) {
        (_, false) => {}
        (None, true) => skipped.push(format!(
            "chapter-4 figures: not part of {} mode (use --quick or --full)",
            s.mode.as_str()
        )),
        (Some(_), true) if opts.skip_dem => skipped.push("chapter-4 figures: --no-dem".into()),
        (Some((d, c)), true) => match dem_figures::available() {
            Err(why) => skipped.push(format!("chapter-4 figures: {why}")),
            Ok(()) => {
                let out = super::chapter4::all(&ctx, s, d, c, &want)?;
                figures.extend(out.figures);
                // the chapter-4 runs (a fixed number of periods per point) are the converged
                // DEM frequency response; the short drives of the DEM figure set are not
                dem_frf = Some(out.sweep);
            }
        },
    }
    if let (Some(e0), Some(e8)) = (&frf_e0, &frf_e8) {
        figures.insert(0, frf_figure(&ctx, s, e0, e8, dem_frf.as_ref())?);
    }
    for why in &skipped {
        progress(&format!("skipped: {why}"));
    }
    let report = ReproduceReport {
        figures,
        effective,
        effective_dem,
        skipped,
        elapsed_s: started.elapsed().as_secs_f64(),
    };
    ctx.write_text(&opts.readme_name(), &super::readme::readme(opts, &report))?;
    Ok(report)
}

fn impact_frf_sweep(ctx: &Ctx, s: &Settings, e: f64) -> Result<SweepResult, StudyError> {
    ctx.sweep(
        &format!("impact_frf_e{e}"),
        IMPACT_B,
        &[
            (DAMPER_RESTITUTION, e.to_string()),
            (RUN_DURATION, s.duration_s.to_string()),
        ],
        &[(EXCITATION_FREQUENCY, s.freq.vary())],
        false,
    )
}

fn impact_gap_grid(ctx: &Ctx, s: &Settings, e: f64) -> Result<SweepResult, StudyError> {
    ctx.sweep_split(
        &format!("impact_gap_grid_e{e}"),
        IMPACT_B,
        &[
            (DAMPER_RESTITUTION, e.to_string()),
            (RUN_DURATION, s.duration_s.to_string()),
        ],
        (DAMPER_GAP, &s.gaps_m),
        &[(EXCITATION_FREQUENCY, s.grid_freq.vary())],
        false,
    )
}

/// Fits (2.1.21) to each group of points (grouped by varied key `key`; `None`: all points as
/// one group), with K and U of scene B.
///
/// # Errors
/// [`StudyError::Step`] naming `step` if a point lacks `key` or a fit fails.
pub fn fit_groups(
    step: &str,
    pts: &SweepPoints,
    key: Option<&str>,
) -> Result<Vec<EffectiveRow>, StudyError> {
    let f = pts.map(|s| s.frequency_hz);
    let z = pts.map(|s| s.amplitude_m);
    let g = key
        .map(|k| pts.values(k))
        .transpose()
        .map_err(|e| StudyError::step(step, e))?;
    let opts = FrfFitOptions::new(SCENE_B.primary.stiffness_n_m, SCENE_B.base_amplitude_m);
    let fits = fit_frf_groups(&f, &z, g.as_deref(), &opts).map_err(|e| {
        let x = e.group_value.unwrap_or(f64::NAN);
        StudyError::step(
            step,
            format!("fit at {} = {x}: {}", key.unwrap_or("group"), e.error),
        )
    })?;
    Ok(fits
        .into_iter()
        .map(|FrfGroupFit { group_value, fit }| EffectiveRow {
            x_m: group_value.unwrap_or(f64::NAN),
            mass_ef_kg: fit.mass_ef_kg,
            mass_ef_stderr_kg: fit.mass_ef_stderr_kg,
            damping_ef_n_s_m: fit.damping_ef_n_s_m,
            damping_ef_stderr_n_s_m: fit.damping_ef_stderr_n_s_m,
        })
        .collect())
}

/// Draws an effective-mass figure from fits and writes its CSV.
///
/// # Errors
/// [`StudyError`] from rendering or writing.
pub fn draw_effective(
    ctx: &Ctx,
    name: &str,
    rows: &[EffectiveRow],
    x_label: &str,
    x_column: &str,
) -> Result<(u32, u32), StudyError> {
    let x: Vec<f64> = rows.iter().map(|r| r.x_m).collect();
    let me: Vec<f64> = rows.iter().map(|r| r.mass_ef_kg).collect();
    let ms: Vec<f64> = rows.iter().map(|r| r.mass_ef_stderr_kg).collect();
    let ce: Vec<f64> = rows.iter().map(|r| r.damping_ef_n_s_m).collect();
    let cs: Vec<f64> = rows.iter().map(|r| r.damping_ef_stderr_n_s_m).collect();
    ctx.write_csv(
        name,
        &[
            x_column,
            "mass_ef_kg",
            "mass_ef_stderr_kg",
            "damping_ef_ns_per_m",
            "damping_ef_stderr_ns_per_m",
        ],
        &rows
            .iter()
            .map(|r| {
                vec![
                    r.x_m,
                    r.mass_ef_kg,
                    r.mass_ef_stderr_kg,
                    r.damping_ef_n_s_m,
                    r.damping_ef_stderr_n_s_m,
                ]
            })
            .collect::<Vec<_>>(),
    )?;
    ctx.render(
        name,
        &EffectiveFigure {
            x: &x,
            x_label: x_label.into(),
            mass_ef_kg: &me,
            mass_ef_stderr_kg: &ms,
            damping_ef_n_s_m: &ce,
            damping_ef_stderr_n_s_m: &cs,
            mass_kg: Some(SCENE_B.primary.mass_kg),
            damping_n_s_m: Some(SCENE_B.primary.damping_n_s_m),
        },
    )
}

fn effective_figure(
    ctx: &Ctx,
    s: &Settings,
    grid: &SweepResult,
) -> Result<(FigureRecord, Vec<EffectiveRow>), StudyError> {
    let name = "effective";
    let rows = fit_groups(name, &grid.points, Some(DAMPER_GAP))?;
    let size = draw_effective(
        ctx,
        name,
        &rows,
        "gap between particle and ceiling (m)",
        "gap_m",
    )?;
    Ok((
        FigureRecord {
            name: name.into(),
            caption: "Impact model (e = 0): effective mass M_ef and damping C_ef/C of fits of \
                      (2.1.21) versus the gap, with standard errors. Gap 0 (clamped particle) \
                      gives M + m_p, a huge gap M; C_ef peaks in between."
                .into(),
            spec_item: "effective damping C_ef/C and effective mass M_ef versus Lz".into(),
            commands: vec![
                grid.command.clone(),
                format!(
                    "pdamp fit-frf {}/sweep.csv --stiffness 21500 --base-amplitude 4.5e-3 --mass 2.37 > fits.csv",
                    ctx.path("data/impact_gap_grid_e0").display()
                ),
                "pdamp plot effective fits.csv --mass 2.37 --damping 7.6 -o effective.png".into(),
            ],
            reductions: s.reductions(&["duration", "gaps", "grid"]),
            size_px: size,
        },
        rows,
    ))
}

/// Per group of varied key `key`, the point of largest amplitude (Z_res over frequency).
fn resonance_points<'a>(
    step: &str,
    pts: &'a SweepPoints,
    key: &str,
) -> Result<Vec<(f64, &'a crate::sweep::SweepPoint)>, StudyError> {
    Ok(pts
        .group_by(key)
        .map_err(|e| StudyError::step(step, e))?
        .into_iter()
        .filter_map(|(x, group)| {
            let best = group
                .into_iter()
                .max_by(|a, b| a.summary.amplitude_m.total_cmp(&b.summary.amplitude_m))?;
            Some((x, best))
        })
        .collect())
}

/// The values of varied key `key` of every point, or a study error naming `step`.
fn key_values(step: &str, pts: &SweepPoints, key: &str) -> Result<Vec<f64>, StudyError> {
    pts.values(key).map_err(|e| StudyError::step(step, e))
}

fn zres_vs_gap(
    ctx: &Ctx,
    s: &Settings,
    e0: &SweepResult,
    e8: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "zres_vs_gap";
    let (x0, z0) = resonance_amplitudes(
        &key_values(name, &e0.points, DAMPER_GAP)?,
        &e0.points.map(|s| s.amplitude_m),
    );
    let (x8, z8) = resonance_amplitudes(
        &key_values(name, &e8.points, DAMPER_GAP)?,
        &e8.points.map(|s| s.amplitude_m),
    );
    let rows: Vec<Vec<f64>> = (0..x0.len()).map(|i| vec![x0[i], z0[i], z8[i]]).collect();
    ctx.write_csv(name, &["gap_m", "zres_e0_m", "zres_e0.8_m"], &rows)?;
    let size = ctx.render(
        name,
        &resonance_figure(
            vec![
                Series {
                    label: "impact model, e = 0",
                    x: &x0,
                    y: &z0,
                },
                Series {
                    label: "impact model, e = 0.8",
                    x: &x8,
                    y: &z8,
                },
            ],
            "gap (m)",
        ),
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model: resonance amplitude Z_res (largest Z over the frequency grid) \
                  versus the gap for two restitutions (the one-particle stand-in for \"several N\"; \
                  the DEM version is zres_vs_lz_dem)."
            .into(),
        spec_item: "Z_res versus Lz for several N".into(),
        commands: vec![
            e0.command.clone(),
            e8.command.clone(),
            "pdamp plot resonance e0/sweep.csv e0.8/sweep.csv --label \"e = 0\" --label \"e = 0.8\" --x damper.gap -o zres_vs_gap.png".into(),
        ],
        reductions: s.reductions(&["duration", "gaps", "grid"]),
        size_px: size,
    })
}

fn energy_vs_gap(
    ctx: &Ctx,
    s: &Settings,
    e0: &SweepResult,
    e8: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "energy_vs_gap";
    let pick = |pts: &SweepPoints| -> Result<(Vec<f64>, Vec<f64>), StudyError> {
        let rows = resonance_points(name, pts, DAMPER_GAP)?;
        Ok(rows
            .iter()
            .map(|&(x, p)| (x, p.summary.energy_impact_j_per_cycle))
            .unzip())
    };
    let (x0, y0) = pick(&e0.points)?;
    let (_, y8) = pick(&e8.points)?;
    ctx.write_csv(
        name,
        &[
            "gap_m",
            "energy_impact_e0_j_per_cycle",
            "energy_impact_e0.8_j_per_cycle",
        ],
        &(0..x0.len())
            .map(|i| vec![x0[i], y0[i], y8[i]])
            .collect::<Vec<_>>(),
    )?;
    let mut fig = energy_figure(
        &x0,
        "gap (m)",
        &[("impacts, e = 0", &y0), ("impacts, e = 0.8", &y8)],
    );
    fig.title = "Energy dissipated by impacts per cycle at the resonance".into();
    let size = ctx.render(name, &fig)?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model: energy dissipated by impacts per forcing cycle at each gap's \
                  resonance frequency (where Z is largest)."
            .into(),
        spec_item: "energy dissipated per cycle versus Lz".into(),
        commands: vec![e0.command.clone(), e8.command.clone()],
        reductions: s.reductions(&["duration", "gaps", "grid"]),
        size_px: size,
    })
}

fn zres_vs_restitution(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
    let name = "zres_vs_restitution";
    let mut curves: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for &g in &s.restitution_gaps_m {
        let sw = ctx.sweep_split(
            &format!("impact_restitution_grid/gap{g}"),
            IMPACT_B,
            &[
                (RUN_DURATION, s.duration_s.to_string()),
                (DAMPER_GAP, g.to_string()),
            ],
            (DAMPER_RESTITUTION, &s.restitutions),
            &[(EXCITATION_FREQUENCY, s.grid_freq.vary())],
            false,
        )?;
        let (xs, zs) = resonance_amplitudes(
            &key_values(name, &sw.points, DAMPER_RESTITUTION)?,
            &sw.points.map(|s| s.amplitude_m),
        );
        for (x, zz) in xs.iter().zip(&zs) {
            rows.push(vec![g, *x, *zz]);
        }
        curves.push((format!("gap = {g} m"), xs, zs));
        commands.push(sw.command);
    }
    ctx.write_csv(name, &["gap_m", "restitution", "zres_m"], &rows)?;
    let series = curves
        .iter()
        .map(|(l, x, y)| Series { label: l, x, y })
        .collect();
    let size = ctx.render(
        name,
        &resonance_figure(series, "effective restitution e (–)"),
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model: resonance amplitude versus the effective restitution e (the \
                  one-particle counterpart of the contact damping γ_n) for several gaps; the DEM \
                  version versus γ_n for several N is zres_vs_gamma_dem."
            .into(),
        spec_item: "Z_res versus γ_n, γ_s for several N".into(),
        commands: {
            commands.push("pdamp plot resonance gap1/sweep.csv gap2/sweep.csv … --label … --x damper.restitution -o zres_vs_restitution.png".into());
            commands
        },
        reductions: s.reductions(&["duration", "restitutions", "grid"]),
        size_px: size,
    })
}

fn energy_vs_frequency(
    ctx: &Ctx,
    s: &Settings,
    sw: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "energy_vs_frequency";
    let f = sw.points.map(|s| s.frequency_hz);
    let imp = sw.points.map(|s| s.energy_impact_j_per_cycle);
    let vis = sw.points.map(|s| s.energy_viscous_j_per_cycle);
    ctx.write_csv(
        name,
        &[
            "frequency_hz",
            "energy_impact_j_per_cycle",
            "energy_viscous_j_per_cycle",
        ],
        &(0..f.len())
            .map(|i| vec![f[i], imp[i], vis[i]])
            .collect::<Vec<_>>(),
    )?;
    let fig = energy_figure(
        &f,
        "frequency f (Hz)",
        &[
            ("impacts (particle)", &imp),
            ("viscous (primary damper C)", &vis),
        ],
    );
    let size = ctx.render(name, &fig)?;
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "Impact model (e = 0, gap {SCENE_B_GAP_M} m): energy dissipated per cycle by impacts \
             and by the primary's damper C versus frequency (the DEM splits the grains' share \
             into collision and friction: energy_vs_frequency_dem)."
        ),
        spec_item: "collision vs friction energy per cycle versus f".into(),
        commands: vec![
            sw.command.clone(),
            "pdamp plot energy sweep.csv -o energy_vs_frequency.png".into(),
        ],
        reductions: s.reductions(&["freq", "duration"]),
        size_px: size,
    })
}

/// Draws a bed-motion figure of the last `periods` forcing periods of a recorded run and writes
/// its CSV.
///
/// # Errors
/// [`StudyError`] from rendering or writing.
pub fn draw_bed_motion(
    ctx: &Ctx,
    name: &str,
    r: &super::pipeline::Recorded,
) -> Result<(u32, u32), StudyError> {
    let band = (!r.grain_zmin_m.is_empty()).then_some((&r.grain_zmin_m[..], &r.grain_zmax_m[..]));
    let rows: Vec<Vec<f64>> = (0..r.time_s.len())
        .map(|i| {
            let mut v = vec![
                r.time_s[i],
                r.floor_z_m[i],
                r.ceiling_z_m[i],
                r.grain_z_m[i],
                r.grain_force_n[i],
            ];
            if let Some((lo, hi)) = band {
                v.extend([lo[i], hi[i]]);
            }
            v
        })
        .collect();
    let mut header = vec![
        "time_s",
        "floor_z_m",
        "ceiling_z_m",
        "grain_z_m",
        "grain_force_n",
    ];
    if band.is_some() {
        header.extend(["grain_zmin_m", "grain_zmax_m"]);
    }
    ctx.write_csv(name, &header, &rows)?;
    ctx.render(
        name,
        &BedMotionFigure {
            time_s: &r.time_s,
            floor_z_m: &r.floor_z_m,
            ceiling_z_m: &r.ceiling_z_m,
            grain_z_m: &r.grain_z_m,
            grain_band: band,
            grain_force_n: Some(&r.grain_force_n),
        },
    )
}

fn bed_motion_impact(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
    let name = "bed_motion";
    let f = 15.0;
    let periods = 60.0;
    let set = [
        (EXCITATION_FREQUENCY, f.to_string()),
        (RUN_PERIODS, periods.to_string()),
    ];
    let scene = scene_with(name, IMPACT_B, &set)?;
    let r = record_run(name, &scene, 1e-4, (periods - 4.0) / f)?;
    let size = draw_bed_motion(ctx, name, &r)?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0, gap 0.0835 m) at 15 Hz, last 4 periods of 60: floor and \
                  ceiling, the particle, and its contact force on the box (impulses at impacts \
                  are not drawn). The DEM version with the grain band is bed_motion_dem."
            .into(),
        spec_item: "bed motion (floor and ceiling, grain band, centre of mass, grain force)".into(),
        commands: vec![
            simulate_command(IMPACT_B, &set, &ctx.path("data/bed_motion")),
            "pdamp plot bed-motion DIR/series.csv --from-time 3.7333 -o bed_motion.png".into(),
        ],
        reductions: if s.mode == Mode::Full {
            vec![]
        } else {
            vec!["none (the impact model is cheap)".into()]
        },
        size_px: size,
    })
}

/// Poincaré section, spectrum and delay reconstruction of the particle at forcing frequency `f`.
fn per_frequency(ctx: &Ctx, s: &Settings, f: f64) -> Result<Vec<FigureRecord>, StudyError> {
    let tag = format!("f{f}");
    let step = format!("per-frequency {tag}");
    let periods = s.series_periods as f64;
    let set = [
        (DAMPER_RESTITUTION, "0.8".to_string()),
        (EXCITATION_FREQUENCY, f.to_string()),
        (RUN_PERIODS, periods.to_string()),
    ];
    let scene = scene_with(&step, IMPACT_B, &set)?;
    let per_period = 64.0;
    let dt = 1.0 / (f * per_period);
    let from = 0.5 * periods / f;
    let (r, summary) = record_run_summary(&step, &scene, dt, from)?;
    let z = &r.grain_z_m;
    let sim = simulate_command(IMPACT_B, &set, &ctx.path(&format!("data/series_{tag}")));
    let reductions = s.reductions(&["series"]);
    let mut out = Vec::new();

    // Poincaré: the exact state (z, ż) at t = kT over the analysis window (closed form of the
    // event-driven model, never a resampled series)
    let (px, py): (Vec<f64>, Vec<f64>) = summary
        .strobe
        .iter()
        .map(|p| (p.grain_z_m, p.grain_v_m_s))
        .unzip();
    let name = format!("poincare_{tag}");
    ctx.write_csv(
        &name,
        &["grain_z_m", "grain_v_m_s"],
        &(0..px.len())
            .map(|i| vec![px[i], py[i]])
            .collect::<Vec<_>>(),
    )?;
    let size = ctx.render(
        &name,
        &PoincareFigure {
            x: &px,
            y: &py,
            x_label: "particle height z (m)".into(),
            y_label: "particle velocity ż (m/s)".into(),
        },
    )?;
    out.push(FigureRecord {
        name: name.clone(),
        caption: format!(
            "Impact model (e = 0.8, gap 0.0835 m) at {f} Hz: exact stroboscopic Poincaré \
             section (z, ż) at t = kT over the last {} periods ({} points).",
            periods / 2.0,
            px.len()
        ),
        spec_item: "per frequency: stroboscopic Poincaré section".into(),
        commands: vec![
            sim.clone(),
            format!(
                "pdamp plot poincare DIR/strobe.csv --x grain_z_m --y grain_v_m_s -o {name}.png"
            ),
        ],
        reductions: reductions.clone(),
        size_px: size,
    });

    // spectrum
    let sp = power_spectrum(
        z,
        &SpectrumOptions {
            dt_s: Some(dt),
            ..Default::default()
        },
    )
    .map_err(|e| StudyError::step(&step, e))?;
    let keep: Vec<usize> = (0..sp.frequency.len())
        .filter(|&i| sp.frequency[i] <= 6.0 * f && sp.frequency[i] > 0.0)
        .collect();
    let fx: Vec<f64> = keep.iter().map(|&i| sp.frequency[i]).collect();
    let pw: Vec<f64> = keep.iter().map(|&i| sp.power[i]).collect();
    let name = format!("spectrum_{tag}");
    ctx.write_csv(
        &name,
        &["frequency_hz", "power_m2"],
        &(0..fx.len())
            .map(|i| vec![fx[i], pw[i]])
            .collect::<Vec<_>>(),
    )?;
    let size = ctx.render(
        &name,
        &SpectrumFigure {
            frequency_hz: &fx,
            power: &pw,
            forcing_hz: Some(f),
            power_label: "power of z (m² per bin, Hann window)".into(),
        },
    )?;
    out.push(FigureRecord {
        name: name.clone(),
        caption: format!(
            "Same run: power spectrum of the particle height (steady state, Hann window), up \
             to 6 f; dashed lines at the harmonics of f = {f} Hz."
        ),
        spec_item: "per frequency: spectrum".into(),
        commands: vec![
            sim.clone(),
            format!("pdamp spectrum DIR/series.csv --column grain_z_m > spectrum.csv && pdamp plot spectrum spectrum.csv --forcing-hz {f} -o {name}.png"),
        ],
        reductions: reductions.clone(),
        size_px: size,
    });

    // delay reconstruction with τ from the first minimum of the mutual information
    let mi = mutual_information(
        z,
        &MutualInformationOptions {
            bins: 16,
            max_lag: per_period as usize,
        },
    )
    .map_err(|e| StudyError::step(&step, e))?;
    let lag = mi.first_minimum.unwrap_or(per_period as usize / 4).max(1);
    let name = format!("reconstruction_{tag}");
    let n = z.len().min(40 * per_period as usize);
    let zs = &z[z.len() - n..];
    ctx.write_csv(
        &name,
        &["s_n_m", "s_n_plus_lag_m"],
        &(0..n - lag)
            .map(|i| vec![zs[i], zs[i + lag]])
            .collect::<Vec<_>>(),
    )?;
    let size = ctx.render(
        &name,
        &ReconstructionFigure {
            series: zs,
            lag,
            dt_s: Some(dt),
            value_label: "particle height z (m)".into(),
        },
    )?;
    out.push(FigureRecord {
        name: name.clone(),
        caption: format!(
            "Same run: 2-D delay reconstruction (z_n, z_(n+τ)) of the last 40 periods, τ = {lag} \
             samples = {:.4} s (first minimum of the mutual information, (4.1.5)).",
            lag as f64 * dt
        ),
        spec_item: "per frequency: 2-D projection of the delay reconstruction".into(),
        commands: vec![
            sim,
            format!("pdamp plot reconstruction DIR/series.csv --column grain_z_m --lag {lag} -o {name}.png"),
        ],
        reductions,
        size_px: size,
    });
    Ok(out)
}

/// The columns of an analysed sweep that the regime figures draw.
struct RegimeColumns {
    f: Vec<f64>,
    y: Vec<f64>,
    regime: Vec<String>,
    period: Vec<Option<u32>>,
    mle: Vec<Option<f64>>,
    mle_se: Vec<Option<f64>>,
    model: Vec<Option<f64>>,
    model_se: Vec<Option<f64>>,
}

/// Frequency, a second column, regime, period and the data and model exponents (with standard
/// errors) of a sweep, also written to `NAME.csv` (`frequency_hz,<y_header>,regime,period,
/// mle_per_s,mle_stderr_per_s,model_mle_per_s,model_mle_stderr_per_s`; empty cells: not
/// estimated) next to the figure.
fn regime_columns(
    ctx: &Ctx,
    name: &str,
    sw: &SweepResult,
    y: Vec<f64>,
    y_header: &str,
) -> Result<RegimeColumns, StudyError> {
    let pts = &sw.points;
    let f = pts.map(|s| s.frequency_hz);
    // a value as sweep.csv keeps it: non-finite values are not estimates
    let opt = |pick: fn(&crate::model::RunAnalysis) -> Option<f64>| -> Vec<Option<f64>> {
        pts.iter()
            .map(|p| {
                p.summary
                    .analysis
                    .as_ref()
                    .and_then(pick)
                    .filter(|v| v.is_finite())
            })
            .collect()
    };
    let c = RegimeColumns {
        regime: pts
            .iter()
            .map(|p| {
                p.summary
                    .analysis
                    .as_ref()
                    .map_or("", |a| a.regime.as_str())
                    .to_string()
            })
            .collect(),
        period: opt(|a| a.period)
            .into_iter()
            .map(|p| {
                p.filter(|p| *p >= 1.0 && p.fract() == 0.0)
                    .map(|p| p as u32)
            })
            .collect(),
        mle: opt(|a| a.data_mle_per_s),
        mle_se: opt(|a| a.data_mle_stderr_per_s),
        model: opt(|a| a.model_mle_per_s),
        model_se: opt(|a| a.model_mle_stderr_per_s),
        f,
        y,
    };
    let cell = |v: Option<f64>| v.map(|m| m.to_string()).unwrap_or_default();
    let mut text = format!(
        "frequency_hz,{y_header},regime,period,mle_per_s,mle_stderr_per_s,model_mle_per_s,\
         model_mle_stderr_per_s\n"
    );
    for i in 0..c.f.len() {
        text += &format!(
            "{},{},{},{},{},{},{},{}\n",
            c.f[i],
            c.y[i],
            c.regime[i],
            c.period[i].map(|p| p.to_string()).unwrap_or_default(),
            cell(c.mle[i]),
            cell(c.mle_se[i]),
            cell(c.model[i]),
            cell(c.model_se[i]),
        );
    }
    ctx.write_text(&format!("{name}.csv"), &text)?;
    Ok(c)
}

fn regime_frf(ctx: &Ctx, s: &Settings, sw: &SweepResult) -> Result<FigureRecord, StudyError> {
    let name = "regime_frf";
    let amplitude = sw.points.map(|s| s.amplitude_m);
    let c = regime_columns(ctx, name, sw, amplitude, "amplitude_m")?;
    let size = ctx.render(
        name,
        &RegimeFrfFigure {
            frequency_hz: &c.f,
            amplitude_m: &c.y,
            regime: &c.regime,
            period: Some(&c.period),
            data: Some(Exponents {
                per_s: &c.mle,
                stderr_per_s: Some(&c.mle_se),
            }),
            model: Some(Exponents {
                per_s: &c.model,
                stderr_per_s: Some(&c.model_se),
            }),
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8, gap 0.0835 m): FRF coloured by the regime of the \
                  particle's steady state (upper panel); below, the largest Lyapunov exponent \
                  (1/s) of the model's stroboscopic map from tangent dynamics and the one \
                  estimated from the data (Kantz), each ± 1 standard error; frequencies \
                  without an estimate have no marker."
            .into(),
        spec_item: "the FRF with regime bands and the Lyapunov exponent overlaid".into(),
        commands: vec![
            sw.command.clone(),
            "pdamp plot regime-frf sweep.csv -o regime_frf.png".into(),
        ],
        reductions: s.reductions(&["regime"]),
        size_px: size,
    })
}

fn bifurcation(ctx: &Ctx, s: &Settings, sw: &SweepResult) -> Result<FigureRecord, StudyError> {
    let name = "bifurcation";
    let (f, z): (Vec<f64>, Vec<f64>) = sw
        .points
        .iter()
        .flat_map(|p| {
            let f = p.summary.frequency_hz;
            p.summary.strobe.iter().map(move |s| (f, s.grain_z_m))
        })
        .unzip();
    if f.is_empty() {
        return Err(StudyError::step(name, "the sweep wrote no strobe.csv rows"));
    }
    ctx.write_csv(
        name,
        &["frequency_hz", "grain_z_m"],
        &(0..f.len()).map(|i| vec![f[i], z[i]]).collect::<Vec<_>>(),
    )?;
    let size = ctx.render(
        name,
        &BifurcationFigure {
            x: &f,
            z_m: &z,
            x_label: "frequency f (Hz)".into(),
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8, gap 0.0835 m): particle height strobed once per \
                  forcing period in the steady state, versus frequency."
            .into(),
        spec_item: "a bifurcation-style diagram (strobed z_cm versus f)".into(),
        commands: vec![
            sw.command.clone(),
            "pdamp plot bifurcation strobe.csv -o bifurcation.png".into(),
        ],
        reductions: s.reductions(&["regime"]),
        size_px: size,
    })
}

fn regime_map(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
    let name = "regime_map";
    let sw = ctx.sweep_split(
        "impact_regime_map_e0.8",
        IMPACT_B,
        &[
            (DAMPER_RESTITUTION, "0.8".into()),
            (RUN_DURATION, s.regime_duration_s.to_string()),
        ],
        (DAMPER_GAP, &s.map_gaps_m),
        &[(EXCITATION_FREQUENCY, s.map_freq.vary())],
        true,
    )?;
    let gap = key_values(name, &sw.points, DAMPER_GAP)?;
    let c = regime_columns(ctx, name, &sw, gap, "gap_m")?;
    // chaotic cells are shaded by the model's exponent (the data's where the model has none)
    let shade: Vec<Option<f64>> = c.model.iter().zip(&c.mle).map(|(m, d)| m.or(*d)).collect();
    let size = ctx.render(
        name,
        &RegimeMapFigure {
            x: &c.f,
            y: &c.y,
            regime: &c.regime,
            period: Some(&c.period),
            mle_per_s: Some(&shade),
            mle_label: "model λ (1/s)".into(),
            x_label: "frequency f (Hz)".into(),
            y_label: "gap (m)".into(),
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8): regime of the particle's steady state over frequency × \
                  gap (one row per gap); chaotic cells shaded by the model's largest Lyapunov \
                  exponent, periodic cells of period ≥ 2 darker and numbered with the period; \
                  the values are in regime_map.csv."
            .into(),
        spec_item: "regimes over frequency and container height (SPEC §4)".into(),
        commands: vec![
            sw.command.clone(),
            "pdamp plot regime-map sweep.csv --x excitation.frequency --y damper.gap -o regime_map.png".into(),
        ],
        reductions: s.reductions(&["map"]),
        size_px: size,
    })
}

fn frf_figure(
    ctx: &Ctx,
    s: &Settings,
    e0: &SweepResult,
    e8: &SweepResult,
    dem: Option<&SweepResult>,
) -> Result<FigureRecord, StudyError> {
    let name = "frf";
    let f0 = e0.points.map(|s| s.frequency_hz);
    let z0 = e0.points.map(|s| s.amplitude_m);
    let f8 = e8.points.map(|s| s.frequency_hz);
    let z8 = e8.points.map(|s| s.amplitude_m);
    let (fd, zd) = match dem {
        Some(d) => (
            d.points.map(|s| s.frequency_hz),
            d.points.map(|s| s.amplitude_m),
        ),
        None => (vec![], vec![]),
    };
    let mut text = String::from("model,frequency_hz,amplitude_m\n");
    for (label, f, z) in [
        ("impact_e0", &f0, &z0),
        ("impact_e0.8", &f8, &z8),
        ("dem", &fd, &zd),
    ] {
        for i in 0..f.len() {
            text += &format!("{label},{},{}\n", f[i], z[i]);
        }
    }
    ctx.write_text(&format!("{name}.csv"), &text)?;
    let mut series = vec![
        Series {
            label: "impact model, e = 0",
            x: &f0,
            y: &z0,
        },
        Series {
            label: "impact model, e = 0.8",
            x: &f8,
            y: &z8,
        },
    ];
    if dem.is_some() {
        series.push(Series {
            label: "DEM, N = 250",
            x: &fd,
            y: &zd,
        });
    }
    let size = ctx.render(
        name,
        &FrfFigure {
            series,
            reference: Some(SCENE_B.reference()),
        },
    )?;
    let mut commands = vec![e0.command.clone(), e8.command.clone()];
    let mut reductions = s.reductions(&["freq", "duration"]);
    if let Some(d) = dem {
        commands.push(d.command.clone());
        reductions.extend(s.reductions(&["dem"]));
    }
    commands.push(
        "pdamp plot frf e0/sweep.csv e0.8/sweep.csv [dem/sweep.csv] --label ... --mass 2.37 --particle-mass 0.227 --stiffness 21500 --damping 7.6 --base-amplitude 4.5e-3 -o frf.png".into(),
    );
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "Scene B, Lz = 0.1225 m: frequency response of the primary with the one-particle \
             model (gap {SCENE_B_GAP_M} m, e = 0 and 0.8){}, and the reference curves (2.1.21) \
             for M and M + m_p.",
            if dem.is_some() {
                " and the granular DEM bed"
            } else {
                ""
            }
        ),
        spec_item: "Frequency response Z(f) with the reference curves for M and M + m_p; the \
                    one-particle model's FRF against the granular one"
            .into(),
        commands,
        reductions,
        size_px: size,
    })
}

/// A lines figure with explicit labels (used by the DEM figures too).
pub fn lines<'a>(
    series: Vec<Series<'a>>,
    x_label: &str,
    y_label: &str,
    y_scale: f64,
    title: &str,
) -> LinesFigure<'a> {
    LinesFigure {
        series,
        x_label: x_label.into(),
        y_label: y_label.into(),
        y_scale,
        title: title.into(),
        kind: "lines",
    }
}
