//! `[environment]`: the body forces on the grains — gravity as a vector.
//!
//! ```toml
//! [environment]
//! gravity = [0.0, 0.0, -9.81]   # m/s², the acceleration of gravity (default [0, 0, -g])
//! ```
//!
//! The top-level `gravity = g` (m/s², along −z) is the short form; give one or the other.

use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// Most gravity accepted (m/s²): 1e5 g. Beyond it the contact time step no longer resolves a
/// grain falling through its own overlap, and no damper runs there.
pub const MAX_GRAVITY_M_S2: f64 = 1e5 * crate::units::G;

/// The scene's `[environment]` table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Environment {
    /// Acceleration of gravity `[gx, gy, gz]` (m/s²). Default `[0, 0, −gravity]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<[f64; 3]>,
}

impl Environment {
    /// Whether the table says nothing (then it is left out of saved scenes).
    pub fn is_empty(&self) -> bool {
        self.gravity.is_none()
    }

    /// Check the gravity vector: finite, at most [`MAX_GRAVITY_M_S2`].
    ///
    /// # Errors
    /// [`SceneError`] naming `environment.gravity`.
    pub fn validate(&self) -> Result<(), SceneError> {
        if let Some(g) = self.gravity {
            let n = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            if !(g.iter().all(|x| x.is_finite()) && n <= MAX_GRAVITY_M_S2) {
                return Err(SceneError::invalid(
                    "environment.gravity",
                    format!("{g:?}"),
                    format!(
                        "must be a finite vector [gx, gy, gz] (m/s²) of magnitude ≤ {MAX_GRAVITY_M_S2:e} \
                         (1e5 g), e.g. [0, 0, -9.81]"
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Refuses the top-level `gravity` and `environment.gravity` together (raw table).
///
/// # Errors
/// [`SceneError::Invalid`] naming `environment.gravity`.
pub(crate) fn check_one_gravity(table: &toml::Table) -> Result<(), SceneError> {
    let vector = table
        .get("environment")
        .and_then(toml::Value::as_table)
        .and_then(|e| e.get("gravity"));
    match (table.get("gravity"), vector) {
        (Some(g), Some(v)) => Err(SceneError::invalid(
            "environment.gravity",
            v,
            format!(
                "is given together with the top-level gravity = {g}: keep one (the top-level \
                 value is the magnitude along −z)"
            ),
        )),
        _ => Ok(()),
    }
}
