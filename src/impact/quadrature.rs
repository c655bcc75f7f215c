//! The base work and viscous loss of a segment: 8-point Gauss–Legendre quadrature of the
//! closed forms, and its node values cached per (segment length, mode) as quadratic forms;
//! and the exact extrema of the box over a segment.

use crate::model::{Anchor, Sdof};

use super::events;
use super::ledger::Ledger;
use super::model::State;
use super::motion::BoxMotion;
use super::world::ImpactWorld;

/// 8-point Gauss–Legendre nodes on [−1, 1] and weights.
pub(super) const GL_X: [f64; 8] = [
    -0.960_289_856_497_536_2,
    -0.796_666_477_413_626_7,
    -0.525_532_409_916_329,
    -0.183_434_642_495_649_8,
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_2,
];

pub(super) const GL_W: [f64; 8] = [
    0.101_228_536_290_376_26,
    0.222_381_034_453_374_48,
    0.313_706_645_877_887_3,
    0.362_683_783_378_362,
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_48,
    0.101_228_536_290_376_26,
];

/// Trigonometric and exponential values at the Gauss–Legendre nodes (and the end) of a
/// segment of length `h`, reused while consecutive segments have the same length and mode
/// (most of a run): the closed forms then cost a few multiplications per node.
#[derive(Debug, Clone, Copy)]
pub(super) struct NodeCache {
    pub(super) h: f64,
    pub(super) loaded: bool,
    /// (sin Ωτ, cos Ωτ) at the 8 nodes and at τ = h.
    pub(super) sc: [(f64, f64); 9],
    /// Homogeneous basis at the 8 nodes and at τ = h.
    pub(super) basis: [(f64, f64); 9],
    /// The 8-point Gauss–Legendre sums of the base work and of the viscous loss over the
    /// segment as quadratic forms of X = (y0, w0, sin Ωt, cos Ωt, 1) (the anchor's homogeneous
    /// part and the phase at the segment start): every node value is linear in X, so the
    /// quadrature is X^T Q X with Q summed once per cache (25 products per segment instead of
    /// the closed forms at 8 nodes).
    pub(super) q_work: [[f64; 5]; 5],
    pub(super) q_visc: [[f64; 5]; 5],
}

impl NodeCache {
    pub(super) fn empty() -> Self {
        NodeCache {
            h: f64::NAN,
            loaded: false,
            sc: [(0.0, 0.0); 9],
            basis: [(0.0, 0.0); 9],
            q_work: [[0.0; 5]; 5],
            q_visc: [[0.0; 5]; 5],
        }
    }

    #[allow(clippy::needless_range_loop)]
    pub(super) fn prepare(&mut self, sd: &Sdof, omega: f64, h: f64, loaded: bool) {
        if self.h == h && self.loaded == loaded {
            return;
        }
        let taus = GL_X
            .iter()
            .map(|x| 0.5 * h * (1.0 + x))
            .chain(std::iter::once(h));
        for (i, tau) in taus.enumerate() {
            self.sc[i] = (omega * tau).sin_cos();
            self.basis[i] = sd.homogeneous_basis(tau);
        }
        self.h = h;
        self.loaded = loaded;
        self.q_work = [[0.0; 5]; 5];
        self.q_visc = [[0.0; 5]; 5];
        let (k, c, u_amp) = (sd.stiffness, sd.damping, sd.base_amplitude);
        let an = |y0: f64, w0: f64| Anchor { t0_s: 0.0, y0, w0 };
        for (i, wgt) in GL_W.iter().enumerate() {
            let basis = self.basis[i];
            // (z, z') at the node as affine maps of (y0, w0) and of (sin, cos) at the node
            let base = sd.eval_parts(&an(0.0, 0.0), basis, (0.0, 0.0));
            let part = |a: &Anchor, sc: (f64, f64)| {
                let (z, v) = sd.eval_parts(a, basis, sc);
                (z - base.0, v - base.1)
            };
            let (zy, vy) = part(&an(1.0, 0.0), (0.0, 0.0));
            let (zw, vw) = part(&an(0.0, 1.0), (0.0, 0.0));
            let (zsn, vsn) = part(&an(0.0, 0.0), (1.0, 0.0));
            let (zcs, vcs) = part(&an(0.0, 0.0), (0.0, 1.0));
            // (sin, cos) at the node from (sin Ωt, cos Ωt) at the start: rotate by (S, C)
            let (sn, cs) = self.sc[i];
            let sin_l = [0.0, 0.0, cs, sn, 0.0];
            let cos_l = [0.0, 0.0, -sn, cs, 0.0];
            let z_l = [
                zy,
                zw,
                zsn * sin_l[2] + zcs * cos_l[2],
                zsn * sin_l[3] + zcs * cos_l[3],
                base.0,
            ];
            let v_l = [
                vy,
                vw,
                vsn * sin_l[2] + vcs * cos_l[2],
                vsn * sin_l[3] + vcs * cos_l[3],
                base.1,
            ];
            let mut du = [0.0; 5];
            let mut force = [0.0; 5];
            let mut rel = [0.0; 5];
            for j in 0..5 {
                let u = u_amp * cos_l[j];
                du[j] = -u_amp * omega * sin_l[j];
                rel[j] = du[j] - v_l[j];
                force[j] = k * (u - z_l[j]) + c * rel[j];
            }
            for j in 0..5 {
                for m in 0..5 {
                    self.q_work[j][m] += wgt * 0.5 * (force[j] * du[m] + force[m] * du[j]);
                    self.q_visc[j][m] += wgt * c * rel[j] * rel[m];
                }
            }
            // a force drive's power F0 sin(Ωt) z' (its base terms above are zero)
            let f0 = sd.force_amplitude;
            if f0 != 0.0 {
                for j in 0..5 {
                    for m in 0..5 {
                        self.q_work[j][m] +=
                            wgt * 0.5 * f0 * (sin_l[j] * v_l[m] + sin_l[m] * v_l[j]);
                    }
                }
            }
        }
    }

    /// X^T Q X for the segment start's X = (y0, w0, sin Ωt, cos Ωt, 1).
    #[inline]
    pub(super) fn form(q: &[[f64; 5]; 5], x: &[f64; 5]) -> f64 {
        let mut total = 0.0;
        for (row, xj) in q.iter().zip(x) {
            let r = row[0] * x[0] + row[1] * x[1] + row[2] * x[2] + row[3] * x[3] + row[4] * x[4];
            total += xj * r;
        }
        total
    }
}

/// A few [`NodeCache`]s keyed by (segment length, mode): a run alternates between flight and
/// sticking (free and loaded system) and between the fast and the slow step, and one cache
/// would be refilled (18 `sin_cos` and 9 `exp`) at every such switch. The values are the same
/// as a single refilled cache's, so results are bit-identical.
#[derive(Debug, Clone, Copy)]
pub(super) struct NodeCaches {
    pub(super) slots: [NodeCache; 4],
    /// Slot refilled next when no slot matches (round robin).
    pub(super) next: usize,
}

impl NodeCaches {
    pub(super) fn empty() -> Self {
        NodeCaches {
            slots: [NodeCache::empty(); 4],
            next: 0,
        }
    }

    /// The cache of segment length `h` and mode `loaded`, filled if no slot holds it.
    pub(super) fn get(&mut self, sd: &Sdof, omega: f64, h: f64, loaded: bool) -> &NodeCache {
        let i = match self
            .slots
            .iter()
            .position(|c| c.h == h && c.loaded == loaded)
        {
            Some(i) => i,
            None => {
                let i = self.next;
                self.next = (i + 1) % self.slots.len();
                self.slots[i].prepare(sd, omega, h, loaded);
                i
            }
        };
        &self.slots[i]
    }
}

impl ImpactWorld {
    /// Gauss–Legendre quadrature of the drive's work (base or force) and the viscous loss on
    /// [a, b].
    pub(super) fn integrate(
        &self,
        led: &mut Ledger,
        motion: &BoxMotion,
        an: &Anchor,
        a: f64,
        b: f64,
    ) {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let (mut work, mut visc) = (0.0, 0.0);
        let BoxMotion::Spring(sd) = motion else {
            return;
        };
        for (x, wgt) in GL_X.iter().zip(GL_W.iter()) {
            let t = mid + half * x;
            // eval and base_motion from one sin_cos (the same expressions, the same values)
            let sc = (self.omega * t).sin_cos();
            let (z, v) = sd.eval_parts(an, sd.homogeneous_basis(t - an.t0_s), sc);
            let (u, du) = (self.u_amp * sc.1, -self.u_amp * self.omega * sc.0);
            let rel_v = du - v;
            work += wgt * (self.k * (u - z) + self.c * rel_v) * du;
            if sd.force_amplitude != 0.0 {
                work += wgt * sd.force_amplitude * sc.0 * v;
            }
            visc += wgt * self.c * rel_v * rel_v;
        }
        led.base_work.add(work * half);
        led.viscous.add(visc * half);
        if a >= self.steady_start {
            led.steady_base.add(work * half);
            led.steady_viscous.add(visc * half);
        }
    }

    /// [`ImpactWorld::integrate`] on a full-length segment with the cached quadrature forms.
    pub(super) fn integrate_cached(
        &self,
        led: &mut Ledger,
        an: &Anchor,
        cache: &NodeCache,
        sc0: (f64, f64),
        a: f64,
    ) {
        let half = 0.5 * cache.h;
        let x = [an.y0, an.w0, sc0.0, sc0.1, 1.0];
        let work = NodeCache::form(&cache.q_work, &x);
        let visc = NodeCache::form(&cache.q_visc, &x);
        led.base_work.add(work * half);
        led.viscous.add(visc * half);
        if a >= self.steady_start {
            led.steady_base.add(work * half);
            led.steady_viscous.add(visc * half);
        }
    }

    /// Exact extrema of z on [st.t, te] (endpoints and interior zero of z').
    #[allow(clippy::too_many_arguments)]
    pub(super) fn track_extrema(
        &self,
        led: &mut Ledger,
        motion: &BoxMotion,
        an: &Anchor,
        st: &State,
        te: f64,
        zb: f64,
        vb: f64,
    ) {
        for z in [st.z, zb] {
            led.zmax = led.zmax.max(z);
            led.zmin = led.zmin.min(z);
        }
        if (st.v > 0.0) != (vb > 0.0) && st.v != 0.0 && vb != 0.0 {
            let (tm, _) = events::brent(|t| motion.eval(an, t).1, st.t, te, st.v, vb);
            let (zm, _) = motion.eval(an, tm);
            led.zmax = led.zmax.max(zm);
            led.zmin = led.zmin.min(zm);
        }
    }
}
