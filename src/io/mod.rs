//! Input/output of series and tables: TISEAN-style plain text / CSV series ([`series`]) and
//! atomic file writes ([`atomic_write`], synced; the one copy every writer uses).

pub mod atomic;
pub mod series;

pub use atomic::atomic_write;
pub use series::{read_columns, read_series, Column, SeriesReadOptions};
