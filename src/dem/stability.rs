//! Time step versus contact stiffness, and detection of unstable runs.

use crate::contact::linear_spring_dashpot::LinearContactParams;
use crate::contact::material::{Material, PairProperties};
use crate::contact::restitution::{hertz_contact_time, linear_contact_time};
use crate::contact::{NormalLaw, TangentialLaw};
use crate::error::{ModelError, Quantity, SimError};
use crate::units::{G, TWO_PI};

use super::model::{DemModel, Grains};
use super::world::{BoxDrive, DemWorld};

/// Default fraction of the contact duration used as time step with `dt = "auto"` (0.01,
/// the thesis's δt ≈ t_s/100): the one default of `run.dt_fraction` and of
/// [`super::DemRunConfig::dt_fraction`].
pub const DEFAULT_DT_FRACTION: f64 = 0.01;
/// Largest accepted explicit time step, as a fraction of the contact duration (1/20).
pub const MAX_DT_FRACTION: f64 = 1.0 / 20.0;
/// Largest time step, as a fraction of the viscous time scale [`viscous_time`], that the
/// automatic step takes and that an explicit step may have without a warning (1/4): the
/// energy ledger of scene B's bed then closes to well under 1 %.
pub const VISCOUS_DT_FRACTION: f64 = 0.25;
/// An explicit step longer than this many normal viscous times (m*/(γ_n √ζ_max), or m*/c_n)
/// is refused: explicit integration of an uncapped dashpot is unstable beyond 2.
pub const MAX_NORMAL_VISCOUS_DT: f64 = 1.0;

/// Viscous time scales (s) of the contacts at impact speed `v` (m/s): (normal, tangential).
///
/// Normal: m* / c_eff with c_eff = γ_n √ζ_max (Hertz–Kuwabara–Kono, ζ_max the Hertz overlap
/// at `v`: ½ m* v² = (8/15) E* √R* ζ_max^{5/2}) or c_n (linear). Tangential: m_t / c_t with
/// c_t = γ_s √ζ_max (or c_s) and m_t = (2/7) m* with rotations (a sphere's contact point
/// slides against its translational and rotational inertia), m* without. The shorter of
/// grain–grain and grain–wall contacts of the smallest grains. A dashpot integrated with a
/// step comparable to its time scale dissipates the wrong energy (the ledger misses it) and,
/// beyond twice it, turns unstable.
///
/// # Errors
/// [`ModelError`] when a linear law's restitution or yield strength is out of range.
pub fn viscous_time(model: &DemModel, v: f64) -> Result<(f64, f64), ModelError> {
    let grains: &Grains = &model.grains;
    let r = grains.r_min_m;
    let m = grains.density_kg_m3 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (g, w) = (grains.material, model.contact.wall.material);
    let pp = PairProperties::new(r, m, &g, r, m, &g);
    let pw = PairProperties::new(r, m, &g, f64::INFINITY, f64::INFINITY, &w);
    let m_t = |m_star: f64| {
        if model.rotations {
            2.0 / 7.0 * m_star
        } else {
            m_star
        }
    };
    let times = |wall: bool, p: &PairProperties| -> Result<(f64, f64), ModelError> {
        let (normal, tangential) = model.contact.laws(wall);
        let (c_n, c_t) = match normal {
            NormalLaw::HertzKuwabaraKono { gamma_n } => {
                let k_n = crate::contact::hertz_stiffness(p.e_star, p.r_star);
                let z_max = (1.25 * p.m_star * v * v / k_n).powf(0.4);
                let gamma_s = match tangential {
                    TangentialLaw::CoulombViscous { gamma_s, .. }
                    | TangentialLaw::MindlinSpring { gamma_s, .. } => gamma_s,
                    _ => 0.0,
                };
                (gamma_n * z_max.sqrt(), gamma_s * z_max.sqrt())
            }
            NormalLaw::LinearSpringDashpot {
                restitution,
                yield_strength,
            } => {
                let l = LinearContactParams::select(p, &g, yield_strength, restitution)?;
                let c_s = match tangential {
                    TangentialLaw::None => 0.0,
                    _ => l.c_s,
                };
                (l.c_n, c_s)
            }
        };
        let t = |m: f64, c: f64| if c > 0.0 { m / c } else { f64::INFINITY };
        Ok((t(p.m_star, c_n), t(m_t(p.m_star), c_t)))
    };
    let (a, b) = (times(false, &pp)?, times(true, &pw)?);
    Ok((a.0.min(b.0), a.1.min(b.1)))
}

/// The time step rule, all its scales at the design impact speed (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStepScales {
    /// Shortest Hertz (or linear) contact duration t_s (s).
    pub contact_time_s: f64,
    /// Normal viscous time m*/(γ_n √ζ_max) (s) (∞ without damping).
    pub normal_viscous_time_s: f64,
    /// Tangential viscous time m_t/(γ_s √ζ_max) (s) (∞ without).
    pub tangential_viscous_time_s: f64,
    /// Half period π/ω_max of a bean bag's fastest bond vibration (s) (∞ without a bag,
    /// [`crate::dem::bag::Bag::bond_time_s`]).
    pub bond_time_s: f64,
}

impl TimeStepScales {
    /// The scales of `model` on `drive`.
    ///
    /// # Errors
    /// As [`contact_time`].
    pub fn of(model: &DemModel, drive: &BoxDrive) -> Result<Self, ModelError> {
        let v = impact_speed(drive, model.box_size_m[2]);
        let (tn, tt) = viscous_time(model, v)?;
        Ok(TimeStepScales {
            contact_time_s: contact_time(model, v)?,
            normal_viscous_time_s: tn,
            tangential_viscous_time_s: tt,
            bond_time_s: model
                .bag
                .as_ref()
                .map_or(f64::INFINITY, |b| b.bond_time_s()),
        })
    }

    /// Longest step for a bag's bonds (s): [`BOND_DT_FRACTION`] × their half period, so that
    /// ω_max dt ≤ π/16 ≈ 0.2 (velocity Verlet's phase error (ω dt)²/24 ≤ 0.2 % per period of
    /// the fastest bond mode; a linear spring needs no finer step, unlike a contact's onset).
    pub fn bond_limit_s(&self) -> f64 {
        BOND_DT_FRACTION * self.bond_time_s
    }

    /// Shorter of the two viscous times (s).
    pub fn viscous_time_s(&self) -> f64 {
        self.normal_viscous_time_s
            .min(self.tangential_viscous_time_s)
    }

    /// Largest step the viscous rule allows without a warning (s).
    pub fn viscous_limit_s(&self) -> f64 {
        VISCOUS_DT_FRACTION * self.viscous_time_s()
    }

    /// A warning when `dt` (s) exceeds [`TimeStepScales::viscous_limit_s`], naming the
    /// scales; `None` otherwise.
    pub fn viscous_warning(&self, dt: f64) -> Option<String> {
        (dt > self.viscous_limit_s()).then(|| {
            format!(
                "the time step {dt:.3e} s is longer than {VISCOUS_DT_FRACTION} x the contacts' viscous time {:.3e} s (normal m*/(gamma_n sqrt(zeta)) = {:.3e} s, tangential m_t/(gamma_s sqrt(zeta)) = {:.3e} s): the dashpots are integrated too coarsely and the energy ledger will not close; use dt <= {:.3e} s (dt = auto does), or lower the damping",
                self.viscous_time_s(),
                self.normal_viscous_time_s,
                self.tangential_viscous_time_s,
                self.viscous_limit_s()
            )
        })
    }
}

/// Largest expected impact speed (m/s): v = max(2 A Ω, √(2 g Lz)) — twice the drive's peak
/// speed (grain and box moving against each other; A = U for a base drive, the primary's
/// forced amplitude F0/|K − MΩ² + iCΩ| when larger for a force drive) or a free fall over the
/// box height (the floor of a free decay's estimate).
pub fn impact_speed(drive: &BoxDrive, lz: f64) -> f64 {
    let mut a = drive.amplitude_m;
    if drive.force_n != 0.0 {
        a = a.max(drive.reference_amplitude_m().unwrap_or(0.0));
    }
    let v_base = 2.0 * a * TWO_PI * drive.frequency_hz;
    v_base.max((2.0 * G * lz).sqrt())
}

/// Shortest contact duration t_s (s) among grain–grain and grain–wall contacts of the
/// smallest grains at impact speed `v` (Hertz: 2.868 (m*²/(R* E*² v))^{1/5}, SPEC §9;
/// linear: π/√(k/m* − (c/2m*)²)), and a bean bag's film contacts (its bonds have their own
/// limit, [`TimeStepScales::bond_limit_s`]).
///
/// # Errors
/// [`ModelError`] when a linear law's restitution or yield strength is out of range.
pub fn contact_time(model: &DemModel, v: f64) -> Result<f64, ModelError> {
    let grains: &Grains = &model.grains;
    let r = grains.r_min_m;
    let m = grains.density_kg_m3 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (g, w) = (grains.material, model.contact.wall.material);
    let pp = PairProperties::new(r, m, &g, r, m, &g);
    let pw = PairProperties::new(r, m, &g, f64::INFINITY, f64::INFINITY, &w);
    let time = |law: NormalLaw, p: &PairProperties, wall: bool| -> Result<f64, ModelError> {
        law_contact_time(law, p, (&g, None), v).map_err(|mut e| {
            if wall && e.quantity == Quantity::Restitution {
                e.quantity = Quantity::WallRestitution;
            }
            e
        })
    };
    let grains =
        time(model.contact.normal, &pp, false)?.min(time(model.contact.wall.normal, &pw, true)?);
    match &model.bag {
        Some(bag) => Ok(grains.min(bag_time(model, bag, (r, m), v)?)),
        None => Ok(grains),
    }
}

/// Shortest time scale of a bean bag's film (s): its nodes' contacts with a grain of radius
/// and mass `(r, m)`, with each other and with the walls at speed `v` (the film's material
/// and yield strength). (The bonds have their own limit, [`TimeStepScales::bond_limit_s`].)
fn bag_time(
    model: &DemModel,
    bag: &crate::dem::bag::Bag,
    (r, m): (f64, f64),
    v: f64,
) -> Result<f64, ModelError> {
    let (f, g, w) = (
        bag.film.material,
        model.grains.material,
        model.contact.wall.material,
    );
    let (rn, mn) = (bag.node_radius_m, bag.node_mass_kg);
    let pairs = [
        (
            PairProperties::new(rn, mn, &f, r, m, &g),
            model.contact.normal,
        ),
        (
            PairProperties::new(rn, mn, &f, rn, mn, &f),
            model.contact.normal,
        ),
        (
            PairProperties::new(rn, mn, &f, f64::INFINITY, f64::INFINITY, &w),
            model.contact.wall.normal,
        ),
    ];
    let mut t = f64::INFINITY;
    for (p, law) in pairs {
        t = t.min(law_contact_time(
            law,
            &p,
            (&f, Some(bag.film.yield_strength_pa)),
            v,
        )?);
    }
    Ok(t)
}

/// Contact duration (s) of pair `p` under normal law `law` at speed `v` (Hertz: 2.868
/// (m*²/(R* E*² v))^{1/5}; linear: π/√(k/m* − (c/2m*)²) with the parameters of
/// [`LinearContactParams::select`] from the material that gives the yield coefficient and the
/// law's yield strength, or `yield_strength` when given).
fn law_contact_time(
    law: NormalLaw,
    p: &PairProperties,
    (material, yield_strength): (&Material, Option<f64>),
    v: f64,
) -> Result<f64, ModelError> {
    Ok(match law {
        NormalLaw::HertzKuwabaraKono { .. } => hertz_contact_time(p.m_star, p.r_star, p.e_star, v),
        NormalLaw::LinearSpringDashpot {
            restitution,
            yield_strength: y,
        } => {
            let l =
                LinearContactParams::select(p, material, yield_strength.unwrap_or(y), restitution)?;
            linear_contact_time(l.k_n, l.c_n, p.m_star)
        }
    })
}

/// Fraction of a bag's fastest bond half period a step may take ([`TimeStepScales::bond_limit_s`]).
pub const BOND_DT_FRACTION: f64 = 1.0 / 16.0;

/// Time step choice: automatic (a fraction of the Hertz contact time) or explicit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum DtChoice {
    /// `dt = "auto"`: dt = `dt_fraction` × t_s at the largest expected impact speed.
    #[default]
    Auto,
    /// Explicit time step (s), rejected above t_s/20.
    Seconds(f64),
}

/// The DEM's time step: the one rule ([`choose_dt`]) applied once, and then put on the run's
/// sample clock ([`TimeStep::on_sample_clock`]). The resolve step computes it
/// (`crate::setup::DemSetup::time_step`); the run, `check-scene`'s plan and the sweep's cost
/// estimate all take the value [`TimeStep::on_sample_clock`] gives for the run's sampling,
/// so that what is printed is what runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStep {
    /// Time step dt (s).
    pub dt_s: f64,
    /// Shortest contact duration t_s (s) at the design impact speed ([`contact_time`]).
    pub contact_time_s: f64,
    /// An automatic step not yet put on a sample clock: [`TimeStep::on_sample_clock`] may
    /// still shorten it (false for an explicit step and once the clock was applied).
    pub snaps_to_samples: bool,
}

impl TimeStep {
    /// The rule's step for `model` on `drive` ([`choose_dt`]).
    ///
    /// # Errors
    /// As [`choose_dt`].
    pub fn choose(
        model: &DemModel,
        drive: &BoxDrive,
        dt: DtChoice,
        fraction: f64,
    ) -> Result<TimeStep, ModelError> {
        let explicit = match dt {
            DtChoice::Auto => None,
            DtChoice::Seconds(s) => Some(s),
        };
        let (dt_s, contact_time_s) = choose_dt(model, drive, explicit, fraction)?;
        Ok(TimeStep {
            dt_s,
            contact_time_s,
            snaps_to_samples: explicit.is_none(),
        })
    }

    /// The step a run sampling every `sample_interval_s` (s) takes: an automatic step longer
    /// than nothing but shorter than the interval is shortened slightly, to
    /// Δ / ⌈Δ/dt⌉, so that samples fall on exact multiples of dt; an explicit step, or one
    /// already put on a clock, is kept as it is (the clock is applied once: in floating point
    /// it is not idempotent).
    pub fn on_sample_clock(self, sample_interval_s: f64) -> TimeStep {
        let mut dt_s = self.dt_s;
        if self.snaps_to_samples && sample_interval_s > dt_s && sample_interval_s.is_finite() {
            dt_s = sample_interval_s / (sample_interval_s / dt_s).ceil();
        }
        TimeStep {
            dt_s,
            snaps_to_samples: false,
            ..self
        }
    }
}

/// Chooses or checks the time step (s). `dt = None` means automatic: `fraction` × t_s.
///
/// # Errors
/// [`ModelError`]: a time step above t_s/20 (names the limit), or a fraction outside
/// (0, 1/20].
pub fn choose_dt(
    model: &DemModel,
    drive: &BoxDrive,
    dt: Option<f64>,
    fraction: f64,
) -> Result<(f64, f64), ModelError> {
    let v = impact_speed(drive, model.box_size_m[2]);
    let scales = TimeStepScales::of(model, drive)?;
    let ts = scales.contact_time_s;
    match dt {
        None => {
            if !(fraction > 0.0 && fraction <= MAX_DT_FRACTION) {
                return Err(ModelError::new(
                    Quantity::TimeStepFraction,
                    fraction,
                    "must be in (0, 0.05]: dt = fraction × t_s (default 0.01, as the thesis used)",
                ));
            }
            // the viscous rule: never longer than a quarter of the viscous time; a bag's bonds
            // their own limit
            Ok((
                (fraction * ts)
                    .min(scales.viscous_limit_s())
                    .min(scales.bond_limit_s()),
                ts,
            ))
        }
        Some(dt) => {
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(ModelError::new(
                    Quantity::TimeStep,
                    dt,
                    "must be > 0 (seconds), or chosen automatically",
                ));
            }
            if dt > MAX_DT_FRACTION * ts {
                return Err(ModelError::new(
                    Quantity::TimeStep,
                    format!("{dt:e} s"),
                    format!(
                        "is larger than t_s/20 = {:.3e} s (Hertz contact time {ts:.3e} s at impact speed \
                         {v:.3} m/s for these materials); lower the time step (t_s/50 = {:.3e} s \
                         recommended), choose it automatically (dt = auto), or soften the grains \
                         (lower Young's modulus)",
                        MAX_DT_FRACTION * ts,
                        ts / 50.0
                    ),
                ));
            }
            if dt > 2.0 * scales.bond_limit_s() {
                return Err(ModelError::new(
                    Quantity::TimeStep,
                    format!("{dt:e} s"),
                    format!(
                        "is longer than twice the bag's bond limit {:.3e} s (1/16 of the half period \
                         {:.3e} s of its fastest bond vibration): lower the time step, choose it \
                         automatically (dt = auto), or use larger film nodes",
                        scales.bond_limit_s(),
                        scales.bond_time_s
                    ),
                ));
            }
            let tn = scales.normal_viscous_time_s;
            if dt > MAX_NORMAL_VISCOUS_DT * tn {
                return Err(ModelError::new(
                    Quantity::TimeStep,
                    format!("{dt:e} s"),
                    format!(
                        "is longer than the normal viscous time m*/(gamma_n sqrt(zeta)) = {tn:.3e} s at impact speed \
                         {v:.3} m/s: the normal dashpot cannot be integrated stably; lower the time step \
                         (<= {:.3e} s recommended, dt = auto chooses it) or the normal damping",
                        scales.viscous_limit_s()
                    ),
                ));
            }
            Ok((dt, ts))
        }
    }
}

/// Checks the state for NaN, escaped grains and energy created without input.
///
/// `relative_balance` is the current ledger error and `residual_j` its signed residual
/// (positive = energy created).
///
/// # Errors
/// [`SimError::Unstable`] naming the cause and the likely fix.
pub fn check(world: &DemWorld, residual_j: f64, relative_balance: f64) -> Result<(), SimError> {
    let t = world.t;
    if !world.box_z.is_finite() || !world.box_v.is_finite() {
        return Err(SimError::Unstable {
            t_s: t,
            reason: "box position/velocity became non-finite: time step too large for the contact stiffness \
                     (lower the time step or its fraction of the contact time)"
                .into(),
        });
    }
    let b = world.box_size;
    for (i, &id) in world.grain_ids().iter().enumerate() {
        let p = world.pos[i];
        let v = world.vel[i];
        if !(p.iter().chain(v.iter()).all(|x| x.is_finite())) {
            return Err(SimError::Unstable {
                t_s: t,
                reason: format!(
                    "grain {id} has a non-finite position or velocity: time step too large for the contact \
                     stiffness (lower the time step or its fraction of the contact time, or the Young's modulus)"
                ),
            });
        }
        let o = world.box_origin();
        let q = [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
        let r = world.radius[i];
        // the centre more than a radius beyond a wall (x < −r, x > Lx + r, …; ρ > R_c + r)
        if world
            .container
            .overlaps(b, q, r)
            .iter()
            .any(|&z| z > 2.0 * r)
        {
            return Err(SimError::Unstable {
                t_s: t,
                reason: format!(
                    "grain {id} left the {} (centre at {:?} m, box corner at {:?} m): contacts too stiff for the \
                     time step or impact speeds above the auto-dt estimate; lower the time step or its fraction of the contact time",
                    world.container.name(), p, o
                ),
            });
        }
    }
    if residual_j > 0.0 && relative_balance > 0.25 {
        return Err(SimError::Unstable {
            t_s: t,
            reason: format!(
                "energy grew without input (ledger residual +{residual_j:.3e} J, {:.0} % of the flows): time \
                 step too large for the contact stiffness; lower the time step or its fraction of the contact time",
                100.0 * relative_balance
            ),
        });
    }
    Ok(())
}
