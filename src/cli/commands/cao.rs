//! `pdamp cao`: Cao's minimum embedding dimension (Cao 1997; DynamicalSystems.jl's
//! `delay_afnn`).

use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, Theiler};
use pdamp::analysis::cao::{cao, CaoOptions};

/// Arguments of `pdamp cao`.
///
/// Output: CSV on stdout with columns `m,e1,e2,e,e_star` (E and E* of dimension m; E1(m) =
/// E(m+1)/E(m), E2(m) = E*(m+1)/E*(m); E* in data units). The saturation dimension (first m
/// with E1 ≥ --saturation and a change < --flatness to the next m) goes to stderr, with a
/// note when E2 stays near 1 (no evidence of determinism).
#[derive(Debug, clap::Args)]
#[command(
    mut_arg("tau", |a| a.help("Delay τ in samples; use the first minimum of `pdamp mutual`")),
    mut_args(edit_arg("theiler", |a| a
        .help(
            "Theiler window in samples (neighbours must be more than this apart in time). Use at \
             least τ for flows"
        )
        .default_value("0")))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Largest dimension m for E1(m), E2(m) (at most 11).
    #[arg(
        short = 'M',
        long = "max-dim",
        default_value_t = 8,
        help_heading = "Estimator"
    )]
    pub m_max: usize,
    /// Delay τ (-d; help below).
    #[command(flatten)]
    pub delay: Delay,
    /// Theiler window -t, 0 by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// E1 level that counts as saturated.
    #[arg(long, default_value_t = 0.85, help_heading = "Estimator")]
    pub saturation: f64,
    /// Largest change of E1 to the next dimension on the plateau.
    #[arg(long, default_value_t = 0.1, help_heading = "Estimator")]
    pub flatness: f64,
}

/// Run `pdamp cao`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let opts = CaoOptions {
        m_max: args.m_max,
        tau: args.delay.tau,
        theiler: args.theiler.window(),
        saturation: args.saturation,
        flatness: args.flatness,
    };
    let r = cao(&x, &opts).with_context(|| format!("Cao's method on {}", args.input.file))?;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    writeln!(out, "m,e1,e2,e,e_star")?;
    for k in 0..r.m.len() {
        writeln!(
            out,
            "{},{:.8},{:.8},{:.8e},{:.8e}",
            r.m[k], r.e1[k], r.e2[k], r.e[k], r.e_star[k]
        )?;
    }
    out.flush()?;
    match r.dimension {
        Some(m) => tracing::info!("minimum embedding dimension (E1 saturated): m = {m}"),
        None => tracing::info!(
            "E1 does not saturate up to m = {} (noise, or raise -M)",
            args.m_max
        ),
    }
    if r.e2.iter().all(|e| (e - 1.0).abs() < 0.05) {
        tracing::info!("E2 ≈ 1 for every m: the series looks random (Cao's test)");
    }
    Ok(())
}
