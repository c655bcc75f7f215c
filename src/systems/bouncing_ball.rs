//! The bouncing ball on a vibrating table: a ball under gravity g bouncing with restitution e
//! on a table moving as s(t) = A cos(ω t) (the kinematic limit M → ∞ of the impact damper,
//! SPEC §3), with Γ = A ω²/g. Analytic existence and period-doubling thresholds of the orbit
//! with one impact every n table periods, and its fixed point.
//!
//! # References
//! Luck, J. M. & Mehta, A. (1993), "Bouncing ball with a finite restitution: chattering,
//! locking, and chaos", Phys. Rev. E 48, 3988. Holmes, P. J. (1982), J. Sound Vib. 84, 173.
//! Tufillaro, N. B., Abbott, T. & Reilly, J. (1992), *An Experimental Approach to Nonlinear
//! Dynamics and Chaos*, ch. 3 (exact impact map, det J = e²).

use crate::scene::{Damper, Excitation, ImpactParams, Run, Scene};
use crate::units::TWO_PI;

/// Γ above which the orbit with one impact every `n` table periods exists.
///
/// # Formula
/// Γ_n = n π (1 − e)/(1 + e)  (SPEC §9).
/// e = 0.5, n = 1 → 1.04720; e = 0.8 → 0.34907.
pub fn existence_gamma(n: u32, e: f64) -> f64 {
    n as f64 * std::f64::consts::PI * (1.0 - e) / (1.0 + e)
}

/// Γ at which the n-periodic orbit loses stability by period doubling.
///
/// # Formula
/// Γ_pd = sqrt( (n π (1 − e)/(1 + e))² + (2 (1 + e²)/(1 + e)²)² )  (SPEC §9).
/// e = 0.5, n = 1 → 1.52682; e = 0.8 → 1.07084.
pub fn period_doubling_gamma(n: u32, e: f64) -> f64 {
    let a = existence_gamma(n, e);
    let b = 2.0 * (1.0 + e * e) / ((1.0 + e) * (1.0 + e));
    a.hypot(b)
}

/// Impact phase θ = ω t_impact (mod 2π, in (−π/2, 0]) of the stable branch of the n-periodic
/// orbit for the table s = A cos(ωt): the table moves up and decelerates at impact.
///
/// # Formula
/// The ball leaves with v⁺ = g nT/2 and returns with −v⁺, so the impact law
/// v⁺ = (1 + e) s'(θ) − e v⁻ gives s'(θ) = −Aω sin θ = g nT (1 − e)/(2(1 + e)), i.e.
/// sin θ = −Γ_n/Γ.
///
/// # Errors
/// `None` when Γ < Γ_n (the orbit does not exist).
pub fn fixed_point_phase(n: u32, e: f64, gamma: f64) -> Option<f64> {
    let s = existence_gamma(n, e) / gamma;
    (s <= 1.0).then(|| -s.asin())
}

/// Trace of the Jacobian of the exact impact map at the stable period-1 fixed point (one impact
/// per table period, [`fixed_point_phase`]).
///
/// # Formula
/// In the impact-map variables (impact time t_k, take-off velocity v_k), with flight time
/// τ = T, take-off speed V = gT/2 and approach speed p = gT/(1 + e) at the fixed point,
/// J = [[1, τ/p], [B − e g, B τ/p − e]], B = (1 + e) s''(θ) + e g, so det J = e² and
/// tr J = 1 + e² + (1 + e)² s''(θ)/g = 1 + e² − (1 + e)² sqrt(Γ² − Γ₁²)
/// (s = A cos ωt decelerating upwards at impact: s''(θ)/g = −sqrt(Γ² − Γ₁²)). The multipliers
/// μ solve μ² − tr J μ + e² = 0; tr J = −(1 + e²) (μ = −1) gives [`period_doubling_gamma`].
///
/// # Errors
/// `None` when Γ < Γ₁ (the orbit does not exist).
///
/// # References
/// Tufillaro, Abbott & Reilly (1992), ch. 3; Luck & Mehta (1993), PRE 48, 3988.
pub fn period_one_trace(e: f64, gamma: f64) -> Option<f64> {
    let g1 = existence_gamma(1, e);
    (gamma >= g1).then(|| 1.0 + e * e - (1.0 + e) * (1.0 + e) * (gamma * gamma - g1 * g1).sqrt())
}

/// Largest Lyapunov exponent of the stable period-1 orbit (per table period, natural log):
/// ln of the spectral radius of the exact impact map's Jacobian ([`period_one_trace`]).
///
/// # Formula
/// ρ = e when tr² < 4e² (complex multipliers, |μ|² = det J = e²), otherwise
/// ρ = (|tr| + sqrt(tr² − 4e²))/2; λ_T = ln ρ. λ_T = ln e on the whole complex band, and
/// λ_T → 0 at the period-doubling threshold (μ = −1).
///
/// # Errors
/// `None` when Γ < Γ₁ (the orbit does not exist).
pub fn period_one_lyapunov(e: f64, gamma: f64) -> Option<f64> {
    let tr = period_one_trace(e, gamma)?;
    let disc = tr * tr - 4.0 * e * e;
    let rho = if disc < 0.0 {
        e
    } else {
        0.5 * (tr.abs() + disc.sqrt())
    };
    Some(rho.ln())
}

/// A scene of the bouncing ball with table amplitude `amplitude` (m), frequency `frequency`
/// (Hz) scaled to Γ = `gamma`, restitution `e`, started exactly on the period-n orbit's fixed
/// point (if it exists; otherwise resting on the table), for `periods` table periods.
pub fn scene(gamma: f64, e: f64, frequency: f64, n: u32, periods: f64) -> Scene {
    let g = crate::units::G;
    let omega = TWO_PI * frequency;
    let amplitude = gamma * g / (omega * omega);
    let t_n = n as f64 / frequency;
    let (h0, v0) = match fixed_point_phase(n, e, gamma) {
        Some(theta) => {
            // impact at t_i = (θ + 2π)/ω, previous impact at t_i − nT; state at t = 0:
            let t_i = (theta + TWO_PI) / omega;
            let tau = n as f64 / frequency - t_i;
            let v_plus = g * t_n / 2.0;
            let table_i = amplitude * theta.cos();
            let y0 = table_i + v_plus * tau - 0.5 * g * tau * tau;
            (y0 - amplitude, v_plus - g * tau)
        }
        None => (0.0, 0.0),
    };
    Scene {
        gravity: g,
        primary: None,
        excitation: Excitation::base(amplitude, frequency),
        damper: Damper::Impact(ImpactParams {
            mass: 1.0,
            gap: f64::INFINITY,
            restitution: e,
            initial_height: h0.max(0.0),
            initial_velocity: v0,
        }),
        run: Run {
            duration: None,
            periods: Some(periods),
            ..Run::with_duration(1.0)
        },
        outputs: Default::default(),
        environment: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_section_9_values() {
        // SPEC §9: e = 0.5 → 1.04720 and 1.52682; e = 0.8 → 0.34907 and 1.07084 (5 decimals)
        // (1.04720 = π/3 exactly for e = 0.5)
        assert!((existence_gamma(1, 0.5) - std::f64::consts::FRAC_PI_3).abs() < 1e-15);
        assert!((period_doubling_gamma(1, 0.5) - 1.52682).abs() < 5e-6);
        assert!((existence_gamma(1, 0.8) - 0.34907).abs() < 5e-6);
        assert!((period_doubling_gamma(1, 0.8) - 1.07084).abs() < 5e-6);
    }

    #[test]
    fn period_one_multiplier_is_minus_one_at_period_doubling() {
        // tr J = −(1 + e²) ⇔ μ = −1 (and μ = −e²): λ_T = 0 at Γ_pd (to rounding)
        for e in [0.5, 0.8] {
            let tr = period_one_trace(e, period_doubling_gamma(1, e)).unwrap();
            assert!((tr + 1.0 + e * e).abs() < 1e-12, "e {e}: tr {tr}");
            assert!(
                period_one_lyapunov(e, period_doubling_gamma(1, e))
                    .unwrap()
                    .abs()
                    < 1e-7
            );
            // inside the complex band |μ| = e exactly
            let mid = 0.5 * (existence_gamma(1, e) + period_doubling_gamma(1, e));
            assert_eq!(period_one_lyapunov(e, mid), Some(e.ln()));
        }
        assert_eq!(period_one_trace(0.5, 1.0), None);
    }
}
