//! `pdamp nrlazy`: Schreiber's simple nonlinear noise reduction (TISEAN `lazy` / `nrlazy`).

use std::fmt::Write as _;

use anyhow::Context;
use rayon::prelude::*;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::surrogates::reject_time_column;
use crate::cli::commands::tisean_args::Output;
use pdamp::analysis::noise_reduction::{
    nonlinear_noise_reduction, Correction, NoiseReductionOptions,
};

/// Samples per block of the output, formatted in parallel.
const OUTPUT_BLOCK: usize = 16_384;

/// Arguments of `pdamp nrlazy`.
///
/// Output: the cleaned series, one value per line (data units), on stdout or in the `-o`
/// file; ε used, the mean neighbourhood size and the RMS correction of each pass go to
/// stderr. Defaults as TISEAN 3.0.1 `nrlazy`: m = 5, d = 1, one pass, ε = (max − min)/1000
/// (almost always too small: set -r to 2–3 noise amplitudes, or --radius-sd as a fraction of the
/// standard deviation, which overrides -r). By default only the middle coordinate of each
/// delay vector is corrected (Schreiber 1993, TISEAN `lazy`), and the first ⌊(m−1)/2⌋·d and last
/// ⌈(m−1)/2⌉·d samples stay as they are; `--tisean` (or `--all`) corrects every coordinate and
/// every sample as TISEAN 3.0.1's `nrlazy` does, after which the output equals TISEAN's to its
/// print precision (`tests/golden_tisean.rs`).
///
/// TISEAN's flags: `-m1,7` (components, dimension) is read as dimension 7 (one component only);
/// with `--tisean` a bare `-m7` is refused, since TISEAN reads it as 7 components of dimension
/// 5. TISEAN's `-v0.2` is `--radius-sd 0.2` here (`-v` is pdamp's `--verbose`) and its `-V`
/// verbosity has no equivalent (`-q` quietens pdamp); both are refused with that message.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Embedding dimension m, or TISEAN's `components,m` with one component (TISEAN -m1,7).
    /// Default 5.
    #[arg(
        short = 'm',
        long = "dimension",
        value_parser = parse_dim,
        help_heading = "Noise reduction"
    )]
    pub dim: Option<DimArg>,
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
    /// TISEAN nrlazy's definition: every coordinate corrected (as --all); -m must then be
    /// given in TISEAN's form `1,m`.
    #[arg(long, help_heading = "Noise reduction")]
    pub tisean: bool,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// The `-m` argument: the dimension, and whether it came in TISEAN's `components,m` form.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DimArg {
    /// Embedding dimension m.
    pub m: usize,
    /// Written as `1,m` (TISEAN's form).
    pub tisean_form: bool,
}

/// Parses `m` or TISEAN's `components,m` (one component only).
pub(crate) fn parse_dim(s: &str) -> Result<DimArg, String> {
    let (comp, m, tisean_form) = match s.split(',').collect::<Vec<_>>().as_slice() {
        [m] => ("1", *m, false),
        [c, m] => (*c, *m, true),
        _ => {
            return Err(format!(
                "`{s}`: expected m or TISEAN's `components,m` (e.g. 1,7)"
            ))
        }
    };
    if comp.trim() != "1" {
        return Err(format!(
            "`{s}`: {comp} components asked; pdamp nrlazy reads one column (-c), write -m 1,{m}"
        ));
    }
    let m = m
        .trim()
        .parse()
        .map_err(|_| format!("`{s}`: `{m}` is not a dimension"))?;
    Ok(DimArg { m, tisean_form })
}

/// Run `pdamp nrlazy`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let dim = args.dim.unwrap_or(DimArg {
        m: 5,
        tisean_form: false,
    });
    if args.tisean && args.dim.is_some() && !dim.tisean_form {
        anyhow::bail!(
            "-m {m} with --tisean: TISEAN nrlazy reads a bare -m{m} as {m} components of \
             dimension 5; write -m 1,{m} for dimension {m}",
            m = dim.m
        );
    }
    let x = args.input.read()?;
    reject_time_column(&x, &args.input)?;
    let all = args.all || args.tisean;
    if dim.tisean_form && !all {
        tracing::warn!(
            "-m 1,{m}: correcting the middle coordinate only (pdamp's default, Schreiber 1993); \
             add --tisean to correct every coordinate as TISEAN nrlazy does",
            m = dim.m
        );
    }
    let opts = NoiseReductionOptions {
        dim: dim.m,
        delay: args.delay,
        epsilon: args.radius,
        epsilon_sd: args.radius_sd,
        iterations: args.iterations,
        correction: if all {
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
    // formatted in parallel over fixed blocks, joined in order
    let text: String = r
        .values
        .par_chunks(OUTPUT_BLOCK)
        .map(|block| {
            let mut text = String::with_capacity(block.len() * 18);
            for v in block {
                writeln!(text, "{v:.10e}").expect("writing to a String cannot fail");
            }
            text
        })
        .collect::<Vec<String>>()
        .concat();
    args.output.write(text.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dim_accepts_tisean_form_and_refuses_components() {
        assert_eq!(
            parse_dim("7"),
            Ok(DimArg {
                m: 7,
                tisean_form: false
            })
        );
        assert_eq!(
            parse_dim("1,7"),
            Ok(DimArg {
                m: 7,
                tisean_form: true
            })
        );
        assert!(parse_dim("2,7").unwrap_err().contains("one column"));
        assert!(parse_dim("1,x").is_err());
        assert!(parse_dim("1,2,3").is_err());
    }
}
