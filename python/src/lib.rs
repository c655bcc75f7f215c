//! `pdamp._pdamp`: the native half of the Python package `pdamp` (PyO3).
//!
//! Thin wrappers over the pdamp library's public API; numbers travel as numpy arrays, reports
//! as JSON text that `pdamp/__init__.py` turns into dataclasses and dicts (so a field added to
//! a report in the library reaches Python without touching this crate).
//!
//! ```text
//! pdamp/__init__.py (typed Python API, dataclasses) → pdamp._pdamp (this crate) → pdamp (library)
//! ```
//! - [`analysis`]: mutual information, false nearest neighbours, Kantz, the whole analysis;
//! - [`run`]: `simulate` and `sweep` of a scene file or dict;
//! - [`systems`]: the library's reference series (logistic map, Lorenz flow);
//! - [`convert`]: Python values → scene tables, overrides and sweep ranges;
//! - [`errors`]: the library's errors → Python exceptions.

mod analysis;
mod convert;
mod errors;
mod run;
mod systems;

use pyo3::prelude::*;

/// The module `pdamp._pdamp`.
#[pymodule]
fn _pdamp(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    analysis::register(m)?;
    run::register(m)?;
    systems::register(m)?;
    Ok(())
}
