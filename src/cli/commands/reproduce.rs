//! `pdamp reproduce [--smoke|--quick|--full] [--out out/figures]`: the whole figure set of SPEC §7
//! for scene B, headless, with `OUT/README.md` saying how each figure was made.

use anyhow::Context;
use pdamp::study::{reproduce, Mode, ReproduceOptions};
use std::path::PathBuf;

/// Arguments of `pdamp reproduce`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("mode").args(["smoke", "quick", "full"])))]
pub struct Args {
    /// Minutes on 2 cores (default): shorter runs, fewer points, softened DEM contacts; every
    /// reduction is listed in OUT/README.md next to its figure.
    #[arg(long)]
    pub quick: bool,
    /// The source's parameters unchanged (13.12 s per frequency, 0.1 Hz steps, real steel
    /// contacts): hours to days.
    #[arg(long)]
    pub full: bool,
    /// Seconds: the smallest runs that still draw every impact-model figure (tests, CI); no
    /// DEM figures.
    #[arg(long)]
    pub smoke: bool,
    /// Output directory: PNG + CSV per figure, README.md, sweeps under OUT/data/ (resumable:
    /// rerunning reuses finished points). The default is outside the repository's tracked
    /// files; the committed reference set in `figures/` is rewritten only when asked for
    /// with `--out figures`.
    #[arg(long, default_value = "out/figures")]
    pub out: PathBuf,
    /// Make only these figures (repeatable; e.g. `--only frf --only poincare`; a name also
    /// selects its variants: `poincare` → `poincare_f10`, …). A selection writes its own
    /// OUT/README.<names>.md and leaves the complete set's OUT/README.md alone. `ch4` selects
    /// the chapter-4 DEM study (`ch4_regime_frf`, `ch4_panel_f14.5`, …).
    #[arg(long, value_name = "FIGURE")]
    pub only: Vec<String>,
    /// Leave out the DEM figures (impact-model figures only).
    #[arg(long)]
    pub no_dem: bool,
    /// Check the chapter-4 verdicts at every frequency of its sweep: two more initial packings
    /// (`ch4_ensemble`: the verdicts of three starts, "split" where they differ), the runs
    /// continued to twice their length on the same trajectory (`ch4_run_length`), and the
    /// other shipped softened scene (thesis_b_soft.toml) at the same length (`ch4_checks`).
    /// About five times the chapter-4 study's own cost on top of it: two starts, a run twice
    /// as long, the other scene (the committed points under figures/data are reused with
    /// `--out figures`).
    #[arg(long)]
    pub ch4_checks: bool,
    /// Width of every figure (pixels).
    #[arg(long, default_value_t = 1024)]
    pub width: u32,
    /// Height of every figure (pixels).
    #[arg(long, default_value_t = 768)]
    pub height: u32,
}

/// Run `pdamp reproduce`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let mode = if args.full {
        Mode::Full
    } else if args.smoke {
        Mode::Smoke
    } else {
        Mode::Quick
    };
    let mut opts = ReproduceOptions::new(mode, &args.out);
    opts.skip_dem = args.no_dem;
    if args.ch4_checks {
        if let Some(c) = opts.settings.dem.as_mut().and_then(|d| d.chapter4.take()) {
            opts.settings.dem.as_mut().expect("checked").chapter4 = Some(c.with_checks());
        }
    }
    opts.only = args.only;
    opts.figure.width = args.width;
    opts.figure.height = args.height;
    let started = std::time::Instant::now();
    let progress = move |msg: &str| {
        tracing::info!("[{:7.1} s] {msg}", started.elapsed().as_secs_f64());
    };
    let readme = args.out.join(opts.readme_name());
    let report = reproduce(&opts, &progress)
        .with_context(|| format!("reproduce {} into {}", mode.flag(), args.out.display()))?;
    println!(
        "{} figures in {:.1} s; wrote {}",
        report.figures.len(),
        report.elapsed_s,
        readme.display()
    );
    Ok(())
}
