//! Correlation sum C(m, ε) and correlation dimension D2 (Grassberger & Procaccia 1983), with
//! TISEAN 3.0.1 `d2`'s definitions (maximum norm, data units, Theiler window), the local
//! slopes d ln C / d ln ε per embedding dimension and an automatic plateau estimate of D2.
//!
//! # Algorithm (why it is fast)
//! All radii come from one pass over the pairs: each pair's maximum-norm distance is
//! extended coordinate by coordinate (it is non-decreasing in m, so one pass gives every
//! dimension), and put in the bin of the smallest ε that contains it; C(ε) is the running
//! sum of the bins. The bin is found without a logarithm: the leading bits of the f64
//! (exponent and a few mantissa bits, monotone in the value) index a table that gives the
//! candidate bin, corrected by one or two comparisons (exact). Only pairs closer than ε_max
//! are visited: a box-assisted search on a grid of cells of side ≥ ε_max over the first two
//! delay coordinates (m ≥ 2) and a sorted-coordinate sweep for m = 1, as TISEAN's `d2` does.
//! Reference points are split into fixed chunks processed in parallel (rayon); the counts
//! are integers, so the result does not depend on the thread count.
//!
//! Cost: O(N log N) set-up plus O(pairs within ε_max · m). With ε_max equal to the attractor
//! size every pair is visited (N²/2).

use rayon::prelude::*;

use crate::analysis::{min_max, require_positive, validate_series};
use crate::error::AnalysisError;

/// Largest embedding dimension supported by [`correlation_sum`].
pub const MAX_DIMENSION: usize = 32;

/// Reference points per parallel work unit (fixed, so that results do not depend on threads).
const CHUNK: usize = 2048;

/// Options of [`correlation_sum`]. `Default` gives TISEAN `d2`'s defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct D2Options {
    /// Smallest embedding dimension (TISEAN computes all from 1). Default 1.
    pub m_min: usize,
    /// Largest embedding dimension, ≤ 32 (TISEAN `-M 1,m_max`). Default 10.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub tau: usize,
    /// Theiler window w in samples: pairs need `|i − j| > w` (TISEAN `-t`). Default 0; use
    /// at least the autocorrelation time for flows.
    pub theiler: usize,
    /// Smallest radius ε in data units (TISEAN `-r`); `None` = (max − min)/1000.
    pub eps_min: Option<f64>,
    /// Largest radius ε in data units (TISEAN `-R`); `None` = max − min.
    pub eps_max: Option<f64>,
    /// Number of radii, log-spaced from `eps_min` to `eps_max` (TISEAN `-#`). Default 100.
    pub eps_count: usize,
}

impl Default for D2Options {
    fn default() -> Self {
        Self {
            m_min: 1,
            m_max: 10,
            tau: 1,
            theiler: 0,
            eps_min: None,
            eps_max: None,
            eps_count: 100,
        }
    }
}

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

fn validate_options(o: &D2Options) -> Result<(), AnalysisError> {
    require_positive("m_min", o.m_min)?;
    require_positive("tau", o.tau)?;
    if o.m_max < o.m_min {
        return Err(AnalysisError::bad(
            "m_max",
            o.m_max,
            format!("must be ≥ m_min = {}", o.m_min),
        ));
    }
    if o.m_max > MAX_DIMENSION {
        return Err(AnalysisError::bad(
            "m_max",
            o.m_max,
            format!("at most {MAX_DIMENSION} dimensions are supported"),
        ));
    }
    if o.eps_count < 2 {
        return Err(AnalysisError::bad(
            "eps_count",
            o.eps_count,
            "need at least 2 radii to form slopes",
        ));
    }
    for (name, v) in [("eps_min", o.eps_min), ("eps_max", o.eps_max)] {
        if let Some(v) = v {
            if !(v.is_finite() && v > 0.0) {
                return Err(AnalysisError::bad(
                    name,
                    v,
                    "the radius must be a positive number in data units",
                ));
            }
        }
    }
    Ok(())
}

/// Log-spaced radii in data units from ε_min to ε_max (defaults range/1000 and range).
fn radii(o: &D2Options, range: f64) -> Result<Vec<f64>, AnalysisError> {
    let hi = o.eps_max.unwrap_or(range);
    let lo = o.eps_min.unwrap_or(hi.min(range) / 1000.0);
    if lo >= hi {
        return Err(AnalysisError::bad(
            "eps_min",
            lo,
            format!("must be smaller than eps_max = {hi}"),
        ));
    }
    let n = o.eps_count;
    let f = (hi / lo).ln() / (n - 1) as f64;
    let mut eps: Vec<f64> = (0..n).map(|l| lo * (f * l as f64).exp()).collect();
    eps[n - 1] = hi;
    Ok(eps)
}

/// Exact bin lookup without logarithms: `bin(d)` = the smallest l with `d ≤ ε_l`.
///
/// For positive f64, `bits >> shift` is monotone in the value; `table[key − key0]` is the
/// smallest l whose ε_l is at least the smallest value with that key, so the answer is at
/// most a few steps above it.
struct BinTable {
    eps: Vec<f64>,
    shift: u32,
    key0: u64,
    table: Vec<u32>,
    /// Whether one comparison corrects every table entry (buckets finer than the ε spacing):
    /// then [`BinTable::bin`] has no data-dependent branch.
    one_step: bool,
}

impl BinTable {
    fn new(eps: &[f64]) -> Self {
        let n = eps.len();
        let fac = (eps[n - 1] / eps[0]).powf(1.0 / (n - 1) as f64);
        // mantissa bits per bucket: buckets finer than half the ε spacing, table ≤ 2^22
        let mut b = ((2.0 / (fac - 1.0)).log2().ceil().max(0.0) as u32).min(20);
        let (mut shift, mut key0, mut key1);
        loop {
            shift = 52 - b;
            key0 = eps[0].to_bits() >> shift;
            key1 = eps[n - 1].to_bits() >> shift;
            if key1 - key0 < (1 << 22) || b == 0 {
                break;
            }
            b -= 1;
        }
        let table: Vec<u32> = (key0..=key1)
            .map(|k| {
                let lower = f64::from_bits(k << shift);
                eps.partition_point(|&e| e < lower).min(n - 1) as u32
            })
            .collect();
        // the largest value of each bucket must lie at most one ε above the bucket's entry
        let one_step = table.iter().enumerate().all(|(k, &l)| {
            let top = f64::from_bits(((key0 + k as u64 + 1) << shift) - 1);
            eps.partition_point(|&e| e < top).min(n - 1) <= l as usize + 1
        });
        Self {
            eps: eps.to_vec(),
            shift,
            key0,
            table,
            one_step,
        }
    }

    /// Bin of a distance `0 ≤ d ≤ ε_max`.
    #[inline]
    fn bin(&self, d: f64) -> usize {
        // below ε_0 the key saturates to the first bucket, whose entry is 0 (ε_0 lies in it)
        let k = ((d.to_bits() >> self.shift).saturating_sub(self.key0) as usize)
            .min(self.table.len() - 1);
        let mut l = self.table[k] as usize;
        if self.one_step {
            return l + usize::from(d > self.eps[l]);
        }
        while d > self.eps[l] {
            l += 1;
        }
        l
    }
}

struct Job<'a> {
    s: &'a [f64],
    lo: f64,
    opts: &'a D2Options,
    vectors: usize,
    eps_max: f64,
    bins: &'a BinTable,
}

/// m = 1: sweep over the values sorted by size; pairs closer than ε_max are contiguous.
fn count_one_dimensional(job: &Job) -> Vec<u64> {
    let n_eps = job.bins.eps.len();
    let mut order: Vec<(f64, u32)> = (0..job.vectors).map(|i| (job.s[i], i as u32)).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let w = job.opts.theiler;
    let n_chunks = order.len().div_ceil(CHUNK);
    let parts: Vec<Vec<u64>> = (0..n_chunks)
        .into_par_iter()
        .map(|c| {
            let mut h = vec![0u64; n_eps];
            for a in c * CHUNK..((c + 1) * CHUNK).min(order.len()) {
                let (va, ia) = order[a];
                for &(vb, ib) in &order[a + 1..] {
                    let d = vb - va;
                    if d > job.eps_max {
                        break;
                    }
                    if (ia as usize).abs_diff(ib as usize) > w {
                        h[job.bins.bin(d)] += 1;
                    }
                }
            }
            h
        })
        .collect();
    sum_hists(parts, n_eps)
}

fn sum_hists(parts: Vec<Vec<u64>>, len: usize) -> Vec<u64> {
    let mut out = vec![0u64; len];
    for p in parts {
        for (a, b) in out.iter_mut().zip(&p) {
            *a += b;
        }
    }
    out
}

/// Cells per ε_max along each grid axis of [`count_grid`]: cells of side ≥ ε_max/`SUB`, so a
/// pair closer than ε_max lies at most `SUB` cells apart per axis. Finer cells visit fewer
/// pairs that are then rejected (the scanned area falls from 9 ε² to (2·SUB + 1)²/SUB² ε²).
const SUB: usize = 2;

/// m ≥ 2: box-assisted search on the first two delay coordinates (s_i, s_{i+τ}), cells of
/// side ≥ ε_max/[`SUB`], vectors stored in cell order. Each pair is visited once, from the
/// vector that comes first in cell order ("half shell": the rest of its own cell and the
/// cells above it in its column, then the next `SUB` columns), so every pair closer than
/// ε_max is counted exactly once.
fn count_grid(job: &Job) -> Vec<u64> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match job.opts.m_max {
                $($k => count_grid_dim::<$k>(job),)*
                _ => count_grid_dim::<0>(job),
            }
        };
    }
    dispatch!(2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

/// [`count_grid`] for `m_max = K` (`K = 0`: any `m_max`, read at run time).
fn count_grid_dim<const K: usize>(job: &Job) -> Vec<u64> {
    let o = job.opts;
    let (s, tau, nv) = (job.s, o.tau, job.vectors);
    let mm = if K == 0 { o.m_max } else { K };
    let m_lo = o.m_min.max(2);
    let n_eps = job.bins.eps.len();
    let n_dims = o.m_max - o.m_min + 1;
    let (_, hi) = min_max(s);
    let range = hi - job.lo;
    // the margin keeps the cell side strictly above ε_max/SUB whatever the rounding
    let g = ((SUB as f64 * range / job.eps_max * (1.0 - 1e-9)).floor() as usize).clamp(1, 1024);
    let cell_of = |v: f64| (((v - job.lo) / range * g as f64) as usize).min(g - 1);
    let key = |i: usize| cell_of(s[i]) * g + cell_of(s[i + tau]);
    let mut start = vec![0u32; g * g + 1];
    for i in 0..nv {
        start[key(i) + 1] += 1;
    }
    for c in 0..g * g {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut index = vec![0u32; nv];
    let mut vecs = vec![0.0f64; nv * mm];
    for i in 0..nv {
        let c = key(i);
        let at = fill[c] as usize;
        fill[c] += 1;
        index[at] = i as u32;
        for k in 0..mm {
            vecs[at * mm + k] = s[i + k * tau];
        }
    }
    let w = o.theiler;
    let n_chunks = nv.div_ceil(CHUNK);
    let parts: Vec<Vec<u64>> = (0..n_chunks)
        .into_par_iter()
        .map(|c| {
            let mut h = vec![0u64; n_dims * n_eps];
            let visit = |a: usize, run: std::ops::Range<usize>, h: &mut [u64]| {
                let i = index[a] as usize;
                let p = &vecs[a * mm..(a + 1) * mm];
                for b in run {
                    let j = index[b] as usize;
                    if i.abs_diff(j) > w {
                        pair::<K>(p, &vecs[b * mm..(b + 1) * mm], job, m_lo, h);
                    }
                }
            };
            for a in c * CHUNK..((c + 1) * CHUNK).min(nv) {
                let p = &vecs[a * mm..(a + 1) * mm];
                let (cx, cy) = (cell_of(p[0]), cell_of(p[1]));
                let (y0, y1) = (cy.saturating_sub(SUB), (cy + SUB).min(g - 1));
                // the rest of the own cell and the cells above it in the same column
                visit(a, a + 1..start[cx * g + y1 + 1] as usize, &mut h);
                for x in cx + 1..=(cx + SUB).min(g - 1) {
                    let run = start[x * g + y0] as usize..start[x * g + y1 + 1] as usize;
                    visit(a, run, &mut h);
                }
            }
            h
        })
        .collect();
    sum_hists(parts, n_dims * n_eps)
}

/// Adds one pair to the histogram of every dimension m ≥ m_lo in which it is within ε_max
/// (`K` coordinates, or `p.len()` for `K = 0`).
#[inline(always)]
fn pair<const K: usize>(p: &[f64], q: &[f64], job: &Job, m_lo: usize, h: &mut [u64]) {
    let n_eps = job.bins.eps.len();
    let m_min = job.opts.m_min;
    let mm = if K == 0 { p.len() } else { K };
    let (p, q) = (&p[..mm], &q[..mm]);
    // branch-free but for the exit: the running maximum and one table lookup per m
    let mut d = 0.0f64;
    for k in 0..mm {
        d = d.max((p[k] - q[k]).abs());
        if d > job.eps_max {
            return;
        }
        let m = k + 1;
        if m >= m_lo {
            h[(m - m_min) * n_eps + job.bins.bin(d)] += 1;
        }
    }
}

/// Settings of the plateau search [`find_plateau`] / [`estimate_d2`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateauOptions {
    /// Radii with fewer pairs than this are ignored (statistical scatter; TISEAN's `-N`
    /// default 1000 uses the same bound). Default 1000.
    pub min_pairs: u64,
    /// Radii with C above this are ignored (the slopes fall at the attractor size).
    /// Default 0.3.
    pub max_c: f64,
    /// Largest relative deviation of a local slope from the plateau mean. Default 0.05.
    pub tolerance: f64,
    /// Shortest plateau as a factor in ε (ε_hi/ε_lo). Default 2.
    pub min_factor: f64,
    /// D2 is averaged over this many of the highest dimensions that have a plateau
    /// (GP: the slopes saturate as m grows). Default 3.
    pub dims: usize,
}

impl Default for PlateauOptions {
    fn default() -> Self {
        Self {
            min_pairs: 1000,
            max_c: 0.3,
            tolerance: 0.05,
            min_factor: 2.0,
            dims: 3,
        }
    }
}

/// The plateau (scaling region) of one curve's local slopes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Plateau {
    /// Embedding dimension.
    pub m: usize,
    /// Smallest radius of the plateau (data units).
    pub eps_lo: f64,
    /// Largest radius of the plateau (data units).
    pub eps_hi: f64,
    /// Mean local slope over the plateau: the D2 estimate of this m.
    pub d2: f64,
    /// Standard deviation of the local slopes over the plateau.
    pub std: f64,
    /// Number of radii in the plateau.
    pub points: usize,
    /// Whether every slope is within `tolerance` of the mean; false = fallback (the flattest
    /// window of the minimum length): no real plateau, do not trust `d2`.
    pub flat: bool,
}

/// Finds the plateau of the local slopes of one curve.
///
/// # Formula
/// Among the radii with at least `min_pairs` pairs and `C ≤ max_c`, every window of
/// consecutive radii spanning at least a factor `min_factor` is tested: it is flat if
/// `|ν_l − ν̄| ≤ tolerance·ν̄` for all its slopes ν_l. The longest flat window wins (ties: the
/// smaller standard deviation). Without a flat window, the window of minimum length with the
/// smallest standard deviation is returned with `flat = false`.
///
/// # Errors
/// `None` when fewer admissible radii than the minimum window remain.
pub fn find_plateau(curve: &CorrelationCurve, opts: &PlateauOptions) -> Option<Plateau> {
    let pts: Vec<(f64, f64)> = (0..curve.eps.len())
        .filter(|&l| curve.pairs[l] >= opts.min_pairs && curve.c[l] <= opts.max_c)
        .filter_map(|l| curve.slope[l].map(|v| (curve.eps[l], v)))
        .collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let stats = |a: usize, b: usize| {
        let k = (b - a + 1) as f64;
        let mean = pts[a..=b].iter().map(|p| p.1).sum::<f64>() / k;
        let var = pts[a..=b].iter().map(|p| (p.1 - mean).powi(2)).sum::<f64>() / k;
        let dev = pts[a..=b]
            .iter()
            .map(|p| (p.1 - mean).abs())
            .fold(0.0, f64::max);
        (mean, var.sqrt(), dev)
    };
    let mut best: Option<(usize, f64, usize, usize, bool)> = None;
    let mut fallback: Option<(f64, usize, usize)> = None;
    // the admissible radii are contiguous: pair counts and C grow with ε
    for a in 0..n {
        let Some(b_min) = (a + 2..n).find(|&b| pts[b].0 / pts[a].0 >= opts.min_factor) else {
            break;
        };
        let (_, std_min, _) = stats(a, b_min);
        if fallback.is_none_or(|f| std_min < f.0) {
            fallback = Some((std_min, a, b_min));
        }
        for b in b_min..n {
            let (mean, std, dev) = stats(a, b);
            if mean > 0.0 && dev <= opts.tolerance * mean {
                let len = b - a + 1;
                let better = match best {
                    None => true,
                    Some((bl, bs, ..)) => len > bl || (len == bl && std < bs),
                };
                if better {
                    best = Some((len, std, a, b, true));
                }
            }
        }
    }
    let (a, b, flat) = match (best, fallback) {
        (Some((_, _, a, b, _)), _) => (a, b, true),
        (None, Some((_, a, b))) => (a, b, false),
        (None, None) => return None,
    };
    let (mean, std, _) = stats(a, b);
    Some(Plateau {
        m: curve.m,
        eps_lo: pts[a].0,
        eps_hi: pts[b].0,
        d2: mean,
        std,
        points: b - a + 1,
        flat,
    })
}

/// The correlation dimension with its spread, from the plateaus of the highest dimensions.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct D2Estimate {
    /// D2: mean of the local slopes pooled over the plateaus of the dimensions used.
    pub d2: f64,
    /// Standard deviation of those pooled slopes (within- and between-dimension scatter).
    pub spread: f64,
    /// Embedding dimensions whose plateaus entered the estimate.
    pub dims_used: Vec<usize>,
    /// Plateau of every dimension that has one.
    pub plateaus: Vec<Plateau>,
    /// Whether all plateaus used are flat (see [`Plateau::flat`]).
    pub flat: bool,
}

/// Automatic D2 from correlation sums: the plateau of every m ([`find_plateau`]), then the
/// pooled mean and standard deviation of the local slopes over the plateaus of the `dims`
/// highest dimensions with a flat plateau (or with any plateau if none is flat).
///
/// # Errors
/// [`AnalysisError::NoResult`] when no curve has a plateau candidate (too few pairs: longer
/// series, larger ε_max or smaller `min_pairs`).
pub fn estimate_d2(
    sums: &CorrelationSums,
    opts: &PlateauOptions,
) -> Result<D2Estimate, AnalysisError> {
    let plateaus: Vec<Plateau> = sums
        .curves
        .iter()
        .filter_map(|c| find_plateau(c, opts))
        .collect();
    let flat: Vec<&Plateau> = plateaus.iter().filter(|p| p.flat).collect();
    let pool: Vec<&Plateau> = if flat.is_empty() {
        plateaus.iter().collect()
    } else {
        flat
    };
    if pool.is_empty() {
        return Err(AnalysisError::NoResult(format!(
            "no scaling region: no radius has ≥ {} pairs with C ≤ {} over a factor {} in ε \
             (use a longer series, a larger eps_max or fewer min_pairs)",
            opts.min_pairs, opts.max_c, opts.min_factor
        )));
    }
    let used: Vec<&Plateau> = pool.iter().rev().take(opts.dims.max(1)).copied().collect();
    let mut slopes = Vec::new();
    for p in &used {
        let curve = &sums.curves[p.m - sums.curves[0].m];
        for l in 0..curve.eps.len() {
            if curve.eps[l] >= p.eps_lo && curve.eps[l] <= p.eps_hi {
                if let Some(v) = curve.slope[l] {
                    slopes.push(v);
                }
            }
        }
    }
    let k = slopes.len() as f64;
    let d2 = slopes.iter().sum::<f64>() / k;
    let spread = (slopes.iter().map(|v| (v - d2).powi(2)).sum::<f64>() / k).sqrt();
    let mut dims_used: Vec<usize> = used.iter().map(|p| p.m).collect();
    dims_used.sort_unstable();
    Ok(D2Estimate {
        d2,
        spread,
        flat: used.iter().all(|p| p.flat),
        dims_used,
        plateaus,
    })
}

/// Correlation dimension D2 of a series: [`correlation_sum`] then [`estimate_d2`].
///
/// # Formula
/// `D2 = d ln C(m, ε) / d ln ε` on the plateau, for the highest embedding dimensions (SPEC §4;
/// Grassberger & Procaccia 1983).
///
/// # Units
/// Dimensionless; ε in data units.
///
/// # Errors
/// Those of [`correlation_sum`] and [`estimate_d2`].
///
/// # References
/// P. Grassberger and I. Procaccia, Phys. Rev. Lett. 50, 346–349 (1983).
/// doi:10.1103/PhysRevLett.50.346
///
/// # Example
/// ```
/// use pdamp::analysis::correlation_dimension::{correlation_dimension, D2Options, PlateauOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(5000);
/// let o = D2Options { m_min: 2, m_max: 4, eps_max: Some(0.5), eps_count: 40, ..D2Options::default() };
/// let (_, est) = correlation_dimension(&x, &o, &PlateauOptions::default()).unwrap();
/// assert!((est.d2 - 1.22).abs() < 0.12); // Grassberger & Procaccia: 1.21 ± 0.01
/// ```
pub fn correlation_dimension(
    x: &[f64],
    opts: &D2Options,
    plateau: &PlateauOptions,
) -> Result<(CorrelationSums, D2Estimate), AnalysisError> {
    let sums = correlation_sum(x, opts)?;
    let est = estimate_d2(&sums, plateau)?;
    Ok((sums, est))
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
