//! `pdamp nrlazy`: Schreiber's simple nonlinear noise reduction (TISEAN `lazy` / `nrlazy`).

use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::surrogates::reject_time_column;
use pdamp::analysis::noise_reduction::{
    nonlinear_noise_reduction, Correction, NoiseReductionOptions,
};

/// Arguments of `pdamp nrlazy`.
///
/// Output: the cleaned series, one value per line (data units), on stdout or in the `-o`
/// file; ε used, the mean neighbourhood size and the RMS correction of each pass go to
/// stderr. Defaults as TISEAN 3.0.1 `nrlazy`: m = 5, d = 1, one pass, ε = (max − min)/1000
/// (almost always too small: set -r to 2–3 noise amplitudes, or --radius-sd as a fraction of the
/// standard deviation, which overrides -r). By default only the middle coordinate of each
/// delay vector is corrected (Schreiber 1993, TISEAN `lazy`); --all corrects every coordinate
/// as TISEAN's `nrlazy` does.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Embedding dimension (TISEAN -m).
    #[arg(
        short = 'm',
        long = "dimension",
        default_value_t = 5,
        help_heading = "Noise reduction"
    )]
    pub dim: usize,
    /// Delay in samples (TISEAN -d).
    #[arg(
        short = 'd',
        long = "delay",
        default_value_t = 1,
        help_heading = "Noise reduction"
    )]
    pub delay: usize,
    /// Neighbourhood radius in data units, maximum norm (TISEAN -r).
    #[arg(short = 'r', long = "radius", help_heading = "Noise reduction")]
    pub radius: Option<f64>,
    /// Neighbourhood radius as a fraction of the standard deviation (TISEAN's -v, long-only
    /// here since -v is pdamp's --verbose; overrides -r).
    #[arg(long = "radius-sd", help_heading = "Noise reduction")]
    pub radius_sd: Option<f64>,
    /// Number of passes (TISEAN -i).
    #[arg(
        short = 'i',
        long = "iterations",
        default_value_t = 1,
        help_heading = "Noise reduction"
    )]
    pub iterations: usize,
    /// Correct every coordinate of the delay vectors (TISEAN nrlazy) instead of the middle one.
    #[arg(long = "all", help_heading = "Noise reduction")]
    pub all: bool,
    /// Write to this file instead of stdout (TISEAN -o).
    #[arg(short = 'o', long = "output", help_heading = "Output")]
    pub output: Option<String>,
}

/// Run `pdamp nrlazy`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    reject_time_column(&x, &args.input)?;
    let opts = NoiseReductionOptions {
        dim: args.dim,
        delay: args.delay,
        epsilon: args.radius,
        epsilon_sd: args.radius_sd,
        iterations: args.iterations,
        correction: if args.all {
            Correction::AllCoordinates
        } else {
            Correction::Middle
        },
    };
    let r = nonlinear_noise_reduction(&x, &opts)
        .with_context(|| format!("noise reduction of {}", args.input.file))?;
    tracing::info!(
        "epsilon = {:.6e} (data units), {:.1} neighbours per vector in the last pass, RMS correction per pass: {}",
        r.epsilon,
        r.mean_neighbors,
        r.rms_correction.iter().map(|v| format!("{v:.4e}")).collect::<Vec<_>>().join(", ")
    );
    if r.mean_neighbors < 1.5 {
        tracing::warn!(
            "almost no neighbours within epsilon; raise -r or --radius-sd (2-3 noise levels)"
        );
    }
    let mut text = String::with_capacity(x.len() * 18);
    for v in &r.values {
        text.push_str(&format!("{v:.10e}\n"));
    }
    match &args.output {
        Some(path) => pdamp::io::atomic_write(std::path::Path::new(path), text.as_bytes())?,
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(text.as_bytes())?;
            out.flush()?;
        }
    }
    Ok(())
}
