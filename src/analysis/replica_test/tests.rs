//! Tests of the two-replica test ([`super::report`]).

#![cfg(test)]

use super::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    let u: f64 = rng.random::<f64>().max(1e-300);
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

fn rows_of(za: &[f64], zb: &[f64], f: f64) -> Vec<ReplicaRow> {
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

const EXTENT: [f64; AXES] = [1e-2, 0.0, 0.0, 0.0];

#[test]
fn small_noise_about_a_fixed_point_is_sensitive_but_small() {
    // two independent noise draws of sd 1 % of the orbit about one point once the
    // separation, growing e-fold per period from 1e-9 m, reaches them
    let (f, sigma) = (14.5, 1e-4);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let za: Vec<f64> = (0..300).map(|_| 0.05 + sigma * gauss(&mut rng)).collect();
    let zb: Vec<f64> = za
        .iter()
        .enumerate()
        .map(|(k, &a)| {
            let d = 1e-9 * (k as f64).exp();
            if d < sigma {
                a + d
            } else {
                0.05 + sigma * gauss(&mut rng)
            }
        })
        .collect();
    let r = report(1e-9, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    let ReplicaOutcome::Sensitive {
        saturation_rel_orbit,
    } = r.outcome
    else {
        panic!("{r:?}");
    };
    // two draws of sd σ differ by a median 0.954 σ; σ = 1 % of the extent
    assert!(
        (0.007..0.013).contains(&saturation_rel_orbit),
        "{saturation_rel_orbit}"
    );
    let g = r.growth.expect("growth phase");
    assert!((g.per_period - 1.0).abs() < 0.1, "{g:?}");
}

#[test]
fn chaotic_map_separates_with_its_exponent() {
    // logistic map r = 4: λ = ln 2 per iteration; B starts 1e-9 (relative) away
    let f = 10.0;
    let (mut a, mut b) = (0.3f64, 0.3 + 1e-9);
    let (mut za, mut zb) = (Vec::new(), Vec::new());
    for _ in 0..300 {
        a = 4.0 * a * (1.0 - a);
        b = 4.0 * b * (1.0 - b);
        za.push(1e-2 * a);
        zb.push(1e-2 * b);
    }
    let r = report(1e-11, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    let ReplicaOutcome::Sensitive {
        saturation_rel_orbit,
    } = r.outcome
    else {
        panic!("{r:?}");
    };
    assert!(saturation_rel_orbit > 0.2, "{r:?}");
    let g = r.growth.expect("growth");
    assert!((g.per_period - 2f64.ln()).abs() < 0.1, "{g:?}");
}

#[test]
fn a_stable_orbit_is_insensitive() {
    // the perturbation decays by e per period about a period-2 orbit
    let f = 10.0;
    let za: Vec<f64> = (0..200).map(|k| [0.01, 0.02][k % 2]).collect();
    let zb: Vec<f64> = za
        .iter()
        .enumerate()
        .map(|(k, &a)| a + 1e-9 * (-(k as f64)).exp())
        .collect();
    let r = report(1e-9, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    assert_eq!(r.outcome, ReplicaOutcome::Insensitive, "{r:?}");
}

#[test]
fn a_step_in_one_replica_is_not_chaos() {
    // A compacts by 20 σ at two thirds of the window, B does not
    let (f, sigma) = (7.5, 2e-5);
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let za: Vec<f64> = (0..120)
        .map(|k| 0.026 - if k > 70 { 20.0 * sigma } else { 0.0 } + sigma * gauss(&mut rng))
        .collect();
    let zb: Vec<f64> = (0..120).map(|_| 0.026 + sigma * gauss(&mut rng)).collect();
    let r = report(1e-9, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    let ReplicaOutcome::Inconclusive { why } = &r.outcome else {
        panic!("{r:?}");
    };
    assert!(why.contains("different macroscopic states"), "{why}");
}

#[test]
fn too_few_strobes_is_inconclusive() {
    let z = [0.05; 10];
    let r = report(1e-9, 0.0, 10.0, EXTENT, rows_of(&z, &z, 10.0));
    assert!(matches!(r.outcome, ReplicaOutcome::Inconclusive { .. }));
}

#[test]
fn a_period_three_orbit_separates_within_its_groups() {
    // A and B visit the same three points (up to half the orbit apart) cyclically, each
    // with an independent scatter of 1 % of the orbit: they are independent within a group
    let f = 13.0;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let centres = [0.01, 0.015, 0.012];
    let za: Vec<f64> = (0..150)
        .map(|k| centres[k % 3] + 1e-4 * gauss(&mut rng))
        .collect();
    let zb: Vec<f64> = (0..150)
        .map(|k| centres[k % 3] + 1e-4 * gauss(&mut rng))
        .collect();
    let whole = report(1e-9, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    // against the whole section (D₁ ≈ 0.3: across the groups) the replicas look far from
    // separated; against the same phase of the 3-cycle (D₃ ≈ 1.1 σ) they are independent
    assert!(
        matches!(whole.outcome, ReplicaOutcome::Inconclusive { .. }),
        "{}",
        whole.describe()
    );
    let r = whole.at_period(3);
    assert!(
        matches!(r.outcome, ReplicaOutcome::Sensitive { .. }),
        "{}",
        r.describe()
    );
    assert!(r.independent_separation_rel < 0.03, "{r:?}");
    assert_eq!(r.phase_period, 3);
    // a period beyond those measured leaves the report as it was
    assert_eq!(whole.at_period(99), whole);
}

#[test]
fn the_worst_axis_decides() {
    // positions coincide, velocities differ by half the velocity extent
    let a = [0.0, 1.0, 0.0, 0.0];
    let b = [0.0, 1.5, 0.0, 0.0];
    assert_eq!(separation(&a, &b, &[1.0, 1.0, 0.0, 0.0]), 0.5);
}
