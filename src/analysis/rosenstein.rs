//! Rosenstein's maximal Lyapunov exponent (Rosenstein, Collins & De Luca 1993), with TISEAN
//! 3.0.1 `lyap_r`'s definition: the mean logarithm of the distance between each point and its
//! nearest neighbour (outside the Theiler window), followed forward in time.
//!
//! # Algorithm
//! A kd-tree (`tree.rs`: squared Euclidean, median splits, leaves of 16) over the candidate
//! delay vectors (read from the series, not copied) gives each reference's exact nearest
//! neighbour outside the Theiler window in one pruned descent that skips the window's points
//! (TISEAN grows a box radius from `-r` by 10 % per round until every reference has a
//! neighbour: the same neighbour). The references are queried in the tree's point order, so
//! that consecutive queries share their leaves in cache, in parallel over fixed blocks (each
//! answer is exact, so neither order nor thread count changes it). The tree is built in
//! parallel (the halves of a split of more than 16 384 points at once: the same tree as a
//! serial build's, its shape depending on N only). The pairs are then followed in time order,
//! in fixed chunks in parallel summed in chunk order (thread-count independent); within a
//! chunk the logarithms of the squared distances are summed as running products (mantissa
//! and binary exponent), one logarithm per Δn and chunk. Cost O(N log N + N · steps · m).

use rayon::prelude::*;

use crate::analysis::scaling_region::{fit_scaling_region, ScalingOptions, SlopeFit};
use crate::analysis::{require_positive, rescale_unit, validate_series};
use crate::error::AnalysisError;

/// Largest embedding dimension supported.
pub const MAX_DIMENSION: usize = 10;

/// References per parallel work unit.
const CHUNK: usize = 1024;

mod tree;
use tree::{Delays, ExclusionTree};

/// Options of [`rosenstein`]. `Default` gives TISEAN `lyap_r`'s defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RosensteinOptions {
    /// Embedding dimension m ≤ 10 (TISEAN `-m`). Default 2.
    pub m: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub tau: usize,
    /// Theiler window w in samples: neighbours need `|n − j| > w` (TISEAN `-t`). Default 0;
    /// Rosenstein et al. use the mean period.
    pub theiler: usize,
    /// Initial neighbourhood size in data units (TISEAN `-r`); `None` = (max − min)/1000.
    /// It does not change which neighbour is found, except for references that have an exact
    /// duplicate outside the Theiler window: TISEAN keeps those only if their nearest
    /// non-duplicate neighbour lies within this radius, and so does pdamp.
    pub eps0: Option<f64>,
    /// Largest Δn in samples (TISEAN `-s`). Default 10.
    pub steps: usize,
}

impl Default for RosensteinOptions {
    fn default() -> Self {
        Self {
            m: 2,
            tau: 1,
            theiler: 0,
            eps0: None,
            steps: 10,
        }
    }
}

/// Result of [`rosenstein`].
#[derive(Debug, Clone, PartialEq)]
pub struct RosensteinResult {
    /// `s[Δn]` = mean ln distance at Δn (rescaled units: add `ln(range)` for data units),
    /// Δn = 0..=steps; `None` where no pair had a distance > 0 (TISEAN's column 2).
    pub s: Vec<Option<f64>>,
    /// Number of pairs averaged at each Δn.
    pub count: Vec<u64>,
    /// `max − min` of the series (data units).
    pub range: f64,
    /// Number of references that found a neighbour.
    pub references: usize,
}

/// Rosenstein's divergence curve S(Δn): the mean log distance of nearest-neighbour pairs
/// followed Δn steps forward.
///
/// # Formula
/// Series rescaled to [0, 1]; `y_n = (s_n, s_{n+τ}, …, s_{n+(m−1)τ})`; candidates
/// `j < N − (m−1)τ − steps`, references `n < N − (m−1)τ − steps − w`. For each reference the
/// nearest candidate `j(n)` in the Euclidean norm with `|n − j| > w` and distance > 0;
/// `S(Δn) = mean_n ln ‖y_{n+Δn} − y_{j(n)+Δn}‖` over the pairs with a non-zero distance at Δn
/// (Rosenstein et al. 1993 eq. (10) with TISEAN `lyap_r`'s conventions). The slope of the
/// linear part of S versus Δn is λ₁ per sample.
///
/// # Units
/// S in rescaled log units (natural log); Δn, τ, w in samples; `eps0` in data units. Divide
/// the slope by the sampling interval (s) for s⁻¹.
///
/// # Parameters
/// [`RosensteinOptions`]: TISEAN `lyap_r` defaults `m = 2`, `τ = 1`, `w = 0`,
/// `eps0 = range/1000`, `steps = 10`.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `m = 0` or > 10, `τ = 0`, a non-positive or
/// non-finite `eps0`; [`AnalysisError::TooShort`] when fewer than 2 references remain
/// (`N − (m−1)τ − steps ≤ w + 2`); [`AnalysisError::NonFinite`], [`AnalysisError::Constant`];
/// [`AnalysisError::NoResult`] if no reference has a neighbour outside the Theiler window.
///
/// # Pitfalls
/// - With `w = 0` a flow's nearest neighbour is the adjacent sample: S then grows only
///   with the flow's local stretching along the trajectory. Use a Theiler window of about
///   one mean period.
/// - S rises linearly only between the neighbours' initial alignment and saturation at the
///   attractor size: fit there ([`rosenstein_exponent`] uses
///   [`crate::analysis::scaling_region::fit_scaling_region`]). With few steps the
///   linear part may be too short (< 6 points).
/// - Noise adds a jump at small Δn and lowers the slope.
///
/// # References
/// M. T. Rosenstein, J. J. Collins and C. J. De Luca, "A practical method for calculating
/// largest Lyapunov exponents from small data sets", Physica D 65, 117–134 (1993).
/// doi:10.1016/0167-2789(93)90009-P.
/// R. Hegger, H. Kantz, T. Schreiber, Chaos 9, 413–435 (1999). doi:10.1063/1.166424
///
/// # Example
/// ```
/// use pdamp::analysis::rosenstein::{rosenstein, RosensteinOptions};
/// use pdamp::systems::logistic::logistic_series;
/// let x = logistic_series(4.0, 0.3, 5000, 100);
/// let r = rosenstein(&x, &RosensteinOptions { m: 1, steps: 8, ..Default::default() }).unwrap();
/// let slope = (r.s[5].unwrap() - r.s[1].unwrap()) / 4.0;
/// assert!((slope - 2f64.ln()).abs() < 0.1); // λ = ln 2 per iteration
/// ```
pub fn rosenstein(x: &[f64], opts: &RosensteinOptions) -> Result<RosensteinResult, AnalysisError> {
    require_positive("m", opts.m)?;
    require_positive("tau", opts.tau)?;
    if opts.m > MAX_DIMENSION {
        return Err(AnalysisError::bad(
            "m",
            opts.m,
            format!("at most {MAX_DIMENSION} dimensions are supported"),
        ));
    }
    if let Some(e) = opts.eps0 {
        if !(e.is_finite() && e > 0.0) {
            return Err(AnalysisError::bad(
                "eps0",
                e,
                "the initial neighbourhood size must be a positive number in data units",
            ));
        }
    }
    validate_series(x, 2, "Rosenstein's Lyapunov estimate")?;
    crate::analysis::reject_monotonic(x)?;
    let span = (opts.m - 1) * opts.tau + opts.steps;
    if x.len() < span + opts.theiler + 3 {
        return Err(AnalysisError::TooShort(format!(
            "Rosenstein with m = {}, tau = {}, steps = {}, Theiler window {} needs at least {} \
             samples, the series has {}",
            opts.m,
            opts.tau,
            opts.steps,
            opts.theiler,
            span + opts.theiler + 3,
            x.len()
        )));
    }
    let rescaled = rescale_unit(x)?;
    let eps0 = opts.eps0.map_or(1e-3, |e| e / rescaled.range);
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match opts.m {
                $($k => run::<$k>(&rescaled.values, opts, eps0)?,)*
                _ => unreachable!("m checked above"),
            }
        };
    }
    let (sum, count, references) = dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10);
    if references == 0 {
        return Err(AnalysisError::NoResult(format!(
            "no reference point has a neighbour outside the Theiler window {}",
            opts.theiler
        )));
    }
    let s = sum
        .iter()
        .zip(&count)
        .map(|(&v, &c)| (c > 0).then(|| v / c as f64))
        .collect();
    Ok(RosensteinResult {
        s,
        count,
        range: rescaled.range,
        references,
    })
}

type Sums = (Vec<f64>, Vec<u64>, usize);

fn run<const K: usize>(s: &[f64], o: &RosensteinOptions, eps0: f64) -> Result<Sums, AnalysisError> {
    let tau = o.tau;
    let n_cand = s.len() - (K - 1) * tau - o.steps;
    let n_ref = n_cand - o.theiler;
    let pts = Delays::<K> {
        s,
        tau,
        len: n_cand,
    };
    let nearest = ExclusionTree::new(&pts).all_nearest(&pts, n_ref, o.theiler);
    let len = o.steps + 1;
    let span_k = len + (K - 1) * tau;
    let eps0_2 = eps0 * eps0;
    let parts: Vec<Sums> = (0..n_ref.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            // per chunk: Σ ln d² as running products (mantissa, binary exponent) with one
            // logarithm per Δn at the end; squared distances below PROD_LO (never in practice:
            // 2^-100 of the squared range) take their logarithm at once
            let mut prod = vec![1.0f64; len];
            let mut exp2 = vec![0i64; len];
            let mut tiny = vec![0.0f64; len];
            let mut count = vec![0u64; len];
            let mut d2s = vec![0.0f64; len];
            let mut e2s = vec![0.0f64; span_k];
            let mut since = 0u32;
            let mut refs = 0usize;
            let mut prev: Option<(usize, usize)> = None;
            for (n, found) in nearest
                .iter()
                .enumerate()
                .take(((c + 1) * CHUNK).min(n_ref))
                .skip(c * CHUNK)
            {
                if found.j == u32::MAX {
                    continue;
                }
                let (j, d2, duplicate) = (found.j as usize, found.d2, found.duplicate);
                // TISEAN: a reference with an exact duplicate is done in the first round
                // (radius eps0) and keeps a neighbour only if one lies within eps0
                if duplicate && d2 > eps0_2 {
                    continue;
                }
                refs += 1;
                // squared distances of the pair at every Δn (contiguous in Δn), each summed in
                // coordinate order. When the pair is the previous pair one step on (a flow's
                // neighbours stay neighbours), its distances are the previous ones shifted by
                // one: the same sums, so only the last is new.
                if prev == Some((n.wrapping_sub(1), j.wrapping_sub(1))) {
                    d2s.copy_within(1.., 0);
                    let t = len - 1;
                    let mut d = 0.0;
                    for k in 0..K {
                        let e = s[n + t + k * tau] - s[j + t + k * tau];
                        d += e * e;
                    }
                    d2s[t] = d;
                } else {
                    // the squared differences of the samples once, then summed
                    let a = &s[n..n + span_k];
                    let b = &s[j..j + span_k];
                    for ((e, &u), &v) in e2s.iter_mut().zip(a).zip(b) {
                        let e1 = u - v;
                        *e = e1 * e1;
                    }
                    d2s.copy_from_slice(&e2s[..len]);
                    for k in 1..K {
                        for (d, &e) in d2s.iter_mut().zip(&e2s[k * tau..k * tau + len]) {
                            *d += e;
                        }
                    }
                }
                prev = Some((n, j));
                let mut rare = false;
                for ((p, &d), c) in prod.iter_mut().zip(&d2s).zip(count.iter_mut()) {
                    let ok = d >= PROD_LO;
                    *p *= if ok { d } else { 1.0 };
                    *c += u64::from(d > 0.0);
                    rare |= !ok;
                }
                if rare {
                    for (l, &d) in tiny.iter_mut().zip(&d2s) {
                        if d > 0.0 && d < PROD_LO {
                            *l += d.ln();
                        }
                    }
                }
                since += 1;
                if since == RENORM_EVERY {
                    since = 0;
                    renormalise(&mut prod, &mut exp2);
                }
            }
            let sum = prod
                .iter()
                .zip(&exp2)
                .zip(&tiny)
                .map(|((&p, &e), &l)| 0.5 * (p.ln() + e as f64 * std::f64::consts::LN_2 + l))
                .collect();
            (sum, count, refs)
        })
        .collect();
    let mut sum = vec![0.0; len];
    let mut count = vec![0u64; len];
    let mut refs = 0;
    for (a, b, r) in parts {
        for t in 0..len {
            sum[t] += a[t];
            count[t] += b[t];
        }
        refs += r;
    }
    Ok((sum, count, refs))
}

/// Smallest factor of a running product (2^-100); squared distances are at most m ≤ 10 in
/// rescaled units.
const PROD_LO: f64 = 7.888_609_052_210_118e-31;
/// Renormalise the products after this many factors: 8 factors in [2^-100, 10] times a
/// mantissa in [1, 2) stay inside 2^±808.
const RENORM_EVERY: u32 = 8;

/// Moves the binary exponents of `prod` into `exp2`, leaving mantissas in [1, 2).
fn renormalise(prod: &mut [f64], exp2: &mut [i64]) {
    const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;
    const ONE_BITS: u64 = 0x3ff0_0000_0000_0000;
    for (x, e) in prod.iter_mut().zip(exp2) {
        let b = x.to_bits();
        *e += ((b >> 52) & 0x7ff) as i64 - 1023;
        *x = f64::from_bits((b & MANTISSA) | ONE_BITS);
    }
}

/// λ₁ per sample from [`rosenstein`]'s curve: the slope of its linear region
/// ([`fit_scaling_region`]), with the curve.
///
/// # Formula
/// `λ₁ = dS/dΔn` over the longest window with R² ≥ `r2_min` whose first and last thirds have
/// equal slopes (see [`fit_scaling_region`]).
///
/// # Units
/// Per sample (natural log); divide by the sampling interval for s⁻¹.
///
/// # Errors
/// Those of [`rosenstein`]; [`AnalysisError::NoResult`] if the curve has fewer than 2 points.
///
/// # References
/// M. T. Rosenstein, J. J. Collins, C. J. De Luca, Physica D 65, 117–134 (1993).
/// doi:10.1016/0167-2789(93)90009-P
///
/// # Example
/// ```
/// use pdamp::analysis::rosenstein::{rosenstein_exponent, RosensteinOptions};
/// use pdamp::systems::henon::henon_x;
/// let o = RosensteinOptions { m: 2, steps: 12, ..Default::default() };
/// let (_, fit) = rosenstein_exponent(&henon_x(5000), &o, &Default::default()).unwrap();
/// assert!((fit.slope - 0.419).abs() < 0.042); // Hénon λ₁ = 0.419 per iteration
/// ```
pub fn rosenstein_exponent(
    x: &[f64],
    opts: &RosensteinOptions,
    scaling: &ScalingOptions,
) -> Result<(RosensteinResult, SlopeFit), AnalysisError> {
    let r = rosenstein(x, opts)?;
    let fit = fit_scaling_region(&r.s, scaling).ok_or_else(|| {
        AnalysisError::NoResult("the divergence curve has fewer than 2 points: raise steps".into())
    })?;
    Ok((r, fit))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn option_validation() {
        let x: Vec<f64> = (0..300).map(|i| (i as f64 * 0.37).sin()).collect();
        let bad = |o: RosensteinOptions| rosenstein(&x, &o).is_err();
        assert!(bad(RosensteinOptions {
            m: 0,
            ..Default::default()
        }));
        assert!(bad(RosensteinOptions {
            m: 11,
            ..Default::default()
        }));
        assert!(bad(RosensteinOptions {
            eps0: Some(-1.0),
            ..Default::default()
        }));
        assert!(bad(RosensteinOptions {
            steps: 400,
            ..Default::default()
        }));
        assert!(!bad(RosensteinOptions::default()));
    }
}
