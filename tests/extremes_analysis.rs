//! Series analysis at the edge (issue "Stability at the extremes"): very short, constant,
//! non-finite and quantised z_cm series. Each estimator either returns finite values or an
//! error that says what is wrong (lengths, the offending index); never NaN.

use pdamp::analysis::{kantz, mutual_information, KantzOptions, MutualInformationOptions};
use pdamp::error::AnalysisError;

fn sine(n: usize) -> Vec<f64> {
    (0..n).map(|i| (i as f64 * 0.1).sin()).collect()
}

#[test]
fn very_short_series_name_both_lengths() {
    let x = sine(10);
    let opts = KantzOptions {
        m_max: 3,
        ..KantzOptions::default()
    };
    // the needed length steps + (m_max − 1)·tau = 50 + 2 = 52, the parameters it comes
    // from, and the series' 10 samples
    match kantz(&x, &opts) {
        Err(AnalysisError::TooShort(m)) => {
            for part in ["steps", "m_max", "tau", "52", "10"] {
                assert!(m.contains(part), "no {part:?} in {m:?}");
            }
        }
        other => panic!("expected TooShort, got {other:?}"),
    }
    match kantz(&[1.0], &opts) {
        Err(AnalysisError::TooShort(m)) => {
            assert!(
                m.contains("at least 2 samples") && m.contains("has 1"),
                "{m}"
            )
        }
        other => panic!("expected TooShort, got {other:?}"),
    }
}

#[test]
fn constant_and_non_finite_series_are_refused() {
    let c = vec![0.25; 500];
    assert!(matches!(
        kantz(&c, &KantzOptions::default()),
        Err(AnalysisError::Constant)
    ));
    let e = mutual_information(&c, &MutualInformationOptions::default()).unwrap_err();
    assert_eq!(e, AnalysisError::Constant);
    assert!(e.to_string().contains("constant"), "{e}");
    let mut x = sine(500);
    x[123] = f64::NAN;
    assert_eq!(
        kantz(&x, &KantzOptions::default()).unwrap_err(),
        AnalysisError::NonFinite { index: 123 }
    );
}

#[test]
fn quantised_series_give_finite_results() {
    // a z_cm recorded with a coarse sensor: the sine rounded to 3 levels (−1, 0, 1); many
    // exact ties between delay vectors, which must not produce NaN (ln 0) in the estimates
    let x: Vec<f64> = sine(3000).iter().map(|v| v.round()).collect();
    let mi =
        mutual_information(&x, &MutualInformationOptions::default()).expect("MI of quantised data");
    let dbg = format!("{mi:?}");
    assert!(!dbg.contains("NaN"), "{dbg}");
    // Kantz's estimate is defined here (the series varies and is finite): it must succeed,
    // with one curve per (m, ε) — m = 2, 3 × the 5 default radii — of steps + 1 = 51 points.
    // At Δn = 0 every neighbour within ε of a reference is an exact tie (distance 0 on 3
    // levels), so ln S(0) is undefined and reported as None, never −∞ or NaN; from Δn = 1
    // on, the distances are positive and every S(Δn) is a finite number.
    let r = kantz(
        &x,
        &KantzOptions {
            m_max: 3,
            ..KantzOptions::default()
        },
    )
    .expect("Kantz on quantised data");
    assert_eq!(r.curves.len(), 10);
    for c in &r.curves {
        assert_eq!(c.s.len(), 51, "m {} ε {}", c.m, c.eps);
        assert_eq!(c.s[0], None, "m {} ε {}: S(0) of exact ties", c.m, c.eps);
        for (dn, v) in c.s.iter().enumerate().skip(1) {
            assert!(
                v.is_some_and(f64::is_finite),
                "m {} ε {} Δn {dn}: {v:?}",
                c.m,
                c.eps
            );
        }
    }
}
