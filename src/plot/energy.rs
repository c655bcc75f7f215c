//! Energy dissipated per forcing cycle by each mechanism (collision, friction, impact,
//! viscous …) versus the forcing frequency or the container height (SPEC §7).

use super::common::Series;
use super::lines::LinesFigure;

/// Builds the energy-per-cycle figure: one curve per `energy_*_j_per_cycle` column.
///
/// `x` is the swept variable (e.g. `frequency_hz` or `damper.box`), `columns` pairs a legend
/// label (e.g. `collision`) with its values in joules per cycle (same length as `x`).
/// Validation (lengths, NaN) happens when the figure is rendered.
pub fn energy_figure<'a>(
    x: &'a [f64],
    x_label: &str,
    columns: &[(&'a str, &'a [f64])],
) -> LinesFigure<'a> {
    LinesFigure {
        series: columns
            .iter()
            .map(|&(label, y)| Series { label, x, y })
            .collect(),
        x_label: x_label.to_string(),
        y_label: "energy dissipated per cycle (J)".into(),
        y_scale: 1.0,
        title: "Energy dissipated per forcing cycle".into(),
        kind: "energy",
    }
}

/// Legend label for an energy column: `energy_collision_j_per_cycle` → `collision`.
pub fn energy_label(column: &str) -> &str {
    column
        .strip_prefix("energy_")
        .and_then(|c| c.strip_suffix("_j_per_cycle"))
        .unwrap_or(column)
}
