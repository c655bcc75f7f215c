//! `pdamp rqa`: recurrence quantification analysis (Marwan et al. 2007).

use std::io::Write;

use anyhow::{bail, Context};

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, Dim, Theiler};
use pdamp::analysis::recurrence::{rqa, RecurrenceOptions, RecurrenceThreshold, DEFAULT_MAX_LEN};

/// Arguments of `pdamp rqa`.
///
/// Output: the measures as `name value` lines on stdout (or one JSON object with --json,
/// including the line-length histograms): vectors, ε (data units), RR, DET, L, L_max, ENTR,
/// LAM, TT, V_max. Undefined measures (no lines ≥ l_min) print as `-` (JSON null). The
/// matrix is never stored (O(N) memory, O(N²) time); series longer than --max-len are
/// refused.
#[derive(Debug, clap::Args)]
#[command(
    mut_args(edit_arg("m", |a| a.help("Embedding dimension").default_value("1"))),
    mut_arg("tau", |a| a.help("Delay τ in samples")),
    mut_args(edit_arg("theiler", |a| a
        .help("Theiler window w: entries with |i − j| ≤ w are excluded (0: the line of identity)")
        .default_value("0")))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Embedding dimension -m, 1 by default.
    #[command(flatten)]
    pub dim: Dim,
    /// Delay τ (-d; help below).
    #[command(flatten)]
    pub delay: Delay,
    /// Theiler window -t, 0 by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// Fixed threshold ε in data units (maximum norm).
    #[arg(
        short = 'r',
        long = "eps",
        help_heading = "Estimator",
        conflicts_with = "rate"
    )]
    pub eps: Option<f64>,
    /// Fixed recurrence rate in (0, 1) (default 0.05 when --eps is not given).
    #[arg(long = "rate", help_heading = "Estimator")]
    pub rate: Option<f64>,
    /// Shortest diagonal line counted in DET, L, ENTR.
    #[arg(long, default_value_t = 2, help_heading = "Estimator")]
    pub l_min: usize,
    /// Shortest vertical line counted in LAM, TT.
    #[arg(long, default_value_t = 2, help_heading = "Estimator")]
    pub v_min: usize,
    /// Refuse more delay vectors than this (the cost grows as N²).
    #[arg(long, default_value_t = DEFAULT_MAX_LEN, help_heading = "Estimator")]
    pub max_len: usize,
    /// Print one JSON object instead of lines.
    #[arg(long, help_heading = "Output")]
    pub json: bool,
}

/// The threshold from `--eps` / `--rate`.
pub(crate) fn threshold(
    eps: Option<f64>,
    rate: Option<f64>,
) -> anyhow::Result<RecurrenceThreshold> {
    Ok(match (eps, rate) {
        (Some(e), None) => RecurrenceThreshold::Fixed(e),
        (None, Some(r)) => RecurrenceThreshold::Rate(r),
        (None, None) => RecurrenceThreshold::Rate(0.05),
        (Some(_), Some(_)) => bail!("give either --eps or --rate, not both"),
    })
}

/// Run `pdamp rqa`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let opts = RecurrenceOptions {
        m: args.dim.get(),
        tau: args.delay.tau,
        theiler: args.theiler.window(),
        threshold: threshold(args.eps, args.rate)?,
        l_min: args.l_min,
        v_min: args.v_min,
        max_len: args.max_len,
    };
    let r = rqa(&x, &opts).with_context(|| format!("RQA of {}", args.input.file))?;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&r)?)?;
        out.flush()?;
        return Ok(());
    }
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    writeln!(out, "vectors {}", r.vectors)?;
    writeln!(out, "eps {:.6e}", r.eps)?;
    writeln!(out, "recurrence_rate {:.6}", r.recurrence_rate)?;
    writeln!(out, "determinism {}", opt(r.determinism))?;
    writeln!(out, "mean_diagonal {}", opt(r.mean_diagonal))?;
    writeln!(out, "max_diagonal {}", r.max_diagonal)?;
    writeln!(out, "diagonal_entropy {}", opt(r.diagonal_entropy))?;
    writeln!(out, "laminarity {}", opt(r.laminarity))?;
    writeln!(out, "trapping_time {}", opt(r.trapping_time))?;
    writeln!(out, "max_vertical {}", r.max_vertical)?;
    out.flush()?;
    Ok(())
}
