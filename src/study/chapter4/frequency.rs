//! The chapter-4 figures along the forcing frequency from the regime sweep:
//! `ch4_regime_frf` (Fig. 4.1: Z(f) coloured by regime, with the data Lyapunov exponent),
//! `ch4_bifurcation` (z_cm strobed once per period versus f) and `ch4_impacts` (collective
//! bed–floor and bed–ceiling impacts per cycle versus f).

use super::points::{opt_cell, Point};
use super::record::Info;
use super::runs::length_text;
use crate::analysis::regime::Regime;
use crate::error::StudyError;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::lines::LinesFigure;
use crate::plot::regime_frf::{Exponents, RegimeFrfFigure};
use crate::plot::Series;
use crate::study::command::Command;
use crate::study::pipeline::FigureRecord;

pub(super) fn regime_frf(
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
             exact section is n tight groups (a typical point within 5 % of the orbit of its \
             group on every axis), quasi-periodic for a closed curve, chaotic where it is a \
             cloud and two replicas started 1e-9 m apart separate by orders of magnitude — to \
             the cloud's size, or partly (slowly mixing) (orange: chaos phase-locked to the \
             forcing, Λ_p ≥ 0.9). Lower panel: the data \
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

pub(super) fn bifurcation(info: &Info) -> Result<FigureRecord, StudyError> {
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

pub(super) fn impacts(info: &Info, pts: &[Point]) -> Result<FigureRecord, StudyError> {
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
