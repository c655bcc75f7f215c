//! `[damper] kind = "auto"`: pick the cheapest model and settings that deliver the scene's
//! `[outputs]` within its tolerance, from the measured speed/accuracy table
//! (`data/reference/tradeoff_scene_b.csv`, built into the binary), and say which and why.
//!
//! # Rules
//! A measured setting is eligible when all its runs finished, its largest relative error of
//! Z (and, with `energies_by_mechanism`, of the grains' dissipation per cycle) is ≤
//! `outputs.tolerance`, and it can deliver
//! the outputs:
//! - grain outputs (`grain_snapshots`, `orientations`, `energies_by_mechanism`) exclude the
//!   one-particle model;
//! - `grain_snapshots` and `orientations` exclude a different N (they are about the scene's
//!   grains); `orientations` excludes rotations off; `energies_by_mechanism` excludes friction
//!   off (the friction share would vanish);
//! - `zcm_series` requires the regime verdict of the reference at every measured frequency.
//!
//! Run-length and steady-window rows describe the run, not the model, and are not chosen
//! (the scene's `[run]` is kept). Among the eligible, the smallest measured wall time wins;
//! if none is eligible the reference is used and the reason says so.
//!
//! # Pitfalls
//! The table was measured on the source's scene B (Sánchez 2012 §3.2) at three frequencies;
//! for other scenes it is a guide by analogy, and the reason says so. Only single changes
//! from the reference were measured, so combinations are never chosen.

use serde::Serialize;

use crate::error::{DataError, SceneError};
use crate::scene::dem::DemParams;
use crate::scene::{Damper, DtSpec, ImpactParams, Outputs, Scene};

use super::ladder::{soften, with_count_at_fixed_mass, Axis, LadderOptions};
use super::table::{read_settings, MeasuredSetting};

/// The built-in measured table (scene B), with its provenance header.
pub const BUILTIN_TABLE: &str = include_str!("../../data/reference/tradeoff_scene_b.csv");

/// Volume fraction assumed for the settled bed when the one-particle gap is estimated
/// (random packing, 0.55–0.64; the DEM's settled scene B bed measures ≈ 0.6).
pub const BED_VOLUME_FRACTION: f64 = 0.6;

/// What `auto` chose.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AutoChoice {
    /// The concrete scene that is simulated (damper `impact` or `dem`).
    #[serde(skip)]
    pub scene: Scene,
    /// `impact` or `dem`.
    pub model: String,
    /// The measured setting used (label of the table).
    pub setting: String,
    /// Its axis.
    pub axis: String,
    /// Measured largest relative error of Z (–).
    pub measured_amplitude_error: Option<f64>,
    /// Measured largest relative error of the dissipation (–).
    pub measured_dissipation_error: Option<f64>,
    /// Measured speed-up over the reference (–).
    pub measured_speedup: f64,
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
    read_settings(BUILTIN_TABLE, "data/reference/tradeoff_scene_b.csv")
}

/// Reference settings of a table, from its `# reference_softening = …` and
/// `# reference_dt_fraction = …` header lines (defaults: [`LadderOptions::default`]).
pub fn table_reference(text: &str) -> LadderOptions {
    let mut o = LadderOptions::default();
    for line in text.lines().filter_map(|l| l.strip_prefix("# ")) {
        let mut kv = line.splitn(2, '=').map(str::trim);
        if let (Some(k), Some(Ok(v))) = (kv.next(), kv.next().map(str::parse::<f64>)) {
            match k {
                "reference_softening" => o.reference_softening = v,
                "reference_dt_fraction" => o.reference_dt_fraction = v,
                _ => {}
            }
        }
    }
    o
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
    choose_with(scene, &table, &table_reference(BUILTIN_TABLE))
}

/// Whether `s` can deliver `o` (ignoring the tolerance).
pub fn delivers(s: &MeasuredSetting, o: &Outputs) -> bool {
    match s.axis {
        Axis::RunLength | Axis::SteadyFraction => false,
        Axis::OneParticle => !o.needs_grains(),
        Axis::GrainCount => !(o.grain_snapshots || o.orientations),
        Axis::Rotations => !o.orientations,
        Axis::Friction => !o.energies_by_mechanism,
        _ => true,
    }
}

/// Whether the measured errors of `s` are within `o.tolerance` (and, for `zcm_series`, the
/// regime matched the reference's at every frequency; `regime_known` = false when the table
/// was measured without the analysis, then only the errors count).
pub fn accurate_enough(s: &MeasuredSetting, o: &Outputs, regime_known: bool) -> bool {
    let within = |e: Option<f64>| e.is_some_and(|e| e <= o.tolerance);
    // the dissipation error counts only when its split is requested: over short runs it is
    // dominated by cycle-to-cycle scatter (the reference's own steady-window rows show ~10 %)
    let dissipation_ok = !o.energies_by_mechanism
        || s.dissipation_max_rel_error
            .is_some_and(|e| e <= o.tolerance);
    let regime_ok = !o.zcm_series || !regime_known || s.regime_matches == s.runs;
    s.complete && within(s.amplitude_max_rel_error) && dissipation_ok && regime_ok
}

/// As [`choose`] with an explicit table and its reference settings.
///
/// # Errors
/// See [`choose`].
pub fn choose_with(
    scene: &Scene,
    table: &[MeasuredSetting],
    reference: &LadderOptions,
) -> Result<AutoChoice, SceneError> {
    let Damper::Auto(params) = &scene.damper else {
        return Ok(AutoChoice {
            scene: scene.clone(),
            model: scene.damper.kind().into(),
            setting: "as written".into(),
            axis: "none".into(),
            measured_amplitude_error: None,
            measured_dissipation_error: None,
            measured_speedup: 1.0,
            reason: "damper.kind is not \"auto\"".into(),
            skipped: Vec::new(),
        });
    };
    let o = &scene.outputs;
    let regime_known = table
        .iter()
        .any(|s| s.axis == Axis::Reference && s.regime_matches > 0);
    let ref_row = table.iter().find(|s| s.axis == Axis::Reference);
    let ref_wall = ref_row.map_or(f64::NAN, |r| r.wall_time_s);
    let mut eligible: Vec<&MeasuredSetting> = table
        .iter()
        .filter(|s| s.axis != Axis::Reference)
        .filter(|s| {
            delivers(s, o) && accurate_enough(s, o, regime_known) && s.wall_time_s.is_finite()
        })
        .collect();
    eligible.sort_by(|a, b| a.wall_time_s.total_cmp(&b.wall_time_s));
    let (pick, why) = match (eligible.first(), ref_row) {
        (Some(s), _) => (
            (*s).clone(),
            format!(
                "cheapest of {} measured settings that deliver the requested outputs within tolerance {}: \
                 largest Z error {}, {:.1}× faster than the reference",
                eligible.len(),
                o.tolerance,
                fmt_err(s.amplitude_max_rel_error),
                ref_wall / s.wall_time_s
            ),
        ),
        (None, Some(r)) => (
            r.clone(),
            format!(
                "no measured cheaper setting meets tolerance {} for these outputs; using the reference \
                 (the most accurate affordable setting measured)",
                o.tolerance
            ),
        ),
        (None, None) => {
            return Err(SceneError::Parse("trade-off table has no reference row".into()));
        }
    };
    let mut reason = why;
    if o.zcm_series && !regime_known {
        reason.push_str("; the table carries no regime verdicts, so only the Z and dissipation errors were checked");
    }
    reason.push_str(
        "; errors measured on the source's scene B (Sánchez 2012 §3.2) at 3 frequencies, applied here by analogy",
    );
    let (concrete, model) = concretise(scene, params, &pick, reference_case(reference))?;
    Ok(AutoChoice {
        scene: concrete,
        model: model.into(),
        setting: pick.setting.clone(),
        axis: pick.axis.as_str().into(),
        measured_amplitude_error: pick.amplitude_max_rel_error,
        measured_dissipation_error: pick.dissipation_max_rel_error,
        measured_speedup: ref_wall / pick.wall_time_s,
        reason,
        skipped: skipped(o, model),
    })
}

fn reference_case(r: &LadderOptions) -> (f64, f64) {
    (r.reference_softening, r.reference_dt_fraction)
}

fn fmt_err(e: Option<f64>) -> String {
    e.map_or("n/a".into(), |e| format!("{:.1} %", 100.0 * e))
}

/// The concrete scene for a measured setting.
fn concretise(
    scene: &Scene,
    params: &DemParams,
    s: &MeasuredSetting,
    (soft, dt_fraction): (f64, f64),
) -> Result<(Scene, &'static str), SceneError> {
    let o = &scene.outputs;
    let mut out = scene.clone();
    if s.axis == Axis::OneParticle {
        let dist = params.radius_distribution()?;
        let radii = dist.sample_n(params.count, params.seed);
        let v: f64 = radii
            .iter()
            .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3))
            .sum();
        let bed = v / (params.r#box[0] * params.r#box[1] * BED_VOLUME_FRACTION);
        out.damper = Damper::Impact(ImpactParams {
            mass: v * params.density,
            gap: (params.r#box[2] - bed).max(0.0),
            restitution: if s.value.is_finite() {
                s.value.clamp(0.0, 1.0)
            } else {
                0.0
            },
            initial_height: 0.0,
            initial_velocity: 0.0,
        });
        return Ok((out, "impact"));
    }
    let (mut soft, mut dtf) = (soft, dt_fraction);
    let mut p = params.clone();
    match s.axis {
        Axis::DtFraction => dtf = s.value,
        Axis::Softening => soft = s.value,
        Axis::ContactLaw => {
            let drive = crate::dem::BoxDrive {
                primary: None,
                amplitude_m: scene.excitation.amplitude,
                frequency_hz: scene.excitation.frequency,
            };
            let e = super::ladder::design_restitution(&p, &drive)?;
            p.contact = crate::scene::dem::ContactKind::Linear;
            p.restitution = Some(e);
            p.yield_strength = Some(
                p.yield_strength
                    .unwrap_or(super::ladder::DEFAULT_YIELD_STRENGTH_PA),
            );
        }
        Axis::Rotations => p.rotations = false,
        Axis::Friction => {
            p.friction = 0.0;
            p.wall_friction = Some(0.0);
        }
        Axis::GrainCount if s.value >= 1.0 => p = with_count_at_fixed_mass(&p, s.value as usize)?,
        _ => {}
    }
    let mut p = soften(&p, soft);
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
    out.run.dt = Some(DtSpec::Auto);
    out.run.dt_fraction = dtf;
    Ok((out, "dem"))
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
        "auto: {} ({}), measured Z error {}, {:.1}× faster than the reference: {}. Not computed: {}",
        c.model,
        c.setting,
        fmt_err(c.measured_amplitude_error),
        c.measured_speedup,
        c.reason,
        if c.skipped.is_empty() { "nothing".into() } else { c.skipped.join("; ") }
    )
}
