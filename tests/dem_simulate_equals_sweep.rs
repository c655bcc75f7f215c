//! `pdamp simulate` and `pdamp sweep` of the same DEM scene point take the same time step and
//! follow the same trajectory (issue 40): the automatic step is chosen once, when the scene
//! is resolved, and put on the scene's step clock (the analysis window's sample clock,
//! `pdamp::setup::dem::step_clock_s`), whatever a run then samples. Before, `simulate` put it
//! on `run.sample_interval` and a sweep point on the analysis clock, and the two runs of one
//! scene took steps a few per cent apart and parted.
//!
//! The scene is the tiny DEM scene with the analysis clock (0.4 s / 100 = 4 ms) far above the
//! series' interval (0.1 ms), as the chapter-4 runs have it.

mod common;
mod scratch;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

fn pdamp(args: &[&str], dir: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The rows of a CSV file as maps from column name to text.
fn rows(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let head: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(str::to_string))
                .collect()
        })
        .collect()
}

fn summary(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn simulate_and_a_sweep_point_take_the_same_step_and_trajectory() {
    let dir = scratch::tempdir().unwrap();
    let scene = common::TINY_DEM.replace(
        "sample_interval = 1e-3",
        "sample_interval = 1e-4\nanalysis_max_samples = 100",
    );
    std::fs::write(dir.path().join("tiny.toml"), scene).unwrap();
    pdamp(&["simulate", "tiny.toml", "--out", "sim"], dir.path());
    pdamp(
        &[
            "sweep",
            "tiny.toml",
            "--vary",
            "excitation.frequency=15",
            "--out",
            "sw",
        ],
        dir.path(),
    );
    let sim = summary(&dir.path().join("sim/summary.json"));
    let point = summary(&dir.path().join("sw/points/0.json"));
    let sw = &point["summary"];
    let dt = sim["dt_s"].as_f64().unwrap();
    assert_eq!(
        dt.to_bits(),
        sw["dt_s"].as_f64().unwrap().to_bits(),
        "time steps: simulate {dt}, sweep {}",
        sw["dt_s"]
    );
    // the step is on the analysis clock (4 ms), not on the series' 0.1 ms
    let clock = 0.4 / 100.0;
    let per_clock = clock / dt;
    assert!(
        (per_clock - per_clock.round()).abs() < 1e-9,
        "{per_clock} steps per analysis sample"
    );
    assert_eq!(sim["amplitude_m"], sw["amplitude_m"]);
    // the sections, period by period, bit for bit (the text of each value)
    let a = rows(&dir.path().join("sim/strobe.csv"));
    let b = rows(&dir.path().join("sw/strobe.csv"));
    assert!(a.len() >= 6, "{} strobe rows", a.len());
    assert_eq!(a.len(), b.len());
    for (ra, rb) in a.iter().zip(&b) {
        for col in ["cycle", "grain_z_m", "box_z_m", "grain_v_m_s", "box_v_m_s"] {
            assert_eq!(ra[col], rb[col], "{col} at cycle {}", ra["cycle"]);
        }
    }
    // simulate's series: a row every whole number of steps nearest 0.1 ms, exact times
    let series = rows(&dir.path().join("sim/series.csv"));
    let t1: f64 = series[1]["time_s"].parse().unwrap();
    let steps = (1e-4 / dt).round();
    assert!((t1 - steps * dt).abs() < 1e-15, "{t1} vs {steps} steps");
}
