//! A sweep gives byte-identical sweep.csv, strobe.csv and point files whatever the number of
//! rayon threads (every point is independent and the files are rebuilt in point order).

mod scratch;

use std::path::Path;
use std::process::Command;

fn sweep(scene: &str, out: &Path, threads: &str) {
    let st = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args([
            "sweep",
            scene,
            "--out",
            out.to_str().unwrap(),
            "--no-analysis",
            "--set",
            "run.periods=100",
            "--vary",
            "excitation.frequency=4:28:3",
            "--vary",
            "damper.restitution=0,0.8",
        ])
        .env("RAYON_NUM_THREADS", threads)
        .status()
        .unwrap();
    assert!(st.success());
}

#[test]
fn one_and_two_threads_give_identical_files() {
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_impact.toml"
    );
    let dir = scratch::tempdir().unwrap();
    let (a, b) = (dir.path().join("t1"), dir.path().join("t2"));
    sweep(scene, &a, "1");
    sweep(scene, &b, "2");
    for f in ["sweep.csv", "strobe.csv"] {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(x == y, "{f} differs between 1 and 2 threads");
    }
    // a point file is the same but for the CPU time it records (a measurement of the
    // machine, not a result)
    for f in ["points/0.json", "points/17.json"] {
        let read = |d: &Path| {
            let mut v: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(d.join(f)).unwrap()).unwrap();
            assert!(v["cpu_s"].as_f64().is_some_and(|c| c >= 0.0), "{f}: {v}");
            v.as_object_mut().unwrap().remove("cpu_s");
            v
        };
        assert!(read(&a) == read(&b), "{f} differs between 1 and 2 threads");
    }
    let csv = std::fs::read_to_string(a.join("sweep.csv")).unwrap();
    // grid of 9 frequencies × 2 restitutions, one row each, varied keys as columns
    assert_eq!(csv.lines().count(), 1 + 18);
    let header = csv.lines().next().unwrap();
    assert!(
        header
            .starts_with("point,excitation.frequency,damper.restitution,frequency_hz,amplitude_m"),
        "{header}"
    );
}

#[test]
fn analysis_columns_are_thread_independent_too() {
    // the nonlinear analysis of each point (regime, period, Lyapunov exponent) must not depend
    // on the thread count either (it may use rayon internally)
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_impact.toml"
    );
    let dir = scratch::tempdir().unwrap();
    let run = |out: &Path, threads: &str| {
        let st = Command::new(env!("CARGO_BIN_EXE_pdamp"))
            .args([
                "sweep",
                scene,
                "--out",
                out.to_str().unwrap(),
                "--set",
                "run.periods=300",
                "--set",
                "run.analysis_max_samples=4000",
                "--vary",
                "excitation.frequency=9,15,22",
            ])
            .env("RAYON_NUM_THREADS", threads)
            .status()
            .unwrap();
        assert!(st.success());
    };
    let (a, b) = (dir.path().join("t1"), dir.path().join("t2"));
    run(&a, "1");
    run(&b, "2");
    let x = std::fs::read_to_string(a.join("sweep.csv")).unwrap();
    let y = std::fs::read_to_string(b.join("sweep.csv")).unwrap();
    assert_eq!(x, y);
    // the regime column is filled
    let row = x.lines().nth(2).unwrap();
    assert!(
        [
            "periodic",
            "quasi-periodic",
            "chaotic",
            "irregular",
            "undetermined",
            "too-short"
        ]
        .iter()
        .any(|r| row.contains(r)),
        "{row}"
    );
}
