//! Input/output of series and tables: TISEAN-style plain text / CSV series ([`series`]), the
//! run directory of `pdamp simulate` ([`run_dir`]) and
//! atomic file writes ([`atomic_write`], synced; the one copy every writer uses).

pub mod atomic;
pub mod clock;
pub mod csv_out;
pub mod run_dir;
pub mod series;

pub use atomic::atomic_write;
pub use csv_out::CsvOut;
pub use run_dir::RunDir;
pub use series::{read_columns, read_series, Column, SeriesReadOptions};
