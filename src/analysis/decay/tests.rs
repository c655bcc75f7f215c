//! The free-decay envelope against two independent references: the exact linear viscous
//! oscillator and the analytic Coulomb (dry-friction) decay; bad inputs; the parabola's
//! refinement at coarse sampling.

use super::*;
use std::f64::consts::PI;

/// Natural frequency f₀ (Hz) of the test oscillators.
const F0_HZ: f64 = 7.3;
/// Initial amplitude A (m).
const A_M: f64 = 2e-3;
/// Static offset c₀ (m): the equilibrium shifted by the grains' weight.
const OFFSET_M: f64 = -4.1e-4;

/// Sample times 0, dt, 2dt, … up to `duration_s` (dt = `period_s` / `per_period`).
fn times(period_s: f64, per_period: f64, duration_s: f64) -> Vec<f64> {
    let dt = period_s / per_period;
    let n = (duration_s / dt) as usize + 1;
    (0..n).map(|i| i as f64 * dt).collect()
}

/// The linear oscillator: ω₀, σ = ζω₀, ω_d, T_d.
struct Viscous {
    zeta: f64,
    sigma: f64,
    omega_d: f64,
    period_d: f64,
}

impl Viscous {
    fn new(zeta: f64) -> Self {
        let omega0 = TWO_PI * F0_HZ;
        let omega_d = omega0 * (1.0 - zeta * zeta).sqrt();
        Viscous {
            zeta,
            sigma: zeta * omega0,
            omega_d,
            period_d: TWO_PI / omega_d,
        }
    }

    /// z = c₀ + A e^{−σt} cos(ω_d t), sampled `per_period` times per T_d (not an integer, so
    /// that the samples fall at a different phase of each extremum) for `periods` periods.
    fn record(&self, per_period: f64, periods: f64) -> (Vec<f64>, Vec<f64>) {
        let t = times(self.period_d, per_period, periods * self.period_d);
        let z = t
            .iter()
            .map(|&t| OFFSET_M + A_M * (-self.sigma * t).exp() * (self.omega_d * t).cos())
            .collect();
        (t, z)
    }

    /// Exact half peak-to-peak at the cycle time t_k = t⁺_k + T_d/4 (extrema T_d/2 apart, of
    /// value c₀ ± A sqrt(1 − ζ²) e^{−σt}): A sqrt(1 − ζ²) cosh(σT_d/4) e^{−σ t_k}.
    fn amplitude_at(&self, t_k: f64) -> f64 {
        A_M * (1.0 - self.zeta * self.zeta).sqrt()
            * (self.sigma * self.period_d / 4.0).cosh()
            * (-self.sigma * t_k).exp()
    }
}

/// Largest relative error of ζ_k against `zeta` over the cycles.
fn worst_zeta_error(env: &DecayEnvelope, zeta: f64) -> f64 {
    env.cycles
        .iter()
        .map(|c| (c.damping_ratio / zeta - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Relative tolerance of ζ_k at 100 samples per period. The parabola through three samples
/// h = 2π/100 rad apart misplaces the vertex value of a cosine by O(h⁴/24 ≈ 6.5e−7) of the
/// amplitude; that error in P_k and P_{k+1} is an error of the same size in δ, i.e.
/// ≈ 1e−6 / δ relative, 1.6e−4 at ζ = 0.001 (δ = 0.0063). Measured worst: 4.0e−5 (ζ = 0.001),
/// 1e−5 or less for ζ ≥ 0.01.
const ZETA_TOL_FINE: f64 = 1e-3;
/// Relative tolerance of the amplitude at the cycle time. The vertex's time is less accurate
/// than its value (O(h³) against O(h⁴)), and an error ε of t_k is an error σε of
/// A e^{−σt_k}: measured worst 5.2e−5 at ζ = 0.2, 3e−6 or less for ζ ≤ 0.05.
const AMPLITUDE_TOL_FINE: f64 = 1e-4;
/// Relative tolerance of the period (the vertex times again): measured worst 2.8e−5 (ζ = 0.2).
const PERIOD_TOL_FINE: f64 = 1e-4;

#[test]
fn linear_oscillator_gives_its_damping_ratio_every_cycle() {
    for zeta in [0.001, 0.01, 0.05, 0.2] {
        let osc = Viscous::new(zeta);
        let (t, z) = osc.record(100.37, 30.0);
        let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
        assert!(
            env.cycle_count >= 8,
            "ζ = {zeta}: {} cycles",
            env.cycle_count
        );
        let (mut amp_err, mut per_err) = (0.0_f64, 0.0_f64);
        for c in &env.cycles {
            amp_err = amp_err.max((c.amplitude_m / osc.amplitude_at(c.time_s) - 1.0).abs());
            per_err = per_err.max((c.period_s / osc.period_d - 1.0).abs());
        }
        let zeta_err = worst_zeta_error(&env, zeta);
        eprintln!(
            "ζ = {zeta}: {} cycles, stop {:?}, worst relative errors ζ {zeta_err:.2e}, \
             amplitude {amp_err:.2e}, period {per_err:.2e}",
            env.cycle_count, env.stop
        );
        assert!(zeta_err < ZETA_TOL_FINE, "ζ = {zeta}: ζ error {zeta_err:e}");
        assert!(
            amp_err < AMPLITUDE_TOL_FINE,
            "ζ = {zeta}: amplitude {amp_err:e}"
        );
        assert!(per_err < PERIOD_TOL_FINE, "ζ = {zeta}: period {per_err:e}");
        assert!((env.mean_damping_ratio / zeta - 1.0).abs() < ZETA_TOL_FINE);
        assert_eq!(env.initial_amplitude_m, env.cycles[0].amplitude_m);
        assert_eq!(env.cycle_count, env.cycles.len());
    }
}

#[test]
fn light_damping_runs_to_the_end_of_the_record_heavy_damping_to_the_floor() {
    let (t, z) = Viscous::new(0.001).record(100.37, 30.0);
    let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
    // the first maximum (t = 0) is the record's edge: cycles start one period later, and the
    // last maximum has no following pair
    assert_eq!(env.cycle_count, 28);
    assert_eq!(env.stop, DecayStop::EndOfRecord);
    let (t, z) = Viscous::new(0.2).record(100.37, 30.0);
    let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
    assert_eq!(env.stop, DecayStop::AmplitudeFloor);
    let last = env.cycles.last().unwrap();
    assert!(last.amplitude_m >= env.floor_m);
    assert!((env.floor_m / (1e-6 * env.initial_amplitude_m) - 1.0).abs() < 1e-12);
}

#[test]
fn an_explicit_floor_ends_the_envelope_earlier() {
    let (t, z) = Viscous::new(0.05).record(100.37, 30.0);
    let opts = DecayOptions {
        min_amplitude_m: Some(1e-4),
        ..DecayOptions::default()
    };
    let env = decay_envelope(&t, &z, &opts).unwrap();
    assert_eq!(env.stop, DecayStop::AmplitudeFloor);
    assert_eq!(env.floor_m, 1e-4);
    assert!(env.cycles.iter().all(|c| c.amplitude_m >= 1e-4));
    // a = 2e-3 e^{−σt}: below 1e-4 after ln(20)/δ ≈ 9.5 periods
    assert!((8..=10).contains(&env.cycle_count), "{}", env.cycle_count);
}

#[test]
fn decrement_and_damping_ratio_are_inverse() {
    for zeta in [1e-4, 0.01, 0.3, 0.9] {
        let delta = TWO_PI * zeta / (1.0 - zeta * zeta).sqrt();
        assert!((damping_ratio_of_decrement(delta) / zeta - 1.0).abs() < 1e-14);
    }
}

/// Coulomb decay m z'' + k z = −F sign(z') released at rest from A₀: half-cycle j (from
/// t_j = jπ/ω₀) is a cosine about (−1)^j Δ, Δ = F/k, from the extremum e_j = (−1)^j (A₀ − 2jΔ);
/// the motion sticks at the first extremum with |e_j| ≤ Δ (Den Hartog).
struct Coulomb {
    omega0: f64,
    a0: f64,
    delta: f64,
}

impl Coulomb {
    /// Extremum e_j (m, about the spring's rest position).
    fn extremum(&self, j: usize) -> f64 {
        let sign = if j.is_multiple_of(2) { 1.0 } else { -1.0 };
        sign * (self.a0 - 2.0 * j as f64 * self.delta)
    }

    /// Index of the extremum where the motion sticks.
    fn stuck_at(&self) -> usize {
        (0..)
            .find(|&j| self.extremum(j).abs() <= self.delta)
            .unwrap_or(0)
    }

    fn z(&self, t: f64) -> f64 {
        let half = PI / self.omega0;
        let j = ((t / half).floor() as usize).min(self.stuck_at());
        if j == self.stuck_at() {
            return self.extremum(j);
        }
        let sign = if j.is_multiple_of(2) { 1.0 } else { -1.0 };
        let r = self.extremum(j).abs() - self.delta;
        sign * (self.delta + r * (self.omega0 * (t - j as f64 * half)).cos())
    }
}

#[test]
fn coulomb_decay_loses_four_f_over_k_per_cycle_and_stops_when_it_sticks() {
    let c = Coulomb {
        omega0: TWO_PI * F0_HZ,
        a0: 1e-3,
        delta: 1e-3 / 41.3,
    };
    let period = TWO_PI / c.omega0;
    let stuck = c.stuck_at();
    assert_eq!(stuck, 21);
    // record: until the sticking time, then 5 periods at rest
    let t_stick = stuck as f64 * period / 2.0;
    let t = times(period, 100.37, t_stick + 5.0 * period);
    let z: Vec<f64> = t.iter().map(|&t| OFFSET_M + c.z(t)).collect();
    let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
    // turning points found: e_1 … e_{J−1} (e_0 is the record's edge, e_J is where it rests);
    // pairs (e_2, e_3), (e_4, e_5), …; one cycle per pair that has a next pair
    let pairs: Vec<f64> = (1..)
        .map(|p| 2 * p)
        .take_while(|&j| j < stuck - 1)
        .map(|j| 0.5 * (c.extremum(j) - c.extremum(j + 1)))
        .collect();
    assert_eq!(env.cycle_count, pairs.len() - 1);
    assert_eq!(env.stop, DecayStop::AtRest);
    let (mut amp_err, mut zeta_err, mut drop_err) = (0.0_f64, 0.0_f64, 0.0_f64);
    for (cy, w) in env.cycles.iter().zip(pairs.windows(2)) {
        // a_k = A₀ − 4kΔ − Δ: exactly 4Δ less each cycle
        assert!((w[0] - w[1] - 4.0 * c.delta).abs() < 1e-15);
        let zeta = damping_ratio_of_decrement((w[0] / w[1]).ln());
        amp_err = amp_err.max((cy.amplitude_m / w[0] - 1.0).abs());
        zeta_err = zeta_err.max((cy.damping_ratio / zeta - 1.0).abs());
        assert!(cy.time_s < t_stick);
    }
    for w in env.cycles.windows(2) {
        drop_err =
            drop_err.max(((w[0].amplitude_m - w[1].amplitude_m) / (4.0 * c.delta) - 1.0).abs());
        // dry friction: ζ rises as the amplitude falls
        assert!(w[1].damping_ratio > w[0].damping_ratio);
    }
    eprintln!(
        "Coulomb: {} cycles, worst relative errors amplitude {amp_err:.2e}, ζ {zeta_err:.2e}, \
         drop per cycle {drop_err:.2e}",
        env.cycle_count
    );
    assert!(amp_err < COULOMB_AMPLITUDE_TOL, "amplitude {amp_err:e}");
    assert!(zeta_err < COULOMB_ZETA_TOL, "ζ {zeta_err:e}");
    assert!(drop_err < COULOMB_ZETA_TOL, "drop {drop_err:e}");
}

/// Relative tolerance of the Coulomb amplitudes at 100 samples per period. The curvature jumps
/// at each turning point (the cosine's centre moves from ∓Δ to ±Δ), so the parabola through
/// the three samples is off by O(Δ h²) (h = 2π/100 rad). Measured worst: 2.7e−5.
const COULOMB_AMPLITUDE_TOL: f64 = 1e-4;
/// Relative tolerance of the Coulomb ζ_k and of the drop per cycle (4Δ): the amplitude error
/// over the drop, ≈ a/(4Δ) ≈ 10 times the amplitude's. Measured worst: 1.8e−4.
const COULOMB_ZETA_TOL: f64 = 1e-3;

/// Relative tolerance of ζ_k at 12 samples per period (h = π/6 rad): the parabola's vertex
/// error O(h⁴/24 ≈ 3e−3) of the amplitude, over δ ≈ 0.31 at ζ = 0.05, i.e. ~1 %. Without the
/// refinement the sampled extremum is up to 1 − cos(h/2) ≈ 3.4 % low, varying from cycle to
/// cycle, i.e. ~10 % errors in ζ. Measured worst: 5.5e−3 refined, 6.9e−2 sampled.
const ZETA_TOL_COARSE: f64 = 0.02;

#[test]
fn refinement_holds_the_damping_ratio_at_coarse_sampling() {
    let zeta = 0.05;
    let (t, z) = Viscous::new(zeta).record(12.37, 30.0);
    let refined = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
    let sampled = DecayOptions {
        refine_extrema: false,
        ..DecayOptions::default()
    };
    let unrefined = decay_envelope(&t, &z, &sampled).unwrap();
    let (e_ref, e_raw) = (
        worst_zeta_error(&refined, zeta),
        worst_zeta_error(&unrefined, zeta),
    );
    eprintln!("12.37 samples per period, ζ = {zeta}: refined {e_ref:.2e}, sampled {e_raw:.2e}");
    assert!(e_ref < ZETA_TOL_COARSE, "refined: {e_ref:e}");
    assert!(
        e_raw > ZETA_TOL_COARSE,
        "sampled extrema should miss: {e_raw:e}"
    );
}

#[test]
fn bad_inputs_are_clear_errors() {
    let (t, z) = Viscous::new(0.01).record(100.37, 10.0);
    let e = decay_envelope(&t[1..], &z, &DecayOptions::default()).unwrap_err();
    assert!(
        matches!(&e, AnalysisError::BadParameter { name, .. } if name == "z_m"),
        "{e}"
    );

    let mut zn = z.clone();
    zn[57] = f64::NAN;
    let e = decay_envelope(&t, &zn, &DecayOptions::default()).unwrap_err();
    assert_eq!(e, AnalysisError::NonFinite { index: 57 });
    zn[57] = f64::INFINITY;
    let e = decay_envelope(&t, &zn, &DecayOptions::default()).unwrap_err();
    assert_eq!(e, AnalysisError::NonFinite { index: 57 });

    let mut tn = t.clone();
    tn[12] = f64::NAN;
    let e = decay_envelope(&tn, &z, &DecayOptions::default()).unwrap_err();
    assert!(
        e.to_string().contains("t_s") && e.to_string().contains("index 12"),
        "{e}"
    );

    let mut td = t.clone();
    td[30] = td[29];
    let e = decay_envelope(&td, &z, &DecayOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("t_s") && msg.contains("index 30") && msg.contains("sort"),
        "{msg}"
    );
    td.swap(40, 41);
    assert!(decay_envelope(&td, &z, &DecayOptions::default()).is_err());
}

#[test]
fn too_few_cycles_say_what_to_do() {
    // 1.6 periods: the first maximum is the record's edge, one pair at most
    let (t, z) = Viscous::new(0.01).record(100.37, 1.6);
    let e = decay_envelope(&t, &z, &DecayOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, AnalysisError::TooShort(_)), "{msg}");
    assert!(
        msg.contains("2 full cycles") && msg.contains("run longer"),
        "{msg}"
    );
    // overdamped (ζ = 2): creeps to equilibrium, never crosses it
    let t = times(0.1, 100.0, 2.0);
    let z: Vec<f64> = t
        .iter()
        .map(|&t| OFFSET_M + A_M * (2.0 * (-3.73 * t).exp() - (-7.46 * t).exp()))
        .collect();
    let e = decay_envelope(&t, &z, &DecayOptions::default()).unwrap_err();
    assert!(matches!(e, AnalysisError::TooShort(_)), "{e}");
    // too few samples, empty, constant
    let short = [0.0, 1.0, 2.0];
    assert!(matches!(
        decay_envelope(&short, &short, &DecayOptions::default()),
        Err(AnalysisError::TooShort(_))
    ));
    assert!(decay_envelope(&[], &[], &DecayOptions::default()).is_err());
    let flat = vec![1.0; 50];
    let t: Vec<f64> = (0..50).map(f64::from).collect();
    assert_eq!(
        decay_envelope(&t, &flat, &DecayOptions::default()),
        Err(AnalysisError::Constant)
    );
}

#[test]
fn bad_options_are_named() {
    let (t, z) = Viscous::new(0.01).record(100.37, 10.0);
    let cases = [
        (
            DecayOptions {
                min_amplitude_m: Some(-1.0),
                ..DecayOptions::default()
            },
            "min_amplitude_m",
        ),
        (
            DecayOptions {
                relative_floor: 1.5,
                ..DecayOptions::default()
            },
            "relative_floor",
        ),
        (
            DecayOptions {
                absolute_floor_m: f64::NAN,
                ..DecayOptions::default()
            },
            "absolute_floor_m",
        ),
    ];
    for (opts, field) in cases {
        let e = decay_envelope(&t, &z, &opts).unwrap_err();
        assert!(
            matches!(&e, AnalysisError::BadParameter { name, .. } if name == field),
            "{e}"
        );
    }
}

#[test]
fn noise_above_the_floor_never_panics() {
    // a pseudo-random walk: whatever it finds, no panic and no non-finite ζ
    let mut x = 0.3_f64;
    let z: Vec<f64> = (0..2000)
        .map(|_| {
            x = (x * 3.9 * (1.0 - x)).clamp(1e-9, 1.0 - 1e-9);
            x - 0.5
        })
        .collect();
    let t: Vec<f64> = (0..2000).map(|i| i as f64 * 1e-3).collect();
    if let Ok(env) = decay_envelope(&t, &z, &DecayOptions::default()) {
        assert!(env.cycles.iter().all(|c| c.damping_ratio.is_finite()));
    }
}

#[test]
fn envelope_serializes_for_the_summary() {
    let (t, z) = Viscous::new(0.05).record(100.37, 6.0);
    let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
    let json = serde_json::to_value(&env).unwrap();
    assert_eq!(json["cycle_count"], env.cycle_count);
    assert_eq!(json["stop"], "end-of-record");
    assert!(json["cycles"][0]["damping_ratio"].is_f64());
}
