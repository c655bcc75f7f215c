//! Reading a series file or text into a [`SeriesTable`]: the entry points (file, standard
//! input, reader, memory) and the stream's line loop ([`parse_table`]; the lines themselves are
//! read by [`Rows`]).

use std::io::{BufRead, BufReader};

use super::rows::Rows;
use super::types::{SeriesReadOptions, SeriesTable};
use crate::error::DataError;

/// Files larger than this are read line by line as a stream (memory: the kept columns only);
/// smaller ones are read whole and parsed on all cores ([`super::parallel`]).
const STREAM_ABOVE_BYTES: u64 = 1 << 30;

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
        if file.metadata().map_err(io_err)?.len() > STREAM_ABOVE_BYTES {
            return parse_table(BufReader::new(file), path, opts);
        }
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut &file, &mut bytes).map_err(io_err)?;
        match String::from_utf8(bytes) {
            Ok(text) => parse_table_str(&text, path, opts),
            Err(e) => {
                let valid = e.utf8_error().valid_up_to();
                let bytes = e.as_bytes();
                Err(DataError::Malformed {
                    path: path.to_string(),
                    line: 1 + bytes[..valid].iter().filter(|&&b| b == b'\n').count(),
                    message: "not UTF-8 text: a series file is plain text (numbers, `#` \
                              comments, an optional header); convert it, e.g. with `iconv`"
                        .into(),
                })
            }
        }
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
    super::parallel::parse_text(text, name, opts)
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
    let mut sink = Rows::new(name, opts)?;
    let mut line = String::new();
    loop {
        line.clear();
        let read = reader
            .read_line(&mut line)
            .map_err(|source| DataError::Io {
                path: name.to_string(),
                source,
            })?;
        if read == 0 || !sink.line(&line)? {
            break;
        }
    }
    sink.finish()
}
