//! Out-of-sample error of the locally constant ("zeroth-order", analogue) predictor in a
//! delay embedding (Farmer & Sidorowich 1987; TISEAN `zeroth` / `lzo-test`): the standard
//! discriminating statistic for surrogate tests that tell deterministic chaos from linear
//! coloured noise.

use crate::analysis::box_grid::BoxGrid;
use crate::analysis::{min_max, standard_deviation, validate_series};
use crate::error::AnalysisError;
use serde::Serialize;

/// Options of [`prediction_error`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PredictionErrorOptions {
    /// Embedding dimension m (TISEAN `-m`). Default 3.
    pub dim: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub delay: usize,
    /// Prediction horizon h in samples (TISEAN `-s`). Default 1.
    pub horizon: usize,
    /// Starting neighbourhood radius ε as a fraction of the standard deviation of the series
    /// (TISEAN's `-v` convention). Default 0.1.
    pub epsilon: f64,
    /// Smallest number of neighbours a prediction must average over (TISEAN `-k`); points
    /// with fewer neighbours are retried with ε multiplied by `epsilon_factor` until the
    /// radius exceeds the range of the data. Default 5 (TISEAN `zeroth`: 30).
    pub min_neighbors: usize,
    /// Factor by which ε grows for points with too few neighbours (TISEAN `-f`). Default 1.2.
    pub epsilon_factor: f64,
    /// Theiler window w in samples: neighbours j must satisfy |n − j| > w. Default 0 (only
    /// the point itself is excluded). For flows use at least a few times τ.
    pub theiler: usize,
}

impl Default for PredictionErrorOptions {
    fn default() -> Self {
        Self {
            dim: 3,
            delay: 1,
            horizon: 1,
            epsilon: 0.1,
            min_neighbors: 5,
            epsilon_factor: 1.2,
            theiler: 0,
        }
    }
}

impl PredictionErrorOptions {
    fn validate(&self) -> Result<(), AnalysisError> {
        crate::analysis::require_positive("dim", self.dim)?;
        crate::analysis::require_positive("delay", self.delay)?;
        crate::analysis::require_positive("horizon", self.horizon)?;
        crate::analysis::require_positive("min_neighbors", self.min_neighbors)?;
        if !(self.epsilon > 0.0 && self.epsilon.is_finite()) {
            return Err(AnalysisError::bad(
                "epsilon",
                self.epsilon,
                "must be > 0 (fraction of the standard deviation, e.g. 0.1)",
            ));
        }
        if !(self.epsilon_factor > 1.0 && self.epsilon_factor.is_finite()) {
            return Err(AnalysisError::bad(
                "epsilon_factor",
                self.epsilon_factor,
                "must be > 1 (TISEAN default 1.2)",
            ));
        }
        Ok(())
    }
}

/// Returns the normalised RMS error of the locally constant predictor of `x`, h steps ahead.
///
/// # Formula
/// Delay vectors `v_n = (x_n, x_{n−τ}, …, x_{n−(m−1)τ})`, n = (m−1)τ..N−h−1. For each n the
/// neighbourhood `U_n = { j : ‖v_j − v_n‖_∞ ≤ ε, |j − n| > w }` (the same set of vectors, so
/// the prediction is in-sample but leaves n and its Theiler window out); the prediction is the
/// average image `x̂_{n+h} = (1/|U_n|) Σ_{j∈U_n} x_{j+h}` and the statistic is
/// `e = sqrt( ⟨(x̂_{n+h} − x_{n+h})²⟩_n ) / σ_x` (not in SPEC). ε starts at `epsilon·σ_x` and
/// grows by `epsilon_factor` for the points with fewer than `min_neighbors` neighbours.
/// e ≈ 1 means no better than predicting the mean; chaos gives e ≪ 1 at short horizons.
///
/// # Units
/// Dimensionless (fraction of the standard deviation); m, τ, h, w in samples.
///
/// # Parameters
/// [`PredictionErrorOptions`]: m = 3, τ = 1, h = 1, ε = 0.1 σ, at least 5 neighbours,
/// ε factor 1.2, w = 0.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for zero m, τ, h or `min_neighbors`, ε ≤ 0 or factor ≤ 1;
/// [`AnalysisError::TooShort`] when fewer than `2 (min_neighbors + w) + 10` delay vectors
/// exist; [`AnalysisError::NonFinite`], [`AnalysisError::Constant`].
///
/// # Pitfalls
/// - For a finely sampled flow, τ = h = 1 makes every smooth series (noise surrogates
///   included) easy to predict: use τ and h near the first minimum of the mutual information
///   and a Theiler window of several τ, or the test loses its power.
/// - Observational noise raises e for the data and for the surrogates alike; at 10 % noise
///   use a larger ε (≈ 2–3 noise levels) and more neighbours.
/// - Non-stationarity lowers e (recurrent neighbours are temporally close): use a Theiler
///   window.
///
/// # References
/// J. D. Farmer and J. J. Sidorowich, "Predicting chaotic time series", Phys. Rev. Lett. 59,
/// 845–848 (1987). doi:10.1103/PhysRevLett.59.845.
/// G. Sugihara and R. M. May, "Nonlinear forecasting as a way of distinguishing chaos from
/// measurement error in time series", Nature 344, 734–741 (1990). doi:10.1038/344734a0.
/// R. Hegger, H. Kantz and T. Schreiber, "Practical implementation of nonlinear time series
/// methods: The TISEAN package", Chaos 9, 413–435 (1999). doi:10.1063/1.166424.
///
/// # Example
/// ```
/// use pdamp::analysis::prediction_error::{prediction_error, PredictionErrorOptions};
/// use pdamp::systems::henon::henon_x;
/// let o = PredictionErrorOptions { dim: 2, ..Default::default() };
/// let e = prediction_error(&henon_x(3000), &o).unwrap();
/// assert!(e < 0.1, "{e}"); // deterministic: predictable one step ahead
/// ```
pub fn prediction_error(x: &[f64], opts: &PredictionErrorOptions) -> Result<f64, AnalysisError> {
    opts.validate()?;
    let first = (opts.dim - 1) * opts.delay;
    let need = first + opts.horizon + 2 * (opts.min_neighbors + opts.theiler) + 10;
    validate_series(x, need, "the nonlinear prediction error")?;
    let n_end = x.len() - opts.horizon; // exclusive
    let sd = standard_deviation(x);
    let (lo, hi) = min_max(x);
    let range = hi - lo;
    let mut eps = opts.epsilon * sd;
    if !(eps > 0.0 && eps.is_finite() && range.is_finite()) {
        // the ε loop below must grow from a positive radius to the range
        return Err(AnalysisError::NoResult(format!(
            "the nonlinear prediction error needs a spread that floating point resolves: \
             standard deviation {sd:e}, range {range:e}; rescale the series"
        )));
    }
    let mut pending: Vec<usize> = (first..n_end).collect();
    let count = pending.len();
    let mut sum_sq = 0.0;
    loop {
        let last_round = eps > range;
        let grid = BoxGrid::new(x, opts.dim, opts.delay, eps, first..n_end);
        let mut still = Vec::new();
        for &n in &pending {
            let (mut k, mut s) = (0usize, 0.0);
            grid.for_each_neighbor(x, n, |j| {
                if j.abs_diff(n) > opts.theiler {
                    k += 1;
                    s += x[j + opts.horizon];
                }
            });
            if k >= opts.min_neighbors || (last_round && k > 0) {
                let e = s / k as f64 - x[n + opts.horizon];
                sum_sq += e * e;
            } else if last_round {
                // no neighbour at all outside the Theiler window: predict the mean
                let mean = x.iter().sum::<f64>() / x.len() as f64;
                let e = mean - x[n + opts.horizon];
                sum_sq += e * e;
            } else {
                still.push(n);
            }
        }
        pending = still;
        if pending.is_empty() || last_round {
            break;
        }
        eps *= opts.epsilon_factor;
    }
    Ok((sum_sq / count as f64).sqrt() / sd)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_series_is_predicted_exactly() {
        // period 7: every delay vector recurs exactly, so the prediction error is 0
        let x: Vec<f64> = (0..700).map(|i| ((i * 3) % 7) as f64).collect();
        let e = prediction_error(&x, &PredictionErrorOptions::default()).unwrap();
        assert!(e < 1e-12, "{e}");
    }

    #[test]
    fn unresolvable_spread_is_an_error_not_a_hang() {
        // found by the mutation fuzzer: the deviations square to 0, so ε = 0 never grew
        let x: Vec<f64> = (0..300)
            .map(|i| if (i * 7) % 3 == 0 { 5e-324 } else { 0.0 })
            .collect();
        let e = prediction_error(&x, &PredictionErrorOptions::default());
        assert!(matches!(e, Err(AnalysisError::NoResult(_))), "{e:?}");
        // a large offset is fine: the standard deviation is taken in two passes
        let y: Vec<f64> = (0..300)
            .map(|i| 1e9 + 1e-6 * (0.3 * i as f64).sin())
            .collect();
        assert!(prediction_error(&y, &PredictionErrorOptions::default()).is_ok());
    }

    #[test]
    fn validation() {
        let x: Vec<f64> = (0..100).map(|i| (i as f64).sin()).collect();
        let bad = PredictionErrorOptions {
            epsilon: 0.0,
            ..Default::default()
        };
        assert!(prediction_error(&x, &bad).is_err());
        let bad = PredictionErrorOptions {
            dim: 0,
            ..Default::default()
        };
        assert!(prediction_error(&x, &bad).is_err());
        assert!(matches!(
            prediction_error(&x[..10], &PredictionErrorOptions::default()),
            Err(AnalysisError::TooShort(_))
        ));
    }
}
