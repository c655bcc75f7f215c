//! The kd-tree of [`super::rosenstein`]: the candidate delay vectors, read from the series,
//! and each reference's exact nearest neighbour outside its Theiler window in one pruned
//! descent (squared Euclidean distance; ties: the smallest index). The references are queried
//! in the tree's own point order ([`ExclusionTree::all_nearest`]): consecutive queries then
//! lie in the same or adjacent leaves, whose points stay in cache.

use rayon::prelude::*;

use crate::analysis::outside_theiler_window;

/// The candidate delay vectors `(s_i, s_{i+τ}, …, s_{i+(K−1)τ})`, i < `len`, read from the
/// series (not stored).
pub(super) struct Delays<'a, const K: usize> {
    pub(super) s: &'a [f64],
    pub(super) tau: usize,
    pub(super) len: usize,
}

impl<const K: usize> Delays<'_, K> {
    #[inline]
    fn get(&self, i: usize) -> [f64; K] {
        std::array::from_fn(|k| self.s[i + k * self.tau])
    }

    #[inline]
    fn coord(&self, i: usize, k: usize) -> f64 {
        self.s[i + k * self.tau]
    }
}

/// Points per leaf of [`ExclusionTree`].
const LEAF: usize = 16;

/// A kd-tree over the candidate delay vectors whose nearest-neighbour query skips the
/// reference's Theiler window and zero distances itself (one descent, pruned by the best
/// admissible distance so far), instead of asking a general kd-tree for 4, 16, 64, …
/// neighbours until one lies outside the window.
pub(super) struct ExclusionTree<const K: usize> {
    /// Point indices, permuted so that every node's points are contiguous.
    perm: Vec<u32>,
    /// The points in `perm` order: a leaf's points are read contiguously.
    sorted: Vec<[f64; K]>,
    nodes: Vec<Node>,
}

#[derive(Clone, Copy, Default)]
struct Node {
    /// Points `lo..hi` of `perm`.
    lo: u32,
    hi: u32,
    /// Children (0: a leaf), split coordinate and value (left: ≤ value, right: ≥ value).
    left: u32,
    right: u32,
    dim: u32,
    split: f64,
}

impl<const K: usize> ExclusionTree<K> {
    pub(super) fn new(pts: &Delays<K>) -> Self {
        let mut perm: Vec<u32> = (0..pts.len as u32).collect();
        let mut lo = [f64::INFINITY; K];
        let mut hi = [f64::NEG_INFINITY; K];
        for i in 0..pts.len {
            let p = pts.get(i);
            for k in 0..K {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let mut nodes = vec![Node::default(); node_count(pts.len)];
        build(pts, &mut perm, &mut nodes, 0, 0, lo, hi);
        let sorted = perm.par_iter().map(|&j| pts.get(j as usize)).collect();
        Self {
            perm,
            sorted,
            nodes,
        }
    }

    /// [`ExclusionTree::nearest`] of every reference `n < n_ref`, indexed by n.
    ///
    /// The queries run in the tree's point order (leaf after leaf), in parallel over fixed
    /// blocks of that order; each answer is the exact nearest neighbour whatever the order,
    /// so the result does not depend on the thread count. (In time order, each query's
    /// leaves were mostly cache misses at 200 000 points.)
    pub(super) fn all_nearest(&self, pts: &Delays<K>, n_ref: usize, w: usize) -> Vec<Nearest> {
        const BLOCK: usize = 2048;
        let blocks: Vec<Vec<(u32, Nearest)>> = self
            .perm
            .par_chunks(BLOCK)
            .map(|block| {
                let mut stack = Vec::with_capacity(64);
                block
                    .iter()
                    .filter(|&&n| (n as usize) < n_ref)
                    .map(|&n| (n, self.nearest(pts, n as usize, w, &mut stack)))
                    .collect()
            })
            .collect();
        let mut all = vec![Nearest::NONE; n_ref];
        for (n, found) in blocks.into_iter().flatten() {
            all[n as usize] = found;
        }
        all
    }

    /// The nearest point j of reference n with `|n − j| > w` and a distance > 0 (squared
    /// Euclidean; ties: the smallest index), its squared distance, and whether an admissible
    /// point lies at distance 0 (an exact duplicate).
    fn nearest(&self, pts: &Delays<K>, n: usize, w: usize, stack: &mut Vec<(u32, f64)>) -> Nearest {
        let q = &pts.get(n);
        let dist = |p: &[f64; K]| -> f64 {
            let mut d = 0.0;
            for k in 0..K {
                let e = q[k] - p[k];
                d += e * e;
            }
            d
        };
        let (mut best, mut best_j) = (f64::INFINITY, usize::MAX);
        let mut duplicate = false;
        stack.clear();
        stack.push((0, 0.0));
        while let Some((id, bound)) = stack.pop() {
            if bound > best {
                continue;
            }
            let node = self.nodes[id as usize];
            if node.left == 0 {
                let (lo, hi) = (node.lo as usize, node.hi as usize);
                for (&j, p) in self.perm[lo..hi].iter().zip(&self.sorted[lo..hi]) {
                    let j = j as usize;
                    if !outside_theiler_window(n, j, w) {
                        continue;
                    }
                    let d = dist(p);
                    if d == 0.0 {
                        duplicate = true;
                    } else if d < best || (d == best && j < best_j) {
                        (best, best_j) = (d, j);
                    }
                }
                continue;
            }
            let e = q[node.dim as usize] - node.split;
            let (near, far) = if e <= 0.0 {
                (node.left, node.right)
            } else {
                (node.right, node.left)
            };
            // the far side is at least e² away (its points lie beyond the split value)
            stack.push((far, bound.max(e * e)));
            stack.push((near, bound));
        }
        if best_j == usize::MAX {
            return Nearest {
                duplicate,
                ..Nearest::NONE
            };
        }
        Nearest {
            j: best_j as u32,
            d2: best,
            duplicate,
        }
    }
}

/// A reference's nearest admissible neighbour ([`ExclusionTree::nearest`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Nearest {
    /// Its index; `u32::MAX`: none (every candidate inside the Theiler window or at distance 0).
    pub(super) j: u32,
    /// Its squared distance.
    pub(super) d2: f64,
    /// An admissible candidate lies at distance 0 (an exact duplicate).
    pub(super) duplicate: bool,
}

impl Nearest {
    /// No neighbour.
    const NONE: Nearest = Nearest {
        j: u32::MAX,
        d2: f64::INFINITY,
        duplicate: false,
    };
}

/// Subtrees with more points than this are built in parallel (both halves at once).
const BUILD_SERIAL: usize = 16_384;

/// Nodes of the subtree over `len` points: a leaf up to [`LEAF`] points, else the node and
/// the subtrees of its lower `len / 2` and upper `len − len / 2` points. The tree's shape
/// depends on `len` only, so every node's index is known before the points are split.
fn node_count(len: usize) -> usize {
    node_counts(len).0
}

/// `(node_count(s), node_count(s + 1))` in O(log s): both split into halves of `⌊s/2⌋` and
/// `⌊s/2⌋ + 1` points.
fn node_counts(s: usize) -> (usize, usize) {
    if s < LEAF {
        return (1, 1);
    }
    let (a, b) = node_counts(s / 2);
    if s.is_multiple_of(2) {
        (if s <= LEAF { 1 } else { 1 + 2 * a }, 1 + a + b)
    } else {
        (1 + a + b, 1 + 2 * b)
    }
}

/// Builds the subtree over `perm` (points `lo..lo + perm.len()` of the whole permutation) into
/// `nodes` (its `node_count` nodes in depth-first order, the first being node `id`), inside
/// the box `bl..bh` (the parent's box cut at the splits: its widest side chooses the split
/// coordinate, split at the median). Large subtrees build their halves in parallel; the result
/// is the same tree as a serial build's (each half is a disjoint part of `perm` and `nodes`).
fn build<const K: usize>(
    pts: &Delays<K>,
    perm: &mut [u32],
    nodes: &mut [Node],
    id: usize,
    lo: usize,
    bl: [f64; K],
    bh: [f64; K],
) {
    let len = perm.len();
    let hi = lo + len;
    nodes[0].lo = lo as u32;
    nodes[0].hi = hi as u32;
    if len <= LEAF {
        return;
    }
    let mut dim = 0;
    for k in 1..K {
        if bh[k] - bl[k] > bh[dim] - bl[dim] {
            dim = k;
        }
    }
    let half = len / 2;
    perm.select_nth_unstable_by(half, |&a, &b| {
        pts.coord(a as usize, dim)
            .total_cmp(&pts.coord(b as usize, dim))
    });
    let split = pts.coord(perm[half] as usize, dim);
    let (mut lh, mut rl) = (bh, bl);
    lh[dim] = split;
    rl[dim] = split;
    let left_nodes = node_count(half);
    let (node, rest) = nodes.split_first_mut().expect("node_count ≥ 1");
    node.left = (id + 1) as u32;
    node.right = (id + 1 + left_nodes) as u32;
    node.dim = dim as u32;
    node.split = split;
    let (ln, rn) = rest.split_at_mut(left_nodes);
    let (lp, rp) = perm.split_at_mut(half);
    let right_id = id + 1 + left_nodes;
    if len > BUILD_SERIAL {
        rayon::join(
            || build(pts, lp, ln, id + 1, lo, bl, lh),
            || build(pts, rp, rn, right_id, lo + half, rl, bh),
        );
    } else {
        build(pts, lp, ln, id + 1, lo, bl, lh);
        build(pts, rp, rn, right_id, lo + half, rl, bh);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_count_is_the_recursive_count() {
        fn naive(len: usize) -> usize {
            if len <= LEAF {
                1
            } else {
                1 + naive(len / 2) + naive(len - len / 2)
            }
        }
        for len in 0..5000 {
            assert_eq!(node_count(len), naive(len), "{len} points");
        }
    }
}
