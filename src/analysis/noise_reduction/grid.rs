//! The neighbour search of [`super::nonlinear_noise_reduction`]: the delay vectors filed by
//! grid cells of their first and last coordinates, and the branch-free scan that sums each
//! neighbourhood's coordinates (maximum norm, ≤ ε as TISEAN).

use crate::analysis::min_max;

/// Cells per ε along each grid axis: a query scans 2·SUB + 1 cells per axis, a strip of
/// (2 + 1/SUB)·ε instead of TISEAN's 3ε (fewer candidates, same neighbours).
const SUB: i64 = 4;
/// Most cells of a grid (4 M u32 offsets = 16 MB); above, fewer cells per ε are used.
const MAX_CELLS: usize = 1 << 22;
/// Lanes of the neighbour kernel (AVX2 holds 4 f64; two vectors per lane group).
pub(super) const LANES: usize = 8;

/// Delay vectors `v_n` (n = span..N−1) filed by the cells of their first and last coordinates,
/// `⌊(x_n − min)·SUB/ε⌋` and `⌊(x_{n−(m−1)τ} − min)·SUB/ε⌋`, and stored in cell order
/// (row-major), one array per coordinate: the cells a query scans are `2·SUB + 1` contiguous
/// runs of slots, read in lanes without branches.
#[derive(Debug, Default)]
pub(super) struct CellTable {
    pub(super) m: usize,
    pub(super) delay: usize,
    eps: f64,
    /// Cells per data unit (SUB/ε or 1/ε).
    inv: f64,
    /// Cells a query scans on each side of its own.
    reach: i64,
    lo: f64,
    rows: usize,
    cols: usize,
    /// The grid is folded (cell indices modulo rows and cols).
    wrapped: bool,
    /// Slots of cell c: `start[c]..start[c + 1]`.
    start: Vec<u32>,
    /// Coordinate k of slot s at `coords[k * len + s]`.
    coords: Vec<f64>,
    len: usize,
}

impl CellTable {
    pub(super) fn build(&mut self, x: &[f64], m: usize, delay: usize, eps: f64, span: usize) {
        let (lo, hi) = min_max(x);
        let mut reach = SUB;
        let mut inv = SUB as f64 / eps;
        let mut side = ((hi - lo) * inv).floor() as usize + 1;
        while reach > 1 && side.saturating_mul(side) > MAX_CELLS {
            reach -= 1;
            inv = reach as f64 / eps;
            side = ((hi - lo) * inv).floor() as usize + 1;
        }
        // a tiny ε over a wide range: fold the grid onto MAX_CELLS cells (wrapped cells only
        // add candidates that the distance test rejects)
        let wrapped = side.saturating_mul(side) > MAX_CELLS;
        let (rows, cols) = if wrapped {
            let s = MAX_CELLS.isqrt();
            (s, s)
        } else {
            (side, side)
        };
        let len = x.len() - span;
        self.m = m;
        self.delay = delay;
        self.wrapped = wrapped;
        self.eps = eps;
        self.inv = inv;
        self.reach = reach;
        self.lo = lo;
        self.rows = rows;
        self.cols = cols;
        self.len = len;
        let back = (m - 1) * delay;
        let cell = |v: usize| -> usize {
            let i = (((x[v] - lo) * inv) as usize) % rows;
            let j = (((x[v - back] - lo) * inv) as usize) % cols;
            i * cols + j
        };
        // counting sort of the vectors by cell
        self.start.clear();
        self.start.resize(rows * cols + 1, 0);
        for v in span..x.len() {
            self.start[cell(v) + 1] += 1;
        }
        for c in 0..rows * cols {
            self.start[c + 1] += self.start[c];
        }
        let mut fill: Vec<u32> = self.start[..rows * cols].to_vec();
        self.coords.clear();
        self.coords.resize(m * len, 0.0);
        for v in span..x.len() {
            let c = cell(v);
            let s = fill[c] as usize;
            fill[c] += 1;
            for k in 0..m {
                self.coords[k * len + s] = x[v - k * delay];
            }
        }
    }

    /// Slot ranges of the cells within reach of the vector `q` (first and last coordinates),
    /// each row's cells being contiguous; calls `f(lo, hi)` per row.
    #[inline]
    pub(super) fn runs(&self, first: f64, last: f64, mut f: impl FnMut(usize, usize)) {
        let ci = ((first - self.lo) * self.inv) as i64;
        let cj = ((last - self.lo) * self.inv) as i64;
        let wrapped = self.wrapped;
        for di in -self.reach..=self.reach {
            let i = ci + di;
            if !wrapped && (i < 0 || i >= self.rows as i64) {
                continue;
            }
            let i = i.rem_euclid(self.rows as i64) as usize;
            let (j0, j1) = (cj - self.reach, cj + self.reach);
            if !wrapped {
                let j0 = j0.max(0) as usize;
                let j1 = (j1.min(self.cols as i64 - 1)) as usize;
                f(
                    self.start[i * self.cols + j0] as usize,
                    self.start[i * self.cols + j1 + 1] as usize,
                );
            } else {
                for j in j0..=j1 {
                    let j = j.rem_euclid(self.cols as i64) as usize;
                    f(
                        self.start[i * self.cols + j] as usize,
                        self.start[i * self.cols + j + 1] as usize,
                    );
                }
            }
        }
    }
}

#[derive(Debug, Clone, Copy)]
pub(super) enum Simd {
    #[cfg(target_arch = "x86_64")]
    Avx512,
    #[cfg(target_arch = "x86_64")]
    Avx2,
    Baseline,
}

impl Simd {
    pub(super) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f") {
            return Simd::Avx512;
        }
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            return Simd::Avx2;
        }
        Simd::Baseline
    }

    /// Adds to `acc` (m × LANES) the coordinates of the slots lo..hi within ε of `q`; returns
    /// how many there were.
    #[inline]
    pub(super) fn scan(
        self,
        t: &CellTable,
        q: &[f64],
        lo: usize,
        hi: usize,
        acc: &mut [f64],
    ) -> u64 {
        match self {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `Simd::Avx512` is only constructed after
            // `is_x86_feature_detected!("avx512f")`.
            Simd::Avx512 => unsafe { scan_avx512(t, q, lo, hi, acc) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `Simd::Avx2` is only constructed after `is_x86_feature_detected!("avx2")`.
            Simd::Avx2 => unsafe { scan_avx2(t, q, lo, hi, acc) },
            Simd::Baseline => scan_impl(t, q, lo, hi, acc),
        }
    }
}

/// [`scan_impl`] compiled for AVX-512 (a lane group of 8 f64 in one register; no FMA: the same
/// sums as the baseline build).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn scan_avx512(t: &CellTable, q: &[f64], lo: usize, hi: usize, acc: &mut [f64]) -> u64 {
    scan_impl(t, q, lo, hi, acc)
}

/// [`scan_impl`] compiled for AVX2 (no FMA: the same sums as the baseline build).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn scan_avx2(t: &CellTable, q: &[f64], lo: usize, hi: usize, acc: &mut [f64]) -> u64 {
    scan_impl(t, q, lo, hi, acc)
}

/// The neighbour scan for the dimension m: [`scan_fixed`] for m ≤ 10 (coordinates and
/// accumulators in registers), [`scan_any`] above.
#[inline(always)]
fn scan_impl(t: &CellTable, q: &[f64], lo: usize, hi: usize, acc: &mut [f64]) -> u64 {
    macro_rules! fixed {
        ($($m:literal),*) => {
            match t.m {
                $($m => scan_fixed::<$m>(t, q, lo, hi, acc),)*
                _ => scan_any(t, q, lo, hi, acc),
            }
        };
    }
    fixed!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10)
}

/// [`scan_any`] for a dimension M known at compile time: each full lane group's M coordinates
/// are read once, kept while the weights are formed and then added with their weights (0 or
/// 1; adding 0·c leaves a sum unchanged, since no sum is ever −0), the sums held in registers
/// over the run. The same sums in the same order as [`scan_any`].
#[inline(always)]
fn scan_fixed<const M: usize>(
    t: &CellTable,
    q: &[f64],
    lo: usize,
    hi: usize,
    acc: &mut [f64],
) -> u64 {
    let (len, eps) = (t.len, t.eps);
    let q: [f64; M] = std::array::from_fn(|k| q[k]);
    let mut sums: [[f64; LANES]; M] =
        std::array::from_fn(|k| acc[k * LANES..(k + 1) * LANES].try_into().expect("LANES"));
    let mut hits = [0.0f64; LANES];
    let mut s = lo;
    while s + LANES <= hi {
        let c: [[f64; LANES]; M] = std::array::from_fn(|k| {
            t.coords[k * len + s..k * len + s + LANES]
                .try_into()
                .expect("LANES")
        });
        let mut w = [1.0f64; LANES];
        for k in 0..M {
            for l in 0..LANES {
                if (c[k][l] - q[k]).abs() > eps {
                    w[l] = 0.0;
                }
            }
        }
        for l in 0..LANES {
            hits[l] += w[l];
        }
        for k in 0..M {
            for l in 0..LANES {
                sums[k][l] += w[l] * c[k][l];
            }
        }
        s += LANES;
    }
    for k in 0..M {
        acc[k * LANES..(k + 1) * LANES].copy_from_slice(&sums[k]);
    }
    let mut count = 0u64;
    for h in hits {
        count += h as u64;
    }
    count + scan_any(t, &q, s, hi, acc)
}

/// Branch-free neighbour test and sums over lanes of LANES slots: a slot's weight is 1 when
/// every coordinate is within ε (maximum norm, ≤ as TISEAN), else 0; each lane sums its own
/// slots (a fixed order, whatever the thread count).
#[inline(always)]
fn scan_any(t: &CellTable, q: &[f64], lo: usize, hi: usize, acc: &mut [f64]) -> u64 {
    let (m, len, eps) = (t.m, t.len, t.eps);
    let mut count = 0u64;
    let mut s = lo;
    let mut w = [0.0f64; LANES];
    while s < hi {
        let n = (hi - s).min(LANES);
        // weights: all coordinates within ε
        w.iter_mut().for_each(|v| *v = 1.0);
        for (k, &qk) in q.iter().enumerate() {
            let c = &t.coords[k * len + s..k * len + s + n];
            for (wl, &cl) in w.iter_mut().zip(c) {
                if (cl - qk).abs() > eps {
                    *wl = 0.0;
                }
            }
        }
        for wl in &mut w[n..] {
            *wl = 0.0;
        }
        if n == LANES {
            let mut hit = 0.0;
            for &wl in &w {
                hit += wl;
            }
            if hit > 0.0 {
                count += hit as u64;
                for k in 0..m {
                    let c = &t.coords[k * len + s..k * len + s + LANES];
                    let a = &mut acc[k * LANES..(k + 1) * LANES];
                    for l in 0..LANES {
                        a[l] += w[l] * c[l];
                    }
                }
            }
        } else {
            for l in 0..n {
                if w[l] > 0.0 {
                    count += 1;
                    for k in 0..m {
                        acc[k * LANES + l] += t.coords[k * len + s + l];
                    }
                }
            }
        }
        s += n;
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_dimension_kernel_equals_the_general_one() {
        // same counts and bitwise the same lane sums over every run of every query
        let x: Vec<f64> = (0..3000)
            .map(|i| (i as f64 * 0.05).sin() + 0.3 * (i as f64 * 0.131).cos())
            .collect();
        for (m, eps) in [(1, 0.05), (4, 0.2), (7, 0.3)] {
            let span = m - 1;
            let mut t = CellTable::default();
            t.build(&x, m, 1, eps, span);
            for v in (span..x.len()).step_by(7) {
                let q: Vec<f64> = (0..m).map(|k| x[v - k]).collect();
                let (mut a, mut b) = (vec![0.0; m * LANES], vec![0.0; m * LANES]);
                let (mut ca, mut cb) = (0, 0);
                t.runs(q[0], q[m - 1], |lo, hi| {
                    ca += scan_impl(&t, &q, lo, hi, &mut a);
                    cb += scan_any(&t, &q, lo, hi, &mut b);
                });
                assert_eq!(ca, cb, "m = {m}, vector {v}");
                let bits = |s: &[f64]| s.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&a), bits(&b), "m = {m}, vector {v}");
                assert!(ca >= 1);
            }
        }
    }
}
