//! The estimator figures of a series: `kantz` (S(Δn) curves with the fitted scaling regions
//! and the median slope), `mutual` (I(τ) with its first minimum) and `fnn` (false nearest
//! neighbours (%) versus m). Each runs the estimator with the analysis verb's defaults
//! (`pdamp lyap-k`, `pdamp mutual`, `pdamp fnn`), reports its result as a `tracing` event and
//! draws.

use std::path::Path;

use super::{context, draw, refuse, TableFigureError, TableFigureOptions};
use crate::analysis::false_nearest_neighbors::{
    false_nearest_neighbors, suggested_dimension, FnnOptions,
};
use crate::analysis::kantz::{
    estimate_from_curves, kantz as kantz_curves, KantzOptions, ScalingOptions,
};
use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use crate::io::{read_series as read_series_file, Column, SeriesReadOptions};
use crate::plot::fnn::FnnFigure;
use crate::plot::kantz::KantzFigure;
use crate::plot::mutual::MutualFigure;
use crate::plot::FigureOptions;

/// The series of an estimator figure, read as the analysis verbs read theirs: column
/// `column` (a header name or a 1-based index, default 1) of `file`, at most `length` samples.
///
/// # Errors
/// An unreadable column selector or file.
pub fn read_estimator_series(
    file: &str,
    o: &TableFigureOptions,
) -> Result<Vec<f64>, TableFigureError> {
    let column: Column = o
        .column
        .as_deref()
        .unwrap_or("1")
        .parse()
        .map_err(|e: String| refuse(format!("--column: {e}")))?;
    let read = SeriesReadOptions {
        columns: vec![column],
        max_rows: o.length,
        ..SeriesReadOptions::default()
    };
    Ok(read_series_file(file, &read)?)
}

/// `kantz`: Kantz's S(Δn) of the series `x` (named `file` in messages), one curve per m and ε,
/// the fitted scaling region of each marked and the median slope (`pdamp lyap-k`'s exponent)
/// in the caption; `dt` for seconds.
///
/// # Errors
/// Refused dimensions, an estimator failure, or a drawing failure.
pub fn kantz(
    x: &[f64],
    file: &str,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let base = if o.tisean {
        KantzOptions::tisean()
    } else {
        KantzOptions::default()
    };
    let (m_min, m_max) = dimensions(o, base.m_min, base.m_max)?;
    // field by field from the defaults, so that options added later keep their defaults
    let mut ko = base;
    (ko.m_min, ko.m_max) = (m_min, m_max);
    ko.tau = o.lag.unwrap_or(base.tau);
    (ko.eps_min, ko.eps_max) = (o.eps_min, o.eps_max);
    ko.eps_count = o.eps_count.unwrap_or(base.eps_count);
    ko.references = o.references;
    ko.steps = o.steps.unwrap_or(base.steps);
    ko.theiler = o.theiler.or(base.theiler);
    let result = context(kantz_curves(x, &ko), || format!("Kantz on {file}"))?;
    let scaling = ScalingOptions {
        r2_min: o.r2_min,
        ..ScalingOptions::default()
    };
    let est = context(estimate_from_curves(&result, &scaling), || {
        format!("Kantz on {file}")
    })?;
    let per_s = o.dt.map_or(String::new(), |dt| {
        format!(" = {:.6} per second", est.per_sample / dt)
    });
    tracing::info!(
        "maximal Lyapunov exponent (median of {} curves): {:.6} per sample{per_s}{}",
        est.curves_used,
        est.per_sample,
        if est.fit.linear {
            ""
        } else {
            " (no linear region: unreliable)"
        }
    );
    let fig = KantzFigure {
        result: &result,
        scaling,
        dt_s: o.dt,
    };
    draw(&fig, out, opts)
}

/// `mutual`: the mutual information I(τ) of the series `x` with its first minimum marked;
/// `max_lag` largest lag (default 20), `bins` (default 16), `dt` for τ in seconds.
///
/// # Errors
/// An estimator failure or a drawing failure.
pub fn mutual(
    x: &[f64],
    file: &str,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let mo = MutualInformationOptions {
        bins: o.bins.unwrap_or(16),
        max_lag: o.max_lag.unwrap_or(20),
    };
    let mi = context(mutual_information(x, &mo), || {
        format!("mutual information of {file}")
    })?;
    match mi.first_minimum {
        Some(t) => tracing::info!("first minimum of I(tau) at tau = {t} samples"),
        None => tracing::info!(
            "no first minimum up to D = {}: raise -D",
            mi.values.len() - 1
        ),
    }
    let fig = MutualFigure {
        values: &mi.values,
        first_minimum: mi.first_minimum,
        bins: mi.bins,
        dt_s: o.dt,
    };
    draw(&fig, out, opts)
}

/// `fnn`: false nearest neighbours (%) of the series `x` versus m with the suggested
/// dimension (≤ 1 %) marked; `m_min`/`m_max` (default 1,6), `lag`, `ratio` (default 10),
/// `theiler`, `tisean` as `pdamp fnn`.
///
/// # Errors
/// Refused dimensions, an estimator failure, or a drawing failure.
pub fn fnn(
    x: &[f64],
    file: &str,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let base = if o.tisean {
        FnnOptions::tisean()
    } else {
        FnnOptions::default()
    };
    let (m_min, m_max) = dimensions(o, base.m_min, base.m_max)?;
    let mut fo = base;
    (fo.m_min, fo.m_max) = (m_min, m_max);
    fo.tau = o.lag.unwrap_or(base.tau);
    fo.ratio = o.ratio.unwrap_or(base.ratio);
    fo.theiler = o.theiler.or(base.theiler);
    let points = context(false_nearest_neighbors(x, &fo), || {
        format!("false nearest neighbours of {file}")
    })?;
    let fig = FnnFigure {
        points: &points,
        threshold: 0.01,
        ratio: fo.ratio,
    };
    match suggested_dimension(&points, 0.01) {
        Some(m) => {
            tracing::info!("suggested embedding dimension: m = {m} (≤ 1 % false neighbours)")
        }
        None => {
            tracing::info!("no tested dimension has ≤ 1 % false neighbours (noise, or raise -M)")
        }
    }
    draw(&fig, out, opts)
}

/// Dimension range from `m_min` and `m_max` (`M` or `min,max`), with the estimator's
/// defaults; a lone `m_min` above the default maximum raises the maximum to it.
fn dimensions(
    o: &TableFigureOptions,
    min0: usize,
    max0: usize,
) -> Result<(usize, usize), TableFigureError> {
    let num = |v: &str| -> Result<usize, TableFigureError> {
        v.trim().parse().map_err(|source| TableFigureError::Number {
            context: format!(
                "-M {}: `{v}` is not a dimension",
                o.m_max.as_deref().unwrap_or("")
            ),
            source,
        })
    };
    match o.m_max.as_deref() {
        None => {
            let lo = o.m_min.unwrap_or(min0);
            Ok((lo, max0.max(lo)))
        }
        Some(s) => match s.split_once(',') {
            Some((a, b)) => {
                let (a, b) = (num(a)?, num(b)?);
                if let Some(m) = o.m_min.filter(|&m| m != a) {
                    return Err(refuse(format!(
                        "-m {m} and -M {s} disagree: give the smallest dimension once"
                    )));
                }
                Ok((a, b))
            }
            None => Ok((o.m_min.unwrap_or(min0), num(s)?)),
        },
    }
}
