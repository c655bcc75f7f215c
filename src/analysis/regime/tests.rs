//! Tests of the regime classifier ([`super::classify`]).

#![cfg(test)]

use super::*;

fn line(f: f64, p: f64) -> SpectralLine {
    SpectralLine {
        frequency: f,
        bin: 0,
        peak_power: p,
        line_power: p,
        prominence: 1e6,
    }
}

#[test]
fn recurrence_finds_smallest_period() {
    let x: Vec<f64> = (0..300).map(|n| [0.1, 0.7, 0.4][n % 3]).collect();
    assert_eq!(recurrence_period(&x, 64, 1e-9), Some(3));
    // A constant series has no period (zero range).
    assert_eq!(recurrence_period(&[1.0; 50], 10, 1e-3), None);
    // A ramp never recurs.
    let ramp: Vec<f64> = (0..100).map(|n| n as f64).collect();
    assert_eq!(recurrence_period(&ramp, 30, 1e-3), None);
}

#[test]
fn harmonics_and_tori() {
    // Period-3 orbit: lines at f/3, 2f/3, f (f strongest) → f₀ = f/3.
    let lines = [
        line(0.1 / 3.0, 0.2),
        line(0.2 / 3.0, 0.1),
        line(0.1, 1.0),
        line(0.2, 0.05),
    ];
    let f0 = harmonic_fundamental(&lines, 8, 1e-5, 1e-3).unwrap();
    assert!((f0 - 0.1 / 3.0).abs() < 1e-12);
    // Torus: f and √2 f are not harmonics of any f/k with k ≤ 8 within the tolerance.
    let torus = [line(0.1, 1.0), line(0.1 * 2f64.sqrt(), 0.25)];
    assert_eq!(harmonic_fundamental(&torus, 8, 1e-4, 1e-3), None);
}

#[test]
fn classify_rules() {
    let t = RegimeThresholds::default();
    let periodic = Evidence {
        recurrence_period_samples: Some(4),
        ..Default::default()
    };
    let v = classify(&periodic, &t);
    assert_eq!((v.regime, v.period), (Regime::Periodic, Some(4.0)));
    let noise = Evidence {
        zero_one_k: Some(0.99),
        fnn_converged: Some(false),
        ..Default::default()
    };
    assert_eq!(classify(&noise, &t).regime, Regime::Irregular);
    assert_eq!("stochastic".parse::<Regime>(), Ok(Regime::Irregular));
    let chaos = Evidence {
        zero_one_k: Some(0.99),
        fnn_converged: Some(true),
        kantz_linear: true,
        mle_per_sample: Some(0.69),
        kantz_growth: Some(4.0),
        ..Default::default()
    };
    assert_eq!(classify(&chaos, &t).regime, Regime::Chaotic);
    // Negative control: the same exponent with K ≈ 0 is not chaos.
    let regular = Evidence {
        zero_one_k: Some(0.02),
        ..chaos
    };
    assert_ne!(classify(&regular, &t).regime, Regime::Chaotic);
    assert_eq!(Regime::QuasiPeriodic.as_str(), "quasi-periodic");
    for r in Regime::ALL {
        assert_eq!(r.as_str().parse::<Regime>(), Ok(r));
    }
    let e = "periodic-2".parse::<Regime>().unwrap_err();
    assert!(
        e.contains("\"periodic-2\"") && e.contains("too-short"),
        "{e}"
    );
    assert_eq!(
        serde_json::to_string(&Regime::QuasiPeriodic).unwrap(),
        "\"quasi-periodic\""
    );
}
