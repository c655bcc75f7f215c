//! The sweep runner: parallel, atomic, resumable (see the module docs of [`crate::sweep`]).

use super::vary::{grid, Vary};
use crate::error::{SceneError, SimError};
use crate::model::{RunOptions, RunSummary};
use crate::observe::{fmt_num, NullObserver};
use crate::scene::{Scene, SceneSource};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

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

/// Summary columns of sweep.csv after the varied keys (model-specific extras are inserted
/// before `impacts_per_cycle`).
const HEAD: [&str; 6] = [
    "frequency_hz",
    "amplitude_m",
    "reference_amplitude_m",
    "energy_input_j_per_cycle",
    "energy_viscous_j_per_cycle",
    "energy_impact_j_per_cycle",
];
const TAIL: [&str; 9] = [
    "impacts_per_cycle",
    "energy_balance_relative_error",
    "regime",
    "period",
    "mle_per_s",
    "mle_stderr_per_s",
    "model_mle_per_s",
    "model_mle_stderr_per_s",
    "section_points",
];

/// One finished point, as stored in `points/<i>.json`. Cells are pre-formatted so that the CSV
/// is byte-identical however and whenever it is rebuilt.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct PointRecord {
    point: usize,
    /// (key, value) of the varied keys.
    values: Vec<(String, String)>,
    /// Column name → formatted cell.
    cells: BTreeMap<String, String>,
    /// Strobe rows `cycle,grain_z_m,box_z_m`.
    strobe: Vec<String>,
    /// The full run summary.
    summary: serde_json::Value,
}

/// Identity of a sweep, stored in `DIR/sweep.json` so that a rerun resumes only the same sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Manifest {
    scene: String,
    set: Vec<(String, String)>,
    vary: Vec<(String, Vec<String>)>,
    analysis: bool,
}

fn out_err(path: &Path, e: impl std::fmt::Display) -> SimError {
    SimError::Output(format!("{}: {e}", path.display()))
}

/// [`crate::io::atomic_write`] with the sweep's error type ([`SimError::Output`] naming the path).
fn atomic_write(path: &Path, data: &[u8]) -> Result<(), SimError> {
    crate::io::atomic_write(path, data).map_err(|e| match e {
        crate::error::DataError::Io { source, .. } => out_err(path, source),
        other => SimError::Output(other.to_string()),
    })
}

fn value_str(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

fn fmt_opt(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite()).map(fmt_num).unwrap_or_default()
}

/// Run (or resume) a sweep into `out`. `on_point` is called after each point finishes (from
/// worker threads) with the number of points done so far.
///
/// # Errors
/// [`SimError::Scene`] if a point's scene is invalid (checked for every point before any
/// runs, naming the key); [`SimError::Output`] for file-system errors or when `out` holds a
/// different sweep.
pub fn run_sweep(
    spec: &SweepSpec,
    out: &Path,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<SweepReport, SimError> {
    let points = grid(&spec.varies);
    let mut scenes = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let mut ov = spec.set.clone();
        ov.extend(p.iter().cloned());
        let s = spec.base.scene(&ov).map_err(|e| match e {
            SceneError::Invalid { field, value, hint } => SceneError::Invalid {
                field,
                value,
                hint: format!("{hint} (sweep point {i})"),
            },
            other => other,
        })?;
        scenes.push(s);
    }
    let points_dir = out.join("points");
    std::fs::create_dir_all(&points_dir).map_err(|e| out_err(&points_dir, e))?;
    check_manifest(spec, out)?;

    // finished points from an earlier run
    let mut records: Vec<Option<PointRecord>> = vec![None; points.len()];
    for (i, slot) in records.iter_mut().enumerate() {
        let path = point_path(&points_dir, i);
        if let Ok(text) = std::fs::read_to_string(&path) {
            match serde_json::from_str::<PointRecord>(&text) {
                Ok(r) if r.point == i => *slot = Some(r),
                _ => {} // unreadable (e.g. a crash mid-write of an old version): recompute
            }
        }
    }
    let skipped = records.iter().filter(|r| r.is_some()).count();
    let pending: Vec<usize> = (0..points.len())
        .filter(|i| records[*i].is_none())
        .collect();
    let state = Mutex::new((records, skipped));
    let failed = Mutex::new(Vec::new());
    if skipped > 0 {
        on_point(skipped);
    }

    pending.par_iter().for_each(|&i| {
        let result =
            run_point(&scenes[i], &points[i], i, spec.analyze, &points_dir).and_then(|rec| {
                let json =
                    serde_json::to_vec_pretty(&rec).map_err(|e| SimError::Output(e.to_string()))?;
                atomic_write(&point_path(&points_dir, i), &json)?;
                let mut guard = state.lock().unwrap_or_else(|p| p.into_inner());
                guard.0[i] = Some(rec);
                guard.1 += 1;
                let csv = sweep_csv(&spec.varies, &guard.0);
                atomic_write(&out.join("sweep.csv"), csv.as_bytes())?;
                on_point(guard.1);
                Ok(())
            });
        if let Err(e) = result {
            failed
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .push((i, e.to_string()));
        }
    });

    let (records, _) = state.into_inner().unwrap_or_else(|p| p.into_inner());
    atomic_write(
        &out.join("sweep.csv"),
        sweep_csv(&spec.varies, &records).as_bytes(),
    )?;
    atomic_write(
        &out.join("strobe.csv"),
        strobe_csv(&spec.varies, &records).as_bytes(),
    )?;
    let mut failed = failed.into_inner().unwrap_or_else(|p| p.into_inner());
    failed.sort();
    Ok(SweepReport {
        points: points.len(),
        skipped,
        computed: pending.len() - failed.len(),
        failed,
    })
}

fn point_path(dir: &Path, i: usize) -> PathBuf {
    dir.join(format!("{i}.json"))
}

fn check_manifest(spec: &SweepSpec, out: &Path) -> Result<(), SimError> {
    let manifest = Manifest {
        scene: spec.base.to_toml(),
        set: spec
            .set
            .iter()
            .map(|(k, v)| (k.clone(), value_str(v)))
            .collect(),
        vary: spec
            .varies
            .iter()
            .map(|v| (v.key.clone(), v.values.iter().map(value_str).collect()))
            .collect(),
        analysis: spec.analyze,
    };
    let path = out.join("sweep.json");
    if let Ok(text) = std::fs::read_to_string(&path) {
        let old: Option<Manifest> = serde_json::from_str(&text).ok();
        if old.as_ref() != Some(&manifest) {
            return Err(SimError::Output(format!(
                "{} holds a different sweep (scene, --set, --vary or --no-analysis differ); \
                 choose another --out directory or delete it to start over",
                out.display()
            )));
        }
        return Ok(());
    }
    let json = serde_json::to_vec_pretty(&manifest).map_err(|e| SimError::Output(e.to_string()))?;
    atomic_write(&path, &json)
}

fn run_point(
    scene: &Scene,
    values: &[(String, toml::Value)],
    i: usize,
    analyze: bool,
    points_dir: &Path,
) -> Result<PointRecord, SimError> {
    let s = run_in_point_dir(scene, &points_dir.join(i.to_string()), analyze)?;
    let mut cells = BTreeMap::new();
    cells.insert("frequency_hz".to_string(), fmt_num(s.frequency_hz));
    cells.insert("amplitude_m".to_string(), fmt_opt(Some(s.amplitude_m)));
    cells.insert(
        "reference_amplitude_m".to_string(),
        fmt_opt(s.reference_amplitude_m),
    );
    cells.insert(
        "energy_input_j_per_cycle".to_string(),
        fmt_opt(Some(s.energy_input_j_per_cycle)),
    );
    cells.insert(
        "energy_viscous_j_per_cycle".to_string(),
        fmt_opt(Some(s.energy_viscous_j_per_cycle)),
    );
    cells.insert(
        "energy_impact_j_per_cycle".to_string(),
        fmt_opt(Some(s.energy_impact_j_per_cycle)),
    );
    cells.insert(
        "impacts_per_cycle".to_string(),
        fmt_opt(Some(s.impacts_per_cycle)),
    );
    cells.insert(
        "energy_balance_relative_error".to_string(),
        fmt_opt(s.energy_balance_relative_error),
    );
    for (k, v) in &s.extra {
        cells.insert(k.clone(), fmt_opt(Some(*v)));
    }
    // the analysis's typed fields (RunAnalysis); no analysis: empty cells
    let a = s.analysis.as_ref();
    let num = |x: Option<f64>| fmt_opt(x);
    for (col, v) in [
        ("regime", a.map(|a| a.regime.as_str().to_string())),
        ("period", a.map(|a| num(a.period))),
        ("mle_per_s", a.map(|a| num(a.data_mle_per_s))),
        ("mle_stderr_per_s", a.map(|a| num(a.data_mle_stderr_per_s))),
        ("model_mle_per_s", a.map(|a| num(a.model_mle_per_s))),
        (
            "model_mle_stderr_per_s",
            a.map(|a| num(a.model_mle_stderr_per_s)),
        ),
        (
            "section_points",
            a.map(|a| num(a.poincare_section_points.map(|n| n as f64))),
        ),
    ] {
        cells.insert(col.to_string(), v.unwrap_or_default());
    }
    let strobe = s
        .strobe
        .iter()
        .map(|p| {
            format!(
                "{},{},{},{},{}",
                p.cycle,
                fmt_num(p.grain_z_m),
                fmt_num(p.box_z_m),
                fmt_num(p.grain_v_m_s),
                fmt_num(p.box_v_m_s)
            )
        })
        .collect();
    let summary = serde_json::to_value(&s).map_err(|e| SimError::Output(e.to_string()))?;
    Ok(PointRecord {
        point: i,
        values: values
            .iter()
            .map(|(k, v)| (k.clone(), value_str(v)))
            .collect(),
        cells,
        strobe,
        summary,
    })
}

/// Runs one point; its own files (DEM snapshots) go under `dir` = `OUT/points/<i>/`, marked
/// incomplete ([`crate::io::run_dir::RUNNING`]) until the run ends and cleared of an earlier
/// attempt's files when it starts.
fn run_in_point_dir(scene: &Scene, dir: &Path, analyze: bool) -> Result<RunSummary, SimError> {
    let mut resolved = scene.resolve()?;
    resolved.place_outputs_in(dir);
    let run_dir = match resolved.snapshot_dir() {
        Some(_) => Some(crate::io::RunDir::create(dir).map_err(|e| out_err(dir, e))?),
        None => None,
    };
    let opts = RunOptions::summary_only();
    let s = super::run::run_resolved(&resolved, &mut NullObserver, &opts, analyze)?;
    if let Some(d) = run_dir {
        d.finish().map_err(|e| out_err(dir, e))?;
    }
    Ok(s)
}

fn sweep_csv(varies: &[Vary], records: &[Option<PointRecord>]) -> String {
    let known: BTreeSet<&str> = HEAD.iter().chain(TAIL.iter()).copied().collect();
    let extras: BTreeSet<String> = records
        .iter()
        .flatten()
        .flat_map(|r| r.cells.keys())
        .filter(|k| !known.contains(k.as_str()))
        .cloned()
        .collect();
    let mut cols: Vec<String> = vec!["point".into()];
    cols.extend(varies.iter().map(|v| v.key.clone()));
    cols.extend(HEAD.iter().map(|s| s.to_string()));
    cols.extend(extras.iter().cloned());
    cols.extend(TAIL.iter().map(|s| s.to_string()));
    let mut out = cols.join(",");
    out.push('\n');
    for r in records.iter().flatten() {
        let mut row = vec![r.point.to_string()];
        row.extend(r.values.iter().map(|(_, v)| v.clone()));
        for c in &cols[1 + varies.len()..] {
            row.push(r.cells.get(c).cloned().unwrap_or_default());
        }
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

fn strobe_csv(varies: &[Vary], records: &[Option<PointRecord>]) -> String {
    let mut cols: Vec<String> = vec!["point".into(), "frequency_hz".into()];
    cols.extend(varies.iter().map(|v| v.key.clone()));
    cols.extend(["cycle", "grain_z_m", "box_z_m", "grain_v_m_s", "box_v_m_s"].map(String::from));
    let mut out = cols.join(",");
    out.push('\n');
    for r in records.iter().flatten() {
        let mut prefix = format!(
            "{},{}",
            r.point,
            r.cells.get("frequency_hz").map_or("", |s| s.as_str())
        );
        for (_, v) in &r.values {
            prefix.push(',');
            prefix.push_str(v);
        }
        for row in &r.strobe {
            out.push_str(&prefix);
            out.push(',');
            out.push_str(row);
            out.push('\n');
        }
    }
    out
}
