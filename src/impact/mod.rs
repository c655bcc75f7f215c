//! Event-driven one-particle impact damper (SPEC §3), the primary alone (SPEC §1) and the
//! bouncing ball on a kinematically driven table.
//!
//! # How it works
//! Time advances segment by segment; within a segment nothing discontinuous happens, so the
//! state is known exactly in closed form ([`crate::model::Sdof`]: the primary's linear ODE with
//! harmonic forcing; the particle flies ballistically). Each segment is at most a fraction
//! (1/16) of the fastest time scale (forcing period, natural period, fastest decay), and within
//! it:
//! 1. the event functions are checked at the segment end and for an interior extremum
//!    ([`events::first_crossing`]): in flight the floor gap y − z and the ceiling gap
//!    z + gap − y; while the particle rests on the floor the sticking condition z'' + g ≥ 0,
//!    pressed to the ceiling z'' + g ≤ 0 (2.1.27); the first event is located by Brent's method
//!    to ~1e-13 s;
//! 2. samples and stroboscopic points falling inside the segment are evaluated exactly from the
//!    closed forms;
//! 3. the base work and the viscous loss are integrated by 8-point Gauss–Legendre quadrature of
//!    the closed forms (exact to rounding at this segment length);
//! 4. the event is applied: an impact ([`collision::collide`], (2.1.25)–(2.1.26), loss (5.3.1)),
//!    the start of a sticking phase (box and particle move together, mass M + m_p, the weight
//!    m_p g loads the primary) or a detachment.
//!
//! Chattering (infinitely many impacts in finite time as e < 1 settles the particle) is cut:
//! when the separation speed after an impact is below s* = sqrt(2 g_eff h*), with
//! h* = 1e-11 × the length scale of the problem (an apex far below anything resolvable), the
//! remaining relative motion is removed by a plastic impact (its kinetic energy, ½ μ s², is
//! booked as impact loss) and the particle sticks if (2.1.27) allows it. Stalled event sequences
//! (no time progress) are detected and resolved, so a run always ends.
//!
//! [`lyapunov`] computes the largest Lyapunov exponent of the stroboscopic map from the model's
//! own equations (tangent dynamics with saltation matrices, riding on the same segment loop
//! through a hook; and two diverging copies of the model as a cross-check).
//!
//! # Files
//! `model.rs` (the inputs, the particle's mode, the state), `world.rs` ([`ImpactWorld`]
//! built from a setup, its energy and summary), `run.rs` (the segment loop), `segment.rs`
//! (a segment's event search and the events applied), `motion.rs` (the box's closed forms),
//! `quadrature.rs` (the ledger's integrals), `ledger.rs` (the run's sums), [`events`] (root
//! finding), [`collision`] (the impact law) and [`lyapunov`].

pub mod collision;
pub mod events;
mod ledger;
pub mod lyapunov;
mod model;
mod motion;
mod quadrature;
mod run;
mod segment;
mod world;

pub use lyapunov::{LyapunovMethod, ModelLyapunov, ModelLyapunovOptions};
pub use model::{ImpactParticle, ImpactSetup, Mode};
pub use world::{simulate, ImpactWorld};
