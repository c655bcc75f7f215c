//! One dimension's test: the nearest neighbour of every query (in parallel over fixed blocks)
//! and the tally of accepted and false neighbours with their distances (data units).

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rayon::prelude::*;

use super::options::{FnnPoint, MAX_DIMENSION};
use super::search::{nearest, Grid, Setup, NONE};
use crate::error::AnalysisError;

/// Accumulated counts of one dimension (of one block of queries, then of all).
#[derive(Default)]
struct Tally {
    accepted: usize,
    false_count: usize,
    sum_d: f64,
    sum_d2: f64,
}

impl Tally {
    fn add(&mut self, setup: &Setup, m: usize, n: usize, j: usize, dist: f64) {
        let t = m * setup.tau;
        let escape = (setup.s[n + t] - setup.s[j + t]).abs() / dist;
        self.accepted += 1;
        self.sum_d += dist;
        self.sum_d2 += dist * dist;
        if escape > setup.ratio {
            self.false_count += 1;
        }
    }

    /// The tally of `self`'s queries followed by `other`'s.
    fn merge(mut self, other: Tally) -> Tally {
        self.accepted += other.accepted;
        self.false_count += other.false_count;
        self.sum_d += other.sum_d;
        self.sum_d2 += other.sum_d2;
        self
    }

    fn finish(self, m: usize, range: f64) -> FnnPoint {
        let a = self.accepted as f64;
        let (fraction, mean, rms) = if self.accepted == 0 {
            (None, 0.0, 0.0)
        } else {
            (
                Some(self.false_count as f64 / a),
                self.sum_d / a * range,
                (self.sum_d2 / a).sqrt() * range,
            )
        };
        FnnPoint {
            m,
            fraction,
            accepted: self.accepted,
            false_count: self.false_count,
            mean_distance: mean,
            rms_distance: rms,
        }
    }
}

/// Queries per parallel work unit. Fixed (not set by the thread count), so that the
/// partial sums, added in block order, do not depend on the thread count.
const QUERY_BLOCK: usize = 2048;

/// Tests dimension m with `grid` (built for m): reads the previous dimension's neighbours
/// from `prev`, writes this dimension's to `next`.
pub(super) fn fnn_in_dimension(
    setup: &Setup,
    m: usize,
    grid: &Grid,
    prev: &[AtomicU32],
    next: &[AtomicU32],
) -> Result<FnnPoint, AnalysisError> {
    macro_rules! dispatch {
        ($($k:literal),*) => {
            match m {
                $($k => Ok(fnn_k::<$k>(setup, grid, prev, next)),)*
                _ => Err(AnalysisError::bad("m", m, format!("1..={MAX_DIMENSION}"))),
            }
        };
    }
    dispatch!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12)
}

fn fnn_k<const K: usize>(
    setup: &Setup,
    grid: &Grid,
    prev: &[AtomicU32],
    next: &[AtomicU32],
) -> FnnPoint {
    // Queries in the grid's cell order (neighbouring queries read the same cells: cache
    // friendly), then the references that are not candidates; in parallel over fixed blocks
    // of that order. Each query's answer depends only on its own n (and its seed, which only
    // speeds it up), so the results do not depend on the thread count; the blocks' tallies
    // are added in block order.
    let n_grid = grid.index.len();
    let blocks = setup.n_ref.div_ceil(QUERY_BLOCK);
    let tallies: Vec<Tally> = (0..blocks)
        .into_par_iter()
        .map(|b| {
            let mut tally = Tally::default();
            for k in b * QUERY_BLOCK..((b + 1) * QUERY_BLOCK).min(setup.n_ref) {
                let n = if k < n_grid {
                    grid.index[k] as usize
                } else {
                    k
                };
                let found = nearest::<K>(grid, setup, n, prev[n].load(Relaxed));
                next[n].store(found.map_or(NONE, |(j, _)| j), Relaxed);
                if let Some((j, d)) = found {
                    tally.add(setup, K, n, j as usize, d);
                }
            }
            tally
        })
        .collect();
    tallies
        .into_iter()
        .fold(Tally::default(), Tally::merge)
        .finish(K, setup.range)
}
