//! One segment of the event-driven loop: its closed-form box motion, the event search inside
//! it ([`first_crossing`]), the step length, and the events applied (impacts,
//! sticking, detachment); the hook that sees every segment and event.

use crate::model::Anchor;

use super::collision::collide;
use super::events::first_crossing;
use super::ledger::Ledger;
use super::model::{Mode, State};
use super::motion::BoxMotion;
use super::world::ImpactWorld;

/// One closed-form segment [t, b] of the box motion, as the event search sees it.
pub(super) struct Segment<'a> {
    pub(super) motion: &'a BoxMotion,
    pub(super) an: &'a Anchor,
    /// End of the segment (s).
    pub(super) b: f64,
    /// Box state (z, z') at `b`.
    pub(super) end: (f64, f64),
    /// (sin Ωt, cos Ωt) at the start and at `b`, for a spring-mounted box.
    pub(super) phases: Option<((f64, f64), (f64, f64))>,
    /// The node cache's segment length h and homogeneous basis at τ = h.
    pub(super) end_basis: Option<(f64, (f64, f64))>,
    /// (sin Ωb, cos Ωb) evaluated exactly by the event search, if it did (the next
    /// segment's start phase when the segment ends at `b`).
    pub(super) exact_end_phase: std::cell::Cell<Option<(f64, f64)>>,
}

/// Which event ended a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Event {
    None,
    HitFloor,
    HitCeiling,
    Detach,
}

/// Receives the exact trajectory segment by segment and event by event ([`lyapunov`]'s tangent
/// dynamics and two-trajectory estimate); a plain run uses [`NoHook`].
pub(super) trait SegmentHook {
    /// The state moved from `from` to `to` along one closed-form segment (mode `from.mode`,
    /// no event inside).
    fn flow(&mut self, _from: &State, _to: &State) {}
    /// An event was applied at `before.t`, turning `before` into `after`.
    fn event(&mut self, _before: &State, _after: &State, _event: Event) {}
}

/// The hook of a plain run: does nothing.
pub(super) struct NoHook;

impl SegmentHook for NoHook {}

impl ImpactWorld {
    /// Segment length: a sixteenth of the fastest time scale, or of the forcing period once
    /// the homogeneous (transient) part of the box motion is negligible (amplitude below
    /// 1e-13 of the motion's scale, or below the rounding floor 640 ε Ω t of the forcing
    /// phase, whichever is larger): it then neither moves the event functions nor the
    /// quadrature at any resolvable level, and the particular solution only varies at the
    /// forcing frequency.
    #[inline]
    pub(super) fn step_for(&self, motion: &BoxMotion, an: &Anchor) -> f64 {
        match motion {
            BoxMotion::Spring(s) => {
                let w0 = (s.stiffness / s.mass).sqrt();
                let amp = an.y0.abs() + an.w0.abs() / w0;
                // the phase Ωt carries a rounding error ~ eps Ω t, which re-anchoring turns into
                // a homogeneous residue of that relative size: the floor grows with t
                let floor =
                    self.negligible * (1.0 + 640.0 * f64::EPSILON / 1e-13 * self.omega * an.t0_s);
                if amp < floor {
                    self.slow_step.max(self.step)
                } else {
                    self.step
                }
            }
            BoxMotion::Kinematic { .. } => self.step,
        }
    }

    /// First event in (st.t, b], or (b, None).
    pub(super) fn find_event(&self, st: &State, seg: &Segment) -> (f64, Event) {
        let (motion, an, b, end) = (seg.motion, seg.an, seg.b, seg.end);
        let Some(p) = self.particle else {
            return (b, Event::None);
        };
        match st.mode {
            Mode::Free | Mode::Clamped => (b, Event::None),
            Mode::Flight => {
                let (t0, y0, w0, g) = (st.t, st.y, st.w, self.g);
                let rel = |t: f64| {
                    let (z, v) = motion.eval(an, t);
                    let tau = t - t0;
                    (y0 + w0 * tau - 0.5 * g * tau * tau - z, w0 - g * tau - v)
                };
                let mut best = (b, Event::None);
                let mut floor = |t: f64| rel(t);
                let fa = if st.departing == 1 {
                    (0.0, st.w - st.v)
                } else {
                    (st.y - st.z, st.w - st.v)
                };
                let tau_b = b - t0;
                let (yb, wb) = (y0 + w0 * tau_b - 0.5 * g * tau_b * tau_b, w0 - g * tau_b);
                let fb = (yb - end.0, wb - end.1);
                if let Some(t) = first_crossing(&mut floor, st.t, b, fa, fb, st.departing == 1) {
                    best = (t, Event::HitFloor);
                }
                if p.gap.is_finite() {
                    let gap = p.gap;
                    let mut ceil = |t: f64| {
                        let (d, dd) = rel(t);
                        (gap - d, -dd)
                    };
                    let ca = if st.departing == 2 {
                        (0.0, st.v - st.w)
                    } else {
                        (gap - fa.0, -fa.1)
                    };
                    let cb = (gap - fb.0, -fb.1);
                    if let Some(t) = first_crossing(&mut ceil, st.t, b, ca, cb, st.departing == 2) {
                        if best.1 == Event::None || t < best.0 {
                            best = (t, Event::HitCeiling);
                        }
                    }
                }
                best
            }
            Mode::Floor | Mode::Ceiling => {
                let sign = if st.mode == Mode::Floor { 1.0 } else { -1.0 };
                let g = self.g;
                let mut f = |t: f64| {
                    let (z, v) = motion.eval(an, t);
                    let a = motion.accel(t, z, v);
                    (sign * (a + g), sign * motion.jerk(t, v, a))
                };
                // the start from the segment's known phase and state (no transcendental; the
                // same value as f(t)); the end freshly evaluated, as the event search sees it
                let fa = match (seg.phases, motion) {
                    (Some((sc0, _)), BoxMotion::Spring(sd)) => {
                        // eval(an, t0) = particular + the anchor's homogeneous part, exactly
                        let (zp, vp) = sd.particular_parts(sc0);
                        let (a, j) = sd.accel_jerk_parts(sc0, zp + an.y0, vp + an.w0);
                        (sign * (a + g), sign * j)
                    }
                    _ => f(st.t),
                };
                // f(b) with one sin_cos (and the cached basis when b − t0 = h): the same
                // expressions as eval, accel and jerk, so the same value
                let fb = match motion {
                    BoxMotion::Spring(sd) => {
                        let sc = (self.omega * b).sin_cos();
                        seg.exact_end_phase.set(Some(sc));
                        let tau = b - an.t0_s;
                        let basis = match seg.end_basis {
                            Some((h, basis)) if h == tau => basis,
                            _ => sd.homogeneous_basis(tau),
                        };
                        let (z, v) = sd.eval_parts(an, basis, sc);
                        let (a, j) = sd.accel_jerk_parts(sc, z, v);
                        (sign * (a + g), sign * j)
                    }
                    BoxMotion::Kinematic { .. } => f(b),
                };
                match first_crossing(&mut f, st.t, b, fa, fb, false) {
                    Some(t) => (t, Event::Detach),
                    None => (b, Event::None),
                }
            }
        }
    }

    /// Apply an impact, the start of sticking or a detachment at st.t.
    pub(super) fn apply_event(&self, st: &mut State, event: Event, led: &mut Ledger) {
        let Some(p) = self.particle else { return };
        let in_steady = st.t >= self.steady_start;
        match event {
            Event::None => {}
            Event::Detach => {
                st.departing = if st.mode == Mode::Floor { 1 } else { 2 };
                st.mode = Mode::Flight;
                st.w = st.v;
            }
            Event::HitFloor | Event::HitCeiling => {
                let floor = event == Event::HitFloor;
                st.y = if floor { st.z } else { st.z + p.gap };
                // approach speed (> 0 for a real impact; ≤ 0 only for a contact found at the
                // very start of a flight, which is then treated as the end of that flight)
                let approach = if floor { st.v - st.w } else { st.w - st.v };
                let mut loss = 0.0;
                if approach > 0.0 {
                    let r = collide(self.box_mass, p.mass, p.e, st.v, st.w);
                    loss = r.loss_j;
                    st.v = r.box_v_m_s;
                    st.w = r.particle_v_m_s;
                    led.impacts += 1;
                    if in_steady {
                        led.steady_impacts += 1;
                    }
                }
                // separation speed (≥ 0) and the chattering cut
                let s = if floor { st.w - st.v } else { st.v - st.w };
                let acc = self.free.accel(st.t, st.z, st.v);
                let g_eff = (self.g + acc)
                    .abs()
                    .max(self.g)
                    .max(self.omega * self.omega * self.u_amp)
                    .max(1e-12);
                let s_star = (2.0 * g_eff * self.h_star).sqrt();
                let mut mode = Mode::Flight;
                if s <= s_star {
                    let plastic = collide(self.box_mass, p.mass, 0.0, st.v, st.w);
                    loss += plastic.loss_j;
                    st.v = plastic.box_v_m_s;
                    st.w = plastic.particle_v_m_s;
                    let holds = if floor {
                        self.floor_holds(st.t, st.z, st.v)
                    } else {
                        self.ceiling_holds(st.t, st.z, st.v)
                    };
                    if holds {
                        mode = if floor { Mode::Floor } else { Mode::Ceiling };
                    }
                }
                led.impact.add(loss);
                if in_steady {
                    led.steady_impact.add(loss);
                }
                st.mode = mode;
                st.departing = if mode == Mode::Flight {
                    if floor {
                        1
                    } else {
                        2
                    }
                } else {
                    0
                };
            }
        }
    }
}
