//! Nonlinear time-series analysis of a scalar series (SPEC §4): delay embedding (4.1.1),
//! time-delayed mutual information (4.1.5), false nearest neighbours (4.1.4), Kantz's maximal
//! Lyapunov exponent (4.1.7), spectra, Poincaré sections and the regime classifier; surrogate
//! data (IAAFT, FT, shuffle) with a rank test of discriminating statistics (time-reversal
//! asymmetry, nonlinear prediction error); the correlation dimension (Grassberger–Procaccia),
//! Cao's embedding dimension, Rosenstein's maximal exponent, recurrence quantification and the
//! autocorrelation's first zero; the free-decay envelope (logarithmic decrement and damping
//! ratio per cycle).
//!
//! One file per estimator. This module holds the helpers they share: series validation
//! ([`validate_series`]), rescaling to [0, 1] as TISEAN does ([`rescale_unit`]) and the Theiler
//! window test ([`outside_theiler_window`]).

pub mod analyze;
pub mod autocorrelation;
pub mod box_grid;
pub mod cao;
pub mod correlation_dimension;
pub mod decay;
pub mod decay_zones;
pub mod embedding;
pub mod false_nearest_neighbors;
pub mod frf_fit;
pub mod kantz;
pub mod kantz_scan;
pub mod mutual_information;
pub mod noise_reduction;
pub mod optimum;
pub mod phase_lock;
pub mod poincare;
pub(crate) mod point_tree;
pub mod prediction_error;
pub mod recurrence;
pub mod regime;
pub mod regime_forced;
pub mod replica_test;
pub mod return_map_lyapunov;
pub mod rosenstein;
pub mod scaling_region;
pub mod section;
pub mod section_dimension;
pub mod section_lyapunov;
pub mod spectrum;
pub mod surrogate_test;
pub mod surrogates;
pub mod time_reversal;
pub mod zero_one_test;

pub use autocorrelation::{autocorrelation, first_zero_lag};
pub use cao::{cao, CaoOptions, CaoResult};
pub use correlation_dimension::{
    correlation_dimension, correlation_sum, estimate_d2, CorrelationSums, D2Estimate, D2Options,
    PlateauOptions,
};
pub use decay::{decay_envelope, DecayCycle, DecayEnvelope, DecayOptions, DecayStop};
pub use embedding::DelayEmbedding;
pub use false_nearest_neighbors::{false_nearest_neighbors, FnnOptions, FnnPoint, FnnVectors};
pub use kantz::{estimate_max_lyapunov, kantz, KantzDefinition, KantzOptions, KantzResult};
pub use mutual_information::{mutual_information, MutualInformation, MutualInformationOptions};
pub use noise_reduction::{
    nonlinear_noise_reduction, Correction, NoiseReduction, NoiseReductionOptions,
};
pub use prediction_error::{prediction_error, PredictionErrorOptions};
pub use recurrence::{rqa, RecurrenceOptions, RecurrenceThreshold, RqaMeasures};
pub use rosenstein::{rosenstein, RosensteinOptions, RosensteinResult};
pub use surrogate_test::{surrogate_test, SurrogateTestOptions, SurrogateTestResult, Tail};
pub use surrogates::{
    end_to_end_segment, surrogate, surrogates, EndToEnd, Surrogate, SurrogateMethod,
    SurrogateOptions,
};
pub use time_reversal::time_reversal_asymmetry;

use crate::error::AnalysisError;

/// Checks that a series can be analysed: at least `min_len` samples, all finite, not constant.
///
/// # Errors
/// [`AnalysisError::TooShort`] (naming `what` and both lengths), [`AnalysisError::NonFinite`]
/// (first offending index) or [`AnalysisError::Constant`]. See also [`reject_monotonic`].
pub fn validate_series(x: &[f64], min_len: usize, what: &str) -> Result<(), AnalysisError> {
    if x.len() < min_len {
        return Err(AnalysisError::TooShort(format!(
            "{what} needs at least {min_len} samples, the series has {}",
            x.len()
        )));
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(AnalysisError::NonFinite { index });
    }
    let (lo, hi) = min_max(x);
    if x.is_empty() || hi <= lo {
        return Err(AnalysisError::Constant);
    }
    Ok(())
}

/// Refuses a series that rises (or falls) at every sample: a time or index column read
/// instead of the signal (nothing recurs, so no estimator here has anything to measure).
/// Called by the estimators after their length checks.
///
/// # Errors
/// [`AnalysisError::Monotonic`] for such a series of at least 3 samples.
pub fn reject_monotonic(x: &[f64]) -> Result<(), AnalysisError> {
    let rising = x.windows(2).all(|w| w[1] > w[0]);
    if x.len() >= 3 && (rising || x.windows(2).all(|w| w[1] < w[0])) {
        return Err(AnalysisError::Monotonic {
            direction: if rising { "increases" } else { "decreases" },
            len: x.len(),
            first: x[0],
            last: x[x.len() - 1],
        });
    }
    Ok(())
}

/// Minimum and maximum of a slice (`(+inf, -inf)` when empty).
pub fn min_max(x: &[f64]) -> (f64, f64) {
    x.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// A series rescaled to [0, 1] by its minimum and range, as every TISEAN program does first
/// (SPEC §8, TISEAN's `rescale_data`).
#[derive(Debug, Clone, PartialEq)]
pub struct Rescaled {
    /// `(x − min) / range`, in [0, 1].
    pub values: Vec<f64>,
    /// Minimum of the original series (data units).
    pub min: f64,
    /// `max − min` of the original series (data units); multiply rescaled distances by it to
    /// get data units, or add `ln(range)` to logarithms of distances.
    pub range: f64,
}

/// Rescales a series to [0, 1]: `y = (x − min)/(max − min)`.
///
/// # Errors
/// Those of [`validate_series`] with `min_len = 1`.
pub fn rescale_unit(x: &[f64]) -> Result<Rescaled, AnalysisError> {
    validate_series(x, 1, "rescaling")?;
    let (min, max) = min_max(x);
    let range = max - min;
    let values = x.iter().map(|&v| (v - min) / range).collect();
    Ok(Rescaled { values, min, range })
}

/// Population standard deviation `sqrt(mean((x − mean(x))²))`, in two passes. (TISEAN's
/// `variance` routine computes `sqrt(|mean(x²) − mean(x)²|)` in one pass, which cancels to 0 for
/// a series with a large offset, e.g. 10⁹ + 10⁻⁷·noise; the two agree to rounding otherwise.)
pub fn standard_deviation(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt()
}

/// True when samples `i` and `j` are far enough apart in time to count as neighbours:
/// `|i − j| > w` (Theiler 1986 window `w`; `w = 0` only excludes `i = j`).
#[inline]
pub fn outside_theiler_window(i: usize, j: usize, w: usize) -> bool {
    i.abs_diff(j) > w
}

/// Checks a positive integer parameter.
pub(crate) fn require_positive(name: &str, value: usize) -> Result<(), AnalysisError> {
    if value == 0 {
        return Err(AnalysisError::bad(name, value, "must be at least 1"));
    }
    Ok(())
}

/// Checks an estimator's embedding dimensions and delay (TISEAN `-m`, `-M`, `-d`):
/// 1 ≤ `m_min` ≤ `m_max` ≤ `max_dimension`, τ ≥ 1. The one check of [`kantz`],
/// [`correlation_dimension`] and [`false_nearest_neighbors`].
///
/// # Errors
/// [`AnalysisError::BadParameter`] naming `m_min`, `tau` or `m_max`.
pub(crate) fn validate_embedding_range(
    m_min: usize,
    m_max: usize,
    tau: usize,
    max_dimension: usize,
) -> Result<(), AnalysisError> {
    require_positive("m_min", m_min)?;
    require_positive("tau", tau)?;
    if m_max < m_min {
        return Err(AnalysisError::bad(
            "m_max",
            m_max,
            format!("must be ≥ m_min = {m_min}"),
        ));
    }
    if m_max > max_dimension {
        return Err(AnalysisError::bad(
            "m_max",
            m_max,
            format!("at most {max_dimension} dimensions are supported"),
        ));
    }
    Ok(())
}

/// Checks the optional radii ε_min and ε_max of an estimator (TISEAN `-r`, `-R`): each, when
/// given, a positive finite number in data units. The one check of [`kantz`] and
/// [`correlation_dimension`]; their own orderings (ε_min < ε_max, or a single radius) stay
/// theirs.
///
/// # Errors
/// [`AnalysisError::BadParameter`] naming `eps_min` or `eps_max`.
pub(crate) fn validate_radii(
    eps_min: Option<f64>,
    eps_max: Option<f64>,
) -> Result<(), AnalysisError> {
    for (name, v) in [("eps_min", eps_min), ("eps_max", eps_max)] {
        if let Some(v) = v {
            if !(v.is_finite() && v > 0.0) {
                return Err(AnalysisError::bad(
                    name,
                    v,
                    "the radius must be a positive number in data units",
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rescale_maps_to_unit_interval() {
        let r = rescale_unit(&[2.0, 4.0, 3.0]).unwrap();
        assert_eq!(r.values, vec![0.0, 1.0, 0.5]);
        assert_eq!((r.min, r.range), (2.0, 2.0));
    }

    #[test]
    fn validation_errors_name_the_problem() {
        assert_eq!(rescale_unit(&[1.0, 1.0]), Err(AnalysisError::Constant));
        assert_eq!(
            rescale_unit(&[1.0, f64::NAN]),
            Err(AnalysisError::NonFinite { index: 1 })
        );
        assert!(matches!(
            validate_series(&[1.0, 2.0], 3, "test"),
            Err(AnalysisError::TooShort(_))
        ));
    }

    #[test]
    fn theiler_window() {
        assert!(!outside_theiler_window(5, 5, 0));
        assert!(outside_theiler_window(5, 6, 0));
        assert!(!outside_theiler_window(5, 8, 3));
        assert!(outside_theiler_window(9, 5, 3));
    }

    #[test]
    fn standard_deviation_of_two_values() {
        assert!((standard_deviation(&[0.0, 2.0]) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn standard_deviation_survives_a_large_offset() {
        // ±1e-7 around 1e9: the one-pass formula loses every digit (gives 0 or noise)
        let x: Vec<f64> = (0..100)
            .map(|i| 1e9 + if i % 2 == 0 { 1e-7 } else { -1e-7 })
            .collect();
        let sd = standard_deviation(&x);
        assert!((sd / 1.1920928955078125e-7 - 1.0).abs() < 0.3, "{sd}");
    }
}
