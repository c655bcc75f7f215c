//! The settings ladder: each cheaper (or more accurate) setting is one [`Change`] applied to
//! the reference [`Case`] of a DEM scene.
//!
//! The reference is the most accurate *affordable* setting: the scene's grains with their
//! Young's modulus divided by [`LadderOptions::reference_softening`] (default 100; the
//! damping rescaled so that the restitution curve e(v) is unchanged, γ ∝ E^{3/5}, SPEC §9),
//! Hertz–Kuwabara–Kono contacts with friction and rotations, dt = t_s/100 (the thesis's
//! rule of thumb), the scene's N and radii, a short run (default 1.5 s of drive) whose last
//! half is the steady state. Each rung changes one thing only.

use crate::contact::hertz_stiffness;
use crate::contact::material::PairProperties;
use crate::contact::restitution::kuwabara_kono_restitution;
use crate::dem::stability::impact_speed;
use crate::dem::BoxDrive;
use crate::error::SceneError;
use crate::scene::dem::{ContactKind, DemParams};
use serde::{Deserialize, Serialize};

/// Yield strength used for the linear law when the scene gives none (Pa): hardened steel,
/// the seed paper's order of magnitude.
pub const DEFAULT_YIELD_STRENGTH_PA: f64 = 1.0e9;

/// Which knob a setting turns (a column of `tradeoff.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Axis {
    /// The reference itself.
    Reference,
    /// Time step as a fraction of the contact duration.
    DtFraction,
    /// Young's modulus divided by a factor (damping rescaled, e(v) unchanged).
    Softening,
    /// Linear spring–dashpot instead of Hertz–Kuwabara–Kono.
    ContactLaw,
    /// Rotations (and so frictional torques) switched off.
    Rotations,
    /// Friction (tangential force) switched off.
    Friction,
    /// Number of grains at fixed total grain mass.
    GrainCount,
    /// The one-particle impact model (SPEC §3) instead of the DEM.
    OneParticle,
    /// Shorter drive.
    RunLength,
    /// Shorter steady-state window (same run).
    SteadyFraction,
}

impl Axis {
    /// The name used in CSV files and plots.
    pub fn as_str(self) -> &'static str {
        match self {
            Axis::Reference => "reference",
            Axis::DtFraction => "dt-fraction",
            Axis::Softening => "softening",
            Axis::ContactLaw => "contact-law",
            Axis::Rotations => "rotations",
            Axis::Friction => "friction",
            Axis::GrainCount => "grain-count",
            Axis::OneParticle => "one-particle",
            Axis::RunLength => "run-length",
            Axis::SteadyFraction => "steady-fraction",
        }
    }

    /// Parses [`Axis::as_str`].
    pub fn parse(s: &str) -> Option<Axis> {
        ALL_AXES.iter().copied().find(|a| a.as_str() == s)
    }
}

/// Every axis, in the order of the tables.
pub const ALL_AXES: [Axis; 10] = [
    Axis::Reference,
    Axis::DtFraction,
    Axis::Softening,
    Axis::ContactLaw,
    Axis::Rotations,
    Axis::Friction,
    Axis::GrainCount,
    Axis::OneParticle,
    Axis::RunLength,
    Axis::SteadyFraction,
];

/// One change to the reference case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Change {
    /// No change (the reference).
    None,
    /// dt = fraction × t_s (–).
    DtFraction(f64),
    /// Young's modulus divided by this factor relative to the scene's material (–).
    Soften(f64),
    /// Linear spring–dashpot law with e equal to the Kuwabara–Kono restitution at the design
    /// impact speed, and the yield strength scaled with E (so k_n scales like Hertz's).
    LinearLaw,
    /// Rotations off (`false`).
    Rotations(bool),
    /// Friction off (`false`): μ = 0, no tangential force.
    Friction(bool),
    /// N grains at the scene's total grain mass (radii scaled by (N₀/N)^{1/3}).
    GrainCount(usize),
    /// One-particle impact model with this restitution; `None`: fitted to the reference.
    OneParticle(Option<f64>),
    /// Drive duration (s).
    Duration(f64),
    /// Steady-state fraction of the same run (–).
    SteadyFraction(f64),
}

/// A rung of the ladder: a change, its axis, its value and a label.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// The knob.
    pub axis: Axis,
    /// Short label, e.g. `dt = t_s/50`.
    pub label: String,
    /// Numeric value of the knob (e.g. 0.02, 1000, 100 grains; 1/0 for on/off; e for the
    /// one-particle model, NaN when fitted).
    pub value: f64,
    /// The change.
    pub change: Change,
}

/// A fully specified DEM run (before softening is applied to the parameters).
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The scene's grains, unsoftened.
    pub params: DemParams,
    /// Young's modulus divisor (–), ≥ 1 normally.
    pub softening: f64,
    /// dt / t_s (–).
    pub dt_fraction: f64,
    /// Drive duration (s).
    pub duration_s: f64,
    /// Steady-state fraction (–).
    pub steady_fraction: f64,
}

impl Case {
    /// The DEM parameters actually simulated: softening applied.
    pub fn effective_params(&self) -> DemParams {
        soften(&self.params, self.softening)
    }
}

/// The softening rule ([`DemParams::softened`]): E/f, γ·f^{-3/5}, Y/f.
pub fn soften(p: &DemParams, factor: f64) -> DemParams {
    p.softened(factor)
}

/// Kuwabara–Kono restitution (–) of two of the scene's grains colliding at the design impact
/// speed max(2UΩ, √(2 g Lz)) of `drive` (used to give the linear law the same e).
pub fn design_restitution(p: &DemParams, drive: &BoxDrive) -> Result<f64, SceneError> {
    let r = p.radius_distribution()?.r_max();
    let m = p.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let g = p.grain_material();
    let pair = PairProperties::new(r, m, &g, r, m, &g);
    let k = hertz_stiffness(pair.e_star, pair.r_star);
    let v = impact_speed(drive, p.r#box[2]);
    Ok(kuwabara_kono_restitution(k, p.gamma_n, pair.m_star, v).clamp(0.01, 1.0))
}

impl Change {
    /// Applies the change to a DEM case. [`Change::OneParticle`] leaves it unchanged (the
    /// impact model is built separately, see [`crate::tradeoff::measure`]).
    ///
    /// # Errors
    /// Radii that cannot be scaled (invalid distribution).
    pub fn apply(&self, base: &Case, drive: &BoxDrive) -> Result<Case, SceneError> {
        let mut c = base.clone();
        match *self {
            Change::None | Change::OneParticle(_) => {}
            Change::DtFraction(f) => c.dt_fraction = f,
            Change::Soften(f) => c.softening = f,
            Change::LinearLaw => {
                let e = design_restitution(&c.params, drive)?;
                c.params.contact = ContactKind::Linear;
                c.params.restitution = Some(e);
                c.params.yield_strength =
                    Some(c.params.yield_strength.unwrap_or(DEFAULT_YIELD_STRENGTH_PA));
            }
            Change::Rotations(on) => c.params.rotations = on,
            Change::Friction(on) => {
                if !on {
                    c.params.friction = 0.0;
                    c.params.wall_friction = Some(0.0);
                }
            }
            Change::GrainCount(n) => c.params = with_count_at_fixed_mass(&c.params, n)?,
            Change::Duration(d) => c.duration_s = d,
            Change::SteadyFraction(f) => c.steady_fraction = f,
        }
        Ok(c)
    }
}

/// The scene's grains replaced by `n` grains of the same total mass: every radius scaled by
/// (N₀/n)^{1/3} (same density, same size distribution shape).
///
/// # Errors
/// `damper.count` when n = 0; radius errors of the distribution.
pub fn with_count_at_fixed_mass(p: &DemParams, n: usize) -> Result<DemParams, SceneError> {
    if n == 0 {
        return Err(SceneError::invalid("damper.count", n, "must be ≥ 1 grain"));
    }
    p.radius_distribution()?;
    let s = (p.count as f64 / n as f64).cbrt();
    let mut q = p.clone();
    q.count = n;
    q.radius = q.radius.map(|r| r * s);
    q.radius_min = q.radius_min.map(|r| r * s);
    q.radius_max = q.radius_max.map(|r| r * s);
    q.radius_std = q.radius_std.map(|r| r * s);
    q.radius_table = q
        .radius_table
        .map(|t| t.into_iter().map(|[r, w]| [r * s, w]).collect());
    q.neighbor_skin = q.neighbor_skin.map(|r| r * s);
    Ok(q)
}

/// How far up and down the ladder goes.
#[derive(Debug, Clone, PartialEq)]
pub struct LadderOptions {
    /// Young's modulus divisor of the reference (–). Default 100 (real steel is ~6× slower
    /// still; state it next to the results).
    pub reference_softening: f64,
    /// dt / t_s of the reference (–). Default 1/100 (the thesis's δt ≈ t_s/100).
    pub reference_dt_fraction: f64,
    /// Drive duration of the reference (s). Default 1.5.
    pub duration_s: f64,
    /// Steady-state fraction of the reference (–). Default 0.5.
    pub steady_fraction: f64,
    /// Quick ladder: no rung costlier than the reference (no real steel, no t_s/200, no
    /// larger N). Default `false`.
    pub quick: bool,
}

impl Default for LadderOptions {
    fn default() -> Self {
        LadderOptions {
            reference_softening: 100.0,
            reference_dt_fraction: 0.01,
            duration_s: 1.5,
            steady_fraction: 0.5,
            quick: false,
        }
    }
}

impl LadderOptions {
    /// The reference case for the scene's grains `params`.
    pub fn reference(&self, params: &DemParams) -> Case {
        let mut p = params.clone();
        p.snapshot_interval = None;
        p.orientations = false;
        Case {
            params: p,
            softening: self.reference_softening,
            dt_fraction: self.reference_dt_fraction,
            duration_s: self.duration_s,
            steady_fraction: self.steady_fraction,
        }
    }

    /// Checks the options.
    ///
    /// # Errors
    /// [`SceneError`] naming the option.
    pub fn validate(&self) -> Result<(), SceneError> {
        crate::scene::run::Run::with_duration(self.duration_s).validate()?;
        if !(self.reference_softening >= 1.0 && self.reference_softening.is_finite()) {
            return Err(SceneError::invalid(
                "reference_softening",
                self.reference_softening,
                "must be ≥ 1",
            ));
        }
        if !(self.reference_dt_fraction > 0.0 && self.reference_dt_fraction <= 0.05) {
            return Err(SceneError::invalid(
                "reference_dt_fraction",
                self.reference_dt_fraction,
                "must be in (0, 0.05]",
            ));
        }
        if !(self.steady_fraction > 0.0 && self.steady_fraction <= 1.0) {
            return Err(SceneError::invalid(
                "steady_fraction",
                self.steady_fraction,
                "must be in (0, 1]",
            ));
        }
        Ok(())
    }
}

fn rung(axis: Axis, label: impl Into<String>, value: f64, change: Change) -> Setting {
    Setting {
        axis,
        label: label.into(),
        value,
        change,
    }
}

/// The ladder of settings for a scene with `count` grains, reference first.
///
/// dt = t_s/10 … t_s/200; E ÷ 1, 10, 100, 1 000, 10 000; linear law; rotations off; friction
/// off; N at fixed mass; one particle with e = 0 and fitted e; run length 1/3 and 2/3 of the
/// reference; steady fraction 0.1 and 0.25. Rungs equal to the reference are left out;
/// `quick` drops the rungs costlier than the reference.
pub fn settings_ladder(opts: &LadderOptions, count: usize) -> Vec<Setting> {
    let mut v = vec![rung(Axis::Reference, "reference", 1.0, Change::None)];
    let dts: &[f64] = if opts.quick {
        &[10.0, 20.0, 50.0]
    } else {
        &[10.0, 20.0, 50.0, 200.0]
    };
    for &d in dts {
        if (1.0 / d - opts.reference_dt_fraction).abs() > 1e-12 {
            v.push(rung(
                Axis::DtFraction,
                format!("dt = t_s/{d}"),
                1.0 / d,
                Change::DtFraction(1.0 / d),
            ));
        }
    }
    let softs: &[f64] = if opts.quick {
        &[1000.0, 10000.0]
    } else {
        &[1.0, 10.0, 1000.0, 10000.0]
    };
    for &s in softs {
        if (s - opts.reference_softening).abs() > 1e-9 {
            v.push(rung(
                Axis::Softening,
                format!("E / {s}"),
                s,
                Change::Soften(s),
            ));
        }
    }
    v.push(rung(Axis::ContactLaw, "linear law", 0.0, Change::LinearLaw));
    v.push(rung(
        Axis::Rotations,
        "rotations off",
        0.0,
        Change::Rotations(false),
    ));
    v.push(rung(
        Axis::Friction,
        "friction off",
        0.0,
        Change::Friction(false),
    ));
    let mut counts: Vec<usize> = vec![(count / 8).max(1), (count * 2 / 5).max(1)];
    if !opts.quick {
        counts.push(count * 2);
    }
    counts.dedup();
    for n in counts.into_iter().filter(|&n| n != count) {
        v.push(rung(
            Axis::GrainCount,
            format!("N = {n}"),
            n as f64,
            Change::GrainCount(n),
        ));
    }
    v.push(rung(
        Axis::OneParticle,
        "one particle e = 0",
        0.0,
        Change::OneParticle(Some(0.0)),
    ));
    v.push(rung(
        Axis::OneParticle,
        "one particle, fitted e",
        f64::NAN,
        Change::OneParticle(None),
    ));
    for frac in [1.0 / 3.0, 2.0 / 3.0] {
        let d = opts.duration_s * frac;
        v.push(rung(
            Axis::RunLength,
            format!("run {d:.2} s"),
            d,
            Change::Duration(d),
        ));
    }
    for sf in [0.1, 0.25] {
        if (sf - opts.steady_fraction).abs() > 1e-12 {
            v.push(rung(
                Axis::SteadyFraction,
                format!("steady {sf}"),
                sf,
                Change::SteadyFraction(sf),
            ));
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn softening_keeps_restitution_curve() {
        // e(v) of Kuwabara–Kono depends on γ_n k_n^{-3/5} only (SPEC §9): softening by 1000
        // with γ ∝ E^{3/5} must leave e at a given speed unchanged (Padé formula, exact
        // algebra up to rounding)
        let drive = BoxDrive {
            primary: None,
            amplitude_m: 4.5e-3,
            frequency_hz: 15.0,
        };
        let p = DemParams::thesis_b();
        let e1 = design_restitution(&p, &drive).unwrap();
        let e2 = design_restitution(&soften(&p, 1000.0), &drive).unwrap();
        assert!((e1 - e2).abs() < 1e-12, "{e1} vs {e2}");
        assert!(e1 > 0.3 && e1 < 1.0);
        assert_eq!(soften(&p, 1000.0), DemParams::thesis_b_softened(1000.0));
    }

    #[test]
    fn fixed_mass_scaling() {
        let p = DemParams::thesis_b();
        let q = with_count_at_fixed_mass(&p, 31).unwrap();
        let m = |p: &DemParams| p.count as f64 * p.radius.unwrap().powi(3);
        assert!((m(&p) / m(&q) - 1.0).abs() < 1e-12);
        assert!(with_count_at_fixed_mass(&p, 0).is_err());
    }

    #[test]
    fn ladder_has_every_axis_and_no_duplicate_reference() {
        let l = settings_ladder(&LadderOptions::default(), 250);
        for a in ALL_AXES {
            assert!(l.iter().any(|s| s.axis == a), "{a:?} missing");
            assert_eq!(Axis::parse(a.as_str()), Some(a));
        }
        assert!(!l.iter().any(|s| s.change == Change::Soften(100.0)));
        let q = settings_ladder(
            &LadderOptions {
                quick: true,
                ..Default::default()
            },
            250,
        );
        assert!(q.len() < l.len());
    }
}
