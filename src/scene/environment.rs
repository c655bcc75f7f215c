//! `[environment]`: the body forces on the grains — gravity as a vector, and the inertial
//! forces of a rotating part the damper sits on.
//!
//! ```toml
//! [environment]
//! gravity = [0.0, 0.0, -9.81]   # m/s², the acceleration of gravity (default [0, 0, -g])
//! # the damper on a rotor: 138 rpm about the z axis, its centre 0.4 m from the axis along +x
//! rotation = { radius = 0.4, rpm = 138.0, axis = [0.0, 0.0, 1.0], radial = [1.0, 0.0, 0.0] }
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
    /// The rotating part the damper sits on (DEM): centrifugal and Coriolis forces on every
    /// grain ([`crate::model::rotation`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<Rotation>,
}

/// `environment.rotation`: the frame of the damper turns at `rpm` about `axis`, the
/// container's centre (at rest) being `radius` from the axis along `radial`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rotation {
    /// Distance r (m) of the container's centre from the rotation axis, ≥ 0.
    pub radius: f64,
    /// Speed n (revolutions per minute), ≥ 0: ω = 2π n / 60.
    pub rpm: f64,
    /// Direction of the rotation axis (normalised; default `[0, 0, 1]`).
    #[serde(default = "default_axis")]
    pub axis: [f64; 3],
    /// Direction from the axis to the container's centre (normalised, across the axis; default
    /// `[1, 0, 0]`).
    #[serde(default = "default_radial")]
    pub radial: [f64; 3],
}

fn default_axis() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

fn default_radial() -> [f64; 3] {
    [1.0, 0.0, 0.0]
}

impl Rotation {
    /// Angular speed ω = 2π n / 60 (rad/s).
    pub fn omega_rad_s(&self) -> f64 {
        crate::units::TWO_PI * self.rpm / 60.0
    }

    /// The centrifugal acceleration at the container's centre, ω² r (m/s²).
    pub fn centrifugal_m_s2(&self) -> f64 {
        self.omega_rad_s().powi(2) * self.radius
    }

    /// Unit axis and unit radial direction.
    pub fn unit_axes(&self) -> ([f64; 3], [f64; 3]) {
        (unit(self.axis), unit(self.radial))
    }

    /// The engine's frame for a container whose centre at rest is `centre_m` (m).
    pub fn frame(&self, centre_m: [f64; 3]) -> crate::model::FrameRotation {
        let (a, e) = self.unit_axes();
        let w = self.omega_rad_s();
        crate::model::FrameRotation {
            omega_rad_s: a.map(|x| w * x),
            axis_point_m: [0, 1, 2].map(|k| centre_m[k] - self.radius * e[k]),
        }
    }

    /// Check r ≥ 0, n ≥ 0, finite non-zero axes across each other, ω² r ≤ 1e5 g.
    ///
    /// # Errors
    /// [`SceneError`] naming `environment.rotation.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        super::checks::non_negative("environment.rotation.radius", self.radius, "m")?;
        super::checks::non_negative("environment.rotation.rpm", self.rpm, "rev/min")?;
        for (key, v) in [("axis", self.axis), ("radial", self.radial)] {
            let n = dot(v, v).sqrt();
            if !(v.iter().all(|x| x.is_finite()) && n > 1e-150 && n.is_finite()) {
                return Err(SceneError::invalid(
                    format!("environment.rotation.{key}"),
                    format!("{v:?}"),
                    "must be a finite non-zero vector [x, y, z] (it is normalised)",
                ));
            }
        }
        let (a, e) = self.unit_axes();
        if dot(a, e).abs() > 1e-9 {
            return Err(SceneError::invalid(
                "environment.rotation.radial",
                format!("{:?}", self.radial),
                format!(
                    "must be across the axis {:?} (the direction from the axis to the \
                     container's centre)",
                    self.axis
                ),
            ));
        }
        let acc = self.centrifugal_m_s2();
        if acc > MAX_GRAVITY_M_S2 {
            return Err(SceneError::invalid(
                "environment.rotation.rpm",
                self.rpm,
                format!(
                    "gives ω²r = {acc:e} m/s² at radius {} m, above 1e5 g: check rpm \
                     (revolutions per minute) and radius (m)",
                    self.radius
                ),
            ));
        }
        Ok(())
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v).sqrt();
    v.map(|x| x / n)
}

impl Environment {
    /// Whether the table says nothing (then it is left out of saved scenes).
    pub fn is_empty(&self) -> bool {
        self.gravity.is_none() && self.rotation.is_none()
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
        if let Some(r) = &self.rotation {
            r.validate()?;
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
