//! The impact model's frequency responses (e = 0 and 0.8), drawn with the DEM's when it ran
//! and the reference curves (2.1.21), and the energy split along f.

use crate::error::StudyError;

use super::command::Command;
use crate::plot::energy::energy_figure;
use crate::plot::frf::FrfFigure;
use crate::plot::Series;
use crate::scene::keys::{DAMPER_RESTITUTION, EXCITATION_FREQUENCY, RUN_DURATION};

use super::kit::SCENE_B;
use super::pipeline::{
    BundledScene, Ctx, FigureRecord, SweepResult, COMMITTED_DATA, DEM_B_REFERENCE,
    DEM_B_REFERENCE_E100, IMPACT_B,
};
use super::settings::Settings;
use super::settings::SCENE_B_GAP_M;

pub(super) fn impact_frf_sweep(ctx: &Ctx, s: &Settings, e: f64) -> Result<SweepResult, StudyError> {
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

pub(super) fn energy_vs_frequency(
    ctx: &Ctx,
    s: &Settings,
    sw: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "energy_vs_frequency";
    let f = sw.points.map(|s| s.frequency_hz);
    let input = sw.points.map(|s| s.energy_input_j_per_cycle);
    let imp = sw.points.map(|s| s.energy_impact_j_per_cycle);
    let vis = sw.points.map(|s| s.energy_viscous_j_per_cycle);
    ctx.write_csv(
        name,
        &[
            "frequency_hz",
            "energy_input_j_per_cycle",
            "energy_impact_j_per_cycle",
            "energy_viscous_j_per_cycle",
        ],
        &(0..f.len())
            .map(|i| vec![f[i], input[i], imp[i], vis[i]])
            .collect::<Vec<_>>(),
    )?;
    let fig = energy_figure(
        &f,
        "frequency f (Hz)",
        &[
            ("input: base work", &input),
            ("dissipated: impacts", &imp),
            ("dissipated: primary's damper C", &vis),
        ],
    );
    let size = ctx.render(name, &fig)?;
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "Impact model (e = 0, gap {SCENE_B_GAP_M} m): energy put in per cycle by the base, \
             and dissipated by impacts and by the primary's damper C, versus frequency (the DEM splits the grains' share \
             into collision and friction: energy_vs_frequency_dem)."
        ),
        spec_item: "collision vs friction energy per cycle versus f".into(),
        commands: sw.commands_then_plot("energy", &ctx.path(&format!("{name}.png"))),
        reductions: s.reductions(&["freq", "duration"]),
        size_px: size,
    })
}

/// The FRF of a converged scene whose points only the speed–accuracy study computes (the
/// real-steel reference, `model = dem_steel` in frf.csv; its E ÷ 100 copy, `dem_e100`): every
/// stored point of `bundled`'s scene under the output's sweeps or the committed ones, by
/// increasing frequency (none where nothing is stored).
fn stored_frf(ctx: &Ctx, bundled: BundledScene) -> (Vec<f64>, Vec<f64>) {
    let Ok(scene) = crate::scene::SceneSource::parse(bundled.text) else {
        return (vec![], vec![]);
    };
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for root in [ctx.path("data"), std::path::PathBuf::from(COMMITTED_DATA)] {
        let Ok(cat) = crate::sweep::Catalog::scan(&root) else {
            continue;
        };
        let found = cat
            .points_of(&scene, true, EXCITATION_FREQUENCY)
            .unwrap_or_default();
        for p in found
            .iter()
            .filter(|p| p.point.physics == crate::model::PHYSICS_REVISION)
        {
            let s = &p.point.summary;
            if !pts.iter().any(|(f, _)| *f == s.frequency_hz) {
                pts.push((s.frequency_hz, s.amplitude_m));
            }
        }
    }
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.into_iter().unzip()
}

pub(super) fn frf_figure(
    ctx: &Ctx,
    s: &Settings,
    e0: &SweepResult,
    e8: &SweepResult,
    dem_run: Option<(&SweepResult, &[&str])>,
) -> Result<FigureRecord, StudyError> {
    let name = "frf";
    let dem = dem_run.map(|(d, _)| d);
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
    let (fs, zs) = stored_frf(ctx, DEM_B_REFERENCE);
    let (fh, zh) = stored_frf(ctx, DEM_B_REFERENCE_E100);
    let mut rows = Vec::new();
    for (label, f, z) in [
        ("impact_e0", &f0, &z0),
        ("impact_e0.8", &f8, &z8),
        ("dem", &fd, &zd),
        ("dem_steel", &fs, &zs),
        ("dem_e100", &fh, &zh),
    ] {
        for i in 0..f.len() {
            rows.push(vec![label.to_string(), f[i].to_string(), z[i].to_string()]);
        }
    }
    ctx.write_table(name, &["model", "frequency_hz", "amplitude_m"], rows)?;
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
            label: "DEM, N = 250, steel ÷ 1000",
            x: &fd,
            y: &zd,
        });
    }
    if !fs.is_empty() {
        series.push(Series {
            label: "DEM, N = 250, real steel",
            x: &fs,
            y: &zs,
        });
    }
    if !fh.is_empty() {
        series.push(Series {
            label: "DEM, N = 250, steel ÷ 100, t_s/100",
            x: &fh,
            y: &zh,
        });
    }
    let labels: Vec<&str> = series.iter().map(|sr| sr.label).collect();
    let size = ctx.render(
        name,
        &FrfFigure {
            series,
            reference: Some(SCENE_B.reference()),
            fitted: Vec::new(),
        },
    )?;
    let mut commands = [e0.commands.clone(), e8.commands.clone()].concat();
    let mut reductions = s.reductions(&["freq", "duration"]);
    let mut csv = [e0.csv.clone(), e8.csv.clone()].concat();
    if let Some(d) = dem {
        commands.extend(d.commands.iter().cloned());
        csv.extend(d.csv.iter().cloned());
        reductions.extend(s.reductions(dem_run.map_or(&[][..], |(_, keys)| keys)));
    }
    let mut plot = Command::plot("frf", &csv, &ctx.path(&format!("{name}.png")));
    for l in labels {
        plot = plot.opt("label", l);
    }
    let b = SCENE_B;
    commands.push(
        plot.opt("mass", b.primary.mass_kg)
            .opt("particle-mass", b.particle_mass_kg)
            .opt("stiffness", b.primary.stiffness_n_m)
            .opt("damping", b.primary.damping_n_s_m)
            .opt("base-amplitude", b.base_amplitude_m),
    );
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "Scene B, Lz = 0.1225 m: frequency response of the primary with the one-particle \
             model (gap {SCENE_B_GAP_M} m, e = 0 and 0.8){}{}{}, and the reference curves (2.1.21) \
             for M and M + m_p.",
            if dem.is_some() {
                " and the granular DEM bed (steel softened 1000×)"
            } else {
                ""
            },
            if fs.is_empty() {
                String::new()
            } else {
                format!(
                    ", the real-steel bed at {} frequencies (the speed–accuracy reference, \
                     {}, committed points under {COMMITTED_DATA})",
                    fs.len(),
                    DEM_B_REFERENCE.path
                )
            },
            if fh.is_empty() {
                String::new()
            } else {
                format!(
                    ", the same bed softened 100× at {} frequencies ({}, 200 periods at \
                     t_s/100)",
                    fh.len(),
                    DEM_B_REFERENCE_E100.path
                )
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
