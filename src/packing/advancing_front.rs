//! Constructive advancing-front packing of spheres in a box (SPEC §5).
//!
//! Outside-in variant grown from the floor: the initial front is three mutually touching
//! spheres resting on the floor at its centre; then, repeatedly, a pivot is taken from the
//! front and a new sphere (radius drawn by Monte Carlo beforehand) is placed in contact with
//! the pivot and two of its neighbours — a neighbour may be a wall plane, as in the paper's
//! outside-in variant — inside the container and overlapping nothing. If no position exists
//! the pivot leaves the front. A regular cell grid makes each placement O(1).
//!
//! Front selection: the paper offers breadth/depth/random selection (9 combinations); for a
//! damper bed under gravity we take the pivot with the lowest centre (a priority queue, so
//! O(n log n)) and, among its feasible positions, the lowest one, which fills the floor layer
//! by layer like a sedimentation. Contact construction: exact "intersection of envelopes"
//! (trilateration of three offset spheres; sphere–sphere–plane and sphere–plane–plane
//! variants for the walls).
//!
//! # References
//! R. L. Roselló Valera, I. P. Pérez Morales, C. A. Recarey Morfa, "Algoritmo general de
//! empaquetamiento de partículas para el método de elementos discretos", Ingeniería
//! Mecánica 21(1) (2018); Y. T. Feng, K. Han & D. R. J. Owen, Int. J. Numer. Meth. Eng. 56,
//! 699 (2003).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::error::{ModelError, Quantity};

/// Volume fraction Σ (4/3)π r³ / V (–). Scaling every radius by λ multiplies it by λ³
/// (the paper's eq. 6 for porous media).
pub fn volume_fraction(radii: &[f64], volume_m3: f64) -> f64 {
    radii
        .iter()
        .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
        .sum::<f64>()
        / volume_m3
}

#[derive(Clone, Copy)]
struct Plane {
    axis: usize,
    /// +1: wall at 0 facing +axis; −1: wall at L facing −axis.
    sign: f64,
    at: f64,
}

impl Plane {
    /// Signed distance of p from the wall into the box (m).
    fn dist(&self, p: [f64; 3]) -> f64 {
        self.sign * (p[self.axis] - self.at)
    }
}

struct Grid {
    inv: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl Grid {
    fn new(box_m: [f64; 3], cell: f64) -> Self {
        let dims = [0, 1, 2].map(|d| ((box_m[d] / cell).ceil() as usize).max(1));
        Grid {
            inv: 1.0 / cell,
            dims,
            cells: vec![Vec::new(); dims[0] * dims[1] * dims[2]],
        }
    }
    fn coord(&self, p: [f64; 3]) -> [usize; 3] {
        [0, 1, 2].map(|d| ((p[d] * self.inv).floor().max(0.0) as usize).min(self.dims[d] - 1))
    }
    fn insert(&mut self, p: [f64; 3], id: u32) {
        let c = self.coord(p);
        self.cells[(c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]].push(id);
    }
    /// Calls f for every id in the 27 cells around p.
    fn around(&self, p: [f64; 3], mut f: impl FnMut(u32) -> bool) -> bool {
        let c = self.coord(p);
        for z in c[2].saturating_sub(1)..=(c[2] + 1).min(self.dims[2] - 1) {
            for y in c[1].saturating_sub(1)..=(c[1] + 1).min(self.dims[1] - 1) {
                for x in c[0].saturating_sub(1)..=(c[0] + 1).min(self.dims[0] - 1) {
                    for &id in &self.cells[(z * self.dims[1] + y) * self.dims[0] + x] {
                        if !f(id) {
                            return false;
                        }
                    }
                }
            }
        }
        true
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Points at distances ρ1, ρ2, ρ3 from c1, c2, c3 (trilateration; 0 or 2 solutions).
fn three_spheres(c: [[f64; 3]; 3], rho: [f64; 3]) -> Option<[[f64; 3]; 2]> {
    let d12 = sub(c[1], c[0]);
    let d = dot(d12, d12).sqrt();
    if d < 1e-15 {
        return None;
    }
    let ex = scale(d12, 1.0 / d);
    let d13 = sub(c[2], c[0]);
    let i = dot(ex, d13);
    let t = sub(d13, scale(ex, i));
    let tn = dot(t, t).sqrt();
    if tn < 1e-12 * d {
        return None;
    }
    let ey = scale(t, 1.0 / tn);
    let ez = cross(ex, ey);
    let j = dot(ey, d13);
    let x = (rho[0] * rho[0] - rho[1] * rho[1] + d * d) / (2.0 * d);
    let y = (rho[0] * rho[0] - rho[2] * rho[2] + i * i + j * j) / (2.0 * j) - i / j * x;
    let z2 = rho[0] * rho[0] - x * x - y * y;
    if z2 < 0.0 {
        return None;
    }
    let z = z2.sqrt();
    let base = add(c[0], add(scale(ex, x), scale(ey, y)));
    Some([add(base, scale(ez, z)), sub(base, scale(ez, z))])
}

/// Points at distances ρ1, ρ2 from c1, c2 lying on the plane p[axis] = at.
fn two_spheres_plane(
    c: [[f64; 3]; 2],
    rho: [f64; 2],
    axis: usize,
    at: f64,
) -> Option<[[f64; 3]; 2]> {
    let mut q = c;
    let mut s = [0.0; 2];
    for k in 0..2 {
        let delta = c[k][axis] - at;
        let s2 = rho[k] * rho[k] - delta * delta;
        if s2 < 0.0 {
            return None;
        }
        s[k] = s2.sqrt();
        q[k][axis] = at;
    }
    let dv = sub(q[1], q[0]);
    let d = dot(dv, dv).sqrt();
    if d < 1e-15 || d > s[0] + s[1] || d < (s[0] - s[1]).abs() {
        return None;
    }
    let ex = scale(dv, 1.0 / d);
    let mut nrm = [0.0; 3];
    nrm[axis] = 1.0;
    let ey = cross(nrm, ex);
    let x = (s[0] * s[0] - s[1] * s[1] + d * d) / (2.0 * d);
    let h = (s[0] * s[0] - x * x).max(0.0).sqrt();
    let base = add(q[0], scale(ex, x));
    Some([add(base, scale(ey, h)), sub(base, scale(ey, h))])
}

/// Points at distance ρ from c on the line p[a1] = at1, p[a2] = at2.
fn sphere_two_planes(
    c: [f64; 3],
    rho: f64,
    a1: usize,
    at1: f64,
    a2: usize,
    at2: f64,
) -> Option<[[f64; 3]; 2]> {
    let free = 3 - a1 - a2;
    let d2 = (c[a1] - at1).powi(2) + (c[a2] - at2).powi(2);
    let s2 = rho * rho - d2;
    if s2 < 0.0 {
        return None;
    }
    let s = s2.sqrt();
    let mut p = [0.0; 3];
    p[a1] = at1;
    p[a2] = at2;
    let (mut p1, mut p2) = (p, p);
    p1[free] = c[free] + s;
    p2[free] = c[free] - s;
    Some([p1, p2])
}

#[derive(PartialEq)]
struct FrontItem(f64, u32);
impl Eq for FrontItem {}
impl PartialOrd for FrontItem {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for FrontItem {
    fn cmp(&self, o: &Self) -> Ordering {
        // min-heap on z, ties by id
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

/// Most cells (one grain diameter wide) of the search grid of [`advancing_front_packing`].
pub const MAX_GRID_CELLS: f64 = 1e8;

/// Packs spheres of the given radii (m, in placement order) on the floor of a box (box frame,
/// floor at z = 0). Returns the centres (m), same order as `radii`.
///
/// # Formula
/// New centre x with |x − c_k| = r_k + r for the pivot and two neighbours, or
/// x·n_w = r from a wall, solved exactly (intersection of envelopes).
///
/// # Errors
/// [`ModelError`] on [`Quantity::GrainCount`] when the box cannot hold all spheres (the
/// front empties first; the resolve step, [`crate::setup`], names the scene keys), or when
/// the box is more than [`MAX_GRID_CELLS`] grain diameters in volume.
///
/// # Example
/// ```
/// let r = vec![0.003; 50];
/// let c = pdamp::packing::advancing_front_packing([0.03, 0.03, 0.1], &r).unwrap();
/// assert_eq!(c.len(), 50);
/// ```
pub fn advancing_front_packing(
    box_m: [f64; 3],
    radii: &[f64],
) -> Result<Vec<[f64; 3]>, ModelError> {
    let n = radii.len();
    if n == 0 {
        return Ok(Vec::new());
    }
    let r_max = radii.iter().cloned().fold(0.0, f64::max);
    let cells: f64 = box_m
        .iter()
        .map(|l| (l / (2.0 * r_max)).ceil().max(1.0))
        .product();
    if cells.is_nan() || cells > MAX_GRID_CELLS {
        return Err(ModelError::new(
            Quantity::GrainCount,
            n,
            format!(
                "the box [{:e}, {:e}, {:e}] m is {cells:.1e} grain diameters in volume, more than \
                 {MAX_GRID_CELLS:.0e}: a box that large is not a damper; make it smaller or the \
                 grains larger",
                box_m[0], box_m[1], box_m[2]
            ),
        ));
    }
    let mut grid = Grid::new(box_m, 2.0 * r_max);
    let mut centres: Vec<[f64; 3]> = Vec::with_capacity(n);
    let planes = [
        Plane {
            axis: 0,
            sign: 1.0,
            at: 0.0,
        },
        Plane {
            axis: 0,
            sign: -1.0,
            at: box_m[0],
        },
        Plane {
            axis: 1,
            sign: 1.0,
            at: 0.0,
        },
        Plane {
            axis: 1,
            sign: -1.0,
            at: box_m[1],
        },
        Plane {
            axis: 2,
            sign: 1.0,
            at: 0.0,
        },
    ];
    let tol = 1e-9 * r_max;
    let fits = |p: [f64; 3], r: f64, centres: &[[f64; 3]], grid: &Grid| -> bool {
        for d in 0..3 {
            if p[d] < r - tol || p[d] > box_m[d] - r + tol {
                return false;
            }
        }
        grid.around(p, |id| {
            let q = centres[id as usize];
            let rr = radii[id as usize] + r - tol;
            let v = sub(p, q);
            dot(v, v) >= rr * rr
        })
    };
    // initial front: three touching spheres on the floor at its centre
    let r0 = radii[0];
    centres.push([0.5 * box_m[0], 0.5 * box_m[1], r0]);
    grid.insert(centres[0], 0);
    let mut front = BinaryHeap::new();
    front.push(FrontItem(r0, 0));
    let mut next = 1;
    // second and third seeds: touching the first (and each other) and the floor
    if n > 1 {
        let r1 = radii[1];
        let p = [centres[0][0] + 2.0 * (r0 * r1).sqrt(), centres[0][1], r1];
        if fits(p, r1, &centres, &grid) {
            centres.push(p);
            grid.insert(p, 1);
            front.push(FrontItem(r1, 1));
            next = 2;
        }
    }
    if next == 2 && n > 2 {
        let r2 = radii[2];
        if let Some([p, _]) =
            two_spheres_plane([centres[0], centres[1]], [r0 + r2, radii[1] + r2], 2, r2)
        {
            if fits(p, r2, &centres, &grid) {
                centres.push(p);
                grid.insert(p, 2);
                front.push(FrontItem(r2, 2));
                next = 3;
            }
        }
    }
    while next < n {
        let Some(FrontItem(_, piv)) = front.peek().map(|f| FrontItem(f.0, f.1)) else {
            return Err(ModelError::new(
                Quantity::GrainCount,
                n,
                format!(
                    "the advancing front placed only {next} grains in the box; fewer grains or a \
                     larger box"
                ),
            ));
        };
        let r = radii[next];
        let pc = centres[piv as usize];
        let pr = radii[piv as usize];
        // neighbours of the pivot that a new sphere can touch together with it
        let mut neigh: Vec<u32> = Vec::new();
        grid.around(pc, |id| {
            if id != piv {
                let v = sub(centres[id as usize], pc);
                let reach = pr + radii[id as usize] + 2.0 * r;
                if dot(v, v) < reach * reach {
                    neigh.push(id);
                }
            }
            true
        });
        let walls: Vec<&Plane> = planes
            .iter()
            .filter(|w| w.dist(pc) < pr + 2.0 * r)
            .collect();
        let mut best: Option<[f64; 3]> = None;
        let consider = |cands: Option<[[f64; 3]; 2]>, best: &mut Option<[f64; 3]>| {
            if let Some(cs) = cands {
                for p in cs {
                    if best.is_none_or(|b| p[2] < b[2]) && fits(p, r, &centres, &grid) {
                        *best = Some(p);
                    }
                }
            }
        };
        let rho_p = pr + r;
        for (k, &a) in neigh.iter().enumerate() {
            let (ca, ra) = (centres[a as usize], radii[a as usize] + r);
            for &b in &neigh[k + 1..] {
                let (cb, rb) = (centres[b as usize], radii[b as usize] + r);
                consider(three_spheres([pc, ca, cb], [rho_p, ra, rb]), &mut best);
            }
            for w in &walls {
                let at = w.at + w.sign * r;
                consider(
                    two_spheres_plane([pc, ca], [rho_p, ra], w.axis, at),
                    &mut best,
                );
            }
        }
        for (k, w1) in walls.iter().enumerate() {
            for w2 in &walls[k + 1..] {
                if w1.axis != w2.axis {
                    let (a1, a2) = (w1.at + w1.sign * r, w2.at + w2.sign * r);
                    consider(
                        sphere_two_planes(pc, rho_p, w1.axis, a1, w2.axis, a2),
                        &mut best,
                    );
                }
            }
        }
        match best {
            Some(p) => {
                centres.push(p);
                grid.insert(p, next as u32);
                front.push(FrontItem(p[2], next as u32));
                next += 1;
            }
            None => {
                front.pop();
            }
        }
    }
    Ok(centres)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fuzzing regression (issue 14): the search grid of a box 1e6 m wide would not fit in
    /// memory; refused.
    #[test]
    fn a_huge_box_is_refused() {
        let e = advancing_front_packing([1e6, 1e6, 1e6], &[0.003; 10]).unwrap_err();
        assert!(e.hint.contains("grain diameters in volume"), "{e}");
    }

    #[test]
    fn trilateration_touches_all_three() {
        let c = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.7, 0.0]];
        let s = three_spheres(c, [2.0, 2.0, 2.0]).unwrap();
        for p in s {
            for ck in c {
                let v = sub(p, ck);
                assert!((dot(v, v).sqrt() - 2.0).abs() < 1e-12);
            }
        }
    }
}
