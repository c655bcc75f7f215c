//! `pdamp surrogate-test`: rank test of a discriminating statistic on the data against
//! surrogates (nonlinear prediction error or time-reversal asymmetry).

use std::io::Write;

use anyhow::Context;
use serde::Serialize;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::surrogates::{reject_time_column, select_segment};
use crate::cli::commands::tisean_args::{edit_arg, Theiler};
use pdamp::analysis::prediction_error::{prediction_error, PredictionErrorOptions};
use pdamp::analysis::surrogate_test::{
    surrogate_test, SurrogateTestOptions, SurrogateTestResult, Tail,
};
use pdamp::analysis::surrogates::{SurrogateMethod, SurrogateOptions};
use pdamp::analysis::time_reversal::time_reversal_asymmetry;
use pdamp::error::AnalysisError;

/// The discriminating statistic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// Locally constant prediction error (TISEAN zeroth); chaos is more predictable than
    /// its surrogates: lower tail.
    PredictionError,
    /// Time-reversal asymmetry ⟨(x_{n+d}−x_n)³⟩/⟨(x_{n+d}−x_n)²⟩^{3/2}: two-sided.
    TimeReversal,
}

/// Arguments of `pdamp surrogate-test`.
///
/// Computes the statistic on the data and on n surrogates (IAAFT by default) and prints the
/// data's value, the surrogates' mean ± standard deviation, the rank of the data, the p-value
/// by rank (smallest possible 1/(n+1) one-sided, 2/(n+1) two-sided) and the significance in
/// standard deviations. With --json: one object with `statistic`, `data_value`,
/// `surrogate_values`, `rank`, `p_value`, `p_min`, `surrogate_mean`, `surrogate_sd`,
/// `significance_sigma`, `tail`, `rejected` (p ≤ --alpha), `max_discrepancy`,
/// `not_converged` and the options used.
#[derive(Debug, clap::Args)]
#[command(mut_args(edit_arg("theiler", |a| a
    .help("Theiler window in samples")
    .help_heading("Statistic")
    .default_value("0"))))]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Discriminating statistic.
    #[arg(
        long = "statistic",
        value_enum,
        default_value = "prediction-error",
        help_heading = "Test"
    )]
    pub statistic: Statistic,
    /// Number of surrogates: 19 for a one-sided test at 0.05, 39 two-sided.
    #[arg(
        short = 'n',
        long = "number",
        default_value_t = 19,
        help_heading = "Test"
    )]
    pub number: usize,
    /// Side of the test: lower, upper or two-sided. Default: lower for the prediction
    /// error, two-sided for the time-reversal asymmetry.
    #[arg(long = "tail", help_heading = "Test")]
    pub tail: Option<Tail>,
    /// Significance level for the verdict.
    #[arg(long = "alpha", default_value_t = 0.05, help_heading = "Test")]
    pub alpha: f64,
    /// Surrogate kind: iaaft, ft or shuffle.
    #[arg(long = "method", default_value = "iaaft", help_heading = "Surrogates")]
    pub method: SurrogateMethod,
    /// Largest number of IAAFT iterations.
    #[arg(
        short = 'i',
        long = "iterations",
        default_value_t = 1000,
        help_heading = "Surrogates"
    )]
    pub iterations: usize,
    /// Seed of the surrogates.
    #[arg(
        short = 'I',
        long = "seed",
        default_value_t = 0,
        help_heading = "Surrogates"
    )]
    pub seed: u64,
    /// Select the sub-segment of at least this fraction with the smallest end-point
    /// mismatch first (recommended for flows, e.g. 0.9).
    #[arg(
        long = "end-to-end",
        value_name = "FRACTION",
        help_heading = "Surrogates"
    )]
    pub end_to_end: Option<f64>,
    /// Embedding dimension m (prediction error).
    #[arg(
        short = 'm',
        long = "dimension",
        default_value_t = 3,
        help_heading = "Statistic"
    )]
    pub dim: usize,
    /// Delay τ in samples (prediction error), or the lag of the time-reversal asymmetry.
    #[arg(
        short = 'd',
        long = "delay",
        default_value_t = 1,
        help_heading = "Statistic"
    )]
    pub delay: usize,
    /// Prediction horizon h in samples.
    #[arg(
        short = 's',
        long = "steps",
        default_value_t = 1,
        help_heading = "Statistic"
    )]
    pub horizon: usize,
    /// Starting neighbourhood radius as a fraction of the standard deviation.
    #[arg(long = "epsilon", default_value_t = 0.1, help_heading = "Statistic")]
    pub epsilon: f64,
    /// Smallest number of neighbours per prediction (ε grows by 1.2 until reached).
    #[arg(
        short = 'k',
        long = "neighbors",
        default_value_t = 5,
        help_heading = "Statistic"
    )]
    pub min_neighbors: usize,
    /// Theiler window -t, 0 by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// Print one JSON object instead of the table.
    #[arg(long, help_heading = "Output")]
    pub json: bool,
}

#[derive(Serialize)]
struct Report<'a> {
    statistic: Statistic,
    #[serde(flatten)]
    result: &'a SurrogateTestResult,
    rejected: bool,
    alpha: f64,
    n_samples: usize,
    surrogate: SurrogateOptions,
    prediction: Option<PredictionErrorOptions>,
}

/// Run `pdamp surrogate-test`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    reject_time_column(&x, &args.input)?;
    let x = select_segment(x, args.end_to_end)?;
    let p = PredictionErrorOptions {
        dim: args.dim,
        delay: args.delay,
        horizon: args.horizon,
        epsilon: args.epsilon,
        min_neighbors: args.min_neighbors,
        theiler: args.theiler.window(),
        ..PredictionErrorOptions::default()
    };
    let lag = args.delay;
    let stat = move |s: &[f64]| -> Result<f64, AnalysisError> {
        match args.statistic {
            Statistic::PredictionError => prediction_error(s, &p),
            Statistic::TimeReversal => time_reversal_asymmetry(s, lag),
        }
    };
    let tail = args.tail.unwrap_or(match args.statistic {
        Statistic::PredictionError => Tail::Lower,
        Statistic::TimeReversal => Tail::TwoSided,
    });
    let opts = SurrogateTestOptions {
        n_surrogates: args.number,
        surrogate: SurrogateOptions {
            method: args.method,
            max_iterations: args.iterations,
            exact_spectrum: false,
            seed: args.seed,
        },
        tail,
    };
    let r = surrogate_test(&x, &stat, &opts)
        .with_context(|| format!("surrogate test of {}", args.input.file))?;
    let rejected = r.rejects(args.alpha);
    let mut out = std::io::stdout().lock();
    if args.json {
        let report = Report {
            statistic: args.statistic,
            result: &r,
            rejected,
            alpha: args.alpha,
            n_samples: x.len(),
            surrogate: opts.surrogate,
            prediction: (args.statistic == Statistic::PredictionError).then_some(p),
        };
        serde_json::to_writer_pretty(&mut out, &report)?;
        writeln!(out)?;
    } else {
        writeln!(out, "statistic            {:?}", args.statistic)?;
        writeln!(out, "samples              {}", x.len())?;
        writeln!(
            out,
            "surrogates           {} ({:?}, seed {})",
            args.number, args.method, args.seed
        )?;
        writeln!(out, "data value           {:.6}", r.data_value)?;
        writeln!(
            out,
            "surrogates           {:.6} ± {:.6}",
            r.surrogate_mean, r.surrogate_sd
        )?;
        writeln!(
            out,
            "rank of data         {} of {}",
            r.rank,
            args.number + 1
        )?;
        let label = format!("p-value ({tail:?})");
        writeln!(
            out,
            "{label:<21}{:.4} (smallest possible {:.4})",
            r.p_value, r.p_min
        )?;
        writeln!(
            out,
            "significance         {:.2} sigma",
            r.significance_sigma
        )?;
        if r.not_converged > 0 {
            writeln!(
                out,
                "warning              {} surrogates did not converge (raise -i)",
                r.not_converged
            )?;
        }
        writeln!(
            out,
            "verdict              {} at alpha = {}",
            if rejected {
                "null hypothesis rejected"
            } else {
                "not rejected"
            },
            args.alpha
        )?;
    }
    out.flush()?;
    Ok(())
}
