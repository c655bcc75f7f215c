//! IAAFT / FT / shuffle surrogates (Schreiber & Schmitz 1996; TISEAN `surrogates`) and the
//! surrogate test by rank (Theiler et al. 1992) with the nonlinear prediction error and the
//! time-reversal asymmetry, against independent references: exact permutation, periodogram
//! and autocorrelation of an AR(1) process (φ^k), thread-count determinism, a negative
//! control (linear Gaussian AR(1) rejected at about the nominal rate) and positive controls
//! (Lorenz x, Hénon x, Lorenz x with 5 % and 10 % observational noise rejected).

use pdamp::analysis::prediction_error::{prediction_error, PredictionErrorOptions};
use pdamp::analysis::surrogate_test::{surrogate_test, SurrogateTestOptions, Tail};
use pdamp::analysis::surrogates::{
    end_to_end_mismatch, end_to_end_segment, periodogram, surrogate, surrogates, SurrogateMethod,
    SurrogateOptions,
};
use pdamp::analysis::time_reversal::time_reversal_asymmetry;
use pdamp::error::AnalysisError;
use pdamp::systems::{henon, lorenz, roessler};

mod common;
use common::with_noise;

/// Gaussian AR(1) `x_n = φ x_{n−1} + ξ_n` (unit innovations) after 1000 transient steps.
fn ar1(phi: f64, n: usize, seed: u64) -> Vec<f64> {
    common::ar1(phi, n, 1000, seed)
}

fn sorted(v: &[f64]) -> Vec<f64> {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s
}

/// Sample autocorrelation at lag k, written independently of the library (mean removed,
/// biased 1/N estimator).
fn acf(x: &[f64], k: usize) -> f64 {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let c0: f64 = x.iter().map(|v| (v - m) * (v - m)).sum();
    let ck: f64 = x.iter().zip(&x[k..]).map(|(a, b)| (a - m) * (b - m)).sum();
    ck / c0
}

/// Periodogram averaged over blocks of `w` bins (DC excluded).
fn smoothed(p: &[f64], w: usize) -> Vec<f64> {
    p[1..]
        .chunks(w)
        .filter(|c| c.len() == w)
        .map(|c| c.iter().sum::<f64>() / w as f64)
        .collect()
}

/// Lorenz x from the shared series file (dt = 0.01, 10 000 samples; its header names the
/// generator), so the test also covers the file the CLI demos use.
fn lorenz_file() -> Vec<f64> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/series/lorenz_x_dt0.01_n10000.txt"
    );
    pdamp::io::read_series(path, &Default::default()).unwrap()
}

#[test]
fn iaaft_is_an_exact_permutation_and_keeps_the_periodogram() {
    let x = lorenz::lorenz_x(4096, 0.05);
    let o = SurrogateOptions {
        seed: 11,
        ..Default::default()
    };
    let s = surrogate(&x, &o, 0).unwrap();
    // exact permutation: identical sorted values, bit for bit
    assert_eq!(sorted(&s.values), sorted(&x));
    assert!(s.converged, "{} iterations", s.iterations);
    let (px, ps) = (periodogram(&x), periodogram(&s.values));
    // total power: identical up to rounding (same values, same variance by Parseval)
    let (tx, ts): (f64, f64) = (px.iter().sum(), ps.iter().sum());
    assert!((tx - ts).abs() < 1e-9 * tx);
    // Periodogram, smoothed over blocks of 16 bins: the exact-amplitude stage of a converged
    // IAAFT surrogate deviates from the data's by the final discrepancy; Schreiber & Schmitz
    // (2000, §4.3) report errors of a few per cent. Measured here (seed 11, 44 iterations):
    // 2e-4 of the total power; the bound 5e-3 leaves a margin of 25 for other seeds and
    // lengths, while a plain shuffle (flat spectrum) is off by more than 0.5.
    let (sx, ss) = (smoothed(&px, 16), smoothed(&ps, 16));
    let weighted: f64 =
        sx.iter().zip(&ss).map(|(a, b)| (a - b).abs()).sum::<f64>() / sx.iter().sum::<f64>();
    eprintln!(
        "IAAFT Lorenz: {} iterations, discrepancy {:.3e}, weighted periodogram error {weighted:.4}",
        s.iterations, s.discrepancy
    );
    assert!(weighted < 5e-3, "{weighted}");
    let shuffle = surrogate(
        &x,
        &SurrogateOptions {
            method: SurrogateMethod::Shuffle,
            ..o
        },
        0,
    )
    .unwrap();
    let sh = smoothed(&periodogram(&shuffle.values), 16);
    let w_shuffle: f64 =
        sx.iter().zip(&sh).map(|(a, b)| (a - b).abs()).sum::<f64>() / sx.iter().sum::<f64>();
    assert!(w_shuffle > 0.5, "{w_shuffle}");
    assert_eq!(sorted(&shuffle.values), sorted(&x));
}

#[test]
fn exact_spectrum_stage_and_ft_surrogates_keep_the_periodogram_exactly() {
    let x = lorenz::lorenz_x(3000, 0.05);
    let px = periodogram(&x);
    let pmax = px.iter().cloned().fold(0.0, f64::max);
    for (method, exact_spectrum) in [
        (SurrogateMethod::Iaaft, true),
        (SurrogateMethod::PhaseRandomized, false),
    ] {
        let o = SurrogateOptions {
            method,
            exact_spectrum,
            seed: 5,
            ..Default::default()
        };
        let s = surrogate(&x, &o, 1).unwrap();
        // amplitudes imposed exactly: only FFT rounding (~1e-13 of the largest bin)
        for (a, b) in px.iter().zip(periodogram(&s.values)) {
            assert!((a - b).abs() < 1e-10 * pmax, "{method:?}: {a} {b}");
        }
    }
}

#[test]
fn iaaft_preserves_the_autocorrelation_of_an_ar1_process() {
    // AR(1) with φ = 0.8: ρ(k) = φ^k. Standard error of a sample ACF of length N:
    // ≈ sqrt((1 + φ²)/(1 − φ²)/N) = 0.017 for N = 16384 (Bartlett); tolerance 0.06 ≈ 3.5 σ.
    // Against the data's own sample ACF the surrogate must agree much better (IAAFT keeps
    // the sample periodogram, i.e. the circular sample ACF): 0.02.
    let phi: f64 = 0.8;
    let x = ar1(phi, 16384, 3);
    let s = surrogate(
        &x,
        &SurrogateOptions {
            seed: 9,
            ..Default::default()
        },
        0,
    )
    .unwrap();
    for k in 1..=5 {
        let (rs, rx, want) = (acf(&s.values, k), acf(&x, k), phi.powi(k as i32));
        eprintln!("AR(1) lag {k}: surrogate {rs:.4} data {rx:.4} phi^k {want:.4}");
        assert!((rs - want).abs() < 0.06, "lag {k}: {rs} vs {want}");
        assert!((rs - rx).abs() < 0.02, "lag {k}: {rs} vs data {rx}");
    }
}

#[test]
fn surrogates_do_not_depend_on_thread_count_or_order() {
    let x = henon::henon_x(2000);
    let o = SurrogateOptions {
        seed: 42,
        ..Default::default()
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| surrogates(&x, 6, &o).unwrap())
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    // surrogate k is the same whether made alone or in a batch
    assert_eq!(one[4], surrogate(&x, &o, 4).unwrap());
    // and a different seed gives different surrogates
    let other = surrogate(&x, &SurrogateOptions { seed: 43, ..o }, 4).unwrap();
    assert_ne!(one[4].values, other.values);
}

/// Prediction-error statistic for Lorenz x at dt = 0.01: delay and horizon of 10 samples
/// (0.1 time units, below the first MI minimum ≈ 16), m = 3, Theiler window 50 samples.
fn lorenz_statistic() -> PredictionErrorOptions {
    PredictionErrorOptions {
        dim: 3,
        delay: 10,
        horizon: 10,
        epsilon: 0.1,
        min_neighbors: 5,
        epsilon_factor: 1.2,
        theiler: 50,
    }
}

fn test_with(x: &[f64], p: PredictionErrorOptions, n: usize, seed: u64) -> (f64, usize, f64) {
    let stat = move |s: &[f64]| -> Result<f64, AnalysisError> { prediction_error(s, &p) };
    let r = surrogate_test(
        x,
        &stat,
        &SurrogateTestOptions {
            n_surrogates: n,
            surrogate: SurrogateOptions {
                seed,
                ..Default::default()
            },
            tail: Tail::Lower,
        },
    )
    .unwrap();
    (r.p_value, r.rank, r.significance_sigma)
}

#[test]
fn linear_gaussian_ar1_is_not_rejected_more_often_than_nominal() {
    // Negative control: under the IAAFT null hypothesis (here exactly true) the one-sided
    // rank test with n = 19 rejects with probability 1/20. Over 20 independent series the
    // number of rejections is Binomial(20, 0.05): mean 1, P(≥ 5) = 0.0026, so ≤ 4 is the
    // bound; a test that always rejects (e.g. surrogates whiter than the data) gets ~20.
    let p = PredictionErrorOptions {
        dim: 3,
        delay: 1,
        horizon: 1,
        theiler: 10,
        ..Default::default()
    };
    let mut rejections = 0;
    let mut ps = Vec::new();
    for seed in 0..20 {
        let x = ar1(0.7, 2000, 100 + seed);
        let (pv, _, _) = test_with(&x, p, 19, seed);
        ps.push(pv);
        if pv <= 0.05 {
            rejections += 1;
        }
    }
    eprintln!("AR(1) negative control: {rejections}/20 rejected; p = {ps:?}");
    assert!(rejections <= 4, "{rejections}/20 rejections: {ps:?}");
    // nor far too conservative: under the null hypothesis p is uniform on {1/20, …, 1},
    // mean 0.525, standard error of a mean of 20 values 0.065 (measured 0.53)
    let mean_p = ps.iter().sum::<f64>() / ps.len() as f64;
    assert!((0.3..=0.75).contains(&mean_p), "mean p {mean_p}");
    // White noise (φ = 0): 10 series, Binomial(10, 0.05), P(≥ 4) = 0.001.
    let white: Vec<f64> = (0..10)
        .map(|seed| test_with(&ar1(0.0, 2000, 500 + seed), p, 19, seed).0)
        .collect();
    let rejected = white.iter().filter(|&&pv| pv <= 0.05).count();
    eprintln!("white-noise negative control: {rejected}/10 rejected; p = {white:?}");
    assert!(rejected <= 3, "{white:?}");
}

#[test]
fn chaos_is_rejected_clean_and_with_observational_noise() {
    // Positive controls: the data's prediction error must be the smallest of the n + 1
    // values, p = 1/(n+1) — the smallest the test can give (0.05 with 19, 0.025 with 39).
    let lorenz = lorenz_file();
    let x = &lorenz[..5000];
    for (name, series, n) in [
        ("Lorenz x", x.to_vec(), 19),
        ("Lorenz x + 5 % noise", with_noise(x, 0.05, 1), 19),
        ("Lorenz x + 10 % noise", with_noise(x, 0.10, 2), 39),
    ] {
        let (pv, rank, sig) = test_with(&series, lorenz_statistic(), n, 7);
        eprintln!("{name}: p = {pv:.4}, rank {rank}, {sig:.1} sigma");
        assert_eq!(rank, 1, "{name}");
        assert!(
            (pv - 1.0 / (n as f64 + 1.0)).abs() < 1e-12,
            "{name}: p = {pv}"
        );
    }
    // Rössler x at dt = 0.1 (mean period 5.9 time units ≈ 59 samples; λ₁ = 0.071 is small,
    // so the horizon must be a sizeable part of a period): τ = 8, h = 15, w = 100.
    let r = roessler::roessler_x(5000, 0.1);
    let pr = PredictionErrorOptions {
        dim: 3,
        delay: 8,
        horizon: 15,
        theiler: 100,
        ..lorenz_statistic()
    };
    for (name, series) in [
        ("Roessler x", r.clone()),
        ("Roessler x + 10 % noise", with_noise(&r, 0.10, 4)),
    ] {
        let (pv, rank, sig) = test_with(&series, pr, 19, 9);
        eprintln!("{name}: p = {pv:.4}, rank {rank}, {sig:.1} sigma");
        assert_eq!(rank, 1, "{name}");
    }
    let h = henon::henon_x(3000);
    let p = PredictionErrorOptions {
        dim: 2,
        ..Default::default()
    };
    for (name, series) in [
        ("Henon x", h.clone()),
        ("Henon x + 10 % noise", with_noise(&h, 0.10, 3)),
    ] {
        let (pv, rank, sig) = test_with(&series, p, 19, 8);
        eprintln!("{name}: p = {pv:.4}, rank {rank}, {sig:.1} sigma");
        assert_eq!(rank, 1, "{name}");
        assert!((pv - 0.05).abs() < 1e-12);
    }
}

#[test]
fn time_reversal_asymmetry_rejects_henon_two_sided_but_not_ar1() {
    let q = |s: &[f64]| time_reversal_asymmetry(s, 1);
    let o = SurrogateTestOptions {
        n_surrogates: 39,
        tail: Tail::TwoSided,
        ..Default::default()
    };
    let r = surrogate_test(&henon::henon_x(3000), &q, &o).unwrap();
    eprintln!(
        "Henon Q(1) = {:.3}, surrogates {:.3} ± {:.3}, p = {}",
        r.data_value, r.surrogate_mean, r.surrogate_sd, r.p_value
    );
    // two-sided with 39 surrogates: smallest p = 2/40 = 0.05
    assert!((r.p_value - 0.05).abs() < 1e-12 && r.p_min == r.p_value);
    assert!(r.significance_sigma > 5.0);
    let r = surrogate_test(&ar1(0.7, 3000, 1), &q, &o).unwrap();
    eprintln!("AR(1) Q(1) = {:.3}, p = {}", r.data_value, r.p_value);
    assert!(r.p_value > 0.05);
}

#[test]
fn end_to_end_reduces_the_mismatch_of_lorenz_x() {
    let x = lorenz::lorenz_x(5000, 0.01);
    let seg = end_to_end_segment(&x, 4500).unwrap();
    let s = &x[seg.start..seg.start + seg.len];
    assert_eq!(end_to_end_mismatch(s), seg.mismatch);
    eprintln!(
        "end-to-end: [{}, {}) mismatch {:.2e} (whole series {:.2e})",
        seg.start,
        seg.start + seg.len,
        seg.mismatch,
        seg.mismatch_whole
    );
    // brute force over a coarse subset must not find anything better
    for len in (4500..=5000).step_by(50) {
        for a in (0..=5000 - len).step_by(25) {
            assert!(end_to_end_mismatch(&x[a..a + len]) >= seg.mismatch);
        }
    }
    assert!(seg.mismatch < 0.01 * seg.mismatch_whole.max(1e-12) || seg.mismatch < 1e-6);
}
