//! Resumable sweeps: interrupting a sweep (killed process, lost point files) and rerunning it
//! skips the finished points and produces byte-identical final files.

mod scratch;

use std::path::Path;
use std::process::Command;

const SCENE: &str = r#"
[primary]
mass = 2.37
stiffness = 21500.0
damping = 7.6
[excitation]
amplitude = 0.0045
frequency = 15.0
[damper]
kind = "impact"
mass = 0.227
gap = 0.0835
restitution = 0.3
[run]
periods = 60
"#;

fn sweep(scene: &Path, out: &Path, threads: &str, vary: &str) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args([
            "sweep",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--no-analysis",
            "--vary",
            vary,
        ])
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .unwrap()
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

const VARY: &str = "excitation.frequency=2:30:2";

#[test]
fn lost_points_are_recomputed_and_files_are_identical() {
    let dir = scratch::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let out = dir.path().join("out");
    assert!(sweep(&scene, &out, "2", VARY).status.success());
    let csv = read(&out.join("sweep.csv"));
    let strobe = read(&out.join("strobe.csv"));
    assert_eq!(String::from_utf8_lossy(&csv).lines().count(), 15 + 1);

    // simulate an interruption: some points lost, the CSVs half-written, a stray temp file
    for i in [0, 3, 4, 14] {
        std::fs::remove_file(out.join(format!("points/{i}.json"))).unwrap();
    }
    std::fs::write(out.join("sweep.csv"), &csv[..csv.len() / 2]).unwrap();
    std::fs::remove_file(out.join("strobe.csv")).unwrap();
    std::fs::write(out.join("points/7.json.tmp999"), b"{garbage").unwrap();
    let again = sweep(&scene, &out, "1", VARY);
    assert!(again.status.success());
    let msg = String::from_utf8_lossy(&again.stdout);
    assert!(
        msg.contains("4 computed") && msg.contains("11 already done"),
        "{msg}"
    );
    assert_eq!(read(&out.join("sweep.csv")), csv);
    assert_eq!(read(&out.join("strobe.csv")), strobe);

    // a complete sweep reruns as a no-op
    let msg = String::from_utf8_lossy(&sweep(&scene, &out, "2", VARY).stdout).into_owned();
    assert!(
        msg.contains("0 computed") && msg.contains("15 already done"),
        "{msg}"
    );

    // a different sweep into the same directory is refused instead of mixing results
    let other = sweep(&scene, &out, "2", "excitation.frequency=2:30:4");
    assert!(!other.status.success());
    assert!(String::from_utf8_lossy(&other.stderr).contains("different sweep"));
}

#[test]
fn killed_sweep_resumes_to_the_same_files() {
    let dir = scratch::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, SCENE.replace("periods = 60", "periods = 400")).unwrap();
    let reference = dir.path().join("ref");
    assert!(sweep(&scene, &reference, "2", VARY).status.success());

    let out = dir.path().join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args([
            "sweep",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--no-analysis",
            "--vary",
            VARY,
        ])
        .env("RAYON_NUM_THREADS", "1")
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // kill once a few points are done (or when it has finished anyway)
    let t0 = std::time::Instant::now();
    loop {
        let done = std::fs::read_dir(out.join("points"))
            .map(|d| d.count())
            .unwrap_or(0);
        if done >= 3 || t0.elapsed().as_secs() > 60 || child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let _ = child.kill();
    let _ = child.wait();
    assert!(sweep(&scene, &out, "2", VARY).status.success());
    assert_eq!(
        read(&out.join("sweep.csv")),
        read(&reference.join("sweep.csv"))
    );
    assert_eq!(
        read(&out.join("strobe.csv")),
        read(&reference.join("strobe.csv"))
    );
}

#[test]
fn points_of_another_physics_revision_are_not_mixed_in() {
    let dir = scratch::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(&scene, SCENE).unwrap();
    let out = dir.path().join("out");
    let vary = "excitation.frequency=2:6:2";
    assert!(sweep(&scene, &out, "2", vary).status.success());
    // each point says which physics made it
    let p1 = out.join("points/1.json");
    let text = String::from_utf8(read(&p1)).unwrap();
    let revision = format!("\"physics\": {}", pdamp::model::PHYSICS_REVISION);
    assert!(text.contains(&revision), "{text}");
    // one point from a binary with other physics, and another lost: the resume refuses
    std::fs::write(&p1, text.replace(&revision, "\"physics\": 999")).unwrap();
    std::fs::remove_file(out.join("points/2.json")).unwrap();
    let again = sweep(&scene, &out, "2", vary);
    assert!(!again.status.success());
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        err.contains("physics revision 999") && err.contains("points/1.json"),
        "{err}"
    );
    assert!(!out.join("points/2.json").exists(), "nothing computed");
}

/// A stop asked for from another thread (the Python binding's Ctrl-C,
/// `pdamp::sweep::stop::request`) ends a running sweep within a forcing period of each
/// running point: the points report `interrupted`, none is written, and a rerun computes
/// them.
#[test]
fn a_stop_request_ends_a_running_sweep_and_leaves_no_point() {
    use pdamp::scene::SceneSource;
    use pdamp::sweep::{run_sweep, stop, SweepSpec, Vary};

    let dir = scratch::tempdir().unwrap();
    let out = dir.path().join("out");
    // four points of 2 000 000 periods: ~7 s each on one core
    let spec = SweepSpec {
        base: SceneSource::parse(&SCENE.replace("periods = 60", "periods = 2000000")).unwrap(),
        set: Vec::new(),
        varies: vec![Vary::parse("excitation.frequency=10,12,14,16").unwrap()],
        analyze: false,
    };
    let t0 = std::time::Instant::now();
    let report = std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(std::time::Duration::from_millis(300));
            stop::request();
        });
        run_sweep(&spec, &out, &|_| {}).unwrap()
    });
    let took = t0.elapsed().as_secs_f64();
    assert!(took < 5.0, "the sweep ran {took} s after the stop");
    assert_eq!(report.failed.len(), 4, "{:?}", report.failed);
    assert!(report
        .failed
        .iter()
        .all(|(_, why)| why.starts_with("interrupted")));
    let written = std::fs::read_dir(out.join("points"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "json"))
        })
        .count();
    assert_eq!(written, 0);
    // the next sweep clears the request and runs (one short point)
    let spec = SweepSpec {
        base: SceneSource::parse(SCENE).unwrap(),
        varies: vec![Vary::parse("excitation.frequency=10").unwrap()],
        ..spec
    };
    let again = run_sweep(&spec, &dir.path().join("again"), &|_| {}).unwrap();
    assert_eq!((again.computed, again.failed.len()), (1, 0));
}
