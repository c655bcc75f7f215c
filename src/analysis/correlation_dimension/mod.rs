//! Correlation sum C(m, ε) and correlation dimension D2 (Grassberger & Procaccia 1983), with
//! TISEAN 3.0.1 `d2`'s definitions (maximum norm, data units, Theiler window), the local
//! slopes d ln C / d ln ε per embedding dimension and an automatic plateau estimate of D2.
//!
//! # Algorithm (why it is fast)
//! All radii come from one pass over the pairs: each pair's maximum-norm distance is
//! extended coordinate by coordinate (it is non-decreasing in m, so one pass gives every
//! dimension), and put in the bin of the smallest ε that contains it; C(ε) is the running
//! sum of the bins. The bin is found without a logarithm: the leading bits of the f64
//! (exponent and a few mantissa bits, monotone in the value) index a table that gives the
//! candidate bin, corrected by one or two comparisons (exact). Only pairs closer than ε_max
//! are visited: a box-assisted search on a grid of cells of side ≥ ε_max over the first two
//! delay coordinates (m ≥ 2) and a sorted-coordinate sweep for m = 1, as TISEAN's `d2` does.
//! Reference points are split into fixed chunks processed in parallel (rayon); the counts
//! are integers, so the result does not depend on the thread count.
//!
//! Cost: O(N log N) set-up plus O(pairs within ε_max · m). With ε_max equal to the attractor
//! size every pair is visited (N²/2).
//!
//! Files: the options and radii, the pair counting, the sums and slopes, the plateau and
//! the D2 estimate; their items are re-exported here.

mod counting;
mod options;
mod plateau;
mod sums;

pub use options::{D2Options, MAX_DIMENSION};
pub use plateau::{
    correlation_dimension, estimate_d2, find_plateau, D2Estimate, Plateau, PlateauOptions,
};
pub use sums::{correlation_sum, local_slopes, CorrelationCurve, CorrelationSums};
