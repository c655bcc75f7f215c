//! The container's shape: a rectangular box, or a circular cylinder whose axis is along x, y
//! or z, inscribed in its bounding box.
//!
//! Both are described in the box frame: the bounding box [L₀, L₁, L₂] (m) with its corner at
//! the origin. A grain touches up to six walls, each in its own slot (the wall kernel's and the
//! tangential springs' storage): the box's x−, x+, y−, y+, z−, z+; the cylinder's two end caps in
//! the slots of its axis a (2a, 2a + 1) and its curved wall in slot 2u, u = (a + 1) mod 3, the
//! other two slots never touched.
//!
//! The curved wall of radius R_c = D/2: a sphere of radius r whose centre lies at distance ρ
//! from the axis overlaps it by ζ = r − (R_c − ρ) (m), along the inward normal
//! n = −(q⊥ − c⊥)/ρ (q⊥ the centre's coordinates across the axis, c⊥ the axis'). The contact
//! law is the flat wall's: the wall's curvature 1/R_c is left out of the equivalent radius
//! (for a 4 mm ball in a 12.5 mm bore Hertz's stiffness would be ~10 % higher).

/// A circular cylinder along a coordinate axis, inscribed in its bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// The axis (0 = x, 1 = y, 2 = z).
    pub axis: usize,
    /// Inner radius R_c = D/2 (m).
    pub radius_m: f64,
    /// Inner length L between the end caps (m).
    pub length_m: f64,
}

/// The container's shape (the engine's resolved form of `damper.container`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Container {
    /// The rectangular box filling its bounding box.
    #[default]
    Box,
    /// A cylinder inscribed in the bounding box.
    Cylinder(Cylinder),
}

/// Slots a grain never touches in a cylinder: overlap −∞.
const NONE: f64 = f64::NEG_INFINITY;

impl Cylinder {
    /// The cylinder of diameter `diameter_m` and length `length_m` along `axis`.
    pub fn new(axis: usize, diameter_m: f64, length_m: f64) -> Self {
        Cylinder {
            axis,
            radius_m: 0.5 * diameter_m,
            length_m,
        }
    }

    /// Its bounding box [L₀, L₁, L₂] (m): the length along the axis, the diameter across.
    pub fn bounding_box(&self) -> [f64; 3] {
        let mut b = [2.0 * self.radius_m; 3];
        b[self.axis] = self.length_m;
        b
    }

    /// The two axes across the cylinder's, (u, v) = (a + 1, a + 2) mod 3.
    #[inline(always)]
    pub fn across(&self) -> (usize, usize) {
        ((self.axis + 1) % 3, (self.axis + 2) % 3)
    }

    /// Offset (m) of the box-frame point `q` from the axis, across it: (Δu, Δv).
    #[inline(always)]
    fn offset(&self, q: [f64; 3]) -> (f64, f64) {
        let (u, v) = self.across();
        (q[u] - self.radius_m, q[v] - self.radius_m)
    }

    /// True when a sphere of radius `r` at `q` (box frame) touches no wall (m).
    #[inline(always)]
    pub fn clear_of_walls(&self, q: [f64; 3], r: f64) -> bool {
        let (du, dv) = self.offset(q);
        let room = self.radius_m - r;
        let a = q[self.axis];
        (du * du + dv * dv < room * room) & (a > r) & (a < self.length_m - r)
    }

    /// Overlaps (m) of a sphere of radius `r` at `q` (box frame) with the walls in the six
    /// slots (module doc); ≤ 0: no contact.
    #[inline(always)]
    pub fn overlaps(&self, q: [f64; 3], r: f64) -> [f64; 6] {
        let (du, dv) = self.offset(q);
        let rho = (du * du + dv * dv).sqrt();
        let a = q[self.axis];
        let mut z = [NONE; 6];
        z[2 * self.axis] = r - a;
        z[2 * self.axis + 1] = r - (self.length_m - a);
        z[2 * self.across().0] = r - (self.radius_m - rho);
        z
    }

    /// Inward unit normal of the wall in slot `w` at a sphere centred at `q` (box frame).
    #[inline(always)]
    pub fn normal(&self, q: [f64; 3], w: usize) -> [f64; 3] {
        let mut n = [0.0; 3];
        if w / 2 == self.axis {
            n[self.axis] = 1.0 - 2.0 * (w % 2) as f64;
        } else {
            let (u, v) = self.across();
            let (du, dv) = self.offset(q);
            let rho = (du * du + dv * dv).sqrt();
            // ρ > 0 at a contact (R_c > r is checked by the scene)
            n[u] = -du / rho;
            n[v] = -dv / rho;
        }
        n
    }

    /// Inner volume π R_c² L (m³).
    pub fn volume_m3(&self) -> f64 {
        std::f64::consts::PI * self.radius_m * self.radius_m * self.length_m
    }

    /// Inner volume below the height `h` (m) above the lowest inner point (z up): π R_c² h for
    /// a vertical axis, L times the circular segment's area of depth h for a horizontal one.
    pub fn volume_below_m3(&self, h: f64) -> f64 {
        let rc = self.radius_m;
        if self.axis == 2 {
            return std::f64::consts::PI * rc * rc * h.clamp(0.0, self.length_m);
        }
        let h = h.clamp(0.0, 2.0 * rc);
        // segment of depth h: R² acos((R − h)/R) − (R − h) √(2Rh − h²)
        let d = rc - h;
        let area = rc * rc * (d / rc).clamp(-1.0, 1.0).acos() - d * (2.0 * rc * h - h * h).sqrt();
        self.length_m * area
    }
}

impl Container {
    /// True when a sphere of radius `r` at `q` (box frame, bounding box `b`) lies wholly
    /// inside the container (m).
    pub fn holds(&self, b: [f64; 3], q: [f64; 3], r: f64) -> bool {
        self.overlaps(b, q, r).iter().all(|&z| z <= 0.0)
    }

    /// Overlaps (m) of a sphere of radius `r` at `q` (box frame, bounding box `b`) with the
    /// walls in the six slots; ≤ 0: no contact.
    pub fn overlaps(&self, b: [f64; 3], q: [f64; 3], r: f64) -> [f64; 6] {
        match self {
            Container::Box => [
                r - q[0],
                r - (b[0] - q[0]),
                r - q[1],
                r - (b[1] - q[1]),
                r - q[2],
                r - (b[2] - q[2]),
            ],
            Container::Cylinder(c) => c.overlaps(q, r),
        }
    }

    /// Inner volume (m³) of the container of bounding box `b`.
    pub fn volume_m3(&self, b: [f64; 3]) -> f64 {
        match self {
            Container::Box => b[0] * b[1] * b[2],
            Container::Cylinder(c) => c.volume_m3(),
        }
    }

    /// Inner volume (m³) below the height `h` above the floor (z up), for a bed's volume
    /// fraction.
    pub fn volume_below_m3(&self, b: [f64; 3], h: f64) -> f64 {
        match self {
            Container::Box => b[0] * b[1] * h,
            Container::Cylinder(c) => c.volume_below_m3(h),
        }
    }

    /// Name in the scene (`damper.container`).
    pub fn name(&self) -> &'static str {
        match self {
            Container::Box => "box",
            Container::Cylinder(_) => "cylinder",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sphere_against_the_curved_wall_overlaps_by_r_minus_the_gap() {
        let c = Cylinder::new(2, 0.0125, 0.037);
        assert_eq!(c.bounding_box(), [0.0125, 0.0125, 0.037]);
        // centre 4.5 mm from the axis along +x, r = 2 mm: overlap 2 − (6.25 − 4.5) = 0.25 mm
        let q = [0.00625 + 0.0045, 0.00625, 0.01];
        let z = c.overlaps(q, 0.002);
        assert!((z[0] - 0.00025).abs() < 1e-15, "{z:?}");
        assert!(z[1] == NONE && z[2] == NONE && z[3] == NONE);
        assert!((z[4] - (0.002 - 0.01)).abs() < 1e-15);
        assert_eq!(c.normal(q, 0), [-1.0, 0.0, 0.0]);
        assert_eq!(c.normal(q, 5), [0.0, 0.0, -1.0]);
        assert!(!c.clear_of_walls(q, 0.002));
        assert!(c.clear_of_walls([0.00625, 0.00625, 0.01], 0.002));
        // a diagonal offset: normal −(1, 1)/√2
        let s = 0.004 / 2f64.sqrt();
        let n = c.normal([0.00625 + s, 0.00625 + s, 0.01], 0);
        assert!((n[0] + 0.5f64.sqrt()).abs() < 1e-15 && (n[1] - n[0]).abs() < 1e-15);
    }

    #[test]
    fn volumes_are_the_solids() {
        let b = Cylinder::new(0, 0.02, 0.05);
        assert!((b.volume_m3() - std::f64::consts::PI * 1e-4 * 0.05).abs() < 1e-18);
        // a horizontal cylinder filled to its axis holds half its volume; full, all of it
        assert!((b.volume_below_m3(0.01) / b.volume_m3() - 0.5).abs() < 1e-12);
        assert!((b.volume_below_m3(0.02) / b.volume_m3() - 1.0).abs() < 1e-12);
        let v = Cylinder::new(2, 0.02, 0.05);
        assert!((v.volume_below_m3(0.025) / v.volume_m3() - 0.5).abs() < 1e-12);
        let bx = Container::Box;
        assert_eq!(bx.volume_m3([1.0, 2.0, 3.0]), 6.0);
        assert_eq!(bx.volume_below_m3([1.0, 2.0, 3.0], 0.5), 1.0);
    }

    #[test]
    fn holds_what_fits() {
        let c = Container::Cylinder(Cylinder::new(1, 0.01, 0.03));
        let b = [0.01, 0.03, 0.01];
        assert!(c.holds(b, [0.005, 0.015, 0.005], 0.004));
        // in the bounding box's corner, outside the cylinder
        assert!(!c.holds(b, [0.0015, 0.015, 0.0015], 0.001));
        assert!(Container::Box.holds(b, [0.0015, 0.015, 0.0015], 0.001));
    }
}
