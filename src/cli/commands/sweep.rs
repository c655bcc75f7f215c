//! `pdamp sweep SCENE --vary KEY=START:STOP:STEP [--vary …] --out DIR [--shard K/N]`:
//! parallel, resumable parameter sweep writing `DIR/points/<i>.json`, the stream log and, for
//! the whole sweep, `DIR/sweep.csv`, `DIR/strobe.csv` and `DIR/timings.csv` (a shard leaves
//! those to `pdamp merge`).

use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use pdamp::sweep::continuation::{hysteresis_values, shard_point_count};
use pdamp::sweep::{run_shard_with, Continuation, Direction, Shard, SweepSpec, Vary};
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
    #[arg(
        long,
        long_help = "Skip the nonlinear analysis of each point (faster; regime columns stay \
empty).\n\n\
For the DEM the analysis includes the two-replica test (run.replica, on by default with a \
verdict): a perturbed copy of the bed is stepped through the analysis window, which costs that \
window once more (+60 % for data/scenes/thesis_b_ch4.toml, whose last 60 % is analysed; \
run.replica = false leaves it out and the verdict then rests on the section and the data \
exponent).\n\n\
Sample grid of a point of the event-driven model (damper none or impact): without the \
analysis, the model is evaluated only at its events (impacts, sticking, detachment), at its \
segment ends (1/16 of the fastest time scale) and once per forcing period T over the analysis \
window (the stroboscopic rows of strobe.csv, t = kT, run.analysis_fraction); the amplitude \
comes from the exact extrema of z(t) between those points and the energies from the closed \
forms (Gauss-Legendre, exact to rounding), so no series is sampled at all. With the analysis, \
the grain series is also sampled every max(run.sample_interval, analysis window / \
run.analysis_max_samples) seconds over the analysis window (default at most 20000 samples)."
    )]
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
    /// Continuation settings.
    #[command(flatten)]
    pub cont: ContinuationArgs,
    /// Longest sweep (its points' summed cost on one core, as `pdamp slurm` estimates it; of
    /// the largest shard with --shard) that starts without being asked for; a longer estimate
    /// is refused before any point runs (e.g. `--max-runtime 3d`). Units s, min, h, d.
    #[arg(long, value_name = "DURATION", default_value = crate::cli::runtime::DEFAULT_MAX_RUNTIME, value_parser = crate::cli::runtime::parse_duration)]
    pub max_runtime: f64,
}

/// The continuation flags of `pdamp sweep` (and of `pdamp slurm`, which passes them on to its
/// shard tasks).
#[derive(Debug, clap::Args)]
pub struct ContinuationArgs {
    /// Continuation: run the one --vary key in order, each point starting from the previous
    /// point's final state (up: increasing, down: decreasing, both: up then down, with
    /// hysteresis.csv).
    #[arg(
        long,
        value_name = "up|down|both",
        long_help = "Continuation (bifurcation-diagram) sweep of one --vary key: the values run \
in order (up: increasing, down: decreasing, both: up then down), each point starting from the \
previous point's state at its last stroboscopic time t = nT (box position and velocity, \
particle height and velocity), so that a multistable system stays on the branch it is on. \
Damper none or impact only. Points 0…n−1 are the --vary values in the order given on the first \
branch; with both, points n…2n−1 are the down branch; sweep.csv and strobe.csv get a `branch` \
column. With both, DIR/hysteresis.csv lists per value the amplitude, impacts per cycle and \
regime of each branch, their relative amplitude difference |A_up − A_down| / max(A_up, A_down), \
and hysteresis = 1 where that difference, or the relative difference of the impacts per \
cycle, exceeds --hysteresis-tol and the branches are not both chaotic (a chaotic attractor's \
extent over a finite window scatters; with --no-analysis regimes are unknown and chaotic \
windows are marked too); the values marked are printed at the end.\n\n\
Sharding: --block B cuts each branch into blocks of B points; every block after the first \
starts --overlap W points earlier from the scene's initial state (warm-up, written to \
points/warmup/ and compared with the previous block's points in DIR/seams.csv, agree = 1 \
when within the tolerance and of the same regime), and --shard K/N runs a contiguous range of \
blocks. sweep.csv depends on B and W, never on N or the thread count.\n\n\
Example (scene B's impact damper at e = 0.8, 500 forcing periods a point):\n  \
pdamp sweep data/scenes/thesis_b_impact.toml --set damper.restitution=0.8 \\\n    \
--set run.periods=500 --vary excitation.frequency=12:14:0.05 --continuation both \\\n    \
--out out/hyst\n\
marks 13.1–13.3 Hz in out/hyst/hysteresis.csv: going up the orbit with 2 impacts per period \
persists, coming down the one with 3 (5–11 % larger amplitude)."
    )]
    pub continuation: Option<String>,
    /// Continuation: points per block along a branch (default: the whole branch); needed
    /// for --shard, which splits the blocks.
    #[arg(long, value_name = "B", requires = "continuation")]
    pub block: Option<usize>,
    /// Continuation: warm-up points run before each block after the first (< --block).
    #[arg(long, value_name = "W", requires = "continuation", default_value_t = pdamp::sweep::continuation::DEFAULT_OVERLAP)]
    pub overlap: usize,
    /// Continuation: relative amplitude difference of the up and down branches above which
    /// hysteresis.csv marks a value (also the agreement tolerance of seams.csv).
    #[arg(long, value_name = "TOL", requires = "continuation", default_value_t = pdamp::sweep::continuation::DEFAULT_TOLERANCE)]
    pub hysteresis_tol: f64,
}

impl ContinuationArgs {
    /// The continuation settings, `None` without --continuation.
    ///
    /// # Errors
    /// A --continuation other than up, down or both (naming the flag).
    pub fn settings(&self) -> anyhow::Result<Option<Continuation>> {
        let Some(d) = &self.continuation else {
            return Ok(None);
        };
        Ok(Some(Continuation {
            direction: Direction::parse(d)?,
            block: self.block,
            overlap: self.overlap,
            tolerance: self.hysteresis_tol,
        }))
    }

    /// The flags again as `pdamp sweep` arguments (empty without --continuation), each one
    /// shell word; the tolerance in Rust's shortest round-trip form (the same f64).
    pub fn sweep_args(&self) -> Vec<String> {
        let Some(d) = &self.continuation else {
            return Vec::new();
        };
        let mut a = vec!["--continuation".to_string(), d.trim().to_string()];
        if let Some(b) = self.block {
            a.extend(["--block".to_string(), b.to_string()]);
        }
        a.extend([
            "--overlap".to_string(),
            self.overlap.to_string(),
            "--hysteresis-tol".to_string(),
            self.hysteresis_tol.to_string(),
        ]);
        a
    }
}

/// Run `pdamp sweep`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let spec = args.def.spec()?;
    let shard = match &args.shard {
        Some(s) => Shard::parse(s)?,
        None => Shard::WHOLE,
    };
    let continuation = args.cont.settings()?;
    let cost = pdamp::sweep::cost::sweep_cost_of(&spec, continuation.as_ref(), shard.count)?;
    crate::cli::runtime::check(cost.max_shard_cpu_s, args.max_runtime, "the sweep")?;
    let n = pdamp::sweep::vary::grid_len(&spec.varies).unwrap_or(usize::MAX);
    let mine = match (&continuation, spec.varies.first()) {
        (Some(c), Some(v)) => shard_point_count(&v.values, c, shard),
        _ => shard.points(n).size_hint().0,
    };
    let bar = ProgressBar::with_draw_target(Some(mine as u64), crate::cli::progress::draw_target());
    bar.set_style(
        ProgressStyle::with_template(
            "sweep [{elapsed_precise}] {wide_bar} {pos}/{len} points (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let out = &args.def.out;
    let started = std::time::Instant::now();
    let report = run_shard_with(&spec, continuation.as_ref(), out, shard, &|done| {
        bar.set_position(done as u64)
    })
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
    if shard.is_whole() && continuation.is_some_and(|c| c.direction == Direction::Both) {
        let marked = hysteresis_values(out);
        let tol = args.cont.hysteresis_tol;
        if marked.is_empty() {
            println!("no hysteresis: the up and down branches agree within {tol} everywhere");
        } else {
            let list: Vec<String> = marked.iter().map(|v| v.to_string()).collect();
            println!(
                "hysteresis (branches differ by more than {tol} in amplitude or impacts per cycle) at \
                 {} values: {}; see {}",
                marked.len(),
                list.join(" "),
                out.join("hysteresis.csv").display()
            );
        }
    }
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
