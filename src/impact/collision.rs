//! The impact law of the one-particle damper: momentum conservation plus an effective
//! coefficient of restitution (2.1.23–2.1.26) and the kinetic energy lost (5.3.1).

/// Velocities of box and particle just after an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PostImpact {
    /// Box velocity v_z⁺ (m/s).
    pub box_v_m_s: f64,
    /// Particle velocity v_p⁺ (m/s).
    pub particle_v_m_s: f64,
    /// Kinetic energy dissipated ΔT (J), (5.3.1).
    pub loss_j: f64,
}

/// Post-impact velocities of box (mass M) and particle (mass m_p).
///
/// # Formula
/// With μ = m_p/M (0 for a kinematically driven box, M → ∞):
/// v_z⁺ = ((1 − e μ) v_z⁻ + μ (1 + e) v_p⁻) / (1 + μ)   (2.1.25)
/// v_p⁺ = ((1 + e) v_z⁻ + (μ − e) v_p⁻) / (1 + μ)         (2.1.26, with SPEC's correction of
/// the thesis's typo (1 − e) → (1 + e) in the first term, which restores momentum conservation)
/// ΔT = ½ (1 − e²) m_p/(1 + μ) (v_p⁻ − v_z⁻)²              (5.3.1)
/// so that e = −(v_p⁺ − v_z⁺)/(v_p⁻ − v_z⁻) (2.1.23) and M v_z + m_p v_p is conserved (2.1.24).
/// The same law holds at floor and ceiling.
///
/// # Units
/// Masses kg, velocities m/s, energy J. `box_mass_kg = f64::INFINITY` for a kinematic box.
///
/// # References
/// Sánchez, M. (2012), thesis, eqs. (2.1.23)–(2.1.26), (5.3.1).
#[inline]
pub fn collide(box_mass_kg: f64, particle_mass_kg: f64, e: f64, vz: f64, vp: f64) -> PostImpact {
    let mu = if box_mass_kg.is_finite() {
        particle_mass_kg / box_mass_kg
    } else {
        0.0
    };
    let box_v = ((1.0 - e * mu) * vz + mu * (1.0 + e) * vp) / (1.0 + mu);
    let part_v = ((1.0 + e) * vz + (mu - e) * vp) / (1.0 + mu);
    PostImpact {
        box_v_m_s: box_v,
        particle_v_m_s: part_v,
        loss_j: impact_energy_loss(box_mass_kg, particle_mass_kg, e, vp - vz),
    }
}

/// Kinetic energy lost in one impact, ΔT = ½ (1 − e²) m_p/(1 + m_p/M) (v_p⁻ − v_z⁻)² (5.3.1).
///
/// # Units
/// kg, m/s → J. `box_mass_kg = f64::INFINITY` for a kinematic box (ΔT = ½(1 − e²) m_p v_rel²).
#[inline]
pub fn impact_energy_loss(box_mass_kg: f64, particle_mass_kg: f64, e: f64, v_rel: f64) -> f64 {
    let mu = if box_mass_kg.is_finite() {
        particle_mass_kg / box_mass_kg
    } else {
        0.0
    };
    0.5 * (1.0 - e * e) * particle_mass_kg / (1.0 + mu) * v_rel * v_rel
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conserves_momentum_and_matches_5_3_1() {
        let (m, mp) = (2.37, 0.227);
        for e in [0.0, 0.3, 0.8, 1.0] {
            let (vz, vp) = (0.4, -1.3);
            let r = collide(m, mp, e, vz, vp);
            let p0 = m * vz + mp * vp;
            let p1 = m * r.box_v_m_s + mp * r.particle_v_m_s;
            assert!((p0 - p1).abs() < 1e-14, "momentum (2.1.24)");
            let e_got = -(r.particle_v_m_s - r.box_v_m_s) / (vp - vz);
            assert!((e_got - e).abs() < 1e-14, "restitution (2.1.23)");
            let t0 = 0.5 * m * vz * vz + 0.5 * mp * vp * vp;
            let t1 = 0.5 * m * r.box_v_m_s.powi(2) + 0.5 * mp * r.particle_v_m_s.powi(2);
            // energy lost equals (5.3.1) to rounding
            assert!((t0 - t1 - r.loss_j).abs() < 1e-14, "ΔT (5.3.1)");
        }
    }

    #[test]
    fn the_thesis_typo_would_break_momentum() {
        // negative control: (1 − e) in the first term of (2.1.26) changes the momentum
        let (m, mp, e, vz, vp) = (2.37, 0.227, 0.5, 0.4, -1.3);
        let mu = mp / m;
        let typo = ((1.0 - e) * vz + (mu - e) * vp) / (1.0 + mu);
        let r = collide(m, mp, e, vz, vp);
        let p_typo = m * r.box_v_m_s + mp * typo;
        assert!((p_typo - (m * vz + mp * vp)).abs() > 1e-3);
    }

    #[test]
    fn kinematic_box_reflects() {
        let r = collide(f64::INFINITY, 0.1, 0.5, 1.0, -2.0);
        assert_eq!(r.box_v_m_s, 1.0);
        assert!((r.particle_v_m_s - (1.5 * 1.0 + 0.5 * 2.0)).abs() < 1e-15);
    }
}
