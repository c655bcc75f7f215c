//! [`DemWorld`]: grains (structure of arrays), the box and the primary mass, and the step.

use nalgebra::UnitQuaternion;
use std::mem::MaybeUninit;
use std::ops::Range;

use crate::contact::hertz_stiffness;
use crate::contact::lanes::{dot, get_lane, set_lane, sub3, F64x8, Lanes};
use crate::contact::linear_spring_dashpot::LinearContactParams;
use crate::contact::material::{Material, PairProperties};
use crate::contact::response::{
    contact_response, ContactCoefficients, ContactKinematics, CoulombViscousKernel, HertzKernel,
    LinearKernel, LinearSpringKernel, MindlinSpringKernel, NoTangential, NormalKernel,
    TangentialKernel,
};
use crate::contact::{AttractionPolicy, NormalLaw, TangentialLaw};
use crate::error::{ModelError, Quantity};
use crate::integrate::{advance_orientation, half_kick, half_kick_predict, kick_drift};
pub use crate::model::{BoxDrive, PrimarySystem};
use crate::neighbor::{Curve, NeighborList, Pair, J_ROLE};
use crate::simd::{Simd, WritePrefetch};
use crate::units::G;

use super::blocks::BlockPairs;
use super::energy::{EnergyLedger, EnergyState};
use super::model::DemModel;
use super::team::{Exec, Parts, Team, View};

/// Own pairs of a block per call of the pair kernel (a block's own pairs are run in these
/// chunks, in order, by the block's thread).
pub const PAIR_CHUNK: usize = 1024;
/// Cross pairs (pairs across grain blocks) per work unit: small, so that the few cross pairs
/// of a two-block bed still divide between two threads.
pub const CROSS_CHUNK: usize = 256;
pub use super::blocks::GRAIN_CHUNK;
/// Default smallest grain count for which a step runs on several threads: two blocks
/// ([`super::blocks::MIN_BLOCK`]). Results do not depend on it.
pub const PARALLEL_MIN_GRAINS: usize = 2 * super::blocks::MIN_BLOCK;
/// Default smallest number of threads for which a step runs on several threads.
pub const PARALLEL_MIN_THREADS: usize = 2;
/// Default smallest grain count for which the grains are stored along the space-filling curve
/// (re-sorted at every neighbour rebuild); smaller beds fit the caches in any order.
pub const SORT_MIN_GRAINS: usize = 1000;

/// Bytes a DEM run holds per grain, neighbour structure included: ~520 B of grain arrays
/// (state, predictions, forces, per-grain coefficients and wall springs, cell list), ~230 B of
/// curve-sort scratch and grain ids (~110 B more of grain-id copies with snapshots) plus up to
/// ~8 candidate pairs of 140 B (pair, its block-ordered copy and block class, its copy in a
/// run of a threaded rebuild, coefficients, state, per-grain index), rounded up.
pub const BYTES_PER_GRAIN: f64 = 2048.0;

/// Memory a DEM run of `n` grains needs (bytes), independent of the box (the cell list is
/// sorted, not a grid over the box volume).
pub fn memory_estimate_bytes(n: usize) -> f64 {
    n as f64 * BYTES_PER_GRAIN
}

/// Memory the machine can give now (bytes): `MemAvailable` of /proc/meminfo; `None` where
/// unknown.
pub fn available_memory_bytes() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = s.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Per cross pair (across grain blocks): the contact's force on i (N) and torque arm from
/// the force pass, gathered per grain afterwards.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct PairResponse {
    force: [f64; 3],
    torque_arm: [f64; 3],
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
    fn friction(&self, wall: bool) -> f64 {
        if wall {
            self.wall_tangential.friction()
        } else {
            self.tangential.friction()
        }
    }

    /// The tangential law the loops run (the grain–grain one, or the wall's if grains have
    /// none; both come from the same scene key).
    fn tangential_kind(&self) -> TangentialLaw {
        if self.tangential != TangentialLaw::None {
            self.tangential
        } else {
            self.wall_tangential
        }
    }

    /// [`ContactCoefficients`] of a pair or grain–wall contact.
    fn coefficients(
        &self,
        r_i: f64,
        m_i: f64,
        r_j: f64,
        m_j: f64,
        wall: bool,
    ) -> ContactCoefficients {
        let (mat_j, normal, tangential) = if wall {
            (&self.wall, self.wall_normal, self.wall_tangential)
        } else {
            (&self.grain, self.normal, self.tangential)
        };
        let p = PairProperties::new(r_i, m_i, &self.grain, r_j, m_j, mat_j);
        let (k, c, c_lin_s, k_lin_s) = match normal {
            NormalLaw::HertzKuwabaraKono { gamma_n } => {
                (hertz_stiffness(p.e_star, p.r_star), gamma_n, 0.0, 0.0)
            }
            NormalLaw::LinearSpringDashpot {
                restitution,
                yield_strength,
            } => {
                let l = LinearContactParams::select(&p, &self.grain, yield_strength, restitution)
                    .expect("validated linear parameters");
                (l.k_n, l.c_n, l.c_s, l.k_s)
            }
        };
        let (cs, kt) = match tangential {
            TangentialLaw::None => (0.0, 0.0),
            TangentialLaw::CoulombViscous { gamma_s, .. } => (gamma_s, 0.0),
            TangentialLaw::LinearDashpotCoulomb { .. } => (c_lin_s, 0.0),
            TangentialLaw::MindlinSpring { gamma_s, .. } => {
                (gamma_s, 8.0 * p.g_star * p.r_star.sqrt())
            }
            TangentialLaw::LinearSpring { .. } => (c_lin_s, k_lin_s),
        };
        [k, c, cs, kt]
    }
}

/// The state of a DEM damper: grains, box, primary mass, neighbour list and ledger.
///
/// Storage order: beds of at least [`DemWorld::sort_min_grains`] grains are re-sorted along a
/// Morton (Z-order) curve of their cells at every neighbour rebuild, so that grains close in
/// space are close in memory. The per-grain public arrays (`pos`, `vel`, `omega`, `force`,
/// `torque`, `radius`, `mass`, `orientation`) are in that storage order; slot k holds grain
/// [`DemWorld::grain_ids`]`[k]` (its index in the arrays given to [`DemWorld::new`]), and
/// what leaves the engine keyed by grain — [`DemWorld::grain_state`] (snapshots),
/// [`DemWorld::set_velocities`] — is in grain-id order. Sums over grains (centre of mass,
/// energies, F_gz) do not depend on the order except for round-off.
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
    /// Whether the step books the energy flows into [`DemWorld::ledger`] (default true). Off,
    /// the contact loops are compiled without the dissipated powers (they cost nothing) and
    /// the ledger stays zero.
    pub energy_ledger: bool,
    base_power_prev: f64,
    viscous_power_prev: f64,
    laws: Laws,
    neighbors: NeighborList,
    /// The candidate pairs sorted by grain block (the order of `pair_coef` and
    /// `pair_history`).
    blocks: BlockPairs,
    pair_coef: Vec<ContactCoefficients>,
    wall_coef: Vec<ContactCoefficients>,
    /// Tangential spring elongation of each candidate pair (m), valid where the pair touched at
    /// the previous force evaluation ([`spring`]); stale elsewhere (never cleared in the step).
    pair_history: Vec<[f64; 3]>,
    /// Per candidate pair, the force evaluation at which it last touched (0: never).
    pair_touch: Vec<u64>,
    /// Number of force evaluations so far (the clock of `pair_touch`).
    force_evals: u64,
    /// Responses of the cross pairs (threaded paths only).
    cross_response: Vec<PairResponse>,
    /// Per cross pair, its (collision, friction) power at the last force evaluation (W),
    /// when the cross pairs are evaluated from both sides with the ledger.
    cross_power: Vec<[f64; 2]>,
    /// Tangential spring elongation of each grain's contacts with the six walls (m).
    wall_history: Vec<[[f64; 3]; 6]>,
    /// Springs of the pairs before a rebuild, keyed by (min, max) grain (scratch).
    history_carry: Vec<(u64, [f64; 3])>,
    /// Runs of occupied cells of a threaded neighbour rebuild, and their pairs (scratch).
    cell_runs: Vec<usize>,
    pair_runs: Vec<Vec<Pair>>,
    /// Partial sums of the chunks (scratch, reused every step).
    partials: Vec<[f64; 3]>,
    /// Partial sums of the grain chunks: F_gz, powers, Σ m z, Σ m ż (scratch).
    grain_partials: Vec<[f64; 5]>,
    /// Total grain mass (kg).
    mass_total: f64,
    /// Centre-of-mass height and vertical velocity at the end of the last step (m, m/s).
    step_cm: (f64, f64),
    /// Smallest grain count for which a step uses the rayon pool (default
    /// [`PARALLEL_MIN_GRAINS`]); results do not depend on it nor on the thread count.
    pub parallel_min_grains: usize,
    /// Smallest pool size (≥ 2) for which a step uses the rayon pool (default
    /// [`PARALLEL_MIN_THREADS`]).
    pub parallel_min_threads: usize,
    /// Smallest grain count for which the grains are kept in space-filling-curve order
    /// (default [`SORT_MIN_GRAINS`]; `usize::MAX`: never sorted, slot = grain id).
    pub sort_min_grains: usize,
    /// Whether laws without contact history drift the grains inside the force pass, block by
    /// block ([`DemWorld::step`]; default true). Results do not depend on it.
    pub fuse_drift: bool,
    /// Grain id of each storage slot.
    id: Vec<u32>,
    /// Scratch of the curve sort (reused: no allocation in the step).
    sort: SortScratch,
    /// Grain-id-ordered copies for [`DemWorld::grain_state`] (made at the first snapshot).
    by_id: Option<Box<ById>>,
    /// Time steps taken since construction (settling included).
    pub steps: u64,
    /// Radius and coefficients shared by every grain, when all grains are alike (the loops
    /// then read them once instead of per contact).
    uniform: Option<Uniform>,
    /// Instruction set of the contact loops (default: the widest this processor has; every
    /// choice gives bitwise the same results).
    pub simd: Simd,
    /// Write prefetches in the drift, where the processor has them (no value changes;
    /// `None` turns them off, e.g. to measure them).
    pub prefetch: Option<WritePrefetch>,
    /// Threads of a [`Team`] to step with (`None`: the rayon pool's size, and a team only when
    /// stepped from outside a rayon pool). Results do not depend on it.
    pub team_threads: Option<usize>,
    team: TeamSlot,
    mode: Mode,
}

/// Who runs the phases of the current step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Serial,
    Rayon,
    Team,
}

impl Mode {
    /// The executor of this mode (the rayon pool when the team could not be made).
    fn exec(self, team: &TeamSlot) -> Exec<'_> {
        match (self, team.0.as_ref()) {
            (Mode::Serial, _) => Exec::Serial,
            (Mode::Team, Some(team)) => Exec::Team(team),
            _ => Exec::Rayon,
        }
    }
}

/// The world's [`Team`], if it made one (a clone of the world makes its own).
#[derive(Debug, Default)]
struct TeamSlot(Option<Team>);

impl Clone for TeamSlot {
    fn clone(&self) -> Self {
        TeamSlot(None)
    }
}

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

/// What every grain shares when all grains are alike (one radius, one mass).
#[derive(Debug, Clone, Copy)]
struct Uniform {
    radius: f64,
    pair: ContactCoefficients,
    wall: ContactCoefficients,
}

impl Uniform {
    /// `Some` when every grain has the radius and mass of the first (a monodisperse bed):
    /// then every pair's and every wall contact's coefficients are the same numbers.
    fn of(laws: &Laws, radius: &[f64], mass: &[f64]) -> Option<Self> {
        let (r, m) = (*radius.first()?, *mass.first()?);
        let alike = radius.iter().all(|&x| x == r) && mass.iter().all(|&x| x == m);
        alike.then(|| Uniform {
            radius: r,
            pair: laws.coefficients(r, m, r, m, false),
            wall: laws.coefficients(r, m, f64::INFINITY, f64::INFINITY, true),
        })
    }
}

/// Sums returned by the contact loops: (F_gz, collision power, friction power).
type LoopOut = (f64, f64, f64);

/// Buffers of the curve sort, kept between rebuilds.
#[derive(Debug, Clone, Default)]
struct SortScratch {
    /// Old slots in the new order.
    order: Vec<u32>,
    /// New slot of each old slot.
    inv: Vec<u32>,
    v3: Vec<[f64; 3]>,
    v1: Vec<f64>,
    coef: Vec<ContactCoefficients>,
    hist: Vec<[[f64; 3]; 6]>,
    quat: Vec<UnitQuaternion<f64>>,
    ids: Vec<u32>,
}

/// Per-grain arrays in grain-id order, for snapshots.
#[derive(Debug, Clone, Default)]
struct ById {
    pos: Vec<[f64; 3]>,
    vel: Vec<[f64; 3]>,
    omega: Vec<[f64; 3]>,
    force: Vec<[f64; 3]>,
    radius: Vec<f64>,
    orientation: Vec<UnitQuaternion<f64>>,
}

/// `a` ← `a` gathered along `order` (`a[k]` = old `a[order[k]]`); `tmp` is the spare buffer.
fn permute<T: Copy>(a: &mut Vec<T>, tmp: &mut Vec<T>, order: &[u32]) {
    tmp.clear();
    tmp.extend(order.iter().map(|&k| a[k as usize]));
    std::mem::swap(a, tmp);
}

/// `out` ← `a` in grain-id order (`out[id[k]]` = `a[k]`).
fn scatter_by_id<T: Copy + Default>(a: &[T], id: &[u32], out: &mut Vec<T>) {
    out.clear();
    out.resize(a.len(), T::default());
    for (x, &g) in a.iter().zip(id) {
        out[g as usize] = *x;
    }
}

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
        // a bed of several grain blocks is stored along vertical columns, so that the blocks'
        // faces are vertical ([`Curve::Columns`]: 4000 grains, vibrated, 16 % fewer cross
        // pairs and 6–15 % more speed on two threads); one block keeps the 3-D Morton curve,
        // which ran a 250-grain bed 7–12 % faster on one thread
        let curve = if super::blocks::block_count(n) > 1 {
            Curve::Columns
        } else {
            Curve::Morton
        };
        let neighbors =
            NeighborList::new(model.box_size_m, r_max, model.skin(r_max)).with_curve(curve);
        let wall_coef = (0..n)
            .map(|i| laws.coefficients(radius[i], mass[i], f64::INFINITY, f64::INFINITY, true))
            .collect();
        let uniform = Uniform::of(&laws, &radius, &mass);
        let mass_total = mass.iter().sum();
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
            energy_ledger: true,
            base_power_prev: 0.0,
            viscous_power_prev: 0.0,
            laws,
            neighbors,
            blocks: BlockPairs::default(),
            pair_coef: Vec::new(),
            wall_coef,
            pair_history: Vec::new(),
            pair_touch: Vec::new(),
            force_evals: 0,
            cross_response: Vec::new(),
            cross_power: Vec::new(),
            wall_history: vec![[[0.0; 3]; 6]; n],
            history_carry: Vec::new(),
            cell_runs: Vec::new(),
            pair_runs: Vec::new(),
            partials: Vec::new(),
            grain_partials: Vec::new(),
            mass_total,
            step_cm: (f64::NAN, f64::NAN),
            parallel_min_grains: PARALLEL_MIN_GRAINS,
            parallel_min_threads: PARALLEL_MIN_THREADS,
            sort_min_grains: SORT_MIN_GRAINS,
            fuse_drift: true,
            id: (0..n as u32).collect(),
            sort: SortScratch::default(),
            by_id: None,
            steps: 0,
            uniform,
            simd: Simd::detect(),
            prefetch: WritePrefetch::detect(),
            team_threads: None,
            team: TeamSlot(None),
            mode: Mode::Serial,
        })
    }

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
                box_z: self.box_z,
            };
        }
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
            box_z: self.box_z,
        }
    }

    /// Grain id of each storage slot of the per-grain arrays (the identity until the first
    /// curve sort).
    pub fn grain_ids(&self) -> &[u32] {
        &self.id
    }

    fn is_identity_order(&self) -> bool {
        self.id.iter().enumerate().all(|(k, &g)| g as usize == k)
    }

    /// Stores the grains along the space-filling curve of their cells: permutes every
    /// per-grain array (state, predictions, coefficients, wall springs, ids). Forces and
    /// torques are carried too (the force pass after the rebuild overwrites them). Leaves the
    /// new slot of each old slot in `self.sort.inv`.
    fn sort_along_curve(&mut self) {
        let shift = [0.0, 0.0, self.box_z];
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

    /// (grain blocks, candidate pairs across blocks) of the force pass ([`super::blocks`]).
    pub fn block_stats(&self) -> (usize, usize) {
        (self.blocks.blocks, self.blocks.cross_len())
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
        let shift = self.box_z - self.neighbors.reference().1[2];
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
        self.forces(rebuild, false)
    }

    /// Who runs this step's phases: one thread for small beds or one-thread pools; a
    /// [`Team`] (made here, kept for the next steps) when the world is stepped from outside
    /// any rayon pool or [`DemWorld::team_threads`] asks for one; else the rayon pool the
    /// caller is in.
    fn choose_mode(&mut self) -> Mode {
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
    /// neighbour build relative to the box's vertical displacement `shift_z` (m²).
    fn kick_drift_phase(&mut self, shift_z: f64) -> f64 {
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
            (shift_z, self.prefetch),
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

    /// Steps 1–2 for the grains (half kick, drift) with the box displaced by `shift_z` (m)
    /// since the last neighbour build, then the neighbour check and the force pass (with the
    /// second half kick). Returns the dissipated powers (collision, friction) (W).
    ///
    /// Laws without contact history drift each block's grains in the force pass itself, just
    /// before the block's own pairs (its grains are then still in cache): a speculation that
    /// no rebuild is due. When the drift shows one is, the pass is thrown away (its forces are
    /// recomputed from gravity up, nothing else was written) and done again after the
    /// rebuild, so the result is the same bits as drifting first. Laws with springs drift
    /// first: their pass writes the springs, which a rebuild carries over.
    fn drift_and_forces(&mut self, shift_z: f64) -> (f64, f64) {
        let fuse = self.fuse_drift
            && !self.laws.tangential_kind().has_history()
            && self.neighbors.reference().0.len() == self.len();
        if fuse {
            if let Some(out) = self.forces_of(true, Some(shift_z)) {
                return out;
            }
            self.rebuild_neighbors();
        } else {
            let max_d2 = self.kick_drift_phase(shift_z);
            if self.neighbors.exceeded(max_d2) {
                self.rebuild_neighbors();
            }
        }
        self.forces_of(true, None)
            .expect("a force pass without drift always completes")
    }

    /// Rebuilds the neighbour list, the per-pair coefficients (computed here only, never in
    /// the step) and carries the tangential springs of the contacts over to the new list.
    fn rebuild_neighbors(&mut self) {
        let shift = [0.0, 0.0, self.box_z];
        let carry = self.laws.tangential_kind().has_history();
        let key = |p: &Pair| ((p.i.min(p.j) as u64) << 32) | p.i.max(p.j) as u64;
        // a spring as seen from the lower grain of its pair, and back (the flip is its own
        // inverse)
        let orient = |p: &Pair, h: [f64; 3]| {
            if p.i < p.j {
                h
            } else {
                [-h[0], -h[1], -h[2]]
            }
        };
        let sort = self.len() >= self.sort_min_grains;
        if sort {
            self.sort_along_curve();
        }
        if carry {
            // the springs of the old list, keyed by the (new) slots of their grains
            self.history_carry.clear();
            let inv = &self.sort.inv;
            for (a, p) in self.blocks.pairs.iter().enumerate() {
                let st = self.last_spring(a);
                if st != [0.0; 3] {
                    let p = if sort {
                        Pair {
                            i: inv[p.i as usize],
                            j: inv[p.j as usize],
                        }
                    } else {
                        *p
                    };
                    self.history_carry.push((key(&p), orient(&p, st)));
                }
            }
            self.history_carry.sort_unstable_by_key(|e| e.0);
        }
        self.find_pairs(shift);
        let (pos, radius) = (&self.pos, &self.radius);
        self.blocks
            .partition(&self.neighbors.pairs, self.pos.len(), |p: &Pair| {
                touching(pos, radius, p)
            });
        self.pair_coef.clear();
        for &Pair { i, j } in &self.blocks.pairs {
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
        self.pair_history.clear();
        self.pair_history.resize(self.blocks.pairs.len(), [0.0; 3]);
        self.pair_touch.clear();
        self.pair_touch.resize(self.blocks.pairs.len(), 0);
        self.cross_response.clear();
        self.cross_response
            .resize(self.blocks.cross_len(), PairResponse::default());
        self.cross_power.clear();
        self.cross_power.resize(self.blocks.cross_len(), [0.0; 2]);
        if carry && !self.history_carry.is_empty() {
            let last = self.force_evals;
            for ((p, st), t) in self
                .blocks
                .pairs
                .iter()
                .zip(self.pair_history.iter_mut())
                .zip(self.pair_touch.iter_mut())
            {
                if let Ok(a) = self.history_carry.binary_search_by_key(&key(p), |e| e.0) {
                    *st = orient(p, self.history_carry[a].1);
                    *t = last;
                }
            }
        }
    }

    /// The neighbour list of the current centres (box origin `shift`, m). On several
    /// threads the cell list is prepared here, the pairs are found run of cells by run on
    /// the step's executor and concatenated in run order: the list a one-thread rebuild
    /// makes, pair for pair.
    fn find_pairs(&mut self, shift: [f64; 3]) {
        let exec = self.mode.exec(&self.team);
        let runs = match exec {
            Exec::Serial => 1,
            Exec::Team(team) => REBUILD_RUNS_PER_THREAD * team.threads(),
            Exec::Rayon => REBUILD_RUNS_PER_THREAD * rayon::current_num_threads(),
        };
        if runs == 1 {
            self.neighbors.rebuild(&self.pos, &self.radius, shift);
            return;
        }
        self.neighbors.prepare(&self.pos, shift);
        self.neighbors.cell_runs(runs, &mut self.cell_runs);
        self.pair_runs.resize_with(runs, Vec::new);
        {
            let (nl, cells) = (&self.neighbors, &self.cell_runs);
            let (pos, radius) = (&self.pos, &self.radius);
            let out = Parts::new(&mut self.pair_runs);
            exec.units(runs, &|u| {
                // SAFETY: run `u` alone touches its list.
                let list = unsafe { &mut out.get(u..u + 1)[0] };
                list.clear();
                nl.pairs_of_cells(cells[u]..cells[u + 1], pos, radius, list);
            });
        }
        let pairs = &mut self.neighbors.pairs;
        pairs.clear();
        for list in &self.pair_runs {
            pairs.extend_from_slice(list);
        }
    }

    /// `kick`: the grains' second half kick of the step, v ← v + (dt/2) F/m (and ω), done
    /// grain by grain as soon as a grain's force is complete.
    fn forces(&mut self, rebuild: bool, kick: bool) -> (f64, f64) {
        if rebuild {
            self.rebuild_neighbors();
        }
        self.forces_of(kick, None)
            .expect("a force pass without drift always completes")
    }

    /// The force pass (with the drift of the blocks if `drift`, see [`Self::contacts`]),
    /// booking the dissipated powers if the ledger is on.
    fn forces_of(&mut self, kick: bool, drift: Option<f64>) -> Option<(f64, f64)> {
        if self.energy_ledger {
            self.forces_ledger::<true>(kick, drift)
        } else {
            self.forces_ledger::<false>(kick, drift)
        }
    }

    /// The force pass of the contact laws, booking the dissipated powers if `LEDGER`
    /// (otherwise they are not computed and (0, 0) is returned); `None` when the drift found
    /// a neighbour rebuild due.
    fn forces_ledger<const LEDGER: bool>(
        &mut self,
        kick: bool,
        drift: Option<f64>,
    ) -> Option<(f64, f64)> {
        // the laws are matched once per step; each arm runs loops monomorphised on the normal
        // and tangential kernels (rotations and the attraction policy are loop-invariant flags)
        let l = &self.laws;
        let hertz = matches!(l.normal, NormalLaw::HertzKuwabaraKono { .. });
        let out = match (hertz, l.tangential_kind()) {
            (true, TangentialLaw::None) => {
                self.contacts::<HertzKernel, NoTangential, LEDGER>(kick, drift)
            }
            (true, TangentialLaw::CoulombViscous { .. })
            | (true, TangentialLaw::LinearDashpotCoulomb { .. }) => {
                self.contacts::<HertzKernel, CoulombViscousKernel, LEDGER>(kick, drift)
            }
            (true, TangentialLaw::MindlinSpring { .. }) => {
                self.contacts::<HertzKernel, MindlinSpringKernel, LEDGER>(kick, drift)
            }
            (true, TangentialLaw::LinearSpring { .. }) => {
                self.contacts::<HertzKernel, LinearSpringKernel, LEDGER>(kick, drift)
            }
            (false, TangentialLaw::None) => {
                self.contacts::<LinearKernel, NoTangential, LEDGER>(kick, drift)
            }
            (false, TangentialLaw::CoulombViscous { .. })
            | (false, TangentialLaw::LinearDashpotCoulomb { .. }) => {
                self.contacts::<LinearKernel, CoulombViscousKernel, LEDGER>(kick, drift)
            }
            (false, TangentialLaw::MindlinSpring { .. }) => {
                self.contacts::<LinearKernel, MindlinSpringKernel, LEDGER>(kick, drift)
            }
            (false, TangentialLaw::LinearSpring { .. }) => {
                self.contacts::<LinearKernel, LinearSpringKernel, LEDGER>(kick, drift)
            }
        };
        let out = out?;
        self.grain_force_n = out.0;
        Some((out.1, out.2))
    }

    /// The force pass, in the order of [`super::blocks`], as two phases of fixed units:
    /// (1) block by block, gravity and drag and the block's own pairs scattered into its
    /// grains; (2) grain unit by grain unit ([`BlockPairs::unit`]), its wall contacts and its
    /// second half kick. Each unit's sums go to its slot and are added in unit order, so the
    /// result does not depend on who runs the units. The cross pairs come in between, so
    /// that each grain gets them in pair order after its block's own pairs:
    ///
    /// - on one thread, scattered straight into the forces after every block's own pairs;
    /// - on a team, for laws without contact history, evaluated from both sides: in phase 2
    ///   each block first computes every cross pair of its grains and adds the response to
    ///   its own grain only (+F for the pair's i, −F for its j; the same numbers either side),
    ///   then runs its grain units. Only the other block's boundary grains are read across
    ///   threads; nothing is stored for another thread to gather;
    /// - on a team, for laws with springs (whose state one side alone may write), their
    ///   responses stored per pair chunk by chunk alongside phase 1, then gathered per grain
    ///   in phase 2.
    ///
    /// The collision and friction powers of the cross pairs are summed chunk by chunk of
    /// [`CROSS_CHUNK`] pairs on every path.
    ///
    /// With `drift` (the box's displacement since the last neighbour build, m; laws without
    /// contact history only), each block first gives its grains the step's first half kick
    /// and drift, then its own pairs; the cross pairs wait until every block has drifted.
    /// `None` when the drift moved a grain past the neighbour skin: the pass is then
    /// incomplete (forces partial, nothing else written) and the caller rebuilds and calls
    /// again without drift.
    fn contacts<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
        &mut self,
        kick: bool,
        drift: Option<f64>,
    ) -> Option<LoopOut> {
        debug_assert!(
            drift.is_none() || !T::HISTORY,
            "drift in the pass: no springs"
        );
        self.force_evals += 1;
        let exec = self.mode.exec(&self.team);
        let n = self.pos.len();
        let (dt, rot) = (self.dt, self.laws.rotations);
        let bp = &self.blocks;
        // phase 1: blocks (and, on a team with springs, cross-pair chunks)
        let nb = bp.blocks;
        let cross0 = bp.seg[nb];
        let serial = matches!(exec, Exec::Serial);
        let both_sides = !serial && !T::HISTORY && nb > 1;
        let nc = if both_sides {
            0
        } else {
            bp.cross_len().div_ceil(CROSS_CHUNK)
        };
        self.partials.clear();
        self.partials.resize(nb + nc, [0.0; 3]);
        let rebuild_due = {
            let slots = Parts::new(&mut self.partials);
            // the drift's arrays (drifted block by block with `drift`, else only read)
            let kin = Drift::new(
                [
                    &mut self.pos,
                    &mut self.vel,
                    &mut self.vel_pred,
                    &mut self.omega,
                    &mut self.omega_pred,
                ],
                (&self.inv_mass, &self.inv_inertia),
                self.neighbors.reference().0,
                (dt, rot),
                (drift.unwrap_or(0.0), self.prefetch),
            );
            let force = Parts::new(&mut self.force);
            let torque = Parts::new(&mut self.torque);
            let history = Parts::new(&mut self.pair_history);
            let touch = Parts::new(&mut self.pair_touch);
            let response = Parts::new(&mut self.cross_response);
            let ctx = PairCtx {
                eval: self.force_evals,
                simd: self.simd,
                uniform: self.uniform,
                pos: kin.pos.view(),
                vel: kin.vel_pred.view(),
                omega: kin.omega_pred.view(),
                radius: &self.radius,
                friction: self.laws.friction(false),
                clamp: self.laws.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let weight = Weight {
                mass: &self.mass,
                vel: kin.vel.view(),
                gravity: self.gravity,
                drag: self.settle_drag,
                rotations: rot,
            };
            let own = |blk: usize| {
                let g = bp.grains(blk);
                let (s0, s1) = (bp.seg[blk], bp.seg[blk + 1]);
                // SAFETY: block `blk` alone touches its grains and its own pairs' states.
                let (f, t, hs, ts) = unsafe {
                    (
                        force.get(g.clone()),
                        torque.get(g.clone()),
                        history.get(s0..s1),
                        touch.get(s0..s1),
                    )
                };
                let max_d2 = if drift.is_some() {
                    // SAFETY: as above (the block's grains, written by this unit only).
                    unsafe { kin.grains(g.clone(), f, t) }
                } else {
                    0.0
                };
                init_forces(&weight, g.start, f, t);
                let (mut pc, mut pf) = (0.0, 0.0);
                for (((h, tc), p), c) in hs
                    .chunks_mut(PAIR_CHUNK)
                    .zip(ts.chunks_mut(PAIR_CHUNK))
                    .zip(bp.pairs[s0..s1].chunks(PAIR_CHUNK))
                    .zip(self.pair_coef[s0..s1].chunks(PAIR_CHUNK))
                {
                    let chunk = PairChunk {
                        pairs: p,
                        coef: c,
                        history: h,
                        touch: tc,
                        response: &mut [],
                        first: g.start,
                        force: &mut *f,
                        torque: &mut *t,
                    };
                    let part = pair_chunk::<N, T, true, LEDGER>(&ctx, chunk);
                    pc += part[0];
                    pf += part[1];
                }
                // SAFETY: slot `blk` is this unit's.
                unsafe { slots.get(blk..blk + 1)[0] = [pc, pf, max_d2] };
            };
            let cross = |c: usize| {
                let r =
                    cross0 + c * CROSS_CHUNK..(cross0 + (c + 1) * CROSS_CHUNK).min(bp.pairs.len());
                let (pairs, coef) = (&bp.pairs[r.clone()], &self.pair_coef[r.clone()]);
                // SAFETY: cross chunk `c` alone touches these springs and responses.
                let (hist, tc) = unsafe { (history.get(r.clone()), touch.get(r.clone())) };
                let resp = unsafe { response.get(r.start - cross0..r.end - cross0) };
                let part = if serial {
                    // one thread, after every block's own pairs: the responses straight into
                    // the forces, pair by pair in pair order — the additions, in the order,
                    // of the per-grain gathering of the threaded paths
                    // SAFETY: one thread: no other piece is in use.
                    let (force, torque) = unsafe { (force.get(0..n), torque.get(0..n)) };
                    let chunk = PairChunk {
                        pairs,
                        coef,
                        history: hist,
                        touch: tc,
                        response: &mut [],
                        first: 0,
                        force,
                        torque,
                    };
                    pair_chunk::<N, T, true, LEDGER>(&ctx, chunk)
                } else {
                    let chunk = PairChunk {
                        pairs,
                        coef,
                        history: hist,
                        touch: tc,
                        response: resp,
                        first: 0,
                        force: &mut [],
                        torque: &mut [],
                    };
                    pair_chunk::<N, T, false, LEDGER>(&ctx, chunk)
                };
                // SAFETY: slot `nb + c` is this unit's.
                unsafe { slots.get(nb + c..nb + c + 1)[0] = part };
            };
            if drift.is_some() {
                exec.units(nb, &own);
                // SAFETY: the phase is over: no unit holds a piece.
                let blocks = unsafe { slots.get(0..nb) };
                let max_d2 = blocks.iter().fold(0.0, |a: f64, s| a.max(s[2]));
                let due = self.neighbors.exceeded(max_d2);
                if !due {
                    exec.units(nc, &cross);
                }
                due
            } else {
                exec.units2((nb, &own), (nc, &cross));
                false
            }
        };
        if rebuild_due {
            return None;
        }
        let fold2 = |s: &[[f64; 3]]| s.iter().fold((0.0, 0.0), |a, p| (a.0 + p[0], a.1 + p[1]));
        let (oc, of) = fold2(&self.partials[..nb]);
        // phase 2: grain units (cross pairs from both sides or gathered, walls, second half
        // kick)
        let units = bp.units();
        self.grain_partials.clear();
        self.grain_partials.resize(units, [0.0; 5]);
        {
            let b = self.box_size;
            let gctx = GrainCtx {
                simd: self.simd,
                uniform: self.uniform,
                pos: &self.pos,
                vel_pred: &self.vel_pred,
                omega_pred: &self.omega_pred,
                radius: &self.radius,
                mass: &self.mass,
                inv_mass: &self.inv_mass,
                inv_inertia: &self.inv_inertia,
                kick,
                wall_coef: &self.wall_coef,
                // (the cross pairs are in the forces already, unless stored per pair)
                cross_start: if serial || both_sides {
                    &[]
                } else {
                    &bp.cross_start
                },
                cross_items: &bp.cross_items,
                cross_state: if serial || both_sides {
                    &[]
                } else {
                    &self.cross_response
                },
                box_size: b,
                floor: self.box_z,
                ceil: self.box_z + b[2],
                wall_v: self.box_v_pred,
                friction: self.laws.friction(true),
                clamp: self.laws.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let ctx = PairCtx {
                eval: self.force_evals,
                simd: self.simd,
                uniform: self.uniform,
                pos: View::of(&self.pos),
                vel: View::of(&self.vel_pred),
                omega: View::of(&self.omega_pred),
                radius: &self.radius,
                friction: self.laws.friction(false),
                clamp: self.laws.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let cross_pairs = &bp.pairs[cross0..];
            let cross_coef = match self.uniform {
                Some(_) => &[][..],
                None => &self.pair_coef[cross0..],
            };
            let slots = Parts::new(&mut self.grain_partials);
            let power = Parts::new(&mut self.cross_power);
            let force = Parts::new(&mut self.force);
            let torque = Parts::new(&mut self.torque);
            let hist = Parts::new(&mut self.wall_history);
            let vel = Parts::new(&mut self.vel);
            let omega = Parts::new(&mut self.omega);
            // grain unit `u` of grains `r`, whose forces and torques are `f` and `t`
            let unit = |u: usize, f: &mut [[f64; 3]], t: &mut [[f64; 3]]| {
                let r = bp.unit(u);
                // SAFETY: grain unit `u` alone touches its grains and its slot.
                let chunk = unsafe {
                    GrainChunk {
                        first: r.start,
                        force: f,
                        torque: t,
                        wall_history: hist.get(r.clone()),
                        vel: vel.get(r.clone()),
                        omega: omega.get(r),
                    }
                };
                let out = grain_chunk::<N, T, LEDGER>(&gctx, chunk);
                // SAFETY: slot `u` is this unit's.
                unsafe { slots.get(u..u + 1)[0] = out };
            };
            if both_sides {
                exec.units(nb, &|blk| {
                    let g = bp.grains(blk);
                    // SAFETY: block `blk` alone touches its grains' forces and the powers of
                    // the cross pairs whose i is one of them.
                    let (f, t) = unsafe { (force.get(g.clone()), torque.get(g.clone())) };
                    let (cross_items, owner) = bp.cross_items_of(blk);
                    let side = CrossSide {
                        first: g.start,
                        cross_items,
                        owner,
                        pairs: cross_pairs,
                        coef: cross_coef,
                        power: &power,
                        force: &mut *f,
                        torque: &mut *t,
                    };
                    // SAFETY: as above.
                    unsafe { cross_side::<N, T, LEDGER>(&ctx, side) };
                    for u in bp.units_of(blk) {
                        let r = bp.unit(u);
                        let local = r.start - g.start..r.end - g.start;
                        unit(u, &mut f[local.clone()], &mut t[local]);
                    }
                });
            } else {
                exec.units(units, &|u| {
                    let r = bp.unit(u);
                    // SAFETY: grain unit `u` alone touches its grains.
                    let (f, t) = unsafe { (force.get(r.clone()), torque.get(r)) };
                    unit(u, f, t);
                });
            }
        }
        let (xc, xf) = if both_sides && !LEDGER {
            (0.0, 0.0)
        } else if both_sides {
            // the powers per cross pair, summed as the cross chunks of the other paths do
            self.cross_power
                .chunks(CROSS_CHUNK)
                .fold((0.0, 0.0), |a, c| {
                    let s = c.iter().fold((0.0, 0.0), |s, p| (s.0 + p[0], s.1 + p[1]));
                    (a.0 + s.0, a.1 + s.1)
                })
        } else {
            fold2(&self.partials[nb..])
        };
        let mut t = [0.0; 5];
        for p in &self.grain_partials {
            for (a, b) in t.iter_mut().zip(p) {
                *a += b;
            }
        }
        if kick {
            self.step_cm = (t[3] / self.mass_total, t[4] / self.mass_total);
        }
        Some((t[0], (oc + xc) + t[1], (of + xf) + t[2]))
    }

    /// Pair `a`'s tangential spring as the last force evaluation left it (m).
    fn last_spring(&self, a: usize) -> [f64; 3] {
        spring(
            &self.pair_history,
            &self.pair_touch,
            a,
            self.force_evals + 1,
        )
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

    /// Centre of mass height z_cm and vertical velocity v_cm of the grains at the end of the
    /// last [`DemWorld::step`] (m, m/s), as the step summed them (chunk by chunk, in its
    /// last phase: no extra pass over the grains); NaN before the first step. Equal to
    /// [`DemWorld::z_cm_state`] up to round-off right after a step.
    pub fn step_cm(&self) -> (f64, f64) {
        self.step_cm
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

    /// Sets grain velocities (m/s) and angular velocities (rad/s), given in grain-id order,
    /// e.g. for tests.
    pub fn set_velocities(&mut self, vel: &[[f64; 3]], omega: &[[f64; 3]]) {
        assert!(vel.len() == self.len() && omega.len() == self.len());
        for (k, &g) in self.id.iter().enumerate() {
            self.vel[k] = vel[g as usize];
            self.omega[k] = omega[g as usize];
        }
    }

    /// Recomputes forces for the current state (call after editing positions or velocities
    /// by hand, before stepping).
    pub fn refresh(&mut self) {
        self.compute_forces();
    }
}

/// Shared inputs of the pair pass.
struct PairCtx<'a> {
    /// Number of this force evaluation (the clock of the pairs' `touch`).
    eval: u64,
    simd: Simd,
    /// Every grain's radius and coefficients, when all grains are alike.
    uniform: Option<Uniform>,
    /// Centres (m), predicted velocities (m/s) and spins (rad/s): views, since a block may
    /// be drifting its own grains in the same phase (it reads them only after).
    pos: View<'a, [f64; 3]>,
    vel: View<'a, [f64; 3]>,
    omega: View<'a, [f64; 3]>,
    radius: &'a [f64],
    friction: f64,
    clamp: bool,
    rotations: bool,
    dt: f64,
}

impl PairCtx<'_> {
    /// (R_i, R_j) of pair (i, j) (m).
    #[inline(always)]
    fn radii(&self, i: usize, j: usize) -> (f64, f64) {
        match self.uniform {
            Some(u) => (u.radius, u.radius),
            None => (self.radius[i], self.radius[j]),
        }
    }
}

/// Pair `a`'s tangential spring at force evaluation `eval` (m): the stored elongation if the
/// pair touched at the evaluation before, else zero (a new contact starts unstretched). The
/// springs of pairs that stop touching are left stale rather than cleared: which candidates
/// touch is unpredictable, and a conditional store per candidate cost a quarter of a step.
#[inline(always)]
fn spring(history: &[[f64; 3]], touch: &[u64], a: usize, eval: u64) -> [f64; 3] {
    if touch[a] + 1 == eval {
        history[a]
    } else {
        [0.0; 3]
    }
}

/// The first `m` entries of a scratch array filled front to back, as a slice.
///
/// # Safety
/// Entries `0..m` must have been written, and `m ≤ a.len()`.
#[inline(always)]
unsafe fn written<T>(a: &[MaybeUninit<T>], m: usize) -> &[T] {
    debug_assert!(m <= a.len());
    // SAFETY: the caller's promise; `MaybeUninit<T>` has the layout of `T`.
    unsafe { std::slice::from_raw_parts(a.as_ptr().cast::<T>(), m) }
}

/// Whether the grains of pair `p` overlap: |r_i − r_j| < R_i + R_j (centres `pos` in m, radii
/// `radius` in m).
fn touching(pos: &[[f64; 3]], radius: &[f64], p: &Pair) -> bool {
    let (i, j) = (p.i as usize, p.j as usize);
    let d = sub3(pos[i], pos[j]);
    let cut = radius[i] + radius[j];
    dot(d, d) < cut * cut
}

/// Runs of cells per thread of a threaded neighbour rebuild (some to claim when a thread
/// finishes its share early).
const REBUILD_RUNS_PER_THREAD: usize = 4;

/// One chunk of candidate pairs: a branch-free pass keeps the pairs in contact (and clears
/// the others' outputs), then [`contact_response`] runs on those only, `L::N`
/// contacts at a time in lanes. Returns the chunk's (collision power, friction power, 0) (W).
///
/// `SCATTER` (a block's own pairs): the forces and torques go straight into the block's `force`
/// and `torque` (which hold gravity and drag already), pair by pair in pair order. Otherwise
/// (cross pairs) each response is stored in the pair's [`PairResponse`] for the per-grain pass.
#[inline(always)]
fn pair_chunk_impl<
    L: Lanes,
    N: NormalKernel,
    T: TangentialKernel,
    const SCATTER: bool,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    chunk: PairChunk,
) -> [f64; 3] {
    let PairChunk {
        pairs,
        coef,
        history,
        touch,
        response,
        first,
        force,
        torque,
    } = chunk;
    let pos = ctx.pos;
    // the pairs in contact and their separations r_i − r_j (m), kept for the gather: the
    // first `m` entries, written before they are read (left uninitialised, as clearing
    // 28 KB per chunk costs a small bed a few per cent of its step)
    let mut active = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut sep = [const { MaybeUninit::<[f64; 3]>::uninit() }; PAIR_CHUNK];
    let mut m = 0usize;
    for (a, pair) in pairs.iter().enumerate() {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let d = sub3(pos.at(i), pos.at(j));
        let r2 = dot(d, d);
        let (ri, rj) = ctx.radii(i, j);
        let cut = ri + rj;
        let on = r2 < cut * cut;
        active[m].write(a as u32);
        sep[m].write(d);
        m += on as usize;
        if !SCATTER {
            response[a] = PairResponse::default();
        }
    }
    // L::N contacts at a time: gathered into lanes, one lane-wise geometry and
    // [`contact_response`] (vector instructions), then the sums contact by contact
    let (mut p_coll, mut p_fric) = (0.0, 0.0);
    let mut g = PairLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.r_i = L::splat(u.radius);
        g.r_j = L::splat(u.radius);
        g.coef = u.pair.map(L::splat);
    }
    // SAFETY: entries 0..m were written by the loop above (entry m is written before m
    // grows past it).
    let (active, sep) = unsafe { (written(&active, m), written(&sep, m)) };
    for (block, seps) in active.chunks(L::N).zip(sep.chunks(L::N)) {
        for (l, (&a, &d)) in block.iter().zip(seps).enumerate() {
            let pair = pairs[a as usize];
            g.gather(ctx, pair.i as usize, pair.j as usize, l, d);
            if ctx.uniform.is_none() {
                set_lane(&mut g.coef, l, coef[a as usize]);
            }
            if T::HISTORY {
                set_lane(
                    &mut g.history,
                    l,
                    spring(history, touch, a as usize, ctx.eval),
                );
            }
        }
        let r = contact_response::<N, T, L>(
            &g.kinematics(ctx.rotations),
            &g.coef,
            ctx.friction,
            ctx.clamp,
            ctx.rotations,
            ctx.dt,
            &mut g.history,
        );
        for (l, &a) in block.iter().enumerate() {
            let a = a as usize;
            let (f, t) = (get_lane(&r.force, l), get_lane(&r.torque_arm, l));
            if T::HISTORY {
                history[a] = get_lane(&g.history, l);
                touch[a] = ctx.eval;
            }
            if SCATTER {
                let pair = pairs[a];
                let (i, j) = (pair.i as usize, pair.j as usize);
                let fi = &mut force[i - first];
                fi[0] += f[0];
                fi[1] += f[1];
                fi[2] += f[2];
                let fj = &mut force[j - first];
                fj[0] -= f[0];
                fj[1] -= f[1];
                fj[2] -= f[2];
                if T::ACTIVE && ctx.rotations {
                    let (ri, rj) = ctx.radii(i, j);
                    let ti = &mut torque[i - first];
                    ti[0] -= ri * t[0];
                    ti[1] -= ri * t[1];
                    ti[2] -= ri * t[2];
                    let tj = &mut torque[j - first];
                    tj[0] -= rj * t[0];
                    tj[1] -= rj * t[1];
                    tj[2] -= rj * t[2];
                }
            } else {
                response[a] = PairResponse {
                    force: f,
                    torque_arm: t,
                };
            }
            if LEDGER {
                p_coll += r.p_collision.get(l);
                p_fric += r.p_friction.get(l);
            }
        }
    }
    [p_coll, p_fric, 0.0]
}

/// The inputs of up to `L::N` grain–grain contacts, one contact per lane (lanes past the
/// block's end keep an earlier contact's values: computed, never used).
#[derive(Default)]
struct PairLanes<L> {
    /// r_i − r_j (m).
    d: [L; 3],
    /// v_i − v_j (m/s).
    v_rel: [L; 3],
    /// R_i ω_i + R_j ω_j (m/s), summed per contact as it is gathered.
    spin: [L; 3],
    r_i: L,
    r_j: L,
    coef: [L; 4],
    history: [L; 3],
}

impl<L: Lanes> PairLanes<L> {
    /// Puts pair (i, j)'s separation `d` (from the distance filter), relative velocity, spin term R_i ω_i + R_j ω_j (and
    /// radii unless all grains are alike) in lane `l`.
    #[inline(always)]
    fn gather(&mut self, ctx: &PairCtx, i: usize, j: usize, l: usize, d: [f64; 3]) {
        set_lane(&mut self.d, l, d);
        set_lane(&mut self.v_rel, l, sub3(ctx.vel.at(i), ctx.vel.at(j)));
        let (ri, rj) = ctx.radii(i, j);
        if ctx.rotations {
            let (wi, wj) = (ctx.omega.at(i), ctx.omega.at(j));
            let spin = std::array::from_fn(|c| ri * wi[c] + rj * wj[c]);
            set_lane(&mut self.spin, l, spin);
        }
        if ctx.uniform.is_none() {
            self.r_i.set(l, ri);
            self.r_j.set(l, rj);
        }
    }

    /// Overlap R_i + R_j − |d|, normal d/|d|, relative velocity and R_i ω_i + R_j ω_j.
    #[inline(always)]
    fn kinematics(&self, rotations: bool) -> ContactKinematics<L> {
        let d = self.d;
        let dist = dot(d, d).sqrt();
        let inv = L::splat(1.0) / dist;
        let spin = if rotations {
            self.spin
        } else {
            [L::default(); 3]
        };
        ContactKinematics {
            overlap_m: self.r_i + self.r_j - dist,
            normal: [d[0] * inv, d[1] * inv, d[2] * inv],
            v_rel: self.v_rel,
            spin,
        }
    }
}

/// One chunk of the pair pass: its candidate pairs, their coefficients and states, and (one
/// thread) the grains' forces and torques to add the responses to.
struct PairChunk<'a> {
    pairs: &'a [Pair],
    coef: &'a [ContactCoefficients],
    /// Tangential springs of the chunk's pairs (m).
    history: &'a mut [[f64; 3]],
    /// Force evaluation at which each of the chunk's pairs last touched.
    touch: &'a mut [u64],
    /// The chunk's responses (cross pairs; empty when they are scattered).
    response: &'a mut [PairResponse],
    /// Grain of `force[0]` and `torque[0]` (the first grain of the block).
    first: usize,
    force: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
}

/// One chunk of the per-grain pass: grains `first..first + force.len()`.
struct GrainChunk<'a> {
    first: usize,
    force: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
    wall_history: &'a mut [[[f64; 3]; 6]],
    vel: &'a mut [[f64; 3]],
    omega: &'a mut [[f64; 3]],
}

/// [`pair_chunk_impl`] compiled for the instruction set `ctx.simd`.
#[inline(never)]
fn pair_chunk<N: NormalKernel, T: TangentialKernel, const SCATTER: bool, const LEDGER: bool>(
    ctx: &PairCtx,
    c: PairChunk,
) -> [f64; 3] {
    match ctx.simd {
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`, made only by `Simd::detect`)
        // that the processor has AVX2.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { pair_chunk_avx2::<N, T, SCATTER, LEDGER>(ctx, c) },
        Simd::Baseline => pair_chunk_impl::<F64x8, N, T, SCATTER, LEDGER>(ctx, c),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn pair_chunk_avx2<
    N: NormalKernel,
    T: TangentialKernel,
    const SCATTER: bool,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    c: PairChunk,
) -> [f64; 3] {
    pair_chunk_impl::<F64x8, N, T, SCATTER, LEDGER>(ctx, c)
}

/// The cross pairs of one block, seen from its side: each of its grains' cross pairs
/// ([`BlockPairs::cross_items_of`]), whose responses go to that grain only.
struct CrossSide<'a> {
    /// The block's first grain (that of `force[0]`).
    first: usize,
    /// The block's items: per grain in grain order, its cross pairs in pair order (index
    /// among the cross pairs, [`J_ROLE`] where the grain is the pair's j), and their grains.
    cross_items: &'a [u32],
    owner: &'a [u32],
    /// All cross pairs, and their coefficients (empty when all grains are alike).
    pairs: &'a [Pair],
    coef: &'a [ContactCoefficients],
    /// Per cross pair, its (collision, friction) power (W): written, with the ledger, by the
    /// block of the pair's i (0 when not in contact).
    power: &'a Parts<'a, [f64; 2]>,
    force: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
}

/// [`cross_side_impl`] compiled for the instruction set `ctx.simd`.
///
/// # Safety
/// No other unit of the phase may touch the powers of the pairs whose i is one of the block's
/// grains, nor write the grains' centres, velocities and spins that `ctx` reads.
#[inline(never)]
unsafe fn cross_side<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    s: CrossSide,
) {
    match ctx.simd {
        // SAFETY: as in `pair_chunk`; the rest is the caller's promise.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { cross_side_avx2::<N, T, LEDGER>(ctx, s) },
        // SAFETY: the caller's promise.
        Simd::Baseline => unsafe { cross_side_impl::<F64x8, N, T, LEDGER>(ctx, s) },
    }
}

/// [`cross_side_impl`] compiled with AVX2.
///
/// # Safety
/// The processor must have AVX2 (a [`Simd::Avx2`] in hand proves it), and the caller keeps the
/// promise of [`cross_side`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn cross_side_avx2<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    s: CrossSide,
) {
    // SAFETY: the caller's promise.
    unsafe { cross_side_impl::<F64x8, N, T, LEDGER>(ctx, s) }
}

/// A block's side of its cross pairs (laws without contact history): a branch-free pass keeps
/// the items in contact, then [`contact_response`] runs on those, `L::N` at a time in lanes,
/// on the pair's own orientation (r_i − r_j, so the numbers are those the pair's other side
/// computes); the force is added to the block's grain (+F for the pair's i, −F for its j) and
/// the torque −R τ_arm, item by item: each grain gets its cross pairs in pair order.
///
/// # Safety
/// As [`cross_side`].
#[inline(always)]
unsafe fn cross_side_impl<L: Lanes, N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    mut s: CrossSide,
) {
    debug_assert!(!T::HISTORY, "springs are written by one side only");
    let pos = ctx.pos;
    // the items in contact, their grains (relative to the block) and separations, kept for the
    // lanes: the first `m` entries (left uninitialised, as in `pair_chunk_impl`)
    let mut item = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut who = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut sep = [const { MaybeUninit::<[f64; 3]>::uninit() }; PAIR_CHUNK];
    let mut m = 0usize;
    let mut g = PairLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.r_i = L::splat(u.radius);
        g.r_j = L::splat(u.radius);
        g.coef = u.pair.map(L::splat);
    }
    for (&e, &gi) in s.cross_items.iter().zip(s.owner) {
        let a = (e & !J_ROLE) as usize;
        let pair = s.pairs[a];
        let (i, j) = (pair.i as usize, pair.j as usize);
        let d = sub3(pos.at(i), pos.at(j));
        let (ri, rj) = ctx.radii(i, j);
        let cut = ri + rj;
        let on = dot(d, d) < cut * cut;
        if LEDGER && e & J_ROLE == 0 {
            // SAFETY: pair a's i is this block's grain (the caller's promise).
            unsafe { s.power.get(a..a + 1)[0] = [0.0; 2] };
        }
        item[m].write(e);
        who[m].write(gi - s.first as u32);
        sep[m].write(d);
        m += on as usize;
        if m == PAIR_CHUNK {
            // SAFETY: entries 0..m were written above.
            let (e, w, d) = unsafe { (written(&item, m), written(&who, m), written(&sep, m)) };
            // SAFETY: the caller's promise.
            unsafe { cross_lanes::<L, N, T, LEDGER>(ctx, &mut s, &mut g, (e, w, d)) };
            m = 0;
        }
    }
    // SAFETY: entries 0..m were written above.
    let (e, w, d) = unsafe { (written(&item, m), written(&who, m), written(&sep, m)) };
    // SAFETY: the caller's promise.
    unsafe { cross_lanes::<L, N, T, LEDGER>(ctx, &mut s, &mut g, (e, w, d)) };
}

/// The responses of a block's cross items in contact `(item, grain in the block,
/// separation)`, `L::N` at a time, added to the block's grains in item order.
///
/// # Safety
/// As [`cross_side`].
#[inline(always)]
unsafe fn cross_lanes<L: Lanes, N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    s: &mut CrossSide,
    g: &mut PairLanes<L>,
    (items, who, seps): (&[u32], &[u32], &[[f64; 3]]),
) {
    for ((block, ks), ds) in items
        .chunks(L::N)
        .zip(who.chunks(L::N))
        .zip(seps.chunks(L::N))
    {
        for (l, (&e, &d)) in block.iter().zip(ds).enumerate() {
            let a = (e & !J_ROLE) as usize;
            let pair = s.pairs[a];
            g.gather(ctx, pair.i as usize, pair.j as usize, l, d);
            if ctx.uniform.is_none() {
                set_lane(&mut g.coef, l, s.coef[a]);
            }
        }
        let r = contact_response::<N, T, L>(
            &g.kinematics(ctx.rotations),
            &g.coef,
            ctx.friction,
            ctx.clamp,
            ctx.rotations,
            ctx.dt,
            &mut g.history,
        );
        for (l, (&e, &k)) in block.iter().zip(ks).enumerate() {
            let (f, t) = (get_lane(&r.force, l), get_lane(&r.torque_arm, l));
            let k = k as usize;
            let fi = &mut s.force[k];
            if e & J_ROLE == 0 {
                fi[0] += f[0];
                fi[1] += f[1];
                fi[2] += f[2];
                if LEDGER {
                    let a = (e & !J_ROLE) as usize;
                    let p = [r.p_collision.get(l), r.p_friction.get(l)];
                    // SAFETY: pair a's i is this block's grain (the caller's promise).
                    unsafe { s.power.get(a..a + 1)[0] = p };
                }
            } else {
                fi[0] -= f[0];
                fi[1] -= f[1];
                fi[2] -= f[2];
            }
            if T::ACTIVE && ctx.rotations {
                let rg = match ctx.uniform {
                    Some(u) => u.radius,
                    None => ctx.radius[s.first + k],
                };
                let ti = &mut s.torque[k];
                ti[0] -= rg * t[0];
                ti[1] -= rg * t[1];
                ti[2] -= rg * t[2];
            }
        }
    }
}

/// [`grain_chunk_impl`] compiled for the instruction set `ctx.simd`.
#[inline(never)]
fn grain_chunk<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &GrainCtx,
    c: GrainChunk,
) -> [f64; 5] {
    match ctx.simd {
        // SAFETY: as in `pair_chunk`.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { grain_chunk_avx2::<N, T, LEDGER>(ctx, c) },
        Simd::Baseline => grain_chunk_impl::<F64x8, N, T, LEDGER>(ctx, c),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn grain_chunk_avx2<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &GrainCtx,
    c: GrainChunk,
) -> [f64; 5] {
    grain_chunk_impl::<F64x8, N, T, LEDGER>(ctx, c)
}

/// Overlaps of grain i with the walls x−, x+, y−, y+, floor, ceiling (m); ≤ 0: no contact.
/// Wall w has the normal ±e_{w/2}, + for even w (pointing into the box).
#[inline(always)]
fn wall_overlaps(ctx: &GrainCtx, i: usize) -> [f64; 6] {
    let (p, r, b) = (ctx.pos[i], ctx.radius[i], ctx.box_size);
    [
        r - p[0],
        r - (b[0] - p[0]),
        r - p[1],
        r - (b[1] - p[1]),
        r - (p[2] - ctx.floor),
        r - (ctx.ceil - p[2]),
    ]
}

/// The grain arrays and constants of the step's first half kick and drift (2.2.4–2.2.5),
/// applied grain range by grain range.
struct Drift<'a> {
    pos: Parts<'a, [f64; 3]>,
    vel: Parts<'a, [f64; 3]>,
    vel_pred: Parts<'a, [f64; 3]>,
    omega: Parts<'a, [f64; 3]>,
    omega_pred: Parts<'a, [f64; 3]>,
    inv_mass: &'a [f64],
    inv_inertia: &'a [f64],
    /// Centres at the last neighbour build (m); empty when not tracked.
    reference: &'a [[f64; 3]],
    /// Half step and step (s).
    h: f64,
    dt: f64,
    rotations: bool,
    /// The box's vertical displacement since the last neighbour build (m).
    shift_z: f64,
    /// Write prefetches of the stored lines ([`WritePrefetch`]).
    prefetch: Option<WritePrefetch>,
}

impl<'a> Drift<'a> {
    /// The drift of the grains whose centres, velocities, predicted velocities, spins and
    /// predicted spins are `kin` (handed out in pieces from here on), with their inverse
    /// masses and inertias `inv`, the centres at the last neighbour build `reference` (not
    /// tracked unless one per grain), the time step and rotation flag `(dt, rotations)`.
    fn new(
        kin: [&'a mut [[f64; 3]]; 5],
        (inv_mass, inv_inertia): (&'a [f64], &'a [f64]),
        reference: &'a [[f64; 3]],
        (dt, rotations): (f64, bool),
        (shift_z, prefetch): (f64, Option<WritePrefetch>),
    ) -> Self {
        let n = kin[0].len();
        let [pos, vel, vel_pred, omega, omega_pred] = kin.map(Parts::new);
        Drift {
            pos,
            vel,
            vel_pred,
            omega,
            omega_pred,
            inv_mass,
            inv_inertia,
            reference: if reference.len() == n { reference } else { &[] },
            h: 0.5 * dt,
            dt,
            rotations,
            shift_z,
            prefetch,
        }
    }

    /// Half kick (v and ω, with their predicted full-step values) and drift of grains `r`,
    /// whose force and torque are `force` and `torque` (N, N m); returns the largest squared
    /// displacement since the last neighbour build relative to the box (m²; ∞ untracked).
    ///
    /// # Safety
    /// No other unit touches grains `r` of the drifted arrays meanwhile.
    unsafe fn grains(&self, r: Range<usize>, force: &[[f64; 3]], torque: &[[f64; 3]]) -> f64 {
        // SAFETY: the caller's promise.
        unsafe {
            if self.rotations {
                half_kick_predict(
                    self.omega.get(r.clone()),
                    self.omega_pred.get(r.clone()),
                    torque,
                    &self.inv_inertia[r.clone()],
                    self.h,
                    self.prefetch,
                );
            }
            let refs = match self.reference {
                [] => &[],
                all => &all[r.clone()],
            };
            kick_drift(
                self.pos.get(r.clone()),
                self.vel.get(r.clone()),
                self.vel_pred.get(r.clone()),
                force,
                &self.inv_mass[r],
                (self.h, self.dt),
                refs,
                [0.0, 0.0, self.shift_z],
                self.prefetch,
            )
        }
    }
}

/// What the force on a grain starts from: its weight and the settling drag.
struct Weight<'a> {
    /// Grain masses (kg).
    mass: &'a [f64],
    /// Grain velocities (m/s), read for the drag.
    vel: View<'a, [f64; 3]>,
    /// Gravity (m/s²).
    gravity: f64,
    /// Settling drag rate (1/s; 0 in a run).
    drag: f64,
    /// Whether torques are computed (then zeroed here).
    rotations: bool,
}

/// Gravity and settling drag on grains `first..first + force.len()` (a block, before its own
/// pairs): F = −m g e_z − m β v, and a zero torque (N, N m).
fn init_forces(w: &Weight, first: usize, force: &mut [[f64; 3]], torque: &mut [[f64; 3]]) {
    for (k, (f, t)) in force.iter_mut().zip(torque.iter_mut()).enumerate() {
        let i = first + k;
        let m = w.mass[i];
        *f = [0.0, 0.0, -m * w.gravity];
        if w.drag > 0.0 {
            let (s, v) = (-m * w.drag, w.vel.at(i));
            f[0] += s * v[0];
            f[1] += s * v[1];
            f[2] += s * v[2];
        }
        if w.rotations {
            *t = [0.0; 3];
        }
    }
}

/// Shared inputs of the per-grain pass.
struct GrainCtx<'a> {
    simd: Simd,
    /// Every grain's radius and coefficients, when all grains are alike.
    uniform: Option<Uniform>,
    pos: &'a [[f64; 3]],
    vel_pred: &'a [[f64; 3]],
    omega_pred: &'a [[f64; 3]],
    radius: &'a [f64],
    mass: &'a [f64],
    inv_mass: &'a [f64],
    inv_inertia: &'a [f64],
    /// Whether the chunk ends with the grains' second half kick (during a step).
    kick: bool,
    wall_coef: &'a [ContactCoefficients],
    /// Per grain, where its cross pairs start in `cross_items` ([`BlockPairs::cross_start`]);
    /// empty when the cross pairs were scattered into the forces (one thread).
    cross_start: &'a [u32],
    /// Per grain, its cross pairs in pair order ([`BlockPairs::cross_items`]).
    cross_items: &'a [u32],
    /// States of the cross pairs (their responses, from the pair pass).
    cross_state: &'a [PairResponse],
    box_size: [f64; 3],
    floor: f64,
    ceil: f64,
    wall_v: f64,
    friction: f64,
    clamp: bool,
    rotations: bool,
    dt: f64,
}

/// One chunk of grains from `first`, whose `force` and `torque` hold gravity, drag and the
/// block's own pairs already: each grain's cross pairs gathered in pair order (so the sums do
/// not depend on the threads), then its contacts with the six walls through the same
/// [`contact_response`]. Returns the chunk's (F_gz, collision power, friction power) (N, W, W).
///
/// With `ctx.kick` the chunk's grains then get the step's second half kick (2.2.5),
/// v ← v + (dt/2) F/m and ω ← ω + (dt/2) τ/I, their forces being complete.
#[inline(always)]
fn grain_chunk_impl<L: Lanes, N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &GrainCtx,
    chunk: GrainChunk,
) -> [f64; 5] {
    let GrainChunk {
        first,
        force,
        torque,
        wall_history,
        vel,
        omega,
    } = chunk;
    let (mut fgz, mut p_coll, mut p_fric) = (0.0, 0.0, 0.0);
    // the chunk's wall contacts (grain × 6 + wall): the first `m` entries, written before
    // they are read (left uninitialised: clearing 12 KB per chunk costs a small bed ~2 %)
    let mut walls = [const { MaybeUninit::<u32>::uninit() }; 6 * GRAIN_CHUNK];
    let mut m = 0usize;
    for (l, ((fi, ti), hist)) in force
        .iter_mut()
        .zip(torque.iter_mut())
        .zip(wall_history.iter_mut())
        .enumerate()
    {
        let i = first + l;
        let r = ctx.radius[i];
        let items = match ctx.cross_start {
            [] => &[],
            s => &ctx.cross_items[s[i] as usize..s[i + 1] as usize],
        };
        for &e in items {
            let st = &ctx.cross_state[(e & !J_ROLE) as usize];
            // +1 where i is the pair's i, −1 where it is its j (exact: a + (−b) = a − b, the
            // scatter's subtraction)
            let sign = 1.0 - 2.0 * (e >> 31) as f64;
            fi[0] += sign * st.force[0];
            fi[1] += sign * st.force[1];
            fi[2] += sign * st.force[2];
            if T::ACTIVE && ctx.rotations {
                ti[0] -= r * st.torque_arm[0];
                ti[1] -= r * st.torque_arm[1];
                ti[2] -= r * st.torque_arm[2];
            }
        }
        // far from every wall (most grains of a wide bed): nothing to do (one branch for
        // the six tests, `&` not `&&`: a small box has grains near some wall at random)
        let p = ctx.pos[i];
        if (p[0] > r)
            & (p[0] < ctx.box_size[0] - r)
            & (p[1] > r)
            & (p[1] < ctx.box_size[1] - r)
            & (p[2] > ctx.floor + r)
            & (p[2] < ctx.ceil - r)
        {
            if T::HISTORY {
                *hist = [[0.0; 3]; 6];
            }
            continue;
        }
        // the grain's wall contacts, kept branch-free (six overlaps against the box)
        let z6 = wall_overlaps(ctx, i);
        for (w, z) in z6.into_iter().enumerate() {
            let on = z > 0.0;
            walls[m].write((l * 6 + w) as u32);
            m += on as usize;
            if T::HISTORY && !on {
                hist[w] = [0.0; 3];
            }
        }
    }
    // eight wall contacts at a time in lanes, like the pair pass
    let mut g = WallLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.coef = u.wall.map(L::splat);
    }
    // SAFETY: entries 0..m were written by the loop above (entry m before m grows past it).
    let walls = unsafe { written(&walls, m) };
    for block in walls.chunks(L::N) {
        for (l, &e) in block.iter().enumerate() {
            let (k, w) = (e as usize / 6, e as usize % 6);
            g.gather(ctx, first + k, w, l);
            if T::HISTORY {
                set_lane(&mut g.history, l, wall_history[k][w]);
            }
        }
        let rs = contact_response::<N, T, L>(
            &g.kin,
            &g.coef,
            ctx.friction,
            ctx.clamp,
            ctx.rotations,
            ctx.dt,
            &mut g.history,
        );
        for (l, &e) in block.iter().enumerate() {
            let (k, w) = (e as usize / 6, e as usize % 6);
            let r = ctx.radius[first + k];
            if T::HISTORY {
                wall_history[k][w] = get_lane(&g.history, l);
            }
            if LEDGER {
                p_coll += rs.p_collision.get(l);
                p_fric += rs.p_friction.get(l);
            }
            let (f, t) = (get_lane(&rs.force, l), get_lane(&rs.torque_arm, l));
            let fi = &mut force[k];
            fi[0] += f[0];
            fi[1] += f[1];
            fi[2] += f[2];
            if T::ACTIVE && ctx.rotations {
                let ti = &mut torque[k];
                ti[0] -= r * t[0];
                ti[1] -= r * t[1];
                ti[2] -= r * t[2];
            }
            fgz -= f[2];
        }
    }
    let (mut mz, mut mv) = (0.0, 0.0);
    if ctx.kick {
        let h = 0.5 * ctx.dt;
        let n = force.len();
        half_kick(vel, force, &ctx.inv_mass[first..first + n], h);
        if ctx.rotations {
            half_kick(omega, torque, &ctx.inv_inertia[first..first + n], h);
        }
        // the centre of mass at the end of the step (its height and vertical velocity)
        for (k, v) in vel.iter().enumerate() {
            let m = ctx.mass[first + k];
            mz += m * ctx.pos[first + k][2];
            mv += m * v[2];
        }
    }
    [fgz, p_coll, p_fric, mz, mv]
}

/// The kinematics and coefficients of up to `L::N` grain–wall contacts, one per lane.
#[derive(Default)]
struct WallLanes<L> {
    kin: ContactKinematics<L>,
    coef: [L; 4],
    history: [L; 3],
}

impl<L: Lanes> WallLanes<L> {
    /// Puts grain i's contact with wall `w` (normal ±e_{w/2}, + for even w) in lane `l`.
    #[inline(always)]
    fn gather(&mut self, ctx: &GrainCtx, i: usize, w: usize, l: usize) {
        let r = ctx.radius[i];
        let (vp, om) = (ctx.vel_pred[i], ctx.omega_pred[i]);
        let (axis, s) = (w / 2, 1.0 - 2.0 * (w % 2) as f64);
        let k = &mut self.kin;
        k.overlap_m.set(l, wall_overlaps(ctx, i)[w]);
        let mut n = [0.0; 3];
        n[axis] = s;
        set_lane(&mut k.normal, l, n);
        set_lane(&mut k.spin, l, [r * om[0], r * om[1], r * om[2]]);
        set_lane(&mut k.v_rel, l, [vp[0], vp[1], vp[2] - ctx.wall_v]);
        if ctx.uniform.is_none() {
            set_lane(&mut self.coef, l, ctx.wall_coef[i]);
        }
    }
}
