//! `pdamp fnn`: false nearest neighbours (Kennel et al. 1992; TISEAN `false_nearest`).

use std::fmt::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, DimRange, Output, Theiler};
use pdamp::analysis::false_nearest_neighbors::suggested_dimension;
use pdamp::analysis::{false_nearest_neighbors, FnnOptions};

/// Arguments of `pdamp fnn`.
///
/// Output: CSV on stdout with columns `m,false_fraction,accepted,false_count,mean_distance,
/// rms_distance` (distances in data units; TISEAN prints m, fraction, mean and RMS distance).
/// The suggested dimension (first m with at most 1 % false neighbours) goes to stderr.
///
/// Definition = TISEAN 3.0.1 (max norm, neighbour accepted if within σ/f, duplicates
/// ignored). Defaults differ: pdamp uses Kennel's ratio f = 10 and a Theiler window of one
/// delay; TISEAN uses f = 2 and no window. The vectors differ when τ > 1: pdamp embeds with
/// delay τ (Kennel et al.), while TISEAN 3.0.1's false_nearest on one column uses consecutive
/// samples (s_n, s_{n+1}, …) and the escape coordinate s_{n+m} whatever -d says (-d only
/// shortens the index ranges). `--tisean` switches to TISEAN's defaults and its vectors
/// (explicit flags still win), and then the numbers match TISEAN's.
#[derive(Debug, clap::Args)]
#[command(
    mut_args(edit_arg("m_min", |a| a.help("Smallest embedding dimension tested (TISEAN -m)"))),
    mut_args(edit_arg("m_max", |a| a.help(
        "Largest dimension: `M` or TISEAN's `comp,M` (only 1 component is supported). Default 6 \
         (TISEAN: 5)"
    ))),
    mut_arg("tau", |a| a.help("Delay τ in samples (TISEAN -d); use the first minimum of `pdamp mutual`")),
    mut_args(edit_arg("theiler", |a| a.help(
        "Theiler window in samples: neighbours must be more than this apart in time. Default τ; \
         TISEAN: 0"
    )))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Dimensions -m -M (help above).
    #[command(flatten)]
    pub dim_range: DimRange,
    /// Delay τ (-d; help below).
    #[command(flatten)]
    pub delay: Delay,
    /// Escape ratio f: the neighbour is false if the distance grows by more than f. Default
    /// 10 (Kennel et al.); TISEAN: 2.
    #[arg(short = 'f', long = "ratio", help_heading = "Estimator")]
    pub ratio: Option<f64>,
    /// Theiler window -t (help above).
    #[command(flatten)]
    pub theiler: Theiler,
    /// TISEAN false_nearest's defaults (-m1 -M1,5 -f2 -t0) and vectors (unit spacing: -d
    /// only sets the ranges, as in TISEAN 3.0.1).
    #[arg(long, help_heading = "Estimator")]
    pub tisean: bool,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// Run `pdamp fnn`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let base = if args.tisean {
        FnnOptions::tisean()
    } else {
        FnnOptions::default()
    };
    let opts = FnnOptions {
        m_min: args.dim_range.min().unwrap_or(base.m_min),
        m_max: args.dim_range.max()?.unwrap_or(base.m_max),
        tau: args.delay.tau,
        ratio: args.ratio.unwrap_or(base.ratio),
        theiler: args.theiler.given().or(base.theiler),
        vectors: base.vectors,
    };
    if args.tisean && opts.tau > 1 {
        tracing::info!(
            "note: as TISEAN 3.0.1 false_nearest, --tisean compares vectors of consecutive samples \
             (s_n, s_n+1, …) and ignores -d {} inside them (it only shortens the ranges); \
             drop --tisean for delay vectors",
            opts.tau
        );
    }
    let fnn = false_nearest_neighbors(&x, &opts)
        .with_context(|| format!("false nearest neighbours of {}", args.input.file))?;
    let mut out =
        String::from("m,false_fraction,accepted,false_count,mean_distance,rms_distance\n");
    for p in &fnn {
        let f = p.fraction.map_or(String::new(), |f| format!("{f:.10e}"));
        writeln!(
            out,
            "{},{f},{},{},{:.10e},{:.10e}",
            p.m, p.accepted, p.false_count, p.mean_distance, p.rms_distance
        )?;
    }
    args.output.write(out.as_bytes())?;
    match suggested_dimension(&fnn, 0.01) {
        Some(m) => {
            tracing::info!("suggested embedding dimension: m = {m} (≤ 1 % false neighbours)")
        }
        None => {
            tracing::info!("no tested dimension has ≤ 1 % false neighbours (noise, or raise -M)")
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::cli::commands::tisean_args::parse_max_dim;

    #[test]
    fn max_dim_accepts_tisean_form() {
        assert_eq!(parse_max_dim("8").unwrap(), 8);
        assert_eq!(parse_max_dim("1,8").unwrap(), 8);
        assert!(parse_max_dim("2,8").is_err());
    }
}
