//! Figures of one run's series or sections: `bed-motion` (series.csv), `poincare` (a return
//! map of strobe.csv or two columns), `spectrum` (`pdamp spectrum` output), `reconstruction`
//! and `recurrence` (a series column or a plain numeric file) and `d2` (`pdamp d2` output).

use std::path::Path;

use super::{context, draw, refuse, TableFigureError, TableFigureOptions};
use crate::analysis::autocorrelation::first_zero_lag;
use crate::analysis::correlation_dimension::{
    estimate_d2, local_slopes, CorrelationCurve, CorrelationSums, PlateauOptions,
};
use crate::analysis::recurrence::{recurrence_grid, RecurrenceOptions};
use crate::io::{read_series as read_series_file, Column, SeriesReadOptions};
use crate::plot::bed_motion::BedMotionFigure;
use crate::plot::correlation_dimension::D2Figure;
use crate::plot::poincare::PoincareFigure;
use crate::plot::reconstruction::ReconstructionFigure;
use crate::plot::recurrence::RecurrenceFigure;
use crate::plot::spectrum::SpectrumFigure;
use crate::plot::table::Table;
use crate::plot::FigureOptions;

/// `bed-motion`: a run's series.csv: floor/ceiling, grain band (`grain_zmin_m`..`grain_zmax_m`
/// if present), `grain_z_m`, and `grain_force_n` on a second panel; `from_time`/`to_time`
/// crop (s).
///
/// # Errors
/// A missing column, a window of fewer than 2 samples, or a drawing failure.
pub fn bed_motion(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let t = first.f64_column("time_s")?;
    let (a, b) = window(&t, o.from_time, o.to_time)?;
    let col =
        |n: &str| -> Result<Vec<f64>, TableFigureError> { Ok(first.f64_column(n)?[a..b].to_vec()) };
    let (floor, ceil, grain) = (col("floor_z_m")?, col("ceiling_z_m")?, col("grain_z_m")?);
    let band = if first.has("grain_zmin_m") && first.has("grain_zmax_m") {
        Some((col("grain_zmin_m")?, col("grain_zmax_m")?))
    } else {
        None
    };
    let force = if first.has("grain_force_n") {
        Some(col("grain_force_n")?)
    } else {
        None
    };
    let fig = BedMotionFigure {
        time_s: &t[a..b],
        floor_z_m: &floor,
        ceiling_z_m: &ceil,
        grain_z_m: &grain,
        grain_band: band.as_ref().map(|(l, h)| (l.as_slice(), h.as_slice())),
        grain_force_n: force.as_deref(),
    };
    draw(&fig, out, opts)
}

/// Index range [a, b) of the samples with from ≤ t ≤ to.
pub(super) fn window(
    t: &[f64],
    from: Option<f64>,
    to: Option<f64>,
) -> Result<(usize, usize), TableFigureError> {
    let a = from.map_or(0, |f| t.partition_point(|&x| x < f));
    let b = to.map_or(t.len(), |e| t.partition_point(|&x| x <= e));
    if b < a + 2 {
        return Err(refuse(format!(
            "--from-time/--to-time leave fewer than 2 samples (series spans {} .. {} s)",
            t[0],
            t[t.len() - 1]
        )));
    }
    Ok((a, b))
}

/// `poincare`: columns `x`/`y` (default `x`,`y`) of a table, or for strobe.csv (no `x` given)
/// the return map (z_k, z_{k+1}) of `grain_z_m` of sweep point `point` (default: the first).
///
/// # Errors
/// A missing column, a sweep point with fewer than 2 strobe rows, or a drawing failure.
pub fn poincare(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let (x, y, xl, yl) = if first.has("cycle") && first.has("grain_z_m") && o.x.is_none() {
        let z = strobe_of_point(first, o.point)?;
        let x = z[..z.len().saturating_sub(1)].to_vec();
        let y = z.get(1..).unwrap_or_default().to_vec();
        (x, y, "z_k (m)".to_string(), "z_(k+1) (m)".to_string())
    } else {
        let xn = o.x.clone().unwrap_or_else(|| "x".into());
        let yn = o.y.clone().unwrap_or_else(|| "y".into());
        (first.f64_column(&xn)?, first.f64_column(&yn)?, xn, yn)
    };
    let fig = PoincareFigure {
        x: &x,
        y: &y,
        x_label: xl,
        y_label: yl,
    };
    draw(&fig, out, opts)
}

/// `grain_z_m` of one sweep point of strobe.csv, in cycle order.
fn strobe_of_point(t: &Table, point: Option<i64>) -> Result<Vec<f64>, TableFigureError> {
    let z = t.f64_column("grain_z_m")?;
    let cyc = t.f64_column("cycle")?;
    let pts = if t.has("point") {
        t.f64_column("point")?
    } else {
        vec![0.0; z.len()]
    };
    let p = point.map_or(pts[0], |p| p as f64);
    let mut rows: Vec<(f64, f64)> = (0..z.len())
        .filter(|&i| pts[i] == p)
        .map(|i| (cyc[i], z[i]))
        .collect();
    if rows.len() < 2 {
        return Err(refuse(format!(
            "{}: sweep point {p} has {} strobe rows; need ≥ 2 (choose --point)",
            t.path,
            rows.len()
        )));
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(rows.into_iter().map(|r| r.1).collect())
}

/// `spectrum`: columns `frequency_hz`, `power` (output of `pdamp spectrum`); `forcing_hz`
/// marks f and its harmonics.
///
/// # Errors
/// A missing column or a drawing failure.
pub fn spectrum(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let f = first.f64_column("frequency_hz")?;
    let p = first.f64_column("power")?;
    let fig = SpectrumFigure {
        frequency_hz: &f,
        power: &p,
        forcing_hz: o.forcing_hz,
        power_label: "power (arb. units)".into(),
    };
    draw(&fig, out, opts)
}

/// `reconstruction`: the 2-D delay reconstruction (s_n, s_{n+τ}) of a series (column
/// `column`, default `grain_z_m`, or the 1-based column of a plain numeric file); `lag` τ in
/// samples (default: the first zero of the autocorrelation), `dt` (default: from `time_s`)
/// for τ in seconds.
///
/// # Errors
/// A missing column, no zero of the autocorrelation without `lag`, or a drawing failure.
pub fn reconstruction(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let (s, name) = read_series(first, o.column.as_deref())?;
    let (dt, s) = match (o.dt, first.has("time_s")) {
        (Some(dt), _) => (Some(dt), s),
        (None, true) => {
            let t = first.f64_column("time_s")?;
            (t.get(1).map(|t1| t1 - t[0]), s)
        }
        (None, false) => (None, s),
    };
    let lag = match o.lag {
        Some(l) => l,
        None => context(first_zero_lag(&s), || {
            format!("{}: give --lag (samples)", first.path)
        })?,
    };
    let fig = ReconstructionFigure {
        series: &s,
        lag,
        dt_s: dt,
        value_label: name,
    };
    draw(&fig, out, opts)
}

/// `recurrence`: the recurrence plot of a series (column `column` or the 1-based column of a
/// plain file): embedding `dim` (default 1) and `lag` (default 1), `threshold`, `theiler`;
/// downsampled to `max_cells` pixels per side.
///
/// # Errors
/// A missing column, refused recurrence parameters, or a drawing failure.
pub fn recurrence(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let (s, _) = read_series(first, o.column.as_deref())?;
    let ro = RecurrenceOptions {
        m: o.dim.unwrap_or(1),
        tau: o.lag.unwrap_or(1),
        theiler: o.theiler.unwrap_or(0),
        threshold: o.threshold,
        ..RecurrenceOptions::default()
    };
    let grid = context(recurrence_grid(&s, &ro, o.max_cells), || {
        format!("recurrence plot of {}", first.path)
    })?;
    let fig = RecurrenceFigure {
        grid: &grid,
        embedding: (ro.m, ro.tau),
    };
    draw(&fig, out, opts)
}

/// A series from a CSV column (header name) or a plain numeric file (1-based column index;
/// the file is re-read from the table's path).
///
/// # Errors
/// A missing column, or a column index that is not a number for a plain file.
pub fn read_series(
    table: &Table,
    column: Option<&str>,
) -> Result<(Vec<f64>, String), TableFigureError> {
    let numeric_header = table
        .headers
        .iter()
        .flat_map(|h| h.split_whitespace())
        .all(|h| h.parse::<f64>().is_ok());
    if numeric_header {
        // plain file: no header row; re-read it with the series reader of every analysis verb
        let idx: usize =
            column
                .unwrap_or("1")
                .parse()
                .map_err(|source| TableFigureError::Number {
                    context: "--column must be a 1-based index for a plain numeric file".into(),
                    source,
                })?;
        // column 0 reads the first column, as before this reader moved to `io::series`
        let read = SeriesReadOptions {
            columns: vec![Column::Index(idx.max(1))],
            ..SeriesReadOptions::default()
        };
        let v = read_series_file(&table.path, &read)?;
        return Ok((v, format!("column {idx}")));
    }
    let name = column.map(str::to_string).unwrap_or_else(|| {
        if table.has("grain_z_m") {
            "grain_z_m".into()
        } else {
            table.headers[0].clone()
        }
    });
    Ok((table.f64_column(&name)?, name))
}

/// `d2`: the output of `pdamp d2` (columns m, eps, c, pairs, slope): local slopes versus ε
/// (log axis) per m, with the automatic plateaus and D2 marked.
///
/// # Errors
/// A missing column, no rows, or a drawing failure.
pub fn d2(first: &Table, out: &Path, opts: &FigureOptions) -> Result<(), TableFigureError> {
    let sums = d2_curves(first)?;
    let est = estimate_d2(&sums, &PlateauOptions::default()).ok();
    let fig = D2Figure {
        sums: &sums,
        estimate: est.as_ref(),
    };
    draw(&fig, out, opts)
}

/// Curves of `pdamp d2`'s CSV (rows grouped by m, ε increasing).
fn d2_curves(t: &Table) -> Result<CorrelationSums, TableFigureError> {
    let (m, eps, c) = (t.f64_column("m")?, t.f64_column("eps")?, t.f64_column("c")?);
    let pairs = t.f64_column("pairs")?;
    let mut curves: Vec<CorrelationCurve> = Vec::new();
    for k in 0..m.len() {
        let mk = m[k] as usize;
        if curves.last().is_none_or(|c| c.m != mk) {
            curves.push(CorrelationCurve {
                m: mk,
                eps: Vec::new(),
                pairs: Vec::new(),
                c: Vec::new(),
                slope: Vec::new(),
            });
        }
        let cur = curves.last_mut().ok_or_else(|| refuse("no rows"))?;
        cur.eps.push(eps[k]);
        cur.c.push(c[k]);
        cur.pairs.push(pairs[k] as u64);
    }
    if curves.is_empty() {
        return Err(refuse(format!("{}: no rows of `pdamp d2` output", t.path)));
    }
    for cur in &mut curves {
        cur.slope = local_slopes(&cur.eps, &cur.c);
    }
    let last = &curves[0];
    let total = last
        .c
        .iter()
        .zip(&last.pairs)
        .rev()
        .find(|(c, _)| **c > 0.0)
        .map_or(0, |(c, p)| (*p as f64 / c).round() as u64);
    Ok(CorrelationSums {
        curves,
        total_pairs: total,
        vectors: 0,
    })
}
