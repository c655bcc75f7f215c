//! [`ImpactWorld`]: the event-driven model built from a resolved setup (time scales, the free
//! and loaded box motions, the initial state), its energy and its run summary.

use crate::error::SimError;
use crate::model::primary::base_motion;
use crate::model::{EnergyTotals, RunOptions, RunSummary, Sdof, StrobePoint};
use crate::observe::Observer;

use super::ledger::Ledger;
use super::model::{ImpactSetup, Mode, Particle, State};
use super::motion::BoxMotion;

/// An impact-damper (or primary-only, or bouncing-ball) simulation built from a scene.
#[derive(Debug, Clone)]
pub struct ImpactWorld {
    pub(super) g: f64,
    pub(super) omega: f64,
    pub(super) u_amp: f64,
    pub(super) period: f64,
    /// Box mass M (kg); infinite for a kinematic box.
    pub(super) box_mass: f64,
    pub(super) k: f64,
    pub(super) c: f64,
    pub(super) free: BoxMotion,
    pub(super) loaded: BoxMotion,
    pub(super) particle: Option<Particle>,
    pub(super) step: f64,
    /// Step when the homogeneous (transient) part is negligible: T/16.
    pub(super) slow_step: f64,
    /// Homogeneous amplitude below which it is negligible (m).
    pub(super) negligible: f64,
    pub(super) h_star: f64,
    pub(super) duration: f64,
    pub(super) steady_start: f64,
    /// First stroboscopic time (s): the start of the analysis window.
    pub(super) strobe_start: f64,
    pub(super) init: State,
    pub(super) reference_amplitude: Option<f64>,
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
                let mut free = Sdof::new(m, k, c, u_amp, omega, 0.0);
                let mut loaded = Sdof::new(m + mp, k, c, u_amp, omega, -mp * g);
                if setup.drive.force_n != 0.0 {
                    free = free.with_force(setup.drive.force_n);
                    loaded = loaded.with_force(setup.drive.force_n);
                }
                let ts = free.time_scale().min(loaded.time_scale());
                let reference = setup.drive.reference_amplitude_m().unwrap_or(0.0);
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
    pub(super) fn initial_state(&self, setup: &ImpactSetup) -> State {
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
    pub(super) fn floor_holds(&self, t: f64, z: f64, v: f64) -> bool {
        self.loaded.accel(t, z, v) + self.g >= 0.0
    }

    /// Sticking condition on the ceiling (2.1.27): z'' + g ≤ 0 with the loaded system.
    #[inline]
    pub(super) fn ceiling_holds(&self, t: f64, z: f64, v: f64) -> bool {
        self.loaded.accel(t, z, v) + self.g <= 0.0
    }

    /// Forcing period T (s).
    pub fn period_s(&self) -> f64 {
        self.period
    }

    /// Mechanical energy ½Mz'² + ½K(z − u)² + ½m_p w² + m_p g y (J); particle only for a
    /// kinematic box.
    pub(super) fn mechanical_energy(&self, st: &State) -> f64 {
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

    pub(super) fn summarize(
        &self,
        st: &State,
        e0: f64,
        led: &Ledger,
        strobe: Vec<StrobePoint>,
    ) -> RunSummary {
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
            dem: None,
            warnings: Vec::new(),
            strobe,
            analysis: None,
            analysis_error: None,
            replica: None,
            decay: None,
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
