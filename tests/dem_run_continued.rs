//! A DEM run made twice as long continues the shorter run's trajectory bit for bit when its
//! analysed series keeps the same sample clock (twice `run.analysis_max_samples`), and does
//! not when the clock moves: the automatic time step is snapped to the analysis sample clock
//! (analysis window / `run.analysis_max_samples`), so a doubled window on the default count
//! takes a time step a fraction of a per cent off, and the bed follows another trajectory.
//! The chapter-4 study's doubling check (`ch4_run_length`, `ch4_checks`) relies on the first
//! half; the second half is why it must.
//!
//! A tiny DEM scene (20 soft grains) keeps the runs to seconds; `analysis_max_samples = 100`
//! puts the analysis clock (4 ms) well above `run.sample_interval` (0.1 ms), as the chapter-4
//! runs' clock is.

mod common;
mod scratch;

use std::collections::BTreeMap;
use std::path::Path;

use pdamp::scene::SceneSource;
use pdamp::sweep::{run_sweep, SweepSpec, Vary};

use common::TINY_DEM as TINY;

/// `run.analysis_max_samples` and `run.sample_interval` of these runs: the analysis clock
/// (0.4 s / 100 = 4 ms) far above the sample interval (0.1 ms).
fn clock_set() -> Vec<(String, toml::Value)> {
    vec![
        ("run.analysis_max_samples".into(), toml::Value::Integer(100)),
        ("run.sample_interval".into(), toml::Value::Float(1e-4)),
    ]
}

/// The time step (s) and the strobe rows by period index of the one point a sweep of TINY
/// with `set` stored.
fn run(dir: &Path, set: &[(&str, i64)]) -> (f64, BTreeMap<i64, String>) {
    let spec = SweepSpec {
        base: SceneSource::parse(TINY).unwrap(),
        set: clock_set()
            .into_iter()
            .chain(
                set.iter()
                    .map(|(k, v)| (k.to_string(), toml::Value::Integer(*v))),
            )
            .collect(),
        varies: vec![Vary::parse("excitation.frequency=15").unwrap()],
        analyze: true,
    };
    let r = run_sweep(&spec, dir, &|_| {}).unwrap();
    assert!(r.failed.is_empty(), "{:?}", r.failed);
    let text = std::fs::read_to_string(dir.join("points/0.json")).unwrap();
    let j: serde_json::Value = serde_json::from_str(&text).unwrap();
    let dt = j["summary"]["dt_s"].as_f64().unwrap();
    let rows = j["strobe"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let r = r.as_str().unwrap().to_string();
            (r.split(',').next().unwrap().parse().unwrap(), r)
        })
        .collect();
    (dt, rows)
}

#[test]
fn doubling_with_the_same_analysis_clock_continues_the_trajectory() {
    let dir = scratch::tempdir().unwrap();
    let (dt, short) = run(&dir.path().join("p12"), &[]);
    let (dt_long, long) = run(
        &dir.path().join("p24"),
        &[("run.periods", 24), ("run.analysis_max_samples", 200)],
    );
    assert_eq!(dt.to_bits(), dt_long.to_bits(), "{dt} vs {dt_long}");
    // the short run's section covers periods 6…12, the long run's 12…24: period 12 is in both
    let common: Vec<_> = short.keys().filter(|n| long.contains_key(n)).collect();
    assert!(!common.is_empty(), "{:?} / {:?}", short.keys(), long.keys());
    for n in common {
        assert_eq!(short[n], long[n], "period {n}");
    }
    // on the default count the doubled window's clock is twice as coarse, and the step moves
    let (dt_own, _) = run(&dir.path().join("p24_own"), &[("run.periods", 24)]);
    assert_ne!(dt.to_bits(), dt_own.to_bits(), "{dt}");
}

/// Amplitude (m) and strobed centre-of-mass heights of TINY run with the analysis, sampled as
/// `opts` says.
fn analysed(opts: &pdamp::model::RunOptions) -> (u64, Vec<u64>) {
    let scene = SceneSource::parse(TINY)
        .unwrap()
        .scene(&clock_set())
        .unwrap();
    let mut obs = pdamp::observe::NullObserver;
    let s = pdamp::sweep::run_with_analysis(&scene, &mut obs, opts, true).unwrap();
    let z = s.strobe.iter().map(|p| p.grain_z_m.to_bits()).collect();
    (s.amplitude_m.to_bits(), z)
}

#[test]
fn a_run_sampled_on_the_analysis_clock_is_the_sweep_points_run() {
    // what the chapter-4 panels do (`pdamp::setup::steady_series`): the same time step, so
    // the same trajectory and verdict as the sweep's point (sampled on its own clock)
    let scene = SceneSource::parse(TINY)
        .unwrap()
        .scene(&clock_set())
        .unwrap();
    let sweep_point = analysed(&pdamp::model::RunOptions::summary_only());
    let panel = analysed(&pdamp::setup::steady_series(&scene));
    assert_eq!(sweep_point, panel);
    // sampled every run.sample_interval instead (`pdamp simulate`): the same step too (the
    // scene's one step clock, `pdamp::setup::dem::step_clock_s`), so the same trajectory
    let fine = analysed(&pdamp::model::RunOptions::full_series(
        scene.run.sample_interval,
    ));
    assert_eq!(sweep_point, fine);
}

#[test]
fn a_kept_sweep_point_is_the_panels_run_and_a_finished_point_is_not_kept() {
    // `pdamp::sweep::run_sweep_keeping` (the chapter-4 panels): the point's own run gives the
    // samples a panel run on the analysis clock records, bit for bit, and its summary
    let dir = scratch::tempdir().unwrap();
    let spec = SweepSpec {
        base: SceneSource::parse(TINY).unwrap(),
        set: clock_set(),
        varies: vec![Vary::parse("excitation.frequency=15,16").unwrap()],
        analyze: true,
    };
    let out = dir.path().join("kept");
    let (report, kept) = pdamp::sweep::run_sweep_keeping(&spec, &out, &|_| {}, &[1]).unwrap();
    assert!(report.failed.is_empty(), "{:?}", report.failed);
    assert_eq!(kept.len(), 1);
    assert_eq!(kept[0].point, 1);
    let scene = SceneSource::parse(TINY)
        .unwrap()
        .scene(
            &[
                clock_set(),
                vec![("excitation.frequency".into(), toml::Value::Float(16.0))],
            ]
            .concat(),
        )
        .unwrap();
    let mut rec = pdamp::observe::Recorded::default();
    let opts = pdamp::setup::steady_series(&scene);
    let panel = pdamp::sweep::run_with_analysis(&scene, &mut rec, &opts, true).unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let k = &kept[0];
    assert!(rec.time_s.len() > 50, "{} samples", rec.time_s.len());
    assert_eq!(bits(&k.samples.time_s), bits(&rec.time_s));
    assert_eq!(bits(&k.samples.grain_z_m), bits(&rec.grain_z_m));
    assert_eq!(bits(&k.samples.grain_zmax_m), bits(&rec.grain_zmax_m));
    assert_eq!(bits(&k.samples.floor_z_m), bits(&rec.floor_z_m));
    assert_eq!(k.summary.strobe, panel.strobe);
    assert_eq!(k.summary.amplitude_m.to_bits(), panel.amplitude_m.to_bits());
    let verdict = |s: &pdamp::model::RunSummary| s.analysis.as_ref().map(|a| a.verdict());
    assert_eq!(verdict(&k.summary), verdict(&panel));
    assert!(verdict(&panel).is_some());
    // the stored point is the kept summary's
    let text = std::fs::read_to_string(out.join("points/1.json")).unwrap();
    let j: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        j["summary"]["amplitude_m"].as_f64().unwrap().to_bits(),
        panel.amplitude_m.to_bits()
    );
    // a rerun finds both points finished: nothing runs, nothing is kept
    let (again, kept) = pdamp::sweep::run_sweep_keeping(&spec, &out, &|_| {}, &[1]).unwrap();
    assert_eq!((again.skipped, again.computed), (2, 0));
    assert!(kept.is_empty());
}
