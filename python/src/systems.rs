//! The library's reference systems ([`pdamp::systems`]) with their literature exponents, so
//! that Python users and the package's tests take the same series and values as the Rust
//! tests.

use numpy::PyArray1;
use pdamp::systems::{henon, logistic, lorenz, roessler};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Adds the generators and the `LYAPUNOV` dict to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(logistic_series, m)?)?;
    m.add_function(wrap_pyfunction!(henon_x, m)?)?;
    m.add_function(wrap_pyfunction!(lorenz_x, m)?)?;
    m.add_function(wrap_pyfunction!(roessler_x, m)?)?;
    let exponents = PyDict::new(m.py());
    exponents.set_item("logistic_r4_per_iteration", logistic::LYAPUNOV_R4)?;
    exponents.set_item("henon_per_iteration", henon::LYAPUNOV)?;
    exponents.set_item("lorenz_per_time", lorenz::LYAPUNOV)?;
    exponents.set_item("roessler_per_time", roessler::LYAPUNOV)?;
    m.add("LYAPUNOV", exponents)?;
    Ok(())
}

/// `n` iterates of the logistic map `x ← r x (1 − x)` from `x0` after `transient` iterates.
#[pyfunction]
#[pyo3(signature = (r, x0, n, transient=100))]
fn logistic_series(
    py: Python<'_>,
    r: f64,
    x0: f64,
    n: usize,
    transient: usize,
) -> PyResult<Bound<'_, PyArray1<f64>>> {
    if !(r > 0.0 && r <= 4.0 && x0 > 0.0 && x0 < 1.0) {
        return Err(PyValueError::new_err(format!(
            "logistic map: r = {r}, x0 = {x0}: need 0 < r ≤ 4 and 0 < x0 < 1"
        )));
    }
    Ok(PyArray1::from_vec(
        py,
        py.detach(|| logistic::logistic_series(r, x0, n, transient)),
    ))
}

/// x of `n` iterates of the Hénon map (1.4, 0.3) after 1000 transient iterates.
#[pyfunction]
fn henon_x(py: Python<'_>, n: usize) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_vec(py, py.detach(|| henon::henon_x(n)))
}

fn check_dt(dt: f64) -> PyResult<()> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!(
            "dt = {dt}: the sampling interval must be > 0 (time units)"
        )))
    }
}

/// x of the Lorenz flow (10, 28, 8/3): `n` samples every `dt` after 50 time units (RK4).
#[pyfunction]
fn lorenz_x(py: Python<'_>, n: usize, dt: f64) -> PyResult<Bound<'_, PyArray1<f64>>> {
    check_dt(dt)?;
    Ok(PyArray1::from_vec(
        py,
        py.detach(|| lorenz::lorenz_x(n, dt)),
    ))
}

/// x of the Rössler flow (0.2, 0.2, 5.7): `n` samples every `dt` (RK4).
#[pyfunction]
fn roessler_x(py: Python<'_>, n: usize, dt: f64) -> PyResult<Bound<'_, PyArray1<f64>>> {
    check_dt(dt)?;
    Ok(PyArray1::from_vec(
        py,
        py.detach(|| roessler::roessler_x(n, dt)),
    ))
}
