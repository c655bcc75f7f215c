//! `pdamp tradeoff SCENE [--out DIR] [--quick]`: run each cheaper setting of a DEM scene
//! against the most accurate affordable reference at three frequencies (below, at and above
//! resonance) and write `tradeoff.csv`, `tradeoff_settings.csv` and Pareto plots (error versus
//! wall time).

use std::path::{Path, PathBuf};

use anyhow::Context;

use pdamp::plot::pareto::{ParetoFigure, ParetoPoint};
use pdamp::plot::{render, FigureOptions};
use pdamp::scene::Damper;
use pdamp::tradeoff::measure::Rig;
use pdamp::tradeoff::study::{run_study, Study, StudyOptions};
use pdamp::tradeoff::table::{runs_csv, settings_csv};
use pdamp::tradeoff::LadderOptions;

/// Arguments of `pdamp tradeoff`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file with a DEM damper (`kind = "dem"` or `"auto"`) and a `[primary]`; its
    /// excitation frequency is replaced by the study's frequencies.
    pub scene: PathBuf,
    /// Output directory (created): tradeoff.csv (one row per run), tradeoff_settings.csv
    /// (one row per setting, with provenance header), tradeoff_*.png Pareto plots.
    #[arg(long, default_value = "tradeoff_out")]
    pub out: PathBuf,
    /// Override a scene key, dotted (as in `simulate`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Quick study: no setting costlier than the reference (no real steel, no t_s/200, no
    /// larger N) and 0.75 s runs instead of 1.5 s.
    #[arg(long)]
    pub quick: bool,
    /// Frequencies (Hz), comma-separated. Default: 0.7, 1 and 1.3 × √(K/(M + m_p))/2π.
    #[arg(long, value_delimiter = ',', value_name = "HZ")]
    pub frequencies: Vec<f64>,
    /// Drive duration of every run (s). Default 1.5 (0.75 with --quick).
    #[arg(long, value_name = "S")]
    pub duration: Option<f64>,
    /// Young's-modulus divisor of the reference (–): the "most accurate affordable" setting.
    /// Default 100 (real steel, divisor 1, costs ~6× more and is measured as a rung).
    #[arg(long, default_value_t = 100.0, value_name = "FACTOR")]
    pub reference_softening: f64,
    /// Time step of the reference as a fraction of the contact duration (–). Default 0.01.
    #[arg(long, default_value_t = 0.01, value_name = "FRACTION")]
    pub reference_dt_fraction: f64,
    /// Worker threads; each run is single-threaded so its wall time is fair. Default: all
    /// cores (RAYON_NUM_THREADS).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Run `pdamp tradeoff`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, _, scene) = super::simulate::load_scene(&args.scene, &args.set)?;
    let params = match &scene.damper {
        Damper::Dem(p) | Damper::Auto(p) => p.clone(),
        other => anyhow::bail!(
            "{}: damper.kind = \"{}\": the trade-off study needs a DEM scene (kind = \"dem\" or \"auto\"), \
             e.g. data/scenes/thesis_b.toml",
            args.scene.display(),
            other.kind()
        ),
    };
    let rig = Rig::of_scene(&scene)?;
    let opts = StudyOptions {
        ladder: LadderOptions {
            reference_softening: args.reference_softening,
            reference_dt_fraction: args.reference_dt_fraction,
            duration_s: args.duration.unwrap_or(if args.quick { 0.75 } else { 1.5 }),
            steady_fraction: 0.5,
            quick: args.quick,
        },
        frequencies_hz: args.frequencies.clone(),
        threads: args.threads,
        ..StudyOptions::default()
    };
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let study = run_study(&params, &rig, &opts, &|line| tracing::info!("{line}"))?;
    let header = vec![
        "pdamp tradeoff: speed against accuracy, one row per setting (errors against the reference row)".to_string(),
        format!("generator: pdamp {} `pdamp tradeoff {}`", env!("CARGO_PKG_VERSION"), std::env::args().skip(2).collect::<Vec<_>>().join(" ")),
        format!("date: {}", pdamp::io::clock::utc_date(pdamp::io::clock::unix_now_s())),
        format!("scene: {}", args.scene.display()),
        format!("reference_softening = {}", opts.ladder.reference_softening),
        format!("reference_dt_fraction = {}", opts.ladder.reference_dt_fraction),
        format!("duration_s = {}", opts.ladder.duration_s),
        "wall_time_s: driven run only (bed building and settling excluded; see total_wall_time_s in tradeoff.csv), measured inside each single-threaded run, summed over the frequencies; machine- and load-dependent".into(),
        "errors: largest over the frequencies of |x - x_ref| / x_ref; M_ef, C_ef fitted with (2.1.21) to the 3 points".into(),
    ];
    let write = |name: &str, text: String| -> anyhow::Result<()> {
        pdamp::io::atomic_write(&args.out.join(name), text.as_bytes())?;
        Ok(())
    };
    write("tradeoff.csv", runs_csv(&study))?;
    write("tradeoff_settings.csv", settings_csv(&study, &header))?;
    plot_all(&study, &args.out)?;
    for s in &study.settings {
        println!(
            "{:<16} {:<30} wall {:>8.2} s  speed-up {:>6.2}  Z err {:>9}  diss err {:>9}  C_ef err {:>9}  regimes {}/{}{}",
            s.axis.as_str(),
            s.setting,
            s.wall_time_s,
            s.speedup,
            pct(s.amplitude_max_rel_error),
            pct(s.dissipation_max_rel_error),
            pct(s.c_ef_rel_error),
            s.regime_matches,
            s.runs,
            if s.pareto_amplitude { "  (Pareto)" } else { "" }
        );
    }
    println!("wrote {}", args.out.display());
    Ok(())
}

fn pct(e: Option<f64>) -> String {
    e.map_or("n/a".into(), |e| format!("{:.2} %", 100.0 * e))
}

/// One Pareto plot: the file, the column of `tradeoff_settings.csv` it draws, the same value
/// of a measured setting, and the y-axis label.
pub(crate) struct ParetoPlot {
    pub file: &'static str,
    pub column: &'static str,
    pub get: fn(&pdamp::tradeoff::study::SettingRow) -> Option<f64>,
    pub label: &'static str,
}

/// The Pareto plots: Z, dissipation, C_ef and Lyapunov-exponent errors against wall time.
pub(crate) const PARETO_FIGURES: [ParetoPlot; 4] = [
    ParetoPlot {
        file: "tradeoff_amplitude.png",
        column: "amplitude_max_rel_error",
        get: |s| s.amplitude_max_rel_error,
        label: "largest relative error of Z (–)",
    },
    ParetoPlot {
        file: "tradeoff_dissipation.png",
        column: "dissipation_max_rel_error",
        get: |s| s.dissipation_max_rel_error,
        label: "largest relative error of the grains' dissipation per cycle (–)",
    },
    ParetoPlot {
        file: "tradeoff_effective.png",
        column: "c_ef_rel_error",
        get: |s| s.c_ef_rel_error,
        label: "relative error of C_ef (–)",
    },
    ParetoPlot {
        file: "tradeoff_lyapunov.png",
        column: "mle_max_abs_error_per_s",
        get: |s| s.mle_max_abs_error_per_s,
        label: "largest |λ − λ_ref| (1/s)",
    },
];

/// One setting as the Pareto figures see it.
pub(crate) struct ParetoRow {
    /// Label (`setting`).
    pub label: String,
    /// Knob (`axis`); `reference` for the reference row.
    pub group: String,
    /// Summed wall time (s).
    pub wall_time_s: f64,
    /// The error drawn, if measured.
    pub error: Option<f64>,
}

/// The Pareto figure of `rows` (the reference row gives the dashed wall-time line; settings
/// without a positive finite wall time or a finite error are left out), `None` when no
/// setting is left.
pub(crate) fn pareto_figure(
    rows: &[ParetoRow],
    y_label: &str,
    title: String,
) -> Option<ParetoFigure> {
    let reference = rows
        .iter()
        .find(|r| r.group == pdamp::tradeoff::Axis::Reference.as_str())
        .map(|r| r.wall_time_s);
    let kept: Vec<(&ParetoRow, f64)> = rows
        .iter()
        .filter(|r| {
            r.group != pdamp::tradeoff::Axis::Reference.as_str()
                && r.wall_time_s > 0.0
                && r.wall_time_s.is_finite()
        })
        .filter_map(|r| r.error.filter(|e| e.is_finite()).map(|e| (r, e)))
        .collect();
    if kept.is_empty() {
        return None;
    }
    let front = pdamp::tradeoff::pareto::pareto_front(
        &kept
            .iter()
            .map(|(r, e)| (r.wall_time_s, *e))
            .collect::<Vec<_>>(),
    );
    let points = kept
        .iter()
        .zip(front)
        .map(|((r, e), f)| ParetoPoint {
            label: r.label.clone(),
            group: r.group.clone(),
            wall_time_s: r.wall_time_s,
            error: *e,
            on_front: f,
        })
        .collect();
    Some(ParetoFigure {
        points,
        y_label: y_label.into(),
        error_floor: 1e-4,
        reference_wall_time_s: reference,
        title,
    })
}

/// Size of the Pareto figures (px).
const PARETO_SIZE: (u32, u32) = (1400, 1000);

/// Draws the Pareto plots of a study into `out`.
fn plot_all(study: &Study, out: &Path) -> anyhow::Result<()> {
    let title = format!(
        "Speed against accuracy, {} Hz",
        study
            .frequencies_hz
            .iter()
            .map(|f| format!("{f}"))
            .collect::<Vec<_>>()
            .join(" / ")
    );
    for plot in &PARETO_FIGURES {
        let rows: Vec<ParetoRow> = study
            .settings
            .iter()
            .map(|s| ParetoRow {
                label: s.setting.clone(),
                group: s.axis.as_str().into(),
                wall_time_s: s.wall_time_s,
                error: (plot.get)(s),
            })
            .collect();
        let Some(fig) = pareto_figure(&rows, plot.label, title.clone()) else {
            continue;
        };
        let opts = FigureOptions {
            width: PARETO_SIZE.0,
            height: PARETO_SIZE.1,
            title: None,
        };
        render(&fig, &out.join(plot.file), &opts)
            .with_context(|| format!("drawing {}", plot.file))?;
    }
    Ok(())
}
