//! `pdamp d2`: correlation sum and correlation dimension (Grassberger & Procaccia 1983;
//! TISEAN `d2`).

use std::fmt::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, DimRange, Output, Radii, Theiler};
use pdamp::analysis::correlation_dimension::{
    correlation_sum, estimate_d2, D2Options, PlateauOptions,
};

/// Arguments of `pdamp d2`.
///
/// Output: CSV on stdout, one row per (m, ε): `m,eps,c,pairs,slope` — ε in data units, C the
/// correlation sum (TISEAN's `.c2`), `pairs` the number of pairs within ε, `slope` the local
/// slope d ln C / d ln ε (centred; TISEAN's `.d2` prints the one-sided slopes, whose mean this
/// is), empty where C = 0. On stderr: the plateau of every m and the D2 estimate (pooled
/// slopes of the highest dimensions' plateaus) with its spread. `pdamp plot d2` draws the
/// output.
///
/// Same definitions and defaults as TISEAN 3.0.1 `d2` (maximum norm, data not rescaled,
/// -M1,10 -d1 -t0, ε from interval/1000 to interval in 100 steps), except that every pair
/// is counted (TISEAN's -N0; its default -N1000 stops counting an ε once 1000 pairs of a
/// random order are within it, which `-N` refuses, naming -N0). `-E` rescales the series to
/// [0, 1] first, as TISEAN's `-E`: ε (given and printed) in units of the data interval.
#[derive(Debug, clap::Args)]
#[command(
    mut_args(edit_arg("m_min", |a| a
        .help("Smallest embedding dimension written (all from 1 by default, as TISEAN)")
        .default_value("1"))),
    mut_args(edit_arg("m_max", |a| a.default_value("10"))),
    mut_args(edit_arg("theiler", |a| a
        .help(
            "Theiler window in samples: pairs closer in time are not counted (TISEAN -t). Use at \
             least the autocorrelation time for flows"
        )
        .default_value("0"))),
    mut_arg("eps_min", |a| a.help("Smallest ε in data units (TISEAN -r). Default: interval/1000")),
    mut_arg("eps_max", |a| a.help(
        "Largest ε in data units (TISEAN -R). Default: the data interval max − min"
    )),
    mut_arg("eps_count", |a| a
        .help("Number of ε, log-spaced (TISEAN -#)")
        .default_value("100"))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Dimensions -m -M (TISEAN), 1 and 10 by default.
    #[command(flatten)]
    pub dim_range: DimRange,
    /// Delay τ (TISEAN -d).
    #[command(flatten)]
    pub delay: Delay,
    /// Theiler window -t (TISEAN), 0 by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// Radii -r -R -# (TISEAN), 100 by default.
    #[command(flatten)]
    pub radii: Radii,
    /// Plateau search: radii with fewer pairs are ignored.
    #[arg(long, default_value_t = 1000, help_heading = "Plateau")]
    pub min_pairs: u64,
    /// Plateau search: largest relative deviation of a slope from the plateau mean.
    #[arg(long, default_value_t = 0.05, help_heading = "Plateau")]
    pub tolerance: f64,
    /// Plateau search: D2 pools the plateaus of this many highest dimensions.
    #[arg(long, default_value_t = 3, help_heading = "Plateau")]
    pub dims: usize,
    /// Rescale the series to [0, 1] first (TISEAN -E): -r, -R and the printed ε are then in
    /// units of the data interval.
    #[arg(short = 'E', long = "rescale", help_heading = "Estimator")]
    pub rescale: bool,
    /// Largest number of pairs per ε (TISEAN -N): only 0, "all pairs", which pdamp always
    /// counts; TISEAN's default 1000 stops early on a random sample of pairs.
    #[arg(short = 'N', long = "max-pairs", value_name = "N", value_parser = parse_max_pairs,
          help_heading = "Estimator")]
    pub max_pairs: Option<u64>,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// `-N`: TISEAN's largest number of pairs per ε; pdamp counts every pair, TISEAN's `-N0`.
fn parse_max_pairs(s: &str) -> Result<u64, String> {
    match s.parse::<u64>() {
        Ok(0) => Ok(0),
        Ok(n) => Err(format!(
            "pdamp d2 counts every pair (TISEAN's -N0); TISEAN's -N{n} stops counting each ε after \
             {n} pairs taken in a random order, which pdamp does not do. Drop -N (or give -N0), \
             and give TISEAN -N0 for the same C(ε)"
        )),
        Err(_) => Err(format!(
            "`{s}` is not a number of pairs; only -N0 (all pairs) is accepted"
        )),
    }
}

/// Run `pdamp d2`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mut x = args.input.read()?;
    if args.rescale {
        x = pdamp::analysis::rescale_unit(&x)
            .with_context(|| format!("-E: rescaling {}", args.input.file))?
            .values;
    }
    let opts = D2Options {
        m_min: args.dim_range.min().expect("d2 gives -m a default"),
        m_max: args.dim_range.max()?.expect("d2 gives -M a default"),
        tau: args.delay.tau,
        theiler: args.theiler.window(),
        eps_min: args.radii.eps_min,
        eps_max: args.radii.eps_max,
        eps_count: args.radii.count(),
    };
    let sums = correlation_sum(&x, &opts)
        .with_context(|| format!("correlation sum of {}", args.input.file))?;
    let mut out = String::from("m,eps,c,pairs,slope\n");
    for c in &sums.curves {
        for l in 0..c.eps.len() {
            let s = c.slope[l].map_or(String::new(), |v| format!("{v:.6}"));
            writeln!(
                out,
                "{},{:.6e},{:.6e},{},{s}",
                c.m, c.eps[l], c.c[l], c.pairs[l]
            )?;
        }
    }
    args.output.write(out.as_bytes())?;
    let plateau = PlateauOptions {
        min_pairs: args.min_pairs,
        tolerance: args.tolerance,
        dims: args.dims,
        ..PlateauOptions::default()
    };
    match estimate_d2(&sums, &plateau) {
        Ok(est) => {
            for p in &est.plateaus {
                tracing::info!(
                    "m {}: plateau {:.4e}..{:.4e} ({} radii{}): slope {:.4} ± {:.4}",
                    p.m,
                    p.eps_lo,
                    p.eps_hi,
                    p.points,
                    if p.flat { "" } else { ", not flat" },
                    p.d2,
                    p.std
                );
            }
            tracing::info!(
                "correlation dimension D2 = {:.4} ± {:.4} (m = {:?}{})",
                est.d2,
                est.spread,
                est.dims_used,
                if est.flat {
                    ""
                } else {
                    "; no flat plateau: do not trust"
                }
            );
        }
        Err(e) => tracing::info!("no D2 estimate: {e}"),
    }
    Ok(())
}
