//! The primary alone (SPEC §1): the event-driven closed-form simulation against the analytic
//! steady-state amplitude (2.1.21) and against an independent RK4 integration of (2.1.2).

use pdamp::error::SimError;
use pdamp::model::RunOptions;
use pdamp::observe::{Observer, Sample};
use pdamp::scene::{Damper, Primary, Scene};
use pdamp::units::TWO_PI;

mod common;

/// Collects (t, z, v) samples.
#[derive(Default)]
struct Collect(Vec<(f64, f64, f64)>);
impl Observer for Collect {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        self.0.push((s.time_s, s.box_z_m, s.box_v_m_s));
        Ok(())
    }
}

fn primary_scene(xi: f64, f: f64, duration: f64) -> Scene {
    let mut s = Scene::primary_only();
    s.primary = Some(Primary {
        damping: None,
        damping_ratio: Some(xi),
        ..Primary::new(common::SCENE_B_MASS_KG, common::SCENE_B_STIFFNESS_N_M, 0.0)
    });
    s.damper = Damper::None;
    s.excitation.frequency = f;
    s.run.duration = Some(duration);
    s.run.steady_fraction = 0.05;
    s
}

#[test]
fn closed_form_matches_2_1_21_over_frequencies_and_damping() {
    let f0 = (21500.0f64 / 2.37).sqrt() / TWO_PI;
    let mut worst: f64 = 0.0;
    for &xi in &[0.001, 0.01, 0.058, 0.2, 0.5] {
        for i in 0..=24 {
            let f = 0.5 + 29.5 * i as f64 / 24.0;
            // long enough for the transient e^{−ξω0 t} to fall below e^{−10} ≈ 5e-5, at least
            // 40 forcing periods; the steady window holds ≥ 2 periods.
            let decay = 10.0 / (xi * TWO_PI * f0);
            let duration = decay.max(40.0 / f) + 2.0 / (0.05 * f);
            let scene = primary_scene(xi, f, duration);
            let s = pdamp::sweep::run_scene(
                &scene,
                &mut pdamp::observe::NullObserver,
                &RunOptions::summary_only(),
            )
            .unwrap();
            let want = common::scene_reference_amplitude(&scene, 0.0);
            let rel = (s.amplitude_m - want).abs() / want;
            worst = worst.max(rel);
            // (2.1.21), tolerance 0.1 % (the requirement; the residual transient is
            // ≤ e^{−10} of the initial one and the extrema are located exactly, so a correct
            // closed form lands at ~1e-5 or better; a wrong particular solution (e.g. forcing
            // K u only, without C u') is off by > 1 % above resonance for ξ ≥ 0.058)
            assert!(
                rel < 1e-3,
                "xi {xi} f {f}: got {} want {want} (rel {rel:e})",
                s.amplitude_m
            );
            // energy ledger closes too
            assert!(s.energy_balance_relative_error.unwrap() < 1e-9);
        }
    }
    eprintln!("worst relative deviation from (2.1.21): {worst:e}");
}

/// RK4 integration of M z'' + C z' + K z = C u' + K u (2.1.2), independent of the closed form.
/// `sys` = (M, K, C, U, Ω), `init` = (z0, v0); `n` steps of `dt`.
fn rk4(sys: (f64, f64, f64, f64, f64), init: (f64, f64), dt: f64, n: usize) -> Vec<(f64, f64)> {
    let (m, k, c, u, w) = sys;
    let acc = |t: f64, z: f64, v: f64| {
        let (s, co) = (w * t).sin_cos();
        (k * (u * co - z) + c * (-u * w * s - v)) / m
    };
    common::rk4(acc, init, dt, n)
}

#[test]
fn closed_form_matches_independent_rk4_in_every_damping_regime() {
    // underdamped (ξ → 0), moderately damped, critically damped and overdamped
    for &(xi, f) in &[
        (0.001, 15.16),
        (0.058, 7.0),
        (0.5, 22.0),
        (1.0, 3.0),
        (2.5, 30.0),
    ] {
        let mut scene = primary_scene(xi, f, 1.0);
        scene.run.sample_interval = 1e-3;
        if let Some(p) = scene.primary.as_mut() {
            p.initial_displacement = Some(0.002);
            p.initial_velocity = Some(-0.05);
        }
        let mut obs = Collect::default();
        pdamp::sweep::run_scene(&scene, &mut obs, &pdamp::setup::full_series(&scene)).unwrap();
        let p = scene.primary.as_ref().unwrap();
        // RK4 with 1e-6 s steps: global error ~ (ω dt)^4 ≈ (190 × 1e-6)^4 × t … ≪ 1e-9 m
        let traj = rk4(
            (
                p.mass,
                p.stiffness,
                p.damping_n_s_m(),
                scene.excitation.amplitude,
                scene.excitation.omega_rad_s(),
            ),
            (0.002, -0.05),
            1e-6,
            1_000_000,
        );
        assert_eq!(obs.0.len(), 1001);
        let scale = obs.0.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
        for &(t, z, _) in &obs.0 {
            let i = (t / 1e-6).round() as usize;
            let (zr, _) = traj[i];
            // tolerance 1e-7 of the motion's scale: RK4 at this step is accurate to ~1e-10;
            // a wrong homogeneous branch (e.g. using cos instead of cosh when overdamped)
            // is off by O(1)
            assert!(
                (z - zr).abs() < 1e-7 * scale,
                "xi {xi} t {t}: closed {z} rk4 {zr}"
            );
        }
    }
}
