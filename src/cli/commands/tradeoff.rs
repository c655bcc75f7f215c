//! `pdamp tradeoff [REFERENCE] [--compute] [--only IDS] [--out DIR] [--data DIR]`: the
//! speed–accuracy study from stored points. Reads every rung's points (wherever a sweep
//! stored them under `--data`), measures them against the reference, and writes
//! `tradeoff.csv`, `tradeoff_settings.csv` and the Pareto figures; `--compute` first runs the
//! missing points (resumable sweeps, one folder per rung).

use std::path::{Path, PathBuf};

use anyhow::Context;

use pdamp::choice::Axis;
use pdamp::plot::pareto::{ParetoFigure, ParetoPoint};
use pdamp::plot::{render, FigureOptions};
use pdamp::sweep::Catalog;
use pdamp::tradeoff::compute::compute_missing;
use pdamp::tradeoff::plan::SCENE_B_FREQUENCIES_HZ;
use pdamp::tradeoff::study::{study, SettingSummary, Study};
use pdamp::tradeoff::table::{rows_csv, settings_csv};
use pdamp::tradeoff::StudyPlan;

/// Arguments of `pdamp tradeoff`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  pdamp tradeoff                                   # tables and figures from the stored points
  pdamp tradeoff --compute --only dt-50,soften-1000  # compute two rungs' missing points first
  pdamp tradeoff --list                            # the rungs and how many points each has")]
pub struct Args {
    /// The reference scene (a DEM damper on a `[primary]`); every rung is one change to it.
    #[arg(default_value = "data/scenes/thesis_b_reference.toml")]
    pub reference: PathBuf,
    /// Folder searched for stored sweep points (any sweep of a rung's scene counts).
    #[arg(long, default_value = "figures/data")]
    pub data: PathBuf,
    /// Output folder: tradeoff.csv, tradeoff_settings.csv, TRADEOFF.md, tradeoff_*.png.
    #[arg(long, default_value = "figures")]
    pub out: PathBuf,
    /// Frequencies (Hz), comma-separated, in computing order. Default: 12–18 Hz every 0.5 Hz,
    /// the peak first.
    #[arg(long, value_delimiter = ',', value_name = "HZ")]
    pub frequencies: Vec<f64>,
    /// Compute the missing points first (resumable: an interrupted run continues where it
    /// stopped). Without it nothing is simulated.
    #[arg(long)]
    pub compute: bool,
    /// With --compute: only these rungs (identifiers as in --list), comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "IDS")]
    pub only: Vec<String>,
    /// List the rungs with their stored points and stop.
    #[arg(long)]
    pub list: bool,
}

/// Run `pdamp tradeoff`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let freqs = if args.frequencies.is_empty() {
        SCENE_B_FREQUENCIES_HZ.to_vec()
    } else {
        args.frequencies.clone()
    };
    let mut catalog = Catalog::scan(&args.data)?;
    let plan = StudyPlan::new(&args.reference, &freqs, &args.data, &catalog)?;
    if let Some(bad) = args
        .only
        .iter()
        .find(|id| !plan.rungs.iter().any(|r| &r.id == *id))
    {
        let ids: Vec<&str> = plan.rungs.iter().map(|r| r.id.as_str()).collect();
        return Err(pdamp::error::SceneError::invalid(
            "--only",
            bad,
            format!("not a rung; choose among {}", ids.join(", ")),
        )
        .into());
    }
    if args.compute {
        for rung in plan
            .rungs
            .iter()
            .filter(|r| args.only.is_empty() || args.only.contains(&r.id))
        {
            let c = compute_missing(&plan, rung, &catalog, &|n| {
                tracing::info!("{}: {n} point(s) done", rung.id)
            })?;
            if let (Some(dir), Some(rep)) = (&c.dir, &c.report) {
                eprintln!(
                    "{}: {} computed, {} failed, in {}",
                    rung.id,
                    rep.computed,
                    rep.failed.len(),
                    dir.display()
                );
            }
            catalog = Catalog::scan(&args.data)?;
        }
    }
    let s = study(&plan, &catalog)?;
    if args.list {
        for x in &s.settings {
            println!(
                "{:<22} {:<15} {:>2}/{:<2} {}  {}",
                x.setting,
                x.axis.as_str(),
                x.frequencies_ok,
                x.frequencies,
                x.status,
                x.message
            );
        }
        return Ok(());
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let header = header(&plan, &args);
    let write = |name: &str, text: String| -> anyhow::Result<()> {
        pdamp::io::atomic_write(&args.out.join(name), text.as_bytes())?;
        Ok(())
    };
    write("tradeoff.csv", rows_csv(&s, &header))?;
    write("tradeoff_settings.csv", settings_csv(&s, &header))?;
    let reference = plan.reference.scene(&[])?;
    write(
        "TRADEOFF.md",
        pdamp::tradeoff::report::markdown(&s, &reference, &header),
    )?;
    plot_all(&s, &args.out)?;
    for x in &s.settings {
        println!(
            "{:<22} {:>2}/{:<2} compared {:>2}  cost/pt {:>9}  Z err {:>8}  f_res err {:>8}  \
             verdicts {}/{}",
            x.setting,
            x.frequencies_ok,
            x.frequencies,
            x.frequencies_compared,
            x.core_seconds_per_point
                .map_or("n/a".into(), |c| format!("{c:.1} s")),
            pct(x.amplitude_max_rel_error),
            pct(x.resonance_frequency_rel_error),
            x.regime_matches,
            x.regime_compared
        );
    }
    println!("wrote {}", args.out.display());
    Ok(())
}

fn header(plan: &StudyPlan, args: &Args) -> Vec<String> {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    vec![
        "pdamp tradeoff: speed against accuracy from stored sweep points, one row per setting \
         and frequency (tradeoff.csv) or per setting (tradeoff_settings.csv)"
            .into(),
        format!("command: pdamp {}", argv.join(" ")),
        format!(
            "date: {}",
            pdamp::io::clock::utc_date(pdamp::io::clock::unix_now_s())
        ),
        format!("commit: {}", pdamp::io::provenance::git_commit()),
        format!("reference: {}", plan.reference_path.display()),
        format!(
            "points: every stored sweep under {} whose scene is the setting's",
            args.data.display()
        ),
        format!(
            "frequencies_hz: {}",
            plan.frequencies_hz
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        ),
        "errors: |x − x_ref| / x_ref where both have a point; resonance from the parabola \
         through the FRF's top three points; M_ef, C_ef fitted with (2.1.21) to the compared \
         points; dissipation = energy the grains dissipate per cycle"
            .into(),
        "core_seconds: DEM — settling and driven stepping of the bed (particle-steps ÷ the \
         measured particle-steps per CPU second; the replica's second bed and the analysis not \
         counted); one particle — the whole point's CPU time. Machine- and load-dependent."
            .into(),
        "empty cell: not applicable or not measured; status says why a point is missing".into(),
    ]
}

/// The checkout's commit (`git describe --always --dirty`), or why it is unknown.
fn pct(e: Option<f64>) -> String {
    e.map_or("n/a".into(), |e| format!("{:.2} %", 100.0 * e))
}

/// One Pareto plot: the file, the column of `tradeoff_settings.csv` it draws, the same value
/// of a setting, and the y-axis label.
pub(crate) struct ParetoPlot {
    pub file: &'static str,
    pub column: &'static str,
    pub get: fn(&SettingSummary) -> Option<f64>,
    pub label: &'static str,
}

/// The Pareto plots: Z, resonance-frequency, dissipation and verdict errors against cost.
pub(crate) const PARETO_FIGURES: [ParetoPlot; 4] = [
    ParetoPlot {
        file: "tradeoff_amplitude.png",
        column: "amplitude_max_rel_error",
        get: |s| s.amplitude_max_rel_error,
        label: "largest relative error of Z (–)",
    },
    ParetoPlot {
        file: "tradeoff_resonance.png",
        column: "resonance_frequency_rel_error",
        get: |s| s.resonance_frequency_rel_error,
        label: "relative error of the resonance frequency (–)",
    },
    ParetoPlot {
        file: "tradeoff_dissipation.png",
        column: "dissipation_max_rel_error",
        get: |s| s.dissipation_max_rel_error,
        label: "largest relative error of the grains' dissipation per cycle (–)",
    },
    ParetoPlot {
        file: "tradeoff_regime.png",
        column: "regime_disagreement",
        get: |s| s.regime_disagreement(),
        label: "share of verdicts unlike the reference's (–)",
    },
];

/// One setting as the Pareto figures see it.
pub(crate) struct ParetoRow {
    /// Label (`setting`).
    pub label: String,
    /// Knob (`axis`); `reference` for the reference row.
    pub group: String,
    /// CPU seconds per point.
    pub core_seconds: f64,
    /// The error drawn, if measured.
    pub error: Option<f64>,
}

/// The Pareto figure of `rows` (the reference row gives the dashed cost line; settings
/// without a positive finite cost or a finite error are left out), `None` when no setting is
/// left.
pub(crate) fn pareto_figure(
    rows: &[ParetoRow],
    y_label: &str,
    title: String,
) -> Option<ParetoFigure> {
    let reference = rows
        .iter()
        .find(|r| r.group == Axis::Reference.as_str())
        .map(|r| r.core_seconds)
        .filter(|c| c.is_finite() && *c > 0.0);
    let kept: Vec<(&ParetoRow, f64)> = rows
        .iter()
        .filter(|r| {
            r.group != Axis::Reference.as_str()
                && r.core_seconds > 0.0
                && r.core_seconds.is_finite()
        })
        .filter_map(|r| r.error.filter(|e| e.is_finite()).map(|e| (r, e)))
        .collect();
    if kept.is_empty() {
        return None;
    }
    let front = pdamp::tradeoff::pareto::pareto_front(
        &kept
            .iter()
            .map(|(r, e)| (r.core_seconds, *e))
            .collect::<Vec<_>>(),
    );
    let points = kept
        .iter()
        .zip(front)
        .map(|((r, e), f)| ParetoPoint {
            label: r.label.clone(),
            group: r.group.clone(),
            core_seconds: r.core_seconds,
            error: *e,
            on_front: f,
        })
        .collect();
    Some(ParetoFigure {
        points,
        y_label: y_label.into(),
        error_floor: 1e-4,
        reference_core_seconds: reference,
        title,
    })
}

/// Size of the Pareto figures (px).
const PARETO_SIZE: (u32, u32) = (1400, 1000);

/// Draws the Pareto plots of a study into `out` (a plot with no measured setting is left out
/// and an older file of that name removed, so that no stale figure remains).
fn plot_all(study: &Study, out: &Path) -> anyhow::Result<()> {
    for plot in &PARETO_FIGURES {
        let rows: Vec<ParetoRow> = study
            .settings
            .iter()
            .map(|s| ParetoRow {
                label: s.label.clone(),
                group: s.axis.as_str().into(),
                core_seconds: s.core_seconds_per_point.unwrap_or(f64::NAN),
                error: (plot.get)(s),
            })
            .collect();
        let path = out.join(plot.file);
        let title = "Speed against accuracy (scene B reference, 12–18 Hz)".to_string();
        let Some(fig) = pareto_figure(&rows, plot.label, title) else {
            let _ = std::fs::remove_file(&path);
            continue;
        };
        let opts = FigureOptions {
            width: PARETO_SIZE.0,
            height: PARETO_SIZE.1,
            title: None,
        };
        render(&fig, &path, &opts).with_context(|| format!("drawing {}", plot.file))?;
    }
    Ok(())
}
