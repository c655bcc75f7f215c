//! Correlation dimension (Grassberger & Procaccia 1983; TISEAN `d2`) against the literature
//! values, an independent brute-force correlation sum and negative controls.

use pdamp::analysis::correlation_dimension::{
    correlation_dimension, correlation_sum, D2Options, PlateauOptions,
};
use pdamp::error::AnalysisError;
use pdamp::systems::{henon, lorenz};

/// Brute force written from the definition: all pairs i < j of the N − (M−1)τ delay vectors
/// with j − i > w, maximum norm in m dimensions, counted at every ε with d ≤ ε.
fn brute_force(x: &[f64], o: &D2Options, eps: &[f64]) -> Vec<Vec<u64>> {
    let nv = x.len() - (o.m_max - 1) * o.tau;
    (o.m_min..=o.m_max)
        .map(|m| {
            let mut counts = vec![0u64; eps.len()];
            for i in 0..nv {
                for j in i + o.theiler + 1..nv {
                    let d = (0..m)
                        .map(|k| (x[i + k * o.tau] - x[j + k * o.tau]).abs())
                        .fold(0.0, f64::max);
                    for (c, &e) in counts.iter_mut().zip(eps) {
                        *c += u64::from(d <= e);
                    }
                }
            }
            counts
        })
        .collect()
}

#[test]
fn correlation_sum_equals_brute_force() {
    // exact integer counts: any pair lost by the box search or binned wrongly fails this
    let x = henon::henon_x(700);
    for o in [
        D2Options {
            m_min: 1,
            m_max: 4,
            tau: 1,
            theiler: 3,
            eps_min: Some(0.01),
            eps_max: Some(0.4),
            eps_count: 17,
        },
        D2Options {
            m_min: 2,
            m_max: 3,
            tau: 2,
            theiler: 0,
            eps_count: 9,
            ..D2Options::default()
        },
    ] {
        let got = correlation_sum(&x, &o).unwrap();
        let eps = got.curves[0].eps.clone();
        let want = brute_force(&x, &o, &eps);
        for (c, w) in got.curves.iter().zip(&want) {
            assert_eq!(&c.pairs, w, "m = {}", c.m);
        }
        let nv = (x.len() - (o.m_max - 1) * o.tau) as u64;
        let w = o.theiler as u64;
        assert_eq!(got.total_pairs, (nv - w - 1) * (nv - w) / 2);
    }
}

#[test]
fn henon_d2_matches_grassberger_procaccia() {
    // Reference: Grassberger & Procaccia, PRL 50, 346 (1983): Hénon (1.4, 0.3) D2 = 1.21 ± 0.01
    // (1.22 in later, longer computations). Tolerance 5 % (the brief's band): with 10⁴ points
    // the local slopes scatter by ~±0.03 around the plateau (lacunarity of the Hénon
    // attractor makes them oscillate in ln ε), well inside 5 %.
    let x = henon::henon_x(10_000);
    let o = D2Options {
        m_min: 1,
        m_max: 4,
        eps_max: Some(0.5),
        eps_count: 50,
        ..D2Options::default()
    };
    let t = std::time::Instant::now();
    let (_, est) = correlation_dimension(&x, &o, &PlateauOptions::default()).unwrap();
    eprintln!(
        "Hénon D2 = {:.4} ± {:.4} ({:?}) in {:?}",
        est.d2,
        est.spread,
        est.dims_used,
        t.elapsed()
    );
    assert!(est.flat, "{est:?}");
    assert!((est.d2 - 1.22).abs() <= 0.05 * 1.22, "{est:?}");
}

#[test]
fn lorenz_d2_matches_grassberger_procaccia() {
    // Reference: Grassberger & Procaccia (1983): Lorenz (10, 28, 8/3) D2 = 2.05 ± 0.01.
    // Tolerance 5 % (the brief's band). Sampling dt = 0.02, τ = 5 samples (0.1 time units),
    // Theiler window 50 samples (one time unit, beyond the autocorrelation time of x) so that
    // temporal neighbours do not pull the slope towards 1.
    let x = lorenz::lorenz_x(10_000, 0.02);
    let o = D2Options {
        m_min: 1,
        m_max: 6,
        tau: 5,
        theiler: 50,
        eps_min: Some(0.05),
        eps_max: Some(8.0),
        eps_count: 50,
    };
    let t = std::time::Instant::now();
    let (_, est) = correlation_dimension(&x, &o, &PlateauOptions::default()).unwrap();
    eprintln!(
        "Lorenz D2 = {:.4} ± {:.4} ({:?}) in {:?}",
        est.d2,
        est.spread,
        est.dims_used,
        t.elapsed()
    );
    assert!((est.d2 - 2.05).abs() <= 0.05 * 2.05, "{est:?}");
}

#[test]
fn white_noise_has_no_saturation() {
    // Negative control: for iid noise the slope grows with m (D2 = m at small ε): the m = 4
    // slope must be far above the m = 1 slope (≈ 1) — a wrong (e.g. dimension-independent)
    // distance would give equal slopes.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let x: Vec<f64> = (0..4000)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let o = D2Options {
        m_min: 1,
        m_max: 4,
        eps_min: Some(0.05),
        eps_max: Some(0.3),
        eps_count: 10,
        ..D2Options::default()
    };
    let r = correlation_sum(&x, &o).unwrap();
    let s1 = r.curves[0].slope[3].unwrap();
    let s4 = r.curves[3].slope[3].unwrap();
    assert!((s1 - 1.0).abs() < 0.1, "m = 1 slope {s1}");
    assert!(s4 > 3.0, "m = 4 slope {s4}");
}

#[test]
fn bad_input_is_named() {
    let o = D2Options::default();
    assert!(matches!(
        correlation_sum(&[1.0; 50], &o),
        Err(AnalysisError::Constant)
    ));
    let mut x = henon::henon_x(100);
    x[7] = f64::NAN;
    assert_eq!(
        correlation_sum(&x, &o),
        Err(AnalysisError::NonFinite { index: 7 })
    );
    assert!(matches!(
        correlation_sum(&henon::henon_x(11), &o),
        Err(AnalysisError::TooShort(_))
    ));
}
