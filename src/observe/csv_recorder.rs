//! Writes samples to `series.csv` (header row, SI units in column names).

use super::{Observer, Sample, SampleKind, FIXED_COLUMNS};
use crate::error::SimError;
use crate::files::CsvOut;
use std::io::Write;

/// CSV recorder: one row per sample; columns [`FIXED_COLUMNS`], the model's columns
/// ([`SampleKind::columns`]), then `grain_force_n`. Numbers use Rust's shortest round-trip formatting.
///
/// No NaN or infinity is ever written: a non-finite value stops the run with
/// [`SimError::Unstable`] naming the column, except an infinite `ceiling_z_m` (no ceiling,
/// `damper.gap = inf`), written as an empty cell.
pub struct CsvRecorder<W: Write> {
    out: CsvOut<W>,
    columns: Vec<&'static str>,
    values: Vec<f64>,
}

impl CsvRecorder<std::io::BufWriter<std::fs::File>> {
    /// Record into a new file at `path`.
    ///
    /// # Errors
    /// [`SimError::Output`] naming the path if the file cannot be created.
    pub fn create(path: &std::path::Path) -> Result<Self, SimError> {
        let f = std::fs::File::create(path)
            .map_err(|e| SimError::Output(format!("{}: {e}", path.display())))?;
        Ok(CsvRecorder::new(std::io::BufWriter::new(f)))
    }
}

impl<W: Write> CsvRecorder<W> {
    /// Record into any writer.
    pub fn new(out: W) -> Self {
        CsvRecorder {
            out: CsvOut::new(out),
            columns: Vec::new(),
            values: Vec::with_capacity(16),
        }
    }

    /// The writer back, flushed (e.g. a `Vec<u8>` in tests).
    ///
    /// # Errors
    /// [`SimError::Output`] if the final flush fails.
    pub fn into_inner(self) -> Result<W, SimError> {
        self.out.into_inner().map_err(output_err)
    }
}

fn output_err(e: std::io::Error) -> SimError {
    SimError::Output(format!("series.csv: {e}"))
}

/// Why a sample value cannot be written, or `None` if it can (finite, or the infinite
/// ceiling of a damper without one, written as an empty cell).
fn refusal(column: &str, v: f64) -> Option<String> {
    if v.is_finite() || (column == "ceiling_z_m" && v == f64::INFINITY) {
        None
    } else {
        Some(format!(
            "the sample's {column} is {v}: the state is no longer finite (nothing non-finite is \
             written to series.csv)"
        ))
    }
}

impl<W: Write> Observer for CsvRecorder<W> {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        let mut cols: Vec<&'static str> = FIXED_COLUMNS.to_vec();
        cols.extend_from_slice(kind.columns());
        cols.push("grain_force_n");
        self.out.row(&cols).map_err(output_err)?;
        self.columns = cols;
        Ok(())
    }

    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.values.clear();
        self.values.extend_from_slice(&s.fixed_values());
        let values = &mut self.values;
        s.model.for_each_value(|v| values.push(v));
        self.values.push(s.grain_force_n);
        // check the whole row first, so that a refused sample leaves no partial row behind
        for (i, &v) in self.values.iter().enumerate() {
            let column = self.columns.get(i).copied().unwrap_or("?");
            if let Some(reason) = refusal(column, v) {
                return Err(SimError::Unstable {
                    t_s: s.time_s,
                    reason,
                });
            }
        }
        for &v in &self.values {
            if v.is_finite() {
                self.out.num(v).map_err(output_err)?;
            } else {
                self.out.text("").map_err(output_err)?;
            }
        }
        self.out.end_row().map_err(output_err)
    }

    fn finish(&mut self) -> Result<(), SimError> {
        self.out.flush().map_err(output_err)
    }
}
