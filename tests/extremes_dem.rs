//! The DEM at the extremes (issue "Stability at the extremes"): each case either works —
//! finite state, grains inside the box, energy ledger closed — or fails with a message naming
//! the key to change; never silently wrong. Cases covered elsewhere: momentum and energy of
//! conservative contacts without gravity (tests/dem_invariants.rs), scene B softened
//! (tests/dem_scene_b.rs); impact-model extremes (tests/impact_extremes.rs).
//! Beds are softened (E ÷ 10⁴, γ ∝ E^{3/5}: e(v) unchanged, SPEC §9) to keep the suite fast.

use pdamp::dem::run::initial_world;
use pdamp::dem::stability::choose_dt;
use pdamp::dem::{BoxDrive, DemRunConfig, DemSample, DemSummary, DtChoice};
use pdamp::error::SimError;
use pdamp::scene::dem::{ContactKind, DemParams};

mod common;
use common::scene_b_drive as drive;

fn bed(count: usize, box_m: [f64; 3]) -> DemParams {
    let mut p = DemParams::thesis_b_softened(1e4);
    p.count = count;
    p.r#box = box_m;
    p
}

fn run(p: &DemParams, f: f64, duration: f64) -> Result<(DemSummary, Vec<DemSample>), SimError> {
    let cfg = DemRunConfig {
        duration_s: duration,
        sample_interval_s: 1e-3,
        // the fraction these runs were written for (the default was 1/50 then)
        dt_fraction: 1.0 / 50.0,
        ..Default::default()
    };
    let mut v = Vec::new();
    pdamp::setup::dem::run_params(p, drive(f), &cfg, &mut v).map(|s| (s, v))
}

/// Finite samples, every grain between floor and ceiling, ledger closed within `tol`.
fn sane(s: &DemSummary, v: &[DemSample], tol: f64) {
    assert!(!v.is_empty());
    for x in v {
        assert!(
            x.sample.box_z_m.is_finite()
                && x.sample.grain_z_m.is_finite()
                && x.sample.grain_force_n.is_finite(),
            "{x:?}"
        );
        assert!(
            x.dem.grain_zmin_m > x.sample.floor_z_m && x.dem.grain_zmax_m < x.sample.ceiling_z_m,
            "grain outside at t = {}",
            x.sample.time_s
        );
    }
    assert!(s.amplitude_m.is_finite());
    assert!(
        s.energy_balance_relative_error < tol,
        "ledger error {}",
        s.energy_balance_relative_error
    );
}

#[test]
fn conservative_bed_holds_energy_over_a_long_run() {
    // μ = 0, γ_n = γ_s = 0 (walls too): a Hamiltonian system. 20 grains dropped in a still
    // box bounce for 2 s (hundreds of collisions); kinetic + rotational + potential + elastic
    // energy must stay within 0.5 % of the energy above the resting floor (velocity Verlet is
    // symplectic: bounded error O((dt/t_s)²), no drift; an integrator that lost energy at
    // each collision, e.g. a one-sided force evaluation, drifts by tens of %)
    let mut p = bed(20, [0.03, 0.03, 0.06]);
    p.friction = 0.0;
    p.gamma_n = 0.0;
    p.gamma_s = 0.0;
    let still = BoxDrive {
        frequency_hz: 1.0,
        ..BoxDrive::STILL
    };
    let (dt, _) = choose_dt(&pdamp::setup::dem_model(&p).unwrap(), &still, None, 0.02).unwrap();
    let mut w = initial_world(&pdamp::setup::dem_model(&p).unwrap(), still, dt, 0.0).unwrap();
    w.refresh();
    let above_floor = |w: &pdamp::dem::DemWorld| -> f64 {
        (0..w.len())
            .map(|i| w.mass[i] * 9.8 * (w.pos[i][2] - w.radius[i] - w.box_z))
            .sum::<f64>()
    };
    let e = |w: &pdamp::dem::DemWorld| {
        let s = w.energy_state();
        s.kinetic_j + s.rotational_j + s.potential_j + s.elastic_j
    };
    let (e0, scale) = (e(&w), above_floor(&w));
    let steps = (2.0 / dt) as usize;
    let mut worst: f64 = 0.0;
    for k in 0..steps {
        w.step();
        if k % 100 == 0 {
            worst = worst.max((e(&w) - e0).abs() / scale);
        }
    }
    assert!(worst < 5e-3, "largest relative energy error {worst:.3e}");
    assert!(w.ledger.collision_j == 0.0 && w.ledger.friction_j == 0.0);
}

#[test]
fn very_stiff_contacts_with_auto_dt() {
    // E = 100 × steel: dt = "auto" follows the shorter contact time (t_s ∝ E^{-2/5}); the
    // run stays finite and the ledger closes within 1 %
    let mut p = DemParams::thesis_b();
    p.youngs_modulus *= 100.0;
    p.count = 8;
    p.settle_time = Some(0.0);
    let (s, v) = run(&p, 15.0, 0.01).expect("stiff run");
    let (dt_steel, _) = choose_dt(
        &pdamp::setup::dem_model(&DemParams::thesis_b()).unwrap(),
        &drive(15.0),
        None,
        0.02,
    )
    .unwrap();
    // dt shrinks by 100^{2/5} = 6.3 (Hertz t_s scaling, SPEC §2); 0.1 %: run_dem may trim
    // dt slightly (e.g. to a whole number of steps per sample)
    assert!(
        (dt_steel / s.dt_s / 100f64.powf(0.4) - 1.0).abs() < 1e-3,
        "dt {} vs steel {}",
        s.dt_s,
        dt_steel
    );
    sane(&s, &v, 0.01);
}

#[test]
fn explicit_dt_above_the_stability_limit_is_refused_before_any_output() {
    let p = DemParams::thesis_b();
    let cfg = DemRunConfig {
        duration_s: 0.1,
        sample_interval_s: 1e-3,
        dt: DtChoice::Seconds(1e-4),
        ..Default::default()
    };
    let mut v: Vec<DemSample> = Vec::new();
    let e = pdamp::setup::dem::run_params(&p, drive(15.0), &cfg, &mut v)
        .unwrap_err()
        .to_string();
    // names the key, the limit and the fix; nothing (so no NaN) was emitted
    assert!(
        e.contains("run.dt") && e.contains("t_s/20") && e.contains("auto"),
        "{e}"
    );
    assert!(v.is_empty());
}

#[test]
fn jammed_bed_with_no_free_gap() {
    // 60 grains (R = 3 mm) in 20 × 20 mm: the bed at a random packing (φ ≈ 0.6) is 28 mm high;
    // Lz = 30 mm leaves ≈ no gap. Either the grains cannot be placed (clear error naming the
    // box or the count) or the jammed bed runs with every grain inside and the ledger closed.
    let p = bed(60, [0.02, 0.02, 0.03]);
    match run(&p, 15.0, 0.1) {
        Ok((s, v)) => sane(&s, &v, 0.02),
        Err(e) => {
            let m = e.to_string();
            assert!(
                m.contains("damper.box") || m.contains("damper.count"),
                "{m}"
            );
        }
    }
}

#[test]
fn dilute_gas_in_a_huge_box() {
    // 10 grains in a 1 m cube: the cell grid covers 1 m³ without trouble, grains fall freely
    let mut p = bed(10, [1.0, 1.0, 1.0]);
    p.settle_time = Some(0.0);
    let (s, v) = run(&p, 15.0, 0.1).expect("dilute run");
    sane(&s, &v, 0.01);
}

#[test]
fn lowest_and_highest_frequencies() {
    // 0.5 Hz (quasi-static: the bed rides on the floor) and 100 Hz (UΩ² ≈ 180 g: the impact
    // speed 2UΩ = 5.7 m/s sets a shorter auto dt)
    let p = bed(20, [0.03, 0.03, 0.06]);
    let (s, v) = run(&p, 0.5, 0.4).expect("0.5 Hz");
    sane(&s, &v, 0.01);
    let (s100, v) = run(&p, 100.0, 0.05).expect("100 Hz");
    sane(&s100, &v, 0.01);
    assert!(s100.dt_s < s.dt_s);
}

#[test]
fn a_single_grain_and_ten_thousand() {
    let p = bed(1, [0.02, 0.02, 0.05]);
    let (s, v) = run(&p, 15.0, 0.3).expect("N = 1");
    sane(&s, &v, 0.01);
    // N = 10 000: construct and take a few steps (size, not physics)
    let big = bed(10_000, [0.15, 0.15, 0.2]);
    let (dt, _) = choose_dt(
        &pdamp::setup::dem_model(&big).unwrap(),
        &drive(15.0),
        None,
        0.02,
    )
    .unwrap();
    let mut w = initial_world(
        &pdamp::setup::dem_model(&big).unwrap(),
        drive(15.0),
        dt,
        0.0,
    )
    .unwrap();
    for _ in 0..5 {
        w.step();
    }
    assert_eq!(w.len(), 10_000);
    assert!(w
        .pos
        .iter()
        .flatten()
        .chain(w.vel.iter().flatten())
        .all(|x| x.is_finite()));
}

#[test]
fn linear_law_restitution_zero_is_refused_with_the_fix() {
    // e = 0 has no linear spring–dashpot equivalent (ζ_d = 1 gives e = 0 only in the limit):
    // refused naming damper.restitution; e = 1 (no damping) runs and conserves the ledger
    let mut p = bed(8, [0.02, 0.02, 0.05]);
    p.contact = ContactKind::Linear;
    // steel's yield strength scaled like E (1e9 Pa ÷ 10⁴ would give k_n ≈ 30 N/m: so soft
    // that an undamped grain was found 2 mm past the ceiling at t = 0.09 s without the run
    // stopping — reported to the DEM's escape check); 1e7 Pa keeps overlaps ≪ R
    p.yield_strength = Some(1e7);
    p.restitution = Some(0.0);
    let e = run(&p, 15.0, 0.05).unwrap_err().to_string();
    assert!(e.contains("damper.restitution"), "{e}");
    p.restitution = Some(1.0);
    p.friction = 0.0;
    p.settle_time = Some(0.0);
    let (s, v) = run(&p, 15.0, 0.1).expect("e = 1");
    sane(&s, &v, 0.01);
}
