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

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

use crate::analysis::{
    outside_theiler_window, reject_monotonic, require_positive, rescale_unit, validate_series,
};
use crate::error::AnalysisError;
use crate::simd::Simd;

/// Largest embedding dimension supported by [`kantz`].
pub const MAX_DIMENSION: usize = 16;

/// References per parallel work unit (fixed, so that sums do not depend on thread count).
const CHUNK: usize = 1024;

/// Which average over the neighbourhood enters the logarithm of S(Δn).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum KantzDefinition {
    /// pdamp's default, (4.1.7) literally: `ln( mean over U_n of ‖y_{n+Δn} − y_{n'+Δn}‖ )`,
    /// the mean of the Euclidean distances of the full m-dimensional delay vectors.
    #[default]
    MeanDistance,
    /// TISEAN `lyap_k`: `ln( sqrt( mean over U_n of ‖y_{n+Δn} − y_{n'+Δn}‖² ) )`, the log of the
    /// root-mean-square distance (SPEC §8).
    TiseanRms,
}

/// Options of [`kantz`]. `Default` gives pdamp's defaults; [`KantzOptions::tisean`] TISEAN's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KantzOptions {
    /// Smallest embedding dimension (TISEAN `-m`, which raises values below 2 to 2). Default 2.
    pub m_min: usize,
    /// Largest embedding dimension, ≤ 16 (TISEAN `-M`). Default 2 (TISEAN) — raise it.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub tau: usize,
    /// Smallest neighbourhood radius ε in data units (TISEAN `-r`); `None` = range/1000.
    pub eps_min: Option<f64>,
    /// Largest radius in data units (TISEAN `-R`); `None` = range/100.
    pub eps_max: Option<f64>,
    /// Number of radii, log-spaced from `eps_min` to `eps_max` (TISEAN `-#`). Default 5.
    pub eps_count: usize,
    /// Number of reference points: the first n admissible indices (TISEAN `-n`); `None` = all.
    pub references: Option<usize>,
    /// Largest Δn in samples (TISEAN `-s`). Default 50.
    pub steps: usize,
    /// Theiler window w in samples: neighbours need `|n − n'| > w` (TISEAN `-t`). pdamp
    /// default `None` = one lag τ; TISEAN's default is 0.
    pub theiler: Option<usize>,
    /// Average inside the logarithm. Default [`KantzDefinition::MeanDistance`].
    pub definition: KantzDefinition,
}

impl Default for KantzOptions {
    fn default() -> Self {
        Self {
            m_min: 2,
            m_max: 2,
            tau: 1,
            eps_min: None,
            eps_max: None,
            eps_count: 5,
            references: None,
            steps: 50,
            theiler: None,
            definition: KantzDefinition::MeanDistance,
        }
    }
}

impl KantzOptions {
    /// TISEAN `lyap_k`'s defaults: `-m2 -M2 -d1 -#5 -s50 -t0`, all references, RMS definition.
    pub fn tisean() -> Self {
        Self {
            theiler: Some(0),
            definition: KantzDefinition::TiseanRms,
            ..Self::default()
        }
    }

    /// The Theiler window in effect (`theiler`, or τ when `None`).
    pub fn theiler_window(&self) -> usize {
        self.theiler.unwrap_or(self.tau)
    }
}

/// One curve S(Δn) for a given dimension and radius.
#[derive(Debug, Clone, PartialEq)]
pub struct KantzCurve {
    /// Embedding dimension m.
    pub m: usize,
    /// Neighbourhood radius ε in data units.
    pub eps: f64,
    /// `s[Δn]` = S(Δn) in rescaled units (add `ln(range)` for data units), Δn = 0..=steps;
    /// `None` where no reference point had a neighbour.
    pub s: Vec<Option<f64>>,
    /// Number of reference points that contributed at each Δn (TISEAN's third column).
    pub count: Vec<u64>,
}

/// All curves of one [`kantz`] call.
#[derive(Debug, Clone, PartialEq)]
pub struct KantzResult {
    /// Curves ordered by ε (outer) then m (inner), as TISEAN prints them.
    pub curves: Vec<KantzCurve>,
    /// `max − min` of the series (data units): S in data units is `S + ln(range)`.
    pub range: f64,
    /// Definition used.
    pub definition: KantzDefinition,
}

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
    require_positive("m_min", o.m_min)?;
    require_positive("tau", o.tau)?;
    require_positive("eps_count", o.eps_count)?;
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
    if o.references == Some(0) {
        return Err(AnalysisError::bad(
            "references",
            0,
            "need at least 1 reference point (omit it for all)",
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

/// Fixed inputs of a run.
struct Job<'a> {
    s: &'a [f64],
    opts: &'a KantzOptions,
    /// Squared radii, increasing.
    eps2: Vec<f64>,
    n_cand: usize,
    n_ref: usize,
    theiler: usize,
    /// No two samples of the (rescaled) series are equal and no difference of two squares to 0:
    /// then no pair has `e_t = 0` and the RMS path skips looking for zeros.
    distinct: bool,
}

impl Job<'_> {
    fn n_dims(&self) -> usize {
        self.opts.m_max - self.opts.m_min + 1
    }
    fn len(&self) -> usize {
        self.opts.steps + 1
    }
    /// Index of (dimension slot, eps) rows in the flat arrays.
    fn row(&self, dim_slot: usize, l: usize) -> usize {
        (dim_slot * self.eps2.len() + l) * self.len()
    }
    fn total_len(&self) -> usize {
        self.n_dims() * self.eps2.len() * self.len()
    }
    /// Factor of the logarithm: ½ for TISEAN's log of the RMS distance, 1 otherwise.
    fn half(&self) -> f64 {
        if self.opts.definition == KantzDefinition::TiseanRms {
            0.5
        } else {
            1.0
        }
    }
}

/// Sums of ln-terms and reference counts, laid out [dim][eps][Δn].
struct Totals {
    lyap: Vec<f64>,
    count: Vec<u64>,
}

impl Totals {
    fn new(n: usize) -> Self {
        Self {
            lyap: vec![0.0; n],
            count: vec![0; n],
        }
    }
    fn add(&mut self, other: &Totals) {
        for (a, b) in self.lyap.iter_mut().zip(&other.lyap) {
            *a += b;
        }
        for (a, b) in self.count.iter_mut().zip(&other.count) {
            *a += b;
        }
    }
}

/// Running products of one chunk's per-reference sums, so that the logarithm is taken once
/// per chunk instead of once per reference: `Σ_r ln(a_r/c_r) = ln Π_r a_r − Σ_r ln c_r`.
/// A product is kept as a mantissa `p` and a binary exponent `exp2` (value `p·2^exp2`);
/// `p` is renormalised to [1, 2) after every [`RENORM_EVERY`] factors, and only factors in
/// [`PROD_LO`, `PROD_HI`] enter it (others take the direct path), so it never leaves the
/// normal f64 range. Rounding: ~1e-16 relative per factor, as for a sum of logarithms.
struct Products {
    /// Mantissa products, [row][Δn] (row = dimension slot × ε).
    p: Vec<f64>,
    /// Binary exponents taken out of `p`, same layout.
    exp2: Vec<i64>,
    /// Factors multiplied into each row since its last renormalisation.
    since: Vec<u32>,
    /// Σ ln c_r of the references in each row's product (c_r: neighbour count, the same
    /// at every Δn for these references).
    ln_count: Vec<f64>,
    /// Number of references in each row's product.
    refs: Vec<u64>,
}

/// Smallest factor admitted to a running product (2^-100).
const PROD_LO: f64 = 7.888_609_052_210_118e-31;
/// Largest factor admitted to a running product (2^100).
const PROD_HI: f64 = 1.267_650_600_228_229_4e30;
/// Renormalise a product after this many factors: 8 factors in [2^-100, 2^100] times a
/// mantissa in [1, 2) stay inside 2^±808.
const RENORM_EVERY: u32 = 8;
/// Mantissa bits of an f64.
const MANTISSA: u64 = 0x000f_ffff_ffff_ffff;
/// Bits of 1.0 (biased exponent 1023, zero mantissa).
const ONE_BITS: u64 = 0x3ff0_0000_0000_0000;

impl Products {
    fn new(rows: usize, len: usize) -> Self {
        Self {
            p: vec![1.0; rows * len],
            exp2: vec![0; rows * len],
            since: vec![0; rows],
            ln_count: vec![0.0; rows],
            refs: vec![0; rows],
        }
    }

    /// Multiplies the factors `a` (all in [PROD_LO, PROD_HI]) of one reference with `c`
    /// neighbours into row `r`.
    #[inline(always)]
    fn multiply(&mut self, r: usize, a: &[f64], c: u32) {
        let len = a.len();
        let p = &mut self.p[r * len..(r + 1) * len];
        for (x, y) in p.iter_mut().zip(a) {
            *x *= y;
        }
        self.ln_count[r] += f64::from(c).ln();
        self.refs[r] += 1;
        self.since[r] += 1;
        if self.since[r] == RENORM_EVERY {
            self.since[r] = 0;
            let exp2 = &mut self.exp2[r * len..(r + 1) * len];
            for (x, e) in p.iter_mut().zip(exp2) {
                let b = x.to_bits();
                *e += ((b >> 52) & 0x7ff) as i64 - 1023;
                *x = f64::from_bits((b & MANTISSA) | ONE_BITS);
            }
        }
    }

    /// Adds `half·(ln Π a − Σ ln c)` and the reference counts to `totals`.
    fn fold_into(&self, totals: &mut Totals, half: f64, len: usize) {
        for (r, &refs) in self.refs.iter().enumerate() {
            if refs == 0 {
                continue;
            }
            let span = r * len..(r + 1) * len;
            let (p, exp2) = (&self.p[span.clone()], &self.exp2[span.clone()]);
            let (lyap, count) = (&mut totals.lyap[span.clone()], &mut totals.count[span]);
            for t in 0..len {
                let ln_prod = p[t].ln() + exp2[t] as f64 * std::f64::consts::LN_2;
                lyap[t] += half * (ln_prod - self.ln_count[r]);
                count[t] += refs;
            }
        }
    }
}

/// Per-worker scratch buffers, allocated once per chunk.
struct Scratch {
    /// Neighbour indices of the current reference.
    nb: Vec<u32>,
    /// Squared coordinate differences e_t of the current pair.
    e: Vec<f64>,
    /// Squared distance of the current pair in the current dimension, per Δn.
    d: Vec<f64>,
    /// Per-reference sums [row][Δn] (bin of the smallest ε containing the pair).
    acc: Vec<f64>,
    /// Per-reference pair counts per row (same binning).
    pairs: Vec<u32>,
    /// Per-reference counts of pairs at distance exactly 0, [row][Δn]; kept only for the
    /// dimension slots flagged in `zero_slot` (pairs with a repeated value: rare).
    zeros: Vec<u32>,
    /// Whether a pair of the current reference had an exactly repeated value, per slot.
    zero_slot: Vec<bool>,
    /// Smallest ε bin of each dimension slot touched by the current reference.
    first_bin: Vec<usize>,
    /// The RMS (TISEAN) path's buffers.
    grouped: Grouped,
}

/// Buffers of the RMS path ([`reference_rms`]). With the TISEAN definition the per-reference
/// sum over neighbours of `‖y_{i+Δn} − y_{j+Δn}‖²_m = Σ_{k<m} e_{Δn+kτ}` is linear in the
/// pair's `e`, so the `e` of all pairs that fall in the same ε bins in every dimension (the
/// same "bin pattern") are summed first — one pass over `e` per pair — and the patterns are
/// then spread over the (m, ε) bins and shifted into distances once per reference.
struct Grouped {
    /// Length of an `e` row: `steps + (m_max−1)τ + 1`.
    width: usize,
    /// Bin pattern code → group number + 1 (0: not seen for this reference). Empty when the
    /// code space `(n_eps+1)^n_dims` is too large; then every pair is spread on its own.
    table: Vec<u32>,
    /// Codes in use (to reset `table`).
    codes: Vec<usize>,
    /// ε bin of each group in each dimension slot (`n_eps`: not a neighbour), [group][slot].
    bins: Vec<u16>,
    /// Largest dimension of each group (its `e` rows are `steps + (m_top−1)τ + 1` long).
    m_top: Vec<usize>,
    /// Pairs in each group.
    npairs: Vec<u32>,
    /// Σ e over the pairs of each group, [group][width].
    sum: Vec<f64>,
    /// Σ e over the pairs of each (slot, ε) bin, [row][width] (rows as `acc`).
    bsum: Vec<f64>,
    /// Rows of `bsum` in use.
    touched: Vec<bool>,
}

/// Largest bin-pattern table (entries) of the RMS path.
const MAX_PATTERN_TABLE: usize = 1 << 16;

fn run<const K: usize>(job: &Job) -> Result<Totals, AnalysisError> {
    let tau = job.opts.tau;
    let s = job.s;
    let pts: Vec<[f64; K]> = (0..job.n_cand)
        .map(|i| std::array::from_fn(|k| s[i + k * tau]))
        .collect();
    let tree: ImmutableKdTree<f64, K> = ImmutableKdTree::new_from_slice(&pts)
        .map_err(|e| AnalysisError::NoResult(format!("kd-tree construction failed: {e:?}")))?;
    let n_chunks = job.n_ref.div_ceil(CHUNK);
    let partials: Vec<Totals> = (0..n_chunks)
        .into_par_iter()
        .map(|c| {
            chunk::<K>(
                job,
                &tree,
                &pts,
                c * CHUNK..((c + 1) * CHUNK).min(job.n_ref),
            )
        })
        .collect();
    let mut totals = Totals::new(job.total_len());
    for p in &partials {
        totals.add(p);
    }
    Ok(totals)
}

fn chunk<const K: usize>(
    job: &Job,
    tree: &ImmutableKdTree<f64, K>,
    pts: &[[f64; K]],
    refs: std::ops::Range<usize>,
) -> Totals {
    let o = job.opts;
    let span = o.steps + (o.m_max - 1) * o.tau;
    let rows = job.n_dims() * job.eps2.len();
    let mut sc = Scratch {
        nb: Vec::with_capacity(256),
        e: vec![0.0; span + 1],
        d: vec![0.0; job.len()],
        acc: vec![0.0; job.total_len()],
        pairs: vec![0; rows],
        zeros: vec![0; job.total_len()],
        zero_slot: vec![false; job.n_dims()],
        first_bin: vec![usize::MAX; job.n_dims()],
        grouped: Grouped::new(job, span + 1),
    };
    let tisean = o.definition == KantzDefinition::TiseanRms;
    let simd = Simd::detect();
    let mut totals = Totals::new(job.total_len());
    let mut products = Products::new(rows, job.len());
    // Query radius slightly above ε_max² so that kiddo's rounding cannot drop a pair that the
    // exact test below accepts; the test below is the definition.
    let r2 = job.eps2[job.eps2.len() - 1] * (1.0 + 1e-9);
    for i in refs {
        sc.nb.clear();
        tree.query(&pts[i])
            .within::<SquaredEuclidean<f64>>(r2)
            .unsorted()
            .visit(|r| {
                let j = r.item as usize;
                if outside_theiler_window(i, j, job.theiler) {
                    sc.nb.push(r.item);
                }
            });
        if sc.nb.is_empty() {
            continue;
        }
        sc.nb.sort_unstable();
        if tisean {
            reference_rms(job, i, &mut sc, simd);
        } else {
            reference(job, i, &mut sc);
        }
        finish_reference(job, &mut sc, &mut products, &mut totals, simd);
    }
    products.fold_into(&mut totals, job.half(), job.len());
    totals
}

/// Whether every value is in [`PROD_LO`, `PROD_HI`] (no early exit: the loop vectorises).
#[inline(always)]
fn in_product_range(a: &[f64]) -> bool {
    a.iter()
        .fold(true, |ok, &v| ok & (PROD_LO..=PROD_HI).contains(&v))
}

/// `e_t = (a_t − b_t)²`; returns the number of exact zeros.
#[inline(always)]
fn squared_differences(a: &[f64], b: &[f64], e: &mut [f64]) -> usize {
    let mut zeros = 0;
    for ((e, x), y) in e.iter_mut().zip(a).zip(b) {
        let v = (x - y) * (x - y);
        *e = v;
        zeros += usize::from(v == 0.0);
    }
    zeros
}

/// `d += e` (the pair's squared distance gains one coordinate, every Δn at once).
#[inline(always)]
fn extend(d: &mut [f64], e: &[f64]) {
    for (x, y) in d.iter_mut().zip(e) {
        *x += y;
    }
}

/// `d += e` (unless `e` is empty) and `acc += d` (TISEAN: squared distances) or
/// `acc += √d` (pdamp: distances), fused.
fn extend_and_accumulate(d: &mut [f64], e: &[f64], acc: &mut [f64], tisean: bool) {
    match (e.is_empty(), tisean) {
        (true, true) => acc.iter_mut().zip(d.iter()).for_each(|(a, x)| *a += x),
        (true, false) => acc
            .iter_mut()
            .zip(d.iter())
            .for_each(|(a, x)| *a += x.sqrt()),
        (false, true) => {
            for ((x, y), a) in d.iter_mut().zip(e).zip(acc) {
                let v = *x + y;
                *x = v;
                *a += v;
            }
        }
        (false, false) => {
            for ((x, y), a) in d.iter_mut().zip(e).zip(acc) {
                let v = *x + y;
                *x = v;
                *a += v.sqrt();
            }
        }
    }
}

/// Bins the pairs of reference `i` (its neighbours are in `sc.nb`) into `sc.acc`/`sc.pairs`.
fn reference(job: &Job, i: usize, sc: &mut Scratch) {
    let o = job.opts;
    let s = job.s;
    let (tau, len) = (o.tau, job.len());
    let n_eps = job.eps2.len();
    let eps2_max = job.eps2[n_eps - 1];
    let tisean = o.definition == KantzDefinition::TiseanRms;
    sc.first_bin.fill(usize::MAX);
    sc.zero_slot.fill(false);
    for idx in 0..sc.nb.len() {
        let j = sc.nb[idx] as usize;
        // Squared distance in dimension m, extended coordinate by coordinate (TISEAN order).
        let mut d2 = 0.0;
        let mut m_top = 0;
        for k in 0..o.m_max {
            let dk = s[i + k * tau] - s[j + k * tau];
            d2 += dk * dk;
            if d2 > eps2_max {
                break;
            }
            m_top = k + 1;
        }
        if m_top < o.m_min {
            continue;
        }
        // e_t for t = 0 ..= steps + (m_top−1)τ
        let t_max = o.steps + (m_top - 1) * tau;
        let e = &mut sc.e[..=t_max];
        let has_zero = squared_differences(&s[i..=i + t_max], &s[j..=j + t_max], e) > 0;
        let e = &sc.e[..=t_max];
        sc.d.copy_from_slice(&e[..len]);
        // the same additions in the same order as a direct sum over k (bitwise equal)
        let mut d2 = e[0];
        for m in 1..=m_top {
            let off = (m - 1) * tau;
            let shifted: &[f64] = if m > 1 { &e[off..off + len] } else { &[] };
            if m > 1 {
                d2 += e[off];
            }
            if m < o.m_min {
                extend(&mut sc.d, shifted);
                continue;
            }
            // smallest ε containing this pair in dimension m
            let l0 = job.eps2.partition_point(|&e2| e2 < d2);
            if l0 >= n_eps {
                break;
            }
            let slot = m - o.m_min;
            sc.first_bin[slot] = sc.first_bin[slot].min(l0);
            let r = slot * n_eps + l0;
            sc.pairs[r] += 1;
            let acc = &mut sc.acc[r * len..(r + 1) * len];
            extend_and_accumulate(&mut sc.d, shifted, acc, tisean);
            if has_zero {
                sc.zero_slot[slot] = true;
                for (z, &dv) in sc.zeros[r * len..(r + 1) * len].iter_mut().zip(&sc.d) {
                    *z += u32::from(dv == 0.0);
                }
            }
        }
    }
}

impl Grouped {
    fn new(job: &Job, width: usize) -> Self {
        let n_eps = job.eps2.len();
        let n_dims = job.n_dims();
        let space = (n_eps + 1).checked_pow(n_dims as u32);
        let table = match space {
            Some(sp) if sp <= MAX_PATTERN_TABLE && n_eps < usize::from(u16::MAX) => vec![0; sp],
            _ => Vec::new(),
        };
        let rows = n_dims * n_eps;
        Self {
            width,
            table,
            codes: Vec::new(),
            bins: Vec::new(),
            m_top: Vec::new(),
            npairs: Vec::new(),
            sum: Vec::new(),
            bsum: vec![0.0; rows * width],
            touched: vec![false; rows],
        }
    }

    /// Adds `e` (length `steps + (m_top−1)τ + 1`) of `pairs` pairs with the bin pattern
    /// `bins` (one entry per slot, `n_eps` = absent) to the (slot, ε) sums.
    #[inline(always)]
    fn spread(
        &mut self,
        job: &Job,
        bins: &[u16],
        m_top: usize,
        e: &[f64],
        pairs: u32,
        sc: &mut SpreadTarget,
    ) {
        let (o, n_eps) = (job.opts, job.eps2.len());
        for (slot, &l) in bins.iter().enumerate() {
            let m = o.m_min + slot;
            if m > m_top || usize::from(l) >= n_eps {
                break;
            }
            let l = usize::from(l);
            let r = slot * n_eps + l;
            let n = o.steps + (m - 1) * o.tau + 1;
            extend(&mut self.bsum[r * self.width..r * self.width + n], &e[..n]);
            self.touched[r] = true;
            sc.pairs[r] += pairs;
            sc.first_bin[slot] = sc.first_bin[slot].min(l);
        }
    }
}

/// The parts of [`Scratch`] that [`Grouped::spread`] updates.
struct SpreadTarget<'a> {
    pairs: &'a mut [u32],
    first_bin: &'a mut [usize],
}

/// `g += (a − b)²` elementwise; returns the number of exact zeros of `a − b` if `count`
/// (else 0: the caller knows there are none).
#[inline(always)]
fn accumulate_squared_differences(a: &[f64], b: &[f64], g: &mut [f64], count: bool) -> usize {
    if !count {
        for ((g, x), y) in g.iter_mut().zip(a).zip(b) {
            let v = x - y;
            *g += v * v;
        }
        return 0;
    }
    let mut zeros = 0;
    for ((g, x), y) in g.iter_mut().zip(a).zip(b) {
        let v = (x - y) * (x - y);
        *g += v;
        zeros += usize::from(v == 0.0);
    }
    zeros
}

/// [`reference`] for the TISEAN (RMS) definition: the same bins and sums, but each pair's
/// `e` is added once into the sum of its bin pattern ([`Grouped`]) instead of once per
/// dimension, and the shifted sums `Σ_{k<m} e_{Δn+kτ}` are formed once per (m, ε) bin.
/// Exactly the same pairs and counts as [`reference`]; the sums differ only in the order of
/// the additions (rounding, ~1e-16 relative).
fn reference_rms(job: &Job, i: usize, sc: &mut Scratch, simd: Simd) {
    match simd {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`) that this processor has AVX2.
        Simd::Avx2(_) => unsafe { reference_rms_avx2(job, i, sc) },
        Simd::Baseline => reference_rms_impl(job, i, sc),
    }
}

/// [`reference_rms_impl`] compiled for AVX2 (4 f64 lanes; no FMA, so the sums are bitwise
/// those of the baseline build).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn reference_rms_avx2(job: &Job, i: usize, sc: &mut Scratch) {
    reference_rms_impl(job, i, sc);
}

#[inline(always)]
fn reference_rms_impl(job: &Job, i: usize, sc: &mut Scratch) {
    let o = job.opts;
    let s = job.s;
    let (tau, len) = (o.tau, job.len());
    let n_eps = job.eps2.len();
    let n_dims = job.n_dims();
    let eps2_max = job.eps2[n_eps - 1];
    let g = &mut sc.grouped;
    let width = g.width;
    sc.first_bin.fill(usize::MAX);
    sc.zero_slot.fill(false);
    let mut bins = [0u16; MAX_DIMENSION];
    let use_table = !g.table.is_empty();
    for idx in 0..sc.nb.len() {
        let j = sc.nb[idx] as usize;
        // Squared distance in dimension m, extended coordinate by coordinate (TISEAN order),
        // and the pair's ε bin in each dimension slot.
        let mut d2 = 0.0;
        let mut m_top = 0;
        let mut code = 0usize;
        let mut weight = 1usize;
        for k in 0..o.m_max {
            let dk = s[i + k * tau] - s[j + k * tau];
            d2 += dk * dk;
            if d2 > eps2_max {
                break;
            }
            m_top = k + 1;
            if m_top >= o.m_min {
                let l = job.eps2.partition_point(|&e2| e2 < d2);
                bins[m_top - o.m_min] = l as u16;
                code += l * weight;
                weight *= n_eps + 1;
            }
        }
        if m_top < o.m_min {
            continue;
        }
        for b in &mut bins[m_top + 1 - o.m_min..n_dims] {
            *b = n_eps as u16;
            code += n_eps * weight;
            weight *= n_eps + 1;
        }
        let t_max = o.steps + (m_top - 1) * tau;
        let (a, b) = (&s[i..=i + t_max], &s[j..=j + t_max]);
        let zeros = if use_table {
            let slot = &mut g.table[code];
            if *slot == 0 {
                g.codes.push(code);
                g.bins.extend_from_slice(&bins[..n_dims]);
                g.m_top.push(m_top);
                g.npairs.push(0);
                g.sum.resize(g.sum.len() + width, 0.0);
                *slot = g.npairs.len() as u32;
            }
            let grp = *slot as usize - 1;
            g.npairs[grp] += 1;
            let row = &mut g.sum[grp * width..grp * width + t_max + 1];
            accumulate_squared_differences(a, b, row, !job.distinct)
        } else {
            let e = &mut sc.e[..=t_max];
            let z = squared_differences(a, b, e);
            let mut target = SpreadTarget {
                pairs: &mut sc.pairs,
                first_bin: &mut sc.first_bin,
            };
            g.spread(job, &bins[..n_dims], m_top, e, 1, &mut target);
            z
        };
        if zeros > 0 {
            // rare: a repeated value; count the Δn at which the pair's distance is exactly 0
            let e = &mut sc.e[..=t_max];
            squared_differences(a, b, e);
            sc.d.copy_from_slice(&e[..len]);
            for m in 1..=m_top {
                let off = (m - 1) * tau;
                if m > 1 {
                    extend(&mut sc.d, &e[off..off + len]);
                }
                if m < o.m_min {
                    continue;
                }
                let slot = m - o.m_min;
                let r = slot * n_eps + usize::from(bins[slot]);
                sc.zero_slot[slot] = true;
                for (z, &dv) in sc.zeros[r * len..(r + 1) * len].iter_mut().zip(&sc.d) {
                    *z += u32::from(dv == 0.0);
                }
            }
        }
    }
    // spread the groups over the (slot, ε) bins, in the order they were first seen
    if use_table {
        let mut target = SpreadTarget {
            pairs: &mut sc.pairs,
            first_bin: &mut sc.first_bin,
        };
        let gsum = std::mem::take(&mut g.sum);
        let gbins = std::mem::take(&mut g.bins);
        for grp in 0..g.npairs.len() {
            let m_top = g.m_top[grp];
            let n = o.steps + (m_top - 1) * tau + 1;
            g.spread(
                job,
                &gbins[grp * n_dims..(grp + 1) * n_dims],
                m_top,
                &gsum[grp * width..grp * width + n],
                g.npairs[grp],
                &mut target,
            );
        }
        g.sum = gsum;
        g.bins = gbins;
        for &c in &g.codes {
            g.table[c] = 0;
        }
        g.codes.clear();
        g.bins.clear();
        g.m_top.clear();
        g.npairs.clear();
        g.sum.clear();
    }
    // per (slot, ε) bin: Σ over its pairs of ‖·‖²_m at every Δn = Σ_{k<m} bsum_{Δn+kτ}
    for slot in 0..n_dims {
        let m = o.m_min + slot;
        for l in 0..n_eps {
            let r = slot * n_eps + l;
            if !g.touched[r] {
                continue;
            }
            g.touched[r] = false;
            let n = o.steps + (m - 1) * tau + 1;
            let row = &mut g.bsum[r * width..r * width + n];
            let acc = &mut sc.acc[r * len..(r + 1) * len];
            acc.copy_from_slice(&row[..len]);
            for k in 1..m {
                extend(acc, &row[k * tau..k * tau + len]);
            }
            row.fill(0.0);
        }
    }
}

/// Accumulates the bins of the current reference over increasing ε and adds its
/// `ln(sum/count)` terms (through `products`, or directly), then clears the scratch rows.
fn finish_reference(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
    simd: Simd,
) {
    match simd {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`) that this processor has AVX2.
        Simd::Avx2(_) => unsafe { finish_reference_avx2(job, sc, products, totals) },
        Simd::Baseline => finish_reference_impl(job, sc, products, totals),
    }
}

/// [`finish_reference_impl`] compiled for AVX2 (no FMA: bitwise the baseline's results).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn finish_reference_avx2(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
) {
    finish_reference_impl(job, sc, products, totals);
}

#[inline(always)]
fn finish_reference_impl(
    job: &Job,
    sc: &mut Scratch,
    products: &mut Products,
    totals: &mut Totals,
) {
    let len = job.len();
    let n_eps = job.eps2.len();
    let half = job.half();
    for slot in 0..job.n_dims() {
        let l_first = sc.first_bin[slot];
        if l_first == usize::MAX {
            continue;
        }
        let zero = sc.zero_slot[slot];
        let mut c = 0u32;
        for l in l_first..n_eps {
            let r = slot * n_eps + l;
            let row = r * len;
            c += sc.pairs[r];
            if l > l_first {
                let (lo, hi) = sc.acc.split_at_mut(row);
                extend(&mut hi[..len], &lo[row - len..]);
                if zero {
                    let (lo, hi) = sc.zeros.split_at_mut(row);
                    for (h, p) in hi[..len].iter_mut().zip(&lo[row - len..]) {
                        *h += p;
                    }
                }
            }
            let a = &sc.acc[row..row + len];
            let (lyap, count) = (
                &mut totals.lyap[row..row + len],
                &mut totals.count[row..row + len],
            );
            if zero {
                // exact per-Δn counts: pairs at distance 0 are skipped at that Δn
                for (t, (&z, &at)) in sc.zeros[row..row + len].iter().zip(a).enumerate() {
                    let ct = c - z;
                    if ct > 0 {
                        lyap[t] += half * (at / f64::from(ct)).ln();
                        count[t] += 1;
                    }
                }
            } else if in_product_range(a) {
                products.multiply(r, a, c);
            } else {
                for (t, &at) in a.iter().enumerate() {
                    lyap[t] += half * (at / f64::from(c)).ln();
                    count[t] += 1;
                }
            }
        }
        for l in l_first..n_eps {
            let r = slot * n_eps + l;
            sc.acc[r * len..(r + 1) * len].fill(0.0);
            sc.pairs[r] = 0;
            if zero {
                sc.zeros[r * len..(r + 1) * len].fill(0);
            }
        }
    }
}

fn assemble(job: &Job, eps: &[f64], range: f64, totals: Totals) -> KantzResult {
    let o = job.opts;
    let mut curves = Vec::with_capacity(eps.len() * job.n_dims());
    for (l, &e) in eps.iter().enumerate() {
        for m in o.m_min..=o.m_max {
            let row = job.row(m - o.m_min, l);
            let count = totals.count[row..row + job.len()].to_vec();
            let s = (0..job.len())
                .map(|t| (count[t] > 0).then(|| totals.lyap[row + t] / count[t] as f64))
                .collect();
            curves.push(KantzCurve {
                m,
                eps: e * range,
                s,
                count,
            });
        }
    }
    KantzResult {
        curves,
        range,
        definition: o.definition,
    }
}

/// A straight-line fit `S ≈ intercept + slope·Δn` over `start..=end`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlopeFit {
    /// First Δn of the fitted window (samples).
    pub start: usize,
    /// Last Δn of the fitted window (samples, inclusive).
    pub end: usize,
    /// Slope: the exponent per sample.
    pub slope: f64,
    /// Intercept (rescaled log units).
    pub intercept: f64,
    /// Coefficient of determination R² of the fit.
    pub r2: f64,
    /// Whether the window met the linearity criterion (R² ≥ `r2_min`); if false the fit is a
    /// fallback over the whole curve and the slope should not be trusted.
    pub linear: bool,
}

/// Settings of the scaling-region finder [`fit_scaling_region`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScalingOptions {
    /// Shortest window, in points (at least 6). Default 6.
    pub min_len: usize,
    /// Minimum R² for a window to count as linear. Default 0.99.
    pub r2_min: f64,
    /// Largest relative difference between the slopes of the window's first and last thirds,
    /// `|s₁ − s₂| ≤ tol·|s|`. Default 0.2.
    pub slope_tolerance: f64,
}

impl Default for ScalingOptions {
    fn default() -> Self {
        Self {
            min_len: 6,
            r2_min: 0.99,
            slope_tolerance: 0.2,
        }
    }
}

/// Finds the linear part of a curve S(Δn) and fits its slope.
///
/// # Formula
/// Every window `[a, b]` of at least `min_len` defined points is fitted by least squares.
/// A window is linear if `R² ≥ r2_min` and the slopes `s₁`, `s₂` fitted to its first and
/// last thirds agree, `|s₁ − s₂| ≤ slope_tolerance·|s|` (a window that bends into saturation fails this
/// even when its R² is high). Among linear windows the longest is chosen (ties: higher R²).
/// If no window qualifies, the whole curve is fitted and `linear = false`.
///
/// # Parameters
/// [`ScalingOptions`]: `min_len = 6`, `r2_min = 0.99`, `slope_tolerance = 0.2`.
///
/// # Pitfalls
/// A curve that bends slowly into saturation can keep R² above the threshold over a window
/// that includes the bend, which lowers the slope; inspect the curve when in doubt.
pub fn fit_scaling_region(s: &[Option<f64>], opts: &ScalingOptions) -> Option<SlopeFit> {
    let pts: Vec<(f64, f64)> = s
        .iter()
        .enumerate()
        .filter_map(|(t, v)| v.map(|v| (t as f64, v)))
        .collect();
    let n = pts.len();
    if n < 2 {
        return None;
    }
    // prefix sums of x, y, xx, xy, yy
    let mut pre = vec![[0.0f64; 5]; n + 1];
    for (k, &(x, y)) in pts.iter().enumerate() {
        let p = pre[k];
        pre[k + 1] = [p[0] + x, p[1] + y, p[2] + x * x, p[3] + x * y, p[4] + y * y];
    }
    let fit = |a: usize, b: usize| -> (f64, f64, f64) {
        let c = (b - a + 1) as f64;
        let d: Vec<f64> = (0..5).map(|q| pre[b + 1][q] - pre[a][q]).collect();
        let sxx = d[2] - d[0] * d[0] / c;
        let sxy = d[3] - d[0] * d[1] / c;
        let syy = d[4] - d[1] * d[1] / c;
        let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
        let intercept = (d[1] - slope * d[0]) / c;
        let r2 = if syy > 0.0 && sxx > 0.0 {
            (sxy * sxy / (sxx * syy)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (slope, intercept, r2)
    };
    let min_len = opts.min_len.max(6).min(n);
    let mut best: Option<(usize, f64, usize, usize)> = None;
    for a in 0..=n - min_len {
        for b in a + min_len - 1..n {
            let (slope, _, r2) = fit(a, b);
            if r2 < opts.r2_min {
                continue;
            }
            // first and last thirds must have the same slope (rejects windows that bend)
            let third = (b - a) / 3;
            let (s1, s2) = (fit(a, a + third).0, fit(b - third, b).0);
            if (s1 - s2).abs() > opts.slope_tolerance * slope.abs() {
                continue;
            }
            let len = b - a + 1;
            let better = match best {
                None => true,
                Some((bl, br2, _, _)) => len > bl || (len == bl && r2 > br2),
            };
            if better {
                best = Some((len, r2, a, b));
            }
        }
    }
    let (a, b, linear) = match best {
        Some((_, _, a, b)) => (a, b, true),
        None => (0, n - 1, false),
    };
    let (slope, intercept, r2) = fit(a, b);
    Some(SlopeFit {
        start: pts[a].0 as usize,
        end: pts[b].0 as usize,
        slope,
        intercept,
        r2,
        linear,
    })
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
