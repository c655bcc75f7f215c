//! The trade-off study end to end on a small bed (src/tradeoff/study.rs): the reference
//! compared with itself has zero error, the measured quantities do not depend on the number
//! of worker threads (only wall times do), a setting that removes a dissipation mechanism
//! shows a dissipation error (negative control: an error metric that always said 0 would
//! fail), and the one-particle model gets the bed's mass.

use pdamp::scene::dem::DemParams;
use pdamp::tradeoff::measure::Rig;
use pdamp::tradeoff::study::{run_study, Study, StudyOptions};
use pdamp::tradeoff::{Axis, LadderOptions};

mod common;

fn small_bed() -> DemParams {
    // 24 steel spheres R = 3 mm in a 20 × 20 × 60 mm box
    let mut p = DemParams::thesis_b();
    p.count = 24;
    p.r#box = [0.02, 0.02, 0.06];
    p
}

fn rig() -> Rig {
    // scene B's primary with the base amplitude of scene B
    Rig {
        primary: common::scene_b_primary(),
        amplitude_m: common::SCENE_B_AMPLITUDE_M,
        gravity: 9.8,
    }
}

fn study(threads: usize) -> Study {
    let opts = StudyOptions {
        ladder: LadderOptions {
            reference_softening: 10000.0,
            reference_dt_fraction: 0.02,
            duration_s: 0.25,
            steady_fraction: 0.5,
            quick: true,
        },
        frequencies_hz: vec![15.0],
        threads: Some(threads),
        fitted_e_candidates: vec![0.0, 0.5],
    };
    run_study(&small_bed(), &rig(), &opts, &|_| {}).expect("study runs")
}

#[test]
fn small_study_is_consistent_and_thread_independent() {
    let a = study(1);
    let b = study(2);
    let measured = |s: &Study| -> Vec<(String, Option<f64>, Option<f64>, String)> {
        s.runs
            .iter()
            .map(|r| {
                (
                    r.setting.clone(),
                    r.amplitude_m,
                    r.dissipation_j_per_cycle,
                    r.status.clone(),
                )
            })
            .collect()
    };
    // bit-identical physics with 1 and 2 threads (each run is sequential and seeded)
    assert_eq!(measured(&a), measured(&b));

    let reference = a
        .settings
        .iter()
        .find(|s| s.axis == Axis::Reference)
        .unwrap();
    assert_eq!(reference.amplitude_max_rel_error, Some(0.0));
    assert_eq!(reference.dissipation_max_rel_error, Some(0.0));
    // t_s/10 is refused by the DEM's stability guard (dt ≤ t_s/20): recorded, not run
    let coarse = a.runs.iter().find(|r| r.setting == "dt = t_s/10").unwrap();
    assert!(
        coarse.status.contains("run.dt_fraction"),
        "{}",
        coarse.status
    );
    assert!(coarse.amplitude_m.is_none());
    // friction off removes the friction share of the dissipation: its error must be well
    // above 0 (friction is tens of % of the loss of a dense bed, Sánchez 2012 ch. 5)
    let fr = a
        .settings
        .iter()
        .find(|s| s.axis == Axis::Friction)
        .unwrap();
    assert!(fr.dissipation_max_rel_error.unwrap() > 0.02, "{fr:?}");
    // every error is finite and ≥ 0 where the run finished
    for r in a.runs.iter().filter(|r| r.status == "ok") {
        assert!(
            r.amplitude_rel_error
                .is_some_and(|e| e.is_finite() && e >= 0.0),
            "{r:?}"
        );
    }
    // the cost side of the trade-off: a DEM run's cost is its number of steps, which is the
    // driven duration over dt (to one step), and dt follows the rung's setting (a rung that
    // ignored its setting, or a step counter that counted something else, fails here; wall
    // times are measured, not asserted)
    let ref_run = a.runs.iter().find(|r| r.axis == Axis::Reference).unwrap();
    let ref_dt = ref_run.dt_s.unwrap();
    for r in a.runs.iter().filter(|r| r.status == "ok") {
        let Some(dt) = r.dt_s else { continue }; // the one-particle model counts events
        let duration = if r.axis == Axis::RunLength {
            r.value
        } else {
            0.25
        };
        let steps = duration / dt;
        assert!(
            (r.steps as f64 - steps).abs() <= 1.0 + 1e-9 * steps,
            "{}: {} steps for {duration} s / {dt:e} s",
            r.setting,
            r.steps
        );
        assert!(
            r.wall_time_s > 0.0 && r.total_wall_time_s >= r.wall_time_s,
            "{r:?}"
        );
    }
    // dt = t_s/20 against the reference's t_s/50: 2.5 × longer steps; the E/1000 rung is 10 ×
    // stiffer than the reference's E/10000 and t_s ∝ E^{-2/5} (Hertz), so its steps are
    // 10^{2/5} = 2.512 × shorter. The run rounds dt down to a whole number of steps per output
    // sample (7 at t_s/20, 18 at the reference, 44 at E/1000 here), which moves these ratios
    // by up to 1/7 ≈ 14 %: hence 15 %. The step counts follow the same ratios.
    let by = |label: &str| a.runs.iter().find(|r| r.setting == label).unwrap();
    let dt20 = by("dt = t_s/20");
    let stiff = by("E / 1000");
    for (run, want) in [(dt20, 2.5), (stiff, 10f64.powf(-0.4))] {
        let ratio = run.dt_s.unwrap() / ref_dt;
        assert!(
            (ratio / want - 1.0).abs() < 0.15,
            "{}: dt ratio {ratio}",
            run.setting
        );
        let cost = ref_run.steps as f64 / run.steps as f64;
        assert!(
            (cost / ratio - 1.0).abs() < 1e-3,
            "{}: {cost} vs {ratio}",
            run.setting
        );
    }
    // and the accuracy side: coarser dt and a different stiffness both move the amplitude
    // away from the reference (an error metric stuck at 0 fails)
    assert!(dt20.amplitude_rel_error.unwrap() > 0.0, "{dt20:?}");
    assert!(stiff.amplitude_rel_error.unwrap() > 0.0, "{stiff:?}");
    // the one-particle note gives m_p = 24 × 8030 × 4/3 π (3 mm)³ = 0.02180 kg
    assert!(
        a.notes.iter().any(|n| n.contains("m_p = 0.0218")),
        "{:?}",
        a.notes
    );
    assert!(a.settings.iter().any(|s| s.pareto_amplitude));
}
