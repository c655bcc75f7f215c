//! What a continuation sweep runs: its settings ([`Continuation`], branches and
//! [`Direction`]), the blocks of each branch with their warm-up values, the blocks of a
//! shard, and the checks made before anything runs.

use crate::error::{SceneError, SimError};
use crate::scene::Damper;
use crate::sweep::point::{point_scene, SweepSpec};
use crate::sweep::shard::Shard;
use serde::{Deserialize, Serialize};

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

pub(super) fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) if x.is_finite() => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// One block of a branch: the warm-up value indices, then the block's (point, value index).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Block {
    pub(super) branch: Branch,
    pub(super) warmup: Vec<(usize, usize)>,
    pub(super) points: Vec<(usize, usize)>,
}

/// The blocks of every branch, `up` first, each in run order.
pub(super) fn blocks(values: &[toml::Value], c: &Continuation) -> Vec<Block> {
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
pub(super) fn shard_blocks(all: &[Block], shard: Shard) -> &[Block] {
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

/// Checks a continuation request before anything is written: one numeric `--vary` key,
/// sane block/overlap/tolerance, no more shards than blocks, a damper whose state is carried
/// (none or impact) at every point.
///
/// # Errors
/// [`SimError::Scene`] naming the flag or key.
pub(in crate::sweep) fn check(
    spec: &SweepSpec,
    c: &Continuation,
    shard: Shard,
) -> Result<(), SimError> {
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
