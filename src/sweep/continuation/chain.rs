//! Running the chains: each block's warm-up and points in parameter order, every point
//! started from the previous point's last stroboscopic row (position m, velocity m/s at
//! t = nT), resumed from the records already written.

use super::plan::{blocks, check, shard_blocks, Block, Branch, Continuation};
use crate::error::{SceneError, SimError};
use crate::io::schema::StrobeRow;
use crate::scene::{Damper, Scene};
use crate::sweep::point::{
    out_err, point_path, point_scene, run_point, write_point, PointRecord, SweepReport, SweepSpec,
};
use crate::sweep::shard::Shard;
use crate::sweep::tables::{read_record, stream_name, StreamLog};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The scene overrides that start a run from the state of a stroboscopic row.
///
/// # Errors
/// [`SceneError::Invalid`] for a damper without an initial state (DEM).
pub fn state_overrides(
    row: &StrobeRow,
    scene: &Scene,
) -> Result<Vec<(String, toml::Value)>, SceneError> {
    let [gz, bz, gv, bv] = row.state();
    let mut ov = Vec::with_capacity(4);
    if scene.primary.is_some() {
        ov.push((
            "primary.initial_displacement".into(),
            toml::Value::Float(bz),
        ));
        ov.push(("primary.initial_velocity".into(), toml::Value::Float(bv)));
    }
    match &scene.damper {
        Damper::None => {}
        Damper::Impact(p) => {
            // height above the floor; rounding of y − z kept inside [0, gap]
            let mut h = (gz - bz).max(0.0);
            if p.gap.is_finite() && h >= p.gap * (1.0 - 1e-12) {
                h = p.gap;
            }
            ov.push(("damper.initial_height".into(), toml::Value::Float(h)));
            ov.push(("damper.initial_velocity".into(), toml::Value::Float(gv)));
        }
        other => {
            return Err(SceneError::invalid(
                "damper.kind",
                other.kind(),
                "a continuation sweep carries the impact model's state (damper none or impact)",
            ))
        }
    }
    Ok(ov)
}

/// Where the warm-up record of point `i` goes.
pub(super) fn warmup_path(dir: &Path, i: usize) -> PathBuf {
    dir.join("points").join("warmup").join(format!("{i}.json"))
}

/// Runs (or resumes) shard `shard` of a continuation sweep into `out` (see the module docs);
/// called by [`super::runner::run_shard`].
///
/// # Errors
/// As [`super::runner::run_shard`]; a scene whose damper has no carried state (DEM).
pub(in crate::sweep) fn run_blocks(
    spec: &SweepSpec,
    c: &Continuation,
    out: &Path,
    shard: Shard,
    keys: &[String],
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<SweepReport, SimError> {
    check(spec, c, shard)?;
    let all = blocks(&spec.varies[0].values, c);
    let mine = shard_blocks(&all, shard);
    let points_dir = out.join("points");
    let warm_dir = points_dir.join("warmup");
    std::fs::create_dir_all(&warm_dir).map_err(|e| out_err(&warm_dir, e))?;
    let total: usize = mine.iter().map(|b| b.points.len()).sum();
    let done_before = mine
        .iter()
        .flat_map(|b| &b.points)
        .filter(|(i, _)| read_record(&point_path(out, *i), *i).is_some())
        .count();
    let label = (!shard.is_whole()).then(|| shard.label());
    let log = StreamLog::open(&out.join(stream_name(label.as_deref())), keys)?;
    let state = Mutex::new((log, done_before));
    if done_before > 0 {
        on_point(done_before);
    }
    let failed = Mutex::new(Vec::new());
    mine.par_iter().for_each(|block| {
        if let Err((i, e)) = run_block(spec, block, out, &state, on_point) {
            failed
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .push((i, e.to_string()));
        }
    });
    let mut failed = failed.into_inner().unwrap_or_else(|p| p.into_inner());
    failed.sort();
    // a failed point stops its block: the block's later points count as not computed
    let computed = mine
        .iter()
        .flat_map(|b| &b.points)
        .filter(|(i, _)| read_record(&point_path(out, *i), *i).is_some())
        .count()
        - done_before;
    Ok(SweepReport {
        points: total,
        skipped: done_before,
        computed,
        failed,
    })
}

/// One block's chain: its warm-up, then its points, each from the previous one's last strobe
/// row; points already recorded are read instead of run.
fn run_block(
    spec: &SweepSpec,
    block: &Block,
    out: &Path,
    state: &Mutex<(StreamLog, usize)>,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<(), (usize, SimError)> {
    let key = &spec.varies[0].key;
    let mut last_row: Option<StrobeRow> = None;
    let chain = block
        .warmup
        .iter()
        .map(|p| (p, true))
        .chain(block.points.iter().map(|p| (p, false)));
    for (&(i, v), warm) in chain {
        let path = if warm {
            warmup_path(out, i)
        } else {
            point_path(out, i)
        };
        let rec = match read_record(&path, i) {
            Some(rec) => rec,
            None => {
                let started = std::time::Instant::now();
                let rec = continue_point(spec, key, block.branch, i, v, last_row.as_ref(), out)
                    .map_err(|e| (i, e))?;
                let json = serde_json::to_vec_pretty(&rec)
                    .map_err(|e| (i, SimError::Output(e.to_string())))?;
                write_point(&path, &json).map_err(|e| (i, e))?;
                if !warm {
                    let mut guard = state.lock().unwrap_or_else(|p| p.into_inner());
                    guard
                        .0
                        .append(&rec, started.elapsed().as_secs_f64())
                        .map_err(|e| (i, e))?;
                    guard.1 += 1;
                    on_point(guard.1);
                }
                rec
            }
        };
        last_row = Some(rec.strobe.last().copied().ok_or_else(|| {
            (
                i,
                SimError::from(SceneError::invalid(
                    "run.analysis_fraction",
                    "(window)",
                    "a continuation point needs at least one stroboscopic point (a whole \
                     forcing period in the analysis window) to hand its state on",
                )),
            )
        })?);
    }
    Ok(())
}

/// Runs point `i` (value index `v`) of `branch`, from the state of strobe row `from` (none:
/// the scene's initial state).
fn continue_point(
    spec: &SweepSpec,
    key: &str,
    branch: Branch,
    i: usize,
    v: usize,
    from: Option<&StrobeRow>,
    out: &Path,
) -> Result<PointRecord, SimError> {
    let mut scene = point_scene(spec, v)?;
    if let Some(row) = from {
        let mut ov = spec.set.clone();
        ov.push((key.to_string(), spec.varies[0].values[v].clone()));
        ov.extend(state_overrides(row, &scene)?);
        scene = spec.base.scene(&ov).map_err(|e| match e {
            SceneError::Invalid { field, value, hint } => SceneError::Invalid {
                field,
                value,
                hint: format!("{hint} (continuation point {i}, from the previous point's state)"),
            },
            other => other,
        })?;
    }
    let values = vec![
        (key.to_string(), spec.varies[0].values[v].clone()),
        (
            "branch".to_string(),
            toml::Value::String(branch.as_str().into()),
        ),
    ];
    run_point(&scene, &values, i, spec.analyze, &out.join("points"), None).map(|(r, _)| r)
}

// ---------------------------------------------------------------- tables
