//! The chapter-4 study's verdict checks in one table and one map (`ch4_checks`): at every
//! frequency, the scene's own start beside two more initial packings, the same run continued
//! to twice its length (the same trajectory: see `ch4_set`), and the other shipped softened
//! scene (`thesis_b_soft.toml`: the same bed, other steady and analysis windows) at the same
//! run length. A verdict is trusted where all agree; where the starts differ the bed is
//! multistable, which the table reports ("split") rather than hides; where the other scene
//! differs, its windows are the one parameter that differs (they also move its sample clock,
//! hence its time step in the last bits: another trajectory).

use super::ensemble::words_at;
use super::{length_text, opt_cell, Info, Point, DEFAULT_SEED};
use crate::analysis::regime::Regime;
use crate::error::StudyError;
use crate::plot::regime_map::RegimeMapFigure;
use crate::study::pipeline::{FigureRecord, SweepResult};

/// The runs compared at each frequency.
pub(super) struct Checks<'a> {
    /// The scene's own start (seed 1) at the mode's run length.
    pub base: &'a [Point],
    /// Every start (f, seed, point), the scene's own included, and the words per frequency
    /// ("chaotic in all 3 starts", "split: …").
    pub starts: &'a [(f64, u64, Point)],
    pub ensemble_words: &'a [(f64, String)],
    /// The same runs continued to twice their length.
    pub doubled: &'a [Point],
    /// `thesis_b_soft.toml` at the mode's run length.
    pub other_scene: &'a [Point],
    /// The two run lengths in words ("200 periods", "400 periods").
    pub lengths: (String, String),
    /// The sweeps behind `doubled` and `other_scene` (their commands go in the record).
    pub sweeps: [&'a SweepResult; 2],
}

const HEADER: [&str; 16] = [
    "frequency_hz",
    "verdict",
    "ensemble",
    "verdict_doubled",
    "same_doubled",
    "run_length",
    "amplitude_change_doubled_pct",
    "verdict_soft_scene",
    "same_soft_scene",
    "section_scatter",
    "section_scatter_soft_scene",
    "replica",
    "replica_soft_scene",
    "replica_saturation_rel",
    "mle_per_s",
    "mle_per_s_soft_scene",
];

fn find(pts: &[Point], f: f64) -> Option<&Point> {
    pts.iter().find(|q| q.f_hz == f)
}

/// One row of `ch4_checks.csv`.
fn row(c: &Checks, p: &Point) -> Vec<String> {
    let d = find(c.doubled, p.f_hz);
    let s = find(c.other_scene, p.f_hz);
    let verdict = |q: Option<&Point>| q.map_or(String::new(), Point::verdict);
    let same =
        |q: Option<&Point>| q.map_or(String::new(), |q| (q.verdict() == p.verdict()).to_string());
    vec![
        p.f_hz.to_string(),
        p.label.clone(),
        words_at(c.ensemble_words, p.f_hz),
        verdict(d),
        same(d),
        d.map_or(String::new(), |d| {
            run_length_words((&c.lengths.0, &c.lengths.1), p, d)
        }),
        d.map_or(String::new(), |d| {
            format!("{:.3}", 100.0 * (d.amplitude_m / p.amplitude_m - 1.0))
        }),
        verdict(s),
        same(s),
        opt_cell(p.section_scatter),
        opt_cell(s.and_then(|s| s.section_scatter)),
        p.replica.unwrap_or_default().to_string(),
        s.and_then(|s| s.replica).unwrap_or_default().to_string(),
        opt_cell(p.replica_saturation_rel),
        opt_cell(p.mle_per_s),
        opt_cell(s.and_then(|s| s.mle_per_s)),
    ]
}

/// Whether continuing the run changed the verdict, in words: "settled over 200 and 400
/// periods" or "unsettled: periodic-2 over 200 periods, undetermined over 400 periods" (the
/// run twice as long continues the same trajectory, so a change is the motion's, not
/// another start's).
fn run_length_words((short, long): (&str, &str), p: &Point, d: &Point) -> String {
    if d.verdict() == p.verdict() {
        format!("settled over {short} and {long}")
    } else {
        format!(
            "unsettled: {} over {short}, {} over {long}",
            p.verdict(),
            d.verdict()
        )
    }
}

/// "k of n" agreement of `other` with the base verdicts, and the frequencies that differ.
fn agreement(base: &[Point], other: &[Point]) -> (usize, usize, Vec<String>) {
    let (mut same, mut n, mut differ) = (0, 0, Vec::new());
    for p in base {
        if let Some(q) = find(other, p.f_hz) {
            n += 1;
            if q.verdict() == p.verdict() {
                same += 1;
            } else {
                differ.push(format!(
                    "{} Hz ({} against {})",
                    p.f_hz,
                    q.verdict(),
                    p.verdict()
                ));
            }
        }
    }
    (same, n, differ)
}

fn agreement_text(what: &str, (same, n, differ): (usize, usize, Vec<String>)) -> String {
    if differ.is_empty() {
        format!("{what}: the same verdict at all {n} frequencies")
    } else {
        format!(
            "{what}: the same verdict at {same} of {n} frequencies, different at {}",
            differ.join(", ")
        )
    }
}

/// The map's rows: (row number, label, points).
fn rows<'a>(c: &'a Checks) -> Vec<(f64, String, Vec<&'a Point>)> {
    let mut seeds: Vec<u64> = c.starts.iter().map(|r| r.1).collect();
    seeds.sort_unstable();
    seeds.dedup();
    let mut out: Vec<(f64, String, Vec<&Point>)> = Vec::new();
    for seed in seeds {
        let pts = c
            .starts
            .iter()
            .filter(|r| r.1 == seed)
            .map(|r| &r.2)
            .collect();
        out.push((0.0, format!("start {seed}"), pts));
    }
    if out.is_empty() {
        out.push((
            0.0,
            format!("start {DEFAULT_SEED}"),
            c.base.iter().collect(),
        ));
    }
    out.push((0.0, "continued ×2".into(), c.doubled.iter().collect()));
    out.push((0.0, "thesis_b_soft".into(), c.other_scene.iter().collect()));
    for (i, r) in out.iter_mut().enumerate() {
        r.0 = (i + 1) as f64;
    }
    out
}

/// Writes `ch4_checks.csv` and draws `ch4_checks.png`.
///
/// # Errors
/// [`StudyError`] naming the table or figure that could not be written.
pub(super) fn checks_figure(info: &Info, c: &Checks) -> Result<FigureRecord, StudyError> {
    let name = "ch4_checks";
    info.ctx
        .write_table(name, &HEADER, c.base.iter().map(|p| row(c, p)))?;
    let rows = rows(c);
    let (mut x, mut y, mut regime, mut period, mut mle) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (r, _, pts) in &rows {
        for p in pts {
            x.push(p.f_hz);
            y.push(*r);
            regime.push(p.regime);
            period.push(
                p.period
                    .filter(|_| p.regime == Some(Regime::Periodic))
                    .map(|q| q as u32),
            );
            mle.push(p.mle_per_s);
        }
    }
    let legend: Vec<String> = rows.iter().map(|(r, l, _)| format!("{r}: {l}")).collect();
    let size = info.ctx.render(
        name,
        &RegimeMapFigure {
            x: &x,
            y: &y,
            regime: &regime,
            period: Some(&period),
            mle_per_s: Some(&mle),
            mle_label: "data λ (1/s)".into(),
            x_label: "frequency f (Hz)".into(),
            y_label: format!("run ({})", legend.join(", ")),
        },
    )?;
    let split: Vec<String> = c
        .ensemble_words
        .iter()
        .filter(|(_, w)| w.starts_with("split"))
        .map(|(f, w)| format!("{f} Hz ({w})"))
        .collect();
    let caption = format!(
        "Verdict checks at {}: {}; {}; {}. One row per run in the map, the verdicts and \
         their qualifiers per frequency in {name}.csv.",
        length_text(info.c, 1.0),
        if split.is_empty() {
            format!(
                "the same verdict from every initial packing at all {} frequencies",
                c.ensemble_words.len()
            )
        } else {
            format!(
                "the starts agree at {} of {} frequencies, split at {}",
                c.ensemble_words.len() - split.len(),
                c.ensemble_words.len(),
                split.join("; ")
            )
        },
        agreement_text(
            &format!(
                "continued to {} (the same trajectory, twice as long)",
                length_text(info.c, 2.0)
            ),
            agreement(c.base, c.doubled)
        ),
        agreement_text(
            "thesis_b_soft.toml (the same bed, other analysis windows)",
            agreement(c.base, c.other_scene)
        ),
    );
    let mut rec = info.record(name, caption, vec![], size);
    for s in c.sweeps {
        rec.commands.extend(s.commands.iter().cloned());
    }
    Ok(rec)
}
