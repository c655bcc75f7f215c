//! `tradeoff_settings.csv` read back: one [`MeasuredSetting`] per rung of the ladder, as
//! [`super::auto`] uses them (the table is written by `crate::tradeoff::table`, which names
//! the same columns; columns are found by name, so added columns do not break the reader).

use serde::Deserialize;

use crate::error::DataError;

use super::ladder::Axis;

/// A row of `tradeoff_settings.csv` as [`super::auto`] reads it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct MeasuredSetting {
    /// Rung identifier (`dt-50`, `soften-1000`, `one-particle-e0`, …).
    pub setting: String,
    /// Its axis.
    pub axis: Axis,
    /// Its label.
    pub label: String,
    /// `complete`, `partial`, `not computed`, `refused`, `failed`.
    pub status: String,
    /// Frequencies where both it and the reference have a point.
    pub frequencies_compared: usize,
    /// Frequencies of the study.
    pub frequencies: usize,
    /// Mean CPU seconds per point.
    pub core_seconds_per_point: Option<f64>,
    /// Speed-up over the reference.
    pub speedup: Option<f64>,
    /// Largest relative error of Z (–).
    pub amplitude_max_rel_error: Option<f64>,
    /// Relative error of the resonance frequency (–).
    pub resonance_frequency_rel_error: Option<f64>,
    /// Largest relative error of the dissipation per cycle (–).
    pub dissipation_max_rel_error: Option<f64>,
    /// Verdicts equal to the reference's.
    pub regime_matches: usize,
    /// Verdicts compared.
    pub regime_compared: usize,
    /// Largest relative error of λ where both are chaotic (–).
    pub mle_max_rel_error: Option<f64>,
}

/// Reads a settings table written by `crate::tradeoff::table::settings_csv` (`#` lines skipped; columns by name,
/// so that added columns do not break it).
///
/// # Errors
/// [`DataError::Malformed`] naming the file, the line and what is wrong.
pub fn read_settings(text: &str, path: &str) -> Result<Vec<MeasuredSetting>, DataError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let bad = |line: usize, message: String| DataError::Malformed {
        path: path.into(),
        line,
        message,
    };
    let headers = reader.headers().map_err(|e| bad(0, e.to_string()))?.clone();
    let mut out = Vec::new();
    for rec in reader.deserialize::<MeasuredSetting>() {
        out.push(rec.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line() as usize);
            match e.kind() {
                csv::ErrorKind::Deserialize { err, .. } => {
                    let column = err
                        .field()
                        .and_then(|i| headers.get(i as usize))
                        .map_or(String::new(), |c| format!("column `{c}`: "));
                    bad(line, format!("{column}{}", err.kind()))
                }
                _ => bad(line, e.to_string()),
            }
        })?);
    }
    Ok(out)
}
