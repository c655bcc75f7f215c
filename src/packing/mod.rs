//! Initial configurations of the grains (SPEC §2, §5): an FCC lattice (stacked rings in a
//! cylinder) to drop and settle, or
//! the advancing-front packing of Roselló Valera et al. (2018), with radii drawn from
//! continuous, discrete or empirical size distributions.

pub mod advancing_front;
pub mod lattice;
pub mod rings;
pub mod size_distribution;

pub use advancing_front::{advancing_front_packing, volume_fraction};
pub use lattice::fcc_lattice;
pub use rings::cylinder_rings;
pub use size_distribution::RadiusDistribution;
