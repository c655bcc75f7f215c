//! Benchmarks of the spectrum (FFT + line picking) and of the whole `analyze_series` chain.
//! - `spectrum/fft/{65536,1048576}`: Hann-windowed power spectrum + [`spectral_lines`] of a
//!   noisy two-tone signal (2^16 and 2^20 samples).
//! - `analysis/analyze/{10000,100000}`: `analyze_series` on Lorenz x (dt = 0.01) — the cost a
//!   sweep pays per point (target: well under a second for 1e5 samples).
//!
//! Run: `cargo bench --bench spectrum`.

use criterion::{criterion_group, criterion_main, Criterion};
use pdamp::analysis::analyze::{analyze_series, AnalyzeOptions};
use pdamp::analysis::spectrum::{power_spectrum, spectral_lines, LineOptions, SpectrumOptions};
use pdamp::systems::lorenz::lorenz_x;
use std::time::Duration;

fn two_tone(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = i as f64;
            (0.0123 * t).sin()
                + 0.3 * (0.0123 * 2f64.sqrt() * t).sin()
                + 1e-3 * (t * t * 0.618).sin()
        })
        .collect()
}

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("spectrum/fft");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for n in [1usize << 16, 1 << 20] {
        let x = two_tone(n);
        g.bench_function(n.to_string(), |b| {
            b.iter(|| {
                let s = power_spectrum(&x, &SpectrumOptions::default()).unwrap();
                spectral_lines(&s, &LineOptions::default())
            })
        });
    }
    g.finish();

    let mut g = c.benchmark_group("analysis/analyze");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for n in [10_000usize, 100_000] {
        let x = lorenz_x(n, 0.01);
        let opts = AnalyzeOptions {
            dt_s: Some(0.01),
            ..Default::default()
        };
        g.bench_function(n.to_string(), |b| {
            b.iter(|| analyze_series(&x, &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(group, benches);
criterion_main!(group);
