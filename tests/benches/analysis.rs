//! Benchmarks of the core estimators on Lorenz x (dt = 0.01), single-threaded (a 1-thread
//! rayon pool), against the issue author's TISEAN 3.0.1 timings:
//! - `lyap_k` on 50 000 points, every point a reference, m = 2..6, 4 ε (default range/1000 ..
//!   range/100), 600 steps: TISEAN 51 s. pdamp: `analysis/kantz/50000` (TISEAN definition,
//!   Theiler 0, τ = 17).
//! - `false_nearest` on 200 000 points, m = 1..8: TISEAN 6.5 s. pdamp: `analysis/fnn/200000`
//!   (TISEAN definition and defaults f = 2, t = 0, τ = 17).
//! - `mutual` (no TISEAN timing given): `analysis/mi/{50000,200000}`, 16 bins, D = 20.
//!
//! Run: `cargo bench --bench analysis`.
//!
//! Measured 2026-11-22 (AMD EPYC, 1 thread, machine shared with other jobs; CPU times of the
//! CLI with `taskset -c 0`, the same code paths):
//! - kantz/50000: 2.59 s (criterion median; CLI 2.55 s user, before this tuning 5.57 s):
//!   51 s / 2.6 s ≈ 20× TISEAN. At 200 000 points 38.0 s (before: 84.8 s): ×14.9 for ×4 data,
//!   i.e. ∝ N² — at a fixed ε the neighbour pairs grow as N² (TISEAN's lyap_k alike); the
//!   neighbour search itself is N log N.
//! - fnn/200000: 0.73 s (criterion median; CLI 0.71 s user, before 1.56 s): 6.5 s / 0.73 s
//!   ≈ 9× TISEAN; fnn/50000 0.165 s, ×4.4 for ×4 data (N log N: ×4.5).

use criterion::{criterion_group, criterion_main, Criterion};
use pdamp::analysis::kantz::{kantz, KantzOptions};
use pdamp::analysis::{
    false_nearest_neighbors, mutual_information, FnnOptions, MutualInformationOptions,
};
use pdamp::systems::lorenz::lorenz_x;
use std::time::Duration;

fn single_thread<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool")
        .install(f)
}

fn benches(c: &mut Criterion) {
    let x50 = lorenz_x(50_000, 0.01);
    let x200 = lorenz_x(200_000, 0.01);

    let mut g = c.benchmark_group("analysis/mi");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for (name, x) in [("50000", &x50), ("200000", &x200)] {
        g.bench_function(name, |b| {
            b.iter(|| mutual_information(x, &MutualInformationOptions::default()).unwrap())
        });
    }
    g.finish();

    let mut g = c.benchmark_group("analysis/fnn");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    let fo = FnnOptions {
        m_min: 1,
        m_max: 8,
        tau: 17,
        ..FnnOptions::tisean()
    };
    for (name, x) in [("50000", &x50), ("200000", &x200)] {
        g.bench_function(name, |b| {
            b.iter(|| single_thread(|| false_nearest_neighbors(x, &fo).unwrap()))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("analysis/kantz");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    let ko = KantzOptions {
        m_min: 2,
        m_max: 6,
        tau: 17,
        eps_count: 4,
        steps: 600,
        ..KantzOptions::tisean()
    };
    g.bench_function("50000", |b| {
        b.iter(|| single_thread(|| kantz(&x50, &ko).unwrap()))
    });
    g.finish();
}

criterion_group!(analysis, benches);
criterion_main!(analysis);
