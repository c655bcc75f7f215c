//! Scene files: TOML → validated [`Scene`] (SPEC §1, §3, §6).
//!
//! A scene describes one simulation: the primary system (`[primary]`, SPEC §1), the base
//! excitation (`[excitation]`), the damper (`[damper]`: none, one effective particle — SPEC §3 —,
//! or a DEM box — SPEC §2) and the run settings (`[run]`). Every key is documented with its unit
//! on the struct field that holds it; the example scenes under `data/scenes/` repeat the units.
//!
//! ```toml
//! gravity = 9.8           # m/s², optional (default 9.8), 0 for weightlessness
//! [primary]               # leave the table out for a container moved kinematically with the base
//! mass = 2.37             # kg
//! stiffness = 21500.0     # N/m
//! damping = 7.6           # N s/m  (or damping_ratio = …, dimensionless)
//! [excitation]
//! amplitude = 0.0045      # m, base displacement U in u(t) = U cos(2π f t)
//! frequency = 15.0        # Hz
//! [damper]
//! kind = "impact"         # "none" | "impact" | "dem"
//! mass = 0.227            # kg, the effective particle
//! gap = 0.0835            # m, free travel between floor and ceiling (inf: no ceiling)
//! restitution = 0.0       # effective e, 0 ≤ e ≤ 1
//! [run]
//! duration = 13.12        # s (or periods = 2000: a number of forcing periods)
//! steady_fraction = 0.1   # last fraction analysed as steady state
//! sample_interval = 1e-4  # s, output sampling
//! ```
//!
//! Any key can be overridden with a dotted name (`excitation.frequency=12`, see
//! [`SceneSource::scene`]); unknown keys are rejected with a message naming them.

mod checks;
pub mod damper;
pub mod dem;
pub mod environment;
pub mod excitation;
pub mod keys;
pub mod material;
pub mod outputs;
pub mod overrides;
pub mod presets;
pub mod primary;
pub mod run;

pub use damper::{Damper, ImpactParams};
pub use environment::Environment;
pub use excitation::{DriveKind, Excitation};
pub use outputs::Outputs;
pub use overrides::{parse_assignment, SceneSource};
pub use primary::Primary;
pub use run::{DtSpec, Run};

use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// A complete, validated simulation scene.
///
/// Build it with [`Scene::from_toml`] (or [`SceneSource`] for overrides); both validate every
/// constraint, so a `Scene` obtained from them can be simulated without further checks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Gravitational acceleration g (m/s²) along −z. Default 9.8 (SPEC §2); 0 switches gravity off.
    #[serde(default = "default_gravity")]
    pub gravity: f64,
    /// The spring-mounted primary mass (SPEC §1). `None`: the container follows the base
    /// kinematically (infinite mass), e.g. the bouncing ball on a vibrating table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub primary: Option<Primary>,
    /// The drive: base motion u(t) = U cos(2π f t), a force on the primary, or none (free
    /// decay), along `excitation.direction`.
    pub excitation: Excitation,
    /// The damper carried by the primary (default: none).
    #[serde(default)]
    pub damper: Damper,
    /// Duration, steady-state window, sampling and time-step settings.
    pub run: Run,
    /// What the run must deliver and the accepted error (`[outputs]`, optional); read by
    /// `[damper] kind = "auto"` (see [`outputs::Outputs`]).
    #[serde(default)]
    pub outputs: Outputs,
    /// Body forces (`[environment]`, optional): gravity as a vector.
    #[serde(default, skip_serializing_if = "Environment::is_empty")]
    pub environment: Environment,
}

fn default_gravity() -> f64 {
    crate::units::G
}

impl Scene {
    /// Deserialize and validate (no syntax pre-pass, no `kind = "none"` check).
    pub(crate) fn parse_validated(text: &str) -> Result<Scene, SceneError> {
        let parse_err = |e: toml::de::Error| SceneError::Parse(clean_toml_error(&e));
        let mut table: toml::Table = text.parse().map_err(parse_err)?;
        environment::check_one_gravity(&table)?;
        let mut edited = excitation::prepare(&mut table)?;
        edited |= primary::move_run_initial_state(&mut table)?;
        if let Some(toml::Value::Table(d)) = table.get_mut("damper") {
            // a material preset fills the keys the scene leaves out
            if d.contains_key("material") {
                material::fill_from_preset(d)?;
                edited = true;
            }
            // then `mass` gives the count
            edited |= dem::count_from_mass(d)?;
            // a cylinder's bounding box is its `box`
            edited |= dem::container::box_from_cylinder(d)?;
        }
        let scene: Scene = if edited {
            table.try_into().map_err(parse_err)?
        } else {
            // straight from the text, so that errors name the line
            toml::from_str(text).map_err(parse_err)?
        };
        scene.validate()?;
        Ok(scene)
    }

    /// Serialise the scene back to TOML (e.g. to store the resolved scene next to results).
    ///
    /// # Errors
    /// [`SceneError::Parse`] if a value cannot be represented (does not happen for validated scenes).
    pub fn to_toml(&self) -> Result<String, SceneError> {
        toml::to_string(self).map_err(|e| SceneError::Parse(e.to_string()))
    }

    /// Check every constraint: positive finite masses and stiffness, non-negative damping,
    /// frequencies > 0, 0 ≤ e ≤ 1, gaps ≥ 0 (or `inf`), a valid run window, no NaN anywhere.
    ///
    /// # Errors
    /// The first violated constraint, as [`SceneError::Invalid`] or [`SceneError::Missing`],
    /// naming the dotted key, the value and the fix.
    pub fn validate(&self) -> Result<(), SceneError> {
        if !self.gravity.is_finite() || self.gravity < 0.0 {
            return Err(SceneError::invalid(
                "gravity",
                self.gravity,
                "must be finite and ≥ 0 (m/s²; 9.8 on Earth, 0 for weightlessness)",
            ));
        }
        if let Some(p) = &self.primary {
            p.validate()?;
        }
        self.excitation.validate()?;
        self.environment.validate()?;
        self.check_drive()?;
        self.check_rotation()?;
        self.damper.validate()?;
        self.run.validate()?;
        self.outputs.validate()?;
        // A DEM box without [primary] moves kinematically with the base (supported by the DEM
        // run); `kind = "auto"` compares against the primary's response, so it needs one.
        if self.primary.is_none() && matches!(self.damper, Damper::Auto(_)) {
            return Err(SceneError::Missing {
                field: "primary".into(),
                hint: "damper.kind = \"auto\" needs a [primary] table (mass, stiffness, damping)"
                    .into(),
            });
        }
        if let (run::ReplicaChoice::Delta(d), Damper::None | Damper::Impact(_)) =
            (self.run.replica, &self.damper)
        {
            return Err(SceneError::invalid(
                "run.replica",
                d,
                "the two-replica test is DEM-only (damper.kind = \"dem\"); the impact model \
                 reports its exponent from tangent dynamics instead",
            ));
        }
        if let (run::ReplicaChoice::Delta(d), Damper::Dem(p)) = (self.run.replica, &self.damper) {
            let r_min = p.radius_distribution()?.r_min();
            if d >= r_min {
                return Err(SceneError::invalid(
                    "run.replica",
                    d,
                    format!(
                        "the replica's perturbation must be below the smallest grain radius \
                         ({r_min:e} m): it is a tiny push on every grain, not a rearrangement \
                         (true: 1e-9 m)"
                    ),
                ));
            }
        }
        self.check_not_undamped_resonance()?;
        Ok(())
    }

    /// The acceleration of gravity (m/s²): `environment.gravity`, else `[0, 0, −gravity]`.
    pub fn gravity_vector(&self) -> [f64; 3] {
        self.environment
            .gravity
            .unwrap_or([0.0, 0.0, -self.gravity])
    }

    /// A force drive or a free decay needs a primary; a free decay needs an initial state
    /// away from rest.
    fn check_drive(&self) -> Result<(), SceneError> {
        let kind = self.excitation.kind;
        if kind == DriveKind::Base {
            return Ok(());
        }
        let Some(p) = &self.primary else {
            return Err(SceneError::Missing {
                field: "primary".into(),
                hint: format!(
                    "excitation.kind = \"{}\" acts on a spring-mounted primary: add a [primary] \
                     table (mass, stiffness, damping)",
                    kind.name()
                ),
            });
        };
        let at_rest = p.initial_displacement.is_none_or(|z| z == 0.0)
            && p.initial_velocity.is_none_or(|v| v == 0.0);
        if kind == DriveKind::Free && at_rest {
            return Err(SceneError::Missing {
                field: "primary.initial_displacement".into(),
                hint: "a free decay starts away from rest: write primary.initial_displacement = \
                       z0 (m, from the static equilibrium) and/or primary.initial_velocity = v0 \
                       (m/s)"
                    .into(),
            });
        }
        Ok(())
    }

    /// A rotating frame acts on DEM grains only, and the primary must move along the rotation
    /// axis (across it, the primary would feel its own centrifugal stiffness, not modelled).
    fn check_rotation(&self) -> Result<(), SceneError> {
        let Some(r) = &self.environment.rotation else {
            return Ok(());
        };
        if !matches!(self.damper, Damper::Dem(_) | Damper::Auto(_)) {
            return Err(SceneError::invalid(
                "environment.rotation",
                format!("{} rpm", r.rpm),
                "acts on the grains of a DEM damper (damper.kind = \"dem\"); the one-particle \
                 model and the bare primary do not take it",
            ));
        }
        let (a, _) = r.unit_axes();
        let d = self.excitation.unit_direction();
        let c = [
            a[1] * d[2] - a[2] * d[1],
            a[2] * d[0] - a[0] * d[2],
            a[0] * d[1] - a[1] * d[0],
        ];
        if (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() > 1e-9 {
            return Err(SceneError::invalid(
                "excitation.direction",
                format!("{d:?}"),
                format!(
                    "must be along the rotation axis {:?} (environment.rotation.axis): a primary \
                     moving across the axis would feel its own centrifugal stiffness, which is \
                     not modelled",
                    r.axis
                ),
            ));
        }
        Ok(())
    }

    /// Forcing frequency f (Hz).
    pub fn frequency_hz(&self) -> f64 {
        self.excitation.frequency
    }

    /// Run duration (s): `run.duration`, or `run.periods` forcing periods.
    pub fn duration_s(&self) -> f64 {
        self.run.duration_s(self.excitation.frequency)
    }

    /// Start of the regime-analysis window (s): duration × (1 − max(analysis_fraction,
    /// steady_fraction)). The stroboscopic section and the analysed series start here.
    pub fn analysis_start_s(&self) -> f64 {
        self.duration_s() * (1.0 - self.run.analysis_fraction.max(self.run.steady_fraction))
    }

    /// Start of the steady-state window (s): duration × (1 − steady_fraction).
    pub fn steady_start_s(&self) -> f64 {
        self.duration_s() * (1.0 - self.run.steady_fraction)
    }

    /// Mass carried by the damper when it moves with the box (kg): the particle mass for the
    /// impact damper, 0 without damper. (DEM: the DEM model computes its own grain mass.)
    pub fn attached_mass_kg(&self) -> f64 {
        match &self.damper {
            Damper::Impact(p) => p.mass,
            _ => 0.0,
        }
    }

    /// An undamped primary forced exactly at one of its natural frequencies (with or without the
    /// particle attached) has no bounded steady state: the closed form would divide by zero.
    fn check_not_undamped_resonance(&self) -> Result<(), SceneError> {
        let Some(p) = &self.primary else {
            return Ok(());
        };
        let omega = crate::units::TWO_PI * self.excitation.frequency;
        let c = p.damping_n_s_m();
        for m in [p.mass, p.mass + self.attached_mass_kg()] {
            let detune = (p.stiffness - m * omega * omega).abs();
            if detune + c * omega < 1e-9 * p.stiffness {
                return Err(SceneError::invalid(
                    "excitation.frequency",
                    self.excitation.frequency,
                    "forces an undamped primary exactly at its natural frequency (unbounded \
                     response); add primary.damping > 0 or shift the frequency",
                ));
            }
        }
        Ok(())
    }
}

/// Shorten toml's multi-line error to something that still names the line and key.
fn clean_toml_error(e: &toml::de::Error) -> String {
    e.to_string().trim_end().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    const B: &str = r#"
        [primary]
        mass = 2.37
        stiffness = 21500.0
        damping = 7.6
        [excitation]
        amplitude = 0.0045
        frequency = 15.0
        [damper]
        kind = "impact"
        mass = 0.227
        gap = 0.0835
        restitution = 0.0
        [run]
        duration = 13.12
    "#;

    #[test]
    fn parses_defaults() {
        let s = Scene::from_toml(B).unwrap();
        assert_eq!(s.gravity, 9.8);
        assert_eq!(s.run.steady_fraction, 0.1);
        assert_eq!(s.run.sample_interval, 1e-4);
        assert!(matches!(s.damper, Damper::Impact(ref p) if p.gap == 0.0835));
        assert!((s.steady_start_s() - 13.12 * 0.9).abs() < 1e-12);
    }

    #[test]
    fn roundtrips_through_toml() {
        let s = Scene::from_toml(B).unwrap();
        let again = Scene::from_toml(&s.to_toml().unwrap()).unwrap();
        assert_eq!(s, again);
    }

    #[test]
    fn rejects_unknown_key_by_name() {
        let text = B.replace("gap = 0.0835", "gap = 0.0835\nspeling = 1");
        let err = Scene::from_toml(&text).unwrap_err().to_string();
        assert!(err.contains("speling"), "{err}");
    }

    #[test]
    fn rejects_undamped_resonance() {
        let f0 = (21500.0f64 / 2.37).sqrt() / crate::units::TWO_PI;
        let text = format!(
            "[primary]\nmass = 2.37\nstiffness = 21500.0\ndamping = 0.0\n[excitation]\namplitude = 0.001\nfrequency = {f0}\n[run]\nduration = 1.0\n"
        );
        let err = Scene::from_toml(&text).unwrap_err().to_string();
        assert!(err.contains("excitation.frequency"), "{err}");
    }
}
