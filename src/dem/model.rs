//! The resolved DEM damper: grains with their masses, the contact model, the box and the
//! initial bed, as the engine takes them. Built once from a scene by the resolve step
//! ([`crate::setup`]), which validates every value and names the scene key on error; the
//! engine checks only what the physics needs (array lengths, dt > 0).

use crate::contact::material::Material;
use crate::contact::ContactModel;

/// The grains of a bed: radii and masses (structure of arrays), their material and the bounds
/// of the radius distribution they were drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct Grains {
    /// Radii R_i (m).
    pub radius_m: Vec<f64>,
    /// Masses m_i = ρ (4/3) π R_i³ (kg).
    pub mass_kg: Vec<f64>,
    /// Grain density ρ (kg/m³).
    pub density_kg_m3: f64,
    /// Grain material E (Pa), ν (–).
    pub material: Material,
    /// Smallest radius the distribution can give (m): sets the shortest contact time.
    pub r_min_m: f64,
    /// Largest radius the distribution can give (m): sets the lattice spacing and the skin.
    pub r_max_m: f64,
}

impl Grains {
    /// Mass of a sphere of radius `r` (m) and density `density` (kg/m³): ρ (4/3) π r³ (kg).
    #[inline]
    pub fn sphere_mass(density: f64, r: f64) -> f64 {
        density * 4.0 / 3.0 * std::f64::consts::PI * r * r * r
    }

    /// Grains of radii `radius_m` (m) and density ρ (kg/m³), with distribution bounds
    /// [`r_min_m`, `r_max_m`] (m).
    pub fn new(
        radius_m: Vec<f64>,
        density_kg_m3: f64,
        material: Material,
        (r_min_m, r_max_m): (f64, f64),
    ) -> Grains {
        let mass_kg = radius_m
            .iter()
            .map(|&r| Grains::sphere_mass(density_kg_m3, r))
            .collect();
        Grains {
            radius_m,
            mass_kg,
            density_kg_m3,
            material,
            r_min_m,
            r_max_m,
        }
    }

    /// Number of grains.
    pub fn len(&self) -> usize {
        self.radius_m.len()
    }

    /// True without grains.
    pub fn is_empty(&self) -> bool {
        self.radius_m.is_empty()
    }

    /// Total mass m_p = Σ m_i (kg).
    pub fn total_mass_kg(&self) -> f64 {
        self.mass_kg.iter().sum()
    }
}

/// How the initial bed is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Packing {
    /// Grains dropped from a jittered FCC lattice and left to settle; `seed` draws the jitter.
    Lattice {
        /// Seed of the lattice jitter.
        seed: u64,
    },
    /// Advancing-front packing (SPEC §5) on the floor, then settled.
    AdvancingFront,
}

/// A resolved DEM damper: box, grains, contact model and the bed's construction.
#[derive(Debug, Clone, PartialEq)]
pub struct DemModel {
    /// Inner box size [Lx, Ly, Lz] (m): the box, or the cylinder's bounding box.
    pub box_size_m: [f64; 3],
    /// The cavity's shape inside `box_size_m`.
    pub container: crate::model::Container,
    /// The grains (radii, masses, material).
    pub grains: Grains,
    /// Contact laws (grain–grain, grain–wall) and the attraction policy.
    pub contact: ContactModel,
    /// Integrate angular velocities and frictional torques.
    pub rotations: bool,
    /// Track orientations as unit quaternions.
    pub orientations: bool,
    /// Verlet-list skin (m); `None`: 0.2 × the largest radius.
    pub neighbor_skin_m: Option<f64>,
    /// How the initial bed is built.
    pub packing: Packing,
    /// Longest settling time before the drive starts (s).
    pub settle_time_s: f64,
    /// Interval between particle snapshots (s); `None`: no snapshots.
    pub snapshot_interval_s: Option<f64>,
    /// A bag of bonded film nodes holding the grains (the bean-bag damper); its nodes follow
    /// the grains in the world's arrays.
    pub bag: Option<crate::dem::bag::Bag>,
}

impl DemModel {
    /// Verlet skin (m) for grains up to `r_max` (m): `neighbor_skin_m` or 0.2 r_max, the
    /// LIGGGHTS decks' choice (against 0.3 r_max: fewer candidate pairs per step for more
    /// frequent rebuilds; bench/README.md has the measurement).
    pub fn skin(&self, r_max: f64) -> f64 {
        self.neighbor_skin_m.unwrap_or(0.2 * r_max)
    }
}
