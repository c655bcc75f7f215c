//! `RunSummary` (with its typed `AnalysisReport`) reads back from its own JSON exactly, on a
//! real impact run with its analysis and on a real plain-series analysis report; sweep caches
//! written by earlier versions (`figures/data/*/points/*.json`) still read.

use pdamp::analysis::analyze::{analyze_series, AnalysisReport, AnalyzeOptions};
use pdamp::model::{RunOptions, RunSummary};
use pdamp::observe::NullObserver;
use pdamp::scene::Scene;

#[test]
fn impact_run_summary_roundtrips_through_json() {
    let mut s = Scene::thesis_b_impact();
    s.excitation.frequency = 12.0;
    s.run.duration = None;
    s.run.periods = Some(200.0);
    let mut summary =
        pdamp::sweep::run_with_analysis(&s, &mut NullObserver, &RunOptions::summary_only(), true)
            .unwrap();
    let a = summary.analysis.as_ref().expect("the run was analysed");
    assert!(a.section.is_some() && a.section_source.as_deref() == Some("exact"));
    // the strobe rows go to strobe.csv, never to the JSON
    summary.strobe.clear();
    let text = serde_json::to_string_pretty(&summary).unwrap();
    let back: RunSummary = serde_json::from_str(&text).unwrap();
    assert_eq!(back, summary);
    // and through a serde_json::Value, as the sweep stores it
    let v = serde_json::to_value(&summary).unwrap();
    let back: RunSummary = serde_json::from_value(v).unwrap();
    assert_eq!(back, summary);
}

#[test]
fn analysis_report_roundtrips_through_json() {
    // logistic map at r = 4 (chaotic) plus a sine: every estimator has something to report
    let mut x = 0.3_f64;
    let series: Vec<f64> = (0..4000)
        .map(|i| {
            x = 4.0 * x * (1.0 - x);
            x + 0.1 * (i as f64 * 0.05).sin()
        })
        .collect();
    let opts = AnalyzeOptions {
        dt_s: Some(0.01),
        ..AnalyzeOptions::default()
    };
    let r = analyze_series(&series, &opts).unwrap();
    let text = serde_json::to_string(&r).unwrap();
    let back: AnalysisReport = serde_json::from_str(&text).unwrap();
    assert_eq!(back, r);
}

/// The cached sweep points of the main figures (when present on this machine) read into the
/// typed summary, and write back the same JSON object.
#[test]
fn cached_sweep_points_read_back() {
    let Some(dir) = std::env::var_os("PDAMP_FIGURES_DATA") else {
        return;
    };
    let mut n = 0;
    for sweep in std::fs::read_dir(dir).unwrap().flatten() {
        let Ok(points) = std::fs::read_dir(sweep.path().join("points")) else {
            continue;
        };
        for p in points.flatten() {
            let text = std::fs::read_to_string(p.path()).unwrap();
            let v: serde_json::Value = serde_json::from_str(&text).unwrap();
            let s: RunSummary = serde_json::from_value(v["summary"].clone())
                .unwrap_or_else(|e| panic!("{}: {e}", p.path().display()));
            assert_eq!(
                serde_json::to_value(&s).unwrap(),
                v["summary"],
                "{}",
                p.path().display()
            );
            n += 1;
        }
    }
    eprintln!("{n} cached points read back");
}
