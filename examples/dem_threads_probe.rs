//! Probe: steps per second of one DEM bed at rest with the serial and the parallel paths.
use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::BoxDrive;
use pdamp::scene::dem::DemParams;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(4000);
    let steps: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(2000);
    let mode = args.get(3).cloned().unwrap_or_else(|| "serial".into());
    let drive = BoxDrive {
        primary: None,
        amplitude_m: 0.0,
        frequency_hz: 15.0,
    };
    let mut p = DemParams::thesis_b_softened(1000.0);
    let widen = ((n as f64) / 250.0).sqrt();
    p.r#box[0] *= widen;
    p.r#box[1] *= widen;
    p.count = n;
    let model = pdamp::setup::dem_model(&p).unwrap();
    let mut w = initial_world(&model, drive, 2.8e-6, 0.0).unwrap();
    if mode == "serial" {
        w.parallel_min_grains = usize::MAX;
    }
    settle(&mut w, 0.03);
    w.start_drive();
    let go = |w: &mut pdamp::dem::DemWorld| {
        let t = Instant::now();
        for _ in 0..steps {
            w.step();
        }
        t.elapsed().as_secs_f64()
    };
    let s = if mode == "inpool" {
        rayon::scope(|_| go(&mut w))
    } else {
        go(&mut w)
    };
    println!(
        "{mode} N={n} blocks/cross={:?} pairs={} {:.2} M particle-steps/s",
        w.block_stats(),
        w.pair_count(),
        (n * steps) as f64 / s / 1e6
    );
}
