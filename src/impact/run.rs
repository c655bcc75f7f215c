//! The event-driven run of an [`ImpactWorld`]: segment after segment, the samples and
//! stroboscopic points inside each, the ledger's integrals and the events.

use crate::error::SimError;
use crate::model::primary::base_motion;
use crate::model::{Anchor, RunOptions, RunSummary, StrobePoint};
use crate::observe::{ModelSample, Observer, Sample, SampleKind, StrobeCollector, Tee};

use super::events::time_tolerance;
use super::ledger::Ledger;
use super::model::{Mode, State};
use super::motion::{rotate, BoxMotion};
use super::quadrature::NodeCaches;
use super::segment::{Event, NoHook, Segment, SegmentHook};
use super::world::ImpactWorld;

impl ImpactWorld {
    /// Run the simulation, sending samples to `obs`.
    ///
    /// # Errors
    /// [`SimError::Unstable`] if the state becomes non-finite or the event sequence stalls;
    /// [`SimError::Output`] if the observer fails.
    pub fn run(&self, obs: &mut dyn Observer, opts: &RunOptions) -> Result<RunSummary, SimError> {
        self.run_hooked(obs, opts, &mut NoHook)
    }

    /// [`ImpactWorld::run`], reporting every segment and event to `hook`.
    pub(super) fn run_hooked<H: SegmentHook>(
        &self,
        obs: &mut dyn Observer,
        opts: &RunOptions,
        hook: &mut H,
    ) -> Result<RunSummary, SimError> {
        // the stroboscopic points go to the caller's observer and to the summary
        let mut strobe = StrobeCollector::default();
        let mut tee = Tee {
            observers: vec![obs, &mut strobe],
        };
        let obs: &mut dyn Observer = &mut tee;
        obs.start(if self.particle.is_some() {
            SampleKind::Impact
        } else {
            SampleKind::Primary
        })?;
        let mut st = self.init;
        let e0 = self.mechanical_energy(&st);
        let mut led = Ledger {
            zmax: f64::NEG_INFINITY,
            zmin: f64::INFINITY,
            ..Default::default()
        };
        // sample clock: times k·Δs ≥ sample_from_s
        let ds = opts.sample_interval_s.filter(|d| *d > 0.0);
        let mut k_sample: u64 = ds.map_or(u64::MAX, |d| {
            (opts.sample_from_s / d - 1e-9).ceil().max(0.0) as u64
        });
        let mut n_strobe: u64 = (self.strobe_start / self.period - 1e-9).ceil().max(0.0) as u64;
        let progress_every = (self.duration / 200.0).max(self.period);
        let mut next_progress = progress_every;
        let mut stall = 0u32;
        let mut caches = NodeCaches::empty();
        // (t, sin_cos(Ω t)) computed by the last segment's event search at its end
        let mut carried_phase: Option<(f64, (f64, f64))> = None;
        let max_events = 2_000_000u64 + (self.duration / self.period * 20_000.0) as u64;

        while st.t < self.duration {
            let forced_stick = stall > 64;
            let motion = if st.mode.stuck() {
                self.loaded
            } else {
                self.free
            };
            // (sin Ωt, cos Ωt) at the segment start: one sin_cos per segment serves the
            // anchor, the end state, the quadrature and the sticking condition
            let sc0 = match carried_phase.take() {
                Some((t, sc)) if t == st.t => sc,
                _ => (self.omega * st.t).sin_cos(),
            };
            let an = match &motion {
                BoxMotion::Spring(sd) => sd.anchor_parts(st.t, st.z, st.v, sc0),
                BoxMotion::Kinematic { .. } => motion.anchor(st.t, st.z, st.v),
            };
            // segment [t, b] of nominal length h (kept exact so that the node cache is reused;
            // b = t + h up to one rounding of t)
            let limit = if st.t < self.steady_start {
                self.steady_start.min(self.duration)
            } else {
                self.duration
            };
            let mut h = self.step_for(&motion, &an);
            let mut b = st.t + h;
            if b >= limit {
                b = limit;
                h = b - st.t;
            }
            // box state at b, through the node cache for spring-mounted boxes
            let (end, cached, cache) = match &motion {
                BoxMotion::Spring(sd) => {
                    let cache = caches.get(sd, self.omega, h, st.mode.stuck());
                    let sc_b = rotate(sc0, cache.sc[8]);
                    (
                        sd.eval_parts(&an, cache.basis[8], sc_b),
                        Some((sc0, sc_b)),
                        Some(cache),
                    )
                }
                BoxMotion::Kinematic { .. } => (motion.eval(&an, b), None, None),
            };
            let (te, event) = if forced_stick {
                (b.min(st.t + 1e-6 * self.period), Event::None)
            } else {
                let seg = Segment {
                    motion: &motion,
                    an: &an,
                    b,
                    end,
                    phases: cached,
                    end_basis: cache.map(|c| (c.h, c.basis[8])),
                    exact_end_phase: std::cell::Cell::new(None),
                };
                let found = self.find_event(&st, &seg);
                if found.0 == b {
                    carried_phase = seg.exact_end_phase.get().map(|sc| (b, sc));
                }
                found
            };
            // samples and strobe points in [t, te)
            while let Some(d) = ds {
                let ts = k_sample as f64 * d;
                if ts >= te || ts > self.duration {
                    break;
                }
                self.emit(obs, &st, &motion, &an, ts)?;
                k_sample += 1;
            }
            loop {
                let ts = n_strobe as f64 * self.period;
                if ts >= te || ts > self.duration {
                    break;
                }
                let (z, v) = motion.eval(&an, ts);
                let y = self.particle_position(&st, z, ts);
                let w = match st.mode {
                    Mode::Flight => st.w - self.g * (ts - st.t),
                    _ => v,
                };
                obs.strobe(&StrobePoint {
                    cycle: n_strobe,
                    time_s: ts,
                    grain_z_m: y,
                    box_z_m: z,
                    grain_v_m_s: w,
                    box_v_m_s: v,
                })?;
                n_strobe += 1;
            }
            // quadrature of base work and viscous loss, extrema of z
            let (zb, vb) = if te == b { end } else { motion.eval(&an, te) };
            if te > st.t {
                match (te == b, cached, cache, &motion) {
                    (true, Some((sc0, _)), Some(cache), BoxMotion::Spring(_)) => {
                        self.integrate_cached(&mut led, &an, cache, sc0, st.t)
                    }
                    _ => self.integrate(&mut led, &motion, &an, st.t, te),
                }
                if st.t >= self.steady_start {
                    self.track_extrema(&mut led, &motion, &an, &st, te, zb, vb);
                }
            }
            if !(zb.is_finite() && vb.is_finite()) {
                return Err(SimError::Unstable {
                    t_s: te,
                    reason: "non-finite box state".into(),
                });
            }
            // advance to te
            let progressed = te - st.t > 10.0 * time_tolerance(te);
            let from = st;
            let (y, w) = match st.mode {
                Mode::Flight => {
                    let tau = te - st.t;
                    (
                        st.y + st.w * tau - 0.5 * self.g * tau * tau,
                        st.w - self.g * tau,
                    )
                }
                _ => (self.particle_position(&st, zb, te), vb),
            };
            st = State {
                t: te,
                z: zb,
                v: vb,
                y,
                w,
                mode: st.mode,
                departing: if progressed { 0 } else { st.departing },
            };
            hook.flow(&from, &st);
            if forced_stick {
                stall = 0;
            }
            if event != Event::None {
                led.events += 1;
                if led.events > max_events {
                    return Err(SimError::Unstable {
                        t_s: st.t,
                        reason: format!(
                            "more than {max_events} events: the event sequence does not progress"
                        ),
                    });
                }
                stall = if progressed { 0 } else { stall + 1 };
                let before = st;
                self.apply_event(&mut st, event, &mut led);
                hook.event(&before, &st, event);
            }
            if st.t >= next_progress {
                obs.progress(st.t, self.duration)?;
                next_progress += progress_every;
            }
        }
        // the last sample at t = duration, if it falls on the clock
        if let Some(d) = ds {
            let ts = k_sample as f64 * d;
            if ts <= self.duration * (1.0 + 1e-12) && ts >= st.t - 1e-12 {
                let motion = if st.mode.stuck() {
                    self.loaded
                } else {
                    self.free
                };
                let an = motion.anchor(st.t, st.z, st.v);
                self.emit(obs, &st, &motion, &an, st.t)?;
            }
        }
        obs.progress(self.duration, self.duration)?;
        obs.finish()?;
        drop(tee);
        Ok(self.summarize(&st, e0, &led, strobe.points))
    }

    /// Particle position at time t given the box position z (particle attached or ballistic).
    #[inline]
    pub(super) fn particle_position(&self, st: &State, z: f64, t: f64) -> f64 {
        match st.mode {
            Mode::Flight => {
                let tau = t - st.t;
                st.y + st.w * tau - 0.5 * self.g * tau * tau
            }
            Mode::Ceiling => z + self.particle.map_or(0.0, |p| p.gap),
            _ => z,
        }
    }

    /// Send the sample at time t (inside the current segment).
    pub(super) fn emit(
        &self,
        obs: &mut dyn Observer,
        st: &State,
        motion: &BoxMotion,
        an: &Anchor,
        t: f64,
    ) -> Result<(), SimError> {
        let (z, v) = motion.eval(an, t);
        let (u, _, _) = base_motion(self.u_amp, self.omega, t);
        let gap = self.particle.map_or(0.0, |p| p.gap);
        let (y, w) = match st.mode {
            Mode::Flight => {
                let tau = t - st.t;
                (
                    st.y + st.w * tau - 0.5 * self.g * tau * tau,
                    st.w - self.g * tau,
                )
            }
            Mode::Ceiling => (z + gap, v),
            _ => (z, v),
        };
        let force = match (st.mode, self.particle) {
            (m, Some(p)) if m.stuck() => -p.mass * (motion.accel(t, z, v) + self.g),
            _ => 0.0,
        };
        let s = Sample {
            time_s: t,
            base_u_m: u,
            box_z_m: z,
            box_v_m_s: v,
            floor_z_m: z,
            ceiling_z_m: z + gap,
            grain_z_m: y,
            model: if self.particle.is_some() {
                ModelSample::Impact {
                    grain_v_m_s: w,
                    contact: st.mode.code(),
                }
            } else {
                ModelSample::Primary
            },
            grain_force_n: force,
        };
        obs.sample(&s)
    }
}
