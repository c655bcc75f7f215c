//! The grain kernel: per chunk of grains, the cross pairs' stored responses gathered in pair
//! order, the contacts with the six walls `L::N` at a time in lanes, and the step's second
//! half kick; and what a grain's force starts from (weight and settling drag).

use std::mem::MaybeUninit;

use crate::contact::lanes::{dot, get_lane, set_lane, F64x8, Lanes};
use crate::contact::response::{
    contact_response, ContactCoefficients, ContactKinematics, NormalKernel, TangentialKernel,
};
use crate::dem::blocks::GRAIN_CHUNK;
use crate::dem::team::View;
use crate::integrate::half_kick;
use crate::model::Cylinder;
use crate::neighbor::J_ROLE;
use crate::simd::Simd;

use super::{written, PairResponse};
use crate::dem::world::laws::Uniform;

/// What the force on a grain starts from: its weight and the settling drag.
pub(crate) struct Weight<'a> {
    /// Grain masses (kg).
    pub(crate) mass: &'a [f64],
    /// Grain velocities (m/s), read for the drag.
    pub(crate) vel: View<'a, [f64; 3]>,
    /// Acceleration of gravity (m/s²).
    pub(crate) gravity: [f64; 3],
    /// Centres (m), read for the rotating frame's centrifugal force.
    pub(crate) pos: View<'a, [f64; 3]>,
    /// Predicted full-step velocities (m/s), read for the Coriolis force (second order, as the
    /// contacts' damping).
    pub(crate) vel_pred: View<'a, [f64; 3]>,
    /// The rotating frame, if any ([`crate::model::rotation`]).
    pub(crate) rotation: Option<crate::model::FrameRotation>,
    /// Settling drag rate (1/s; 0 in a run).
    pub(crate) drag: f64,
    /// Whether torques are computed (then zeroed here).
    pub(crate) rotations: bool,
    /// Forces already known per grain before the contacts (N): the bean bag's bonds.
    pub(crate) bonds: Option<&'a [[f64; 3]]>,
}

/// Gravity and settling drag on grains `first..first + force.len()` (a block, before its own
/// pairs): F = m g − m β v (+ m (|Ω|² R⊥ − 2 Ω × v) in a rotating frame, + the bonds' pull
/// on a bag's nodes), and a zero torque
/// (N, N m).
pub(crate) fn init_forces(
    w: &Weight,
    first: usize,
    force: &mut [[f64; 3]],
    torque: &mut [[f64; 3]],
) {
    for (k, (f, t)) in force.iter_mut().zip(torque.iter_mut()).enumerate() {
        let i = first + k;
        let m = w.mass[i];
        let g = w.gravity;
        *f = [m * g[0], m * g[1], m * g[2]];
        if let Some(r) = &w.rotation {
            let a = r.acceleration(w.pos.at(i), w.vel_pred.at(i));
            f[0] += m * a[0];
            f[1] += m * a[1];
            f[2] += m * a[2];
        }
        if w.drag > 0.0 {
            let (s, v) = (-m * w.drag, w.vel.at(i));
            f[0] += s * v[0];
            f[1] += s * v[1];
            f[2] += s * v[2];
        }
        if let Some(b) = w.bonds {
            let b = b[i];
            f[0] += b[0];
            f[1] += b[1];
            f[2] += b[2];
        }
        if w.rotations {
            *t = [0.0; 3];
        }
    }
}

/// Shared inputs of the per-grain pass.
pub(crate) struct GrainCtx<'a> {
    pub(crate) simd: Simd,
    /// Every grain's radius and coefficients, when all grains are alike.
    pub(crate) uniform: Option<Uniform>,
    pub(crate) pos: &'a [[f64; 3]],
    pub(crate) vel_pred: &'a [[f64; 3]],
    pub(crate) omega_pred: &'a [[f64; 3]],
    pub(crate) radius: &'a [f64],
    pub(crate) mass: &'a [f64],
    pub(crate) inv_mass: &'a [f64],
    pub(crate) inv_inertia: &'a [f64],
    /// Whether the chunk ends with the grains' second half kick (during a step).
    pub(crate) kick: bool,
    pub(crate) wall_coef: &'a [ContactCoefficients],
    /// Per grain, where its cross pairs start in `cross_items`
    /// ([`BlockPairs::cross_start`](crate::dem::blocks::BlockPairs::cross_start));
    /// empty when the cross pairs were scattered into the forces (one thread).
    pub(crate) cross_start: &'a [u32],
    /// Per grain, its cross pairs in pair order
    /// ([`BlockPairs::cross_items`](crate::dem::blocks::BlockPairs::cross_items)).
    pub(crate) cross_items: &'a [u32],
    /// States of the cross pairs (their responses, from the pair pass).
    pub(crate) cross_state: &'a [PairResponse],
    pub(crate) box_size: [f64; 3],
    /// The cylinder inscribed in the box, if the cavity is one (its curved wall and end caps
    /// replace the box's six walls, [`crate::model::container`]).
    pub(crate) cylinder: Option<Cylinder>,
    /// The box's corner (floor, x = y = 0) (m).
    pub(crate) origin: [f64; 3],
    /// Height of the ceiling, `origin[2] + box_size[2]` (m).
    pub(crate) ceil: f64,
    /// Velocity of the box (m/s).
    pub(crate) wall_v: [f64; 3],
    /// The drive axis d (unit vector): F_gz is the walls' force along it.
    pub(crate) axis: [f64; 3],
    pub(crate) friction: f64,
    pub(crate) clamp: bool,
    pub(crate) rotations: bool,
    pub(crate) dt: f64,
}

/// One chunk of the per-grain pass: grains `first..first + force.len()`.
pub(crate) struct GrainChunk<'a> {
    pub(crate) first: usize,
    pub(crate) force: &'a mut [[f64; 3]],
    pub(crate) torque: &'a mut [[f64; 3]],
    pub(crate) wall_history: &'a mut [[[f64; 3]; 6]],
    pub(crate) vel: &'a mut [[f64; 3]],
    pub(crate) omega: &'a mut [[f64; 3]],
}

/// [`grain_chunk_impl`] compiled for the instruction set `ctx.simd`.
#[inline(never)]
pub(crate) fn grain_chunk<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &GrainCtx,
    c: GrainChunk,
) -> [f64; 5] {
    match ctx.simd {
        // SAFETY: as in `pair_chunk`.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2(_) => unsafe { grain_chunk_avx2::<N, T, LEDGER>(ctx, c) },
        Simd::Baseline => grain_chunk_impl::<F64x8, N, T, LEDGER>(ctx, c),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(crate) fn grain_chunk_avx2<N: NormalKernel, T: TangentialKernel, const LEDGER: bool>(
    ctx: &GrainCtx,
    c: GrainChunk,
) -> [f64; 5] {
    grain_chunk_impl::<F64x8, N, T, LEDGER>(ctx, c)
}

/// One chunk of grains from `first`, whose `force` and `torque` hold gravity, drag and the
/// block's own pairs already: each grain's cross pairs gathered in pair order (so the sums do
/// not depend on the threads), then its contacts with the six walls through the same
/// [`contact_response`]. Returns the chunk's (F_gz, collision power, friction power, Σ m z,
/// Σ m ż) (N, W, W, kg m, kg m/s): F_gz and z along the drive axis d.
///
/// With `ctx.kick` the chunk's grains then get the step's second half kick (2.2.5),
/// v ← v + (dt/2) F/m and ω ← ω + (dt/2) τ/I, their forces being complete.
#[inline(always)]
pub(crate) fn grain_chunk_impl<
    L: Lanes,
    N: NormalKernel,
    T: TangentialKernel,
    const LEDGER: bool,
>(
    ctx: &GrainCtx,
    chunk: GrainChunk,
) -> [f64; 5] {
    let GrainChunk {
        first,
        force,
        torque,
        wall_history,
        vel,
        omega,
    } = chunk;
    let (mut fgz, mut p_coll, mut p_fric) = (0.0, 0.0, 0.0);
    // the chunk's wall contacts (grain × 6 + wall): the first `m` entries, written before
    // they are read (left uninitialised: clearing 12 KB per chunk costs a small bed ~2 %)
    let mut walls = [const { MaybeUninit::<u32>::uninit() }; 6 * GRAIN_CHUNK];
    let mut m = 0usize;
    for (l, ((fi, ti), hist)) in force
        .iter_mut()
        .zip(torque.iter_mut())
        .zip(wall_history.iter_mut())
        .enumerate()
    {
        let i = first + l;
        let r = ctx.radius[i];
        let items = match ctx.cross_start {
            [] => &[],
            s => &ctx.cross_items[s[i] as usize..s[i + 1] as usize],
        };
        for &e in items {
            let st = &ctx.cross_state[(e & !J_ROLE) as usize];
            // +1 where i is the pair's i, −1 where it is its j (exact: a + (−b) = a − b, the
            // scatter's subtraction)
            let sign = 1.0 - 2.0 * (e >> 31) as f64;
            fi[0] += sign * st.force[0];
            fi[1] += sign * st.force[1];
            fi[2] += sign * st.force[2];
            if T::ACTIVE && ctx.rotations {
                ti[0] -= r * st.torque_arm[0];
                ti[1] -= r * st.torque_arm[1];
                ti[2] -= r * st.torque_arm[2];
            }
        }
        // far from every wall (most grains of a wide bed): nothing to do (one branch for
        // the six tests, `&` not `&&`: a small box has grains near some wall at random)
        let (p, o) = (ctx.pos[i], ctx.origin);
        let (x, y) = (p[0] - o[0], p[1] - o[1]);
        let clear = match &ctx.cylinder {
            None => {
                (x > r)
                    & (x < ctx.box_size[0] - r)
                    & (y > r)
                    & (y < ctx.box_size[1] - r)
                    & (p[2] > o[2] + r)
                    & (p[2] < ctx.ceil - r)
            }
            Some(c) => c.clear_of_walls([x, y, p[2] - o[2]], r),
        };
        if clear {
            if T::HISTORY {
                *hist = [[0.0; 3]; 6];
            }
            continue;
        }
        // the grain's wall contacts, kept branch-free (six overlaps against the box)
        let z6 = wall_overlaps(ctx, i);
        for (w, z) in z6.into_iter().enumerate() {
            let on = z > 0.0;
            walls[m].write((l * 6 + w) as u32);
            m += on as usize;
            if T::HISTORY && !on {
                hist[w] = [0.0; 3];
            }
        }
    }
    // eight wall contacts at a time in lanes, like the pair pass
    let mut g = WallLanes::<L>::default();
    if let Some(u) = ctx.uniform {
        g.coef = u.wall.map(L::splat);
    }
    // SAFETY: entries 0..m were written by the loop above (entry m before m grows past it).
    let walls = unsafe { written(&walls, m) };
    for block in walls.chunks(L::N) {
        for (l, &e) in block.iter().enumerate() {
            let (k, w) = (e as usize / 6, e as usize % 6);
            g.gather(ctx, first + k, w, l);
            if T::HISTORY {
                set_lane(&mut g.history, l, wall_history[k][w]);
            }
        }
        let rs = contact_response::<N, T, L>(
            &g.kin,
            &g.coef,
            ctx.friction,
            ctx.clamp,
            ctx.rotations,
            ctx.dt,
            &mut g.history,
        );
        for (l, &e) in block.iter().enumerate() {
            let (k, w) = (e as usize / 6, e as usize % 6);
            let r = ctx.radius[first + k];
            if T::HISTORY {
                wall_history[k][w] = get_lane(&g.history, l);
            }
            if LEDGER {
                p_coll += rs.p_collision.get(l);
                p_fric += rs.p_friction.get(l);
            }
            let (f, t) = (get_lane(&rs.force, l), get_lane(&rs.torque_arm, l));
            let fi = &mut force[k];
            fi[0] += f[0];
            fi[1] += f[1];
            fi[2] += f[2];
            if T::ACTIVE && ctx.rotations {
                let ti = &mut torque[k];
                ti[0] -= r * t[0];
                ti[1] -= r * t[1];
                ti[2] -= r * t[2];
            }
            fgz -= dot(f, ctx.axis);
        }
    }
    let (mut mz, mut mv) = (0.0, 0.0);
    if ctx.kick {
        let h = 0.5 * ctx.dt;
        let n = force.len();
        half_kick(vel, force, &ctx.inv_mass[first..first + n], h);
        if ctx.rotations {
            half_kick(omega, torque, &ctx.inv_inertia[first..first + n], h);
        }
        // the centre of mass at the end of the step along the drive axis (its height and
        // vertical velocity for the vertical axis)
        if ctx.axis == [0.0, 0.0, 1.0] {
            // the vertical axis: the same sums without the zero terms
            for (k, v) in vel.iter().enumerate() {
                let m = ctx.mass[first + k];
                mz += m * ctx.pos[first + k][2];
                mv += m * v[2];
            }
        } else {
            for (k, v) in vel.iter().enumerate() {
                let m = ctx.mass[first + k];
                mz += m * dot(ctx.pos[first + k], ctx.axis);
                mv += m * dot(*v, ctx.axis);
            }
        }
    }
    [fgz, p_coll, p_fric, mz, mv]
}

/// Overlaps of grain i with the walls x−, x+, y−, y+, floor, ceiling (m); ≤ 0: no contact.
/// Wall w has the normal ±e_{w/2}, + for even w (pointing into the box). In a cylinder, the
/// slots of [`crate::model::container`].
#[inline(always)]
pub(crate) fn wall_overlaps(ctx: &GrainCtx, i: usize) -> [f64; 6] {
    let (p, r, b, o) = (ctx.pos[i], ctx.radius[i], ctx.box_size, ctx.origin);
    let (x, y) = (p[0] - o[0], p[1] - o[1]);
    if let Some(c) = &ctx.cylinder {
        return c.overlaps([x, y, p[2] - o[2]], r);
    }
    [
        r - x,
        r - (b[0] - x),
        r - y,
        r - (b[1] - y),
        r - (p[2] - o[2]),
        r - (ctx.ceil - p[2]),
    ]
}

/// The kinematics and coefficients of up to `L::N` grain–wall contacts, one per lane.
#[derive(Default)]
pub(crate) struct WallLanes<L> {
    pub(crate) kin: ContactKinematics<L>,
    pub(crate) coef: [L; 4],
    pub(crate) history: [L; 3],
}

impl<L: Lanes> WallLanes<L> {
    /// Puts grain i's contact with wall `w` (normal ±e_{w/2}, + for even w; a cylinder's
    /// curved wall: towards its axis) in lane `l`.
    #[inline(always)]
    pub(crate) fn gather(&mut self, ctx: &GrainCtx, i: usize, w: usize, l: usize) {
        let r = ctx.radius[i];
        let (vp, om) = (ctx.vel_pred[i], ctx.omega_pred[i]);
        let (axis, s) = (w / 2, 1.0 - 2.0 * (w % 2) as f64);
        let k = &mut self.kin;
        k.overlap_m.set(l, wall_overlaps(ctx, i)[w]);
        let mut n = [0.0; 3];
        match &ctx.cylinder {
            None => n[axis] = s,
            Some(c) => {
                let (p, o) = (ctx.pos[i], ctx.origin);
                n = c.normal([p[0] - o[0], p[1] - o[1], p[2] - o[2]], w);
            }
        }
        set_lane(&mut k.normal, l, n);
        set_lane(&mut k.spin, l, [r * om[0], r * om[1], r * om[2]]);
        let wv = ctx.wall_v;
        set_lane(
            &mut k.v_rel,
            l,
            [vp[0] - wv[0], vp[1] - wv[1], vp[2] - wv[2]],
        );
        if ctx.uniform.is_none() {
            set_lane(&mut self.coef, l, ctx.wall_coef[i]);
        }
    }
}
