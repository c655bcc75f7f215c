//! `pdamp embed`: write delay vectors (SPEC (4.1.1)).

use std::io::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use pdamp::analysis::DelayEmbedding;

/// Arguments of `pdamp embed`.
///
/// Output: CSV on stdout, one delay vector per row: `n` (index of the first component) and
/// `x_0 … x_{m-1}` with `x_k = s_{n+k·τ}` (data units of the input column). TISEAN's
/// `delay` writes the same vectors without a header.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Embedding dimension m.
    #[arg(
        short = 'm',
        long = "dimension",
        default_value_t = 2,
        help_heading = "Embedding"
    )]
    pub m: usize,
    /// Delay τ in samples.
    #[arg(
        short = 'd',
        long = "delay",
        default_value_t = 1,
        help_heading = "Embedding"
    )]
    pub tau: usize,
}

/// Run `pdamp embed`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let e = DelayEmbedding::new(&x, args.m, args.tau)
        .with_context(|| format!("embedding {}", args.input.file))?;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let header: Vec<String> = (0..args.m).map(|k| format!("x_{k}")).collect();
    writeln!(out, "n,{}", header.join(","))?;
    for i in 0..e.len() {
        write!(out, "{i}")?;
        for k in 0..args.m {
            write!(out, ",{}", e.component(i, k))?;
        }
        writeln!(out)?;
    }
    out.flush()?;
    Ok(())
}
