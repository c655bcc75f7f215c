//! The cross kernel: a block's side of the pairs across grain blocks (laws without contact
//! history), each response added to the block's own grain, so that no thread gathers what
//! another stored.

use std::mem::MaybeUninit;

use crate::contact::lanes::{dot, get_lane, set_lane, sub3, F64x8, Lanes};
use crate::contact::response::{
    contact_response, ContactCoefficients, NormalKernel, TangentialKernel,
};
use crate::dem::team::Parts;
use crate::neighbor::{Pair, J_ROLE};
use crate::simd::Simd;

use super::pair::{PairCtx, PairLanes};
use super::{written, PAIR_CHUNK};

/// The cross pairs of one block, seen from its side: each of its grains' cross pairs
/// ([`BlockPairs::cross_items_of`](crate::dem::blocks::BlockPairs::cross_items_of)), whose
/// responses go to that grain only.
pub(crate) struct CrossSide<'a> {
    /// The block's first grain (that of `force[0]`).
    pub(crate) first: usize,
    /// The block's items: per grain in grain order, its cross pairs in pair order (index
    /// among the cross pairs, [`J_ROLE`] where the grain is the pair's j), and their grains.
    pub(crate) cross_items: &'a [u32],
    pub(crate) owner: &'a [u32],
    /// All cross pairs, and their coefficients (empty when all grains are alike).
    pub(crate) pairs: &'a [Pair],
    pub(crate) coef: &'a [ContactCoefficients],
    /// Per cross pair, its (collision, friction) power (W): written, with the ledger, by the
    /// block of the pair's i (0 when not in contact).
    pub(crate) power: &'a Parts<'a, [f64; 2]>,
    pub(crate) force: &'a mut [[f64; 3]],
    pub(crate) torque: &'a mut [[f64; 3]],
}

/// [`cross_side_impl`] compiled for the instruction set `ctx.simd`.
///
/// # Safety
/// No other unit of the phase may touch the powers of the pairs whose i is one of the block's
/// grains, nor write the grains' centres, velocities and spins that `ctx` reads.
#[inline(never)]
pub(crate) unsafe fn cross_side<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    s: CrossSide,
) {
    match ctx.simd {
        // SAFETY: as in `pair_chunk`; the rest is the caller's promise.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { cross_side_avx2::<N, T, LEDGER>(ctx, s) },
        // SAFETY: the caller's promise.
        Simd::Baseline => unsafe { cross_side_impl::<F64x8, N, T, LEDGER>(ctx, s) },
    }
}

/// [`cross_side_impl`] compiled with AVX2.
///
/// # Safety
/// The processor must have AVX2 (a [`Simd::Avx2`] in hand proves it), and the caller keeps the
/// promise of [`cross_side`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn cross_side_avx2<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &PairCtx,
    s: CrossSide,
) {
    // SAFETY: the caller's promise.
    unsafe { cross_side_impl::<F64x8, N, T, LEDGER>(ctx, s) }
}

/// A block's side of its cross pairs (laws without contact history): a branch-free pass keeps
/// the items in contact, then [`contact_response`] runs on those, `L::N` at a time in lanes,
/// on the pair's own orientation (r_i − r_j, so the numbers are those the pair's other side
/// computes); the force is added to the block's grain (+F for the pair's i, −F for its j) and
/// the torque −R τ_arm, item by item: each grain gets its cross pairs in pair order.
///
/// # Safety
/// As [`cross_side`].
#[inline(always)]
pub(crate) unsafe fn cross_side_impl<
    L: Lanes,
    N: NormalKernel,
    T: TangentialKernel,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    mut s: CrossSide,
) {
    debug_assert!(!T::HISTORY, "springs are written by one side only");
    let pos = ctx.pos;
    // the items in contact, their grains (relative to the block) and separations, kept for the
    // lanes: the first `m` entries (left uninitialised, as in `pair_chunk_impl`)
    let mut item = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut who = [const { MaybeUninit::<u32>::uninit() }; PAIR_CHUNK];
    let mut sep = [const { MaybeUninit::<[f64; 3]>::uninit() }; PAIR_CHUNK];
    let mut m = 0usize;
    let mut g = PairLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.r_i = L::splat(u.radius);
        g.r_j = L::splat(u.radius);
        g.coef = u.pair.map(L::splat);
    }
    for (&e, &gi) in s.cross_items.iter().zip(s.owner) {
        let a = (e & !J_ROLE) as usize;
        let pair = s.pairs[a];
        let (i, j) = (pair.i as usize, pair.j as usize);
        let d = sub3(pos.at(i), pos.at(j));
        let (ri, rj) = ctx.radii(i, j);
        let cut = ri + rj;
        let on = dot(d, d) < cut * cut;
        if LEDGER && e & J_ROLE == 0 {
            // SAFETY: pair a's i is this block's grain (the caller's promise).
            unsafe { s.power.get(a..a + 1)[0] = [0.0; 2] };
        }
        item[m].write(e);
        who[m].write(gi - s.first as u32);
        sep[m].write(d);
        m += on as usize;
        if m == PAIR_CHUNK {
            // SAFETY: entries 0..m were written above.
            let (e, w, d) = unsafe { (written(&item, m), written(&who, m), written(&sep, m)) };
            // SAFETY: the caller's promise.
            unsafe { cross_lanes::<L, N, T, LEDGER>(ctx, &mut s, &mut g, (e, w, d)) };
            m = 0;
        }
    }
    // SAFETY: entries 0..m were written above.
    let (e, w, d) = unsafe { (written(&item, m), written(&who, m), written(&sep, m)) };
    // SAFETY: the caller's promise.
    unsafe { cross_lanes::<L, N, T, LEDGER>(ctx, &mut s, &mut g, (e, w, d)) };
}

/// The responses of a block's cross items in contact `(item, grain in the block,
/// separation)`, `L::N` at a time, added to the block's grains in item order.
///
/// # Safety
/// As [`cross_side`].
#[inline(always)]
pub(crate) unsafe fn cross_lanes<
    L: Lanes,
    N: NormalKernel,
    T: TangentialKernel,
    const LEDGER: bool,
>(
    ctx: &PairCtx,
    s: &mut CrossSide,
    g: &mut PairLanes<L>,
    (items, who, seps): (&[u32], &[u32], &[[f64; 3]]),
) {
    for ((block, ks), ds) in items
        .chunks(L::N)
        .zip(who.chunks(L::N))
        .zip(seps.chunks(L::N))
    {
        for (l, (&e, &d)) in block.iter().zip(ds).enumerate() {
            let a = (e & !J_ROLE) as usize;
            let pair = s.pairs[a];
            g.gather(ctx, pair.i as usize, pair.j as usize, l, d);
            if ctx.uniform.is_none() {
                set_lane(&mut g.coef, l, s.coef[a]);
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
        for (l, (&e, &k)) in block.iter().zip(ks).enumerate() {
            let (f, t) = (get_lane(&r.force, l), get_lane(&r.torque_arm, l));
            let k = k as usize;
            let fi = &mut s.force[k];
            if e & J_ROLE == 0 {
                fi[0] += f[0];
                fi[1] += f[1];
                fi[2] += f[2];
                if LEDGER {
                    let a = (e & !J_ROLE) as usize;
                    let p = [r.p_collision.get(l), r.p_friction.get(l)];
                    // SAFETY: pair a's i is this block's grain (the caller's promise).
                    unsafe { s.power.get(a..a + 1)[0] = p };
                }
            } else {
                fi[0] -= f[0];
                fi[1] -= f[1];
                fi[2] -= f[2];
            }
            if T::ACTIVE && ctx.rotations {
                let rg = match ctx.uniform {
                    Some(u) => u.radius,
                    None => ctx.radius[s.first + k],
                };
                let ti = &mut s.torque[k];
                ti[0] -= rg * t[0];
                ti[1] -= rg * t[1];
                ti[2] -= rg * t[2];
            }
        }
    }
}
