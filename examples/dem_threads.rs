//! Steps per second of one DEM bed at rest on one thread, on the world's own team of threads
//! and on the rayon pool (issue 12's thread speed-up, without the CLI's observers).
//!
//! ```sh
//! RAYON_NUM_THREADS=2 cargo run --release --example dem_threads -- 4000 3000 team
//! #                                                             N     steps mode (serial | team | rayon) [mindlin] [settle s]
//! ```
//!
//! The bed: scene B's grains softened 1000× (E = 2.03e8 Pa), dt = 2.8e-6 s, the box footprint
//! widened with √(N/250), dropped from the lattice and settled for 0.03 s (the fifth argument:
//! another time; 0.2 s gives the dense bed of `bench/dem_vs_liggghts.sh`); then `steps` steps
//! of the box at rest are timed. `team` and `rayon` use `RAYON_NUM_THREADS` threads; `mindlin`
//! swaps the thesis's Coulomb law for the Mindlin spring (`coulomb` keeps the thesis's law).
//! It prints the candidate pairs and the contacts per grain of the timed bed.
use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::BoxDrive;
use pdamp::scene::dem::DemParams;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg =
        |k: usize, default: usize| args.get(k).and_then(|s| s.parse().ok()).unwrap_or(default);
    let (n, steps) = (arg(1, 4000), arg(2, 3000));
    let mode = args.get(3).cloned().unwrap_or_else(|| "team".into());
    let drive = BoxDrive {
        primary: None,
        amplitude_m: 0.0,
        frequency_hz: 15.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    };
    let mut p = DemParams::thesis_b_softened(1000.0);
    let widen = ((n as f64) / 250.0).sqrt();
    p.r#box[0] *= widen;
    p.r#box[1] *= widen;
    p.count = n;
    if args.get(4).map(String::as_str) == Some("mindlin") {
        p.tangential = pdamp::scene::dem::TangentialKind::Mindlin;
    }
    let model = pdamp::setup::dem_model(&p).expect("the softened scene B");
    let mut w = initial_world(&model, drive, 2.8e-6, 0.0).expect("a lattice bed");
    if mode == "serial" {
        w.parallel_min_grains = usize::MAX;
    }
    let settle_s: f64 = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(0.03);
    let timed = |w: &mut pdamp::dem::DemWorld| {
        settle(w, settle_s);
        w.start_drive();
        let t = Instant::now();
        for _ in 0..steps {
            w.step();
        }
        t.elapsed().as_secs_f64()
    };
    // `rayon`: stepped from inside the pool, so the phases run on the pool's workers
    let s = if mode == "rayon" {
        rayon::scope(|_| timed(&mut w))
    } else {
        timed(&mut w)
    };
    let (blocks, cross) = w.block_stats();
    let contacts = contacts(&w.grain_state());
    println!(
        "{mode}: N = {n}, {} threads, {blocks} blocks, {cross} of {} pairs across blocks, \
         {:.2} candidates and {:.2} contacts per grain: {:.2} M particle-steps/s",
        rayon::current_num_threads(),
        w.pair_count(),
        2.0 * w.pair_count() as f64 / n as f64,
        2.0 * contacts as f64 / n as f64,
        (n * steps) as f64 / s / 1e6
    );
}

/// Grain–grain pairs that overlap (sorted along x, so that only close x are compared).
fn contacts(g: &pdamp::observe::GrainState) -> usize {
    let mut order: Vec<usize> = (0..g.pos.len()).collect();
    order.sort_by(|&a, &b| g.pos[a][0].total_cmp(&g.pos[b][0]));
    let r_max = g.radius.iter().cloned().fold(0.0, f64::max);
    let mut count = 0;
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if g.pos[b][0] - g.pos[a][0] > 2.0 * r_max {
                break;
            }
            let d: f64 = (0..3).map(|c| (g.pos[a][c] - g.pos[b][c]).powi(2)).sum();
            let cut = g.radius[a] + g.radius[b];
            count += (d < cut * cut) as usize;
        }
    }
    count
}
