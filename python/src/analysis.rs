//! The analysis estimators on a 1-D float64 array: each wrapper builds the library's options
//! from keyword arguments (the defaults are the library's), runs the estimator without the GIL
//! and returns numpy arrays (`NaN` where the library has `None`).

use numpy::{PyArray1, PyArray2, PyReadonlyArray1};
use pdamp::analysis::analyze::{analyze_series, AnalyzeOptions};
use pdamp::analysis::kantz::{
    estimate_from_curves, fit_scaling_region, kantz as kantz_curves, KantzDefinition, KantzOptions,
    ScalingOptions,
};
use pdamp::analysis::{
    false_nearest_neighbors as fnn, mutual_information as mi, FnnOptions, FnnVectors,
    MutualInformationOptions,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;

/// Adds the analysis functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(mutual_information, m)?)?;
    m.add_function(wrap_pyfunction!(false_nearest_neighbors, m)?)?;
    m.add_function(wrap_pyfunction!(kantz, m)?)?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    Ok(())
}

fn nan(x: Option<f64>) -> f64 {
    x.unwrap_or(f64::NAN)
}

/// Time-delayed mutual information I(τ), τ = 0..=max_lag (nats; SPEC (4.1.5), TISEAN
/// `mutual`). Returns `(values, first_minimum or None, bins)`.
#[pyfunction]
#[pyo3(signature = (x, bins=None, max_lag=None))]
fn mutual_information<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    bins: Option<usize>,
    max_lag: Option<usize>,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Option<usize>, usize)> {
    let x = x.as_slice()?;
    let d = MutualInformationOptions::default();
    let opts = MutualInformationOptions {
        bins: bins.unwrap_or(d.bins),
        max_lag: max_lag.unwrap_or(d.max_lag),
    };
    let r = py.detach(|| mi(x, &opts)).map_err(errors::analysis)?;
    Ok((PyArray1::from_vec(py, r.values), r.first_minimum, r.bins))
}

/// False nearest neighbours for m = m_min..=m_max (SPEC (4.1.4)). Returns a dict of arrays
/// `m, fraction (NaN: no accepted neighbour), accepted, false_count, mean_distance,
/// rms_distance`.
#[pyfunction]
#[pyo3(signature = (x, m_min=None, m_max=None, tau=None, ratio=None, theiler=None, tisean_vectors=false))]
#[allow(clippy::too_many_arguments)] // one keyword argument per library option
fn false_nearest_neighbors<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    m_min: Option<usize>,
    m_max: Option<usize>,
    tau: Option<usize>,
    ratio: Option<f64>,
    theiler: Option<usize>,
    tisean_vectors: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let x = x.as_slice()?;
    let d = FnnOptions::default();
    let opts = FnnOptions {
        m_min: m_min.unwrap_or(d.m_min),
        m_max: m_max.unwrap_or(d.m_max),
        tau: tau.unwrap_or(d.tau),
        ratio: ratio.unwrap_or(d.ratio),
        theiler: theiler.or(d.theiler),
        vectors: if tisean_vectors {
            FnnVectors::TiseanUnivariate
        } else {
            FnnVectors::Delay
        },
    };
    let points = py.detach(|| fnn(x, &opts)).map_err(errors::analysis)?;
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&pdamp::analysis::FnnPoint) -> f64| -> Vec<f64> {
        points.iter().map(f).collect()
    };
    let ints = |f: &dyn Fn(&pdamp::analysis::FnnPoint) -> usize| -> Vec<u64> {
        points.iter().map(|p| f(p) as u64).collect()
    };
    d.set_item("m", PyArray1::from_vec(py, ints(&|p| p.m)))?;
    d.set_item(
        "fraction",
        PyArray1::from_vec(py, col(&|p| nan(p.fraction))),
    )?;
    d.set_item("accepted", PyArray1::from_vec(py, ints(&|p| p.accepted)))?;
    d.set_item(
        "false_count",
        PyArray1::from_vec(py, ints(&|p| p.false_count)),
    )?;
    d.set_item(
        "mean_distance",
        PyArray1::from_vec(py, col(&|p| p.mean_distance)),
    )?;
    d.set_item(
        "rms_distance",
        PyArray1::from_vec(py, col(&|p| p.rms_distance)),
    )?;
    Ok(d)
}

fn definition(name: &str) -> PyResult<KantzDefinition> {
    match name {
        "mean-distance" => Ok(KantzDefinition::MeanDistance),
        "tisean-rms" => Ok(KantzDefinition::TiseanRms),
        other => Err(PyValueError::new_err(format!(
            "definition = {other:?}: expected \"mean-distance\" (pdamp, (4.1.7)) or \"tisean-rms\" (TISEAN lyap_k)"
        ))),
    }
}

/// Kantz's stretching curves S(Δn) for every (ε, m) (SPEC (4.1.7)) and the median slope of
/// their linear regions. Returns a dict: `m, eps` (per curve), `s` (curves × (steps+1), NaN
/// where no reference had a neighbour), `count`, `range`, per-curve fits `fit_start, fit_end,
/// fit_slope, fit_r2, fit_linear`, and `exponent` (a dict, or None with `exponent_error`).
#[pyfunction]
#[pyo3(signature = (x, m_min=None, m_max=None, tau=None, eps_min=None, eps_max=None, eps_count=None, references=None, steps=None, theiler=None, definition_name=None))]
#[allow(clippy::too_many_arguments)] // one keyword argument per library option
fn kantz<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    m_min: Option<usize>,
    m_max: Option<usize>,
    tau: Option<usize>,
    eps_min: Option<f64>,
    eps_max: Option<f64>,
    eps_count: Option<usize>,
    references: Option<usize>,
    steps: Option<usize>,
    theiler: Option<usize>,
    definition_name: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let x = x.as_slice()?;
    let d = KantzOptions::default();
    let opts = KantzOptions {
        m_min: m_min.unwrap_or(d.m_min),
        m_max: m_max.unwrap_or(d.m_max),
        tau: tau.unwrap_or(d.tau),
        eps_min: eps_min.or(d.eps_min),
        eps_max: eps_max.or(d.eps_max),
        eps_count: eps_count.unwrap_or(d.eps_count),
        references: references.or(d.references),
        steps: steps.unwrap_or(d.steps),
        theiler: theiler.or(d.theiler),
        definition: definition_name.map_or(Ok(d.definition), definition)?,
    };
    let r = py
        .detach(|| kantz_curves(x, &opts))
        .map_err(errors::analysis)?;
    let scaling = ScalingOptions::default();
    let fits: Vec<_> = r
        .curves
        .iter()
        .map(|c| fit_scaling_region(&c.s, &scaling))
        .collect();
    let d = PyDict::new(py);
    let per_curve = |f: &dyn Fn(usize) -> f64| -> Vec<f64> { (0..r.curves.len()).map(f).collect() };
    d.set_item(
        "m",
        PyArray1::from_vec(py, r.curves.iter().map(|c| c.m as u64).collect()),
    )?;
    d.set_item(
        "eps",
        PyArray1::from_vec(py, per_curve(&|i| r.curves[i].eps)),
    )?;
    let s: Vec<Vec<f64>> = r
        .curves
        .iter()
        .map(|c| c.s.iter().map(|v| nan(*v)).collect())
        .collect();
    let count: Vec<Vec<u64>> = r.curves.iter().map(|c| c.count.clone()).collect();
    d.set_item("s", PyArray2::from_vec2(py, &s)?)?;
    d.set_item("count", PyArray2::from_vec2(py, &count)?)?;
    d.set_item("range", r.range)?;
    let fit = |f: &dyn Fn(&pdamp::analysis::kantz::SlopeFit) -> f64| -> Vec<f64> {
        fits.iter()
            .map(|v| v.as_ref().map_or(f64::NAN, f))
            .collect()
    };
    d.set_item(
        "fit_start",
        PyArray1::from_vec(py, fit(&|f| f.start as f64)),
    )?;
    d.set_item("fit_end", PyArray1::from_vec(py, fit(&|f| f.end as f64)))?;
    d.set_item("fit_slope", PyArray1::from_vec(py, fit(&|f| f.slope)))?;
    d.set_item("fit_r2", PyArray1::from_vec(py, fit(&|f| f.r2)))?;
    d.set_item(
        "fit_linear",
        fits.iter()
            .map(|v| v.is_some_and(|f| f.linear))
            .collect::<Vec<bool>>(),
    )?;
    match estimate_from_curves(&r, &scaling) {
        Ok(e) => {
            let json = serde_json::to_string(&e)
                .map_err(|err| errors::AnalysisError::new_err(err.to_string()))?;
            d.set_item("exponent", json)?;
        }
        Err(e) => {
            d.set_item("exponent", py.None())?;
            d.set_item("exponent_error", e.to_string())?;
        }
    }
    Ok(d)
}

/// The whole analysis chain and the regime verdict ([`analyze_series`], as `pdamp analyze`).
/// Returns the report as JSON text (the `analysis` object of `summary.json`) with `verdict`
/// added (`periodic-2`, `chaotic`, …).
#[pyfunction]
#[pyo3(signature = (x, dt=None, forcing_hz=None, max_samples=None, max_lag=None, max_dim=None, fnn_threshold=None, max_fnn_samples=None, kantz_references=None, seed=None))]
#[allow(clippy::too_many_arguments)] // one keyword argument per library option
fn analyze(
    py: Python<'_>,
    x: PyReadonlyArray1<'_, f64>,
    dt: Option<f64>,
    forcing_hz: Option<f64>,
    max_samples: Option<usize>,
    max_lag: Option<usize>,
    max_dim: Option<usize>,
    fnn_threshold: Option<f64>,
    max_fnn_samples: Option<usize>,
    kantz_references: Option<usize>,
    seed: Option<u64>,
) -> PyResult<String> {
    let x = x.as_slice()?;
    let d = AnalyzeOptions::default();
    let opts = AnalyzeOptions {
        dt_s: dt,
        forcing_hz,
        max_samples: max_samples.unwrap_or(d.max_samples),
        max_lag: max_lag.unwrap_or(d.max_lag),
        max_dim: max_dim.unwrap_or(d.max_dim),
        fnn_threshold: fnn_threshold.unwrap_or(d.fnn_threshold),
        max_fnn_samples: max_fnn_samples.unwrap_or(d.max_fnn_samples),
        kantz_references: kantz_references.unwrap_or(d.kantz_references),
        seed: seed.unwrap_or(d.seed),
        ..d
    };
    let report = py
        .detach(|| analyze_series(x, &opts))
        .map_err(errors::analysis)?;
    let mut value =
        serde_json::to_value(&report).map_err(|e| errors::AnalysisError::new_err(e.to_string()))?;
    if let Some(obj) = value.as_object_mut() {
        obj.insert("verdict".into(), report.verdict().into());
    }
    Ok(value.to_string())
}
