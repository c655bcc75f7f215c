//! Input/output of series and tables: TISEAN-style plain text / CSV series ([`series`]), the
//! run directory of `pdamp simulate` ([`run_dir`]), the free-decay envelope's `decay.csv`
//! ([`decay`]); atomic file writes ([`atomic_write`],
//! synced; the one copy every writer uses) and CSV text ([`CsvOut`]) live beneath the
//! observers, in [`crate::files`], and are re-exported here.

pub mod clock;
pub mod decay;
pub mod provenance;
pub mod run_dir;
pub mod schema;
pub mod series;

pub use crate::files::{atomic, csv_out};
pub use crate::files::{atomic_write, CsvOut};
pub use decay::{write_decay_csv, DECAY_COLUMNS, DECAY_CSV};
pub use run_dir::RunDir;
pub use series::{read_columns, read_series, Column, SeriesReadOptions};
