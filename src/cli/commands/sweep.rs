//! `pdamp sweep SCENE --vary KEY=START:STOP:STEP [--vary …] --out DIR [--shard K/N]`:
//! parallel, resumable parameter sweep writing `DIR/points/<i>.json`, the stream log and, for
//! the whole sweep, `DIR/sweep.csv`, `DIR/strobe.csv` and `DIR/timings.csv` (a shard leaves
//! those to `pdamp merge`).

use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use pdamp::sweep::{run_shard, Shard, SweepSpec, Vary};
use std::path::PathBuf;

/// What to sweep (shared by `pdamp sweep` and `pdamp slurm`).
#[derive(Debug, clap::Args)]
pub struct SweepDef {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Varied key: `KEY=START:STOP:STEP` (STOP included when on the grid) or `KEY=v1,v2,…`,
    /// e.g. `--vary excitation.frequency=0.5:30:0.1`. Several `--vary` make a grid (first
    /// varies slowest).
    #[arg(long, value_name = "KEY=RANGE", required = true)]
    pub vary: Vec<String>,
    /// Output directory. Rerunning the same sweep into it skips the finished points; the
    /// shards of one sweep may share it.
    #[arg(long)]
    pub out: PathBuf,
    /// Override a scene key for every point, e.g. `--set run.periods=2000`. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Skip the nonlinear analysis of each point (faster; regime columns stay empty).
    #[arg(long)]
    pub no_analysis: bool,
}

impl SweepDef {
    /// The library's sweep request.
    pub fn spec(&self) -> anyhow::Result<SweepSpec> {
        let (base, set, _) = super::simulate::load_scene(&self.scene, &self.set)?;
        let varies = self
            .vary
            .iter()
            .map(|v| Vary::parse(v))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SweepSpec {
            base,
            set,
            varies,
            analyze: !self.no_analysis,
        })
    }
}

/// Arguments of `pdamp sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The sweep.
    #[command(flatten)]
    pub def: SweepDef,
    /// Compute only shard K of N (K = 0 … N−1; point i belongs to shard i mod N), e.g.
    /// `--shard $SLURM_ARRAY_TASK_ID/8`. Shards write points and their own stream log; once
    /// all are done, `pdamp merge DIR…` writes sweep.csv and strobe.csv.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
}

/// Run `pdamp sweep`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let spec = args.def.spec()?;
    let shard = match &args.shard {
        Some(s) => Shard::parse(s)?,
        None => Shard::WHOLE,
    };
    let n = pdamp::sweep::vary::grid_len(&spec.varies).unwrap_or(usize::MAX);
    let mine = shard.points(n).size_hint().0;
    let bar = ProgressBar::with_draw_target(Some(mine as u64), crate::cli::progress::draw_target());
    bar.set_style(
        ProgressStyle::with_template(
            "sweep [{elapsed_precise}] {wide_bar} {pos}/{len} points (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let out = &args.def.out;
    let started = std::time::Instant::now();
    let report = run_shard(&spec, out, shard, &|done| bar.set_position(done as u64))
        .with_context(|| format!("sweep of {}", args.def.scene.display()))?;
    bar.finish_and_clear();
    let wrote = if shard.is_whole() {
        format!("wrote {}", out.join("sweep.csv").display())
    } else {
        format!(
            "shard {shard}; once every shard is done: pdamp merge {}",
            out.display()
        )
    };
    println!(
        "{} points: {} computed, {} already done, {} failed in {:.2} s; {wrote}",
        report.points,
        report.computed,
        report.skipped,
        report.failed.len(),
        started.elapsed().as_secs_f64(),
    );
    if !report.failed.is_empty() {
        for (i, why) in &report.failed {
            tracing::error!("point {i}: {why}");
        }
        return Err(crate::cli::exit::PointsFailed {
            failed: report.failed.len(),
            points: report.points,
        }
        .into());
    }
    Ok(())
}
