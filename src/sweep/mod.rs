//! Parameter sweeps: every point of a grid of scene overrides runs in parallel (rayon), each
//! finished point is written atomically to `DIR/points/<i>.json` and appended as one line to a
//! stream log; `DIR/sweep.csv`, `DIR/strobe.csv` and `DIR/timings.csv` are rebuilt in point
//! order at the end (or by [`merge`] over the shards of a sweep split with `--shard K/N`).
//! Re-running the same sweep skips finished points (resume), and `sweep.csv` / `strobe.csv`
//! do not depend on the number of threads, shards or machines (timings live in
//! `timings.csv`). A grid too large for the disk or memory is refused up front ([`budget`]).

pub mod budget;
pub mod catalog;
pub mod continuation;
pub mod cost;
pub mod point;
pub mod points;
pub mod run;
pub mod runner;
pub mod shard;
pub mod slurm;
pub mod stop;
pub mod tables;
pub mod vary;

pub use crate::io::schema::VERDICT_COLUMNS;
pub use catalog::{Catalog, FoundPoint};
pub use continuation::{Continuation, Direction};
pub use points::{SweepPoint, SweepPoints};
pub use run::{run_scene, run_with_analysis};
pub use runner::{merge, MergeReport};
pub use runner::{
    run_shard, run_shard_with, run_sweep, run_sweep_keeping, KeptRun, SweepReport, SweepSpec,
};
pub use shard::Shard;
pub use vary::{grid, Vary};
