//! Reading one- or many-column series files as TISEAN users expect — and refusing what cannot
//! be read unambiguously.
//!
//! Accepted format: one sample per line; blank lines and lines starting with `#` are skipped;
//! an optional header row (the first non-comment line, if any field is not a number) names the
//! columns. Columns are selected by 1-based number as TISEAN's `-c`, or by header name. `-`
//! reads standard input.
//!
//! What the reader checks, so that nothing is misread silently:
//! - **One delimiter per file**: comma, semicolon, tab or whitespace, detected from the first
//!   non-comment line (header or first data row) or given ([`SeriesReadOptions::delimiter`]).
//! - **Every row has the field count of the first row**; a row with more or fewer fields is an
//!   error naming the line.
//! - **Decimal commas** (`-4,408e0`, `0,25`) are refused with the way to convert them, unless
//!   [`SeriesReadOptions::decimal_comma`] says the file uses them (then the delimiter is a
//!   semicolon, tab or whitespace).
//! - **A time column**: a first column named `t`, `time` or `time_s` (any case) that increases
//!   uniformly is taken as time ([`SeriesTable::time`], with its inferred step `dt`); with no
//!   column selected, the data column is then the next one. A time-named first column that
//!   is not uniformly increasing is an error unless columns are selected explicitly.

//!
//! Files: the types, the entry points and line loop, the fields of a line, the choice of
//! columns; their public items are re-exported here.

mod columns;
mod fields;
mod parallel;
mod read;
mod rows;
mod types;

pub use read::{
    parse_columns, parse_str, parse_table, parse_table_str, read_columns, read_series, read_table,
};
pub use types::{Column, Delimiter, SeriesReadOptions, SeriesTable, TimeAxis};

mod tests;
