//! The figure set of SPEC §7 for scene B (Sánchez 2012 §3.2), headless: sweeps through
//! [`crate::sweep`] (resumable, under `OUT/data/`), fits of (2.1.21), figures through
//! [`crate::plot`], and `OUT/README.md` saying which command made each figure and how it
//! departs from the source's parameters.
//!
//! Order: impact-model sweeps (cheap) → their figures → DEM sweeps and figures (if the DEM
//! model is in this build and the mode includes them) → the README.

use crate::error::StudyError;

use super::command::Command;
use super::options::{ReproduceOptions, ReproduceReport};
use super::pipeline::{Ctx, SweepResult};
use super::{dem_figures, impact_frf, impact_gap, impact_regimes, impact_series};

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
        points: Default::default(),
    };
    let s = &opts.settings;
    let want = |name: &str| opts.wants(name);
    let mut figures = Vec::new();
    let mut skipped = Vec::new();
    let mut effective = Vec::new();

    // ---- impact model (SPEC §3) ----
    let need_frf = want("frf") || want("energy_vs_frequency");
    let frf_e0 = need_frf
        .then(|| impact_frf::impact_frf_sweep(&ctx, s, 0.0))
        .transpose()?;
    let frf_e8 = want("frf")
        .then(|| impact_frf::impact_frf_sweep(&ctx, s, 0.8))
        .transpose()?;
    let need_grid = want("effective") || want("zres_vs_gap") || want("energy_vs_gap");
    if need_grid {
        let grid_e0 = impact_gap::impact_gap_grid(&ctx, s, 0.0)?;
        let (rec, rows) = impact_gap::effective_figure(&ctx, s, &grid_e0)?;
        effective = rows;
        if want("effective") {
            figures.push(rec);
        }
        if want("zres_vs_gap") || want("energy_vs_gap") {
            let grid_e8 = impact_gap::impact_gap_grid(&ctx, s, 0.8)?;
            if want("zres_vs_gap") {
                figures.push(impact_gap::zres_vs_gap(&ctx, s, &grid_e0, &grid_e8)?);
            }
            if want("energy_vs_gap") {
                figures.push(impact_gap::energy_vs_gap(&ctx, s, &grid_e0, &grid_e8)?);
            }
        }
    }
    if want("zres_vs_restitution") {
        figures.push(impact_gap::zres_vs_restitution(&ctx, s)?);
    }
    if let (true, Some(e0)) = (want("energy_vs_frequency"), &frf_e0) {
        figures.push(impact_frf::energy_vs_frequency(&ctx, s, e0)?);
    }
    if want("bed_motion") {
        figures.push(impact_series::bed_motion_impact(&ctx, s)?);
    }
    if want("poincare") || want("spectrum") || want("reconstruction") {
        for &f in &s.series_freqs_hz {
            figures.extend(impact_series::per_frequency(&ctx, s, f)?);
        }
    }
    if want("regime_frf") || want("bifurcation") {
        let regime = impact_regimes::regime_sweep(&ctx, s)?;
        if want("regime_frf") {
            figures.push(impact_regimes::regime_frf(&ctx, s, &regime)?);
        }
        if want("bifurcation") {
            figures.push(impact_regimes::bifurcation(&ctx, s, &regime)?);
        }
    }
    if want("regime_map") {
        figures.push(impact_regimes::regime_map(&ctx, s)?);
    }

    // ---- DEM (SPEC §2), the linear-DEM paper's dampers, and the source's chapter 4 ----
    // the three parts run side by side, so that the two cores stay busy through every
    // sweep's last points: the papers' long single runs (the bean bag, Saeki's acrylic bed)
    // start first and the many short points of the other two fill the other core (results do
    // not depend on the order)
    let (papers, (ch4, dem)) = rayon::join(
        || papers_part(&ctx, opts, &want),
        || {
            rayon::join(
                || chapter4_part(&ctx, opts, &want),
                || dem_part(&ctx, opts, &want),
            )
        },
    );
    let (dem, papers, Chapter4Part(ch4)) = (dem?, papers?, ch4?);
    figures.extend(dem.figures);
    let effective_dem = dem.effective_dem;
    skipped.extend(dem.skipped);
    figures.extend(ch4.figures);
    skipped.extend(ch4.skipped);
    figures.extend(papers.figures);
    skipped.extend(papers.skipped);
    // the chapter-4 runs (a fixed number of periods per point) are the converged DEM
    // frequency response; the short drives of the DEM figure set are not
    // (with the reductions of the run it comes from)
    let dem_frf = match (ch4.sweep, dem.frf) {
        (Some(c), _) => Some((c, &["dem_material", "dem_ch4"][..])),
        (None, d) => d.map(|d| (d, &["dem"][..])),
    };
    if let (Some(e0), Some(e8)) = (&frf_e0, &frf_e8) {
        figures.insert(
            0,
            impact_frf::frf_figure(&ctx, s, e0, e8, dem_frf.as_ref().map(|(d, k)| (d, *k)))?,
        );
    }
    // each figure again, alone, as it was made here
    for f in &mut figures {
        let mut again = Command::reproduce(s.mode.flag(), &opts.out, &f.name);
        let default = crate::plot::FigureOptions::default();
        if (opts.figure.width, opts.figure.height) != (default.width, default.height) {
            again = again
                .opt("width", opts.figure.width)
                .opt("height", opts.figure.height);
        }
        if opts.skip_dem {
            again = again.arg("--no-dem");
        }
        f.commands.push(again);
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
        points_computed_reused: ctx.points.get(),
    };
    ctx.write_text(&opts.readme_name(), &super::readme::readme(opts, &report))?;
    Ok(report)
}

/// What one part of the DEM figure set made: its figures, the DEM frequency response it ran
/// (if any), the effective-mass rows and the parts it skipped, with why.
#[derive(Default)]
struct DemPart {
    figures: Vec<super::pipeline::FigureRecord>,
    effective_dem: Vec<super::check::EffectiveRow>,
    frf: Option<SweepResult>,
    sweep: Option<SweepResult>,
    skipped: Vec<String>,
}

/// Whether the DEM may run in this mode, run and build; otherwise `why` says why not,
/// naming `what` was skipped.
fn dem_allowed(
    what: &str,
    has_settings: bool,
    opts: &ReproduceOptions,
    why: &mut Vec<String>,
) -> bool {
    let reason = if !has_settings {
        format!(
            "not part of {} mode (use --quick or --full)",
            opts.settings.mode.as_str()
        )
    } else if opts.skip_dem {
        "--no-dem".into()
    } else if let Err(e) = dem_figures::available() {
        e.to_string()
    } else {
        return true;
    };
    why.push(format!("{what}: {reason}"));
    false
}

/// The DEM figure set of SPEC §2 (not the chapter-4 study).
fn dem_part(
    ctx: &Ctx,
    opts: &ReproduceOptions,
    want: &(dyn Fn(&str) -> bool + Sync),
) -> Result<DemPart, StudyError> {
    let s = &opts.settings;
    let mut part = DemPart::default();
    let wanted = dem_figures::NAMES.iter().any(|n| want(n)) || want("frf");
    if !wanted || !dem_allowed("DEM figures", s.dem.is_some(), opts, &mut part.skipped) {
        return Ok(part);
    }
    if let Some(d) = &s.dem {
        let out = dem_figures::all(ctx, s, d)?;
        part.figures = out.figures;
        part.effective_dem = out.effective;
        part.frf = Some(out.frf);
    }
    Ok(part)
}

/// What the chapter-4 study made (its own type, so that it cannot be mistaken for the DEM
/// figure set's part where the two are joined).
struct Chapter4Part(DemPart);

/// The source's chapter 4 (DEM regimes along f); its sweep in `sweep`.
fn chapter4_part(
    ctx: &Ctx,
    opts: &ReproduceOptions,
    want: &(dyn Fn(&str) -> bool + Sync),
) -> Result<Chapter4Part, StudyError> {
    let s = &opts.settings;
    let mut part = DemPart::default();
    let wanted = super::chapter4::NAMES.iter().any(|n| want(n));
    let settings = s
        .dem
        .as_ref()
        .and_then(|d| d.chapter4.as_ref().map(|c| (d, c)));
    let what = "chapter-4 figures";
    if !wanted || !dem_allowed(what, settings.is_some(), opts, &mut part.skipped) {
        return Ok(Chapter4Part(part));
    }
    if let Some((d, c)) = settings {
        let out = super::chapter4::all(ctx, s, d, c, want)?;
        part.figures = out.figures;
        part.sweep = Some(out.sweep);
    }
    Ok(Chapter4Part(part))
}

/// The linear-DEM paper's dampers (Saeki 2002's materials, the bean bag, Els 2009's decay).
fn papers_part(
    ctx: &Ctx,
    opts: &ReproduceOptions,
    want: &(dyn Fn(&str) -> bool + Sync),
) -> Result<DemPart, StudyError> {
    let mut part = DemPart::default();
    let saeki = super::saeki::NAMES.iter().any(|n| want(n));
    let els = super::els::NAMES.iter().any(|n| want(n));
    let bag = super::bean_bag::NAMES.iter().any(|n| want(n));
    let what = "linear-DEM paper figures";
    if !(saeki || els || bag)
        || !dem_allowed(what, opts.settings.dem.is_some(), opts, &mut part.skipped)
    {
        return Ok(part);
    }
    // the longest run (the bean bag, one point) first, the others beside it
    let (bag, (saeki, els)) = rayon::join(
        || bag.then(|| super::bean_bag::bean_bag_response(ctx)),
        || {
            rayon::join(
                || saeki.then(|| super::saeki::saeki_materials(ctx)),
                || els.then(|| super::els::els_decay(ctx)),
            )
        },
    );
    for f in [saeki, els, bag].into_iter().flatten() {
        part.figures.push(f?);
    }
    Ok(part)
}
