//! [`DemWorld`]: grains (structure of arrays), the box and the primary mass, and the step.

use nalgebra::UnitQuaternion;

use crate::contact::linear_spring_dashpot::LinearContactParams;
use crate::contact::material::{Material, PairProperties};
use crate::contact::{coulomb_viscous_force, hertz_stiffness};
use crate::contact::{
    hertz_elastic_force, hertz_normal_force, linear_elastic_force, linear_normal_force,
};
use crate::contact::{AttractionPolicy, NormalLaw, TangentialLaw};
use crate::error::{ModelError, Quantity};
use crate::integrate::{advance_orientation, half_kick, half_kick_predict, kick_drift};
pub use crate::model::{BoxDrive, PrimarySystem};
use crate::neighbor::{NeighborList, Pair};
use crate::units::G;

use super::energy::{EnergyLedger, EnergyState};
use super::model::DemModel;

/// Normal-law kernel used by the monomorphised contact loops: the public kernels of
/// [`crate::contact`] (tests/contact_properties.rs checks their properties).
trait NormalKernel {
    /// Returns (raw total force, elastic force, factor of the tangential damping) (N, N, –).
    fn eval(k: f64, c: f64, overlap: f64, v_n: f64) -> (f64, f64, f64);
}

struct HertzKernel;
impl NormalKernel for HertzKernel {
    #[inline(always)]
    fn eval(k: f64, c: f64, z: f64, v_n: f64) -> (f64, f64, f64) {
        (
            hertz_normal_force(k, z, v_n, c),
            hertz_elastic_force(k, z),
            z.sqrt(),
        )
    }
}

struct LinearKernel;
impl NormalKernel for LinearKernel {
    #[inline(always)]
    fn eval(k: f64, c: f64, z: f64, v_n: f64) -> (f64, f64, f64) {
        (
            linear_normal_force(k, z, v_n, c),
            linear_elastic_force(k, z),
            1.0,
        )
    }
}

/// Contact laws (grain–grain and grain–wall) of the [`DemModel`], flattened for the loops.
#[derive(Debug, Clone)]
struct Laws {
    normal: NormalLaw,
    wall_normal: NormalLaw,
    tangential: TangentialLaw,
    wall_tangential: TangentialLaw,
    attraction: AttractionPolicy,
    rotations: bool,
    grain: Material,
    wall: Material,
}

impl Laws {
    fn any_tangential(&self) -> bool {
        self.tangential != TangentialLaw::None || self.wall_tangential != TangentialLaw::None
    }

    fn friction(&self, wall: bool) -> f64 {
        match if wall {
            self.wall_tangential
        } else {
            self.tangential
        } {
            TangentialLaw::None => 0.0,
            TangentialLaw::CoulombViscous { friction, .. }
            | TangentialLaw::LinearDashpotCoulomb { friction } => friction,
        }
    }

    /// (k_n, normal damping, tangential damping) of a pair or grain–wall contact.
    fn coefficients(&self, r_i: f64, m_i: f64, r_j: f64, m_j: f64, wall: bool) -> [f64; 3] {
        let (mat_j, normal, tangential) = if wall {
            (&self.wall, self.wall_normal, self.wall_tangential)
        } else {
            (&self.grain, self.normal, self.tangential)
        };
        let p = PairProperties::new(r_i, m_i, &self.grain, r_j, m_j, mat_j);
        let (k, c, c_lin_s) = match normal {
            NormalLaw::HertzKuwabaraKono { gamma_n } => {
                (hertz_stiffness(p.e_star, p.r_star), gamma_n, 0.0)
            }
            NormalLaw::LinearSpringDashpot {
                restitution,
                yield_strength,
            } => {
                let l = LinearContactParams::select(&p, &self.grain, yield_strength, restitution)
                    .expect("validated linear parameters");
                (l.k_n, l.c_n, l.c_s)
            }
        };
        let cs = match tangential {
            TangentialLaw::None => 0.0,
            TangentialLaw::CoulombViscous { gamma_s, .. } => gamma_s,
            TangentialLaw::LinearDashpotCoulomb { .. } => c_lin_s,
        };
        [k, c, cs]
    }
}

/// The state of a DEM damper: grains, box, primary mass, neighbour list and ledger.
///
/// Lab frame: z up, the floor at z = `box_z`, the ceiling at `box_z + Lz`, side walls at
/// x ∈ {0, Lx}, y ∈ {0, Ly}. `box_z` is the primary's displacement from its static
/// equilibrium without grains (SPEC §1), or u(t) for a kinematic box.
#[derive(Debug, Clone)]
pub struct DemWorld {
    /// Time since the drive started (s) (settling runs before t = 0 and does not advance it).
    pub t: f64,
    /// Time step (s).
    pub dt: f64,
    /// Grain centres (m).
    pub pos: Vec<[f64; 3]>,
    /// Grain velocities (m/s).
    pub vel: Vec<[f64; 3]>,
    /// Grain angular velocities (rad/s).
    pub omega: Vec<[f64; 3]>,
    /// Forces on grains (N).
    pub force: Vec<[f64; 3]>,
    /// Torques on grains (N m).
    pub torque: Vec<[f64; 3]>,
    vel_pred: Vec<[f64; 3]>,
    omega_pred: Vec<[f64; 3]>,
    box_v_pred: f64,
    /// Radii (m).
    pub radius: Vec<f64>,
    /// Masses (kg).
    pub mass: Vec<f64>,
    inv_mass: Vec<f64>,
    inv_inertia: Vec<f64>,
    /// Orientations (only when the scene asks for them).
    pub orientation: Option<Vec<UnitQuaternion<f64>>>,
    /// Inner box size [Lx, Ly, Lz] (m).
    pub box_size: [f64; 3],
    /// Box (floor) position z (m).
    pub box_z: f64,
    /// Box velocity z' (m/s).
    pub box_v: f64,
    box_a: f64,
    /// Vertical force of the grains on the box F_gz (N), from the last force evaluation.
    pub grain_force_n: f64,
    /// The drive (primary and base motion).
    pub drive: BoxDrive,
    /// Whether the base moves (false while the bed settles, box held still).
    pub drive_on: bool,
    /// Extra drag rate 1/τ (1/s) on the grains while settling (0 when driven).
    pub settle_drag: f64,
    /// Gravitational acceleration g (m/s², along −z); default 9.8 (tests may set 0).
    pub gravity: f64,
    /// Energy flows since the drive started (collision and friction also accumulate while
    /// settling; [`DemWorld::start_drive`] resets the ledger).
    pub ledger: EnergyLedger,
    base_power_prev: f64,
    viscous_power_prev: f64,
    laws: Laws,
    neighbors: NeighborList,
    pair_coef: Vec<[f64; 3]>,
    wall_coef: Vec<[f64; 3]>,
    /// Time steps taken since construction (settling included).
    pub steps: u64,
}

/// Sums returned by the contact loops: (F_gz, collision power, friction power).
type LoopOut = (f64, f64, f64);

impl DemWorld {
    /// Builds a world of `model`'s box, material and contact laws with grains at rest at
    /// `pos` (m) with `radius` (m) (usually `model.grains.radius_m`; masses from the density).
    ///
    /// # Errors
    /// [`ModelError`] for empty or inconsistent arrays, or a time step that is not > 0.
    pub fn new(
        model: &DemModel,
        drive: BoxDrive,
        dt: f64,
        radius: Vec<f64>,
        pos: Vec<[f64; 3]>,
    ) -> Result<Self, ModelError> {
        if radius.len() != pos.len() || radius.is_empty() {
            return Err(ModelError::new(
                Quantity::GrainCount,
                pos.len(),
                format!(
                    "{} positions for {} radii (need ≥ 1 grain, one radius each)",
                    pos.len(),
                    radius.len()
                ),
            ));
        }
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(ModelError::new(
                Quantity::TimeStep,
                dt,
                "must be > 0 (seconds)",
            ));
        }
        let n = pos.len();
        let density = model.grains.density_kg_m3;
        let mass: Vec<f64> = radius
            .iter()
            .map(|&r| super::model::Grains::sphere_mass(density, r))
            .collect();
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        let inv_inertia = mass
            .iter()
            .zip(&radius)
            .map(|(m, r)| 1.0 / (0.4 * m * r * r))
            .collect();
        let c = &model.contact;
        let laws = Laws {
            normal: c.normal,
            wall_normal: c.wall.normal,
            tangential: c.tangential,
            wall_tangential: c.wall.tangential,
            attraction: c.attraction,
            rotations: model.rotations,
            grain: model.grains.material,
            wall: c.wall.material,
        };
        let r_max = radius.iter().cloned().fold(0.0, f64::max);
        let neighbors = NeighborList::new(model.box_size_m, r_max, model.skin(r_max));
        let wall_coef = (0..n)
            .map(|i| laws.coefficients(radius[i], mass[i], f64::INFINITY, f64::INFINITY, true))
            .collect();
        Ok(DemWorld {
            t: 0.0,
            dt,
            vel: vec![[0.0; 3]; n],
            omega: vec![[0.0; 3]; n],
            force: vec![[0.0; 3]; n],
            torque: vec![[0.0; 3]; n],
            vel_pred: vec![[0.0; 3]; n],
            omega_pred: vec![[0.0; 3]; n],
            box_v_pred: 0.0,
            pos,
            radius,
            mass,
            inv_mass,
            inv_inertia,
            orientation: model
                .orientations
                .then(|| vec![UnitQuaternion::identity(); n]),
            box_size: model.box_size_m,
            box_z: 0.0,
            box_v: 0.0,
            box_a: 0.0,
            grain_force_n: 0.0,
            drive,
            drive_on: false,
            settle_drag: 0.0,
            gravity: G,
            ledger: EnergyLedger::default(),
            base_power_prev: 0.0,
            viscous_power_prev: 0.0,
            laws,
            neighbors,
            pair_coef: Vec::new(),
            wall_coef,
            steps: 0,
        })
    }

    /// The grains' state now, for snapshots.
    pub fn grain_state(&self) -> crate::observe::GrainState<'_> {
        crate::observe::GrainState {
            time_s: self.t,
            pos: &self.pos,
            vel: &self.vel,
            omega: &self.omega,
            radius: &self.radius,
            orientation: self.orientation.as_deref(),
            force: &self.force,
            box_size: self.box_size,
            box_z: self.box_z,
        }
    }

    /// Number of grains.
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// True when there are no grains.
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Number of neighbour-list builds so far.
    pub fn neighbor_builds(&self) -> u64 {
        self.neighbors.builds
    }

    /// Candidate pairs currently in the Verlet list.
    pub fn pair_count(&self) -> usize {
        self.neighbors.pairs.len()
    }

    /// Base displacement and velocity now (zero motion while the drive is off).
    pub fn base_now(&self) -> (f64, f64) {
        if self.drive_on {
            self.drive.base(self.t)
        } else {
            (self.box_z_hold(), 0.0)
        }
    }

    fn box_z_hold(&self) -> f64 {
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
            let dz = u - self.box_z;
            for p in &mut self.pos {
                p[2] += dz;
            }
            self.box_z = u;
            self.box_v = v;
        }
        self.compute_forces();
        self.box_a = self.box_acceleration();
        let (bp, vp) = self.box_powers();
        self.base_power_prev = bp;
        self.viscous_power_prev = vp;
    }

    /// Moves the box (and the grains with it) to `z` (m) without changing velocities.
    pub fn shift_box_to(&mut self, z: f64) {
        let dz = z - self.box_z;
        for p in &mut self.pos {
            p[2] += dz;
        }
        self.box_z = z;
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
    /// 5. box equation (2.1.22): M z'' = −C(z' − u') − K(z − u) + F_gz;
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
        let (reference, ref_shift) = self.neighbors.reference();
        let shift = [0.0, 0.0, self.box_z - ref_shift[2]];
        let max_d2 = kick_drift(
            &mut self.pos,
            &mut self.vel,
            &mut self.vel_pred,
            &self.force,
            &self.inv_mass,
            h,
            dt,
            reference,
            shift,
        );
        if self.laws.rotations {
            half_kick_predict(
                &mut self.omega,
                &mut self.omega_pred,
                &self.torque,
                &self.inv_inertia,
                h,
            );
        }
        self.box_v_pred = if primary_free {
            self.box_v + h * self.box_a
        } else {
            self.box_v
        };
        if let Some(q) = self.orientation.as_mut() {
            for (q, w) in q.iter_mut().zip(&self.omega) {
                advance_orientation(q, *w, dt);
            }
        }
        // 3.–4. neighbours and forces
        let rebuild = self.neighbors.exceeded(max_d2);
        let (p_coll, p_fric) = self.forces(rebuild);
        // 5. box equation
        if primary_free {
            self.box_a = self.box_acceleration();
        }
        // 6. second half kick
        half_kick(&mut self.vel, &self.force, &self.inv_mass, h);
        if self.laws.rotations {
            half_kick(&mut self.omega, &self.torque, &self.inv_inertia, h);
        }
        if primary_free {
            self.box_v += h * self.box_a;
        }
        // 7. ledger
        self.ledger.collision_j += p_coll * dt;
        self.ledger.friction_j += p_fric * dt;
        if self.drive_on {
            let (bp, vp) = self.box_powers();
            self.ledger.base_work_j += 0.5 * (bp + self.base_power_prev) * dt;
            self.ledger.viscous_j += 0.5 * (vp + self.viscous_power_prev) * dt;
            self.base_power_prev = bp;
            self.viscous_power_prev = vp;
        }
        self.steps += 1;
    }

    fn box_acceleration(&self) -> f64 {
        match self.drive.primary {
            Some(p) if self.drive_on => {
                let (u, du) = self.drive.base(self.t);
                (-p.damping_n_s_m * (self.box_v_pred - du) - p.stiffness_n_m * (self.box_z - u)
                    + self.grain_force_n)
                    / p.mass_kg
            }
            _ => 0.0,
        }
    }

    /// (power of the base on the system, viscous power in C) now (W).
    fn box_powers(&self) -> (f64, f64) {
        let (u, du) = self.drive.base(self.t);
        match self.drive.primary {
            Some(p) => {
                let rel_v = self.box_v - du;
                let f_spring = p.stiffness_n_m * (self.box_z - u) + p.damping_n_s_m * rel_v;
                (-f_spring * du, p.damping_n_s_m * rel_v * rel_v)
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
        let rebuild = self
            .neighbors
            .needs_rebuild(&self.pos, [0.0, 0.0, self.box_z]);
        self.forces(rebuild)
    }

    fn forces(&mut self, rebuild: bool) -> (f64, f64) {
        let shift = [0.0, 0.0, self.box_z];
        if rebuild {
            self.neighbors.rebuild(&self.pos, &self.radius, shift);
            self.pair_coef.clear();
            for &Pair { i, j } in &self.neighbors.pairs {
                let (i, j) = (i as usize, j as usize);
                let c = self.laws.coefficients(
                    self.radius[i],
                    self.mass[i],
                    self.radius[j],
                    self.mass[j],
                    false,
                );
                self.pair_coef.push(c);
            }
        }
        let g = self.gravity;
        for (f, m) in self.force.iter_mut().zip(&self.mass) {
            *f = [0.0, 0.0, -m * g];
        }
        if self.laws.rotations {
            self.torque.iter_mut().for_each(|t| *t = [0.0; 3]);
        }
        if self.settle_drag > 0.0 {
            for ((f, v), m) in self.force.iter_mut().zip(&self.vel).zip(&self.mass) {
                let s = -m * self.settle_drag;
                f[0] += s * v[0];
                f[1] += s * v[1];
                f[2] += s * v[2];
            }
        }
        // the enums are matched once per step; each arm runs a monomorphised loop without
        // per-pair branches on the law, friction, rotations or the attraction policy
        let l = &self.laws;
        let hertz = matches!(l.normal, NormalLaw::HertzKuwabaraKono { .. });
        let clamp = l.attraction == AttractionPolicy::Clamp;
        let out = match (hertz, l.any_tangential(), l.rotations, clamp) {
            (true, true, true, true) => self.contacts::<HertzKernel, true, true, true>(),
            (true, true, true, false) => self.contacts::<HertzKernel, true, true, false>(),
            (true, true, false, true) => self.contacts::<HertzKernel, true, false, true>(),
            (true, true, false, false) => self.contacts::<HertzKernel, true, false, false>(),
            (true, false, _, true) => self.contacts::<HertzKernel, false, false, true>(),
            (true, false, _, false) => self.contacts::<HertzKernel, false, false, false>(),
            (false, true, true, true) => self.contacts::<LinearKernel, true, true, true>(),
            (false, true, true, false) => self.contacts::<LinearKernel, true, true, false>(),
            (false, true, false, true) => self.contacts::<LinearKernel, true, false, true>(),
            (false, true, false, false) => self.contacts::<LinearKernel, true, false, false>(),
            (false, false, _, true) => self.contacts::<LinearKernel, false, false, true>(),
            (false, false, _, false) => self.contacts::<LinearKernel, false, false, false>(),
        };
        self.grain_force_n = out.0;
        (out.1, out.2)
    }

    fn contacts<K: NormalKernel, const TANG: bool, const ROT: bool, const CLAMP: bool>(
        &mut self,
    ) -> LoopOut {
        let (pc, pf) = pair_loop::<K, TANG, ROT, CLAMP>(
            &self.pos,
            &self.vel_pred,
            &self.omega_pred,
            &self.radius,
            &self.neighbors.pairs,
            &self.pair_coef,
            (self.laws.friction(false), self.laws.friction(true)),
            &mut self.force,
            &mut self.torque,
        );
        let (fgz, wc, wf) = wall_loop::<K, TANG, ROT, CLAMP>(self);
        (fgz, pc + wc, pf + wf)
    }

    /// Stored energies now (J).
    pub fn energy_state(&self) -> EnergyState {
        let mut s = EnergyState::default();
        for i in 0..self.len() {
            let v = self.vel[i];
            let w = self.omega[i];
            s.kinetic_j += 0.5 * self.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            s.rotational_j += 0.5 / self.inv_inertia[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            s.potential_j += self.mass[i] * self.gravity * self.pos[i][2];
        }
        let elastic = |k: f64, z: f64| match self.laws.normal {
            NormalLaw::HertzKuwabaraKono { .. } => 0.4 * k * z * z * z.sqrt(),
            NormalLaw::LinearSpringDashpot { .. } => 0.5 * k * z * z,
        };
        for (p, c) in self.neighbors.pairs.iter().zip(&self.pair_coef) {
            let (i, j) = (p.i as usize, p.j as usize);
            let d = sub(self.pos[i], self.pos[j]);
            let z = self.radius[i] + self.radius[j] - norm(d);
            if z > 0.0 {
                s.elastic_j += elastic(c[0], z);
            }
        }
        for i in 0..self.len() {
            for z in self.wall_overlaps(i) {
                if z > 0.0 {
                    s.elastic_j += elastic(self.wall_coef[i][0], z);
                }
            }
        }
        if let Some(p) = self.drive.primary {
            let (u, _) = self.base_now();
            s.primary_j = 0.5 * p.mass_kg * self.box_v * self.box_v
                + 0.5 * p.stiffness_n_m * (self.box_z - u).powi(2);
        }
        s
    }

    /// Overlaps with the six walls (x−, x+, y−, y+, floor, ceiling) (m); ≤ 0 = no contact.
    pub fn wall_overlaps(&self, i: usize) -> [f64; 6] {
        let (p, r, b) = (self.pos[i], self.radius[i], self.box_size);
        let z = p[2] - self.box_z;
        [
            r - p[0],
            r - (b[0] - p[0]),
            r - p[1],
            r - (b[1] - p[1]),
            r - z,
            r - (b[2] - z),
        ]
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

    /// Centre of mass height z_cm and vertical velocity v_cm of the grains (m, m/s).
    pub fn z_cm_state(&self) -> (f64, f64) {
        let (mut zm, mut vm, mut mt) = (0.0, 0.0, 0.0);
        for ((p, v), m) in self.pos.iter().zip(&self.vel).zip(&self.mass) {
            zm += m * p[2];
            vm += m * v[2];
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

    /// Sets grain velocities (m/s) and angular velocities (rad/s), e.g. for tests.
    pub fn set_velocities(&mut self, vel: &[[f64; 3]], omega: &[[f64; 3]]) {
        self.vel.copy_from_slice(vel);
        self.omega.copy_from_slice(omega);
    }

    /// Recomputes forces for the current state (call after editing positions or velocities
    /// by hand, before stepping).
    pub fn refresh(&mut self) {
        self.compute_forces();
    }
}

#[inline(always)]
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline(always)]
fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
#[inline(always)]
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Grain–grain contacts over the Verlet list. Returns (collision power, friction power) (W).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn pair_loop<K: NormalKernel, const TANG: bool, const ROT: bool, const CLAMP: bool>(
    pos: &[[f64; 3]],
    vel: &[[f64; 3]],
    omega: &[[f64; 3]],
    radius: &[f64],
    pairs: &[Pair],
    coef: &[[f64; 3]],
    mu: (f64, f64),
    force: &mut [[f64; 3]],
    torque: &mut [[f64; 3]],
) -> (f64, f64) {
    let (mut p_coll, mut p_fric) = (0.0, 0.0);
    let mu = mu.0;
    for (pair, c) in pairs.iter().zip(coef) {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let (ri, rj) = (radius[i], radius[j]);
        let d = sub(pos[i], pos[j]);
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let cut = ri + rj;
        if r2 >= cut * cut {
            continue;
        }
        let dist = r2.sqrt();
        let inv = 1.0 / dist;
        let n = [d[0] * inv, d[1] * inv, d[2] * inv];
        let z = cut - dist;
        let vr = sub(vel[i], vel[j]);
        let vrn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
        let v_n = -vrn;
        let (raw, fel, ts) = K::eval(c[0], c[1], z, v_n);
        let f = if CLAMP {
            AttractionPolicy::Clamp.apply(raw)
        } else {
            raw
        };
        p_coll += (f - fel) * v_n;
        let mut fv = [f * n[0], f * n[1], f * n[2]];
        if TANG {
            let mut vs = [vr[0] - vrn * n[0], vr[1] - vrn * n[1], vr[2] - vrn * n[2]];
            if ROT {
                let (wi, wj) = (omega[i], omega[j]);
                let w = [
                    ri * wi[0] + rj * wj[0],
                    ri * wi[1] + rj * wj[1],
                    ri * wi[2] + rj * wj[2],
                ];
                let wn = cross(w, n);
                vs = sub(vs, wn);
            }
            let (fs, p) = coulomb_viscous_force(vs, ts, f, c[2], mu);
            p_fric += p;
            fv[0] += fs[0];
            fv[1] += fs[1];
            fv[2] += fs[2];
            if ROT {
                let t = cross(n, fs);
                let ti = &mut torque[i];
                ti[0] -= ri * t[0];
                ti[1] -= ri * t[1];
                ti[2] -= ri * t[2];
                let tj = &mut torque[j];
                tj[0] -= rj * t[0];
                tj[1] -= rj * t[1];
                tj[2] -= rj * t[2];
            }
        }
        let fi = &mut force[i];
        fi[0] += fv[0];
        fi[1] += fv[1];
        fi[2] += fv[2];
        let fj = &mut force[j];
        fj[0] -= fv[0];
        fj[1] -= fv[1];
        fj[2] -= fv[2];
    }
    (p_coll, p_fric)
}

/// Grain–wall contacts with the six planes of the box. Returns (F_gz, collision power,
/// friction power).
#[inline(never)]
fn wall_loop<K: NormalKernel, const TANG: bool, const ROT: bool, const CLAMP: bool>(
    w: &mut DemWorld,
) -> LoopOut {
    let b = w.box_size;
    let floor = w.box_z;
    let ceil = w.box_z + b[2];
    let vw = w.box_v_pred;
    let mu = w.laws.friction(true);
    let (mut fgz, mut p_coll, mut p_fric) = (0.0, 0.0, 0.0);
    for i in 0..w.pos.len() {
        let p = w.pos[i];
        let r = w.radius[i];
        // cheap reject: far from every wall
        if p[0] > r
            && p[0] < b[0] - r
            && p[1] > r
            && p[1] < b[1] - r
            && p[2] > floor + r
            && p[2] < ceil - r
        {
            continue;
        }
        let c = w.wall_coef[i];
        let vr = [w.vel_pred[i][0], w.vel_pred[i][1], w.vel_pred[i][2] - vw];
        let om = w.omega_pred[i];
        let cands: [(f64, usize, f64); 6] = [
            (r - p[0], 0, 1.0),
            (r - (b[0] - p[0]), 0, -1.0),
            (r - p[1], 1, 1.0),
            (r - (b[1] - p[1]), 1, -1.0),
            (r - (p[2] - floor), 2, 1.0),
            (r - (ceil - p[2]), 2, -1.0),
        ];
        for (z, axis, s) in cands {
            if z <= 0.0 {
                continue;
            }
            let mut n = [0.0; 3];
            n[axis] = s;
            let vrn = vr[axis] * s;
            let v_n = -vrn;
            let (raw, fel, ts) = K::eval(c[0], c[1], z, v_n);
            let f = if CLAMP {
                AttractionPolicy::Clamp.apply(raw)
            } else {
                raw
            };
            p_coll += (f - fel) * v_n;
            let mut fv = [f * n[0], f * n[1], f * n[2]];
            if TANG {
                let mut vs = vr;
                vs[axis] = 0.0;
                if ROT {
                    let wn = cross([r * om[0], r * om[1], r * om[2]], n);
                    vs = sub(vs, wn);
                }
                let (fs, pw) = coulomb_viscous_force(vs, ts, f, c[2], mu);
                p_fric += pw;
                fv[0] += fs[0];
                fv[1] += fs[1];
                fv[2] += fs[2];
                if ROT {
                    let t = cross(n, fs);
                    let ti = &mut w.torque[i];
                    ti[0] -= r * t[0];
                    ti[1] -= r * t[1];
                    ti[2] -= r * t[2];
                }
            }
            let fi = &mut w.force[i];
            fi[0] += fv[0];
            fi[1] += fv[1];
            fi[2] += fv[2];
            fgz -= fv[2];
        }
    }
    (fgz, p_coll, p_fric)
}
