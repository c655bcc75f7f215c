//! Sorted cell list + Verlet pair list (O(N) neighbour search, O(N) memory).
//!
//! Grains are keyed by their cell (cubic-ish cells of side ≥ 2 R_max + skin in the box frame)
//! and sorted by key; only occupied cells are kept, and a neighbour cell is found in an
//! open-addressing hash table of them (O(1) expected, against the O(log cells) of a binary
//! search: the 13 lookups per occupied cell were a third of a rebuild), so the memory does not
//! grow with the box volume. The key is the cell's
//! Morton (Z-order) code, so cells — and the pairs, which are listed cell by cell — follow a
//! space-filling curve; [`NeighborList::curve_order`] gives the same order for the grains, so
//! that the engine can store them along the curve. Each cell is compared with itself and its 13
//! "forward" neighbours, so every pair is found once (i < j in cell order) and its force is
//! computed once (Newton's third law). The list keeps every pair closer than
//! R_i + R_j + skin; it stays valid while every grain has moved less than skin/2 relative to
//! a common shift (the box displacement), because a common translation does not change any
//! pair distance: |Δr_ij| ≤ |d_i − s| + |d_j − s|.

/// One candidate pair of grains (indices into the grain arrays), i ≠ j.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pair {
    /// First grain.
    pub i: u32,
    /// Second grain.
    pub j: u32,
}

/// Bit set in the entries of [`index_by_grain`] where the grain is the pair's `j`.
pub const J_ROLE: u32 = 1 << 31;

/// Per-grain index of `pairs` of `n` grains (counting sort, pair order kept): grain g's
/// entries are `items[start[g]..start[g + 1]]`, each a pair index with [`J_ROLE`] set where g
/// is the pair's `j`. Reuses the buffers.
pub fn index_by_grain(pairs: &[Pair], n: usize, start: &mut Vec<u32>, items: &mut Vec<u32>) {
    start.clear();
    start.resize(n + 1, 0);
    for p in pairs {
        start[p.i as usize + 1] += 1;
        start[p.j as usize + 1] += 1;
    }
    for g in 0..n {
        start[g + 1] += start[g];
    }
    items.clear();
    items.resize(2 * pairs.len(), 0);
    // fill, using start[g] as g's cursor, then shift the ends back into starts
    for (k, p) in pairs.iter().enumerate() {
        let (i, j) = (p.i as usize, p.j as usize);
        items[start[i] as usize] = k as u32;
        start[i] += 1;
        items[start[j] as usize] = k as u32 | J_ROLE;
        start[j] += 1;
    }
    // start[g] now holds the end of g = the start of g + 1: shift back
    for g in (1..=n).rev() {
        start[g] = start[g - 1];
    }
    start[0] = 0;
}

/// Verlet neighbour list built with a sorted (hashed) cell list: only occupied cells are
/// stored, so its memory is O(N) whatever the box volume.
#[derive(Debug, Clone)]
pub struct NeighborList {
    /// Candidate pairs (valid until [`NeighborList::needs_rebuild`] says otherwise).
    pub pairs: Vec<Pair>,
    skin_m: f64,
    box_m: [f64; 3],
    dims: [usize; 3],
    inv_cell: [f64; 3],
    /// (cell key, grain) sorted by key then grain.
    keyed: Vec<(u64, u32)>,
    /// Keys of the occupied cells, ascending.
    cell_keys: Vec<u64>,
    /// Start of each occupied cell's grains in `keyed` (one more entry than cells).
    cell_start: Vec<u32>,
    /// Open-addressing hash table of the occupied cells (a power of two ≥ 2 × cells
    /// slots): a slot holds 1 + the cell's index in `cell_keys`, 0 when empty.
    cell_table: Vec<u32>,
    /// [`Curve::Columns`] only: the occupied columns' codes (key >> 21), ascending, and the
    /// start of each column's cells in `cell_keys` (one more entry than columns).
    col_keys: Vec<u64>,
    col_start: Vec<u32>,
    /// Open-addressing hash table of the occupied columns (as `cell_table`).
    col_table: Vec<u32>,
    ref_pos: Vec<[f64; 3]>,
    ref_shift: [f64; 3],
    /// Number of (re)builds so far.
    pub builds: u64,
    /// The space-filling curve of the cell keys.
    curve: Curve,
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
    fn key(&self, c: [usize; 3]) -> u64 {
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
    fn cell_of(&self, key: u64) -> [usize; 3] {
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

    /// The first half of a rebuild: reference positions, the sorted cell list and its hash
    /// tables. The pairs are then found by [`NeighborList::pairs_of_cells`] and stored in
    /// [`NeighborList::pairs`] by the caller.
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

    /// Appends to `out` the candidate pairs whose first grain lies in the occupied cells
    /// `cells` (indices in curve order, after [`NeighborList::prepare`]), in list order: the
    /// lists of consecutive runs of cells, concatenated, are the list of the whole.
    pub fn pairs_of_cells(
        &self,
        cells: std::ops::Range<usize>,
        pos: &[[f64; 3]],
        radius: &[f64],
        out: &mut Vec<Pair>,
    ) {
        match self.curve {
            Curve::Morton => self.pairs_by_hash(cells, pos, radius, out),
            Curve::Columns => self.pairs_by_columns(cells, pos, radius, out),
        }
    }

    /// [`NeighborList::pairs_of_cells`] with one hash lookup per neighbour cell.
    fn pairs_by_hash(
        &self,
        cells: std::ops::Range<usize>,
        pos: &[[f64; 3]],
        radius: &[f64],
        out: &mut Vec<Pair>,
    ) {
        let [nx, ny, nz] = self.dims;
        for c in cells {
            let key = self.cell_keys[c];
            let [cx, cy, cz] = self.cell_of(key);
            for (dx, dy, dz) in HALF_STENCIL {
                let (x, y, z) = (cx as isize + dx, cy as isize + dy, cz as isize + dz);
                if x < 0 || y < 0 || z < 0 {
                    continue;
                }
                let (x, y, z) = (x as usize, y as usize, z as usize);
                if x >= nx || y >= ny || z >= nz {
                    continue;
                }
                let same = (dx, dy, dz) == (0, 0, 0);
                let c2 = if same {
                    c
                } else {
                    match self.find_cell(self.key([x, y, z])) {
                        Some(c2) => c2,
                        None => continue,
                    }
                };
                self.cell_pairs(c, c2, (pos, radius), out);
            }
        }
    }

    /// [`NeighborList::pairs_of_cells`] for [`Curve::Columns`]: one hash lookup per
    /// neighbour *column* (9 per column), then each neighbour cell found by a cursor that
    /// walks up its column as the cells of this column go up. The same pairs in the same
    /// order as [`NeighborList::pairs_by_hash`] (unit test), for a fraction of the lookups.
    fn pairs_by_columns(
        &self,
        cells: std::ops::Range<usize>,
        pos: &[[f64; 3]],
        radius: &[f64],
        out: &mut Vec<Pair>,
    ) {
        if cells.is_empty() {
            return;
        }
        let [nx, ny, _] = self.dims;
        let z_of = |c: usize| self.cell_keys[c] & Z_MASK;
        // the column of the run's first cell
        let mut col = self
            .col_start
            .partition_point(|&s| s as usize <= cells.start)
            - 1;
        while col + 1 < self.col_start.len() && (self.col_start[col] as usize) < cells.end {
            let (c0, c1) = (
                (self.col_start[col] as usize).max(cells.start),
                (self.col_start[col + 1] as usize).min(cells.end),
            );
            let [cx, cy, _] = self.cell_of(self.cell_keys[c0]);
            // per (dx, dy) ∈ {−1, 0, 1}²: the neighbour column's cells, as [cursor, end)
            let mut cursor = [(0usize, 0usize); 9];
            for (k, cur) in cursor.iter_mut().enumerate() {
                let (x, y) = (
                    cx as isize + k as isize % 3 - 1,
                    cy as isize + k as isize / 3 - 1,
                );
                if x < 0 || y < 0 || x as usize >= nx || y as usize >= ny {
                    continue;
                }
                let code = spread2(x as u64) | (spread2(y as u64) << 1);
                if let Some(q) = self.find_column(code) {
                    *cur = (self.col_start[q] as usize, self.col_start[q + 1] as usize);
                }
            }
            for c in c0..c1 {
                let z = z_of(c);
                for (dx, dy, dz) in HALF_STENCIL {
                    let c2 = if (dx, dy, dz) == (0, 0, 0) {
                        c
                    } else {
                        let (cur, end) = &mut cursor[((dy + 1) * 3 + dx + 1) as usize];
                        while *cur < *end && z_of(*cur) < z {
                            *cur += 1;
                        }
                        // the first cell at z or above; one further for z + 1
                        let mut q = *cur;
                        if dz == 1 && q < *end && z_of(q) == z {
                            q += 1;
                        }
                        if q >= *end || z_of(q) != z + dz as u64 {
                            continue;
                        }
                        q
                    };
                    self.cell_pairs(c, c2, (pos, radius), out);
                }
            }
            col += 1;
        }
    }

    /// The candidate pairs (i in cell `c`, j in cell `c2`; i before j when `c2 == c`).
    #[inline]
    fn cell_pairs(
        &self,
        c: usize,
        c2: usize,
        (pos, radius): (&[[f64; 3]], &[f64]),
        out: &mut Vec<Pair>,
    ) {
        let skin = self.skin_m;
        let same = c == c2;
        let (a0, a1) = (self.cell_start[c] as usize, self.cell_start[c + 1] as usize);
        let (b0, b1) = (
            self.cell_start[c2] as usize,
            self.cell_start[c2 + 1] as usize,
        );
        for a in a0..a1 {
            let i = self.keyed[a].1 as usize;
            let (pi, ri) = (pos[i], radius[i]);
            let start = if same { a + 1 } else { b0 };
            for b in start..b1 {
                let j = self.keyed[b].1 as usize;
                let d = [pi[0] - pos[j][0], pi[1] - pos[j][1], pi[2] - pos[j][2]];
                let cut = ri + radius[j] + skin;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                    out.push(Pair {
                        i: i as u32,
                        j: j as u32,
                    });
                }
            }
        }
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
    fn find_column(&self, code: u64) -> Option<usize> {
        find_hashed(&self.col_keys, &self.col_table, code)
    }

    /// Fills [`NeighborList::cell_table`] from `cell_keys`.
    fn fill_table(&mut self) {
        fill_hash(&self.cell_keys, &mut self.cell_table);
    }

    /// Index in `cell_keys` of the occupied cell of key `key`, if any (expected O(1): the
    /// table is at most half full).
    #[inline]
    fn find_cell(&self, key: u64) -> Option<usize> {
        find_hashed(&self.cell_keys, &self.cell_table, key)
    }

    /// Box size the grid was made for (m).
    pub fn box_size(&self) -> [f64; 3] {
        self.box_m
    }
}

/// The height bits of a [`Curve::Columns`] key.
const Z_MASK: u64 = 0x1f_ffff;

/// An open-addressing hash table of the distinct `keys` (a power of two ≥ 2 × keys slots):
/// a slot holds 1 + the key's index in `keys`, 0 when empty.
fn fill_hash(keys: &[u64], table: &mut Vec<u32>) {
    let slots = (2 * keys.len()).next_power_of_two().max(2);
    table.clear();
    table.resize(slots, 0);
    let mask = slots - 1;
    for (c, &k) in keys.iter().enumerate() {
        let mut s = slot_of(k, mask);
        while table[s] != 0 {
            s = (s + 1) & mask;
        }
        table[s] = c as u32 + 1;
    }
}

/// Index in `keys` of `key` through its [`fill_hash`] table, if present.
#[inline]
fn find_hashed(keys: &[u64], table: &[u32], key: u64) -> Option<usize> {
    let mask = table.len() - 1;
    let mut s = slot_of(key, mask);
    loop {
        match table[s] {
            0 => return None,
            e if keys[e as usize - 1] == key => return Some(e as usize - 1),
            _ => s = (s + 1) & mask,
        }
    }
}

/// Home slot of cell key `key` in a table of `mask + 1` slots (Fibonacci hashing: the high
/// bits of key × 2⁶⁴/φ, which spread the Morton codes of neighbouring cells).
#[inline]
fn slot_of(key: u64, mask: usize) -> usize {
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 32) as usize & mask
}

/// The 21 low bits of `x` spread to every second bit (from bit 0).
#[inline]
fn spread2(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
    x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    x = (x | (x << 1)) & 0x5555_5555_5555_5555;
    x
}

/// Inverse of [`spread2`]: every second bit of `x` (from bit 0) packed into 21 bits.
#[inline]
fn compact2(x: u64) -> u64 {
    let mut x = x & 0x5555_5555_5555_5555;
    x = (x | (x >> 1)) & 0x3333_3333_3333_3333;
    x = (x | (x >> 2)) & 0x0f0f_0f0f_0f0f_0f0f;
    x = (x | (x >> 4)) & 0x00ff_00ff_00ff_00ff;
    x = (x | (x >> 8)) & 0x0000_ffff_0000_ffff;
    x = (x | (x >> 16)) & 0x0000_0000_ffff_ffff;
    x & 0x1f_ffff
}

/// The low 21 bits of `x` spread to every third bit (bit k → bit 3k).
#[inline]
fn spread3(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}

/// Inverse of [`spread3`]: every third bit of `x` (from bit 0) packed into 21 bits.
#[inline]
fn compact3(x: u64) -> u64 {
    let mut x = x & 0x1249_2492_4924_9249;
    x = (x | (x >> 2)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x >> 4)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x >> 8)) & 0x001f_0000_ff00_00ff;
    x = (x | (x >> 16)) & 0x001f_0000_0000_ffff;
    x = (x | (x >> 32)) & 0x1f_ffff;
    x
}

/// Own cell plus the 13 forward neighbours: each unordered cell pair is visited once.
const HALF_STENCIL: [(isize, isize, isize); 14] = [
    (0, 0, 0),
    (1, 0, 0),
    (-1, 1, 0),
    (0, 1, 0),
    (1, 1, 0),
    (-1, -1, 1),
    (0, -1, 1),
    (1, -1, 1),
    (-1, 0, 1),
    (0, 0, 1),
    (1, 0, 1),
    (-1, 1, 1),
    (0, 1, 1),
    (1, 1, 1),
];

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
    fn cell_table_finds_every_occupied_cell_and_no_other() {
        // clustered grains (a few cells crowded, most of the grid empty), then every cell of
        // the grid looked up against a binary search of the sorted occupied keys
        let bx = [0.05, 0.04, 0.06];
        let mut s = 7u64;
        let mut rnd = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1, 2, 3, 50, 700] {
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
            let mut nl = NeighborList::new(bx, 0.001, 0.0002);
            nl.rebuild(&pos, &vec![0.001; n], [0.0; 3]);
            assert!(nl.cell_table.len() >= 2 * nl.cell_keys.len());
            let [nx, ny, nz] = nl.dims();
            let mut found = 0;
            for x in 0..nx {
                for y in 0..ny {
                    for z in 0..nz {
                        let k = nl.key([x, y, z]);
                        let want = nl.cell_keys.binary_search(&k).ok();
                        assert_eq!(nl.find_cell(k), want, "n {n}, cell {x} {y} {z}");
                        found += want.is_some() as usize;
                    }
                }
            }
            assert_eq!(found, nl.occupied_cells());
        }
    }

    #[test]
    fn column_cursors_find_the_pairs_of_the_hash_lookups_in_their_order() {
        // a dense layer and a sparse gas above it, with empty cells and gaps in the columns
        let bx = [0.031, 0.023, 0.05];
        let mut s = 99u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let n = 900;
        let pos: Vec<[f64; 3]> = (0..n)
            .map(|k| {
                let z = if k % 4 == 0 {
                    0.05 * rnd()
                } else {
                    0.012 * rnd()
                };
                [rnd() * bx[0], rnd() * bx[1], z + 0.003]
            })
            .collect();
        let rad: Vec<f64> = (0..n).map(|_| 0.0008 + 0.0004 * rnd()).collect();
        for curve in [Curve::Morton, Curve::Columns] {
            let mut nl = NeighborList::new(bx, 0.0012, 0.0003).with_curve(curve);
            nl.rebuild(&pos, &rad, [0.0, 0.0, 0.003]);
            let whole = nl.pairs.clone();
            assert!(whole.len() > n);
            // every pair closer than R_i + R_j + skin, once (brute force)
            let mut got: Vec<(u32, u32)> =
                whole.iter().map(|p| (p.i.min(p.j), p.i.max(p.j))).collect();
            got.sort_unstable();
            let mut want = Vec::new();
            for i in 0..n {
                for j in i + 1..n {
                    let d2: f64 = (0..3).map(|k| (pos[i][k] - pos[j][k]).powi(2)).sum();
                    let cut = rad[i] + rad[j] + 0.0003;
                    if d2 < cut * cut {
                        want.push((i as u32, j as u32));
                    }
                }
            }
            assert_eq!(got, want, "{curve:?}");
            let mut by_hash = Vec::new();
            nl.pairs_by_hash(0..nl.occupied_cells(), &pos, &rad, &mut by_hash);
            assert_eq!(whole, by_hash, "{curve:?}");
            // runs of cells, listed one after the other, give the whole list
            let mut runs = Vec::new();
            for units in [1, 2, 3, 7, 64, 5000] {
                nl.cell_runs(units, &mut runs);
                assert_eq!(runs.len(), units + 1);
                assert!(runs.windows(2).all(|w| w[0] <= w[1]));
                assert_eq!(*runs.last().unwrap(), nl.occupied_cells());
                let mut cat = Vec::new();
                for w in runs.windows(2) {
                    nl.pairs_of_cells(w[0]..w[1], &pos, &rad, &mut cat);
                }
                assert_eq!(cat, whole, "{curve:?}, {units} runs");
            }
            // the runs share the grains out about evenly
            nl.cell_runs(4, &mut runs);
            for w in runs.windows(2) {
                let g = (nl.cell_start[w[1]] - nl.cell_start[w[0]]) as usize;
                assert!(
                    g > n / 8 && g < n / 2,
                    "{curve:?}: {g} grains in a run of 4"
                );
            }
        }
    }

    #[test]
    fn grid_finds_exactly_the_brute_force_pairs() {
        // pseudo-random cloud (LCG, fixed) in a 3×2×5 cm box
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let bx = [0.03, 0.02, 0.05];
        let n = 400;
        let pos: Vec<[f64; 3]> = (0..n)
            .map(|_| [rnd() * bx[0], rnd() * bx[1], 0.01 + rnd() * bx[2]])
            .collect();
        let rad: Vec<f64> = (0..n).map(|_| 0.001 + 0.001 * rnd()).collect();
        let mut nl = NeighborList::new(bx, 0.002, 0.0005);
        nl.rebuild(&pos, &rad, [0.0, 0.0, 0.01]);
        let mut got: Vec<(u32, u32)> = nl
            .pairs
            .iter()
            .map(|p| (p.i.min(p.j), p.i.max(p.j)))
            .collect();
        got.sort();
        let mut want = vec![];
        for i in 0..n {
            for j in i + 1..n {
                let d: f64 = (0..3)
                    .map(|k| (pos[i][k] - pos[j][k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                if d < rad[i] + rad[j] + 0.0005 {
                    want.push((i as u32, j as u32));
                }
            }
        }
        assert_eq!(got, want);
        assert!(!want.is_empty());
        // the per-grain index lists every pair of each grain once, in pair order
        let (mut start, mut items) = (Vec::new(), Vec::new());
        index_by_grain(&nl.pairs, n, &mut start, &mut items);
        for g in 0..n {
            let mine: Vec<usize> = items[start[g] as usize..start[g + 1] as usize]
                .iter()
                .map(|&e| {
                    let k = (e & !J_ROLE) as usize;
                    let p = nl.pairs[k];
                    assert_eq!(if e & J_ROLE != 0 { p.j } else { p.i } as usize, g);
                    k
                })
                .collect();
            let want: Vec<usize> = (0..nl.pairs.len())
                .filter(|&k| nl.pairs[k].i as usize == g || nl.pairs[k].j as usize == g)
                .collect();
            assert_eq!(mine, want);
        }
        // memory does not follow the box volume: a 1 km box holds no more than the grains need
        let mut big = NeighborList::new([1e3, 1e3, 1e3], 0.002, 0.0005);
        big.rebuild(&pos, &rad, [0.0; 3]);
        assert!(big.memory_bytes() < 200 * n + 16 * big.pairs.len() + 4096);
        // a common translation does not invalidate the list; a single grain moving does
        let moved: Vec<[f64; 3]> = pos.iter().map(|p| [p[0], p[1], p[2] + 0.01]).collect();
        assert!(!nl.needs_rebuild(&moved, [0.0, 0.0, 0.02]));
        let mut one = pos.clone();
        one[7][0] += 0.0003;
        assert!(nl.needs_rebuild(&one, [0.0, 0.0, 0.01]));
    }
}
