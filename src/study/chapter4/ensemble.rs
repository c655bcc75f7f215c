//! The chapter-4 study's ensemble check (`ch4_ensemble`): the check frequencies from further
//! initial packings (`damper.seed`), each start's verdict, and "split" where they differ — a
//! multistable bed is a finding to report.

use super::{length_text, opt_cell, point, Info, Point, DEFAULT_SEED};
use crate::error::StudyError;
use crate::plot::lines::LinesFigure;
use crate::plot::Series;
use crate::scene::keys::DAMPER_SEED;
use crate::study::pipeline::{FigureRecord, SweepResult};

/// The verdicts of every start at each frequency.
pub(super) struct Ensemble {
    /// (f, seed, point) of every start, the scene's own seed first.
    pub(super) runs: Vec<(f64, u64, Point)>,
    /// (f, "3 of 3 starts" / "split: chaotic in 2 of 3 starts, periodic-1 in 1").
    pub(super) words: Vec<(f64, String)>,
    /// Seeds in order (the scene's first).
    pub(super) seeds: Vec<u64>,
    /// The sweep of the further starts.
    pub(super) sweep: SweepResult,
}

/// The words of the ensemble check at `f` (`words` as in [`Ensemble::words`]), empty where
/// the check did not run.
pub(super) fn words_at(words: &[(f64, String)], f: f64) -> String {
    words
        .iter()
        .find(|(g, _)| *g == f)
        .map_or(String::new(), |(_, w)| w.clone())
}

/// "all 3 starts" or "split: chaotic in 2 of 3 starts, periodic-1 in 1" for the verdicts
/// (regime and period) of the starts.
fn ensemble_words(verdicts: &[String]) -> String {
    let n = verdicts.len();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for v in verdicts {
        match counts.iter_mut().find(|(w, _)| w == v) {
            Some(c) => c.1 += 1,
            None => counts.push((v.clone(), 1)),
        }
    }
    counts.sort_by_key(|c| std::cmp::Reverse(c.1));
    if counts.len() == 1 {
        return format!("{} in all {n} starts", counts[0].0);
    }
    let parts: Vec<String> = counts
        .iter()
        .enumerate()
        .map(|(i, (w, c))| {
            if i == 0 {
                format!("{w} in {c} of {n} starts")
            } else {
                format!("{w} in {c}")
            }
        })
        .collect();
    format!("split: {}", parts.join(", "))
}

pub(super) fn ensemble_check(base: &[Point], more: &SweepResult) -> Result<Ensemble, StudyError> {
    let step = "ch4_ensemble";
    let checked = |f: f64| more.points.iter().any(|q| q.summary.frequency_hz == f);
    let mut runs: Vec<(f64, u64, Point)> = base
        .iter()
        .filter(|p| checked(p.f_hz))
        .map(|p| (p.f_hz, DEFAULT_SEED, p.clone()))
        .collect();
    for sp in more.points.iter() {
        let seed = sp
            .value(DAMPER_SEED)
            .filter(|s| *s >= 0.0)
            .map(|s| s as u64)
            .ok_or_else(|| StudyError::step(step, format!("point {}: no damper.seed", sp.index)))?;
        runs.push((
            sp.summary.frequency_hz,
            seed,
            point(step, &more.points.dir, sp)?,
        ));
    }
    runs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut seeds: Vec<u64> = runs.iter().map(|r| r.1).collect();
    seeds.sort_unstable();
    seeds.dedup();
    let words = base
        .iter()
        .filter(|p| more.points.iter().any(|q| q.summary.frequency_hz == p.f_hz))
        .map(|p| {
            let v: Vec<String> = runs
                .iter()
                .filter(|r| r.0 == p.f_hz)
                .map(|r| r.2.verdict())
                .collect();
            (p.f_hz, ensemble_words(&v))
        })
        .collect();
    Ok(Ensemble {
        runs,
        words,
        seeds,
        sweep: more.clone(),
    })
}

pub(super) fn ensemble_figure(info: &Info, e: &Ensemble) -> Result<FigureRecord, StudyError> {
    let name = "ch4_ensemble";
    let header = [
        "frequency_hz",
        "seed",
        "amplitude_m",
        "verdict",
        "section_scatter",
        "replica",
        "replica_saturation_rel",
        "ensemble",
    ];
    let rows = e.runs.iter().map(|(f, seed, p)| {
        vec![
            f.to_string(),
            seed.to_string(),
            p.amplitude_m.to_string(),
            p.label.clone(),
            opt_cell(p.section_scatter),
            p.replica.unwrap_or_default().to_string(),
            opt_cell(p.replica_saturation_rel),
            e.words
                .iter()
                .find(|(g, _)| g == f)
                .map_or(String::new(), |(_, w)| w.clone()),
        ]
    });
    info.ctx.write_table(name, &header, rows)?;
    let curves: Vec<(String, Vec<f64>, Vec<f64>)> = e
        .seeds
        .iter()
        .map(|&seed| {
            let (f, z) = e
                .runs
                .iter()
                .filter(|r| r.1 == seed)
                .map(|r| (r.0, r.2.amplitude_m))
                .unzip();
            (format!("packing seed {seed}"), f, z)
        })
        .collect();
    let size = info.ctx.render(
        name,
        &LinesFigure {
            series: curves
                .iter()
                .map(|(label, f, z)| Series { label, x: f, y: z })
                .collect(),
            x_label: "frequency f (Hz)".into(),
            y_label: "primary amplitude Z (mm)".into(),
            y_scale: 1e3,
            title: "DEM frequency response from three initial packings".into(),
            kind: "dem-ensemble",
        },
    )?;
    let split: Vec<String> = e
        .words
        .iter()
        .filter(|(_, w)| w.starts_with("split"))
        .map(|(f, w)| format!("{f} Hz ({w})"))
        .collect();
    let mut rec = info.record(
        name,
        format!(
            "Ensemble check: the source's example frequencies from {} initial packings (damper.seed \
             {}), {} each; the verdict (regime and period) is the same in every start at {} of \
             {} frequencies{}. Verdicts per start in {name}.csv.",
            e.seeds.len(),
            e.seeds
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            length_text(info.c, 1.0),
            e.words.len() - split.len(),
            e.words.len(),
            if split.is_empty() {
                String::new()
            } else {
                format!("; split at {}", split.join("; "))
            }
        ),
        vec![],
        size,
    );
    rec.commands.extend(e.sweep.commands.iter().cloned());
    Ok(rec)
}
