//! Autocorrelation of a scalar series and its first zero crossing, the simplest default delay
//! for a reconstruction (the first minimum of the mutual information,
//! [`mutual_information`](mod@crate::analysis::mutual_information), is the better choice for
//! nonlinear series).
//!
//! With the mean s̄ = (1/N) Σ sₙ, the (unnormalised) autocovariance at lag k (samples) is
//!
//! ```text
//! C(k) = Σ_{n=0}^{N−1−k} (sₙ − s̄)(sₙ₊ₖ − s̄)
//! ```
//!
//! and the normalised autocorrelation ρ(k) = C(k) / C(0) (dimensionless, ρ(0) = 1; the sums
//! are not divided by the number of pairs N − k, as in Box & Jenkins' estimator).
//! [`first_zero_lag`] is the smallest k ≥ 1 with C(k) ≤ 0, searched for k < N/2. Lags are in
//! samples; multiply by the sampling step for seconds.
//!
//! Reference: G. E. P. Box, G. M. Jenkins, *Time Series Analysis* (1976), §2.1.

use crate::error::AnalysisError;

/// Normalised autocorrelation ρ(k) = C(k)/C(0) for k = 0..=`max_lag` (clamped to N − 1).
///
/// # Errors
/// [`AnalysisError::TooShort`] for fewer than 2 samples; [`AnalysisError::Constant`] for a
/// series of zero variance.
pub fn autocorrelation(s: &[f64], max_lag: usize) -> Result<Vec<f64>, AnalysisError> {
    if s.len() < 2 {
        return Err(AnalysisError::TooShort(format!(
            "{} samples; the autocorrelation needs at least 2",
            s.len()
        )));
    }
    let (mean, c0) = mean_and_c0(s);
    if c0 <= 0.0 {
        return Err(AnalysisError::Constant);
    }
    Ok((0..=max_lag.min(s.len() - 1))
        .map(|k| autocovariance(s, mean, k) / c0)
        .collect())
}

/// First lag k ≥ 1 (samples) with C(k) ≤ 0, searched for k < N/2.
///
/// # Errors
/// [`AnalysisError::NoResult`] if the series is constant or empty ("series is constant: no
/// delay reconstruction") or the autocovariance stays positive up to N/2 ("autocorrelation
/// never reaches 0 within half the series").
pub fn first_zero_lag(s: &[f64]) -> Result<usize, AnalysisError> {
    let n = s.len();
    let (mean, c0) = mean_and_c0(s);
    if c0 <= 0.0 {
        return Err(AnalysisError::NoResult(
            "series is constant: no delay reconstruction".into(),
        ));
    }
    for lag in 1..n / 2 {
        if autocovariance(s, mean, lag) <= 0.0 {
            return Ok(lag);
        }
    }
    Err(AnalysisError::NoResult(
        "autocorrelation never reaches 0 within half the series".into(),
    ))
}

fn mean_and_c0(s: &[f64]) -> (f64, f64) {
    let mean = s.iter().sum::<f64>() / s.len() as f64;
    (mean, s.iter().map(|x| (x - mean).powi(2)).sum())
}

fn autocovariance(s: &[f64], mean: f64, lag: usize) -> f64 {
    (0..s.len() - lag)
        .map(|i| (s[i] - mean) * (s[i + lag] - mean))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sine_crosses_zero_at_a_quarter_period() {
        // 41 samples per period: ρ(k) ≈ cos(2πk/41) crosses 0 between k = 10 and 11
        let s: Vec<f64> = (0..4100)
            .map(|i| (2.0 * std::f64::consts::PI * i as f64 / 41.0).sin())
            .collect();
        assert_eq!(first_zero_lag(&s).unwrap(), 11);
        let r = autocorrelation(&s, 20).unwrap();
        assert!((r[0] - 1.0).abs() < 1e-12);
        // ρ(20) ≈ (1 − 20/N) cos(2π·20/41) (the sums are not divided by N − k)
        let expected = (1.0 - 20.0 / 4100.0) * (2.0 * std::f64::consts::PI * 20.0 / 41.0).cos();
        assert!((r[20] - expected).abs() < 1e-3, "{} vs {expected}", r[20]);
    }

    #[test]
    fn constant_and_positive_series_are_refused() {
        let e = first_zero_lag(&[1.0; 10]).unwrap_err();
        assert_eq!(e.to_string(), "series is constant: no delay reconstruction");
        let e = first_zero_lag(&[]).unwrap_err();
        assert_eq!(e.to_string(), "series is constant: no delay reconstruction");
        // three samples: no lag below N/2 = 1 to search
        let e = first_zero_lag(&[1.0, 2.0, 3.0]).unwrap_err();
        assert!(e.to_string().contains("never reaches 0"), "{e}");
        assert_eq!(autocorrelation(&[1.0; 4], 2), Err(AnalysisError::Constant));
    }
}
