//! The fuzz targets of pdamp, shared by the cargo-fuzz binaries (`fuzz/fuzz_targets/*.rs`,
//! nightly, libFuzzer with coverage) and the stable mutation driver
//! (`tests/fuzz_mutation.rs`). Each target takes arbitrary bytes and must never panic or
//! hang; where it accepts an input, the result must be finite.
//!
//! Limits of the harness (not of pdamp): a scene is only resolved when it has at most
//! [`MAX_FUZZ_GRAINS`] grains, and only event-driven runs of at most [`MAX_FUZZ_STEPS`] steps
//! are simulated, so that one execution stays in the millisecond range.

use pdamp::io::series::{parse_table_str, Column, Delimiter, SeriesReadOptions};
use pdamp::scene::{parse_assignment, Damper, SceneSource};
use pdamp::setup::{RunPlan, Setup};
use pdamp::sweep::vary::Vary;

/// Largest DEM bed the harness resolves (the packing is built when resolving).
pub const MAX_FUZZ_GRAINS: usize = 2_000;
/// Longest event-driven run the harness simulates.
pub const MAX_FUZZ_STEPS: f64 = 2e4;
/// Longest series the analysis target analyses.
pub const MAX_FUZZ_SAMPLES: usize = 256;

/// A fuzz target: arbitrary bytes in, no panic out.
pub type Target = fn(&[u8]);

/// The targets by name, in the order the driver runs them.
pub const TARGETS: [(&str, Target); 5] = [
    ("scene_toml", scene_toml),
    ("set_assignment", set_assignment),
    ("vary_range", vary_range),
    ("series_reader", series_reader),
    ("analysis", analysis),
];

/// A scene file: parse, validate, resolve, plan, and (short event-driven runs) simulate with
/// `series.csv` recorded in memory.
pub fn scene_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(src) = SceneSource::parse(text) else {
        return;
    };
    let Ok(scene) = src.scene(&[]) else {
        return;
    };
    // the scene that validated must print back to TOML
    let _ = scene.to_toml();
    if let Damper::Dem(d) = &scene.damper {
        if d.count > MAX_FUZZ_GRAINS {
            return;
        }
    }
    if let Damper::Auto(_) = &scene.damper {
        return; // the automatic choice runs trial simulations: too slow for the harness
    }
    let Ok(resolved) = scene.resolve() else {
        return;
    };
    let opts = pdamp::setup::full_series(&resolved.scene);
    let Ok(plan) = RunPlan::new(&resolved, &opts) else {
        return;
    };
    assert_plan_finite(&plan);
    if matches!(resolved.setup, Setup::Impact(_))
        && plan.steps <= MAX_FUZZ_STEPS
        && plan.samples <= 1e4
    {
        let mut csv = pdamp::observe::CsvRecorder::new(Vec::new());
        let ok = pdamp::setup::simulate(&resolved, &mut csv, &opts).is_ok();
        let text = String::from_utf8(csv.into_inner().expect("an in-memory series.csv flushes"))
            .expect("series.csv is UTF-8");
        assert!(
            !has_non_finite(&text),
            "series.csv with a non-finite value (run ok: {ok}):\n{text:.2000}"
        );
    }
}

/// A `--set KEY=VALUE` assignment applied to the first scene of `data/scenes`.
pub fn set_assignment(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(assignment) = parse_assignment(text) else {
        return;
    };
    let base = SceneSource::parse(include_str!("../data/scenes/thesis_b_impact.toml"))
        .expect("the seed scene parses");
    if let Ok(scene) = base.scene(&[assignment]) {
        if let Ok(resolved) = scene.resolve() {
            if let Ok(plan) = RunPlan::new(&resolved, &pdamp::setup::full_series(&scene)) {
                assert_plan_finite(&plan);
            }
        }
    }
}

/// A `--vary KEY=START:STOP:STEP` or `KEY=a,b,c` range.
pub fn vary_range(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(v) = Vary::parse(text) {
        assert!(
            !v.values.is_empty(),
            "an accepted --vary range is not empty"
        );
    }
}

/// A series file, read with options taken from the first byte.
pub fn series_reader(data: &[u8]) {
    let (opts, text) = split_options(data);
    let Ok(text) = std::str::from_utf8(text) else {
        return;
    };
    if let Ok(t) = parse_table_str(text, "fuzz", &opts) {
        let n = t.columns[0].len();
        assert!(n > 0, "an accepted series has rows");
        for c in &t.columns {
            assert_eq!(c.len(), n, "every selected column has every row");
            assert!(
                c.iter().all(|v| v.is_finite()),
                "accepted values are finite"
            );
        }
        if let Some(time) = &t.time {
            assert!(
                time.dt > 0.0 && time.dt.is_finite(),
                "time step {}",
                time.dt
            );
        }
    }
}

/// The whole analysis chain on a series the reader accepts (at most
/// [`MAX_FUZZ_SAMPLES`] samples).
pub fn analysis(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(t) = parse_table_str(text, "fuzz", &SeriesReadOptions::default()) else {
        return;
    };
    let x = &t.columns[0];
    let x = &x[x.len().saturating_sub(MAX_FUZZ_SAMPLES)..];
    let opts = pdamp::analysis::analyze::AnalyzeOptions {
        max_samples: MAX_FUZZ_SAMPLES,
        ..Default::default()
    };
    if let Ok(r) = pdamp::analysis::analyze::analyze_series(x, &opts) {
        // JSON writes a non-finite number as null: a value the report has must be finite
        let mut values = vec![("line_power_fraction", Some(r.line_power_fraction))];
        values.extend([
            ("mle_per_sample", r.mle_per_sample),
            ("mle_fit_r2", r.mle_fit_r2),
            ("period", r.period),
            ("closed_curve_score", r.closed_curve_score),
            ("zero_one_k", r.zero_one_k),
        ]);
        values.extend(
            r.spectral_lines
                .iter()
                .map(|l| ("line frequency", Some(l.frequency))),
        );
        values.extend(
            r.spectral_lines
                .iter()
                .map(|l| ("line power", Some(l.power))),
        );
        for (name, v) in values {
            assert!(
                v.is_none_or(f64::is_finite),
                "analysis report: {name} = {v:?}"
            );
        }
        serde_json::to_string(&r).expect("a report serialises");
    }
}

/// Reader options from the first byte (delimiter, decimal comma, a column), the text after.
fn split_options(data: &[u8]) -> (SeriesReadOptions, &[u8]) {
    let Some((&b, rest)) = data.split_first() else {
        return (SeriesReadOptions::default(), data);
    };
    let delimiter = match b & 7 {
        1 => Some(Delimiter::Comma),
        2 => Some(Delimiter::Semicolon),
        3 => Some(Delimiter::Tab),
        4 => Some(Delimiter::Whitespace),
        _ => None,
    };
    let columns = match (b >> 4) & 3 {
        1 => vec![Column::Index(((b >> 6) as usize) % 4)],
        2 => vec![Column::Name("x".into()), Column::Index(1)],
        _ => Vec::new(),
    };
    let opts = SeriesReadOptions {
        columns,
        delimiter,
        decimal_comma: b & 8 != 0,
        max_rows: None,
        skip_lines: 0,
    };
    (opts, rest)
}

/// Every figure of a plan is finite (the bounds refuse the rest).
fn assert_plan_finite(p: &RunPlan) {
    for (name, v) in [
        ("duration", p.duration_s),
        ("dt", p.dt_s),
        ("steps", p.steps),
        ("samples", p.samples),
        ("snapshot files", p.snapshot_files),
        ("output", p.output_bytes),
        ("run time", p.run_time_s),
    ] {
        assert!(v.is_finite() && v >= 0.0, "plan {name} = {v}: {p:?}");
    }
}

/// Whether CSV text holds a NaN or an infinity as a cell.
pub fn has_non_finite(text: &str) -> bool {
    text.lines().skip(1).any(|l| {
        l.split(',').any(|c| {
            let c = c.trim().to_ascii_lowercase();
            c.contains("nan") || c.contains("inf")
        })
    })
}
