//! Tests of the surrogates ([`super::surrogate`], [`super::end_to_end_segment`]).

#![cfg(test)]

use super::*;

fn sorted(v: &[f64]) -> Vec<f64> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s
}

#[test]
fn order_key_is_total_cmp() {
    let v = [
        f64::NEG_INFINITY,
        -3.5,
        -1e-300,
        -0.0,
        0.0,
        1e-300,
        2.0,
        f64::INFINITY,
    ];
    for a in v {
        for b in v {
            assert_eq!(
                total_order_key(a).cmp(&total_order_key(b)),
                a.total_cmp(&b),
                "{a} {b}"
            );
        }
    }
}

#[test]
fn shuffle_and_iaaft_are_permutations() {
    let x: Vec<f64> = (0..101).map(|i| ((i * 37) % 101) as f64).collect();
    for method in [SurrogateMethod::Shuffle, SurrogateMethod::Iaaft] {
        let o = SurrogateOptions {
            method,
            ..Default::default()
        };
        let s = surrogate(&x, &o, 3).unwrap();
        assert_eq!(sorted(&s.values), sorted(&x));
        assert_ne!(s.values, x);
    }
}

#[test]
fn phase_randomized_keeps_the_periodogram() {
    let x: Vec<f64> = (0..64)
        .map(|i| (i as f64 * 0.3).sin() + 0.1 * i as f64)
        .collect();
    let o = SurrogateOptions {
        method: SurrogateMethod::PhaseRandomized,
        ..Default::default()
    };
    let s = surrogate(&x, &o, 0).unwrap();
    for (a, b) in periodogram(&x).iter().zip(periodogram(&s.values)) {
        assert!((a - b).abs() <= 1e-12 * a.max(1e-3), "{a} {b}");
    }
}

#[test]
fn index_selects_the_stream() {
    let x: Vec<f64> = (0..50).map(|i| (i as f64).sqrt()).collect();
    let o = SurrogateOptions::default();
    let all = surrogates(&x, 3, &o).unwrap();
    assert_eq!(all[2], surrogate(&x, &o, 2).unwrap());
    assert_ne!(all[0].values, all[1].values);
}

#[test]
fn errors() {
    let o = SurrogateOptions::default();
    assert!(matches!(
        surrogate(&[1.0, 2.0], &o, 0),
        Err(AnalysisError::TooShort(_))
    ));
    assert_eq!(surrogate(&[1.0; 10], &o, 0), Err(AnalysisError::Constant));
    assert!(surrogates(&[1.0, 2.0, 3.0, 4.0], 0, &o).is_err());
    assert!(end_to_end_segment(&[1.0, 2.0, 3.0, 4.0], 5).is_err());
}

#[test]
fn end_to_end_finds_a_whole_period() {
    // a sine with 10.25 periods: the best segment of length ≥ 300 ends near a full period
    let x: Vec<f64> = (0..410)
        .map(|i| (std::f64::consts::TAU * i as f64 / 40.0).sin())
        .collect();
    let seg = end_to_end_segment(&x, 300).unwrap();
    assert!(seg.mismatch < 1e-3 * seg.mismatch_whole.max(1e-9) || seg.mismatch < 1e-6);
    assert_eq!(seg.len % 40, 1, "{seg:?}");
}
