//! Lorenz flow `x' = σ(y − x), y' = x(ρ − z) − y, z' = xy − βz` with σ = 10, ρ = 28, β = 8/3.

use crate::systems::sample_flow;

/// σ.
pub const SIGMA: f64 = 10.0;
/// ρ.
pub const RHO: f64 = 28.0;
/// β.
pub const BETA: f64 = 8.0 / 3.0;
/// Largest Lyapunov exponent per time unit: 0.90563 (SPEC §9; J. C. Sprott, "Chaos and
/// Time-Series Analysis", Oxford University Press 2003, Table A.1).
pub const LYAPUNOV: f64 = 0.90563;
/// Largest internal RK4 step (time units); samples are taken every `dt` on top of it.
pub const H_MAX: f64 = 1e-3;

/// Right-hand side of the Lorenz equations.
pub fn lorenz_rhs(v: &[f64; 3]) -> [f64; 3] {
    [
        SIGMA * (v[1] - v[0]),
        v[0] * (RHO - v[2]) - v[1],
        v[0] * v[1] - BETA * v[2],
    ]
}

/// `n` states sampled every `dt` time units, from (1, 1, 1) after a transient of 50 time
/// units, integrated by RK4 with internal step ≤ 1e-3.
///
/// # References
/// E. N. Lorenz, "Deterministic nonperiodic flow", J. Atmos. Sci. 20, 130–141 (1963).
/// doi:10.1175/1520-0469(1963)020<0130:DNF>2.0.CO;2
pub fn lorenz_series(n: usize, dt: f64) -> Vec<[f64; 3]> {
    let transient = (50.0 / dt).ceil() as usize;
    sample_flow(lorenz_rhs, [1.0, 1.0, 1.0], dt, H_MAX, n, transient)
}

/// The x component of [`lorenz_series`].
pub fn lorenz_x(n: usize, dt: f64) -> Vec<f64> {
    lorenz_series(n, dt).into_iter().map(|p| p[0]).collect()
}
