//! The small kit shared by the figure families: scene B's values (SPEC §6), fits of (2.1.21)
//! to groups of sweep points, and the drawings more than one family makes (effective mass,
//! bed motion, labelled lines).

use crate::analysis::frf_fit::{fit_frf_groups, FrfFitOptions, FrfGroupFit};
use crate::error::StudyError;
use crate::model::PrimarySystem;
use crate::plot::bed_motion::BedMotionFigure;
use crate::plot::effective::EffectiveFigure;
use crate::plot::frf::FrfReference;
use crate::plot::lines::LinesFigure;
use crate::plot::Series;
use crate::sweep::SweepPoints;

use super::check::EffectiveRow;
use super::command::Command;
use super::pipeline::{Ctx, Recorded};

/// Scene B's primary system and grains (SPEC §6): M, m_p, K, C, U.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneB {
    /// The primary system M, K, C.
    pub primary: PrimarySystem,
    /// Grain mass m_p (kg).
    pub particle_mass_kg: f64,
    /// Base amplitude U (m).
    pub base_amplitude_m: f64,
}

/// Scene B's values (Sánchez 2012 §3.2).
pub const SCENE_B: SceneB = SceneB {
    primary: PrimarySystem {
        mass_kg: 2.37,
        stiffness_n_m: 21500.0,
        damping_n_s_m: 7.6,
    },
    particle_mass_kg: 0.227,
    base_amplitude_m: 4.5e-3,
};

impl SceneB {
    /// The FRF reference curves for M and M + m_p.
    pub fn reference(&self) -> FrfReference {
        FrfReference {
            primary: self.primary,
            particle_mass_kg: Some(self.particle_mass_kg),
            base_amplitude_m: self.base_amplitude_m,
        }
    }
}

/// Fits (2.1.21) to each group of points (grouped by varied key `key`; `None`: all points as
/// one group), with K and U of scene B.
///
/// # Errors
/// [`StudyError::Step`] naming `step` if a point lacks `key` or a fit fails.
pub fn fit_groups(
    step: &str,
    pts: &SweepPoints,
    key: Option<&str>,
) -> Result<Vec<EffectiveRow>, StudyError> {
    let f = pts.map(|s| s.frequency_hz);
    let z = pts.map(|s| s.amplitude_m);
    let g = key
        .map(|k| pts.values(k))
        .transpose()
        .map_err(|e| StudyError::step(step, e))?;
    let opts = FrfFitOptions::new(SCENE_B.primary.stiffness_n_m, SCENE_B.base_amplitude_m);
    let fits = fit_frf_groups(&f, &z, g.as_deref(), &opts).map_err(|e| {
        let x = e.group_value.unwrap_or(f64::NAN);
        StudyError::step(
            step,
            format!("fit at {} = {x}: {}", key.unwrap_or("group"), e.error),
        )
    })?;
    Ok(fits
        .into_iter()
        .map(|FrfGroupFit { group_value, fit }| EffectiveRow {
            x_m: group_value.unwrap_or(f64::NAN),
            mass_ef_kg: fit.mass_ef_kg,
            mass_ef_stderr_kg: fit.mass_ef_stderr_kg,
            damping_ef_n_s_m: fit.damping_ef_n_s_m,
            damping_ef_stderr_n_s_m: fit.damping_ef_stderr_n_s_m,
        })
        .collect())
}

/// `pdamp fit-frf` of each sweep table (K and U of scene B; M for the ratios), then
/// `pdamp plot effective` of the figure's own CSV (`OUT/<name>.csv`, one row per fit).
pub fn effective_commands<P: AsRef<std::path::Path>>(
    ctx: &Ctx,
    name: &str,
    csv: &[P],
    x_column: &str,
) -> Vec<Command> {
    let b = SCENE_B;
    let mut out: Vec<Command> = csv
        .iter()
        .map(|p| {
            Command::new(["fit-frf"])
                .path(p.as_ref())
                .opt("stiffness", b.primary.stiffness_n_m)
                .opt("base-amplitude", b.base_amplitude_m)
                .opt("mass", b.primary.mass_kg)
        })
        .collect();
    out.push(
        Command::plot(
            "effective",
            &[ctx.path(&format!("{name}.csv"))],
            &ctx.path(&format!("{name}.png")),
        )
        .opt("x", x_column)
        .opt("mass", b.primary.mass_kg)
        .opt("damping", b.primary.damping_n_s_m),
    );
    out
}

/// Draws an effective-mass figure from fits and writes its CSV.
///
/// # Errors
/// [`StudyError`] from rendering or writing.
pub fn draw_effective(
    ctx: &Ctx,
    name: &str,
    rows: &[EffectiveRow],
    x_label: &str,
    x_column: &str,
) -> Result<(u32, u32), StudyError> {
    let x: Vec<f64> = rows.iter().map(|r| r.x_m).collect();
    let me: Vec<f64> = rows.iter().map(|r| r.mass_ef_kg).collect();
    let ms: Vec<f64> = rows.iter().map(|r| r.mass_ef_stderr_kg).collect();
    let ce: Vec<f64> = rows.iter().map(|r| r.damping_ef_n_s_m).collect();
    let cs: Vec<f64> = rows.iter().map(|r| r.damping_ef_stderr_n_s_m).collect();
    ctx.write_csv(
        name,
        &[
            x_column,
            "mass_ef_kg",
            "mass_ef_stderr_kg",
            "damping_ef_ns_per_m",
            "damping_ef_stderr_ns_per_m",
        ],
        &rows
            .iter()
            .map(|r| {
                vec![
                    r.x_m,
                    r.mass_ef_kg,
                    r.mass_ef_stderr_kg,
                    r.damping_ef_n_s_m,
                    r.damping_ef_stderr_n_s_m,
                ]
            })
            .collect::<Vec<_>>(),
    )?;
    ctx.render(
        name,
        &EffectiveFigure {
            x: &x,
            x_label: x_label.into(),
            mass_ef_kg: &me,
            mass_ef_stderr_kg: &ms,
            damping_ef_n_s_m: &ce,
            damping_ef_stderr_n_s_m: &cs,
            mass_kg: Some(SCENE_B.primary.mass_kg),
            damping_n_s_m: Some(SCENE_B.primary.damping_n_s_m),
        },
    )
}

/// Draws a bed-motion figure of the last `periods` forcing periods of a recorded run and writes
/// its CSV.
///
/// # Errors
/// [`StudyError`] from rendering or writing.
pub fn draw_bed_motion(ctx: &Ctx, name: &str, r: &Recorded) -> Result<(u32, u32), StudyError> {
    let band = (!r.grain_zmin_m.is_empty()).then_some((&r.grain_zmin_m[..], &r.grain_zmax_m[..]));
    let rows: Vec<Vec<f64>> = (0..r.time_s.len())
        .map(|i| {
            let mut v = vec![
                r.time_s[i],
                r.floor_z_m[i],
                r.ceiling_z_m[i],
                r.grain_z_m[i],
                r.grain_force_n[i],
            ];
            if let Some((lo, hi)) = band {
                v.extend([lo[i], hi[i]]);
            }
            v
        })
        .collect();
    let mut header = vec![
        "time_s",
        "floor_z_m",
        "ceiling_z_m",
        "grain_z_m",
        "grain_force_n",
    ];
    if band.is_some() {
        header.extend(["grain_zmin_m", "grain_zmax_m"]);
    }
    ctx.write_csv(name, &header, &rows)?;
    ctx.render(
        name,
        &BedMotionFigure {
            time_s: &r.time_s,
            floor_z_m: &r.floor_z_m,
            ceiling_z_m: &r.ceiling_z_m,
            grain_z_m: &r.grain_z_m,
            grain_band: band,
            grain_force_n: Some(&r.grain_force_n),
        },
    )
}

/// The values of varied key `key` of every point, or a study error naming `step`.
///
/// # Errors
/// [`StudyError::Step`] if a point lacks `key`.
pub fn key_values(step: &str, pts: &SweepPoints, key: &str) -> Result<Vec<f64>, StudyError> {
    pts.values(key).map_err(|e| StudyError::step(step, e))
}

/// Z_res per value of varied key `key`: the largest amplitude of each group of points (over
/// the frequencies), groups by increasing value.
///
/// # Errors
/// [`StudyError::Step`] if a point lacks `key`.
pub fn resonance_curve(
    step: &str,
    pts: &SweepPoints,
    key: &str,
) -> Result<(Vec<f64>, Vec<f64>), StudyError> {
    Ok(pts
        .group_by(key)
        .map_err(|e| StudyError::step(step, e))?
        .into_iter()
        .filter_map(|(x, group)| {
            let z = group
                .iter()
                .map(|p| p.summary.amplitude_m)
                .reduce(f64::max)?;
            Some((x, z))
        })
        .unzip())
}

/// A lines figure with explicit labels (used by the DEM figures too).
pub fn lines<'a>(
    series: Vec<Series<'a>>,
    x_label: &str,
    y_label: &str,
    y_scale: f64,
    title: &str,
) -> LinesFigure<'a> {
    LinesFigure {
        series,
        x_label: x_label.into(),
        y_label: y_label.into(),
        y_scale,
        title: title.into(),
        kind: "lines",
    }
}
