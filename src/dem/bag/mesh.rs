//! The bag's mesh: nodes on a closed cylinder (side rings and two end caps of concentric
//! rings) and their bonds, and the cylinder inside it that the grains are packed in.

use super::{dist, Bag, Bond, Film};
use crate::error::{ModelError, Quantity};
use crate::model::Cylinder;

/// Shape of a bag standing on the floor along z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BagGeometry {
    /// Outer diameter of the film (m).
    pub diameter_m: f64,
    /// Outer length of the film between its end caps (m).
    pub length_m: f64,
    /// Centre of the bag's cross-section in the box frame (x, y) (m).
    pub centre_m: [f64; 2],
    /// Node spacing s = 2 × node radius (m).
    pub spacing_m: f64,
}

impl BagGeometry {
    /// Radius of the circle through the side nodes' centres (m).
    pub fn node_circle_m(&self) -> f64 {
        0.5 * self.diameter_m - 0.5 * self.spacing_m
    }

    /// The cylinder the grains' centres are packed in, as a container of its own (inner film
    /// surface less nothing: the packing keeps its grains a radius from it), and the offset
    /// (m) of that container's corner in the box frame.
    pub fn interior(&self) -> (Cylinder, [f64; 3]) {
        let s = self.spacing_m;
        // the inner surface of the film: node circle less a node radius; caps likewise
        let r_in = self.node_circle_m() - 0.5 * s;
        let l_in = self.length_m - 2.0 * s;
        let corner = [self.centre_m[0] - r_in, self.centre_m[1] - r_in, s];
        (Cylinder::new(2, 2.0 * r_in, l_in), corner)
    }
}

/// Nodes on the ring of radius `rho` (m) at height `z` (m) about `centre`, `count` of them,
/// the first at angle `phase` (rad).
fn ring(centre: [f64; 2], rho: f64, z: f64, count: usize, phase: f64) -> Vec<[f64; 3]> {
    if count == 1 {
        return vec![[centre[0], centre[1], z]];
    }
    (0..count)
        .map(|k| {
            let a = phase + std::f64::consts::TAU * k as f64 / count as f64;
            [centre[0] + rho * a.cos(), centre[1] + rho * a.sin(), z]
        })
        .collect()
}

/// Nodes of a cap at height `z` (m): concentric rings inside the side's node circle `rho`.
fn cap(centre: [f64; 2], rho: f64, z: f64, s: f64) -> Vec<[f64; 3]> {
    let mut nodes = Vec::new();
    let rings = ((rho / s).floor() as usize).max(1);
    for j in 1..=rings {
        let r = rho * (rings - j) as f64 / rings as f64;
        let count = ((std::f64::consts::TAU * r / s).floor() as usize).max(1);
        nodes.extend(ring(centre, r, z, count, 0.0));
    }
    nodes
}

/// The bag of `geometry` and `film`: nodes on the side (rings along z of spacing ≈ s, a
/// square mesh) and
/// on the two caps (concentric rings), node mass from the film's mass, and a bond between
/// every two nodes closer than 1.5 s at rest — mesh bonds (≤ 1.2 s) with k₁, diagonal ones
/// with k₂ ([`Film`]).
///
/// # Errors
/// [`ModelError`] ([`Quantity::BagSize`]) when the bag is too small for its nodes (fewer
/// than three per ring or two rings).
pub fn bag_mesh(geometry: BagGeometry, film: Film) -> Result<Bag, ModelError> {
    let s = geometry.spacing_m;
    let rho = geometry.node_circle_m();
    // counts rounded down: no two nodes closer than s, so that touching neighbours do not
    // push the film taut before any load
    let per_ring = (std::f64::consts::TAU * rho / s).floor() as usize;
    let side = geometry.length_m - s;
    let rings = (side / s).floor() as usize;
    if per_ring < 3 || rings < 2 {
        return Err(ModelError::new(
            Quantity::BagSize,
            format!("{per_ring} nodes per ring, {rings} rings"),
            "the bag is too small for its node spacing",
        ));
    }
    let c = geometry.centre_m;
    let (z0, z1) = (0.5 * s, 0.5 * s + side);
    let mut nodes = Vec::new();
    for k in 0..=rings {
        let z = z0 + side * k as f64 / rings as f64;
        nodes.extend(ring(c, rho, z, per_ring, 0.0));
    }
    nodes.extend(cap(c, rho, z0, s));
    nodes.extend(cap(c, rho, z1, s));
    let area = std::f64::consts::PI * geometry.diameter_m * geometry.length_m
        + 0.5 * std::f64::consts::PI * geometry.diameter_m * geometry.diameter_m;
    let node_mass_kg = film.density_kg_m3 * film.thickness_m * area / nodes.len() as f64;
    let bonds = bond_nodes(&nodes, s, film, node_mass_kg);
    Ok(Bag {
        nodes,
        node_radius_m: 0.5 * s,
        node_mass_kg,
        bonds,
        film,
        geometry,
    })
}

/// A bond between every two of `nodes` closer than 1.5 `s` (m): mesh bonds (≤ 1.2 s) of
/// stiffness k₁, diagonal ones of k₂ ([`Film`]), damped at ζ_b = η/2 for nodes of
/// `node_mass_kg`.
pub fn bond_nodes(nodes: &[[f64; 3]], s: f64, film: Film, node_mass_kg: f64) -> Vec<Bond> {
    let (k1, k2) = (film.mesh_bond_stiffness(), film.diagonal_bond_stiffness());
    let zeta = 0.5 * film.loss_factor;
    let mut bonds = Vec::new();
    for i in 0..nodes.len() {
        for j in i + 1..nodes.len() {
            let d = dist(nodes[i], nodes[j]);
            if d < 1.5 * s {
                let k = if d <= 1.2 * s { k1 } else { k2 };
                bonds.push(Bond {
                    i: i as u32,
                    j: j as u32,
                    rest_m: d,
                    stiffness_n_m: k,
                    damping_kg_s: 2.0 * zeta * (k * 0.5 * node_mass_kg).sqrt(),
                });
            }
        }
    }
    bonds
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::material::Material;

    fn film() -> Film {
        Film {
            material: Material {
                youngs_modulus: 2.0e8,
                poisson: 0.46,
            },
            yield_strength_pa: 1.0e7,
            thickness_m: 1e-4,
            density_kg_m3: 920.0,
            loss_factor: 0.1,
        }
    }

    #[test]
    fn the_mesh_closes_the_bag_and_weighs_the_film() {
        let g = BagGeometry {
            diameter_m: 0.03,
            length_m: 0.038,
            centre_m: [0.015, 0.015],
            spacing_m: 0.002,
        };
        let bag = bag_mesh(g, film()).unwrap();
        // film mass: ρ t (π D L + π D²/2) = 920 × 1e-4 × 5.0e-3 m² = 0.46 g
        let area = std::f64::consts::PI * 0.03 * 0.038 + 0.5 * std::f64::consts::PI * 0.03 * 0.03;
        assert!((bag.mass_kg() - 920.0 * 1e-4 * area).abs() < 1e-12);
        // every node touches the outer surface of the bag, none leaves its bounding box
        for p in &bag.nodes {
            let r = ((p[0] - 0.015).powi(2) + (p[1] - 0.015).powi(2)).sqrt();
            assert!(r + 0.001 <= 0.015 + 1e-12, "{p:?}");
            assert!(p[2] >= 0.001 - 1e-12 && p[2] <= 0.037 + 1e-12, "{p:?}");
        }
        // no two nodes overlap (no prestress), every node is bonded (no loose node) to at
        // least three others
        let mut deg = vec![0usize; bag.nodes.len()];
        for b in &bag.bonds {
            deg[b.i as usize] += 1;
            deg[b.j as usize] += 1;
            assert!(b.rest_m < 0.003 && b.rest_m >= 0.002 - 1e-12, "{b:?}");
        }
        assert!(deg.iter().all(|&d| d >= 3), "{:?}", deg.iter().min());
    }

    #[test]
    fn a_flat_patch_of_the_mesh_is_the_films_membrane() {
        // a square patch of nodes bonded by the bag's rule, stretched by ε along x with y
        // held (uniaxial strain): the membrane stresses across a cut are N_x = C11 ε and
        // N_y = C12 ε; an isotropic film of modulus E t and ν = 1/3 has
        // C11 = E t/(1 − ν²) = (9/8) E t, C12 = ν C11 = (3/8) E t (plane stress). The
        // lattice is exact for a uniform strain, so 1e-9 relative (the strain's second order).
        let (s, n, eps) = (0.002, 12usize, 1e-6);
        let f = film();
        let nodes: Vec<[f64; 3]> = (0..n * n)
            .map(|k| [(k % n) as f64 * s, (k / n) as f64 * s, 0.0])
            .collect();
        let bonds = bond_nodes(&nodes, s, f, 1e-6);
        let moved: Vec<[f64; 3]> = nodes
            .iter()
            .map(|p| [p[0] * (1.0 + eps), p[1], 0.0])
            .collect();
        // the force carried across the line x = x_c (between columns 5 and 6) per unit length,
        // and across y = y_c
        let (xc, yc) = (5.5 * s, 5.5 * s);
        let (mut fx, mut fy) = (0.0, 0.0);
        for b in &bonds {
            let (a, c) = (nodes[b.i as usize], nodes[b.j as usize]);
            let (pa, pc) = (moved[b.i as usize], moved[b.j as usize]);
            let (Some((t, u)), _) = super::super::bonds::tension_of(b, pa, pc, [0.0; 3], [0.0; 3])
            else {
                continue;
            };
            // bonds whose midpoints lie in a band of six rows (columns) away from the patch's
            // edges: width 6 s
            let mid = [0.5 * (a[0] + c[0]) / s, 0.5 * (a[1] + c[1]) / s];
            if (a[0] - xc) * (c[0] - xc) < 0.0 && (2.0..8.0).contains(&mid[1]) {
                fx += t * u[0].abs();
            }
            if (a[1] - yc) * (c[1] - yc) < 0.0 && (2.0..8.0).contains(&mid[0]) {
                fy += t * u[1].abs();
            }
        }
        let (nx, ny) = (fx / (6.0 * s), fy / (6.0 * s));
        let et = f.material.youngs_modulus * f.thickness_m;
        assert!((nx / (eps * 9.0 / 8.0 * et) - 1.0).abs() < 1e-5, "{nx}");
        assert!((ny / (eps * 3.0 / 8.0 * et) - 1.0).abs() < 1e-5, "{ny}");
    }

    #[test]
    fn a_bag_too_small_for_its_nodes_is_refused() {
        let g = BagGeometry {
            diameter_m: 0.003,
            length_m: 0.01,
            centre_m: [0.0015, 0.0015],
            spacing_m: 0.002,
        };
        let e = bag_mesh(g, film()).unwrap_err();
        assert_eq!(e.quantity, Quantity::BagSize);
        assert!(e.hint.contains("too small"), "{e}");
    }
}
