//! Tests of the tight grouping ([`super::tight_grouping`]) through
//! [`crate::analysis::section::analyze_section`], on sections whose answer is known by
//! construction.

#![cfg(test)]

use crate::analysis::section::{analyze_section, SectionOptions};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    let u: f64 = rng.random::<f64>().max(1e-300);
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// `n` points of a period-`centres.len()` orbit in the unit square (extents 1), each with
/// Gaussian scatter `sd` per axis, plus `extra(k)`.
fn orbit(
    n: usize,
    centres: &[[f64; 2]],
    sd: f64,
    seed: u64,
    extra: impl Fn(usize, &mut ChaCha8Rng) -> [f64; 2],
) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|k| {
            let c = centres[k % centres.len()];
            let (gx, gy) = (gauss(&mut rng), gauss(&mut rng));
            let e = extra(k, &mut rng);
            vec![c[0] + sd * gx + e[0], c[1] + sd * gy + e[1]]
        })
        .collect()
}

fn tight_period(pts: &[Vec<f64>]) -> Option<usize> {
    let a = analyze_section(pts, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    a.tight.map(|g| g.period)
}

#[test]
fn a_slow_drift_inside_a_small_blob_does_not_veto_period_one() {
    // one group of 0.5 % scatter carrying a period-14 wobble of 0.8 %: period 14 leaves a
    // smaller residue (the old rule, "within 1.5 × the best residue", rejected period 1), but
    // its 14 centroids are not distinct points of an orbit
    let pts = orbit(200, &[[0.5, 0.5]], 0.005, 1, |k, _| {
        let s = (k as f64 * std::f64::consts::TAU / 14.0).sin();
        [0.008 * s, 0.008 * s]
    });
    assert_eq!(tight_period(&pts), Some(1));
}

#[test]
fn a_period_two_orbit_three_percent_wide_is_period_two() {
    // two points 3 % apart with 0.2 % scatter: one blob of 1.5 % at period 1, but period 2
    // resolves it into two distinct points
    let pts = orbit(200, &[[0.5, 0.5], [0.53, 0.5]], 0.002, 2, |_, _| [0.0, 0.0]);
    assert_eq!(tight_period(&pts), Some(2));
}

#[test]
fn rare_excursions_do_not_make_a_period_two_orbit_a_cloud() {
    // period 2 with 2.5 % scatter; one strobe in 20 thrown 15 % off: the RMS per axis reads
    // ~4.3 % against a typical distance of ~2.6 % — tight
    let pts = orbit(240, &[[0.3, 0.3], [0.7, 0.6]], 0.025, 3, |k, rng| {
        if k % 20 == 7 {
            [0.15 * gauss(rng).signum(), 0.15 * gauss(rng).signum()]
        } else {
            [0.0, 0.0]
        }
    });
    assert_eq!(tight_period(&pts), Some(2));
}

#[test]
fn an_intermittent_orbit_is_not_tight() {
    // the same orbit away from its points one strobe in three (bursts of 25 %): the typical
    // distance stays small but the RMS exceeds twice the bound — intermittent, not periodic
    let pts = orbit(240, &[[0.3, 0.3], [0.7, 0.6]], 0.02, 4, |k, rng| {
        if k % 3 == 0 {
            [0.25 * gauss(rng), 0.25 * gauss(rng)]
        } else {
            [0.0, 0.0]
        }
    });
    assert_eq!(tight_period(&pts), None);
}

#[test]
fn a_cloud_of_eight_percent_is_not_tight_at_any_period() {
    let pts = orbit(240, &[[0.5, 0.5]], 0.08, 5, |_, _| [0.0, 0.0]);
    assert_eq!(tight_period(&pts), None);
}

#[test]
fn the_bound_is_on_the_worst_axis() {
    // 1 % on position, 7 % on velocity: not tight; 4 % on both: tight
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let pts: Vec<Vec<f64>> = (0..200)
        .map(|_| vec![0.5 + 0.01 * gauss(&mut rng), 0.5 + 0.07 * gauss(&mut rng)])
        .collect();
    assert_eq!(tight_period(&pts), None);
    let pts = orbit(200, &[[0.5, 0.5]], 0.04, 7, |_, _| [0.0, 0.0]);
    assert_eq!(tight_period(&pts), Some(1));
}
