//! `pdamp poincare`: stroboscopic Poincaré section (one point per forcing period).

use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use pdamp::analysis::poincare::{
    classify_section, period_in_samples, stroboscopic_section, ClusterOptions, Interpolation,
    SecondCoordinate, SectionShape, StrobeOptions,
};
use pdamp::io::{read_series, Column};

/// Long help of `pdamp poincare`: what it writes and how to read it.
const LONG_HELP: &str =
    "Output (CSV on stdout, header row): `cycle,time_samples[,time_s],s,second` — one row per
forcing period k, at t_k = offset + k·T, with `s` the series there and `second` either the
delayed value s(t_k + τ) (`--delay`, default 1 sample) or another column (`--second-column`).
Between samples the series is interpolated (cubic by default). The forcing period T is
`--period-samples`, or 1/(f·dt) from `--forcing-hz` and `--dt`. On stderr: the number of
distinct points (period n, clustered at `--rel-tol` of the series range), or whether the
section is a closed curve (quasi-periodic) or a cloud.";

/// Arguments of `pdamp poincare`.
///
/// Output (CSV on stdout, header row): `cycle,time_samples[,time_s],s,second` — one row per
/// forcing period k, at t_k = offset + k·T, with `s` the series there and `second` either the
/// delayed value s(t_k + τ) (`--delay`, default 1 sample) or another column (`--second-column`).
/// Between samples the series is interpolated (cubic by default). The forcing period T is
/// `--period-samples`, or 1/(f·dt) from `--forcing-hz` and `--dt`. On stderr: the number of
/// distinct points (period n, clustered at `--rel-tol` of the series range), or whether the
/// section is a closed curve (quasi-periodic) or a cloud.
#[derive(Debug, clap::Args)]
#[command(after_long_help = LONG_HELP)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Forcing period in samples (fractional allowed). Alternative to --forcing-hz + --dt.
    #[arg(long, help_heading = "Section")]
    pub period_samples: Option<f64>,
    /// Forcing frequency in Hz (needs --dt).
    #[arg(long, help_heading = "Section")]
    pub forcing_hz: Option<f64>,
    /// Sampling interval in seconds.
    #[arg(long = "dt", help_heading = "Section")]
    pub dt_s: Option<f64>,
    /// Time of the first section point in samples (the forcing phase).
    #[arg(long, default_value_t = 0.0, help_heading = "Section")]
    pub offset_samples: f64,
    /// Delay τ in samples of the second coordinate s(t + τ) (fractional allowed).
    #[arg(long, default_value_t = 1.0, help_heading = "Section")]
    pub delay: f64,
    /// Use this column (number or header name) as the second coordinate instead of a delay.
    #[arg(long, help_heading = "Section")]
    pub second_column: Option<Column>,
    /// Interpolation between samples: cubic (4-point Lagrange) or linear.
    #[arg(long, default_value = "cubic", help_heading = "Section")]
    pub interpolation: Interpolation,
    /// Points closer than this fraction of the series range count as one (distinct points).
    #[arg(long, default_value_t = 1e-3, help_heading = "Summary")]
    pub rel_tol: f64,
}

/// Run `pdamp poincare`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let period = match (args.period_samples, args.forcing_hz, args.dt_s) {
        (Some(p), None, _) => p,
        (None, Some(f), Some(dt)) => period_in_samples(f, dt)?,
        (None, Some(_), None) => {
            anyhow::bail!("--forcing-hz needs --dt (the sampling interval in seconds)")
        }
        (Some(_), Some(_), _) => {
            anyhow::bail!("give either --period-samples or --forcing-hz with --dt, not both")
        }
        (None, None, _) => {
            anyhow::bail!(
                "the forcing period is missing: give --period-samples T or --forcing-hz F --dt S"
            )
        }
    };
    if !(args.rel_tol.is_finite() && args.rel_tol > 0.0) {
        anyhow::bail!(
            "--rel-tol {}: must be > 0 (a fraction of the series range)",
            args.rel_tol
        );
    }
    let x = args.input.read()?;
    let y = match &args.second_column {
        Some(c) => Some(read_series(
            &args.input.file,
            &args.input.options(vec![c.clone()]),
        )?),
        None => None,
    };
    let second = match &y {
        Some(y) => SecondCoordinate::Column(y),
        None => SecondCoordinate::Delay(args.delay),
    };
    let opts = StrobeOptions {
        period_samples: period,
        offset_samples: args.offset_samples,
        interpolation: args.interpolation,
    };
    let sec = stroboscopic_section(&x, second, &opts)
        .with_context(|| format!("section of {}", args.input.file))?;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let second_name = if y.is_some() { "second" } else { "s_delayed" };
    match args.dt_s {
        Some(_) => writeln!(out, "cycle,time_samples,time_s,s,{second_name}")?,
        None => writeln!(out, "cycle,time_samples,s,{second_name}")?,
    }
    for (k, (t, p)) in sec.times.iter().zip(&sec.points).enumerate() {
        match args.dt_s {
            Some(dt) => writeln!(
                out,
                "{k},{t:.6},{:.10e},{:.10e},{:.10e}",
                t * dt,
                p[0],
                p[1]
            )?,
            None => writeln!(out, "{k},{t:.6},{:.10e},{:.10e}", p[0], p[1])?,
        }
    }
    out.flush()?;
    let (lo, hi) = pdamp::analysis::min_max(&x);
    let summary = classify_section(
        &sec.points,
        hi - lo,
        &ClusterOptions {
            rel_tol: args.rel_tol,
            ..Default::default()
        },
    );
    let shape = match summary.shape {
        SectionShape::Points(n) => format!("{n} distinct point(s): period-{n}"),
        SectionShape::ClosedCurve => {
            format!(
                "a closed curve (score {:.3}): quasi-periodic",
                summary.closed_curve_score
            )
        }
        SectionShape::Cloud => format!(
            "a cloud (closed-curve score {:.3}): chaotic or noisy",
            summary.closed_curve_score
        ),
        SectionShape::TooFew => "too few points to tell".to_string(),
    };
    tracing::info!(
        "{} section points, period {period:.6} samples; the section is {shape}",
        summary.n_points
    );
    Ok(())
}
