//! Parsing series text held in memory, large files on all cores: the lines up to the first row
//! (skipped lines, comments, the header) are read in order, the rest is cut at line ends into
//! pieces of [`PIECE_BYTES`] that are parsed in parallel and joined in file order. The pieces
//! depend on the text alone, and every line is parsed by the same [`Rows::line`] as a
//! stream's, so the table and the first error (its line number counted over the whole file)
//! are those of reading the text line by line, whatever the thread count.

use rayon::prelude::*;

use super::rows::Rows;
use super::types::{SeriesReadOptions, SeriesTable};
use crate::error::DataError;

/// Bytes per piece parsed on one thread (about 7 000 lines of a one-column file).
pub(super) const PIECE_BYTES: usize = 128 * 1024;

/// [`super::parse_table`] of text in memory.
pub(super) fn parse_text(
    text: &str,
    name: &str,
    opts: &SeriesReadOptions,
) -> Result<SeriesTable, DataError> {
    let mut sink = Rows::new(name, opts)?;
    let mut rest = text;
    // in order up to the first data row (past the skipped lines and the header), and to the
    // end when a row limit is set or what is left is too short to share
    while !rest.is_empty()
        && (sink.rows == 0
            || sink.lineno < opts.skip_lines
            || opts.max_rows.is_some()
            || rest.len() < 2 * PIECE_BYTES)
    {
        let (line, after) = split_line(rest);
        rest = after;
        if !sink.line(line)? {
            return sink.finish();
        }
    }
    if rest.is_empty() {
        return sink.finish();
    }
    let pieces = pieces(rest);
    let parsed: Vec<Result<Rows<'_>, DataError>> = pieces
        .par_iter()
        .map(|piece| {
            let mut part = Rows::continuing(&sink);
            for line in piece.split('\n') {
                part.line(line)?;
            }
            Ok(part)
        })
        .collect();
    let mut before = sink.lineno;
    for part in parsed {
        match part {
            Ok(part) => {
                before += part.lineno;
                sink.append(part);
            }
            Err(DataError::Malformed {
                path,
                line,
                message,
            }) => {
                return Err(DataError::Malformed {
                    path,
                    line: before + line,
                    message,
                })
            }
            Err(e) => return Err(e),
        }
    }
    sink.finish()
}

/// The first line of `text` (without its `\n`) and the text after it.
fn split_line(text: &str) -> (&str, &str) {
    match text.find('\n') {
        Some(k) => (&text[..k], &text[k + 1..]),
        None => (text, ""),
    }
}

/// `text` cut after a line end every [`PIECE_BYTES`] or so; the pieces hold whole lines
/// without the last line end of each, so that splitting each at `\n` gives the lines of
/// `text` in order.
fn pieces(text: &str) -> Vec<&str> {
    let mut out = Vec::with_capacity(text.len() / PIECE_BYTES + 1);
    let mut rest = text;
    while rest.len() > PIECE_BYTES {
        // bytes, not `str` indices: PIECE_BYTES may fall inside a multi-byte character; a
        // `\n` byte never does, so the cut after it is a character boundary
        let Some(k) = rest.as_bytes()[PIECE_BYTES..]
            .iter()
            .position(|&b| b == b'\n')
        else {
            break;
        };
        let end = PIECE_BYTES + k;
        out.push(&rest[..end]);
        rest = &rest[end + 1..];
    }
    if !rest.is_empty() {
        out.push(rest);
    }
    out
}
