//! The bonds' force pass: the tension of every stretched bond on its two nodes, the
//! dissipated power and the stored energy (formulas in [`super`]).

use super::{dist, Bag};

/// A bag inside a world: its bonds, where its nodes are stored, and the bonds' forces of the
/// last evaluation.
#[derive(Debug, Clone)]
pub struct BondPass {
    /// The bag (nodes, bonds, film).
    pub bag: Bag,
    /// Grain id of the bag's first node (the nodes follow the grains).
    pub first_id: usize,
    /// Storage slot of each node (refreshed whenever the world re-sorts its arrays).
    pub(crate) slot: Vec<u32>,
    /// Bond force on each storage slot (N), zero off the nodes.
    pub(crate) force: Vec<[f64; 3]>,
    /// Power dissipated in the bonds at the last evaluation (W).
    pub(crate) power_w: f64,
}

impl BondPass {
    /// The pass of `bag` whose first node has grain id `first_id`, in a world of `n`
    /// particles stored in id order.
    pub fn new(bag: Bag, first_id: usize, n: usize) -> BondPass {
        let slot = (first_id..first_id + bag.nodes.len())
            .map(|s| s as u32)
            .collect();
        BondPass {
            bag,
            first_id,
            slot,
            force: vec![[0.0; 3]; n],
            power_w: 0.0,
        }
    }

    /// Refreshes the nodes' slots from the world's slot → id map `ids`.
    pub(crate) fn reslot(&mut self, ids: &[u32]) {
        let (lo, hi) = (self.first_id, self.first_id + self.bag.nodes.len());
        for (s, &id) in ids.iter().enumerate() {
            let id = id as usize;
            if (lo..hi).contains(&id) {
                self.slot[id - lo] = s as u32;
            }
        }
    }

    /// Whether the particle of grain id `id` is one of the bag's nodes.
    pub(crate) fn is_node(&self, id: u32) -> bool {
        (id as usize) >= self.first_id
    }

    /// Evaluates every bond at positions `pos` (m) and velocities `vel` (m/s, the predicted
    /// ones), writing the forces per slot (N) and keeping the dissipated power (W).
    pub(crate) fn evaluate(&mut self, pos: &[[f64; 3]], vel: &[[f64; 3]]) {
        for f in &mut self.force {
            *f = [0.0; 3];
        }
        let mut power = 0.0;
        for b in &self.bag.bonds {
            let (i, j) = (
                self.slot[b.i as usize] as usize,
                self.slot[b.j as usize] as usize,
            );
            let (t, p) = tension_of(b, pos[i], pos[j], vel[i], vel[j]);
            let Some((t, n)) = t else { continue };
            power += p;
            let f = [t * n[0], t * n[1], t * n[2]];
            for (a, fk) in self.force[i].iter_mut().zip(f) {
                *a += fk;
            }
            for (a, fk) in self.force[j].iter_mut().zip(f) {
                *a -= fk;
            }
        }
        self.power_w = power;
    }

    /// The bonds' force on each storage slot at the last evaluation (N; zero off the nodes).
    pub fn forces(&self) -> &[[f64; 3]] {
        &self.force
    }

    /// Stretch (d − L₀)⁺ of every bond at positions `pos` (m), in bond order.
    fn stretches<'a>(&'a self, pos: &'a [[f64; 3]]) -> impl Iterator<Item = f64> + 'a {
        self.bag.bonds.iter().map(move |b| {
            let (i, j) = (
                self.slot[b.i as usize] as usize,
                self.slot[b.j as usize] as usize,
            );
            (dist(pos[i], pos[j]) - b.rest_m).max(0.0)
        })
    }

    /// Elastic energy stored in the stretched bonds at positions `pos` (J): Σ ½ k (d − L₀)⁺².
    pub fn elastic_energy_j(&self, pos: &[[f64; 3]]) -> f64 {
        self.stretches(pos)
            .zip(&self.bag.bonds)
            .map(|(x, b)| 0.5 * b.stiffness_n_m * x * x)
            .sum()
    }

    /// Tension of every bond at positions `pos` (N), elastic part k (d − L₀)⁺, in bond
    /// order.
    pub fn tensions(&self, pos: &[[f64; 3]]) -> Vec<f64> {
        self.stretches(pos)
            .zip(&self.bag.bonds)
            .map(|(x, b)| b.stiffness_n_m * x)
            .collect()
    }
}

/// The pull T (N) of bond `b` on node i towards j along the unit vector n̂ from i to j, when
/// the bond is stretched, and the power it dissipates (W).
#[inline]
pub(super) fn tension_of(
    b: &super::Bond,
    pi: [f64; 3],
    pj: [f64; 3],
    vi: [f64; 3],
    vj: [f64; 3],
) -> (Option<(f64, [f64; 3])>, f64) {
    let d = [pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let x = len - b.rest_m;
    if x <= 0.0 {
        return (None, 0.0);
    }
    let n = [d[0] / len, d[1] / len, d[2] / len];
    let rate = (vj[0] - vi[0]) * n[0] + (vj[1] - vi[1]) * n[1] + (vj[2] - vi[2]) * n[2];
    let elastic = b.stiffness_n_m * x;
    let t = (elastic + b.damping_kg_s * rate).max(0.0);
    (Some((t, n)), (t - elastic) * rate)
}

#[cfg(test)]
mod tests {
    use super::super::Bond;
    use super::*;

    fn bond() -> Bond {
        Bond {
            i: 0,
            j: 1,
            rest_m: 1e-3,
            stiffness_n_m: 100.0,
            damping_kg_s: 0.01,
        }
    }

    #[test]
    fn a_bond_pulls_when_stretched_and_never_pushes() {
        let b = bond();
        // stretched by 1 µm, at rest: T = k x = 1e-4 N, no power
        let (t, p) = tension_of(&b, [0.0; 3], [1.001e-3, 0.0, 0.0], [0.0; 3], [0.0; 3]);
        let (t, n) = t.unwrap();
        assert!((t - 100.0 * 1e-6).abs() < 1e-15 && n == [1.0, 0.0, 0.0] && p == 0.0);
        // separating at 1 mm/s: T = k x + c ḋ, power c ḋ² = 1e-8 W
        let (t, p) = tension_of(
            &b,
            [0.0; 3],
            [1.001e-3, 0.0, 0.0],
            [0.0; 3],
            [1e-3, 0.0, 0.0],
        );
        assert!((t.unwrap().0 - (1e-4 + 1e-5)).abs() < 1e-15);
        assert!((p - 0.01 * 1e-6).abs() < 1e-18);
        // closing fast: the dashpot would push; the film goes slack (T = 0) and the stored
        // energy's release is dissipated, k x |ḋ| ≥ 0
        let (t, p) = tension_of(
            &b,
            [0.0; 3],
            [1.001e-3, 0.0, 0.0],
            [0.0; 3],
            [-1.0, 0.0, 0.0],
        );
        assert_eq!(t.unwrap().0, 0.0);
        assert!((p - 100.0 * 1e-6 * 1.0).abs() < 1e-15);
        // compressed: no force at all
        assert!(
            tension_of(&b, [0.0; 3], [0.9e-3, 0.0, 0.0], [0.0; 3], [0.0; 3])
                .0
                .is_none()
        );
    }
}
