//! One point of a sweep: what to sweep ([`SweepSpec`]) and what a sweep did
//! ([`SweepReport`]); the scene of point i, its run in its own directory, and the record
//! stored as `points/<i>.json` (`PointRecord`, with the formatted `sweep.csv` cells).
//! Beneath the tables (`super::tables`), the continuation (`super::continuation`) and the
//! runner (`super::runner`), which all take points from here.

use super::vary::{grid_point, Vary};
use crate::error::{SceneError, SimError};
use crate::io::schema::{StrobeRow, SWEEP_HEAD, SWEEP_TAIL};
use crate::model::{RunOptions, RunSummary};
use crate::observe::{fmt_num, Recorded, Tee};
use crate::scene::{Scene, SceneSource};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What to sweep.
#[derive(Debug, Clone)]
pub struct SweepSpec {
    /// The scene file.
    pub base: SceneSource,
    /// `--set` overrides applied to every point.
    pub set: Vec<(String, toml::Value)>,
    /// The varied keys (several make a grid; the first varies slowest).
    pub varies: Vec<Vary>,
    /// Run the nonlinear analysis of each point's steady state.
    pub analyze: bool,
}

/// What a sweep did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport {
    /// Points in the grid.
    pub points: usize,
    /// Points already finished by an earlier run (skipped).
    pub skipped: usize,
    /// Points computed now.
    pub computed: usize,
    /// Points that failed, with the reason (no point file is written for them, so a rerun
    /// retries them).
    pub failed: Vec<(usize, String)>,
}

/// One finished point, as stored in `points/<i>.json`. Cells are pre-formatted so that the CSV
/// is byte-identical however and whenever it is rebuilt.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct PointRecord {
    pub(super) point: usize,
    /// The [`crate::model::PHYSICS_REVISION`] of the binary that computed it.
    #[serde(default = "super::points::first_revision")]
    pub(super) physics: u32,
    /// (key, value) of the varied keys.
    pub(super) values: Vec<(String, String)>,
    /// Column name → formatted cell.
    pub(super) cells: BTreeMap<String, String>,
    /// Strobe rows (stored as their text `cycle,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s`).
    pub(super) strobe: Vec<StrobeRow>,
    /// The full run summary.
    pub(super) summary: serde_json::Value,
    /// CPU time (s) of the thread that ran the point (bed, settling, drive, replica test and
    /// analysis; a DEM's extra force threads are not counted); absent in points written before
    /// it was recorded, or where the platform cannot measure it. Not part of the physics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) cpu_s: Option<f64>,
}

/// A sweep output error naming `path`.
pub(super) fn out_err(path: &Path, e: impl std::fmt::Display) -> SimError {
    SimError::Output(format!("{}: {e}", path.display()))
}

/// `points/<i>.json` of `dir`.
pub(super) fn point_path(dir: &Path, i: usize) -> PathBuf {
    dir.join("points").join(format!("{i}.json"))
}

/// Writes a point record atomically (temporary file + rename; the temporary file is removed
/// on error, e.g. a full disk) but without [`crate::io::atomic_write`]'s sync: a sweep's
/// cost per point would be the disk's flush latency, and a record lost or cut by an
/// operating-system crash is recomputed anyway, since every record is parsed and checked
/// before a rerun skips its point.
pub(super) fn write_point(path: &Path, data: &[u8]) -> Result<(), SimError> {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(".{name}.tmp{}", std::process::id()));
    let result = std::fs::write(&tmp, data).and_then(|()| std::fs::rename(&tmp, path));
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        out_err(path, e)
    })
}

pub(super) fn value_str(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

fn fmt_opt(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite()).map(fmt_num).unwrap_or_default()
}

/// The scene of point `i`, with the point named in a scene error.
pub(super) fn point_scene(spec: &SweepSpec, i: usize) -> Result<Scene, SceneError> {
    let mut ov = spec.set.clone();
    ov.extend(grid_point(&spec.varies, i));
    spec.base.scene(&ov).map_err(|e| match e {
        SceneError::Invalid { field, value, hint } => SceneError::Invalid {
            field,
            value,
            hint: format!("{hint} (sweep point {i})"),
        },
        other => other,
    })
}

/// The section's scatter quoted beside a verdict: W_n of its tight grouping, else its size
/// (RMS distance from the centroid), relative to the orbit.
fn section_scatter(sec: &crate::analysis::section::SectionAnalysis) -> f64 {
    sec.tight.as_ref().map_or(sec.size, |g| g.scatter)
}

/// Runs point `i` and forms its record; with `keep`, the samples of the analysis window
/// (the analysis clock, [`crate::setup::steady_series`]) also go to `keep` — the same run and
/// trajectory, since the analysis samples on that clock anyway. Returns the typed summary
/// beside the record.
pub(super) fn run_point(
    scene: &Scene,
    values: &[(String, toml::Value)],
    i: usize,
    analyze: bool,
    points_dir: &Path,
    keep: Option<&mut Recorded>,
) -> Result<(PointRecord, RunSummary), SimError> {
    let cpu0 = crate::dem::run::thread_cpu_time_s();
    let s = run_in_point_dir(scene, &points_dir.join(i.to_string()), analyze, keep)?;
    let cpu_s = match (cpu0, crate::dem::run::thread_cpu_time_s()) {
        (Some(a), Some(b)) => Some(b - a),
        _ => None,
    };
    let cells = cells_of(&s);
    let strobe = s.strobe.iter().map(StrobeRow::of).collect();
    let summary = serde_json::to_value(&s).map_err(|e| SimError::Output(e.to_string()))?;
    let record = PointRecord {
        point: i,
        physics: crate::model::PHYSICS_REVISION,
        values: values
            .iter()
            .map(|(k, v)| (k.clone(), value_str(v)))
            .collect(),
        cells,
        strobe,
        summary,
        cpu_s,
    };
    Ok((record, s))
}

/// The formatted cells of a point (`sweep.csv` and `timings.csv` columns) from its typed
/// summary: also used to refresh the cells of a stored point whose derived values (e.g. the
/// replica's growth rate) are computed by a newer rule than the one that wrote it.
pub(super) fn cells_of(s: &RunSummary) -> BTreeMap<String, String> {
    // the cells in the column order of SWEEP_HEAD and SWEEP_TAIL (the model's extras are
    // inserted after the tail's first two, as before)
    let head = [
        fmt_num(s.frequency_hz),
        fmt_opt(Some(s.amplitude_m)),
        fmt_opt(s.reference_amplitude_m),
        fmt_opt(Some(s.energy_input_j_per_cycle)),
        fmt_opt(Some(s.energy_viscous_j_per_cycle)),
        fmt_opt(Some(s.energy_impact_j_per_cycle)),
    ];
    let mut cells: BTreeMap<String, String> =
        SWEEP_HEAD.iter().map(|c| c.to_string()).zip(head).collect();
    let balance = [
        fmt_opt(Some(s.impacts_per_cycle)),
        fmt_opt(s.energy_balance_relative_error),
    ];
    cells.extend(SWEEP_TAIL.iter().map(|c| c.to_string()).zip(balance));
    // the DEM's own figures, by their summary.json keys (a value written as null, e.g. an
    // unmeasured CPU time, has no cell)
    if let Some(serde_json::Value::Object(dem)) =
        s.dem.as_ref().and_then(|d| serde_json::to_value(d).ok())
    {
        for (k, v) in dem {
            if let Some(v) = v.as_f64() {
                cells.insert(k, fmt_opt(Some(v)));
            }
        }
    }
    // the analysis's typed fields (RunAnalysis); no analysis: empty cells
    let a = s.analysis.as_ref();
    let num = |x: Option<f64>| fmt_opt(x);
    let r = s.replica.as_ref();
    let verdict: [Option<String>; 15] = [
        a.map(|a| a.regime.as_str().to_string()),
        a.map(|a| num(a.period)),
        a.map(|a| a.verdict()),
        a.map(|a| a.phase_locked.to_string()),
        a.map(|a| num(a.phase_lock.map(|l| l.locked_fraction))),
        a.map(|a| num(a.section.as_ref().map(section_scatter))),
        a.map(|a| {
            a.chaos_dimension
                .map_or(String::new(), |d| d.as_str().to_string())
        }),
        r.map(|r| r.outcome.as_str().to_string()),
        r.map(|r| num(Some(r.saturation_rel))),
        r.map(|r| num(r.growth_rate_per_s().map(|g| g.0))),
        a.map(|a| num(a.data_mle_per_s)),
        a.map(|a| num(a.data_mle_stderr_per_s)),
        a.map(|a| num(a.model_mle_per_s)),
        a.map(|a| num(a.model_mle_stderr_per_s)),
        a.map(|a| num(a.poincare_section_points.map(|n| n as f64))),
    ];
    for (col, v) in SWEEP_TAIL[2..].iter().zip(verdict) {
        cells.insert(col.to_string(), v.unwrap_or_default());
    }
    cells
}

/// Runs one point; its own files (DEM snapshots) go under `dir` = `OUT/points/<i>/`, marked
/// incomplete ([`crate::io::run_dir::RUNNING`]) until the run ends and cleared of an earlier
/// attempt's files when it starts. `keep`: see [`run_point`].
fn run_in_point_dir(
    scene: &Scene,
    dir: &Path,
    analyze: bool,
    keep: Option<&mut Recorded>,
) -> Result<RunSummary, SimError> {
    let mut resolved = scene.resolve()?;
    resolved.place_point_outputs_in(dir);
    let run_dir = match resolved.snapshot_dir() {
        Some(_) => Some(crate::io::RunDir::create(dir).map_err(|e| out_err(dir, e))?),
        None => None,
    };
    let mut stop = super::stop::StopCheck;
    let s = match keep {
        Some(rec) => {
            let opts = crate::setup::steady_series(scene);
            let mut tee = Tee {
                observers: vec![&mut stop, rec],
            };
            super::run::run_resolved(&resolved, &mut tee, &opts, analyze)?
        }
        None => {
            let opts = RunOptions::summary_only();
            super::run::run_resolved(&resolved, &mut stop, &opts, analyze)?
        }
    };
    super::run::emit_warnings(&s);
    if let Some(d) = run_dir {
        d.finish().map_err(|e| out_err(dir, e))?;
    }
    Ok(s)
}
