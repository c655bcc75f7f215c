//! Figures of a sweep's `regime` column: `regime-frf` (Z(f) banded by regime with λ(f) below)
//! and `regime-map` (cells of two varied keys coloured by regime, chaotic cells shaded by λ).

use std::path::Path;

use super::{
    axis_label, draw, exponents, optional_column, period_column, refuse, regime_column,
    TableFigureError, TableFigureOptions,
};
use crate::plot::regime_frf::RegimeFrfFigure;
use crate::plot::regime_map::RegimeMapFigure;
use crate::plot::table::Table;
use crate::plot::FigureOptions;

/// `regime-frf`: a sweep table's Z(f) with colour bands per `regime` (periods ≥ 2 written in
/// their band); below it λ(f) from `model_mle_per_s` and `mle_per_s`, each with its
/// `*_stderr_per_s` error bar (points without an exponent omitted).
///
/// # Errors
/// A missing column, a `regime` cell pdamp does not write, or a drawing failure.
pub fn regime_frf(first: &Table, out: &Path, opts: &FigureOptions) -> Result<(), TableFigureError> {
    let f = first.f64_column("frequency_hz")?;
    let z = first.f64_column("amplitude_m")?;
    let r = regime_column(&first.str_column("regime")?)?;
    let col = |name: &str| optional_column(first, name);
    let period = period_column(&col("period")?);
    let (m, ms) = (col("mle_per_s")?, col("mle_stderr_per_s")?);
    let (mm, mms) = (col("model_mle_per_s")?, col("model_mle_stderr_per_s")?);
    let growth = col("replica_growth_per_s")?;
    let no_stderr = None;
    // `phase_locked` (sweeps since issue 39): true / false / empty
    let locked: Option<Vec<bool>> = if first.has("phase_locked") {
        Some(
            first
                .str_column("phase_locked")?
                .iter()
                .map(|c| c.trim() == "true")
                .collect(),
        )
    } else {
        None
    };
    let fig = RegimeFrfFigure {
        frequency_hz: &f,
        amplitude_m: &z,
        regime: &r,
        period: period.as_deref(),
        data: exponents(&m, &ms),
        model: exponents(&mm, &mms),
        phase_locked: locked.as_deref(),
        replica: exponents(&growth, &no_stderr),
    };
    draw(&fig, out, opts)
}

/// `regime-map`: a sweep table with two varied keys `x` and `y`: cells coloured by `regime`,
/// chaotic cells shaded by `model_mle_per_s` (else `mle_per_s`), periodic cells of `period`
/// ≥ 2 darker and numbered where the number fits.
///
/// # Errors
/// No `x` or `y`, a missing column, a `regime` cell pdamp does not write, or a drawing
/// failure.
pub fn regime_map(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let xn = o.x.clone().ok_or_else(|| {
        refuse("regime-map needs --x COLUMN and --y COLUMN (the two varied keys)")
    })?;
    let yn =
        o.y.clone()
            .ok_or_else(|| refuse("regime-map needs --y COLUMN"))?;
    let (x, y) = (first.f64_column(&xn)?, first.f64_column(&yn)?);
    let r = regime_column(&first.str_column("regime")?)?;
    let col = |name: &str| optional_column(first, name);
    let period = period_column(&col("period")?);
    // chaotic cells shaded by the model's exponent, the data's where there is none
    let (model, data) = (col("model_mle_per_s")?, col("mle_per_s")?);
    let (shade, label) = match (&model, &data) {
        (Some(m), Some(d)) if m.iter().any(Option::is_some) => (
            Some(m.iter().zip(d).map(|(m, d)| m.or(*d)).collect::<Vec<_>>()),
            "model λ (1/s)",
        ),
        (Some(m), None) => (Some(m.clone()), "model λ (1/s)"),
        (_, Some(d)) => (Some(d.clone()), "data λ (1/s)"),
        (_, None) => (None, "λ (1/s)"),
    };
    let fig = RegimeMapFigure {
        x: &x,
        y: &y,
        regime: &r,
        period: period.as_deref(),
        mle_per_s: shade.as_deref(),
        mle_label: label.into(),
        x_label: axis_label(&xn),
        y_label: axis_label(&yn),
    };
    draw(&fig, out, opts)
}
