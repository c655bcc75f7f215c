//! The DEM two-replica test (issue 9, item 2; `pdamp::dem::replica`) on the softened scene B
//! (`data/scenes/thesis_b_soft.toml`, 250 grains), with shortened runs:
//! (a) through `pdamp simulate --set run.replica=1e-9` (`replica.csv`, the `replica` block of
//!     `summary.json`) replica A is the run itself (its columns equal `strobe.csv`), and a
//!     perturbation that is zero, not finite or not below the grain radius is refused;
//! (b) with δ0 = 1e-9 m applied just before a strobe, the first strobed separation is of
//!     order δ0;
//! (c) at 14.5 Hz — period-1 collective motion with granular noise (issue 9: one tight cluster,
//!     sd 0.35 mm) — the micro-states decorrelate (the replicas are sensitive), yet they
//!     separate only to the size of the cluster: a few per cent of the orbit.
//! Run in release: `cargo test --release --test dem_replica`.

mod scratch;

use pdamp::dem::replica::{run_replica, ReplicaOptions, ReplicaOutcome};
use pdamp::dem::DemSample;
use pdamp::model::RunOptions;
use pdamp::observe::NullObserver;
use pdamp::scene::run::ReplicaChoice;
use pdamp::scene::{parse_assignment, Scene, SceneSource};
use std::process::Command;

const SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/scenes/thesis_b_soft.toml"
);

fn scene(set: &[&str]) -> Scene {
    let src = SceneSource::parse(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    let ov: Vec<_> = set.iter().map(|a| parse_assignment(a).unwrap()).collect();
    src.scene(&ov).unwrap()
}

fn csv_rows(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (head, rows)
}

#[test]
fn scene_key_run_replica() {
    assert_eq!(scene(&[]).run.replica, ReplicaChoice::WithVerdict);
    assert_eq!(
        scene(&["run.replica=true"]).run.replica,
        ReplicaChoice::Delta(1e-9)
    );
    assert_eq!(
        scene(&["run.replica=false"]).run.replica,
        ReplicaChoice::Off
    );
    assert_eq!(
        scene(&["run.replica=2e-8"]).run.replica,
        ReplicaChoice::Delta(2e-8)
    );
    // by default it runs exactly where a verdict is asked for
    assert_eq!(ReplicaChoice::WithVerdict.delta_m(true), Some(1e-9));
    assert_eq!(ReplicaChoice::WithVerdict.delta_m(false), None);
    assert_eq!(ReplicaChoice::Off.delta_m(true), None);
    let src = SceneSource::parse(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    for bad in [
        "run.replica=-1e-9",
        "run.replica=0.01",
        "run.replica=0",
        "run.replica=nan",
    ] {
        let err = src.scene(&[parse_assignment(bad).unwrap()]).unwrap_err();
        assert!(err.to_string().contains("run.replica"), "{err}");
    }
    // larger than the grains (3 mm spheres): refused naming the radius
    let ov = [
        parse_assignment("run.replica=5e-4").unwrap(),
        parse_assignment("damper.radius=4e-4").unwrap(),
    ];
    let err = src.scene(&ov).unwrap_err().to_string();
    assert!(
        err.contains("run.replica")
            && err.contains("smallest grain radius")
            && err.contains("4e-4"),
        "{err}"
    );
    // DEM only
    let impact = "[primary]\nmass = 2.37\nstiffness = 21500.0\ndamping = 7.6\n[excitation]\n\
                  amplitude = 0.0045\nfrequency = 15.0\n[damper]\nkind = \"impact\"\nmass = 0.227\n\
                  gap = 0.0835\nrestitution = 0.0\n[run]\nduration = 1.0\nreplica = true\n";
    let err = Scene::from_toml(impact).unwrap_err().to_string();
    assert!(err.contains("run.replica"), "{err}");
    // the resolved scene keeps the key
    let s = scene(&["run.replica=true"]);
    assert_eq!(Scene::from_toml(&s.to_toml().unwrap()).unwrap(), s);
    let s = scene(&["run.replica=false"]);
    assert_eq!(Scene::from_toml(&s.to_toml().unwrap()).unwrap(), s);
    let s = scene(&[]);
    assert_eq!(Scene::from_toml(&s.to_toml().unwrap()).unwrap(), s);
}

#[test]
fn a_perturbation_beyond_the_grain_radius_is_refused_by_the_engine() {
    // a scene refuses δ0 ≥ the smallest radius (`scene_key_run_replica`); the engine, called
    // directly with 0.5 mm grains and δ0 = 0.8 mm, refuses it too
    let s = scene(&["damper.radius=0.0005", "damper.count=20"]);
    let setup = s.resolve_dem().unwrap();
    let (drive, cfg) = (setup.drive, setup.config(&RunOptions::summary_only()));
    let opts = ReplicaOptions {
        delta_m: 8e-4,
        perturb_at_s: 0.1,
    };
    let err = run_replica(
        &setup.model,
        drive,
        &cfg,
        setup.time_step,
        &opts,
        &mut Vec::<DemSample>::new(),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("smallest grain radius"), "{err}");
}

/// `pdamp simulate` of the softened scene at 14.5 Hz for 0.8 s into `dir`, with `extra`
/// arguments; panics unless it succeeds.
fn simulate_short(dir: &std::path::Path, extra: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", SCENE, "--out", dir.to_str().unwrap()])
        .args([
            "--set",
            "excitation.frequency=14.5",
            "--set",
            "run.duration=0.8",
        ])
        .args(["--set", "run.sample_interval=1e-3"])
        .args(extra)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn replica_a_is_the_run_through_simulate() {
    let dir = scratch::tempdir().unwrap();
    simulate_short(dir.path(), &["--no-analysis", "--set", "run.replica=1e-9"]);
    let (head, rows) = csv_rows(&std::fs::read_to_string(dir.path().join("replica.csv")).unwrap());
    assert_eq!(
        head,
        [
            "cycle",
            "time_s",
            "grain_z_a_m",
            "grain_z_b_m",
            "grain_v_a_m_s",
            "grain_v_b_m_s",
            "box_z_a_m",
            "box_z_b_m",
            "box_v_a_m_s",
            "box_v_b_m_s",
            "separation_rel"
        ]
    );
    // perturbed at 0.4 s: strobes 6 … 11 of T = 1/14.5 s
    assert!(rows.len() >= 5, "{rows:?}");
    // replica A is the run: its strobes are strobe.csv's, digit for digit, on every axis
    let (sh, strobe) = csv_rows(&std::fs::read_to_string(dir.path().join("strobe.csv")).unwrap());
    let col = |name: &str| sh.iter().position(|c| c == name).unwrap();
    for r in &rows {
        let s = strobe
            .iter()
            .find(|s| s[0] == r[0])
            .expect("cycle in strobe.csv");
        for (a, name) in [
            (2, "grain_z_m"),
            (4, "grain_v_m_s"),
            (6, "box_z_m"),
            (8, "box_v_m_s"),
        ] {
            assert_eq!(s[col(name)], r[a], "cycle {} {name}", r[0]);
        }
        assert!(r[10].parse::<f64>().unwrap() >= 0.0, "{r:?}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    let rep = &summary["replica"];
    assert_eq!(rep["delta0_m"], 1e-9);
    assert_eq!(rep["strobes"], rows.len());
    for key in [
        "orbit_extent",
        "independent_separation_rel",
        "saturation_rel",
        "growth",
        "outcome",
    ] {
        assert!(
            rep.get(key).is_some(),
            "summary.json replica.{key} missing: {rep}"
        );
    }
}

#[test]
fn first_separation_is_of_order_delta0() {
    let s = scene(&["excitation.frequency=14.5", "run.duration=0.7"]);
    let setup = s.resolve_dem().unwrap();
    let (drive, cfg) = (setup.drive, setup.config(&RunOptions::summary_only()));
    // perturbed ≈ 38 time steps before the strobe t = 8 T
    let opts = ReplicaOptions {
        delta_m: 1e-9,
        perturb_at_s: 8.0 / 14.5 - 2e-4,
    };
    let (_, r) = run_replica(
        &setup.model,
        drive,
        &cfg,
        setup.time_step,
        &opts,
        &mut Vec::<DemSample>::new(),
    )
    .unwrap();
    eprintln!("{r:?}");
    assert!(r.perturbed_at_s < 8.0 / 14.5 && r.perturbed_at_s > 8.0 / 14.5 - 3e-4);
    let first = &r.rows[0];
    assert_eq!(first.cycle, 8);
    let dz = (first.a[0] - first.b[0]).abs();
    assert!(
        (0.2e-9..5e-9).contains(&dz),
        "first separation {dz} m in z_cm for δ0 = 1e-9 m"
    );
    // and it grows: the grains' micro-state is chaotic
    assert!(
        r.max_separation_rel > 100.0 * r.first_separation_rel,
        "{r:?}"
    );
}

#[test]
fn period_one_with_granular_noise_is_sensitive_only_within_its_cluster() {
    // 5 s, perturbed at 2.5 s (the analysis window): 36 strobes. The step clock (the
    // analysis window's sample interval, 2.5 s / `run.analysis_max_samples`) is pinned at
    // the 0.1 ms this trajectory was measured on: on the default 20 000 samples (0.125 ms)
    // the step is put on another clock, and on that trajectory the two replicas end in different
    // macroscopic states ("inconclusive"), a bed on the margin between its arrangements
    let s = scene(&[
        "excitation.frequency=14.5",
        "run.duration=5",
        "run.replica=true",
        "run.analysis_max_samples=25000",
    ]);
    let summary = pdamp::setup::simulate(
        &s.resolve().unwrap(),
        &mut NullObserver,
        &RunOptions::summary_only(),
    )
    .unwrap();
    let r = summary.replica.expect("replica report");
    let mut shown = r.clone();
    shown.rows.clear();
    eprintln!("{}", serde_json::to_string_pretty(&shown).unwrap());
    assert!(r.strobes >= 30, "{} strobes", r.strobes);
    // the micro-states decorrelate: the replicas end as independent draws of the cluster
    let ReplicaOutcome::Sensitive {
        saturation_rel_orbit,
    } = r.outcome
    else {
        panic!("{}", r.describe());
    };
    // … which is small against the orbit (issue 9 measured sd 0.35 mm on a 2.9 cm orbit)
    assert!(
        (1e-3..0.05).contains(&saturation_rel_orbit),
        "{}",
        r.describe()
    );
}

#[test]
fn the_test_runs_by_default_wherever_a_verdict_is_asked_for() {
    let run = |extra: &[&str]| {
        let dir = scratch::tempdir().unwrap();
        simulate_short(dir.path(), extra);
        let summary: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("summary.json")).unwrap(),
        )
        .unwrap();
        (
            dir.path().join("replica.csv").exists(),
            summary.get("replica").is_some_and(|r| !r.is_null()),
        )
    };
    // analysed (the default): the verdict's replica test ran
    assert_eq!(run(&[]), (true, true));
    // no verdict asked for: no replica; turned off: none either
    assert_eq!(run(&["--no-analysis"]), (false, false));
    assert_eq!(run(&["--set", "run.replica=false"]), (false, false));
}
