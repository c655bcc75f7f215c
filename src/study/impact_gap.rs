//! The impact model over the gap and the restitution: effective mass and damping per gap,
//! Z_res and the impact energy at resonance versus the gap, Z_res versus e.

use crate::error::StudyError;
use crate::plot::energy::energy_figure;
use crate::plot::resonance::resonance_figure;
use crate::plot::Series;
use crate::scene::keys::{DAMPER_GAP, DAMPER_RESTITUTION, EXCITATION_FREQUENCY, RUN_DURATION};
use crate::sweep::{SweepPoint, SweepPoints};

use super::check::EffectiveRow;
use super::kit::{draw_effective, effective_commands, fit_groups, resonance_curve};
use super::pipeline::{Ctx, FigureRecord, SweepResult, IMPACT_B};
use super::settings::Settings;

pub(super) fn impact_gap_grid(ctx: &Ctx, s: &Settings, e: f64) -> Result<SweepResult, StudyError> {
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

pub(super) fn effective_figure(
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
            commands: [
                grid.commands.clone(),
                effective_commands(ctx, name, &grid.csv, "gap_m"),
            ]
            .concat(),
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
) -> Result<Vec<(f64, &'a SweepPoint)>, StudyError> {
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

pub(super) fn zres_vs_gap(
    ctx: &Ctx,
    s: &Settings,
    e0: &SweepResult,
    e8: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "zres_vs_gap";
    let (x0, z0) = resonance_curve(name, &e0.points, DAMPER_GAP)?;
    let (x8, z8) = resonance_curve(name, &e8.points, DAMPER_GAP)?;
    let rows: Vec<Vec<f64>> = (0..x0.len()).map(|i| vec![x0[i], z0[i], z8[i]]).collect();
    ctx.write_csv(name, &["gap_m", "zres_e0_m", "zres_e0.8_m"], &rows)?;
    // drawn in mm, like the amplitude
    let (x0, x8) = (to_mm(&x0), to_mm(&x8));
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
            "gap (mm)",
        ),
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model: resonance amplitude Z_res (largest Z over the frequency grid) \
                  versus the gap for two restitutions (the one-particle stand-in for \"several N\"; \
                  the DEM version is zres_vs_lz_dem)."
            .into(),
        spec_item: "Z_res versus Lz for several N".into(),
        commands: [e0.commands.clone(), e8.commands.clone()].concat(),
        reductions: s.reductions(&["duration", "gaps", "grid"]),
        size_px: size,
    })
}

pub(super) fn energy_vs_gap(
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
    let x0 = to_mm(&x0);
    let mut fig = energy_figure(
        &x0,
        "gap (mm)",
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
        commands: [e0.commands.clone(), e8.commands.clone()].concat(),
        reductions: s.reductions(&["duration", "gaps", "grid"]),
        size_px: size,
    })
}

pub(super) fn zres_vs_restitution(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
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
        let (xs, zs) = resonance_curve(name, &sw.points, DAMPER_RESTITUTION)?;
        for (x, zz) in xs.iter().zip(&zs) {
            rows.push(vec![g, *x, *zz]);
        }
        curves.push((format!("gap = {g} m"), xs, zs));
        commands.extend(sw.commands);
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
        commands,
        reductions: s.reductions(&["duration", "restitutions", "grid"]),
        size_px: size,
    })
}

/// Lengths in metres as millimetres (the unit of every length drawn in this figure family).
pub(super) fn to_mm(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| 1e3 * x).collect()
}
