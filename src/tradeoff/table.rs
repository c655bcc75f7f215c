//! `tradeoff.csv` (one row per setting × frequency) and `tradeoff_settings.csv` (one row per
//! setting): writing them with their `#` provenance header, and reading the settings table
//! back by [`crate::choice::measured::read_settings`]. Empty cells mean "not applicable / not measured": no cell is
//! ever NaN or infinite; a refused or failed setting says so in `status` and `message`.

use crate::io::csv_out::CsvOut;
use crate::observe::fmt_num;

use super::study::{Row, SettingSummary, Study};

type Col<T> = (&'static str, fn(&T) -> String);

fn num(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite()).map(fmt_num).unwrap_or_default()
}

fn text(x: &Option<String>) -> String {
    x.clone().unwrap_or_default()
}

/// The columns of `tradeoff.csv`.
pub const ROW_COLUMNS: [Col<Row>; 19] = [
    ("setting", |r| r.setting.clone()),
    ("axis", |r| r.axis.as_str().into()),
    ("label", |r| r.label.clone()),
    ("frequency_hz", |r| num(Some(r.frequency_hz))),
    ("status", |r| r.status.clone()),
    ("youngs_modulus_pa", |r| num(r.youngs_modulus_pa)),
    ("dt_s", |r| num(r.dt_s)),
    ("periods", |r| num(r.periods)),
    ("amplitude_m", |r| num(r.amplitude_m)),
    ("amplitude_rel_error", |r| num(r.amplitude_rel_error)),
    (
        "dissipation_j_per_cycle",
        |r| num(r.dissipation_j_per_cycle),
    ),
    ("dissipation_rel_error", |r| num(r.dissipation_rel_error)),
    ("regime", |r| text(&r.regime)),
    ("regime_reference", |r| text(&r.regime_reference)),
    ("regime_match", |r| {
        r.regime_match.map(|b| b.to_string()).unwrap_or_default()
    }),
    ("mle_per_s", |r| num(r.mle_per_s)),
    ("core_seconds", |r| num(r.core_seconds)),
    ("particle_steps", |r| num(r.particle_steps)),
    ("message", |r| r.message.clone()),
];

/// The columns of `tradeoff_settings.csv` (read back by
/// [`crate::choice::measured::read_settings`], which finds them by name).
pub const SETTING_COLUMNS: [Col<SettingSummary>; 30] = [
    ("setting", |s| s.setting.clone()),
    ("axis", |s| s.axis.as_str().into()),
    ("label", |s| s.label.clone()),
    ("status", |s| s.status.clone()),
    ("frequencies_ok", |s| s.frequencies_ok.to_string()),
    ("frequencies", |s| s.frequencies.to_string()),
    ("frequencies_compared", |s| {
        s.frequencies_compared.to_string()
    }),
    ("core_seconds_per_point", |s| num(s.core_seconds_per_point)),
    ("speedup", |s| num(s.speedup)),
    (
        "amplitude_max_rel_error",
        |s| num(s.amplitude_max_rel_error),
    ),
    ("amplitude_median_rel_error", |s| {
        num(s.amplitude_median_rel_error)
    }),
    ("resonance_frequency_hz", |s| {
        num(s.resonance.map(|p| p.frequency_hz))
    }),
    ("resonance_frequency_rel_error", |s| {
        num(s.resonance_frequency_rel_error)
    }),
    ("resonance_amplitude_m", |s| {
        num(s.resonance.map(|p| p.amplitude_m))
    }),
    ("resonance_amplitude_rel_error", |s| {
        num(s.resonance_amplitude_rel_error)
    }),
    ("m_ef_kg", |s| num(s.effective.map(|e| e.mass_kg))),
    ("m_ef_rel_error", |s| num(s.m_ef_rel_error)),
    ("c_ef_n_s_m", |s| num(s.effective.map(|e| e.damping_n_s_m))),
    ("c_ef_rel_error", |s| num(s.c_ef_rel_error)),
    ("dissipation_max_rel_error", |s| {
        num(s.dissipation_max_rel_error)
    }),
    ("regime_matches", |s| s.regime_matches.to_string()),
    ("regime_compared", |s| s.regime_compared.to_string()),
    ("regime_disagreement", |s| num(s.regime_disagreement())),
    ("regime_confusion", |s| s.confusion.clone()),
    ("mle_max_rel_error", |s| num(s.mle_max_rel_error)),
    ("pareto_amplitude", |s| s.pareto_amplitude.to_string()),
    ("pareto_resonance", |s| s.pareto_resonance.to_string()),
    ("pareto_dissipation", |s| s.pareto_dissipation.to_string()),
    ("pareto_regime", |s| s.pareto_regime.to_string()),
    ("message", |s| s.message.clone()),
];

fn write_table<T>(header: &[String], cols: &[Col<T>], items: &[T]) -> String {
    let mut out = String::new();
    for h in header {
        out.push_str("# ");
        out.push_str(h);
        out.push('\n');
    }
    let mut csv = CsvOut::in_memory();
    // writing into memory cannot fail
    let _ = csv.row(cols.iter().map(|(name, _)| *name));
    for it in items {
        let _ = csv.row(cols.iter().map(|(_, get)| get(it)));
    }
    out.push_str(&csv.into_string());
    out
}

/// `tradeoff.csv`: the `#` header lines, then one row per rung and frequency.
pub fn rows_csv(study: &Study, header: &[String]) -> String {
    write_table(header, &ROW_COLUMNS, &study.rows)
}

/// `tradeoff_settings.csv`: the `#` header lines, then one row per rung.
pub fn settings_csv(study: &Study, header: &[String]) -> String {
    write_table(header, &SETTING_COLUMNS, &study.settings)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::choice::{read_settings, Axis};

    #[test]
    fn read_rejects_bad_numbers_with_line() {
        let head: Vec<&str> = SETTING_COLUMNS.iter().map(|(n, _)| *n).collect();
        let mut cells = vec![""; head.len()];
        cells[0] = "reference";
        cells[1] = "reference";
        cells[2] = "reference";
        cells[3] = "complete";
        cells[4] = "3";
        cells[5] = "3";
        cells[6] = "3";
        cells[7] = "abc";
        cells[20] = "3";
        cells[21] = "3";
        let t = format!("# x\n{}\n{}\n", head.join(","), cells.join(","));
        let e = read_settings(&t, "t.csv").unwrap_err().to_string();
        assert!(e.contains("t.csv:3"), "{e}");
        assert!(e.contains("core_seconds_per_point"), "{e}");
        cells[7] = "12.5";
        let t = format!("# x\n{}\n{}\n", head.join(","), cells.join(","));
        let s = read_settings(&t, "t.csv").unwrap();
        assert_eq!(s[0].core_seconds_per_point, Some(12.5));
        assert_eq!(s[0].axis, Axis::Reference);
    }
}
