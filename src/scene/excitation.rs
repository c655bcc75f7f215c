//! `[excitation]`: the harmonic base motion u(t) = U cos(2π f t) (SPEC §1).

use super::checks::{non_negative, positive};
use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// Base displacement u(t) = U cos(Ω t), Ω = 2π f.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Excitation {
    /// Base displacement amplitude U (m), ≥ 0.
    pub amplitude: f64,
    /// Forcing frequency f (Hz), > 0.
    pub frequency: f64,
}

impl Excitation {
    /// Angular forcing frequency Ω = 2π f (rad/s).
    pub fn omega_rad_s(&self) -> f64 {
        crate::units::TWO_PI * self.frequency
    }

    /// Forcing period T = 1/f (s).
    pub fn period_s(&self) -> f64 {
        1.0 / self.frequency
    }

    /// Check U ≥ 0 and f > 0, both finite.
    ///
    /// # Errors
    /// [`SceneError`] naming `excitation.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        non_negative("excitation.amplitude", self.amplitude, "m")?;
        positive("excitation.frequency", self.frequency, "Hz")
    }
}
