//! The linear-DEM paper's §3.1 (`../shared/seeds`): Saeki's non-obstructive particle damper
//! (J. Sound Vib. 251 (2002) 153), a box on a leaf spring vibrated horizontally at the
//! primary's natural frequency, with grains of four materials at one grain-to-primary mass
//! ratio (0.092). The paper (experiment and simulation) finds lead attenuating least: the
//! densest grains are the fewest at a given mass.

use crate::error::StudyError;
use crate::plot::lines::LinesFigure;
use crate::plot::Series;

use super::pipeline::{BundledScene, Ctx, FigureRecord};

/// The figures of this module (for `--only`).
pub(super) const NAMES: [&str; 1] = ["saeki_materials"];

/// `data/scenes/saeki_2002.toml`.
pub const SAEKI: BundledScene = BundledScene {
    path: "data/scenes/saeki_2002.toml",
    text: include_str!("../../data/scenes/saeki_2002.toml"),
};

/// The paper's four grain materials, as `damper.material` presets.
const MATERIALS: [&str; 4] = ["lead", "sus304", "steel", "acrylic"];

/// Steady amplitude of the primary per grain material, against the number of grains the
/// material gives at the scene's grain mass.
pub(super) fn saeki_materials(ctx: &Ctx) -> Result<FigureRecord, StudyError> {
    let name = "saeki_materials";
    let sweep = ctx.sweep(
        "saeki_2002",
        SAEKI,
        &[],
        &[("damper.material", MATERIALS.join(","))],
        false,
    )?;
    let mut rows = Vec::new();
    let mut data = Vec::new();
    let mut reference = f64::NAN;
    for (k, m) in MATERIALS.iter().enumerate() {
        let p = sweep
            .points
            .iter()
            .find(|p| p.values.iter().any(|(_, v)| v.as_str() == Some(m)))
            .ok_or_else(|| StudyError::step(name, format!("no point for material {m}")))?;
        let s = &p.summary;
        let grains = s.dem.as_ref().map_or(f64::NAN, |d| d.grains);
        let z0 = s.reference_amplitude_m.unwrap_or(f64::NAN);
        reference = z0;
        rows.push(vec![
            k as f64,
            grains,
            s.amplitude_m,
            z0,
            1.0 - s.amplitude_m / z0,
        ]);
        data.push(((*m).to_string(), vec![grains], vec![s.amplitude_m]));
    }
    ctx.write_csv(
        name,
        &[
            "material_index",
            "grains",
            "amplitude_m",
            "primary_alone_amplitude_m",
            "attenuation",
        ],
        &rows,
    )?;
    let series = data
        .iter()
        .map(|(l, x, y)| Series { label: l, x, y })
        .collect();
    let size = ctx.render(
        name,
        &LinesFigure {
            series,
            x_label: "grains in the box (at 0.092 × M of grains)".into(),
            y_label: "steady amplitude of the primary Z (mm)".into(),
            y_scale: 1e3,
            title: "Saeki's horizontal damper: amplitude per grain material".into(),
            kind: "saeki",
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: format!(
            "DEM, Saeki's non-obstructive damper (linear-DEM paper §3.1): a 58 × 38 × 38 mm box \
             on a primary (M = 0.293 kg, k = 1602.7 N/m, c = 0.116 N s/m) driven horizontally \
             through its base, U = 1 mm at f0 = 11.77 Hz, 6 mm grains of 0.092 M; linear \
             spring–dashpot contacts from each material's yield strength. Steady amplitude of \
             the primary (last 20 % of 300 periods) against the number of grains; the primary \
             alone reaches {:.1} mm. The paper finds lead (fewest grains) attenuating least.",
            reference * 1e3
        ),
        spec_item: "linear-DEM paper §3.1: amplitude per grain material".into(),
        commands: sweep.commands.clone(),
        reductions: Vec::new(),
        size_px: size,
    })
}
