//! The data of a Kantz run shared by both paths of the kernel: the fixed inputs ([`Job`]),
//! the per-worker scratch buffers ([`Scratch`]) and the RMS path's bin-pattern groups
//! ([`Grouped`]) with their spreading over the (m, ε) bins; squared coordinate differences
//! e_t in rescaled units².

use super::arith::*;
use super::options::{KantzDefinition, KantzOptions};

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
    pub(super) fn n_dims(&self) -> usize {
        self.opts.m_max - self.opts.m_min + 1
    }
    pub(super) fn len(&self) -> usize {
        self.opts.steps + 1
    }
    /// Index of (dimension slot, eps) rows in the flat arrays.
    pub(super) fn row(&self, dim_slot: usize, l: usize) -> usize {
        (dim_slot * self.eps2.len() + l) * self.len()
    }
    pub(super) fn total_len(&self) -> usize {
        self.n_dims() * self.eps2.len() * self.len()
    }
    /// Factor of the logarithm: ½ for TISEAN's log of the RMS distance, 1 otherwise.
    pub(super) fn half(&self) -> f64 {
        if self.opts.definition == KantzDefinition::TiseanRms {
            0.5
        } else {
            1.0
        }
    }
}

/// Per-worker scratch buffers, allocated once per chunk.
pub(super) struct Scratch {
    /// Neighbour indices of the current reference.
    pub(super) nb: Vec<u32>,
    /// Squared coordinate differences e_t of the current pair.
    pub(super) e: Vec<f64>,
    /// Squared distance of the current pair in the current dimension, per Δn.
    pub(super) d: Vec<f64>,
    /// Per-reference sums [row][Δn] (bin of the smallest ε containing the pair).
    pub(super) acc: Vec<f64>,
    /// Per-reference pair counts per row (same binning).
    pub(super) pairs: Vec<u32>,
    /// Per-reference counts of pairs at distance exactly 0, [row][Δn]; kept only for the
    /// dimension slots flagged in `zero_slot` (pairs with a repeated value: rare).
    pub(super) zeros: Vec<u32>,
    /// Whether a pair of the current reference had an exactly repeated value, per slot.
    pub(super) zero_slot: Vec<bool>,
    /// Smallest ε bin of each dimension slot touched by the current reference.
    pub(super) first_bin: Vec<usize>,
    /// The RMS (TISEAN) path's buffers.
    pub(super) grouped: Grouped,
}

/// Buffers of the RMS path ([`reference_rms`]). With the TISEAN definition the per-reference
/// sum over neighbours of `‖y_{i+Δn} − y_{j+Δn}‖²_m = Σ_{k<m} e_{Δn+kτ}` is linear in the
/// pair's `e`, so the `e` of all pairs that fall in the same ε bins in every dimension (the
/// same "bin pattern") are summed first — one pass over the row per four pairs
/// ([`Grouped::accumulate`]) — and the patterns are then spread over the (m, ε) bins and shifted
/// into distances once per reference.
pub(super) struct Grouped {
    /// Length of an `e` row: `steps + (m_max−1)τ + 1`.
    pub(super) width: usize,
    /// Bin pattern code → group number + 1 (0: not seen for this reference). Empty when the
    /// code space `(n_eps+1)^n_dims` is too large; then every pair is spread on its own.
    pub(super) table: Vec<u32>,
    /// Codes in use (to reset `table`).
    pub(super) codes: Vec<usize>,
    /// ε bin of each group in each dimension slot (`n_eps`: not a neighbour), [group][slot].
    pub(super) bins: Vec<u16>,
    /// Largest dimension of each group (its `e` rows are `steps + (m_top−1)τ + 1` long).
    pub(super) m_top: Vec<usize>,
    /// Pairs in each group.
    pub(super) npairs: Vec<u32>,
    /// Σ e over the pairs of each group, [group][width].
    pub(super) sum: Vec<f64>,
    /// Σ e over the pairs of each (slot, ε) bin, [row][width] (rows as `acc`).
    pub(super) bsum: Vec<f64>,
    /// Rows of `bsum` in use.
    pub(super) touched: Vec<bool>,
    /// The pairs of the current reference as (group, neighbour), in neighbour order, for
    /// [`Grouped::accumulate`].
    pub(super) batch: Vec<(u32, u32)>,
    /// The neighbours of `batch` ordered by group (stable: neighbour order within a group).
    by_group: Vec<u32>,
    /// Where each group's run in `by_group` ends.
    group_end: Vec<u32>,
}

/// Largest bin-pattern table (entries) of the RMS path.
const MAX_PATTERN_TABLE: usize = 1 << 16;

impl Grouped {
    pub(super) fn new(job: &Job, width: usize) -> Self {
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
            batch: Vec::with_capacity(256),
            by_group: Vec::with_capacity(256),
            group_end: Vec::new(),
        }
    }

    /// Adds `e` (length `steps + (m_top−1)τ + 1`) of `pairs` pairs with the bin pattern
    /// `bins` (one entry per slot, `n_eps` = absent) to the (slot, ε) sums.
    #[inline(always)]
    pub(super) fn spread(
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
pub(super) struct SpreadTarget<'a> {
    pub(super) pairs: &'a mut [u32],
    pub(super) first_bin: &'a mut [usize],
}

impl Grouped {
    /// Adds every batched pair's `(a − b)²` (reference `i`) into its group's row and empties
    /// the batch: the pairs of a group in neighbour order, four at a time,
    /// `g = (((g + e₁) + e₂) + e₃) + e₄` — the additions of adding them one by one, in the
    /// same order (bitwise the same sums), with one load and store of the row per four pairs
    /// instead of per pair.
    #[inline(always)]
    pub(super) fn accumulate(&mut self, job: &Job, i: usize) {
        // counting sort by group, stable: group_end[k] ends as the end of group k's run
        let n_groups = self.npairs.len();
        let group_end = &mut self.group_end;
        group_end.clear();
        group_end.resize(n_groups, 0);
        for &(grp, _) in &self.batch {
            group_end[grp as usize] += 1;
        }
        let mut start = 0;
        for c in group_end.iter_mut() {
            (*c, start) = (start, start + *c);
        }
        self.by_group.clear();
        self.by_group.resize(self.batch.len(), 0);
        for &(grp, j) in &self.batch {
            let at = &mut group_end[grp as usize];
            self.by_group[*at as usize] = j;
            *at += 1;
        }
        let (s, o, width) = (job.s, job.opts, self.width);
        for grp in 0..n_groups {
            let n = o.steps + (self.m_top[grp] - 1) * o.tau + 1;
            let row = &mut self.sum[grp * width..grp * width + n];
            let a = &s[i..i + n];
            let from = if grp == 0 {
                0
            } else {
                self.group_end[grp - 1] as usize
            };
            let js = &self.by_group[from..self.group_end[grp] as usize];
            let mut quads = js.chunks_exact(4);
            for q in &mut quads {
                let b = |k: usize| &s[q[k] as usize..q[k] as usize + n];
                let (b0, b1, b2, b3) = (b(0), b(1), b(2), b(3));
                for t in 0..n {
                    let x = a[t];
                    let (d0, d1, d2, d3) = (x - b0[t], x - b1[t], x - b2[t], x - b3[t]);
                    row[t] = (((row[t] + d0 * d0) + d1 * d1) + d2 * d2) + d3 * d3;
                }
            }
            for &j in quads.remainder() {
                accumulate_squared_differences(a, &s[j as usize..j as usize + n], row, false);
            }
        }
        self.batch.clear();
    }
}

/// `g += (a − b)²` elementwise; returns the number of exact zeros of `a − b` if `count`
/// (else 0: the caller knows there are none).
#[inline(always)]
pub(super) fn accumulate_squared_differences(
    a: &[f64],
    b: &[f64],
    g: &mut [f64],
    count: bool,
) -> usize {
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
