//! The kinematic limit of the impact model (no primary: the container follows the base) is the
//! bouncing ball on a vibrating table. Its period-1 orbit (one impact per table period) exists
//! for Γ ≥ π(1 − e)/(1 + e) and period-doubles at
//! Γ = sqrt((π(1 − e)/(1 + e))² + (2(1 + e²)/(1 + e)²)²) (SPEC §9; Luck & Mehta, PRE 48,
//! 3988, 1993). It coexists with the chattering-and-locking orbit, so the runs start on the
//! analytic fixed point ([`pdamp::systems::bouncing_ball::scene`]).

use pdamp::model::{RunOptions, RunSummary};
use pdamp::observe::NullObserver;
use pdamp::scene::Damper;
use pdamp::systems::bouncing_ball::{existence_gamma, period_doubling_gamma, scene};

fn run(gamma: f64, e: f64, periods: f64) -> (RunSummary, f64) {
    let s = scene(gamma, e, 10.0, 1, periods);
    let y0 = match &s.damper {
        Damper::Impact(p) => s.excitation.amplitude + p.initial_height,
        _ => unreachable!(),
    };
    let r = pdamp::sweep::run_scene(&s, &mut NullObserver, &RunOptions::summary_only()).unwrap();
    (r, y0)
}

/// Largest distance between stroboscopic particle heights n and n + k over the last 40 cycles.
fn spread(r: &RunSummary, k: usize) -> f64 {
    let z: Vec<f64> = r
        .strobe
        .iter()
        .rev()
        .take(40)
        .map(|p| p.grain_z_m)
        .collect();
    z.windows(k + 1)
        .map(|w| (w[0] - w[k]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn period_one_orbit_is_the_analytic_fixed_point_below_period_doubling() {
    for (e, frac) in [(0.5, 0.3), (0.5, 0.97), (0.8, 0.5), (0.8, 0.97)] {
        // Γ a fraction `frac` of the way from existence to period doubling
        let (g1, g2) = (existence_gamma(1, e), period_doubling_gamma(1, e));
        let gamma = g1 + frac * (g2 - g1);
        let (r, y0) = run(gamma, e, 3000.0);
        // one impact per period, strobe points all equal to the analytic orbit's height at
        // t = nT (the fixed point the run started from). Tolerance 1e-9 m: event times are
        // located to ~1e-13 s; a wrong impact law (2.1.26) or missed impact moves the orbit
        // by millimetres.
        assert!(
            (r.impacts_per_cycle - 1.0).abs() < 1e-9,
            "e {e} Γ {gamma}: {}",
            r.impacts_per_cycle
        );
        assert!(
            spread(&r, 1) < 1e-9,
            "e {e} Γ {gamma}: spread {}",
            spread(&r, 1)
        );
        let last = r.strobe.last().unwrap().grain_z_m;
        assert!(
            (last - y0).abs() < 1e-9,
            "e {e} Γ {gamma}: {last} vs fixed point {y0}"
        );
    }
}

#[test]
fn period_doubles_just_above_the_analytic_threshold() {
    for e in [0.5, 0.8] {
        let g2 = period_doubling_gamma(1, e);
        // 1 % below: period 1 (perturbations decay, the Floquet multiplier is > −1)
        let (below, _) = run(0.99 * g2, e, 3000.0);
        assert!(
            spread(&below, 1) < 1e-8,
            "e {e}: below threshold spread {}",
            spread(&below, 1)
        );
        // 1 % above: period 2 — strobe points alternate (distance n, n+1 ≫ 0, n, n+2 ≈ 0).
        // The run starts on the (now unstable) period-1 fixed point; rounding seeds the
        // instability, which grows by |λ| > 1 per period.
        let (above, _) = run(1.01 * g2, e, 3000.0);
        let d1 = spread(&above, 1);
        let d2 = spread(&above, 2);
        assert!(
            d1 > 1e-5,
            "e {e}: above threshold, no period doubling (spread {d1})"
        );
        assert!(
            d2 < 1e-8,
            "e {e}: above threshold, not period 2 (spread2 {d2})"
        );
    }
}

#[test]
fn no_period_one_orbit_below_existence() {
    // e = 0.5, Γ = 1.03: the table throws a resting ball (Γ > 1) but Γ < π(1 − e)/(1 + e)
    // = 1.0472, so the one-impact-per-period orbit cannot exist: the ball chatters and locks.
    let (r, _) = run(1.03, 0.5, 400.0);
    assert!(
        (r.impacts_per_cycle - 1.0).abs() > 0.5,
        "impacts per cycle {}",
        r.impacts_per_cycle
    );
    // negative control: Γ < 1 — a resting ball is never thrown, so no impacts at all
    let (r, _) = run(0.9, 0.5, 100.0);
    assert_eq!(r.impacts_total, 0);
}
