//! Two runs of the same frequencies compared verdict by verdict and amplitude by amplitude:
//! `ch4_run_length` (the sweep's runs continued to twice their length: the same trajectory,
//! see `ch4_set`) and `ch4_time_step` (the same runs at a shorter time step, beside the
//! spread of the study's own initial packings and, where both steps ran the ensemble, the
//! amplitude averaged over the starts: at a chaotic frequency one start's Z is one sample of
//! the attractor, and the mean over starts is what a step changes or not).

use super::ensemble::{words_at, Ensemble};
use super::points::{opt_cell, Point};
use super::record::Info;
use super::runs::length_text;
use crate::error::StudyError;
use crate::plot::lines::LinesFigure;
use crate::plot::Series;
use crate::study::pipeline::{FigureRecord, SweepResult};

/// What is compared with the study's runs.
pub(super) struct Other<'a> {
    /// The figure's name (`ch4_run_length`, `ch4_time_step`).
    pub name: &'static str,
    /// The column suffix of the other run (`doubled`, `slower_step`).
    pub suffix: &'static str,
    /// The study's runs and the other runs in the figure's legend.
    pub labels: (String, String),
    /// The figure's title.
    pub title: &'static str,
    /// The caption's first words ("Run-length check: …"), before the agreement.
    pub what: String,
    /// The other runs' sweep and points.
    pub sweep: &'a SweepResult,
    pub points: &'a [Point],
    /// The ensembles of starts, the study's and the other runs' (when the ensemble check ran
    /// at both): the spread of the study's starts, the mean over each step's starts and their
    /// verdicts in words.
    pub starts: Option<(&'a Ensemble, Option<&'a Ensemble>)>,
}

/// Over the starts at `f`: (mean Z, (max − min) / mean), `None` without starts there.
fn over_starts(e: &Ensemble, f: f64) -> Option<(f64, f64)> {
    let a: Vec<f64> = e
        .runs
        .iter()
        .filter(|r| r.0 == f)
        .map(|r| r.2.amplitude_m)
        .collect();
    if a.is_empty() {
        return None;
    }
    let mean = a.iter().sum::<f64>() / a.len() as f64;
    let (lo, hi) = a
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    Some((mean, (hi - lo) / mean))
}

/// The columns of the starts: the study's spread and words, and with the other step's
/// ensemble both means, their change and the other's words.
fn start_cells(starts: (&Ensemble, Option<&Ensemble>), f: f64, worst: &mut f64) -> Vec<String> {
    let (mine, other) = starts;
    let m = over_starts(mine, f);
    let mut row = vec![
        m.map_or(String::new(), |m| format!("{:.3}", 100.0 * m.1)),
        words_at(&mine.words, f),
    ];
    if let Some(o) = other {
        let q = over_starts(o, f);
        row.push(m.map_or(String::new(), |m| m.0.to_string()));
        row.push(q.map_or(String::new(), |q| q.0.to_string()));
        row.push(match (m, q) {
            (Some(m), Some(q)) => {
                let c = 100.0 * (q.0 / m.0 - 1.0);
                *worst = worst.max(c.abs());
                format!("{c:.3}")
            }
            _ => String::new(),
        });
        row.push(words_at(&o.words, f));
    }
    row
}

/// Writes `<name>.csv` and draws `<name>.png`: both runs' verdicts and amplitudes per
/// frequency.
///
/// # Errors
/// [`StudyError`] naming the table or figure that could not be written.
pub(super) fn compared(info: &Info, pts: &[Point], o: &Other) -> Result<FigureRecord, StudyError> {
    let sfx = o.suffix;
    let mut header: Vec<String> = [
        "frequency_hz".to_string(),
        "verdict".into(),
        format!("verdict_{sfx}"),
        "same_verdict".into(),
        "amplitude_m".into(),
        format!("amplitude_{sfx}_m"),
        "amplitude_change_pct".into(),
        "impacts_per_cycle".into(),
        format!("impacts_per_cycle_{sfx}"),
        "mle_per_s".into(),
        format!("mle_per_s_{sfx}"),
    ]
    .into();
    if let Some((_, other)) = o.starts {
        header.push("amplitude_spread_starts_pct".into());
        header.push("ensemble".into());
        if other.is_some() {
            header.push("amplitude_mean_starts_m".into());
            header.push(format!("amplitude_mean_starts_{sfx}_m"));
            header.push("amplitude_mean_change_pct".into());
            header.push(format!("ensemble_{sfx}"));
        }
    }
    let mut rows = Vec::new();
    let (mut same, mut worst, mut beyond) = (0usize, 0.0f64, Vec::new());
    let mut worst_mean = 0.0f64;
    let mut pairs = Vec::new();
    for p in pts {
        let Some(q) = o.points.iter().find(|q| q.f_hz == p.f_hz) else {
            continue;
        };
        let change = 100.0 * (q.amplitude_m / p.amplitude_m - 1.0);
        worst = worst.max(change.abs());
        let agree = p.verdict() == q.verdict();
        same += usize::from(agree);
        let mut row = vec![
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
        ];
        if let Some(starts) = o.starts {
            row.extend(start_cells(starts, p.f_hz, &mut worst_mean));
            if change.abs() > 2.0 {
                beyond.push(format!("{} Hz ({change:+.2} %)", p.f_hz));
            }
        }
        rows.push(row);
        pairs.push((p.f_hz, p.amplitude_m, q.amplitude_m));
    }
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    info.ctx.write_table(o.name, &header, rows)?;
    let f: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    let a: Vec<f64> = pairs.iter().map(|p| p.1).collect();
    let b: Vec<f64> = pairs.iter().map(|p| p.2).collect();
    let size = info.ctx.render(
        o.name,
        &LinesFigure {
            series: vec![
                Series {
                    label: &o.labels.0,
                    x: &f,
                    y: &a,
                },
                Series {
                    label: &o.labels.1,
                    x: &f,
                    y: &b,
                },
            ],
            x_label: "frequency f (Hz)".into(),
            y_label: "primary amplitude Z (mm)".into(),
            y_scale: 1e3,
            title: o.title.into(),
            kind: "dem-run-length",
        },
    )?;
    let beyond = match (o.starts, beyond.is_empty()) {
        (None, _) => String::new(),
        (Some(_), true) => "; every change within 2 %".into(),
        (Some(_), false) => format!(
            "; beyond 2 % at {} (chaotic frequencies, where one start's Z is one sample of \
             the attractor)",
            beyond.join(", ")
        ),
    };
    let beyond = match o.starts {
        Some((e, Some(_))) => format!(
            "{beyond}; averaged over the {} starts of each step the amplitude changes by at \
             most {worst_mean:.2} %",
            e.seeds.len()
        ),
        _ => beyond,
    };
    let mut rec = info.record(
        o.name,
        format!(
            "{}: the verdict (regime and period) is unchanged at {same} of {} frequencies and \
             the amplitude changes by at most {worst:.2} %{beyond} (table in {}.csv).",
            o.what,
            pairs.len(),
            o.name
        ),
        vec![],
        size,
    );
    rec.commands.extend(o.sweep.commands.iter().cloned());
    Ok(rec)
}

/// `ch4_run_length`: the sweep's runs continued to twice their length.
pub(super) fn run_length(
    info: &Info,
    pts: &[Point],
    long: &SweepResult,
    long_pts: &[Point],
) -> Result<FigureRecord, StudyError> {
    let other = Other {
        name: "ch4_run_length",
        suffix: "doubled",
        labels: (
            length_text(info.c, 1.0),
            format!("{} (continued)", length_text(info.c, 2.0)),
        ),
        title: "DEM frequency response at two run lengths",
        what: format!(
            "Run-length check: the sweep's runs continued to {} (the same trajectory: the \
             same time step, the first half bit for bit the shorter run)",
            length_text(info.c, 2.0)
        ),
        sweep: long,
        points: long_pts,
        starts: None,
    };
    compared(info, pts, &other)
}

/// `ch4_time_step`: the sweep's runs at the shorter step of `slower` (t_s/50 against the quick
/// study's t_s/20), beside the study's own initial packings and, with the slower step's
/// ensemble too, the amplitude averaged over each step's starts (`starts`).
pub(super) fn time_step(
    info: &Info,
    pts: &[Point],
    slower: (&SweepResult, &[Point], f64),
    starts: Option<(&Ensemble, Option<&Ensemble>)>,
) -> Result<FigureRecord, StudyError> {
    let step = |dt: f64| format!("dt = t_s/{}", 1.0 / dt);
    let other = Other {
        name: "ch4_time_step",
        suffix: "slower_step",
        labels: (step(info.c.dt_fraction), step(slower.2)),
        title: "DEM frequency response at two time steps",
        what: format!(
            "Time-step check: the sweep's runs ({}) again at {} (the same start and run \
             length)",
            step(info.c.dt_fraction),
            step(slower.2)
        ),
        sweep: slower.0,
        points: slower.1,
        starts,
    };
    let mut rec = compared(info, pts, &other)?;
    // the slower step's own starts
    if let Some((_, Some(e))) = starts {
        rec.commands.extend(e.sweep.commands.iter().cloned());
    }
    Ok(rec)
}
