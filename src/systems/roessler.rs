//! Rössler flow `x' = −y − z, y' = x + a y, z' = b + z (x − c)` with a = b = 0.2, c = 5.7.

use crate::systems::sample_flow;

/// a.
pub const A: f64 = 0.2;
/// b.
pub const B: f64 = 0.2;
/// c.
pub const C: f64 = 5.7;
/// Largest Lyapunov exponent per time unit: 0.0714 (SPEC §9; J. C. Sprott, "Chaos and
/// Time-Series Analysis", Oxford University Press 2003, Table A.1).
pub const LYAPUNOV: f64 = 0.0714;
/// Mean rotation period of the attractor, ≈ 5.9 time units (angular frequency ≈ 1.07, the
/// spectral peak of x; e.g. Sprott 2003, §10). The first minimum of the mutual information
/// of x lies near a quarter of it, ≈ 1.5 time units, as for any nearly harmonic rotation.
pub const MEAN_PERIOD: f64 = 5.9;
/// Largest internal RK4 step (time units).
pub const H_MAX: f64 = 1e-2;

/// Right-hand side of the Rössler equations.
pub fn roessler_rhs(v: &[f64; 3]) -> [f64; 3] {
    [-v[1] - v[2], v[0] + A * v[1], B + v[2] * (v[0] - C)]
}

/// `n` states sampled every `dt` from (1, 1, 0) after a transient of 200 time units.
///
/// # References
/// O. E. Rössler, "An equation for continuous chaos", Phys. Lett. A 57, 397–398 (1976).
/// doi:10.1016/0375-9601(76)90101-8
pub fn roessler_series(n: usize, dt: f64) -> Vec<[f64; 3]> {
    let transient = (200.0 / dt).ceil() as usize;
    sample_flow(roessler_rhs, [1.0, 1.0, 0.0], dt, H_MAX, n, transient)
}

/// The x component of [`roessler_series`].
pub fn roessler_x(n: usize, dt: f64) -> Vec<f64> {
    roessler_series(n, dt).into_iter().map(|p| p[0]).collect()
}
