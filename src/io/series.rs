//! Reading one- or many-column series files as TISEAN users expect.
//!
//! Accepted format: one sample per line; fields separated by commas, semicolons, tabs or
//! spaces; blank lines and lines starting with `#` are skipped; an optional header row (the
//! first non-comment line, if any field is not a number) names the columns. Columns are
//! selected by 1-based number as TISEAN's `-c`, or by header name. `-` reads standard input.

use std::io::{BufRead, BufReader};

use crate::error::DataError;

/// One column to read: 1-based index (TISEAN `-c 2`) or header name (`-c grain_z_m`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Column {
    /// 1-based column number.
    Index(usize),
    /// Name in the header row.
    Name(String),
}

impl std::str::FromStr for Column {
    type Err = String;
    /// A positive integer is an index, anything else a header name.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        match s.parse::<usize>() {
            Ok(0) => Err("column numbers start at 1 (as TISEAN's -c)".into()),
            Ok(i) => Ok(Column::Index(i)),
            Err(_) if s.is_empty() => Err("empty column name".into()),
            Err(_) => Ok(Column::Name(s.to_string())),
        }
    }
}

/// Options of [`read_columns`], mirroring TISEAN's `-c`, `-x`, `-l`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeriesReadOptions {
    /// Columns to read (default: the first).
    pub columns: Vec<Column>,
    /// Number of lines to skip at the start of the file (TISEAN `-x`), counted before
    /// comments and the header are recognised. Default 0.
    pub skip_lines: usize,
    /// Keep at most this many data rows (TISEAN `-l`). Default: all.
    pub max_rows: Option<usize>,
}

impl Default for SeriesReadOptions {
    fn default() -> Self {
        Self {
            columns: vec![Column::Index(1)],
            skip_lines: 0,
            max_rows: None,
        }
    }
}

/// Reads the selected columns of a series file (`-` = standard input): one `Vec` per column.
///
/// # Errors
/// [`DataError::Io`] if the file cannot be read; [`DataError::Malformed`] naming `file:line`
/// for a non-numeric or non-finite value, a missing column, an unknown column name, or a
/// file without data rows.
pub fn read_columns(path: &str, opts: &SeriesReadOptions) -> Result<Vec<Vec<f64>>, DataError> {
    let io_err = |source| DataError::Io {
        path: path.to_string(),
        source,
    };
    if path == "-" {
        let stdin = std::io::stdin();
        parse_columns(stdin.lock(), "<stdin>", opts)
    } else {
        let file = std::fs::File::open(path).map_err(io_err)?;
        parse_columns(BufReader::new(file), path, opts)
    }
}

/// Reads one column (the first of `opts.columns`) of a series file.
///
/// # Errors
/// Those of [`read_columns`].
pub fn read_series(path: &str, opts: &SeriesReadOptions) -> Result<Vec<f64>, DataError> {
    let mut one = opts.clone();
    one.columns.truncate(1);
    if one.columns.is_empty() {
        one.columns.push(Column::Index(1));
    }
    Ok(read_columns(path, &one)?.remove(0))
}

fn split_fields(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|f| !f.is_empty())
}

/// Parses series text from any buffered reader; `name` is used in error messages.
///
/// # Errors
/// Those of [`read_columns`].
pub fn parse_columns(
    reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    parse_lines(reader, name, opts)
}

fn parse_lines(
    mut reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    let malformed = |line: usize, message: String| DataError::Malformed {
        path: name.to_string(),
        line,
        message,
    };
    let mut indices: Option<Vec<usize>> = None; // 0-based, resolved at the first data/header line
    let mut out: Vec<Vec<f64>> = vec![Vec::new(); opts.columns.len()];
    let mut rows = 0usize;
    // one buffer for all lines (no allocation per line)
    let mut line = String::new();
    let mut lineno = 0usize;
    loop {
        line.clear();
        let read = reader
            .read_line(&mut line)
            .map_err(|source| DataError::Io {
                path: name.to_string(),
                source,
            })?;
        if read == 0 {
            break;
        }
        lineno += 1;
        if lineno <= opts.skip_lines {
            continue;
        }
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        if opts.max_rows.is_some_and(|m| rows >= m) {
            break;
        }
        if indices.is_none() {
            let fields: Vec<&str> = split_fields(trimmed).collect();
            let is_header = fields.iter().any(|f| f.parse::<f64>().is_err());
            indices = Some(resolve_columns(
                &opts.columns,
                &fields,
                is_header,
                lineno,
                name,
            )?);
            if is_header {
                continue;
            }
        }
        let idx = indices.as_ref().expect("resolved above");
        for (col, &i) in idx.iter().enumerate() {
            let field = split_fields(trimmed).nth(i).ok_or_else(|| {
                malformed(
                    lineno,
                    format!(
                        "column {} missing (the line has {} fields)",
                        i + 1,
                        split_fields(trimmed).count()
                    ),
                )
            })?;
            let v: f64 = field.parse().map_err(|_| {
                malformed(
                    lineno,
                    format!("column {}: `{field}` is not a number", i + 1),
                )
            })?;
            if !v.is_finite() {
                return Err(malformed(
                    lineno,
                    format!(
                        "column {}: non-finite value `{field}`; remove or interpolate it",
                        i + 1
                    ),
                ));
            }
            out[col].push(v);
        }
        rows += 1;
    }
    if rows == 0 {
        return Err(malformed(0, "no data rows found".into()));
    }
    Ok(out)
}

fn resolve_columns(
    cols: &[Column],
    fields: &[&str],
    is_header: bool,
    lineno: usize,
    name: &str,
) -> Result<Vec<usize>, DataError> {
    cols.iter()
        .map(|c| match c {
            Column::Index(i) => Ok(i - 1),
            Column::Name(n) if is_header => {
                fields
                    .iter()
                    .position(|f| f == n)
                    .ok_or_else(|| DataError::Malformed {
                        path: name.to_string(),
                        line: lineno,
                        message: format!(
                            "no column named `{n}` in the header ({})",
                            fields.join(", ")
                        ),
                    })
            }
            Column::Name(n) => Err(DataError::Malformed {
                path: name.to_string(),
                line: lineno,
                message: format!("column `{n}` selected by name but the file has no header row"),
            }),
        })
        .collect()
}

/// Parses series text held in memory (e.g. in tests); `name` is used in error messages.
///
/// # Errors
/// Those of [`read_columns`].
pub fn parse_str(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    parse_lines(text.as_bytes(), name, opts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(cols: &[&str]) -> SeriesReadOptions {
        SeriesReadOptions {
            columns: cols.iter().map(|c| c.parse().unwrap()).collect(),
            ..SeriesReadOptions::default()
        }
    }

    #[test]
    fn reads_whitespace_csv_comments_and_header() {
        let text = "# a comment\ntime_s,grain_z_m\n0.0, 1.5\n\n0.1,2.5\n# end\n";
        let cols = parse_str(text, "f.csv", &opts(&["grain_z_m", "1"])).unwrap();
        assert_eq!(cols, vec![vec![1.5, 2.5], vec![0.0, 0.1]]);
        let ws = parse_str("1 2\n3\t4\n", "f.dat", &opts(&["2"])).unwrap();
        assert_eq!(ws, vec![vec![2.0, 4.0]]);
    }

    #[test]
    fn skip_and_length_like_tisean() {
        let text = "9\n1\n2\n3\n4\n";
        let o = SeriesReadOptions {
            skip_lines: 1,
            max_rows: Some(2),
            ..SeriesReadOptions::default()
        };
        assert_eq!(parse_str(text, "f", &o).unwrap(), vec![vec![1.0, 2.0]]);
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = parse_str("1\n2\nnan\n", "data.txt", &opts(&["1"])).unwrap_err();
        assert!(e.to_string().starts_with("data.txt:3:"), "{e}");
        let e = parse_str("1 2\n3\n", "d", &opts(&["2"])).unwrap_err();
        assert!(e.to_string().starts_with("d:2:"), "{e}");
        let e = parse_str("1,2\n2,x\n", "d", &opts(&["2"])).unwrap_err();
        assert!(e.to_string().contains("`x` is not a number"), "{e}");
        assert!("0".parse::<Column>().is_err());
    }
}
