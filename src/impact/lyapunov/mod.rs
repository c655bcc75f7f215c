//! Largest Lyapunov exponent of the impact model's stroboscopic map (t = kT), computed from the
//! model's own equations rather than from a series: a tangent vector carried along the exact
//! event-driven trajectory by the closed-form flow Jacobians and the saltation matrices of the
//! events ([`ImpactWorld::model_lyapunov`]), and, as an independent cross-check sharing no
//! tangent code, the divergence of two copies of the model (Benettin;
//! [`ImpactWorld::model_lyapunov_two_trajectory`]).
//!
//! # How it works
//! The state is x = (z, z', y, y') = (box position and velocity, particle position and
//! velocity); for a kinematic box (no `[primary]`) z, z' are given functions of time and only
//! the particle's components are perturbed. The tangent vector δx follows the run of
//! [`ImpactWorld::run`] (the same trajectory, bit for bit, through a hook in its segment loop):
//! - between events, the exact linear flow: the box by the homogeneous solution of the free
//!   (flight) or loaded (M + m_p, particle stuck) primary (2.1.2), the particle in flight by
//!   δy += δy' τ, a stuck particle by δy = δz, δy' = δz';
//! - at an impact (h = y − z on the floor, h = z + gap − y at the ceiling) the saltation matrix
//!   S = J_g + (f⁺ − J_g f⁻) ∇hᵀ / (∇h · f⁻), J_g the Jacobian of the collision law
//!   (2.1.25)–(2.1.26) (linear in the velocities), f∓ the vector fields just before and after;
//! - at the chattering cut (a plastic impact, e = 0, that starts a sticking phase) the same
//!   formula with the plastic J_g and the loaded field f⁺: it maps δx onto the constrained
//!   manifold y = z (+ gap), y' = z';
//! - at lift-off (event function z'' + g, (2.1.27)) S = I + (f⁺ − f⁻) ∇h_dᵀ / ḣ_d; the contact
//!   force vanishes there, so f⁺ = f⁻ and S = I to rounding (computed anyway).
//!
//! The vector is renormalised at every t = kT; the logarithms of the growth factors over the
//! steady window (after the scene's `steady_start`) are averaged.
//!
//! [`ImpactWorld::model_lyapunov`]: super::ImpactWorld::model_lyapunov
//! [`ImpactWorld::model_lyapunov_two_trajectory`]: super::ImpactWorld::model_lyapunov_two_trajectory
//! [`ImpactWorld::run`]: super::ImpactWorld::run
//!
//! # Files
//! `estimate.rs` (the result, the options, the norm and the batch means), `tangent.rs` (the
//! tangent estimate and its saltation matrices), `two_trajectory.rs` (the cross-check).

mod estimate;
mod tangent;
mod two_trajectory;

pub use estimate::{LyapunovMethod, ModelLyapunov, ModelLyapunovOptions};
