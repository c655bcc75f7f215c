//! Stroboscopic Poincaré sections against analytic references: a sine strobed at its own
//! frequency is one point (to interpolation accuracy), a period-3 signal three points, a
//! two-frequency signal with an irrational ratio a closed curve; noise and the Hénon attractor
//! are clouds (negative controls).

use pdamp::analysis::poincare::{
    classify_section, closed_curve_score, count_distinct_points, period_in_samples,
    stroboscopic_section, ClusterOptions, Interpolation, SecondCoordinate, SectionShape,
    StrobeOptions,
};
use std::f64::consts::TAU;

mod common;

fn spread(points: &[[f64; 2]], coord: usize) -> f64 {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p[coord]), h.max(p[coord]))
        });
    hi - lo
}

#[test]
fn sine_strobed_at_its_frequency_is_one_point() {
    // 100 Hz sine sampled at dt = 1/3730 s: 37.3 samples per period, so the section times fall
    // between samples and interpolation matters.
    let (f_hz, dt) = (100.0, 1.0 / 3730.0);
    let period = period_in_samples(f_hz, dt).unwrap();
    assert!((period - 37.3).abs() < 1e-9);
    let x: Vec<f64> = (0..20_000)
        .map(|n| (TAU * f_hz * n as f64 * dt + 0.7).sin())
        .collect();
    let w = TAU / period; // angular frequency per sample
    for (interp, bound) in [
        // Lagrange remainder: |e| ≤ max|x⁗|/4! · max|Π(s − node)| = ω⁴/24 (the end intervals,
        // 9/16 of that inside) = 3.4e-5 here.
        (Interpolation::Cubic, w.powi(4) / 24.0),
        // Linear: |e| ≤ max|x''|/8 = ω²/8 (= 3.5e-3 here).
        (Interpolation::Linear, w * w / 8.0),
    ] {
        let opts = StrobeOptions {
            interpolation: interp,
            ..StrobeOptions::new(period)
        };
        let sec = stroboscopic_section(&x, SecondCoordinate::Delay(5.5), &opts).unwrap();
        assert_eq!(sec.points.len(), 537); // ⌊(19999 − 5.5)/37.3⌋ + 1 = 536 + 1
                                           // Every point is the same up to twice the interpolation bound (two errors of opposite sign).
        for c in 0..2 {
            assert!(
                spread(&sec.points, c) <= 2.0 * bound,
                "{interp:?} coord {c}: {}",
                spread(&sec.points, c)
            );
        }
        // And clustering with the interpolation accuracy as tolerance (relative to the range 2)
        // sees one point. (With linear interpolation the default 0.1 % would see 2: 37 samples
        // per period are too few for it, hence cubic is the default.)
        let opts = ClusterOptions {
            rel_tol: (2.0 * bound / 2.0).max(1e-3),
            ..Default::default()
        };
        let d = count_distinct_points(&sec.points, 2.0, &opts);
        assert_eq!(d.n_distinct, Some(1), "{interp:?}");
        // The section point is (sin(0.7), sin(0.7 + 5.5 ω)), the exact values.
        let p = d.clusters[0].centre;
        assert!((p[0] - 0.7f64.sin()).abs() <= bound);
        assert!((p[1] - (0.7 + 5.5 * w).sin()).abs() <= bound);
    }
}

#[test]
fn period_three_signal_has_three_points() {
    // x(t) = sin(ωt) + 0.5 sin(ωt/3 + 1): a period-3 response to forcing at ω; 23.7 samples
    // per forcing period.
    let period = 23.7;
    let w = TAU / period;
    let x: Vec<f64> = (0..30_000)
        .map(|n| (w * n as f64).sin() + 0.5 * (w * n as f64 / 3.0 + 1.0).sin())
        .collect();
    let sec = stroboscopic_section(
        &x,
        SecondCoordinate::Delay(6.0),
        &StrobeOptions::new(period),
    )
    .unwrap();
    let range = 3.0; // max − min of x is ≤ 3
    let summary = classify_section(&sec.points, range, &ClusterOptions::default());
    assert_eq!(summary.shape, SectionShape::Points(3));
    // Negative control: a tolerance larger than the points' separation merges them.
    let coarse = ClusterOptions {
        rel_tol: 0.5,
        ..Default::default()
    };
    assert_eq!(
        count_distinct_points(&sec.points, range, &coarse).n_distinct,
        Some(1)
    );
}

#[test]
fn second_column_coordinates() {
    // (x, v) = (sin ωt, ω cos ωt) strobed at the period: one point (0, ω) up to cubic error.
    let period = 50.3;
    let w = TAU / period;
    let x: Vec<f64> = (0..5000).map(|n| (w * n as f64).sin()).collect();
    let v: Vec<f64> = (0..5000).map(|n| w * (w * n as f64).cos()).collect();
    let sec = stroboscopic_section(
        &x,
        SecondCoordinate::Column(&v),
        &StrobeOptions::new(period),
    )
    .unwrap();
    for p in &sec.points {
        // Cubic error bound ω⁴·(9/16)/24 ≈ 5e-6 (scaled by ω for the velocity).
        assert!(p[0].abs() < 1e-5 && (p[1] - w).abs() < 1e-5, "{p:?}");
    }
    // Mismatched column lengths are an error naming the column.
    let err = stroboscopic_section(
        &x,
        SecondCoordinate::Column(&v[..10]),
        &StrobeOptions::new(period),
    )
    .unwrap_err();
    assert!(err.to_string().contains("column"));
}

#[test]
fn quasi_periodic_section_is_a_closed_curve() {
    // sin(ωt) + 0.5 sin(√2 ωt): strobed at ω the first term is constant and the second rotates
    // by 2π√2 per period, filling an ellipse in (s(t), s(t+τ)) — an invariant circle.
    let period = 31.9;
    let w = TAU / period;
    let x: Vec<f64> = (0..40_000)
        .map(|n| (w * n as f64).sin() + 0.5 * (2f64.sqrt() * w * n as f64).sin())
        .collect();
    let sec = stroboscopic_section(
        &x,
        SecondCoordinate::Delay(8.0),
        &StrobeOptions::new(period),
    )
    .unwrap();
    let summary = classify_section(&sec.points, 3.0, &ClusterOptions::default());
    assert_eq!(summary.shape, SectionShape::ClosedCurve, "{summary:?}");
    // A rotation preserves the cyclic order exactly: the score is 1 up to the orbit's end point.
    assert!(
        summary.closed_curve_score > 0.99,
        "{}",
        summary.closed_curve_score
    );
}

#[test]
fn noise_and_henon_are_clouds() {
    // Negative controls. Gaussian noise: no order is preserved, the score is ~ 5/n per shift.
    let x = common::white_gaussian(20_000, 42);
    let sec =
        stroboscopic_section(&x, SecondCoordinate::Delay(3.0), &StrobeOptions::new(17.3)).unwrap();
    let s = classify_section(&sec.points, 8.0, &ClusterOptions::default());
    assert_eq!(s.shape, SectionShape::Cloud, "{s:?}");
    assert!(s.closed_curve_score < 0.2);
    // The Hénon map (a = 1.4, b = 0.3) as its own section: a folded, chaotic set.
    let (mut u, mut v) = (0.1, 0.1);
    let mut pts = Vec::new();
    for k in 0..3000 {
        let un = 1.0 - 1.4 * u * u + v;
        v = 0.3 * u;
        u = un;
        if k >= 100 {
            pts.push([u, v]);
        }
    }
    let s = classify_section(&pts, 2.5, &ClusterOptions::default());
    assert_eq!(s.shape, SectionShape::Cloud, "{s:?}");
    assert!(closed_curve_score(&pts) < 0.5);
}
