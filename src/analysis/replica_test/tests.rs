//! Tests of the two-replica test ([`super::report`]).

#![cfg(test)]

use super::fixtures::{gauss, rows_of, slow_motion_pair, EXTENT};
use super::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

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
    // separated (partial: grown from δ0 by orders of magnitude, below D₁/2); against the same
    // phase of the 3-cycle (D₃ ≈ 1.1 σ) they are independent
    assert!(
        matches!(whole.outcome, ReplicaOutcome::Partial { .. }),
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

/// Two copies of the logistic map r = 4 (λ = ln 2 per period) from 1e-9 apart, B put back
/// 1e-9 from A at the strobes in `together` (a contracting episode both replicas follow; they
/// separate again in ~30 periods), on an orbit of extent 1e-2.
fn logistic_pair(n: usize, together: std::ops::Range<usize>) -> (Vec<f64>, Vec<f64>) {
    let (mut a, mut b) = (0.3f64, 0.3 + 1e-9);
    let (mut za, mut zb) = (Vec::new(), Vec::new());
    for k in 0..n {
        a = 4.0 * a * (1.0 - a);
        b = 4.0 * b * (1.0 - b);
        if together.contains(&k) {
            b = a + 1e-9;
        }
        za.push(1e-2 * a);
        zb.push(1e-2 * b);
    }
    (za, zb)
}

#[test]
fn a_re_approach_in_the_last_third_does_not_undo_sensitivity() {
    // separated within ~30 periods; then the replicas are pulled together in the last third
    // and separate again, ~40 of the last 80 periods close (at 16 Hz on thesis_b_ch4.toml,
    // 400 periods, ~40 of 240 strobes): a median over the last third alone reads under D/2,
    // the span from the first reach reads the separation of independent states
    let f = 16.0;
    let (za, zb) = logistic_pair(240, 170..180);
    let r = report(1e-11, 0.0, f, EXTENT, rows_of(&za, &zb, f));
    let tail: Vec<f64> = r.rows[160..].iter().map(|row| r.separation(row)).collect();
    let mut tail_sorted = tail.clone();
    tail_sorted.sort_by(f64::total_cmp);
    assert!(
        tail_sorted[tail.len() / 2] < SEPARATED_FACTOR * r.independent_separation_rel,
        "the episode must pull the last third's median under D/2: {tail_sorted:?}"
    );
    assert!(
        matches!(r.outcome, ReplicaOutcome::Sensitive { .. }),
        "{}",
        r.describe()
    );
    assert!(r.spans[0].start < 40, "{:?}", r.spans[0]);
}

#[test]
fn replicas_sharing_a_slow_motion_are_partial_not_independent() {
    // sensitive at the noise's scale (grown from 1e-9 m to ~6e-4 m: five decades), but the
    // separation stays near 0.1 × the separation of independent states — partial, never
    // "sensitive"
    let r = slow_motion_pair(1e-9);
    let ReplicaOutcome::Partial {
        saturation_rel_orbit,
        over_independent,
    } = r.outcome
    else {
        panic!("{}", r.describe());
    };
    assert!(
        (0.05..0.3).contains(&over_independent),
        "{over_independent}"
    );
    assert_eq!(saturation_rel_orbit, r.saturation_rel);
    assert_eq!(r.outcome.as_str(), "partial");
    assert!(r.describe().starts_with("partial:"), "{}", r.describe());
}

#[test]
fn a_separation_between_the_scales_that_barely_grew_is_inconclusive() {
    // the same replicas perturbed by 1e-5 m (1e-3 of the orbit): d_sat ≈ 6e-2 of the orbit is
    // only ~60 δ0 — not three decades of growth: inconclusive, naming the growth
    let r = slow_motion_pair(1e-5);
    let ReplicaOutcome::Inconclusive { why } = &r.outcome else {
        panic!("{}", r.describe());
    };
    assert!(why.contains("between") && why.contains("δ0"), "{why}");
}
