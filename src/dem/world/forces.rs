//! The force pass of a [`DemWorld`](super::DemWorld): the laws matched once per force
//! evaluation, then gravity, drag, grain–grain, cross-block and grain–wall contacts in two
//! phases of fixed units on the step's executor (the same sums in the same order on any
//! number of threads).

use crate::contact::response::{
    CoulombViscousKernel, HertzKernel, LinearKernel, LinearSpringKernel, MindlinSpringKernel,
    NoTangential, NormalKernel, TangentialKernel,
};
use crate::contact::{AttractionPolicy, NormalLaw, TangentialLaw};
use crate::dem::team::{Exec, Parts, View};

use super::drift::Drift;
use super::kernels::{
    cross_side, grain_chunk, init_forces, pair_chunk, CrossSide, GrainChunk, GrainCtx, PairChunk,
    PairCtx, Weight, PAIR_CHUNK,
};
use super::state::DemWorld;

/// Cross pairs (pairs across grain blocks) per work unit: small, so that the few cross pairs
/// of a two-block bed still divide between two threads.
pub const CROSS_CHUNK: usize = 256;

/// Sums returned by the contact loops: (F_gz, collision power, friction power).
pub(super) type LoopOut = (f64, f64, f64);

impl DemWorld {
    /// The force pass (with the drift of the blocks if `drift`, see [`Self::contacts`]),
    /// booking the dissipated powers if the ledger is on.
    pub(super) fn forces_of(&mut self, kick: bool, drift: Option<[f64; 3]>) -> Option<(f64, f64)> {
        if self.energy_ledger {
            self.forces_ledger::<true>(kick, drift)
        } else {
            self.forces_ledger::<false>(kick, drift)
        }
    }

    /// The force pass of the contact laws, booking the dissipated powers if `LEDGER`
    /// (otherwise they are not computed and (0, 0) is returned); `None` when the drift found
    /// a neighbour rebuild due.
    pub(super) fn forces_ledger<const LEDGER: bool>(
        &mut self,
        kick: bool,
        drift: Option<[f64; 3]>,
    ) -> Option<(f64, f64)> {
        if drift.is_none() {
            if let Some(b) = self.bag.as_mut() {
                b.evaluate(&self.pos, &self.vel_pred);
            }
        }
        // the laws are matched once per step (the normal law here, the tangential one in
        // `contacts_with`); each arm runs loops monomorphised on the normal and tangential
        // kernels (rotations and the attraction policy are loop-invariant flags)
        let out = match self.laws.contact.normal {
            NormalLaw::HertzKuwabaraKono { .. } => {
                self.contacts_with::<HertzKernel, LEDGER>(kick, drift)
            }
            NormalLaw::LinearSpringDashpot { .. } => {
                self.contacts_with::<LinearKernel, LEDGER>(kick, drift)
            }
        };
        let out = out?;
        self.grain_force_n = out.0;
        Some((out.1, out.2))
    }

    /// [`Self::contacts`] with the normal kernel `N` and the tangential kernel of the laws'
    /// tangential law.
    pub(super) fn contacts_with<N: NormalKernel, const LEDGER: bool>(
        &mut self,
        kick: bool,
        drift: Option<[f64; 3]>,
    ) -> Option<LoopOut> {
        match self.laws.tangential_kind() {
            TangentialLaw::None => self.contacts::<N, NoTangential, LEDGER>(kick, drift),
            TangentialLaw::CoulombViscous { .. } | TangentialLaw::LinearDashpotCoulomb { .. } => {
                self.contacts::<N, CoulombViscousKernel, LEDGER>(kick, drift)
            }
            TangentialLaw::MindlinSpring { .. } => {
                self.contacts::<N, MindlinSpringKernel, LEDGER>(kick, drift)
            }
            TangentialLaw::LinearSpring { .. } => {
                self.contacts::<N, LinearSpringKernel, LEDGER>(kick, drift)
            }
        }
    }

    /// The force pass, in the order of [`crate::dem::blocks`], as two phases of fixed units:
    /// (1) block by block, gravity and drag and the block's own pairs scattered into its
    /// grains; (2) grain unit by grain unit
    /// ([`BlockPairs::unit`](crate::dem::blocks::BlockPairs::unit)), its wall contacts and its
    /// second half kick. Each unit's sums go to its slot and are added in unit order, so the
    /// result does not depend on who runs the units. The cross pairs come in between, so
    /// that each grain gets them in pair order after its block's own pairs:
    ///
    /// - on one thread, scattered straight into the forces after every block's own pairs;
    /// - on a team, for laws without contact history, evaluated from both sides: in phase 2
    ///   each block first computes every cross pair of its grains and adds the response to
    ///   its own grain only (+F for the pair's i, −F for its j; the same numbers either side),
    ///   then runs its grain units. Only the other block's boundary grains are read across
    ///   threads; nothing is stored for another thread to gather;
    /// - on a team, for laws with springs (whose state one side alone may write), their
    ///   responses stored per pair chunk by chunk alongside phase 1, then gathered per grain
    ///   in phase 2.
    ///
    /// The collision and friction powers of the cross pairs are summed chunk by chunk of
    /// [`CROSS_CHUNK`] pairs on every path.
    ///
    /// With `drift` (the box's displacement since the last neighbour build, m; laws without
    /// contact history only), each block first gives its grains the step's first half kick
    /// and drift, then its own pairs; the cross pairs wait until every block has drifted.
    /// `None` when the drift moved a grain past the neighbour skin: the pass is then
    /// incomplete (forces partial, nothing else written) and the caller rebuilds and calls
    /// again without drift.
    pub(super) fn contacts<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
        &mut self,
        kick: bool,
        drift: Option<[f64; 3]>,
    ) -> Option<LoopOut> {
        debug_assert!(
            drift.is_none() || !T::HISTORY,
            "drift in the pass: no springs"
        );
        self.force_evals += 1;
        let exec = self.mode.exec(&self.team);
        let n = self.pos.len();
        let (dt, rot) = (self.dt, self.laws.rotations);
        let bp = &self.blocks;
        // phase 1: blocks (and, on a team with springs, cross-pair chunks)
        let nb = bp.blocks;
        let cross0 = bp.seg[nb];
        let serial = matches!(exec, Exec::Serial);
        let both_sides = !serial && !T::HISTORY && nb > 1;
        let nc = if both_sides {
            0
        } else {
            bp.cross_len().div_ceil(CROSS_CHUNK)
        };
        self.partials.clear();
        self.partials.resize(nb + nc, [0.0; 3]);
        let rebuild_due = {
            let slots = Parts::new(&mut self.partials);
            // the drift's arrays (drifted block by block with `drift`, else only read)
            let kin = Drift::new(
                [
                    &mut self.pos,
                    &mut self.vel,
                    &mut self.vel_pred,
                    &mut self.omega,
                    &mut self.omega_pred,
                ],
                (&self.inv_mass, &self.inv_inertia),
                self.neighbors.reference().0,
                (dt, rot),
                (drift.unwrap_or([0.0; 3]), self.prefetch),
            );
            let force = Parts::new(&mut self.force);
            let torque = Parts::new(&mut self.torque);
            let history = Parts::new(&mut self.pair_history);
            let touch = Parts::new(&mut self.pair_touch);
            let response = Parts::new(&mut self.cross_response);
            let ctx = PairCtx {
                eval: self.force_evals,
                simd: self.simd,
                uniform: self.uniform,
                pos: kin.pos.view(),
                vel: kin.vel_pred.view(),
                omega: kin.omega_pred.view(),
                radius: &self.radius,
                friction: self.laws.friction(false),
                clamp: self.laws.contact.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let weight = Weight {
                mass: &self.mass,
                vel: kin.vel.view(),
                pos: kin.pos.view(),
                vel_pred: kin.vel_pred.view(),
                rotation: self.rotation,
                gravity: self.gravity,
                drag: self.settle_drag,
                rotations: rot,
                bonds: self.bag.as_ref().map(|b| &b.force[..]),
            };
            let own = |blk: usize| {
                let g = bp.grains(blk);
                let (s0, s1) = (bp.seg[blk], bp.seg[blk + 1]);
                // SAFETY: block `blk` alone touches its grains and its own pairs' states.
                let (f, t, hs, ts) = unsafe {
                    (
                        force.get(g.clone()),
                        torque.get(g.clone()),
                        history.get(s0..s1),
                        touch.get(s0..s1),
                    )
                };
                let max_d2 = if drift.is_some() {
                    // SAFETY: as above (the block's grains, written by this unit only).
                    unsafe { kin.grains(g.clone(), f, t) }
                } else {
                    0.0
                };
                init_forces(&weight, g.start, f, t);
                let (mut pc, mut pf) = (0.0, 0.0);
                for (((h, tc), p), c) in hs
                    .chunks_mut(PAIR_CHUNK)
                    .zip(ts.chunks_mut(PAIR_CHUNK))
                    .zip(bp.pairs[s0..s1].chunks(PAIR_CHUNK))
                    .zip(self.pair_coef[s0..s1].chunks(PAIR_CHUNK))
                {
                    let chunk = PairChunk {
                        pairs: p,
                        coef: c,
                        history: h,
                        touch: tc,
                        response: &mut [],
                        first: g.start,
                        force: &mut *f,
                        torque: &mut *t,
                    };
                    let part = pair_chunk::<N, T, true, LEDGER>(&ctx, chunk);
                    pc += part[0];
                    pf += part[1];
                }
                // SAFETY: slot `blk` is this unit's.
                unsafe { slots.get(blk..blk + 1)[0] = [pc, pf, max_d2] };
            };
            let cross = |c: usize| {
                let r =
                    cross0 + c * CROSS_CHUNK..(cross0 + (c + 1) * CROSS_CHUNK).min(bp.pairs.len());
                let (pairs, coef) = (&bp.pairs[r.clone()], &self.pair_coef[r.clone()]);
                // SAFETY: cross chunk `c` alone touches these springs and responses.
                let (hist, tc) = unsafe { (history.get(r.clone()), touch.get(r.clone())) };
                // SAFETY: the responses of chunk `c` (its pairs' offsets from the first cross
                // pair) are written by this unit alone.
                let resp = unsafe { response.get(r.start - cross0..r.end - cross0) };
                let part = if serial {
                    // one thread, after every block's own pairs: the responses straight into
                    // the forces, pair by pair in pair order — the additions, in the order,
                    // of the per-grain gathering of the threaded paths
                    // SAFETY: one thread: no other piece is in use.
                    let (force, torque) = unsafe { (force.get(0..n), torque.get(0..n)) };
                    let chunk = PairChunk {
                        pairs,
                        coef,
                        history: hist,
                        touch: tc,
                        response: &mut [],
                        first: 0,
                        force,
                        torque,
                    };
                    pair_chunk::<N, T, true, LEDGER>(&ctx, chunk)
                } else {
                    let chunk = PairChunk {
                        pairs,
                        coef,
                        history: hist,
                        touch: tc,
                        response: resp,
                        first: 0,
                        force: &mut [],
                        torque: &mut [],
                    };
                    pair_chunk::<N, T, false, LEDGER>(&ctx, chunk)
                };
                // SAFETY: slot `nb + c` is this unit's.
                unsafe { slots.get(nb + c..nb + c + 1)[0] = part };
            };
            if drift.is_some() {
                exec.units(nb, &own);
                // SAFETY: the phase is over: no unit holds a piece.
                let blocks = unsafe { slots.get(0..nb) };
                let max_d2 = blocks.iter().fold(0.0, |a: f64, s| a.max(s[2]));
                let due = self.neighbors.exceeded(max_d2);
                if !due {
                    exec.units(nc, &cross);
                }
                due
            } else {
                exec.units2((nb, &own), (nc, &cross));
                false
            }
        };
        if rebuild_due {
            return None;
        }
        let fold2 = |s: &[[f64; 3]]| s.iter().fold((0.0, 0.0), |a, p| (a.0 + p[0], a.1 + p[1]));
        let (oc, of) = fold2(&self.partials[..nb]);
        // phase 2: grain units (cross pairs from both sides or gathered, walls, second half
        // kick)
        let units = bp.units();
        self.grain_partials.clear();
        self.grain_partials.resize(units, [0.0; 5]);
        {
            let (b, origin) = (self.box_size, self.box_origin());
            let gctx = GrainCtx {
                simd: self.simd,
                uniform: self.uniform,
                pos: &self.pos,
                vel_pred: &self.vel_pred,
                omega_pred: &self.omega_pred,
                radius: &self.radius,
                mass: &self.mass,
                inv_mass: &self.inv_mass,
                inv_inertia: &self.inv_inertia,
                kick,
                wall_coef: &self.wall_coef,
                // (the cross pairs are in the forces already, unless stored per pair)
                cross_start: if serial || both_sides {
                    &[]
                } else {
                    &bp.cross_start
                },
                cross_items: &bp.cross_items,
                cross_state: if serial || both_sides {
                    &[]
                } else {
                    &self.cross_response
                },
                box_size: b,
                cylinder: match self.container {
                    crate::model::Container::Box => None,
                    crate::model::Container::Cylinder(c) => Some(c),
                },
                origin,
                ceil: origin[2] + b[2],
                wall_v: self.drive.direction.map(|d| d * self.box_v_pred),
                axis: self.drive.direction,
                friction: self.laws.friction(true),
                clamp: self.laws.contact.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let ctx = PairCtx {
                eval: self.force_evals,
                simd: self.simd,
                uniform: self.uniform,
                pos: View::of(&self.pos),
                vel: View::of(&self.vel_pred),
                omega: View::of(&self.omega_pred),
                radius: &self.radius,
                friction: self.laws.friction(false),
                clamp: self.laws.contact.attraction == AttractionPolicy::Clamp,
                rotations: rot,
                dt,
            };
            let cross_pairs = &bp.pairs[cross0..];
            let cross_coef = match self.uniform {
                Some(_) => &[][..],
                None => &self.pair_coef[cross0..],
            };
            let slots = Parts::new(&mut self.grain_partials);
            let power = Parts::new(&mut self.cross_power);
            let force = Parts::new(&mut self.force);
            let torque = Parts::new(&mut self.torque);
            let hist = Parts::new(&mut self.wall_history);
            let vel = Parts::new(&mut self.vel);
            let omega = Parts::new(&mut self.omega);
            // grain unit `u` of grains `r`, whose forces and torques are `f` and `t`
            let unit = |u: usize, f: &mut [[f64; 3]], t: &mut [[f64; 3]]| {
                let r = bp.unit(u);
                // SAFETY: grain unit `u` alone touches its grains and its slot.
                let chunk = unsafe {
                    GrainChunk {
                        first: r.start,
                        force: f,
                        torque: t,
                        wall_history: hist.get(r.clone()),
                        vel: vel.get(r.clone()),
                        omega: omega.get(r),
                    }
                };
                let out = grain_chunk::<N, T, LEDGER>(&gctx, chunk);
                // SAFETY: slot `u` is this unit's.
                unsafe { slots.get(u..u + 1)[0] = out };
            };
            if both_sides {
                exec.units(nb, &|blk| {
                    let g = bp.grains(blk);
                    // SAFETY: block `blk` alone touches its grains' forces and the powers of
                    // the cross pairs whose i is one of them.
                    let (f, t) = unsafe { (force.get(g.clone()), torque.get(g.clone())) };
                    let (cross_items, owner) = bp.cross_items_of(blk);
                    let side = CrossSide {
                        first: g.start,
                        cross_items,
                        owner,
                        pairs: cross_pairs,
                        coef: cross_coef,
                        power: &power,
                        force: &mut *f,
                        torque: &mut *t,
                    };
                    // SAFETY: as above.
                    unsafe { cross_side::<N, T, LEDGER>(&ctx, side) };
                    for u in bp.units_of(blk) {
                        let r = bp.unit(u);
                        let local = r.start - g.start..r.end - g.start;
                        unit(u, &mut f[local.clone()], &mut t[local]);
                    }
                });
            } else {
                exec.units(units, &|u| {
                    let r = bp.unit(u);
                    // SAFETY: grain unit `u` alone touches its grains.
                    let (f, t) = unsafe { (force.get(r.clone()), torque.get(r)) };
                    unit(u, f, t);
                });
            }
        }
        let (xc, xf) = if both_sides && !LEDGER {
            (0.0, 0.0)
        } else if both_sides {
            // the powers per cross pair, summed as the cross chunks of the other paths do
            self.cross_power
                .chunks(CROSS_CHUNK)
                .fold((0.0, 0.0), |a, c| {
                    let s = c.iter().fold((0.0, 0.0), |s, p| (s.0 + p[0], s.1 + p[1]));
                    (a.0 + s.0, a.1 + s.1)
                })
        } else {
            fold2(&self.partials[nb..])
        };
        let mut t = [0.0; 5];
        for p in &self.grain_partials {
            for (a, b) in t.iter_mut().zip(p) {
                *a += b;
            }
        }
        if kick {
            self.step_cm = (t[3] / self.mass_total, t[4] / self.mass_total);
        }
        Some((t[0], (oc + xc) + t[1], (of + xf) + t[2]))
    }
}
