//! False nearest neighbours (Kennel, Brown & Abarbanel 1992; SPEC (4.1.4)), with TISEAN
//! 3.0.1 `false_nearest`'s definition (SPEC §8).
//!
//! # Algorithm (why it is fast)
//! Exact nearest neighbours in the maximum norm by a box-assisted search, as TISEAN's: the
//! candidates are sorted into the cells of a grid on two delay coordinates (the first and
//! the last of the m-dimensional vector; one coordinate for m = 1) and a query scans only
//! the cells within its current bound, columns outward from its own. The bound starts at
//! the smallest of σ/R_t (farther neighbours are never accepted), the distance to the
//! nearest indices outside the Theiler window, and the distance to the previous dimension's
//! neighbour, and shrinks with every closer candidate, so a query visits a few cells. The
//! queries of one dimension run in parallel (rayon); each answer depends only on its query,
//! so the results do not depend on the thread count.

use rayon::prelude::*;

use crate::analysis::{outside_theiler_window, require_positive, rescale_unit, standard_deviation};
use crate::error::AnalysisError;

/// Largest embedding dimension supported (distances are unrolled for a compile-time dimension).
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
    /// Which coordinates make up the vectors. Default [`FnnVectors::Delay`] (Kennel et al.);
    /// [`FnnOptions::tisean`] uses [`FnnVectors::TiseanUnivariate`].
    pub vectors: FnnVectors,
}

/// The coordinates of the vectors compared by [`false_nearest_neighbors`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FnnVectors {
    /// Delay vectors `(s_n, s_{n+τ}, …, s_{n+(m−1)τ})`, escape coordinate `s_{n+mτ}` (Kennel
    /// et al. 1992, SPEC (4.1.4)). pdamp's default.
    #[default]
    Delay,
    /// TISEAN 3.0.1 `false_nearest` on a univariate series: the vectors are *consecutive*
    /// samples `(s_n, s_{n+1}, …, s_{n+m−1})` and the escape coordinate is `s_{n+m}`, whatever
    /// the delay τ — its code sets the offsets `vemb[i] = i` for one component (and
    /// `(i/comp)·delay` only for several). τ still sets the index ranges: references
    /// `n < N − M·τ`, candidates `j < N − (M+1)·τ`. With τ = 1 both choices are the same.
    TiseanUnivariate,
}

impl Default for FnnOptions {
    fn default() -> Self {
        Self {
            m_min: 1,
            m_max: 6,
            tau: 1,
            ratio: 10.0,
            theiler: None,
            vectors: FnnVectors::Delay,
        }
    }
}

impl FnnOptions {
    /// TISEAN `false_nearest`'s defaults and definition: `-m1 -M1,5 -d1 -f2 -t0`, and
    /// [`FnnVectors::TiseanUnivariate`] (TISEAN ignores `-d` inside the vectors).
    pub fn tisean() -> Self {
        Self {
            m_min: 1,
            m_max: 5,
            tau: 1,
            ratio: 2.0,
            theiler: Some(0),
            vectors: FnnVectors::TiseanUnivariate,
        }
    }

    /// Spacing in samples of the vectors' coordinates: τ, or 1 for TISEAN's univariate vectors.
    pub fn stride(&self) -> usize {
        match self.vectors {
            FnnVectors::Delay => self.tau,
            FnnVectors::TiseanUnivariate => 1,
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
/// `x_n = (s_n, s_{n+k}, …, s_{n+(m−1)k})` for `n < N − m_max·τ` (the same points for every m);
/// candidate neighbours `j < N − (m_max+1)·τ` (TISEAN's range). The nearest neighbour `j` of
/// `n` in the maximum norm with `|n − j| > w` and distance `δ > 0` (exact duplicates are
/// ignored) is accepted if `δ ≤ σ/R_t` (σ: standard deviation of the rescaled series); the
/// pair is false if `|s_{n+mk} − s_{j+mk}| / δ > R_t`. Fraction = false / accepted. The
/// coordinate spacing is `k = τ` for [`FnnVectors::Delay`] (pdamp's default) and `k = 1` for
/// [`FnnVectors::TiseanUnivariate`] (TISEAN 3.0.1, which ignores `-d` inside the vectors of a
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
/// [`FnnVectors::TiseanUnivariate`]); for a flow sampled finely that is a different and much
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
    // shrinks the search radius
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
    /// Spacing of the vectors' coordinates ([`FnnOptions::stride`]).
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

/// Queries per parallel work unit (at least).
const QUERY_BLOCK: usize = 2048;

/// Marks "no neighbour found" in the previous-dimension list.
const NONE: u32 = u32::MAX;

fn fnn_in_dimension(setup: &Setup, m: usize, prev: &mut [u32]) -> Result<FnnPoint, AnalysisError> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match m {
                $($k => Ok(fnn_k::<$k>(setup, prev)),)*
                _ => Err(AnalysisError::bad("m", m, format!("1..={MAX_DIMENSION}"))),
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

fn fnn_k<const K: usize>(setup: &Setup, prev: &mut [u32]) -> FnnPoint {
    let grid = Grid::<K>::new(setup);
    // Queries in the grid's cell order (neighbouring queries read the same cells: cache
    // friendly), in parallel over fixed blocks of that order; each query's answer depends
    // only on its own n, so results do not depend on the thread count. They are stored per
    // n and tallied in n order (sums as in a plain loop).
    let n_grid = grid.index.len();
    let found: Vec<Option<(u32, f64)>> = (0..setup.n_ref)
        .into_par_iter()
        .with_min_len(QUERY_BLOCK)
        .map(|k| {
            let (n, q) = if k < n_grid {
                (grid.index[k] as usize, grid.points[k])
            } else {
                let n = setup.n_cand + (k - n_grid);
                (n, std::array::from_fn(|c| setup.s[n + c * setup.tau]))
            };
            nearest(&grid, setup, n, q, prev[n])
        })
        .collect();
    let mut dist = vec![0.0f64; setup.n_ref];
    for (k, f) in found.into_iter().enumerate() {
        let n = if k < n_grid {
            grid.index[k] as usize
        } else {
            setup.n_cand + (k - n_grid)
        };
        prev[n] = f.map_or(NONE, |(j, _)| j);
        dist[n] = f.map_or(0.0, |(_, d)| d);
    }
    let mut tally = Tally::default();
    for (n, (&j, &d)) in prev.iter().zip(&dist).enumerate() {
        if j != NONE {
            tally.add(setup, K, n, j as usize, d);
        }
    }
    tally.finish(K, setup.range)
}

/// Box-assisted search structure (as TISEAN's): the candidates sorted by the cell of their
/// first and last coordinates `(s_j, s_{j+(K−1)τ})` on a `g1 × g2` grid over [0, 1]² (the
/// first coordinate only, `g2 = 1`, for K = 1), column-major, so that the cells of one
/// column form one contiguous run. The delay vectors are stored in that order (contiguous
/// reads while scanning a run).
struct Grid<const K: usize> {
    g1: usize,
    g2: usize,
    /// `start[c]..start[c + 1]`: the candidates of cell `c = cx·g2 + cy`.
    start: Vec<u32>,
    /// Delay vectors of the candidates, in cell order.
    points: Vec<[f64; K]>,
    /// Index j of each of them.
    index: Vec<u32>,
    /// Position of candidate j in cell order (inverse of `index`).
    pos: Vec<u32>,
}

/// Cell of a rescaled coordinate `v ∈ [0, 1]` on a grid of `g` cells (monotone in `v`).
fn cell(v: f64, g: usize) -> usize {
    ((v * g as f64) as usize).min(g - 1)
}

impl<const K: usize> Grid<K> {
    fn new(setup: &Setup) -> Self {
        let n = setup.n_cand;
        // a few candidates per occupied cell (the attractor covers part of the square)
        let (g1, g2) = if K == 1 {
            (n.max(1), 1)
        } else {
            let g = ((n as f64).sqrt().ceil() as usize).clamp(1, 1 << 12);
            (g, g)
        };
        let (s, tau) = (setup.s, setup.tau);
        let point = |j: usize| -> [f64; K] { std::array::from_fn(|k| s[j + k * tau]) };
        let key = |p: &[f64; K]| cell(p[0], g1) * g2 + cell(p[K - 1], g2);
        let mut start = vec![0u32; g1 * g2 + 1];
        for j in 0..n {
            start[key(&point(j)) + 1] += 1;
        }
        for c in 0..g1 * g2 {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut points = vec![[0.0; K]; n];
        let mut index = vec![0u32; n];
        let mut pos = vec![0u32; n];
        for (j, pos_j) in pos.iter_mut().enumerate() {
            let p = point(j);
            let c = key(&p);
            let at = fill[c] as usize;
            points[at] = p;
            index[at] = j as u32;
            *pos_j = at as u32;
            fill[c] += 1;
        }
        Self {
            g1,
            g2,
            start,
            points,
            index,
            pos,
        }
    }

    /// Positions (in cell order) of the candidates of the cells `cx × (cy0..=cy1)`.
    fn run(&self, cx: usize, cy0: usize, cy1: usize) -> std::ops::Range<usize> {
        self.start[cx * self.g2 + cy0] as usize..self.start[cx * self.g2 + cy1 + 1] as usize
    }
}

/// The best neighbour found so far and the current search bound.
struct Search<'a, const K: usize> {
    q: [f64; K],
    n: usize,
    w: usize,
    /// Current bound on the distance (σ/R_t, then the best distance).
    r: f64,
    best: Option<(u32, f64)>,
    grid: &'a Grid<K>,
}

impl<const K: usize> Search<'_, K> {
    /// Max-norm distance from the query to `p`, or `None` beyond the bound (early exit).
    fn distance(&self, p: &[f64; K]) -> Option<f64> {
        let mut d = 0.0f64;
        for (a, b) in self.q.iter().zip(p) {
            d = d.max((a - b).abs());
            if d > self.r {
                return None;
            }
        }
        Some(d)
    }

    /// Takes candidate j at point p if it is admissible and beats the best `(distance, j)`.
    fn consider(&mut self, j: u32, p: &[f64; K]) {
        if !outside_theiler_window(self.n, j as usize, self.w) {
            return;
        }
        if let Some(d) = self.distance(p) {
            let better = d > 0.0
                && match self.best {
                    None => true,
                    Some((bj, bd)) => d < bd || (d == bd && j < bj),
                };
            if better {
                self.best = Some((j, d));
                self.r = d;
            }
        }
    }

    /// [`Search::consider`] for candidate j (`j < n_cand`).
    fn consider_index(&mut self, j: usize) {
        let p = self.grid.points[self.grid.pos[j] as usize];
        self.consider(j as u32, &p);
    }

    /// Scans the candidates at positions `range` of the grid (box test on the first and
    /// last coordinates first).
    fn scan(&mut self, range: std::ops::Range<usize>) {
        let grid = self.grid;
        let (qx, qy) = (self.q[0], self.q[K - 1]);
        for (p, &j) in grid.points[range.clone()].iter().zip(&grid.index[range]) {
            if (p[0] - qx).abs() <= self.r && (p[K - 1] - qy).abs() <= self.r {
                self.consider(j, p);
            }
        }
    }
}

/// The nearest candidate of reference `n` (delay vector `q`) in the max norm, ties to the smallest index:
/// the minimum of `(distance, j)` over `j < n_cand` with `|n − j| > w` and distance in
/// `(0, σ/R_t]` (neighbours farther than σ/R_t are never accepted, so the search stops
/// there). `seed` (the neighbour of the previous dimension) and the nearest indices outside
/// the Theiler window give the first bound on the distance; the grid scan is exact.
fn nearest<const K: usize>(
    grid: &Grid<K>,
    setup: &Setup,
    n: usize,
    q: [f64; K],
    seed: u32,
) -> Option<(u32, f64)> {
    let w = setup.theiler;
    let mut sr = Search {
        q,
        n,
        w,
        r: setup.max_dist,
        best: None,
        grid,
    };
    if seed != NONE {
        sr.consider_index(seed as usize);
    }
    if n > w && n - w - 1 < setup.n_cand {
        sr.consider_index(n - w - 1);
    }
    if n + w + 1 < setup.n_cand {
        sr.consider_index(n + w + 1);
    }
    let (g1, g2) = (grid.g1, grid.g2);
    let (qx, qy) = (sr.q[0], sr.q[K - 1]);
    let (cx_q, cy_q) = (cell(qx, g1), cell(qy, g2));
    // rings of cells at Chebyshev cell distance d around the query's cell, nearest first,
    // so that the bound shrinks early; only cells inside the current bound's box are read
    for d in 0..g1.max(g2) {
        let r = sr.r;
        let (lo, hi) = (cell((qx - r).max(0.0), g1), cell((qx + r).min(1.0), g1));
        let (ylo, yhi) = (cell((qy - r).max(0.0), g2), cell((qy + r).min(1.0), g2));
        if d == 0 {
            sr.scan(grid.run(cx_q, cy_q, cy_q));
            continue;
        }
        let left = cx_q.checked_sub(d).filter(|&c| c >= lo);
        let right = Some(cx_q + d).filter(|&c| c <= hi);
        let below = cy_q.checked_sub(d).filter(|&c| c >= ylo);
        let above = Some(cy_q + d).filter(|&c| c <= yhi);
        if left.is_none() && right.is_none() && below.is_none() && above.is_none() {
            break;
        }
        // columns cx_q ± d, rows strictly inside the ring (one contiguous run each)
        let (c0, c1) = (
            (cy_q + 1).saturating_sub(d).max(ylo),
            (cy_q + d).min(yhi + 1),
        );
        for cx in [left, right].into_iter().flatten() {
            if c0 < c1 {
                sr.scan(grid.run(cx, c0, c1 - 1));
            }
        }
        // rows cy_q ± d, columns across the ring (corners included)
        for cy in [below, above].into_iter().flatten() {
            for cx in cx_q.saturating_sub(d).max(lo)..=(cx_q + d).min(hi) {
                sr.scan(grid.run(cx, cy, cy));
            }
        }
    }
    sr.best
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
