//! Bad scenes and arguments give clear errors naming the key (library and CLI binary).

mod scratch;

use pdamp::scene::{Scene, SceneSource};
use pdamp::sweep::Vary;
use std::process::Command;

const GOOD: &str = r#"
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
restitution = 0.0
[run]
duration = 1.0
"#;

/// The error message for GOOD with `from` replaced by `to`.
fn err_with(from: &str, to: &str) -> String {
    assert!(GOOD.contains(from), "test bug: {from}");
    let text = GOOD.replacen(from, to, 1);
    Scene::from_toml(&text)
        .expect_err(&format!("{to} should be rejected"))
        .to_string()
}

#[test]
fn the_good_scene_is_accepted() {
    Scene::from_toml(GOOD).unwrap();
}

#[test]
fn unknown_keys_are_named() {
    for (from, to, key) in [
        ("mass = 2.37", "mass = 2.37\nmas = 1.0", "mas"),
        ("gap = 0.0835", "gap = 0.0835\ngapp = 1.0", "gapp"),
        ("duration = 1.0", "duration = 1.0\nsteady = 0.2", "steady"),
        ("frequency = 15.0", "frequency = 15.0\nphase = 0.3", "phase"),
        ("[primary]", "gravty = 9.8\n[primary]", "gravty"),
        ("kind = \"impact\"", "kind = \"dampr\"", "dampr"),
        (
            "kind = \"impact\"",
            "kind = \"none\"",
            "takes no parameters",
        ),
    ] {
        let err = err_with(from, to);
        assert!(err.contains(key), "{key}: {err}");
    }
}

#[test]
fn missing_keys_are_named() {
    for (from, key) in [
        ("frequency = 15.0", "frequency"),
        ("stiffness = 21500.0", "stiffness"),
        ("restitution = 0.0", "restitution"),
        ("damping = 7.6", "primary.damping"),
        ("duration = 1.0", "run.duration"),
        (
            "[excitation]\namplitude = 0.0045\nfrequency = 15.0",
            "excitation",
        ),
    ] {
        let err = err_with(from, "");
        assert!(err.contains(key), "{key}: {err}");
    }
}

#[test]
fn impossible_values_are_named_with_the_fix() {
    for (from, to, key) in [
        ("mass = 2.37", "mass = -2.37", "primary.mass"),
        ("mass = 0.227", "mass = -0.2", "damper.mass"),
        ("gap = 0.0835", "gap = -0.01", "damper.gap"),
        ("gap = 0.0835", "gap = nan", "damper.gap"),
        (
            "restitution = 0.0",
            "restitution = 1.5",
            "damper.restitution",
        ),
        (
            "restitution = 0.0",
            "restitution = -0.1",
            "damper.restitution",
        ),
        (
            "restitution = 0.0",
            "restitution = nan",
            "damper.restitution",
        ),
        (
            "frequency = 15.0",
            "frequency = 0.0",
            "excitation.frequency",
        ),
        (
            "frequency = 15.0",
            "frequency = -3.0",
            "excitation.frequency",
        ),
        (
            "frequency = 15.0",
            "frequency = nan",
            "excitation.frequency",
        ),
        (
            "frequency = 15.0",
            "frequency = inf",
            "excitation.frequency",
        ),
        (
            "stiffness = 21500.0",
            "stiffness = nan",
            "primary.stiffness",
        ),
        ("damping = 7.6", "damping = -1.0", "primary.damping"),
        (
            "damping = 7.6",
            "damping = 7.6\ndamping_ratio = 0.1",
            "primary.damping_ratio",
        ),
        (
            "amplitude = 0.0045",
            "amplitude = -0.001",
            "excitation.amplitude",
        ),
        ("duration = 1.0", "duration = 0.0", "run.duration"),
        (
            "duration = 1.0",
            "duration = 1.0\nsteady_fraction = 1.5",
            "run.steady_fraction",
        ),
        (
            "duration = 1.0",
            "duration = 1.0\nsample_interval = -1e-4",
            "run.sample_interval",
        ),
        ("duration = 1.0", "duration = 1.0\ndt = \"fast\"", "run.dt"),
        ("duration = 1.0", "duration = 1.0\ndt = -1e-6", "run.dt"),
    ] {
        let err = err_with(from, to);
        assert!(err.contains(key), "{key}: {err}");
    }
    // a negative value's message says what is allowed
    let err = err_with("mass = 2.37", "mass = -2.37");
    assert!(err.contains("> 0") && err.contains("kg"), "{err}");
}

#[test]
fn wrong_types_and_syntax() {
    let err = err_with("mass = 2.37", "mass = \"heavy\"");
    assert!(err.contains("mass"), "{err}");
    assert!(Scene::from_toml("[primary\nmass = 1").is_err());
}

#[test]
fn dt_accepts_auto_and_seconds() {
    let s =
        Scene::from_toml(&GOOD.replace("duration = 1.0", "duration = 1.0\ndt = \"auto\"")).unwrap();
    assert_eq!(s.run.dt, Some(pdamp::scene::DtSpec::Auto));
    let s = Scene::from_toml(&GOOD.replace("duration = 1.0", "duration = 1.0\ndt = 1e-6")).unwrap();
    assert_eq!(s.run.dt, Some(pdamp::scene::DtSpec::Seconds(1e-6)));
}

#[test]
fn overrides_are_checked_like_the_file() {
    let src = SceneSource::parse(GOOD).unwrap();
    let set = |kv: &str| pdamp::scene::parse_assignment(kv).unwrap();
    let err = src
        .scene(&[set("damper.restitution=2")])
        .unwrap_err()
        .to_string();
    assert!(err.contains("damper.restitution"), "{err}");
    let err = src
        .scene(&[set("excitation.frequncy=2")])
        .unwrap_err()
        .to_string();
    assert!(err.contains("frequncy"), "{err}");
    // switching the damper off through an override drops its parameters
    let s = src.scene(&[set("damper.kind=none")]).unwrap();
    assert_eq!(s.damper, pdamp::scene::Damper::None);
    let err = src
        .scene(&[set("excitation.frequency.x=2")])
        .unwrap_err()
        .to_string();
    assert!(err.contains("excitation.frequency"), "{err}");
}

#[test]
fn empty_vary_ranges_are_named() {
    for bad in [
        "excitation.frequency=30:0.5:0.1",
        "excitation.frequency=1:2:0",
        "excitation.frequency=",
        "excitation.frequency=1:nan:1",
    ] {
        let err = Vary::parse(bad).unwrap_err().to_string();
        assert!(err.contains("excitation.frequency"), "{bad}: {err}");
    }
}

fn pdamp(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn cli_reports_the_key() {
    let dir = scratch::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, GOOD.replace("gap = 0.0835", "gap = 0.0835\ngapp = 2")).unwrap();
    let good = dir.path().join("good.toml");
    std::fs::write(&good, GOOD).unwrap();
    let out = dir.path().join("out");
    let (ok, err) = pdamp(&["check-scene", bad.to_str().unwrap()]);
    assert!(!ok && err.contains("gapp"), "{err}");
    let (ok, err) = pdamp(&[
        "simulate",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--set",
        "damper.gap=-1",
    ]);
    assert!(!ok && err.contains("damper.gap"), "{err}");
    let (ok, err) = pdamp(&[
        "sweep",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.frequency=5:1:1",
    ]);
    assert!(
        !ok && err.contains("excitation.frequency") && err.contains("empty"),
        "{err}"
    );
    let (ok, err) = pdamp(&[
        "sweep",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "damper.restitution=0:2:0.5",
    ]);
    assert!(!ok && err.contains("damper.restitution"), "{err}");
    let (ok, err) = pdamp(&[
        "check-scene",
        dir.path().join("missing.toml").to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("missing.toml"), "{err}");
    let (ok, _) = pdamp(&["check-scene", good.to_str().unwrap()]);
    assert!(ok);
}

/// A run whose own estimate exceeds 24 h on one core is refused before it starts, naming the
/// estimate and `--max-runtime` (issue 40): scene B's bed with a radius given in the wrong unit
/// (30 µm) plans days at a tiny step; a short run given a tiny limit is refused the same way.
#[test]
fn a_run_too_long_to_be_meant_is_asked_for() {
    let dir = scratch::tempdir().unwrap();
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_soft.toml"
    );
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    let (ok, err) = pdamp(&["simulate", scene, "--out", o, "--set", "damper.radius=3e-5"]);
    assert!(
        !ok && err.contains("--max-runtime") && err.contains("estimated at"),
        "{err}"
    );
    assert!(!out.exists(), "a refused run wrote {}", out.display());
    let (ok, err) = pdamp(&[
        "sweep",
        scene,
        "--out",
        o,
        "--set",
        "damper.radius=3e-5",
        "--vary",
        "excitation.frequency=14,15",
    ]);
    assert!(
        !ok && err.contains("--max-runtime") && err.contains("the sweep"),
        "{err}"
    );
    assert!(!out.exists(), "a refused sweep wrote {}", out.display());
    // the flag sets the limit: a short impact run refused below its estimate, run above it
    let good = dir.path().join("good.toml");
    std::fs::write(&good, GOOD).unwrap();
    let g = good.to_str().unwrap();
    let (ok, err) = pdamp(&["simulate", g, "--out", o, "--max-runtime", "1e-9s"]);
    assert!(!ok && err.contains("--max-runtime"), "{err}");
    let (ok, err) = pdamp(&[
        "simulate",
        g,
        "--out",
        o,
        "--max-runtime",
        "1h",
        "--no-analysis",
    ]);
    assert!(ok, "{err}");
}

/// A DEM box without `[primary]` moves kinematically with the base (issue 4); `kind = "auto"`
/// compares against the primary's response, so without `[primary]` it is refused naming the key.
#[test]
fn kinematic_dem_is_accepted_and_auto_needs_a_primary() {
    let soft = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/thesis_b_soft.toml"
    ))
    .unwrap();
    let start = soft.find("[primary]").unwrap();
    let end = soft.find("[excitation]").unwrap();
    let kinematic = format!("{}{}", &soft[..start], &soft[end..]);
    let scene = Scene::from_toml(&kinematic).expect("kinematic DEM scene");
    assert!(scene.primary.is_none());
    let auto = kinematic.replace("kind = \"dem\"", "kind = \"auto\"");
    let err = Scene::from_toml(&auto).unwrap_err().to_string();
    assert!(err.contains("primary"), "{err}");
}
