//! Effective-property mixing for a contact: E*, R*, m*, G* and the wall limit R_j → ∞,
//! m_j → ∞ (2.2.9), in one place (as LAMMPS's `mix_stiffnessE`).

/// Elastic material of grains or walls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio ν (–), 0 ≤ ν < 0.5.
    pub poisson: f64,
}

impl Material {
    /// Shear modulus G = E / (2 (1 + ν)) (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson))
    }
}

/// Effective Young's modulus E* of two materials (Pa).
///
/// # Formula
/// 1/E* = (1 − ν_i²)/E_i + (1 − ν_j²)/E_j  (2.2.9)
pub fn effective_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / ((1.0 - a.poisson * a.poisson) / a.youngs_modulus
        + (1.0 - b.poisson * b.poisson) / b.youngs_modulus)
}

/// Effective shear modulus G* of two materials (Pa), Mindlin's combination.
///
/// # Formula
/// 1/G* = (2 − ν_i)/G_i + (2 − ν_j)/G_j  (Di Renzo & Di Maio, Chem. Eng. Sci. 59, 525, 2004)
pub fn effective_shear_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / ((2.0 - a.poisson) / a.shear_modulus() + (2.0 - b.poisson) / b.shear_modulus())
}

/// Effective radius R* = R_i R_j / (R_i + R_j) (m); pass `f64::INFINITY` for a wall (R* = R_i).
pub fn effective_radius(r_i: f64, r_j: f64) -> f64 {
    if r_j.is_infinite() {
        r_i
    } else if r_i.is_infinite() {
        r_j
    } else {
        r_i * r_j / (r_i + r_j)
    }
}

/// Reduced mass m* = m_i m_j / (m_i + m_j) (kg); pass `f64::INFINITY` for a wall (m* = m_i).
pub fn effective_mass(m_i: f64, m_j: f64) -> f64 {
    effective_radius(m_i, m_j)
}

/// Effective properties of one contact pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairProperties {
    /// Effective modulus E* (Pa).
    pub e_star: f64,
    /// Effective shear modulus G* (Pa).
    pub g_star: f64,
    /// Effective radius R* (m).
    pub r_star: f64,
    /// Reduced mass m* (kg).
    pub m_star: f64,
}

impl PairProperties {
    /// Mixes two bodies (radius m, mass kg, material); a wall has infinite radius and mass.
    pub fn new(r_i: f64, m_i: f64, mat_i: &Material, r_j: f64, m_j: f64, mat_j: &Material) -> Self {
        PairProperties {
            e_star: effective_modulus(mat_i, mat_j),
            g_star: effective_shear_modulus(mat_i, mat_j),
            r_star: effective_radius(r_i, r_j),
            m_star: effective_mass(m_i, m_j),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_material_pair_halves_modulus_and_radius() {
        let steel = Material {
            youngs_modulus: 2.03e11,
            poisson: 0.28,
        };
        let p = PairProperties::new(0.003, 1e-3, &steel, 0.003, 1e-3, &steel);
        // E* = E / (2 (1 − ν²)) for identical materials (exact)
        assert!((p.e_star - 2.03e11 / (2.0 * (1.0 - 0.28f64.powi(2)))).abs() < 1.0);
        assert!((p.r_star - 0.0015).abs() < 1e-15);
        assert!((p.m_star - 0.5e-3).abs() < 1e-15);
        // wall limit: R* = R_i, m* = m_i
        let w = PairProperties::new(0.003, 1e-3, &steel, f64::INFINITY, f64::INFINITY, &steel);
        assert_eq!(w.r_star, 0.003);
        assert_eq!(w.m_star, 1e-3);
    }
}
