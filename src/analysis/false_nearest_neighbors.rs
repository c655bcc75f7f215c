//! False nearest neighbours (Kennel, Brown & Abarbanel 1992; SPEC (4.1.4)), with TISEAN
//! 3.0.1 `false_nearest`'s definition (SPEC §8). Nearest neighbours come from a kiddo 6
//! kd-tree in the maximum (Chebyshev) norm, one tree per dimension.

use std::num::NonZero;

use kiddo::{Chebyshev, ImmutableKdTree};

use crate::analysis::{outside_theiler_window, require_positive, rescale_unit, standard_deviation};
use crate::error::AnalysisError;

/// Largest embedding dimension supported (kd-trees are built for a compile-time dimension).
pub const MAX_DIMENSION: usize = 12;

/// Options of [`false_nearest_neighbors`].
///
/// `Default` gives pdamp's defaults (Kennel's ratio 10, Theiler window = lag). TISEAN's
/// `false_nearest` defaults are [`FnnOptions::tisean`] (ratio 2, no Theiler window, `M = 5`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FnnOptions {
    /// Smallest embedding dimension tested, `m_min ≥ 1` (TISEAN `-m`). Default 1.
    pub m_min: usize,
    /// Largest embedding dimension tested, `m_max ≤ 12` (TISEAN `-M 1,m_max`). Default 6.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1 (use the MI lag).
    pub tau: usize,
    /// Escape ratio `R_t` (TISEAN `-f`). pdamp default 10 (Kennel et al. eq. 4's threshold);
    /// TISEAN's default is 2.
    pub ratio: f64,
    /// Theiler window `w` in samples: neighbours need `|n − j| > w` (TISEAN `-t`).
    /// pdamp default `None` = one lag τ; TISEAN's default is 0.
    pub theiler: Option<usize>,
}

impl Default for FnnOptions {
    fn default() -> Self {
        Self {
            m_min: 1,
            m_max: 6,
            tau: 1,
            ratio: 10.0,
            theiler: None,
        }
    }
}

impl FnnOptions {
    /// TISEAN `false_nearest`'s defaults: `-m1 -M1,5 -d1 -f2 -t0`.
    pub fn tisean() -> Self {
        Self {
            m_min: 1,
            m_max: 5,
            tau: 1,
            ratio: 2.0,
            theiler: Some(0),
        }
    }

    /// The Theiler window in effect (`theiler`, or τ when `None`).
    pub fn theiler_window(&self) -> usize {
        self.theiler.unwrap_or(self.tau)
    }
}

/// Result of the false-nearest-neighbour test in one dimension (one line of TISEAN's output).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FnnPoint {
    /// Embedding dimension m.
    pub m: usize,
    /// Fraction of false neighbours among the points with an accepted neighbour; `None` when
    /// no point had one (all nearest neighbours farther than σ/R_t).
    pub fraction: Option<f64>,
    /// Number of points with an accepted nearest neighbour (the denominator).
    pub accepted: usize,
    /// Number of false neighbours (the numerator).
    pub false_count: usize,
    /// Mean nearest-neighbour distance of the accepted points, data units (TISEAN column 3).
    pub mean_distance: f64,
    /// Root mean square of those distances, data units (TISEAN column 4).
    pub rms_distance: f64,
}

/// Fraction of false nearest neighbours for m = m_min..=m_max.
///
/// # Formula
/// (4.1.4), with TISEAN's conventions (SPEC §8): the series is rescaled to [0, 1]; vectors
/// `x_n = (s_n, s_{n+τ}, …, s_{n+(m−1)τ})` for `n < N − m_max·τ` (the same points for every m);
/// candidate neighbours `j < N − (m_max+1)·τ` (TISEAN's range). The nearest neighbour `j` of
/// `n` in the maximum norm with `|n − j| > w` and distance `δ > 0` (exact duplicates are
/// ignored) is accepted if `δ ≤ σ/R_t` (σ: standard deviation of the rescaled series); the
/// pair is false if `|s_{n+mτ} − s_{j+mτ}| / δ > R_t`. Fraction = false / accepted.
///
/// # Units
/// Input in any units; τ and w in samples; distances reported in data units.
///
/// # Parameters
/// [`FnnOptions`]: pdamp defaults `m = 1..=6`, `τ = 1`, `R_t = 10` (Kennel et al.), `w = τ`;
/// [`FnnOptions::tisean`] gives `R_t = 2`, `w = 0`, `m = 1..=5` as TISEAN `false_nearest`.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for `m_min = 0`, `m_min > m_max`, `m_max > 12`, `τ = 0`,
/// `R_t ≤ 0` or non-finite; [`AnalysisError::TooShort`] if `N ≤ (m_max+1)τ + 1`;
/// [`AnalysisError::NonFinite`]; [`AnalysisError::Constant`].
///
/// # Pitfalls
/// Noisy data never reach 0 % (noise fills every dimension). With `w = 0` and a finely
/// sampled flow the nearest neighbour is often the next sample on the same trajectory, which
/// is rarely false: use a Theiler window of at least τ. Ties (several neighbours at exactly the
/// same distance) may pick a different neighbour than TISEAN's box scan.
///
/// # References
/// M. B. Kennel, R. Brown and H. D. I. Abarbanel, "Determining embedding dimension for
/// phase-space reconstruction using a geometrical construction", Phys. Rev. A 45, 3403–3411
/// (1992). doi:10.1103/PhysRevA.45.3403.
/// R. Hegger, H. Kantz, T. Schreiber, Chaos 9, 413–435 (1999). doi:10.1063/1.166424
///
/// # Example
/// ```
/// use pdamp::analysis::{false_nearest_neighbors, FnnOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(3000);
/// let fnn = false_nearest_neighbors(&x, &FnnOptions { m_max: 3, ..FnnOptions::default() }).unwrap();
/// // Hénon needs 2 dimensions: m = 1 has many false neighbours, m = 2 almost none
/// assert!(fnn[0].fraction.unwrap() > 0.3);
/// assert!(fnn[1].fraction.unwrap() < 0.02);
/// ```
pub fn false_nearest_neighbors(
    x: &[f64],
    opts: &FnnOptions,
) -> Result<Vec<FnnPoint>, AnalysisError> {
    validate_options(opts)?;
    let needed = (opts.m_max + 1) * opts.tau + 2;
    crate::analysis::validate_series(x, needed, "false nearest neighbours")?;
    let rescaled = rescale_unit(x)?;
    let sigma = standard_deviation(&rescaled.values);
    let setup = Setup {
        s: &rescaled.values,
        tau: opts.tau,
        n_ref: x.len() - opts.m_max * opts.tau,
        n_cand: x.len() - (opts.m_max + 1) * opts.tau,
        theiler: opts.theiler_window(),
        ratio: opts.ratio,
        max_dist: sigma / opts.ratio,
        range: rescaled.range,
    };
    // nearest neighbour of each reference in the previous dimension: its distance in the next
    // dimension bounds the new nearest-neighbour distance from above (max norm), which
    // shrinks the kd-tree search radius
    let mut prev: Vec<u32> = vec![NONE; setup.n_ref];
    (opts.m_min..=opts.m_max)
        .map(|m| fnn_in_dimension(&setup, m, &mut prev))
        .collect()
}

/// The embedding dimension FNN suggests: the first m whose false fraction is ≤ `threshold`
/// (e.g. 0.01), or `None` if no tested dimension gets there.
pub fn suggested_dimension(points: &[FnnPoint], threshold: f64) -> Option<usize> {
    points
        .iter()
        .find(|p| p.fraction.is_some_and(|f| f <= threshold))
        .map(|p| p.m)
}

fn validate_options(opts: &FnnOptions) -> Result<(), AnalysisError> {
    require_positive("m_min", opts.m_min)?;
    require_positive("tau", opts.tau)?;
    if opts.m_max < opts.m_min {
        return Err(AnalysisError::bad(
            "m_max",
            opts.m_max,
            format!("must be ≥ m_min = {}", opts.m_min),
        ));
    }
    if opts.m_max > MAX_DIMENSION {
        return Err(AnalysisError::bad(
            "m_max",
            opts.m_max,
            format!("at most {MAX_DIMENSION} dimensions are supported"),
        ));
    }
    if !(opts.ratio.is_finite() && opts.ratio > 0.0) {
        return Err(AnalysisError::bad(
            "ratio",
            opts.ratio,
            "the escape ratio R_t must be a positive number (Kennel: 10, TISEAN: 2)",
        ));
    }
    Ok(())
}

/// Everything fixed across dimensions.
struct Setup<'a> {
    s: &'a [f64],
    tau: usize,
    n_ref: usize,
    n_cand: usize,
    theiler: usize,
    ratio: f64,
    max_dist: f64,
    range: f64,
}

/// Accumulated counts of one dimension.
#[derive(Default)]
struct Tally {
    accepted: usize,
    false_count: usize,
    sum_d: f64,
    sum_d2: f64,
}

impl Tally {
    fn add(&mut self, setup: &Setup, m: usize, n: usize, j: usize, dist: f64) {
        let t = m * setup.tau;
        let escape = (setup.s[n + t] - setup.s[j + t]).abs() / dist;
        self.accepted += 1;
        self.sum_d += dist;
        self.sum_d2 += dist * dist;
        if escape > setup.ratio {
            self.false_count += 1;
        }
    }

    fn finish(self, m: usize, range: f64) -> FnnPoint {
        let a = self.accepted as f64;
        let (fraction, mean, rms) = if self.accepted == 0 {
            (None, 0.0, 0.0)
        } else {
            (
                Some(self.false_count as f64 / a),
                self.sum_d / a * range,
                (self.sum_d2 / a).sqrt() * range,
            )
        };
        FnnPoint {
            m,
            fraction,
            accepted: self.accepted,
            false_count: self.false_count,
            mean_distance: mean,
            rms_distance: rms,
        }
    }
}

/// Marks "no neighbour found" in the previous-dimension list.
const NONE: u32 = u32::MAX;

fn fnn_in_dimension(setup: &Setup, m: usize, prev: &mut [u32]) -> Result<FnnPoint, AnalysisError> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match m {
                $($k => fnn_k::<$k>(setup, prev),)*
                _ => Err(AnalysisError::bad("m", m, format!("1..={MAX_DIMENSION}"))),
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

fn fnn_k<const K: usize>(setup: &Setup, prev: &mut [u32]) -> Result<FnnPoint, AnalysisError> {
    let tau = setup.tau;
    let s = setup.s;
    let point = |i: usize| -> [f64; K] { std::array::from_fn(|k| s[i + k * tau]) };
    let cands: Vec<[f64; K]> = (0..setup.n_cand).map(point).collect();
    let tree: ImmutableKdTree<f64, K> = ImmutableKdTree::new_from_slice(&cands)
        .map_err(|e| AnalysisError::NoResult(format!("kd-tree construction failed: {e:?}")))?;
    let mut tally = Tally::default();
    // Enough candidates to step over the Theiler window and the point itself.
    let k_start = (2 * setup.theiler + 2).min(setup.n_cand).max(1);
    for (n, prev_n) in prev.iter_mut().enumerate().take(setup.n_ref) {
        let q = point(n);
        let bound = match *prev_n {
            NONE => setup.max_dist,
            j => {
                let pj = point(j as usize);
                let d = q
                    .iter()
                    .zip(&pj)
                    .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
                d.min(setup.max_dist)
            }
        };
        *prev_n = NONE;
        if let Some((j, dist)) = nearest_valid(&tree, &q, n, setup, k_start, bound) {
            *prev_n = j as u32;
            if dist <= setup.max_dist {
                tally.add(setup, K, n, j, dist);
            }
        }
    }
    Ok(tally.finish(K, setup.range))
}

/// Nearest candidate j of reference n with |n − j| > w and distance in (0, bound]
/// (max norm). Grows k until one is found or all candidates within `bound` are exhausted.
fn nearest_valid<const K: usize>(
    tree: &ImmutableKdTree<f64, K>,
    q: &[f64; K],
    n: usize,
    setup: &Setup,
    k_start: usize,
    bound: f64,
) -> Option<(usize, f64)> {
    let mut k = k_start;
    loop {
        let found = tree
            .query(q)
            .nearest_n::<Chebyshev<f64>>(NonZero::new(k)?)
            .within(bound)
            .execute();
        let exhausted = found.len() < k;
        if let Some(hit) = found
            .iter()
            .find(|r| r.distance > 0.0 && outside_theiler_window(n, r.item as usize, setup.theiler))
        {
            return Some((hit.item as usize, hit.distance));
        }
        if exhausted || k >= setup.n_cand {
            return None;
        }
        k = (2 * k).min(setup.n_cand);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn option_validation() {
        let x: Vec<f64> = (0..100).map(|i| (i as f64 * 0.37).sin()).collect();
        let bad = |o: FnnOptions| false_nearest_neighbors(&x, &o).is_err();
        assert!(bad(FnnOptions {
            m_min: 0,
            ..FnnOptions::default()
        }));
        assert!(bad(FnnOptions {
            m_min: 4,
            m_max: 3,
            ..FnnOptions::default()
        }));
        assert!(bad(FnnOptions {
            m_max: 13,
            ..FnnOptions::default()
        }));
        assert!(bad(FnnOptions {
            ratio: 0.0,
            ..FnnOptions::default()
        }));
        assert!(bad(FnnOptions {
            tau: 0,
            ..FnnOptions::default()
        }));
        assert!(!bad(FnnOptions::default()));
    }

    #[test]
    fn suggested_dimension_picks_first_below_threshold() {
        let p = |m, f| FnnPoint {
            m,
            fraction: f,
            accepted: 1,
            false_count: 0,
            mean_distance: 0.0,
            rms_distance: 0.0,
        };
        let pts = [p(1, Some(0.5)), p(2, None), p(3, Some(0.0))];
        assert_eq!(suggested_dimension(&pts, 0.01), Some(3));
    }
}
