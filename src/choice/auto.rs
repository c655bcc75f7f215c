//! `[damper] kind = "auto"`: pick the cheapest setting that delivers the scene's `[outputs]`
//! within its tolerance, from the measured speed–accuracy table
//! (`data/reference/tradeoff_settings.csv`, a copy of `figures/tradeoff_settings.csv` built
//! into the binary), and say which row and which measured errors.
//!
//! # Rules
//! A measured setting is eligible when
//! - it was compared with the reference at every frequency the reference has, and at least
//!   [`MIN_COMPARED`] of them (a setting measured at fewer is not trusted yet);
//! - it can deliver the outputs: grain outputs (`grain_snapshots`, `orientations`,
//!   `energies_by_mechanism`) exclude the one-particle model; `grain_snapshots` and
//!   `orientations` exclude another N; `orientations` excludes rotations off;
//!   `energies_by_mechanism` excludes friction off;
//! - its measured errors are within `outputs.tolerance`: always the largest Z error; with
//!   `frf_only` also the resonance frequency's; with `energies_by_mechanism` the largest
//!   error of the dissipation per cycle; with `zcm_series` every verdict equal to the
//!   reference's and the largest relative error of λ (where both are chaotic).
//!
//! Run-length and window rows describe the run, not the model, and are never chosen (the
//! scene's `[run]` is kept). Among the eligible the smallest measured CPU time per point
//! wins; if none is eligible the scene is run as written (the reference's settings) and the
//! reason says why.
//!
//! # Pitfalls
//! The table was measured on the source's scene B (Sánchez 2012 §3.2); for other scenes it is
//! a guide by analogy, and the reason says so. Only single changes from the reference were
//! measured, so combinations are never chosen.

use serde::Serialize;

use crate::error::{DataError, SceneError};
use crate::scene::dem::{ContactKind, DemParams, TangentialKind};
use crate::scene::{Damper, Outputs, Scene};

use super::ladder::DEFAULT_YIELD_STRENGTH_PA;
use super::ladder::{
    design_restitution, ladder, one_particle, with_count_at_fixed_mass, Axis, Change, Gap,
};
use super::measured::{read_settings, MeasuredSetting};

/// The built-in measured table (scene B), with its provenance header.
pub const BUILTIN_TABLE: &str = include_str!("../../data/reference/tradeoff_settings.csv");

/// Fewest frequencies at which a setting must have been compared with the reference.
pub const MIN_COMPARED: usize = 3;

/// Volume fraction assumed for the settled bed when the one-particle gap is estimated for a
/// scene other than the measured one (random packing, 0.55–0.64; scene B's settled bed
/// measures ≈ 0.6).
pub const BED_VOLUME_FRACTION: f64 = 0.6;

/// Scene B's grain count, for which the ladder's rung identifiers were made.
const SCENE_B_COUNT: usize = 250;

/// What `auto` chose.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AutoChoice {
    /// The concrete scene that is simulated (damper `impact` or `dem`).
    #[serde(skip)]
    pub scene: Scene,
    /// `impact` or `dem`.
    pub model: String,
    /// The measured setting used (identifier of the table's row).
    pub setting: String,
    /// Its axis.
    pub axis: String,
    /// Measured largest relative error of Z (–).
    pub measured_amplitude_error: Option<f64>,
    /// Measured largest relative error of the dissipation (–).
    pub measured_dissipation_error: Option<f64>,
    /// Measured speed-up over the reference (–).
    pub measured_speedup: Option<f64>,
    /// Why, in words.
    pub reason: String,
    /// What is not computed because no requested output needs it.
    pub skipped: Vec<String>,
}

/// The built-in table, parsed.
///
/// # Errors
/// [`DataError`] if the built-in file is malformed (a build defect; tested).
pub fn builtin_table() -> Result<Vec<MeasuredSetting>, DataError> {
    read_settings(BUILTIN_TABLE, "data/reference/tradeoff_settings.csv")
}

/// Chooses for a scene with `kind = "auto"` using the built-in table. Other scenes are
/// returned unchanged with `model` = their kind and reason "not auto".
///
/// # Errors
/// [`SceneError`] if the scene's grains cannot be rescaled (invalid radii) or the built-in
/// table cannot be read.
pub fn choose(scene: &Scene) -> Result<AutoChoice, SceneError> {
    let table =
        builtin_table().map_err(|e| SceneError::Parse(format!("built-in trade-off table: {e}")))?;
    choose_with(scene, &table)
}

/// Whether `s` can deliver `o` (ignoring the tolerance).
pub fn delivers(s: &MeasuredSetting, o: &Outputs) -> bool {
    match s.axis {
        Axis::Reference | Axis::RunLength | Axis::Window => false,
        Axis::OneParticle => !o.needs_grains(),
        Axis::GrainCount => !(o.grain_snapshots || o.orientations),
        Axis::Rotations => !o.orientations,
        Axis::Friction => !o.energies_by_mechanism,
        _ => true,
    }
}

/// Whether the measured errors of `s` are within `o.tolerance` (see the module's rules).
pub fn accurate_enough(s: &MeasuredSetting, o: &Outputs) -> bool {
    let within = |e: Option<f64>| e.is_some_and(|e| e <= o.tolerance);
    let within_if_any = |e: Option<f64>| e.is_none_or(|e| e <= o.tolerance);
    within(s.amplitude_max_rel_error)
        && (!o.frf_only || within(s.resonance_frequency_rel_error))
        && (!o.energies_by_mechanism || within(s.dissipation_max_rel_error))
        && (!o.zcm_series
            || (s.regime_compared > 0
                && s.regime_matches == s.regime_compared
                && within_if_any(s.mle_max_rel_error)))
}

fn measured_enough(s: &MeasuredSetting, reference: &MeasuredSetting) -> bool {
    s.frequencies_compared >= MIN_COMPARED
        && s.frequencies_compared >= reference.frequencies_compared
        && s.core_seconds_per_point.is_some()
}

/// As [`choose`] with an explicit table.
///
/// # Errors
/// See [`choose`]; a table without a reference row.
pub fn choose_with(scene: &Scene, table: &[MeasuredSetting]) -> Result<AutoChoice, SceneError> {
    let Damper::Auto(params) = &scene.damper else {
        return Ok(AutoChoice {
            scene: scene.clone(),
            model: scene.damper.kind().into(),
            setting: "as written".into(),
            axis: "none".into(),
            measured_amplitude_error: None,
            measured_dissipation_error: None,
            measured_speedup: None,
            reason: "damper.kind is not \"auto\"".into(),
            skipped: Vec::new(),
        });
    };
    let o = &scene.outputs;
    let reference = table
        .iter()
        .find(|s| s.axis == Axis::Reference)
        .ok_or_else(|| SceneError::Parse("trade-off table has no reference row".into()))?;
    // the table was measured on a box on a vertical base drive under gravity along −z: another
    // drive, axis, gravity, a rotating frame or a cylinder is not covered by it, and runs as
    // written
    let e = &scene.excitation;
    let in_a_box = params.container.is_box();
    let measured_drive = e.kind == crate::scene::DriveKind::Base
        && e.is_vertical()
        && scene.environment.gravity.is_none()
        && scene.environment.rotation.is_none()
        && in_a_box;
    let mut eligible: Vec<&MeasuredSetting> = table
        .iter()
        .filter(|s| delivers(s, o) && measured_enough(s, reference) && accurate_enough(s, o))
        .filter(|_| measured_drive)
        .collect();
    let cost = |s: &MeasuredSetting| s.core_seconds_per_point.unwrap_or(f64::INFINITY);
    eligible.sort_by(|a, b| cost(a).total_cmp(&cost(b)));
    let (pick, mut reason) = match eligible.first() {
        Some(s) => (
            *s,
            format!(
                "row `{}` of the measured table: the cheapest of {} settings that deliver the \
                 requested outputs within tolerance {} (largest Z error {}, resonance frequency \
                 error {}, {} of {} verdicts as the reference's, {} faster than the reference, \
                 measured at {} frequencies)",
                s.setting,
                eligible.len(),
                o.tolerance,
                fmt_err(s.amplitude_max_rel_error),
                fmt_err(s.resonance_frequency_rel_error),
                s.regime_matches,
                s.regime_compared,
                s.speedup.map_or("n/a".into(), |x| format!("{x:.1}×")),
                s.frequencies_compared
            ),
        ),
        None if !measured_drive => (
            reference,
            format!(
                "the settings were measured on a box on a vertical base drive under gravity \
                 along −z, and this scene has a {} drive along {:?}{}{}{}: the scene is run as \
                 written (the reference's settings)",
                e.kind.name(),
                e.unit_direction(),
                if scene.environment.gravity.is_some() {
                    " with its own gravity"
                } else {
                    ""
                },
                if scene.environment.rotation.is_some() {
                    " in a rotating frame"
                } else {
                    ""
                },
                if in_a_box { "" } else { " in a cylinder" }
            ),
        ),
        None => (
            reference,
            format!(
                "no measured setting meets tolerance {} for these outputs at every frequency \
                 the reference was measured at ({} of {}); the scene is run as written (the \
                 reference's settings)",
                o.tolerance, reference.frequencies_compared, reference.frequencies
            ),
        ),
    };
    reason.push_str(
        "; errors measured on the source's scene B (Sánchez 2012 §3.2, \
         figures/tradeoff_settings.csv), applied here by analogy",
    );
    let (concrete, model) = concretise(scene, params, pick)?;
    Ok(AutoChoice {
        scene: concrete,
        model: model.into(),
        setting: pick.setting.clone(),
        axis: pick.axis.as_str().into(),
        measured_amplitude_error: pick.amplitude_max_rel_error,
        measured_dissipation_error: pick.dissipation_max_rel_error,
        measured_speedup: pick.speedup,
        reason,
        skipped: skipped(o, model),
    })
}

fn fmt_err(e: Option<f64>) -> String {
    e.map_or("n/a".into(), |e| format!("{:.1} %", 100.0 * e))
}

/// The change of the table's row `id` (the ladder's rung of that identifier; a grain-count
/// rung keeps its ratio to scene B's count).
fn change_of(id: &str, count: usize) -> Change {
    let found = ladder(SCENE_B_COUNT, None)
        .into_iter()
        .find(|r| r.id == id)
        .map_or(Change::None, |r| r.change);
    match found {
        Change::GrainCount(n) => Change::GrainCount((count * n / SCENE_B_COUNT).max(1)),
        c => c,
    }
}

/// The concrete scene for a measured setting.
fn concretise(
    scene: &Scene,
    params: &DemParams,
    s: &MeasuredSetting,
) -> Result<(Scene, &'static str), SceneError> {
    let o = &scene.outputs;
    let mut out = scene.clone();
    let mut p = params.clone();
    match change_of(&s.setting, params.count) {
        Change::OneParticle { restitution, gap } => {
            let gap_m = match gap {
                Gap::Given(g) if scene_b_like(params) => g,
                _ => params.r#box[2] - estimated_bed_height_m(params)?,
            };
            out.damper = Damper::Impact(one_particle(params, restitution, gap_m.max(0.0))?);
            return Ok((out, "impact"));
        }
        Change::DtFraction(f) => out.run.dt_fraction = f,
        Change::Soften(f) => p = p.softened(f),
        Change::LinearLaw => {
            let drive = crate::dem::BoxDrive {
                primary: None,
                amplitude_m: scene.excitation.amplitude,
                frequency_hz: scene.excitation.frequency,
                force_n: 0.0,
                direction: [0.0, 0.0, 1.0],
            };
            p.restitution = Some(design_restitution(&p, &drive)?);
            p.contact = ContactKind::Linear;
            p.yield_strength = Some(p.yield_strength.unwrap_or(DEFAULT_YIELD_STRENGTH_PA));
        }
        Change::Mindlin => p.tangential = TangentialKind::Mindlin,
        Change::RotationsOff => p.rotations = false,
        Change::FrictionOff => {
            p.friction = 0.0;
            p.wall_friction = Some(0.0);
        }
        Change::GrainCount(n) => p = with_count_at_fixed_mass(&p, n)?,
        Change::None | Change::Periods(_) | Change::Window(_) => {}
    }
    p.orientations = o.orientations;
    if o.orientations {
        p.rotations = true;
    }
    p.snapshot_interval = if o.grain_snapshots {
        Some(p.snapshot_interval.unwrap_or(0.01))
    } else {
        None
    };
    out.damper = Damper::Dem(p);
    Ok((out, "dem"))
}

/// Height of the settled bed (m) estimated from its mass at [`BED_VOLUME_FRACTION`] (for a
/// scene whose bed was not measured).
fn estimated_bed_height_m(p: &DemParams) -> Result<f64, SceneError> {
    let mass = super::ladder::bed_mass_kg(p)?;
    Ok(mass / p.density / (p.r#box[0] * p.r#box[1] * BED_VOLUME_FRACTION))
}

/// Whether the grains are scene B's box and mass (the given gap was measured for it).
fn scene_b_like(p: &DemParams) -> bool {
    let b = DemParams::thesis_b();
    p.r#box == b.r#box && p.count == b.count && p.radius == b.radius && p.density == b.density
}

fn skipped(o: &Outputs, model: &str) -> Vec<String> {
    let mut v = Vec::new();
    if model == "impact" {
        v.push("individual grains (one effective particle, SPEC §3)".into());
    }
    if model == "dem" {
        if !o.orientations {
            v.push("orientations (quaternions not tracked)".into());
        }
        if !o.grain_snapshots {
            v.push("grain snapshots (none written)".into());
        }
    }
    if !o.zcm_series {
        v.push(
            "nonlinear analysis of z_cm (not requested; `pdamp simulate --no-analysis` skips it)"
                .into(),
        );
    }
    v
}

/// Prints nothing; returns the stderr line `auto: …` describing a choice (for the CLI).
pub fn describe(c: &AutoChoice) -> String {
    format!(
        "auto: {} ({}), measured largest Z error {}: {}. Not computed: {}",
        c.model,
        c.setting,
        fmt_err(c.measured_amplitude_error),
        c.reason,
        if c.skipped.is_empty() {
            "nothing".into()
        } else {
            c.skipped.join("; ")
        }
    )
}
