//! Extreme parameters of the one-particle impact damper (SPEC §3): vanishing and infinite gap,
//! zero gravity, e = 0 and e = 1, ξ → 0 at resonance, 0.5 Hz and 100 Hz, and chattering that
//! must end in sticking (Luck & Mehta 1993) after a finite, analytically known time.

use pdamp::error::SimError;
use pdamp::model::{RunOptions, RunSummary};
use pdamp::observe::{ModelSample, NullObserver, Observer, Sample};
use pdamp::scene::{Damper, ImpactParams, Primary, Scene};

mod common;
use common::{SCENE_B_GAP_M, SCENE_B_PARTICLE_MASS_KG};

fn impact_scene(f: f64, gap: f64, e: f64) -> Scene {
    let mut s = Scene::thesis_b_impact();
    s.excitation.frequency = f;
    s.damper = Damper::Impact(ImpactParams {
        mass: SCENE_B_PARTICLE_MASS_KG,
        gap,
        restitution: e,
        initial_height: 0.0,
        initial_velocity: 0.0,
    });
    s.run.duration = None;
    s.run.periods = Some(200.0);
    s
}

fn run(s: &Scene) -> RunSummary {
    pdamp::sweep::run_scene(s, &mut NullObserver, &RunOptions::summary_only()).unwrap()
}

/// Amplitude of scene B's primary carrying the particle as rigid added mass (2.1.21, M + m_p).
fn loaded_reference(s: &Scene) -> f64 {
    common::scene_reference_amplitude(s, SCENE_B_PARTICLE_MASS_KG)
}

#[test]
fn vanishing_gap_is_added_mass() {
    for f in [5.0, 15.0, 25.0] {
        let mut s = impact_scene(f, 0.0, 0.5);
        s.run.periods = Some(400.0); // transient e^{−ξω0 t} < 1e-6 by then
        let r = run(&s);
        let want = loaded_reference(&s);
        // (2.1.21) with M + m_p: a clamped particle is rigid added mass; 1e-4 covers the
        // decayed transient (the extrema are exact)
        assert!(
            (r.amplitude_m - want).abs() < 1e-4 * want,
            "f {f}: {} vs {want}",
            r.amplitude_m
        );
        assert_eq!(r.impacts_total, 0);
        assert!(r.energy_balance_relative_error.unwrap() < 1e-9);
    }
    // a tiny but finite gap with e = 0 behaves the same within 1 % (the particle rattles
    // in 1 µm of play)
    let mut s = impact_scene(25.0, 1e-6, 0.0);
    s.run.periods = Some(400.0);
    let r = run(&s);
    let want = loaded_reference(&s);
    assert!(
        (r.amplitude_m - want).abs() < 1e-2 * want,
        "{} vs {want}",
        r.amplitude_m
    );
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
}

#[test]
fn low_frequency_sticking_particle_is_added_mass() {
    // 0.5 Hz: box acceleration ≈ UΩ² ≈ 0.04 m/s² ≪ g, the particle never leaves the floor in
    // the steady state: the response is (2.1.21) with M + m_p.
    let mut s = impact_scene(0.5, SCENE_B_GAP_M, 0.5);
    s.run.periods = Some(40.0);
    let r = run(&s);
    let want = loaded_reference(&s);
    // 1e-4: the transient has decayed to < e^{−ξω0 t} ≈ 1e-30 and the extrema are exact; the
    // reference with M alone differs by 2e-4 at 0.5 Hz, so the test tells the masses apart
    assert!(
        (r.amplitude_m - want).abs() < 5e-5 * want,
        "{} vs {want}",
        r.amplitude_m
    );
    // (the start from u(0) = U rings the primary at f0, which makes the particle hop during
    // the transient; none in the steady state)
    assert_eq!(r.impacts_per_cycle, 0.0);
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
}

#[test]
fn high_frequency_runs_and_balances() {
    // 100 Hz (6.6 f0): far above resonance the box acceleration tends to K U / M ≈ 37 m/s² > g,
    // so the particle keeps hopping; the run must stay event-resolved and balanced, and the
    // primary is isolated (Z well below U).
    let mut s = impact_scene(100.0, SCENE_B_GAP_M, 0.5);
    s.run.periods = Some(4000.0);
    let r = run(&s);
    assert!(r.impacts_per_cycle > 0.0);
    assert!(
        r.amplitude_m < 0.5 * s.excitation.amplitude,
        "{}",
        r.amplitude_m
    );
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
}

#[test]
fn infinite_gap_and_zero_gravity() {
    // no ceiling: the particle only ever meets the floor; the run stays finite
    let r = run(&impact_scene(15.0, f64::INFINITY, 0.6));
    assert!(r.impacts_total > 0);
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
    // weightlessness with both walls: impacts on both sides, ledger closes
    let mut s = impact_scene(15.0, 0.02, 0.7);
    s.gravity = 0.0;
    let r = run(&s);
    assert!(r.impacts_total > 10);
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
    // weightlessness without ceiling: the particle is launched once and flies off
    let mut s = impact_scene(15.0, f64::INFINITY, 0.7);
    s.gravity = 0.0;
    let r = run(&s);
    assert!(r.impacts_total <= 2, "impacts {}", r.impacts_total);
    assert!(r.energy_balance_relative_error.unwrap() < 1e-6);
}

#[test]
fn restitution_limits() {
    // e = 0: every impact is plastic; e = 1: no impact loss at all (5.3.1)
    let r0 = run(&impact_scene(15.0, SCENE_B_GAP_M, 0.0));
    let r1 = run(&impact_scene(15.0, SCENE_B_GAP_M, 1.0));
    assert!(r0.energy_impact_j_per_cycle > 0.1);
    assert_eq!(r1.energy_totals.impact_j, 0.0);
    assert!(r0.energy_balance_relative_error.unwrap() < 1e-6);
    assert!(r1.energy_balance_relative_error.unwrap() < 1e-6);
    // the damper works: scene B's resonant amplitude drops well below the bare primary's
    assert!(r0.amplitude_m < 0.5 * r0.reference_amplitude_m.unwrap());
}

#[test]
fn vanishing_damping_at_resonance() {
    // primary alone, ξ = 1e-4, forced exactly at f0: the amplitude approaches
    // U sqrt(1 + 4ξ²)/(2ξ) (2.1.21); the run must be long enough for e^{−ξω0 t} to decay.
    let xi = 1e-4;
    let mut s = Scene::primary_only();
    s.primary = Some(Primary {
        damping: None,
        damping_ratio: Some(xi),
        ..Primary::new(common::SCENE_B_MASS_KG, common::SCENE_B_STIFFNESS_N_M, 0.0)
    });
    let f0 = s.primary.as_ref().unwrap().natural_frequency_hz();
    s.excitation.frequency = f0;
    s.excitation.amplitude = 1e-6;
    let decay_time = 1.0 / (xi * pdamp::units::TWO_PI * f0);
    s.run.duration = Some(14.0 * decay_time); // e^{-14} ≈ 8e-7
    s.run.steady_fraction = 0.01;
    let r = run(&s);
    let want = 1e-6 * (1.0 + 4.0 * xi * xi).sqrt() / (2.0 * xi);
    assert!(
        (r.amplitude_m - want).abs() < 1e-4 * want,
        "{} vs {want}",
        r.amplitude_m
    );
    assert!(r.energy_balance_relative_error.unwrap() < 1e-9);
    // with the particle the resonance is limited, and the run stays well-behaved
    let mut s2 = impact_scene(f0, SCENE_B_GAP_M, 0.3);
    s2.primary = s.primary.clone();
    let r2 = run(&s2);
    assert!(r2.amplitude_m.is_finite() && r2.amplitude_m < 0.1);
    assert!(r2.energy_balance_relative_error.unwrap() < 1e-6);
}

/// Records the first time the particle comes to rest (contact code 1) after being in flight.
struct RestTime {
    flew: bool,
    rest: Option<f64>,
}
impl Observer for RestTime {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        let ModelSample::Impact { contact, .. } = s.model else {
            panic!("the impact model's samples carry its contact code");
        };
        if contact == 0.0 {
            self.flew = true;
        } else if self.flew && self.rest.is_none() && contact == 1.0 {
            self.rest = Some(s.time_s);
        }
        Ok(())
    }
}

#[test]
fn chattering_ends_in_sticking_at_the_analytic_time() {
    // A ball dropped from h onto a still table with restitution e makes infinitely many
    // bounces that end at t∞ = sqrt(2h/g) (1 + e)/(1 − e) (geometric series of flight
    // times). The model must stop chattering and stick, with all of m_p g h dissipated.
    let (h, e, g) = (0.05, 0.6, 9.8);
    let mut s = Scene::thesis_b_impact();
    s.primary = None; // kinematic, motionless table
    s.excitation.amplitude = 0.0;
    s.excitation.frequency = 1.0;
    s.damper = Damper::Impact(ImpactParams {
        mass: 0.1,
        gap: f64::INFINITY,
        restitution: e,
        initial_height: h,
        initial_velocity: 0.0,
    });
    s.run.duration = Some(2.0);
    s.run.sample_interval = 1e-5;
    let mut obs = RestTime {
        flew: false,
        rest: None,
    };
    let r = pdamp::sweep::run_scene(&s, &mut obs, &pdamp::setup::full_series(&s)).unwrap();
    let t_inf = (2.0 * h / g).sqrt() * (1.0 + e) / (1.0 - e);
    let rest = obs.rest.expect("the ball must come to rest");
    // within one sample interval (1e-5 s) plus the cut of the geometric tail (≪ 1e-6 s)
    assert!(
        (rest - t_inf).abs() < 2e-5,
        "rest at {rest}, analytic {t_inf}"
    );
    // all potential energy m g h is dissipated by impacts (plus the plastic cut)
    assert!(
        (r.energy_totals.impact_j - 0.1 * g * h).abs() < 1e-9,
        "{}",
        r.energy_totals.impact_j
    );
    // finite number of impacts: log(v0/s*)/log(1/e) ≈ 50 for these numbers
    assert!(r.impacts_total < 200, "impacts {}", r.impacts_total);
}
