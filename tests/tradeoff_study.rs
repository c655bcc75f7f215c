//! The speed–accuracy study from stored points (src/tradeoff): points are found by what was
//! simulated wherever a sweep stored them, only the missing ones are computed (and resume),
//! errors are measured against the reference's points read independently from the stored
//! files, a guard's refusal is a row with its message, and no cell is NaN or infinite.
//!
//! A tiny DEM scene (20 soft grains, 12 forcing periods) keeps the runs to seconds.

mod common;
mod scratch;

use std::path::Path;

use pdamp::choice::Change;
use pdamp::scene::SceneSource;
use pdamp::sweep::{run_sweep, Catalog, SweepSpec, Vary};
use pdamp::tradeoff::compute::compute_missing;
use pdamp::tradeoff::study::study;
use pdamp::tradeoff::table::{rows_csv, settings_csv};
use pdamp::tradeoff::StudyPlan;

use common::TINY_DEM;

/// The tiny DEM scene run three times as long: a run's CPU time is measured in clock ticks of
/// 10 ms and kept only above 50 ms ([`pdamp::dem::run`]), which 12 periods of 20 grains do
/// not reach once the two-replica test's copy is not stepped (periodic points).
fn tiny() -> String {
    let long = TINY_DEM.replace("periods = 12", "periods = 36");
    assert_ne!(long, TINY_DEM, "TINY_DEM's run length moved");
    long
}

fn plain_sweep(data: &Path, freqs: &str) {
    let spec = SweepSpec {
        base: SceneSource::parse(&tiny()).unwrap(),
        set: Vec::new(),
        varies: vec![Vary::parse(&format!("excitation.frequency={freqs}")).unwrap()],
        analyze: true,
    };
    let r = run_sweep(&spec, &data.join("plain"), &|_| {}).unwrap();
    assert!(r.failed.is_empty(), "{:?}", r.failed);
}

/// Z of every stored point of `dir` by frequency, read straight from the JSON files.
fn stored_amplitudes(dir: &Path) -> Vec<(f64, f64)> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir.join("points")).unwrap().flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "json") {
            let j: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
            let s = &j["summary"];
            v.push((
                s["frequency_hz"].as_f64().unwrap(),
                s["amplitude_m"].as_f64().unwrap(),
            ));
        }
    }
    v
}

#[test]
fn study_reuses_stored_points_computes_the_rest_and_measures_errors() {
    let dir = scratch::tempdir().unwrap();
    let data = dir.path().join("data");
    let scene = dir.path().join("tiny.toml");
    std::fs::write(&scene, tiny()).unwrap();
    // a user's sweep of the reference scene at 14 and 16 Hz, in a folder of its own
    plain_sweep(&data, "14,16");

    let freqs = [14.0, 15.0, 16.0];
    let catalog = Catalog::scan(&data).unwrap();
    let plan = StudyPlan::new(&scene, &freqs, &data, &catalog).unwrap();
    let reference = plan
        .rungs
        .iter()
        .find(|r| r.change == Change::None)
        .unwrap();
    // only 15 Hz is missing: the user's points are the reference's (same scene)
    let c = compute_missing(&plan, reference, &catalog, &|_| {}).unwrap();
    assert_eq!(c.missing_hz, vec![15.0]);
    assert_eq!(c.report.as_ref().unwrap().computed, 1);
    // dt = t_s/50 is the tiny scene's own time step: that rung is the reference's points
    let catalog = Catalog::scan(&data).unwrap();
    let dt50 = plan.rungs.iter().find(|r| r.id == "dt-50").unwrap();
    assert!(compute_missing(&plan, dt50, &catalog, &|_| {})
        .unwrap()
        .missing_hz
        .is_empty());
    // a rung that changes the physics is computed at all three, and resumes to nothing
    let rot = plan.rungs.iter().find(|r| r.id == "rotations-off").unwrap();
    let c = compute_missing(&plan, rot, &catalog, &|_| {}).unwrap();
    assert_eq!(c.report.as_ref().unwrap().computed, 3);
    let catalog = Catalog::scan(&data).unwrap();
    assert!(compute_missing(&plan, rot, &catalog, &|_| {})
        .unwrap()
        .missing_hz
        .is_empty());

    let s = study(&plan, &catalog).unwrap();
    let row = |id: &str, f: f64| {
        s.rows
            .iter()
            .find(|r| r.setting == id && r.frequency_hz == f)
            .unwrap()
    };
    // the reference against itself: zero error, all verdicts equal, speed-up exactly 1
    for f in freqs {
        assert_eq!(row("reference", f).amplitude_rel_error, Some(0.0));
        assert_eq!(row("reference", f).status, "ok");
    }
    let ref_sum = &s.settings[0];
    assert_eq!(ref_sum.speedup, Some(1.0));
    assert_eq!(ref_sum.regime_matches, ref_sum.regime_compared);
    // the rung's Z error equals |Z − Z_ref| / Z_ref from the stored files (to rounding)
    let mut reference_z = stored_amplitudes(&data.join("plain"));
    for e in std::fs::read_dir(plan.home(reference)).unwrap().flatten() {
        reference_z.extend(stored_amplitudes(&e.path()));
    }
    let rot_dir = std::fs::read_dir(plan.home(rot))
        .unwrap()
        .flatten()
        .next()
        .unwrap();
    for (f, z) in stored_amplitudes(&rot_dir.path()) {
        let zr = reference_z.iter().find(|(g, _)| *g == f).unwrap().1;
        let e = row("rotations-off", f).amplitude_rel_error.unwrap();
        assert!((e - (z - zr).abs() / zr).abs() < 1e-12, "{f} Hz: {e}");
    }
    // a point judged by other verdict rules is not compared with the reference's verdict
    // (a point stored by an earlier binary: its analysis says rules 1)
    assert!(row("rotations-off", 14.0).regime_match.is_some());
    let older = std::fs::read_dir(rot_dir.path().join("points"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| {
            let j: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
            j["summary"]["frequency_hz"].as_f64() == Some(14.0)
        })
        .unwrap();
    let mut j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&older).unwrap()).unwrap();
    j["summary"]["analysis"]["verdict_rules"] = serde_json::json!(1);
    std::fs::write(&older, serde_json::to_string(&j).unwrap()).unwrap();
    let s_old = study(&plan, &Catalog::scan(&data).unwrap()).unwrap();
    let r = s_old
        .rows
        .iter()
        .find(|r| r.setting == "rotations-off" && r.frequency_hz == 14.0)
        .unwrap();
    assert_eq!(r.regime_match, None);
    assert!(r.message.contains("not compared"), "{}", r.message);
    // t_s/10 is refused by the time-step guard: a row with its message, not a NaN
    let coarse = row("dt-10", 15.0);
    assert_eq!(coarse.status, "refused");
    assert!(
        coarse.message.contains("run.dt_fraction"),
        "{}",
        coarse.message
    );
    assert_eq!(row("soften-10", 15.0).status, "not computed");
    // the report answers its three questions and lists every setting
    let md = pdamp::tradeoff::report::markdown(
        &s,
        &SceneSource::parse(&tiny()).unwrap().scene(&[]).unwrap(),
        &[],
    );
    assert_eq!(md.matches("\n- For ").count(), 3, "{md}");
    for x in &s.settings {
        assert!(md.contains(&format!("| `{}` ", x.setting)), "{md}");
    }
    let header = vec!["test".to_string()];
    for text in [rows_csv(&s, &header), settings_csv(&s, &header)] {
        assert!(text.starts_with("# test\n"));
        let mut r = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        for rec in r.records() {
            for cell in rec.unwrap().iter() {
                // a cell that reads as a number reads as a finite one ("NaN", "inf" parse)
                assert!(
                    cell.parse::<f64>().map_or(true, f64::is_finite),
                    "{cell}: {text}"
                );
            }
        }
    }
}

#[test]
fn a_scene_without_grains_cannot_be_laddered() {
    let dir = scratch::tempdir().unwrap();
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_impact.toml"
    );
    let e = StudyPlan::new(Path::new(scene), &[15.0], dir.path(), &Catalog::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("damper.kind") && e.contains("DEM"), "{e}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["tradeoff", scene, "--data"])
        .arg(dir.path())
        .arg("--out")
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
