//! What the Lyapunov estimators return and take ([`ModelLyapunov`],
//! [`ModelLyapunovOptions`]), and what both share: the measured window of forcing periods,
//! the scaled norm ‖δx‖² = (δz² + δy²)/L² + (δz'² + δy'²)/(L Ω)² and the batch-means mean
//! and standard error of the per-period logarithms.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, Quantity, SimError};
use crate::impact::world::ImpactWorld;

/// Which estimator produced a [`ModelLyapunov`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LyapunovMethod {
    /// Tangent vector carried by the exact flow Jacobians and saltation matrices.
    TangentSaltation,
    /// Two copies of the model, their separation renormalised every forcing period.
    TwoTrajectory,
}

/// Largest Lyapunov exponent of the impact model's stroboscopic map over the steady window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelLyapunov {
    /// The estimator used.
    pub method: LyapunovMethod,
    /// Forcing frequency f (Hz).
    pub frequency_hz: f64,
    /// λ_T: mean natural log of the growth factor per forcing period (dimensionless per period).
    /// `-inf` (JSON `null`) when every perturbation dies in finite time (a kinematic box whose
    /// ball locks onto the table: superstable).
    pub per_period: f64,
    /// λ = λ_T f (1/s).
    pub per_second: f64,
    /// Standard error of λ_T from batch means (per period); 0 when λ_T = −∞.
    pub stderr_per_period: f64,
    /// Standard error of λ (1/s).
    pub stderr_per_second: f64,
    /// Number of forcing periods averaged.
    pub periods: u64,
    /// Fraction of the steady window during which the particle moved with the box (stuck on
    /// the floor or pressed to the ceiling).
    pub stuck_fraction: f64,
    /// The particle moved with the box during the whole steady window (the damper is
    /// inactive: for a spring-mounted box λ is then the loaded primary's decay rate
    /// −C/(2(M + m_p)); for a kinematic box λ = −∞).
    pub locked: bool,
    /// Impacts with a non-zero approach speed per forcing period in the steady window.
    pub impacts_per_period: f64,
}

/// Settings of [`ImpactWorld::model_lyapunov`] and
/// [`ImpactWorld::model_lyapunov_two_trajectory`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ModelLyapunovOptions {
    /// Number of contiguous blocks of periods for the batch-means standard error
    /// (dimensionless), ≥ 2; fewer if the window has fewer periods. Default 10.
    pub blocks: usize,
    /// Initial separation d0 of the two-trajectory estimate, in the scaled norm (lengths over
    /// the length scale L, velocities over L Ω; dimensionless), in (0, 1e-3]. Default 1e-7:
    /// event times are located to ~1e-13 s, which puts a noise of ~1e-11 (scaled) on each
    /// impact; at d0 = 1e-9 that is a 1 % error per impact (scene B, periodic orbits: up to
    /// 0.4 1/s off), while d0 = 1e-7 and 1e-6 agree to ~0.01 1/s.
    pub separation: f64,
}

impl Default for ModelLyapunovOptions {
    fn default() -> Self {
        ModelLyapunovOptions {
            blocks: 10,
            separation: 1e-7,
        }
    }
}

impl ModelLyapunovOptions {
    pub(super) fn validate(&self) -> Result<(), SimError> {
        if self.blocks < 2 {
            return Err(SimError::Unavailable(format!(
                "Lyapunov option blocks = {}: the batch-means standard error needs at least 2 \
                 blocks of forcing periods",
                self.blocks
            )));
        }
        if !(self.separation > 0.0 && self.separation <= 1e-3) {
            return Err(SimError::Unavailable(format!(
                "Lyapunov option separation = {:e}: the two trajectories must start a small \
                 scaled distance apart, in (0, 1e-3] (1e-7 is the default)",
                self.separation
            )));
        }
        Ok(())
    }
}

/// Generic initial direction (scaled components), far from any special subspace.
pub(super) const SEED: [f64; 4] = [0.61, 0.47, -0.39, 0.51];

/// Weights of the scaled norm: 1/L for lengths, 1/(L Ω) for velocities, with the problem's
/// length scale L = max(U, m_p g/K, 1 µm) (the one the chattering cut uses).
pub(super) fn norm_weights(w: &ImpactWorld) -> [f64; 4] {
    let mp = w.particle.map_or(0.0, |p| p.mass);
    let static_defl = if w.box_mass.is_finite() && w.k > 0.0 {
        mp * w.g / w.k
    } else {
        0.0
    };
    let l = w.u_amp.max(static_defl).max(1e-6);
    let v = l * w.omega;
    [1.0 / l, 1.0 / v, 1.0 / l, 1.0 / v]
}

pub(super) fn scaled_norm(d: &[f64; 4], wt: &[f64; 4]) -> f64 {
    d.iter()
        .zip(wt)
        .map(|(x, s)| (x * s) * (x * s))
        .sum::<f64>()
        .sqrt()
}

/// Mean and batch-means standard error of the per-period logarithms.
pub(super) fn batch_means(logs: &[f64], blocks: usize) -> (f64, f64) {
    let n = logs.len();
    let mean = logs.iter().sum::<f64>() / n as f64;
    if !mean.is_finite() {
        return (mean, 0.0);
    }
    let b = blocks.min(n).max(1);
    if b < 2 {
        return (mean, f64::INFINITY);
    }
    let means: Vec<f64> = (0..b)
        .map(|i| {
            let (lo, hi) = (i * n / b, (i + 1) * n / b);
            logs[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
        })
        .collect();
    let m = means.iter().sum::<f64>() / b as f64;
    let var = means.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (b as f64 * (b - 1) as f64);
    (mean, var.sqrt())
}

impl ImpactWorld {
    /// Measured periods: renormalisation times kT with k0 = ⌈steady_start/T⌉ ≤ k ≤ k_end.
    pub(super) fn lyapunov_window(&self) -> Result<(u64, u64), SimError> {
        let k0 = (self.steady_start / self.period - 1e-9).ceil().max(0.0) as u64;
        let k_end = (self.duration / self.period + 1e-9).floor() as u64;
        if k_end < k0 + 2 {
            let frac = 1.0 - self.steady_start / self.duration;
            return Err(SimError::Model(ModelError::new(
                Quantity::SteadyFraction,
                frac,
                format!(
                    "the steady window {:.6} … {:.6} s holds {} complete forcing period(s) of \
                     {:.6} s; the Lyapunov exponent needs at least 2: raise the duration or the \
                     steady-state fraction",
                    self.steady_start,
                    self.duration,
                    k_end.saturating_sub(k0),
                    self.period
                ),
            )));
        }
        Ok((k0, k_end))
    }

    pub(super) fn lyapunov_result(
        &self,
        method: LyapunovMethod,
        logs: &[f64],
        blocks: usize,
        stuck_s: f64,
        impacts: u64,
    ) -> ModelLyapunov {
        let (mean, se) = batch_means(logs, blocks);
        let f = 1.0 / self.period;
        let n = logs.len() as u64;
        let window = n as f64 * self.period;
        let stuck_fraction = (stuck_s / window).clamp(0.0, 1.0);
        ModelLyapunov {
            method,
            frequency_hz: f,
            per_period: mean,
            per_second: mean * f,
            stderr_per_period: se,
            stderr_per_second: se * f,
            periods: n,
            stuck_fraction,
            locked: self.particle.is_some() && stuck_fraction >= 1.0 - 1e-9,
            impacts_per_period: impacts as f64 / n as f64,
        }
    }
}
