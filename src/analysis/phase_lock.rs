//! Returns how much of a forced response is locked to the forcing: the fraction of the series'
//! variance carried by its mean waveform over p forcing periods (synchronous average), and the
//! RMS of what is left — the measured noise level of a periodic-p motion with noise.
//!
//! # Formula
//! The samples x_i (uniform spacing Δt, forcing frequency f) are filed by their phase over p
//! forcing periods, φ_i = (i Δt f / p) mod 1, into B = clamp(⌊p/(f Δt)⌋ / 2, 8, 64 p) equal
//! bins; the waveform w(φ) interpolates the bin means linearly between the bins' mean phases
//! (circularly), and
//!
//! Λ_p = 1 − Σ_i (x_i − w(φ_i))² / Σ_i (x_i − x̄)²,   σ_res = √(Σ_i (x_i − w(φ_i))² / n).
//!
//! A periodic-p motion has Λ_p = 1 up to the interpolation error, O((2π/B)²) of the waveform's
//! height (the bin means alone, without the interpolation, would leave a sinusoid's
//! (π/B)²/3 of the variance: an RMS of 2 % of its amplitude at B = 64, more than many noise
//! levels); independent noise of RMS σ on a waveform of
//! RMS a gives Λ_p = a²/(a² + σ²); a stationary random signal gives Λ_p ≈ B/n (the bin means
//! of noise). Chaos gives anything in between: Λ_p alone never tells chaos from noise, it
//! measures how far the motion is from the locked waveform.
//!
//! # Units
//! σ_res in the units of x; Λ_p dimensionless.
//!
//! # Pitfalls
//! The phase is counted from the first sample: its offset is irrelevant (it only rotates the
//! bins). The spacing must be uniform (the simulators' sample grid is). A slow drift (a bed
//! still compacting) counts as noise. Needs at least two whole windows of p periods.
//!
//! # References
//! S. Braun, "The synchronous (time domain) average revisited", Mech. Syst. Signal Process.
//! 25, 1087–1102 (2011), doi:10.1016/j.ymssp.2010.07.016 (the synchronous average of rotating
//! machinery, which separates the locked part of a signal from the rest).

use crate::error::AnalysisError;
use serde::{Deserialize, Serialize};

/// Result of [`phase_lock`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PhaseLock {
    /// The window p of the synchronous average, in forcing periods.
    pub periods: usize,
    /// Λ_p: fraction of the variance carried by the mean waveform (0…1).
    pub locked_fraction: f64,
    /// σ_res: RMS deviation from the mean waveform (units of the series).
    pub noise_rms: f64,
    /// Peak-to-peak height of the mean waveform (units of the series).
    pub waveform_peak_to_peak: f64,
    /// Phase bins B used.
    pub bins: usize,
}

/// Returns the locked fraction Λ_p and the noise RMS of `x` (see the module docs).
///
/// # Units
/// `dt_s` in s, `forcing_hz` in Hz; the outputs in the units of `x`.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `p = 0`, a non-positive or non-finite `dt_s` or
/// `forcing_hz`; [`AnalysisError::NonFinite`] for a non-finite sample; [`AnalysisError::TooShort`] when `x` spans fewer
/// than two windows of p forcing periods or a window holds fewer than 16 samples.
///
/// # Example
/// ```
/// use pdamp::analysis::phase_lock::phase_lock;
/// use std::f64::consts::TAU;
/// // a 5 Hz sine sampled at 1 kHz plus a small disturbance at 37.7 Hz (not a harmonic of 5 Hz,
/// // so it is not locked: its RMS 0.01/√2 is the noise level)
/// let x: Vec<f64> = (0..4000)
///     .map(|i| (TAU * 5.0 * i as f64 * 1e-3).sin() + 0.01 * (TAU * 37.7 * i as f64 * 1e-3).sin())
///     .collect();
/// let l = phase_lock(&x, 1e-3, 5.0, 1).unwrap();
/// assert!(l.locked_fraction > 0.999 && (l.noise_rms - 0.01 / 2f64.sqrt()).abs() < 5e-4, "{l:?}");
/// ```
pub fn phase_lock(
    x: &[f64],
    dt_s: f64,
    forcing_hz: f64,
    p: usize,
) -> Result<PhaseLock, AnalysisError> {
    if p == 0 {
        return Err(AnalysisError::bad("periods", 0, "must be ≥ 1"));
    }
    if !(dt_s.is_finite() && dt_s > 0.0) {
        return Err(AnalysisError::bad("dt", dt_s, "must be > 0 s"));
    }
    if !(forcing_hz.is_finite() && forcing_hz > 0.0) {
        return Err(AnalysisError::bad(
            "forcing_hz",
            forcing_hz,
            "must be > 0 Hz",
        ));
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(AnalysisError::NonFinite { index });
    }
    let per_window = p as f64 / (forcing_hz * dt_s);
    let windows = x.len() as f64 / per_window;
    if windows < 2.0 || per_window < 16.0 {
        return Err(AnalysisError::TooShort(format!(
            "the phase lock over {p} forcing period(s) needs two windows of at least 16 samples each ({} samples); got {}",
            (2.0 * per_window.max(16.0)).ceil() as usize,
            x.len()
        )));
    }
    let bins = ((per_window / 2.0) as usize).clamp(8, 64 * p);
    let rate = forcing_hz * dt_s / p as f64;
    // phase in bin units, u ∈ [0, B)
    let phase = |i: usize| (i as f64 * rate).fract() * bins as f64;
    let bin_of = |u: f64| (u as usize).min(bins - 1);
    let mut sum = vec![0.0; bins];
    let mut sum_u = vec![0.0; bins];
    let mut count = vec![0usize; bins];
    for (i, v) in x.iter().enumerate() {
        let u = phase(i);
        let b = bin_of(u);
        sum[b] += v;
        sum_u[b] += u;
        count[b] += 1;
    }
    // every bin holds samples: B ≤ half the samples of one window
    let mean: Vec<f64> = sum
        .iter()
        .zip(&count)
        .map(|(s, &c)| s / c.max(1) as f64)
        .collect();
    let centre: Vec<f64> = sum_u
        .iter()
        .zip(&count)
        .enumerate()
        .map(|(b, (s, &c))| if c > 0 { s / c as f64 } else { b as f64 + 0.5 })
        .collect();
    // the waveform at a phase: the bin means interpolated linearly between the bins' mean
    // phases (circularly), so that neither the bins' width nor where the samples fall inside
    // a bin counts as noise
    let waveform = |u: f64| {
        let b = bin_of(u);
        let (b0, b1) = if u >= centre[b] {
            (b, (b + 1) % bins)
        } else {
            ((b + bins - 1) % bins, b)
        };
        let (mut u0, mut u1) = (centre[b0], centre[b1]);
        if b1 < b0 {
            // wrapped: bring both phases to one side of the seam
            if u >= centre[b] {
                u1 += bins as f64;
            } else {
                u0 -= bins as f64;
            }
        }
        let w = if u1 > u0 { (u - u0) / (u1 - u0) } else { 0.0 };
        (1.0 - w) * mean[b0] + w * mean[b1]
    };
    let n = x.len() as f64;
    let grand = x.iter().sum::<f64>() / n;
    let total: f64 = x.iter().map(|v| (v - grand) * (v - grand)).sum();
    let resid: f64 = x
        .iter()
        .enumerate()
        .map(|(i, v)| (v - waveform(phase(i))).powi(2))
        .sum();
    let (lo, hi) = crate::analysis::min_max(&mean);
    Ok(PhaseLock {
        periods: p,
        locked_fraction: if total > 0.0 {
            1.0 - resid / total
        } else {
            1.0
        },
        noise_rms: (resid / n).sqrt(),
        waveform_peak_to_peak: hi - lo,
        bins,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// Uniform deviates in [−½, ½) from a fixed LCG (variance 1/12).
    fn lcg(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    #[test]
    fn sine_with_noise_gives_the_signal_to_noise_fraction() {
        // a = 1/√2 (RMS of a unit sine), σ = 0.3/√12: Λ = a²/(a² + σ²) = 0.5/(0.5 + 0.0075)
        let u = lcg(40_000, 3);
        let x: Vec<f64> = (0..40_000)
            .map(|i| (TAU * 7.0 * i as f64 * 5e-4).sin() + 0.3 * u[i])
            .collect();
        let l = phase_lock(&x, 5e-4, 7.0, 1).unwrap();
        let expected = 0.5 / (0.5 + 0.09 / 12.0);
        assert!((l.locked_fraction - expected).abs() < 2e-3, "{l:?}");
        assert!((l.noise_rms - 0.3 / 12f64.sqrt()).abs() < 3e-3, "{l:?}");
        assert!((l.waveform_peak_to_peak - 2.0).abs() < 0.02, "{l:?}");
    }

    #[test]
    fn period_two_needs_a_two_period_window() {
        // a subharmonic at f/2: not locked to one forcing period, fully locked to two
        let x: Vec<f64> = (0..20_000)
            .map(|i| (TAU * 2.5 * i as f64 * 1e-3).sin())
            .collect();
        let one = phase_lock(&x, 1e-3, 5.0, 1).unwrap();
        let two = phase_lock(&x, 1e-3, 5.0, 2).unwrap();
        assert!(one.locked_fraction < 0.01, "{one:?}");
        assert!(two.locked_fraction > 0.999, "{two:?}");
    }

    #[test]
    fn noise_is_not_locked_and_bad_input_is_refused() {
        let x = lcg(20_000, 9);
        let l = phase_lock(&x, 1e-3, 5.0, 1).unwrap();
        assert!(l.locked_fraction < 0.02, "{l:?}");
        assert!(phase_lock(&x[..300], 1e-3, 5.0, 1).is_err());
        assert!(phase_lock(&x, 0.0, 5.0, 1).is_err());
        assert!(phase_lock(&x, 1e-3, 5.0, 0).is_err());
        assert!(phase_lock(&[f64::NAN; 1000], 1e-3, 5.0, 1).is_err());
    }
}
