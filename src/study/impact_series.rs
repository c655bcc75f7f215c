//! Single impact-model runs: the bed motion at 15 Hz, and per forcing frequency the exact
//! Poincaré section, the spectrum and the delay reconstruction of the particle.

use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use crate::analysis::spectrum::{power_spectrum, SpectrumOptions};
use crate::error::StudyError;
use crate::plot::poincare::PoincareFigure;
use crate::plot::reconstruction::ReconstructionFigure;
use crate::plot::spectrum::SpectrumFigure;
use crate::scene::keys::{
    DAMPER_RESTITUTION, EXCITATION_FREQUENCY, RUN_PERIODS, RUN_SAMPLE_INTERVAL,
};

use super::command::Command;
use super::kit::draw_bed_motion;
use super::pipeline::{
    record_run, record_run_summary, scene_with, simulate_command, Ctx, FigureRecord, IMPACT_B,
};
use super::settings::{Mode, Settings};

pub(super) fn bed_motion_impact(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
    let name = "bed_motion";
    let f = 15.0;
    let periods = 60.0;
    let set = [
        (EXCITATION_FREQUENCY, f.to_string()),
        (RUN_PERIODS, periods.to_string()),
    ];
    let scene = scene_with(name, IMPACT_B, &set)?;
    let from = (periods - 4.0) / f;
    let r = record_run(name, &scene, 1e-4, from)?;
    let size = draw_bed_motion(ctx, name, &r)?;
    let dir = ctx.path("data/bed_motion");
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0, gap 0.0835 m) at 15 Hz, last 4 periods of 60: floor and \
                  ceiling, the particle, and its contact force on the box (impulses at impacts \
                  are not drawn). The DEM version with the grain band is bed_motion_dem."
            .into(),
        spec_item: "bed motion (floor and ceiling, grain band, centre of mass, grain force)".into(),
        commands: vec![
            simulate_command(IMPACT_B, &set, &dir),
            Command::plot(
                "bed-motion",
                &[dir.join("series.csv")],
                &ctx.path(&format!("{name}.png")),
            )
            .opt("from-time", from),
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
pub(super) fn per_frequency(
    ctx: &Ctx,
    s: &Settings,
    f: f64,
) -> Result<Vec<FigureRecord>, StudyError> {
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
    // the run again, into a directory, sampled as the figures' series (dt = T/64)
    let dir = ctx.path(&format!("data/series_{tag}"));
    let sim_set = [&set[..], &[(RUN_SAMPLE_INTERVAL, dt.to_string())]].concat();
    let sim = simulate_command(IMPACT_B, &sim_set, &dir);
    let series_csv = dir.join("series.csv");
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
            Command::plot(
                "poincare",
                &[dir.join("strobe.csv")],
                &ctx.path(&format!("{name}.png")),
            )
            .opt("x", "grain_z_m")
            .opt("y", "grain_v_m_s"),
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
            Command::new(["spectrum"])
                .path(&series_csv)
                .opt("column", "grain_z_m")
                .opt("dt", dt)
                .to_file(&dir.join("spectrum.csv")),
            Command::plot(
                "spectrum",
                &[dir.join("spectrum.csv")],
                &ctx.path(&format!("{name}.png")),
            )
            .opt("forcing-hz", f),
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
            Command::plot(
                "reconstruction",
                &[&series_csv],
                &ctx.path(&format!("{name}.png")),
            )
            .opt("column", "grain_z_m")
            .opt("lag", lag),
        ],
        reductions,
        size_px: size,
    });
    Ok(out)
}
