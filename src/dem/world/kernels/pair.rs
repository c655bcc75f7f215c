//! The pair kernel: one chunk of candidate pairs, the pairs in contact kept by a branch-free
//! pass, their responses computed `L::N` at a time in lanes and scattered into the block's
//! forces (a block's own pairs) or stored per pair (cross pairs).

use std::mem::MaybeUninit;

use crate::contact::lanes::{dot, get_lane, set_lane, sub3, F64x8, Lanes};
use crate::contact::response::{
    contact_response, ContactCoefficients, ContactKinematics, NormalKernel, TangentialKernel,
};
use crate::dem::team::View;
use crate::neighbor::Pair;
use crate::simd::Simd;

use super::{spring, written, PairResponse, PAIR_CHUNK};
use crate::dem::world::laws::Uniform;

/// Shared inputs of the pair pass.
pub(crate) struct PairCtx<'a> {
    /// Number of this force evaluation (the clock of the pairs' `touch`).
    pub(crate) eval: u64,
    pub(crate) simd: Simd,
    /// Every grain's radius and coefficients, when all grains are alike.
    pub(crate) uniform: Option<Uniform>,
    /// Centres (m), predicted velocities (m/s) and spins (rad/s): views, since a block may
    /// be drifting its own grains in the same phase (it reads them only after).
    pub(crate) pos: View<'a, [f64; 3]>,
    pub(crate) vel: View<'a, [f64; 3]>,
    pub(crate) omega: View<'a, [f64; 3]>,
    pub(crate) radius: &'a [f64],
    pub(crate) friction: f64,
    pub(crate) clamp: bool,
    pub(crate) rotations: bool,
    pub(crate) dt: f64,
}

impl PairCtx<'_> {
    /// (R_i, R_j) of pair (i, j) (m).
    #[inline(always)]
    pub(crate) fn radii(&self, i: usize, j: usize) -> (f64, f64) {
        match self.uniform {
            Some(u) => (u.radius, u.radius),
            None => (self.radius[i], self.radius[j]),
        }
    }
}

/// One chunk of the pair pass: its candidate pairs, their coefficients and states, and (one
/// thread) the grains' forces and torques to add the responses to.
pub(crate) struct PairChunk<'a> {
    pub(crate) pairs: &'a [Pair],
    pub(crate) coef: &'a [ContactCoefficients],
    /// Tangential springs of the chunk's pairs (m).
    pub(crate) history: &'a mut [[f64; 3]],
    /// Force evaluation at which each of the chunk's pairs last touched.
    pub(crate) touch: &'a mut [u64],
    /// The chunk's responses (cross pairs; empty when they are scattered).
    pub(crate) response: &'a mut [PairResponse],
    /// Grain of `force[0]` and `torque[0]` (the first grain of the block).
    pub(crate) first: usize,
    pub(crate) force: &'a mut [[f64; 3]],
    pub(crate) torque: &'a mut [[f64; 3]],
}

/// [`pair_chunk_impl`] compiled for the instruction set `ctx.simd`.
#[inline(never)]
pub(crate) fn pair_chunk<
    N: NormalKernel,
    T: TangentialKernel,
    const SCATTER: bool,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    c: PairChunk,
) -> [f64; 3] {
    match ctx.simd {
        // SAFETY: a `Simd::Avx2` carries the proof (`HasAvx2`, made only by `Simd::detect`)
        // that the processor has AVX2.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { pair_chunk_avx2::<N, T, SCATTER, LEDGER>(ctx, c) },
        Simd::Baseline => pair_chunk_impl::<F64x8, N, T, SCATTER, LEDGER>(ctx, c),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(crate) fn pair_chunk_avx2<
    N: NormalKernel,
    T: TangentialKernel,
    const SCATTER: bool,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    c: PairChunk,
) -> [f64; 3] {
    pair_chunk_impl::<F64x8, N, T, SCATTER, LEDGER>(ctx, c)
}

/// One chunk of candidate pairs: a branch-free pass keeps the pairs in contact (and clears
/// the others' outputs), then [`contact_response`] runs on those only, `L::N`
/// contacts at a time in lanes. Returns the chunk's (collision power, friction power, 0) (W).
///
/// `SCATTER` (a block's own pairs): the forces and torques go straight into the block's `force`
/// and `torque` (which hold gravity and drag already), pair by pair in pair order. Otherwise
/// (cross pairs) each response is stored in the pair's [`PairResponse`] for the per-grain pass.
#[inline(always)]
pub(crate) fn pair_chunk_impl<
    L: Lanes,
    N: NormalKernel,
    T: TangentialKernel,
    const SCATTER: bool,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    chunk: PairChunk,
) -> [f64; 3] {
    let PairChunk {
        pairs,
        coef,
        history,
        touch,
        response,
        first,
        force,
        torque,
    } = chunk;
    let pos = ctx.pos;
    // the pairs in contact and their separations r_i − r_j (m), kept for the gather: the
    // first `m` entries, written before they are read (left uninitialised, as clearing
    // 28 KB per chunk costs a small bed a few per cent of its step)
    let mut active = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut sep = [const { MaybeUninit::<[f64; 3]>::uninit() }; PAIR_CHUNK];
    let mut m = 0usize;
    for (a, pair) in pairs.iter().enumerate() {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let d = sub3(pos.at(i), pos.at(j));
        let r2 = dot(d, d);
        let (ri, rj) = ctx.radii(i, j);
        let cut = ri + rj;
        let on = r2 < cut * cut;
        active[m].write(a as u32);
        sep[m].write(d);
        m += on as usize;
        if !SCATTER {
            response[a] = PairResponse::default();
        }
    }
    // L::N contacts at a time: gathered into lanes, one lane-wise geometry and
    // [`contact_response`] (vector instructions), then the sums contact by contact
    let (mut p_coll, mut p_fric) = (0.0, 0.0);
    let mut g = PairLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.r_i = L::splat(u.radius);
        g.r_j = L::splat(u.radius);
        g.coef = u.pair.map(L::splat);
    }
    // SAFETY: entries 0..m were written by the loop above (entry m is written before m
    // grows past it).
    let (active, sep) = unsafe { (written(&active, m), written(&sep, m)) };
    for (block, seps) in active.chunks(L::N).zip(sep.chunks(L::N)) {
        for (l, (&a, &d)) in block.iter().zip(seps).enumerate() {
            let pair = pairs[a as usize];
            g.gather(ctx, pair.i as usize, pair.j as usize, l, d);
            if ctx.uniform.is_none() {
                set_lane(&mut g.coef, l, coef[a as usize]);
            }
            if T::HISTORY {
                set_lane(
                    &mut g.history,
                    l,
                    spring(history, touch, a as usize, ctx.eval),
                );
            }
        }
        let r = contact_response::<N, T, L>(
            &g.kinematics(ctx.rotations),
            &g.coef,
            ctx.friction,
            ctx.clamp,
            ctx.rotations,
            ctx.dt,
            &mut g.history,
        );
        for (l, &a) in block.iter().enumerate() {
            let a = a as usize;
            let (f, t) = (get_lane(&r.force, l), get_lane(&r.torque_arm, l));
            if T::HISTORY {
                history[a] = get_lane(&g.history, l);
                touch[a] = ctx.eval;
            }
            if SCATTER {
                let pair = pairs[a];
                let (i, j) = (pair.i as usize, pair.j as usize);
                let fi = &mut force[i - first];
                fi[0] += f[0];
                fi[1] += f[1];
                fi[2] += f[2];
                let fj = &mut force[j - first];
                fj[0] -= f[0];
                fj[1] -= f[1];
                fj[2] -= f[2];
                if T::ACTIVE && ctx.rotations {
                    let (ri, rj) = ctx.radii(i, j);
                    let ti = &mut torque[i - first];
                    ti[0] -= ri * t[0];
                    ti[1] -= ri * t[1];
                    ti[2] -= ri * t[2];
                    let tj = &mut torque[j - first];
                    tj[0] -= rj * t[0];
                    tj[1] -= rj * t[1];
                    tj[2] -= rj * t[2];
                }
            } else {
                response[a] = PairResponse {
                    force: f,
                    torque_arm: t,
                };
            }
            if LEDGER {
                p_coll += r.p_collision.get(l);
                p_fric += r.p_friction.get(l);
            }
        }
    }
    [p_coll, p_fric, 0.0]
}

/// The inputs of up to `L::N` grain–grain contacts, one contact per lane (lanes past the
/// block's end keep an earlier contact's values: computed, never used).
#[derive(Default)]
pub(crate) struct PairLanes<L> {
    /// r_i − r_j (m).
    pub(crate) d: [L; 3],
    /// v_i − v_j (m/s).
    pub(crate) v_rel: [L; 3],
    /// R_i ω_i + R_j ω_j (m/s), summed per contact as it is gathered.
    pub(crate) spin: [L; 3],
    pub(crate) r_i: L,
    pub(crate) r_j: L,
    pub(crate) coef: [L; 4],
    pub(crate) history: [L; 3],
}

impl<L: Lanes> PairLanes<L> {
    /// Puts pair (i, j)'s separation `d` (from the distance filter), relative velocity, spin term R_i ω_i + R_j ω_j (and
    /// radii unless all grains are alike) in lane `l`.
    #[inline(always)]
    pub(crate) fn gather(&mut self, ctx: &PairCtx, i: usize, j: usize, l: usize, d: [f64; 3]) {
        set_lane(&mut self.d, l, d);
        set_lane(&mut self.v_rel, l, sub3(ctx.vel.at(i), ctx.vel.at(j)));
        let (ri, rj) = ctx.radii(i, j);
        if ctx.rotations {
            let (wi, wj) = (ctx.omega.at(i), ctx.omega.at(j));
            let spin = std::array::from_fn(|c| ri * wi[c] + rj * wj[c]);
            set_lane(&mut self.spin, l, spin);
        }
        if ctx.uniform.is_none() {
            self.r_i.set(l, ri);
            self.r_j.set(l, rj);
        }
    }

    /// Overlap R_i + R_j − |d|, normal d/|d|, relative velocity and R_i ω_i + R_j ω_j.
    #[inline(always)]
    pub(crate) fn kinematics(&self, rotations: bool) -> ContactKinematics<L> {
        let d = self.d;
        let dist = dot(d, d).sqrt();
        let inv = L::splat(1.0) / dist;
        let spin = if rotations {
            self.spin
        } else {
            [L::default(); 3]
        };
        ContactKinematics {
            overlap_m: self.r_i + self.r_j - dist,
            normal: [d[0] * inv, d[1] * inv, d[2] * inv],
            v_rel: self.v_rel,
            spin,
        }
    }
}
