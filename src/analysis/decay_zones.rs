//! The three zones of a particle damper's free decay (the linear-DEM paper §3.3, after Els
//! 2009): **I**, the grains move like a liquid and damp strongly; **II**, the transition;
//! **III**, the bed moves with its container like a solid and the damping is the primary's own.
//!
//! From the decay envelope's per-cycle damping ratios ζ_k ([`super::decay`]) and the primary's
//! own ratio ζ₀ = c / (2√(kM)): the added damping fraction
//!
//! φ_k = (ζ̃_k − ζ₀) / (max_j ζ̃_j − ζ₀),
//!
//! with ζ̃_k the median of ζ over cycles k − 2 … k + 2 (a DEM bed's ζ_k scatters from cycle to
//! cycle with its impacts). Zone I runs from the first cycle to the last with φ ≥ 1/2; zone III
//! from the first cycle after which φ stays below 1/10; zone II lies between. A decay that
//! never adds damping (max ζ̃ ≤ ζ₀) is one zone III.

use serde::Serialize;

use super::decay::DecayEnvelope;

/// Added damping fraction φ at or above which a cycle is in zone I (–).
pub const LIQUID_FRACTION: f64 = 0.5;
/// Added damping fraction φ below which the decay has entered zone III for good (–).
pub const SOLID_FRACTION: f64 = 0.1;
/// Half-width of the running median over cycles.
const HALF_WINDOW: usize = 2;

/// The zones of one decay, as ranges of cycle indices (0-based into `envelope.cycles`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecayZones {
    /// The primary's own damping ratio ζ₀ (–).
    pub primary_damping_ratio: f64,
    /// Largest smoothed ζ̃ (–).
    pub peak_damping_ratio: f64,
    /// Smoothed ζ̃_k per cycle (–).
    pub smoothed: Vec<f64>,
    /// Added damping fraction φ_k per cycle (–).
    pub added_fraction: Vec<f64>,
    /// Cycles of zone I (liquid-like): `0..liquid_end`; empty when the first cycle is below
    /// the half.
    pub liquid_end: usize,
    /// First cycle of zone III (solid-like); `cycles.len()` when the decay never gets there.
    pub solid_start: usize,
}

impl DecayZones {
    /// The zone (1, 2 or 3) of cycle `k`.
    pub fn zone(&self, k: usize) -> u8 {
        if k < self.liquid_end {
            1
        } else if k >= self.solid_start {
            3
        } else {
            2
        }
    }
}

/// The zones of `envelope` for a primary of damping ratio `zeta0` (module doc).
pub fn decay_zones(envelope: &DecayEnvelope, zeta0: f64) -> DecayZones {
    let z: Vec<f64> = envelope.cycles.iter().map(|c| c.damping_ratio).collect();
    let n = z.len();
    let smoothed: Vec<f64> = (0..n)
        .map(|k| {
            let (lo, hi) = (k.saturating_sub(HALF_WINDOW), (k + HALF_WINDOW + 1).min(n));
            let mut w = z[lo..hi].to_vec();
            w.sort_by(f64::total_cmp);
            let m = w.len();
            if m % 2 == 1 {
                w[m / 2]
            } else {
                0.5 * (w[m / 2 - 1] + w[m / 2])
            }
        })
        .collect();
    let peak = smoothed.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let span = peak - zeta0;
    let added_fraction: Vec<f64> = smoothed
        .iter()
        .map(|&s| if span > 0.0 { (s - zeta0) / span } else { 0.0 })
        .collect();
    let liquid_end = added_fraction
        .iter()
        .rposition(|&f| f >= LIQUID_FRACTION)
        .map_or(0, |k| k + 1);
    let solid_start = added_fraction
        .iter()
        .rposition(|&f| f >= SOLID_FRACTION)
        .map_or(0, |k| k + 1)
        .max(liquid_end);
    DecayZones {
        primary_damping_ratio: zeta0,
        peak_damping_ratio: peak,
        smoothed,
        added_fraction,
        liquid_end,
        solid_start,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::decay::{DecayCycle, DecayStop};

    fn envelope(zeta: &[f64]) -> DecayEnvelope {
        let cycles: Vec<DecayCycle> = zeta
            .iter()
            .enumerate()
            .map(|(k, &z)| DecayCycle {
                cycle: k + 1,
                time_s: k as f64,
                amplitude_m: 1.0 / (k + 1) as f64,
                period_s: 1.0,
                log_decrement: 0.0,
                damping_ratio: z,
            })
            .collect();
        DecayEnvelope {
            initial_amplitude_m: 1.0,
            cycle_count: cycles.len(),
            first_damping_ratio: zeta[0],
            last_damping_ratio: zeta[zeta.len() - 1],
            mean_damping_ratio: 0.0,
            floor_m: 0.0,
            stop: DecayStop::EndOfRecord,
            cycles,
        }
    }

    #[test]
    fn a_staircase_gives_its_three_steps() {
        // ζ0 = 0.01: 6 cycles at 0.11, 4 at 0.05, 8 at 0.01 (one outlier in each)
        let mut z = vec![0.11; 6];
        z.extend([0.05; 4]);
        z.extend([0.01; 8]);
        z[2] = 0.3;
        z[14] = 0.04;
        let zones = decay_zones(&envelope(&z), 0.01);
        assert_eq!(zones.peak_damping_ratio, 0.11);
        // the median keeps the steps where they are, within its half-window
        assert!((6..=7).contains(&zones.liquid_end), "{zones:?}");
        assert!((10..=11).contains(&zones.solid_start), "{zones:?}");
        assert_eq!(zones.zone(0), 1);
        assert_eq!(zones.zone(8), 2);
        assert_eq!(zones.zone(17), 3);
    }

    #[test]
    fn a_linear_primary_is_all_zone_three() {
        let zones = decay_zones(&envelope(&[0.02; 10]), 0.02);
        assert_eq!((zones.liquid_end, zones.solid_start), (0, 0));
        assert!((0..10).all(|k| zones.zone(k) == 3));
    }
}
