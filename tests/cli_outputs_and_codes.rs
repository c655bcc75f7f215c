//! Where a run's snapshots go when `damper.snapshot_dir` is absolute, the exit status of a
//! sweep whose points fail, the guard on an infinite contact time (issue 14), and `fit-frf`
//! refusing a force-driven sweep (issue 41).

mod scratch;

use std::path::Path;
use std::process::{Command, Output};

fn pdamp(args: &[&str], extra: &[&Path]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_pdamp"));
    cmd.args(args);
    for p in extra {
        cmd.arg(p);
    }
    cmd.output().unwrap()
}

/// A 40-grain DEM scene of 0.02 s with a snapshot every 0.01 s into `snap`.
fn small_dem_sets(snap: &Path) -> Vec<String> {
    vec![
        "--set".into(),
        "run.duration=0.02".into(),
        "--set".into(),
        "damper.count=40".into(),
        "--set".into(),
        "damper.snapshot_interval=0.01".into(),
        "--set".into(),
        format!("damper.snapshot_dir=\"{}\"", snap.display()),
    ]
}

#[test]
fn simulate_writes_snapshots_into_the_absolute_dir_as_given() {
    let dir = scratch::tempdir().unwrap();
    let snap = dir.path().join("my_snaps");
    let out = dir.path().join("run");
    let sets = small_dem_sets(&snap);
    let mut args = vec!["simulate", "data/scenes/thesis_b_soft.toml"];
    args.extend(sets.iter().map(String::as_str));
    args.push("--out");
    let o = pdamp(&args, &[&out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // exactly the directory the user named: not `my_snaps/run/`
    assert!(snap.join("grains_000000.vtp").is_file());
    assert!(snap.join("grains.pvd").is_file());
    assert!(!snap.join("run").exists());
}

#[test]
fn sweep_points_with_an_absolute_snapshot_dir_never_share_files() {
    let dir = scratch::tempdir().unwrap();
    let snap = dir.path().join("snaps");
    let out = dir.path().join("sw");
    let sets = small_dem_sets(&snap);
    let mut args = vec![
        "sweep",
        "data/scenes/thesis_b_soft.toml",
        "--vary",
        "excitation.frequency=14,16",
    ];
    args.extend(sets.iter().map(String::as_str));
    args.push("--out");
    let o = pdamp(&args, &[&out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for point in ["0", "1"] {
        let pvd = snap.join(point).join("grains.pvd");
        assert!(pvd.is_file(), "{}", pvd.display());
        assert!(snap.join(point).join("grains_000002.vtp").is_file());
    }
}

#[test]
fn a_sweep_whose_points_fail_exits_1_and_names_the_count() {
    let dir = scratch::tempdir().unwrap();
    // a snapshot directory that cannot be created: every point fails on output
    let sets = small_dem_sets(Path::new("/proc/pdamp-cannot-write-here"));
    let out = dir.path().join("sw");
    let mut args = vec![
        "sweep",
        "data/scenes/thesis_b_soft.toml",
        "--vary",
        "excitation.frequency=14,16",
    ];
    args.extend(sets.iter().map(String::as_str));
    args.push("--out");
    let o = pdamp(&args, &[&out]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("2 of 2 sweep points failed"), "{err}");
    assert!(
        err.contains("point 0:") && err.contains("point 1:"),
        "{err}"
    );
}

#[test]
fn an_infinite_contact_time_is_refused_naming_the_keys() {
    // E = 2.5e-324 Pa (parses as the smallest subnormal): t_s ∝ E^(-2/5) overflows to inf
    let dir = scratch::tempdir().unwrap();
    let o = pdamp(
        &[
            "simulate",
            "data/scenes/thesis_b_soft.toml",
            "--set",
            "damper.youngs_modulus=2.5e-324",
            "--out",
        ],
        &[&dir.path().join("o")],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "input error expected: {err}");
    assert!(
        err.contains("damper.youngs_modulus") && err.contains("contact time"),
        "{err}"
    );
    assert!(!dir.path().join("o").join("series.csv").exists());
    // check-scene refuses it the same way
    let scene = dir.path().join("s.toml");
    let text = std::fs::read_to_string("data/scenes/thesis_b_soft.toml").unwrap();
    let text = text.replace("youngs_modulus = 2.03e8", "youngs_modulus = 2.5e-324");
    assert!(text.contains("2.5e-324"));
    std::fs::write(&scene, text).unwrap();
    let o = pdamp(&["check-scene"], &[&scene]);
    assert_eq!(o.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&o.stderr).contains("contact time"));
}

#[test]
fn quiet_and_verbose_change_only_what_goes_to_stderr() {
    let dir = scratch::tempdir().unwrap();
    let run = |flag: Option<&str>, out: &str| {
        let mut args: Vec<&str> = flag.into_iter().collect();
        args.extend([
            "simulate",
            "data/scenes/thesis_b_impact.toml",
            "--set",
            "run.duration=1",
            "--out",
        ]);
        pdamp(&args, &[&dir.path().join(out)])
    };
    let normal = run(None, "n");
    let quiet = run(Some("-q"), "q");
    let verbose = run(Some("-v"), "v");
    for o in [&normal, &quiet, &verbose] {
        assert!(o.status.success());
    }
    let err = |o: &Output| String::from_utf8_lossy(&o.stderr).to_string();
    assert!(err(&normal).contains("plan: dt ="), "{}", err(&normal));
    assert!(!err(&quiet).contains("plan:"), "{}", err(&quiet));
    assert!(err(&verbose).contains("[pdamp::setup::resolve] resolved event-driven scene"));
    // the results on stdout and in the files are the same whatever the level
    let results = |o: &Output| {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .filter(|l| !l.starts_with("wrote "))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    assert!(!results(&normal).is_empty());
    assert_eq!(results(&normal), results(&quiet));
    assert_eq!(results(&normal), results(&verbose));
    let series = |d: &str| std::fs::read(dir.path().join(d).join("series.csv")).unwrap();
    assert_eq!(series("n"), series("q"));
    assert_eq!(series("n"), series("v"));
}

#[test]
fn completions_and_man_pages_cover_every_subcommand() {
    let o = pdamp(&["completions", "bash"], &[]);
    assert!(o.status.success());
    let script = String::from_utf8_lossy(&o.stdout);
    for sub in ["simulate", "sweep", "lyap-k", "check-scene", "completions"] {
        assert!(script.contains(sub), "{sub}");
    }
    let dir = scratch::tempdir().unwrap();
    let o = pdamp(&["man", "-o"], &[dir.path()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(dir.path().join("pdamp-simulate.1")).unwrap();
    assert!(page.contains(".TH pdamp-simulate") && page.contains("\\-\\-out"));
    assert!(dir.path().join("pdamp.1").is_file());
}

#[test]
fn fit_frf_refuses_a_force_driven_sweep() {
    // the base-drive form (2.1.21) would misread a force drive's response (issue 41)
    let dir = scratch::tempdir().unwrap();
    let csv = dir.path().join("sweep.csv");
    std::fs::write(
        &csv,
        "point,excitation.frequency,frequency_hz,amplitude_m\n0,5,5,0.001\n1,6,6,0.002\n2,7,7,0.001\n",
    )
    .unwrap();
    let spec = |kind: &str| {
        serde_json::json!({
            "scene": format!("[primary]\nmass = 1.0\nstiffness = 1000.0\ndamping = 1.0\n\
                              [excitation]\nkind = \"{kind}\"\nforce_amplitude = 1.0\nfrequency = 5.0\n\
                              [damper]\nkind = \"none\"\n[run]\nperiods = 10\n"),
            "set": [],
            "vary": [],
            "analysis": false,
        })
        .to_string()
    };
    std::fs::write(dir.path().join("sweep.json"), spec("force")).unwrap();
    let args = [
        "fit-frf",
        "--stiffness",
        "1000",
        "--base-amplitude",
        "0.001",
    ];
    let out = pdamp(&args, &[&csv]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("excitation.kind = \"force\""),
        "{err}"
    );
    // the same table from a base drive is fitted
    std::fs::write(dir.path().join("sweep.json"), spec("base")).unwrap();
    let out = pdamp(&args, &[&csv]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("excitation.kind"), "{err}");
}
