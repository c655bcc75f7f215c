//! `pdamp lyap-r`: Rosenstein's maximal Lyapunov exponent (TISEAN `lyap_r`).

use std::fmt::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, Dim, Output, Theiler};
use pdamp::analysis::kantz::{fit_scaling_region, ScalingOptions};
use pdamp::analysis::rosenstein::{rosenstein, RosensteinOptions};

/// Arguments of `pdamp lyap-r`.
///
/// Output: CSV on stdout `dn_samples,s,count`: S(Δn), the mean log distance of the nearest
/// neighbour pairs after Δn steps, in rescaled units (add ln(max − min) for data units), as
/// TISEAN lyap_r's two columns plus the number of pairs. On stderr: the linear region (longest
/// window with R² ≥ --r2-min whose first and last thirds have slopes within 20 %) and its
/// slope = the exponent per sample (and per second with --dt).
///
/// Same definition and defaults as TISEAN 3.0.1 lyap_r (-m2 -d1 -t0 -s10, -r = interval/1000
/// as the initial search radius, Euclidean nearest neighbour, series rescaled to [0, 1]).
#[derive(Debug, clap::Args)]
#[command(
    mut_args(edit_arg("m", |a| a.default_value("2"))),
    mut_args(edit_arg("theiler", |a| a
        .help("Theiler window in samples (TISEAN -t); about one mean period for flows")
        .default_value("0")))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Embedding dimension -m (TISEAN), 2 by default.
    #[command(flatten)]
    pub dim: Dim,
    /// Delay τ (TISEAN -d).
    #[command(flatten)]
    pub delay: Delay,
    /// Theiler window -t (TISEAN), 0 by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// Initial neighbourhood size in data units (TISEAN -r): matters only for points with
    /// exact duplicates, which keep a neighbour only within it. Default interval/1000.
    #[arg(short = 'r', long = "eps0", help_heading = "Estimator")]
    pub eps0: Option<f64>,
    /// Largest Δn in samples (TISEAN -s).
    #[arg(
        short = 's',
        long = "steps",
        default_value_t = 10,
        help_heading = "Estimator"
    )]
    pub steps: usize,
    /// Sampling interval in seconds, to report the exponent per second too.
    #[arg(long = "dt", help_heading = "Output")]
    pub dt_s: Option<f64>,
    /// Minimum R² of the linear region.
    #[arg(long, default_value_t = 0.99, help_heading = "Output")]
    pub r2_min: f64,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// Run `pdamp lyap-r`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let opts = RosensteinOptions {
        m: args.dim.get(),
        tau: args.delay.tau,
        theiler: args.theiler.window(),
        eps0: args.eps0,
        steps: args.steps,
    };
    let r = rosenstein(&x, &opts).with_context(|| format!("Rosenstein on {}", args.input.file))?;
    let mut out = String::from("dn_samples,s,count\n");
    for (t, (s, c)) in r.s.iter().zip(&r.count).enumerate() {
        if let Some(s) = s {
            writeln!(out, "{t},{s:.10e},{c}")?;
        }
    }
    args.output.write(out.as_bytes())?;
    let scaling = ScalingOptions {
        r2_min: args.r2_min,
        ..ScalingOptions::default()
    };
    if let Some(f) = fit_scaling_region(&r.s, &scaling) {
        let per_s = args.dt_s.map_or(String::new(), |dt| {
            format!(" = {:.6} per second", f.slope / dt)
        });
        tracing::info!(
            "maximal Lyapunov exponent (Rosenstein, {} references): {:.6} per sample{per_s} \
             over dn {}..={} (R² {:.4}{})",
            r.references,
            f.slope,
            f.start,
            f.end,
            f.r2,
            if f.linear {
                ""
            } else {
                "; no linear region: raise -s or inspect the curve"
            }
        );
    }
    Ok(())
}
