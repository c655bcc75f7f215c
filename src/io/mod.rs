//! Input/output of series and tables: TISEAN-style plain text / CSV series ([`series`]) and
//! atomic file writes ([`atomic_write`]).

pub mod series;

pub use series::{atomic_write, read_columns, read_series, Column, SeriesReadOptions};
