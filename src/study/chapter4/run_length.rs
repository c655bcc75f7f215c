//! `ch4_run_length`: the check frequencies again with every run continued to twice its length
//! (the same trajectory, see `ch4_set`), verdict by verdict and amplitude by amplitude.

use super::points::{opt_cell, Point};
use super::record::Info;
use super::runs::length_text;
use crate::error::StudyError;
use crate::plot::lines::LinesFigure;
use crate::plot::Series;
use crate::study::pipeline::{FigureRecord, SweepResult};

pub(super) fn run_length(
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
