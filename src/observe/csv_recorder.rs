//! Writes samples to `series.csv` (header row, SI units in column names).

use super::{Observer, Sample, SampleKind, FIXED_COLUMNS};
use crate::error::SimError;
use std::io::Write;

/// CSV recorder: one row per sample; columns [`FIXED_COLUMNS`], the model's columns
/// ([`SampleKind::columns`]), then `grain_force_n`. Numbers use Rust's shortest round-trip formatting.
///
/// No NaN or infinity is ever written: a non-finite value stops the run with
/// [`SimError::Unstable`] naming the column, except an infinite `ceiling_z_m` (no ceiling,
/// `damper.gap = inf`), written as an empty cell.
pub struct CsvRecorder<W: Write> {
    out: W,
    line: String,
    columns: Vec<&'static str>,
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
            out,
            line: String::with_capacity(256),
            columns: Vec::new(),
        }
    }

    /// The writer back (e.g. a `Vec<u8>` in tests).
    pub fn into_inner(self) -> W {
        self.out
    }

    fn write_line(&mut self) -> Result<(), SimError> {
        self.line.push('\n');
        self.out
            .write_all(self.line.as_bytes())
            .map_err(|e| SimError::Output(format!("series.csv: {e}")))?;
        self.line.clear();
        Ok(())
    }
}

/// Appends one cell: the number, an empty cell for an infinite ceiling, or why not.
fn push_cell(line: &mut String, column: &str, v: f64) -> Result<(), String> {
    use std::fmt::Write as _;
    if v.is_finite() {
        let _ = write!(line, "{}", super::fmt_num(v));
        Ok(())
    } else if column == "ceiling_z_m" && v == f64::INFINITY {
        Ok(())
    } else {
        Err(format!(
            "the sample's {column} is {v}: the state is no longer finite (nothing non-finite is \
             written to series.csv)"
        ))
    }
}

impl<W: Write> Observer for CsvRecorder<W> {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        let mut cols: Vec<&str> = FIXED_COLUMNS.to_vec();
        cols.extend_from_slice(kind.columns());
        cols.push("grain_force_n");
        self.line = cols.join(",");
        self.columns = cols;
        self.write_line()
    }

    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        let mut values = Vec::with_capacity(self.columns.len());
        values.extend_from_slice(&[
            s.time_s,
            s.base_u_m,
            s.box_z_m,
            s.box_v_m_s,
            s.floor_z_m,
            s.ceiling_z_m,
            s.grain_z_m,
        ]);
        s.model.for_each_value(|v| values.push(v));
        values.push(s.grain_force_n);
        self.line.clear();
        for (i, v) in values.iter().enumerate() {
            if i > 0 {
                self.line.push(',');
            }
            let column = self.columns.get(i).copied().unwrap_or("?");
            push_cell(&mut self.line, column, *v).map_err(|reason| SimError::Unstable {
                t_s: s.time_s,
                reason,
            })?;
        }
        self.write_line()
    }

    fn finish(&mut self) -> Result<(), SimError> {
        self.out
            .flush()
            .map_err(|e| SimError::Output(format!("series.csv: {e}")))
    }
}
