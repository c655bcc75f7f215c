//! What the event-driven model is given and where it is: the resolved inputs
//! ([`ImpactSetup`], [`ImpactParticle`]), the particle's [`Mode`] and the dynamic state.

use crate::model::{BoxDrive, RunWindow};

/// The one effective particle of the impact damper (SPEC §3), resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactParticle {
    /// Effective particle mass m_p (kg), > 0.
    pub mass_kg: f64,
    /// Free travel between floor and ceiling (m), ≥ 0; `inf`: no ceiling; 0: clamped.
    pub gap_m: f64,
    /// Effective coefficient of restitution e (–), 0 ≤ e ≤ 1 (2.1.23).
    pub restitution: f64,
    /// Initial height above the floor (m), 0 ≤ h ≤ gap.
    pub initial_height_m: f64,
    /// Initial velocity in the lab frame (m/s).
    pub initial_velocity_m_s: f64,
}

/// Everything the event-driven model needs, resolved and validated by [`crate::setup`]:
/// gravity, the box drive (primary + base motion, or a kinematic box), the particle (none:
/// the primary alone), the initial box state and the run's windows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactSetup {
    /// Gravitational acceleration g (m/s², along −z), ≥ 0.
    pub gravity_m_s2: f64,
    /// The box drive; `primary = None` moves the box with the base (bouncing ball).
    pub drive: BoxDrive,
    /// The particle, or `None` for the primary alone.
    pub particle: Option<ImpactParticle>,
    /// Initial displacement z(0) (m); `None`: static equilibrium with a resting particle.
    pub initial_box_z_m: Option<f64>,
    /// Initial velocity z'(0) (m/s); `None`: 0.
    pub initial_box_v_m_s: Option<f64>,
    /// Duration, steady-state and analysis windows (s).
    pub window: RunWindow,
}

/// Where the particle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// No particle (primary alone).
    Free,
    /// Particle in flight between floor and ceiling.
    Flight,
    /// Particle resting on the floor, moving with the box.
    Floor,
    /// Particle pressed against the ceiling, moving with the box.
    Ceiling,
    /// Zero gap: the particle is clamped to the box for good.
    Clamped,
}

impl Mode {
    /// Code written in the `contact` column: 0 flight (or no particle), 1 floor, 2 ceiling,
    /// 3 clamped.
    pub fn code(self) -> f64 {
        match self {
            Mode::Free | Mode::Flight => 0.0,
            Mode::Floor => 1.0,
            Mode::Ceiling => 2.0,
            Mode::Clamped => 3.0,
        }
    }
    pub(super) fn stuck(self) -> bool {
        matches!(self, Mode::Floor | Mode::Ceiling | Mode::Clamped)
    }
}

/// The particle's parameters (SPEC §3).
#[derive(Debug, Clone, Copy)]
pub(super) struct Particle {
    pub(super) mass: f64,
    pub(super) gap: f64,
    pub(super) e: f64,
}

impl From<ImpactParticle> for Particle {
    fn from(p: ImpactParticle) -> Particle {
        Particle {
            mass: p.mass_kg,
            gap: p.gap_m,
            e: p.restitution,
        }
    }
}

/// Dynamic state.
#[derive(Debug, Clone, Copy)]
pub(super) struct State {
    pub(super) t: f64,
    pub(super) z: f64,
    pub(super) v: f64,
    pub(super) y: f64,
    pub(super) w: f64,
    pub(super) mode: Mode,
    /// Wall just left (the event root at the segment start is ignored): 1 floor, 2 ceiling.
    pub(super) departing: u8,
}
