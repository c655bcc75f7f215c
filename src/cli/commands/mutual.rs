//! `pdamp mutual`: time-delayed mutual information I(τ) (TISEAN `mutual`).

use std::fmt::Write;

use crate::cli::commands::tisean_args::Output;

use anyhow::Context;
use pdamp::analysis::mutual_information::small_sample_bias;
use pdamp::analysis::{mutual_information, MutualInformationOptions};
use pdamp::io::series::{read_table, Delimiter, SeriesTable};
use pdamp::io::{Column, SeriesReadOptions};

/// Series input shared by the analysis subcommands (TISEAN's file, `-c`, `-l`, `-x`).
#[derive(Debug, Clone, clap::Args)]
pub struct SeriesInput {
    /// Series file: plain text or CSV, one sample per line, `#` comments, optional header
    /// row; `-` reads standard input. One delimiter per file, every row with the same number
    /// of fields.
    #[arg(default_value = "-", help_heading = "Input")]
    pub file: String,
    /// Column to read: 1-based number (as TISEAN -c) or header name. Default: the first, or
    /// the second when the first is a time column (header `t`, `time` or `time_s`, uniformly
    /// increasing; its step is reported).
    #[arg(short = 'c', long = "column", help_heading = "Input")]
    pub column: Option<Column>,
    /// Use at most this many samples (TISEAN -l). Default: all.
    #[arg(short = 'l', long = "length", help_heading = "Input")]
    pub length: Option<usize>,
    /// Skip this many lines at the start of the file (TISEAN -x).
    #[arg(
        short = 'x',
        long = "skip",
        default_value_t = 0,
        help_heading = "Input"
    )]
    pub skip: usize,
    /// Field delimiter: comma, semicolon, tab or whitespace. Default: detected from the first
    /// row.
    #[arg(long, value_name = "DELIMITER", help_heading = "Input")]
    pub delimiter: Option<Delimiter>,
    /// The file writes decimals with a comma (`-4,408e0`); its delimiter is then a semicolon,
    /// tab or whitespace.
    #[arg(long, help_heading = "Input")]
    pub decimal_comma: bool,
}

impl SeriesInput {
    /// The reader's options for `columns` (empty: the automatic choice).
    pub fn options(&self, columns: Vec<Column>) -> SeriesReadOptions {
        SeriesReadOptions {
            columns,
            skip_lines: self.skip,
            max_rows: self.length,
            delimiter: self.delimiter,
            decimal_comma: self.decimal_comma,
        }
    }

    /// Reads the selected column, saying on stderr which one when a time column was found.
    pub fn read_table(&self) -> anyhow::Result<SeriesTable> {
        let table = read_table(
            &self.file,
            &self.options(self.column.iter().cloned().collect()),
        )?;
        if table.time.is_some() {
            tracing::info!("{}: reading {}", self.file, table.describe_choice());
        }
        Ok(table)
    }

    /// Reads the selected column (see [`SeriesInput::read_table`]).
    pub fn read(&self) -> anyhow::Result<Vec<f64>> {
        Ok(self.read_table()?.columns.remove(0))
    }

    /// The selected column as given (`1` when chosen automatically), for messages.
    pub fn column_label(&self) -> String {
        self.column
            .as_ref()
            .map_or_else(|| "1".to_string(), ToString::to_string)
    }
}

/// Arguments of `pdamp mutual`.
///
/// Output: CSV on stdout with columns `lag_samples,mutual_information_nats`; the first
/// minimum (the usual choice of the embedding lag τ) is reported on stderr. Same definition
/// and defaults as TISEAN 3.0.1 `mutual` (series rescaled to [0,1], b bins, histograms over
/// the N − τ pairs, natural log), so the numbers match TISEAN's to rounding.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Largest lag D in samples (TISEAN -D).
    #[arg(
        short = 'D',
        long = "max-lag",
        default_value_t = 20,
        help_heading = "Estimator"
    )]
    pub max_lag: usize,
    /// Number of histogram bins per axis (TISEAN -b).
    #[arg(
        short = 'b',
        long = "bins",
        default_value_t = 16,
        help_heading = "Estimator"
    )]
    pub bins: usize,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// Run `pdamp mutual`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let mi = mutual_information(
        &x,
        &MutualInformationOptions {
            bins: args.bins,
            max_lag: args.max_lag,
        },
    )
    .with_context(|| format!("mutual information of {}", args.input.file))?;
    let mut out = String::from("lag_samples,mutual_information_nats\n");
    for (tau, v) in mi.values.iter().enumerate() {
        writeln!(out, "{tau},{v:.10e}")?;
    }
    args.output.write(out.as_bytes())?;
    // the estimator's bias at the largest lag (fewest pairs) against the entropy I(0)
    let max_lag = mi.values.len() - 1;
    let bias = small_sample_bias(x.len() - max_lag, mi.bins);
    let unreliable = bias > 0.05 * mi.values[0];
    if unreliable {
        tracing::warn!(
            "{} samples are too few for {b}×{b} bins: the small-sample bias of I(tau), \
             (b−1)²/(2(N−D)) = {bias:.3} nats, exceeds 5 % of I(0) = {:.3} nats, so the curve and \
             its minimum reflect the estimator, not the data; use a longer series or fewer bins (-b)",
            x.len(),
            mi.values[0],
            b = mi.bins
        );
    }
    match mi.first_minimum {
        Some(t) if unreliable => {
            tracing::info!(
                "first minimum of I(tau) at tau = {t} samples (unreliable: see the warning)"
            )
        }
        Some(t) => tracing::info!("first minimum of I(tau) at tau = {t} samples"),
        None => tracing::info!(
            "no first minimum up to D = {}: raise -D (the curve still decreases)",
            mi.values.len() - 1
        ),
    }
    Ok(())
}
