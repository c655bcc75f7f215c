//! Cao's method for the minimum embedding dimension (Cao 1997): E1(m), E2(m) and the
//! saturation dimension. DynamicalSystems.jl's `delay_afnn` ("averaged false nearest
//! neighbours") computes the same E1.
//!
//! # Algorithm
//! For every dimension m a kiddo 6 kd-tree in the maximum norm (`Chebyshev`) gives each
//! point's nearest neighbour; the Theiler window is applied by asking for more neighbours
//! (4, 16, 64, … nearest) until one lies outside it. References are processed in fixed
//! chunks in parallel (rayon) and summed in chunk order (thread-count independent).
//! Cost O(m_max · N log N).

use std::num::NonZero;

use kiddo::{Chebyshev, ImmutableKdTree};
use rayon::prelude::*;

use crate::analysis::{outside_theiler_window, require_positive, validate_series};
use crate::error::AnalysisError;

/// Largest embedding dimension for which E1 and E2 are reported (E needs m_max + 1 ≤ 12).
pub const MAX_DIMENSION: usize = 11;

/// References per parallel work unit.
const CHUNK: usize = 1024;

/// Options of [`cao`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaoOptions {
    /// Largest dimension m for E1(m), E2(m), ≤ 11 (E is computed up to m_max + 1). Default 8.
    pub m_max: usize,
    /// Delay τ in samples. Default 1 (use the first minimum of the mutual information).
    pub tau: usize,
    /// Theiler window w in samples: neighbours need `|i − n| > w`. Default 0 (Cao 1997 has
    /// none; DynamicalSystems.jl's `delay_afnn` default `w = 1`). Use ≥ τ for flows.
    pub theiler: usize,
    /// E1 counts as saturated from the first m with `E1(m) ≥ saturation` and
    /// `|E1(m+1) − E1(m)| ≤ flatness` (E1 near its plateau at 1, and flat). Default 0.85.
    pub saturation: f64,
    /// Largest change of E1 to the next dimension on the plateau. Default 0.1.
    pub flatness: f64,
}

impl Default for CaoOptions {
    fn default() -> Self {
        Self {
            m_max: 8,
            tau: 1,
            theiler: 0,
            saturation: 0.85,
            flatness: 0.1,
        }
    }
}

/// Result of [`cao`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CaoResult {
    /// Dimensions m = 1..=m_max.
    pub m: Vec<usize>,
    /// E(m) = mean of a(i, m), m = 1..=m_max+1 (one longer than `m`).
    pub e: Vec<f64>,
    /// E*(m) = mean of |x_{i+mτ} − x_{n(i,m)+mτ}|, m = 1..=m_max+1 (data units).
    pub e_star: Vec<f64>,
    /// E1(m) = E(m+1)/E(m) for m = 1..=m_max.
    pub e1: Vec<f64>,
    /// E2(m) = E*(m+1)/E*(m) for m = 1..=m_max.
    pub e2: Vec<f64>,
    /// The minimum embedding dimension: the first m where E1 is saturated (see
    /// [`CaoOptions::saturation`]); `None` if E1 never saturates up to m_max (noise, or too
    /// small m_max).
    pub dimension: Option<usize>,
}

/// Cao's E1(m) and E2(m) for m = 1..=m_max and the saturation (minimum embedding) dimension.
///
/// # Formula
/// Cao (1997) eqs. (1)–(5), maximum norm, delay vectors `y_i(m) = (x_i, x_{i+τ}, …,
/// x_{i+(m−1)τ})`, `i = 0 .. N − mτ`; `n(i, m)` the nearest neighbour of `y_i(m)` with
/// `|i − n| > w` and distance > 0:
/// `a(i, m) = ‖y_i(m+1) − y_n(m+1)‖ / ‖y_i(m) − y_n(m)‖`, `E(m) = mean_i a(i, m)`,
/// `E1(m) = E(m+1)/E(m)`; `E*(m) = mean_i |x_{i+mτ} − x_{n+mτ}|`, `E2(m) = E*(m+1)/E*(m)`.
/// E1 stops changing (→ 1) from the minimum embedding dimension on (Cao: "d0 + 1" where E1
/// is constant for m > d0); E2 = 1 for all m distinguishes random from deterministic data.
///
/// # Units
/// E and E1, E2 are dimensionless; E* in data units; τ and w in samples.
///
/// # Parameters
/// [`CaoOptions`]: `m_max = 8`, `τ = 1`, `w = 0`; saturation: `E1(m) ≥ 0.85` and
/// `|E1(m+1) − E1(m)| ≤ 0.1` (a heuristic reading of Cao's "E1 stops changing"; with
/// 10⁴ points E1 of the Lorenz x series is 0.30, 0.90, 0.95 at m = 2, 3, 4, of Hénon 0.95,
/// 0.97 at m = 2, 3; DynamicalSystems.jl applies a slope threshold 0.05 to E1 alone).
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `m_max = 0` or > 11, `τ = 0`, a saturation level
/// outside (0, 1), a flatness ≤ 0; [`AnalysisError::TooShort`] if fewer than `w + 10` vectors of dimension
/// m_max + 1 exist; [`AnalysisError::NonFinite`]; [`AnalysisError::Constant`];
/// [`AnalysisError::NoResult`] if some dimension has no admissible neighbour at all (all
/// candidates inside the Theiler window or duplicates).
///
/// # Pitfalls
/// - Without a Theiler window a finely sampled flow's nearest neighbour is the next sample,
///   whose ratio a(i, m) ≈ 1 in every dimension: E1 ≈ 1 from m = 1 (false saturation).
/// - For noise E1 keeps creeping towards 1 slowly as m grows (finite data); E2 ≈ 1 is the
///   test for randomness, not E1.
/// - Quantised data have many exact duplicates; they are skipped (distance 0), as Cao says.
///
/// # References
/// L. Cao, "Practical method for determining the minimum embedding dimension of a scalar
/// time series", Physica D 110, 43–50 (1997). doi:10.1016/S0167-2789(97)00118-8.
///
/// # Example
/// ```
/// use pdamp::analysis::cao::{cao, CaoOptions};
/// use pdamp::systems::henon::henon_x;
/// let r = cao(&henon_x(3000), &CaoOptions { m_max: 4, ..CaoOptions::default() }).unwrap();
/// assert_eq!(r.dimension, Some(2)); // the Hénon map needs 2 delay coordinates
/// ```
pub fn cao(x: &[f64], opts: &CaoOptions) -> Result<CaoResult, AnalysisError> {
    require_positive("m_max", opts.m_max)?;
    require_positive("tau", opts.tau)?;
    if opts.m_max > MAX_DIMENSION {
        return Err(AnalysisError::bad(
            "m_max",
            opts.m_max,
            format!("at most {MAX_DIMENSION} (E is needed up to m_max + 1)"),
        ));
    }
    if !(opts.saturation > 0.0 && opts.saturation < 1.0) {
        return Err(AnalysisError::bad(
            "saturation",
            opts.saturation,
            "must lie in (0, 1), e.g. 0.85",
        ));
    }
    if !(opts.flatness.is_finite() && opts.flatness > 0.0) {
        return Err(AnalysisError::bad(
            "flatness",
            opts.flatness,
            "must be a positive number, e.g. 0.1",
        ));
    }
    let need = (opts.m_max + 1) * opts.tau + opts.theiler + 10;
    validate_series(x, need, "Cao's method")?;
    crate::analysis::reject_monotonic(x)?;
    let mut e = Vec::with_capacity(opts.m_max + 1);
    let mut e_star = Vec::with_capacity(opts.m_max + 1);
    for m in 1..=opts.m_max + 1 {
        let (a, b) = dimension_sums(x, m, opts)?;
        e.push(a);
        e_star.push(b);
    }
    let ratio = |v: &[f64]| -> Vec<f64> { v.windows(2).map(|w| w[1] / w[0]).collect() };
    let e1 = ratio(&e);
    let e2 = ratio(&e_star);
    let dimension = saturation_dimension(&e1, opts.saturation, opts.flatness);
    Ok(CaoResult {
        m: (1..=opts.m_max).collect(),
        e,
        e_star,
        e1,
        e2,
        dimension,
    })
}

/// The first m (1-based) with `E1(m) ≥ level` and `|E1(m+1) − E1(m)| ≤ flatness` (the last
/// m cannot be confirmed, so it never counts).
pub fn saturation_dimension(e1: &[f64], level: f64, flatness: f64) -> Option<usize> {
    (0..e1.len().saturating_sub(1))
        .find(|&k| e1[k] >= level && (e1[k + 1] - e1[k]).abs() <= flatness)
        .map(|k| k + 1)
}

/// E(m) and E*(m) of one dimension.
fn dimension_sums(x: &[f64], m: usize, opts: &CaoOptions) -> Result<(f64, f64), AnalysisError> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match m {
                $($k => sums_k::<$k>(x, opts),)*
                _ => Err(AnalysisError::bad("m", m, format!("1..={}", MAX_DIMENSION + 1))),
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

fn sums_k<const K: usize>(x: &[f64], opts: &CaoOptions) -> Result<(f64, f64), AnalysisError> {
    let tau = opts.tau;
    let n = x.len() - K * tau;
    let pts: Vec<[f64; K]> = (0..n)
        .map(|i| std::array::from_fn(|k| x[i + k * tau]))
        .collect();
    let tree: ImmutableKdTree<f64, K> = ImmutableKdTree::new_from_slice(&pts)
        .map_err(|e| AnalysisError::NoResult(format!("kd-tree construction failed: {e:?}")))?;
    let w = opts.theiler;
    let parts: Vec<(f64, f64, usize)> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let (mut sa, mut sb, mut cnt) = (0.0, 0.0, 0usize);
            for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                if let Some((j, d)) = nearest(&tree, &pts, i, w) {
                    let ext = (x[i + K * tau] - x[j + K * tau]).abs();
                    sa += d.max(ext) / d;
                    sb += ext;
                    cnt += 1;
                }
            }
            (sa, sb, cnt)
        })
        .collect();
    let (mut sa, mut sb, mut cnt) = (0.0, 0.0, 0usize);
    for (a, b, c) in parts {
        sa += a;
        sb += b;
        cnt += c;
    }
    if cnt == 0 {
        return Err(AnalysisError::NoResult(format!(
            "Cao's method: no point has a neighbour outside the Theiler window {w} in dimension {K}"
        )));
    }
    Ok((sa / cnt as f64, sb / cnt as f64))
}

/// Nearest neighbour of point i (index, max-norm distance) with `|i − j| > w` and distance
/// > 0, asking the tree for 4, 16, 64, … neighbours until one qualifies.
pub(crate) fn nearest<const K: usize>(
    tree: &ImmutableKdTree<f64, K>,
    pts: &[[f64; K]],
    i: usize,
    w: usize,
) -> Option<(usize, f64)> {
    let n = pts.len();
    let mut k = 4usize.min(n);
    loop {
        let nb = tree
            .query(&pts[i])
            .nearest_n::<Chebyshev<f64>>(NonZero::new(k)?)
            .execute();
        let found = nb.iter().find(|r| {
            let j = r.item as usize;
            r.distance > 0.0 && outside_theiler_window(i, j, w)
        });
        if let Some(r) = found {
            // ties at the same distance: the smallest index (deterministic)
            let best = nb
                .iter()
                .filter(|q| {
                    q.distance == r.distance && outside_theiler_window(i, q.item as usize, w)
                })
                .map(|q| q.item as usize)
                .min()
                .unwrap_or(r.item as usize);
            return Some((best, r.distance));
        }
        if k >= n {
            return None;
        }
        k = (k * 4).min(n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saturation_rule() {
        assert_eq!(
            saturation_dimension(&[0.3, 0.7, 0.95, 0.97, 0.98], 0.85, 0.1),
            Some(3)
        );
        // a value above the level followed by a jump is not a plateau
        assert_eq!(
            saturation_dimension(&[0.3, 0.92, 0.7, 0.95, 0.96], 0.85, 0.1),
            Some(4)
        );
        // the last dimension alone cannot confirm saturation
        assert_eq!(saturation_dimension(&[0.3, 0.95], 0.85, 0.1), None);
    }

    #[test]
    fn option_validation() {
        let x: Vec<f64> = (0..300).map(|i| (i as f64 * 0.37).sin()).collect();
        let bad = |o: CaoOptions| cao(&x, &o).is_err();
        assert!(bad(CaoOptions {
            m_max: 0,
            ..CaoOptions::default()
        }));
        assert!(bad(CaoOptions {
            m_max: 12,
            ..CaoOptions::default()
        }));
        assert!(bad(CaoOptions {
            saturation: 1.0,
            ..CaoOptions::default()
        }));
        assert!(!bad(CaoOptions::default()));
    }
}
