//! Time-reversal asymmetry statistic, a cheap discriminating statistic for surrogate tests
//! (Theiler et al. 1992; TISEAN `timerev`).

use crate::analysis::validate_series;
use crate::error::AnalysisError;

/// Returns the normalised time-reversal asymmetry `Q(τ)` of `x` at lag `τ` samples.
///
/// # Formula
/// `Q(τ) = ⟨(x_{n+τ} − x_n)³⟩ / ⟨(x_{n+τ} − x_n)²⟩^{3/2}`, averages over n = 0..N−τ−1
/// (the skewness of the increments about zero; not in SPEC). A linear Gaussian process, or any
/// static monotone transform of one, is statistically time-reversible: `E Q(τ) = 0`.
///
/// # Units
/// Dimensionless (invariant under `x → a x + b` with `a > 0`; changes sign for `a < 0`).
///
/// # Parameters
/// `lag` τ ≥ 1 in samples; a natural choice is 1 for maps and about the first minimum of the
/// mutual information for flows.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `lag = 0`; [`AnalysisError::TooShort`] for fewer than
/// `lag + 3` samples; [`AnalysisError::NonFinite`], [`AnalysisError::Constant`].
///
/// # Pitfalls
/// Its sign depends on the system, so test it two-sided ([`crate::analysis::surrogate_test::Tail::TwoSided`]).
/// Some chaotic systems are nearly time-reversible in a given observable (Lorenz x, by the
/// symmetry of the equations): a small |Q| does not mean linear. Use it together with the
/// nonlinear prediction error ([`crate::analysis::prediction_error`](mod@crate::analysis::prediction_error)).
///
/// # References
/// J. Theiler, S. Eubank, A. Longtin, B. Galdrikian and J. D. Farmer, "Testing for
/// nonlinearity in time series: the method of surrogate data", Physica D 58, 77–94 (1992).
/// doi:10.1016/0167-2789(92)90102-S.
/// T. Schreiber and A. Schmitz, "Surrogate time series", Physica D 142, 346–382 (2000), eq. (7).
/// doi:10.1016/S0167-2789(00)00043-9.
///
/// # Example
/// ```
/// use pdamp::analysis::time_reversal::time_reversal_asymmetry;
/// use pdamp::systems::henon::henon_x;
/// // the Hénon map is strongly irreversible: |Q(1)| is of order 1
/// let q = time_reversal_asymmetry(&henon_x(5000), 1).unwrap();
/// assert!(q.abs() > 0.3, "{q}");
/// ```
pub fn time_reversal_asymmetry(x: &[f64], lag: usize) -> Result<f64, AnalysisError> {
    if lag == 0 {
        return Err(AnalysisError::bad("lag", lag, "must be at least 1 sample"));
    }
    validate_series(x, lag + 3, "time-reversal asymmetry")?;
    let (mut s2, mut s3) = (0.0, 0.0);
    for (a, b) in x.iter().zip(&x[lag..]) {
        let d = b - a;
        s2 += d * d;
        s3 += d * d * d;
    }
    let m = (x.len() - lag) as f64;
    let (m2, m3) = (s2 / m, s3 / m);
    if m2 <= 0.0 {
        return Err(AnalysisError::Constant);
    }
    Ok(m3 / m2.powf(1.5))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sawtooth_is_irreversible_and_reversed_changes_sign() {
        // slow rise, sudden drop: increments 1,1,1,−3 → ⟨d³⟩ = (3 − 27)/4 = −6, ⟨d²⟩ = 3
        let x: Vec<f64> = (0..400).map(|i| (i % 4) as f64).collect();
        let q = time_reversal_asymmetry(&x, 1).unwrap();
        let want = -6.0 / 3f64.powf(1.5);
        assert!((q - want).abs() < 0.01, "{q} vs {want}");
        let r: Vec<f64> = x.iter().rev().copied().collect();
        assert!((time_reversal_asymmetry(&r, 1).unwrap() + q).abs() < 0.01);
        assert!(time_reversal_asymmetry(&x, 0).is_err());
    }
}
