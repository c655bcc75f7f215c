//! The tangent estimate of the largest Lyapunov exponent
//! ([`ImpactWorld::model_lyapunov`], and [`ImpactWorld::run_with_model_lyapunov`] riding on a
//! run): a tangent vector δx = (δz, δz', δy, δy') carried along the run by the exact flow
//! Jacobians and the saltation matrices of the events.

use crate::error::SimError;
use crate::impact::collision::collide;
use crate::impact::model::{Mode, State};
use crate::impact::motion::BoxMotion;
use crate::impact::segment::{Event, SegmentHook};
use crate::impact::world::ImpactWorld;
use crate::model::{RunOptions, Sdof};
use crate::observe::NullObserver;

use super::estimate::{
    norm_weights, scaled_norm, LyapunovMethod, ModelLyapunov, ModelLyapunovOptions, SEED,
};

impl ImpactWorld {
    /// One run that serves both the run's summary (samples to `obs`, as [`ImpactWorld::run`])
    /// and [`ImpactWorld::model_lyapunov`] over the analysis window (from the setup's
    /// `analysis_start_s` instead of the steady start): the tangent dynamics ride on the run
    /// itself, so an analysed point costs one simulation, not two.
    ///
    /// # Errors
    /// The run's errors (outer); the exponent's own (inner), as
    /// [`ImpactWorld::model_lyapunov`] over the analysis window.
    pub fn run_with_model_lyapunov(
        &self,
        obs: &mut dyn crate::observe::Observer,
        run_opts: &RunOptions,
        opts: &ModelLyapunovOptions,
    ) -> Result<(crate::model::RunSummary, Result<ModelLyapunov, SimError>), SimError> {
        let mut window = self.clone();
        window.steady_start = self.strobe_start;
        let (k0, k_end) = match opts.validate().and_then(|()| window.lyapunov_window()) {
            Ok(w) => w,
            Err(e) => return Ok((self.run(obs, run_opts)?, Err(e))),
        };
        let mut tan = Tangent::new(self, k0, k_end);
        let summary = self.run_hooked(obs, run_opts, &mut tan)?;
        tan.finish();
        if let Some(err) = tan.failure {
            return Ok((summary, Err(err)));
        }
        if tan.logs.len() < 2 {
            let err = SimError::Unstable {
                t_s: tan.t,
                reason: format!(
                    "the run ended after {} of {} measured forcing periods",
                    tan.logs.len(),
                    k_end - k0
                ),
            };
            return Ok((summary, Err(err)));
        }
        let l = self.lyapunov_result(
            LyapunovMethod::TangentSaltation,
            &tan.logs,
            opts.blocks,
            tan.stuck_s,
            tan.impacts,
        );
        Ok((summary, Ok(l)))
    }

    /// Largest Lyapunov exponent of the stroboscopic map, from the tangent dynamics of the
    /// model with saltation matrices (per forcing period and per second, with a standard error).
    ///
    /// # Formula
    /// δx = (δz, δz', δy, δy') is carried along the run of [`ImpactWorld::run`] (the same
    /// trajectory): between events by the exact flow Jacobian (box: homogeneous solution of
    /// (2.1.2) for M, or M + m_p while the particle is stuck; particle in flight: δy += δy' τ);
    /// at an impact by S = J_g + (f⁺ − J_g f⁻) ∇hᵀ/(∇h·f⁻) with J_g from (2.1.25)–(2.1.26)
    /// (plastic, e = 0, at the chattering cut, which projects onto y = z, y' = z'); at lift-off
    /// (2.1.27) by S = I + (f⁺ − f⁻) ∇h_dᵀ/ḣ_d (= I, the contact force vanishing there).
    /// With g_k = ‖δx((k+1)T)‖/‖δx(kT)‖, δx renormalised at every kT:
    /// λ_T = (1/N) Σ ln g_k over the N periods of the steady window, λ = λ_T f.
    /// Norm: ‖δx‖² = (δz² + δy²)/L² + (δz'² + δy'²)/(L Ω)², L = max(U, m_p g/K, 1 µm).
    ///
    /// # Units
    /// `per_period` per forcing period, `per_second` 1/s, `frequency_hz` Hz.
    ///
    /// # Parameters
    /// `opts.blocks` = 10 blocks for the batch-means error (`opts.separation` is not used).
    /// Transient: t < the scene's steady_start (the vector is renormalised there too, so it is
    /// aligned with the most expanding direction when the average starts).
    ///
    /// # Errors
    /// [`SimError::Scene`] if the steady window holds fewer than 2 forcing periods;
    /// [`SimError::Unstable`] if the run fails or the tangent vector overflows (an impact at a
    /// vanishing approach speed); [`SimError::Unavailable`] for bad options.
    ///
    /// # Pitfalls
    /// - Near a grazing impact (approach speed → 0) a single saltation matrix is huge: the
    ///   exponent is then dominated by rare periods and its standard error is large.
    /// - A kinematic box whose ball locks onto the table gives λ_T = −∞ (every perturbation
    ///   dies in finite time); a tangent vector that collapses during the transient is reseeded.
    /// - Like any exponent from one orbit, it is that of the attractor the run settles on;
    ///   coexisting attractors are not explored.
    ///
    /// # References
    /// Müller, P. C. (1995), "Calculation of Lyapunov exponents for dynamic systems with
    /// discontinuities", Chaos, Solitons & Fractals 5(9), 1671–1681.
    /// Leine, R. I. & Nijmeijer, H. (2004), *Dynamics and Bifurcations of Non-Smooth Mechanical
    /// Systems*, Springer, ch. 3 (saltation matrix), doi:10.1007/978-3-540-44398-8.
    /// di Bernardo, M., Budd, C., Champneys, A. & Kowalczyk, P. (2008), *Piecewise-smooth
    /// Dynamical Systems*, Springer, §2.5, doi:10.1007/978-1-84628-708-4.
    ///
    /// # Example
    /// ```
    /// # use pdamp::impact::{ImpactWorld, ModelLyapunovOptions};
    /// # use pdamp::scene::{Damper, Run, Scene};
    /// // scene B's impact damper at 2 Hz: the particle never leaves the floor, so λ is the
    /// // loaded primary's decay rate −C/(2(M + m_p)) = −1.463 1/s (up to a boundary term
    /// // ≤ ln(ω_d/Ω)/(N T) = 0.02 1/s for these N = 200 periods)
    /// let mut s = Scene::thesis_b_impact();
    /// s.excitation.frequency = 2.0;
    /// s.run = Run::with_duration(200.0);
    /// s.run.steady_fraction = 0.5;
    /// let l = ImpactWorld::new(&s.resolve_impact()?).model_lyapunov(&ModelLyapunovOptions::default())?;
    /// assert!(l.locked && l.periods == 200);
    /// assert!((l.per_second + 7.6 / (2.0 * (2.37 + 0.227))).abs() < 0.05);
    /// # Ok::<(), pdamp::error::SimError>(())
    /// ```
    pub fn model_lyapunov(&self, opts: &ModelLyapunovOptions) -> Result<ModelLyapunov, SimError> {
        opts.validate()?;
        let (k0, k_end) = self.lyapunov_window()?;
        let mut tan = Tangent::new(self, k0, k_end);
        self.run_hooked(&mut NullObserver, &RunOptions::summary_only(), &mut tan)?;
        tan.finish();
        if let Some(err) = tan.failure {
            return Err(err);
        }
        if tan.logs.len() < 2 {
            return Err(SimError::Unstable {
                t_s: tan.t,
                reason: format!(
                    "the run ended after {} of {} measured forcing periods",
                    tan.logs.len(),
                    k_end - k0
                ),
            });
        }
        Ok(self.lyapunov_result(
            LyapunovMethod::TangentSaltation,
            &tan.logs,
            opts.blocks,
            tan.stuck_s,
            tan.impacts,
        ))
    }
}

/// Exact flow Jacobian of the homogeneous primary over τ applied to (δz, δz'): the matrix of
/// [`Sdof::eval`]'s homogeneous part, y = y0 C + (y0' + a y0) S, y' = y0' C − (a y0' + ω0² y0) S.
#[inline]
fn box_flow(sd: &Sdof, tau: f64, dz: f64, dv: f64) -> (f64, f64) {
    let (ce, se) = sd.homogeneous_basis(tau);
    let a = sd.damping / (2.0 * sd.mass);
    let w0sq = sd.stiffness / sd.mass;
    (
        dz * (ce + a * se) + dv * se,
        dv * (ce - a * se) - w0sq * se * dz,
    )
}

/// The tangent vector riding on a run (lazy: propagated to the next event or kT only).
struct Tangent<'a> {
    w: &'a ImpactWorld,
    wt: [f64; 4],
    /// δz, δz', δy, δy' (m, m/s) at time `t`.
    dx: [f64; 4],
    t: f64,
    /// Mode since the last event (the one the lazy propagation uses).
    mode: Mode,
    next_k: u64,
    k0: u64,
    k_end: u64,
    logs: Vec<f64>,
    stuck_s: f64,
    impacts: u64,
    failure: Option<SimError>,
}

impl<'a> Tangent<'a> {
    fn new(w: &'a ImpactWorld, k0: u64, k_end: u64) -> Self {
        let mut t = Tangent {
            w,
            wt: norm_weights(w),
            dx: [0.0; 4],
            t: w.init.t,
            mode: w.init.mode,
            next_k: (w.init.t / w.period).floor() as u64 + 1,
            k0,
            k_end,
            logs: Vec::with_capacity((k_end - k0) as usize),
            stuck_s: 0.0,
            impacts: 0,
            failure: None,
        };
        t.seed();
        t
    }

    /// Unit vector along [`SEED`], on the constraint of the current mode.
    fn seed(&mut self) {
        let wt = self.wt;
        self.dx = std::array::from_fn(|i| SEED[i] / wt[i]);
        if !self.w.box_mass.is_finite() {
            self.dx[0] = 0.0;
            self.dx[1] = 0.0;
        }
        self.constrain();
        let n = scaled_norm(&self.dx, &self.wt);
        if n > 0.0 {
            self.dx.iter_mut().for_each(|x| *x /= n);
        }
    }

    /// Impose the mode's constraint on the particle's components.
    fn constrain(&mut self) {
        match self.mode {
            Mode::Flight => {}
            Mode::Floor | Mode::Ceiling | Mode::Clamped => {
                self.dx[2] = self.dx[0];
                self.dx[3] = self.dx[1];
            }
            Mode::Free => {
                self.dx[2] = 0.0;
                self.dx[3] = 0.0;
            }
        }
    }

    /// Exact linear flow from `self.t` to `t1` in the current mode.
    fn propagate(&mut self, t1: f64) {
        let tau = t1 - self.t;
        if tau != 0.0 {
            let motion = if self.mode.stuck() {
                self.w.loaded
            } else {
                self.w.free
            };
            if let BoxMotion::Spring(sd) = motion {
                let (dz, dv) = box_flow(&sd, tau, self.dx[0], self.dx[1]);
                self.dx[0] = dz;
                self.dx[1] = dv;
            }
            if self.mode == Mode::Flight {
                self.dx[2] += self.dx[3] * tau;
            }
            self.constrain();
        }
        self.t = t1;
    }

    /// Renormalise at kT and book ln of the growth over the period ending there.
    fn renormalise(&mut self, k: u64) {
        let n = scaled_norm(&self.dx, &self.wt);
        if !n.is_finite() {
            self.failure.get_or_insert(SimError::Unstable {
                t_s: self.t,
                reason: "the tangent vector of the Lyapunov exponent overflowed (an impact at a \
                         vanishing approach speed: grazing)"
                    .into(),
            });
            self.dx = [0.0; 4];
            return;
        }
        if k > self.k0 && k <= self.k_end {
            self.logs.push(n.ln());
        }
        if n > 0.0 {
            self.dx.iter_mut().for_each(|x| *x /= n);
        } else if k <= self.k0 {
            // collapsed during the transient (a kinematic ball locked): start afresh
            self.seed();
        }
    }

    /// Renormalisation times up to `t` (with a rounding allowance of 1e-9 T when `slack`).
    fn strobe_until(&mut self, t: f64, slack: bool) {
        let allow = if slack { 1e-9 * self.w.period } else { 0.0 };
        while self.next_k <= self.k_end && self.next_k as f64 * self.w.period <= t + allow {
            let tk = self.next_k as f64 * self.w.period;
            self.propagate(tk);
            self.renormalise(self.next_k);
            self.next_k += 1;
        }
    }

    /// The last renormalisation times, which rounding may put just past the run's end.
    fn finish(&mut self) {
        let t = self.t.max(self.w.duration);
        self.strobe_until(t, true);
    }

    fn in_window(&self, t: f64) -> bool {
        let p = self.w.period;
        t >= self.k0 as f64 * p && t < self.k_end as f64 * p
    }

    /// Saltation matrix of `event` applied to δx at `before.t`.
    fn saltation(&mut self, b: &State, a: &State, event: Event) {
        let w = self.w;
        let Some(p) = w.particle else { return };
        let g = w.g;
        let d = self.dx;
        match event {
            Event::None => {}
            Event::Detach => {
                // h_d = ±(z''_loaded + g) (2.1.27); ∇h_d = ±(−K, −C, 0, 0)/(M + m_p),
                // ḣ_d = ±(loaded jerk); f⁺ − f⁻ = (0, z''_free − z''_loaded, 0, −g − z''_loaded),
                // which vanishes at the root (contact force zero). A kinematic box has no box
                // components: ∇h_d · δx = 0.
                if let (BoxMotion::Spring(ld), BoxMotion::Spring(_)) = (w.loaded, w.free) {
                    let al = ld.accel(b.t, b.z, b.v);
                    let af = w.free.accel(b.t, b.z, b.v);
                    let hdot = ld.jerk(b.t, b.v, al);
                    let grad = -(ld.stiffness * d[0] + ld.damping * d[1]) / ld.mass;
                    if hdot.is_finite() && hdot != 0.0 {
                        let q = grad / hdot;
                        self.dx[1] += (af - al) * q;
                        self.dx[3] += (-g - al) * q;
                    }
                }
            }
            Event::HitFloor | Event::HitCeiling => {
                let floor = event == Event::HitFloor;
                let approach = if floor { b.v - b.w } else { b.w - b.v };
                // the plastic law (e = 0) gives bitwise equal velocities: the chattering cut
                let plastic = a.w == a.v;
                let e = if plastic { 0.0 } else { p.e };
                let jg = |vz: f64, vp: f64| {
                    let r = collide(w.box_mass, p.mass, e, vz, vp);
                    (r.box_v_m_s, r.particle_v_m_s)
                };
                if approach <= 0.0 {
                    // contact at the very start of a flight, no collision: the cut only
                    // projects onto the constraint (box position kept, momentum velocity)
                    if plastic {
                        let (dv, dw) = jg(d[1], d[3]);
                        self.dx = [d[0], dv, d[0], dw];
                    }
                    return;
                }
                if self.in_window(b.t) {
                    self.impacts += 1;
                }
                // f⁻: flight field before; J_g f⁻; f⁺: flight or stuck field after
                let fm = [b.v, w.free.accel(b.t, b.z, b.v), b.w, -g];
                let (jv, jw) = jg(fm[1], fm[3]);
                let jfm = [fm[0], jv, fm[2], jw];
                let fp = if a.mode.stuck() {
                    let al = w.loaded.accel(a.t, a.z, a.v);
                    [a.v, al, a.v, al]
                } else {
                    [a.v, w.free.accel(a.t, a.z, a.v), a.w, -g]
                };
                // ∇h · δx and ∇h · f⁻ (= −approach < 0)
                let (grad_dx, grad_f) = if floor {
                    (d[2] - d[0], b.w - b.v)
                } else {
                    (d[0] - d[2], b.v - b.w)
                };
                let q = grad_dx / grad_f;
                let (dv, dw) = jg(d[1], d[3]);
                let jd = [d[0], dv, d[2], dw];
                self.dx = std::array::from_fn(|i| jd[i] + (fp[i] - jfm[i]) * q);
            }
        }
    }
}

impl SegmentHook for Tangent<'_> {
    fn flow(&mut self, from: &State, to: &State) {
        if from.mode.stuck() {
            let p = self.w.period;
            let lo = from.t.max(self.k0 as f64 * p);
            let hi = to.t.min(self.k_end as f64 * p);
            if hi > lo {
                self.stuck_s += hi - lo;
            }
        }
        self.strobe_until(to.t, false);
    }

    fn event(&mut self, before: &State, after: &State, event: Event) {
        self.strobe_until(before.t, false);
        self.propagate(before.t);
        self.saltation(before, after, event);
        self.mode = after.mode;
        self.constrain();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn impact_lyapunov_plastic_law_gives_bitwise_equal_velocities() {
        // the tangent code recognises the chattering cut by a.w == a.v: collide(e = 0) must
        // return bitwise equal velocities (a regular impact with e > 0 never does unless its
        // separation rounds to zero, when the model cuts it too)
        for (vz, vp) in [(0.3, -1.7), (1e-3, 2.2e-3), (-0.41, 0.123_456_789)] {
            let r = collide(2.37, 0.227, 0.0, vz, vp);
            assert_eq!(r.box_v_m_s.to_bits(), r.particle_v_m_s.to_bits());
            let r = collide(f64::INFINITY, 0.227, 0.0, vz, vp);
            assert_eq!(r.box_v_m_s.to_bits(), r.particle_v_m_s.to_bits());
        }
    }

    #[test]
    fn impact_lyapunov_box_flow_matches_the_closed_form() {
        // the flow Jacobian applied to (δz, δz') equals the difference of two exact solutions
        // (linear ODE: exact to rounding, 1e-12 relative)
        let sd = Sdof::new(2.37, 21500.0, 7.6, 0.0045, 60.0, -2.2);
        let (t0, tau) = (0.3, 0.0123);
        let (dz, dv) = (1e-4, -2e-3);
        let a0 = sd.anchor(t0, 0.001, 0.02);
        let a1 = sd.anchor(t0, 0.001 + dz, 0.02 + dv);
        let (z0, v0) = sd.eval(&a0, t0 + tau);
        let (z1, v1) = sd.eval(&a1, t0 + tau);
        let (fz, fv) = box_flow(&sd, tau, dz, dv);
        assert!(((z1 - z0) - fz).abs() < 1e-12 * dz.abs().max(fz.abs()) * 10.0);
        assert!(((v1 - v0) - fv).abs() < 1e-11 * fv.abs().max(dv.abs()) * 10.0);
    }
}
