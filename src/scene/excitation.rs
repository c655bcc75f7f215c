//! `[excitation]`: how the primary is driven — through its base, u(t) = U cos(2π f t) (SPEC §1),
//! by a harmonic force F0 sin(2π f t) on its mass, or not at all (free decay) — and along which
//! axis.

use super::checks::{non_negative, positive};
use crate::error::SceneError;
use serde::{Deserialize, Serialize};

/// What drives the primary (`excitation.kind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DriveKind {
    /// Base motion u(t) = U cos(Ω t) through the spring and the damper (2.1.2); the default.
    #[default]
    Base,
    /// A force F0 sin(Ω t) on the primary mass, the base at rest.
    Force,
    /// No drive: the primary starts from `primary.initial_displacement` /
    /// `primary.initial_velocity` and decays freely.
    Free,
}

impl DriveKind {
    /// Whether this is the default (base motion); used to leave the key out of saved scenes.
    pub fn is_base(&self) -> bool {
        *self == DriveKind::Base
    }

    /// The key's spelling.
    pub fn name(&self) -> &'static str {
        match self {
            DriveKind::Base => "base",
            DriveKind::Force => "force",
            DriveKind::Free => "free",
        }
    }
}

/// The drive of the primary.
///
/// `kind = "base"` (default): base displacement u(t) = U cos(Ω t), Ω = 2π f, with `amplitude`
/// U (m). `kind = "force"`: a force F(t) = F0 sin(Ω t) on the primary mass with
/// `force_amplitude` F0 (N). `kind = "free"`: no drive; `frequency` is optional (default the
/// primary's natural frequency f0) and only sets the clock of `run.periods`, the sampling of
/// the analysis and the stroboscopic section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Excitation {
    /// What drives the primary: `"base"` (default), `"force"` or `"free"`.
    #[serde(default, skip_serializing_if = "DriveKind::is_base")]
    pub kind: DriveKind,
    /// Base displacement amplitude U (m), ≥ 0; required with `kind = "base"`, absent or 0
    /// otherwise.
    #[serde(default)]
    pub amplitude: f64,
    /// Force amplitude F0 (N), ≥ 0; `kind = "force"` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force_amplitude: Option<f64>,
    /// Forcing frequency f (Hz), > 0.
    pub frequency: f64,
    /// Axis along which the primary (and the container on it) moves, `[x, y, z]`: any finite
    /// non-zero vector, normalised (default `[0, 0, 1]`, vertical). Gravity stays where
    /// `gravity` / `environment.gravity` puts it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f64; 3]>,
}

impl Excitation {
    /// A vertical base drive u(t) = U cos(2π f t) with amplitude U (m) at f (Hz).
    pub fn base(amplitude: f64, frequency: f64) -> Excitation {
        Excitation {
            kind: DriveKind::Base,
            amplitude,
            force_amplitude: None,
            frequency,
            direction: None,
        }
    }

    /// Angular forcing frequency Ω = 2π f (rad/s).
    pub fn omega_rad_s(&self) -> f64 {
        crate::units::TWO_PI * self.frequency
    }

    /// Forcing period T = 1/f (s).
    pub fn period_s(&self) -> f64 {
        1.0 / self.frequency
    }

    /// Force amplitude F0 (N) of a force drive, 0 otherwise.
    pub fn force_n(&self) -> f64 {
        match self.kind {
            DriveKind::Force => self.force_amplitude.unwrap_or(0.0),
            _ => 0.0,
        }
    }

    /// The drive axis as a unit vector (default e_z). Call after [`Excitation::validate`].
    pub fn unit_direction(&self) -> [f64; 3] {
        match self.direction {
            None => [0.0, 0.0, 1.0],
            Some(d) => {
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if n == 1.0 {
                    d
                } else {
                    [d[0] / n, d[1] / n, d[2] / n]
                }
            }
        }
    }

    /// Whether the drive axis is the default vertical e_z (bit for bit).
    pub fn is_vertical(&self) -> bool {
        self.unit_direction() == [0.0, 0.0, 1.0]
    }

    /// Check the keys of the drive's kind: U ≥ 0 for a base drive, F0 ≥ 0 for a force drive,
    /// no amplitude of the other kind, f > 0, a finite non-zero direction.
    ///
    /// # Errors
    /// [`SceneError`] naming `excitation.<key>` and the fix.
    pub fn validate(&self) -> Result<(), SceneError> {
        non_negative("excitation.amplitude", self.amplitude, "m")?;
        positive("excitation.frequency", self.frequency, "Hz")?;
        match (self.kind, self.force_amplitude) {
            (DriveKind::Force, None) => {
                return Err(SceneError::Missing {
                    field: "excitation.force_amplitude".into(),
                    hint: "kind = \"force\" drives the primary mass with F0 sin(2π f t): write \
                           force_amplitude = F0 (N)"
                        .into(),
                })
            }
            (DriveKind::Force, Some(f0)) => {
                non_negative("excitation.force_amplitude", f0, "N")?;
            }
            (kind, Some(f0)) => {
                return Err(SceneError::invalid(
                    "excitation.force_amplitude",
                    f0,
                    format!(
                        "is a key of kind = \"force\", not of kind = \"{}\": remove it, or set \
                         excitation.kind = \"force\"",
                        kind.name()
                    ),
                ))
            }
            _ => {}
        }
        if self.kind != DriveKind::Base && self.amplitude != 0.0 {
            return Err(SceneError::invalid(
                "excitation.amplitude",
                self.amplitude,
                format!(
                    "is the base motion's amplitude, and kind = \"{}\" keeps the base at rest: \
                     remove it (or set excitation.kind = \"base\")",
                    self.kind.name()
                ),
            ));
        }
        if let Some(d) = self.direction {
            let n2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if !(d.iter().all(|x| x.is_finite()) && n2.is_finite() && n2 > 1e-300) {
                return Err(SceneError::invalid(
                    "excitation.direction",
                    format!("{d:?}"),
                    "must be a finite non-zero vector [x, y, z] (it is normalised), e.g. \
                     [1, 0, 0] for a horizontal drive along x",
                ));
            }
        }
        Ok(())
    }
}

/// Checks on the raw `[excitation]` table that the typed one cannot make, because a missing
/// key there reads as 0: a base drive needs `amplitude`. A free decay without `frequency`
/// gets the primary's natural frequency f0 = sqrt(K/M)/(2π) (the clock of `run.periods` and
/// of the section). Returns whether the table was changed.
///
/// # Errors
/// [`SceneError::Missing`] naming the absent key.
pub(crate) fn prepare(table: &mut toml::Table) -> Result<bool, SceneError> {
    let f0 = natural_frequency(table);
    let Some(toml::Value::Table(e)) = table.get_mut("excitation") else {
        return Ok(false);
    };
    let kind = e
        .get("kind")
        .and_then(toml::Value::as_str)
        .unwrap_or("base");
    if kind == "base" && !e.contains_key("amplitude") {
        return Err(SceneError::Missing {
            field: "excitation.amplitude".into(),
            hint: "a base drive u(t) = U cos(2π f t) needs amplitude = U (m); or set kind = \
                   \"force\" (force_amplitude, N) or \"free\" (a free decay)"
                .into(),
        });
    }
    if kind == "free" && !e.contains_key("frequency") {
        let Some(f0) = f0 else {
            return Err(SceneError::Missing {
                field: "excitation.frequency".into(),
                hint: "a free decay without [primary] has no natural frequency to count \
                       periods by: write frequency = f (Hz)"
                    .into(),
            });
        };
        e.insert("frequency".into(), toml::Value::Float(f0));
        return Ok(true);
    }
    Ok(false)
}

/// f0 = sqrt(K/M)/(2π) (Hz) of the raw `[primary]` table, when both keys are positive numbers.
fn natural_frequency(table: &toml::Table) -> Option<f64> {
    let p = table.get("primary")?.as_table()?;
    let num = |k: &str| {
        p.get(k)
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
    };
    let (m, k) = (num("mass")?, num("stiffness")?);
    let f0 = (k / m).sqrt() / crate::units::TWO_PI;
    (f0.is_finite() && f0 > 0.0).then_some(f0)
}
