//! The state of a [`DemWorld`]: its fields (grains as a structure of arrays, the box and
//! primary mass, neighbour list, ledger, scratch), the constructor, and who runs a step's
//! phases ([`Mode`]).

use nalgebra::UnitQuaternion;

use crate::contact::response::ContactCoefficients;
use crate::dem::bag::BondPass;
use crate::dem::blocks::BlockPairs;
use crate::dem::energy::EnergyLedger;
use crate::dem::model::DemModel;
use crate::dem::team::{Exec, Team};
use crate::error::{ModelError, Quantity};
use crate::model::BoxDrive;
use crate::neighbor::{Curve, NeighborList, Pair};
use crate::simd::{Simd, WritePrefetch};
use crate::units::G;

use super::kernels::PairResponse;
use super::laws::{Laws, Uniform};

/// Default smallest grain count for which a step runs on several threads: two blocks
/// ([`crate::dem::blocks::MIN_BLOCK`]). Results do not depend on it.
pub const PARALLEL_MIN_GRAINS: usize = 2 * crate::dem::blocks::MIN_BLOCK;

/// Default smallest number of threads for which a step runs on several threads.
pub const PARALLEL_MIN_THREADS: usize = 2;

/// Default smallest grain count for which the grains are stored along the space-filling curve
/// (re-sorted at every neighbour rebuild); smaller beds fit the caches in any order.
pub const SORT_MIN_GRAINS: usize = 1000;

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
    pub(super) vel_pred: Vec<[f64; 3]>,
    pub(super) omega_pred: Vec<[f64; 3]>,
    pub(super) box_v_pred: f64,
    /// Radii (m).
    pub radius: Vec<f64>,
    /// Masses (kg).
    pub mass: Vec<f64>,
    pub(super) inv_mass: Vec<f64>,
    pub(super) inv_inertia: Vec<f64>,
    /// Orientations (only when the scene asks for them).
    pub orientation: Option<Vec<UnitQuaternion<f64>>>,
    /// Inner box size [Lx, Ly, Lz] (m): the box, or the cylinder's bounding box.
    pub box_size: [f64; 3],
    /// The cavity's shape inside `box_size`.
    pub container: crate::model::Container,
    /// Box displacement along the drive axis `drive.direction` d (m): the box's corner (its
    /// floor, x = y = 0 corner) is at `box_z`·d ([`DemWorld::box_origin`]); with the default
    /// vertical axis, the floor's height.
    pub box_z: f64,
    /// Box velocity along the drive axis (m/s).
    pub box_v: f64,
    pub(super) box_a: f64,
    /// Force of the grains on the box along the drive axis, F_gz = F·d (N), from the last
    /// force evaluation.
    pub grain_force_n: f64,
    /// The drive (primary and base motion).
    pub drive: BoxDrive,
    /// Whether the base moves (false while the bed settles, box held still).
    pub drive_on: bool,
    /// Extra drag rate 1/τ (1/s) on the grains while settling (0 when driven).
    pub settle_drag: f64,
    /// Acceleration of gravity (m/s²); default [0, 0, −9.8] (tests may set 0).
    pub gravity: [f64; 3],
    /// The rotating frame the damper sits on: centrifugal and Coriolis accelerations of every
    /// grain (none by default).
    pub rotation: Option<crate::model::FrameRotation>,
    /// Energy flows since the drive started (collision and friction also accumulate while
    /// settling; [`DemWorld::start_drive`] resets the ledger).
    pub ledger: EnergyLedger,
    /// Whether the step books the energy flows into [`DemWorld::ledger`] (default true). Off,
    /// the contact loops are compiled without the dissipated powers (they cost nothing) and
    /// the ledger stays zero.
    pub energy_ledger: bool,
    pub(super) base_power_prev: f64,
    pub(super) viscous_power_prev: f64,
    pub(super) laws: Laws,
    pub(super) neighbors: NeighborList,
    /// The candidate pairs sorted by grain block (the order of `pair_coef` and
    /// `pair_history`).
    pub(super) blocks: BlockPairs,
    pub(super) pair_coef: Vec<ContactCoefficients>,
    pub(super) wall_coef: Vec<ContactCoefficients>,
    /// Tangential spring elongation of each candidate pair (m), valid where the pair touched at
    /// the previous force evaluation ([`spring`](super::kernels::spring)); stale elsewhere
    /// (never cleared in the step).
    pub(super) pair_history: Vec<[f64; 3]>,
    /// Per candidate pair, the force evaluation at which it last touched (0: never).
    pub(super) pair_touch: Vec<u64>,
    /// Number of force evaluations so far (the clock of `pair_touch`).
    pub(super) force_evals: u64,
    /// Responses of the cross pairs (threaded paths only).
    pub(super) cross_response: Vec<PairResponse>,
    /// Per cross pair, its (collision, friction) power at the last force evaluation (W),
    /// when the cross pairs are evaluated from both sides with the ledger.
    pub(super) cross_power: Vec<[f64; 2]>,
    /// Tangential spring elongation of each grain's contacts with the six walls (m).
    pub(super) wall_history: Vec<[[f64; 3]; 6]>,
    /// Springs of the pairs before a rebuild, keyed by (min, max) grain (scratch).
    pub(super) history_carry: Vec<(u64, [f64; 3])>,
    /// Runs of occupied cells of a threaded neighbour rebuild, and their pairs (scratch).
    pub(super) cell_runs: Vec<usize>,
    pub(super) pair_runs: Vec<Vec<Pair>>,
    /// Partial sums of the chunks (scratch, reused every step).
    pub(super) partials: Vec<[f64; 3]>,
    /// Partial sums of the grain chunks: F_gz, powers, Σ m z, Σ m ż (scratch).
    pub(super) grain_partials: Vec<[f64; 5]>,
    /// Total grain mass (kg).
    pub(super) mass_total: f64,
    /// Centre-of-mass height and vertical velocity at the end of the last step (m, m/s).
    pub(super) step_cm: (f64, f64),
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
    pub(super) id: Vec<u32>,
    /// Scratch of the curve sort (reused: no allocation in the step).
    pub(super) sort: SortScratch,
    /// Grain-id-ordered copies for [`DemWorld::grain_state`] (made at the first snapshot).
    pub(super) by_id: Option<Box<ById>>,
    /// Time steps taken since construction (settling included).
    pub steps: u64,
    /// Radius and coefficients shared by every grain, when all grains are alike (the loops
    /// then read them once instead of per contact).
    pub(super) uniform: Option<Uniform>,
    /// Instruction set of the contact loops (default: the widest this processor has; every
    /// choice gives bitwise the same results).
    pub simd: Simd,
    /// Write prefetches in the drift, where the processor has them (no value changes;
    /// `None` turns them off, e.g. to measure them).
    pub prefetch: Option<WritePrefetch>,
    /// Threads of a [`Team`] to step with (`None`: the rayon pool's size, and a team only when
    /// stepped from outside a rayon pool). Results do not depend on it.
    pub team_threads: Option<usize>,
    pub(super) team: TeamSlot,
    pub(super) mode: Mode,
    /// The bean bag's bonds, when the damper has a bag (its nodes are the last particles).
    pub(super) bag: Option<Box<BondPass>>,
}

/// Who runs the phases of the current step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Mode {
    Serial,
    Rayon,
    Team,
}

impl Mode {
    /// The executor of this mode (the rayon pool when the team could not be made).
    pub(super) fn exec(self, team: &TeamSlot) -> Exec<'_> {
        match (self, team.0.as_ref()) {
            (Mode::Serial, _) => Exec::Serial,
            (Mode::Team, Some(team)) => Exec::Team(team),
            _ => Exec::Rayon,
        }
    }
}

/// The world's [`Team`], if it made one (a clone of the world makes its own).
#[derive(Debug, Default)]
pub(super) struct TeamSlot(pub(super) Option<Team>);

impl Clone for TeamSlot {
    fn clone(&self) -> Self {
        TeamSlot(None)
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
        let nodes = model.bag.as_ref().map_or(0, |b| b.nodes.len());
        if nodes >= n {
            return Err(ModelError::new(
                Quantity::GrainCount,
                n,
                format!("{n} particles for a bag of {nodes} nodes: the grains come first, then the bag's nodes"),
            ));
        }
        let density = model.grains.density_kg_m3;
        let mass: Vec<f64> = radius
            .iter()
            .enumerate()
            .map(|(i, &r)| match &model.bag {
                Some(b) if i >= n - nodes => b.node_mass_kg,
                _ => crate::dem::model::Grains::sphere_mass(density, r),
            })
            .collect();
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        let inv_inertia = mass
            .iter()
            .zip(&radius)
            .map(|(m, r)| 1.0 / (0.4 * m * r * r))
            .collect();
        let laws = Laws {
            contact: model.contact,
            rotations: model.rotations,
            grain: model.grains.material,
            film: model.bag.as_ref().map(|b| b.film),
        };
        let r_max = radius.iter().cloned().fold(0.0, f64::max);
        // a bed of several grain blocks is stored along vertical columns, so that the blocks'
        // faces are vertical ([`Curve::Columns`]: 4000 grains, vibrated, 16 % fewer cross
        // pairs and 6–15 % more speed on two threads); one block keeps the 3-D Morton curve,
        // which ran a 250-grain bed 7–12 % faster on one thread
        let curve = if crate::dem::blocks::block_count(n) > 1 {
            Curve::Columns
        } else {
            Curve::Morton
        };
        let neighbors =
            NeighborList::new(model.box_size_m, r_max, model.skin(r_max)).with_curve(curve);
        let wall_coef = (0..n)
            .map(|i| {
                laws.coefficients(
                    (radius[i], mass[i], i >= n - nodes),
                    (f64::INFINITY, f64::INFINITY, false),
                    true,
                )
            })
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
            container: model.container,
            box_z: 0.0,
            box_v: 0.0,
            box_a: 0.0,
            grain_force_n: 0.0,
            drive,
            drive_on: false,
            settle_drag: 0.0,
            gravity: [0.0, 0.0, -G],
            rotation: None,
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
            bag: model
                .bag
                .clone()
                .map(|b| Box::new(BondPass::new(b, n - nodes, n))),
        })
    }

    /// Number of grains.
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// True when there are no grains.
    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }
}

/// Buffers of the curve sort, kept between rebuilds.
#[derive(Debug, Clone, Default)]
pub(super) struct SortScratch {
    /// Old slots in the new order.
    pub(super) order: Vec<u32>,
    /// New slot of each old slot.
    pub(super) inv: Vec<u32>,
    pub(super) v3: Vec<[f64; 3]>,
    pub(super) v1: Vec<f64>,
    pub(super) coef: Vec<ContactCoefficients>,
    pub(super) hist: Vec<[[f64; 3]; 6]>,
    pub(super) quat: Vec<UnitQuaternion<f64>>,
    pub(super) ids: Vec<u32>,
}

/// Per-grain arrays in grain-id order, for snapshots.
#[derive(Debug, Clone, Default)]
pub(super) struct ById {
    pub(super) pos: Vec<[f64; 3]>,
    pub(super) vel: Vec<[f64; 3]>,
    pub(super) omega: Vec<[f64; 3]>,
    pub(super) force: Vec<[f64; 3]>,
    pub(super) radius: Vec<f64>,
    pub(super) orientation: Vec<UnitQuaternion<f64>>,
}
