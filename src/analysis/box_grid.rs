//! Box-assisted fixed-radius neighbour search in delay space (TISEAN's `make_box` /
//! `find_neighbors`): delay vectors are filed into a 2-D grid of ε-sized boxes by their first
//! and last coordinates; a query scans the 3 × 3 boxes around it and keeps the vectors within
//! ε in the maximum norm over all m coordinates.

/// Most boxes per grid axis (a power of two; box indices wrap around, as TISEAN's
/// `BOX = 1024`, so any ε works with bounded memory — wrapped boxes only add candidates that
/// the exact distance test then rejects).
const MAX_BOXES: usize = 512;
/// Fewest boxes per grid axis. Any power of two ≥ 4 finds the same neighbours in the same
/// order: a vector within ε lies in one of the 3 neighbouring cells per axis, which map to
/// distinct boxes, and the accepted entries of a box keep their filing order.
const MIN_BOXES: usize = 16;
const NONE: usize = usize::MAX;

/// A grid of delay vectors `v_n = (x_n, x_{n−τ}, …, x_{n−(m−1)τ})` for a chosen set of indices
/// `n`, for fixed-radius queries in the maximum norm.
#[derive(Debug, Clone)]
pub struct BoxGrid {
    dim: usize,
    delay: usize,
    eps: f64,
    /// Boxes per axis (a power of two between `MIN_BOXES` and `MAX_BOXES`).
    boxes: usize,
    head: Vec<usize>,
    next: Vec<usize>,
}

impl BoxGrid {
    /// Files the delay vectors of the indices `refs` (each `≥ (dim−1)·delay` and `< x.len()`)
    /// for queries with radius `eps` (> 0, data units).
    pub fn new(
        x: &[f64],
        dim: usize,
        delay: usize,
        eps: f64,
        refs: impl IntoIterator<Item = usize>,
    ) -> Self {
        // about one box per vector: a short series does not pay for clearing a large grid
        let boxes = x
            .len()
            .isqrt()
            .next_power_of_two()
            .clamp(MIN_BOXES, MAX_BOXES);
        Self::with_boxes(x, dim, delay, eps, boxes, refs)
    }

    /// [`BoxGrid::new`] with `boxes` boxes per axis (a power of two ≥ 4).
    fn with_boxes(
        x: &[f64],
        dim: usize,
        delay: usize,
        eps: f64,
        boxes: usize,
        refs: impl IntoIterator<Item = usize>,
    ) -> Self {
        debug_assert!(boxes.is_power_of_two() && boxes >= 4);
        let mut g = Self {
            dim,
            delay,
            eps,
            boxes,
            head: vec![NONE; boxes * boxes],
            next: vec![NONE; x.len()],
        };
        for n in refs {
            let b = g.box_of(x, n);
            g.next[n] = g.head[b];
            g.head[b] = n;
        }
        g
    }

    /// Radius of the grid (data units).
    pub fn eps(&self) -> f64 {
        self.eps
    }

    #[inline]
    fn cell(&self, v: f64) -> i64 {
        (v / self.eps).floor() as i64
    }

    #[inline]
    fn box_of(&self, x: &[f64], n: usize) -> usize {
        let i = (self.cell(x[n]) as usize) & (self.boxes - 1);
        let j = (self.cell(x[n - (self.dim - 1) * self.delay]) as usize) & (self.boxes - 1);
        i * self.boxes + j
    }

    /// Calls `f(j)` for every filed index `j` whose delay vector lies within `eps` of the delay
    /// vector of `n` in the maximum norm (`n` itself included if it is filed). `x` must be the
    /// series the grid was built from. Neighbours come in a fixed order (deterministic).
    pub fn for_each_neighbor(&self, x: &[f64], n: usize, mut f: impl FnMut(usize)) {
        let ci = self.cell(x[n]);
        let cj = self.cell(x[n - (self.dim - 1) * self.delay]);
        let mask = (self.boxes - 1) as i64;
        for di in -1..=1 {
            let bi = ((ci + di) & mask) as usize;
            for dj in -1..=1 {
                let bj = ((cj + dj) & mask) as usize;
                let mut e = self.head[bi * self.boxes + bj];
                while e != NONE {
                    if self.within(x, n, e) {
                        f(e);
                    }
                    e = self.next[e];
                }
            }
        }
    }

    #[inline]
    fn within(&self, x: &[f64], n: usize, e: usize) -> bool {
        (0..self.dim).all(|k| {
            let o = k * self.delay;
            (x[n - o] - x[e - o]).abs() <= self.eps
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_brute_force() {
        let x: Vec<f64> = (0..400)
            .map(|i| ((i * 7919) % 401) as f64 / 401.0 - 3.0)
            .collect();
        let (m, d, eps) = (3, 2, 0.07);
        let refs: Vec<usize> = ((m - 1) * d..x.len()).collect();
        let g = BoxGrid::new(&x, m, d, eps, refs.iter().copied());
        for &n in &refs {
            let mut got = Vec::new();
            g.for_each_neighbor(&x, n, |j| got.push(j));
            got.sort_unstable();
            let want: Vec<usize> = refs
                .iter()
                .copied()
                .filter(|&j| (0..m).all(|k| (x[n - k * d] - x[j - k * d]).abs() <= eps))
                .collect();
            assert_eq!(got, want, "n = {n}");
        }
    }

    #[test]
    fn grid_size_changes_neither_neighbours_nor_their_order() {
        // the sums over neighbours are bit-identical only if the order is
        let x: Vec<f64> = (0..2000)
            .map(|i| (0.37 * i as f64).sin() + ((i * 7919) % 13) as f64 * 0.01)
            .collect();
        let (m, d) = (3, 4);
        let refs = || (m - 1) * d..x.len();
        for eps in [0.003, 0.05, 0.4, 3.0] {
            let big = BoxGrid::with_boxes(&x, m, d, eps, MAX_BOXES, refs());
            for boxes in [4, MIN_BOXES, 64] {
                let small = BoxGrid::with_boxes(&x, m, d, eps, boxes, refs());
                for n in refs().step_by(7) {
                    let (mut a, mut b) = (Vec::new(), Vec::new());
                    big.for_each_neighbor(&x, n, |j| a.push(j));
                    small.for_each_neighbor(&x, n, |j| b.push(j));
                    assert_eq!(a, b, "eps {eps}, {boxes} boxes, n = {n}");
                }
            }
        }
    }
}
