//! Replica records built by hand for the tests of the replica test and of the classifier.

#![cfg(test)]

use super::{report, ReplicaReport, ReplicaRow, AXES};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Extent of the first axis (m); the others unused.
pub(crate) const EXTENT: [f64; AXES] = [1e-2, 0.0, 0.0, 0.0];

/// A standard normal deviate (Box–Muller).
pub(crate) fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    let u: f64 = rng.random::<f64>().max(1e-300);
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// Strobe rows of two replicas moving on the first axis only (z series `za`, `zb` in m,
/// forcing `f` Hz, strobe k at t = (k + 1)/f).
pub(crate) fn rows_of(za: &[f64], zb: &[f64], f: f64) -> Vec<ReplicaRow> {
    za.iter()
        .zip(zb)
        .enumerate()
        .map(|(k, (&a, &b))| ReplicaRow {
            cycle: k as u64 + 1,
            time_s: (k + 1) as f64 / f,
            a: [a, 0.0, 0.0, 0.0],
            b: [b, 0.0, 0.0, 0.0],
        })
        .collect()
}

/// Two replicas riding the same slow oscillation of amplitude 4e-3 m (the section's spread)
/// and differing by independent fast noise of sd 4e-4 m, perturbed by `delta0_m`, at 11 Hz.
pub(crate) fn slow_motion_pair(delta0_m: f64) -> ReplicaReport {
    let f = 11.0;
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let slow: Vec<f64> = (0..240)
        .map(|k| 0.05 + 4e-3 * (k as f64 * 0.37).sin())
        .collect();
    let za: Vec<f64> = slow.iter().map(|s| s + 4e-4 * gauss(&mut rng)).collect();
    let zb: Vec<f64> = slow.iter().map(|s| s + 4e-4 * gauss(&mut rng)).collect();
    report(delta0_m, 0.0, f, EXTENT, rows_of(&za, &zb, f))
}
