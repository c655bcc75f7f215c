//! Kantz's maximal Lyapunov exponent from a scalar series (Kantz 1994; SPEC (4.1.7)), with
//! TISEAN 3.0.1 `lyap_k`'s definition available exactly (SPEC §8), plus an automatic finder
//! of the linear (scaling) region of S(Δn).
//!
//! # Algorithm (why it is fast)
//! Neighbours are found once per reference point, at the largest ε, with a kiddo 6 kd-tree
//! on the first two delay coordinates `(s_i, s_{i+τ})` (the ε-ball in m dimensions lies inside
//! the ε-disc of its first two coordinates); each candidate's squared distance is extended
//! coordinate by coordinate, which gives its distance in every dimension m at once (the
//! neighbours in dimension m are a subset of those in m − 1). Each pair's squared
//! coordinate differences `e_t = (s_{i+t} − s_{j+t})²` are computed once and reused for all
//! m (`‖y_{i+Δn} − y_{j+Δn}‖²_m = Σ_{k<m} e_{Δn+kτ}`) and all ε (a pair is summed into the
//! bin of the smallest ε that contains it, bins are then accumulated over increasing ε).
//! The logarithms are not taken per reference: within a chunk the per-reference sums are
//! multiplied into running products (mantissa + binary exponent), `Σ ln(a/c) = ln Π a − Σ ln c`,
//! one logarithm per (m, ε, Δn) and chunk; pairs at distance exactly 0 and sums outside
//! [2^-100, 2^100] take an exact direct path. The pair loops are contiguous and vectorise.
//! References are processed in fixed chunks in parallel (rayon) and combined in chunk order,
//! so results do not depend on the thread count.
//!
//! Cost: the kd-tree search is O(N log N); the accumulation is O(pairs · steps · m), and at a
//! fixed ε the number of neighbour pairs grows as N² (each reference has ∝ N neighbours), as
//! in TISEAN's `lyap_k`.

use crate::analysis::{
    reject_monotonic, require_positive, rescale_unit, validate_radii, validate_series,
};
use crate::error::AnalysisError;

pub use crate::analysis::scaling_region::{fit_scaling_region, ScalingOptions, SlopeFit};

mod arith;
mod buffers;
mod kernel;
mod options;
mod rms;

pub use options::{KantzCurve, KantzDefinition, KantzOptions, KantzResult, MAX_DIMENSION};

use buffers::Job;
use kernel::{assemble, run};

/// Kantz's stretching curves S(ε, m, Δn) for every m in `m_min..=m_max` and every ε.
///
/// # Formula
/// (4.1.7): `S(Δn) = (1/|R|) Σ_{n∈R} ln( (1/|U_n|) Σ_{n'∈U_n} dist(y_{n+Δn}, y_{n'+Δn}) )`,
/// with `y_n = (s_n, s_{n+τ}, …, s_{n+(m−1)τ})` of the series rescaled to [0, 1], `U_n` all
/// `n'` with Euclidean `‖y_n − y_{n'}‖ ≤ ε` and `|n − n'| > w`, and R the references that have
/// neighbours. Pairs at distance exactly 0 at step Δn are skipped at that step. `dist` is the
/// Euclidean distance ([`KantzDefinition::MeanDistance`]) or, for
/// [`KantzDefinition::TiseanRms`], the average is of squared distances and the log is halved
/// (log of the RMS distance) — TISEAN `lyap_k` number for number. References and neighbour
/// candidates are the indices `0 .. N − steps − (m_max−1)τ` (references: the first n of them).
///
/// # Units
/// ε in data units; S in rescaled units (natural log); Δn, τ, w in samples. The slope of S vs
/// Δn is the exponent per sample (divide by the sampling interval for per second).
///
/// # Parameters
/// [`KantzOptions`] (pdamp: m = 2, τ = 1, ε = range/1000 … range/100 in 5 steps, 50 steps,
/// w = τ, mean of distances; [`KantzOptions::tisean`]: w = 0, RMS).
///
/// # Errors
/// [`AnalysisError::BadParameter`] for m_min = 0, m_min > m_max, m_max > 16, τ = 0,
/// eps_count = 0, non-positive or non-finite ε, `references = Some(0)`;
/// [`AnalysisError::TooShort`] when `steps + (m_max−1)τ ≥ N`; [`AnalysisError::NonFinite`],
/// [`AnalysisError::Constant`], [`AnalysisError::Monotonic`] (a time column).
///
/// # Pitfalls
/// S grows linearly only between the initial alignment transient and saturation at the
/// attractor size: fit the slope there ([`fit_scaling_region`]). Too small ε leaves most
/// references without neighbours (see `count`); noise makes S jump at Δn = 0 and flattens it.
///
/// # References
/// H. Kantz, "A robust method to estimate the maximal Lyapunov exponent of a time series",
/// Phys. Lett. A 185, 77–87 (1994). doi:10.1016/0375-9601(94)90991-1.
/// R. Hegger, H. Kantz, T. Schreiber, Chaos 9, 413–435 (1999). doi:10.1063/1.166424
///
/// # Example
/// ```
/// use pdamp::analysis::kantz::{kantz, KantzOptions};
/// use pdamp::systems::logistic::logistic_series;
/// let x = logistic_series(4.0, 0.3, 5000, 100);
/// let r = kantz(&x, &KantzOptions { m_min: 1, m_max: 1, steps: 10, ..KantzOptions::default() }).unwrap();
/// let s = &r.curves[0].s;
/// // S grows by about ln 2 per step while neighbours separate
/// let slope = (s[4].unwrap() - s[1].unwrap()) / 3.0;
/// assert!((slope - 2f64.ln()).abs() < 0.1);
/// ```
pub fn kantz(x: &[f64], opts: &KantzOptions) -> Result<KantzResult, AnalysisError> {
    validate_options(opts)?;
    validate_series(x, 2, "Kantz's Lyapunov estimate")?;
    let span = opts.steps + (opts.m_max - 1) * opts.tau;
    if span >= x.len() {
        return Err(AnalysisError::TooShort(format!(
            "steps + (m_max−1)·tau = {span} must be smaller than the series length {}",
            x.len()
        )));
    }
    reject_monotonic(x)?;
    let rescaled = rescale_unit(x)?;
    let eps = radii(opts, rescaled.range)?;
    let n_cand = x.len() - span;
    let n_ref = opts.references.unwrap_or(usize::MAX).min(n_cand);
    let job = Job {
        s: &rescaled.values,
        opts,
        eps2: eps.iter().map(|e| e * e).collect(),
        n_cand,
        n_ref,
        theiler: opts.theiler_window(),
        distinct: all_differences_square_nonzero(&rescaled.values),
    };
    let totals = if opts.m_min == 1 {
        run::<1>(&job)?
    } else {
        run::<2>(&job)?
    };
    Ok(assemble(&job, &eps, rescaled.range, totals))
}

fn validate_options(o: &KantzOptions) -> Result<(), AnalysisError> {
    crate::analysis::validate_embedding_range(o.m_min, o.m_max, o.tau, MAX_DIMENSION)?;
    require_positive("eps_count", o.eps_count)?;
    if o.references == Some(0) {
        return Err(AnalysisError::bad(
            "references",
            0,
            "need at least 1 reference point (omit it for all)",
        ));
    }
    validate_radii(o.eps_min, o.eps_max)
}

/// Whether `(a − b)² > 0` for every two samples `a`, `b` at different indices: all values
/// distinct and the smallest gap between sorted values does not square to 0.
fn all_differences_square_nonzero(s: &[f64]) -> bool {
    let mut v = s.to_vec();
    v.sort_unstable_by(f64::total_cmp);
    v.windows(2).all(|w| {
        let d = w[1] - w[0];
        d * d > 0.0
    })
}

/// Radii in rescaled units, TISEAN's way: ε_l = ε_min·f^l, f = (ε_max/ε_min)^{1/(count−1)};
/// a single radius ε_min if ε_min ≥ ε_max.
fn radii(o: &KantzOptions, range: f64) -> Result<Vec<f64>, AnalysisError> {
    let lo = o.eps_min.map_or(1e-3, |e| e / range);
    let hi = o.eps_max.map_or(1e-2, |e| e / range);
    if lo >= hi || o.eps_count == 1 {
        return Ok(vec![lo]);
    }
    let fak = (hi / lo).powf(1.0 / (o.eps_count - 1) as f64);
    Ok((0..o.eps_count).map(|l| lo * fak.powf(l as f64)).collect())
}

/// The maximal Lyapunov exponent from a series: the median slope of the linear regions of
/// all Kantz curves.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LyapunovEstimate {
    /// Exponent per sample (natural log). Divide by the sampling interval for per second.
    pub per_sample: f64,
    /// Fit of the curve whose slope is the median (its window, R², m and ε below).
    pub fit: SlopeFit,
    /// Embedding dimension of that curve.
    pub m: usize,
    /// Radius of that curve (data units).
    pub eps: f64,
    /// Number of curves with a linear region that entered the median.
    pub curves_used: usize,
    /// Spread of the slopes that entered the median (max − min), per sample.
    pub spread: f64,
}

/// Maximal Lyapunov exponent per sample: runs [`kantz`], fits every curve's linear region
/// ([`fit_scaling_region`]) and returns the median slope of the curves with a linear region
/// (if none has one, the median of the fallback whole-curve fits, flagged `linear = false`).
///
/// # Formula
/// (4.1.7) and the slope of S vs Δn in its linear region.
///
/// # Units
/// Per sample (natural log); divide by the sampling interval (s) for s⁻¹.
///
/// # Errors
/// Those of [`kantz`]; [`AnalysisError::NoResult`] if no curve has two defined points (no
/// neighbours at any ε: raise ε).
///
/// # References
/// H. Kantz, Phys. Lett. A 185, 77–87 (1994). doi:10.1016/0375-9601(94)90991-1
///
/// # Example
/// ```
/// use pdamp::analysis::kantz::{estimate_max_lyapunov, KantzOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(5000);
/// let o = KantzOptions { m_min: 2, m_max: 2, steps: 12, ..KantzOptions::default() };
/// let est = estimate_max_lyapunov(&x, &o, &Default::default()).unwrap();
/// assert!((est.per_sample - 0.419).abs() < 0.08);
/// ```
pub fn estimate_max_lyapunov(
    x: &[f64],
    opts: &KantzOptions,
    scaling: &ScalingOptions,
) -> Result<LyapunovEstimate, AnalysisError> {
    let result = kantz(x, opts)?;
    estimate_from_curves(&result, scaling)
}

/// The median-slope estimate of [`estimate_max_lyapunov`] from already computed curves.
///
/// # Errors
/// [`AnalysisError::NoResult`] if no curve has two defined points.
pub fn estimate_from_curves(
    result: &KantzResult,
    scaling: &ScalingOptions,
) -> Result<LyapunovEstimate, AnalysisError> {
    let fits: Vec<(usize, f64, SlopeFit)> = result
        .curves
        .iter()
        .filter_map(|c| fit_scaling_region(&c.s, scaling).map(|f| (c.m, c.eps, f)))
        .collect();
    if fits.is_empty() {
        return Err(AnalysisError::NoResult(
            "no Kantz curve has neighbours: raise eps_max (or eps_min) or use a longer series"
                .into(),
        ));
    }
    let linear: Vec<&(usize, f64, SlopeFit)> = fits.iter().filter(|f| f.2.linear).collect();
    let mut pool: Vec<&(usize, f64, SlopeFit)> = if linear.is_empty() {
        fits.iter().collect()
    } else {
        linear
    };
    pool.sort_by(|a, b| a.2.slope.total_cmp(&b.2.slope));
    let (m, eps, fit) = *pool[(pool.len() - 1) / 2];
    Ok(LyapunovEstimate {
        per_sample: fit.slope,
        fit,
        m,
        eps,
        curves_used: pool.len(),
        spread: pool[pool.len() - 1].2.slope - pool[0].2.slope,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radii_follow_tisean() {
        let o = KantzOptions {
            eps_min: Some(1.0),
            eps_max: Some(8.0),
            eps_count: 4,
            ..KantzOptions::default()
        };
        let r = radii(&o, 2.0).unwrap();
        assert_eq!(r.len(), 4);
        assert!((r[0] - 0.5).abs() < 1e-15 && (r[3] - 4.0).abs() < 1e-12);
        let single = KantzOptions {
            eps_min: Some(3.0),
            eps_max: Some(1.0),
            ..KantzOptions::default()
        };
        assert_eq!(radii(&single, 1.0).unwrap(), vec![3.0]);
    }

    #[test]
    fn fit_finds_linear_part_of_a_ramp_then_plateau() {
        let s: Vec<Option<f64>> = (0..40)
            .map(|t| Some(if t < 20 { 0.5 * t as f64 } else { 10.0 }))
            .collect();
        let f = fit_scaling_region(&s, &ScalingOptions::default()).unwrap();
        assert!(f.linear);
        assert!((f.slope - 0.5).abs() < 0.02, "{f:?}");
        assert!(f.end <= 21);
    }

    #[test]
    fn option_validation() {
        let x: Vec<f64> = (0..200).map(|i| (i as f64 * 0.37).sin()).collect();
        let bad = |o: KantzOptions| kantz(&x, &o).is_err();
        assert!(bad(KantzOptions {
            m_min: 0,
            ..KantzOptions::default()
        }));
        assert!(bad(KantzOptions {
            m_min: 3,
            m_max: 2,
            ..KantzOptions::default()
        }));
        assert!(bad(KantzOptions {
            eps_min: Some(-1.0),
            ..KantzOptions::default()
        }));
        assert!(bad(KantzOptions {
            steps: 500,
            ..KantzOptions::default()
        }));
        assert!(bad(KantzOptions {
            references: Some(0),
            ..KantzOptions::default()
        }));
        assert!(!bad(KantzOptions::default()));
    }
}
