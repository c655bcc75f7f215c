//! DEM throughput (particle-steps per second, one core) on the source's scene B bed,
//! vibrated kinematically at 15 Hz with U = 4.5 mm (the LIGGGHTS 3.8 comparison case:
//! ~6.5 M particle-steps/CPU-s for N = 250, 8–9 M for N = 1000–4000).
//!
//! Groups: `dem/step/{250,1000,4000}_steel` (real stiffness, E = 2.03e11 Pa) and
//! `dem/step/{250,1000,4000}_soft1000` (E/1000; box widened to keep the bed height),
//! `neighbor/cell_grid/{250,1000,4000}`, `contact/hertz_kuwabara_kono` and
//! `contact/response/{hertz_coulomb_viscous,hertz_mindlin}` (the routine the engine calls).
//! Criterion reports "elements/s" = particle-steps/s. The bed is settled and driven for
//! a while before timing so that the measured steps are those of the fluidised steady state.
//! Run: `cargo bench --bench dem`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use pdamp::contact::hertz_normal_force;
use pdamp::contact::lanes::{F64x8, Real};
use pdamp::contact::response::{
    contact_response, ContactKinematics, CoulombViscousKernel, HertzKernel, MindlinSpringKernel,
};
use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::stability::{choose_dt, DEFAULT_DT_FRACTION};
use pdamp::dem::{BoxDrive, DemWorld};
use pdamp::neighbor::NeighborList;
use pdamp::scene::dem::DemParams;
use std::hint::black_box;

fn drive() -> BoxDrive {
    BoxDrive {
        primary: None,
        amplitude_m: 4.5e-3,
        frequency_hz: 15.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    }
}

fn vibrated_world(n: usize, soft: f64) -> DemWorld {
    let mut p = if soft > 1.0 {
        DemParams::thesis_b_softened(soft)
    } else {
        DemParams::thesis_b()
    };
    let widen = ((n as f64) / 250.0).sqrt();
    p.r#box[0] *= widen;
    p.r#box[1] *= widen;
    p.count = n;
    let (dt, _) = choose_dt(
        &pdamp::setup::dem_model(&p).unwrap(),
        &drive(),
        None,
        DEFAULT_DT_FRACTION,
    )
    .unwrap();
    let mut w = initial_world(&pdamp::setup::dem_model(&p).unwrap(), drive(), dt, 4.5e-3).unwrap();
    if soft > 1.0 {
        // softened: settle first, then two forcing periods
        settle(&mut w, 0.5);
        w.start_drive();
        for _ in 0..(2.0 / 15.0 / dt) as usize {
            w.step();
        }
    } else {
        // real steel: settling 4000 grains would take minutes; drop the lattice onto the
        // vibrating floor for one forcing period instead
        w.start_drive();
        for _ in 0..(1.0 / 15.0 / dt) as usize {
            w.step();
        }
    }
    w
}

fn bench_step(c: &mut Criterion) {
    let mut g = c.benchmark_group("dem/step");
    g.sample_size(10);
    for (name, n, soft) in [
        ("250_steel", 250, 1.0),
        ("250_soft1000", 250, 1000.0),
        ("1000_steel", 1000, 1.0),
        ("1000_soft1000", 1000, 1000.0),
        ("4000_steel", 4000, 1.0),
        ("4000_soft1000", 4000, 1000.0),
    ] {
        let mut w = vibrated_world(n, soft);
        let batch = 200_000 / n;
        g.throughput(Throughput::Elements((n * batch) as u64));
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                for _ in 0..batch {
                    w.step();
                }
            })
        });
    }
    g.finish();
}

fn bench_neighbor(c: &mut Criterion) {
    let mut g = c.benchmark_group("neighbor/cell_grid");
    for n in [250usize, 1000, 4000] {
        let w = vibrated_world(n, 1000.0);
        let mut nl = NeighborList::new(w.box_size, 0.003, 0.0009);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| nl.rebuild(black_box(&w.pos), &w.radius, [0.0, 0.0, w.box_z]))
        });
    }
    g.finish();
}

fn bench_contact(c: &mut Criterion) {
    c.bench_function("contact/hertz_kuwabara_kono", |b| {
        b.iter(|| {
            hertz_normal_force(
                black_box(5.7e9),
                black_box(1e-6),
                black_box(0.3),
                black_box(3660.0),
            )
        })
    });
}

/// The response routine the engine's pair and wall passes call (one per law pair), on a
/// contact with rotation: Hertz–Kuwabara–Kono with the thesis's Coulomb law and with the
/// Mindlin spring.
fn bench_response(c: &mut Criterion) {
    let k = ContactKinematics {
        overlap_m: 2e-6,
        normal: [0.6, 0.0, 0.8],
        v_rel: [0.1, -0.2, -0.3],
        spin: [0.0, 1e-3, 2e-3],
    };
    let coef = [5.7e9, 3660.0, 10980.0, 2.0e9];
    let mut g = c.benchmark_group("contact/response");
    g.bench_function("hertz_coulomb_viscous", |b| {
        let mut h = [0.0; 3];
        b.iter(|| {
            contact_response::<HertzKernel, CoulombViscousKernel, f64>(
                black_box(&k),
                &coef,
                0.3,
                true,
                true,
                1e-7,
                &mut h,
            )
        })
    });
    g.bench_function("hertz_mindlin", |b| {
        let mut h = [0.0; 3];
        b.iter(|| {
            contact_response::<HertzKernel, MindlinSpringKernel, f64>(
                black_box(&k),
                &coef,
                0.3,
                true,
                true,
                1e-7,
                &mut h,
            )
        })
    });
    // the same contact in the eight lanes the engine's loops use (baseline instruction set
    // here; the engine runs its AVX2 build where the processor has it): per call, 8 contacts
    let k8 = ContactKinematics {
        overlap_m: F64x8::splat(k.overlap_m),
        normal: k.normal.map(F64x8::splat),
        v_rel: k.v_rel.map(F64x8::splat),
        spin: k.spin.map(F64x8::splat),
    };
    let coef8 = coef.map(F64x8::splat);
    g.bench_function("hertz_coulomb_viscous_x8", |b| {
        let mut h = [F64x8::splat(0.0); 3];
        b.iter(|| {
            contact_response::<HertzKernel, CoulombViscousKernel, F64x8>(
                black_box(&k8),
                &coef8,
                0.3,
                true,
                true,
                1e-7,
                &mut h,
            )
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    bench_step,
    bench_neighbor,
    bench_contact,
    bench_response
);
criterion_main!(benches);
