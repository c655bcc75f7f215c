//! `pdamp plot KIND INPUT... -o FILE.png|FILE.svg`: draw one figure kind of SPEC §7 from the CSV files
//! of the output contract (series.csv, sweep.csv, strobe.csv, fit-frf output) or plain series.
//!
//! This file holds the flags and the dispatch only: the table → figure adapters are the
//! library's [`pdamp::plot::from_table`] (one function per kind), which the flags fill in as a
//! [`TableFigureOptions`]. The `pareto` kind stays here: its figure is built by
//! `pdamp tradeoff` (`super::tradeoff`).

use std::path::{Path, PathBuf};

use anyhow::bail;

use crate::cli::commands::tisean_args::{edit_arg, Theiler};

use pdamp::analysis::recurrence::RecurrenceThreshold;
use pdamp::error::TableFigureError;
use pdamp::plot::from_table::{self, TableFigureOptions};
use pdamp::plot::table::Table;
use pdamp::plot::FigureOptions;

/// Figure kinds (SPEC §7) and the input each one reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Kind {
    /// Z(f) of one or more sweep.csv (`frequency_hz`, `amplitude_m`; one curve per file), with
    /// the (2.1.21) reference curves for M and M + m_p if --mass, --stiffness, --damping,
    /// --base-amplitude (and --particle-mass) are given.
    Frf,
    /// series.csv: floor/ceiling, grain band (`grain_zmin_m`..`grain_zmax_m` if present),
    /// `grain_z_m`, and `grain_force_n` on a second panel. --from-time/--to-time crop.
    BedMotion,
    /// Poincaré section: columns --x/--y (default `x`,`y`) of a CSV, or for strobe.csv the
    /// return map (z_k, z_{k+1}) of `grain_z_m` of sweep point --point.
    Poincare,
    /// Spectrum from columns `frequency_hz`, `power` (output of `pdamp spectrum`); --forcing-hz
    /// marks f and its harmonics.
    Spectrum,
    /// 2-D delay reconstruction (s_n, s_{n+τ}) of a series (CSV column --column, default
    /// `grain_z_m`, or 1-based column of a plain numeric file); --lag τ in samples.
    Reconstruction,
    /// strobe.csv: strobed `grain_z_m` versus --x (default `frequency_hz`).
    Bifurcation,
    /// sweep.csv: Z(f) with colour bands per `regime` (periods ≥ 2 written in their band);
    /// below it λ(f) from `model_mle_per_s` and `mle_per_s`, each with its `*_stderr_per_s`
    /// error bar (points without an exponent omitted).
    RegimeFrf,
    /// Output of `pdamp fit-frf` (CSV, grouped): M_ef and C_ef/C versus the group column (--x,
    /// default the first column) with error bars; --mass and --damping for the references.
    Effective,
    /// sweep.csv: every `energy_*_j_per_cycle` column versus --x (default `frequency_hz`).
    Energy,
    /// One sweep.csv per N (labels via --label): Z_res = max `amplitude_m` per value of --x
    /// (the damping parameter, e.g. `damper.gamma_n`).
    Resonance,
    /// sweep.csv with two varied keys --x and --y: cells coloured by `regime`, chaotic cells
    /// shaded by `model_mle_per_s` (else `mle_per_s`), periodic cells of `period` ≥ 2 darker and
    /// numbered where the number fits; unevenly spaced keys get one equal row per value.
    RegimeMap,
    /// Recurrence plot of a series (CSV column --column or 1-based column of a plain file):
    /// embedding --dim (default 1) and --lag (default 1), threshold --eps (data units) or
    /// --rate (default 0.05), --theiler; downsampled to --max-cells pixels per side (stated on
    /// the figure).
    Recurrence,
    /// Output of `pdamp d2` (columns m, eps, c, pairs, slope): local slopes versus ε (log
    /// axis) per m, with the automatic plateaus and D2 marked.
    D2,
    /// Kantz S(Δn) of a series (plain text or CSV, --column), one curve per m and ε, the fitted
    /// scaling region of each marked and the median slope (`pdamp lyap-k`'s exponent) in the
    /// caption; -m -M -d -r -R -# -s -n -t --tisean --r2-min as lyap-k, --dt for seconds.
    Kantz,
    /// Mutual information I(τ) of a series with its first minimum marked; -D largest lag
    /// (default 20), -b bins (default 16) as `pdamp mutual`, --dt for τ in seconds.
    Mutual,
    /// False nearest neighbours (%) versus m with the suggested dimension (≤ 1 %) marked;
    /// -M min,max (default 1,6), -d, -f ratio (default 10), -t, --tisean as `pdamp fnn`.
    Fnn,
    /// `tradeoff_settings.csv` of `pdamp tradeoff`: the error in column --y (default
    /// `amplitude_max_rel_error`; also `dissipation_max_rel_error`, `c_ef_rel_error`,
    /// `mle_max_abs_error_per_s`) against `wall_time_s`, log–log, one labelled marker per setting
    /// coloured by `axis`, the Pareto front as a staircase, the reference's wall time dashed.
    Pareto,
    /// Free decay: the equivalent damping ratio ζ of each cycle against its amplitude (log
    /// axis), from decay.csv (`amplitude_m`, `damping_ratio`), or from a run's series.csv or
    /// run folder (its decay.csv if there, else the envelope of the primary's `box_z_m`, or
    /// --column, between --from-time and --to-time). The plotted data goes to FILE.csv beside
    /// the figure.
    Decay,
}

/// Arguments of `pdamp plot`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  pdamp plot frf run_a/sweep.csv run_b/sweep.csv --label a --label b -o frf.png
  pdamp plot bed-motion run/series.csv --from-time 2 --to-time 3 -o bed.svg
  pdamp plot decay run/ -o run/damping.png   (ζ against amplitude of a free decay; \
run/decay.csv, else the envelope of box_z_m in run/series.csv)")]
pub struct Args {
    /// Figure kind.
    #[arg(value_enum)]
    pub kind: Kind,
    /// Input file(s): CSV with a header row (see the kind for the columns).
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output image: .png (raster) or .svg (vector), by the extension.
    #[arg(short, long, value_name = "FILE.png|FILE.svg")]
    pub output: PathBuf,
    /// Figure options (size, labels, columns, reference parameters).
    #[command(flatten)]
    pub opts: Box<PlotOptions>,
}

/// Options of `pdamp plot` shared by the figure kinds (boxed in [`Args`]).
#[derive(Debug, clap::Args)]
#[command(mut_args(edit_arg("theiler", |a| a
    .help(
        "Theiler window in samples for kantz and fnn (TISEAN -t; default τ, TISEAN 0) and for \
         recurrence (RR excludes |i − j| ≤ w; default 0)"
    )
    .help_heading("Estimators (kantz, mutual, fnn)"))))]
pub struct PlotOptions {
    /// Image width in pixels (default 1024).
    #[arg(long, default_value_t = 1024)]
    pub width: u32,
    /// Image height in pixels (default 768).
    #[arg(long, default_value_t = 768)]
    pub height: u32,
    /// Caption (default: a description of the figure kind).
    #[arg(long)]
    pub title: Option<String>,
    /// Legend label per input file, in order (default: the file's parent directory name).
    #[arg(long)]
    pub label: Vec<String>,
    /// x column (energy, bifurcation, resonance, regime-map, effective, poincare).
    #[arg(long)]
    pub x: Option<String>,
    /// y column (regime-map, poincare).
    #[arg(long)]
    pub y: Option<String>,
    /// Series column for reconstruction, kantz, mutual, fnn: a header name, or a 1-based index
    /// (default 1 for plain files); for decay the displacement column of series.csv (default
    /// `box_z_m`).
    #[arg(short = 'c', long)]
    pub column: Option<String>,
    /// Delay τ in samples: reconstruction (default: first zero of the autocorrelation), kantz
    /// and fnn (default 1, TISEAN -d).
    #[arg(short = 'd', long, visible_alias = "delay")]
    pub lag: Option<usize>,
    /// Sampling interval (s) of a plain series: τ in seconds (reconstruction, mutual), the
    /// Δn axis in seconds and the exponent per second (kantz).
    #[arg(long)]
    pub dt: Option<f64>,
    /// Use at most this many samples of the series (kantz, mutual, fnn; TISEAN -l).
    #[arg(short = 'l', long, help_heading = "Estimators (kantz, mutual, fnn)")]
    pub length: Option<usize>,
    /// Smallest embedding dimension (kantz: default 2, fnn: default 1; TISEAN -m).
    #[arg(
        short = 'm',
        long = "min-dim",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub m_min: Option<usize>,
    /// Largest embedding dimension, `M` or `min,max` (kantz: default 2, fnn: default 6;
    /// TISEAN's `1,M` of false_nearest reads the same).
    #[arg(
        short = 'M',
        long = "max-dim",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub m_max: Option<String>,
    /// Smallest radius ε in data units for kantz (TISEAN -r). Default: (max − min)/1000.
    #[arg(
        short = 'r',
        long = "eps-min",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub eps_min: Option<f64>,
    /// Largest radius ε in data units for kantz (TISEAN -R). Default: (max − min)/100.
    #[arg(
        short = 'R',
        long = "eps-max",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub eps_max: Option<f64>,
    /// Number of radii for kantz, log-spaced (TISEAN -#). Default 5.
    #[arg(
        short = '#',
        long = "eps-count",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub eps_count: Option<usize>,
    /// Largest Δn in samples for kantz (TISEAN -s). Default 50.
    #[arg(
        short = 's',
        long = "steps",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub steps: Option<usize>,
    /// Number of reference points for kantz (TISEAN -n). Default: all.
    #[arg(
        short = 'n',
        long = "references",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub references: Option<usize>,
    /// Theiler window -t (kantz, fnn, recurrence).
    #[command(flatten)]
    pub theiler: Theiler,
    /// TISEAN's definitions and defaults for kantz (RMS, Theiler 0) and fnn (-M 1,5 -f 2 -t 0).
    #[arg(long, help_heading = "Estimators (kantz, mutual, fnn)")]
    pub tisean: bool,
    /// Largest lag D in samples for mutual (TISEAN -D). Default 20.
    #[arg(
        short = 'D',
        long = "max-lag",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub max_lag: Option<usize>,
    /// Histogram bins per axis for mutual (TISEAN -b). Default 16.
    #[arg(
        short = 'b',
        long = "bins",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub bins: Option<usize>,
    /// Escape ratio f for fnn (TISEAN -f). Default 10 (TISEAN: 2).
    #[arg(
        short = 'f',
        long = "ratio",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub ratio: Option<f64>,
    /// Minimum R² of a linear scaling region for kantz (as lyap-k).
    #[arg(
        long,
        default_value_t = 0.99,
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub r2_min: f64,
    /// Forcing frequency f (Hz) marked on spectra.
    #[arg(long)]
    pub forcing_hz: Option<f64>,
    /// Sweep point (`point` column of strobe.csv) for the Poincaré return map (default: first).
    #[arg(long)]
    pub point: Option<i64>,
    /// Start of the time window (s) for bed-motion and decay (from series.csv).
    #[arg(long)]
    pub from_time: Option<f64>,
    /// End of the time window (s) for bed-motion and decay (from series.csv).
    #[arg(long)]
    pub to_time: Option<f64>,
    /// Primary mass M (kg): FRF reference curve; M reference line of `effective`.
    #[arg(long)]
    pub mass: Option<f64>,
    /// Grain mass m_p (kg): FRF reference curve for M + m_p.
    #[arg(long)]
    pub particle_mass: Option<f64>,
    /// Spring stiffness K (N/m) for the FRF reference curves.
    #[arg(long)]
    pub stiffness: Option<f64>,
    /// Primary damping C (N s/m): FRF references; `effective` then shows C_ef/C.
    #[arg(long)]
    pub damping: Option<f64>,
    /// Base amplitude U (m) for the FRF reference curves.
    #[arg(long)]
    pub base_amplitude: Option<f64>,
    /// `frf`: fit the effective mass and damping (2.1.21) to each input, K and U held at
    /// --stiffness and --base-amplitude (as `pdamp fit-frf`), and draw the fitted curves.
    #[arg(long)]
    pub fit: bool,
    /// Embedding dimension for recurrence (default 1).
    #[arg(long)]
    pub dim: Option<usize>,
    /// Recurrence threshold ε in data units (recurrence).
    #[arg(long, conflicts_with = "rate")]
    pub eps: Option<f64>,
    /// Recurrence rate in (0, 1) fixing ε (recurrence; default 0.05).
    #[arg(long)]
    pub rate: Option<f64>,
    /// Largest number of pixels per side of the recurrence plot (longer series are
    /// downsampled in blocks).
    #[arg(long, default_value_t = 600)]
    pub max_cells: usize,
}

/// Run `pdamp plot`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let o: &PlotOptions = &args.opts;
    let opts = FigureOptions {
        width: o.width,
        height: o.height,
        title: o.title.clone(),
    };
    let options = table_figure_options(o)?;
    if matches!(args.kind, Kind::Kantz | Kind::Mutual | Kind::Fnn) {
        return estimator(&args, &options, &opts);
    }
    if args.kind == Kind::Decay {
        return decay(&args, &options, &opts);
    }
    let tables = args
        .inputs
        .iter()
        .map(|p| Table::read(p))
        .collect::<Result<Vec<_>, _>>()?;
    if tables.len() > 1 && !matches!(args.kind, Kind::Frf | Kind::Resonance) {
        bail!("{:?} takes one input file, got {}", args.kind, tables.len());
    }
    let (out, first) = (&args.output, &tables[0]);
    let drawn = match args.kind {
        Kind::Frf => from_table::frf(&tables, &options, out, &opts),
        Kind::BedMotion => from_table::bed_motion(first, &options, out, &opts),
        Kind::Poincare => from_table::poincare(first, &options, out, &opts),
        Kind::Spectrum => from_table::spectrum(first, &options, out, &opts),
        Kind::Reconstruction => from_table::reconstruction(first, &options, out, &opts),
        Kind::Bifurcation => from_table::bifurcation(first, &options, out, &opts),
        Kind::RegimeFrf => from_table::regime_frf(first, out, &opts),
        Kind::Effective => from_table::effective(first, &options, out, &opts),
        Kind::Energy => from_table::energy(first, &options, out, &opts),
        Kind::Resonance => from_table::resonance(&tables, &options, out, &opts),
        Kind::RegimeMap => from_table::regime_map(first, &options, out, &opts),
        Kind::Recurrence => from_table::recurrence(first, &options, out, &opts),
        Kind::D2 => from_table::d2(first, out, &opts),
        Kind::Pareto => return pareto(first, o, out, &opts),
        Kind::Kantz | Kind::Mutual | Kind::Fnn => return estimator(&args, &options, &opts),
        Kind::Decay => return decay(&args, &options, &opts),
    };
    drawn.map_err(cli_error)?;
    wrote(out);
    Ok(())
}

/// The library's options from the flags.
fn table_figure_options(o: &PlotOptions) -> anyhow::Result<TableFigureOptions> {
    Ok(TableFigureOptions {
        labels: o.label.clone(),
        x: o.x.clone(),
        y: o.y.clone(),
        column: o.column.clone(),
        lag: o.lag,
        dt: o.dt,
        length: o.length,
        m_min: o.m_min,
        m_max: o.m_max.clone(),
        eps_min: o.eps_min,
        eps_max: o.eps_max,
        eps_count: o.eps_count,
        steps: o.steps,
        references: o.references,
        theiler: o.theiler.given(),
        tisean: o.tisean,
        max_lag: o.max_lag,
        bins: o.bins,
        ratio: o.ratio,
        r2_min: o.r2_min,
        forcing_hz: o.forcing_hz,
        point: o.point,
        from_time: o.from_time,
        to_time: o.to_time,
        mass: o.mass,
        particle_mass: o.particle_mass,
        stiffness: o.stiffness,
        damping: o.damping,
        base_amplitude: o.base_amplitude,
        fit: o.fit,
        dim: o.dim,
        threshold: recurrence_threshold(o)?,
        max_cells: o.max_cells,
    })
}

/// `--eps` / `--rate` (clap refuses both together) as `pdamp rqa` reads them.
fn recurrence_threshold(o: &PlotOptions) -> anyhow::Result<RecurrenceThreshold> {
    crate::cli::commands::rqa::threshold(o.eps, o.rate)
}

/// The estimator figures (kantz, mutual, fnn): read one series as the analysis verbs do,
/// run the estimator with the verb's defaults, report its result on stderr, draw.
fn estimator(
    args: &Args,
    options: &TableFigureOptions,
    opts: &FigureOptions,
) -> anyhow::Result<()> {
    if args.inputs.len() != 1 {
        bail!(
            "{:?} takes one series file, got {}",
            args.kind,
            args.inputs.len()
        );
    }
    let file = args.inputs[0].to_string_lossy().into_owned();
    let x = from_table::read_estimator_series(&file, options).map_err(cli_error)?;
    let out = &args.output;
    match args.kind {
        Kind::Kantz => from_table::kantz(&x, &file, options, out, opts),
        Kind::Mutual => from_table::mutual(&x, &file, options, out, opts),
        Kind::Fnn => from_table::fnn(&x, &file, options, out, opts),
        other => bail!("{other:?} is not an estimator figure"),
    }
    .map_err(cli_error)?;
    wrote(out);
    Ok(())
}

/// `decay`: one decay.csv, series.csv or run folder ([`from_table::decay_input`]).
fn decay(args: &Args, options: &TableFigureOptions, opts: &FigureOptions) -> anyhow::Result<()> {
    if args.inputs.len() != 1 {
        bail!(
            "decay takes one decay.csv, series.csv or run folder, got {} inputs",
            args.inputs.len()
        );
    }
    let table = Table::read(&from_table::decay_input(&args.inputs[0]))?;
    from_table::decay(&table, options, &args.output, opts).map_err(cli_error)?;
    wrote(&args.output);
    Ok(())
}

/// `pareto`: `tradeoff_settings.csv` drawn as `pdamp tradeoff` draws it (the figure and its
/// columns are the trade-off command's, [`super::tradeoff::PARETO_FIGURES`]).
fn pareto(first: &Table, o: &PlotOptions, out: &Path, opts: &FigureOptions) -> anyhow::Result<()> {
    let column = o.y.as_deref().unwrap_or("amplitude_max_rel_error");
    let Some(plot) = super::tradeoff::PARETO_FIGURES
        .iter()
        .find(|p| p.column == column)
    else {
        let known: Vec<&str> = super::tradeoff::PARETO_FIGURES
            .iter()
            .map(|p| p.column)
            .collect();
        let msg = format!("`{column}`: choose one of {}", known.join(", "));
        return Err(pdamp::error::PlotError::bad("pareto", "y", msg).into());
    };
    let (labels, groups) = (first.str_column("setting")?, first.str_column("axis")?);
    let cost = first.opt_f64_column("core_seconds_per_point")?;
    let err = first.opt_f64_column(column)?;
    let rows: Vec<super::tradeoff::ParetoRow> = labels
        .into_iter()
        .zip(groups)
        .zip(cost.into_iter().zip(err))
        .map(|((label, group), (c, error))| super::tradeoff::ParetoRow {
            label,
            group,
            core_seconds: c.unwrap_or(f64::NAN),
            error,
        })
        .collect();
    let fig = super::tradeoff::pareto_figure(&rows, plot.label, "Speed against accuracy".into())
        .ok_or_else(|| {
            let msg = format!(
                "{}: no setting has both a cost and a finite `{column}`",
                first.path
            );
            pdamp::error::PlotError::bad("pareto", "y", msg)
        })?;
    pdamp::plot::render(&fig, out, opts)?;
    wrote(out);
    Ok(())
}

fn wrote(out: &Path) {
    tracing::info!("wrote {}", out.display());
}

/// The library's error as the CLI's: the same chain of messages (context, then cause) and the
/// typed cause kept, so that the message and the exit status ([`crate::cli::exit`]) are
/// those of the error itself.
fn cli_error(e: TableFigureError) -> anyhow::Error {
    match e {
        TableFigureError::Data(e) => e.into(),
        TableFigureError::Plot(e) => e.into(),
        TableFigureError::Analysis(e) => e.into(),
        TableFigureError::Options(message) => anyhow::anyhow!(message),
        TableFigureError::Context { context, source } => cli_error(*source).context(context),
        TableFigureError::Number { context, source } => anyhow::Error::new(source).context(context),
    }
}
