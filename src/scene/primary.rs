//! `[primary]`: the spring-mounted primary mass (SPEC §1, (2.1.2)).

use super::checks::{non_negative, positive};
use crate::error::SceneError;
use crate::model::PrimarySystem;
use serde::{Deserialize, Serialize};

/// The primary system M z'' + C z' + K z = C u' + K u + F_gz (2.1.2).
///
/// Give either `damping` (C, N s/m) or `damping_ratio` (ξ = C / (2 sqrt(K M))), not both.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Primary {
    /// Primary mass M (kg), > 0.
    pub mass: f64,
    /// Spring stiffness K (N/m), > 0.
    pub stiffness: f64,
    /// Viscous damping C (N s/m), ≥ 0. Exclusive with `damping_ratio`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Damping ratio ξ = C / (2 sqrt(K M)) (dimensionless), ≥ 0. Exclusive with `damping`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<f64>,
    /// Initial displacement z(0) (m) from the static equilibrium of M alone. Default: the static
    /// equilibrium with the damper's load resting on the floor, −m_p g / K (no initial transient
    /// from gravity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_displacement: Option<f64>,
    /// Initial velocity z'(0) (m/s). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial_velocity: Option<f64>,
}

impl Primary {
    /// A primary with mass M (kg), stiffness K (N/m) and viscous damping C (N s/m).
    pub fn new(mass: f64, stiffness: f64, damping: f64) -> Primary {
        Primary {
            mass,
            stiffness,
            damping: Some(damping),
            damping_ratio: None,
            initial_displacement: None,
            initial_velocity: None,
        }
    }

    /// Viscous damping C (N s/m), from `damping` or from `damping_ratio` (C = 2 ξ sqrt(K M)).
    pub fn damping_n_s_m(&self) -> f64 {
        match (self.damping, self.damping_ratio) {
            (Some(c), _) => c,
            (None, Some(xi)) => 2.0 * xi * (self.stiffness * self.mass).sqrt(),
            (None, None) => 0.0,
        }
    }

    /// The engine's primary system M, K, C (C resolved from `damping` or `damping_ratio`).
    pub fn system(&self) -> PrimarySystem {
        PrimarySystem {
            mass_kg: self.mass,
            stiffness_n_m: self.stiffness,
            damping_n_s_m: self.damping_n_s_m(),
        }
    }

    /// Damping ratio ξ = C / (2 sqrt(K M)) (dimensionless).
    pub fn damping_ratio(&self) -> f64 {
        self.system().damping_ratio()
    }

    /// Natural frequency f0 = sqrt(K/M)/(2π) (Hz).
    pub fn natural_frequency_hz(&self) -> f64 {
        self.system().natural_frequency_hz()
    }

    /// Check M > 0, K > 0, exactly one of C ≥ 0 / ξ ≥ 0, finite initial state.
    ///
    /// # Errors
    /// [`SceneError`] naming `primary.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        positive("primary.mass", self.mass, "kg")?;
        positive("primary.stiffness", self.stiffness, "N/m")?;
        match (self.damping, self.damping_ratio) {
            (Some(_), Some(_)) => {
                return Err(SceneError::invalid(
                    "primary.damping_ratio",
                    self.damping_ratio.unwrap_or_default(),
                    "give either primary.damping (N s/m) or primary.damping_ratio, not both",
                ))
            }
            (None, None) => {
                return Err(SceneError::Missing {
                    field: "primary.damping".into(),
                    hint: "write damping = C (N s/m) or damping_ratio = ξ (dimensionless)".into(),
                })
            }
            (Some(c), None) => non_negative("primary.damping", c, "N s/m")?,
            (None, Some(xi)) => non_negative("primary.damping_ratio", xi, "dimensionless")?,
        }
        if let Some(z0) = self.initial_displacement {
            if !z0.is_finite() {
                return Err(SceneError::invalid(
                    "primary.initial_displacement",
                    z0,
                    "must be finite (m)",
                ));
            }
        }
        if let Some(v0) = self.initial_velocity {
            if !v0.is_finite() {
                return Err(SceneError::invalid(
                    "primary.initial_velocity",
                    v0,
                    "must be finite (m/s)",
                ));
            }
        }
        Ok(())
    }
}

/// `run.initial_displacement` and `run.initial_velocity` are accepted as spellings of
/// `primary.initial_displacement` / `primary.initial_velocity` (the primary's state at t = 0;
/// one place in the typed scene): moved there in the raw table. Returns whether it changed.
///
/// # Errors
/// [`SceneError::Invalid`] when a key is given in both places, or without a `[primary]`.
pub(crate) fn move_run_initial_state(table: &mut toml::Table) -> Result<bool, SceneError> {
    let mut moved = Vec::new();
    if let Some(toml::Value::Table(run)) = table.get_mut("run") {
        for key in ["initial_displacement", "initial_velocity"] {
            if let Some(v) = run.remove(key) {
                moved.push((key, v));
            }
        }
    }
    if moved.is_empty() {
        return Ok(false);
    }
    let Some(toml::Value::Table(p)) = table.get_mut("primary") else {
        return Err(SceneError::invalid(
            format!("run.{}", moved[0].0),
            &moved[0].1,
            "sets the primary's initial state, and the scene has no [primary] table",
        ));
    };
    for (key, v) in moved {
        if p.contains_key(key) {
            return Err(SceneError::invalid(
                format!("run.{key}"),
                &v,
                format!("is also given as primary.{key}: keep one"),
            ));
        }
        p.insert(key.into(), v);
    }
    Ok(true)
}
