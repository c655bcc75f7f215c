//! Contact duration and coefficient of restitution of single collisions: Hertz contact time,
//! Rayleigh time, the viscoelastic (Kuwabara–Kono) restitution in closed form (Müller &
//! Pöschel 2011) and the linear spring–dashpot relations (SPEC §9).

use std::f64::consts::PI;

/// Hertz contact duration of an elastic impact at speed v (s).
///
/// # Formula
/// t_s = 3.21807 (m*/k_n)^{2/5} v^{-1/5} = 2.86827 (m*² / (R* E*² v))^{1/5}, k_n = (4/3)E*√R*
/// (SPEC §2, §9; the constant is 2 (5/4)^{2/5} ∫₀¹ dx/√(1 − x^{5/2}) = 3.218065).
///
/// # Units
/// `m_star` kg, `r_star` m, `e_star` Pa, `v_m_s` m/s.
///
/// # References
/// L. D. Landau & E. M. Lifshitz, *Theory of Elasticity* §9; Johnson (1985) §11.4.
pub fn hertz_contact_time(m_star: f64, r_star: f64, e_star: f64, v_m_s: f64) -> f64 {
    let k_n = super::hertz_stiffness(e_star, r_star);
    3.218_065_459_719_043_5 * (m_star / k_n).powf(0.4) * v_m_s.powf(-0.2)
}

/// Rayleigh time T_R = π R √(ρ/G) / (0.1631 ν + 0.8766) (s).
///
/// # Units
/// `radius` m, `density` kg/m³, `shear_modulus` Pa.
pub fn rayleigh_time(radius: f64, density: f64, shear_modulus: f64, poisson: f64) -> f64 {
    PI * radius * (density / shear_modulus).sqrt() / (0.1631 * poisson + 0.8766)
}

/// Coefficient of normal restitution of a viscoelastic (Hertz + Kuwabara–Kono) collision (–).
///
/// # Formula
/// ρ = k_n/m*, A = 2γ_n/(3k_n), β = (3/2) A ρ^{2/5}, v* = β^{1/2} v^{1/10},
/// e = (1 + 0.501086 v*) / (1 + 0.501086 v* + 1.15345 v*² + 0.577977 v*³ + 0.532178 v*⁴)
/// (SPEC §9).
///
/// # Units
/// `k_n` N m^-3/2, `gamma_n` kg s⁻¹ m^-1/2, `m_star` kg, `v_m_s` impact speed m/s.
///
/// # Pitfalls
/// Padé approximant: < 0.1 % error for e ≳ 0.75, ~1 % at e ≈ 0.4. It assumes the collision
/// ends when the force vanishes (clamped normal force).
///
/// # References
/// P. Müller & T. Pöschel, Phys. Rev. E 84, 021302 (2011); R. Ramírez, T. Pöschel,
/// N. V. Brilliantov & T. Schwager, Phys. Rev. E 60, 4465 (1999); T. Schwager & T. Pöschel,
/// Phys. Rev. E 78, 051304 (2008).
pub fn kuwabara_kono_restitution(k_n: f64, gamma_n: f64, m_star: f64, v_m_s: f64) -> f64 {
    let rho = k_n / m_star;
    let a = 2.0 * gamma_n / (3.0 * k_n);
    let beta = 1.5 * a * rho.powf(0.4);
    let v = beta.sqrt() * v_m_s.powf(0.1);
    let num = 1.0 + 0.501086 * v;
    num / (num + v * v * (1.15345 + v * (0.577977 + 0.532178 * v)))
}

/// The Kuwabara–Kono damping γ_n that gives the restitution `e` at the impact speed `v_m_s`
/// (kg s⁻¹ m^-1/2): the inverse of [`kuwabara_kono_restitution`], for scenes that state the
/// coefficient of restitution users measure instead of γ_n.
///
/// # Formula
/// Solve e(v*) = e for v* ≥ 0 on the Padé form of [`kuwabara_kono_restitution`] (monotone
/// decreasing from e(0) = 1; bisection to 1e-14 relative), then β = v*² v^{-1/5},
/// A = 2β / (3 ρ^{2/5}), γ_n = (3/2) k_n A with ρ = k_n/m* (SPEC §9).
///
/// # Units
/// `k_n` N m^-3/2, `m_star` kg, `v_m_s` m/s, `e` –; returns kg s⁻¹ m^-1/2.
///
/// # Errors
/// `None` unless 0 < e ≤ 1 and k_n, m*, v are positive and finite (e = 1 gives γ_n = 0).
///
/// # Pitfalls
/// e depends on the impact speed (viscoelastic collisions are softer at low speed): the γ_n
/// returned reproduces `e` at `v_m_s` only. The Padé form is accurate to < 0.1 % for
/// e ≳ 0.75 and ~1 % near e ≈ 0.4.
pub fn kuwabara_kono_gamma_n(k_n: f64, m_star: f64, v_m_s: f64, e: f64) -> Option<f64> {
    let finite_pos = |x: f64| x.is_finite() && x > 0.0;
    if !(finite_pos(k_n) && finite_pos(m_star) && finite_pos(v_m_s) && e > 0.0 && e <= 1.0) {
        return None;
    }
    if e == 1.0 {
        return Some(0.0);
    }
    let pade = |v: f64| {
        let num = 1.0 + 0.501086 * v;
        num / (num + v * v * (1.15345 + v * (0.577977 + 0.532178 * v)))
    };
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while pade(hi) > e {
        hi *= 2.0;
        if hi > 1e12 {
            return None;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if pade(mid) > e {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-14 * hi {
            break;
        }
    }
    let v_star = 0.5 * (lo + hi);
    let beta = v_star * v_star / v_m_s.powf(0.2);
    let rho = k_n / m_star;
    let a = 2.0 * beta / (3.0 * rho.powf(0.4));
    Some(1.5 * k_n * a)
}

/// Damping ratio of a linear spring–dashpot with restitution e (–).
///
/// # Formula
/// ζ_d = −ln e / √(π² + ln² e) (seed paper eq. 17; SPEC §9)
pub fn linear_damping_ratio(restitution: f64) -> f64 {
    let l = restitution.ln();
    -l / (PI * PI + l * l).sqrt()
}

/// Restitution of a linear spring–dashpot whose contact ends when the overlap returns to 0 (–).
///
/// # Formula
/// e = exp(−ζ_d π / √(1 − ζ_d²)), ζ_d = c / (2√(k m*)) (SPEC §9)
pub fn linear_restitution(k_n: f64, c_n: f64, m_star: f64) -> f64 {
    let z = c_n / (2.0 * (k_n * m_star).sqrt());
    (-z * PI / (1.0 - z * z).sqrt()).exp()
}

/// Contact duration of a linear spring–dashpot (overlap criterion) (s).
///
/// # Formula
/// t_c = π / √(k/m* − (c/2m*)²) (SPEC §9)
pub fn linear_contact_time(k_n: f64, c_n: f64, m_star: f64) -> f64 {
    PI / (k_n / m_star - (c_n / (2.0 * m_star)).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restitution_limits_and_monotonic() {
        assert!((kuwabara_kono_restitution(1e10, 0.0, 1e-3, 1.0) - 1.0).abs() < 1e-15);
        let e1 = kuwabara_kono_restitution(1e10, 3660.0, 4.5e-4, 0.1);
        let e2 = kuwabara_kono_restitution(1e10, 3660.0, 4.5e-4, 1.0);
        assert!(e1 > e2 && e2 > 0.0 && e1 < 1.0);
    }

    #[test]
    fn linear_round_trip() {
        for e in [0.2, 0.5, 0.9] {
            let z = linear_damping_ratio(e);
            let (k, m) = (1e5f64, 1e-3f64);
            let c = 2.0 * z * (k * m).sqrt();
            assert!((linear_restitution(k, c, m) - e).abs() < 1e-12);
        }
    }

    #[test]
    fn hertz_time_matches_spec_constant() {
        // 2.868 (m*²/(R* E*² v))^{1/5} (SPEC §9) vs the exact constant: agree to 0.01 %
        let (m, r, e, v) = (4.5e-4f64, 1.5e-3f64, 1.1e11f64, 0.5f64);
        let spec = 2.868 * (m * m / (r * e * e * v)).powf(0.2);
        assert!((hertz_contact_time(m, r, e, v) / spec - 1.0).abs() < 1e-4);
    }
}
