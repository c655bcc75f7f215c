//! `simulate` and `sweep` of a scene (a file path or a dict), as `pdamp simulate` and
//! `pdamp sweep` run them: the same resolve step, the same sampling (every
//! `run.sample_interval` from t = 0), the same analysis, the same files when `out` is given.

use std::path::PathBuf;

use numpy::PyArray1;
use pdamp::error::SimError;
use pdamp::io::RunDir;
use pdamp::model::{RunOptions, RunSummary};
use pdamp::observe::{Observer, Sample, SampleKind, Tee, FIXED_COLUMNS};
use pdamp::sweep::run::run_resolved;
use pdamp::sweep::{run_sweep, SweepSpec};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{convert, errors};

/// Adds `simulate` and `sweep` to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    Ok(())
}

/// The sampled series in memory, one column per `series.csv` column, in its order:
/// [`FIXED_COLUMNS`], the model's columns ([`SampleKind::columns`]), `grain_force_n`. A
/// non-finite value stops the run, as it does `series.csv`'s recorder (but `ceiling_z_m` is
/// `inf` without a ceiling, where the CSV leaves the cell empty).
#[derive(Default)]
struct Columns {
    names: Vec<&'static str>,
    data: Vec<Vec<f64>>,
}

impl Observer for Columns {
    fn start(&mut self, kind: SampleKind) -> Result<(), SimError> {
        self.names = FIXED_COLUMNS.to_vec();
        self.names.extend_from_slice(kind.columns());
        self.names.push("grain_force_n");
        self.data = vec![Vec::new(); self.names.len()];
        Ok(())
    }

    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        let mut values = Vec::with_capacity(self.names.len());
        values.extend_from_slice(&s.fixed_values());
        s.model.for_each_value(|v| values.push(v));
        values.push(s.grain_force_n);
        for ((name, column), v) in self.names.iter().zip(&mut self.data).zip(values) {
            // as series.csv: no NaN leaks; `ceiling_z_m = inf` means no ceiling
            let no_ceiling = *name == "ceiling_z_m" && v == f64::INFINITY;
            if !(v.is_finite() || no_ceiling) {
                return Err(SimError::Unstable {
                    t_s: s.time_s,
                    reason: format!("the sample's {name} is {v}: the state is no longer finite"),
                });
            }
            column.push(v);
        }
        Ok(())
    }
}

/// Stops a run when Python has a pending signal (Ctrl-C): checked at the simulators'
/// progress reports (about once per forcing period, whether the run keeps samples or not),
/// which then end the run; the signal's exception is raised.
///
/// Why at the progress reports: while the run holds no GIL (`py.detach`) Python only sets a
/// flag on SIGINT, and runs its handler when some code asks (`check_signals`). Asking at the
/// samples alone — as this did before — never asked a run without samples (`series=False`,
/// no `out`), which ran to its end past the first Ctrl-C.
#[derive(Default)]
struct Interrupt {
    raised: Option<PyErr>,
}

impl Observer for Interrupt {
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }

    fn progress(&mut self, _t_s: f64, _duration_s: f64) -> Result<(), SimError> {
        if self.raised.is_none() {
            self.raised = Python::attach(|py| py.check_signals()).err();
        }
        match self.raised {
            Some(_) => Err(SimError::Interrupted("Ctrl-C in Python".into())),
            None => Ok(()),
        }
    }
}

/// The summary as a JSON object (`summary.json`'s content, with `auto_choice` when
/// `kind = "auto"` chose the model).
fn summary_json(summary: &RunSummary, auto_choice: Option<String>) -> PyResult<String> {
    let mut value =
        serde_json::to_value(summary).map_err(|e| errors::sim(SimError::Output(e.to_string())))?;
    if let (Some(why), Some(obj)) = (auto_choice, value.as_object_mut()) {
        obj.insert("auto_choice".into(), why.into());
    }
    Ok(value.to_string())
}

/// The stroboscopic points as a dict of arrays (`strobe.csv`'s columns).
fn strobe_dict<'py>(py: Python<'py>, summary: &RunSummary) -> PyResult<Bound<'py, PyDict>> {
    let p = &summary.strobe;
    let col =
        |f: &dyn Fn(&pdamp::model::StrobePoint) -> f64| -> Vec<f64> { p.iter().map(f).collect() };
    let d = PyDict::new(py);
    d.set_item(
        "cycle",
        PyArray1::from_vec(py, p.iter().map(|s| s.cycle).collect()),
    )?;
    d.set_item("time_s", PyArray1::from_vec(py, col(&|s| s.time_s)))?;
    d.set_item("grain_z_m", PyArray1::from_vec(py, col(&|s| s.grain_z_m)))?;
    d.set_item("box_z_m", PyArray1::from_vec(py, col(&|s| s.box_z_m)))?;
    d.set_item(
        "grain_v_m_s",
        PyArray1::from_vec(py, col(&|s| s.grain_v_m_s)),
    )?;
    d.set_item("box_v_m_s", PyArray1::from_vec(py, col(&|s| s.box_v_m_s)))?;
    Ok(d)
}

/// Runs one scene. Returns `(series, strobe, summary_json)`: `series` a dict of arrays in
/// `series.csv`'s column order (empty with `series=False`), `strobe` a dict of arrays,
/// `summary_json` the run summary. With `out`, also writes `pdamp simulate`'s run directory.
#[pyfunction]
#[pyo3(signature = (scene, set=None, analyze=true, series=true, out=None))]
fn simulate<'py>(
    py: Python<'py>,
    scene: &Bound<'py, PyAny>,
    set: Option<&Bound<'py, PyAny>>,
    analyze: bool,
    series: bool,
    out: Option<PathBuf>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyDict>, String)> {
    let scene = convert::scene_source(scene)?
        .scene(&convert::overrides(set)?)
        .map_err(errors::scene)?;
    let resolved = scene.resolve().map_err(errors::scene)?;
    let auto_choice = resolved.auto.as_ref().map(pdamp::choice::auto::describe);
    let dir = out
        .map(|p| RunDir::create(&p).map_err(|e| errors::io(&p, e)))
        .transpose()?;
    let mut csv = dir
        .as_ref()
        .map(|d| d.series_recorder())
        .transpose()
        .map_err(errors::sim)?;
    let opts = if series || dir.is_some() {
        pdamp::setup::full_series(&scene)
    } else {
        RunOptions::summary_only()
    };
    let mut columns = Columns::default();
    let mut interrupt = Interrupt::default();
    let result = py.detach(|| {
        let mut observers: Vec<&mut dyn Observer> = vec![&mut interrupt];
        if series {
            observers.push(&mut columns);
        }
        if let Some(c) = csv.as_mut() {
            observers.push(c);
        }
        run_resolved(&resolved, &mut Tee { observers }, &opts, analyze)
    });
    if let (Some(d), Err(e)) = (&dir, &result) {
        // as `pdamp simulate`: the directory stays marked incomplete, with the reason
        let _ = d.mark_failed(&e.to_string());
    }
    if let Some(e) = interrupt.raised {
        return Err(e);
    }
    let summary = result.map_err(errors::sim)?;
    // the run's warnings (returned by the library), on standard error as `pdamp simulate`
    // says them
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(d) = &dir {
        d.write_outputs(&scene, &summary, auto_choice.clone())
            .map_err(|e| errors::io(d.path(), e))?;
    }
    let series = PyDict::new(py);
    for (name, data) in columns.names.iter().zip(columns.data) {
        series.set_item(*name, PyArray1::from_vec(py, data))?;
    }
    Ok((
        series,
        strobe_dict(py, &summary)?,
        summary_json(&summary, auto_choice)?,
    ))
}

/// What a sweep did: points in the grid, skipped (finished earlier), computed now, and the
/// failed points with their reason.
type SweepOutcome = (usize, usize, usize, Vec<(usize, String)>);

/// Runs (or resumes) a sweep into `out` exactly as `pdamp sweep` does (`sweep.csv`,
/// `strobe.csv`, `points/`). Returns `(points, skipped, computed, failed)` with `failed` a
/// list of `(point, reason)`.
#[pyfunction]
#[pyo3(signature = (scene, vary, out, set=None, analyze=true))]
fn sweep<'py>(
    py: Python<'py>,
    scene: &Bound<'py, PyAny>,
    vary: Vec<(String, Bound<'py, PyAny>)>,
    out: PathBuf,
    set: Option<&Bound<'py, PyAny>>,
    analyze: bool,
) -> PyResult<SweepOutcome> {
    let spec = SweepSpec {
        base: convert::scene_source(scene)?,
        set: convert::overrides(set)?,
        varies: convert::varies(&vary)?,
        analyze,
    };
    let (report, raised) = py.detach(|| sweep_until_interrupted(&spec, &out));
    if let Some(e) = raised {
        return Err(e);
    }
    let report = report.map_err(errors::sim)?;
    Ok((
        report.points,
        report.skipped,
        report.computed,
        report.failed,
    ))
}

/// Runs the sweep on a worker thread while this (Python's main) thread asks Python for
/// pending signals every 50 ms: a Ctrl-C asks the sweep to stop
/// ([`pdamp::sweep::stop::request`]) — the running points end at their next progress report,
/// the others are not started, the finished ones stay on disk — and its exception is
/// returned. (The points run on worker threads, where Python's handler cannot be asked.)
fn sweep_until_interrupted(
    spec: &SweepSpec,
    out: &std::path::Path,
) -> (Result<pdamp::sweep::SweepReport, SimError>, Option<PyErr>) {
    std::thread::scope(|scope| {
        let worker = scope.spawn(|| run_sweep(spec, out, &|_| {}));
        let mut raised = None;
        while !worker.is_finished() {
            std::thread::sleep(std::time::Duration::from_millis(50));
            if raised.is_none() {
                if let Err(e) = Python::attach(|py| py.check_signals()) {
                    pdamp::sweep::stop::request();
                    raised = Some(e);
                }
            }
        }
        let report = worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (report, raised)
    })
}
