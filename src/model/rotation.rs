//! A damper on a rotating part (a turbine blade, a rotor arm): the simulation's frame turns at
//! a constant angular velocity Ω about a fixed axis, and every grain feels the inertial forces
//! of that frame.
//!
//! # Formula
//! With R = p − a the grain's position from a point a of the rotation axis,
//! R⊥ = R − (R·Ω̂)Ω̂ its part across the axis and v its velocity in the rotating frame:
//!
//! - centrifugal acceleration a_cf = −Ω × (Ω × R) = |Ω|² R⊥ (m/s²), potential −½ m |Ω|² |R⊥|²;
//! - Coriolis acceleration a_co = −2 Ω × v (m/s²), no work.
//!
//! Both are included: the frame turns with the damper. The Euler force −Ω' × R is zero at a
//! constant speed.
//!
//! # References
//! Any dynamics text (Goldstein, *Classical Mechanics*, §4.10, the equation of motion in a
//! rotating frame); the linear-DEM paper's §3.3 (a damper at 0.4 m from the axis, 138 rpm).

/// A frame rotating at Ω (rad/s, a vector along the axis) about the axis through `axis_point_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameRotation {
    /// Angular velocity Ω (rad/s), along the rotation axis.
    pub omega_rad_s: [f64; 3],
    /// A point of the rotation axis (m), in the simulation's coordinates.
    pub axis_point_m: [f64; 3],
}

impl FrameRotation {
    /// Inertial acceleration of the frame at position `p` (m) with velocity `v` (m/s):
    /// |Ω|² R⊥ − 2 Ω × v (m/s², see the module formula).
    #[inline]
    pub fn acceleration(&self, p: [f64; 3], v: [f64; 3]) -> [f64; 3] {
        let w = self.omega_rad_s;
        let r = [
            p[0] - self.axis_point_m[0],
            p[1] - self.axis_point_m[1],
            p[2] - self.axis_point_m[2],
        ];
        // −Ω × (Ω × R) = |Ω|² R − (Ω·R) Ω
        let (ww, wr) = (dot(w, w), dot(w, r));
        let cf = [0, 1, 2].map(|k| ww * r[k] - wr * w[k]);
        let c = cross(w, v);
        [0, 1, 2].map(|k| cf[k] - 2.0 * c[k])
    }

    /// Centrifugal potential energy −½ m |Ω × R|² (J) of a mass `m` (kg) at `p` (m).
    pub fn potential_j(&self, m: f64, p: [f64; 3]) -> f64 {
        let r = [0, 1, 2].map(|k| p[k] - self.axis_point_m[k]);
        let c = cross(self.omega_rad_s, r);
        -0.5 * m * dot(c, c)
    }
}

// (the model layer sits below `contact`, whose vector helpers the engines use)
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
