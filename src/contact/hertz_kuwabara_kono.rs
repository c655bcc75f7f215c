//! Hertz normal force with the Kuwabara–Kono viscous term (2.2.8–2.2.9).

use super::lanes::Real;

/// Hertz stiffness k_n = (4/3) E* √R* (N m^-3/2).
///
/// # Formula
/// k_n = (4/3) E* √R*  (2.2.9)
///
/// # Units
/// `e_star` in Pa, `r_star` in m.
///
/// # References
/// H. Hertz, J. reine angew. Math. 92, 156 (1882); K. L. Johnson, *Contact Mechanics*,
/// Cambridge University Press (1985), §4.2.
#[inline]
pub fn hertz_stiffness(e_star: f64, r_star: f64) -> f64 {
    4.0 / 3.0 * e_star * r_star.sqrt()
}

/// Raw total normal force F_n = k_n ζ^{3/2} + γ_n ζ' √ζ (N), positive = repulsive.
///
/// The caller applies the [`crate::contact::AttractionPolicy`] (clamp to ≥ 0 by default).
///
/// # Formula
/// F_n = k_n ζ^{3/2} + γ_n ζ' √ζ  (2.2.8)
///
/// # Units
/// `k_n` N m^-3/2, `overlap_m` ζ in m, `v_n_m_s` ζ' in m/s (> 0 approaching),
/// `gamma_n` kg s⁻¹ m^-1/2.
///
/// # Parameters
/// Scene B (Sánchez 2012 §3.2): γ_n = 3660 kg s⁻¹ m^-1/2 for steel.
///
/// # References
/// G. Kuwabara & K. Kono, Jpn. J. Appl. Phys. 26, 1230 (1987); N. V. Brilliantov, F. Spahn,
/// J.-M. Hertzsch & T. Pöschel, Phys. Rev. E 53, 5382 (1996).
///
/// # Example
/// ```
/// use pdamp::contact::hertz_normal_force;
/// let f = hertz_normal_force(1.0e9, 1.0e-6, 0.0, 3660.0);
/// assert!((f - 1.0).abs() < 1e-9); // 1e9 · (1e-6)^{3/2} = 1 N
/// ```
#[inline(always)]
pub fn hertz_normal_force<R: Real>(k_n: R, overlap_m: R, v_n_m_s: R, gamma_n: R) -> R {
    let s = overlap_m.sqrt();
    k_n * overlap_m * s + gamma_n * v_n_m_s * s
}

/// Elastic part of [`hertz_normal_force`], k_n ζ^{3/2} (N): the conservative force whose
/// potential is [`hertz_elastic_energy`]. The DEM's collision ledger books
/// (F_n − k_n ζ^{3/2}) ζ' as dissipated power.
///
/// # Formula
/// F_el = k_n ζ^{3/2}  (2.2.8, elastic term)
///
/// # Units
/// `k_n` N m^-3/2, `overlap_m` ζ in m → N.
#[inline(always)]
pub fn hertz_elastic_force<R: Real>(k_n: R, overlap_m: R) -> R {
    k_n * overlap_m * overlap_m.sqrt()
}

/// Elastic energy stored in a Hertz contact, (2/5) k_n ζ^{5/2} = (8/15) E* √R* ζ^{5/2} (J).
///
/// # Formula
/// U_el = (8/15) E* √R* ζ^{5/2}  (2.6.x, elastic term of the energy ledger)
#[inline(always)]
pub fn hertz_elastic_energy(k_n: f64, overlap_m: f64) -> f64 {
    0.4 * k_n * overlap_m * overlap_m * overlap_m.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_derivative_of_energy() {
        // dU/dζ = k ζ^{3/2}: central difference, relative error O(h²) ≈ 1e-8
        let (k, z, h) = (2.0e10, 1.0e-6, 1.0e-10);
        let du = (hertz_elastic_energy(k, z + h) - hertz_elastic_energy(k, z - h)) / (2.0 * h);
        let f = hertz_normal_force(k, z, 0.0, 0.0);
        assert!((du - f).abs() / f < 1e-6);
    }

    #[test]
    fn damping_term_sign_follows_velocity() {
        let f_in = hertz_normal_force(1e9, 1e-6, 0.1, 100.0);
        let f_out = hertz_normal_force(1e9, 1e-6, -0.1, 100.0);
        assert!(f_in > 1.0 && f_out < 1.0);
    }
}
