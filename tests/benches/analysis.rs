//! Benchmarks of the core estimators on Lorenz x (dt = 0.01, `lorenz_x`, the series of
//! `examples/gen_series.rs`), single-threaded (a 1-thread rayon pool). Each benchmark does the
//! work of exactly one CLI command; the side-by-side comparison with TISEAN 3.0.1 (same
//! commands, same machine, same run, outputs checked equal) is `bench/vs_tisean.sh`, and its
//! measured table is in `bench/README.md`.
//! - `analysis/kantz/50000`: `pdamp lyap-k lorenz_x_n50000.dat --tisean -m2 -M6 -d17
//!   -r0.0755099 -R0.755099 -#4 -s600 -t100`, i.e. TISEAN's `lyap_k` with the same options
//!   (ε = 0.002…0.02 of the range 37.755, Theiler window 100).
//! - `analysis/fnn/{50000,200000}`: `pdamp fnn lorenz_x_n<N>.dat --tisean -m1 -M1,8 -d17 -f10
//!   -t100`, i.e. TISEAN's `false_nearest` with the same options.
//! - `analysis/mi/{50000,200000}`: `pdamp mutual lorenz_x_n<N>.dat` (16 bins, D = 20).
//!
//! The benches use `lorenz_x(N, 0.01)` directly; the files hold the same values to 13 digits.
//!
//! Run: `cargo bench --bench analysis`. Figures (1 thread, CPU seconds of the CLI) are in
//! `bench/README.md`; criterion's medians of these benches exclude reading the file.

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
    // pdamp fnn --tisean -m1 -M1,8 -d17 -f10 -t100
    let fo = FnnOptions {
        m_min: 1,
        m_max: 8,
        tau: 17,
        ratio: 10.0,
        theiler: Some(100),
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
    // pdamp lyap-k --tisean -m2 -M6 -d17 -r0.0755099 -R0.755099 -#4 -s600 -t100
    let ko = KantzOptions {
        m_min: 2,
        m_max: 6,
        tau: 17,
        eps_min: Some(0.0755099),
        eps_max: Some(0.755099),
        eps_count: 4,
        steps: 600,
        theiler: Some(100),
        ..KantzOptions::tisean()
    };
    g.bench_function("50000", |b| {
        b.iter(|| single_thread(|| kantz(&x50, &ko).unwrap()))
    });
    g.finish();
}

criterion_group!(analysis, benches);
criterion_main!(analysis);
