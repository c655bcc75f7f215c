//! The time step of a [`DemWorld`](super::DemWorld): drive and box equation, the half kicks
//! and drift, the choice of executor, and the ledger's box terms.

use crate::dem::blocks::GRAIN_CHUNK;
use crate::dem::energy::EnergyLedger;
use crate::dem::team::{Parts, Team};
use crate::integrate::advance_orientation;

use super::drift::Drift;
use super::state::{DemWorld, Mode};

impl DemWorld {
    /// Base displacement and velocity now (zero motion while the drive is off).
    pub fn base_now(&self) -> (f64, f64) {
        if self.drive_on {
            self.drive.base(self.t)
        } else {
            (self.box_z_hold(), 0.0)
        }
    }

    pub(super) fn box_z_hold(&self) -> f64 {
        if self.drive.primary.is_none() {
            self.box_z
        } else {
            0.0
        }
    }

    /// Starts the drive at t = 0: resets time and ledger. A kinematic box is placed at u(0);
    /// a box on a primary keeps its position and velocity (e.g. settled static equilibrium).
    pub fn start_drive(&mut self) {
        self.t = 0.0;
        self.drive_on = true;
        self.settle_drag = 0.0;
        self.ledger = EnergyLedger::default();
        if self.drive.primary.is_none() {
            let (u, v) = self.drive.base(0.0);
            self.move_grains_along_axis(u - self.box_z);
            self.box_z = u;
            self.box_v = v;
        }
        self.compute_forces();
        self.box_a = self.box_acceleration();
        let (bp, vp) = self.box_powers();
        self.base_power_prev = bp;
        self.viscous_power_prev = vp;
    }

    /// Moves the box (and the grains with it) to `z` (m) along the drive axis without
    /// changing velocities.
    pub fn shift_box_to(&mut self, z: f64) {
        self.move_grains_along_axis(z - self.box_z);
        self.box_z = z;
    }

    /// Moves every grain by `dz` (m) along the drive axis.
    fn move_grains_along_axis(&mut self, dz: f64) {
        let d = self.drive.direction;
        let s = [d[0] * dz, d[1] * dz, d[2] * dz];
        for p in &mut self.pos {
            p[0] += s[0];
            p[1] += s[1];
            p[2] += s[2];
        }
    }

    /// The box's corner (floor, x = y = 0) now: `box_z`·d (m).
    #[inline]
    pub fn box_origin(&self) -> [f64; 3] {
        let d = self.drive.direction;
        [d[0] * self.box_z, d[1] * self.box_z, d[2] * self.box_z]
    }

    /// Advances one time step.
    ///
    /// Stages, in order:
    /// 1. half kick of grain velocities, angular velocities and the box velocity (2.2.5);
    /// 2. drift of positions (2.2.4) and orientations (unit quaternions, renormalised,
    ///    2.4.11–2.4.17, only if enabled); the box moves with the primary or the base;
    /// 3. neighbour search: the Verlet list is rebuilt on the cell grid only when a grain has
    ///    moved more than skin/2 relative to the box;
    /// 4. contact forces: gravity, grain–grain contacts (once per pair, Newton's third law),
    ///    grain–wall contacts, their torques and F_gz (2.2.8–2.2.15); velocity-dependent terms
    ///    use the predicted full-step velocity v(t+dt/2) + (dt/2) F(t)/m, so that damping and
    ///    its ledger entry are second-order accurate (with v(t+dt/2) the ledger misses O(dt));
    /// 5. box equation (2.1.22): M z'' = −C(z' − u') − K(z − u) + F_gz (+ F0 sin Ωt for a
    ///    force drive), z along the drive axis d and F_gz = F·d;
    /// 6. second half kick;
    /// 7. energy ledger: collision and friction dissipation, viscous loss in C, base work.
    pub fn step(&mut self) {
        let dt = self.dt;
        let h = 0.5 * dt;
        // 1.–2. box first (its new position is the common shift of the displacement check)
        let primary_free = self.drive_on && self.drive.primary.is_some();
        if primary_free {
            self.box_v += h * self.box_a;
        }
        if self.drive_on {
            self.t += dt;
            if primary_free {
                self.box_z += dt * self.box_v;
            } else {
                let (u, v) = self.drive.base(self.t);
                self.box_z = u;
                self.box_v = v;
            }
        }
        // half kick + drift of the grains, fused with the Verlet-list displacement check
        let (o, r) = (self.box_origin(), self.neighbors.reference().1);
        let shift = [o[0] - r[0], o[1] - r[1], o[2] - r[2]];
        self.mode = self.choose_mode();
        self.box_v_pred = if primary_free {
            self.box_v + h * self.box_a
        } else {
            self.box_v
        };
        // 2.–4. drift, neighbours and forces; 6. the grains' second half kick rides on the
        // per-grain pass of the forces (a grain's force is complete there)
        let (p_coll, p_fric) = self.drift_and_forces(shift);
        if let Some(q) = self.orientation.as_mut() {
            for (q, w) in q.iter_mut().zip(&self.omega) {
                advance_orientation(q, *w, dt);
            }
        }
        // 5. box equation
        if primary_free {
            self.box_a = self.box_acceleration();
        }
        // 6. the box's second half kick
        if primary_free {
            self.box_v += h * self.box_a;
        }
        // 7. ledger
        if !self.energy_ledger {
            self.steps += 1;
            return;
        }
        self.ledger.collision_j += p_coll * dt;
        self.ledger.friction_j += p_fric * dt;
        if let Some(b) = &self.bag {
            self.ledger.bag_j += b.power_w * dt;
        }
        if self.drive_on {
            let (bp, vp) = self.box_powers();
            self.ledger.base_work_j += 0.5 * (bp + self.base_power_prev) * dt;
            self.ledger.viscous_j += 0.5 * (vp + self.viscous_power_prev) * dt;
            self.base_power_prev = bp;
            self.viscous_power_prev = vp;
        }
        self.steps += 1;
    }

    pub(super) fn box_acceleration(&self) -> f64 {
        match self.drive.primary {
            Some(p) if self.drive_on => {
                let (u, du) = self.drive.base(self.t);
                let mut f = -p.damping_n_s_m * (self.box_v_pred - du)
                    - p.stiffness_n_m * (self.box_z - u)
                    + self.grain_force_n;
                if self.drive.force_n != 0.0 {
                    f += self.drive.force(self.t);
                }
                f / p.mass_kg
            }
            _ => 0.0,
        }
    }

    /// (power of the drive on the system — the base's, or the force's F(t) z' —, viscous power
    /// in C) now (W).
    pub(super) fn box_powers(&self) -> (f64, f64) {
        let (u, du) = self.drive.base(self.t);
        match self.drive.primary {
            Some(p) => {
                let rel_v = self.box_v - du;
                let f_spring = p.stiffness_n_m * (self.box_z - u) + p.damping_n_s_m * rel_v;
                let mut drive = -f_spring * du;
                if self.drive.force_n != 0.0 {
                    drive += self.drive.force(self.t) * self.box_v;
                }
                (drive, p.damping_n_s_m * rel_v * rel_v)
            }
            None => (-self.grain_force_n * du, 0.0),
        }
    }

    /// Rebuilds the neighbour list if needed, then evaluates every force and torque.
    /// Returns the dissipated powers (collision, friction) (W).
    pub fn compute_forces(&mut self) -> (f64, f64) {
        self.vel_pred.copy_from_slice(&self.vel);
        self.omega_pred.copy_from_slice(&self.omega);
        self.box_v_pred = self.box_v;
        let rebuild = self.neighbors.needs_rebuild(&self.pos, self.box_origin());
        self.forces(rebuild, false)
    }

    /// Recomputes forces for the current state (call after editing positions or velocities
    /// by hand, before stepping).
    pub fn refresh(&mut self) {
        self.compute_forces();
    }

    /// Who runs this step's phases: one thread for small beds or one-thread pools; a
    /// [`Team`] (made here, kept for the next steps) when the world is stepped from outside
    /// any rayon pool or [`DemWorld::team_threads`] asks for one; else the rayon pool the
    /// caller is in.
    pub(super) fn choose_mode(&mut self) -> Mode {
        let threads = self.team_threads.unwrap_or_else(rayon::current_num_threads);
        if self.len() < self.parallel_min_grains || threads < self.parallel_min_threads.max(2) {
            return Mode::Serial;
        }
        if self.team_threads.is_none() && rayon::current_thread_index().is_some() {
            return Mode::Rayon;
        }
        if self.team.0.as_ref().map(Team::threads) != Some(threads) {
            self.team.0 = Team::new(threads).ok();
        }
        if self.team.0.is_some() {
            Mode::Team
        } else {
            Mode::Rayon
        }
    }

    /// Steps 1–2 for the grains: half kick, drift, predicted velocities (and the spins' half
    /// kick), chunk by chunk; returns the largest squared displacement since the last
    /// neighbour build relative to the box's displacement `shift` (m²).
    pub(super) fn kick_drift_phase(&mut self, shift: [f64; 3]) -> f64 {
        let n = self.pos.len();
        let rot = self.laws.rotations;
        let units = n.div_ceil(GRAIN_CHUNK);
        self.partials.clear();
        self.partials.resize(units, [0.0; 3]);
        let exec = self.mode.exec(&self.team);
        let slots = Parts::new(&mut self.partials);
        let (force, torque) = (&self.force, &self.torque);
        let drift = Drift::new(
            [
                &mut self.pos,
                &mut self.vel,
                &mut self.vel_pred,
                &mut self.omega,
                &mut self.omega_pred,
            ],
            (&self.inv_mass, &self.inv_inertia),
            self.neighbors.reference().0,
            (self.dt, rot),
            (shift, self.prefetch),
        );
        exec.units(units, &|c| {
            let r = c * GRAIN_CHUNK..((c + 1) * GRAIN_CHUNK).min(n);
            // SAFETY: grain chunk `c` alone touches its grains and its slot.
            unsafe {
                let m = drift.grains(r.clone(), &force[r.clone()], &torque[r]);
                slots.get(c..c + 1)[0][0] = m;
            }
        });
        self.partials.iter().fold(0.0, |a, s| a.max(s[0]))
    }

    /// Steps 1–2 for the grains (half kick, drift) with the box displaced by `shift` (m)
    /// since the last neighbour build, then the neighbour check and the force pass (with the
    /// second half kick). Returns the dissipated powers (collision, friction) (W).
    ///
    /// Laws without contact history drift each block's grains in the force pass itself, just
    /// before the block's own pairs (its grains are then still in cache): a speculation that
    /// no rebuild is due. When the drift shows one is, the pass is thrown away (its forces are
    /// recomputed from gravity up, nothing else was written) and done again after the
    /// rebuild, so the result is the same bits as drifting first. Laws with springs drift
    /// first: their pass writes the springs, which a rebuild carries over.
    pub(super) fn drift_and_forces(&mut self, shift: [f64; 3]) -> (f64, f64) {
        // a bag's bonds are evaluated on the drifted grains before the pass: no fusion
        let fuse = self.fuse_drift
            && self.bag.is_none()
            && !self.laws.tangential_kind().has_history()
            && self.neighbors.reference().0.len() == self.len();
        if fuse {
            if let Some(out) = self.forces_of(true, Some(shift)) {
                return out;
            }
            self.rebuild_neighbors();
        } else {
            let max_d2 = self.kick_drift_phase(shift);
            if self.neighbors.exceeded(max_d2) {
                self.rebuild_neighbors();
            }
        }
        self.forces_of(true, None)
            .expect("a force pass without drift always completes")
    }

    /// `kick`: the grains' second half kick of the step, v ← v + (dt/2) F/m (and ω), done
    /// grain by grain as soon as a grain's force is complete.
    pub(super) fn forces(&mut self, rebuild: bool, kick: bool) -> (f64, f64) {
        if rebuild {
            self.rebuild_neighbors();
        }
        self.forces_of(kick, None)
            .expect("a force pass without drift always completes")
    }
}
