//! The neighbour rebuild of a [`DemWorld`](super::DemWorld): the Verlet list (threaded run
//! of cells by run of cells), the pairs' block order and coefficients, and the tangential
//! springs carried over to the new list.

use crate::contact::lanes::{dot, sub3};
use crate::dem::team::{Exec, Parts};
use crate::neighbor::Pair;

use super::kernels::{spring, PairResponse};
use super::state::DemWorld;

/// Runs of cells per thread of a threaded neighbour rebuild (some to claim when a thread
/// finishes its share early).
pub(super) const REBUILD_RUNS_PER_THREAD: usize = 4;

/// Whether the grains of pair `p` overlap: |r_i − r_j| < R_i + R_j (centres `pos` in m, radii
/// `radius` in m).
pub(super) fn touching(pos: &[[f64; 3]], radius: &[f64], p: &Pair) -> bool {
    let (i, j) = (p.i as usize, p.j as usize);
    let d = sub3(pos[i], pos[j]);
    let cut = radius[i] + radius[j];
    dot(d, d) < cut * cut
}

impl DemWorld {
    /// Rebuilds the neighbour list, the per-pair coefficients (computed here only, never in
    /// the step) and carries the tangential springs of the contacts over to the new list.
    pub(super) fn rebuild_neighbors(&mut self) {
        let shift = self.box_origin();
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
            if let Some(b) = self.bag.as_mut() {
                b.reslot(&self.id);
            }
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
            let node = |s: usize| self.bag.as_ref().is_some_and(|b| b.is_node(self.id[s]));
            let c = self.laws.coefficients(
                (self.radius[i], self.mass[i], node(i)),
                (self.radius[j], self.mass[j], node(j)),
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
    pub(super) fn find_pairs(&mut self, shift: [f64; 3]) {
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

    /// Pair `a`'s tangential spring as the last force evaluation left it (m).
    pub(super) fn last_spring(&self, a: usize) -> [f64; 3] {
        spring(
            &self.pair_history,
            &self.pair_touch,
            a,
            self.force_evals + 1,
        )
    }
}
