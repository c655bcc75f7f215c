//! Exact neighbour queries on a few thousand points of a low-dimensional state space (a k-d tree
//! with per-node bounding boxes), returning the same neighbours as a brute-force scan, ties
//! included.
//!
//! # Formula
//! The distance is the one of [`dist2`]: `d² = Σ_d (q_d − x_d)²`
//! summed in coordinate order, reported either as d² ([`Metric::Squared`]) or as `√d²`
//! ([`Metric::Euclidean`]). A node is skipped only when the lower bound of d² over its bounding
//! box, `Σ_d gap_d²` (`gap_d` the distance of `q_d` to the box's interval, 0 inside), maps to a
//! reported distance strictly greater than the bound of the query. Floating-point subtraction,
//! squaring, addition and the square root are monotone, so the computed lower bound never
//! exceeds the computed distance of a point inside the box: no point that a scan would accept
//! is ever skipped, and a point at the bound itself (a tie) is visited.
//!
//! # Ties
//! [`PointTree::nearest`] returns the minimum of (distance, index) in the lexicographic order —
//! what a scan by increasing index keeping the first strict minimum returns.
//!
//! # Units
//! Those of the points (the section analyses pass points divided by their extents).
//!
//! # Cost
//! Building: O(n log n). A query: O(log n) for well-spread points, O(n) in the worst case
//! (every point at the same distance).

/// Points per leaf: below this a scan is cheaper than descending further.
const LEAF: usize = 12;

/// How a query reports a distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Metric {
    /// d² (no square root).
    Squared,
    /// √d².
    Euclidean,
}

impl Metric {
    /// The reported distance of the squared distance `d2`.
    #[inline]
    fn of(self, d2: f64) -> f64 {
        match self {
            Metric::Squared => d2,
            Metric::Euclidean => d2.sqrt(),
        }
    }
}

/// One node: the points `order[start..end]`; children `left`, `left + 1`… stored explicitly.
#[derive(Debug, Clone, Copy)]
struct Node {
    start: usize,
    end: usize,
    /// Index of the first child, 0 for a leaf (the root is node 0, never a child).
    left: usize,
    right: usize,
}

/// A k-d tree over the points `0..n` of a flat row-major array (`dim` coordinates per point).
#[derive(Debug, Clone)]
pub(crate) struct PointTree {
    dim: usize,
    /// The points' coordinates in tree order (row-major, `dim` per point).
    coords: Vec<f64>,
    /// Original index of each point in tree order.
    order: Vec<usize>,
    nodes: Vec<Node>,
    /// Bounding box of each node: `dim` minima then `dim` maxima.
    boxes: Vec<f64>,
}

impl PointTree {
    /// Builds the tree over the first `n` rows of `flat` (`dim` ≥ 1 coordinates per row, all
    /// finite).
    pub(crate) fn new(flat: &[f64], dim: usize, n: usize) -> PointTree {
        let dim = dim.max(1);
        let n = n.min(flat.len() / dim);
        let mut tree = PointTree {
            dim,
            coords: Vec::new(),
            order: (0..n).collect(),
            nodes: Vec::with_capacity(2 * n / LEAF + 1),
            boxes: Vec::with_capacity((2 * n / LEAF + 1) * 2 * dim),
        };
        tree.build(flat, 0, n);
        tree.coords = tree
            .order
            .iter()
            .flat_map(|&i| flat[i * dim..(i + 1) * dim].iter().copied())
            .collect();
        tree
    }

    /// Appends the node over `order[start..end]` and its subtree; returns its index.
    fn build(&mut self, flat: &[f64], start: usize, end: usize) -> usize {
        let dim = self.dim;
        let id = self.nodes.len();
        self.nodes.push(Node {
            start,
            end,
            left: 0,
            right: 0,
        });
        let base = self.boxes.len();
        self.boxes.extend(std::iter::repeat_n(f64::INFINITY, dim));
        self.boxes
            .extend(std::iter::repeat_n(f64::NEG_INFINITY, dim));
        for &i in &self.order[start..end] {
            for (d, &x) in flat[i * dim..(i + 1) * dim].iter().enumerate() {
                let (lo, hi) = (base + d, base + dim + d);
                self.boxes[lo] = self.boxes[lo].min(x);
                self.boxes[hi] = self.boxes[hi].max(x);
            }
        }
        if end - start <= LEAF {
            return id;
        }
        let split = (0..dim)
            .max_by(|&a, &b| {
                let wa = self.boxes[base + dim + a] - self.boxes[base + a];
                let wb = self.boxes[base + dim + b] - self.boxes[base + b];
                wa.total_cmp(&wb)
            })
            .unwrap_or(0);
        let mid = start + (end - start) / 2;
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            flat[a * dim + split].total_cmp(&flat[b * dim + split])
        });
        let left = self.build(flat, start, mid);
        let right = self.build(flat, mid, end);
        self.nodes[id].left = left;
        self.nodes[id].right = right;
        id
    }

    /// Lower bound of d² from `q` to the bounding box of `node` (see the module docs).
    #[inline]
    fn box_bound(&self, node: usize, q: &[f64]) -> f64 {
        let dim = self.dim;
        let b = &self.boxes[node * 2 * dim..(node + 1) * 2 * dim];
        let mut acc = 0.0;
        for (d, &x) in q.iter().enumerate() {
            let (lo, hi) = (b[d], b[dim + d]);
            let gap = if x < lo {
                lo - x
            } else if x > hi {
                x - hi
            } else {
                0.0
            };
            acc += gap * gap;
        }
        acc
    }

    /// The admissible point nearest to `q`: the minimum of (distance, index) over the indices
    /// `j` with `admissible(j, distance)`, `None` when none is admissible.
    pub(crate) fn nearest(
        &self,
        q: &[f64],
        metric: Metric,
        admissible: impl Fn(usize, f64) -> bool,
    ) -> Option<(f64, usize)> {
        let mut best = (f64::INFINITY, usize::MAX);
        if !self.nodes.is_empty() {
            self.nearest_in(0, q, metric, &admissible, &mut best);
        }
        (best.1 != usize::MAX).then_some(best)
    }

    fn nearest_in(
        &self,
        node: usize,
        q: &[f64],
        metric: Metric,
        admissible: &impl Fn(usize, f64) -> bool,
        best: &mut (f64, usize),
    ) {
        let nd = self.nodes[node];
        if nd.left == 0 {
            let dim = self.dim;
            for t in nd.start..nd.end {
                let d = metric.of(dist2(q, &self.coords[t * dim..(t + 1) * dim]));
                let j = self.order[t];
                if (d < best.0 || (d == best.0 && j < best.1)) && admissible(j, d) {
                    *best = (d, j);
                }
            }
            return;
        }
        let bl = metric.of(self.box_bound(nd.left, q));
        let br = metric.of(self.box_bound(nd.right, q));
        let (first, b1, second, b2) = if bl <= br {
            (nd.left, bl, nd.right, br)
        } else {
            (nd.right, br, nd.left, bl)
        };
        if b1 <= best.0 {
            self.nearest_in(first, q, metric, admissible, best);
        }
        if b2 <= best.0 {
            self.nearest_in(second, q, metric, admissible, best);
        }
    }
}

/// Squared Euclidean distance d² = Σ_d (a_d − b_d)² (the tree's and the section tests').
#[inline]
pub(crate) fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};

    /// Points with many exact ties: a coarse lattice, some duplicates, one line.
    fn points(n: usize, dim: usize, seed: u64) -> Vec<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..n * dim)
            .map(|i| match i % 3 {
                0 => (rng.random::<f64>() * 6.0).floor() / 6.0,
                1 => rng.random::<f64>(),
                _ => 0.25,
            })
            .collect()
    }

    fn brute_nearest(
        flat: &[f64],
        dim: usize,
        n: usize,
        q: &[f64],
        metric: Metric,
        ok: impl Fn(usize, f64) -> bool,
    ) -> Option<(f64, usize)> {
        let mut best = (f64::INFINITY, usize::MAX);
        for j in 0..n {
            let d = metric.of(dist2(q, &flat[j * dim..(j + 1) * dim]));
            if ok(j, d) && d < best.0 {
                best = (d, j);
            }
        }
        (best.1 != usize::MAX).then_some(best)
    }

    #[test]
    fn nearest_equals_a_scan_with_ties() {
        for (dim, n) in [(1, 50), (2, 700), (3, 400), (4, 1000)] {
            let flat = points(n, dim, dim as u64);
            let tree = PointTree::new(&flat, dim, n);
            for k in 0..n {
                let q = &flat[k * dim..(k + 1) * dim];
                for metric in [Metric::Squared, Metric::Euclidean] {
                    let ok = |j: usize, d: f64| j.abs_diff(k) > 2 && d > 0.0;
                    assert_eq!(
                        tree.nearest(q, metric, ok),
                        brute_nearest(&flat, dim, n, q, metric, ok),
                        "dim {dim} k {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn empty_and_all_excluded() {
        let tree = PointTree::new(&[], 2, 0);
        assert_eq!(
            tree.nearest(&[0.0, 0.0], Metric::Squared, |_, _| true),
            None
        );
        let flat = [0.5; 40];
        let tree = PointTree::new(&flat, 2, 20);
        assert_eq!(
            tree.nearest(&[0.5, 0.5], Metric::Euclidean, |_, d| d > 0.0),
            None
        );
        assert_eq!(
            tree.nearest(&[0.5, 0.5], Metric::Euclidean, |j, _| j > 3),
            Some((0.0, 4))
        );
    }
}
