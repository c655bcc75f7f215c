//! Reference dynamical systems with literature values (SPEC §9), shared by tests, examples,
//! benchmarks and the CLI's self-checks so that each reference value is defined once.
//!
//! - [`logistic`]: logistic map, λ = ln 2 at r = 4.
//! - [`henon`]: Hénon map (1.4, 0.3), λ = 0.419217.
//! - [`lorenz`]: Lorenz flow (10, 28, 8/3), λ₁ = 0.90563 per time unit.
//! - [`roessler`]: Rössler flow (0.2, 0.2, 5.7), λ₁ = 0.0714 per time unit.
//! - [`bouncing_ball`]: ball on a vibrating table, period-1 thresholds in Γ.
//! - [`forced_ring`]: a driven damped oscillator kicked by a ring of chaotic maps (regime
//!   verdicts of a collective motion stirred by a high-dimensional chaotic subsystem).

pub mod bouncing_ball;
pub mod forced_ring;
pub mod henon;
pub mod logistic;
pub mod lorenz;
pub mod roessler;

/// One classical fourth-order Runge–Kutta step of `dy/dt = f(y)` for a 3-dimensional state.
pub fn rk4_step(f: impl Fn(&[f64; 3]) -> [f64; 3], y: &[f64; 3], h: f64) -> [f64; 3] {
    let add = |a: &[f64; 3], b: &[f64; 3], s: f64| -> [f64; 3] {
        [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
    };
    let k1 = f(y);
    let k2 = f(&add(y, &k1, 0.5 * h));
    let k3 = f(&add(y, &k2, 0.5 * h));
    let k4 = f(&add(y, &k3, h));
    std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// Samples a 3-D flow every `dt` (time units) after discarding `transient` samples, using
/// RK4 with `substeps = ⌈dt / h_max⌉` internal steps per sample.
pub fn sample_flow(
    f: impl Fn(&[f64; 3]) -> [f64; 3] + Copy,
    y0: [f64; 3],
    dt: f64,
    h_max: f64,
    n: usize,
    transient: usize,
) -> Vec<[f64; 3]> {
    let substeps = (dt / h_max).ceil().max(1.0) as usize;
    let h = dt / substeps as f64;
    let mut y = y0;
    let mut out = Vec::with_capacity(n);
    for k in 0..n + transient {
        if k >= transient {
            out.push(y);
        }
        for _ in 0..substeps {
            y = rk4_step(f, &y, h);
        }
    }
    out
}
