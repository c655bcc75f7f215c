//! The box's drive of a validated scene, as the engines take it ([`BoxDrive`]).

use crate::model::BoxDrive;
use crate::scene::Scene;

/// The box's drive of a validated scene: the primary, the base or force amplitude, the
/// frequency and the unit drive axis.
pub fn box_drive(scene: &Scene) -> BoxDrive {
    BoxDrive {
        primary: scene.primary.as_ref().map(|p| p.system()),
        amplitude_m: scene.excitation.amplitude,
        frequency_hz: scene.excitation.frequency,
        force_n: scene.excitation.force_n(),
        direction: scene.excitation.unit_direction(),
    }
}
