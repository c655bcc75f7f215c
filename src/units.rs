//! Physical constants and SI conventions.
//!
//! All quantities are SI: metres, kilograms, seconds, newtons, joules, hertz. Names of
//! struct fields and CSV/JSON columns carry the unit where it is not obvious
//! (`amplitude_m`, `frequency_hz`, `dt_s`).

/// Standard gravity used throughout the thesis, g = 9.8 m/s² (SPEC §2).
pub const G: f64 = 9.8;

/// 2π, for Ω = 2π f (rad/s from Hz).
pub const TWO_PI: f64 = std::f64::consts::TAU;
