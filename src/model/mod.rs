//! Equations of the primary system, no time stepping: the linear single-degree-of-freedom
//! system under harmonic base excitation (2.1.2), its closed-form solution between events and
//! its analytic steady-state amplitude (2.1.21); and what every run reports ([`summary`]).

pub mod primary;
pub mod summary;

pub use primary::{base_motion, Anchor, BoxDrive, PrimarySystem, Sdof};
pub use summary::{EnergyTotals, RunAnalysis, RunOptions, RunSummary, RunWindow, StrobePoint};
