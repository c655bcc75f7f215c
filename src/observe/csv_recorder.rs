//! Writes samples to `series.csv` (header row, SI units in column names).

use super::{Observer, Sample, SampleKind, FIXED_COLUMNS};
use crate::error::SimError;
use std::io::Write;

/// CSV recorder: one row per sample; columns [`FIXED_COLUMNS`], the model's columns
/// ([`SampleKind::columns`]), then `grain_force_n`. Numbers use Rust's shortest round-trip formatting.
pub struct CsvRecorder<W: Write> {
    out: W,
    line: String,
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

impl<W: Write> Observer for CsvRecorder<W> {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        let mut cols: Vec<&str> = FIXED_COLUMNS.to_vec();
        cols.extend_from_slice(kind.columns());
        cols.push("grain_force_n");
        self.line = cols.join(",");
        self.write_line()
    }

    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        use std::fmt::Write as _;
        for (i, v) in s.fixed_values().iter().enumerate() {
            if i > 0 {
                self.line.push(',');
            }
            let _ = write!(self.line, "{}", super::fmt_num(*v));
        }
        let line = &mut self.line;
        s.model.for_each_value(|v| {
            let _ = write!(line, ",{}", super::fmt_num(v));
        });
        let _ = write!(self.line, ",{}", super::fmt_num(s.grain_force_n));
        self.write_line()
    }

    fn finish(&mut self) -> Result<(), SimError> {
        self.out
            .flush()
            .map_err(|e| SimError::Output(format!("series.csv: {e}")))
    }
}
