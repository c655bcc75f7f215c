//! Threads inside one DEM run (issue 12): the pair pass and the per-grain passes run on the
//! rayon pool in fixed chunks, each grain's forces gathered in pair order, so positions,
//! velocities, spins, the ledger and the box force are bit-identical on 1, 2 and 3 threads —
//! and equal to the one-thread path that scatters the pair forces directly.

use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::stability::{choose_dt, DEFAULT_DT_FRACTION};
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::{DemParams, TangentialKind};

fn drive() -> BoxDrive {
    BoxDrive {
        primary: None,
        amplitude_m: 4.5e-3,
        frequency_hz: 15.0,
    }
}

/// Bits of everything a step produces.
fn fingerprint(w: &DemWorld) -> Vec<u64> {
    let mut v: Vec<u64> = Vec::new();
    for a in [&w.pos, &w.vel, &w.omega, &w.force, &w.torque] {
        v.extend(a.iter().flatten().map(|x| x.to_bits()));
    }
    let l = w.ledger;
    v.extend(
        [
            l.collision_j,
            l.friction_j,
            l.base_work_j,
            w.grain_force_n,
            w.box_z,
        ]
        .map(f64::to_bits),
    );
    v
}

/// `n` grains of scene B (softened) dropped on the shaking floor, `steps` steps on a pool of
/// `threads` threads; `parallel`: the chunked parallel path even for small beds.
fn run(
    n: usize,
    tangential: TangentialKind,
    threads: usize,
    parallel: bool,
    steps: usize,
) -> Vec<u64> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut p = DemParams::thesis_b_softened(1000.0);
        let widen = ((n as f64) / 250.0).sqrt();
        p.r#box[0] *= widen;
        p.r#box[1] *= widen;
        p.count = n;
        p.tangential = tangential;
        let model = pdamp::setup::dem_model(&p).unwrap();
        let (dt, _) = choose_dt(&model, &drive(), None, DEFAULT_DT_FRACTION).unwrap();
        let mut w = initial_world(&model, drive(), dt, 0.0).unwrap();
        w.parallel_min_grains = if parallel { 0 } else { usize::MAX };
        // the lattice falls onto the floor (settling drag on), then the floor shakes
        settle(&mut w, 0.03);
        w.start_drive();
        for _ in 0..steps {
            w.step();
        }
        assert!(
            w.pair_count() > n,
            "a bed in contact: {} pairs",
            w.pair_count()
        );
        fingerprint(&w)
    })
}

#[test]
fn one_two_and_three_threads_give_bit_identical_runs() {
    for tangential in [TangentialKind::CoulombViscous, TangentialKind::Mindlin] {
        let serial = run(2500, tangential, 1, false, 1500);
        for threads in [1, 2, 3] {
            assert!(
                run(2500, tangential, threads, true, 1500) == serial,
                "{tangential:?}: {threads} threads differ from the one-thread path"
            );
        }
    }
}
