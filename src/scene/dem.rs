//! `[damper] kind = "dem"`: parameters of the granular (DEM) damper (SPEC §2, §5).
//!
//! This is the contract between the scene format and the DEM simulator; the DEM issue owns
//! the validation and derived quantities (effective moduli, automatic time step).

use serde::{Deserialize, Serialize};

/// Parameters of a box of spheres simulated with the discrete element method.
///
/// Every field gives its unit. Defaults are the thesis's scene B (Sánchez 2012 §3.2) where a
/// default makes sense.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemParams {
    /// Inner box size [Lx, Ly, Lz] (m).
    pub r#box: [f64; 3],
    /// Number of spheres.
    pub count: usize,
    /// Sphere radius (m) when all grains are equal.
    #[serde(default)]
    pub radius: Option<f64>,
    /// Smallest radius (m) of a uniform radius range.
    #[serde(default)]
    pub radius_min: Option<f64>,
    /// Largest radius (m) of a uniform radius range.
    #[serde(default)]
    pub radius_max: Option<f64>,
    /// Grain density (kg/m³).
    pub density: f64,
    /// Grain Young's modulus E (Pa).
    pub youngs_modulus: f64,
    /// Grain Poisson ratio ν (–), 0 ≤ ν < 0.5.
    pub poisson: f64,
    /// Coulomb friction coefficient μ (–).
    pub friction: f64,
    /// Kuwabara–Kono normal damping γ_n (kg s⁻¹ m^-1/2), (2.2.8).
    pub gamma_n: f64,
    /// Tangential damping γ_s (kg s⁻¹ m^-1/2), (2.2.12).
    pub gamma_s: f64,
    /// Contact law: `"hertz-kk"` (Hertz + Kuwabara–Kono) or `"linear"`.
    #[serde(default = "default_contact")]
    pub contact: String,
}

fn default_contact() -> String {
    "hertz-kk".to_string()
}
