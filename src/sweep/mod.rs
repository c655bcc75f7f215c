//! Parameter sweeps: every point of a grid of scene overrides runs in parallel (rayon), each
//! finished point is written atomically to `DIR/points/<i>.json`, and `DIR/sweep.csv` is
//! rebuilt atomically, in point order, from the finished points after each one. Re-running
//! the same sweep skips finished points (resume), and the output does not depend on the
//! number of threads.

pub mod points;
pub mod run;
pub mod runner;
pub mod vary;

pub use points::{SweepPoint, SweepPoints};
pub use run::{run_scene, run_with_analysis};
pub use runner::{run_sweep, SweepReport, SweepSpec};
pub use vary::{grid, Vary};
