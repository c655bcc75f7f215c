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
    match kantz(&x, &opts) {
        Err(AnalysisError::TooShort(m)) => assert!(m.contains("10"), "{m}"),
        other => panic!("expected TooShort, got {other:?}"),
    }
    assert!(matches!(
        kantz(&[1.0], &opts),
        Err(AnalysisError::TooShort(_))
    ));
}

#[test]
fn constant_and_non_finite_series_are_refused() {
    let c = vec![0.25; 500];
    assert!(matches!(
        kantz(&c, &KantzOptions::default()),
        Err(AnalysisError::Constant)
    ));
    assert!(mutual_information(&c, &MutualInformationOptions::default()).is_err());
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
    match kantz(
        &x,
        &KantzOptions {
            m_max: 3,
            ..KantzOptions::default()
        },
    ) {
        Ok(r) => {
            let d = format!("{r:?}");
            assert!(!d.contains("NaN"), "Kantz curves contain NaN: {d:.400}");
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}
