//! Time integration of the grains: velocity Verlet (2.2.4–2.2.5) for positions and
//! (angular) velocities, unit quaternions for orientations (2.4.11–2.4.17).

pub mod quaternion;
pub mod velocity_verlet;

pub use quaternion::advance_orientation;
pub use velocity_verlet::{drift, half_kick, half_kick_predict, kick_drift};
