//! Tests of the forced-system classifier's replica rules ([`super::classify_forced`]) on
//! sections and replica records whose answer is known by construction.

#![cfg(test)]

use super::*;
use crate::analysis::replica_test::fixtures::{gauss, rows_of, slow_motion_pair, EXTENT};
use crate::analysis::replica_test::report;
use crate::analysis::section::{analyze_section, SectionOptions};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

const F: f64 = 11.0;

/// A replica report from two strobed z series (m) perturbed by 1e-9 m.
fn replicas(za: &[f64], zb: &[f64]) -> ReplicaReport {
    report(1e-9, 0.0, F, EXTENT, rows_of(za, zb, F))
}

/// Replicas sharing a slow motion, differing by independent noise: partial.
fn partial() -> ReplicaReport {
    let r = slow_motion_pair(1e-9);
    assert!(matches!(r.outcome, ReplicaOutcome::Partial { .. }), "{r:?}");
    r
}

/// Two independent clouds whose means differ by three spreads: different macroscopic states.
fn different_states() -> ReplicaReport {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let za: Vec<f64> = (0..240).map(|_| 0.05 + 1e-3 * gauss(&mut rng)).collect();
    let zb: Vec<f64> = (0..240).map(|_| 0.053 + 1e-3 * gauss(&mut rng)).collect();
    let r = replicas(&za, &zb);
    let ReplicaOutcome::Inconclusive { why } = &r.outcome else {
        panic!("{r:?}");
    };
    assert!(why.contains("different macroscopic states"), "{why}");
    r
}

fn section(points: &[Vec<f64>]) -> SectionAnalysis {
    analyze_section(points, &[1.0, 1.0], &SectionOptions::default()).unwrap()
}

/// Period 2 with 2 % scatter: two tight groups.
fn period_two() -> SectionAnalysis {
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    let pts: Vec<Vec<f64>> = (0..240)
        .map(|k| {
            let c = [[0.3, 0.3], [0.7, 0.6]][k % 2];
            vec![c[0] + 0.02 * gauss(&mut rng), c[1] + 0.02 * gauss(&mut rng)]
        })
        .collect();
    section(&pts)
}

fn cloud() -> SectionAnalysis {
    let mut rng = ChaCha8Rng::seed_from_u64(8);
    let pts: Vec<Vec<f64>> = (0..240)
        .map(|_| vec![0.5 + 0.1 * gauss(&mut rng), 0.5 + 0.1 * gauss(&mut rng)])
        .collect();
    let s = section(&pts);
    assert!(
        s.tight.is_none() && s.pattern == SectionPattern::Irregular,
        "{s:?}"
    );
    s
}

/// The verdict from the section and the simulator's replica test alone (no exponents, no
/// phase lock): `replica` as it ran, or held back (`deferred`).
fn classify(sec: &SectionAnalysis, replica: Option<&ReplicaReport>, deferred: bool) -> Verdict {
    classify_forced(&ForcedEvidence {
        section: sec,
        data_exponent: None,
        model_exponent: None,
        zero_band: 0.01,
        phase_lock: None,
        replica,
        replica_deferred: deferred,
        dimension: None,
    })
}

fn verdict(sec: &SectionAnalysis, r: &ReplicaReport) -> Verdict {
    classify(sec, Some(r), false)
}

#[test]
fn a_cloud_with_partial_replicas_is_chaotic_and_slowly_mixing() {
    let v = verdict(&cloud(), &partial());
    assert_eq!(v.regime, Regime::Chaotic, "{}", v.reason);
    assert!(v.reason.contains("slowly mixing"), "{}", v.reason);
}

#[test]
fn a_thin_closed_curve_with_partial_replicas_is_quasi_periodic() {
    // a circle of radius 0.2 rotated by ρ = 0.136 per strobe, 0.3 % radial noise
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let pts: Vec<Vec<f64>> = (0..240)
        .map(|k| {
            let th = std::f64::consts::TAU * 0.136 * k as f64;
            let r = 0.2 * (1.0 + 0.003 * gauss(&mut rng));
            vec![0.5 + r * th.cos(), 0.5 + r * th.sin()]
        })
        .collect();
    let s = section(&pts);
    assert!(
        matches!(s.pattern, SectionPattern::QuasiPeriodic { .. }),
        "{s:?}"
    );
    let v = verdict(&s, &partial());
    assert_eq!(v.regime, Regime::QuasiPeriodic, "{}", v.reason);
}

#[test]
fn tight_groups_are_periodic_whatever_the_replicas() {
    // period 2 with 2 % scatter: periodic-2 with partial replicas and with replicas that
    // ended in different states (the run itself repeats; the replicas size its sensitive part)
    let s = period_two();
    for r in [partial(), different_states()] {
        let v = verdict(&s, &r);
        assert_eq!(
            (v.regime, v.period),
            (Regime::Periodic, Some(2.0)),
            "{}",
            v.reason
        );
    }
}

#[test]
fn a_cloud_is_not_chaotic_without_sensitivity() {
    // replicas in different macroscopic states: undetermined, never chaotic
    let v = verdict(&cloud(), &different_states());
    assert_eq!(v.regime, Regime::Undetermined, "{}", v.reason);
    assert!(
        v.reason.contains("different macroscopic states"),
        "{}",
        v.reason
    );
    // replicas that stay together: undetermined (a long transient or a long period)
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let za: Vec<f64> = (0..240).map(|_| 0.05 + 1e-3 * gauss(&mut rng)).collect();
    let zb: Vec<f64> = za.iter().map(|z| z + 1e-12).collect();
    let r = replicas(&za, &zb);
    assert_eq!(r.outcome, ReplicaOutcome::Insensitive, "{r:?}");
    let v = verdict(&cloud(), &r);
    assert_eq!(v.regime, Regime::Undetermined, "{}", v.reason);
}

/// The verdict with the simulator's replica test held back (`replica_deferred`).
fn verdict_deferred(sec: &SectionAnalysis) -> Verdict {
    classify(sec, None, true)
}

#[test]
fn a_held_back_replica_test_is_not_needed_for_tight_groups_only() {
    // period 2 with 2 % scatter: periodic-2 without the replicas, as with them
    let s = period_two();
    let v = verdict_deferred(&s);
    assert_eq!((v.regime, v.period), (Regime::Periodic, Some(2.0)));
    assert!(v.reason.contains("not needed"), "{}", v.reason);
    assert_eq!(
        (v.regime, v.period),
        {
            let w = verdict(&s, &partial());
            (w.regime, w.period)
        },
        "with the replicas"
    );
    // a cloud is not judged without them: the caller must run the test (here the data rule
    // answers, never "chaotic" by replicas it has not seen)
    let c = verdict_deferred(&cloud());
    assert!(!c.reason.contains("not needed"), "{}", c.reason);
    assert!(!c.reason.contains("two replicas"), "{}", c.reason);
}
