//! The library's errors as Python exceptions: bad scenes and bad series are `ValueError`s
//! (`pdamp.SceneError`, `pdamp.AnalysisError`), a run that fails is a `RuntimeError`
//! (`pdamp.SimulationError`), a file that cannot be read or written an `OSError`. The message
//! is the library's own, which names the scene key or parameter and the fix.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    pdamp,
    SceneError,
    PyValueError,
    "A scene (file, dict or override) that pdamp refuses; the message names the key and the fix."
);
create_exception!(
    pdamp,
    AnalysisError,
    PyValueError,
    "A series or parameter the analysis refuses (too short, non-finite, constant, a time column, …)."
);
create_exception!(
    pdamp,
    SimulationError,
    PyRuntimeError,
    "A simulation that could not run to its end (unstable time step, output error, …)."
);

/// Adds the exception types to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("AnalysisError", py.get_type::<AnalysisError>())?;
    m.add("SimulationError", py.get_type::<SimulationError>())?;
    Ok(())
}

/// A scene error as `pdamp.SceneError`.
pub fn scene(e: pdamp::error::SceneError) -> PyErr {
    SceneError::new_err(e.to_string())
}

/// An analysis error as `pdamp.AnalysisError`.
pub fn analysis(e: pdamp::error::AnalysisError) -> PyErr {
    AnalysisError::new_err(e.to_string())
}

/// A run's error: scene errors (named by their key) as `pdamp.SceneError`, the rest as
/// `pdamp.SimulationError`.
pub fn sim(e: pdamp::error::SimError) -> PyErr {
    match e {
        pdamp::error::SimError::Scene(s) => scene(s),
        other => SimulationError::new_err(other.to_string()),
    }
}

/// A file-system error naming the path, as `OSError`.
pub fn io(path: &std::path::Path, e: impl std::fmt::Display) -> PyErr {
    PyOSError::new_err(format!("{}: {e}", path.display()))
}
