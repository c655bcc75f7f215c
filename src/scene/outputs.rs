//! `[outputs]`: what a scene needs from its run, and how accurately. `[damper] kind = "auto"`
//! uses it to pick the cheapest model and settings that deliver it
//! ([`crate::choice::auto`]); the simulators use it to skip work nobody asked for.
//!
//! ```toml
//! [outputs]
//! frf_only = true               # only the primary's amplitude Z and energies per cycle
//! zcm_series = false            # the grains' centre-of-mass series z_cm(t) and its analysis
//! grain_snapshots = false       # per-grain positions (DEM snapshots)
//! orientations = false          # per-grain orientations (unit quaternions)
//! energies_by_mechanism = false # collision and friction dissipation separately
//! tolerance = 0.1               # largest accepted relative error of Z and of the dissipation
//! ```

use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// What a run must deliver, and the accepted error. Every flag defaults to `false`; with no
/// flag set the scene needs only what every model delivers (Z and total dissipation), as
/// with `frf_only = true`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outputs {
    /// Only the frequency response matters: the primary's steady amplitude Z (m) and the
    /// energy dissipated per cycle (J). Any model may stand in for the grains, including the
    /// one-particle impact model (SPEC §3). Default `false`.
    #[serde(default)]
    pub frf_only: bool,
    /// The grains' centre-of-mass series z_cm(t) (m) is wanted, with its regime verdict and
    /// Lyapunov exponent (SPEC §4): the chosen model must reproduce the reference regime.
    /// Default `false`.
    #[serde(default)]
    pub zcm_series: bool,
    /// Per-grain snapshots are wanted: needs the DEM with the scene's grains (same N and
    /// radii). Default `false` (no snapshots are written).
    #[serde(default)]
    pub grain_snapshots: bool,
    /// Per-grain orientations are wanted: needs the DEM with rotations on, and quaternions
    /// are tracked (SPEC (2.4.11)–(2.4.17)). Default `false` (not tracked).
    #[serde(default)]
    pub orientations: bool,
    /// Dissipation split into collisions and friction (2.6.1–2.6.6): needs the DEM with
    /// friction on. Default `false`.
    #[serde(default)]
    pub energies_by_mechanism: bool,
    /// Largest accepted relative error (dimensionless) of the amplitude Z at every measured
    /// frequency and of the grains' dissipation per cycle, against the reference of the
    /// measured trade-off table. Default 0.1 (10 %). Must lie in (0, 10].
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
}

fn default_tolerance() -> f64 {
    0.1
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs {
            frf_only: false,
            zcm_series: false,
            grain_snapshots: false,
            orientations: false,
            energies_by_mechanism: false,
            tolerance: default_tolerance(),
        }
    }
}

impl Outputs {
    /// Whether the outputs need individual grains (snapshots, orientations or the energy
    /// split): the one-particle model cannot deliver them.
    pub fn needs_grains(&self) -> bool {
        self.grain_snapshots || self.orientations || self.energies_by_mechanism
    }

    /// Check `tolerance` ∈ (0, 10] and that `frf_only` is not combined with a grain output.
    ///
    /// # Errors
    /// [`SceneError`] naming `outputs.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        let t = self.tolerance;
        if !(t > 0.0 && t <= 10.0) {
            return Err(SceneError::invalid(
                "outputs.tolerance",
                t,
                "must lie in (0, 10] (relative error, e.g. 0.1 for 10 %)",
            ));
        }
        if self.frf_only && (self.needs_grains() || self.zcm_series) {
            return Err(SceneError::invalid(
                "outputs.frf_only",
                true,
                "contradicts zcm_series / grain_snapshots / orientations / energies_by_mechanism; \
                 drop frf_only or the other outputs",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_validation() {
        let o: Outputs = toml::from_str("").unwrap();
        assert_eq!(o, Outputs::default());
        assert!(!o.needs_grains());
        o.validate().unwrap();
        let bad = Outputs {
            tolerance: 0.0,
            ..Outputs::default()
        };
        assert!(bad
            .validate()
            .unwrap_err()
            .to_string()
            .contains("outputs.tolerance"));
        let clash = Outputs {
            frf_only: true,
            orientations: true,
            ..Outputs::default()
        };
        assert!(clash
            .validate()
            .unwrap_err()
            .to_string()
            .contains("outputs.frf_only"));
        assert!(toml::from_str::<Outputs>("frf_onyl = true").is_err());
    }
}
