//! [`DemWorld`]: grains (structure of arrays), the box and the primary mass, and the step.
//!
//! One file per job (this file only names them):
//! - `state.rs`: the fields, the constructor, who runs a step's phases;
//! - `laws.rs`: the contact laws flattened for the loops (their mixing is
//!   [`ContactModel::coefficients`](crate::contact::ContactModel::coefficients));
//! - `order.rs`: the grains' storage order (curve sort, grain ids, snapshots);
//! - `step.rs`: the time step (drive, box equation, half kicks, executor);
//! - `rebuild.rs`: the neighbour rebuild and the springs carried over;
//! - `forces.rs`: the force pass on the step's executor (laws matched once per evaluation);
//! - `drift.rs`: the first half kick and drift, grain range by grain range;
//! - `kernels/`: the pair, cross-pair and per-grain kernels, per instruction set;
//! - `diagnostics.rs`: contact counts, energies, momentum, centre of mass;
//! - `memory.rs`: the memory a run needs and what the machine has.

mod diagnostics;
mod drift;
mod forces;
mod kernels;
mod laws;
mod memory;
mod order;
mod rebuild;
mod state;
mod step;

pub use super::blocks::GRAIN_CHUNK;
pub use crate::model::{BoxDrive, PrimarySystem};
pub use diagnostics::{ContactCounts, ContactsPerGrain};
pub use forces::CROSS_CHUNK;
pub use kernels::PAIR_CHUNK;
pub use memory::{available_memory_bytes, memory_estimate_bytes, BYTES_PER_GRAIN};
pub use state::{DemWorld, PARALLEL_MIN_GRAINS, PARALLEL_MIN_THREADS, SORT_MIN_GRAINS};
