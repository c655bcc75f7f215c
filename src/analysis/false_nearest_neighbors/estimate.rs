//! The test itself ([`false_nearest_neighbors`], SPEC (4.1.4)): the fraction of false
//! neighbours per dimension m, dimension by dimension with the grids built alternately, and
//! the suggested dimension.

use std::sync::atomic::AtomicU32;

use super::count::fnn_in_dimension;
use super::options::{FnnOptions, FnnPoint, MAX_DIMENSION};
use super::search::{Grid, Setup, NONE};
use crate::analysis::{rescale_unit, standard_deviation};
use crate::error::AnalysisError;

/// Fraction of false nearest neighbours for m = m_min..=m_max.
///
/// # Formula
/// (4.1.4), with TISEAN's conventions (SPEC §8): the series is rescaled to [0, 1]; vectors
/// `x_n = (s_n, s_{n+k}, …, s_{n+(m−1)k})` for `n < N − m_max·τ` (the same points for every m);
/// candidate neighbours `j < N − (m_max+1)·τ` (TISEAN's range). The nearest neighbour `j` of
/// `n` in the maximum norm with `|n − j| > w` and distance `δ > 0` (exact duplicates are
/// ignored) is accepted if `δ ≤ σ/R_t` (σ: standard deviation of the rescaled series); the
/// pair is false if `|s_{n+mk} − s_{j+mk}| / δ > R_t`. Fraction = false / accepted. The
/// coordinate spacing is `k = τ` for [`FnnVectors::Delay`](super::FnnVectors::Delay) (pdamp's default) and `k = 1` for
/// [`FnnVectors::TiseanUnivariate`](super::FnnVectors::TiseanUnivariate) (TISEAN 3.0.1, which ignores `-d` inside the vectors of a
/// univariate series: only the ranges depend on τ).
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
/// [`AnalysisError::NonFinite`]; [`AnalysisError::Constant`]; [`AnalysisError::Monotonic`]
/// (a time column).
///
/// # Pitfalls
/// TISEAN's `false_nearest -d τ` with τ > 1 tests the unit-delay embedding (see
/// [`FnnVectors::TiseanUnivariate`](super::FnnVectors::TiseanUnivariate)); for a flow sampled finely that is a different and much
/// less informative test than Kennel's. Noisy data never reach 0 % (noise fills every dimension). With `w = 0` and a finely
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
    crate::analysis::reject_monotonic(x)?;
    let rescaled = rescale_unit(x)?;
    let sigma = standard_deviation(&rescaled.values);
    let setup = Setup {
        s: &rescaled.values,
        tau: opts.stride(),
        n_ref: x.len() - opts.m_max * opts.tau,
        n_cand: x.len() - (opts.m_max + 1) * opts.tau,
        theiler: opts.theiler_window(),
        ratio: opts.ratio,
        max_dist: sigma / opts.ratio,
        range: rescaled.range,
    };
    // nearest neighbour of each reference in the previous dimension: its distance in the next
    // dimension bounds the new nearest-neighbour distance from above (max norm), which
    // shrinks the search radius. Written by one dimension (`next`), read by the next (`prev`).
    let none = || (0..setup.n_ref).map(|_| AtomicU32::new(NONE)).collect();
    let (mut prev, mut next): (Vec<AtomicU32>, Vec<AtomicU32>) = (none(), none());
    // two grids: the next dimension's is built while this one's queries run
    let (mut grid, mut spare) = (Grid::default(), Grid::default());
    grid.build(&setup, opts.m_min);
    let mut points = Vec::with_capacity(opts.m_max - opts.m_min + 1);
    for m in opts.m_min..=opts.m_max {
        let (point, ()) = rayon::join(
            || fnn_in_dimension(&setup, m, &grid, &prev, &next),
            || {
                if m < opts.m_max {
                    spare.build(&setup, m + 1);
                }
            },
        );
        points.push(point?);
        std::mem::swap(&mut grid, &mut spare);
        std::mem::swap(&mut prev, &mut next);
    }
    Ok(points)
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
    crate::analysis::validate_embedding_range(opts.m_min, opts.m_max, opts.tau, MAX_DIMENSION)?;
    if !(opts.ratio.is_finite() && opts.ratio > 0.0) {
        return Err(AnalysisError::bad(
            "ratio",
            opts.ratio,
            "the escape ratio R_t must be a positive number (Kennel: 10, TISEAN: 2)",
        ));
    }
    Ok(())
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
