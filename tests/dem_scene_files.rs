//! The DEM scene files under data/scenes parse into the presets they claim to be
//! (`DemParams::thesis_b()`, `DemParams::thesis_b_softened(1000.0)`), and `pdamp simulate`
//! runs a short DEM scene end to end, writing the contract's columns and summary keys.

mod scratch;

use pdamp::scene::dem::DemParams;
use pdamp::scene::{Damper, Scene};

fn dem_of(path: &str) -> (Scene, DemParams) {
    let text = std::fs::read_to_string(path).unwrap();
    let scene = Scene::from_toml(&text).unwrap();
    let Damper::Dem(d) = scene.damper.clone() else {
        panic!("{path}: not a DEM scene")
    };
    (scene, d)
}

#[test]
fn scene_files_match_presets() {
    let (scene, d) = dem_of("data/scenes/thesis_b.toml");
    assert_eq!(d, DemParams::thesis_b());
    let p = scene.primary.unwrap();
    assert_eq!(
        (p.mass, p.stiffness, p.damping_n_s_m()),
        (2.37, 21500.0, 7.6)
    );
    assert_eq!(
        (scene.excitation.amplitude, scene.excitation.frequency),
        (0.0045, 15.0)
    );
    let (_, s) = dem_of("data/scenes/thesis_b_soft.toml");
    let want = DemParams::thesis_b_softened(1000.0);
    // γ printed with 10 significant digits in the file
    assert!(
        (s.gamma_n / want.gamma_n - 1.0).abs() < 1e-9
            && (s.gamma_s / want.gamma_s - 1.0).abs() < 1e-9
    );
    assert_eq!(
        DemParams {
            gamma_n: want.gamma_n,
            gamma_s: want.gamma_s,
            ..s
        },
        want
    );
}

#[test]
fn simulate_cli_writes_dem_series_and_summary() {
    let dir = scratch::tempdir().unwrap();
    let out = dir.path().join("b");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", "data/scenes/thesis_b_soft.toml", "--out"])
        .arg(&out)
        .args([
            "--set",
            "run.duration=0.05",
            "--set",
            "damper.count=60",
            "--set",
            "run.sample_interval=1e-3",
        ])
        .status()
        .unwrap();
    assert!(st.success());
    let csv = std::fs::read_to_string(out.join("series.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.starts_with("time_s,base_u_m,box_z_m,box_v_m_s,floor_z_m,ceiling_z_m,grain_z_m,grain_zmin_m,grain_zmax_m,e_collision_j"), "{header}");
    assert!(header.ends_with("grain_force_n"));
    assert_eq!(csv.lines().count(), 1 + 51, "samples at 0, 1 ms, …, 50 ms");
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    for k in [
        "amplitude_m",
        "energy_balance_relative_error",
        "energy_collision_j_per_cycle",
        "energy_friction_j_per_cycle",
        "energy_viscous_j_per_cycle",
        "steps",
        "wall_time_s",
        "particle_steps_per_s",
    ] {
        assert!(
            js.get(k).is_some_and(|v| v.is_number()),
            "summary.json lacks {k}"
        );
    }
    assert!(js["energy_balance_relative_error"].as_f64().unwrap() < 0.01);
}

/// `pdamp check-scene` prints the time step `pdamp simulate` then runs, to the last bit (the
/// automatic step put on the sample clock; issue 40).
#[test]
fn check_scene_prints_the_time_step_the_run_takes() {
    let dir = scratch::tempdir().unwrap();
    let out = dir.path().join("o");
    let set = [
        "--set",
        "run.duration=0.01",
        "--set",
        "damper.count=30",
        "--set",
        "run.sample_interval=1e-3",
    ];
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["check-scene", "data/scenes/thesis_b_soft.toml"])
        .args(set)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    let printed: f64 = text
        .split("dt = ")
        .find_map(|s| s.split(" s,").next()?.parse().ok())
        .unwrap_or_else(|| panic!("no dt in {text}"));
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", "data/scenes/thesis_b_soft.toml", "--out"])
        .arg(&out)
        .args(set)
        .status()
        .unwrap();
    assert!(st.success());
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let run = js["dt_s"].as_f64().unwrap();
    assert_eq!(
        printed.to_bits(),
        run.to_bits(),
        "check-scene {printed:e}, run {run:e}"
    );
}

#[test]
fn explicit_dt_above_the_limit_is_a_scene_error() {
    let text = std::fs::read_to_string("data/scenes/thesis_b.toml").unwrap();
    let dir = scratch::tempdir().unwrap();
    let f = dir.path().join("s.toml");
    std::fs::write(&f, text.replace("dt = \"auto\"", "dt = 1e-5")).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate"])
        .arg(&f)
        .arg("--out")
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("run.dt") && err.contains("t_s/20"), "{err}");
}

#[test]
fn snapshots_are_written_as_csv_and_vtk_xml() {
    let dir = scratch::tempdir().unwrap();
    // the default `damper.snapshot_dir` is `snapshots` under the run's output directory
    let snaps = dir.path().join("o").join("snapshots");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args(["simulate", "data/scenes/thesis_b_soft.toml", "--out"])
        .arg(dir.path().join("o"))
        .args([
            "--set",
            "run.duration=0.02",
            "--set",
            "damper.count=40",
            "--set",
            "damper.snapshot_interval=0.01",
        ])
        .status()
        .unwrap();
    assert!(st.success());
    // t = 0, 0.01, 0.02 s → three snapshots of each kind
    for k in 0..3 {
        let csv = std::fs::read_to_string(snaps.join(format!("grains_{k:06}.csv"))).unwrap();
        assert_eq!(csv.lines().count(), 41, "header + 40 grains");
        let vtp = std::fs::read_to_string(snaps.join(format!("grains_{k:06}.vtp"))).unwrap();
        assert!(
            vtp.contains("<VTKFile type=\"PolyData\"") && vtp.contains("NumberOfPoints=\"40\"")
        );
        for array in ["id", "radius", "velocity", "angular_velocity", "force"] {
            assert!(vtp.contains(&format!("Name=\"{array}\"")), "{array}");
        }
        let vbox = std::fs::read_to_string(snaps.join(format!("box_{k:06}.vtp"))).unwrap();
        assert!(vbox.contains("NumberOfPoints=\"8\"") && vbox.contains("NumberOfPolys=\"6\""));
    }
    // the time series lists the three snapshots with their times
    for part in ["grains", "box"] {
        let pvd = std::fs::read_to_string(snaps.join(format!("{part}.pvd"))).unwrap();
        assert_eq!(pvd.matches("<DataSet ").count(), 3, "{part}");
        assert!(
            pvd.contains(&format!("file=\"{part}_000002.vtp\"")),
            "{part}"
        );
    }
}

/// `damper.radius = 3e-5` (issue 12, bad input): one check, the memory estimate, decides. With
/// the lattice, 250 such grains need ~0.5 MB (the cell list is O(N), not a grid over the box)
/// and the scene resolves; with the advancing front, the packer's grid over the box (7.7e8
/// cells) is refused naming damper.radius and the estimate in GB.
#[test]
fn tiny_grains_are_judged_by_the_memory_estimate() {
    let text = std::fs::read_to_string("data/scenes/thesis_b_soft.toml").unwrap();
    let tiny = text.replace("radius = 0.003 ", "radius = 3e-5 ");
    assert_ne!(tiny, text);
    let scene = Scene::from_toml(&tiny).unwrap();
    scene.resolve().expect("250 grains of 3e-5 m fit in memory");
    let af = tiny.replace(
        "contact = \"hertz-kk\"",
        "contact = \"hertz-kk\"\npacking = \"advancing-front\"",
    );
    let e = Scene::from_toml(&af)
        .unwrap()
        .resolve()
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("damper.radius = 3e-5 m") && e.contains("18.4 GB") && !e.contains("damper.box"),
        "{e}"
    );
}
