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
//!
//! Files: the settings, blocks and checks; the chains; the hysteresis and seam tables.

mod chain;
mod hysteresis;
mod plan;

pub use chain::state_overrides;
pub use hysteresis::hysteresis_values;
pub use plan::{
    check_shards, shard_point_count, shard_value_runs, Branch, Continuation, Direction,
    DEFAULT_OVERLAP, DEFAULT_TOLERANCE,
};

pub(in crate::sweep) use chain::run_blocks;
pub(in crate::sweep) use hysteresis::write_tables;
pub(in crate::sweep) use plan::check;

mod tests;
