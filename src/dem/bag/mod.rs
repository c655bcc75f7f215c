//! The bean-bag damper's bag (the linear-DEM paper's §3.2, "flexible-constrained" particle
//! damper): a closed cylindrical film discretised as a particle–spring shell. The film's
//! nodes are spheres that touch the grains, each other and the walls through the scene's
//! contact law (with the film's material); neighbouring nodes are bonded by springs that carry
//! tension only (a film buckles instead of pushing), so that the shell holds the grains.
//!
//! # The film as a spring network
//! Nodes sit on a square-ish mesh of spacing s (node radius s/2, so that neighbours touch and
//! no grain passes between them). Each node is bonded to its neighbours along the mesh
//! (rest length ≈ s, stiffness k₁) and across its diagonals (≈ √2 s, k₂). A square network
//! of such springs is an isotropic membrane when k₁ = 2 k₂, with Poisson ratio 1/3 and
//! membrane (2-D) Young's modulus E₂ = (4/3) k₁ (N/m) (e.g. Ostoja-Starzewski, Appl. Mech.
//! Rev. 55, 35 (2002), the central-force square lattice). Matching E₂ to the film's E_f t
//! (Pa × m) gives
//!
//!   k₁ = (3/4) E_f t,  k₂ = (3/8) E_f t   (N/m),
//!
//! independent of s. Bending stiffness is left out: a polyethylene film of t = 0.1 mm bends
//! with D = E_f t³ / (12 (1 − ν²)) ≈ 2e-5 N m, nothing next to the grains' loads.
//!
//! A bond of rest length L₀ between nodes at distance d pulls with
//!
//!   T = max(0, k (d − L₀) + c ḋ)  for d > L₀, 0 otherwise   (N),
//!
//! ḋ = (v_j − v_i)·n̂ the stretch rate on the predicted velocities (as the contacts use), and
//! c = 2 ζ_b √(k m_node / 2) (kg/s): the film's loss factor η gives ζ_b = η/2 at the bond's
//! own frequency. Stored energy ½ k (d − L₀)² (J) while stretched; dissipated power
//! (T − k(d − L₀)) ḋ ≥ 0 (W), booked in the ledger as `bag_j`.
//!
//! Node mass: the film's mass ρ_f t × area, shared equally by the nodes.

mod bonds;
mod mesh;

pub use bonds::BondPass;
pub use mesh::{bag_mesh, BagGeometry};

use crate::contact::material::Material;

/// Distance between two points (m).
fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// One tension-only spring between two nodes of the bag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bond {
    /// First node (index among the bag's nodes).
    pub i: u32,
    /// Second node.
    pub j: u32,
    /// Rest length L₀ (m).
    pub rest_m: f64,
    /// Stiffness k (N/m).
    pub stiffness_n_m: f64,
    /// Damping c (kg/s).
    pub damping_kg_s: f64,
}

/// The film of the bag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Film {
    /// Elastic constants of the film (contacts of its nodes).
    pub material: Material,
    /// Yield strength of the film (Pa): the linear law's stiffness of its nodes' contacts.
    pub yield_strength_pa: f64,
    /// Thickness t (m).
    pub thickness_m: f64,
    /// Density ρ_f (kg/m³).
    pub density_kg_m3: f64,
    /// Loss factor η (–) of the film: bond damping ratio η/2.
    pub loss_factor: f64,
}

impl Film {
    /// Stiffness of a mesh bond k₁ = (3/4) E_f t (N/m).
    pub fn mesh_bond_stiffness(&self) -> f64 {
        0.75 * self.material.youngs_modulus * self.thickness_m
    }

    /// Stiffness of a diagonal bond k₂ = (3/8) E_f t (N/m).
    pub fn diagonal_bond_stiffness(&self) -> f64 {
        0.5 * self.mesh_bond_stiffness()
    }
}

/// The resolved bag: its nodes (after the grains in the world's arrays), bonds and film.
#[derive(Debug, Clone, PartialEq)]
pub struct Bag {
    /// Node centres at rest (m), in the box frame (box corner at the origin).
    pub nodes: Vec<[f64; 3]>,
    /// Node radius (m).
    pub node_radius_m: f64,
    /// Node mass (kg): the film's mass over the nodes.
    pub node_mass_kg: f64,
    /// Bonds between nodes.
    pub bonds: Vec<Bond>,
    /// The film.
    pub film: Film,
    /// The bag's shape as built (for the grains' placement and reports).
    pub geometry: BagGeometry,
}

impl Bag {
    /// Film mass (kg).
    pub fn mass_kg(&self) -> f64 {
        self.node_mass_kg * self.nodes.len() as f64
    }

    /// The largest Σ k over the bonds of one node (N/m): with the node mass it bounds the
    /// highest frequency of the network (Gershgorin: ω² ≤ 2 max Σk / m).
    pub fn max_node_stiffness(&self) -> f64 {
        let mut sum = vec![0.0; self.nodes.len()];
        for b in &self.bonds {
            sum[b.i as usize] += b.stiffness_n_m;
            sum[b.j as usize] += b.stiffness_n_m;
        }
        sum.into_iter().fold(0.0, f64::max)
    }

    /// Half period π/ω_max of the fastest bond vibration (s), ω_max = √(2 max Σk / m_node):
    /// the bag's analogue of a contact duration for the time step.
    pub fn bond_time_s(&self) -> f64 {
        let k = self.max_node_stiffness();
        if k > 0.0 {
            std::f64::consts::PI / (2.0 * k / self.node_mass_kg).sqrt()
        } else {
            f64::INFINITY
        }
    }
}
