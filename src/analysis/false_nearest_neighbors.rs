//! False nearest neighbours (Kennel, Brown & Abarbanel 1992; SPEC (4.1.4)), with TISEAN
//! 3.0.1 `false_nearest`'s definition (SPEC §8).
//!
//! # Algorithm (why it is fast)
//! Exact nearest neighbours in the maximum norm by a box-assisted search, as TISEAN's: the
//! candidates are sorted into the cells of a grid on two delay coordinates (the first and
//! the last of the m-dimensional vector; one coordinate for m = 1) and a query scans only
//! the cells within its current bound, rings of cells outward from its own. The bound
//! starts at the smaller of σ/R_t (farther neighbours are never accepted) and the distance
//! to the previous dimension's neighbour (without one: to the nearest indices outside the
//! Theiler window), and shrinks with every closer candidate, so a query visits a few
//! cells. The grid stores only the two gridded coordinates (contiguous box tests); the full
//! vector is read from the series for the few candidates that pass. The queries of one
//! dimension run in parallel (rayon) over fixed blocks, while the next dimension's grid is
//! built; each answer depends only on its query, and the blocks' sums are added in block
//! order, so the results do not depend on the thread count.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

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

/// Accumulated counts of one dimension (of one block of queries, then of all).
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

    /// The tally of `self`'s queries followed by `other`'s.
    fn merge(mut self, other: Tally) -> Tally {
        self.accepted += other.accepted;
        self.false_count += other.false_count;
        self.sum_d += other.sum_d;
        self.sum_d2 += other.sum_d2;
        self
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

/// Queries per parallel work unit. Fixed (not set by the thread count), so that the
/// partial sums, added in block order, do not depend on the thread count.
const QUERY_BLOCK: usize = 2048;

/// Marks "no neighbour found" in the neighbour lists.
const NONE: u32 = u32::MAX;

/// Tests dimension m with `grid` (built for m): reads the previous dimension's neighbours
/// from `prev`, writes this dimension's to `next`.
fn fnn_in_dimension(
    setup: &Setup,
    m: usize,
    grid: &Grid,
    prev: &[AtomicU32],
    next: &[AtomicU32],
) -> Result<FnnPoint, AnalysisError> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match m {
                $($k => Ok(fnn_k::<$k>(setup, grid, prev, next)),)*
                _ => Err(AnalysisError::bad("m", m, format!("1..={MAX_DIMENSION}"))),
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

fn fnn_k<const K: usize>(
    setup: &Setup,
    grid: &Grid,
    prev: &[AtomicU32],
    next: &[AtomicU32],
) -> FnnPoint {
    // Queries in the grid's cell order (neighbouring queries read the same cells: cache
    // friendly), then the references that are not candidates; in parallel over fixed blocks
    // of that order. Each query's answer depends only on its own n (and its seed, which only
    // speeds it up), so the results do not depend on the thread count; the blocks' tallies
    // are added in block order.
    let n_grid = grid.index.len();
    let blocks = setup.n_ref.div_ceil(QUERY_BLOCK);
    let tallies: Vec<Tally> = (0..blocks)
        .into_par_iter()
        .map(|b| {
            let mut tally = Tally::default();
            for k in b * QUERY_BLOCK..((b + 1) * QUERY_BLOCK).min(setup.n_ref) {
                let n = if k < n_grid {
                    grid.index[k] as usize
                } else {
                    k
                };
                let found = nearest::<K>(grid, setup, n, prev[n].load(Relaxed));
                next[n].store(found.map_or(NONE, |(j, _)| j), Relaxed);
                if let Some((j, d)) = found {
                    tally.add(setup, K, n, j as usize, d);
                }
            }
            tally
        })
        .collect();
    tallies
        .into_iter()
        .fold(Tally::default(), Tally::merge)
        .finish(K, setup.range)
}

/// Box-assisted search structure (as TISEAN's): the candidates sorted by the cell of their
/// first and last coordinates `(s_j, s_{j+(m−1)τ})` on a `g1 × g2` grid over [0, 1]² (the
/// first coordinate only, `g2 = 1`, for m = 1), column-major, so that the cells of one
/// column form one contiguous run. Those two coordinates are stored in that order (the box
/// test reads them contiguously); the others are read from the series when a candidate
/// passes it. Its buffers are reused from one dimension to the next.
#[derive(Default)]
struct Grid {
    g1: usize,
    g2: usize,
    /// `start[c]..start[c + 1]`: the candidates of cell `c = cx·g2 + cy`.
    start: Vec<u32>,
    /// `(s_j, s_{j+(m−1)τ})` of the candidates, in cell order.
    ends: Vec<[f64; 2]>,
    /// Index j of each of them.
    index: Vec<u32>,
    /// Cell of candidate j (scratch of [`Grid::build`]).
    cell_of: Vec<u32>,
}

/// Cell of a rescaled coordinate `v` on a grid of `g` cells over [0, 1] (monotone in `v`;
/// values outside [0, 1] go to the first or last cell).
#[inline]
fn cell(v: f64, g: usize) -> isize {
    // f64 → i64 is one instruction on x86-64 (→ usize is not)
    ((v * g as f64) as i64).clamp(0, g as i64 - 1) as isize
}

impl Grid {
    /// Files the candidates `j < n_cand` for dimension `m` (a counting sort by cell).
    fn build(&mut self, setup: &Setup, m: usize) {
        let n = setup.n_cand;
        // 4N cells (at most 4096²): the attractor covers part of the square, so an occupied
        // cell holds a few candidates, and a cell is not much wider than a typical
        // nearest-neighbour distance
        let (g1, g2) = if m == 1 {
            (n.max(1), 1)
        } else {
            let g = ((4.0 * n as f64).sqrt().ceil() as usize).clamp(1, 1 << 12);
            (g, g)
        };
        let (s, last) = (setup.s, (m - 1) * setup.tau);
        let cells = g1 * g2;
        self.start.clear();
        self.start.resize(cells + 1, 0);
        self.cell_of.resize(n, 0);
        self.ends.resize(n, [0.0; 2]);
        self.index.resize(n, 0);
        for (j, c) in self.cell_of.iter_mut().enumerate() {
            let key = cell(s[j], g1) as usize * g2 + cell(s[j + last], g2) as usize;
            *c = key as u32;
            self.start[key + 1] += 1;
        }
        for c in 0..cells {
            self.start[c + 1] += self.start[c];
        }
        // file each candidate at the running start of its cell, then shift the starts back
        for (j, &c) in self.cell_of.iter().enumerate() {
            let at = self.start[c as usize] as usize;
            self.ends[at] = [s[j], s[j + last]];
            self.index[at] = j as u32;
            self.start[c as usize] += 1;
        }
        self.start.copy_within(0..cells, 1);
        self.start[0] = 0;
        (self.g1, self.g2) = (g1, g2);
    }

    /// Positions (in cell order) of the candidates of the cells `cx × (cy0..=cy1)`.
    #[inline]
    fn run(&self, cx: isize, cy0: isize, cy1: isize) -> std::ops::Range<usize> {
        let col = cx as usize * self.g2;
        self.start[col + cy0 as usize] as usize..self.start[col + cy1 as usize + 1] as usize
    }
}

/// The query's cell `(cx, cy)` and the cells `lo..=hi × ylo..=yhi` of the box of half-width
/// r around it (with a margin far below any distance, against rounding at a cell edge).
#[derive(Default)]
struct CellBox {
    cx: isize,
    cy: isize,
    lo: isize,
    hi: isize,
    ylo: isize,
    yhi: isize,
}

impl CellBox {
    #[inline]
    fn new(grid: &Grid, qx: f64, qy: f64, r: f64) -> Self {
        let (g1, g2, r) = (grid.g1, grid.g2, r + 1e-12);
        Self {
            cx: cell(qx, g1),
            cy: cell(qy, g2),
            lo: cell(qx - r, g1),
            hi: cell(qx + r, g1),
            ylo: cell(qy - r, g2),
            yhi: cell(qy + r, g2),
        }
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
    s: &'a [f64],
    tau: usize,
}

impl<const K: usize> Search<'_, K> {
    /// Takes candidate j if it is admissible and beats the best `(distance, j)`; its vector
    /// is read from the series (max-norm distance with an early exit beyond the bound).
    #[inline]
    fn consider(&mut self, j: usize) {
        if !outside_theiler_window(self.n, j, self.w) {
            return;
        }
        let mut d = 0.0f64;
        for (k, &q) in self.q.iter().enumerate() {
            // (no NaN here: the series is finite)
            let a = (q - self.s[j + k * self.tau]).abs();
            if a > d {
                d = a;
            }
            if d > self.r {
                return;
            }
        }
        let better = d > 0.0
            && match self.best {
                None => true,
                Some((bj, bd)) => d < bd || (d == bd && (j as u32) < bj),
            };
        if better {
            self.best = Some((j as u32, d));
            self.r = d;
        }
    }

    /// Scans the candidates at positions `range` of the grid: box test on the first and
    /// last coordinates (one branch), then the full distance.
    #[inline(always)]
    fn scan(&mut self, grid: &Grid, range: std::ops::Range<usize>) {
        let (qx, qy) = (self.q[0], self.q[K - 1]);
        for (p, &j) in grid.ends[range.clone()].iter().zip(&grid.index[range]) {
            if ((p[0] - qx).abs() <= self.r) & ((p[1] - qy).abs() <= self.r) {
                self.consider(j as usize);
            }
        }
    }
}

/// The nearest candidate of reference `n` in the max norm, ties to the smallest index: the
/// minimum of `(distance, j)` over `j < n_cand` with `|n − j| > w` and distance in
/// `(0, σ/R_t]` (neighbours farther than σ/R_t are never accepted, so the search stops
/// there). `seed` (the neighbour of the previous dimension), or without one the nearest
/// indices outside the Theiler window, give the first bound on the distance; the grid scan
/// is exact (the first bound only makes it shorter).
fn nearest<const K: usize>(grid: &Grid, setup: &Setup, n: usize, seed: u32) -> Option<(u32, f64)> {
    let w = setup.theiler;
    let (s, tau) = (setup.s, setup.tau);
    let mut sr = Search::<K> {
        q: std::array::from_fn(|k| s[n + k * tau]),
        n,
        w,
        r: setup.max_dist,
        best: None,
        s,
        tau,
    };
    if seed != NONE {
        sr.consider(seed as usize);
    } else {
        // no neighbour in the previous dimension (or the first dimension): the nearest
        // indices outside the Theiler window (rarely better than the seed, so not tried then)
        if n > w && n - w - 1 < setup.n_cand {
            sr.consider(n - w - 1);
        }
        if n + w + 1 < setup.n_cand {
            sr.consider(n + w + 1);
        }
    }
    let (qx, qy) = (sr.q[0], sr.q[K - 1]);
    if K >= 3 && sr.best.is_some() {
        // The seed (the previous dimension's neighbour, whose distance gains one coordinate)
        // is usually within a few per cent of the answer: scan the bound's box directly,
        // column by column outward (each column one contiguous run).
        let mut r_box = f64::NAN;
        let mut b = CellBox::default();
        for d in 0.. {
            if sr.r != r_box {
                r_box = sr.r;
                b = CellBox::new(grid, qx, qy, r_box);
            }
            let (left, right) = (b.cx - d, b.cx + d);
            let (l_in, r_in) = (left >= b.lo, right <= b.hi && d > 0);
            if !(l_in | r_in) {
                break;
            }
            if l_in {
                sr.scan(grid, grid.run(left, b.ylo, b.yhi));
            }
            if r_in {
                sr.scan(grid, grid.run(right, b.ylo, b.yhi));
            }
        }
    } else {
        // No seed, or one from one dimension (a poor bound in two): rings of cells at
        // Chebyshev cell distance d around the query's cell, nearest first, so that the bound
        // shrinks early; only cells inside the current bound's box are read.
        let mut b = CellBox::new(grid, qx, qy, sr.r);
        let (cx_q, cy_q) = (b.cx, b.cy);
        sr.scan(grid, grid.run(cx_q, cy_q, cy_q));
        let mut r_box = f64::NAN;
        for d in 1.. {
            if sr.r != r_box {
                r_box = sr.r;
                b = CellBox::new(grid, qx, qy, r_box);
            }
            let (left, right, below, above) = (cx_q - d, cx_q + d, cy_q - d, cy_q + d);
            let (l_in, r_in) = (left >= b.lo, right <= b.hi);
            let (b_in, a_in) = (below >= b.ylo, above <= b.yhi);
            if !(l_in | r_in | b_in | a_in) {
                break;
            }
            // columns cx_q ± d, rows strictly inside the ring (one contiguous run each)
            let (c0, c1) = ((cy_q - d + 1).max(b.ylo), (cy_q + d - 1).min(b.yhi));
            if c0 <= c1 {
                if l_in {
                    sr.scan(grid, grid.run(left, c0, c1));
                }
                if r_in {
                    sr.scan(grid, grid.run(right, c0, c1));
                }
            }
            // rows cy_q ± d, columns across the ring (corners included)
            let (x0, x1) = ((cx_q - d).max(b.lo), (cx_q + d).min(b.hi));
            for (cy, inside) in [(below, b_in), (above, a_in)] {
                if inside {
                    for cx in x0..=x1 {
                        sr.scan(grid, grid.run(cx, cy, cy));
                    }
                }
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
