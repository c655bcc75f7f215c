//! Surrogate-data test of a null hypothesis by rank (Theiler et al. 1992; Schreiber & Schmitz
//! 2000): compute a discriminating statistic on the data and on n surrogates, and reject when
//! the data's value is extreme among the n + 1 values.

use rayon::prelude::*;
use serde::Serialize;

use crate::analysis::surrogates::{surrogates, SurrogateOptions};
use crate::error::AnalysisError;

/// Which side of the surrogate distribution counts as evidence against the null hypothesis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Tail {
    /// Data value smaller than the surrogates' (e.g. a prediction error: chaos is more
    /// predictable than its linear surrogates). The default.
    #[default]
    Lower,
    /// Data value larger than the surrogates'.
    Upper,
    /// Either side (e.g. time-reversal asymmetry, whose sign is not known in advance).
    TwoSided,
}

impl std::str::FromStr for Tail {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "lower" => Ok(Self::Lower),
            "upper" => Ok(Self::Upper),
            "two-sided" | "two_sided" | "both" => Ok(Self::TwoSided),
            _ => Err(format!("unknown tail `{s}`: use lower, upper or two-sided")),
        }
    }
}

/// Options of [`surrogate_test`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SurrogateTestOptions {
    /// Number of surrogates n. Default 19: the smallest one-sided p-value is 1/(n+1) = 0.05.
    /// Use 39 for a two-sided test at 0.05 (smallest two-sided p = 2/(n+1)).
    pub n_surrogates: usize,
    /// How the surrogates are made (method, iterations, seed). Default IAAFT, seed 0.
    pub surrogate: SurrogateOptions,
    /// Side of the test. Default [`Tail::Lower`].
    pub tail: Tail,
}

impl Default for SurrogateTestOptions {
    fn default() -> Self {
        Self {
            n_surrogates: 19,
            surrogate: SurrogateOptions::default(),
            tail: Tail::Lower,
        }
    }
}

/// Outcome of [`surrogate_test`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurrogateTestResult {
    /// Statistic of the data.
    pub data_value: f64,
    /// Statistic of each surrogate, in surrogate order (surrogate k uses stream k of the seed).
    pub surrogate_values: Vec<f64>,
    /// 1-based rank of the data among the n + 1 values in ascending order (1 = smallest);
    /// ties with surrogates count against the data (the rank is 1 + #{surrogates < data}).
    pub rank: usize,
    /// Number of surrogates whose value is ≤ the data's.
    pub n_le: usize,
    /// Number of surrogates whose value is ≥ the data's.
    pub n_ge: usize,
    /// p-value by rank for the chosen tail (see [`surrogate_test`]).
    pub p_value: f64,
    /// Smallest p-value this test can give: 1/(n+1) one-sided, 2/(n+1) two-sided.
    pub p_min: f64,
    /// Mean of the surrogates' values.
    pub surrogate_mean: f64,
    /// Sample standard deviation (n − 1 denominator) of the surrogates' values.
    pub surrogate_sd: f64,
    /// Significance |t_data − mean_s| / sd_s in standard deviations (∞ if sd_s = 0 and the
    /// data differ, 0 if all equal).
    pub significance_sigma: f64,
    /// Side used.
    pub tail: Tail,
    /// Largest IAAFT discrepancy among the surrogates (0 for FT/shuffle).
    pub max_discrepancy: f64,
    /// Number of IAAFT surrogates whose iteration hit `max_iterations` before the ranks
    /// stopped changing.
    pub not_converged: usize,
}

impl SurrogateTestResult {
    /// True when `p_value ≤ alpha`.
    pub fn rejects(&self, alpha: f64) -> bool {
        self.p_value <= alpha
    }
}

/// Returns the surrogate test of the null hypothesis represented by `opts.surrogate` with the
/// discriminating statistic `statistic`.
///
/// # Formula
/// With `t_0` the data's statistic and `t_1..t_n` the surrogates':
/// lower tail `p = (1 + #{t_i ≤ t_0})/(n + 1)`; upper tail `p = (1 + #{t_i ≥ t_0})/(n + 1)`;
/// two-sided `p = min(1, 2 min(p_lower, p_upper))`. Ties count against rejection
/// (conservative). Under the null hypothesis the n + 1 values are exchangeable, so
/// `P(p ≤ k/(n+1)) = k/(n+1)` (one-sided): the smallest achievable p is 1/(n+1).
/// Significance `S = |t_0 − ⟨t⟩| / sd(t)`, sample standard deviation of the surrogates
/// (Theiler et al. 1992, eq. (1); only indicative — the rank test needs no Gaussian
/// assumption). Not in SPEC.
///
/// # Units
/// Those of the statistic; p dimensionless; S in standard deviations.
///
/// # Parameters
/// [`SurrogateTestOptions`]: 19 IAAFT surrogates, seed 0, lower tail.
/// The statistic must be `Sync`: the surrogates are generated and evaluated in parallel with
/// rayon; results do not depend on the number of threads.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `n_surrogates = 0`; those of
/// [`crate::analysis::surrogates::surrogates`]; the first error of the statistic on the data
/// or on a surrogate (in surrogate order).
///
/// # Pitfalls
/// - With n = 19 a one-sided test can only reach p = 0.05; "significance" in σ is not a
///   p-value (the surrogate distribution of a statistic is seldom Gaussian).
/// - Choose the tail before looking at the result; a two-sided test at 0.05 needs n ≥ 39.
/// - End-point mismatch and non-stationarity make IAAFT surrogates rougher than the data and
///   give false rejections for smooth series; see [`crate::analysis::surrogates::end_to_end_segment`].
/// - Repeating the test over many statistics or parameters inflates the false-rejection
///   rate.
///
/// # References
/// J. Theiler, S. Eubank, A. Longtin, B. Galdrikian and J. D. Farmer, "Testing for
/// nonlinearity in time series: the method of surrogate data", Physica D 58, 77–94 (1992).
/// doi:10.1016/0167-2789(92)90102-S.
/// T. Schreiber and A. Schmitz, "Surrogate time series", Physica D 142, 346–382 (2000).
/// doi:10.1016/S0167-2789(00)00043-9.
///
/// # Example
/// ```
/// use pdamp::analysis::prediction_error::{prediction_error, PredictionErrorOptions};
/// use pdamp::analysis::surrogate_test::{surrogate_test, SurrogateTestOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(2000);
/// let o = PredictionErrorOptions { dim: 2, ..Default::default() };
/// let stat = |s: &[f64]| prediction_error(s, &o);
/// let r = surrogate_test(&x, &stat, &SurrogateTestOptions::default()).unwrap();
/// assert_eq!(r.rank, 1);
/// assert!((r.p_value - 0.05).abs() < 1e-12); // 1/(19+1): rejected at the 5 % level
/// ```
pub fn surrogate_test(
    x: &[f64],
    statistic: &(dyn Fn(&[f64]) -> Result<f64, AnalysisError> + Sync),
    opts: &SurrogateTestOptions,
) -> Result<SurrogateTestResult, AnalysisError> {
    let n = opts.n_surrogates;
    crate::analysis::require_positive("n_surrogates", n)?;
    let data_value = statistic(x)?;
    let surr = surrogates(x, n, &opts.surrogate)?;
    let values: Vec<Result<f64, AnalysisError>> =
        surr.par_iter().map(|s| statistic(&s.values)).collect();
    let surrogate_values = values.into_iter().collect::<Result<Vec<f64>, _>>()?;
    let max_discrepancy = surr
        .iter()
        .map(|s| s.discrepancy)
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    let not_converged = surr.iter().filter(|s| !s.converged).count();
    Ok(rank_test(
        data_value,
        surrogate_values,
        opts.tail,
        max_discrepancy,
        not_converged,
    ))
}

/// Rank-based p-value and significance of `data_value` among `surrogate_values` (the part of
/// [`surrogate_test`] after the statistics are computed; useful when the surrogates' values
/// come from elsewhere).
pub fn rank_test(
    data_value: f64,
    surrogate_values: Vec<f64>,
    tail: Tail,
    max_discrepancy: f64,
    not_converged: usize,
) -> SurrogateTestResult {
    let n = surrogate_values.len();
    let nf = (n + 1) as f64;
    let n_lt = surrogate_values.iter().filter(|&&t| t < data_value).count();
    let n_le = surrogate_values
        .iter()
        .filter(|&&t| t <= data_value)
        .count();
    let n_ge = surrogate_values
        .iter()
        .filter(|&&t| t >= data_value)
        .count();
    let p_lower = (1 + n_le) as f64 / nf;
    let p_upper = (1 + n_ge) as f64 / nf;
    let (p_value, p_min) = match tail {
        Tail::Lower => (p_lower, 1.0 / nf),
        Tail::Upper => (p_upper, 1.0 / nf),
        Tail::TwoSided => ((2.0 * p_lower.min(p_upper)).min(1.0), (2.0 / nf).min(1.0)),
    };
    let mean = surrogate_values.iter().sum::<f64>() / n.max(1) as f64;
    let sd = if n > 1 {
        (surrogate_values
            .iter()
            .map(|t| (t - mean) * (t - mean))
            .sum::<f64>()
            / (n - 1) as f64)
            .sqrt()
    } else {
        0.0
    };
    let diff = (data_value - mean).abs();
    let significance_sigma = if sd > 0.0 {
        diff / sd
    } else if diff > 0.0 {
        f64::INFINITY
    } else {
        0.0
    };
    SurrogateTestResult {
        data_value,
        surrogate_values,
        rank: 1 + n_lt,
        n_le,
        n_ge,
        p_value,
        p_min,
        surrogate_mean: mean,
        surrogate_sd: sd,
        significance_sigma,
        tail,
        max_discrepancy,
        not_converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rank_p_values() {
        let s: Vec<f64> = (1..=19).map(|i| i as f64).collect();
        let r = rank_test(0.5, s.clone(), Tail::Lower, 0.0, 0);
        assert_eq!((r.rank, r.p_value), (1, 0.05));
        let r = rank_test(0.5, s.clone(), Tail::Upper, 0.0, 0);
        assert_eq!(r.p_value, 1.0);
        let r = rank_test(0.5, s.clone(), Tail::TwoSided, 0.0, 0);
        assert!((r.p_value - 0.1).abs() < 1e-15);
        assert!((r.p_min - 0.1).abs() < 1e-15);
        // a tie with the smallest surrogate counts against the data
        let r = rank_test(1.0, s.clone(), Tail::Lower, 0.0, 0);
        assert_eq!((r.rank, r.p_value), (1, 0.1));
        // middle: rank 10, p = 10/20
        let r = rank_test(9.5, s, Tail::Lower, 0.0, 0);
        assert_eq!((r.rank, r.p_value), (10, 0.5));
        // mean 10, sd of 1..19 = sqrt(31.666…) → S = 0.5/5.627
        assert!((r.significance_sigma - 0.5 / (95.0f64 / 3.0).sqrt()).abs() < 1e-12);
    }
}
