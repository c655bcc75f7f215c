//! `pdamp merge DIR… [--out OUT]`: joins the shards of one sweep (`pdamp sweep … --shard
//! K/N`) into `sweep.csv`, `strobe.csv` and `timings.csv`, byte-identical (sweep.csv,
//! strobe.csv) to an unsharded run.

use anyhow::Context;
use std::path::PathBuf;

/// Arguments of `pdamp merge`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The shards' output directories (one shared directory, or one per shard). All must hold
    /// the same sweep (their sweep.json).
    #[arg(required = true, value_name = "DIR")]
    pub dirs: Vec<PathBuf>,
    /// Where to write the tables (default: the first DIR).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Run `pdamp merge`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let out = args.out.clone().unwrap_or_else(|| args.dirs[0].clone());
    let report = pdamp::sweep::merge(&args.dirs, &out).context("merge")?;
    let from: Vec<String> = args
        .dirs
        .iter()
        .zip(&report.per_dir)
        .map(|(d, k)| format!("{k} from {}", d.display()))
        .collect();
    println!(
        "merged {} points ({}); wrote {}",
        report.points,
        from.join(", "),
        out.join("sweep.csv").display()
    );
    Ok(())
}
