//! Energy ledger of the DEM (2.6.1–2.6.6) plus the viscous loss in the primary's damper C and
//! the work done by the base.
//!
//! Balance: E(t) − E(0) = W_base − D_collision − D_friction − D_viscous − D_bag, with
//! E = T_trans + T_rot + V_grav + U_elastic + T_box + V_spring (U_elastic includes a bean
//! bag's stretched bonds). The relative error reported
//! is |residual| / max(W_base, D_total, |ΔE|).

/// Cumulative flows (J) since the ledger was reset (start of the drive).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyLedger {
    /// Dissipated by normal damping in collisions, ∫(F_n − F_el) ζ' dt (2.6.x) (J).
    pub collision_j: f64,
    /// Dissipated by friction, ∫ −F_s·v_s dt (J).
    pub friction_j: f64,
    /// Dissipated in the primary's viscous damper, ∫ C (z' − u')² dt (J).
    pub viscous_j: f64,
    /// Work done by the base on the system (J).
    pub base_work_j: f64,
    /// Dissipated in the bean bag's bonds, ∫ (T − k(d − L₀)) ḋ dt (J) (0 without a bag).
    pub bag_j: f64,
}

impl EnergyLedger {
    /// Total dissipated energy (J).
    pub fn dissipated_j(&self) -> f64 {
        self.collision_j + self.friction_j + self.viscous_j + self.bag_j
    }
}

/// Mechanical energy stored in the system at one instant (J).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyState {
    /// Translational kinetic energy of the grains ½ Σ m v² (J).
    pub kinetic_j: f64,
    /// Rotational kinetic energy ½ Σ I ω² (J).
    pub rotational_j: f64,
    /// Gravitational potential Σ m g z (lab frame) (J).
    pub potential_j: f64,
    /// Elastic energy stored in contacts, e.g. (8/15) E* √R* ζ^{5/2} (J).
    pub elastic_j: f64,
    /// Primary mass kinetic energy + spring energy ½ M z'² + ½ K (z − u)² (J).
    pub primary_j: f64,
}

impl EnergyState {
    /// Sum of all stored energies (J).
    pub fn total_j(&self) -> f64 {
        self.kinetic_j + self.rotational_j + self.potential_j + self.elastic_j + self.primary_j
    }
}

/// Residual of the balance E − E₀ − W_base + D (J) and its relative size (–).
pub fn balance(now: &EnergyState, start: &EnergyState, ledger: &EnergyLedger) -> (f64, f64) {
    let de = now.total_j() - start.total_j();
    let r = de - ledger.base_work_j + ledger.dissipated_j();
    let scale = ledger
        .base_work_j
        .abs()
        .max(ledger.dissipated_j())
        .max(de.abs());
    (r, if scale > 0.0 { r.abs() / scale } else { 0.0 })
}
