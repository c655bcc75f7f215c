//! The exact nearest neighbour in the maximum norm by a box-assisted search (as TISEAN's):
//! the grid of candidates on two delay coordinates, and the ring-by-ring scan of its cells
//! within a shrinking bound (rescaled units).

use crate::analysis::outside_theiler_window;

/// Everything fixed across dimensions.
pub(super) struct Setup<'a> {
    pub(super) s: &'a [f64],
    /// Spacing of the vectors' coordinates ([`FnnOptions::stride`]).
    pub(super) tau: usize,
    pub(super) n_ref: usize,
    pub(super) n_cand: usize,
    pub(super) theiler: usize,
    pub(super) ratio: f64,
    pub(super) max_dist: f64,
    pub(super) range: f64,
}

/// Marks "no neighbour found" in the neighbour lists.
pub(super) const NONE: u32 = u32::MAX;

/// Box-assisted search structure (as TISEAN's): the candidates sorted by the cell of their
/// first and last coordinates `(s_j, s_{j+(m−1)τ})` on a `g1 × g2` grid over [0, 1]² (the
/// first coordinate only, `g2 = 1`, for m = 1), column-major, so that the cells of one
/// column form one contiguous run. Those two coordinates are stored in that order (the box
/// test reads them contiguously); the others are read from the series when a candidate
/// passes it. Its buffers are reused from one dimension to the next.
#[derive(Default)]
pub(super) struct Grid {
    g1: usize,
    g2: usize,
    /// `start[c]..start[c + 1]`: the candidates of cell `c = cx·g2 + cy`.
    start: Vec<u32>,
    /// `(s_j, s_{j+(m−1)τ})` of the candidates, in cell order.
    ends: Vec<[f64; 2]>,
    /// Index j of each of them.
    pub(super) index: Vec<u32>,
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
    pub(super) fn build(&mut self, setup: &Setup, m: usize) {
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
pub(super) fn nearest<const K: usize>(
    grid: &Grid,
    setup: &Setup,
    n: usize,
    seed: u32,
) -> Option<(u32, f64)> {
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
