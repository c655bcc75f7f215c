//! Resonance amplitude Z_res versus a damper parameter (γ_n, γ_s, Lz …) for several grain
//! numbers N (SPEC §7).

use super::common::Series;
use super::lines::LinesFigure;

/// Builds the Z_res figure: one curve per N; y values are amplitudes in metres (drawn in mm).
pub fn resonance_figure<'a>(series: Vec<Series<'a>>, parameter_label: &str) -> LinesFigure<'a> {
    LinesFigure {
        series,
        x_label: parameter_label.to_string(),
        y_label: "resonance amplitude Z_res (mm)".into(),
        y_scale: 1e3,
        title: format!(
            "Resonance amplitude versus {}",
            parameter_name(parameter_label)
        ),
        kind: "resonance",
    }
}

/// Z_res per parameter value: groups the sweep rows by `parameter` (exact equality) and keeps
/// the largest `amplitude_m` of each group (the resonance over the frequency sweep).
/// Returns (parameter values ascending, Z_res).
pub fn resonance_amplitudes(parameter: &[f64], amplitude_m: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut pairs: Vec<(f64, f64)> = parameter
        .iter()
        .copied()
        .zip(amplitude_m.iter().copied())
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut xs, mut zs): (Vec<f64>, Vec<f64>) = (vec![], vec![]);
    for (p, z) in pairs {
        match xs.last() {
            Some(&last) if last == p => {
                let zl = zs.last_mut().expect("zs has one entry per xs");
                *zl = zl.max(z);
            }
            _ => {
                xs.push(p);
                zs.push(z);
            }
        }
    }
    (xs, zs)
}

/// The parameter's name without its unit: `gap (mm)` → `gap`.
fn parameter_name(label: &str) -> &str {
    match label.rfind(" (") {
        Some(i) if label.ends_with(')') => &label[..i],
        _ => label,
    }
}
