//! CSV tables read by the figure and fit commands (the output-file contract of
//! `pdamp simulate` / `pdamp sweep` / `pdamp fit-frf`): columns by header name, with errors
//! that name the file, line and column.

use std::path::Path;

use crate::error::DataError;

/// A CSV file held as text cells, addressed by header name.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Path as given (for error messages).
    pub path: String,
    /// Header names, trimmed.
    pub headers: Vec<String>,
    /// Data rows (cells trimmed); every row has `headers.len()` cells.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads a CSV file with a header row. Lines starting with `#` are comments.
    ///
    /// # Errors
    /// [`DataError::Io`] if unreadable or in an incomplete run directory
    /// ([`crate::io::run_dir::check_complete`]); [`DataError::Malformed`] for a missing
    /// header, a row with the wrong number of cells, or no data rows.
    pub fn read(path: &Path) -> Result<Table, DataError> {
        crate::io::run_dir::check_complete(path)?;
        let text = std::fs::read_to_string(path).map_err(|source| DataError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Table::parse(&path.display().to_string(), &text)
    }

    /// Parses CSV text (see [`Table::read`]); `path` is used in messages only.
    ///
    /// # Errors
    /// As [`Table::read`].
    pub fn parse(path: &str, text: &str) -> Result<Table, DataError> {
        let mut rdr = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .flexible(false)
            .from_reader(text.as_bytes());
        let malformed = |line: usize, message: String| DataError::Malformed {
            path: path.to_string(),
            line,
            message,
        };
        let headers: Vec<String> = rdr
            .headers()
            .map_err(|e| malformed(1, format!("cannot read the header row: {e}")))?
            .iter()
            .map(|h| h.to_string())
            .collect();
        if headers.is_empty() || headers.iter().all(|h| h.is_empty()) {
            return Err(malformed(
                1,
                "no header row: the first line must name the columns".into(),
            ));
        }
        let mut rows = Vec::new();
        for rec in rdr.records() {
            let rec = rec.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line() as usize);
                malformed(line, format!("{e}"))
            })?;
            rows.push(rec.iter().map(|c| c.to_string()).collect());
        }
        if rows.is_empty() {
            return Err(malformed(2, "no data rows after the header".into()));
        }
        Ok(Table {
            path: path.to_string(),
            headers,
            rows,
        })
    }

    /// Index of a column, if present.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.headers.iter().position(|h| h == name)
    }

    /// Whether the table has column `name`.
    pub fn has(&self, name: &str) -> bool {
        self.index(name).is_some()
    }

    fn require(&self, name: &str) -> Result<usize, DataError> {
        self.index(name).ok_or_else(|| DataError::Malformed {
            path: self.path.clone(),
            line: 1,
            message: format!(
                "missing column `{name}` (columns present: {})",
                self.headers.join(", ")
            ),
        })
    }

    /// Column `name` as finite f64 values.
    ///
    /// # Errors
    /// [`DataError::Malformed`] naming the file, line and column if the column is missing or a
    /// cell is empty, not a number, NaN or infinite.
    pub fn f64_column(&self, name: &str) -> Result<Vec<f64>, DataError> {
        let j = self.require(name)?;
        self.rows
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let cell = &r[j];
                match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() => Ok(v),
                    _ => Err(DataError::Malformed {
                        path: self.path.clone(),
                        line: i + 2,
                        message: format!(
                            "column `{name}`: `{cell}` is not a finite number (NaN/inf/empty are \
                             not allowed here)"
                        ),
                    }),
                }
            })
            .collect()
    }

    /// Column `name` where empty, `NaN` or non-numeric cells become `None` (for optional
    /// estimates such as `mle_per_s`).
    ///
    /// # Errors
    /// [`DataError::Malformed`] if the column is missing.
    pub fn opt_f64_column(&self, name: &str) -> Result<Vec<Option<f64>>, DataError> {
        let j = self.require(name)?;
        Ok(self
            .rows
            .iter()
            .map(|r| r[j].parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect())
    }

    /// Column `name` as text.
    ///
    /// # Errors
    /// [`DataError::Malformed`] if the column is missing.
    pub fn str_column(&self, name: &str) -> Result<Vec<String>, DataError> {
        let j = self.require(name)?;
        Ok(self.rows.iter().map(|r| r[j].clone()).collect())
    }

    /// Headers that start with `prefix` and end with `suffix`, in file order.
    pub fn columns_matching(&self, prefix: &str, suffix: &str) -> Vec<String> {
        self.headers
            .iter()
            .filter(|h| h.starts_with(prefix) && h.ends_with(suffix))
            .cloned()
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_column_and_nan_are_named() {
        let t = Table::parse("s.csv", "frequency_hz,amplitude_m\n1,2\n3,NaN\n").unwrap();
        let e = t.f64_column("regime").unwrap_err().to_string();
        assert!(e.contains("s.csv") && e.contains("regime"), "{e}");
        let e = t.f64_column("amplitude_m").unwrap_err().to_string();
        assert!(e.contains("s.csv:3") && e.contains("amplitude_m"), "{e}");
        assert_eq!(
            t.opt_f64_column("amplitude_m").unwrap(),
            vec![Some(2.0), None]
        );
    }

    #[test]
    fn ragged_rows_are_rejected() {
        assert!(Table::parse("s.csv", "a,b\n1,2\n3\n").is_err());
        assert!(Table::parse("s.csv", "a,b\n").is_err());
    }
}
