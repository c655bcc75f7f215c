//! `pdamp surrogates`: IAAFT (default), phase-randomised or shuffled surrogate series
//! (TISEAN `surrogates`, `endtoend`).

use anyhow::{bail, Context};

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::Output;
use pdamp::analysis::surrogates::{
    end_to_end_segment, surrogates, SurrogateMethod, SurrogateOptions,
};

/// Arguments of `pdamp surrogates`.
///
/// Output: one column per surrogate (whitespace separated, `# surrogate_1 …` comment header)
/// on stdout or in the `-o` file; for each surrogate the number of iterations, whether the
/// rank order converged and the RMS discrepancy between the exact-spectrum and exact-value
/// stages (fraction of the data's standard deviation) go to stderr, as TISEAN prints them.
/// Same options as TISEAN 3.0.1 `surrogates` (-n, -i, -S, -I); unlike TISEAN the length is
/// not truncated to a product of 2, 3 and 5, and the iteration is capped at -i 1000 by
/// default (TISEAN: until no change). `--end-to-end F` first selects the sub-segment of at
/// least F·N samples with the smallest end-point mismatch (TISEAN `endtoend`).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Number of surrogates (TISEAN -n).
    #[arg(
        short = 'n',
        long = "number",
        default_value_t = 1,
        help_heading = "Surrogates"
    )]
    pub number: usize,
    /// Largest number of IAAFT iterations (TISEAN -i); the iteration stops when the rank
    /// order no longer changes. -i 0: a random shuffle (with -S: an FT surrogate).
    #[arg(
        short = 'i',
        long = "iterations",
        default_value_t = 1000,
        help_heading = "Surrogates"
    )]
    pub iterations: usize,
    /// Output the stage with the exact spectrum instead of the exact values (TISEAN -S).
    #[arg(short = 'S', long = "exact-spectrum", help_heading = "Surrogates")]
    pub exact_spectrum: bool,
    /// Seed of the random numbers (TISEAN -I); surrogate k uses stream k of it.
    #[arg(
        short = 'I',
        long = "seed",
        default_value_t = 0,
        help_heading = "Surrogates"
    )]
    pub seed: u64,
    /// Kind of surrogate: iaaft (Schreiber & Schmitz 1996), ft (phase-randomised,
    /// Theiler et al. 1992) or shuffle.
    #[arg(long = "method", default_value = "iaaft", help_heading = "Surrogates")]
    pub method: SurrogateMethod,
    /// Select the sub-segment of at least this fraction of the series with the smallest
    /// end-point mismatch before making surrogates (e.g. 0.9); its range goes to stderr.
    #[arg(
        long = "end-to-end",
        value_name = "FRACTION",
        help_heading = "Surrogates"
    )]
    pub end_to_end: Option<f64>,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// Refuses a strictly monotone column (a time or index column, usually column 1 of a
/// simulation's CSV): no surrogate or noise analysis makes sense of it.
pub(crate) fn reject_time_column(x: &[f64], input: &SeriesInput) -> anyhow::Result<()> {
    let increasing = x.windows(2).all(|w| w[1] > w[0]);
    let decreasing = x.windows(2).all(|w| w[1] < w[0]);
    if x.len() >= 3 && (increasing || decreasing) {
        bail!(
            "{}: column {} is strictly monotone ({} … {}), which looks like a time or index \
             column; select the signal column with -c (e.g. -c 2)",
            input.file,
            input.column_label(),
            x[0],
            x[x.len() - 1]
        );
    }
    Ok(())
}

/// Applies `--end-to-end`: returns the selected segment (or the whole series).
pub(crate) fn select_segment(x: Vec<f64>, fraction: Option<f64>) -> anyhow::Result<Vec<f64>> {
    let Some(f) = fraction else {
        return Ok(x);
    };
    if !(f > 0.0 && f <= 1.0) {
        bail!("--end-to-end {f}: the fraction must be in (0, 1], e.g. 0.9");
    }
    let min_len = ((f * x.len() as f64).ceil() as usize).clamp(3, x.len());
    let seg = end_to_end_segment(&x, min_len).context("end-to-end segment selection")?;
    tracing::info!(
        "end-to-end: using samples {}..{} ({} of {}), mismatch {:.3e} (whole series {:.3e})",
        seg.start,
        seg.start + seg.len,
        seg.len,
        x.len(),
        seg.mismatch,
        seg.mismatch_whole
    );
    Ok(x[seg.start..seg.start + seg.len].to_vec())
}

/// Run `pdamp surrogates`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    reject_time_column(&x, &args.input)?;
    let x = select_segment(x, args.end_to_end)?;
    let opts = SurrogateOptions {
        method: args.method,
        max_iterations: args.iterations,
        exact_spectrum: args.exact_spectrum,
        seed: args.seed,
    };
    let surr = surrogates(&x, args.number, &opts)
        .with_context(|| format!("surrogates of {}", args.input.file))?;
    for (k, s) in surr.iter().enumerate() {
        if args.method == SurrogateMethod::Iaaft {
            tracing::info!(
                "surrogate {}: {} iterations{}, discrepancy {:.3e}",
                k + 1,
                s.iterations,
                if s.converged {
                    " (converged)"
                } else {
                    " (not converged: raise -i)"
                },
                s.discrepancy
            );
        }
    }
    let mut text = String::with_capacity(x.len() * 18 * surr.len() + 64);
    let names: Vec<String> = (1..=surr.len()).map(|k| format!("surrogate_{k}")).collect();
    text.push_str(&format!("# {}\n", names.join(" ")));
    for i in 0..x.len() {
        let row: Vec<String> = surr
            .iter()
            .map(|s| format!("{:.10e}", s.values[i]))
            .collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    args.output.write(text.as_bytes())
}
