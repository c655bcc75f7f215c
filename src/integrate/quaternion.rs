//! Orientation of spheres as unit quaternions (2.4.11–2.4.17).
//!
//! Spheres' dynamics do not depend on orientation, so orientations are only tracked when the
//! scene asks for them (`damper.orientations = true`), e.g. for snapshots.

use nalgebra::{UnitQuaternion, Vector3};

/// Rotates `q` by the lab-frame angular velocity ω over dt and renormalises (–).
///
/// # Formula
/// q(t + dt) = exp(½ ω dt) ⊗ q(t), then q ← q/|q| (2.4.11–2.4.17): singularity-free,
/// unlike Euler angles.
///
/// # Units
/// `omega` rad/s, `dt` s.
pub fn advance_orientation(q: &mut UnitQuaternion<f64>, omega: [f64; 3], dt: f64) {
    let w = Vector3::new(omega[0], omega[1], omega[2]) * dt;
    let r = UnitQuaternion::from_scaled_axis(w);
    let mut next = (r * *q).into_inner();
    next.normalize_mut();
    *q = UnitQuaternion::new_unchecked(next);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_spin_gives_the_exact_angle() {
        let mut q = UnitQuaternion::identity();
        for _ in 0..1000 {
            advance_orientation(&mut q, [0.0, 0.0, 2.0], 1e-3);
        }
        // 2 rad/s for 1 s about z: angle 2 rad (exact composition), norm 1 to round-off
        assert!((q.angle() - 2.0).abs() < 1e-9);
        assert!((q.into_inner().norm() - 1.0).abs() < 1e-14);
    }
}
