//! `pdamp sweep SCENE --vary KEY=START:STOP:STEP [--vary …] --out DIR`: parallel, resumable
//! parameter sweep writing `DIR/sweep.csv`, `DIR/strobe.csv` and `DIR/points/<i>.json`.

use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use pdamp::sweep::{run_sweep, SweepSpec, Vary};
use std::path::PathBuf;

/// Arguments of `pdamp sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Varied key: `KEY=START:STOP:STEP` (STOP included when on the grid) or `KEY=v1,v2,…`,
    /// e.g. `--vary excitation.frequency=0.5:30:0.1`. Several `--vary` make a grid (first
    /// varies slowest).
    #[arg(long, value_name = "KEY=RANGE", required = true)]
    pub vary: Vec<String>,
    /// Output directory. Rerunning the same sweep into it skips the finished points.
    #[arg(long)]
    pub out: PathBuf,
    /// Override a scene key for every point, e.g. `--set run.periods=2000`. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Skip the nonlinear analysis of each point (faster; regime columns stay empty).
    #[arg(long)]
    pub no_analysis: bool,
}

/// Run `pdamp sweep`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (base, set, _) = super::simulate::load_scene(&args.scene, &args.set)?;
    let varies = args
        .vary
        .iter()
        .map(|v| Vary::parse(v))
        .collect::<Result<Vec<_>, _>>()?;
    let spec = SweepSpec {
        base,
        set,
        varies,
        analyze: !args.no_analysis,
    };
    let n: usize = spec.varies.iter().map(|v| v.values.len()).product();
    let bar = ProgressBar::with_draw_target(Some(n as u64), crate::cli::progress::draw_target());
    bar.set_style(
        ProgressStyle::with_template(
            "sweep [{elapsed_precise}] {wide_bar} {pos}/{len} points (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let started = std::time::Instant::now();
    let report = run_sweep(&spec, &args.out, &|done| bar.set_position(done as u64))
        .with_context(|| format!("sweep of {}", args.scene.display()))?;
    bar.finish_and_clear();
    println!(
        "{} points: {} computed, {} already done, {} failed in {:.2} s; wrote {}",
        report.points,
        report.computed,
        report.skipped,
        report.failed.len(),
        started.elapsed().as_secs_f64(),
        args.out.join("sweep.csv").display()
    );
    if !report.failed.is_empty() {
        for (i, why) in report.failed.iter().take(10) {
            eprintln!("point {i}: {why}");
        }
        anyhow::bail!(
            "{} sweep points failed (rerun to retry them)",
            report.failed.len()
        );
    }
    Ok(())
}
