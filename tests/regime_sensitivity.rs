//! Regime verdicts of a forced system whose collective motion follows the drive while a
//! high-dimensional chaotic subsystem stirs it (issue 39, item 5): a driven damped oscillator
//! kicked once per period by a ring of 16 coupled logistic maps
//! ([`pdamp::systems::forced_ring`]), the coupling ε swept.
//!
//! References we can compute: uncoupled, the oscillator is linear, its section one stable
//! point (periodic-1) and the replicas coincide; coupled, the ring's chaos (about 16 positive
//! exponents) makes the motion sensitive at every ε > 0, and what changes with ε is only how
//! large the sensitive part is against the orbit. So the verdict must be periodic-1 exactly
//! while the section's scatter is small against the orbit (≤ 5 % on every axis) and chaotic
//! once it is not — phase-locked while the motion still follows the drive (Λ₁ ≥ 0.9) and
//! high-dimensional (the section in (x, ẋ) does not predict its successor: the ring is hidden).
//!
//! Run in release: `cargo test --release --test regime_sensitivity`.

use pdamp::analysis::analyze::{analyze_forced, AnalysisReport, AnalyzeOptions, ForcedRun};
use pdamp::analysis::regime::Regime;
use pdamp::analysis::replica_test::{report, ReplicaOutcome, ReplicaReport, ReplicaRow};
use pdamp::analysis::section_dimension::ChaosDimension;
use pdamp::systems::forced_ring::{run_with_replica, ForcedRingParams};

const DELTA: f64 = 1e-9;
/// Damping ratio: strong enough that a kick's response dies within about a period, as a
/// grain's collision does in a bed (the oscillator's own resonance would otherwise carry the
/// ring's chaos far from the strobes).
const ZETA: f64 = 0.5;

fn verdict_at(coupling: f64) -> (AnalysisReport, ReplicaReport) {
    let p = ForcedRingParams {
        coupling,
        zeta: ZETA,
        ..ForcedRingParams::default()
    };
    let rec = run_with_replica(p, 200, 300, DELTA);
    let rows: Vec<ReplicaRow> = (0..rec.times_s.len())
        .map(|k| ReplicaRow {
            cycle: k as u64 + 1,
            time_s: rec.times_s[k],
            a: [rec.section_a[k][0], rec.section_a[k][1], 0.0, 0.0],
            b: [rec.section_b[k][0], rec.section_b[k][1], 0.0, 0.0],
        })
        .collect();
    // δ0 acts on the ring, not on x: quote it in metres of x as the kick it makes
    let rep = report(
        DELTA * coupling.max(1e-300) / 40.0,
        rec.perturbed_at_s,
        p.forcing_hz,
        [rec.extent[0], rec.extent[1], 0.0, 0.0],
        rows,
    );
    let section: Vec<Vec<f64>> = rec.section_a.iter().map(|s| s.to_vec()).collect();
    let run = ForcedRun {
        series: &rec.series_m,
        dt_s: rec.dt_s,
        forcing_hz: p.forcing_hz,
        section: &section,
        scales: &rec.extent,
        model_exponent: None,
        in_box_series: &[],
        replica: Some(&rep),
        replica_deferred: false,
    };
    let a = analyze_forced(&run, &AnalyzeOptions::default()).expect("analysis");
    (a, rep)
}

#[test]
fn uncoupled_the_oscillator_is_periodic_and_insensitive() {
    let (a, rep) = verdict_at(0.0);
    assert_eq!(
        rep.outcome,
        ReplicaOutcome::Insensitive,
        "{}",
        rep.describe()
    );
    assert_eq!(
        (a.regime, a.period),
        (Regime::Periodic, Some(1.0)),
        "{}",
        a.reason
    );
    assert!(!a.phase_locked);
}

#[test]
fn periodic_while_the_sensitive_part_is_small_chaotic_once_it_is_not() {
    let mut seen_periodic = false;
    let mut seen_locked_chaos = false;
    for coupling in [0.003, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 1.0, 3.0, 10.0] {
        let (a, rep) = verdict_at(coupling);
        let sec = a.section.as_ref().expect("section");
        let worst = sec.axis_scatter.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "ε = {coupling}: {} | section size {:.4}, scatter {:.4} (worst axis {worst:.4}), Λ {:?}; replica {}",
            a.verdict(),
            sec.size,
            sec.scatter,
            a.phase_lock.map(|l| l.locked_fraction),
            rep.describe()
        );
        // the ring's chaos reaches the oscillator at every ε > 0
        assert!(
            matches!(rep.outcome, ReplicaOutcome::Sensitive { .. }),
            "ε = {coupling}: {}",
            rep.describe()
        );
        // the orbit is period 1 (a forced linear oscillator): its scatter is W₁, the size
        if sec.size <= 0.05 {
            assert_eq!(
                (a.regime, a.period),
                (Regime::Periodic, Some(1.0)),
                "ε = {coupling}: {}",
                a.reason
            );
            seen_periodic = true;
        } else {
            assert_eq!(a.regime, Regime::Chaotic, "ε = {coupling}: {}", a.reason);
            assert!(
                matches!(a.chaos_dimension, Some(ChaosDimension::High { .. })),
                "ε = {coupling}: {:?}",
                a.chaos_dimension
            );
            if a.phase_locked {
                assert!(a
                    .verdict()
                    .starts_with("chaotic; phase-locked to the forcing (Λ₁ = "));
                seen_locked_chaos = true;
            }
        }
    }
    assert!(
        seen_periodic,
        "no coupling small enough for a periodic verdict"
    );
    assert!(seen_locked_chaos, "no coupling giving phase-locked chaos");
}
