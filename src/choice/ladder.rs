//! The settings ladder: every shortcut a user reaches for, each one [`Change`] to the
//! reference scene, turned into the scene that is simulated ([`Rung::scene`]).
//!
//! The reference is a scene file (for scene B, `data/scenes/thesis_b_reference.toml`: real
//! steel, Hertz–Kuwabara–Kono with friction and rotations, dt = t_s/100, 200 forcing periods,
//! the last 60 % analysed). Each rung changes one thing only: the time step, the stiffness
//! (E ÷ f with the damping rescaled so that the restitution e(v) is kept, γ ∝ f^{-3/5}, SPEC
//! §9), the contact law, the tangential law, rotations, friction, the number of grains at the
//! same total mass, the one-particle model in place of the grains, the run length, the
//! analysis window.

use crate::contact::hertz_stiffness;
use crate::contact::material::PairProperties;
use crate::contact::restitution::kuwabara_kono_restitution;
use crate::dem::stability::impact_speed;
use crate::dem::BoxDrive;
use crate::error::SceneError;
use crate::scene::dem::DemParams;
use crate::scene::{Damper, ImpactParams, Scene, SceneSource};
use serde::{Deserialize, Serialize};

/// Yield strength used for the linear law when the scene gives none (Pa): hardened steel,
/// the linear-DEM paper's order of magnitude.
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
    /// Mindlin tangential spring with history instead of the history-free Coulomb law.
    TangentialLaw,
    /// Rotations (and so frictional torques) switched off.
    Rotations,
    /// Friction (tangential force) switched off.
    Friction,
    /// Fewer, larger grains at the same total grain mass.
    GrainCount,
    /// The one-particle impact model (SPEC §3) instead of the DEM.
    OneParticle,
    /// Fewer forcing periods of drive.
    RunLength,
    /// A shorter steady-state and analysis window (same run length).
    Window,
}

/// Every axis, in the order of the tables.
pub const ALL_AXES: [Axis; 11] = [
    Axis::Reference,
    Axis::DtFraction,
    Axis::Softening,
    Axis::ContactLaw,
    Axis::TangentialLaw,
    Axis::Rotations,
    Axis::Friction,
    Axis::GrainCount,
    Axis::OneParticle,
    Axis::RunLength,
    Axis::Window,
];

impl Axis {
    /// The name used in CSV files and plots.
    pub fn as_str(self) -> &'static str {
        match self {
            Axis::Reference => "reference",
            Axis::DtFraction => "dt-fraction",
            Axis::Softening => "softening",
            Axis::ContactLaw => "contact-law",
            Axis::TangentialLaw => "tangential-law",
            Axis::Rotations => "rotations",
            Axis::Friction => "friction",
            Axis::GrainCount => "grain-count",
            Axis::OneParticle => "one-particle",
            Axis::RunLength => "run-length",
            Axis::Window => "window",
        }
    }

    /// Parses [`Axis::as_str`].
    pub fn parse(s: &str) -> Option<Axis> {
        ALL_AXES.iter().copied().find(|a| a.as_str() == s)
    }

    /// Whether the axis describes how long or how much of a run is looked at rather than the
    /// model (never chosen by `auto`: the scene's `[run]` is the user's).
    pub fn is_run_setting(self) -> bool {
        matches!(self, Axis::RunLength | Axis::Window)
    }
}

/// Where the one-particle model's gap comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gap {
    /// A given free travel (m), e.g. the source's 0.0835 m for scene B.
    Given(f64),
    /// The box height minus the settled bed's height, measured by the reference runs
    /// (`bed_height_m`); the value (m) once known.
    SettledBed(Option<f64>),
}

/// One change to the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Change {
    /// No change (the reference).
    None,
    /// dt = fraction × t_s (–).
    DtFraction(f64),
    /// Young's modulus divided by this factor (–), γ_n, γ_s × factor^{-3/5}, Y ÷ factor.
    Soften(f64),
    /// Linear spring–dashpot law (the linear-DEM paper's parameters from the yield strength)
    /// with e equal to the Kuwabara–Kono restitution at the design impact speed.
    LinearLaw,
    /// Mindlin tangential spring with per-contact history (`damper.tangential = "mindlin"`).
    Mindlin,
    /// Rotations off.
    RotationsOff,
    /// Friction off: μ = 0 for grains and walls.
    FrictionOff,
    /// N grains at the reference's total grain mass (radius × (N₀/N)^{1/3}).
    GrainCount(usize),
    /// The one-particle model: the bed's mass as one particle with restitution e and a gap.
    OneParticle {
        /// Effective restitution e (–).
        restitution: f64,
        /// Free travel.
        gap: Gap,
    },
    /// Forcing periods of drive.
    Periods(u32),
    /// Steady-state and analysis fraction of the run (–).
    Window(f64),
}

/// A rung of the ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    /// Short identifier, also the folder name of its points (`dt-50`, `soften-1000`, …).
    pub id: String,
    /// The knob.
    pub axis: Axis,
    /// Label for tables and figures, e.g. `dt = t_s/50`.
    pub label: String,
    /// The change.
    pub change: Change,
}

impl Rung {
    fn new(id: impl Into<String>, axis: Axis, label: impl Into<String>, change: Change) -> Rung {
        Rung {
            id: id.into(),
            axis,
            label: label.into(),
            change,
        }
    }

    /// The scene this rung simulates: `reference` with the change applied.
    ///
    /// # Errors
    /// [`SceneError`] naming the key when the reference cannot take the change (no DEM
    /// damper, radii that are not one fixed radius for a grain-count change, a one-particle
    /// gap that is not known yet).
    pub fn scene(&self, reference: &SceneSource) -> Result<SceneSource, SceneError> {
        let scene = reference.scene(&[])?;
        let p = dem_params(&scene)?;
        let mut src = reference.clone();
        let set = |src: &mut SceneSource, k: &str, v: toml::Value| src.set(k, v);
        match self.change {
            Change::None => {}
            Change::DtFraction(f) => set(&mut src, "run.dt_fraction", f.into())?,
            Change::Soften(f) => soften_keys(&mut src, p, f)?,
            Change::LinearLaw => {
                let e = design_restitution(p, &drive_of(&scene))?;
                set(&mut src, "damper.contact", "linear".into())?;
                set(&mut src, "damper.restitution", e.into())?;
                let y = p.yield_strength.unwrap_or(DEFAULT_YIELD_STRENGTH_PA);
                set(&mut src, "damper.yield_strength", y.into())?;
            }
            Change::Mindlin => set(&mut src, "damper.tangential", "mindlin".into())?,
            Change::RotationsOff => set(&mut src, "damper.rotations", false.into())?,
            Change::FrictionOff => {
                set(&mut src, "damper.friction", 0.0.into())?;
                set(&mut src, "damper.wall_friction", 0.0.into())?;
            }
            Change::GrainCount(n) => count_keys(&mut src, p, n)?,
            Change::OneParticle { restitution, gap } => {
                return one_particle_scene(reference, p, restitution, gap)
            }
            Change::Periods(n) => set(&mut src, "run.periods", i64::from(n).into())?,
            Change::Window(f) => {
                set(&mut src, "run.steady_fraction", f.into())?;
                set(&mut src, "run.analysis_fraction", f.into())?;
            }
        }
        Ok(src)
    }
}

fn dem_params(scene: &Scene) -> Result<&DemParams, SceneError> {
    match &scene.damper {
        Damper::Dem(p) => Ok(p),
        other => Err(SceneError::invalid(
            "damper.kind",
            other.kind(),
            "the speed–accuracy ladder starts from a DEM reference (kind = \"dem\")",
        )),
    }
}

fn drive_of(scene: &Scene) -> BoxDrive {
    BoxDrive {
        primary: None,
        amplitude_m: scene.excitation.amplitude,
        frequency_hz: scene.excitation.frequency,
        force_n: 0.0,
        direction: [0.0, 0.0, 1.0],
    }
}

/// E ÷ f, γ × f^{-3/5} (grain–grain and, where given, grain–wall), Y ÷ f: the keys
/// [`DemParams::softened`] changes.
fn soften_keys(src: &mut SceneSource, p: &DemParams, f: f64) -> Result<(), SceneError> {
    let q = p.softened(f);
    src.set("damper.youngs_modulus", q.youngs_modulus.into())?;
    src.set("damper.gamma_n", q.gamma_n.into())?;
    src.set("damper.gamma_s", q.gamma_s.into())?;
    let optional = [
        ("damper.wall_youngs_modulus", q.wall_youngs_modulus),
        ("damper.wall_gamma_n", q.wall_gamma_n),
        ("damper.wall_gamma_s", q.wall_gamma_s),
        ("damper.yield_strength", q.yield_strength),
    ];
    for (k, v) in optional {
        if let Some(v) = v {
            src.set(k, v.into())?;
        }
    }
    Ok(())
}

/// `damper.count = n` and `damper.radius` scaled by [`with_count_at_fixed_mass`] (the rung
/// writes one fixed radius, so a distribution is refused).
fn count_keys(src: &mut SceneSource, p: &DemParams, n: usize) -> Result<(), SceneError> {
    if p.radius.is_none() || p.radius_table.is_some() || p.radius_min.is_some() {
        return Err(SceneError::invalid(
            "damper.radius",
            "a distribution",
            "the grain-count rung scales one fixed radius; give damper.radius",
        ));
    }
    let q = with_count_at_fixed_mass(p, n)?;
    src.set("damper.count", (n as i64).into())?;
    if let Some(r) = q.radius {
        src.set("damper.radius", r.into())?;
    }
    if let Some(s) = q.neighbor_skin {
        src.set("damper.neighbor_skin", s.into())?;
    }
    Ok(())
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

/// The grains of `p` as one effective particle of their total mass (SPEC §3) with restitution
/// `restitution` (–) and free travel `gap_m` (m), starting at rest on the floor.
///
/// # Errors
/// Radius errors of the distribution.
pub fn one_particle(
    p: &DemParams,
    restitution: f64,
    gap_m: f64,
) -> Result<ImpactParams, SceneError> {
    Ok(ImpactParams {
        mass: bed_mass_kg(p)?,
        gap: gap_m,
        restitution,
        initial_height: 0.0,
        initial_velocity: 0.0,
    })
}

/// The reference's primary, drive and run with the grains replaced by one particle of their
/// total mass (SPEC §3).
fn one_particle_scene(
    reference: &SceneSource,
    p: &DemParams,
    restitution: f64,
    gap: Gap,
) -> Result<SceneSource, SceneError> {
    let gap_m = match gap {
        Gap::Given(g) => g,
        Gap::SettledBed(Some(h)) => p.r#box[2] - h,
        Gap::SettledBed(None) => {
            return Err(SceneError::invalid(
                "damper.gap",
                "the settled bed",
                "the settled bed's height comes from the reference runs: compute at least \
                 one reference point first",
            ))
        }
    };
    let one = one_particle(p, restitution, gap_m)?;
    let mut table = reference.table().clone();
    let mut damper = toml::Table::new();
    damper.insert("kind".into(), "impact".into());
    damper.insert("mass".into(), one.mass.into());
    damper.insert("gap".into(), one.gap.into());
    damper.insert("restitution".into(), one.restitution.into());
    table.insert("damper".into(), toml::Value::Table(damper));
    if let Some(toml::Value::Table(run)) = table.get_mut("run") {
        for k in ["dt", "dt_fraction", "replica", "replica_perturbation"] {
            run.remove(k);
        }
    }
    SceneSource::parse(&toml::to_string(&table).unwrap_or_default())
}

/// Total mass of the grains (kg): Σ ρ 4/3 π r_i³ over the radii the packing draws
/// (`damper.seed`).
///
/// # Errors
/// Radius errors of the distribution.
pub fn bed_mass_kg(p: &DemParams) -> Result<f64, SceneError> {
    let radii = p.radius_distribution()?.sample_n(p.count, p.seed);
    let v: f64 = radii
        .iter()
        .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3))
        .sum();
    Ok(v * p.density)
}

/// Kuwabara–Kono restitution (–) of two of the scene's grains colliding at the design impact
/// speed max(2UΩ, √(2 g Lz)) of `drive` (gives the linear law the same e).
///
/// # Errors
/// Radius errors of the distribution.
pub fn design_restitution(p: &DemParams, drive: &BoxDrive) -> Result<f64, SceneError> {
    let r = p.radius_distribution()?.r_max();
    let m = p.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let g = p.grain_material();
    let pair = PairProperties::new(r, m, &g, r, m, &g);
    let k = hertz_stiffness(pair.e_star, pair.r_star);
    let v = impact_speed(drive, p.r#box[2]);
    Ok(kuwabara_kono_restitution(k, p.gamma_n, pair.m_star, v).clamp(0.01, 1.0))
}

/// The source's gap for scene B's one-particle model (m) (thesis §5, Fig. 5.2a).
pub const SCENE_B_SOURCE_GAP_M: f64 = 0.0835;

/// The ladder of scene B's reference with `count` grains, reference first: dt = t_s/50, /20,
/// /10; E ÷ 10, 100, 1000, 10 000; the linear law; Mindlin; rotations off; friction off;
/// N/2 grains; one particle with e = 0, 0.5, 0.8 at the source's gap and e = 0 at the settled
/// bed's gap (`bed_height_m`, when known); 50 and 100 periods (reference: `periods`); the
/// last 30 % analysed (reference: 60 %).
pub fn ladder(count: usize, bed_height_m: Option<f64>) -> Vec<Rung> {
    let mut v = vec![Rung::new(
        "reference",
        Axis::Reference,
        "reference",
        Change::None,
    )];
    for d in [50u32, 20, 10] {
        v.push(Rung::new(
            format!("dt-{d}"),
            Axis::DtFraction,
            format!("dt = t_s/{d}"),
            Change::DtFraction(1.0 / f64::from(d)),
        ));
    }
    for f in [10u32, 100, 1000, 10000] {
        v.push(Rung::new(
            format!("soften-{f}"),
            Axis::Softening,
            format!("E / {f}"),
            Change::Soften(f64::from(f)),
        ));
    }
    v.push(Rung::new(
        "linear",
        Axis::ContactLaw,
        "linear spring-dashpot",
        Change::LinearLaw,
    ));
    v.push(Rung::new(
        "mindlin",
        Axis::TangentialLaw,
        "Mindlin tangential",
        Change::Mindlin,
    ));
    v.push(Rung::new(
        "rotations-off",
        Axis::Rotations,
        "rotations off",
        Change::RotationsOff,
    ));
    v.push(Rung::new(
        "friction-off",
        Axis::Friction,
        "friction off",
        Change::FrictionOff,
    ));
    let half = (count / 2).max(1);
    v.push(Rung::new(
        format!("n-{half}"),
        Axis::GrainCount,
        format!("N = {half}, same mass"),
        Change::GrainCount(half),
    ));
    for e in [0.0, 0.5, 0.8] {
        v.push(Rung::new(
            format!("one-particle-e{e}"),
            Axis::OneParticle,
            format!("one particle, e = {e}"),
            Change::OneParticle {
                restitution: e,
                gap: Gap::Given(SCENE_B_SOURCE_GAP_M),
            },
        ));
    }
    v.push(Rung::new(
        "one-particle-e0-bed",
        Axis::OneParticle,
        "one particle, e = 0, gap of the settled bed",
        Change::OneParticle {
            restitution: 0.0,
            gap: Gap::SettledBed(bed_height_m),
        },
    ));
    for n in [50u32, 100] {
        v.push(Rung::new(
            format!("periods-{n}"),
            Axis::RunLength,
            format!("{n} periods"),
            Change::Periods(n),
        ));
    }
    v.push(Rung::new(
        "window-0.3",
        Axis::Window,
        "last 30 % analysed",
        Change::Window(0.3),
    ));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference() -> SceneSource {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/data/scenes/thesis_b_reference.toml"
        ))
        .unwrap();
        SceneSource::parse(&text).unwrap()
    }

    #[test]
    fn softening_keeps_restitution_curve() {
        // e(v) of Kuwabara–Kono depends on γ_n k_n^{-3/5} only (SPEC §9): softening by 1000
        // with γ ∝ E^{3/5} must leave e at a given speed unchanged (Padé formula, exact
        // algebra up to rounding)
        let drive = BoxDrive {
            primary: None,
            amplitude_m: 4.5e-3,
            frequency_hz: 15.0,
            force_n: 0.0,
            direction: [0.0, 0.0, 1.0],
        };
        let p = DemParams::thesis_b();
        let e1 = design_restitution(&p, &drive).unwrap();
        let e2 = design_restitution(&p.softened(1000.0), &drive).unwrap();
        assert!((e1 - e2).abs() < 1e-12, "{e1} vs {e2}");
        assert!(e1 > 0.3 && e1 < 1.0);
    }

    #[test]
    fn every_rung_makes_a_valid_scene_that_differs_from_the_reference() {
        let r = reference();
        let rungs = ladder(250, Some(0.0347));
        for a in ALL_AXES {
            assert!(rungs.iter().any(|s| s.axis == a), "{a:?} missing");
            assert_eq!(Axis::parse(a.as_str()), Some(a));
        }
        for rung in &rungs {
            let s = rung
                .scene(&r)
                .unwrap_or_else(|e| panic!("{}: {e}", rung.id));
            let scene = s.scene(&[]).unwrap_or_else(|e| panic!("{}: {e}", rung.id));
            assert_eq!(
                rung.change == Change::None,
                s.table() == r.table(),
                "{}",
                rung.id
            );
            if let Change::OneParticle { .. } = rung.change {
                assert_eq!(scene.damper.kind(), "impact");
            }
        }
    }

    #[test]
    fn the_e100_scene_file_is_the_soften_100_rung() {
        // the committed 5–26 Hz sweep of thesis_b_reference_e100.toml is found as the
        // E ÷ 100 rung's points only if the two scenes are the same table, value for value
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/data/scenes/thesis_b_reference_e100.toml"
        ))
        .unwrap();
        let e100 = SceneSource::parse(&text).unwrap();
        let rung = ladder(250, None)
            .into_iter()
            .find(|r| r.id == "soften-100")
            .unwrap();
        assert_eq!(rung.scene(&reference()).unwrap().table(), e100.table());
    }

    #[test]
    fn grain_count_keeps_the_mass_and_one_particle_takes_it() {
        let r = reference();
        let half = Rung::new("n", Axis::GrainCount, "n", Change::GrainCount(125));
        let s = half.scene(&r).unwrap().scene(&[]).unwrap();
        let Damper::Dem(q) = &s.damper else { panic!() };
        let mass = |p: &DemParams| p.count as f64 * p.radius.unwrap().powi(3);
        let p = DemParams::thesis_b();
        assert!((mass(q) / mass(&p) - 1.0).abs() < 1e-12);
        let one = Rung::new(
            "o",
            Axis::OneParticle,
            "o",
            Change::OneParticle {
                restitution: 0.0,
                gap: Gap::SettledBed(Some(0.035)),
            },
        );
        let s = one.scene(&r).unwrap().scene(&[]).unwrap();
        let Damper::Impact(i) = &s.damper else {
            panic!()
        };
        // 250 steel grains of 3 mm radius: 250 × 8030 × 4/3 π (0.003)³ = 0.22704 kg
        assert!((i.mass - 0.227_043).abs() < 1e-5, "{}", i.mass);
        assert!((i.gap - (0.1225 - 0.035)).abs() < 1e-12);
        let unknown = Rung::new(
            "u",
            Axis::OneParticle,
            "u",
            Change::OneParticle {
                restitution: 0.0,
                gap: Gap::SettledBed(None),
            },
        );
        assert!(unknown
            .scene(&r)
            .unwrap_err()
            .to_string()
            .contains("damper.gap"));
    }
}
