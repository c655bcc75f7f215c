//! The line loop's state shared by the stream reader ([`super::read`]) and the parallel
//! pieces ([`super::parallel`]): one line at a time, the layout fixed by the first row, the
//! kept columns, the rows read.

use super::columns::{is_time_name, resolve_column, select};
use super::fields::{field_count_message, field_ranges, first_row, parse_field, Layout};
use super::types::{Delimiter, SeriesReadOptions, SeriesTable};
use crate::error::DataError;

/// The line loop's state: the layout once the first row fixed it, the kept columns, the rows
/// read. Fed one line at a time ([`Rows::line`]); [`Rows::finish`] checks and selects.
pub(super) struct Rows<'a> {
    name: &'a str,
    opts: &'a SeriesReadOptions,
    pub(super) layout: Option<Layout>,
    /// Kept columns (selected, time candidates) by 0-based index; the rest are only counted.
    raw: Vec<Option<Vec<f64>>>,
    pub(super) rows: usize,
    /// Lines seen (the number of the last line fed).
    pub(super) lineno: usize,
    /// Lines to skip at the start (TISEAN `-x`), counted from this sink's first line.
    skip: usize,
    /// Byte ranges of the fields of the current line (no allocation per line).
    fields: Vec<(usize, usize)>,
}

impl<'a> Rows<'a> {
    /// # Errors
    /// [`DataError::Malformed`] (line 0) for options that contradict each other.
    pub(super) fn new(name: &'a str, opts: &'a SeriesReadOptions) -> Result<Self, DataError> {
        if opts.decimal_comma && opts.delimiter == Some(Delimiter::Comma) {
            return Err(DataError::Malformed {
                path: name.to_string(),
                line: 0,
                message: "--decimal-comma with --delimiter comma: a comma cannot be both; the \
                          delimiter of a decimal-comma file is a semicolon, tab or whitespace"
                    .into(),
            });
        }
        Ok(Self {
            name,
            opts,
            layout: None,
            raw: Vec::new(),
            rows: 0,
            lineno: 0,
            skip: opts.skip_lines,
            fields: Vec::new(),
        })
    }

    /// A sink for lines after the first row, with `layout` and the kept columns of `of`, line
    /// numbers counted from 1 again, nothing skipped.
    pub(super) fn continuing(of: &Rows<'a>) -> Self {
        Self {
            name: of.name,
            opts: of.opts,
            layout: of.layout.clone(),
            raw: of
                .raw
                .iter()
                .map(|c| c.as_ref().map(|_| Vec::new()))
                .collect(),
            rows: 0,
            lineno: 0,
            skip: 0,
            fields: Vec::new(),
        }
    }

    fn malformed(&self, message: String) -> DataError {
        DataError::Malformed {
            path: self.name.to_string(),
            line: self.lineno,
            message,
        }
    }

    /// Reads one line (with or without its line end). `Ok(false)`: the row limit is reached,
    /// stop reading.
    pub(super) fn line(&mut self, line: &str) -> Result<bool, DataError> {
        self.lineno += 1;
        if self.lineno <= self.skip {
            return Ok(true);
        }
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            return Ok(true);
        }
        if self.opts.max_rows.is_some_and(|m| self.rows >= m) {
            return Ok(false);
        }
        if self.layout.is_none() {
            let l = first_row(trimmed, self.lineno, self.opts).map_err(|m| self.malformed(m))?;
            self.raw = kept_columns(&l, self.opts).map_err(|m| self.malformed(m))?;
            let is_header = l.header.is_some();
            self.layout = Some(l);
            if is_header {
                return Ok(true);
            }
        }
        let lay = self.layout.as_ref().expect("set above");
        field_ranges(trimmed, lay.delimiter, &mut self.fields);
        if self.fields.len() != lay.fields {
            let m = field_count_message(self.fields.len(), lay, self.opts, trimmed);
            return Err(self.malformed(m));
        }
        for k in 0..self.raw.len() {
            if let Some(column) = &mut self.raw[k] {
                let (a, b) = self.fields[k];
                match parse_field(&trimmed[a..b], k, self.opts) {
                    Ok(v) => column.push(v),
                    Err(m) => return Err(self.malformed(m)),
                }
            }
        }
        self.rows += 1;
        Ok(true)
    }

    /// Appends the rows of a [`Rows::continuing`] sink.
    pub(super) fn append(&mut self, more: Rows<'_>) {
        for (c, m) in self.raw.iter_mut().zip(more.raw) {
            if let (Some(c), Some(m)) = (c, m) {
                c.extend_from_slice(&m);
            }
        }
        self.rows += more.rows;
    }

    /// The table, or why there is none.
    pub(super) fn finish(self) -> Result<SeriesTable, DataError> {
        let malformed = |line: usize, message: String| DataError::Malformed {
            path: self.name.to_string(),
            line,
            message,
        };
        let Some(layout) = self.layout else {
            return Err(malformed(0, "no data rows found".into()));
        };
        if self.rows == 0 {
            return Err(malformed(0, "no data rows found".into()));
        }
        select(self.raw, &layout, self.opts).map_err(|m| malformed(layout.line, m))
    }
}

/// The columns to keep (`Some` = kept) once the first row is known: the selected ones, or
/// with none selected columns 1 and 2 (the automatic choice); column 1 when named like time.
fn kept_columns(lay: &Layout, opts: &SeriesReadOptions) -> Result<Vec<Option<Vec<f64>>>, String> {
    let header = lay.header.as_deref();
    let mut keep = vec![false; lay.fields];
    keep[0] = opts.columns.is_empty() || header.is_some_and(|h| is_time_name(&h[0]));
    if opts.columns.is_empty() && lay.fields > 1 {
        keep[1] = true;
    }
    for c in &opts.columns {
        keep[resolve_column(c, header, lay.fields)?] = true;
    }
    Ok(keep.into_iter().map(|k| k.then(Vec::new)).collect())
}
