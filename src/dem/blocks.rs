//! Grain blocks of the force pass: the candidate pairs sorted by the block of their grains.
//!
//! The grains (stored along the space-filling curve) are cut into a fixed number of
//! contiguous blocks that depends on the grain count only ([`block_count`]), never on the
//! threads; the cuts are placed at each neighbour rebuild so that the blocks hold about as
//! much pair work each (cut by grain count, two blocks of a 4000-grain bed at rest differed
//! by 20–30 % in pair work, and the thread with the heavier block set the pace). A pair whose
//! two grains are in the same block is that block's *own* pair; the others are *cross* pairs. The force on a grain is then always summed in one order:
//!
//! 1. gravity (and the settling drag),
//! 2. its block's own pairs, in pair order (scattered straight into the block's forces),
//! 3. its cross pairs, in pair order (their responses stored per pair, then gathered),
//! 4. its six walls.
//!
//! Blocks are disjoint in memory, so they can run on different threads with no atomics, and
//! the sums are the same on any number of threads. A bed of fewer than 2 × [`MIN_BLOCK`]
//! grains is one block: no cross pairs at all.

#[cfg(test)]
use crate::neighbor::J_ROLE;
use crate::neighbor::{index_by_grain, Pair};

/// Grains per work unit of the per-grain phases (kick–drift; cross gathering, walls, kick).
pub const GRAIN_CHUNK: usize = 512;

/// Smallest number of grains in a block.
pub const MIN_BLOCK: usize = 1500;

/// Number of blocks for `n` grains: the largest power of two (so that the blocks divide
/// evenly between 2 or 4 threads) with blocks of at least [`MIN_BLOCK`] grains, and 1 for
/// small beds.
pub fn block_count(n: usize) -> usize {
    let mut b = 1;
    while 2 * b * MIN_BLOCK <= n {
        b *= 2;
    }
    b
}

/// Weight of a grain's own work (gravity, integration) against one candidate pair's, in the
/// cost the block cuts balance.
const GRAIN_WEIGHT: u64 = 1;
/// Weight of one candidate pair not in contact (its distance test).
const PAIR_WEIGHT: u64 = 1;
/// Weight of one candidate pair in contact at the rebuild (the test and a contact response).
const CONTACT_WEIGHT: u64 = 6;

/// Candidate pairs ordered block by block: `pairs[seg[b]..seg[b + 1]]` are block b's own
/// pairs (in neighbour-list order), `pairs[seg[nb]..]` the cross pairs (those whose i is in
/// block 0, then in block 1, …, each in neighbour-list order, so that what a block writes per
/// cross pair of its i lies together in memory); and, per grain, the
/// cross pairs it belongs to (index relative to `seg[nb]`, with [`J_ROLE`](crate::neighbor::J_ROLE) where the grain is
/// the pair's `j`).
#[derive(Debug, Clone, Default)]
pub struct BlockPairs {
    /// Number of blocks.
    pub blocks: usize,
    /// First grain of each block (`blocks + 1` entries, the last one N).
    pub starts: Vec<usize>,
    /// Block of each grain (scratch of [`BlockPairs::partition`]).
    block_of: Vec<u32>,
    /// The pairs, own pairs of block 0, 1, …, then the cross pairs by the block of their i.
    pub pairs: Vec<Pair>,
    /// Start of each block's own pairs; `seg[blocks]` is the start of the cross pairs and
    /// `seg[blocks + 1]` the number of pairs.
    pub seg: Vec<usize>,
    /// Per grain (N + 1 entries), where its cross items start in `cross_items`.
    pub cross_start: Vec<u32>,
    /// Per grain, its cross pairs in pair order (relative index, [`J_ROLE`](crate::neighbor::J_ROLE) for the `j`).
    pub cross_items: Vec<u32>,
    /// The grain of each entry of `cross_items` (derivable from `cross_start`, but stored:
    /// the cross-pair pass then walks only a block's items instead of every grain of the
    /// block, most of which have none; 2–4 % of a two-thread step on the vibrated 4000 bed).
    pub cross_owner: Vec<u32>,
    /// Block of each candidate pair (scratch of [`BlockPairs::partition`]).
    class: Vec<u32>,
    /// The grain units of the per-grain pass: each block cut into runs of at most
    /// [`GRAIN_CHUNK`] grains; unit u is grains `unit_start[u]..unit_start[u + 1]`.
    unit_start: Vec<usize>,
    /// First grain unit of each block (`blocks + 1` entries, the last one the unit count).
    block_unit: Vec<usize>,
}

impl BlockPairs {
    /// Sorts `pairs` of `n` grains into blocks (stable: each segment keeps the list order)
    /// and indexes the cross pairs per grain; `in_contact` tells the pairs in contact now (they
    /// weigh more in the block cuts). Reuses its buffers.
    pub fn partition(&mut self, pairs: &[Pair], n: usize, in_contact: impl Fn(&Pair) -> bool) {
        let nb = block_count(n);
        self.blocks = nb;
        self.cut(pairs, n, in_contact);
        self.class.clear();
        // classes: block b's own pairs (b), then the cross pairs whose i is in block b (nb + b)
        let seg = &mut self.seg;
        seg.clear();
        seg.resize(2 * nb + 1, 0);
        for p in pairs {
            let (bi, bj) = (self.block_of[p.i as usize], self.block_of[p.j as usize]);
            let c = if bi == bj { bi } else { nb as u32 + bi };
            self.class.push(c);
            seg[c as usize + 1] += 1;
        }
        for c in 0..2 * nb {
            seg[c + 1] += seg[c];
        }
        self.pairs.clear();
        self.pairs.resize(pairs.len(), Pair { i: 0, j: 0 });
        // counting sort by class (cursor in `cross_start`, reused as scratch)
        let cursor = &mut self.cross_start;
        cursor.clear();
        cursor.extend(seg[..2 * nb].iter().map(|&s| s as u32));
        for (p, &c) in pairs.iter().zip(&self.class) {
            let k = &mut cursor[c as usize];
            self.pairs[*k as usize] = *p;
            *k += 1;
        }
        // from here on `seg` has the blocks' starts, the cross pairs' start and the end
        seg.truncate(nb + 1);
        seg.push(pairs.len());
        self.index_cross(n);
        self.cut_units();
    }

    /// [`BlockPairs::unit_start`] and [`BlockPairs::block_unit`] from the block cuts. A grain
    /// unit never straddles two blocks, so the thread that runs a block's pairs can run its
    /// grains' per-grain work too (the per-unit sums are then grouped the same way whichever
    /// thread runs them).
    fn cut_units(&mut self) {
        self.unit_start.clear();
        self.block_unit.clear();
        for b in 0..self.blocks {
            self.block_unit.push(self.unit_start.len());
            self.unit_start.extend(self.grains(b).step_by(GRAIN_CHUNK));
        }
        self.block_unit.push(self.unit_start.len());
        self.unit_start.push(self.starts[self.blocks]);
    }

    /// Number of grain units.
    pub fn units(&self) -> usize {
        self.unit_start.len().saturating_sub(1)
    }

    /// Grains of grain unit `u`.
    pub fn unit(&self, u: usize) -> std::ops::Range<usize> {
        self.unit_start[u]..self.unit_start[u + 1]
    }

    /// Grain units of block `b`.
    pub fn units_of(&self, b: usize) -> std::ops::Range<usize> {
        self.block_unit[b]..self.block_unit[b + 1]
    }

    /// Block b's items of [`BlockPairs::cross_items`] (its grains' cross pairs, grain by
    /// grain) and their grains.
    pub fn cross_items_of(&self, b: usize) -> (&[u32], &[u32]) {
        let g = self.grains(b);
        let r = self.cross_start[g.start] as usize..self.cross_start[g.end] as usize;
        (&self.cross_items[r.clone()], &self.cross_owner[r])
    }

    /// Block cuts at equal shares of the cost Σ (GRAIN_WEIGHT + the weights of the pairs listed
    /// with the grain as their `i`: CONTACT_WEIGHT if `in_contact`, else PAIR_WEIGHT), each
    /// block at least one grain; `block_of` to match.
    fn cut(&mut self, pairs: &[Pair], n: usize, in_contact: impl Fn(&Pair) -> bool) {
        let nb = self.blocks;
        // per-grain cost, in `block_of` (reused as scratch before it gets the blocks)
        let cost = &mut self.block_of;
        cost.clear();
        cost.resize(n, GRAIN_WEIGHT as u32);
        for p in pairs {
            let w = if in_contact(p) {
                CONTACT_WEIGHT
            } else {
                PAIR_WEIGHT
            };
            cost[p.i as usize] += w as u32;
        }
        let total: u64 = cost.iter().map(|&c| c as u64).sum();
        self.starts.clear();
        self.starts.push(0);
        let mut acc = 0u64;
        for (g, &c) in cost.iter().enumerate() {
            let b = self.starts.len(); // the block whose start is searched next
            if b < nb && acc * nb as u64 >= b as u64 * total && g > self.starts[b - 1] {
                self.starts.push(g);
            }
            acc += c as u64;
        }
        // (a degenerate cost leaves blocks unplaced: spread them over the last grains)
        while self.starts.len() < nb {
            let last = *self.starts.last().unwrap_or(&0);
            self.starts.push((last + 1).min(n));
        }
        self.starts.push(n);
        for b in 0..nb {
            for g in self.starts[b]..self.starts[b + 1] {
                self.block_of[g] = b as u32;
            }
        }
    }

    /// Per-grain index of the cross pairs ([`index_by_grain`]).
    fn index_cross(&mut self, n: usize) {
        let cross = &self.pairs[self.seg[self.blocks]..];
        index_by_grain(cross, n, &mut self.cross_start, &mut self.cross_items);
        self.cross_owner.clear();
        self.cross_owner.resize(self.cross_items.len(), 0);
        for g in 0..n {
            let r = self.cross_start[g] as usize..self.cross_start[g + 1] as usize;
            self.cross_owner[r].fill(g as u32);
        }
    }

    /// Grains of block `b`.
    pub fn grains(&self, b: usize) -> std::ops::Range<usize> {
        self.starts[b]..self.starts[b + 1]
    }

    /// Number of cross pairs.
    pub fn cross_len(&self) -> usize {
        self.pairs.len() - self.seg[self.blocks]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_counts_are_powers_of_two_of_at_least_min_block_grains() {
        assert_eq!(block_count(1), 1);
        assert_eq!(block_count(2999), 1);
        assert_eq!(block_count(3000), 2);
        assert_eq!(block_count(4000), 2);
        assert_eq!(block_count(16_000), 8);
        assert_eq!(block_count(64_000), 32);
        for n in [3000, 5999, 6000, 64_000, 1_000_000] {
            assert!(n / block_count(n) >= MIN_BLOCK);
        }
    }

    #[test]
    fn partition_keeps_every_pair_once_in_list_order_per_segment() {
        let n = 7000; // 4 blocks
        let mut s = 99u64;
        let mut rnd = |m: u64| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1);
            (s >> 33) % m
        };
        let pairs: Vec<Pair> = (0..5000)
            .map(|_| {
                let i = rnd(n as u64) as u32;
                // mostly near neighbours in index, some far
                let j = if rnd(4) == 0 {
                    rnd(n as u64) as u32
                } else {
                    (i + 1 + rnd(40) as u32) % n as u32
                };
                Pair { i, j }
            })
            .filter(|p| p.i != p.j)
            .collect();
        let mut bp = BlockPairs::default();
        bp.partition(&pairs, n, |_| false);
        assert_eq!(bp.blocks, 4);
        assert_eq!(bp.pairs.len(), pairs.len());
        let block = |g: u32| {
            (0..bp.blocks)
                .find(|&b| bp.grains(b).contains(&(g as usize)))
                .unwrap()
        };
        assert_eq!(bp.starts.len(), 5);
        assert!(bp.starts.windows(2).all(|w| w[0] < w[1]) && bp.starts[4] == n);
        // the cuts balance the listed pairs (each pair counted at its `i`)
        let per_block: Vec<usize> = (0..4)
            .map(|b| pairs.iter().filter(|p| block(p.i) == b).count())
            .collect();
        let (lo, hi) = (
            per_block.iter().min().unwrap(),
            per_block.iter().max().unwrap(),
        );
        assert!(
            *hi as f64 <= 1.05 * *lo as f64 + 10.0,
            "pairs per block {per_block:?}"
        );
        for b in 0..bp.blocks {
            let want: Vec<Pair> = pairs
                .iter()
                .copied()
                .filter(|p| block(p.i) == b && block(p.j) == b)
                .collect();
            assert_eq!(&bp.pairs[bp.seg[b]..bp.seg[b + 1]], &want[..]);
        }
        // the cross pairs by the block of their i, each block's in list order
        let cross: Vec<Pair> = (0..bp.blocks)
            .flat_map(|b| {
                pairs
                    .iter()
                    .copied()
                    .filter(move |p| block(p.i) == b && block(p.j) != b)
            })
            .collect();
        assert!(!cross.is_empty());
        assert_eq!(&bp.pairs[bp.seg[bp.blocks]..], &cross[..]);
        assert_eq!(bp.cross_len(), cross.len());
        for g in 0..n {
            let got: Vec<u32> =
                bp.cross_items[bp.cross_start[g] as usize..bp.cross_start[g + 1] as usize].to_vec();
            let want: Vec<u32> = cross
                .iter()
                .enumerate()
                .filter_map(|(k, p)| {
                    if p.i as usize == g {
                        Some(k as u32)
                    } else if p.j as usize == g {
                        Some(k as u32 | J_ROLE)
                    } else {
                        None
                    }
                })
                .collect();
            assert_eq!(got, want, "grain {g}");
        }
        // one block: no cross pairs, the list unchanged
        let small: Vec<Pair> = pairs
            .iter()
            .copied()
            .filter(|p| p.i < 2000 && p.j < 2000)
            .collect();
        bp.partition(&small, 2000, |_| false);
        assert_eq!(bp.blocks, 1);
        assert_eq!(bp.pairs, small);
        assert_eq!(bp.cross_len(), 0);
    }
}
