//! The initial bed of a DEM run: the grains placed by the model's packing (jittered FCC
//! lattice or advancing front), settled under gravity with the box held still at its static
//! equilibrium, and released from the primary's initial state.

use crate::contact::lanes::dot;
use crate::error::{ModelError, SimError};
use crate::packing::{advancing_front_packing, cylinder_rings, fcc_lattice, volume_fraction};

use super::model::{DemModel, Packing};
use super::world::{BoxDrive, DemWorld};
use crate::model::{Container, FrameRotation};

/// The grains' initial centres (m) by the model's packing: a jittered FCC lattice (stacked
/// rings in a cylinder) or the advancing front; with a bag, the grains inside it and then the
/// bag's nodes. Also the resolve step's check that the grains fit the box.
///
/// # Errors
/// [`ModelError`] ([`crate::error::Quantity::GrainCount`]) if the grains do not fit.
pub fn initial_positions(model: &DemModel) -> Result<Vec<[f64; 3]>, ModelError> {
    if let Some(bag) = &model.bag {
        return in_bag(model, bag);
    }
    match model.packing {
        Packing::Lattice { seed } => match &model.container {
            Container::Box => fcc_lattice(
                model.box_size_m,
                model.grains.radius_m.len(),
                model.grains.r_max_m,
                0.05,
                seed ^ 0x5eed,
            ),
            Container::Cylinder(c) => cylinder_rings(
                c,
                model.grains.radius_m.len(),
                model.grains.r_max_m,
                0.05,
                seed ^ 0x5eed,
            ),
        },
        Packing::AdvancingFront => match model.container {
            Container::Box => advancing_front_packing(model.box_size_m, &model.grains.radius_m),
            Container::Cylinder(_) => Err(ModelError::new(
                crate::error::Quantity::GrainCount,
                model.grains.radius_m.len(),
                "the advancing-front packing fills boxes only: use the lattice packing in a \
                 cylinder"
                    .to_string(),
            )),
        },
    }
}

/// The grains stacked in rings inside the bag (its interior as a cylinder of its own), then
/// the bag's nodes.
fn in_bag(model: &DemModel, bag: &crate::dem::bag::Bag) -> Result<Vec<[f64; 3]>, ModelError> {
    let seed = match model.packing {
        Packing::Lattice { seed } => seed,
        Packing::AdvancingFront => 1,
    };
    let (inside, corner) = bag.geometry.interior();
    let n = model.grains.radius_m.len();
    let mut pos =
        cylinder_rings(&inside, n, model.grains.r_max_m, 0.05, seed ^ 0x5eed).map_err(|e| {
            ModelError::new(
                crate::error::Quantity::BagSize,
                n,
                format!("{n} grains do not fit inside the bag ({})", e.hint),
            )
        })?;
    for p in &mut pos {
        for (x, c) in p.iter_mut().zip(corner) {
            *x += c;
        }
    }
    pos.extend_from_slice(&bag.nodes);
    Ok(pos)
}

/// The radii of every particle of `model`: its grains', then its bag's nodes'.
pub fn particle_radii(model: &DemModel) -> Vec<f64> {
    let mut radii = model.grains.radius_m.clone();
    if let Some(bag) = &model.bag {
        radii.extend(std::iter::repeat_n(bag.node_radius_m, bag.nodes.len()));
    }
    radii
}

/// Builds the initial bed of `model` (its grains placed on a lattice or by the advancing
/// front) at rest, with the box held still at `box_z` (m).
///
/// # Errors
/// Grains that do not fit the box (packing errors); [`DemWorld::new`]'s errors.
pub fn initial_world(
    model: &DemModel,
    drive: BoxDrive,
    dt: f64,
    box_z: f64,
) -> Result<DemWorld, SimError> {
    let radii = particle_radii(model);
    let pos = initial_positions(model)?;
    let mut w = DemWorld::new(model, drive, dt, radii, pos)?;
    w.shift_box_to(box_z);
    w.refresh();
    Ok(w)
}

/// Lets the bed settle under gravity with the box held still and a drag of rate 1/0.05 s⁻¹
/// on the grains, until the mean grain speed is below 1 mm/s (after at least 0.05 s) or
/// `max_time_s` elapsed. Returns (settling time s, steps).
pub fn settle(world: &mut DemWorld, max_time_s: f64) -> (f64, u64) {
    world.drive_on = false;
    world.settle_drag = 1.0 / 0.05;
    world.refresh();
    let check_every = ((1e-3 / world.dt).round() as u64).max(1);
    let mut t = 0.0;
    let mut steps = 0u64;
    while t < max_time_s {
        world.step();
        t += world.dt;
        steps += 1;
        if steps.is_multiple_of(check_every) && t > 0.05 {
            let mean_v = world
                .vel
                .iter()
                .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
                .sum::<f64>()
                / world.len() as f64;
            if mean_v < 1e-3 {
                break;
            }
        }
    }
    world.settle_drag = 0.0;
    (t, steps)
}

/// The settled bed before the drive.
pub(super) struct SettledBed {
    pub(super) mass_kg: f64,
    pub(super) height_m: f64,
    pub(super) volume_fraction: f64,
    pub(super) settle_time_s: f64,
    pub(super) settle_steps: u64,
}

/// The initial bed, settled under gravity with the box held at its start position: u(0) for
/// a kinematic box, the static equilibrium with the grains' weight for a primary; the world
/// under `gravity` (m/s²), in the rotating frame `rotation`, booking its ledger if
/// `energy_ledger`.
pub(super) fn settled_bed(
    model: &DemModel,
    drive: BoxDrive,
    (gravity, rotation, energy_ledger): ([f64; 3], Option<FrameRotation>, bool),
    dt: f64,
) -> Result<(DemWorld, SettledBed), SimError> {
    let mut world = initial_world(model, drive, dt, 0.0)?;
    world.gravity = gravity;
    world.rotation = rotation;
    world.energy_ledger = energy_ledger;
    let m_p: f64 = world.mass.iter().sum();
    // the static equilibrium along the drive axis d: K z = m_p g·d
    let z_hold = match drive.primary {
        Some(p) => m_p * dot(gravity, drive.direction) / p.stiffness_n_m,
        None => drive.base(0.0).0,
    };
    world.shift_box_to(z_hold);
    let (settle_time_s, settle_steps) = settle(&mut world, model.settle_time_s);
    let (zcm, _, _) = world.z_stats();
    let height_m = 2.0 * (zcm - world.box_origin()[2]);
    let volume_fraction = volume_fraction(
        &world.radius,
        world.container.volume_below_m3(world.box_size, height_m),
    );
    let bed = SettledBed {
        mass_kg: m_p,
        height_m,
        volume_fraction,
        settle_time_s,
        settle_steps,
    };
    Ok((world, bed))
}

/// Puts the primary in its initial state before the drive starts: the box and the settled bed
/// in it moved to `primary.initial_displacement` along the drive axis, the box given
/// `primary.initial_velocity` (the grains left at rest): `z0` (m), `v0` (m/s). Nothing for a
/// kinematic box.
pub(super) fn release(world: &mut DemWorld, z0: Option<f64>, v0: Option<f64>) {
    if world.drive.primary.is_none() {
        return;
    }
    if let Some(z0) = z0 {
        world.shift_box_to(z0);
    }
    if let Some(v0) = v0 {
        world.box_v = v0;
    }
}
