//! `pdamp slurm SCENE --vary … --out DIR --shards N [--parallel P] [--script FILE]`: writes
//! (or prints) a bash script that submits the sweep to Slurm as a job array of N shards and its
//! merge as a dependent job, with time and memory per task estimated from the scenes' cost.

use anyhow::Context;
use pdamp::sweep::continuation::check_shards;
use pdamp::sweep::cost::sweep_cost_of;
use pdamp::sweep::slurm::{submit_script, SlurmJob};
use std::path::PathBuf;

/// Arguments of `pdamp slurm`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The sweep (as `pdamp sweep`; --out must be on a file system every node sees).
    #[command(flatten)]
    pub def: super::sweep::SweepDef,
    /// Continuation sweep (as `pdamp sweep`): the flags are passed to every shard task, the
    /// shards are contiguous ranges of --block blocks (N ≤ the number of blocks), and the
    /// merge job reads the settings from the shards' sweep.json.
    #[command(flatten)]
    pub cont: super::sweep::ContinuationArgs,
    /// Number of shards N: job-array tasks 0 … N−1.
    #[arg(long)]
    pub shards: usize,
    /// Most tasks running at once (`--array=0-(N-1)%P`).
    #[arg(long)]
    pub parallel: Option<usize>,
    /// CPUs per task (the threads of each shard).
    #[arg(long, default_value_t = 1)]
    pub cpus_per_task: usize,
    /// Safety factor on the estimated time per task.
    #[arg(long, default_value_t = 2.0)]
    pub time_factor: f64,
    /// Slurm partition.
    #[arg(long)]
    pub partition: Option<String>,
    /// Slurm account.
    #[arg(long)]
    pub account: Option<String>,
    /// Job name (default: pdamp-sweep).
    #[arg(long, default_value = "pdamp-sweep")]
    pub job_name: String,
    /// The pdamp executable on the nodes (default: this one).
    #[arg(long)]
    pub pdamp: Option<PathBuf>,
    /// Write the script to this file (default: standard output).
    #[arg(long)]
    pub script: Option<PathBuf>,
}

/// Run `pdamp slurm`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.shards == 0 {
        anyhow::bail!("--shards 0: a job array needs at least one shard (--shards 1 or more)");
    }
    if args.time_factor.is_nan() || args.time_factor < 1.0 {
        anyhow::bail!("--time-factor {}: must be ≥ 1", args.time_factor);
    }
    let spec = args.def.spec()?;
    let continuation = args.cont.settings()?;
    if let Some(c) = &continuation {
        check_shards(&spec, c, args.shards)?;
    }
    let cost = sweep_cost_of(&spec, continuation.as_ref(), args.shards)?;
    let abs = |p: &PathBuf| std::path::absolute(p).unwrap_or_else(|_| p.clone());
    let pdamp = match &args.pdamp {
        Some(p) => p.clone(),
        None => std::env::current_exe().context("cannot locate this pdamp executable")?,
    };
    let out = abs(&args.def.out).display().to_string();
    let mut sweep_args = vec![abs(&args.def.scene).display().to_string()];
    for s in &args.def.set {
        sweep_args.extend(["--set".to_string(), s.clone()]);
    }
    for v in &args.def.vary {
        sweep_args.extend(["--vary".to_string(), v.clone()]);
    }
    if args.def.no_analysis {
        sweep_args.push("--no-analysis".into());
    }
    sweep_args.extend(args.cont.sweep_args());
    // each task asks for its own estimated time (the check of `pdamp sweep`)
    let limit = crate::cli::runtime::parse_duration(crate::cli::runtime::DEFAULT_MAX_RUNTIME)
        .unwrap_or(f64::INFINITY);
    if cost.max_shard_cpu_s > limit {
        let hours = (cost.max_shard_cpu_s * 1.1 / 3600.0).ceil();
        sweep_args.extend(["--max-runtime".to_string(), format!("{hours:.0}h")]);
    }
    sweep_args.extend(["--out".to_string(), out.clone()]);
    let job = SlurmJob {
        pdamp: pdamp.display().to_string(),
        sweep_args,
        out,
        shards: args.shards,
        parallel: args.parallel,
        cpus_per_task: args.cpus_per_task,
        time_factor: args.time_factor,
        name: args.job_name.clone(),
        partition: args.partition.clone(),
        account: args.account.clone(),
        continuation,
    };
    let script = submit_script(&job, &cost);
    match &args.script {
        Some(path) => {
            pdamp::io::atomic_write(path, script.as_bytes())?;
            tracing::info!(
                "{} points, estimated {:.3} core-hours ({:.0} CPU-s in the largest of {} shards); \
                 submit with: bash {}",
                cost.points,
                cost.total_cpu_s / 3600.0,
                cost.max_shard_cpu_s,
                args.shards,
                path.display()
            );
        }
        None => print!("{script}"),
    }
    Ok(())
}
