//! Delay embedding (Takens 1981; SPEC (4.1.1)).

use crate::error::AnalysisError;

/// Delay vectors of a scalar series, without copying it.
///
/// Vector `i` (for `i = 0 .. len()`) is `(s_i, s_{i+τ}, …, s_{i+(m−1)τ})`. SPEC (4.1.1) writes
/// the same vectors labelled by their last time, `s_n = (s_{n−(m−1)τ}, …, s_n)` with
/// `n = i + (m−1)τ`; TISEAN labels them by the first time, as here.
///
/// # Formula
/// (4.1.1): `s_n = (s_{n−(m−1)τ}, …, s_{n−τ}, s_n)`.
///
/// # Units
/// Components carry the units of the series; `τ` is in samples.
///
/// # Parameters
/// `m ≥ 1` (embedding dimension), `τ ≥ 1` (lag, samples).
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `m = 0` or `τ = 0`; [`AnalysisError::TooShort`] when
/// the series has no complete vector (`N ≤ (m−1)τ`).
///
/// # References
/// F. Takens, "Detecting strange attractors in turbulence", Lecture Notes in Mathematics 898,
/// 366–381 (1981). doi:10.1007/BFb0091924
///
/// # Example
/// ```
/// use pdamp::analysis::DelayEmbedding;
/// let x = [1.0, 2.0, 3.0, 4.0, 5.0];
/// let e = DelayEmbedding::new(&x, 2, 3).unwrap();
/// assert_eq!(e.len(), 2);
/// assert_eq!(e.vector(1), vec![2.0, 5.0]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct DelayEmbedding<'a> {
    x: &'a [f64],
    m: usize,
    tau: usize,
}

impl<'a> DelayEmbedding<'a> {
    /// Delay embedding of `x` in dimension `m` with lag `tau` (samples).
    ///
    /// # Errors
    /// See the type's documentation.
    pub fn new(x: &'a [f64], m: usize, tau: usize) -> Result<Self, AnalysisError> {
        crate::analysis::require_positive("m (embedding dimension)", m)?;
        crate::analysis::require_positive("tau (lag, samples)", tau)?;
        if x.len() <= (m - 1) * tau {
            return Err(AnalysisError::TooShort(format!(
                "an embedding with m = {m}, tau = {tau} needs more than {} samples, the series has {}",
                (m - 1) * tau,
                x.len()
            )));
        }
        Ok(Self { x, m, tau })
    }

    /// Number of complete delay vectors, `N − (m−1)τ`.
    pub fn len(&self) -> usize {
        vector_count(self.x.len(), self.m, self.tau)
    }

    /// Always false: construction requires at least one vector.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Embedding dimension `m`.
    pub fn dimension(&self) -> usize {
        self.m
    }

    /// Lag `τ` in samples.
    pub fn lag(&self) -> usize {
        self.tau
    }

    /// Component `k` (`0 ≤ k < m`) of vector `i`: `s_{i+kτ}`.
    #[inline]
    pub fn component(&self, i: usize, k: usize) -> f64 {
        self.x[i + k * self.tau]
    }

    /// Vector `i` as a new `Vec` (convenience; hot loops should use [`Self::component`]).
    pub fn vector(&self, i: usize) -> Vec<f64> {
        (0..self.m).map(|k| self.component(i, k)).collect()
    }

    /// Fills a fixed-size array with vector `i`; `K` must equal `m`.
    #[inline]
    pub fn array<const K: usize>(&self, i: usize) -> [f64; K] {
        debug_assert_eq!(K, self.m);
        std::array::from_fn(|k| self.component(i, k))
    }
}

/// Number of delay vectors of a series of length `n`: `n − (m−1)τ`, or 0 if none fits.
pub fn vector_count(n: usize, m: usize, tau: usize) -> usize {
    n.saturating_sub(m.saturating_sub(1) * tau)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_components() {
        let x: Vec<f64> = (0..10).map(|v| v as f64).collect();
        let e = DelayEmbedding::new(&x, 3, 2).unwrap();
        assert_eq!(e.len(), 6);
        assert_eq!(e.vector(5), vec![5.0, 7.0, 9.0]);
        assert_eq!(e.array::<3>(0), [0.0, 2.0, 4.0]);
    }

    #[test]
    fn rejects_bad_parameters() {
        let x = [1.0, 2.0, 3.0];
        assert!(DelayEmbedding::new(&x, 0, 1).is_err());
        assert!(DelayEmbedding::new(&x, 2, 0).is_err());
        assert!(DelayEmbedding::new(&x, 3, 1).is_ok());
        assert!(DelayEmbedding::new(&x, 2, 3).is_err());
    }
}
