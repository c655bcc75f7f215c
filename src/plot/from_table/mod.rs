//! Table → figure adapters: the figure kinds of `pdamp plot` (SPEC §7) drawn from the CSV files
//! of the output contract (`series.csv`, `sweep.csv`, `strobe.csv`, the output of
//! `pdamp fit-frf` and `pdamp d2`) or from a plain series, one function per figure kind.
//!
//! Each adapter takes the parsed [`Table`] (or the series, for the estimator figures), the
//! [`TableFigureOptions`] and the [`FigureOptions`], and writes the figure to a `.png` or
//! `.svg` file with [`render`]; the command line (`pdamp plot`) only turns its flags into
//! these options. A refused table or option is a [`TableFigureError`] whose message names the
//! column or flag and the fix.
//!
//! - [`frequency`]: `frf`, `effective`, `energy`, `resonance`, `bifurcation` (against f or a
//!   swept parameter);
//! - [`regime`]: `regime-frf`, `regime-map` (the `regime` column of a sweep);
//! - [`series`]: `bed-motion`, `poincare`, `spectrum`, `reconstruction`, `recurrence`, `d2`;
//! - [`decay`](mod@decay): `decay` (`decay.csv`, or the free-decay envelope of a run's `series.csv`);
//! - [`estimators`]: `kantz`, `mutual`, `fnn` (a series, the estimator run with the analysis
//!   verbs' defaults).

use std::path::Path;

use crate::analysis::recurrence::RecurrenceThreshold;
use crate::analysis::regime::Regime;
pub use crate::error::TableFigureError;
use crate::plot::regime_frf::Exponents;
use crate::plot::table::Table;
use crate::plot::{render, Figure, FigureOptions};

pub mod decay;
pub mod estimators;
pub mod frequency;
pub mod regime;
pub mod series;

pub use decay::{decay, decay_input};
pub use estimators::{fnn, kantz, mutual, read_estimator_series};
pub use frequency::{bifurcation, effective, energy, frf, resonance};
pub use regime::{regime_frf, regime_map};
pub use series::{bed_motion, d2, poincare, reconstruction, recurrence, spectrum};

/// Options of the table figures (the flags of `pdamp plot`); each field names the kinds that
/// read it, the others ignore it. [`Default`] gives `pdamp plot`'s defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct TableFigureOptions {
    /// Legend label per input table, in order (default: the file's parent directory name).
    pub labels: Vec<String>,
    /// x column (energy, bifurcation, resonance, regime-map, effective, poincare).
    pub x: Option<String>,
    /// y column (regime-map, poincare).
    pub y: Option<String>,
    /// Series column for reconstruction, recurrence, kantz, mutual, fnn: a header name, or a
    /// 1-based index (default 1 for plain files); for decay the displacement column of
    /// series.csv (default `box_z_m`).
    pub column: Option<String>,
    /// Delay τ in samples: reconstruction (default: first zero of the autocorrelation),
    /// recurrence, kantz and fnn (default 1, TISEAN -d).
    pub lag: Option<usize>,
    /// Sampling interval (s) of a plain series: τ in seconds (reconstruction, mutual), the
    /// Δn axis in seconds and the exponent per second (kantz).
    pub dt: Option<f64>,
    /// Use at most this many samples of the series (kantz, mutual, fnn; TISEAN -l).
    pub length: Option<usize>,
    /// Smallest embedding dimension (kantz: default 2, fnn: default 1; TISEAN -m).
    pub m_min: Option<usize>,
    /// Largest embedding dimension, `M` or `min,max` (kantz: default 2, fnn: default 6).
    pub m_max: Option<String>,
    /// Smallest radius ε in data units for kantz (TISEAN -r). Default: (max − min)/1000.
    pub eps_min: Option<f64>,
    /// Largest radius ε in data units for kantz (TISEAN -R). Default: (max − min)/100.
    pub eps_max: Option<f64>,
    /// Number of radii for kantz, log-spaced (TISEAN -#). Default 5.
    pub eps_count: Option<usize>,
    /// Largest Δn in samples for kantz (TISEAN -s). Default 50.
    pub steps: Option<usize>,
    /// Number of reference points for kantz (TISEAN -n). Default: all.
    pub references: Option<usize>,
    /// Theiler window in samples for kantz and fnn (default τ, TISEAN 0) and for recurrence
    /// (RR excludes |i − j| ≤ w; default 0).
    pub theiler: Option<usize>,
    /// TISEAN's definitions and defaults for kantz (RMS, Theiler 0) and fnn (-M 1,5 -f 2 -t 0).
    pub tisean: bool,
    /// Largest lag D in samples for mutual (TISEAN -D). Default 20.
    pub max_lag: Option<usize>,
    /// Histogram bins per axis for mutual (TISEAN -b). Default 16.
    pub bins: Option<usize>,
    /// Escape ratio f for fnn (TISEAN -f). Default 10 (TISEAN: 2).
    pub ratio: Option<f64>,
    /// Minimum R² of a linear scaling region for kantz. Default 0.99.
    pub r2_min: f64,
    /// Forcing frequency f (Hz) marked on spectra.
    pub forcing_hz: Option<f64>,
    /// Sweep point (`point` column of strobe.csv) for the Poincaré return map (default: first).
    pub point: Option<i64>,
    /// Start of the time window (s) for bed-motion and decay (from series.csv).
    pub from_time: Option<f64>,
    /// End of the time window (s) for bed-motion and decay (from series.csv).
    pub to_time: Option<f64>,
    /// Primary mass M (kg): FRF reference curve; M reference line of `effective`.
    pub mass: Option<f64>,
    /// Grain mass m_p (kg): FRF reference curve for M + m_p.
    pub particle_mass: Option<f64>,
    /// Spring stiffness K (N/m) for the FRF reference curves.
    pub stiffness: Option<f64>,
    /// Primary damping C (N s/m): FRF references; `effective` then shows C_ef/C.
    pub damping: Option<f64>,
    /// Base amplitude U (m) for the FRF reference curves.
    pub base_amplitude: Option<f64>,
    /// `frf`: fit the effective mass and damping (2.1.21) to each input, K and U held at
    /// `stiffness` and `base_amplitude`, and draw the fitted curves.
    pub fit: bool,
    /// Embedding dimension for recurrence (default 1).
    pub dim: Option<usize>,
    /// Recurrence threshold: ε in data units or a recurrence rate. Default: rate 0.05.
    pub threshold: RecurrenceThreshold,
    /// Largest number of pixels per side of the recurrence plot (longer series are
    /// downsampled in blocks). Default 600.
    pub max_cells: usize,
}

impl Default for TableFigureOptions {
    fn default() -> Self {
        Self {
            labels: Vec::new(),
            x: None,
            y: None,
            column: None,
            lag: None,
            dt: None,
            length: None,
            m_min: None,
            m_max: None,
            eps_min: None,
            eps_max: None,
            eps_count: None,
            steps: None,
            references: None,
            theiler: None,
            tisean: false,
            max_lag: None,
            bins: None,
            ratio: None,
            r2_min: 0.99,
            forcing_hz: None,
            point: None,
            from_time: None,
            to_time: None,
            mass: None,
            particle_mass: None,
            stiffness: None,
            damping: None,
            base_amplitude: None,
            fit: false,
            dim: None,
            threshold: RecurrenceThreshold::Rate(0.05),
            max_cells: 600,
        }
    }
}

/// Writes `fig` to `out` (`.png` or `.svg`).
fn draw<F: Figure>(fig: &F, out: &Path, opts: &FigureOptions) -> Result<(), TableFigureError> {
    render(fig, out, opts)?;
    Ok(())
}

/// A message-only error (an option or a table refused; the text names it and the fix).
fn refuse(message: impl Into<String>) -> TableFigureError {
    TableFigureError::Options(message.into())
}

/// `result`, its error preceded by `context` (what was being done).
fn context<T, E: Into<TableFigureError>>(
    result: Result<T, E>,
    context: impl FnOnce() -> String,
) -> Result<T, TableFigureError> {
    result.map_err(|e| TableFigureError::Context {
        context: context(),
        source: Box::new(e.into()),
    })
}

/// The legend label of each table: the given one, else the file's parent directory name.
pub fn labels(tables: &[Table], given: &[String]) -> Vec<String> {
    tables
        .iter()
        .enumerate()
        .map(|(i, t)| {
            given
                .get(i)
                .cloned()
                .unwrap_or_else(|| default_label(Path::new(&t.path)))
        })
        .collect()
}

/// The default legend label of a file: its parent directory's name (else its stem).
pub fn default_label(p: &Path) -> String {
    p.parent()
        .and_then(|d| d.file_name())
        .or_else(|| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| p.display().to_string())
}

/// Axis description for a column: known names get words and units.
pub fn axis_label(col: &str) -> String {
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

/// An optional numeric column (empty cells: none), `None` if the table has no such column.
fn optional_column(t: &Table, name: &str) -> Result<Option<Vec<Option<f64>>>, TableFigureError> {
    Ok(if t.has(name) {
        Some(t.opt_f64_column(name)?)
    } else {
        None
    })
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
fn regime_column(cells: &[String]) -> Result<Vec<Option<Regime>>, TableFigureError> {
    cells
        .iter()
        .enumerate()
        .map(|(row, c)| {
            if c.trim().is_empty() {
                Ok(None)
            } else {
                c.parse()
                    .map(Some)
                    .map_err(|e| refuse(format!("column regime, data row {}: {e}", row + 1)))
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
