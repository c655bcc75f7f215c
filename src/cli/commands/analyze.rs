//! `pdamp analyze`: the whole analysis chain with automatic choices and a regime verdict.

use std::fmt::Write as _;
use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use pdamp::analysis::analyze::{analyze_series, AnalysisReport, AnalyzeOptions};

/// Long help of `pdamp analyze`: what it writes and how to read it.
const LONG_HELP: &str =
    "Runs spectrum and lines, recurrence, mutual information (lag τ = first minimum), false
nearest neighbours (dimension m), Kantz's exponent with an automatically found scaling
region, the stroboscopic section (with --forcing-hz) and the Gottwald–Melbourne 0–1 test,
then classifies the regime: periodic (with its period), quasi-periodic, chaotic,
irregular (noise-like) or undetermined. Feed it the steady state (drop transients with -x or by
trimming the file).

With --json: one JSON object with `lag`, `embedding_dim`, `mle_per_sample`, `mle_per_time`
(per second; null without --dt), `regime`, `period` (in forcing periods with --forcing-hz,
else in samples; null unless periodic), `reason`, and the evidence: `spectral_lines`,
`line_power_fraction`, `poincare_distinct_points`, `poincare_shape`, `closed_curve_score`,
`kantz_fit` (start, end, r2, linear), `zero_one_k`, `fnn_fractions`, `notes`.
Without --json: a readable report.";

/// Arguments of `pdamp analyze`.
///
/// Runs spectrum and lines, recurrence, mutual information (lag τ = first minimum), false
/// nearest neighbours (dimension m), Kantz's exponent with an automatically found scaling
/// region, the stroboscopic section (with --forcing-hz) and the Gottwald–Melbourne 0–1 test,
/// then classifies the regime: periodic (with its period), quasi-periodic, chaotic,
/// irregular (noise-like) or undetermined. Feed it the steady state (drop transients with -x or by
/// trimming the file).
///
/// With --json: one JSON object with `lag`, `embedding_dim`, `mle_per_sample`, `mle_per_time`
/// (per second; null without --dt), `regime`, `period` (in forcing periods with --forcing-hz,
/// else in samples; null unless periodic), `reason`, and the evidence: `spectral_lines`,
/// `line_power_fraction`, `poincare_distinct_points`, `poincare_shape`, `closed_curve_score`,
/// `kantz_fit` (start, end, r2, linear), `zero_one_k`, `fnn_fractions`, `notes`.
/// Without --json: a readable report.
#[derive(Debug, clap::Args)]
#[command(after_long_help = LONG_HELP)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Sampling interval in seconds: exponents per second and frequencies in Hz. Default: the
    /// step of the file's time column, if it has one.
    #[arg(long = "dt", help_heading = "Analysis")]
    pub dt_s: Option<f64>,
    /// Forcing frequency in Hz (needs --dt): enables the stroboscopic section; the period is
    /// then reported in forcing periods.
    #[arg(long, help_heading = "Analysis")]
    pub forcing_hz: Option<f64>,
    /// Analyse only the last N samples.
    #[arg(long, default_value_t = 100_000, help_heading = "Analysis")]
    pub max_samples: usize,
    /// Seed of the 0–1 test's random frequencies (results are deterministic for a seed).
    #[arg(long, default_value_t = 1, help_heading = "Analysis")]
    pub seed: u64,
    /// Print one JSON object instead of the text report.
    #[arg(long, help_heading = "Output")]
    pub json: bool,
}

/// Run `pdamp analyze`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let table = args.input.read_table()?;
    // a time column gives the sampling interval unless --dt says otherwise
    let dt_s = args.dt_s.or(table.time.as_ref().map(|t| t.dt));
    let x = table.columns.into_iter().next().unwrap_or_default();
    let opts = AnalyzeOptions {
        dt_s,
        forcing_hz: args.forcing_hz,
        max_samples: args.max_samples,
        seed: args.seed,
        ..AnalyzeOptions::default()
    };
    let report =
        analyze_series(&x, &opts).with_context(|| format!("analysis of {}", args.input.file))?;
    let mut out = std::io::stdout().lock();
    if args.json {
        serde_json::to_writer_pretty(&mut out, &report)?;
        writeln!(out)?;
    } else {
        out.write_all(text_report(&report, &args).as_bytes())?;
    }
    out.flush()?;
    Ok(())
}

/// Formats an optional number, or "—".
fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".to_string(), |v| format!("{v:.digits$}"))
}

/// The human-readable report.
fn text_report(r: &AnalysisReport, args: &Args) -> String {
    let mut s = String::new();
    let period_unit = if args.forcing_hz.is_some() {
        "forcing periods"
    } else {
        "samples"
    };
    let _ = writeln!(
        s,
        "series           {} ({} samples analysed)",
        args.input.file, r.n_samples
    );
    let _ = writeln!(
        s,
        "regime           {}{}",
        r.regime,
        r.period
            .map_or_else(String::new, |p| format!(", period {p} {period_unit}"))
    );
    let _ = writeln!(s, "because          {}", r.reason);
    let _ = writeln!(
        s,
        "lag τ            {} samples",
        r.lag.map_or("—".into(), |v| v.to_string())
    );
    let _ = writeln!(
        s,
        "embedding m      {}",
        r.embedding_dim.map_or("—".into(), |v| v.to_string())
    );
    let _ = writeln!(
        s,
        "max. Lyapunov    {} per sample, {} per second",
        opt(r.mle_per_sample, 5),
        opt(r.mle_per_time, 4)
    );
    if let Some(f) = r.kantz_fit {
        let _ = writeln!(
            s,
            "  Kantz fit      Δn = {}..{} of {}, R² = {:.4}{}, m = {}, ε = {:.3e}",
            f.start,
            f.end,
            f.steps,
            f.r2,
            if f.linear { "" } else { " (no linear region)" },
            f.m,
            f.eps
        );
    }
    let _ = writeln!(
        s,
        "0-1 test K       {} (≈0 regular, ≈1 irregular)",
        opt(r.zero_one_k, 3)
    );
    let _ = writeln!(
        s,
        "spectral lines   {} carrying {:.1} % of the power",
        r.spectral_lines.len(),
        100.0 * r.line_power_fraction
    );
    for l in &r.spectral_lines {
        let _ = writeln!(
            s,
            "  {:>14.6e} {:<13} power {:.4e}",
            l.frequency, r.frequency_unit, l.power
        );
    }
    if let Some(shape) = &r.poincare_shape {
        let _ = writeln!(
            s,
            "Poincaré section {} points: {}{}",
            r.poincare_section_points.unwrap_or(0),
            shape,
            r.poincare_distinct_points.map_or_else(
                || format!(" (closed-curve score {})", opt(r.closed_curve_score, 3)),
                |n| format!(" ({n} distinct)")
            )
        );
    }
    if !r.fnn_fractions.is_empty() {
        let f: Vec<String> = r
            .fnn_fractions
            .iter()
            .map(|(m, v)| format!("m={m}: {}", opt(*v, 3)))
            .collect();
        let _ = writeln!(s, "FNN fractions    {}", f.join(", "));
    }
    for n in &r.notes {
        let _ = writeln!(s, "note             {n}");
    }
    s
}
