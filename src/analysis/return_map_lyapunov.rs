//! Returns the largest Lyapunov exponent of a phase-coherent flow from the first-return map of
//! its delay embedding: a Poincaré section at the upward crossings of the series' mean, Kantz's
//! divergence (4.1.7) on the section states ([`section_lyapunov`]), divided by the mean return
//! time.
//!
//! # Formula
//! With delay vectors y_n = (x_n, x_{n+τ}, …, x_{n+(m−1)τ}) and x̄ the mean of the series, the
//! section is crossed at every n with x_n < x̄ ≤ x_{n+1}; its state is the remaining m − 1
//! coordinates interpolated linearly at the crossing time t_k = n + (x̄ − x_n)/(x_{n+1} − x_n):
//!
//! ```text
//! u_k = (x(t_k + τ), …, x(t_k + (m−1)τ)),   T_k = t_{k+1} − t_k
//! λ_flow = λ_map / mean(T_k)      (per sample; λ_map per return, (4.1.7) on u_k)
//! ```
//!
//! The return map is that of a phase-coherent flow when its return times are nearly constant:
//! the coefficient of variation cv = sd(T_k)/mean(T_k) must not exceed `max_return_cv`
//! (default 0.2; Rössler (0.2, 0.2, 5.7) x: 0.086; Lorenz x, which switches lobes at random,
//! 0.58). Above it the estimate is refused.
//!
//! Why: in a phase-coherent flow the perturbation along the flow (a shift of the phase) neither
//! grows nor decays for a long time. Kantz's curve of the series itself measures the distance
//! of delay vectors at equal times, whose along-flow part stays flat while the transverse part
//! grows; with a small exponent per rotation (Rössler: λT ≈ 0.42) the curve approaches the
//! slope λ only after tens of time units, close to saturation, and any fit window mixes the
//! two (Rössler x, dt = 0.05: 0.054 per time unit against 0.0714). Comparing states on the
//! section after the same number of returns removes the phase by construction, as the
//! stroboscopic section does for a forced system.
//!
//! # Units
//! `x` in any unit (the section is scaled by its extents); λ per return and per sample (divide
//! by the sampling interval for s⁻¹); return times in samples.
//!
//! # Parameters
//! [`ReturnMapOptions`]: `m` (≥ 2), `tau` (samples), `max_return_cv = 0.2`, and the
//! [`SectionLyapunovOptions`] of the section exponent (defaults: 12 returns, 6 radii from the
//! section's noise floor over a factor 8, Theiler window 2 returns).
//!
//! # Errors
//! [`AnalysisError::BadParameter`] for m < 2 or τ = 0; [`AnalysisError::TooShort`] when the
//! section has too few points for the section exponent (4·(steps + 1) returns);
//! [`AnalysisError::NoResult`] when the return times scatter more than `max_return_cv` (not a
//! phase-coherent flow) and those of [`section_lyapunov`].
//!
//! # References
//! O. E. Rössler, Phys. Lett. A 57, 397–398 (1976); A. S. Pikovsky, M. G. Rosenblum,
//! G. V. Osipov, J. Kurths, Physica D 104, 219–238 (1997) (phase coherence: small diffusion of
//! the phase, nearly constant return times); H. Kantz, T. Schreiber, *Nonlinear Time Series
//! Analysis*, CUP (2004), §9.3 (Poincaré sections of flows) and §5.3.

use crate::analysis::section_lyapunov::{
    section_lyapunov, SectionLyapunov, SectionLyapunovOptions,
};
use crate::analysis::{min_max, validate_series};
use crate::error::AnalysisError;
use serde::{Deserialize, Serialize};

/// Options of [`return_map_lyapunov`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReturnMapOptions {
    /// Embedding dimension m (≥ 2: the section keeps m − 1 coordinates).
    pub m: usize,
    /// Delay τ in samples.
    pub tau: usize,
    /// Largest coefficient of variation of the return times for a phase-coherent flow
    /// (default 0.2).
    pub max_return_cv: f64,
    /// Options of the section exponent (its `steps` and Theiler window count returns).
    pub section: SectionLyapunovOptions,
}

impl Default for ReturnMapOptions {
    fn default() -> Self {
        Self {
            m: 3,
            tau: 1,
            max_return_cv: 0.2,
            section: SectionLyapunovOptions::default(),
        }
    }
}

/// Result of [`return_map_lyapunov`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReturnMapLyapunov {
    /// λ per sample (λ per return / mean return time).
    pub per_sample: f64,
    /// Standard error of λ per sample.
    pub stderr_per_sample: f64,
    /// λ of the return map per return.
    pub per_return: f64,
    /// Mean return time (samples).
    pub mean_return_samples: f64,
    /// Coefficient of variation of the return times.
    pub return_cv: f64,
    /// Number of section points.
    pub points: usize,
    /// The section exponent's curves and fits.
    pub section: SectionLyapunov,
}

/// The section of a delay embedding at the upward crossings of `level` by the first
/// coordinate: the crossing times (fractional samples) and the states of the other m − 1
/// coordinates, linearly interpolated.
///
/// # Formula
/// See the module documentation.
///
/// # Units
/// Times in samples; states in the units of `x`.
pub fn mean_crossing_section(
    x: &[f64],
    m: usize,
    tau: usize,
    level: f64,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let span = (m - 1) * tau;
    let mut times = Vec::new();
    let mut states = Vec::new();
    for n in 0..x.len().saturating_sub(span + 1) {
        let (a, b) = (x[n], x[n + 1]);
        if a < level && level <= b {
            let f = (level - a) / (b - a);
            let state = (1..m)
                .map(|k| {
                    let i = n + k * tau;
                    x[i] + f * (x[i + 1] - x[i])
                })
                .collect();
            times.push(n as f64 + f);
            states.push(state);
        }
    }
    (times, states)
}

/// Returns λ of a phase-coherent flow from its first-return map (see the module docs).
///
/// # Formula
/// See the module documentation ((4.1.7) on the mean-crossing section, per mean return time).
///
/// # Units
/// λ per sample and per return.
///
/// # Errors
/// See the module documentation.
///
/// # Example
/// ```
/// use pdamp::analysis::return_map_lyapunov::{return_map_lyapunov, ReturnMapOptions};
/// use pdamp::systems::roessler::roessler_x;
/// // Rössler x at dt = 0.05: λ = 0.0714 per time unit
/// let x = roessler_x(20_000, 0.05);
/// let r = return_map_lyapunov(&x, &ReturnMapOptions { m: 3, tau: 25, ..Default::default() }).unwrap();
/// assert!((r.per_sample / 0.05 - 0.0714).abs() < 0.015, "{}", r.per_sample / 0.05);
/// ```
pub fn return_map_lyapunov(
    x: &[f64],
    opts: &ReturnMapOptions,
) -> Result<ReturnMapLyapunov, AnalysisError> {
    if opts.m < 2 {
        return Err(AnalysisError::bad(
            "m",
            opts.m,
            "the return map needs m ≥ 2 (the section keeps m − 1 coordinates)",
        ));
    }
    if opts.tau == 0 {
        return Err(AnalysisError::bad("tau", 0, "the delay must be ≥ 1 sample"));
    }
    validate_series(x, 8, "the return-map exponent")?;
    let mean = x.iter().sum::<f64>() / x.len() as f64;
    let (times, states) = mean_crossing_section(x, opts.m, opts.tau, mean);
    if times.len() < 3 {
        return Err(AnalysisError::TooShort(format!(
            "the series crosses its mean upward {} times: a return map needs many rotations",
            times.len()
        )));
    }
    let returns: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    let t_mean = returns.iter().sum::<f64>() / returns.len() as f64;
    let var = returns.iter().map(|t| (t - t_mean).powi(2)).sum::<f64>() / returns.len() as f64;
    let cv = var.sqrt() / t_mean;
    if cv.is_nan() || cv > opts.max_return_cv {
        return Err(AnalysisError::NoResult(format!(
            "return times scatter by {:.0} % (more than {:.0} %): not a phase-coherent flow, its return map is not a map of the phase",
            100.0 * cv,
            100.0 * opts.max_return_cv
        )));
    }
    let scales: Vec<f64> = (0..opts.m - 1)
        .map(|d| {
            let column: Vec<f64> = states.iter().map(|s| s[d]).collect();
            let (lo, hi) = min_max(&column);
            (hi - lo).max(f64::MIN_POSITIVE)
        })
        .collect();
    let section = section_lyapunov(&states, &scales, &opts.section)?;
    Ok(ReturnMapLyapunov {
        per_sample: section.per_period / t_mean,
        stderr_per_sample: section.stderr_per_period / t_mean,
        per_return: section.per_period,
        mean_return_samples: t_mean,
        return_cv: cv,
        points: states.len(),
        section,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn section_of_a_sine_is_one_point_per_period() {
        // x = sin(2πn/40): upward crossings of 0 at n = 40k exactly (between 40k − 1 and 40k);
        // the state x(t + 10) = sin(π/2) = 1.
        let x: Vec<f64> = (0..400)
            .map(|n| (2.0 * std::f64::consts::PI * n as f64 / 40.0 - 1e-9).sin())
            .collect();
        let (t, s) = mean_crossing_section(&x, 2, 10, 0.0);
        assert_eq!(t.len(), 10);
        for (k, (tk, sk)) in t.iter().zip(&s).enumerate() {
            assert!((tk - 40.0 * k as f64).abs() < 1e-6, "{tk}");
            assert!((sk[0] - 1.0).abs() < 2e-3, "{}", sk[0]);
        }
    }

    #[test]
    fn bad_parameters_are_errors() {
        let x: Vec<f64> = (0..1000).map(|n| (n as f64 * 0.1).sin()).collect();
        for o in [
            ReturnMapOptions {
                m: 1,
                ..Default::default()
            },
            ReturnMapOptions {
                tau: 0,
                ..Default::default()
            },
        ] {
            assert!(matches!(
                return_map_lyapunov(&x, &o),
                Err(AnalysisError::BadParameter { .. })
            ));
        }
    }
}
