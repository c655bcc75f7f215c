//! Reading a series file or text into a [`SeriesTable`]: the entry points (file, standard
//! input, reader, memory) and the line loop of [`parse_table`].

use std::io::{BufRead, BufReader};

use super::columns::{is_time_name, resolve_column, select};
use super::fields::{field_count_message, field_ranges, first_row, parse_field, Layout};
use super::types::{Delimiter, SeriesReadOptions, SeriesTable};
use crate::error::DataError;

/// Reads the selected columns of a series file (`-` = standard input): one `Vec` per column.
///
/// # Errors
/// As [`read_table`].
pub fn read_columns(path: &str, opts: &SeriesReadOptions) -> Result<Vec<Vec<f64>>, DataError> {
    Ok(read_table(path, opts)?.columns)
}

/// Reads a series file (`-` = standard input) with the checks of the module documentation.
///
/// # Errors
/// [`DataError::Io`] if the file cannot be read; [`DataError::Incomplete`] if it lies in a
/// run directory that is still being written or was interrupted
/// ([`crate::io::run_dir::check_complete`]);
/// [`DataError::Malformed`] naming `file:line` for a non-numeric or non-finite value, a row
/// whose field count differs from the first row's, decimal commas, a missing column, an
/// unknown column name, a time column that is not uniform, or a file without data rows.
pub fn read_table(path: &str, opts: &SeriesReadOptions) -> Result<SeriesTable, DataError> {
    let io_err = |source| DataError::Io {
        path: path.to_string(),
        source,
    };
    if path == "-" {
        let stdin = std::io::stdin();
        parse_table(stdin.lock(), "<stdin>", opts)
    } else {
        crate::io::run_dir::check_complete(std::path::Path::new(path))?;
        let file = std::fs::File::open(path).map_err(io_err)?;
        parse_table(BufReader::new(file), path, opts)
    }
}

/// Reads one column (the first of `opts.columns`, or the automatic choice) of a series file.
///
/// # Errors
/// Those of [`read_table`].
pub fn read_series(path: &str, opts: &SeriesReadOptions) -> Result<Vec<f64>, DataError> {
    let mut one = opts.clone();
    one.columns.truncate(1);
    Ok(read_columns(path, &one)?.remove(0))
}

/// Parses series text from any buffered reader; `name` is used in error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_columns(
    reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    Ok(parse_table(reader, name, opts)?.columns)
}

/// Parses series text held in memory (e.g. in tests); `name` is used in error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_str(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<Vec<Vec<f64>>, DataError> {
    parse_columns(text.as_bytes(), name, opts)
}

/// [`parse_table`] of text held in memory.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_table_str(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, DataError> {
    parse_table(text.as_bytes(), name, opts)
}

/// Parses series text from any buffered reader into a [`SeriesTable`]; `name` is used in
/// error messages.
///
/// # Errors
/// Those of [`read_table`].
pub fn parse_table(
    mut reader: impl BufRead,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, DataError> {
    let malformed = |line: usize, message: String| DataError::Malformed {
        path: name.to_string(),
        line,
        message,
    };
    if opts.decimal_comma && opts.delimiter == Some(Delimiter::Comma) {
        return Err(malformed(
            0,
            "--decimal-comma with --delimiter comma: a comma cannot be both; the delimiter of \
             a decimal-comma file is a semicolon, tab or whitespace"
                .into(),
        ));
    }
    let mut layout: Option<Layout> = None;
    // kept columns (selected, time candidates) by 0-based index; the rest are only counted
    let mut raw: Vec<Option<Vec<f64>>> = Vec::new();
    let mut rows = 0usize;
    let mut line = String::new();
    let mut lineno = 0usize;
    // byte ranges of the fields of the current line (no allocation per line)
    let mut fields: Vec<(usize, usize)> = Vec::new();
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
        let lay = match &layout {
            Some(l) => l,
            None => {
                let l = first_row(trimmed, lineno, opts).map_err(|m| malformed(lineno, m))?;
                raw = kept_columns(&l, opts).map_err(|m| malformed(lineno, m))?;
                let is_header = l.header.is_some();
                layout = Some(l);
                if is_header {
                    continue;
                }
                layout.as_ref().expect("set above")
            }
        };
        field_ranges(trimmed, lay.delimiter, &mut fields);
        if fields.len() != lay.fields {
            return Err(malformed(
                lineno,
                field_count_message(fields.len(), lay, opts, trimmed),
            ));
        }
        for (k, column) in raw.iter_mut().enumerate() {
            if let Some(column) = column {
                let field = &trimmed[fields[k].0..fields[k].1];
                column.push(parse_field(field, k, opts).map_err(|m| malformed(lineno, m))?);
            }
        }
        rows += 1;
    }
    let Some(layout) = layout else {
        return Err(malformed(0, "no data rows found".into()));
    };
    if rows == 0 {
        return Err(malformed(0, "no data rows found".into()));
    }
    select(raw, &layout, opts).map_err(|m| malformed(layout.line, m))
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
