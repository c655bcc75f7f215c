//! What a [`DemWorld`](super::DemWorld) reports about its state: contact counts, stored
//! energies, momentum, centre of mass, wall overlaps and the neighbour list's sizes.

use crate::contact::lanes::{dot, sub3};
use crate::contact::response::ContactCoefficients;
use crate::contact::{NormalLaw, TangentialLaw};
use crate::dem::energy::EnergyState;

use super::rebuild::touching;
use super::state::DemWorld;

/// Contact counts of a state ([`DemWorld::contact_counts`]). Twice `pair_contacts` per grain
/// is the mean coordination number of the grains among themselves; the cost of a step grows
/// with it (a pair in contact costs far more than a grain).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ContactCounts {
    /// Candidate pairs of the neighbour list (closer than R_i + R_j + skin).
    pub candidate_pairs: usize,
    /// Grain–grain pairs in contact.
    pub pair_contacts: usize,
    /// Grain–wall contacts.
    pub wall_contacts: usize,
}

impl std::ops::AddAssign for ContactCounts {
    fn add_assign(&mut self, o: ContactCounts) {
        self.candidate_pairs += o.candidate_pairs;
        self.pair_contacts += o.pair_contacts;
        self.wall_contacts += o.wall_contacts;
    }
}

/// Contacts per grain: a state's [`ContactCounts`] over the grain count,
/// or their mean over several states.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct ContactsPerGrain {
    /// Candidate pairs of the neighbour list per grain.
    pub candidate_pairs: f64,
    /// Grain–grain pairs in contact per grain (half the mean coordination number).
    pub pair_contacts: f64,
    /// Grain–wall contacts per grain.
    pub wall_contacts: f64,
}

impl ContactsPerGrain {
    /// The counts `c` of `n` grains, per grain (0 without grains).
    pub fn of(c: ContactCounts, n: usize) -> Self {
        let per = |k: usize| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        ContactsPerGrain {
            candidate_pairs: per(c.candidate_pairs),
            pair_contacts: per(c.pair_contacts),
            wall_contacts: per(c.wall_contacts),
        }
    }
}

impl DemWorld {
    /// Number of neighbour-list builds so far.
    pub fn neighbor_builds(&self) -> u64 {
        self.neighbors.builds
    }

    /// Candidate pairs currently in the Verlet list.
    pub fn pair_count(&self) -> usize {
        self.neighbors.pairs.len()
    }

    /// The contacts of the current state: candidate pairs of the neighbour list, grain–grain
    /// pairs in contact (overlap > 0) and grain–wall contacts.
    pub fn contact_counts(&self) -> ContactCounts {
        let mut c = ContactCounts {
            candidate_pairs: self.neighbors.pairs.len(),
            ..ContactCounts::default()
        };
        for p in &self.neighbors.pairs {
            c.pair_contacts += usize::from(touching(&self.pos, &self.radius, p));
        }
        for i in 0..self.len() {
            c.wall_contacts += self.wall_overlaps(i).iter().filter(|&&z| z > 0.0).count();
        }
        c
    }

    /// (grain blocks, candidate pairs across blocks) of the force pass ([`crate::dem::blocks`]).
    pub fn block_stats(&self) -> (usize, usize) {
        (self.blocks.blocks, self.blocks.cross_len())
    }

    /// The bean bag's bonds, if the damper has a bag.
    pub fn bag(&self) -> Option<&crate::dem::bag::BondPass> {
        self.bag.as_deref()
    }

    /// Stored energies now (J).
    pub fn energy_state(&self) -> EnergyState {
        let mut s = EnergyState::default();
        for i in 0..self.len() {
            let v = self.vel[i];
            let w = self.omega[i];
            s.kinetic_j += 0.5 * self.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            s.rotational_j += 0.5 / self.inv_inertia[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            let (g, p) = (self.gravity, self.pos[i]);
            s.potential_j -= self.mass[i] * (g[0] * p[0] + g[1] * p[1] + g[2] * p[2]);
            if let Some(r) = &self.rotation {
                s.potential_j += r.potential_j(self.mass[i], p);
            }
        }
        let elastic = |k: f64, z: f64| match self.laws.contact.normal {
            NormalLaw::HertzKuwabaraKono { .. } => 0.4 * k * z * z * z.sqrt(),
            NormalLaw::LinearSpringDashpot { .. } => 0.5 * k * z * z,
        };
        // tangential springs: ½ k_t |ξ|² (k_t = k_t' √ζ for Mindlin)
        let tangential = |c: &ContactCoefficients, z: f64, h: [f64; 3]| -> f64 {
            let kt = match self.laws.tangential_kind() {
                TangentialLaw::MindlinSpring { .. } => c[3] * z.sqrt(),
                TangentialLaw::LinearSpring { .. } => c[3],
                _ => return 0.0,
            };
            0.5 * kt * (h[0] * h[0] + h[1] * h[1] + h[2] * h[2])
        };
        for (a, (p, c)) in self.blocks.pairs.iter().zip(&self.pair_coef).enumerate() {
            let (i, j) = (p.i as usize, p.j as usize);
            let d = sub3(self.pos[i], self.pos[j]);
            let z = self.radius[i] + self.radius[j] - dot(d, d).sqrt();
            if z > 0.0 {
                s.elastic_j += elastic(c[0], z) + tangential(c, z, self.last_spring(a));
            }
        }
        for i in 0..self.len() {
            for (w, z) in self.wall_overlaps(i).into_iter().enumerate() {
                if z > 0.0 {
                    let c = &self.wall_coef[i];
                    s.elastic_j += elastic(c[0], z) + tangential(c, z, self.wall_history[i][w]);
                }
            }
        }
        if let Some(b) = &self.bag {
            s.elastic_j += b.elastic_energy_j(&self.pos);
        }
        if let Some(p) = self.drive.primary {
            let (u, _) = self.base_now();
            s.primary_j = 0.5 * p.mass_kg * self.box_v * self.box_v
                + 0.5 * p.stiffness_n_m * (self.box_z - u).powi(2);
        }
        s
    }

    /// Overlaps with the six walls (x−, x+, y−, y+, floor, ceiling; a cylinder's in the slots
    /// of [`crate::model::container`]) (m); ≤ 0 = no contact.
    pub fn wall_overlaps(&self, i: usize) -> [f64; 6] {
        let (p, o) = (self.pos[i], self.box_origin());
        let q = [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
        self.container.overlaps(self.box_size, q, self.radius[i])
    }

    /// Total linear momentum Σ m v (kg m/s).
    pub fn momentum(&self) -> [f64; 3] {
        let mut m = [0.0; 3];
        for (v, ma) in self.vel.iter().zip(&self.mass) {
            for d in 0..3 {
                m[d] += ma * v[d];
            }
        }
        m
    }

    /// Centre of mass z_cm and its velocity v_cm along the drive axis d of the grains at the
    /// end of the last [`DemWorld::step`] (m, m/s; the height and vertical velocity for the
    /// default vertical axis), as the step summed them (chunk by chunk, in its
    /// last phase: no extra pass over the grains); NaN before the first step. Equal to
    /// [`DemWorld::z_cm_state`] up to round-off right after a step.
    pub fn step_cm(&self) -> (f64, f64) {
        self.step_cm
    }

    /// Centre of mass z_cm and its velocity v_cm along the drive axis d (m, m/s; height and
    /// vertical velocity for the default vertical axis).
    pub fn z_cm_state(&self) -> (f64, f64) {
        let (mut zm, mut vm, mut mt) = (0.0, 0.0, 0.0);
        let d = self.drive.direction;
        for ((p, v), m) in self.pos.iter().zip(&self.vel).zip(&self.mass) {
            zm += m * dot(*p, d);
            vm += m * dot(*v, d);
            mt += m;
        }
        (zm / mt, vm / mt)
    }

    /// Centre of mass height z_cm (lab frame) and the lowest/highest grain centre (m).
    pub fn z_stats(&self) -> (f64, f64, f64) {
        let (mut zm, mut mt, mut lo, mut hi) = (0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY);
        for (p, m) in self.pos.iter().zip(&self.mass) {
            zm += m * p[2];
            mt += m;
            lo = lo.min(p[2]);
            hi = hi.max(p[2]);
        }
        (zm / mt, lo, hi)
    }
}
