//! The DEM time-stepping pipeline (SPEC §2): [`DemWorld`] owns the grains' arrays, the box
//! and primary mass, the neighbour list and the energy ledger; [`DemWorld::step`] runs
//! neighbour search → contact forces → box equation (2.1.22) → velocity Verlet (2.2.4–2.2.5)
//! → quaternion renormalisation → energy ledger. [`run`] deposits a bed, settles it and
//! drives the box, emitting samples to an observer. [`run_replica`] runs the two-replica
//! test of the collective motion's stability (issue 9).

pub mod bag;
mod bed;
pub mod bed_impacts;
pub mod blocks;
pub mod energy;
pub mod model;
pub mod replica;
pub mod run;
pub mod stability;
mod steady;
pub mod team;
pub mod world;

pub use bed_impacts::BedImpacts;
pub use energy::{EnergyLedger, EnergyState};
pub use model::{DemModel, Grains, Packing};
pub use replica::{
    run_replica, run_replica_deferred, DeferredReplica, ReplicaOptions, ReplicaOutcome,
    ReplicaReport, ReplicaRow, ReplicaTracker,
};
pub use run::{initial_positions, run_dem, DemRunConfig, DemSample, DemSummary, DtChoice};
pub use world::{BoxDrive, ContactCounts, ContactsPerGrain, DemWorld, PrimarySystem};
