//! `pdamp plot KIND INPUT... -o FILE.png|FILE.svg`: draw one figure kind of SPEC §7 from the CSV files
//! of the output contract (series.csv, sweep.csv, strobe.csv, fit-frf output) or plain series.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};

use pdamp::analysis::autocorrelation::first_zero_lag;
use pdamp::analysis::false_nearest_neighbors::{false_nearest_neighbors, FnnOptions};
use pdamp::analysis::kantz::{estimate_from_curves, kantz, KantzOptions, ScalingOptions};
use pdamp::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use pdamp::io::{read_series as read_series_file, Column, SeriesReadOptions};

use pdamp::analysis::correlation_dimension::{
    estimate_d2, local_slopes, CorrelationCurve, CorrelationSums, PlateauOptions,
};
use pdamp::analysis::recurrence::{recurrence_grid, RecurrenceOptions};
use pdamp::plot::bed_motion::BedMotionFigure;
use pdamp::plot::bifurcation::BifurcationFigure;
use pdamp::plot::correlation_dimension::D2Figure;
use pdamp::plot::effective::EffectiveFigure;
use pdamp::plot::energy::{energy_figure, energy_label};
use pdamp::plot::fnn::FnnFigure;
use pdamp::plot::frf::{FrfFigure, FrfReference};
use pdamp::plot::kantz::KantzFigure;
use pdamp::plot::mutual::MutualFigure;
use pdamp::plot::poincare::PoincareFigure;
use pdamp::plot::reconstruction::ReconstructionFigure;
use pdamp::plot::recurrence::RecurrenceFigure;
use pdamp::plot::regime_frf::{Exponents, RegimeFrfFigure};
use pdamp::plot::regime_map::RegimeMapFigure;
use pdamp::plot::resonance::{resonance_amplitudes, resonance_figure};
use pdamp::plot::spectrum::SpectrumFigure;
use pdamp::plot::table::Table;
use pdamp::plot::{render, Figure, FigureOptions, Series};

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
}

/// Arguments of `pdamp plot`.
#[derive(Debug, clap::Args)]
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
    /// (default 1 for plain files).
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
    /// Theiler window in samples for kantz and fnn (TISEAN -t; default τ, TISEAN 0) and for
    /// recurrence (RR excludes |i − j| ≤ w; default 0).
    #[arg(
        short = 't',
        long = "theiler",
        help_heading = "Estimators (kantz, mutual, fnn)"
    )]
    pub theiler: Option<usize>,
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
    /// Start of the time window (s) for bed-motion.
    #[arg(long)]
    pub from_time: Option<f64>,
    /// End of the time window (s) for bed-motion.
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
    if matches!(args.kind, Kind::Kantz | Kind::Mutual | Kind::Fnn) {
        return estimator(&args, &opts);
    }
    let tables = args
        .inputs
        .iter()
        .map(|p| Table::read(p))
        .collect::<Result<Vec<_>, _>>()?;
    let labels: Vec<String> = args
        .inputs
        .iter()
        .enumerate()
        .map(|(i, p)| o.label.get(i).cloned().unwrap_or_else(|| default_label(p)))
        .collect();
    let out = &args.output;
    let first = &tables[0];
    let one = || -> anyhow::Result<()> {
        if tables.len() > 1 {
            bail!("{:?} takes one input file, got {}", args.kind, tables.len());
        }
        Ok(())
    };
    match args.kind {
        Kind::Frf => {
            let cols = tables
                .iter()
                .map(|t| Ok((t.f64_column("frequency_hz")?, t.f64_column("amplitude_m")?)))
                .collect::<anyhow::Result<Vec<_>>>()?;
            let series = cols
                .iter()
                .zip(&labels)
                .map(|((x, y), l)| Series { label: l, x, y })
                .collect();
            let reference = if o.fit && o.mass.is_none() && o.damping.is_none() {
                None
            } else {
                frf_reference(o)?
            };
            let fitted = if o.fit {
                frf_fits(o, &cols, &labels)?
            } else {
                Vec::new()
            };
            draw(
                &FrfFigure {
                    series,
                    reference,
                    fitted,
                },
                out,
                &opts,
            )
        }
        Kind::BedMotion => {
            one()?;
            let t = first.f64_column("time_s")?;
            let (a, b) = window(&t, o.from_time, o.to_time)?;
            let col =
                |n: &str| -> anyhow::Result<Vec<f64>> { Ok(first.f64_column(n)?[a..b].to_vec()) };
            let (floor, ceil, grain) = (col("floor_z_m")?, col("ceiling_z_m")?, col("grain_z_m")?);
            let band = if first.has("grain_zmin_m") && first.has("grain_zmax_m") {
                Some((col("grain_zmin_m")?, col("grain_zmax_m")?))
            } else {
                None
            };
            let force = if first.has("grain_force_n") {
                Some(col("grain_force_n")?)
            } else {
                None
            };
            let fig = BedMotionFigure {
                time_s: &t[a..b],
                floor_z_m: &floor,
                ceiling_z_m: &ceil,
                grain_z_m: &grain,
                grain_band: band.as_ref().map(|(l, h)| (l.as_slice(), h.as_slice())),
                grain_force_n: force.as_deref(),
            };
            draw(&fig, out, &opts)
        }
        Kind::Poincare => {
            one()?;
            let (x, y, xl, yl) = if first.has("cycle") && first.has("grain_z_m") && o.x.is_none() {
                let z = strobe_of_point(first, o.point)?;
                let x = z[..z.len().saturating_sub(1)].to_vec();
                let y = z.get(1..).unwrap_or_default().to_vec();
                (x, y, "z_k (m)".to_string(), "z_(k+1) (m)".to_string())
            } else {
                let xn = o.x.clone().unwrap_or_else(|| "x".into());
                let yn = o.y.clone().unwrap_or_else(|| "y".into());
                (first.f64_column(&xn)?, first.f64_column(&yn)?, xn, yn)
            };
            let fig = PoincareFigure {
                x: &x,
                y: &y,
                x_label: xl,
                y_label: yl,
            };
            draw(&fig, out, &opts)
        }
        Kind::Spectrum => {
            one()?;
            let f = first.f64_column("frequency_hz")?;
            let p = first.f64_column("power")?;
            let fig = SpectrumFigure {
                frequency_hz: &f,
                power: &p,
                forcing_hz: o.forcing_hz,
                power_label: "power (arb. units)".into(),
            };
            draw(&fig, out, &opts)
        }
        Kind::Reconstruction => {
            one()?;
            let (s, name) = read_series(&args.inputs[0], first, o.column.as_deref())?;
            let (dt, s) = match (o.dt, first.has("time_s")) {
                (Some(dt), _) => (Some(dt), s),
                (None, true) => {
                    let t = first.f64_column("time_s")?;
                    (t.get(1).map(|t1| t1 - t[0]), s)
                }
                (None, false) => (None, s),
            };
            let lag = match o.lag {
                Some(l) => l,
                None => first_zero_lag(&s).with_context(|| {
                    format!("{}: give --lag (samples)", args.inputs[0].display())
                })?,
            };
            let fig = ReconstructionFigure {
                series: &s,
                lag,
                dt_s: dt,
                value_label: name,
            };
            draw(&fig, out, &opts)
        }
        Kind::Bifurcation => {
            one()?;
            let xn = o.x.clone().unwrap_or_else(|| "frequency_hz".into());
            let x = first.f64_column(&xn)?;
            let z = first.f64_column("grain_z_m")?;
            let fig = BifurcationFigure {
                x: &x,
                z_m: &z,
                x_label: axis_label(&xn),
            };
            draw(&fig, out, &opts)
        }
        Kind::RegimeFrf => {
            one()?;
            let f = first.f64_column("frequency_hz")?;
            let z = first.f64_column("amplitude_m")?;
            let r = regime_column(&first.str_column("regime")?)?;
            let col = |name: &str| -> anyhow::Result<Option<Vec<Option<f64>>>> {
                Ok(if first.has(name) {
                    Some(first.opt_f64_column(name)?)
                } else {
                    None
                })
            };
            let period = period_column(&col("period")?);
            let (m, ms) = (col("mle_per_s")?, col("mle_stderr_per_s")?);
            let (mm, mms) = (col("model_mle_per_s")?, col("model_mle_stderr_per_s")?);
            let growth = col("replica_growth_per_s")?;
            let no_stderr = None;
            // `phase_locked` (sweeps since issue 39): true / false / empty
            let locked: Option<Vec<bool>> = if first.has("phase_locked") {
                Some(
                    first
                        .str_column("phase_locked")?
                        .iter()
                        .map(|c| c.trim() == "true")
                        .collect(),
                )
            } else {
                None
            };
            let fig = RegimeFrfFigure {
                frequency_hz: &f,
                amplitude_m: &z,
                regime: &r,
                period: period.as_deref(),
                data: exponents(&m, &ms),
                model: exponents(&mm, &mms),
                phase_locked: locked.as_deref(),
                replica: exponents(&growth, &no_stderr),
            };
            draw(&fig, out, &opts)
        }
        Kind::Effective => {
            one()?;
            let xn = o.x.clone().unwrap_or_else(|| first.headers[0].clone());
            // an ungrouped fit (one row, no group column) has no parameter to put on x
            const FIT_COLUMNS: [&str; 4] = [
                "mass_ef_kg",
                "mass_ef_stderr_kg",
                "damping_ef_ns_per_m",
                "damping_ef_stderr_ns_per_m",
            ];
            if FIT_COLUMNS.contains(&xn.as_str()) || first.rows.len() < 2 {
                let msg = format!(
                    "{}: `effective` plots M_ef and C_ef against the parameter the fits were \
                     grouped by, and this table has {} (x column `{xn}`): run \
                     `pdamp fit-frf SWEEP.csv --group COLUMN …` on a sweep over that parameter \
                     (e.g. --vary damper.gap=… --vary excitation.frequency=…)",
                    first.path,
                    if first.rows.len() < 2 {
                        "a single fit".to_string()
                    } else {
                        "no group column".to_string()
                    }
                );
                return Err(pdamp::error::PlotError::bad("effective", "x", msg).into());
            }
            let x = first.f64_column(&xn)?;
            let c = |n: &str| first.f64_column(n);
            let (m, ms, d, ds) = (
                c("mass_ef_kg")?,
                c("mass_ef_stderr_kg")?,
                c("damping_ef_ns_per_m")?,
                c("damping_ef_stderr_ns_per_m")?,
            );
            let fig = EffectiveFigure {
                x: &x,
                x_label: axis_label(&xn),
                mass_ef_kg: &m,
                mass_ef_stderr_kg: &ms,
                damping_ef_n_s_m: &d,
                damping_ef_stderr_n_s_m: &ds,
                mass_kg: o.mass,
                damping_n_s_m: o.damping,
            };
            draw(&fig, out, &opts)
        }
        Kind::Energy if first.has("time_s") => {
            one()?;
            // one run's series.csv: the ledger over time
            let t = first.f64_column("time_s")?;
            let present: Vec<(&str, &str)> = pdamp::plot::energy::LEDGER_COLUMNS
                .into_iter()
                .filter(|(c, _)| first.has(c))
                .collect();
            if present.is_empty() {
                let msg = format!(
                    "{}: no energy ledger (`e_*_j` columns): only DEM runs write one; for a \
                     sweep, pass its sweep.csv (energy per cycle against frequency)",
                    first.path
                );
                return Err(pdamp::error::PlotError::bad("energy", "series", msg).into());
            }
            let cols = present
                .iter()
                .map(|(c, _)| first.f64_column(c))
                .collect::<Result<Vec<_>, _>>()?;
            let pairs: Vec<(&str, &[f64])> = present
                .iter()
                .zip(&cols)
                .map(|((_, label), v)| (*label, v.as_slice()))
                .collect();
            draw(&pdamp::plot::energy::ledger_figure(&t, &pairs), out, &opts)
        }
        Kind::Energy => {
            one()?;
            let xn = o.x.clone().unwrap_or_else(|| "frequency_hz".into());
            let x = first.f64_column(&xn)?;
            let names = first.columns_matching("energy_", "_j_per_cycle");
            if names.is_empty() {
                bail!(
                    "{}: no `energy_*_j_per_cycle` columns (columns present: {})",
                    first.path,
                    first.headers.join(", ")
                );
            }
            let cols = names
                .iter()
                .map(|n| first.f64_column(n))
                .collect::<Result<Vec<_>, _>>()?;
            let labels: Vec<String> = names.iter().map(|n| energy_label(n)).collect();
            let pairs: Vec<(&str, &[f64])> = labels
                .iter()
                .zip(&cols)
                .map(|(n, c)| (n.as_str(), c.as_slice()))
                .collect();
            draw(&energy_figure(&x, &axis_label(&xn), &pairs), out, &opts)
        }
        Kind::Resonance => {
            let xn = o.x.clone().context(
                "resonance needs --x COLUMN (the damping parameter, e.g. damper.gamma_n)",
            )?;
            let curves = tables
                .iter()
                .map(|t| {
                    Ok(resonance_amplitudes(
                        &t.f64_column(&xn)?,
                        &t.f64_column("amplitude_m")?,
                    ))
                })
                .collect::<anyhow::Result<Vec<_>>>()?;
            let series = curves
                .iter()
                .zip(&labels)
                .map(|((x, y), l)| Series { label: l, x, y })
                .collect();
            draw(&resonance_figure(series, &axis_label(&xn)), out, &opts)
        }
        Kind::Recurrence => {
            one()?;
            let (s, _) = read_series(&args.inputs[0], first, o.column.as_deref())?;
            let ro = RecurrenceOptions {
                m: o.dim.unwrap_or(1),
                tau: o.lag.unwrap_or(1),
                theiler: o.theiler.unwrap_or(0),
                threshold: crate::cli::commands::rqa::threshold(o.eps, o.rate)?,
                ..RecurrenceOptions::default()
            };
            let grid = recurrence_grid(&s, &ro, o.max_cells)
                .with_context(|| format!("recurrence plot of {}", args.inputs[0].display()))?;
            let fig = RecurrenceFigure {
                grid: &grid,
                embedding: (ro.m, ro.tau),
            };
            draw(&fig, out, &opts)
        }
        Kind::D2 => {
            one()?;
            let sums = d2_curves(first)?;
            let est = estimate_d2(&sums, &PlateauOptions::default()).ok();
            let fig = D2Figure {
                sums: &sums,
                estimate: est.as_ref(),
            };
            draw(&fig, out, &opts)
        }
        Kind::Pareto => {
            one()?;
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
            let fig =
                super::tradeoff::pareto_figure(&rows, plot.label, "Speed against accuracy".into())
                    .ok_or_else(|| {
                        let msg = format!(
                            "{}: no setting has both a cost and a finite `{column}`",
                            first.path
                        );
                        pdamp::error::PlotError::bad("pareto", "y", msg)
                    })?;
            draw(&fig, out, &opts)
        }
        Kind::RegimeMap => {
            one()?;
            let xn =
                o.x.clone()
                    .context("regime-map needs --x COLUMN and --y COLUMN (the two varied keys)")?;
            let yn = o.y.clone().context("regime-map needs --y COLUMN")?;
            let (x, y) = (first.f64_column(&xn)?, first.f64_column(&yn)?);
            let r = regime_column(&first.str_column("regime")?)?;
            let col = |name: &str| -> anyhow::Result<Option<Vec<Option<f64>>>> {
                Ok(if first.has(name) {
                    Some(first.opt_f64_column(name)?)
                } else {
                    None
                })
            };
            let period = period_column(&col("period")?);
            // chaotic cells shaded by the model's exponent, the data's where there is none
            let (model, data) = (col("model_mle_per_s")?, col("mle_per_s")?);
            let (shade, label) = match (&model, &data) {
                (Some(m), Some(d)) if m.iter().any(Option::is_some) => (
                    Some(m.iter().zip(d).map(|(m, d)| m.or(*d)).collect::<Vec<_>>()),
                    "model λ (1/s)",
                ),
                (Some(m), None) => (Some(m.clone()), "model λ (1/s)"),
                (_, Some(d)) => (Some(d.clone()), "data λ (1/s)"),
                (_, None) => (None, "λ (1/s)"),
            };
            let fig = RegimeMapFigure {
                x: &x,
                y: &y,
                regime: &r,
                period: period.as_deref(),
                mle_per_s: shade.as_deref(),
                mle_label: label.into(),
                x_label: axis_label(&xn),
                y_label: axis_label(&yn),
            };
            draw(&fig, out, &opts)
        }
        Kind::Kantz | Kind::Mutual | Kind::Fnn => estimator(&args, &opts),
    }
}

/// An exponent column and its standard errors, if the column is there.
fn exponents<'a>(
    v: &'a Option<Vec<Option<f64>>>,
    s: &'a Option<Vec<Option<f64>>>,
) -> Option<Exponents<'a>> {
    v.as_deref().map(|per_s| Exponents {
        per_s,
        stderr_per_s: s.as_deref(),
    })
}

/// The `regime` column as regimes: an empty cell is a point without a verdict (a sweep run with
/// `--no-analysis`); any other name must be one that pdamp writes.
fn regime_column(cells: &[String]) -> anyhow::Result<Vec<Option<pdamp::analysis::regime::Regime>>> {
    cells
        .iter()
        .enumerate()
        .map(|(row, c)| {
            if c.trim().is_empty() {
                Ok(None)
            } else {
                c.parse()
                    .map(Some)
                    .map_err(|e| anyhow::anyhow!("column regime, data row {}: {e}", row + 1))
            }
        })
        .collect()
}

/// The `period` column as whole periods ≥ 1 (other cells: none).
fn period_column(p: &Option<Vec<Option<f64>>>) -> Option<Vec<Option<u32>>> {
    p.as_ref().map(|p| {
        p.iter()
            .map(|v| {
                v.filter(|v| *v >= 1.0 && v.fract() == 0.0)
                    .map(|v| v as u32)
            })
            .collect()
    })
}

/// The estimator figures (kantz, mutual, fnn): read one series as the analysis verbs do,
/// run the estimator with the verb's defaults, report its result on stderr, draw.
fn estimator(args: &Args, opts: &FigureOptions) -> anyhow::Result<()> {
    let o: &PlotOptions = &args.opts;
    if args.inputs.len() != 1 {
        bail!(
            "{:?} takes one series file, got {}",
            args.kind,
            args.inputs.len()
        );
    }
    let file = args.inputs[0].to_string_lossy().into_owned();
    let column: Column = o
        .column
        .as_deref()
        .unwrap_or("1")
        .parse()
        .map_err(|e: String| anyhow!("--column: {e}"))?;
    let read = SeriesReadOptions {
        columns: vec![column],
        max_rows: o.length,
        ..SeriesReadOptions::default()
    };
    let x = read_series_file(&file, &read)?;
    let out = &args.output;
    match args.kind {
        Kind::Kantz => {
            let base = if o.tisean {
                KantzOptions::tisean()
            } else {
                KantzOptions::default()
            };
            let (m_min, m_max) = dimensions(o, base.m_min, base.m_max)?;
            // field by field from the defaults, so that options added later keep their defaults
            let mut ko = base;
            (ko.m_min, ko.m_max) = (m_min, m_max);
            ko.tau = o.lag.unwrap_or(base.tau);
            (ko.eps_min, ko.eps_max) = (o.eps_min, o.eps_max);
            ko.eps_count = o.eps_count.unwrap_or(base.eps_count);
            ko.references = o.references;
            ko.steps = o.steps.unwrap_or(base.steps);
            ko.theiler = o.theiler.or(base.theiler);
            let result = kantz(&x, &ko).with_context(|| format!("Kantz on {file}"))?;
            let scaling = ScalingOptions {
                r2_min: o.r2_min,
                ..ScalingOptions::default()
            };
            let est = estimate_from_curves(&result, &scaling)
                .with_context(|| format!("Kantz on {file}"))?;
            let per_s = o.dt.map_or(String::new(), |dt| {
                format!(" = {:.6} per second", est.per_sample / dt)
            });
            tracing::info!(
                "maximal Lyapunov exponent (median of {} curves): {:.6} per sample{per_s}{}",
                est.curves_used,
                est.per_sample,
                if est.fit.linear {
                    ""
                } else {
                    " (no linear region: unreliable)"
                }
            );
            let fig = KantzFigure {
                result: &result,
                scaling,
                dt_s: o.dt,
            };
            draw(&fig, out, opts)
        }
        Kind::Mutual => {
            let mo = MutualInformationOptions {
                bins: o.bins.unwrap_or(16),
                max_lag: o.max_lag.unwrap_or(20),
            };
            let mi = mutual_information(&x, &mo)
                .with_context(|| format!("mutual information of {file}"))?;
            match mi.first_minimum {
                Some(t) => tracing::info!("first minimum of I(tau) at tau = {t} samples"),
                None => tracing::info!(
                    "no first minimum up to D = {}: raise -D",
                    mi.values.len() - 1
                ),
            }
            let fig = MutualFigure {
                values: &mi.values,
                first_minimum: mi.first_minimum,
                bins: mi.bins,
                dt_s: o.dt,
            };
            draw(&fig, out, opts)
        }
        Kind::Fnn => {
            let base = if o.tisean {
                FnnOptions::tisean()
            } else {
                FnnOptions::default()
            };
            let (m_min, m_max) = dimensions(o, base.m_min, base.m_max)?;
            let mut fo = base;
            (fo.m_min, fo.m_max) = (m_min, m_max);
            fo.tau = o.lag.unwrap_or(base.tau);
            fo.ratio = o.ratio.unwrap_or(base.ratio);
            fo.theiler = o.theiler.or(base.theiler);
            let points = false_nearest_neighbors(&x, &fo)
                .with_context(|| format!("false nearest neighbours of {file}"))?;
            let fig = FnnFigure {
                points: &points,
                threshold: 0.01,
                ratio: fo.ratio,
            };
            match pdamp::analysis::false_nearest_neighbors::suggested_dimension(&points, 0.01) {
                Some(m) => {
                    tracing::info!(
                        "suggested embedding dimension: m = {m} (≤ 1 % false neighbours)"
                    )
                }
                None => {
                    tracing::info!(
                        "no tested dimension has ≤ 1 % false neighbours (noise, or raise -M)"
                    )
                }
            }
            draw(&fig, out, opts)
        }
        other => bail!("{other:?} is not an estimator figure"),
    }
}

/// Dimension range from -m and -M (`M` or `min,max`), with the estimator's defaults; a lone
/// -m above the default maximum raises the maximum to it.
fn dimensions(o: &PlotOptions, min0: usize, max0: usize) -> anyhow::Result<(usize, usize)> {
    let num = |v: &str| -> anyhow::Result<usize> {
        v.trim().parse().with_context(|| {
            format!(
                "-M {}: `{v}` is not a dimension",
                o.m_max.as_deref().unwrap_or("")
            )
        })
    };
    match o.m_max.as_deref() {
        None => {
            let lo = o.m_min.unwrap_or(min0);
            Ok((lo, max0.max(lo)))
        }
        Some(s) => match s.split_once(',') {
            Some((a, b)) => {
                let (a, b) = (num(a)?, num(b)?);
                if let Some(m) = o.m_min.filter(|&m| m != a) {
                    bail!("-m {m} and -M {s} disagree: give the smallest dimension once");
                }
                Ok((a, b))
            }
            None => Ok((o.m_min.unwrap_or(min0), num(s)?)),
        },
    }
}

/// Curves of `pdamp d2`'s CSV (rows grouped by m, ε increasing).
fn d2_curves(t: &Table) -> anyhow::Result<CorrelationSums> {
    let (m, eps, c) = (t.f64_column("m")?, t.f64_column("eps")?, t.f64_column("c")?);
    let pairs = t.f64_column("pairs")?;
    let mut curves: Vec<CorrelationCurve> = Vec::new();
    for k in 0..m.len() {
        let mk = m[k] as usize;
        if curves.last().is_none_or(|c| c.m != mk) {
            curves.push(CorrelationCurve {
                m: mk,
                eps: Vec::new(),
                pairs: Vec::new(),
                c: Vec::new(),
                slope: Vec::new(),
            });
        }
        let cur = curves.last_mut().context("no rows")?;
        cur.eps.push(eps[k]);
        cur.c.push(c[k]);
        cur.pairs.push(pairs[k] as u64);
    }
    if curves.is_empty() {
        bail!("{}: no rows of `pdamp d2` output", t.path);
    }
    for cur in &mut curves {
        cur.slope = local_slopes(&cur.eps, &cur.c);
    }
    let last = &curves[0];
    let total = last
        .c
        .iter()
        .zip(&last.pairs)
        .rev()
        .find(|(c, _)| **c > 0.0)
        .map_or(0, |(c, p)| (*p as f64 / c).round() as u64);
    Ok(CorrelationSums {
        curves,
        total_pairs: total,
        vectors: 0,
    })
}

fn draw<F: Figure>(fig: &F, out: &Path, opts: &FigureOptions) -> anyhow::Result<()> {
    render(fig, out, opts)?;
    tracing::info!("wrote {}", out.display());
    Ok(())
}

fn default_label(p: &Path) -> String {
    p.parent()
        .and_then(|d| d.file_name())
        .or_else(|| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| p.display().to_string())
}

/// Axis description for a column: known names get words and units.
fn axis_label(col: &str) -> String {
    match col {
        "frequency_hz" | "excitation.frequency" => "frequency f (Hz)".into(),
        "damper.box" | "damper.lz" => "container height Lz (m)".into(),
        "damper.gap" => "gap (m)".into(),
        "damper.gamma_n" => "normal damping γ_n (kg s⁻¹ m^-1/2)".into(),
        "damper.gamma_s" => "tangential damping γ_s (kg s⁻¹ m^-1/2)".into(),
        "excitation.amplitude" => "base amplitude U (m)".into(),
        other => other.into(),
    }
}

/// `plot frf --fit`: the effective system of each input (K, U fixed), printed as `fit-frf`
/// does; an input the fit refuses is named and left without a curve.
fn frf_fits(
    o: &PlotOptions,
    cols: &[(Vec<f64>, Vec<f64>)],
    labels: &[String],
) -> anyhow::Result<Vec<pdamp::plot::frf::FrfFitted>> {
    let (Some(k), Some(u)) = (o.stiffness, o.base_amplitude) else {
        bail!("--fit needs --stiffness (N/m) and --base-amplitude (m): they are held fixed in the fit (2.1.21)");
    };
    let opts = pdamp::analysis::frf_fit::FrfFitOptions::new(k, u);
    let mut out = Vec::new();
    for (i, ((f, z), label)) in cols.iter().zip(labels).enumerate() {
        match pdamp::analysis::frf_fit::fit_frf(f, z, &opts) {
            Ok(fit) => {
                tracing::info!(
                    "{label}: M_ef = {:.6} ± {:.2e} kg, C_ef = {:.6} ± {:.2e} N s/m ({} points)",
                    fit.mass_ef_kg,
                    fit.mass_ef_stderr_kg,
                    fit.damping_ef_n_s_m,
                    fit.damping_ef_stderr_n_s_m,
                    fit.points
                );
                out.push(pdamp::plot::frf::FrfFitted {
                    series: i,
                    system: pdamp::model::PrimarySystem {
                        mass_kg: fit.mass_ef_kg,
                        stiffness_n_m: k,
                        damping_n_s_m: fit.damping_ef_n_s_m,
                    },
                    base_amplitude_m: u,
                });
            }
            Err(e) => tracing::warn!("{label}: no fitted curve: {e}"),
        }
    }
    Ok(out)
}

fn frf_reference(a: &PlotOptions) -> anyhow::Result<Option<FrfReference>> {
    match (a.mass, a.stiffness, a.damping, a.base_amplitude) {
        (Some(m), Some(k), Some(c), Some(u)) => Ok(Some(FrfReference {
            primary: pdamp::model::PrimarySystem {
                mass_kg: m,
                stiffness_n_m: k,
                damping_n_s_m: c,
            },
            particle_mass_kg: a.particle_mass,
            base_amplitude_m: u,
        })),
        (None, None, None, None) => Ok(None),
        _ => bail!("reference curves need all of --mass, --stiffness, --damping, --base-amplitude (and optionally --particle-mass)"),
    }
}

/// Index range [a, b) of the samples with from ≤ t ≤ to.
fn window(t: &[f64], from: Option<f64>, to: Option<f64>) -> anyhow::Result<(usize, usize)> {
    let a = from.map_or(0, |f| t.partition_point(|&x| x < f));
    let b = to.map_or(t.len(), |e| t.partition_point(|&x| x <= e));
    if b < a + 2 {
        bail!(
            "--from-time/--to-time leave fewer than 2 samples (series spans {} .. {} s)",
            t[0],
            t[t.len() - 1]
        );
    }
    Ok((a, b))
}

/// `grain_z_m` of one sweep point of strobe.csv, in cycle order.
fn strobe_of_point(t: &Table, point: Option<i64>) -> anyhow::Result<Vec<f64>> {
    let z = t.f64_column("grain_z_m")?;
    let cyc = t.f64_column("cycle")?;
    let pts = if t.has("point") {
        t.f64_column("point")?
    } else {
        vec![0.0; z.len()]
    };
    let p = point.map_or(pts[0], |p| p as f64);
    let mut rows: Vec<(f64, f64)> = (0..z.len())
        .filter(|&i| pts[i] == p)
        .map(|i| (cyc[i], z[i]))
        .collect();
    if rows.len() < 2 {
        bail!(
            "{}: sweep point {p} has {} strobe rows; need ≥ 2 (choose --point)",
            t.path,
            rows.len()
        );
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(rows.into_iter().map(|r| r.1).collect())
}

/// A series from a CSV column (header name) or a plain numeric file (1-based column index).
fn read_series(
    path: &Path,
    table: &Table,
    column: Option<&str>,
) -> anyhow::Result<(Vec<f64>, String)> {
    let numeric_header = table
        .headers
        .iter()
        .flat_map(|h| h.split_whitespace())
        .all(|h| h.parse::<f64>().is_ok());
    if numeric_header {
        // plain file: no header row; re-read it with the series reader of every analysis verb
        let idx: usize = column
            .unwrap_or("1")
            .parse()
            .context("--column must be a 1-based index for a plain numeric file")?;
        // column 0 reads the first column, as before this reader moved to `io::series`
        let read = SeriesReadOptions {
            columns: vec![Column::Index(idx.max(1))],
            ..SeriesReadOptions::default()
        };
        let v = read_series_file(&path.to_string_lossy(), &read)?;
        return Ok((v, format!("column {idx}")));
    }
    let name = column.map(str::to_string).unwrap_or_else(|| {
        if table.has("grain_z_m") {
            "grain_z_m".into()
        } else {
            table.headers[0].clone()
        }
    });
    Ok((table.f64_column(&name)?, name))
}
