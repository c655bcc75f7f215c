//! The drive of the primary (issue 41): a harmonic force on the mass, a free decay and a drive
//! along any axis, each against an independent reference — the receptance
//! F0/sqrt((K − MΩ²)² + (CΩ)²), an RK4 integration of M z'' + C z' + K z = F0 sin Ωt, the
//! closed-form free response of a damped oscillator, (2.1.21) for a horizontal drive of the
//! primary alone — and the bad inputs of the new keys refused by name.

use pdamp::error::SimError;
use pdamp::model::RunOptions;
use pdamp::observe::{Observer, Sample};
use pdamp::scene::{Damper, DriveKind, Primary, Scene};
use pdamp::units::TWO_PI;

mod common;

/// Collects (t, z, v) samples of the primary.
#[derive(Default)]
struct Collect(Vec<(f64, f64, f64)>);
impl Observer for Collect {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.0.push((s.time_s, s.box_z_m, s.box_v_m_s));
        Ok(())
    }
}

const M: f64 = common::SCENE_B_MASS_KG;
const K: f64 = common::SCENE_B_STIFFNESS_N_M;

fn force_scene(xi: f64, f: f64, f0: f64, duration: f64) -> Scene {
    let mut s = Scene::primary_only();
    s.primary = Some(Primary {
        damping: None,
        damping_ratio: Some(xi),
        ..Primary::new(M, K, 0.0)
    });
    s.damper = Damper::None;
    s.excitation.kind = DriveKind::Force;
    s.excitation.amplitude = 0.0;
    s.excitation.force_amplitude = Some(f0);
    s.excitation.frequency = f;
    s.run.duration = Some(duration);
    s.run.steady_fraction = 0.05;
    s.validate().unwrap();
    s
}

fn receptance(xi: f64, f: f64, f0: f64) -> f64 {
    let c = 2.0 * xi * (K * M).sqrt();
    let w = TWO_PI * f;
    f0 / ((K - M * w * w).powi(2) + (c * w).powi(2)).sqrt()
}

#[test]
fn force_drive_of_the_primary_alone_gives_the_receptance() {
    let f0n = (K / M).sqrt() / TWO_PI;
    let mut worst: f64 = 0.0;
    for &xi in &[0.005, 0.05, 0.3] {
        for &f in &[3.0, 10.0, f0n, 17.0, 40.0] {
            let decay = 14.0 / (xi * TWO_PI * f0n);
            let duration = decay.max(40.0 / f) + 2.0 / (0.05 * f);
            let scene = force_scene(xi, f, 2.5, duration);
            let s = pdamp::sweep::run_scene(
                &scene,
                &mut pdamp::observe::NullObserver,
                &RunOptions::summary_only(),
            )
            .unwrap();
            let want = receptance(xi, f, 2.5);
            let rel = (s.amplitude_m - want).abs() / want;
            worst = worst.max(rel);
            // the transient is ≤ e^{−14} of its start and the extrema are exact: a correct
            // particular solution lands at ~1e-5; a base-drive transfer (K + iCΩ)/… or a
            // missing force is off by far more
            assert!(
                rel < 1e-4,
                "xi {xi} f {f}: {} vs {want} ({rel:e})",
                s.amplitude_m
            );
            // the summary's reference is the same receptance
            let r = s.reference_amplitude_m.unwrap();
            assert!((r - want).abs() < 1e-12 * want, "{r} vs {want}");
            // the drive's work balances the viscous loss and the stored energy
            let e = s.energy_balance_relative_error.unwrap();
            assert!(e.abs() < 1e-6, "xi {xi} f {f}: balance {e:e}");
        }
    }
    eprintln!("force drive: worst relative amplitude error {worst:e}");
}

/// RK4 of M z'' + C z' + K z = F0 sin(Ωt) from (z0, v0), `n` steps of `dt`.
fn rk4_force(
    (m, k, c, f0, w): (f64, f64, f64, f64, f64),
    init: (f64, f64),
    dt: f64,
    n: usize,
) -> Vec<(f64, f64)> {
    common::rk4(
        |t, z, v| (f0 * (w * t).sin() - k * z - c * v) / m,
        init,
        dt,
        n,
    )
}

fn series_against_rk4(scene: &Scene, f0: f64) {
    let mut obs = Collect::default();
    pdamp::sweep::run_scene(scene, &mut obs, &pdamp::setup::full_series(scene)).unwrap();
    let p = scene.primary.as_ref().unwrap();
    let init = (
        p.initial_displacement.unwrap_or(0.0),
        p.initial_velocity.unwrap_or(0.0),
    );
    let traj = rk4_force(
        (
            p.mass,
            p.stiffness,
            p.damping_n_s_m(),
            f0,
            scene.excitation.omega_rad_s(),
        ),
        init,
        1e-6,
        1_000_000,
    );
    assert_eq!(obs.0.len(), 1001);
    let scale = obs.0.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
    for &(t, z, _) in &obs.0 {
        let (zr, _) = traj[(t / 1e-6).round() as usize];
        // RK4 at 1e-6 s is accurate to ~1e-10 of the scale; 1e-7 leaves room and catches any
        // wrong phase or sign of the force (errors of order 1)
        assert!((z - zr).abs() < 1e-7 * scale, "t {t}: {z} vs rk4 {zr}");
    }
}

#[test]
fn force_drive_transient_matches_rk4() {
    for &(xi, f) in &[(0.001, 15.16), (0.058, 7.0), (1.0, 3.0), (2.5, 30.0)] {
        let mut scene = force_scene(xi, f, 4.0, 1.0);
        scene.run.sample_interval = 1e-3;
        if let Some(p) = scene.primary.as_mut() {
            p.initial_displacement = Some(0.002);
            p.initial_velocity = Some(-0.05);
        }
        series_against_rk4(&scene, 4.0);
    }
}

#[test]
fn free_decay_of_the_primary_alone_is_the_damped_oscillator() {
    for &xi in &[0.001f64, 0.0169, 0.2, 1.0, 3.0] {
        let text = format!(
            "[primary]\nmass = {M}\nstiffness = {K}\ndamping_ratio = {xi}\n\
             initial_displacement = 0.0065\n[excitation]\nkind = \"free\"\n\
             [run]\nduration = 1.0\nsample_interval = 1e-3\n"
        );
        let scene = Scene::from_toml(&text).unwrap();
        // the clock of a free decay is the primary's natural frequency
        let f0 = (K / M).sqrt() / TWO_PI;
        assert!((scene.excitation.frequency - f0).abs() < 1e-12 * f0);
        series_against_rk4(&scene, 0.0);
        // the same run's samples against the closed form of the underdamped oscillator
        if xi < 1.0 {
            let mut obs = Collect::default();
            pdamp::sweep::run_scene(&scene, &mut obs, &pdamp::setup::full_series(&scene)).unwrap();
            let w0 = TWO_PI * f0;
            let wd = w0 * (1.0 - xi * xi).sqrt();
            for &(t, z, _) in &obs.0 {
                let exact = 0.0065
                    * (-xi * w0 * t).exp()
                    * ((wd * t).cos() + xi * w0 / wd * (wd * t).sin());
                assert!((z - exact).abs() < 1e-12, "xi {xi} t {t}: {z} vs {exact}");
            }
        }
    }
}

#[test]
fn horizontal_drive_of_the_primary_alone_follows_2_1_21() {
    let mut v = Scene::primary_only();
    v.excitation.frequency = 12.0;
    v.run.duration = Some(20.0);
    let mut h = v.clone();
    h.excitation.direction = Some([1.0, 0.0, 0.0]);
    h.validate().unwrap();
    let run = |s: &Scene| {
        pdamp::sweep::run_scene(
            s,
            &mut pdamp::observe::NullObserver,
            &RunOptions::summary_only(),
        )
        .unwrap()
    };
    let (sv, sh) = (run(&v), run(&h));
    // gravity does not enter the primary alone: the same motion along x, bit for bit
    assert_eq!(sv.amplitude_m.to_bits(), sh.amplitude_m.to_bits());
    let want = common::scene_reference_amplitude(&h, 0.0);
    assert!((sh.amplitude_m - want).abs() < 1e-4 * want);
}

fn err(text: &str) -> String {
    Scene::from_toml(text).unwrap_err().to_string()
}

const PRIMARY: &str = "[primary]\nmass = 2.37\nstiffness = 21500.0\ndamping = 7.6\n";
const RUN: &str = "[run]\nduration = 1.0\n";

#[test]
fn bad_drive_keys_are_refused_by_name() {
    let cases: &[(&str, &str)] = &[
        // a zero, non-finite or malformed direction
        (
            "[excitation]\namplitude = 0.001\nfrequency = 10.0\ndirection = [0.0, 0.0, 0.0]\n",
            "excitation.direction",
        ),
        (
            "[excitation]\namplitude = 0.001\nfrequency = 10.0\ndirection = [nan, 0.0, 1.0]\n",
            "excitation.direction",
        ),
        (
            "[excitation]\namplitude = 0.001\nfrequency = 10.0\ndirection = [1.0, inf, 0.0]\n",
            "excitation.direction",
        ),
        // a force drive with a base amplitude, without its amplitude, with a negative one
        (
            "[excitation]\nkind = \"force\"\namplitude = 0.001\nforce_amplitude = 1.0\nfrequency = 10.0\n",
            "excitation.amplitude",
        ),
        (
            "[excitation]\nkind = \"force\"\nfrequency = 10.0\n",
            "excitation.force_amplitude",
        ),
        (
            "[excitation]\nkind = \"force\"\nforce_amplitude = -1.0\nfrequency = 10.0\n",
            "excitation.force_amplitude",
        ),
        // a key of another kind
        (
            "[excitation]\namplitude = 0.001\nforce_amplitude = 1.0\nfrequency = 10.0\n",
            "excitation.force_amplitude",
        ),
        // a base drive without amplitude (it would read as 0)
        ("[excitation]\nfrequency = 10.0\n", "excitation.amplitude"),
        // a free decay with no initial condition
        (
            "[excitation]\nkind = \"free\"\n",
            "primary.initial_displacement",
        ),
        // gravity twice, or absurd
        (
            "gravity = 9.8\n[environment]\ngravity = [0.0, 0.0, -9.8]\n[excitation]\namplitude = 0.001\nfrequency = 10.0\n",
            "environment.gravity",
        ),
        (
            "[environment]\ngravity = [0.0, 0.0, -1e7]\n[excitation]\namplitude = 0.001\nfrequency = 10.0\n",
            "environment.gravity",
        ),
        // an unknown kind
        (
            "[excitation]\nkind = \"shaker\"\namplitude = 0.001\nfrequency = 10.0\n",
            "kind",
        ),
    ];
    for (body, key) in cases {
        // top-level keys and tables other than [primary] come first
        let text = format!("{body}{PRIMARY}{RUN}");
        let e = err(&text);
        assert!(e.contains(key), "{body}: {e}");
    }
    // a force drive or a free decay needs a primary
    let e = err("[excitation]\nkind = \"force\"\nforce_amplitude = 1.0\nfrequency = 10.0\n[run]\nduration = 1.0\n");
    assert!(e.contains("primary"), "{e}");
    // run.initial_displacement is a spelling of primary.initial_displacement; both: refused
    let ok = Scene::from_toml(&format!(
        "{PRIMARY}[excitation]\nkind = \"free\"\n[run]\nduration = 1.0\ninitial_displacement = -0.0065\n"
    ))
    .unwrap();
    assert_eq!(ok.primary.unwrap().initial_displacement, Some(-0.0065));
    let e = err(&format!(
        "{PRIMARY}initial_displacement = 0.001\n[excitation]\nkind = \"free\"\n[run]\nduration = 1.0\ninitial_displacement = -0.0065\n"
    ));
    assert!(e.contains("run.initial_displacement"), "{e}");
}

#[test]
fn the_impact_model_refuses_a_drive_off_the_vertical() {
    let mut s = Scene::thesis_b_impact();
    s.excitation.direction = Some([1.0, 0.0, 0.0]);
    s.validate().unwrap();
    let e = pdamp::setup::impact::impact_setup(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("excitation.direction"), "{e}");
    let mut s = Scene::thesis_b_impact();
    s.environment.gravity = Some([9.8, 0.0, 0.0]);
    let e = pdamp::setup::impact::impact_setup(&s)
        .unwrap_err()
        .to_string();
    assert!(e.contains("environment.gravity"), "{e}");
}

#[test]
fn default_keys_are_left_out_of_saved_scenes() {
    // a scene saved today reads as the scene saved before the drive kinds (cached points and
    // their scene hashes stay valid)
    let t = Scene::thesis_b_impact().to_toml().unwrap();
    let table: toml::Table = t.parse().unwrap();
    let e = table["excitation"].as_table().unwrap();
    assert_eq!(e.keys().collect::<Vec<_>>(), ["amplitude", "frequency"]);
    assert!(!table.contains_key("environment"), "{t}");
    let mut f = force_scene(0.05, 10.0, 1.0, 1.0);
    f.excitation.direction = Some([0.0, 1.0, 0.0]);
    let again = Scene::from_toml(&f.to_toml().unwrap()).unwrap();
    assert_eq!(again, f);
}

fn free_scene(xi: f64, z0: f64, duration: f64) -> Scene {
    Scene::from_toml(&format!(
        "[primary]\nmass = {M}\nstiffness = {K}\ndamping_ratio = {xi}\n\
         initial_displacement = {z0}\n[excitation]\nkind = \"free\"\n\
         [run]\nduration = {duration}\n"
    ))
    .unwrap()
}

#[test]
fn a_free_decay_reports_the_primary_damping_ratio_per_cycle() {
    for &xi in &[0.002, 0.0169, 0.1] {
        let scene = free_scene(xi, -0.0065, 3.0);
        let s = pdamp::sweep::run_with_analysis(
            &scene,
            &mut pdamp::observe::NullObserver,
            &RunOptions::summary_only(),
            true,
        )
        .unwrap();
        let env = s.decay.as_ref().expect("a free decay has its envelope");
        assert!(env.cycle_count >= 5, "xi {xi}: {} cycles", env.cycle_count);
        let worst = env
            .cycles
            .iter()
            .map(|c| (c.damping_ratio - xi).abs() / xi)
            .fold(0.0, f64::max);
        eprintln!(
            "free decay ξ = {xi}: {} cycles, worst relative ζ error {worst:.2e}",
            env.cycle_count
        );
        // c/(2√(KM)) on every cycle: the envelope's peaks at 64 samples per period are
        // parabola-refined, their ratio exact to ~1e-5 (the estimator's own tests); 1e-3
        // relative catches a wrong ζ formula (δ/2π alone is off by ζ²/2 ~ 5e-3 at ζ = 0.1)
        for c in &env.cycles {
            assert!(
                (c.damping_ratio - xi).abs() < 1e-3 * xi,
                "xi {xi} cycle {}: {}",
                c.cycle,
                c.damping_ratio
            );
        }
        // no regime verdict for a decaying motion, and the reason says so
        assert!(s.analysis.is_none());
        assert!(s.analysis_error.as_deref().unwrap().contains("free decay"));
    }
}

#[test]
fn pdamp_simulate_writes_decay_csv_for_a_free_decay() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("free.toml");
    std::fs::write(&scene, free_scene(0.0169, -0.0065, 2.0).to_toml().unwrap()).unwrap();
    let out = dir.path().join("run");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_pdamp"))
        .args([
            "simulate",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "-q",
        ])
        .status()
        .unwrap();
    assert!(st.success());
    let csv = std::fs::read_to_string(out.join("decay.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("cycle,time_s,amplitude_m,period_s,log_decrement,damping_ratio")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 10);
    for r in &rows {
        assert!((r[5] - 0.0169).abs() < 1e-3 * 0.0169, "{r:?}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        summary["decay"]["cycles"].as_array().unwrap().len(),
        rows.len()
    );
}
