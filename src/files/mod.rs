//! Writing files, beneath everything that writes one: atomic writes ([`atomic_write`], synced;
//! the one copy every writer uses) and CSV text ([`CsvOut`], numbers in their shortest
//! round-trip form). The observers (`crate::observe`) write through these, and so does
//! [`crate::io`], which re-exports them under its own paths (`crate::io::atomic_write`,
//! `crate::io::csv_out`).

pub mod atomic;
pub mod csv_out;

pub use atomic::atomic_write;
pub use csv_out::CsvOut;
