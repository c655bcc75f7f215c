//! Cell grid + Verlet pair list (O(N) neighbour search).
//!
//! Grains are binned (counting sort, no allocation after the first build) into cubic-ish cells
//! of side ≥ 2 R_max + skin in the box frame; each cell is compared with itself and its 13
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

/// Verlet neighbour list built with a cell grid over the box.
#[derive(Debug, Clone)]
pub struct NeighborList {
    /// Candidate pairs (valid until [`NeighborList::needs_rebuild`] says otherwise).
    pub pairs: Vec<Pair>,
    skin_m: f64,
    box_m: [f64; 3],
    dims: [usize; 3],
    inv_cell: [f64; 3],
    cell_count: Vec<u32>,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    cell_of: Vec<u32>,
    ref_pos: Vec<[f64; 3]>,
    ref_shift: [f64; 3],
    /// Number of (re)builds so far.
    pub builds: u64,
}

impl NeighborList {
    /// Prepares a grid for a box of size `box_m` (m), grains up to `r_max` (m), skin (m).
    pub fn new(box_m: [f64; 3], r_max: f64, skin_m: f64) -> Self {
        let cell = 2.0 * r_max + skin_m;
        let mut dims = [1usize; 3];
        let mut inv_cell = [0.0; 3];
        for d in 0..3 {
            dims[d] = ((box_m[d] / cell).floor() as usize).clamp(1, 1 << 20);
            inv_cell[d] = dims[d] as f64 / box_m[d];
        }
        let n_cells = dims[0] * dims[1] * dims[2];
        NeighborList {
            pairs: Vec::new(),
            skin_m,
            box_m,
            dims,
            inv_cell,
            cell_count: vec![0; n_cells],
            cell_start: vec![0; n_cells + 1],
            cell_items: Vec::new(),
            cell_of: Vec::new(),
            ref_pos: Vec::new(),
            ref_shift: [0.0; 3],
            builds: 0,
        }
    }

    /// Verlet skin (m).
    pub fn skin(&self) -> f64 {
        self.skin_m
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    #[inline]
    fn cell_index(&self, p: [f64; 3]) -> usize {
        let mut c = [0usize; 3];
        for d in 0..3 {
            let x = (p[d] * self.inv_cell[d]).floor();
            c[d] = if x <= 0.0 {
                0
            } else {
                (x as usize).min(self.dims[d] - 1)
            };
        }
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
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

    /// Rebuilds the pair list: all pairs with |r_i − r_j| < R_i + R_j + skin.
    ///
    /// `pos` are lab-frame centres (m), `shift` the box origin in the lab frame (m).
    pub fn rebuild(&mut self, pos: &[[f64; 3]], radius: &[f64], shift: [f64; 3]) {
        let n = pos.len();
        self.builds += 1;
        self.ref_pos.clear();
        self.ref_pos.extend_from_slice(pos);
        self.ref_shift = shift;
        self.cell_of.resize(n, 0);
        self.cell_items.resize(n, 0);
        self.cell_count.iter_mut().for_each(|c| *c = 0);
        for (i, q) in pos.iter().enumerate() {
            let c = self.cell_index([q[0] - shift[0], q[1] - shift[1], q[2] - shift[2]]);
            self.cell_of[i] = c as u32;
            self.cell_count[c] += 1;
        }
        let mut acc = 0u32;
        for (c, &cnt) in self.cell_count.iter().enumerate() {
            self.cell_start[c] = acc;
            acc += cnt;
        }
        let nc = self.cell_count.len();
        self.cell_start[nc] = acc;
        // fill (reuse cell_count as a cursor)
        for c in 0..nc {
            self.cell_count[c] = self.cell_start[c];
        }
        for i in 0..n {
            let c = self.cell_of[i] as usize;
            self.cell_items[self.cell_count[c] as usize] = i as u32;
            self.cell_count[c] += 1;
        }
        self.pairs.clear();
        let [nx, ny, nz] = self.dims;
        let skin = self.skin_m;
        for cz in 0..nz {
            for cy in 0..ny {
                for cx in 0..nx {
                    let c = (cz * ny + cy) * nx + cx;
                    let (a0, a1) = (self.cell_start[c] as usize, self.cell_start[c + 1] as usize);
                    if a0 == a1 {
                        continue;
                    }
                    for (dx, dy, dz) in HALF_STENCIL {
                        let (x, y, z) = (cx as isize + dx, cy as isize + dy, cz as isize + dz);
                        if x < 0 || y < 0 || z < 0 {
                            continue;
                        }
                        let (x, y, z) = (x as usize, y as usize, z as usize);
                        if x >= nx || y >= ny || z >= nz {
                            continue;
                        }
                        let c2 = (z * ny + y) * nx + x;
                        let (b0, b1) = (
                            self.cell_start[c2] as usize,
                            self.cell_start[c2 + 1] as usize,
                        );
                        let same = c2 == c;
                        for a in a0..a1 {
                            let i = self.cell_items[a] as usize;
                            let (pi, ri) = (pos[i], radius[i]);
                            let start = if same { a + 1 } else { b0 };
                            for b in start..b1 {
                                let j = self.cell_items[b] as usize;
                                let d = [pi[0] - pos[j][0], pi[1] - pos[j][1], pi[2] - pos[j][2]];
                                let cut = ri + radius[j] + skin;
                                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                                    self.pairs.push(Pair {
                                        i: i as u32,
                                        j: j as u32,
                                    });
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Box size the grid was made for (m).
    pub fn box_size(&self) -> [f64; 3] {
        self.box_m
    }
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
        // a common translation does not invalidate the list; a single grain moving does
        let moved: Vec<[f64; 3]> = pos.iter().map(|p| [p[0], p[1], p[2] + 0.01]).collect();
        assert!(!nl.needs_rebuild(&moved, [0.0, 0.0, 0.02]));
        let mut one = pos.clone();
        one[7][0] += 0.0003;
        assert!(nl.needs_rebuild(&one, [0.0, 0.0, 0.01]));
    }
}
