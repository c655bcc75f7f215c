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

/// Coefficient of normal restitution of a viscoelastic (Hertz + Kuwabara–Kono) collision,
/// from the collision's equation of motion itself (–): the reference for
/// [`kuwabara_kono_restitution`]'s Padé form and the forward map that
/// [`kuwabara_kono_gamma_n`] inverts.
///
/// # Formula
/// m* ξ'' = −max(0, k_n ξ^{3/2} + γ_n ξ^{1/2} ξ') (2.2.8, force clamped ≥ 0), ξ(0) = 0,
/// ξ'(0) = v; e = −ξ'(t_end)/v when ξ returns to 0. In the units ξ₀ = (m* v²/k_n)^{2/5},
/// t₀ = ξ₀/v it reads x'' = −max(0, x^{3/2} + c x^{1/2} x') with the one parameter
/// c = γ_n ξ₀^{3/2}/(m* v), integrated with classical Runge–Kutta, Δτ = 10⁻³
/// (error < 2·10⁻⁶ in e for c ≤ 2, e ≥ 0.2).
///
/// # Units
/// `k_n` N m^-3/2, `gamma_n` kg s⁻¹ m^-1/2, `m_star` kg, `v_m_s` impact speed m/s.
pub fn kuwabara_kono_restitution_exact(k_n: f64, gamma_n: f64, m_star: f64, v_m_s: f64) -> f64 {
    restitution_of_scaled_damping(scaled_damping(k_n, gamma_n, m_star, v_m_s))
}

/// c = γ_n ξ₀^{3/2}/(m* v), ξ₀ = (m* v²/k_n)^{2/5}: the one parameter of a Kuwabara–Kono
/// collision (see [`kuwabara_kono_restitution_exact`]).
fn scaled_damping(k_n: f64, gamma_n: f64, m_star: f64, v_m_s: f64) -> f64 {
    let xi0 = (m_star * v_m_s * v_m_s / k_n).powf(0.4);
    gamma_n * xi0.powf(1.5) / (m_star * v_m_s)
}

/// e(c) of x'' = −max(0, x^{3/2} + c x^{1/2} x'), x(0) = 0, x'(0) = 1 (RK4, Δτ = 10⁻³).
fn restitution_of_scaled_damping(c: f64) -> f64 {
    const DT: f64 = 1e-3;
    let acc = |x: f64, v: f64| {
        let x = x.max(0.0);
        -(x * x.sqrt() + c * x.sqrt() * v).max(0.0)
    };
    let (mut x, mut v) = (0.0_f64, 1.0_f64);
    // the contact ends within a few units of τ; the bound only guards non-finite c
    for _ in 0..10_000_000 {
        let (k1x, k1v) = (v, acc(x, v));
        let (k2x, k2v) = (
            v + 0.5 * DT * k1v,
            acc(x + 0.5 * DT * k1x, v + 0.5 * DT * k1v),
        );
        let (k3x, k3v) = (
            v + 0.5 * DT * k2v,
            acc(x + 0.5 * DT * k2x, v + 0.5 * DT * k2v),
        );
        let (k4x, k4v) = (v + DT * k3v, acc(x + DT * k3x, v + DT * k3v));
        x += DT / 6.0 * (k1x + 2.0 * (k2x + k3x) + k4x);
        v += DT / 6.0 * (k1v + 2.0 * (k2v + k3v) + k4v);
        if x < 0.0 {
            return (-v).max(0.0);
        }
        if v >= 0.0 && acc(x, v) == 0.0 && x > 0.0 && k1v == 0.0 {
            // stopped inside the contact with no force left (overdamped): no rebound
            return 0.0;
        }
    }
    0.0
}

/// The Kuwabara–Kono damping γ_n that gives the restitution `e` at the impact speed `v_m_s`
/// (kg s⁻¹ m^-1/2): the inverse of [`kuwabara_kono_restitution_exact`], for scenes that state
/// the coefficient of restitution users measure instead of γ_n.
///
/// # Formula
/// Solve e(c) = e for the scaled damping c (bisection to 10⁻¹² relative; e(c) decreases
/// from e(0) = 1), then γ_n = c m* v / ξ₀^{3/2}, ξ₀ = (m* v²/k_n)^{2/5}.
///
/// # Units
/// `k_n` N m^-3/2, `m_star` kg, `v_m_s` m/s, `e` –; returns kg s⁻¹ m^-1/2.
///
/// # Errors
/// `None` unless 0 < e ≤ 1 and k_n, m*, v are positive and finite (e = 1 gives γ_n = 0), or
/// e so small that no finite damping gives it (e(c) → 0 as c → ∞).
///
/// # Pitfalls
/// e depends on the impact speed (viscoelastic collisions are softer at low speed): the γ_n
/// returned reproduces `e` at `v_m_s` only. (The Padé form of [`kuwabara_kono_restitution`]
/// is off by ~4 % at e = 0.2, hence the exact forward map here.)
pub fn kuwabara_kono_gamma_n(k_n: f64, m_star: f64, v_m_s: f64, e: f64) -> Option<f64> {
    let finite_pos = |x: f64| x.is_finite() && x > 0.0;
    if !(finite_pos(k_n) && finite_pos(m_star) && finite_pos(v_m_s) && e > 0.0 && e <= 1.0) {
        return None;
    }
    if e == 1.0 {
        return Some(0.0);
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    while restitution_of_scaled_damping(hi) > e {
        hi *= 2.0;
        if hi > 1e3 {
            return None;
        }
    }
    while hi - lo > 1e-12 * hi {
        let mid = 0.5 * (lo + hi);
        if restitution_of_scaled_damping(mid) > e {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let c = 0.5 * (lo + hi);
    let xi0 = (m_star * v_m_s * v_m_s / k_n).powf(0.4);
    let gamma_n = c * m_star * v_m_s / xi0.powf(1.5);
    gamma_n.is_finite().then_some(gamma_n)
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
    fn exact_restitution_agrees_with_the_pade_form_where_it_is_accurate() {
        // Müller & Pöschel's Padé form: < 0.1 % for e ≳ 0.75 (their Fig. 2)
        let (k, m) = (1e10_f64, 4.5e-4_f64);
        for (gamma, v) in [(3660.0, 1.0), (3660.0, 0.1), (1000.0, 2.0), (8000.0, 0.5)] {
            let pade = kuwabara_kono_restitution(k, gamma, m, v);
            let exact = kuwabara_kono_restitution_exact(k, gamma, m, v);
            if pade > 0.75 {
                assert!(
                    (pade / exact - 1.0).abs() < 1e-3,
                    "{gamma} {v}: {pade} {exact}"
                );
            }
        }
        assert!((kuwabara_kono_restitution_exact(k, 0.0, m, 1.0) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn gamma_n_inversion_round_trips_down_to_low_restitution() {
        let (k, m, v) = (5e9_f64, 2e-5_f64, 1.0_f64);
        for e in [0.97, 0.9, 0.7, 0.4, 0.2, 0.05] {
            let g = kuwabara_kono_gamma_n(k, m, v, e).unwrap();
            let back = kuwabara_kono_restitution_exact(k, g, m, v);
            assert!((back - e).abs() < 1e-9, "{e}: {back}");
        }
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
