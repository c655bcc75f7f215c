//! `TRADEOFF.md`: what a reader takes away from the study — which setting to use for an FRF,
//! for regime maps and for grain-level output (chosen by [`crate::choice::auto`]'s rules from the
//! measured table, each pointing at its row), then the per-setting table.

use std::fmt::Write as _;

use crate::scene::{Damper, Outputs, Scene};

use super::study::{SettingSummary, Study};
use super::table::settings_csv;
use crate::choice::auto::choose_with;
use crate::choice::measured::read_settings;

/// The questions answered at the top of the report: (what for, the outputs that ask it).
fn questions() -> [(&'static str, Outputs); 3] {
    [
        (
            "an FRF (Z and the resonance) within 2 %",
            Outputs {
                frf_only: true,
                tolerance: 0.02,
                ..Outputs::default()
            },
        ),
        (
            "regime maps (every verdict as the reference's, λ within 10 %)",
            Outputs {
                zcm_series: true,
                tolerance: 0.1,
                ..Outputs::default()
            },
        ),
        (
            "grain-level output (snapshots of the scene's grains, Z within 5 %)",
            Outputs {
                grain_snapshots: true,
                tolerance: 0.05,
                ..Outputs::default()
            },
        ),
    ]
}

fn pct(x: Option<f64>) -> String {
    x.map_or("–".into(), |e| format!("{:.2} %", 100.0 * e))
}

fn secs(x: Option<f64>) -> String {
    x.map_or("–".into(), |c| format!("{c:.1}"))
}

/// The report's markdown. `reference` is the reference scene (its damper is offered to `auto`
/// as `kind = "auto"`); `header` the provenance lines of the tables.
pub fn markdown(study: &Study, reference: &Scene, header: &[String]) -> String {
    let mut md = String::from("# Speed against accuracy (scene B)\n\n");
    for h in header {
        let _ = writeln!(md, "    {h}");
    }
    let table = read_settings(&settings_csv(study, &[]), "tradeoff_settings.csv").ok();
    md.push_str("\n## What to use\n\n");
    md.push_str(
        "Chosen by `kind = \"auto\"`'s rules from `tradeoff_settings.csv`: the cheapest setting \
         compared with the reference at every frequency the reference has (and at least 3) whose \
         measured errors are within the tolerance.\n\n",
    );
    let mut auto_scene = reference.clone();
    if let Damper::Dem(p) = &reference.damper {
        auto_scene.damper = Damper::Auto(p.clone());
    }
    for (what, outputs) in questions() {
        auto_scene.outputs = outputs;
        let line = match table.as_deref().map(|t| choose_with(&auto_scene, t)) {
            Some(Ok(c)) => format!("`{}` ({}): {}", c.setting, c.model, c.reason),
            Some(Err(e)) => format!("not decidable: {e}"),
            None => "not decidable: the settings table does not read back".into(),
        };
        let _ = writeln!(md, "- For {what}: {line}.");
    }
    md.push_str(
        "\n## Every setting\n\nErrors are the largest over the frequencies where both the \
         setting and the reference have a point (`compared`); cost is CPU seconds per point \
         (see the header); `tradeoff.csv` has every frequency.\n\n\
         | setting | status | points | compared | CPU s / point | speed-up | Z error | f_res error | \
         dissipation error | verdicts as ref. | message |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for s in &study.settings {
        md.push_str(&setting_row(s));
    }
    md
}

fn setting_row(s: &SettingSummary) -> String {
    format!(
        "| `{}` {} | {} | {}/{} | {} | {} | {} | {} | {} | {} | {}/{} | {} |\n",
        s.setting,
        s.label,
        s.status,
        s.frequencies_ok,
        s.frequencies,
        s.frequencies_compared,
        secs(s.core_seconds_per_point),
        s.speedup.map_or("–".into(), |x| format!("{x:.1}×")),
        pct(s.amplitude_max_rel_error),
        pct(s.resonance_frequency_rel_error),
        pct(s.dissipation_max_rel_error),
        s.regime_matches,
        s.regime_compared,
        s.message.replace('|', "/")
    )
}
