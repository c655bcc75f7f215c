//! `run.energy_ledger = false` (issue 12: "energy bookkeeping must cost nothing when not asked
//! for"): the same trajectory bit for bit, no flows booked, no per-cycle energies, no balance;
//! `pdamp simulate` runs such a scene end to end.

use pdamp::dem::run::{initial_world, settle};
use pdamp::dem::stability::{choose_dt, DEFAULT_DT_FRACTION};
use pdamp::dem::{BoxDrive, DemRunConfig, DemSample};
use pdamp::scene::dem::DemParams;
use pdamp::scene::Scene;

fn drive() -> BoxDrive {
    BoxDrive {
        primary: None,
        amplitude_m: 4.5e-3,
        frequency_hz: 15.0,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    }
}

#[test]
fn the_ledger_switch_changes_no_trajectory() {
    let run = |ledger: bool| {
        let p = DemParams::thesis_b_softened(1000.0);
        let model = pdamp::setup::dem_model(&p).unwrap();
        let (dt, _) = choose_dt(&model, &drive(), None, DEFAULT_DT_FRACTION).unwrap();
        let mut w = initial_world(&model, drive(), dt, 0.0).unwrap();
        w.energy_ledger = ledger;
        settle(&mut w, 0.02);
        w.start_drive();
        for _ in 0..2000 {
            w.step();
        }
        let bits: Vec<u64> = [&w.pos, &w.vel, &w.omega, &w.force]
            .iter()
            .flat_map(|a| a.iter().flatten().map(|x| x.to_bits()))
            .chain([w.grain_force_n.to_bits(), w.box_z.to_bits()])
            .collect();
        (bits, w.ledger)
    };
    let (on, l_on) = run(true);
    let (off, l_off) = run(false);
    assert!(on == off, "the ledger switch changed the trajectory");
    assert!(l_on.collision_j > 0.0 && l_on.base_work_j != 0.0);
    assert_eq!(l_off, Default::default());
}

#[test]
fn a_run_without_ledger_reports_no_energies() {
    let p = DemParams::thesis_b_softened(1000.0);
    let cfg = DemRunConfig {
        duration_s: 0.05,
        sample_interval_s: 1e-3,
        energy_ledger: false,
        // the fraction this run was written for (the default was 1/50 then)
        dt_fraction: 1.0 / 50.0,
        ..Default::default()
    };
    let mut v: Vec<DemSample> = Vec::new();
    let s = pdamp::setup::dem::run_params(&p, drive(), &cfg, &mut v).unwrap();
    assert!(s.energy_collision_j_per_cycle.is_none() && s.energy_base_work_j_per_cycle.is_none());
    assert!(s.energy_balance_relative_error.is_nan() && s.energy_balance_warning.is_none());
    assert!(!v.is_empty() && v.iter().all(|x| x.dem.e_collision_j == 0.0));
    assert!(v.iter().all(|x| x.dem.e_balance_residual_j == 0.0));
    assert!(v.iter().all(|x| x.dem.e_kinetic_j.is_finite()));
}

#[test]
fn the_scene_key_parses_and_defaults_to_on() {
    let base = include_str!("../bench/dem_bed.toml");
    let on = Scene::from_toml(base).unwrap();
    assert!(on.run.energy_ledger);
    let off = Scene::from_toml(&format!("{base}energy_ledger = false\n")).unwrap();
    assert!(!off.run.energy_ledger);
}

#[test]
fn pdamp_simulate_runs_without_a_ledger() {
    let out = std::env::temp_dir().join(format!("pdamp_ledger_off_{}", std::process::id()));
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", "bench/dem_bed.toml", "--no-analysis", "--out"])
        .arg(&out)
        .args([
            "--set",
            "run.energy_ledger=false",
            "--set",
            "run.duration=0.01",
            "--set",
            "damper.settle_time=0.02",
        ])
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let s = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(!s.contains("energy_collision_j_per_cycle\": 0"), "{s}");
    let _ = std::fs::remove_dir_all(&out);
}
