//! Broad phase of the DEM (SPEC §2): an O(N) sorted cell list that builds a Verlet pair list with a
//! skin, rebuilt only when some grain has moved more than half the skin relative to the box.

pub mod cell_grid;
mod morton;
mod pair;
mod pair_search;

pub use cell_grid::{index_by_grain, Curve, NeighborList, Pair, J_ROLE};
