//! Storage order of a [`DemWorld`](super::DemWorld)'s grains: the curve sort at a
//! neighbour rebuild, the grain id of each slot, and what leaves the engine in grain-id order
//! (snapshots, [`DemWorld::set_velocities`](super::DemWorld::set_velocities)).

use nalgebra::UnitQuaternion;

use super::state::DemWorld;

/// `a` ← `a` gathered along `order` (`a[k]` = old `a[order[k]]`); `tmp` is the spare buffer.
pub(super) fn permute<T: Copy>(a: &mut Vec<T>, tmp: &mut Vec<T>, order: &[u32]) {
    tmp.clear();
    tmp.extend(order.iter().map(|&k| a[k as usize]));
    std::mem::swap(a, tmp);
}

/// `out` ← `a` in grain-id order (`out[id[k]]` = `a[k]`).
pub(super) fn scatter_by_id<T: Copy + Default>(a: &[T], id: &[u32], out: &mut Vec<T>) {
    out.clear();
    out.resize(a.len(), T::default());
    for (x, &g) in a.iter().zip(id) {
        out[g as usize] = *x;
    }
}

impl DemWorld {
    /// The grains' state now, for snapshots, in grain-id order (copied out of the storage
    /// order when the grains are sorted; the state itself is not changed).
    pub fn grain_state(&mut self) -> crate::observe::GrainState<'_> {
        if self.is_identity_order() {
            return crate::observe::GrainState {
                time_s: self.t,
                pos: &self.pos,
                vel: &self.vel,
                omega: &self.omega,
                radius: &self.radius,
                orientation: self.orientation.as_deref(),
                force: &self.force,
                box_size: self.box_size,
                box_origin: self.box_origin(),
                container: self.container,
            };
        }
        let box_origin = self.box_origin();
        let b = self.by_id.get_or_insert_with(Default::default);
        let id = &self.id;
        scatter_by_id(&self.pos, id, &mut b.pos);
        scatter_by_id(&self.vel, id, &mut b.vel);
        scatter_by_id(&self.omega, id, &mut b.omega);
        scatter_by_id(&self.force, id, &mut b.force);
        scatter_by_id(&self.radius, id, &mut b.radius);
        if let Some(q) = &self.orientation {
            b.orientation.clear();
            b.orientation.resize(q.len(), UnitQuaternion::identity());
            for (x, &g) in q.iter().zip(id) {
                b.orientation[g as usize] = *x;
            }
        }
        crate::observe::GrainState {
            time_s: self.t,
            pos: &b.pos,
            vel: &b.vel,
            omega: &b.omega,
            radius: &b.radius,
            orientation: self.orientation.as_ref().map(|_| &b.orientation[..]),
            force: &b.force,
            box_size: self.box_size,
            box_origin,
            container: self.container,
        }
    }

    /// Grain id of each storage slot of the per-grain arrays (the identity until the first
    /// curve sort).
    pub fn grain_ids(&self) -> &[u32] {
        &self.id
    }

    pub(super) fn is_identity_order(&self) -> bool {
        self.id.iter().enumerate().all(|(k, &g)| g as usize == k)
    }

    /// Stores the grains along the space-filling curve of their cells: permutes every
    /// per-grain array (state, predictions, coefficients, wall springs, ids). Forces and
    /// torques are carried too (the force pass after the rebuild overwrites them). Leaves the
    /// new slot of each old slot in `self.sort.inv`.
    pub(super) fn sort_along_curve(&mut self) {
        let shift = self.box_origin();
        let s = &mut self.sort;
        self.neighbors.curve_order(&self.pos, shift, &mut s.order);
        let order = &s.order;
        s.inv.clear();
        s.inv.resize(order.len(), 0);
        for (k, &o) in order.iter().enumerate() {
            s.inv[o as usize] = k as u32;
        }
        for a in [
            &mut self.pos,
            &mut self.vel,
            &mut self.omega,
            &mut self.vel_pred,
            &mut self.omega_pred,
            &mut self.force,
            &mut self.torque,
        ] {
            permute(a, &mut s.v3, order);
        }
        for a in [
            &mut self.radius,
            &mut self.mass,
            &mut self.inv_mass,
            &mut self.inv_inertia,
        ] {
            permute(a, &mut s.v1, order);
        }
        permute(&mut self.wall_coef, &mut s.coef, order);
        permute(&mut self.wall_history, &mut s.hist, order);
        permute(&mut self.id, &mut s.ids, order);
        if let Some(q) = self.orientation.as_mut() {
            permute(q, &mut s.quat, order);
        }
    }

    /// Sets grain velocities (m/s) and angular velocities (rad/s), given in grain-id order,
    /// e.g. for tests.
    pub fn set_velocities(&mut self, vel: &[[f64; 3]], omega: &[[f64; 3]]) {
        assert!(vel.len() == self.len() && omega.len() == self.len());
        for (k, &g) in self.id.iter().enumerate() {
            self.vel[k] = vel[g as usize];
            self.omega[k] = omega[g as usize];
        }
    }
}
