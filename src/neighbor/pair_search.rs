//! The pair search of a prepared cell list: the candidate pairs of a run of occupied cells,
//! cell by cell along the curve and the half stencil, by one lookup per neighbour cell
//! ([`Curve::Morton`]) or by cursors walking up the neighbour columns ([`Curve::Columns`]).

use super::cell_grid::{Curve, NeighborList};
use super::morton::{spread2, HALF_STENCIL, Z_MASK};
use super::pair::Pair;

impl NeighborList {
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

    /// [`NeighborList::pairs_of_cells`] with one lookup (direct or hashed) per neighbour cell.
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
                    match self.find_cell([x, y, z]) {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::neighbor::morton::fill_hash;
    use crate::neighbor::pair::{index_by_grain, J_ROLE};

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
            // the direct cell table and the hash table find the same pairs in the same order
            assert!(!nl.dense.is_empty());
            let mut hashed = nl.clone();
            hashed.dense.clear();
            fill_hash(&hashed.cell_keys, &mut hashed.cell_table);
            let mut through_hash = Vec::new();
            hashed.pairs_by_hash(0..nl.occupied_cells(), &pos, &rad, &mut through_hash);
            assert_eq!(by_hash, through_hash, "{curve:?}");
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
