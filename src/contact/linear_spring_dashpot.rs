//! Linear spring–dashpot contact with the parameter selection of Zhang, Chen, Wang & Chen
//! (2014): stiffness from Hertz work equivalence up to the yield overlap, damping from the
//! coefficient of restitution.

use super::lanes::Real;
use super::material::{Material, PairProperties};
use super::restitution::linear_damping_ratio;
use crate::error::{ModelError, Quantity};

/// Raw total normal force F_n = k_n ζ + c_n ζ' (N), positive = repulsive.
///
/// # Formula
/// F_n = k_n ζ + c_n ζ' (seed paper, Fig. 1 spring–dashpot)
///
/// # Units
/// `k_n` N/m, `overlap_m` m, `v_n_m_s` m/s (> 0 approaching), `c_n` kg/s.
#[inline(always)]
pub fn linear_normal_force<R: Real>(k_n: R, overlap_m: R, v_n_m_s: R, c_n: R) -> R {
    k_n * overlap_m + c_n * v_n_m_s
}

/// Elastic part of [`linear_normal_force`], k_n ζ (N): the conservative spring force. The
/// DEM's collision ledger books (F_n − k_n ζ) ζ' as dissipated power.
///
/// # Formula
/// F_el = k_n ζ (seed paper, Fig. 1 spring)
///
/// # Units
/// `k_n` N/m, `overlap_m` m → N.
#[inline(always)]
pub fn linear_elastic_force<R: Real>(k_n: R, overlap_m: R) -> R {
    k_n * overlap_m
}

/// Yield coefficient c_e(ν) = p₀/Y at first yield of a Hertz contact (–).
///
/// # Formula
/// c_e = 2.8 (0.454 + 0.41 ν) (Kogut & Etsion, J. Appl. Mech. 69, 657, 2002; von Mises).
/// The seed paper's eq. (14) gives c_e as a function of ν through the depth z/a of the
/// maximum shear stress; its printed form is not legible in our copy, so the published fit
/// above (1.61 at ν = 0.3, Johnson's classic value) is used.
pub fn yield_coefficient(poisson: f64) -> f64 {
    2.8 * (0.454 + 0.41 * poisson)
}

/// Parameters of a linear contact for one pair (or grain–wall) of materials.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearContactParams {
    /// Yield overlap δ_y (m).
    pub yield_overlap_m: f64,
    /// Normal stiffness k_n (N/m).
    pub k_n: f64,
    /// Tangential stiffness k_s = γ k_n (N/m).
    pub k_s: f64,
    /// Normal damping c_n (kg/s).
    pub c_n: f64,
    /// Tangential damping c_s (kg/s), equal damping ratio as the normal one (seed paper).
    pub c_s: f64,
    /// Damping ratio ζ_d (–).
    pub damping_ratio: f64,
}

impl LinearContactParams {
    /// Selects k_n, k_s, c_n, c_s from material data (seed paper §2.2).
    ///
    /// # Formula
    /// - yield overlap: δ_y = R* (π c_e Y / (2 E*))² (Hertz p₀ = 2E*a/(πR*) = c_e Y, a² = R*δ)
    /// - equal work up to δ_y: ½ k_n δ_y² = (8/15) E* √R* δ_y^{5/2} ⇒ k_n = (16/15) E* √R* √δ_y
    ///   (seed eqs. 11–13)
    /// - k_s = γ k_n with γ = 4 G*/E* (Mindlin/Hertz stiffness ratio; = 2(1−ν)/(2−ν) for one
    ///   material) (seed eqs. 15–16)
    /// - ζ_d = −ln e / √(π² + ln² e), c = 2 ζ_d √(m* k) (seed eq. 17)
    ///
    /// # Units
    /// `yield_strength` Pa, `restitution` e (–).
    ///
    /// # Errors
    /// [`ModelError`] about the yield strength or the restitution when Y ≤ 0 or e ∉ (0, 1].
    ///
    /// # References
    /// Zhang C., Chen T., Wang X., Chen W., J. Xi'an Jiaotong Univ. 48(3), 96–101 (2014),
    /// doi:10.7652/xjtuxb201403018; A. Di Renzo & F. P. Di Maio, Chem. Eng. Sci. 59, 525 (2004).
    pub fn select(
        pair: &PairProperties,
        grain: &Material,
        yield_strength: f64,
        restitution: f64,
    ) -> Result<Self, ModelError> {
        if !(yield_strength > 0.0 && yield_strength.is_finite()) {
            return Err(ModelError::new(
                Quantity::YieldStrength,
                yield_strength,
                "must be > 0 (Pa), e.g. 1.0e9 for hardened steel",
            ));
        }
        if !(restitution > 0.0 && restitution <= 1.0) {
            return Err(ModelError::new(
                Quantity::Restitution,
                restitution,
                "must be in (0, 1] (coefficient of restitution)",
            ));
        }
        let ce = yield_coefficient(grain.poisson);
        let a = std::f64::consts::PI * ce * yield_strength / (2.0 * pair.e_star);
        let yield_overlap_m = pair.r_star * a * a;
        let k_n = 16.0 / 15.0 * pair.e_star * pair.r_star.sqrt() * yield_overlap_m.sqrt();
        let gamma = 4.0 * pair.g_star / pair.e_star;
        let k_s = gamma * k_n;
        let zeta = linear_damping_ratio(restitution);
        Ok(LinearContactParams {
            yield_overlap_m,
            k_n,
            k_s,
            c_n: 2.0 * zeta * (pair.m_star * k_n).sqrt(),
            c_s: 2.0 * zeta * (pair.m_star * k_s).sqrt(),
            damping_ratio: zeta,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_equivalence_at_yield() {
        let steel = Material {
            youngs_modulus: 2.03e11,
            poisson: 0.28,
        };
        let pair = PairProperties::new(0.003, 1e-3, &steel, 0.003, 1e-3, &steel);
        let p = LinearContactParams::select(&pair, &steel, 1.0e9, 0.8).unwrap();
        // ½ k δ² equals the Hertz work (8/15) E* √R* δ^{5/2} at δ_y (definition, exact)
        let d = p.yield_overlap_m;
        let hertz = 8.0 / 15.0 * pair.e_star * pair.r_star.sqrt() * d.powf(2.5);
        assert!((0.5 * p.k_n * d * d - hertz).abs() / hertz < 1e-12);
        // single material: γ = 2(1−ν)/(2−ν) (Di Renzo & Di Maio 2004)
        let g = 2.0 * (1.0 - 0.28) / (2.0 - 0.28);
        assert!((p.k_s / p.k_n - g).abs() < 1e-12);
        assert!(LinearContactParams::select(&pair, &steel, -1.0, 0.8).is_err());
        assert!(LinearContactParams::select(&pair, &steel, 1e9, 1.5).is_err());
    }
}
