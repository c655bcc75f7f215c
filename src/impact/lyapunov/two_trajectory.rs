//! The two-trajectory (Benettin) estimate of the largest Lyapunov exponent
//! ([`ImpactWorld::model_lyapunov_two_trajectory`]): two copies of the model, their
//! separation renormalised every forcing period; no tangent code shared with the other
//! estimate.

use crate::error::SimError;
use crate::impact::model::{Mode, State};
use crate::impact::segment::{Event, SegmentHook};
use crate::impact::world::ImpactWorld;
use crate::model::RunOptions;
use crate::observe::NullObserver;

use super::estimate::{
    norm_weights, scaled_norm, LyapunovMethod, ModelLyapunov, ModelLyapunovOptions, SEED,
};

impl ImpactWorld {
    /// Largest Lyapunov exponent of the stroboscopic map from the divergence of two copies of
    /// the model (Benettin's method): the reference for [`ImpactWorld::model_lyapunov`].
    ///
    /// # Formula
    /// The model runs to k_a T, max(N, 10) periods before the steady window's first kT (state
    /// A; the periods before the window only align u and are not averaged). Each period, a copy
    /// B = A + d0 u (u a unit vector in the scaled norm; projected onto y = z, y' = z' with
    /// the plastic law's momentum weighting when the particle is stuck, and on the particle's
    /// components only for a kinematic box) and A are both advanced by the exact model to
    /// (k+1)T; g_k = ‖B − A‖/d0, u ← (B − A)/‖B − A‖. λ_T = (1/N) Σ ln g_k, λ = λ_T f.
    /// No tangent (linearised) equation is used.
    ///
    /// # Units
    /// As [`ImpactWorld::model_lyapunov`].
    ///
    /// # Parameters
    /// `opts.separation` d0 = 1e-7 (scaled norm), `opts.blocks` = 10.
    ///
    /// # Errors
    /// As [`ImpactWorld::model_lyapunov`]; [`SimError::Unstable`] if the separation becomes
    /// non-finite.
    ///
    /// # Pitfalls
    /// - The finite separation also sees the model's discontinuities that the tangent misses
    ///   (a grazing impact present in one copy only, the chattering cut s ≤ s* decided
    ///   differently): rare periods with a large ln g_k. Keep d0 small, but well above the
    ///   event-time noise (~1e-11 scaled per impact).
    /// - About twice the cost of a run plus twice the cost of the steady window (two one-period
    ///   runs per period from k_a T).
    ///
    /// # References
    /// Benettin, G., Galgani, L., Giorgilli, A. & Strelcyn, J.-M. (1980), "Lyapunov
    /// characteristic exponents for smooth dynamical systems and for Hamiltonian systems; a
    /// method for computing all of them", Meccanica 15, 9–20, doi:10.1007/BF02128236.
    ///
    /// # Example
    /// ```
    /// # use pdamp::impact::{ImpactWorld, ModelLyapunovOptions};
    /// # use pdamp::scene::{Run, Scene};
    /// let mut s = Scene::thesis_b_impact();
    /// s.excitation.frequency = 2.0;
    /// s.run = Run::with_duration(200.0);
    /// s.run.steady_fraction = 0.5;
    /// let w = ImpactWorld::new(&s.resolve_impact()?);
    /// let l = w.model_lyapunov_two_trajectory(&ModelLyapunovOptions::default())?;
    /// assert!((l.per_second + 7.6 / (2.0 * (2.37 + 0.227))).abs() < 0.05);
    /// # Ok::<(), pdamp::error::SimError>(())
    /// ```
    pub fn model_lyapunov_two_trajectory(
        &self,
        opts: &ModelLyapunovOptions,
    ) -> Result<ModelLyapunov, SimError> {
        opts.validate()?;
        let (k0, k_end) = self.lyapunov_window()?;
        let wt = norm_weights(self);
        let kinematic = !self.box_mass.is_finite();
        let d0 = opts.separation;
        // transient: the same segments as a plain run, stopped at k_a T; the periods k_a … k0
        // (as many as are measured, at least 10) align u with the most expanding direction
        let k_a = k0.saturating_sub((k_end - k0).max(10));
        let (mut a, _) = self.advance(self.init, k_a as f64 * self.period, false)?;
        let mut u = SEED;
        if kinematic {
            u[0] = 0.0;
            u[1] = 0.0;
        }
        let n0 = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        u.iter_mut().for_each(|x| *x /= n0);
        let mut logs = Vec::with_capacity((k_end - k0) as usize);
        let (mut stuck_s, mut impacts) = (0.0, 0u64);
        for k in k_a..k_end {
            let t1 = (k + 1) as f64 * self.period;
            let b = self.perturbed(&a, &u, d0, &wt);
            let (a1, rec) = self.advance(a, t1, true)?;
            let (b1, _) = self.advance(b, t1, true)?;
            let measured = k >= k0;
            if measured {
                stuck_s += rec.stuck_s;
                impacts += rec.impacts;
            }
            let diff = [b1.z - a1.z, b1.v - a1.v, b1.y - a1.y, b1.w - a1.w];
            let d = scaled_norm(&diff, &wt);
            if !d.is_finite() {
                return Err(SimError::Unstable {
                    t_s: t1,
                    reason: "the separation of the two trajectories became non-finite".into(),
                });
            }
            if measured {
                logs.push((d / d0).ln());
            }
            if d > 0.0 {
                for (ui, (di, wi)) in u.iter_mut().zip(diff.iter().zip(&wt)) {
                    *ui = di * wi / d;
                }
            }
            a = a1;
        }
        Ok(self.lyapunov_result(
            LyapunovMethod::TwoTrajectory,
            &logs,
            opts.blocks,
            stuck_s,
            impacts,
        ))
    }

    /// Advance the exact model from `st` to `t1` (a run of a copy of this world started at
    /// `st`); with `restart` the copy's steady window starts at `st.t` (one segment grid per
    /// call), otherwise the world's own steady start is kept (the segments of a plain run).
    fn advance(&self, st: State, t1: f64, restart: bool) -> Result<(State, Recorder), SimError> {
        let mut w = self.clone();
        w.init = st;
        w.duration = t1;
        if restart {
            w.steady_start = st.t;
        }
        let mut rec = Recorder {
            last: st,
            stuck_s: 0.0,
            impacts: 0,
        };
        if t1 > st.t {
            w.run_hooked(&mut NullObserver, &RunOptions::summary_only(), &mut rec)?;
        }
        Ok((rec.last, rec))
    }

    /// The state A + d0 u (u in scaled components), kept on the constraint when A is stuck.
    fn perturbed(&self, a: &State, u: &[f64; 4], d0: f64, wt: &[f64; 4]) -> State {
        let mut d: [f64; 4] = std::array::from_fn(|i| d0 * u[i] / wt[i]);
        if !self.box_mass.is_finite() {
            d[0] = 0.0;
            d[1] = 0.0;
        }
        let mut b = *a;
        match a.mode {
            Mode::Flight => {
                b.z += d[0];
                b.v += d[1];
                b.y += d[2];
                b.w += d[3];
            }
            Mode::Free | Mode::Floor | Mode::Ceiling | Mode::Clamped => {
                // the perturbation a sticking impact would leave: box position kept, common
                // velocity from momentum (the plastic law)
                let mp = self.particle.map_or(0.0, |p| p.mass);
                let dv = if self.box_mass.is_finite() {
                    (self.box_mass * d[1] + mp * d[3]) / (self.box_mass + mp)
                } else {
                    0.0
                };
                b.z += d[0];
                b.v += dv;
                b.y += d[0];
                b.w = b.v;
            }
        }
        b
    }
}

/// Records the last state, the stuck time and the impacts of a run (two-trajectory estimate).
#[derive(Debug, Clone, Copy)]
struct Recorder {
    last: State,
    stuck_s: f64,
    impacts: u64,
}

impl SegmentHook for Recorder {
    fn flow(&mut self, from: &State, to: &State) {
        if from.mode.stuck() {
            self.stuck_s += to.t - from.t;
        }
        self.last = *to;
    }
    fn event(&mut self, before: &State, after: &State, event: Event) {
        let approach = match event {
            Event::HitFloor => before.v - before.w,
            Event::HitCeiling => before.w - before.v,
            _ => 0.0,
        };
        if approach > 0.0 {
            self.impacts += 1;
        }
        self.last = *after;
    }
}
