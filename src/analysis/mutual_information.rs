//! Time-delayed mutual information I(τ) with a fixed-bin histogram (Fraser & Swinney 1986;
//! SPEC (4.1.5)), computed exactly as TISEAN 3.0.1's `mutual` (SPEC §8).

use crate::analysis::{reject_monotonic, rescale_unit, validate_series};
use crate::error::AnalysisError;

/// Options of [`mutual_information`]; the defaults are TISEAN `mutual`'s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MutualInformationOptions {
    /// Number of histogram bins per axis `b` (TISEAN `-b`). Default 16.
    pub bins: usize,
    /// Largest lag `D` in samples (TISEAN `-D`). Default 20. Lowered to `N − 1` if larger.
    pub max_lag: usize,
}

impl Default for MutualInformationOptions {
    fn default() -> Self {
        Self {
            bins: 16,
            max_lag: 20,
        }
    }
}

/// The curve I(τ), τ = 0..=D, and its first minimum.
#[derive(Debug, Clone, PartialEq)]
pub struct MutualInformation {
    /// `values[τ]` = I(τ) in nats; `values[0]` is the Shannon entropy of the binned series.
    pub values: Vec<f64>,
    /// First local minimum (see [`first_minimum`]), in samples; `None` if the curve has none
    /// up to `D`.
    pub first_minimum: Option<usize>,
    /// Number of bins used.
    pub bins: usize,
}

/// Time-delayed mutual information I(τ) for τ = 0..=D and its first minimum.
///
/// # Formula
/// (4.1.5): `I(τ) = Σ_ij p_ij(τ) ln( p_ij(τ) / (p_i p_j) )`, natural log. The series is first
/// rescaled to [0, 1]; sample `x` falls in bin `⌊x·b⌋` (`x = 1` in bin `b − 1`). For each τ the
/// joint histogram `p_ij` and both marginals `p_i` (of `s_{n−τ}`) and `p_j` (of `s_n`) are
/// counted over the `N − τ` pairs `(s_{n−τ}, s_n)`, `n = τ..N−1` — TISEAN `mutual`'s definition
/// (SPEC §8), reproduced to rounding.
///
/// # Units
/// Input in any units (rescaled internally); output in nats; lags in samples.
///
/// # Parameters
/// [`MutualInformationOptions`]: `bins = 16`, `max_lag = 20` (TISEAN's defaults).
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `bins < 2`; [`AnalysisError::TooShort`] for fewer than
/// 2 samples; [`AnalysisError::NonFinite`], [`AnalysisError::Constant`],
/// [`AnalysisError::Monotonic`] (a time column).
///
/// # Pitfalls
/// The fixed-bin estimator is biased upwards for short series and many bins (roughly
/// `(b−1)²/(2N)` nats); the position of the first minimum is much less affected than its
/// value; see [`small_sample_bias`] (with 10 samples and 16 bins the curve is all bias).
/// A monotonically decaying I(τ) (e.g. noise, or `D` too small) has no first minimum:
/// `first_minimum` is `None`.
///
/// # References
/// A. M. Fraser and H. L. Swinney, "Independent coordinates for strange attractors from mutual
/// information", Phys. Rev. A 33, 1134–1140 (1986). doi:10.1103/PhysRevA.33.1134.
/// R. Hegger, H. Kantz, T. Schreiber, "Practical implementation of nonlinear time series
/// methods: The TISEAN package", Chaos 9, 413–435 (1999). doi:10.1063/1.166424
///
/// # Example
/// ```
/// use pdamp::analysis::{mutual_information, MutualInformationOptions};
/// use pdamp::systems::lorenz::lorenz_x;
/// let x = lorenz_x(10_000, 0.01);
/// let mi = mutual_information(&x, &MutualInformationOptions { bins: 16, max_lag: 50 }).unwrap();
/// // Lorenz x at dt = 0.01: first minimum at 0.15–0.2 time units
/// let tau = mi.first_minimum.unwrap();
/// assert!((15..=20).contains(&tau));
/// ```
pub fn mutual_information(
    x: &[f64],
    opts: &MutualInformationOptions,
) -> Result<MutualInformation, AnalysisError> {
    if opts.bins < 2 {
        return Err(AnalysisError::bad(
            "bins",
            opts.bins,
            "need at least 2 histogram bins (TISEAN default 16)",
        ));
    }
    validate_series(x, 2, "mutual information")?;
    reject_monotonic(x)?;
    let b = opts.bins;
    let rescaled = rescale_unit(x)?;
    let binned: Vec<u32> = rescaled
        .values
        .iter()
        .map(|&v| bin_of(v, b) as u32)
        .collect();
    let max_lag = opts.max_lag.min(x.len() - 1);
    let mut hist = Histograms::new(b);
    let values: Vec<f64> = (0..=max_lag)
        .map(|tau| hist.mutual_information(&binned, tau))
        .collect();
    let first_minimum = first_minimum(&values);
    Ok(MutualInformation {
        values,
        first_minimum,
        bins: b,
    })
}

/// Bin index of a rescaled value `v ∈ [0, 1]`: `⌊v·b⌋`, with `v ≥ 1` in the last bin.
#[inline]
fn bin_of(v: f64, b: usize) -> usize {
    if v < 1.0 {
        ((v * b as f64) as usize).min(b - 1)
    } else {
        b - 1
    }
}

/// Reusable histogram storage (no allocation per lag).
struct Histograms {
    b: usize,
    h_past: Vec<u64>,
    h_now: Vec<u64>,
    joint: Vec<u64>,
}

impl Histograms {
    fn new(b: usize) -> Self {
        Self {
            b,
            h_past: vec![0; b],
            h_now: vec![0; b],
            joint: vec![0; b * b],
        }
    }

    /// I(τ) from the pairs (binned[n−τ], binned[n]), n = τ..N−1.
    fn mutual_information(&mut self, binned: &[u32], tau: usize) -> f64 {
        let b = self.b;
        self.h_past.fill(0);
        self.h_now.fill(0);
        self.joint.fill(0);
        for (&past, &now) in binned.iter().zip(&binned[tau..]) {
            let (i, j) = (past as usize, now as usize);
            self.h_past[i] += 1;
            self.h_now[j] += 1;
            self.joint[i * b + j] += 1;
        }
        let norm = 1.0 / (binned.len() - tau) as f64;
        let mut sum = 0.0;
        for i in 0..b {
            let pi = self.h_past[i] as f64 * norm;
            if pi <= 0.0 {
                continue;
            }
            for j in 0..b {
                let pj = self.h_now[j] as f64 * norm;
                let pij = self.joint[i * b + j] as f64 * norm;
                if pj > 0.0 && pij > 0.0 {
                    // same operation order as TISEAN: ln(p_ij / p_j / p_i)
                    sum += pij * (pij / pj / pi).ln();
                }
            }
        }
        sum
    }
}

/// Leading small-sample bias of the fixed-bin estimate of I(τ), in nats:
/// `(b − 1)² / (2·n_pairs)` (the Miller–Madow term of the joint histogram minus those of the
/// two marginals, for independent variables). When it is comparable with I(τ) itself the
/// curve, and its first minimum, are dominated by the estimator, not by the data.
pub fn small_sample_bias(n_pairs: usize, bins: usize) -> f64 {
    let b1 = bins.saturating_sub(1) as f64;
    b1 * b1 / (2.0 * n_pairs.max(1) as f64)
}

/// Index of the first local minimum of a curve: the first `τ ≥ 1` with
/// `I(τ) < I(τ−1)` and `I(τ) ≤ I(τ+1)`. `None` if there is none (the last point never counts,
/// since the curve might still be decreasing).
pub fn first_minimum(values: &[f64]) -> Option<usize> {
    (1..values.len().saturating_sub(1))
        .find(|&t| values[t] < values[t - 1] && values[t] <= values[t + 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_follow_tisean() {
        assert_eq!(bin_of(0.0, 16), 0);
        assert_eq!(bin_of(0.999_999, 16), 15);
        assert_eq!(bin_of(1.0, 16), 15);
        assert_eq!(bin_of(0.5, 16), 8);
    }

    #[test]
    fn first_minimum_definition() {
        assert_eq!(first_minimum(&[3.0, 2.0, 1.0, 1.5, 0.5]), Some(2));
        assert_eq!(first_minimum(&[3.0, 2.0, 1.0]), None);
        assert_eq!(first_minimum(&[3.0, 2.0, 2.0, 1.0, 1.0]), Some(1));
    }

    #[test]
    fn mi_at_zero_is_entropy_of_uniform_bins() {
        // 4 values, one per bin with b = 4 → entropy ln 4 exactly (not in increasing order:
        // a series that rises at every sample is refused as a time column).
        let x = [1.0 / 3.0, 0.0, 1.0, 2.0 / 3.0];
        let mi = mutual_information(
            &x,
            &MutualInformationOptions {
                bins: 4,
                max_lag: 1,
            },
        )
        .unwrap();
        assert!((mi.values[0] - 4f64.ln()).abs() < 1e-12);
    }

    #[test]
    fn rejects_one_bin() {
        let o = MutualInformationOptions {
            bins: 1,
            max_lag: 3,
        };
        assert!(mutual_information(&[1.0, 2.0, 3.0], &o).is_err());
    }
}
