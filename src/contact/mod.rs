//! Narrow phase and force laws of the DEM (SPEC §2): one file per contact law, selected by
//! the [`NormalLaw`] and [`TangentialLaw`] enums (LAMMPS-style sub-models).
//!
//! A contact is a [`ContactGeometry`] (overlap ζ, unit normal n, relative velocity) plus a
//! normal law and a tangential law. The kernels are pure functions of the geometry; the laws'
//! coefficients for a pair (k_n, damping) come from [`material`] mixing ([`mixing`]:
//! [`ContactModel::coefficients`]). The hot loop of
//! [`crate::dem`] matches the enums once per step and runs a monomorphised loop.

pub mod coulomb_viscous;
pub mod hertz_kuwabara_kono;
pub mod lanes;
pub mod linear_spring_dashpot;
pub mod material;
pub mod mixing;
pub mod response;
pub mod restitution;

pub use coulomb_viscous::coulomb_viscous_force;
pub use hertz_kuwabara_kono::{
    hertz_elastic_energy, hertz_elastic_force, hertz_normal_force, hertz_stiffness,
};
pub use linear_spring_dashpot::{linear_elastic_force, linear_normal_force, LinearContactParams};
pub use material::{Material, PairProperties};
pub use response::{
    contact_response, tangential_spring_force, ContactCoefficients, ContactKinematics,
    ContactResponse, NormalKernel, TangentialKernel,
};

use serde::{Deserialize, Serialize};

/// Geometry and kinematics of one contact, as seen from grain i.
///
/// `normal` points from j (or the wall) to i; `overlap_m` ζ = R_i + R_j − |r_i − r_j| > 0;
/// `v_n_m_s` = ζ' is the normal approach speed (> 0 while approaching); `v_s_m_s` is the
/// sliding velocity of i's contact point relative to j's (2.2.13–2.2.15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Overlap ζ (m).
    pub overlap_m: f64,
    /// Unit normal from j to i (–).
    pub normal: [f64; 3],
    /// Normal approach speed ζ' (m/s), positive when approaching.
    pub v_n_m_s: f64,
    /// Tangential slip velocity of the contact point, i relative to j (m/s).
    pub v_s_m_s: [f64; 3],
}

/// Normal contact law (the enum is the registry: one variant per law).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "law")]
pub enum NormalLaw {
    /// Hertz with the Kuwabara–Kono viscous term (2.2.8–2.2.9):
    /// F_n = k_n ζ^{3/2} + γ_n ζ' √ζ, k_n = (4/3) E* √R* (k_n mixed per pair).
    HertzKuwabaraKono {
        /// Normal damping γ_n (kg s⁻¹ m^-1/2).
        gamma_n: f64,
    },
    /// Linear spring–dashpot F_n = k_n ζ + c_n ζ' with the seed paper's parameter selection
    /// (see [`linear_spring_dashpot`]).
    LinearSpringDashpot {
        /// Coefficient of restitution e the damping is built from (–).
        restitution: f64,
        /// Yield strength Y of the grain material (Pa), fixes the yield overlap.
        yield_strength: f64,
    },
}

/// Tangential contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "law")]
pub enum TangentialLaw {
    /// No tangential force (frictionless grains).
    None,
    /// Simplified Coulomb law with viscous regularisation (2.2.12):
    /// F_s = −min(γ_s |v_s| √ζ, μ |F_n|) v_s/|v_s|.
    CoulombViscous {
        /// Tangential damping γ_s (kg s⁻¹ m^-1/2).
        gamma_s: f64,
        /// Coulomb friction coefficient μ (–).
        friction: f64,
    },
    /// Tangential part of the linear law: F_s = −min(c_s |v_s|, μ |F_n|) v_s/|v_s| with c_s
    /// from the seed paper's damping ratio and k_s = γ k_n. The tangential spring k_s is not
    /// integrated (history-free, like the thesis's law); k_s is reported by
    /// [`LinearContactParams`].
    LinearDashpotCoulomb {
        /// Coulomb friction coefficient μ (–).
        friction: f64,
    },
    /// Mindlin (Hertz) tangential spring with per-contact history, capped by Coulomb:
    /// F_t = −k_t ξ − γ_s √ζ v_s with k_t = 8 G* √(R* ζ), |F_t| ≤ μ|F_n|, the spring reset to
    /// the Coulomb force while sliding ([`response::tangential_spring_force`]; LIGGGHTS's
    /// `tangential history`, Di Renzo & Di Maio 2004's "no-slip" model).
    MindlinSpring {
        /// Tangential damping γ_s (kg s⁻¹ m^-1/2), may be 0.
        gamma_s: f64,
        /// Coulomb friction coefficient μ (–).
        friction: f64,
    },
    /// Linear tangential spring k_s = γ k_n with history and the seed paper's dashpot c_s,
    /// capped by Coulomb (the linear law's tangential spring integrated).
    LinearSpring {
        /// Coulomb friction coefficient μ (–).
        friction: f64,
    },
}

impl TangentialLaw {
    /// Coulomb friction coefficient μ (0 without a tangential force).
    pub fn friction(&self) -> f64 {
        match *self {
            TangentialLaw::None => 0.0,
            TangentialLaw::CoulombViscous { friction, .. }
            | TangentialLaw::LinearDashpotCoulomb { friction }
            | TangentialLaw::MindlinSpring { friction, .. }
            | TangentialLaw::LinearSpring { friction } => friction,
        }
    }

    /// Whether the law keeps a spring elongation per contact.
    pub fn has_history(&self) -> bool {
        matches!(
            self,
            TangentialLaw::MindlinSpring { .. } | TangentialLaw::LinearSpring { .. }
        )
    }
}

/// Whether the total normal force may turn attractive near the end of a contact.
///
/// With viscous normal damping the sum k_n ζ^{3/2} + γ_n ζ' √ζ becomes negative while the
/// grains separate. [`AttractionPolicy::Clamp`] (default) sets it to 0, so the collision ends
/// when the force vanishes, which is the assumption of the Müller–Pöschel restitution formula
/// (SPEC §9); [`AttractionPolicy::Allow`] keeps the raw sum until the overlap vanishes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttractionPolicy {
    /// Total normal force clamped to ≥ 0 (default).
    #[default]
    Clamp,
    /// Attractive (negative) total normal force allowed until ζ = 0.
    Allow,
}

impl AttractionPolicy {
    /// Applies the policy to a raw total normal force (N).
    #[inline(always)]
    pub fn apply(self, f_n: f64) -> f64 {
        match self {
            AttractionPolicy::Clamp => f_n.max(0.0),
            AttractionPolicy::Allow => f_n,
        }
    }
}

/// Grain–wall contacts: the wall's material and its laws (R_j, m_j → ∞ in the mixing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallContact {
    /// Wall material E_b (Pa), ν_b (–).
    pub material: Material,
    /// Normal law of grain–wall contacts.
    pub normal: NormalLaw,
    /// Tangential law of grain–wall contacts.
    pub tangential: TangentialLaw,
}

/// The resolved contact model of a DEM damper: grain–grain laws, grain–wall laws and the
/// attraction policy (LAMMPS-style sub-models selected by the enums; SPEC (2.2.8)–(2.2.15)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel {
    /// Normal law of grain–grain contacts.
    pub normal: NormalLaw,
    /// Tangential law of grain–grain contacts.
    pub tangential: TangentialLaw,
    /// Grain–wall contacts.
    pub wall: WallContact,
    /// Whether the total normal force may turn attractive.
    pub attraction: AttractionPolicy,
}

impl ContactModel {
    /// Whether any contact has a tangential force.
    pub fn any_tangential(&self) -> bool {
        self.tangential != TangentialLaw::None || self.wall.tangential != TangentialLaw::None
    }

    /// The (normal, tangential) laws of grain–grain (`wall = false`) or grain–wall contacts.
    pub fn laws(&self, wall: bool) -> (NormalLaw, TangentialLaw) {
        if wall {
            (self.wall.normal, self.wall.tangential)
        } else {
            (self.normal, self.tangential)
        }
    }
}
