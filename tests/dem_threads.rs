//! Threads inside one DEM run (issue 12): the force pass runs in fixed grain blocks and
//! chunks (`pdamp::dem::blocks`), on the rayon pool or on the world's own team of threads, so
//! positions, velocities, spins, the ledger and the box force are bit-identical on 1, 2 and 3
//! threads of either kind — and equal to the one-thread path.

use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::stability::{choose_dt, DEFAULT_DT_FRACTION};
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::scene::dem::{DemParams, TangentialKind};

fn drive() -> BoxDrive {
    BoxDrive {
        primary: None,
        amplitude_m: 4.5e-3,
        frequency_hz: 15.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
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

/// Who steps the world.
#[derive(Debug, Clone, Copy)]
enum Exec {
    /// One thread (the parallel paths switched off).
    Serial,
    /// The phases on a rayon pool of this many threads.
    Rayon(usize),
    /// The phases on the world's own team of this many threads.
    Team(usize),
}

/// `n` grains of scene B (softened) dropped on the shaking floor, `steps` steps run by `exec`
/// (the drift inside the force pass if `fuse`); the fingerprint and the driven run's rebuilds.
fn run_with(
    n: usize,
    tangential: TangentialKind,
    exec: Exec,
    steps: usize,
    fuse: bool,
) -> (Vec<u64>, u64) {
    let threads = match exec {
        Exec::Rayon(t) => t,
        _ => 1,
    };
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
        w.fuse_drift = fuse;
        match exec {
            Exec::Serial => w.parallel_min_grains = usize::MAX,
            Exec::Rayon(_) => w.parallel_min_grains = 0,
            Exec::Team(t) => {
                w.parallel_min_grains = 0;
                w.team_threads = Some(t);
            }
        }
        // the lattice falls onto the floor (settling drag on), then the floor shakes
        settle(&mut w, 0.02);
        w.start_drive();
        let builds = w.neighbor_builds();
        for _ in 0..steps {
            w.step();
        }
        assert!(
            w.pair_count() > n,
            "a bed in contact: {} pairs",
            w.pair_count()
        );
        let (blocks, cross) = w.block_stats();
        assert!(
            blocks >= 2 && cross > 0,
            "{blocks} blocks, {cross} cross pairs"
        );
        (fingerprint(&w), w.neighbor_builds() - builds)
    })
}

/// [`run_with`] with the default drift (inside the force pass where the law allows it).
fn run(n: usize, tangential: TangentialKind, exec: Exec, steps: usize) -> Vec<u64> {
    run_with(n, tangential, exec, steps, true).0
}

/// The drift done block by block inside the force pass (laws without springs), with its pass
/// thrown away and redone when a rebuild turns out due, gives the bits of drifting every grain
/// first, on one thread and on a team of two.
#[test]
fn drift_inside_the_force_pass_gives_the_bits_of_drifting_first() {
    for exec in [Exec::Serial, Exec::Team(2)] {
        let (fused, builds) = run_with(3500, TangentialKind::CoulombViscous, exec, 1500, true);
        let (first, builds_first) =
            run_with(3500, TangentialKind::CoulombViscous, exec, 1500, false);
        assert!(
            builds >= 2,
            "{exec:?}: {builds} rebuilds (the redo path must run)"
        );
        assert_eq!(builds, builds_first);
        assert!(fused == first, "{exec:?}: the fused drift changes the run");
    }
}

#[test]
fn one_two_and_three_threads_give_bit_identical_runs() {
    // 3500 grains: two blocks; 6000: four blocks (uneven shares on three threads)
    for (n, tangential) in [
        (3500, TangentialKind::CoulombViscous),
        (3500, TangentialKind::Mindlin),
        (6000, TangentialKind::Mindlin),
    ] {
        let serial = run(n, tangential, Exec::Serial, 1000);
        for exec in [
            Exec::Rayon(1),
            Exec::Rayon(2),
            Exec::Rayon(3),
            Exec::Team(1),
            Exec::Team(2),
            Exec::Team(3),
        ] {
            assert!(
                run(n, tangential, exec, 1000) == serial,
                "{n} grains, {tangential:?}: {exec:?} differs from the one-thread path"
            );
        }
    }
}

/// The grains stored along the space-filling curve (re-sorted at every neighbour rebuild) and
/// the same run kept in grain-id order give the same trajectory grain by grain (up to the
/// round-off of summing the contacts in another order); snapshots come out in grain-id order.
#[test]
fn curve_sorted_storage_keeps_grain_ids() {
    let run = |sorted: bool| {
        let mut p = DemParams::thesis_b_softened(1000.0);
        let widen = (2500.0f64 / 250.0).sqrt();
        p.r#box[0] *= widen;
        p.r#box[1] *= widen;
        p.count = 2500;
        p.tangential = TangentialKind::Mindlin;
        let model = pdamp::setup::dem_model(&p).unwrap();
        let (dt, _) = choose_dt(&model, &drive(), None, DEFAULT_DT_FRACTION).unwrap();
        let mut w = initial_world(&model, drive(), dt, 0.0).unwrap();
        w.sort_min_grains = if sorted { 0 } else { usize::MAX };
        settle(&mut w, 0.02);
        w.start_drive();
        for _ in 0..300 {
            w.step();
        }
        let builds = w.neighbor_builds();
        let ids = w.grain_ids().to_vec();
        let g = w.grain_state();
        (
            g.pos.to_vec(),
            g.vel.to_vec(),
            g.radius.to_vec(),
            ids,
            builds,
        )
    };
    let (pa, va, ra, ida, ba) = run(true);
    let (pb, vb, rb, idb, bb) = run(false);
    assert!(ba > 2 && ba == bb, "rebuilds {ba} {bb}");
    // (the unsorted run was sorted once, at its first build inside `initial_world`)
    assert!(
        ida.iter().zip(&idb).filter(|(a, b)| a != b).count() > 1000,
        "the sorted run keeps re-sorting its grains"
    );
    assert_eq!(ra, rb);
    let (mut dp, mut dv) = (0.0f64, 0.0f64);
    for i in 0..pa.len() {
        for d in 0..3 {
            dp = dp.max((pa[i][d] - pb[i][d]).abs());
            dv = dv.max((va[i][d] - vb[i][d]).abs());
        }
    }
    assert!(
        dp < 1e-9 && dv < 1e-6,
        "by grain id: |Δx| {dp:e} m, |Δv| {dv:e} m/s"
    );
}

/// The contact loops compiled for every instruction set this processor has (baseline SSE2 and
/// AVX2), monodisperse (one radius and coefficient set read once) and polydisperse (per-pair
/// coefficients gathered), give bit-identical runs, with every tangential law.
#[test]
fn every_instruction_set_gives_the_same_run() {
    use pdamp::scene::dem::ContactKind;
    use pdamp::simd::Simd;
    let run = |contact: ContactKind, tangential: TangentialKind, poly: bool, simd: Simd| {
        let mut p = DemParams::thesis_b_softened(1000.0);
        p.count = 250;
        p.contact = contact;
        p.tangential = tangential;
        if contact == ContactKind::Linear {
            p.restitution = Some(0.9);
            p.yield_strength = Some(1.0e9);
        }
        if poly {
            p.radius = None;
            p.radius_min = Some(2.7e-3);
            p.radius_max = Some(3.0e-3);
        }
        let model = pdamp::setup::dem_model(&p).unwrap();
        let (dt, _) = choose_dt(&model, &drive(), None, DEFAULT_DT_FRACTION).unwrap();
        let mut w = initial_world(&model, drive(), dt, 0.0).unwrap();
        w.simd = simd;
        settle(&mut w, 0.03);
        w.start_drive();
        for _ in 0..1500 {
            w.step();
        }
        assert!(w.pair_count() > 250, "a bed in contact");
        fingerprint(&w)
    };
    let sets = Simd::available();
    for (contact, tangential) in [
        (ContactKind::HertzKk, TangentialKind::CoulombViscous),
        (ContactKind::HertzKk, TangentialKind::Mindlin),
        (ContactKind::Linear, TangentialKind::LinearSpring),
        (ContactKind::Linear, TangentialKind::CoulombViscous),
    ] {
        for poly in [false, true] {
            let base = run(contact, tangential, poly, Simd::Baseline);
            for &s in &sets[1..] {
                assert!(
                    run(contact, tangential, poly, s) == base,
                    "{contact:?}/{tangential:?}, polydisperse {poly}: {s:?} differs from the \
                     baseline build"
                );
            }
        }
    }
}

/// The contact counts a run reports (`DemWorld::contact_counts`, summary.json's
/// `*_per_grain`) are those of a brute-force count over every pair of grains and every wall
/// of the settled bed.
#[test]
fn contact_counts_match_a_brute_force_count() {
    let mut p = DemParams::thesis_b_softened(1000.0);
    p.count = 400;
    let model = pdamp::setup::dem_model(&p).unwrap();
    let (dt, _) = choose_dt(&model, &drive(), None, DEFAULT_DT_FRACTION).unwrap();
    let mut w = initial_world(&model, drive(), dt, 0.0).unwrap();
    settle(&mut w, 0.2);
    let c = w.contact_counts();
    let n = w.len();
    let (mut pairs, mut walls) = (0, 0);
    for i in 0..n {
        for j in i + 1..n {
            let d2: f64 = (0..3).map(|k| (w.pos[i][k] - w.pos[j][k]).powi(2)).sum();
            let cut = w.radius[i] + w.radius[j];
            pairs += usize::from(d2 < cut * cut);
        }
        // the six walls of the box at rest: x, y in [0, L], floor at box_z
        let (q, r, b) = (w.pos[i], w.radius[i], w.box_size);
        let gaps = [
            q[0],
            b[0] - q[0],
            q[1],
            b[1] - q[1],
            q[2] - w.box_z,
            b[2] - (q[2] - w.box_z),
        ];
        walls += gaps.iter().filter(|&&g| g < r).count();
    }
    assert_eq!(c.pair_contacts, pairs);
    assert_eq!(c.wall_contacts, walls);
    assert!(c.candidate_pairs >= pairs);
    // a settled bed: most grains touch others, the bottom layer the floor
    assert!(
        pairs > n && walls > n / 10,
        "{pairs} contacts, {walls} on walls"
    );
}
