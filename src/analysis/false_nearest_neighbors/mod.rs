//! False nearest neighbours (Kennel, Brown & Abarbanel 1992; SPEC (4.1.4)), with TISEAN
//! 3.0.1 `false_nearest`'s definition (SPEC §8).
//!
//! # Algorithm (why it is fast)
//! Exact nearest neighbours in the maximum norm by a box-assisted search, as TISEAN's: the
//! candidates are sorted into the cells of a grid on two delay coordinates (the first and
//! the last of the m-dimensional vector; one coordinate for m = 1) and a query scans only
//! the cells within its current bound, rings of cells outward from its own. The bound
//! starts at the smaller of σ/R_t (farther neighbours are never accepted) and the distance
//! to the previous dimension's neighbour (without one: to the nearest indices outside the
//! Theiler window), and shrinks with every closer candidate, so a query visits a few
//! cells. The grid stores only the two gridded coordinates (contiguous box tests); the full
//! vector is read from the series for the few candidates that pass. The queries of one
//! dimension run in parallel (rayon) over fixed blocks, while the next dimension's grid is
//! built; each answer depends only on its query, and the blocks' sums are added in block
//! order, so the results do not depend on the thread count.
//!
//! Files: the options and result, the test over the dimensions, one dimension's queries and
//! tally, and the box-assisted search; their public items are re-exported here.

mod count;
mod estimate;
mod options;
mod search;

pub use estimate::{false_nearest_neighbors, suggested_dimension};
pub use options::{FnnOptions, FnnPoint, FnnVectors, MAX_DIMENSION};
