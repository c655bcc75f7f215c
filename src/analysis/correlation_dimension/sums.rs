//! The correlation sum C(m, ε) (Grassberger & Procaccia 1983, eq. (4)) per embedding
//! dimension, and its local slopes d ln C / d ln ε (dimensionless; ε in data units).

use super::counting::{count_grid, count_one_dimensional, BinTable, Job};
use super::options::{radii, validate_options, D2Options};
use crate::analysis::{min_max, validate_series};
use crate::error::AnalysisError;

/// The correlation sum of one embedding dimension at every radius.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrelationCurve {
    /// Embedding dimension m.
    pub m: usize,
    /// Radii ε in data units, increasing (the same for every m).
    pub eps: Vec<f64>,
    /// Number of pairs at maximum-norm distance ≤ ε.
    pub pairs: Vec<u64>,
    /// Correlation sum C(m, ε) = pairs / total pairs.
    pub c: Vec<f64>,
    /// Local slope d ln C / d ln ε ([`local_slopes`]); `None` where C = 0 at ε or its neighbours.
    pub slope: Vec<Option<f64>>,
}

/// All curves of one [`correlation_sum`] call.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrelationSums {
    /// One curve per m, in increasing m.
    pub curves: Vec<CorrelationCurve>,
    /// Number of pairs (i < j, j − i > w) among the delay vectors: the normalisation of C.
    pub total_pairs: u64,
    /// Number of delay vectors used, `N − (m_max − 1)τ` (the same for every m).
    pub vectors: usize,
}

/// Correlation sums C(m, ε) for m = m_min..=m_max and all ε, with their local slopes.
///
/// # Formula
/// `C(m, ε) = (1/P) Σ_{i<j, j−i>w} Θ(ε − ‖y_i − y_j‖_∞)` with delay vectors
/// `y_i = (s_i, s_{i+τ}, …, s_{i+(m−1)τ})`, `i = 0 .. N − (m_max−1)τ` (the same vectors for every
/// m, as TISEAN), Θ(0) = 1 (a pair at distance exactly ε counts), and P the number of pairs in
/// the sum. The correlation dimension is the slope of ln C versus ln ε in the scaling region,
/// `D2 = lim d ln C / d ln ε`, reached as m grows (SPEC §4; Grassberger & Procaccia 1983
/// eq. (4)). Radii: `ε_l = ε_min·f^l`, `f = (ε_max/ε_min)^{1/(count−1)}`.
///
/// # Units
/// ε in data units (the series is not rescaled, as TISEAN `d2` without `-E`); C is a
/// fraction; D2 is dimensionless. τ and w in samples.
///
/// # Parameters
/// [`D2Options`]: TISEAN `d2`'s defaults `m = 1..=10`, `τ = 1`, `w = 0`, ε from
/// (max − min)/1000 to max − min in 100 log-spaced steps. pdamp counts every pair (TISEAN's
/// `-N 0`); TISEAN's default `-N 1000` stops counting small radii early once they have 1000
/// pairs, which changes C by sampling noise only.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `m_min = 0`, `m_min > m_max`, `m_max > 32`, `τ = 0`,
/// `eps_count < 2`, a non-positive or non-finite radius, or `eps_min ≥ eps_max`;
/// [`AnalysisError::TooShort`] if fewer than 2 pairs remain after the Theiler window
/// (`N − (m_max−1)τ ≤ w + 2`); [`AnalysisError::NonFinite`]; [`AnalysisError::Constant`].
///
/// # Pitfalls
/// - Without a Theiler window a finely sampled flow gives a spuriously low D2 at small ε
///   (temporal neighbours on the same trajectory piece are 1-dimensional): set `w` to at
///   least the autocorrelation time.
/// - The plateau exists only between the noise/discreteness scale (small ε, few pairs: the
///   slopes scatter) and the attractor size (large ε, slopes fall); with N points one cannot
///   measure D2 larger than about 2 log10 N (Eckmann & Ruelle 1992).
/// - Noise gives slopes that grow with m at small ε (no plateau there).
///
/// # References
/// P. Grassberger and I. Procaccia, "Characterization of strange attractors", Phys. Rev.
/// Lett. 50, 346–349 (1983). doi:10.1103/PhysRevLett.50.346.
/// J. Theiler, "Spurious dimension from correlation algorithms applied to limited time-series
/// data", Phys. Rev. A 34, 2427–2432 (1986). doi:10.1103/PhysRevA.34.2427.
/// R. Hegger, H. Kantz, T. Schreiber, Chaos 9, 413–435 (1999). doi:10.1063/1.166424
///
/// # Example
/// ```
/// use pdamp::analysis::correlation_dimension::{correlation_sum, D2Options};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(2000);
/// let o = D2Options { m_min: 2, m_max: 2, eps_count: 20, ..D2Options::default() };
/// let r = correlation_sum(&x, &o).unwrap();
/// let c = &r.curves[0].c;
/// assert!(c[19] > 0.99 && c[0] < c[10]); // C grows with ε up to 1 at the attractor size
/// ```
pub fn correlation_sum(x: &[f64], opts: &D2Options) -> Result<CorrelationSums, AnalysisError> {
    validate_options(opts)?;
    validate_series(x, 2, "the correlation sum")?;
    crate::analysis::reject_monotonic(x)?;
    let span = (opts.m_max - 1) * opts.tau;
    let vectors = x.len().saturating_sub(span);
    if vectors < opts.theiler + 3 {
        return Err(AnalysisError::TooShort(format!(
            "the correlation sum with m_max = {}, tau = {}, Theiler window {} needs at least {} \
             samples, the series has {}",
            opts.m_max,
            opts.tau,
            opts.theiler,
            span + opts.theiler + 3,
            x.len()
        )));
    }
    let (lo, hi) = min_max(x);
    let eps = radii(opts, hi - lo)?;
    let bins = BinTable::new(&eps);
    let job = Job {
        s: x,
        lo,
        opts,
        vectors,
        eps_max: eps[eps.len() - 1],
        bins: &bins,
    };
    let n_dims = opts.m_max - opts.m_min + 1;
    let mut hist = vec![0u64; n_dims * eps.len()];
    if opts.m_min == 1 {
        let h1 = count_one_dimensional(&job);
        hist[..eps.len()].copy_from_slice(&h1);
    }
    if opts.m_max >= 2 {
        let h = count_grid(&job);
        for (a, b) in hist.iter_mut().zip(&h) {
            *a += b;
        }
    }
    let w = opts.theiler as u64;
    let nv = vectors as u64;
    let total_pairs = (nv - w - 1) * (nv - w) / 2;
    let curves = (opts.m_min..=opts.m_max)
        .map(|m| {
            let row = &hist[(m - opts.m_min) * eps.len()..(m - opts.m_min + 1) * eps.len()];
            let mut acc = 0u64;
            let pairs: Vec<u64> = row
                .iter()
                .map(|&h| {
                    acc += h;
                    acc
                })
                .collect();
            let c: Vec<f64> = pairs
                .iter()
                .map(|&p| p as f64 / total_pairs as f64)
                .collect();
            CorrelationCurve {
                m,
                slope: local_slopes(&eps, &c),
                eps: eps.clone(),
                pairs,
                c,
            }
        })
        .collect();
    Ok(CorrelationSums {
        curves,
        total_pairs,
        vectors,
    })
}

/// Local slopes `d ln C / d ln ε` of a correlation sum: centred differences
/// `(ln C_{l+1} − ln C_{l−1}) / (ln ε_{l+1} − ln ε_{l−1})` inside, one-sided at the ends.
///
/// # Formula
/// The centred difference is the mean of TISEAN `d2`'s one-sided slopes
/// `ln(C_l/C_{l−1})/ln f` on both sides of ε_l. `None` where a needed C is 0.
pub fn local_slopes(eps: &[f64], c: &[f64]) -> Vec<Option<f64>> {
    let n = eps.len().min(c.len());
    (0..n)
        .map(|l| {
            let (a, b) = match (l, n) {
                (_, 0 | 1) => return None,
                (0, _) => (0, 1),
                (l, n) if l == n - 1 => (l - 1, l),
                (l, _) => (l - 1, l + 1),
            };
            (c[a] > 0.0 && c[b] > 0.0 && eps[b] > eps[a])
                .then(|| (c[b] / c[a]).ln() / (eps[b] / eps[a]).ln())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bin_table_is_exact() {
        let o = D2Options {
            eps_min: Some(1e-3),
            eps_max: Some(2.0),
            eps_count: 37,
            ..D2Options::default()
        };
        let eps = radii(&o, 5.0).unwrap();
        let t = BinTable::new(&eps);
        let mut d = 0.0;
        while d <= 2.0 {
            let want = eps.partition_point(|&e| e < d);
            assert_eq!(t.bin(d), want, "d = {d}");
            d += 1.3e-4;
        }
        for &e in &eps {
            assert_eq!(t.bin(e), eps.partition_point(|&x| x < e));
        }
    }

    #[test]
    fn option_validation() {
        let x: Vec<f64> = (0..100).map(|i| (i as f64 * 0.37).sin()).collect();
        let bad = |o: D2Options| correlation_sum(&x, &o).is_err();
        assert!(bad(D2Options {
            m_min: 0,
            ..D2Options::default()
        }));
        assert!(bad(D2Options {
            eps_count: 1,
            ..D2Options::default()
        }));
        assert!(bad(D2Options {
            eps_min: Some(2.0),
            eps_max: Some(1.0),
            ..D2Options::default()
        }));
        assert!(bad(D2Options {
            theiler: 200,
            ..D2Options::default()
        }));
        assert!(!bad(D2Options::default()));
    }

    #[test]
    fn local_slopes_of_a_power_law() {
        let eps: Vec<f64> = (0..10).map(|l| 0.01 * 1.5f64.powi(l)).collect();
        let c: Vec<f64> = eps.iter().map(|e| e.powf(1.7)).collect();
        for s in local_slopes(&eps, &c) {
            assert!((s.unwrap() - 1.7).abs() < 1e-12);
        }
    }
}
