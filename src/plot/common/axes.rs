//! Axes and data shared by the figures: padded ranges, input checks (finite values, equal
//! lengths), the [`Series`] type, the plot legend and mesh, tick text and min/max decimation
//! of long curves.

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::render::draw_err;
use super::style::{label_font, tick_font};
use crate::error::PlotError;

/// Min and max of the finite values of one or more slices, padded by `pad` of the range
/// (a zero range is widened by ±1 % of |value| or ±1).
pub fn padded_range<'a>(values: impl IntoIterator<Item = &'a [f64]>, pad: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        for &x in v.iter().filter(|x| x.is_finite()) {
            lo = lo.min(x);
            hi = hi.max(x);
        }
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()) {
        let w = if lo == 0.0 { 1.0 } else { 0.01 * lo.abs() };
        return (lo - w, hi + w);
    }
    let w = (hi - lo) * pad;
    (lo - w, hi + w)
}

/// Checks that a field is non-empty and finite; `Err` names the first bad index.
pub fn check_finite(figure: &str, field: &str, v: &[f64]) -> Result<(), PlotError> {
    if v.is_empty() {
        return Err(PlotError::bad(
            figure,
            field,
            "no data: the column is empty",
        ));
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(PlotError::bad(
            figure,
            field,
            format!(
                "value {} at row {i} is not finite: remove or recompute that row",
                v[i]
            ),
        ));
    }
    Ok(())
}

/// Checks that `v` has `n` entries (same length as the figure's x data).
pub fn check_len(figure: &str, field: &str, v: usize, n: usize) -> Result<(), PlotError> {
    if v != n {
        return Err(PlotError::bad(
            figure,
            field,
            format!("has {v} values but the x data has {n}: columns must have equal lengths"),
        ));
    }
    Ok(())
}

/// A named (x, y) data series borrowed from the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates (same length as `x`).
    pub y: &'a [f64],
}

impl Series<'_> {
    /// Checks non-empty, equal lengths, finite values.
    pub fn validate(&self, figure: &str) -> Result<(), PlotError> {
        check_finite(figure, &format!("{} (x)", self.label), self.x)?;
        check_len(
            figure,
            &format!("{} (y)", self.label),
            self.y.len(),
            self.x.len(),
        )?;
        check_finite(figure, &format!("{} (y)", self.label), self.y)
    }
}

/// Draws the legend of `chart` in its upper-right corner.
pub fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    pos: SeriesLabelPosition,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(pos)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.5))
        .label_font(label_font())
        .draw()
        .map_err(draw_err)
}

/// Standard mesh (grid, axis descriptions, tick font) of a 2-D chart; tick labels by
/// [`fmt_axis_tick`] (an exact `0` where the axis crosses zero).
pub fn mesh<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    x_desc: &str,
    y_desc: &str,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (x_lo, x_hi) = {
        let r = chart.x_range();
        (r.start, r.end)
    };
    let (y_lo, y_hi) = {
        let r = chart.y_range();
        (r.start, r.end)
    };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(label_font())
        .label_style(tick_font())
        .light_line_style(BLACK.mix(0.05))
        .bold_line_style(BLACK.mix(0.15))
        .x_label_formatter(&|v| fmt_axis_tick(*v, x_lo, x_hi))
        .y_label_formatter(&|v| fmt_axis_tick(*v, y_lo, y_hi))
        .draw()
        .map_err(draw_err)
}

/// Relative size (of the axis span) below which a tick value on an axis through zero is zero.
pub const ZERO_TICK_FRACTION: f64 = 1e-9;

/// A tick label of `v` on an axis from `lo` to `hi`: as [`fmt_tick`], except that on an axis
/// that contains zero a value within [`ZERO_TICK_FRACTION`] of the span from zero prints `0`
/// (tick positions are computed in floating point: the tick at zero of a −0.1…0.3 axis
/// arrives as 3.5e-18). Axes that do not contain zero (log axes among them) are never
/// snapped, so that 1e-15 on a spectrum's power axis keeps its value.
pub fn fmt_axis_tick(v: f64, lo: f64, hi: f64) -> String {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    let tol = (hi - lo) * ZERO_TICK_FRACTION;
    if tol.is_finite() && lo <= 0.0 && hi >= 0.0 && v.abs() <= tol {
        "0".into()
    } else {
        fmt_tick(v)
    }
}

/// Compact number labels: plain decimals for moderate magnitudes, scientific otherwise.
/// For tick labels use [`fmt_axis_tick`] (or [`mesh`]), which prints an exact `0`.
pub fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// Pixel size helper: a fraction of the smaller side of the drawing area, at least `min`.
pub fn scaled<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, frac: f64, min: u32) -> u32 {
    let (w, h) = area.dim_in_pixel();
    ((w.min(h) as f64 * frac) as u32).max(min)
}

/// Reduces a long line to at most ~`max_points` points keeping each bucket's minimum and
/// maximum in time order, so that peaks survive (unlike plain striding).
pub fn decimate_minmax(x: &[f64], y: &[f64], max_points: usize) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    if n <= max_points || max_points < 4 {
        return x.iter().copied().zip(y.iter().copied()).collect();
    }
    let buckets = max_points / 2;
    let mut out = Vec::with_capacity(2 * buckets + 2);
    for b in 0..buckets {
        let (lo, hi) = (b * n / buckets, ((b + 1) * n / buckets).min(n));
        if lo >= hi {
            continue;
        }
        let (mut imin, mut imax) = (lo, lo);
        for i in lo..hi {
            if y[i] < y[imin] {
                imin = i;
            }
            if y[i] > y[imax] {
                imax = i;
            }
        }
        let (a, b) = if imin <= imax {
            (imin, imax)
        } else {
            (imax, imin)
        };
        out.push((x[a], y[a]));
        if b != a {
            out.push((x[b], y[b]));
        }
    }
    out
}
