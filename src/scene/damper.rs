//! `[damper]`: what the primary carries — nothing, one effective particle (SPEC §3) or a DEM
//! box of spheres (SPEC §2, parameters in [`super::dem::DemParams`]).

use super::checks::{non_negative, positive};
use super::dem::DemParams;
use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// The damper, selected by `kind = "none" | "impact" | "dem" | "auto"` in the `[damper]` table.
// DemParams is large next to the other variants; a scene is built once per run, so the size
// does not matter and the payload stays unboxed (the shared contract `Dem(DemParams)`).
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Damper {
    /// No damper: the primary alone (the reference system of SPEC §1).
    #[default]
    None,
    /// One effective particle between floor and ceiling (SPEC §3).
    Impact(ImpactParams),
    /// A box of spheres simulated with the discrete element method (SPEC §2).
    Dem(DemParams),
    /// A box of spheres described as for `dem`, simulated with the cheapest model and settings
    /// that meet the scene's `[outputs]` (chosen by [`crate::choice::auto::choose`] from the
    /// measured speed/accuracy table).
    Auto(DemParams),
}

impl Damper {
    /// The `kind` string of this damper as written in scene files.
    pub fn kind(&self) -> &'static str {
        match self {
            Damper::None => "none",
            Damper::Impact(_) => "impact",
            Damper::Dem(_) => "dem",
            Damper::Auto(_) => "auto",
        }
    }

    /// Validate the damper's parameters.
    ///
    /// # Errors
    /// [`SceneError`] naming `damper.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        match self {
            Damper::None => Ok(()),
            Damper::Impact(p) => p.validate(),
            // DemParams' validation is owned by the DEM model (src/scene/dem.rs)
            Damper::Dem(d) | Damper::Auto(d) => d.validate(),
        }
    }
}

/// Parameters of the one-particle impact damper (SPEC §3, (2.1.23)–(2.1.27)).
///
/// The particle is a point of mass m_p moving between the box floor (at the box position z) and
/// its ceiling (at z + gap).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactParams {
    /// Effective particle mass m_p (kg), > 0.
    pub mass: f64,
    /// Free travel between floor and ceiling (m), ≥ 0. `inf` (TOML float literal): no ceiling.
    /// 0: the particle is clamped to the box (it only adds mass).
    pub gap: f64,
    /// Effective coefficient of restitution e (dimensionless), 0 ≤ e ≤ 1 (2.1.23).
    pub restitution: f64,
    /// Initial height of the particle above the floor (m), 0 ≤ h ≤ gap. Default 0 (resting).
    #[serde(default)]
    pub initial_height: f64,
    /// Initial particle velocity in the lab frame (m/s). Default 0.
    #[serde(default)]
    pub initial_velocity: f64,
}

impl ImpactParams {
    /// Check m_p > 0, gap ≥ 0 (or `inf`), 0 ≤ e ≤ 1, 0 ≤ initial_height ≤ gap.
    ///
    /// # Errors
    /// [`SceneError`] naming `damper.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        positive("damper.mass", self.mass, "kg")?;
        if self.gap.is_nan() || self.gap < 0.0 {
            return Err(SceneError::invalid(
                "damper.gap",
                self.gap,
                "must be ≥ 0 (m); use gap = inf for a box without ceiling",
            ));
        }
        let e = self.restitution;
        if !(0.0..=1.0).contains(&e) {
            return Err(SceneError::invalid(
                "damper.restitution",
                e,
                "must lie in [0, 1] (0: perfectly plastic, 1: elastic)",
            ));
        }
        non_negative("damper.initial_height", self.initial_height, "m")?;
        if self.initial_height > self.gap {
            return Err(SceneError::invalid(
                "damper.initial_height",
                self.initial_height,
                format!("must not exceed damper.gap = {} m", self.gap),
            ));
        }
        if !self.initial_velocity.is_finite() {
            return Err(SceneError::invalid(
                "damper.initial_velocity",
                self.initial_velocity,
                "must be finite (m/s)",
            ));
        }
        Ok(())
    }
}
