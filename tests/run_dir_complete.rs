//! Output directories are whole or marked incomplete, snapshots live under the run's
//! directory, readers refuse what they cannot read, and the exit status tells failure kinds
//! apart (issue 14).

mod scratch;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn pdamp(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .current_dir(cwd)
        .output()
        .unwrap()
}

fn data(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(rel)
        .display()
        .to_string()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|r| {
            r.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// A small DEM run with snapshots: soft steel, 0.02 s driven, a snapshot every 0.01 s.
fn dem_snapshot_args(out: &str) -> Vec<String> {
    [
        "simulate",
        &data("data/scenes/thesis_b_soft.toml"),
        "--out",
        out,
        "--no-analysis",
        "--set",
        "run.duration=0.02",
        "--set",
        "damper.count=40",
        "--set",
        "damper.snapshot_interval=0.01",
        "--set",
        "damper.snapshot_format=csv",
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn snapshots_go_under_the_run_directory_and_stale_ones_are_removed() {
    let dir = scratch::tempdir().unwrap();
    let args = dem_snapshot_args("run");
    let o = pdamp(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // nothing in the current directory but the run directory
    assert_eq!(names(dir.path()), vec!["run"]);
    let snaps = dir.path().join("run/snapshots");
    assert_eq!(
        names(&snaps),
        vec![
            "grains_000000.csv",
            "grains_000001.csv",
            "grains_000002.csv"
        ]
    );
    assert!(!dir.path().join("run/RUNNING").exists());
    // a second run into the same directory with fewer snapshots leaves none of the first's
    let mut args2 = args.clone();
    args2.extend(["--set", "damper.snapshot_interval=0.015"].map(String::from));
    let o = pdamp(
        &args2.iter().map(String::as_str).collect::<Vec<_>>(),
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        names(&snaps),
        vec!["grains_000000.csv", "grains_000001.csv"]
    );
}

#[test]
fn every_sweep_point_keeps_its_own_snapshots() {
    let dir = scratch::tempdir().unwrap();
    let mut args = dem_snapshot_args("unused");
    args[0] = "sweep".into();
    args.drain(2..4); // no --out of simulate
    args.extend(["--out", "sw", "--vary", "excitation.frequency=14,16"].map(String::from));
    let o = pdamp(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.path().join("snapshots").exists());
    for i in 0..2 {
        let snaps = dir.path().join(format!("sw/points/{i}/snapshots"));
        assert_eq!(names(&snaps).len(), 3, "point {i}: {:?}", names(&snaps));
        assert!(!dir.path().join(format!("sw/points/{i}/RUNNING")).exists());
    }
}

/// Starts a long impact run into `out`, waits until it has started (marker written) and written
/// 3 MB of `series.csv` (more than the earlier run's whole file), and kills it (SIGKILL).
fn kill_mid_run(cwd: &Path, out: &str) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args([
            "simulate",
            &data("data/scenes/thesis_b_impact.toml"),
            "--out",
            out,
            "--no-analysis",
            "--set",
            "run.periods=20000",
            "--set",
            "run.sample_interval=1e-5",
            "--max-output",
            "1e12",
        ])
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let series = cwd.join(out).join("series.csv");
    let marker = cwd.join(out).join("RUNNING");
    let start = Instant::now();
    while !marker.exists() || std::fs::metadata(&series).map_or(0, |m| m.len()) < 3_000_000 {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the run never wrote"
        );
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before the kill"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
}

#[test]
fn a_killed_simulate_leaves_a_directory_marked_incomplete_that_readers_refuse() {
    let dir = scratch::tempdir().unwrap();
    // a complete run first: the reused directory holds its summary.json and scene.toml
    let o = pdamp(
        &[
            "simulate",
            &data("data/scenes/thesis_b_impact.toml"),
            "--out",
            "run",
            "--no-analysis",
            "--set",
            "run.periods=10",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let run: PathBuf = dir.path().join("run");
    assert_eq!(
        names(&run),
        vec!["scene.toml", "series.csv", "strobe.csv", "summary.json"]
    );
    let ok = pdamp(&["analyze", "run/series.csv", "--json"], dir.path());
    assert!(ok.status.success(), "{}", stderr(&ok));

    kill_mid_run(dir.path(), "run");
    // the old run's files are gone, the marker says the directory is incomplete
    assert_eq!(names(&run), vec!["RUNNING", "series.csv"]);
    for args in [
        &["analyze", "run/series.csv"][..],
        &["plot", "bed-motion", "run/series.csv", "-o", "b.png"][..],
        &["mutual", "run/series.csv"][..],
    ] {
        let o = pdamp(args, dir.path());
        assert_eq!(o.status.code(), Some(3), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("incomplete run directory"),
            "{}",
            stderr(&o)
        );
    }
    // a fresh directory killed the same way
    kill_mid_run(dir.path(), "fresh");
    assert_eq!(
        names(&dir.path().join("fresh")),
        vec!["RUNNING", "series.csv"]
    );
}

#[test]
fn exit_status_tells_failure_kinds_apart() {
    let dir = scratch::tempdir().unwrap();
    let series = dir.path().join("x.txt");
    std::fs::write(
        &series,
        (0..200)
            .map(|i| format!("{}\n", (i as f64 * 0.3).sin()))
            .collect::<String>(),
    )
    .unwrap();
    let s = series.to_str().unwrap();
    let code = |args: &[&str]| pdamp(args, dir.path()).status.code();
    // usage: unknown option; an option value the command refuses
    assert_eq!(code(&["mutual", "--no-such-option", s]), Some(2));
    assert_eq!(code(&["spectrum", "--factor", "0.5", s]), Some(2));
    // input: a refused scene key, decimal commas, a missing column
    assert_eq!(
        code(&[
            "check-scene",
            &data("data/scenes/thesis_b_impact.toml"),
            "--set",
            "primary.mass=-1"
        ]),
        Some(3)
    );
    // fuzzing regression: a box a million metres wide is refused at once, not packed
    assert_eq!(
        code(&[
            "check-scene",
            &data("data/scenes/thesis_b_soft.toml"),
            "--set",
            "damper.box=[1e6, 1e6, 0.1]"
        ]),
        Some(3)
    );
    std::fs::write(dir.path().join("dc.txt"), "-4,408e0\n-3,1e0\n").unwrap();
    assert_eq!(code(&["mutual", "dc.txt"]), Some(3));
    assert_eq!(code(&["mutual", "-c", "3", s]), Some(3));
    // I/O: a file that is not there
    assert_eq!(code(&["mutual", "no-such-file.txt"]), Some(5));
}

#[test]
fn a_closed_pipe_ends_quietly() {
    let dir = scratch::tempdir().unwrap();
    let lorenz = data("data/series/lorenz_x_dt0.01_n10000.txt");
    let bin = env!("CARGO_BIN_EXE_pdamp");
    for cmd in [
        format!("'{bin}' embed -m 3 -d 5 '{lorenz}' | head -1"),
        format!("'{bin}' mutual -D 2000 '{lorenz}' | head -1"),
    ] {
        let o = Command::new("bash")
            .args(["-c", &format!("set -o pipefail; {cmd} > /dev/null")])
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(o.status.success(), "{cmd}: {:?} {}", o.status, stderr(&o));
        // no error message (mutual's own report of the first minimum may come first)
        let e = stderr(&o);
        assert!(
            !e.contains("error") && !e.contains("panicked") && !e.contains("Broken pipe"),
            "{cmd}: {e}"
        );
    }
}
