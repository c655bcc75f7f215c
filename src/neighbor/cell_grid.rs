//! Sorted cell list + Verlet pair list (O(N) neighbour search, O(N) memory).
//!
//! Grains are keyed by their cell (cubic-ish cells of side ≥ 2 R_max + skin in the box frame)
//! and sorted by key; only occupied cells are kept, and a neighbour cell is found in an
//! open-addressing hash table of them (O(1) expected, against the O(log cells) of a binary
//! search: the 13 lookups per occupied cell were a third of a rebuild), so the memory does not
//! grow with the box volume — or, on a grid of at most a few cells per grain, in a direct
//! table of every cell (one load per lookup, the same cells found). The key is the cell's
//! Morton (Z-order) code, so cells — and the pairs, which are listed cell by cell — follow a
//! space-filling curve; [`NeighborList::curve_order`] gives the same order for the grains, so
//! that the engine can store them along the curve. Each cell is compared with itself and its 13
//! "forward" neighbours, so every pair is found once (i < j in cell order) and its force is
//! computed once (Newton's third law). The list keeps every pair closer than
//! R_i + R_j + skin; it stays valid while every grain has moved less than skin/2 relative to
//! a common shift (the box displacement), because a common translation does not change any
//! pair distance: |Δr_ij| ≤ |d_i − s| + |d_j − s|.
//!
//! Here the list and its cells; the pair search in `pair_search.rs`, the Morton codes and
//! hash tables in `morton.rs`, [`Pair`] in `pair.rs`.

pub use super::pair::{index_by_grain, Pair, J_ROLE};

use super::morton::{compact2, compact3, fill_hash, find_hashed, spread2, spread3};

/// Largest number of grid cells per grain for which the occupied cells are found through a
/// direct table (one entry per cell) rather than a hash table.
const DENSE_CELLS_PER_GRAIN: usize = 8;

/// Grid cells always allowed a direct table, whatever the grain count.
const DENSE_CELLS_MIN: usize = 4096;

/// Verlet neighbour list built with a sorted (hashed) cell list: only occupied cells are
/// stored, so its memory is O(N) whatever the box volume.
#[derive(Debug, Clone)]
pub struct NeighborList {
    /// Candidate pairs (valid until [`NeighborList::needs_rebuild`] says otherwise).
    pub pairs: Vec<Pair>,
    pub(super) skin_m: f64,
    pub(super) box_m: [f64; 3],
    pub(super) dims: [usize; 3],
    pub(super) inv_cell: [f64; 3],
    /// (cell key, grain) sorted by key then grain.
    pub(super) keyed: Vec<(u64, u32)>,
    /// Keys of the occupied cells, ascending.
    pub(super) cell_keys: Vec<u64>,
    /// Start of each occupied cell's grains in `keyed` (one more entry than cells).
    pub(super) cell_start: Vec<u32>,
    /// Open-addressing hash table of the occupied cells (a power of two ≥ 2 × cells
    /// slots): a slot holds 1 + the cell's index in `cell_keys`, 0 when empty. Empty when
    /// `dense` is used.
    pub(super) cell_table: Vec<u32>,
    /// Direct table of every cell of a small grid (at most [`DENSE_CELLS_PER_GRAIN`] per
    /// grain, plus [`DENSE_CELLS_MIN`]), indexed x + nx (y + ny z): 1 + the cell's index in
    /// `cell_keys`, 0 when empty. A lookup is then one load instead of a key and a hash
    /// probe (scene B's 250-grain bed, 5 × 5 × 18 cells, rebuilt every ~8 steps: 9–11 %
    /// less CPU per run); the same cells are found, so the pairs and their order do not
    /// change. Empty on a grid too large for it, whose memory would follow the box volume.
    pub(super) dense: Vec<u32>,
    /// [`Curve::Columns`] only: the occupied columns' codes (key >> 21), ascending, and the
    /// start of each column's cells in `cell_keys` (one more entry than columns).
    pub(super) col_keys: Vec<u64>,
    pub(super) col_start: Vec<u32>,
    /// Open-addressing hash table of the occupied columns (as `cell_table`).
    pub(super) col_table: Vec<u32>,
    pub(super) ref_pos: Vec<[f64; 3]>,
    pub(super) ref_shift: [f64; 3],
    /// Number of (re)builds so far.
    pub builds: u64,
    /// The space-filling curve of the cell keys.
    pub(super) curve: Curve,
}

/// The space-filling curve the cells (and grains) are stored along.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Curve {
    /// 3-D Morton (Z-order) code: the bits of x, y and z interleaved (21 bits each).
    #[default]
    Morton,
    /// Vertical columns: the 2-D Morton code of (x, y) above the height z (21 bits each).
    /// A run of this curve is a set of whole columns, so a run cut out of a shallow bed has
    /// only vertical faces: the engine's grain blocks (runs of the curve) then share fewer
    /// pairs than 3-D Morton runs, whose faces include horizontal ones across the bed.
    Columns,
}

impl NeighborList {
    /// Prepares a cell list for a box of size `box_m` (m), grains up to `r_max` (m), skin (m).
    /// Allocates nothing that depends on the box volume.
    pub fn new(box_m: [f64; 3], r_max: f64, skin_m: f64) -> Self {
        let cell = 2.0 * r_max + skin_m;
        let mut dims = [1usize; 3];
        let mut inv_cell = [0.0; 3];
        for d in 0..3 {
            dims[d] = ((box_m[d] / cell).floor() as usize).clamp(1, 1 << 20);
            inv_cell[d] = dims[d] as f64 / box_m[d];
        }
        NeighborList {
            pairs: Vec::new(),
            skin_m,
            box_m,
            dims,
            inv_cell,
            keyed: Vec::new(),
            cell_keys: Vec::new(),
            cell_start: Vec::new(),
            cell_table: Vec::new(),
            dense: Vec::new(),
            col_keys: Vec::new(),
            col_start: Vec::new(),
            col_table: Vec::new(),
            ref_pos: Vec::new(),
            ref_shift: [0.0; 3],
            builds: 0,
            curve: Curve::Morton,
        }
    }

    /// The same list with its cells stored along `curve`.
    pub fn with_curve(mut self, curve: Curve) -> Self {
        self.curve = curve;
        self
    }

    /// Verlet skin (m).
    pub fn skin(&self) -> f64 {
        self.skin_m
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// Occupied cells at the last build.
    pub fn occupied_cells(&self) -> usize {
        self.cell_keys.len()
    }

    /// Bytes held by the neighbour structure now (pairs, cell list, reference positions).
    pub fn memory_bytes(&self) -> usize {
        self.pairs.capacity() * std::mem::size_of::<Pair>()
            + self.keyed.capacity() * 16
            + self.cell_keys.capacity() * 8
            + self.cell_start.capacity() * 4
            + self.cell_table.capacity() * 4
            + self.dense.capacity() * 4
            + self.col_keys.capacity() * 8
            + (self.col_start.capacity() + self.col_table.capacity()) * 4
            + self.ref_pos.capacity() * 24
    }

    #[inline]
    fn cell_coords(&self, p: [f64; 3]) -> [usize; 3] {
        let mut c = [0usize; 3];
        for d in 0..3 {
            let x = (p[d] * self.inv_cell[d]).floor();
            c[d] = if x <= 0.0 {
                0
            } else {
                (x as usize).min(self.dims[d] - 1)
            };
        }
        c
    }

    /// Key of cell `c` along the list's [`Curve`].
    #[inline]
    pub(super) fn key(&self, c: [usize; 3]) -> u64 {
        match self.curve {
            Curve::Morton => {
                spread3(c[0] as u64) | (spread3(c[1] as u64) << 1) | (spread3(c[2] as u64) << 2)
            }
            Curve::Columns => {
                ((spread2(c[0] as u64) | (spread2(c[1] as u64) << 1)) << 21)
                    | (c[2] as u64 & 0x1f_ffff)
            }
        }
    }

    /// The cell of `key` (inverse of [`NeighborList::key`]).
    #[inline]
    pub(super) fn cell_of(&self, key: u64) -> [usize; 3] {
        match self.curve {
            Curve::Morton => [compact3(key), compact3(key >> 1), compact3(key >> 2)],
            Curve::Columns => [compact2(key >> 21), compact2(key >> 22), key & 0x1f_ffff],
        }
        .map(|x| x as usize)
    }

    /// Sorts the grains by their cell's Morton code (ties by index) for positions `pos`
    /// (lab frame, m) and box origin `shift` (m), and writes into `order` the grain indices
    /// in that order: the permutation that stores the grains along the space-filling curve.
    /// A following [`NeighborList::rebuild`] of the permuted positions finds its cell list
    /// already sorted.
    pub fn curve_order(&mut self, pos: &[[f64; 3]], shift: [f64; 3], order: &mut Vec<u32>) {
        self.fill_keys(pos, shift);
        order.clear();
        order.extend(self.keyed.iter().map(|e| e.1));
    }

    /// `keyed` = (cell key, grain) of every grain, sorted.
    fn fill_keys(&mut self, pos: &[[f64; 3]], shift: [f64; 3]) {
        self.keyed.clear();
        for (i, q) in pos.iter().enumerate() {
            let c = self.cell_coords([q[0] - shift[0], q[1] - shift[1], q[2] - shift[2]]);
            self.keyed.push((self.key(c), i as u32));
        }
        self.keyed.sort_unstable();
    }

    /// True when some grain moved more than skin/2 relative to the common `shift` (m) since
    /// the last build (or when the grain count changed).
    pub fn needs_rebuild(&self, pos: &[[f64; 3]], shift: [f64; 3]) -> bool {
        if self.ref_pos.len() != pos.len() || self.builds == 0 {
            return true;
        }
        let ds = [
            shift[0] - self.ref_shift[0],
            shift[1] - self.ref_shift[1],
            shift[2] - self.ref_shift[2],
        ];
        let lim = 0.25 * self.skin_m * self.skin_m;
        let mut worst = 0.0f64;
        for (p, r) in pos.iter().zip(&self.ref_pos) {
            let dx = p[0] - r[0] - ds[0];
            let dy = p[1] - r[1] - ds[1];
            let dz = p[2] - r[2] - ds[2];
            worst = worst.max(dx * dx + dy * dy + dz * dz);
        }
        worst > lim
    }

    /// Reference positions of the last build and the shift then (m), for fused checks.
    pub fn reference(&self) -> (&[[f64; 3]], [f64; 3]) {
        (&self.ref_pos, self.ref_shift)
    }

    /// True when a largest squared displacement `max_d2` (m², relative to the common shift)
    /// exceeds (skin/2)².
    pub fn exceeded(&self, max_d2: f64) -> bool {
        self.builds == 0 || max_d2 > 0.25 * self.skin_m * self.skin_m
    }

    /// Rebuilds the pair list: all pairs with |r_i − r_j| < R_i + R_j + skin, in the order of
    /// the cells along the curve, then the half stencil, then the grains' order in the cells.
    ///
    /// `pos` are lab-frame centres (m), `shift` the box origin in the lab frame (m).
    /// The same as [`NeighborList::prepare`], then [`NeighborList::pairs_of_cells`] over
    /// every cell (which a caller may instead split into runs and do on several threads).
    pub fn rebuild(&mut self, pos: &[[f64; 3]], radius: &[f64], shift: [f64; 3]) {
        self.prepare(pos, shift);
        let mut pairs = std::mem::take(&mut self.pairs);
        pairs.clear();
        self.pairs_of_cells(0..self.cell_keys.len(), pos, radius, &mut pairs);
        self.pairs = pairs;
    }

    /// The first half of a rebuild: reference positions, the sorted cell list and its
    /// lookup tables. The pairs are then found by [`NeighborList::pairs_of_cells`] and stored
    /// in [`NeighborList::pairs`] by the caller.
    pub fn prepare(&mut self, pos: &[[f64; 3]], shift: [f64; 3]) {
        let n = pos.len();
        self.builds += 1;
        self.ref_pos.clear();
        self.ref_pos.extend_from_slice(pos);
        self.ref_shift = shift;
        // sorted cell list: (key, grain), occupied cells and their ranges
        self.fill_keys(pos, shift);
        self.cell_keys.clear();
        self.cell_start.clear();
        for (a, &(k, _)) in self.keyed.iter().enumerate() {
            if self.cell_keys.last() != Some(&k) {
                self.cell_keys.push(k);
                self.cell_start.push(a as u32);
            }
        }
        self.cell_start.push(n as u32);
        self.fill_table();
        self.fill_columns();
    }

    /// Cuts the occupied cells into `units` runs of about equal grain counts (whole columns
    /// with [`Curve::Columns`]): `out` gets the `units + 1` boundaries (indices of cells).
    pub fn cell_runs(&self, units: usize, out: &mut Vec<usize>) {
        let cells = self.cell_keys.len();
        let units = units.max(1);
        // grains before cell c: cell_start[c]; a run ends at the first allowed cell (any cell,
        // or the start of a column) with at least `want` grains before it
        let grains = |c: usize| self.cell_start[c] as usize;
        let cut = |want: usize| match self.curve {
            Curve::Morton => self.cell_start.partition_point(|&s| (s as usize) < want),
            Curve::Columns => {
                let k = self
                    .col_start
                    .partition_point(|&c| grains(c as usize) < want);
                self.col_start.get(k).map_or(cells, |&c| c as usize)
            }
        };
        let n = self.keyed.len();
        out.clear();
        out.push(0);
        out.extend((1..units).map(|u| cut(u * n / units).min(cells)));
        out.push(cells);
    }

    /// Fills the column list and its table from `cell_keys` ([`Curve::Columns`] only).
    fn fill_columns(&mut self) {
        self.col_keys.clear();
        self.col_start.clear();
        self.col_table.clear();
        if self.curve != Curve::Columns {
            return;
        }
        for (c, &k) in self.cell_keys.iter().enumerate() {
            if self.col_keys.last() != Some(&(k >> 21)) {
                self.col_keys.push(k >> 21);
                self.col_start.push(c as u32);
            }
        }
        self.col_start.push(self.cell_keys.len() as u32);
        fill_hash(&self.col_keys, &mut self.col_table);
    }

    /// Index in `col_keys` of the occupied column `code`, if any.
    #[inline]
    pub(super) fn find_column(&self, code: u64) -> Option<usize> {
        find_hashed(&self.col_keys, &self.col_table, code)
    }

    /// Fills the lookup of the occupied cells from `cell_keys`: the direct table
    /// [`NeighborList::dense`] when the grid has at most [`DENSE_CELLS_PER_GRAIN`] cells per
    /// grain (plus [`DENSE_CELLS_MIN`]), else the hash table [`NeighborList::cell_table`].
    fn fill_table(&mut self) {
        let [nx, ny, nz] = self.dims;
        let cells = nx.saturating_mul(ny).saturating_mul(nz);
        self.dense.clear();
        self.cell_table.clear();
        if cells <= DENSE_CELLS_PER_GRAIN * self.keyed.len() + DENSE_CELLS_MIN {
            self.dense.resize(cells, 0);
            for (c, &k) in self.cell_keys.iter().enumerate() {
                let at = self.dense_index(self.cell_of(k));
                self.dense[at] = c as u32 + 1;
            }
        } else {
            fill_hash(&self.cell_keys, &mut self.cell_table);
        }
    }

    /// Position of cell `[x, y, z]` in [`NeighborList::dense`]: x + nx (y + ny z).
    #[inline]
    fn dense_index(&self, [x, y, z]: [usize; 3]) -> usize {
        let [nx, ny, _] = self.dims;
        x + nx * (y + ny * z)
    }

    /// Index in `cell_keys` of the occupied cell `[x, y, z]` (inside the grid), if any: one
    /// load from the direct table, or a hash probe (expected O(1): the table is at most half
    /// full).
    #[inline]
    pub(super) fn find_cell(&self, [x, y, z]: [usize; 3]) -> Option<usize> {
        if self.dense.is_empty() {
            find_hashed(&self.cell_keys, &self.cell_table, self.key([x, y, z]))
        } else {
            match self.dense[self.dense_index([x, y, z])] {
                0 => None,
                e => Some(e as usize - 1),
            }
        }
    }

    /// Box size the grid was made for (m).
    pub fn box_size(&self) -> [f64; 3] {
        self.box_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn morton_codes_round_trip_and_interleave() {
        for x in [0u64, 1, 2, 5, 1000, (1 << 20) - 1, (1 << 21) - 1] {
            assert_eq!(compact3(spread3(x)), x);
        }
        let nl = NeighborList::new([1.0; 3], 0.01, 0.001);
        assert_eq!(nl.key([1, 0, 0]), 1);
        assert_eq!(nl.key([0, 1, 0]), 2);
        assert_eq!(nl.key([0, 0, 1]), 4);
        assert_eq!(nl.key([3, 3, 3]), 63);
        for x in [0u64, 1, 2, 5, 1000, (1 << 20) - 1, (1 << 21) - 1] {
            assert_eq!(compact2(spread2(x)), x);
        }
        let cols = NeighborList::new([1.0; 3], 0.01, 0.001).with_curve(Curve::Columns);
        assert_eq!(cols.key([0, 0, 1]), 1);
        assert_eq!(cols.key([1, 0, 0]), 1 << 21);
        assert_eq!(cols.key([0, 1, 0]), 2 << 21);
        // a whole column comes before the next one
        assert!(cols.key([0, 0, (1 << 21) - 1]) < cols.key([1, 0, 0]));
        for c in [[0, 0, 0], [3, 7, 1], [1000, 5, 77], [(1 << 21) - 1; 3]] {
            assert_eq!(cols.cell_of(cols.key(c)), c);
            assert_eq!(nl.cell_of(nl.key(c)), c);
        }
    }

    #[test]
    fn cell_lookup_finds_every_occupied_cell_and_no_other() {
        // clustered grains (a few cells crowded, most of the grid empty), then every cell of
        // the grid looked up against a binary search of the sorted occupied keys: through
        // the hash table (many cells per grain) and the direct table (few), on both curves
        let bx = [0.05, 0.04, 0.06];
        let mut s = 7u64;
        let mut rnd = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut hashed, mut direct) = (0, 0);
        for curve in [Curve::Morton, Curve::Columns] {
            for r in [0.001, 0.003] {
                for n in [1, 2, 3, 50, 700, 2000] {
                    let pos: Vec<[f64; 3]> = (0..n)
                        .map(|k| {
                            let c = if k % 3 == 0 { 0.2 } else { 0.8 };
                            [
                                c * bx[0] * rnd(),
                                bx[1] * rnd() * rnd(),
                                bx[2] * rnd().powi(3),
                            ]
                        })
                        .collect();
                    let mut nl = NeighborList::new(bx, r, 0.2 * r).with_curve(curve);
                    nl.rebuild(&pos, &vec![r; n], [0.0; 3]);
                    let [nx, ny, nz] = nl.dims();
                    if nx * ny * nz <= DENSE_CELLS_PER_GRAIN * n + DENSE_CELLS_MIN {
                        assert_eq!(nl.dense.len(), nx * ny * nz);
                        assert!(nl.cell_table.is_empty());
                        direct += 1;
                    } else {
                        assert!(nl.dense.is_empty());
                        assert!(nl.cell_table.len() >= 2 * nl.cell_keys.len());
                        hashed += 1;
                    }
                    let mut found = 0;
                    for x in 0..nx {
                        for y in 0..ny {
                            for z in 0..nz {
                                let k = nl.key([x, y, z]);
                                let want = nl.cell_keys.binary_search(&k).ok();
                                let got = nl.find_cell([x, y, z]);
                                assert_eq!(got, want, "{curve:?} r {r} n {n}: {x} {y} {z}");
                                found += want.is_some() as usize;
                            }
                        }
                    }
                    assert_eq!(found, nl.occupied_cells());
                }
            }
        }
        assert!(
            hashed >= 4 && direct >= 4,
            "{hashed} hashed, {direct} direct"
        );
    }
}
