//! The Gottwald–Melbourne 0–1 test for chaos (correlation method): K ≈ 0 for regular
//! (periodic, quasi-periodic) dynamics, K ≈ 1 for chaos. An independent cross-check of the
//! Lyapunov exponent that needs no embedding.

use crate::analysis::spectrum::check_finite;
use crate::error::AnalysisError;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Options of [`zero_one_test`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZeroOneOptions {
    /// Number of random frequencies c drawn uniformly in (π/5, 4π/5) (default 100).
    pub n_c: usize,
    /// Seed of the ChaCha8 generator that draws c (default 1): results are deterministic.
    pub seed: u64,
    /// Use at most this many samples, the last ones (default 4000): the cost is
    /// O(n_c · N · N/10).
    pub max_samples: usize,
}

impl Default for ZeroOneOptions {
    fn default() -> Self {
        ZeroOneOptions {
            n_c: 100,
            seed: 1,
            max_samples: 4000,
        }
    }
}

/// Result of [`zero_one_test`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZeroOneResult {
    /// Median of K_c over the random c: ≈ 0 regular, ≈ 1 chaotic (threshold 0.5).
    pub k: f64,
    /// Number of samples used.
    pub n_samples: usize,
}

/// Returns the 0–1 test statistic K of the observable φ(j) = `x[j]`.
///
/// # Formula
/// p_c(n) = Σ_{j≤n} φ(j) cos(jc), q_c(n) = Σ_{j≤n} φ(j) sin(jc);
/// M_c(n) = (1/(N−n_cut)) Σ_{j<N−n_cut} [(p_c(j+n) − p_c(j))² + (q_c(j+n) − q_c(j))²];
/// D_c(n) = M_c(n) − (E φ)² (1 − cos nc)/(1 − cos c) (the oscillatory term removed);
/// K_c = corr(n, D_c(n)) over n = 1..n_cut = N/10; K = median over c ∈ (π/5, 4π/5)
/// (SPEC §9: K ≈ 0 regular, ≈ 1 chaos, threshold 0.5).
///
/// # Units
/// K is dimensionless; φ in any unit (the correlation is scale-free).
///
/// # Parameters
/// See [`ZeroOneOptions`]: 100 values of c, seed 1, at most the last 4000 samples.
///
/// # Errors
/// Fewer than 100 samples, non-finite samples, `n_c` = 0. A constant series returns K = 0.
///
/// # Pitfalls
/// Oversampled flows make the test report K ≈ 0 even for chaos: feed it one sample per forcing
/// period or per delay time τ (as [`crate::analysis::analyze`] does). For white noise K ≈ 1 as
/// well: the test detects irregularity, not determinism.
///
/// # References
/// G. A. Gottwald, I. Melbourne, "On the implementation of the 0–1 test for chaos", SIAM J.
/// Appl. Dyn. Syst. 8(1), 129–145 (2009), doi:10.1137/080718851; and "The 0–1 test for chaos: a
/// review", Lect. Notes Phys. 915, 221–247 (2016).
///
/// # Example
/// ```
/// use pdamp::analysis::zero_one_test::{zero_one_test, ZeroOneOptions};
/// let mut x = vec![0.3_f64];
/// for _ in 0..1999 { let v = *x.last().unwrap(); x.push(4.0 * v * (1.0 - v)); }
/// assert!(zero_one_test(&x, &ZeroOneOptions::default()).unwrap().k > 0.8);
/// ```
pub fn zero_one_test(x: &[f64], opts: &ZeroOneOptions) -> Result<ZeroOneResult, AnalysisError> {
    check_finite(x, 100, "the 0-1 test")?;
    if opts.n_c == 0 {
        return Err(AnalysisError::bad(
            "n_c",
            0,
            "draw at least one frequency c",
        ));
    }
    let start = x.len().saturating_sub(opts.max_samples.max(100));
    let phi = &x[start..];
    let n = phi.len();
    let n_samples = n;
    let mean = phi.iter().sum::<f64>() / n as f64;
    let (lo, hi) = phi
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    if hi - lo <= 1e-12 * hi.abs().max(lo.abs()).max(f64::MIN_POSITIVE) {
        return Ok(ZeroOneResult { k: 0.0, n_samples });
    }
    let n_cut = n / 10;
    let m_len = n - n_cut;
    let mut rng = ChaCha8Rng::seed_from_u64(opts.seed);
    let pi = std::f64::consts::PI;
    let mut p = vec![0.0; n];
    let mut q = vec![0.0; n];
    let mut d = vec![0.0; n_cut];
    let mut ks = Vec::with_capacity(opts.n_c);
    for _ in 0..opts.n_c {
        let c = pi / 5.0 + rng.random::<f64>() * 3.0 * pi / 5.0;
        let (mut ps, mut qs) = (0.0, 0.0);
        for (j, &v) in phi.iter().enumerate() {
            let arg = (j + 1) as f64 * c;
            ps += v * arg.cos();
            qs += v * arg.sin();
            p[j] = ps;
            q[j] = qs;
        }
        for (i, slot) in d.iter_mut().enumerate() {
            let lag = i + 1;
            let mut acc = 0.0;
            for j in 0..m_len {
                let dp = p[j + lag] - p[j];
                let dq = q[j + lag] - q[j];
                acc += dp * dp + dq * dq;
            }
            let v_osc = mean * mean * (1.0 - (lag as f64 * c).cos()) / (1.0 - c.cos());
            *slot = acc / m_len as f64 - v_osc;
        }
        ks.push(correlation_with_index(&d));
    }
    ks.sort_by(f64::total_cmp);
    let mid = ks.len() / 2;
    let k = if ks.len() % 2 == 1 {
        ks[mid]
    } else {
        0.5 * (ks[mid - 1] + ks[mid])
    };
    Ok(ZeroOneResult { k, n_samples })
}

/// Pearson correlation of (1, 2, …, len) with `d`; 0 when `d` is constant.
fn correlation_with_index(d: &[f64]) -> f64 {
    let n = d.len() as f64;
    let mx = (n + 1.0) / 2.0;
    let my = d.iter().sum::<f64>() / n;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (i, &y) in d.iter().enumerate() {
        let dx = (i + 1) as f64 - mx;
        let dy = y - my;
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    if syy <= 0.0 || sxx <= 0.0 {
        return 0.0;
    }
    sxy / (sxx * syy).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn correlation_of_line_is_one() {
        let d: Vec<f64> = (0..50).map(|i| 3.0 * i as f64 - 2.0).collect();
        assert!((correlation_with_index(&d) - 1.0).abs() < 1e-12);
        assert_eq!(correlation_with_index(&[2.0; 10]), 0.0);
    }

    #[test]
    fn constant_and_short_series() {
        assert_eq!(
            zero_one_test(&[1.0; 200], &ZeroOneOptions::default())
                .unwrap()
                .k,
            0.0
        );
        assert!(matches!(
            zero_one_test(&[1.0; 50], &ZeroOneOptions::default()),
            Err(AnalysisError::TooShort(_))
        ));
    }
}
