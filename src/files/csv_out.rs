//! The one CSV writer of pdamp: every table it writes (`series.csv`, `sweep.csv`,
//! `strobe.csv`, `timings.csv`, figure data, trade-off tables) goes through the `csv` crate
//! here, so that quoting, separators and line ends are the same everywhere and a text cell
//! holding a comma or a quote is quoted instead of shifting the columns after it.
//!
//! Numbers use [`crate::observe::fmt_num`]'s shortest round-trip text (plain between 1e-4
//! and 1e15, scientific outside); rows end in `\n`. Non-finite numbers are the caller's
//! business: writers that may meet them refuse them before calling [`CsvOut::num`].

use std::fmt::Write as _;
use std::io::Write;

/// A CSV table being written: a header, then cells field by field or row by row.
///
/// Allocation-free per cell after the first row (one reused text buffer), so that the
/// sample recorder can use it in the run's loop.
pub struct CsvOut<W: Write> {
    inner: csv::Writer<W>,
    cell: String,
}

impl<W: Write> CsvOut<W> {
    /// A writer with `\n` line ends, quoting only where a cell needs it.
    pub fn new(out: W) -> Self {
        CsvOut {
            inner: csv::WriterBuilder::new()
                .has_headers(false)
                .terminator(csv::Terminator::Any(b'\n'))
                .from_writer(out),
            cell: String::with_capacity(32),
        }
    }

    /// Writes a whole row of text cells (a header, or a row already formatted).
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn row<I, T>(&mut self, cells: I) -> std::io::Result<()>
    where
        I: IntoIterator<Item = T>,
        T: AsRef<[u8]>,
    {
        self.inner.write_record(cells).map_err(into_io)
    }

    /// Writes one numeric cell of the current row (shortest round-trip text).
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn num(&mut self, x: f64) -> std::io::Result<()> {
        self.cell.clear();
        push_num(&mut self.cell, x);
        self.inner
            .write_field(self.cell.as_bytes())
            .map_err(into_io)
    }

    /// Writes one integer cell of the current row.
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn int(&mut self, i: u64) -> std::io::Result<()> {
        self.cell.clear();
        let _ = write!(self.cell, "{i}");
        self.inner
            .write_field(self.cell.as_bytes())
            .map_err(into_io)
    }

    /// Writes one text cell of the current row (quoted if it holds a comma, quote or line end).
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn text(&mut self, s: &str) -> std::io::Result<()> {
        self.inner.write_field(s.as_bytes()).map_err(into_io)
    }

    /// Ends the current row.
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn end_row(&mut self) -> std::io::Result<()> {
        self.inner.write_record(None::<&[u8]>).map_err(into_io)
    }

    /// Flushes the CSV buffer and the writer.
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }

    /// The writer back, flushed.
    ///
    /// # Errors
    /// The writer's I/O error on the final flush.
    pub fn into_inner(self) -> std::io::Result<W> {
        self.inner.into_inner().map_err(|e| e.into_error())
    }
}

impl CsvOut<Vec<u8>> {
    /// A table written into memory (for an atomic write of the whole file).
    pub fn in_memory() -> Self {
        CsvOut::new(Vec::new())
    }

    /// The table's text.
    pub fn into_string(self) -> String {
        // a Vec<u8> never fails to flush, and every cell written is UTF-8
        let bytes = self.into_inner().unwrap_or_default();
        String::from_utf8(bytes).unwrap_or_default()
    }
}

/// Appends `x` as [`crate::observe::fmt_num`] writes it, without allocating.
pub fn push_num(out: &mut String, x: f64) {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&a) {
        let _ = write!(out, "{x}");
    } else {
        let _ = write!(out, "{x:e}");
    }
}

fn into_io(e: csv::Error) -> std::io::Error {
    std::io::Error::from(e)
}

/// A whole table in memory: `header`, then `rows` of text cells.
pub fn table_text<R, C>(header: &[&str], rows: R) -> String
where
    R: IntoIterator<Item = C>,
    C: IntoIterator,
    C::Item: AsRef<[u8]>,
{
    let mut t = CsvOut::in_memory();
    // writes into memory cannot fail
    let _ = t.row(header);
    for r in rows {
        let _ = t.row(r);
    }
    t.into_string()
}

/// One CSV record as a line of text ending in `\n` (a header, or a line appended to a log).
pub fn record_line<I, T>(cells: I) -> String
where
    I: IntoIterator<Item = T>,
    T: AsRef<[u8]>,
{
    let mut t = CsvOut::in_memory();
    // writes into memory cannot fail
    let _ = t.row(cells);
    t.into_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_rows_and_quoting() {
        let mut t = CsvOut::in_memory();
        t.row(["t_s", "label"]).unwrap();
        t.num(0.5).unwrap();
        t.text("a,b").unwrap();
        t.end_row().unwrap();
        t.num(1e-7).unwrap();
        t.text("say \"hi\"").unwrap();
        t.end_row().unwrap();
        t.int(3).unwrap();
        t.text("").unwrap();
        t.end_row().unwrap();
        assert_eq!(
            t.into_string(),
            "t_s,label\n0.5,\"a,b\"\n1e-7,\"say \"\"hi\"\"\"\n3,\n"
        );
    }

    #[test]
    fn push_num_matches_fmt_num() {
        for x in [
            0.0, -0.0, 1.0, 1e-4, 9.99e-5, 1e15, 123456.789, -3.5e-18, 2.5e300,
        ] {
            let mut s = String::new();
            push_num(&mut s, x);
            assert_eq!(s, crate::observe::fmt_num(x), "{x}");
        }
    }

    #[test]
    fn table_text_reads_back_with_the_csv_reader() {
        let text = table_text(&["a", "b"], [vec!["1", "x,y"], vec!["2", ""]]);
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 2);
        assert_eq!(&rows[0][1], "x,y");
        assert_eq!(&rows[1][1], "");
    }
}
