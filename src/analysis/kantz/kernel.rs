//! The kernel of [`super::kantz`]: neighbours from a kd-tree on the first two delay
//! coordinates, the per-pair squared coordinate differences reused for every dimension m and
//! radius ε, and the running products that take one logarithm per (m, ε, Δn) and chunk (the
//! module documentation of [`super`] explains why this is fast). References run in fixed
//! chunks in parallel and are combined in chunk order, so results do not depend on the
//! thread count.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

use super::arith::*;
use super::options::{KantzCurve, KantzDefinition, KantzOptions, KantzResult, MAX_DIMENSION};
use crate::analysis::outside_theiler_window;
use crate::error::AnalysisError;
use crate::simd::Simd;

/// References per parallel work unit (fixed, so that sums do not depend on thread count).
const CHUNK: usize = 1024;

/// Fixed inputs of a run.
pub(super) struct Job<'a> {
    pub(super) s: &'a [f64],
    pub(super) opts: &'a KantzOptions,
    /// Squared radii, increasing.
    pub(super) eps2: Vec<f64>,
    pub(super) n_cand: usize,
    pub(super) n_ref: usize,
    pub(super) theiler: usize,
    /// No two samples of the (rescaled) series are equal and no difference of two squares to 0:
    /// then no pair has `e_t = 0` and the RMS path skips looking for zeros.
    pub(super) distinct: bool,
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

pub(super) fn run<const K: usize>(job: &Job) -> Result<Totals, AnalysisError> {
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

pub(super) fn assemble(job: &Job, eps: &[f64], range: f64, totals: Totals) -> KantzResult {
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
