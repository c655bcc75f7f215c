//! The box's motion in closed form: on the primary's spring ([`Sdof`]) or imposed (the base
//! motion), and the phase rotation the segment loop advances.

use crate::model::primary::base_motion;
use crate::model::{Anchor, Sdof};

/// Motion of the box: on the primary's spring (closed form) or imposed (= base motion).
#[derive(Debug, Clone, Copy)]
pub(super) enum BoxMotion {
    Spring(Sdof),
    Kinematic { u_amp: f64, omega: f64 },
}

impl BoxMotion {
    #[inline]
    pub(super) fn anchor(&self, t: f64, z: f64, v: f64) -> Anchor {
        match self {
            BoxMotion::Spring(s) => s.anchor(t, z, v),
            BoxMotion::Kinematic { .. } => Anchor {
                t0_s: t,
                y0: 0.0,
                w0: 0.0,
            },
        }
    }
    #[inline]
    pub(super) fn eval(&self, an: &Anchor, t: f64) -> (f64, f64) {
        match self {
            BoxMotion::Spring(s) => s.eval(an, t),
            BoxMotion::Kinematic { u_amp, omega } => {
                let (u, du, _) = base_motion(*u_amp, *omega, t);
                (u, du)
            }
        }
    }
    #[inline]
    pub(super) fn accel(&self, t: f64, z: f64, v: f64) -> f64 {
        match self {
            BoxMotion::Spring(s) => s.accel(t, z, v),
            BoxMotion::Kinematic { u_amp, omega } => base_motion(*u_amp, *omega, t).2,
        }
    }
    #[inline]
    pub(super) fn jerk(&self, t: f64, v: f64, acc: f64) -> f64 {
        match self {
            BoxMotion::Spring(s) => s.jerk(t, v, acc),
            BoxMotion::Kinematic { u_amp, omega } => {
                let (s, _) = (omega * t).sin_cos();
                u_amp * omega * omega * omega * s
            }
        }
    }
}

/// (sin(A + B), cos(A + B)) from (sin A, cos A) and (sin B, cos B).
#[inline]
pub(super) fn rotate(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.1 + a.1 * b.0, a.1 * b.1 - a.0 * b.0)
}
