//! The sweep runner: parallel, atomic, resumable, sharded (see the module docs of
//! [`crate::sweep`]).

use super::budget::{available_memory_bytes, free_disk_bytes, Budget};
use super::continuation::Continuation;
use super::shard::Shard;
use super::tables::{out_err, point_path, read_record, stream_name, write_tables, StreamLog};
use super::vary::{grid_len, grid_point, Vary};
use crate::error::{SceneError, SimError};
use crate::model::{RunOptions, RunSummary};
use crate::observe::{fmt_num, NullObserver};
use crate::scene::{Scene, SceneSource};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
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
    /// Strobe rows `cycle,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s`.
    pub(super) strobe: Vec<String>,
    /// The full run summary.
    pub(super) summary: serde_json::Value,
    /// CPU time (s) of the thread that ran the point (bed, settling, drive, replica test and
    /// analysis; a DEM's extra force threads are not counted); absent in points written before
    /// it was recorded, or where the platform cannot measure it. Not part of the physics.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(super) cpu_s: Option<f64>,
}

/// Identity of a sweep, stored in `DIR/sweep.json` so that a rerun resumes only the same sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct Manifest {
    scene: String,
    set: Vec<(String, String)>,
    vary: Vec<(String, Vec<String>)>,
    analysis: bool,
    /// A continuation sweep's settings (absent for an ordinary sweep).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    continuation: Option<Continuation>,
}

impl Manifest {
    fn of(spec: &SweepSpec) -> Manifest {
        Manifest {
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
            continuation: None,
        }
    }

    fn of_continuation(spec: &SweepSpec, c: Option<&Continuation>) -> Manifest {
        Manifest {
            continuation: c.copied(),
            ..Manifest::of(spec)
        }
    }

    /// The continuation settings, if this is a continuation sweep.
    pub(super) fn continuation(&self) -> Option<&Continuation> {
        self.continuation.as_ref()
    }

    /// The values of the varied keys, as in `--vary` (parsed back).
    pub(super) fn values(&self) -> Vec<Vec<toml::Value>> {
        self.vary
            .iter()
            .map(|(_, v)| {
                v.iter()
                    .map(|x| crate::scene::overrides::parse_value(x))
                    .collect()
            })
            .collect()
    }

    /// What every point of the sweep shares: the scene with the `--set` overrides
    /// applied (varied keys as in the base scene), the varied keys, and whether the points were
    /// analysed.
    ///
    /// # Errors
    /// [`SimError::Scene`] if the stored scene or an override no longer parses.
    pub(super) fn identity(
        &self,
    ) -> Result<(crate::scene::SceneSource, Vec<String>, bool), SimError> {
        let mut src = crate::scene::SceneSource::parse(&self.scene)?;
        for (k, v) in &self.set {
            src.set(k, crate::scene::overrides::parse_value(v))?;
        }
        let keys = self.vary.iter().map(|(k, _)| k.clone()).collect();
        Ok((src, keys, self.analysis))
    }

    /// The manifest `DIR/sweep.json`.
    pub(super) fn read(dir: &Path) -> Result<Manifest, SimError> {
        let path = dir.join("sweep.json");
        let text = std::fs::read_to_string(&path).map_err(|e| {
            out_err(
                &path,
                format!("{e} (not a sweep directory: `pdamp sweep` writes sweep.json first)"),
            )
        })?;
        serde_json::from_str(&text).map_err(|e| out_err(&path, e))
    }

    pub(super) fn write(&self, dir: &Path) -> Result<(), SimError> {
        let json = serde_json::to_vec_pretty(self).map_err(|e| SimError::Output(e.to_string()))?;
        atomic_write(&dir.join("sweep.json"), &json)
    }

    /// Points in the grid.
    pub(super) fn points(&self) -> usize {
        let n = self.vary.iter().map(|(_, v)| v.len()).product();
        match &self.continuation {
            Some(c) => c.points(n),
            None => n,
        }
    }

    /// The varied keys, slowest first (and `branch` for a continuation sweep).
    pub(super) fn keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self.vary.iter().map(|(k, _)| k.clone()).collect();
        if self.continuation.is_some() {
            keys.push("branch".into());
        }
        keys
    }
}

/// [`crate::io::atomic_write`] with the sweep's error type ([`SimError::Output`] naming the path).
fn atomic_write(path: &Path, data: &[u8]) -> Result<(), SimError> {
    crate::io::atomic_write(path, data).map_err(|e| match e {
        crate::error::DataError::Io { source, .. } => out_err(path, source),
        other => SimError::Output(other.to_string()),
    })
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

use crate::io::csv_out::push_num;

fn value_str(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

fn fmt_opt(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite()).map(fmt_num).unwrap_or_default()
}

/// Run (or resume) a sweep into `out`: [`run_shard`] of the whole sweep, which also writes
/// `sweep.csv`, `strobe.csv` and `timings.csv`.
///
/// # Errors
/// As [`run_shard`].
pub fn run_sweep(
    spec: &SweepSpec,
    out: &Path,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<SweepReport, SimError> {
    run_shard(spec, out, Shard::WHOLE, on_point)
}

/// Run (or resume) shard `shard` of a sweep into `out`. `on_point` is called after each point
/// finishes (from worker threads) with the number of this shard's points done so far.
///
/// Each finished point is written atomically to `out/points/<i>.json` (the source of truth:
/// a rerun skips the points found there) and appended as one line to the stream log
/// (`stream.csv`, or `stream.shard-K-of-N.csv`), so that the cost of a point does not depend
/// on the size of the sweep. The whole sweep then rebuilds `sweep.csv`, `strobe.csv` and
/// `timings.csv` in point order; a shard leaves that to [`super::merge`] once all shards
/// are done.
///
/// # Errors
/// [`SimError::Scene`] if the grid is too large for the disk or memory (with its size, the
/// estimate and the key, before anything runs) or if a point's scene is invalid (checked for
/// every point of the shard before any runs, naming the key); [`SimError::Output`] for
/// file-system errors or when `out` holds a different sweep.
pub fn run_shard(
    spec: &SweepSpec,
    out: &Path,
    shard: Shard,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<SweepReport, SimError> {
    run_shard_with(spec, None, out, shard, on_point)
}

/// [`run_shard`] of a continuation sweep (`c` set: see [`super::continuation`]) or of an
/// ordinary one (`c = None`).
///
/// # Errors
/// As [`run_shard`]; for a continuation, a `--vary` other than one numeric key, a damper
/// without carried state (DEM), more shards than blocks.
pub fn run_shard_with(
    spec: &SweepSpec,
    c: Option<&Continuation>,
    out: &Path,
    shard: Shard,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<SweepReport, SimError> {
    if let Some(c) = c {
        super::continuation::check(spec, c, shard)?;
    }
    let branches = c.map_or(1, |c| c.direction.branches().len());
    let n = check_budget(spec, out, branches)?;
    if let Some(c) = c {
        let points_dir = out.join("points");
        std::fs::create_dir_all(&points_dir).map_err(|e| out_err(&points_dir, e))?;
        check_manifest(spec, Some(c), out)?;
        let manifest = Manifest::of_continuation(spec, Some(c));
        let keys = manifest.keys();
        let report = super::continuation::run_blocks(spec, c, out, shard, &keys, on_point)?;
        if shard.is_whole() {
            write_all_tables(&manifest, &[out.to_path_buf()], out)?;
        }
        return Ok(report);
    }
    for i in shard.points(n) {
        point_scene(spec, i)?;
    }
    let points_dir = out.join("points");
    std::fs::create_dir_all(&points_dir).map_err(|e| out_err(&points_dir, e))?;
    check_manifest(spec, None, out)?;

    // finished points from an earlier run (unreadable ones, e.g. from a crash mid-write of an
    // old version, are recomputed)
    let mine: Vec<usize> = shard.points(n).collect();
    // each stored point read once: missing (pending) or finished with its physics revision
    let stored: Vec<(usize, Option<u32>)> = mine
        .iter()
        .map(|&i| (i, read_record(&point_path(out, i), i).map(|r| r.physics)))
        .collect();
    let pending: Vec<usize> = stored
        .iter()
        .filter(|(_, p)| p.is_none())
        .map(|(i, _)| *i)
        .collect();
    check_physics(out, stored.iter().filter_map(|(i, p)| p.map(|p| (*i, p))))?;
    let skipped = mine.len() - pending.len();
    let keys: Vec<String> = spec.varies.iter().map(|v| v.key.clone()).collect();
    let label = (!shard.is_whole()).then(|| shard.label());
    let log = StreamLog::open(&out.join(stream_name(label.as_deref())), &keys)?;
    let state = Mutex::new((log, skipped));
    let failed = Mutex::new(Vec::new());
    if skipped > 0 {
        on_point(skipped);
    }

    pending.par_iter().for_each(|&i| {
        let started = std::time::Instant::now();
        let result = point_scene(spec, i)
            .map_err(SimError::from)
            .and_then(|scene| {
                run_point(
                    &scene,
                    &grid_point(&spec.varies, i),
                    i,
                    spec.analyze,
                    &points_dir,
                )
            })
            .and_then(|rec| {
                let json =
                    serde_json::to_vec_pretty(&rec).map_err(|e| SimError::Output(e.to_string()))?;
                write_point(&point_path(out, i), &json)?;
                let mut guard = state.lock().unwrap_or_else(|p| p.into_inner());
                guard.0.append(&rec, started.elapsed().as_secs_f64())?;
                guard.1 += 1;
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

    if shard.is_whole() {
        let present: Vec<(usize, PathBuf)> = (0..n)
            .map(|i| (i, point_path(out, i)))
            .filter(|(_, p)| p.is_file())
            .collect();
        write_tables(&keys, &present, &[out.to_path_buf()], out)?;
    }
    let mut failed = failed.into_inner().unwrap_or_else(|p| p.into_inner());
    failed.sort();
    Ok(SweepReport {
        points: mine.len(),
        skipped,
        computed: pending.len() - failed.len(),
        failed,
    })
}

/// Writes the tables of the finished points of the sweep `manifest` found in `dirs` into
/// `out`: `sweep.csv`, `strobe.csv`, `timings.csv` and, for a continuation sweep,
/// `hysteresis.csv` / `seams.csv`. Points not finished are left out.
///
/// # Errors
/// As [`write_tables`].
pub(super) fn write_all_tables(
    manifest: &Manifest,
    dirs: &[PathBuf],
    out: &Path,
) -> Result<(), SimError> {
    let present: Vec<(usize, PathBuf)> = (0..manifest.points())
        .filter_map(|i| {
            dirs.iter()
                .map(|d| point_path(d, i))
                .find(|p| p.is_file())
                .map(|p| (i, p))
        })
        .collect();
    let rows = write_tables(&manifest.keys(), &present, dirs, out)?;
    if let Some(c) = manifest.continuation() {
        let values = manifest.values();
        let key = &manifest.vary[0].0;
        super::continuation::write_tables(c, key, &values[0], &rows, dirs, out)?;
    }
    Ok(())
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

/// The number of points, after checking that the sweep fits the disk and memory
/// ([`Budget`]); the stroboscopic rows per point are taken as the larger of the first and last
/// point's. A continuation with `branches` = 2 (`both`) runs every point twice.
fn check_budget(spec: &SweepSpec, out: &Path, branches: usize) -> Result<usize, SimError> {
    let rows = |i: usize| -> f64 {
        point_scene(spec, i).map_or(0.0, |s| {
            (s.duration_s() - s.analysis_start_s()).max(0.0) * s.frequency_hz() + 1.0
        })
    };
    let n = grid_len(&spec.varies);
    let strobe_rows = n.map_or(0.0, |n| rows(0).max(rows(n.saturating_sub(1))));
    let budget = Budget::estimate(&spec.varies, strobe_rows, spec.analyze, branches);
    budget.check(&spec.varies, free_disk_bytes(out), available_memory_bytes())?;
    Ok(n.unwrap_or(0))
}

fn check_manifest(spec: &SweepSpec, c: Option<&Continuation>, out: &Path) -> Result<(), SimError> {
    let manifest = Manifest::of_continuation(spec, c);
    if out.join("sweep.json").is_file() {
        if Manifest::read(out).ok().as_ref() != Some(&manifest) {
            return Err(SimError::Output(format!(
                "{} holds a different sweep (scene, --set, --vary, --no-analysis or the \
                 continuation settings differ); \
                 choose another --out directory or delete it to start over",
                out.display()
            )));
        }
        return Ok(());
    }
    manifest.write(out)
}

/// Refuses to resume over finished points (index, physics revision) computed with another
/// physics revision.
fn check_physics(out: &Path, done: impl Iterator<Item = (usize, u32)>) -> Result<(), SimError> {
    let stale: Vec<(usize, u32)> = done
        .filter(|(_, p)| *p != crate::model::PHYSICS_REVISION)
        .collect();
    match stale.first() {
        None => Ok(()),
        Some((i, p)) => Err(SimError::Output(format!(
            "{}: {} finished point(s) (first: points/{i}.json) were computed with physics \
             revision {p}, this binary computes revision {}: their trajectories may differ, \
             so they are not mixed into one table; delete {} to recompute them, or choose \
             another --out directory",
            out.display(),
            stale.len(),
            crate::model::PHYSICS_REVISION,
            out.join("points").display()
        ))),
    }
}

/// The section's scatter quoted beside a verdict: W_n of its tight grouping, else its size
/// (RMS distance from the centroid), relative to the orbit.
fn section_scatter(sec: &crate::analysis::section::SectionAnalysis) -> f64 {
    sec.tight.as_ref().map_or(sec.size, |g| g.scatter)
}

pub(super) fn run_point(
    scene: &Scene,
    values: &[(String, toml::Value)],
    i: usize,
    analyze: bool,
    points_dir: &Path,
) -> Result<PointRecord, SimError> {
    let cpu0 = crate::dem::run::thread_cpu_time_s();
    let s = run_in_point_dir(scene, &points_dir.join(i.to_string()), analyze)?;
    let cpu_s = match (cpu0, crate::dem::run::thread_cpu_time_s()) {
        (Some(a), Some(b)) => Some(b - a),
        _ => None,
    };
    let cells = cells_of(&s);
    // the same text as format!("{},{},…", cycle, fmt_num(…), …), written into one buffer
    let strobe = s
        .strobe
        .iter()
        .map(|p| {
            use std::fmt::Write;
            let mut row = String::with_capacity(96);
            let _ = write!(row, "{}", p.cycle);
            for x in [p.grain_z_m, p.box_z_m, p.grain_v_m_s, p.box_v_m_s] {
                row.push(',');
                push_num(&mut row, x);
            }
            row
        })
        .collect();
    let summary = serde_json::to_value(&s).map_err(|e| SimError::Output(e.to_string()))?;
    Ok(PointRecord {
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
    })
}

/// The formatted cells of a point (`sweep.csv` and `timings.csv` columns) from its typed
/// summary: also used to refresh the cells of a stored point whose derived values (e.g. the
/// replica's growth rate) are computed by a newer rule than the one that wrote it.
pub(super) fn cells_of(s: &RunSummary) -> BTreeMap<String, String> {
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
    let r = s.replica.as_ref();
    for (col, v) in [
        ("regime", a.map(|a| a.regime.as_str().to_string())),
        ("period", a.map(|a| num(a.period))),
        ("verdict", a.map(|a| a.verdict())),
        ("phase_locked", a.map(|a| a.phase_locked.to_string())),
        (
            "locked_fraction",
            a.map(|a| num(a.phase_lock.map(|l| l.locked_fraction))),
        ),
        (
            "section_scatter",
            a.map(|a| num(a.section.as_ref().map(section_scatter))),
        ),
        (
            "chaos_dimension",
            a.map(|a| {
                a.chaos_dimension
                    .map_or(String::new(), |d| d.as_str().to_string())
            }),
        ),
        ("replica", r.map(|r| r.outcome.as_str().to_string())),
        (
            "replica_saturation_rel",
            r.map(|r| num(Some(r.saturation_rel))),
        ),
        (
            "replica_growth_per_s",
            r.map(|r| num(r.growth_rate_per_s().map(|g| g.0))),
        ),
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
    cells
}

/// Runs one point; its own files (DEM snapshots) go under `dir` = `OUT/points/<i>/`, marked
/// incomplete ([`crate::io::run_dir::RUNNING`]) until the run ends and cleared of an earlier
/// attempt's files when it starts.
fn run_in_point_dir(scene: &Scene, dir: &Path, analyze: bool) -> Result<RunSummary, SimError> {
    let mut resolved = scene.resolve()?;
    resolved.place_point_outputs_in(dir);
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
