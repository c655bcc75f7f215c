//! The pair counting behind [`correlation_sum`](super::correlation_sum): a histogram of
//! maximum-norm pair distances per embedding dimension over the bins of the radii ε_l (data
//! units), found without logarithms ([`BinTable`]); a sorted-value sweep for m = 1 and a
//! box-assisted grid search for m ≥ 2, in fixed chunks of reference points (rayon; integer
//! counts, so the result does not depend on the thread count).

use rayon::prelude::*;

use super::options::D2Options;
use crate::analysis::min_max;

/// Reference points per parallel work unit (fixed, so that results do not depend on threads).
const CHUNK: usize = 2048;

/// Exact bin lookup without logarithms: `bin(d)` = the smallest l with `d ≤ ε_l`.
///
/// For positive f64, `bits >> shift` is monotone in the value; `table[key − key0]` is the
/// smallest l whose ε_l is at least the smallest value with that key, so the answer is at
/// most a few steps above it.
pub(super) struct BinTable {
    eps: Vec<f64>,
    shift: u32,
    key0: u64,
    table: Vec<u32>,
    /// Whether one comparison corrects every table entry (buckets finer than the ε spacing):
    /// then [`BinTable::bin`] has no data-dependent branch.
    one_step: bool,
}

impl BinTable {
    pub(super) fn new(eps: &[f64]) -> Self {
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
    pub(super) fn bin(&self, d: f64) -> usize {
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

pub(super) struct Job<'a> {
    pub(super) s: &'a [f64],
    pub(super) lo: f64,
    pub(super) opts: &'a D2Options,
    pub(super) vectors: usize,
    pub(super) eps_max: f64,
    pub(super) bins: &'a BinTable,
}

/// m = 1: sweep over the values sorted by size; pairs closer than ε_max are contiguous.
pub(super) fn count_one_dimensional(job: &Job) -> Vec<u64> {
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
pub(super) fn count_grid(job: &Job) -> Vec<u64> {
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
