//! Fixtures shared by the integration tests (each test file that needs them declares
//! `mod common;`): scene B's primary system, seeded noise generators, the (2.1.21) amplitude
//! adapters and the design tests' source-file walker. Each test binary uses a part of them,
//! hence `dead_code` is allowed for the module.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use pdamp::model::{BoxDrive, PrimarySystem};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

// ---------------------------------------------------------------------------------------
// Scene B (Sánchez 2012 §3.2, SPEC §6; the preset `Scene::thesis_b_impact()` and
// data/scenes/thesis_b*.toml hold the same numbers)

/// Scene B's primary mass M (kg).
pub const SCENE_B_MASS_KG: f64 = 2.37;
/// Scene B's spring stiffness K (N/m).
pub const SCENE_B_STIFFNESS_N_M: f64 = 21500.0;
/// Scene B's viscous damping C (N s/m).
pub const SCENE_B_DAMPING_N_S_M: f64 = 7.6;
/// Scene B's base amplitude U (m).
pub const SCENE_B_AMPLITUDE_M: f64 = 4.5e-3;
/// Mass of scene B's 250 steel spheres, m_p = 250 × 8030 × 4/3 π (3 mm)³ (kg), the one
/// particle of the impact-damper equivalent.
pub const SCENE_B_PARTICLE_MASS_KG: f64 = 0.227;
/// Gap of scene B's impact-damper equivalent (m).
pub const SCENE_B_GAP_M: f64 = 0.0835;

/// Scene B's primary system: M = 2.37 kg, K = 21500 N/m, C = 7.6 N s/m (f0 = 15.16 Hz).
pub fn scene_b_primary() -> PrimarySystem {
    PrimarySystem {
        mass_kg: SCENE_B_MASS_KG,
        stiffness_n_m: SCENE_B_STIFFNESS_N_M,
        damping_n_s_m: SCENE_B_DAMPING_N_S_M,
    }
}

/// The box on scene B's primary, driven through its base with U = 4.5 mm at `frequency_hz`.
pub fn scene_b_drive(frequency_hz: f64) -> BoxDrive {
    BoxDrive {
        primary: Some(scene_b_primary()),
        amplitude_m: SCENE_B_AMPLITUDE_M,
        frequency_hz,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    }
}

// ---------------------------------------------------------------------------------------
// Steady-state amplitude (2.1.21), through the library's one implementation

/// Z(f) of (2.1.21) (m) for M (kg), C (N s/m), K (N/m), U (m) at `f` (Hz).
pub fn sdof_amplitude(f: f64, m: f64, c: f64, k: f64, u: f64) -> f64 {
    PrimarySystem {
        mass_kg: m,
        stiffness_n_m: k,
        damping_n_s_m: c,
    }
    .steady_amplitude_at_hz(u, f)
}

/// Steady amplitude (2.1.21) (m) of a scene's primary carrying `added_mass_kg` as rigid
/// added mass (0 for the primary alone), at the scene's forcing.
pub fn scene_reference_amplitude(s: &pdamp::scene::Scene, added_mass_kg: f64) -> f64 {
    s.primary
        .as_ref()
        .expect("a scene with a primary")
        .system()
        .with_added_mass(added_mass_kg)
        .steady_amplitude_m(s.excitation.amplitude, s.excitation.omega_rad_s())
}

// ---------------------------------------------------------------------------------------
// Seeded noise (every generator is reproducible from its seed)

/// A stream of standard Gaussian samples N(0, 1) from a seeded ChaCha8 generator.
pub struct Gaussian(ChaCha8Rng);

impl Gaussian {
    /// The stream of `seed`.
    pub fn new(seed: u64) -> Self {
        Gaussian(ChaCha8Rng::seed_from_u64(seed))
    }

    /// The next sample.
    pub fn sample(&mut self) -> f64 {
        StandardNormal.sample(&mut self.0)
    }
}

/// `n` samples of Gaussian white noise N(0, 1), seeded.
pub fn white_gaussian(n: usize, seed: u64) -> Vec<f64> {
    let mut g = Gaussian::new(seed);
    (0..n).map(|_| g.sample()).collect()
}

/// Gaussian AR(1) `x_k = φ x_{k−1} + ξ_k` (unit innovations, x starts at 0), the first
/// `burn_in` values dropped, `n` kept; seeded.
pub fn ar1(phi: f64, n: usize, burn_in: usize, seed: u64) -> Vec<f64> {
    let mut g = Gaussian::new(seed);
    let mut x = 0.0;
    let mut out = Vec::with_capacity(n);
    for k in 0..n + burn_in {
        x = phi * x + g.sample();
        if k >= burn_in {
            out.push(x);
        }
    }
    out
}

/// `x` plus Gaussian observational noise of standard deviation `level × sd(x)`
/// (sd: [`pdamp::analysis::standard_deviation`]), seeded.
pub fn with_noise(x: &[f64], level: f64, seed: u64) -> Vec<f64> {
    let sd = pdamp::analysis::standard_deviation(x);
    let mut g = Gaussian::new(seed);
    x.iter().map(|v| v + level * sd * g.sample()).collect()
}

/// `n` samples of uniform white noise on [0, 1) from xorshift64 (Marsaglia 2003) started at
/// `state` (≠ 0): dependency-free and identical on every platform.
pub fn uniform_white(n: usize, mut state: u64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// Source tree

/// Every `.rs` file below `dir`, recursively, appended to `out` (the design-rule tests read
/// the source tree with it).
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

// ---------------------------------------------------------------------------------------
// A tiny DEM scene: 20 soft grains (steel ÷ 10 000) in a small box on scene B's primary,
// 12 forcing periods, so that a sweep point takes seconds

/// The tiny DEM scene (TOML).
pub const TINY_DEM: &str = r#"
[primary]
mass = 2.37
stiffness = 21500.0
damping = 7.6

[excitation]
amplitude = 0.0045
frequency = 15.0

[damper]
kind = "dem"
box = [0.02, 0.02, 0.05]
count = 20
radius = 0.003
density = 8030.0
youngs_modulus = 2.03e7
poisson = 0.28
friction = 0.3
gamma_n = 14.57
gamma_s = 43.72
contact = "hertz-kk"

[run]
periods = 12
steady_fraction = 0.5
analysis_fraction = 0.5
sample_interval = 1e-3
dt = "auto"
dt_fraction = 0.02
"#;

/// Classical RK4 of z'' = acc(t, z, z') from `init` = (z0, v0) at t = 0, `n` steps of `dt`: the
/// independent integrator the closed forms are checked against. Returns (z, z') at every step.
pub fn rk4(
    acc: impl Fn(f64, f64, f64) -> f64,
    init: (f64, f64),
    dt: f64,
    n: usize,
) -> Vec<(f64, f64)> {
    let (mut z, mut v) = init;
    let mut out = Vec::with_capacity(n + 1);
    out.push((z, v));
    for i in 0..n {
        let t = i as f64 * dt;
        let (k1z, k1v) = (v, acc(t, z, v));
        let (k2z, k2v) = (
            v + 0.5 * dt * k1v,
            acc(t + 0.5 * dt, z + 0.5 * dt * k1z, v + 0.5 * dt * k1v),
        );
        let (k3z, k3v) = (
            v + 0.5 * dt * k2v,
            acc(t + 0.5 * dt, z + 0.5 * dt * k2z, v + 0.5 * dt * k2v),
        );
        let (k4z, k4v) = (v + dt * k3v, acc(t + dt, z + dt * k3z, v + dt * k3v));
        z += dt / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z);
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        out.push((z, v));
    }
    out
}
