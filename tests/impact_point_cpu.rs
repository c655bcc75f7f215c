//! CPU time of one analysed impact point and of the no-analysis sweep's points, measured as the
//! thread's own time on a CPU (`/proc/thread-self/schedstat`), so that a loaded machine does not
//! inflate the figure as it inflates criterion's wall time. Ignored by default (a measurement,
//! not a check): `cargo test --release --test impact_point_cpu -- --ignored --nocapture`.

use pdamp::model::RunOptions;
use pdamp::observe::NullObserver;
use pdamp::scene::{Damper, Scene};

/// Nanoseconds this thread has spent on a CPU (Linux), `None` elsewhere.
fn thread_cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
}

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

/// CPU and wall milliseconds per call of `f` over `reps` calls.
fn per_call(reps: usize, mut f: impl FnMut()) -> (f64, f64) {
    f();
    let (c0, t0) = (thread_cpu_ns(), std::time::Instant::now());
    for _ in 0..reps {
        f();
    }
    let wall = t0.elapsed().as_secs_f64() * 1e3 / reps as f64;
    let cpu = match (c0, thread_cpu_ns()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-6 / reps as f64,
        _ => f64::NAN,
    };
    (cpu, wall)
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn analysed_point_cpu_ms() {
    for f in [9.0, 15.0, 22.0] {
        let s = scene(f, 0.8, 2000.0);
        let (cpu, wall) = per_call(30, || {
            pdamp::sweep::run_with_analysis(
                &s,
                &mut NullObserver,
                &RunOptions::summary_only(),
                true,
            )
            .unwrap();
        });
        println!("analysed_point f{f}: {cpu:.2} ms CPU, {wall:.2} ms wall per point");
    }
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn sweep_300x2000_point_cpu_ms() {
    let scenes: Vec<Scene> = (1..=300)
        .map(|i| scene(0.1 * i as f64, 0.0, 2000.0))
        .collect();
    let (cpu, wall) = per_call(3, || {
        for s in &scenes {
            pdamp::sweep::run_scene(s, &mut NullObserver, &RunOptions::summary_only()).unwrap();
        }
    });
    println!("sweep_300x2000 serial: {cpu:.1} ms CPU, {wall:.1} ms wall (one thread)");
}
