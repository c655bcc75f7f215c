//! Event-driven one-particle impact damper (SPEC §3), the primary alone (SPEC §1) and the
//! bouncing ball on a kinematically driven table.
//!
//! # How it works
//! Time advances segment by segment; within a segment nothing discontinuous happens, so the
//! state is known exactly in closed form ([`crate::model::Sdof`]: the primary's linear ODE with
//! harmonic forcing; the particle flies ballistically). Each segment is at most a fraction
//! (1/16) of the fastest time scale (forcing period, natural period, fastest decay), and within
//! it:
//! 1. the event functions are checked at the segment end and for an interior extremum
//!    ([`events::first_crossing`]): in flight the floor gap y − z and the ceiling gap
//!    z + gap − y; while the particle rests on the floor the sticking condition z'' + g ≥ 0,
//!    pressed to the ceiling z'' + g ≤ 0 (2.1.27); the first event is located by Brent's method
//!    to ~1e-13 s;
//! 2. samples and stroboscopic points falling inside the segment are evaluated exactly from the
//!    closed forms;
//! 3. the base work and the viscous loss are integrated by 8-point Gauss–Legendre quadrature of
//!    the closed forms (exact to rounding at this segment length);
//! 4. the event is applied: an impact ([`collision::collide`], (2.1.25)–(2.1.26), loss (5.3.1)),
//!    the start of a sticking phase (box and particle move together, mass M + m_p, the weight
//!    m_p g loads the primary) or a detachment.
//!
//! Chattering (infinitely many impacts in finite time as e < 1 settles the particle) is cut:
//! when the separation speed after an impact is below s* = sqrt(2 g_eff h*), with
//! h* = 1e-11 × the length scale of the problem (an apex far below anything resolvable), the
//! remaining relative motion is removed by a plastic impact (its kinetic energy, ½ μ s², is
//! booked as impact loss) and the particle sticks if (2.1.27) allows it. Stalled event sequences
//! (no time progress) are detected and resolved, so a run always ends.
//!
//! [`lyapunov`] computes the largest Lyapunov exponent of the stroboscopic map from the model's
//! own equations (tangent dynamics with saltation matrices, riding on the same segment loop
//! through a hook; and two diverging copies of the model as a cross-check).

pub mod collision;
pub mod events;
pub mod lyapunov;

use crate::error::SimError;
use crate::model::primary::base_motion;
use crate::model::{
    Anchor, BoxDrive, EnergyTotals, RunOptions, RunSummary, RunWindow, Sdof, StrobePoint,
};
use crate::observe::{ModelSample, Observer, Sample, SampleKind, StrobeCollector, Tee};
use collision::collide;
use events::{first_crossing, time_tolerance};
use std::collections::BTreeMap;

pub use lyapunov::{LyapunovMethod, ModelLyapunov, ModelLyapunovOptions};

/// The one effective particle of the impact damper (SPEC §3), resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactParticle {
    /// Effective particle mass m_p (kg), > 0.
    pub mass_kg: f64,
    /// Free travel between floor and ceiling (m), ≥ 0; `inf`: no ceiling; 0: clamped.
    pub gap_m: f64,
    /// Effective coefficient of restitution e (–), 0 ≤ e ≤ 1 (2.1.23).
    pub restitution: f64,
    /// Initial height above the floor (m), 0 ≤ h ≤ gap.
    pub initial_height_m: f64,
    /// Initial velocity in the lab frame (m/s).
    pub initial_velocity_m_s: f64,
}

/// Everything the event-driven model needs, resolved and validated by [`crate::setup`]:
/// gravity, the box drive (primary + base motion, or a kinematic box), the particle (none:
/// the primary alone), the initial box state and the run's windows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactSetup {
    /// Gravitational acceleration g (m/s², along −z), ≥ 0.
    pub gravity_m_s2: f64,
    /// The box drive; `primary = None` moves the box with the base (bouncing ball).
    pub drive: BoxDrive,
    /// The particle, or `None` for the primary alone.
    pub particle: Option<ImpactParticle>,
    /// Initial displacement z(0) (m); `None`: static equilibrium with a resting particle.
    pub initial_box_z_m: Option<f64>,
    /// Initial velocity z'(0) (m/s); `None`: 0.
    pub initial_box_v_m_s: Option<f64>,
    /// Duration, steady-state and analysis windows (s).
    pub window: RunWindow,
}

/// Where the particle is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// No particle (primary alone).
    Free,
    /// Particle in flight between floor and ceiling.
    Flight,
    /// Particle resting on the floor, moving with the box.
    Floor,
    /// Particle pressed against the ceiling, moving with the box.
    Ceiling,
    /// Zero gap: the particle is clamped to the box for good.
    Clamped,
}

impl Mode {
    /// Code written in the `contact` column: 0 flight (or no particle), 1 floor, 2 ceiling,
    /// 3 clamped.
    pub fn code(self) -> f64 {
        match self {
            Mode::Free | Mode::Flight => 0.0,
            Mode::Floor => 1.0,
            Mode::Ceiling => 2.0,
            Mode::Clamped => 3.0,
        }
    }
    fn stuck(self) -> bool {
        matches!(self, Mode::Floor | Mode::Ceiling | Mode::Clamped)
    }
}

/// Motion of the box: on the primary's spring (closed form) or imposed (= base motion).
#[derive(Debug, Clone, Copy)]
enum BoxMotion {
    Spring(Sdof),
    Kinematic { u_amp: f64, omega: f64 },
}

impl BoxMotion {
    #[inline]
    fn anchor(&self, t: f64, z: f64, v: f64) -> Anchor {
        match self {
            BoxMotion::Spring(s) => s.anchor(t, z, v),
            BoxMotion::Kinematic { .. } => Anchor {
                t0_s: t,
                y0: 0.0,
                w0: 0.0,
            },
        }
    }
    #[inline]
    fn eval(&self, an: &Anchor, t: f64) -> (f64, f64) {
        match self {
            BoxMotion::Spring(s) => s.eval(an, t),
            BoxMotion::Kinematic { u_amp, omega } => {
                let (u, du, _) = base_motion(*u_amp, *omega, t);
                (u, du)
            }
        }
    }
    #[inline]
    fn accel(&self, t: f64, z: f64, v: f64) -> f64 {
        match self {
            BoxMotion::Spring(s) => s.accel(t, z, v),
            BoxMotion::Kinematic { u_amp, omega } => base_motion(*u_amp, *omega, t).2,
        }
    }
    #[inline]
    fn jerk(&self, t: f64, v: f64, acc: f64) -> f64 {
        match self {
            BoxMotion::Spring(s) => s.jerk(t, v, acc),
            BoxMotion::Kinematic { u_amp, omega } => {
                let (s, _) = (omega * t).sin_cos();
                u_amp * omega * omega * omega * s
            }
        }
    }
}

/// The particle's parameters (SPEC §3).
#[derive(Debug, Clone, Copy)]
struct Particle {
    mass: f64,
    gap: f64,
    e: f64,
}

impl From<ImpactParticle> for Particle {
    fn from(p: ImpactParticle) -> Particle {
        Particle {
            mass: p.mass_kg,
            gap: p.gap_m,
            e: p.restitution,
        }
    }
}

/// Dynamic state.
#[derive(Debug, Clone, Copy)]
struct State {
    t: f64,
    z: f64,
    v: f64,
    y: f64,
    w: f64,
    mode: Mode,
    /// Wall just left (the event root at the segment start is ignored): 1 floor, 2 ceiling.
    departing: u8,
}

/// One closed-form segment [t, b] of the box motion, as the event search sees it.
struct Segment<'a> {
    motion: &'a BoxMotion,
    an: &'a Anchor,
    /// End of the segment (s).
    b: f64,
    /// Box state (z, z') at `b`.
    end: (f64, f64),
    /// (sin Ωt, cos Ωt) at the start and at `b`, for a spring-mounted box.
    phases: Option<((f64, f64), (f64, f64))>,
    /// The node cache's segment length h and homogeneous basis at τ = h.
    end_basis: Option<(f64, (f64, f64))>,
    /// (sin Ωb, cos Ωb) evaluated exactly by the event search, if it did (the next
    /// segment's start phase when the segment ends at `b`).
    exact_end_phase: std::cell::Cell<Option<(f64, f64)>>,
}

/// Which event ended a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    None,
    HitFloor,
    HitCeiling,
    Detach,
}

/// Receives the exact trajectory segment by segment and event by event ([`lyapunov`]'s tangent
/// dynamics and two-trajectory estimate); a plain run uses [`NoHook`].
trait SegmentHook {
    /// The state moved from `from` to `to` along one closed-form segment (mode `from.mode`,
    /// no event inside).
    fn flow(&mut self, _from: &State, _to: &State) {}
    /// An event was applied at `before.t`, turning `before` into `after`.
    fn event(&mut self, _before: &State, _after: &State, _event: Event) {}
}

/// The hook of a plain run: does nothing.
struct NoHook;

impl SegmentHook for NoHook {}

/// Compensated (Kahan–Babuška) sum, so that 1e6 forcing periods do not drift.
#[derive(Debug, Clone, Copy, Default)]
struct Sum {
    s: f64,
    c: f64,
}

impl Sum {
    #[inline]
    fn add(&mut self, x: f64) {
        let t = self.s + x;
        if self.s.abs() >= x.abs() {
            self.c += (self.s - t) + x;
        } else {
            self.c += (x - t) + self.s;
        }
        self.s = t;
    }
    fn value(&self) -> f64 {
        self.s + self.c
    }
}

/// 8-point Gauss–Legendre nodes on [−1, 1] and weights.
const GL_X: [f64; 8] = [
    -0.960_289_856_497_536_2,
    -0.796_666_477_413_626_7,
    -0.525_532_409_916_329,
    -0.183_434_642_495_649_8,
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_2,
];
const GL_W: [f64; 8] = [
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
struct NodeCache {
    h: f64,
    loaded: bool,
    /// (sin Ωτ, cos Ωτ) at the 8 nodes and at τ = h.
    sc: [(f64, f64); 9],
    /// Homogeneous basis at the 8 nodes and at τ = h.
    basis: [(f64, f64); 9],
    /// The 8-point Gauss–Legendre sums of the base work and of the viscous loss over the
    /// segment as quadratic forms of X = (y0, w0, sin Ωt, cos Ωt, 1) (the anchor's homogeneous
    /// part and the phase at the segment start): every node value is linear in X, so the
    /// quadrature is X^T Q X with Q summed once per cache (25 products per segment instead of
    /// the closed forms at 8 nodes).
    q_work: [[f64; 5]; 5],
    q_visc: [[f64; 5]; 5],
}

impl NodeCache {
    fn empty() -> Self {
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
    fn prepare(&mut self, sd: &Sdof, omega: f64, h: f64, loaded: bool) {
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
        }
    }

    /// X^T Q X for the segment start's X = (y0, w0, sin Ωt, cos Ωt, 1).
    #[inline]
    fn form(q: &[[f64; 5]; 5], x: &[f64; 5]) -> f64 {
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
struct NodeCaches {
    slots: [NodeCache; 4],
    /// Slot refilled next when no slot matches (round robin).
    next: usize,
}

impl NodeCaches {
    fn empty() -> Self {
        NodeCaches {
            slots: [NodeCache::empty(); 4],
            next: 0,
        }
    }

    /// The cache of segment length `h` and mode `loaded`, filled if no slot holds it.
    fn get(&mut self, sd: &Sdof, omega: f64, h: f64, loaded: bool) -> &NodeCache {
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

/// (sin(A + B), cos(A + B)) from (sin A, cos A) and (sin B, cos B).
#[inline]
fn rotate(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.1 + a.1 * b.0, a.1 * b.1 - a.0 * b.0)
}

/// An impact-damper (or primary-only, or bouncing-ball) simulation built from a scene.
#[derive(Debug, Clone)]
pub struct ImpactWorld {
    g: f64,
    omega: f64,
    u_amp: f64,
    period: f64,
    /// Box mass M (kg); infinite for a kinematic box.
    box_mass: f64,
    k: f64,
    c: f64,
    free: BoxMotion,
    loaded: BoxMotion,
    particle: Option<Particle>,
    step: f64,
    /// Step when the homogeneous (transient) part is negligible: T/16.
    slow_step: f64,
    /// Homogeneous amplitude below which it is negligible (m).
    negligible: f64,
    h_star: f64,
    duration: f64,
    steady_start: f64,
    /// First stroboscopic time (s): the start of the analysis window.
    strobe_start: f64,
    init: State,
    reference_amplitude: Option<f64>,
}

/// Accumulators of a run.
#[derive(Debug, Default)]
struct Ledger {
    base_work: Sum,
    viscous: Sum,
    impact: Sum,
    steady_base: Sum,
    steady_viscous: Sum,
    steady_impact: Sum,
    impacts: u64,
    steady_impacts: u64,
    events: u64,
    zmax: f64,
    zmin: f64,
}

impl ImpactWorld {
    /// Build the simulation of a resolved impact setup (see [`crate::setup`]; the setup is
    /// already validated, so this cannot fail).
    pub fn new(setup: &ImpactSetup) -> ImpactWorld {
        let particle = setup.particle.map(Particle::from);
        let g = setup.gravity_m_s2;
        let omega = setup.drive.omega_rad_s();
        let u_amp = setup.drive.amplitude_m;
        let period = setup.drive.period_s();
        let mp = particle.map_or(0.0, |p| p.mass);
        let (free, loaded, box_mass, k, c, mut ts, reference) = match &setup.drive.primary {
            Some(p) => {
                let (m, k, c) = (p.mass_kg, p.stiffness_n_m, p.damping_n_s_m);
                let free = Sdof::new(m, k, c, u_amp, omega, 0.0);
                let loaded = Sdof::new(m + mp, k, c, u_amp, omega, -mp * g);
                let ts = free.time_scale().min(loaded.time_scale());
                let reference = p.steady_amplitude_m(u_amp, omega);
                (
                    BoxMotion::Spring(free),
                    BoxMotion::Spring(loaded),
                    m,
                    k,
                    c,
                    ts,
                    Some(reference),
                )
            }
            None => {
                let kin = BoxMotion::Kinematic { u_amp, omega };
                (kin, kin, f64::INFINITY, 0.0, 0.0, period, None)
            }
        };
        ts = ts.min(period);
        let static_defl = match &setup.drive.primary {
            Some(p) => mp * g / p.stiffness_n_m,
            None => 0.0,
        };
        let length = u_amp.max(static_defl).max(1e-6);
        let duration = setup.window.duration_s;
        let mut world = ImpactWorld {
            g,
            omega,
            u_amp,
            period,
            box_mass,
            k,
            c,
            free,
            loaded,
            particle,
            step: ts / 16.0,
            slow_step: period / 16.0,
            negligible: 1e-13 * length.max(reference.unwrap_or(0.0)),
            h_star: 1e-11 * length,
            duration,
            steady_start: setup.window.steady_start_s,
            strobe_start: setup.window.analysis_start_s,
            init: State {
                t: 0.0,
                z: 0.0,
                v: 0.0,
                y: 0.0,
                w: 0.0,
                mode: Mode::Free,
                departing: 0,
            },
            reference_amplitude: reference,
        };
        world.init = world.initial_state(setup);
        world
    }

    /// Initial state: box at the static equilibrium with the particle resting on the floor
    /// (z = −m_p g/K) unless the setup says otherwise; kinematic box at u(0).
    fn initial_state(&self, setup: &ImpactSetup) -> State {
        let (h0, w0) = setup
            .particle
            .map_or((0.0, 0.0), |p| (p.initial_height_m, p.initial_velocity_m_s));
        let resting = h0 == 0.0 && w0 == 0.0;
        let (z0, v0) = match &setup.drive.primary {
            Some(p) => {
                let mp = self.particle.map_or(0.0, |q| q.mass);
                let zdef = if resting {
                    -mp * self.g / p.stiffness_n_m
                } else {
                    0.0
                };
                (
                    setup.initial_box_z_m.unwrap_or(zdef),
                    setup.initial_box_v_m_s.unwrap_or(0.0),
                )
            }
            None => {
                let (u, du, _) = base_motion(self.u_amp, self.omega, 0.0);
                (u, du)
            }
        };
        let mut st = State {
            t: 0.0,
            z: z0,
            v: v0,
            y: z0 + h0,
            w: w0,
            mode: Mode::Free,
            departing: 0,
        };
        if let Some(p) = self.particle {
            st.mode = if p.gap == 0.0 {
                st.y = z0;
                st.w = v0;
                Mode::Clamped
            } else if h0 == 0.0 && w0 == v0 && self.floor_holds(0.0, z0, v0) {
                Mode::Floor
            } else {
                if h0 == 0.0 {
                    st.departing = 1;
                } else if h0 == p.gap {
                    st.departing = 2;
                }
                Mode::Flight
            };
        } else {
            st.y = z0;
            st.w = v0;
        }
        st
    }

    /// Sticking condition on the floor (2.1.27): z'' + g ≥ 0 with the loaded system.
    #[inline]
    fn floor_holds(&self, t: f64, z: f64, v: f64) -> bool {
        self.loaded.accel(t, z, v) + self.g >= 0.0
    }

    /// Sticking condition on the ceiling (2.1.27): z'' + g ≤ 0 with the loaded system.
    #[inline]
    fn ceiling_holds(&self, t: f64, z: f64, v: f64) -> bool {
        self.loaded.accel(t, z, v) + self.g <= 0.0
    }

    /// Forcing period T (s).
    pub fn period_s(&self) -> f64 {
        self.period
    }

    /// Run the simulation, sending samples to `obs`.
    ///
    /// # Errors
    /// [`SimError::Unstable`] if the state becomes non-finite or the event sequence stalls;
    /// [`SimError::Output`] if the observer fails.
    pub fn run(&self, obs: &mut dyn Observer, opts: &RunOptions) -> Result<RunSummary, SimError> {
        self.run_hooked(obs, opts, &mut NoHook)
    }

    /// [`ImpactWorld::run`], reporting every segment and event to `hook`.
    fn run_hooked<H: SegmentHook>(
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
                obs.progress(st.t, self.duration);
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
        obs.progress(self.duration, self.duration);
        obs.finish()?;
        drop(tee);
        Ok(self.summarize(&st, e0, &led, strobe.points))
    }

    /// Segment length: a sixteenth of the fastest time scale, or of the forcing period once
    /// the homogeneous (transient) part of the box motion is negligible (amplitude below
    /// 1e-13 of the motion's scale, or below the rounding floor 640 ε Ω t of the forcing
    /// phase, whichever is larger): it then neither moves the event functions nor the
    /// quadrature at any resolvable level, and the particular solution only varies at the
    /// forcing frequency.
    #[inline]
    fn step_for(&self, motion: &BoxMotion, an: &Anchor) -> f64 {
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
    fn find_event(&self, st: &State, seg: &Segment) -> (f64, Event) {
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
    fn apply_event(&self, st: &mut State, event: Event, led: &mut Ledger) {
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

    /// Particle position at time t given the box position z (particle attached or ballistic).
    #[inline]
    fn particle_position(&self, st: &State, z: f64, t: f64) -> f64 {
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
    fn emit(
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

    /// Gauss–Legendre quadrature of the base work and viscous loss on [a, b].
    fn integrate(&self, led: &mut Ledger, motion: &BoxMotion, an: &Anchor, a: f64, b: f64) {
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
    fn integrate_cached(
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
    fn track_extrema(
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

    /// Mechanical energy ½Mz'² + ½K(z − u)² + ½m_p w² + m_p g y (J); particle only for a
    /// kinematic box.
    fn mechanical_energy(&self, st: &State) -> f64 {
        let (u, _, _) = base_motion(self.u_amp, self.omega, st.t);
        let mut e = 0.0;
        if self.box_mass.is_finite() {
            e += 0.5 * self.box_mass * st.v * st.v + 0.5 * self.k * (st.z - u) * (st.z - u);
        }
        if let Some(p) = self.particle {
            e += 0.5 * p.mass * st.w * st.w + p.mass * self.g * st.y;
        }
        e
    }

    fn summarize(&self, st: &State, e0: f64, led: &Ledger, strobe: Vec<StrobePoint>) -> RunSummary {
        let cycles = (self.duration - self.steady_start) / self.period;
        let totals = EnergyTotals {
            base_work_j: led.base_work.value(),
            viscous_j: led.viscous.value(),
            impact_j: led.impact.value(),
            initial_mechanical_j: e0,
            final_mechanical_j: self.mechanical_energy(st),
        };
        let kinematic = !self.box_mass.is_finite();
        let model = match (self.particle, kinematic) {
            (None, _) => "primary",
            (Some(_), false) => "impact",
            (Some(_), true) => "bouncing-ball",
        };
        let (zmax, zmin) = if led.zmax.is_finite() {
            (led.zmax, led.zmin)
        } else {
            (st.z, st.z)
        };
        RunSummary {
            model: model.into(),
            frequency_hz: 1.0 / self.period,
            duration_s: self.duration,
            steady_start_s: self.steady_start,
            cycles_steady: cycles,
            amplitude_m: 0.5 * (zmax - zmin),
            box_z_max_m: zmax,
            box_z_min_m: zmin,
            reference_amplitude_m: self.reference_amplitude,
            energy_input_j_per_cycle: led.steady_base.value() / cycles,
            energy_viscous_j_per_cycle: led.steady_viscous.value() / cycles,
            energy_impact_j_per_cycle: led.steady_impact.value() / cycles,
            impacts_per_cycle: led.steady_impacts as f64 / cycles,
            energy_balance_relative_error: (!kinematic).then(|| totals.relative_error()),
            energy_totals: totals,
            impacts_total: led.impacts,
            events_total: led.events,
            extra: BTreeMap::new(),
            strobe,
            analysis: None,
            analysis_error: None,
            replica: None,
        }
    }
}

/// Simulate a resolved impact setup (convenience wrapper of [`ImpactWorld`]).
///
/// # Errors
/// See [`ImpactWorld::run`].
pub fn simulate(
    setup: &ImpactSetup,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<RunSummary, SimError> {
    ImpactWorld::new(setup).run(obs, opts)
}
