//! Rosenstein's maximal Lyapunov exponent (Rosenstein, Collins & De Luca 1993; TISEAN
//! `lyap_r` definition) against exact and literature exponents, a brute force and a
//! negative control.

use pdamp::analysis::kantz::ScalingOptions;
use pdamp::analysis::rosenstein::{rosenstein, rosenstein_exponent, RosensteinOptions};
use pdamp::error::AnalysisError;
use pdamp::systems::{henon, logistic, lorenz};

/// Brute force from TISEAN lyap_r's definition: rescale to [0, 1]; candidates
/// j < N − (m−1)τ − s, references n < that − t; nearest j (Euclidean, > 0, |n − j| > t);
/// S(k) = mean over pairs with d > 0 of ln d(y_{n+k}, y_{j+k}).
fn brute_force(x: &[f64], o: &RosensteinOptions) -> Vec<Option<f64>> {
    let lo = x.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = x.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let s: Vec<f64> = x.iter().map(|v| (v - lo) / (hi - lo)).collect();
    let d2 = |a: usize, b: usize| -> f64 {
        (0..o.m)
            .map(|k| (s[a + k * o.tau] - s[b + k * o.tau]).powi(2))
            .sum()
    };
    let n_cand = s.len() - (o.m - 1) * o.tau - o.steps;
    let mut sum = vec![0.0; o.steps + 1];
    let mut cnt = vec![0u64; o.steps + 1];
    for n in 0..n_cand - o.theiler {
        let best = (0..n_cand)
            .filter(|&j| n.abs_diff(j) > o.theiler && d2(n, j) > 0.0)
            .min_by(|&a, &b| d2(n, a).total_cmp(&d2(n, b)).then(a.cmp(&b)));
        if let Some(j) = best {
            for k in 0..=o.steps {
                let d = d2(n + k, j + k);
                if d > 0.0 {
                    sum[k] += 0.5 * d.ln();
                    cnt[k] += 1;
                }
            }
        }
    }
    sum.iter()
        .zip(&cnt)
        .map(|(s, &c)| (c > 0).then(|| s / c as f64))
        .collect()
}

#[test]
fn curve_equals_brute_force() {
    let x = henon::henon_x(600);
    for o in [
        RosensteinOptions::default(),
        RosensteinOptions {
            m: 3,
            tau: 2,
            theiler: 5,
            steps: 7,
            eps0: None,
        },
    ] {
        let got = rosenstein(&x, &o).unwrap();
        let want = brute_force(&x, &o);
        for (g, w) in got.s.iter().zip(&want) {
            let (g, w) = (g.unwrap(), w.unwrap());
            assert!((g - w).abs() < 1e-12, "{g} vs {w}");
        }
    }
}

#[test]
fn logistic_gives_ln2() {
    // Exact reference: the logistic map at r = 4 has λ = ln 2 per iteration (conjugate to the
    // tent map). Tolerance 5 %: the nearest-neighbour divergence averages the local stretching
    // |f'(x)| over the invariant density, which is ln 2 exactly; the residual is sampling noise
    // of ~5000 pairs and the curvature of f over the neighbour distances (~1e-4).
    let x = logistic::logistic_series(4.0, 0.3, 5000, 100);
    let o = RosensteinOptions {
        m: 1,
        steps: 10,
        ..Default::default()
    };
    let (_, fit) = rosenstein_exponent(&x, &o, &ScalingOptions::default()).unwrap();
    eprintln!("logistic slope {fit:?}");
    assert!(
        (fit.slope - logistic::LYAPUNOV_R4).abs() < 0.05 * logistic::LYAPUNOV_R4,
        "{fit:?}"
    );
}

#[test]
fn henon_matches_literature() {
    // Reference: Hénon (1.4, 0.3) λ₁ = 0.419217 per iteration (Sprott 2003, Table A.1; SPEC
    // §9). Tolerance 10 %: SPEC §9's band for data-based estimates from 10⁴ clean samples.
    let x = henon::henon_x(10_000);
    let o = RosensteinOptions {
        m: 2,
        steps: 15,
        ..Default::default()
    };
    let (_, fit) = rosenstein_exponent(&x, &o, &ScalingOptions::default()).unwrap();
    eprintln!("Hénon slope {fit:?}");
    assert!(
        (fit.slope - henon::LYAPUNOV).abs() < 0.1 * henon::LYAPUNOV,
        "{fit:?}"
    );
}

#[test]
fn lorenz_matches_literature() {
    // Reference: Lorenz (10, 28, 8/3) λ₁ = 0.90563 per time unit (Sprott 2003; SPEC §9).
    // Tolerance 10 % (SPEC §9's band). dt = 0.01, m = 5, τ = 10 samples (0.1 time units),
    // Theiler window 100 samples (about one mean orbit, as Rosenstein et al. advise).
    let dt = 0.01;
    let x = lorenz::lorenz_x(20_000, dt);
    let o = RosensteinOptions {
        m: 5,
        tau: 10,
        theiler: 100,
        steps: 150,
        eps0: None,
    };
    let (_, fit) = rosenstein_exponent(&x, &o, &ScalingOptions::default()).unwrap();
    let per_time = fit.slope / dt;
    eprintln!("Lorenz {per_time} per time unit, {fit:?}");
    assert!(
        (per_time - lorenz::LYAPUNOV).abs() < 0.1 * lorenz::LYAPUNOV,
        "{fit:?}"
    );
}

#[test]
fn sine_is_not_chaotic() {
    // Negative control: a periodic signal has λ₁ = 0; neighbours keep their distance, so the
    // curve is flat (a wrong time shift of the pairs would make it grow).
    let x: Vec<f64> = (0..5000).map(|i| (i as f64 * 0.05).sin()).collect();
    let o = RosensteinOptions {
        m: 2,
        tau: 30,
        theiler: 130,
        steps: 40,
        eps0: None,
    };
    let (_, fit) = rosenstein_exponent(&x, &o, &ScalingOptions::default()).unwrap();
    assert!(fit.slope.abs() < 0.01, "{fit:?}");
}

#[test]
fn bad_input_is_named() {
    let o = RosensteinOptions::default();
    assert!(matches!(
        rosenstein(&[3.0; 100], &o),
        Err(AnalysisError::Constant)
    ));
    let mut x = henon::henon_x(100);
    x[0] = f64::NAN;
    assert_eq!(
        rosenstein(&x, &o),
        Err(AnalysisError::NonFinite { index: 0 })
    );
    assert!(matches!(
        rosenstein(&henon::henon_x(12), &o),
        Err(AnalysisError::TooShort(_))
    ));
}

#[test]
fn output_does_not_depend_on_the_thread_count() {
    // long enough for several chunks of references and for the parallel tree build
    // (splits of more than 16 384 points)
    let x = lorenz::lorenz_x(40_000, 0.01);
    let o = RosensteinOptions {
        m: 4,
        tau: 10,
        theiler: 100,
        steps: 30,
        eps0: None,
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| rosenstein(&x, &o).unwrap())
    };
    let one = run(1);
    assert!(one.references > 30_000);
    for threads in [2, 3] {
        let r = run(threads);
        assert_eq!(r.count, one.count, "{threads} threads");
        let bits = |s: &[Option<f64>]| s.iter().map(|v| v.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&r.s), bits(&one.s), "{threads} threads");
    }
}
