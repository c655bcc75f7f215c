//! `pdamp simulate SCENE --out DIR [--set key=value …]`: run one scene, write
//! `DIR/series.csv`, `DIR/summary.json`, `DIR/strobe.csv` and the resolved `DIR/scene.toml`;
//! with `run.replica` (DEM two-replica test) also `DIR/replica.csv` (layout and writer:
//! [`pdamp::io::run_dir`]).

use crate::cli::progress::ProgressObserver;
use anyhow::Context;
use pdamp::io::RunDir;
use pdamp::observe::Tee;
use pdamp::scene::{parse_assignment, Scene, SceneSource};
use pdamp::sweep::run::run_resolved;
use std::path::{Path, PathBuf};

/// Arguments of `pdamp simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML; see data/scenes/*.toml for documented examples).
    pub scene: PathBuf,
    /// Output directory (created if missing): series.csv, summary.json, strobe.csv, scene.toml.
    #[arg(long)]
    pub out: PathBuf,
    /// Override a scene key, dotted: `--set excitation.frequency=12 --set damper.gap=inf`.
    /// Values are TOML (numbers, inf, true, "text"); bare words are strings. Repeatable.
    /// `run.periods` replaces `run.duration` (and vice versa), `primary.damping` replaces
    /// `primary.damping_ratio`; `damper.kind=none` drops the damper's keys; an empty value
    /// (`--set run.dt=`) removes a key.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Skip the nonlinear analysis of the steady-state grain series (faster; for the DEM also
    /// the two-replica test that the verdict uses, which costs the analysis window once more).
    #[arg(long)]
    pub no_analysis: bool,
    /// Largest output (bytes) the run may write; a larger estimate is refused before the
    /// run starts (e.g. `--max-output 2e10` for 20 GB).
    #[arg(long, value_name = "BYTES", default_value_t = pdamp::setup::plan::DEFAULT_MAX_OUTPUT_BYTES)]
    pub max_output: f64,
    /// Longest run (on one core, as the plan estimates it) that starts without being asked
    /// for; a longer estimate is refused before the run starts (e.g. `--max-runtime 3d`).
    /// Units s, min, h, d.
    #[arg(long, value_name = "DURATION", default_value = crate::cli::runtime::DEFAULT_MAX_RUNTIME, value_parser = crate::cli::runtime::parse_duration)]
    pub max_runtime: f64,
}

/// The plan of a resolved scene's full-series run (what `simulate` writes), refused above
/// `max_output` bytes: the one check `simulate` and `check-scene` share.
pub(crate) fn plan_full_run(
    resolved: &pdamp::setup::Resolved,
    max_output: f64,
) -> anyhow::Result<pdamp::setup::RunPlan> {
    let plan = pdamp::setup::RunPlan::new(resolved, &pdamp::setup::full_series(&resolved.scene))?;
    plan.check_output(max_output)?;
    Ok(plan)
}

/// Load a scene file and apply `--set` overrides.
/// A scene file, its `--set` overrides and the validated scene they give.
pub(crate) type LoadedScene = (SceneSource, Vec<(String, toml::Value)>, Scene);

pub(crate) fn load_scene(path: &Path, set: &[String]) -> anyhow::Result<LoadedScene> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read scene file {}", path.display()))?;
    let src = SceneSource::parse(&text).with_context(|| format!("in {}", path.display()))?;
    let overrides = set
        .iter()
        .map(|a| parse_assignment(a))
        .collect::<Result<Vec<_>, _>>()?;
    let scene = src
        .scene(&overrides)
        .with_context(|| format!("in {}", path.display()))?;
    Ok((src, overrides, scene))
}

/// Runs the resolved scene with `series.csv` recorded into `dir`.
fn run_into(
    dir: &RunDir,
    resolved: &pdamp::setup::Resolved,
    scene: &Scene,
    analysis: bool,
) -> anyhow::Result<pdamp::model::RunSummary> {
    let mut csv = dir.series_recorder()?;
    let mut bar = ProgressObserver::new(scene.duration_s(), "simulate");
    let mut tee = Tee {
        observers: vec![&mut csv, &mut bar],
    };
    Ok(run_resolved(
        resolved,
        &mut tee,
        &pdamp::setup::full_series(scene),
        analysis,
    )?)
}

/// Run `pdamp simulate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, _, scene) = load_scene(&args.scene, &args.set)?;
    // `kind = "auto"`: say which model and settings were chosen, and why (stderr + summary).
    let mut resolved = scene.resolve()?;
    resolved.place_outputs_in(&args.out);
    let plan = plan_full_run(&resolved, args.max_output)?;
    tracing::info!("plan: {}", plan.describe());
    crate::cli::runtime::check(plan.run_time_s, args.max_runtime, "the run")?;
    let auto_choice = resolved.auto.as_ref().map(|c| {
        let why = pdamp::choice::auto::describe(c);
        tracing::info!("{why}");
        why
    });
    let dir = RunDir::create(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let summary = match run_into(&dir, &resolved, &scene, !args.no_analysis) {
        Ok(s) => s,
        Err(e) => {
            // the directory stays marked incomplete, with the reason in its marker
            let _ = dir.mark_failed(&format!("{e:#}"));
            return Err(e);
        }
    };
    // the run's warnings (the library returns them; printed as `warning: …`)
    for w in &summary.warnings {
        tracing::warn!("{w}");
    }
    dir.write_outputs(&scene, &summary, auto_choice)?;
    println!(
        "{}: f = {} Hz, amplitude Z = {:.6e} m{}, impacts/cycle = {}, energy balance residual = {}",
        summary.model,
        pdamp::observe::fmt_num(summary.frequency_hz),
        summary.amplitude_m,
        // (a free decay has no steady amplitude of the primary alone)
        summary
            .reference_amplitude_m
            .filter(|_| summary.decay.is_none())
            .map(|r| format!(" (primary alone: {r:.6e} m)"))
            .unwrap_or_default(),
        if summary.impacts_per_cycle.is_finite() {
            format!("{:.4}", summary.impacts_per_cycle)
        } else {
            "n/a (not counted for DEM)".into()
        },
        summary
            .energy_balance_relative_error
            .map(|e| format!("{e:.2e}"))
            .unwrap_or_else(|| "n/a (kinematic box)".into()),
    );
    if let Some(d) = &summary.decay {
        println!(
            "decay: {} cycles from amplitude {:.4e} m, damping ratio ζ = {:.4e} (first cycle) … \
             {:.4e} (last), mean {:.4e}; decay.csv",
            d.cycle_count,
            d.initial_amplitude_m,
            d.first_damping_ratio,
            d.last_damping_ratio,
            d.mean_damping_ratio
        );
    }
    if let Some(r) = &summary.replica {
        println!(
            "replica (δ0 = {:e} m, {} strobes): {}",
            r.delta0_m,
            r.strobes,
            r.describe()
        );
    }
    println!("wrote {}", args.out.display());
    Ok(())
}
