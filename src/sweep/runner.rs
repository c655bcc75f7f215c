//! The sweep runner: parallel, atomic, resumable, sharded (see the module docs of
//! [`crate::sweep`]).

use super::budget::{available_memory_bytes, free_disk_bytes, Budget};
use super::continuation::Continuation;
use super::point::{out_err, point_path, point_scene, run_point, value_str, write_point};
pub use super::point::{SweepReport, SweepSpec};
use super::shard::Shard;
use super::tables::{ranges, read_record, stream_name, write_tables, StreamLog};
use super::vary::{grid_len, grid_point};
use crate::error::SimError;
use crate::model::RunSummary;
use crate::observe::Recorded;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

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
    super::stop::clear();
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
    run_ordinary(spec, out, shard, n, on_point, &[]).map(|(report, _)| report)
}

/// Run (or resume) a whole ordinary sweep as [`run_sweep`] does, and keep in memory the
/// samples of the points `keep` computed now (each point's analysis window on the analysis
/// clock, [`crate::setup::steady_series`]) with their summaries — what a figure of one point
/// draws, without running the point a second time. Points found finished are not rerun and
/// not kept.
///
/// # Errors
/// As [`run_shard`].
pub fn run_sweep_keeping(
    spec: &SweepSpec,
    out: &Path,
    on_point: &(dyn Fn(usize) + Sync),
    keep: &[usize],
) -> Result<(SweepReport, Vec<KeptRun>), SimError> {
    super::stop::clear();
    let n = check_budget(spec, out, 1)?;
    run_ordinary(spec, out, Shard::WHOLE, n, on_point, keep)
}

/// A point's run kept by [`run_sweep_keeping`].
#[derive(Debug, Clone)]
pub struct KeptRun {
    /// The point's index in the grid.
    pub point: usize,
    /// Its summary (as stored in `points/<i>.json`).
    pub summary: RunSummary,
    /// Its samples over the analysis window.
    pub samples: Recorded,
}

/// The points of `shard` of an ordinary (not continued) sweep of `n` points, keeping the
/// samples of the points in `keep` that run now.
fn run_ordinary(
    spec: &SweepSpec,
    out: &Path,
    shard: Shard,
    n: usize,
    on_point: &(dyn Fn(usize) + Sync),
    keep: &[usize],
) -> Result<(SweepReport, Vec<KeptRun>), SimError> {
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
    let kept = Mutex::new(Vec::new());
    if skipped > 0 {
        on_point(skipped);
    }

    pending.par_iter().for_each(|&i| {
        let started = std::time::Instant::now();
        // a point not started when a stop is asked for is not started
        let scene = match super::stop::requested() {
            true => Err(super::stop::interrupted()),
            false => point_scene(spec, i).map_err(SimError::from),
        };
        let mut samples = keep.contains(&i).then(Recorded::default);
        let result = scene
            .and_then(|scene| {
                run_point(
                    &scene,
                    &grid_point(&spec.varies, i),
                    i,
                    spec.analyze,
                    &points_dir,
                    samples.as_mut(),
                )
            })
            .and_then(|(rec, summary)| {
                let json =
                    serde_json::to_vec_pretty(&rec).map_err(|e| SimError::Output(e.to_string()))?;
                write_point(&point_path(out, i), &json)?;
                let mut guard = state.lock().unwrap_or_else(|p| p.into_inner());
                guard.0.append(&rec, started.elapsed().as_secs_f64())?;
                guard.1 += 1;
                on_point(guard.1);
                if let Some(samples) = samples.take() {
                    let kept_run = KeptRun {
                        point: i,
                        summary,
                        samples,
                    };
                    kept.lock()
                        .unwrap_or_else(|p| p.into_inner())
                        .push(kept_run);
                }
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
    let mut kept = kept.into_inner().unwrap_or_else(|p| p.into_inner());
    kept.sort_by_key(|k| k.point);
    let report = SweepReport {
        points: mine.len(),
        skipped,
        computed: pending.len() - failed.len(),
        failed,
    };
    Ok((report, kept))
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

/// What [`merge`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeReport {
    /// Points in the sweep's grid.
    pub points: usize,
    /// How many points each directory contributed (in the order given).
    pub per_dir: Vec<usize>,
}

/// Merges the shards of one sweep: checks that every directory in `dirs` holds the same
/// sweep (its `sweep.json` manifest), that every point of the grid is finished in one of
/// them, and writes `sweep.csv`, `strobe.csv` and `timings.csv` (and the manifest) into `out`
/// — byte-identical `sweep.csv` and `strobe.csv` to an unsharded run of the same sweep.
///
/// # Errors
/// [`SimError::Output`] if a directory has no manifest or a different one, if points are
/// missing (listing them, nothing is written), or for file-system errors.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<MergeReport, SimError> {
    let Some(first) = dirs.first() else {
        return Err(SimError::Output("merge: no sweep directories given".into()));
    };
    let manifest = Manifest::read(first)?;
    for d in &dirs[1..] {
        if Manifest::read(d)? != manifest {
            return Err(SimError::Output(format!(
                "{} holds a different sweep than {} (scene, --set, --vary or --no-analysis \
                 differ): only shards of one sweep can be merged",
                d.display(),
                first.display()
            )));
        }
    }
    let n = manifest.points();
    let mut per_dir = vec![0; dirs.len()];
    let mut missing = Vec::new();
    for i in 0..n {
        let found = dirs
            .iter()
            .enumerate()
            .find(|(_, d)| point_path(d, i).is_file());
        match found {
            Some((k, _)) => per_dir[k] += 1,
            None => missing.push(i),
        }
    }
    let whose = if manifest.continuation().is_some() {
        "a continuation sweep's shard K of N holds a contiguous range of blocks"
    } else {
        "point i belongs to shard i mod N of --shard K/N"
    };
    if !missing.is_empty() {
        return Err(SimError::Output(format!(
            "{} of {n} points are not finished in {}: {}; run (or rerun) the shards that \
             hold them — {whose} — then merge again",
            missing.len(),
            dirs.iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            ranges(&missing)
        )));
    }
    std::fs::create_dir_all(out).map_err(|e| out_err(out, e))?;
    if !out.join("sweep.json").is_file() {
        manifest.write(out)?;
    }
    super::runner::write_all_tables(&manifest, dirs, out)?;
    Ok(MergeReport { points: n, per_dir })
}
