//! `pdamp spectrum`: windowed power spectrum and its spectral lines.

use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use pdamp::analysis::spectrum::{
    line_power_fraction, power_spectrum, spectral_lines, LineOptions, Normalization,
    SpectrumOptions, Window,
};

/// Long help of `pdamp spectrum`: what it writes and how to read it.
const LONG_HELP: &str = "Output (CSV on stdout, header row): the one-sided spectrum, columns
`frequency_hz` (with --dt) or `frequency_cycles_per_sample`, then `power` (series units² per
bin; a sine of amplitude A puts A²/2 in its line, Σ power = mean square), `psd_per_hz`
(`--normalization density`) or `power_tisean` (|X_k|²/N², TISEAN `spectrum`). With `--lines`
the output is instead the table of detected lines: frequency, `line_power` (summed over the
window's main lobe), `peak_power`, `prominence` (peak over local median floor). A one-line
summary (number of lines, fraction of the power in lines) goes to stderr.

To reproduce TISEAN's `spectrum`: `--window rectangular --normalization tisean --no-detrend`.";

/// Arguments of `pdamp spectrum`.
///
/// Output (CSV on stdout, header row): the one-sided spectrum, columns
/// `frequency_hz` (with --dt) or `frequency_cycles_per_sample`, then `power` (series units² per
/// bin; a sine of amplitude A puts A²/2 in its line, Σ power = mean square), `psd_per_hz`
/// (`--normalization density`) or `power_tisean` (|X_k|²/N², TISEAN `spectrum`). With `--lines`
/// the output is instead the table of detected lines: frequency, `line_power` (summed over the
/// window's main lobe), `peak_power`, `prominence` (peak over local median floor). A one-line
/// summary (number of lines, fraction of the power in lines) goes to stderr.
///
/// To reproduce TISEAN's `spectrum`: `--window rectangular --normalization tisean --no-detrend`.
#[derive(Debug, clap::Args)]
#[command(after_long_help = LONG_HELP)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Sampling interval in seconds; frequencies are then in Hz. Default: cycles/sample.
    #[arg(long = "dt", help_heading = "Spectrum")]
    pub dt_s: Option<f64>,
    /// Window: rectangular, hann, hamming or blackman-harris (4-term, −92 dB side lobes).
    #[arg(long, default_value = "hann", help_heading = "Spectrum")]
    pub window: Window,
    /// Normalisation: power (per bin, one-sided, window-corrected), density (power/Hz) or
    /// tisean (|X_k|²/N²).
    #[arg(long, default_value = "power", help_heading = "Spectrum")]
    pub normalization: Normalization,
    /// Keep the mean (by default it is subtracted so that DC does not leak into low lines).
    #[arg(long, help_heading = "Spectrum")]
    pub no_detrend: bool,
    /// Print the detected spectral lines instead of the spectrum.
    #[arg(long, help_heading = "Lines")]
    pub lines: bool,
    /// A line's peak must exceed this factor × the local median floor (100 = 20 dB).
    #[arg(long, default_value_t = 100.0, help_heading = "Lines")]
    pub factor: f64,
    /// Half-width in bins of the window whose median is the local noise floor.
    #[arg(long, default_value_t = 32, help_heading = "Lines")]
    pub floor_half_width: usize,
    /// Report at most this many lines (the strongest).
    #[arg(long, default_value_t = 64, help_heading = "Lines")]
    pub max_lines: usize,
}

/// Run `pdamp spectrum`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.factor.is_finite() && args.factor >= 1.0) {
        anyhow::bail!(
            "--factor {}: must be ≥ 1 (a line stands this many times above its floor)",
            args.factor
        );
    }
    let x = args.input.read()?;
    let opts = SpectrumOptions {
        window: args.window,
        normalization: args.normalization,
        dt_s: args.dt_s,
        detrend: !args.no_detrend,
    };
    let spec =
        power_spectrum(&x, &opts).with_context(|| format!("spectrum of {}", args.input.file))?;
    let line_opts = LineOptions {
        factor: args.factor,
        floor_half_width: args.floor_half_width.max(1),
        max_lines: args.max_lines,
        ..LineOptions::default()
    };
    let lines = spectral_lines(&spec, &line_opts);
    let f_col = if spec.in_hz {
        "frequency_hz"
    } else {
        "frequency_cycles_per_sample"
    };
    let p_col = match args.normalization {
        Normalization::Power => "power",
        Normalization::Density => {
            if spec.in_hz {
                "psd_per_hz"
            } else {
                "psd_per_cycle_per_sample"
            }
        }
        Normalization::Tisean => "power_tisean",
    };
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if args.lines {
        writeln!(out, "{f_col},line_power,peak_power,prominence")?;
        for l in &lines {
            writeln!(
                out,
                "{:.10e},{:.10e},{:.10e},{:.4e}",
                l.frequency, l.line_power, l.peak_power, l.prominence
            )?;
        }
    } else {
        writeln!(out, "{f_col},{p_col}")?;
        for (f, p) in spec.frequency.iter().zip(&spec.power) {
            writeln!(out, "{f:.10e},{p:.10e}")?;
        }
    }
    out.flush()?;
    tracing::info!(
        "{} samples, bin width {:.6e} {}, {} line(s) carrying {:.1} % of the power",
        spec.n_samples,
        spec.bin_width,
        if spec.in_hz { "Hz" } else { "cycles/sample" },
        lines.len(),
        100.0 * line_power_fraction(&spec, &lines)
    );
    Ok(())
}
