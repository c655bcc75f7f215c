//! The engine's errors named by the scene keys that set the quantities: the engine speaks of
//! physics ([`ModelError`], [`Quantity`]), the resolve step of the scene
//! (`run.dt = 1e-4 s: …`).

use crate::error::{ModelError, Quantity, SceneError, SimError};

/// The scene key that sets an engine quantity.
pub fn scene_key(q: Quantity) -> &'static str {
    match q {
        Quantity::TimeStep => "run.dt",
        Quantity::TimeStepFraction => "run.dt_fraction",
        Quantity::Duration => "run.duration",
        Quantity::SampleInterval => "run.sample_interval",
        Quantity::SteadyFraction => "run.steady_fraction",
        Quantity::Restitution => "damper.restitution",
        Quantity::WallRestitution => "damper.wall_restitution",
        Quantity::YieldStrength => "damper.yield_strength",
        Quantity::GrainCount => "damper.count",
        Quantity::ReplicaPerturbation => "run.replica",
        Quantity::BagSize => "damper.bag",
    }
}

/// What to change in the scene file, for quantities whose fix involves several keys.
fn scene_fix(q: Quantity) -> Option<&'static str> {
    match q {
        Quantity::TimeStep => {
            Some("in the scene: lower run.dt, use dt = \"auto\", or lower damper.youngs_modulus")
        }
        Quantity::SteadyFraction => {
            Some("in the scene: raise run.duration (or run.periods) or run.steady_fraction")
        }
        Quantity::BagSize => Some(
            "in the scene: lower damper.count, enlarge damper.bag (diameter, length) or use \
             smaller film nodes (damper.bag.node_radius)",
        ),
        Quantity::GrainCount => Some(
            "in the scene: lower damper.count, enlarge damper.box or use \
             damper.packing = \"advancing-front\"",
        ),
        _ => None,
    }
}

/// An engine error named by its scene key: `run.dt = 1e-4 s: is larger than t_s/20 …`.
pub fn scene_error(e: ModelError) -> SceneError {
    let hint = match scene_fix(e.quantity) {
        Some(fix) => format!("{} ({}); {fix}", e.hint, e.quantity),
        None => format!("{} ({})", e.hint, e.quantity),
    };
    SceneError::Invalid {
        field: scene_key(e.quantity).into(),
        value: e.value,
        hint,
    }
}

/// [`SimError::Model`] mapped to [`SimError::Scene`] with the scene key
/// ([`scene_error`]); other errors unchanged.
pub fn keyed(e: SimError) -> SimError {
    match e {
        SimError::Model(m) => SimError::Scene(scene_error(m)),
        other => other,
    }
}

/// The DEM's instabilities (non-finite state, escaped grains, energy created) all come from
/// a time step too long for the contact stiffness: name the keys that set it.
pub(super) fn dem_instability_keys(e: SimError) -> SimError {
    match e {
        SimError::Unstable { t_s, reason } => SimError::Unstable {
            t_s,
            reason: format!(
                "{reason} (in the scene: lower run.dt or run.dt_fraction, or damper.youngs_modulus)"
            ),
        },
        other => other,
    }
}
