//! Continuation sweeps (`pdamp sweep --continuation up|down|both`): a one-parameter sweep run
//! in parameter order, each point starting from the previous point's final state, the way
//! bifurcation diagrams of multistable systems are made; `both` runs the increasing and the
//! decreasing branch and marks hysteresis where they differ.
//!
//! # The chain
//! The values of the one `--vary` key are ordered increasing (branch `up`) or decreasing
//! (branch `down`). The first point of a chain starts from the scene's own initial state;
//! point k starts from the state of point k − 1 at its last stroboscopic time t = nT (forcing
//! phase 0, so the next point's forcing cos(2π f t) continues without a phase jump; with
//! `run.periods` whole, that is the end of the run or one period before it): box position and
//! velocity (`primary.initial_displacement`, `primary.initial_velocity`), particle height
//! above the floor and velocity (`damper.initial_height`, `damper.initial_velocity`). The
//! state is handed over through the point record's last `strobe.csv` row (shortest
//! round-trip decimal: exact), so a resumed chain continues bit for bit.
//!
//! # Blocks, overlap and shards
//! A branch is cut into blocks of `--block B` consecutive values (default: one block, the
//! whole branch). Block b > 0 starts `--overlap W` values earlier, from the scene's initial
//! state, and runs those W points as warm-up (written to `points/warmup/<i>.json`, not to
//! `sweep.csv`); `seams.csv` compares each warm-up point with the same point of the previous
//! block's chain (amplitude and regime), which says whether the warm-up found the branch.
//! Shard K of N computes a contiguous range of blocks (blocks are numbered along `up`, then
//! `down`). Every block depends only on the scene, B and W, so `sweep.csv` is byte-identical
//! for any thread count and any shard count; B and W are part of the sweep's identity.
//!
//! # Output
//! Points 0 … n−1 are the `--vary` values in the order given (point i = value i) on the first
//! branch; with `both`, points n … 2n−1 are the same values on the `down` branch. A `branch`
//! column follows the varied key in `sweep.csv` and `strobe.csv`. With `both`,
//! `hysteresis.csv` lists, per value, both branches' amplitude, impacts per cycle and regime,
//! the relative amplitude difference |A_up − A_down| / max(A_up, A_down), and `hysteresis` =
//! 1 where that difference, or the relative difference of the impacts per cycle, exceeds the
//! tolerance (`--hysteresis-tol`, default 0.05) and the two branches are not both chaotic (a
//! chaotic attractor's extent over a finite window scatters; with `--no-analysis` regimes
//! are unknown and chaotic windows are marked by that scatter too). Regime verdicts are
//! reported beside but do not mark by themselves (a slowly converging orbit can be
//! `undetermined` on one branch and `periodic` on the other).

use super::point::{
    out_err, point_path, point_scene, run_point, write_point, PointRecord, SweepReport, SweepSpec,
};
use super::shard::Shard;
use super::tables::{read_record, stream_name, Row, StreamLog};
use crate::error::{SceneError, SimError};
use crate::io::CsvOut;
use crate::observe::fmt_num;
use crate::scene::{Damper, Scene};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Which branches a continuation sweep runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Increasing parameter.
    Up,
    /// Decreasing parameter.
    Down,
    /// Up, then down (hysteresis).
    Both,
}

impl Direction {
    /// Parse `up`, `down` or `both`.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming `--continuation`.
    pub fn parse(s: &str) -> Result<Direction, SceneError> {
        match s.trim() {
            "up" => Ok(Direction::Up),
            "down" => Ok(Direction::Down),
            "both" => Ok(Direction::Both),
            _ => Err(SceneError::invalid(
                "--continuation",
                s,
                "expected up, down or both",
            )),
        }
    }

    pub(crate) fn branches(self) -> &'static [Branch] {
        match self {
            Direction::Up => &[Branch::Up],
            Direction::Down => &[Branch::Down],
            Direction::Both => &[Branch::Up, Branch::Down],
        }
    }
}

/// One branch of a continuation sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Branch {
    /// Increasing parameter.
    Up,
    /// Decreasing parameter.
    Down,
}

impl Branch {
    /// `up` or `down` (the `branch` column).
    pub fn as_str(self) -> &'static str {
        match self {
            Branch::Up => "up",
            Branch::Down => "down",
        }
    }
}

/// Default `--overlap`: warm-up points before each block after the first.
pub const DEFAULT_OVERLAP: usize = 3;
/// Default `--hysteresis-tol`: relative amplitude difference that marks hysteresis.
pub const DEFAULT_TOLERANCE: f64 = 0.05;

/// A continuation sweep's settings (part of the sweep's identity, `sweep.json`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Continuation {
    /// The branches.
    pub direction: Direction,
    /// Points per block along a branch; `None`: the whole branch is one block.
    pub block: Option<usize>,
    /// Warm-up points run before each block after the first (< block).
    pub overlap: usize,
    /// Relative amplitude difference above which `hysteresis.csv` marks a value.
    pub tolerance: f64,
}

impl Continuation {
    /// A continuation with the default overlap and tolerance and one block per branch.
    pub fn new(direction: Direction) -> Continuation {
        Continuation {
            direction,
            block: None,
            overlap: DEFAULT_OVERLAP,
            tolerance: DEFAULT_TOLERANCE,
        }
    }

    /// Number of points (the values times the branches).
    pub fn points(&self, values: usize) -> usize {
        values * self.direction.branches().len()
    }

    fn check(&self, spec: &SweepSpec) -> Result<(), SceneError> {
        if spec.varies.len() != 1 {
            return Err(SceneError::invalid(
                "--continuation",
                format!("{} --vary keys", spec.varies.len()),
                "a continuation sweep varies exactly one key",
            ));
        }
        let v = &spec.varies[0];
        if v.values.iter().any(|x| number(x).is_none()) {
            return Err(SceneError::invalid(
                &v.key,
                "(values)",
                "a continuation sweep needs numeric values to order",
            ));
        }
        if self.block == Some(0) {
            return Err(SceneError::invalid("--block", "0", "must be at least 1"));
        }
        if let Some(b) = self.block {
            if self.overlap >= b {
                return Err(SceneError::invalid(
                    "--overlap",
                    self.overlap,
                    format!("must be smaller than --block ({b})"),
                ));
            }
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(SceneError::invalid(
                "--hysteresis-tol",
                self.tolerance,
                "must be a finite number ≥ 0",
            ));
        }
        Ok(())
    }
}

fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) if x.is_finite() => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// One block of a branch: the warm-up value indices, then the block's (point, value index).
#[derive(Debug, Clone, PartialEq)]
struct Block {
    branch: Branch,
    warmup: Vec<(usize, usize)>,
    points: Vec<(usize, usize)>,
}

/// The blocks of every branch, `up` first, each in run order.
fn blocks(values: &[toml::Value], c: &Continuation) -> Vec<Block> {
    let n = values.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        let (x, y) = (number(&values[a]), number(&values[b]));
        x.unwrap_or(f64::NAN)
            .total_cmp(&y.unwrap_or(f64::NAN))
            .then(a.cmp(&b))
    });
    let mut out = Vec::new();
    for (bi, &branch) in c.direction.branches().iter().enumerate() {
        let offset = bi * n;
        let run: Vec<usize> = match branch {
            Branch::Up => order.clone(),
            Branch::Down => order.iter().rev().copied().collect(),
        };
        let size = c.block.unwrap_or(n).max(1);
        let mut start = 0;
        while start < n {
            let end = (start + size).min(n);
            let w0 = start.saturating_sub(c.overlap);
            out.push(Block {
                branch,
                warmup: run[w0..start].iter().map(|&v| (offset + v, v)).collect(),
                points: run[start..end].iter().map(|&v| (offset + v, v)).collect(),
            });
            start = end;
        }
    }
    out
}

/// The blocks of shard `shard`: a contiguous range.
fn shard_blocks(all: &[Block], shard: Shard) -> &[Block] {
    let nb = all.len();
    let lo = shard.index * nb / shard.count;
    let hi = (shard.index + 1) * nb / shard.count;
    &all[lo..hi]
}

/// Number of points shard `shard` of a continuation sweep over `values` computes.
pub fn shard_point_count(values: &[toml::Value], c: &Continuation, shard: Shard) -> usize {
    let all = blocks(values, c);
    if shard.count > all.len() {
        return 0;
    }
    shard_blocks(&all, shard)
        .iter()
        .map(|b| b.points.len())
        .sum()
}

/// The value indices shard `shard` of a continuation sweep over `values` runs, warm-up points
/// included, in run order (empty when the shard has no block).
pub fn shard_value_runs(values: &[toml::Value], c: &Continuation, shard: Shard) -> Vec<usize> {
    let all = blocks(values, c);
    if shard.count > all.len() {
        return Vec::new();
    }
    shard_blocks(&all, shard)
        .iter()
        .flat_map(|b| b.warmup.iter().chain(&b.points).map(|&(_, v)| v))
        .collect()
}

/// Checks a continuation sweep meant to run as `shards` shards (e.g. a Slurm job array)
/// before anything runs: one numeric `--vary` key, `--block`, `--overlap`,
/// `--hysteresis-tol` valid, at least `shards` blocks, an impact (or no) damper.
///
/// # Errors
/// [`SimError::Scene`] naming the flag (`--continuation`, `--block`, `--overlap`,
/// `--hysteresis-tol`, `--shards`) or the scene key.
pub fn check_shards(spec: &SweepSpec, c: &Continuation, shards: usize) -> Result<(), SimError> {
    c.check(spec)?;
    let vary = &spec.varies[0];
    let nb = blocks(&vary.values, c).len();
    if shards > nb {
        return Err(SceneError::invalid(
            "--shards",
            shards,
            format!(
                "a continuation sweep shards by blocks and this one has {nb} (set --block to \
                 at most {} points per block for {shards} shards)",
                (vary.values.len() / shards).max(1),
            ),
        )
        .into());
    }
    let shard = Shard {
        index: 0,
        count: shards.max(1),
    };
    check(spec, c, shard)
}

/// The scene overrides that start a run from the state of a `strobe.csv` row
/// `cycle,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s`.
///
/// # Errors
/// [`SceneError::Invalid`] for a malformed row or a damper without an initial state (DEM).
pub fn state_overrides(row: &str, scene: &Scene) -> Result<Vec<(String, toml::Value)>, SceneError> {
    let bad = || {
        SceneError::invalid(
            "--continuation",
            row,
            "the previous point's last strobe row is not `cycle,z,z_box,v,v_box`",
        )
    };
    let v: Vec<f64> = row
        .split(',')
        .skip(1)
        .map(|s| s.parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let [gz, bz, gv, bv] = v[..] else {
        return Err(bad());
    };
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

/// Checks a continuation request before anything is written: one numeric `--vary` key,
/// sane block/overlap/tolerance, no more shards than blocks, a damper whose state is carried
/// (none or impact) at every point.
///
/// # Errors
/// [`SimError::Scene`] naming the flag or key.
pub(super) fn check(spec: &SweepSpec, c: &Continuation, shard: Shard) -> Result<(), SimError> {
    c.check(spec)?;
    let vary = &spec.varies[0];
    let nb = blocks(&vary.values, c).len();
    if shard.count > nb {
        return Err(SceneError::invalid(
            "--shard",
            shard.to_string(),
            format!(
                "a continuation sweep shards by blocks and this one has {nb} (set --block to \
                 at most {} points per block for {} shards)",
                (vary.values.len() / shard.count).max(1),
                shard.count
            ),
        )
        .into());
    }
    for v in 0..vary.values.len() {
        let scene = point_scene(spec, v)?;
        if matches!(scene.damper, Damper::Dem(_) | Damper::Auto(_)) {
            return Err(SceneError::invalid(
                "damper.kind",
                scene.damper.kind(),
                "a continuation sweep carries the impact model's state (damper none or impact)",
            )
            .into());
        }
    }
    Ok(())
}

/// Runs (or resumes) shard `shard` of a continuation sweep into `out` (see the module docs);
/// called by [`super::runner::run_shard`].
///
/// # Errors
/// As [`super::runner::run_shard`]; a scene whose damper has no carried state (DEM).
pub(super) fn run_blocks(
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
    let mut last_row: Option<String> = None;
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
                let rec = continue_point(spec, key, block.branch, i, v, last_row.as_deref(), out)
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
        last_row = Some(rec.strobe.last().cloned().ok_or_else(|| {
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
    from: Option<&str>,
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
    run_point(&scene, &values, i, spec.analyze, &out.join("points"))
}

// ---------------------------------------------------------------- tables

/// Writes `hysteresis.csv` (with `both`) and `seams.csv` (with more than one block) into
/// `out` from the sweep's rows and the warm-up records found in `dirs`.
///
/// # Errors
/// [`SimError::Output`] for file-system errors.
pub(super) fn write_tables(
    c: &Continuation,
    key: &str,
    values: &[toml::Value],
    rows: &[Row],
    dirs: &[PathBuf],
    out: &Path,
) -> Result<(), SimError> {
    let n = values.len();
    let by_point: BTreeMap<usize, &Row> = rows.iter().map(|r| (r.0, r)).collect();
    let cell = |i: usize, c: &str| -> String {
        by_point
            .get(&i)
            .and_then(|r| r.2.get(c).cloned())
            .unwrap_or_default()
    };
    if c.direction == Direction::Both {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| {
            number(&values[a])
                .unwrap_or(f64::NAN)
                .total_cmp(&number(&values[b]).unwrap_or(f64::NAN))
                .then(a.cmp(&b))
        });
        let mut t = CsvOut::in_memory();
        let header = [
            key,
            "amplitude_up_m",
            "amplitude_down_m",
            "amplitude_relative_difference",
            "impacts_per_cycle_up",
            "impacts_per_cycle_down",
            "regime_up",
            "regime_down",
            "hysteresis",
        ];
        let _ = t.row(header);
        for v in order {
            let (up, down) = (v, n + v);
            let (au, ad) = (cell(up, "amplitude_m"), cell(down, "amplitude_m"));
            let (ru, rd) = (cell(up, "regime"), cell(down, "regime"));
            let rel = relative_difference(&au, &ad);
            let (iu, id) = (
                cell(up, "impacts_per_cycle"),
                cell(down, "impacts_per_cycle"),
            );
            let rel_impacts = relative_difference(&iu, &id);
            let marked = marks_hysteresis(rel, rel_impacts, &ru, &rd, c.tolerance);
            let rel = rel.map(fmt_num).unwrap_or_default();
            let flag = u8::from(marked).to_string();
            let value = value_text(&values[v]);
            // writes into memory cannot fail
            let _ = t.row([&value, &au, &ad, &rel, &iu, &id, &ru, &rd, &flag]);
        }
        let text = t.into_string();
        crate::io::atomic_write(&out.join("hysteresis.csv"), text.as_bytes())
            .map_err(|e| SimError::Output(e.to_string()))?;
    }
    let all = blocks(values, c);
    if all.iter().any(|b| !b.warmup.is_empty()) {
        let mut t = CsvOut::in_memory();
        let header = [
            "branch",
            "block_first_point",
            "point",
            key,
            "amplitude_chain_m",
            "amplitude_warmup_m",
            "amplitude_relative_difference",
            "regime_chain",
            "regime_warmup",
            "agree",
        ];
        let _ = t.row(header);
        for b in all.iter().filter(|b| !b.warmup.is_empty()) {
            for &(i, v) in &b.warmup {
                let warm = dirs.iter().find_map(|d| read_record(&warmup_path(d, i), i));
                let (aw, rw) = warm.map_or((String::new(), String::new()), |r| {
                    (
                        r.cells.get("amplitude_m").cloned().unwrap_or_default(),
                        r.cells.get("regime").cloned().unwrap_or_default(),
                    )
                });
                let (ac, rc) = (cell(i, "amplitude_m"), cell(i, "regime"));
                let rel = relative_difference(&ac, &aw);
                let agree = rel.is_some_and(|r| r <= c.tolerance) && rc == rw;
                let row = [
                    b.branch.as_str().to_string(),
                    b.points[0].0.to_string(),
                    i.to_string(),
                    value_text(&values[v]),
                    ac,
                    aw,
                    rel.map(fmt_num).unwrap_or_default(),
                    rc,
                    rw,
                    u8::from(agree).to_string(),
                ];
                // writes into memory cannot fail
                let _ = t.row(&row);
            }
        }
        let text = t.into_string();
        crate::io::atomic_write(&out.join("seams.csv"), text.as_bytes())
            .map_err(|e| SimError::Output(e.to_string()))?;
    }
    Ok(())
}

/// |a − b| / max(a, b) of two numeric cells (0 when both are 0), `None` if either is not a
/// number.
fn relative_difference(a: &str, b: &str) -> Option<f64> {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(a), Ok(b)) if a.max(b) > 0.0 => Some((a - b).abs() / a.max(b)),
        (Ok(_), Ok(_)) => Some(0.0),
        _ => None,
    }
}

/// A varied value as its CSV cell (a string without its TOML quotes).
fn value_text(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Whether one value's two branches are different motions: their relative amplitude
/// difference `rel` or relative impacts-per-cycle difference `rel_impacts` exceeds `tol`,
/// unless both are chaotic (the extent and impact rate of a chaotic attractor over a finite
/// window scatter from run to run: not a second branch). The regime verdicts alone do not
/// mark (a slowly converging orbit is `undetermined` on one branch and `periodic` on the
/// other); they are reported beside.
fn marks_hysteresis(
    rel: Option<f64>,
    rel_impacts: Option<f64>,
    regime_up: &str,
    regime_down: &str,
    tol: f64,
) -> bool {
    let chaotic = regime_up == "chaotic" && regime_down == "chaotic";
    !chaotic && (rel.is_some_and(|r| r > tol) || rel_impacts.is_some_and(|r| r > tol))
}

/// The values marked in `hysteresis.csv` of `dir`, in increasing order (empty if there is
/// none or no such file).
pub fn hysteresis_values(dir: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join("hysteresis.csv")).unwrap_or_default();
    text.lines()
        .skip(1)
        .filter(|l| l.ends_with(",1"))
        .filter_map(|l| l.split(',').next()?.parse::<f64>().ok())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vals(n: usize) -> Vec<toml::Value> {
        (0..n).map(|i| toml::Value::Float(i as f64)).collect()
    }

    #[test]
    fn blocks_cover_each_branch_in_order_with_warmup() {
        let mut c = Continuation::new(Direction::Both);
        c.block = Some(4);
        c.overlap = 2;
        let b = blocks(&vals(10), &c);
        assert_eq!(b.len(), 6);
        assert!(b[0].warmup.is_empty());
        assert_eq!(b[1].warmup, [(2, 2), (3, 3)]);
        assert_eq!(b[1].points, [(4, 4), (5, 5), (6, 6), (7, 7)]);
        // down: points 10..19, values decreasing
        assert_eq!(b[3].points[0], (19, 9));
        // down runs 9, 8, …, 0 in blocks [9..6], [5..2], [1, 0]: the second warms up on 7, 6
        assert_eq!(b[4].warmup, [(17, 7), (16, 6)]);
        assert_eq!(b[4].points[0], (15, 5));
        let covered: usize = b.iter().map(|x| x.points.len()).sum();
        assert_eq!(covered, 20);
        // shards: contiguous ranges of blocks, all covered once
        let mut seen = 0;
        for k in 0..4 {
            seen += shard_blocks(&b, Shard { index: k, count: 4 }).len();
        }
        assert_eq!(seen, 6);
    }

    #[test]
    fn hysteresis_needs_a_regime_change_or_a_non_chaotic_amplitude_jump() {
        let m = marks_hysteresis;
        // two periodic orbits: 2 against 3 impacts per period, or a jump in amplitude
        assert!(m(Some(0.01), Some(1.0 / 3.0), "periodic", "periodic", 0.05));
        assert!(m(Some(0.5), Some(0.0), "periodic", "chaotic", 0.05));
        // the same orbit judged differently, and two chaotic windows, are not marked
        assert!(!m(Some(0.005), Some(0.0), "chaotic", "periodic", 0.05));
        assert!(!m(Some(0.5), Some(0.2), "chaotic", "chaotic", 0.05));
        assert!(!m(Some(0.01), Some(0.0), "undetermined", "periodic", 0.05));
        // no analysis: amplitude and impacts decide
        assert!(m(Some(0.5), None, "", "", 0.05));
        assert!(!m(None, None, "", "", 0.05));
    }

    #[test]
    fn state_overrides_from_a_strobe_row() {
        let s = Scene::thesis_b_impact();
        let ov = state_overrides("7,0.01,0.002,-0.5,0.25", &s).unwrap();
        let get = |k: &str| {
            ov.iter()
                .find(|(x, _)| x == k)
                .unwrap()
                .1
                .as_float()
                .unwrap()
        };
        assert_eq!(get("primary.initial_displacement"), 0.002);
        assert_eq!(get("primary.initial_velocity"), 0.25);
        assert_eq!(get("damper.initial_height"), 0.01 - 0.002);
        assert_eq!(get("damper.initial_velocity"), -0.5);
        assert!(state_overrides("7,0.01", &s).is_err());
    }
}
