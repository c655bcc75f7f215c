//! The first-return-map exponent of a phase-coherent flow
//! (`pdamp::analysis::return_map_lyapunov`) against literature values, and its refusal of a
//! flow whose mean crossings do not return regularly.

use pdamp::analysis::return_map_lyapunov::{return_map_lyapunov, ReturnMapOptions};
use pdamp::error::AnalysisError;
use pdamp::systems::lorenz::lorenz_x;
use pdamp::systems::roessler::{roessler_x, LYAPUNOV};

#[test]
fn roessler_exponent_from_its_return_map() {
    // Rössler (0.2, 0.2, 5.7): λ₁ = 0.0714 per time unit (Sprott; SPEC §9). Measured through
    // the return map with m = 3, τ = 1.25 time units: 0.0645 (20 000 samples at dt = 0.05,
    // 170 returns) and 0.0678 (80 000, 683 returns); Kantz on the series gives 0.052 / 0.055.
    // The band is 15 %: the section exponent of ~170 returns is biased low by ~10 %.
    let dt = 0.05;
    for n in [20_000, 80_000] {
        let x = roessler_x(n, dt);
        let r = return_map_lyapunov(
            &x,
            &ReturnMapOptions {
                m: 3,
                tau: 25,
                ..Default::default()
            },
        )
        .unwrap();
        let l = r.per_sample / dt;
        assert!((l - LYAPUNOV).abs() < 0.15 * LYAPUNOV, "n = {n}: {l}");
        // mean return time ≈ 5.9 time units (the rotation), scatter < 10 %
        assert!(
            (r.mean_return_samples * dt - 5.86).abs() < 0.1,
            "{}",
            r.mean_return_samples
        );
        assert!(r.return_cv < 0.1, "{}", r.return_cv);
        assert!(r.points > n / 120, "{}", r.points);
    }
}

#[test]
fn lorenz_is_not_phase_coherent() {
    // Lorenz x switches lobes at random: its upward mean crossings return at scattered times
    // (cv ≈ 0.6), so the return map is refused rather than misread.
    let x = lorenz_x(20_000, 0.01);
    let r = return_map_lyapunov(
        &x,
        &ReturnMapOptions {
            m: 3,
            tau: 17,
            ..Default::default()
        },
    );
    match r {
        Err(AnalysisError::NoResult(msg)) => assert!(msg.contains("phase-coherent"), "{msg}"),
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn too_few_rotations_are_too_short() {
    let x: Vec<f64> = (0..500).map(|n| (n as f64 * 0.01).sin()).collect();
    assert!(matches!(
        return_map_lyapunov(&x, &ReturnMapOptions::default()),
        Err(AnalysisError::TooShort(_))
    ));
}
