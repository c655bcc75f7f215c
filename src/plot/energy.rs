//! Energy per forcing cycle by mechanism (the input, base work, beside what collisions,
//! friction and viscous damping dissipate) versus the forcing frequency or the container
//! height (SPEC §7), and the energy ledger of one DEM run over time.

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
        y_label: "energy per cycle (J)".into(),
        y_scale: 1.0,
        title: "Energy per forcing cycle: input and dissipation by mechanism".into(),
        kind: "energy",
    }
}

/// The ledger columns of a DEM run's `series.csv` drawn by [`ledger_figure`], with their
/// legend labels: cumulative input and dissipation, the stored energies, and the residual.
pub const LEDGER_COLUMNS: [(&str, &str); 9] = [
    ("e_base_work_j", "input: base work on the system"),
    ("e_collision_j", "dissipated: collisions"),
    ("e_friction_j", "dissipated: friction"),
    ("e_viscous_j", "dissipated: viscous (primary)"),
    ("e_kinetic_j", "stored: grains' kinetic"),
    ("e_potential_j", "stored: grains' potential"),
    ("e_elastic_j", "stored: contacts' elastic"),
    ("e_primary_j", "stored: primary (kinetic + spring)"),
    ("e_balance_residual_j", "balance residual"),
];

/// The energy ledger of one run over time: one curve per `(label, values)` of
/// [`LEDGER_COLUMNS`] against `time_s`.
pub fn ledger_figure<'a>(time_s: &'a [f64], columns: &[(&'a str, &'a [f64])]) -> LinesFigure<'a> {
    LinesFigure {
        series: columns
            .iter()
            .map(|&(label, y)| Series {
                label,
                x: time_s,
                y,
            })
            .collect(),
        x_label: "time t (s)".into(),
        y_label: "energy since the start (J)".into(),
        y_scale: 1.0,
        title: "Energy ledger of the run".into(),
        kind: "energy",
    }
}

/// Legend label for an energy column: `energy_collision_j_per_cycle` → `dissipated:
/// collision`, `energy_base_work_j_per_cycle` → `input: base work`.
pub fn energy_label(column: &str) -> String {
    let name = column
        .strip_prefix("energy_")
        .and_then(|c| c.strip_suffix("_j_per_cycle"))
        .unwrap_or(column);
    match name {
        "base_work" | "input" => "input: base work".into(),
        other => format!("dissipated: {}", other.replace('_', " ")),
    }
}
