//! Cao's minimum embedding dimension (Cao, Physica D 110, 43 (1997)) on the reference systems
//! and white noise.

use pdamp::analysis::cao::{cao, CaoOptions};
use pdamp::error::AnalysisError;
use pdamp::systems::{henon, lorenz};

mod common;
use common::uniform_white as white_noise;

#[test]
fn lorenz_needs_three_dimensions() {
    // Reference: Cao (1997) §3 (Lorenz x): E1 saturates from m = 3. Sampling dt = 0.02,
    // τ = 5 samples (0.1 time units), Theiler window 50 samples (one time unit) so that the
    // nearest neighbour is not the next sample of the same trajectory piece.
    let x = lorenz::lorenz_x(10_000, 0.02);
    let o = CaoOptions {
        m_max: 6,
        tau: 5,
        theiler: 50,
        ..CaoOptions::default()
    };
    let r = cao(&x, &o).unwrap();
    assert_eq!(r.dimension, Some(3), "E1 = {:?}", r.e1);
    // m = 2 is clearly unsaturated (E1(2) ≈ 0.3): a dimension-blind distance would miss it
    assert!(r.e1[1] < 0.6, "E1 = {:?}", r.e1);
    // deterministic data: E2 differs from 1 at small m (Cao's criterion for determinism)
    assert!(r.e2[0] < 0.5, "E2 = {:?}", r.e2);
}

#[test]
fn henon_needs_two_dimensions() {
    // Reference: Cao (1997) §3: the Hénon map's minimum embedding dimension is 2.
    let r = cao(
        &henon::henon_x(5000),
        &CaoOptions {
            m_max: 6,
            ..CaoOptions::default()
        },
    )
    .unwrap();
    assert_eq!(r.dimension, Some(2), "E1 = {:?}", r.e1);
    assert!(r.e2[0] < 0.5, "E2 = {:?}", r.e2);
}

#[test]
fn white_noise_has_e2_one() {
    // Reference: Cao (1997): for random data x_{i+mτ} is independent of the neighbour
    // choice, so E*(m) is the mean |x − x'| of two independent samples (1/3 for U(0, 1)) and
    // E2(m) = 1 for all m. Tolerance 0.05: the standard error of each mean over 5000 pairs is
    // 0.236/√5000 ≈ 0.0033 (0.010 relative), the ratio of two ≈ 0.014; 0.05 is > 3σ.
    let r = cao(
        &white_noise(5000, 7),
        &CaoOptions {
            m_max: 6,
            ..CaoOptions::default()
        },
    )
    .unwrap();
    for (m, e2) in r.m.iter().zip(&r.e2) {
        assert!((e2 - 1.0).abs() < 0.05, "E2({m}) = {e2}");
    }
    for e in &r.e_star {
        assert!((e - 1.0 / 3.0).abs() < 0.02, "E* = {e}");
    }
    // and E1 does not saturate within m ≤ 6 (negative control)
    assert_eq!(r.dimension, None, "E1 = {:?}", r.e1);
}

#[test]
fn bad_input_is_named() {
    let o = CaoOptions::default();
    assert!(matches!(cao(&[2.0; 100], &o), Err(AnalysisError::Constant)));
    let mut x = henon::henon_x(100);
    x[3] = f64::INFINITY;
    assert_eq!(cao(&x, &o), Err(AnalysisError::NonFinite { index: 3 }));
    assert!(matches!(
        cao(&henon::henon_x(15), &o),
        Err(AnalysisError::TooShort(_))
    ));
}
