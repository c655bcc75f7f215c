//! The largest Lyapunov exponent of the impact model computed from the model's own equations
//! (`pdamp::impact::lyapunov`): tangent dynamics with saltation matrices, checked against
//! (1) the exact Jacobian of the bouncing ball's period-1 orbit (SPEC §9), (2) the loaded
//! primary's decay rate when the particle never leaves the floor, and (3) the independent
//! two-trajectory (Benettin) estimate on scene B's one-particle damper, in chaotic and periodic
//! states (frequencies from `examples/impact_lyapunov_scan.rs`,
//! `data/reference/impact_model_lyapunov.csv`).

use pdamp::impact::{ImpactWorld, ModelLyapunov, ModelLyapunovOptions};
use pdamp::scene::{Damper, Run, Scene};
use pdamp::setup::{model_lyapunov_of_scene, two_trajectory_lyapunov_of_scene};
use pdamp::systems::bouncing_ball::{
    existence_gamma, period_doubling_gamma, period_one_lyapunov, scene as ball_scene,
};

fn opts() -> ModelLyapunovOptions {
    ModelLyapunovOptions::default()
}

/// Both estimates for the bouncing ball at Γ, e, started on the period-1 fixed point.
fn ball(gamma: f64, e: f64, periods: f64, steady_fraction: f64) -> (ModelLyapunov, ModelLyapunov) {
    let mut s = ball_scene(gamma, e, 10.0, 1, periods);
    s.run.steady_fraction = steady_fraction;
    let w = ImpactWorld::new(&s.resolve_impact().unwrap());
    (
        w.model_lyapunov(&opts()).unwrap(),
        w.model_lyapunov_two_trajectory(&opts()).unwrap(),
    )
}

/// Scene B's one-particle damper (data/scenes/thesis_b_impact.toml) with restitution e at f.
fn scene_b(e: f64, f: f64, duration: f64) -> Scene {
    let mut s = Scene::thesis_b_impact();
    s.excitation.frequency = f;
    s.run = Run::with_duration(duration);
    if let Damper::Impact(p) = &mut s.damper {
        p.restitution = e;
    }
    s
}

fn both(s: &Scene) -> (ModelLyapunov, ModelLyapunov) {
    (
        model_lyapunov_of_scene(s, &opts()).unwrap().unwrap(),
        two_trajectory_lyapunov_of_scene(s, &opts())
            .unwrap()
            .unwrap(),
    )
}

#[test]
fn bouncing_ball_complex_multipliers_give_ln_e_exactly() {
    // Inside the band where the period-1 multipliers are complex, |μ|² = det J = e², so
    // λ_T = ln e exactly (SPEC §9; systems::bouncing_ball::period_one_lyapunov). The estimate
    // telescopes to ln(|J^N δ|/|δ|)/N = ln e + O(ln κ / N), κ the condition number of the
    // eigenbasis in the scaled norm (measured: 3e-4 for N = 1500, i.e. ln κ ≈ 0.5): tolerance
    // 1e-3 per period.
    // Omitting the saltation's transversal term would give det S = −e, |μ| = sqrt(e):
    // λ_T = ln(e)/2, off by 0.35 (e = 0.5).
    for (e, gamma) in [(0.5, 1.25), (0.8, 0.7)] {
        let want = period_one_lyapunov(e, gamma).unwrap();
        assert_eq!(want, f64::ln(e));
        let (tan, two) = ball(gamma, e, 3000.0, 0.5);
        eprintln!(
            "complex e {e} Γ {gamma}: exact {want:.6}, tangent {:.6}, two-trajectory {:.6}",
            tan.per_period, two.per_period
        );
        assert_eq!(tan.periods, 1500);
        assert!(
            (tan.per_period - want).abs() < 1e-3,
            "e {e} Γ {gamma}: tangent {} vs ln e = {want}",
            tan.per_period
        );
        assert!(
            (two.per_period - want).abs() < 1e-3,
            "e {e} Γ {gamma}: two-trajectory {} vs ln e = {want}",
            two.per_period
        );
        assert!((tan.impacts_per_period - 1.0).abs() < 1e-12 && tan.stuck_fraction == 0.0);
    }
}

#[test]
fn bouncing_ball_real_multipliers_match_the_exact_jacobian() {
    // Real multipliers: the tangent vector aligns with the dominant eigenvector (the other
    // multiplier is e²/μ₁, ≥ 4 times smaller), then every period grows by exactly ρ = |μ₁|:
    // λ_T = ln ρ to rounding. Tolerance 1e-6 per period (alignment after the 135-period
    // transient is complete to 1e-80; the fixed point's start is exact to ~1e-15 m).
    // Γ = 1.05 (e = 0.5): just above existence, 0 < μ₂ < μ₁ < 1;
    // 0.99 Γ_pd: μ₁ → −1 from inside, λ_T slightly negative;
    // 1.01 Γ_pd: the period-1 orbit is unstable (μ₁ < −1), λ_T > 0: a 150-period run stays on
    // it (event-time errors of ~1e-11 relative grow by e^{0.06 × 150} ≈ 1e4) — the exponent changes sign at the
    // period-doubling threshold.
    let e = 0.5;
    let pd = period_doubling_gamma(1, e);
    for (gamma, sign) in [(1.05, -1.0), (0.99 * pd, -1.0), (1.01 * pd, 1.0)] {
        let want = period_one_lyapunov(e, gamma).unwrap();
        assert_eq!(want.signum(), sign);
        let (tan, two) = ball(gamma, e, 150.0, 0.1);
        eprintln!(
            "real Γ {gamma:.5}: exact {want:.9}, tangent {:.9}, two-trajectory {:.9}",
            tan.per_period, two.per_period
        );
        assert!(
            (tan.per_period - want).abs() < 1e-6,
            "Γ {gamma}: tangent {} vs exact {want}",
            tan.per_period
        );
        // the finite separation d0 = 1e-7 sees the curvature of the map: ~d0 relative, and
        // event-time noise 1e-11/1e-7 = 1e-4 per period
        assert!(
            (two.per_period - want).abs() < 1e-3,
            "Γ {gamma}: two-trajectory {} vs exact {want}",
            two.per_period
        );
    }
    // the exact exponent approaches 0 from both sides at the threshold (|λ_T| < 0.07 at ±1 %)
    assert!(period_one_lyapunov(e, 0.99 * pd).unwrap() > -0.07);
    assert!(period_one_lyapunov(e, 1.01 * pd).unwrap() < 0.07);
}

#[test]
fn bouncing_ball_above_period_doubling_settles_on_a_stable_period_two() {
    // 1 % above Γ_pd the run leaves the unstable period-1 orbit (tests/impact_bouncing_ball.rs)
    // for the period-2 orbit born in the flip bifurcation, whose exponent is negative (its
    // larger two-period multiplier starts at +1 at the threshold; measured here e^{2λ_T} ≈ 0.74,
    // λ_T ≈ −0.149, against +0.060 for the unstable period-1 orbit at the same Γ): the exponent
    // of the attractor crosses zero only at the threshold itself. Both methods agree to the
    // boundary term (2e-3 for 1500 periods; measured 3e-6).
    let e = 0.5;
    let gamma = 1.01 * period_doubling_gamma(1, e);
    let (tan, two) = ball(gamma, e, 3000.0, 0.5);
    eprintln!(
        "period-2 Γ {gamma:.5}: tangent {:.6}, two-trajectory {:.6}",
        tan.per_period, two.per_period
    );
    assert!(
        tan.per_period < 0.0 && tan.per_period > -0.2,
        "period-2: λ_T = {}",
        tan.per_period
    );
    assert!(
        (tan.per_period - two.per_period).abs() < 2e-3,
        "tangent {} vs two-trajectory {}",
        tan.per_period,
        two.per_period
    );
}

#[test]
fn locked_ball_is_superstable() {
    // Γ = 0.9 < 1: a ball resting on the table is never thrown (SPEC §9); every perturbation
    // of the particle dies when it sticks (the kinematic box has no state of its own): λ = −∞
    // for both methods. Negative control of the collapse: the same ball on its period-1 orbit
    // (first test) has a finite exponent.
    let mut s = ball_scene(0.9, 0.5, 10.0, 1, 100.0);
    if let Damper::Impact(p) = &mut s.damper {
        p.initial_height = 0.0;
        p.initial_velocity = 0.0;
    }
    let w = ImpactWorld::new(&s.resolve_impact().unwrap());
    let tan = w.model_lyapunov(&opts()).unwrap();
    let two = w.model_lyapunov_two_trajectory(&opts()).unwrap();
    assert!(tan.locked && two.locked);
    assert_eq!(tan.per_period, f64::NEG_INFINITY);
    assert_eq!(two.per_period, f64::NEG_INFINITY);
    // the existence threshold is where the period-1 exponent is defined from
    assert!(period_one_lyapunov(0.5, 0.99 * existence_gamma(1, 0.5)).is_none());
}

#[test]
fn particle_resting_on_the_floor_gives_the_loaded_primary_decay_rate() {
    // At 2 Hz scene B's box acceleration stays below g, the particle never leaves the floor:
    // the stroboscopic map is the loaded primary's (M + m_p), multipliers e^{(−a ± iω_d)T},
    // λ = −a = −C/(2(M + m_p)) = −1.4632 1/s exactly. Boundary term ≤ ln κ/(N T), κ ≈ ω_d/Ω
    // = 7.2 (the scaled norm's ellipse): ≤ 0.002 1/s for N T = 1000 s; tolerance 0.005 1/s.
    let want = -7.6 / (2.0 * (2.37 + 0.227));
    for e in [0.8, 0.5] {
        let mut s = scene_b(e, 2.0, 2000.0);
        s.run.steady_fraction = 0.5;
        let (tan, two) = both(&s);
        eprintln!(
            "loaded e {e}: exact {want:.5}, tangent {:.5}, two-trajectory {:.5} 1/s",
            tan.per_second, two.per_second
        );
        assert!(tan.locked && two.locked, "{tan:?}");
        assert!(
            (tan.per_second - want).abs() < 5e-3,
            "tangent {} vs {want}",
            tan.per_second
        );
        assert!(
            (two.per_second - want).abs() < 5e-3,
            "two-trajectory {} vs {want}",
            two.per_second
        );
    }
}

/// Tangent vs two-trajectory: |Δλ| ≤ 3 σ (σ² = sum of the two batch-means variances) plus an
/// allowance `abs` for the boundary term ln κ/(N T) of periodic orbits (the batch-means error
/// of an exactly periodic orbit is ~0).
fn assert_agree(tan: &ModelLyapunov, two: &ModelLyapunov, abs: f64, what: &str) {
    let sigma = tan.stderr_per_second.hypot(two.stderr_per_second);
    let diff = (tan.per_second - two.per_second).abs();
    eprintln!(
        "{what}: tangent {:.4} ± {:.4} vs two-trajectory {:.4} ± {:.4} 1/s, |Δ| = {diff:.4} \
         ({:.2} σ; {} periods)",
        tan.per_second,
        tan.stderr_per_second,
        two.per_second,
        two.stderr_per_second,
        diff / sigma,
        tan.periods
    );
    assert!(
        diff <= 3.0 * sigma + abs,
        "{what}: tangent {:.4} ± {:.4} vs two-trajectory {:.4} ± {:.4} 1/s",
        tan.per_second,
        tan.stderr_per_second,
        two.per_second,
        two.stderr_per_second
    );
}

#[test]
fn scene_b_chaotic_states_agree_with_two_trajectories() {
    // Chaotic states of scene B's impact damper (scan: λ ≈ 12–16 1/s with both methods, 1–2
    // impacts per period): 1000 s runs, last 10 % (1800–2100 periods). Tolerance 3σ of the
    // batch means (σ ≈ 0.3–0.5 1/s here); sign: λ − 3σ > 0 for both methods.
    for (e, f) in [(0.8, 20.5), (0.8, 21.0), (0.5, 18.5), (0.5, 21.0)] {
        let (tan, two) = both(&scene_b(e, f, 1000.0));
        let what = format!("e {e} f {f} Hz");
        assert_agree(&tan, &two, 0.0, &what);
        assert!(
            tan.per_second - 3.0 * tan.stderr_per_second > 0.0,
            "{what}: {tan:?}"
        );
        assert!(
            two.per_second - 3.0 * two.stderr_per_second > 0.0,
            "{what}: {two:?}"
        );
        assert!(!tan.locked);
    }
}

#[test]
fn scene_b_periodic_states_agree_with_two_trajectories() {
    // Periodic states (two impacts per period; scan: λ = −2.1 and −5.5 1/s): 1000 s runs,
    // last 10 % (100 s). Allowance 0.05 1/s for the boundary term ln κ/(N T) (κ of a few over
    // N T = 100 s) plus the two-trajectory noise; sign: λ < 0 for both (negative control of
    // the chaotic test).
    for (e, f) in [(0.8, 11.0), (0.5, 12.0), (0.5, 16.0)] {
        let (tan, two) = both(&scene_b(e, f, 1000.0));
        let what = format!("e {e} f {f} Hz");
        assert_agree(&tan, &two, 0.05, &what);
        assert!(
            tan.per_second < -1.0 && two.per_second < -1.0,
            "{what}: {tan:?} {two:?}"
        );
        assert!(
            (tan.impacts_per_period - 2.0).abs() < 1e-9,
            "{what}: {tan:?}"
        );
    }
}

#[test]
fn non_impact_scenes_have_no_model_exponent() {
    // the sweep's entry point answers None for scenes the impact model does not simulate
    let s = Scene::primary_only();
    assert!(model_lyapunov_of_scene(&s, &opts()).unwrap().is_none());
    assert!(two_trajectory_lyapunov_of_scene(&s, &opts())
        .unwrap()
        .is_none());
}

#[test]
fn reference_table_matches_the_code() {
    // data/reference/impact_model_lyapunov.csv (examples/impact_lyapunov_scan.rs, 200 s runs)
    // is the reference of the regime classifier's agreement test: the model is deterministic,
    // so rows recomputed now must equal the file to its 7 significant digits (tolerance 1e-6
    // relative + 1e-9 absolute). A change of the model or of the estimators that moves the
    // exponents fails here: regenerate the file with the command in its header.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/reference/impact_model_lyapunov.csv"
    ))
    .unwrap();
    assert!(text.contains("# generator: cargo run --release --example impact_lyapunov_scan"));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|x| match x {
                    "true" => 1.0,
                    "false" => 0.0,
                    _ => x.parse().unwrap(),
                })
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 114, "e = 0.8, 0.5 × 57 frequencies 2 … 30 Hz");
    for (e, f) in [(0.8, 9.0), (0.8, 20.0), (0.5, 12.0), (0.5, 2.0)] {
        let row = rows
            .iter()
            .find(|r| r[col("restitution")] == e && r[col("frequency_hz")] == f)
            .unwrap();
        let (tan, two) = both(&scene_b(e, f, 200.0));
        let close = |got: f64, want: f64| (got - want).abs() <= 1e-6 * want.abs() + 1e-9;
        assert!(
            close(tan.per_second, row[col("lambda_per_s")]),
            "e {e} f {f}: {tan:?}"
        );
        assert!(
            close(tan.stderr_per_second, row[col("stderr_per_s")]),
            "e {e} f {f}"
        );
        assert!(
            close(two.per_second, row[col("lambda_two_traj_per_s")]),
            "e {e} f {f}"
        );
        assert_eq!(tan.periods as f64, row[col("periods")]);
    }
}
