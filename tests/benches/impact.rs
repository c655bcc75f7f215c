//! Criterion benchmarks of the event-driven impact model (STYLE §15: `impact/period`).
//!
//! - `impact/period/*`: cost of one forcing period of scene B's one-particle equivalent
//!   (m_p = 0.227 kg, gap 0.0835 m) at resonance, for e = 0 and e = 0.8 (run of 200 periods,
//!   divided by 200 via `Throughput`).
//! - `impact/frf_point/*`: one point of the 300-frequency FRF sweep (2000 periods) at a low,
//!   resonant and high frequency.
//! - `primary/period`: the primary alone.
//! - `impact/sweep_300x2000/no_analysis`: the whole 300-frequency, 2000-period sweep.
//! - `impact/analysed_point/*`: one 2000-period point with the full analysis chain.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use pdamp::model::RunOptions;
use pdamp::observe::NullObserver;
use pdamp::scene::{Damper, Scene};

fn scene(f: f64, e: f64, periods: f64) -> Scene {
    let mut s = Scene::thesis_b_impact();
    s.excitation.frequency = f;
    if let Damper::Impact(p) = &mut s.damper {
        p.restitution = e;
    }
    s.run.duration = None;
    s.run.periods = Some(periods);
    s
}

fn run(s: &Scene) -> f64 {
    pdamp::sweep::run_scene(s, &mut NullObserver, &RunOptions::summary_only())
        .unwrap()
        .amplitude_m
}

fn period(c: &mut Criterion) {
    let mut g = c.benchmark_group("impact/period");
    g.throughput(Throughput::Elements(200));
    for e in [0.0, 0.8] {
        let s = scene(15.0, e, 200.0);
        g.bench_with_input(BenchmarkId::from_parameter(format!("e{e}")), &s, |b, s| {
            b.iter(|| run(s))
        });
    }
    g.finish();
    let mut g = c.benchmark_group("primary/period");
    g.throughput(Throughput::Elements(200));
    let mut s = scene(15.0, 0.0, 200.0);
    s.damper = Damper::None;
    g.bench_function("f15", |b| b.iter(|| run(&s)));
    g.finish();
}

fn frf_point(c: &mut Criterion) {
    let mut g = c.benchmark_group("impact/frf_point");
    g.sample_size(10);
    for f in [0.5, 15.0, 30.0] {
        let s = scene(f, 0.8, 2000.0);
        g.bench_with_input(BenchmarkId::from_parameter(format!("f{f}")), &s, |b, s| {
            b.iter(|| run(s))
        });
    }
    g.finish();
}

/// The issue-13 sweep: 300 frequencies × 2000 forcing periods of the one-particle model
/// (e = 0, 0.1–30 Hz), no analysis, the points spread over rayon's threads as `pdamp sweep`
/// does (target: ≤ 1 s on 2 cores).
fn frf_sweep(c: &mut Criterion) {
    use rayon::prelude::*;
    let mut g = c.benchmark_group("impact/sweep_300x2000");
    g.sample_size(10);
    let scenes: Vec<Scene> = (1..=300)
        .map(|i| scene(0.1 * i as f64, 0.0, 2000.0))
        .collect();
    g.bench_function("no_analysis", |b| {
        b.iter(|| scenes.par_iter().map(run).sum::<f64>())
    });
    g.finish();
}

/// One point with the full analysis chain (the model exponent, the exact section, the
/// steady-state series' analysis), 2000 periods (target: ≤ 20 ms per point).
fn analysed_point(c: &mut Criterion) {
    let mut g = c.benchmark_group("impact/analysed_point");
    g.sample_size(10);
    for f in [9.0, 15.0, 22.0] {
        let s = scene(f, 0.8, 2000.0);
        g.bench_with_input(BenchmarkId::from_parameter(format!("f{f}")), &s, |b, s| {
            b.iter(|| {
                pdamp::sweep::run_with_analysis(
                    s,
                    &mut NullObserver,
                    &RunOptions::summary_only(),
                    true,
                )
                .unwrap()
                .amplitude_m
            })
        });
    }
    g.finish();
}

criterion_group!(benches, period, frf_point, frf_sweep, analysed_point);
criterion_main!(benches);
