//! Error types of the library (thiserror). The CLI wraps them with `anyhow`.
//!
//! Every error names the offending field or input and says how to fix it, e.g.
//! ``damper.radius = -0.003: must be > 0 (metres)``.
//! Each area owns its enum: scene validation ([`SceneError`]), simulation ([`SimError`]),
//! series analysis ([`AnalysisError`]) and data files ([`DataError`]).

use thiserror::Error;

/// A scene (TOML) that cannot be used: names the key, the value and the fix.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SceneError {
    /// The TOML text does not parse, or a key has the wrong type, or is unknown.
    #[error("scene file: {0}")]
    Parse(String),
    /// A key is present but its value is impossible.
    #[error("{field} = {value}: {hint}")]
    Invalid {
        /// Dotted key, e.g. `damper.radius`.
        field: String,
        /// The value as given.
        value: String,
        /// What is wrong and how to fix it.
        hint: String,
    },
    /// A required key is missing.
    #[error("{field} is missing: {hint}")]
    Missing {
        /// Dotted key.
        field: String,
        /// What to write.
        hint: String,
    },
}

impl SceneError {
    /// Shorthand for [`SceneError::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        hint: impl Into<String>,
    ) -> Self {
        SceneError::Invalid {
            field: field.into(),
            value: value.to_string(),
            hint: hint.into(),
        }
    }
}

/// A physical quantity that the engine cannot use, in the words of the physics: the engine
/// (`dem`, `impact`, `model`) knows no scene file; the resolve step ([`crate::setup`]) maps
/// [`Quantity`] to the scene key that set it (e.g. [`Quantity::TimeStep`] → `run.dt`).
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{quantity} = {value}: {hint}")]
pub struct ModelError {
    /// Which quantity.
    pub quantity: Quantity,
    /// The value as given.
    pub value: String,
    /// What is wrong and how to fix it, in physical terms.
    pub hint: String,
}

impl ModelError {
    /// Shorthand constructor.
    pub fn new(quantity: Quantity, value: impl ToString, hint: impl Into<String>) -> Self {
        ModelError {
            quantity,
            value: value.to_string(),
            hint: hint.into(),
        }
    }
}

/// The physical quantities an engine error can be about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Integration time step dt (s).
    TimeStep,
    /// Time step as a fraction of the contact duration, dt / t_s (–).
    TimeStepFraction,
    /// Simulated (driven) duration (s).
    Duration,
    /// Output sampling interval (s).
    SampleInterval,
    /// Fraction of the run treated as steady state (–).
    SteadyFraction,
    /// Grain–grain coefficient of restitution e (–).
    Restitution,
    /// Grain–wall coefficient of restitution e (–).
    WallRestitution,
    /// Yield strength Y of the grain material (Pa).
    YieldStrength,
    /// Number of grains (positions and radii).
    GrainCount,
    /// Perturbation δ0 of the two-replica test (m).
    ReplicaPerturbation,
    /// The bean bag's size against its nodes and grains.
    BagSize,
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Quantity::TimeStep => "time step dt",
            Quantity::TimeStepFraction => "time step fraction dt/t_s",
            Quantity::Duration => "duration",
            Quantity::SampleInterval => "sample interval",
            Quantity::SteadyFraction => "steady-state fraction",
            Quantity::Restitution => "grain–grain restitution e",
            Quantity::WallRestitution => "grain–wall restitution e",
            Quantity::YieldStrength => "yield strength Y",
            Quantity::GrainCount => "number of grains",
            Quantity::ReplicaPerturbation => "replica perturbation δ0",
            Quantity::BagSize => "bag size",
        })
    }
}

/// A simulation that had to stop.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SimError {
    /// The state became non-finite or energy grew without input: the integration is unstable.
    #[error("simulation unstable at t = {t_s:.6e} s: {reason}")]
    Unstable {
        /// Simulated time when detected (s).
        t_s: f64,
        /// What was detected and its likely cause (e.g. time step versus stiffness).
        reason: String,
    },
    /// The scene was rejected.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A physical quantity was rejected by the engine (mapped to a scene key by
    /// [`crate::setup`] when the run came from a scene).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Output (series, summary, sweep files) could not be written: names the file.
    #[error("output: {0}")]
    Output(String),
    /// The scene is valid but asks for a model that is not available in this build.
    #[error("{0}")]
    Unavailable(String),
    /// The caller stopped the run (an observer's progress report said so, or
    /// [`crate::sweep::stop::request`] was called): nothing of it is complete.
    #[error("interrupted: {0}")]
    Interrupted(String),
}

/// A series analysis that cannot be carried out on the given data/parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AnalysisError {
    /// The series is too short for the requested parameters.
    #[error("series too short: {0}")]
    TooShort(String),
    /// A parameter is out of range.
    #[error("parameter {name} = {value}: {hint}")]
    BadParameter {
        /// Parameter name (as on the command line, e.g. `bins`).
        name: String,
        /// Given value.
        value: String,
        /// What is allowed.
        hint: String,
    },
    /// The series contains NaN or infinite values.
    #[error("series contains a non-finite value at index {index}")]
    NonFinite {
        /// First offending index.
        index: usize,
    },
    /// The series is constant (zero range), so it cannot be rescaled or embedded.
    #[error("series is constant: nothing to analyse")]
    Constant,
    /// The series rises (or falls) at every sample: a time or index column, not a signal.
    #[error(
        "series {direction} at every one of its {len} samples (from {first} to {last}): this looks \
         like a time or index column, not data; select the signal's column (e.g. -c 2)"
    )]
    Monotonic {
        /// "increases" or "decreases".
        direction: &'static str,
        /// Number of samples.
        len: usize,
        /// First sample.
        first: f64,
        /// Last sample.
        last: f64,
    },
    /// A numerical procedure did not converge or found nothing (e.g. no MI minimum, fit failed).
    #[error("{0}")]
    NoResult(String),
}

impl AnalysisError {
    /// Shorthand for [`AnalysisError::BadParameter`].
    pub fn bad(name: impl Into<String>, value: impl ToString, hint: impl Into<String>) -> Self {
        AnalysisError::BadParameter {
            name: name.into(),
            value: value.to_string(),
            hint: hint.into(),
        }
    }
}

/// A data file (series, CSV) that cannot be read.
#[derive(Debug, Error)]
pub enum DataError {
    /// File-system error, with the path.
    #[error("{path}: {source}")]
    Io {
        /// Path of the file.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// A file of a run directory that is incomplete (a run still writing it, or one that
    /// failed or was killed: see [`crate::io::run_dir`]).
    #[error("{path}: {message}")]
    Incomplete {
        /// The run directory.
        path: String,
        /// What its marker says and what to do.
        message: String,
    },
    /// Malformed content: names the file, line and column.
    #[error("{path}:{line}: {message}")]
    Malformed {
        /// Path of the file.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong and how to fix it.
        message: String,
    },
}

/// A figure that cannot be drawn: names the figure, the input field and the fix.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The data given to a figure is unusable (empty, mismatched lengths, NaN …).
    #[error("{figure} figure: {field}: {hint}")]
    BadData {
        /// Figure kind, e.g. `frf`.
        figure: String,
        /// Input field or column, e.g. `amplitude_m`.
        field: String,
        /// What is wrong and how to fix it.
        hint: String,
    },
    /// The output file name has an extension no backend handles.
    #[error("{path}: unsupported figure format (use .png or .svg)")]
    Format {
        /// Requested output path.
        path: String,
    },
    /// The drawing backend failed (file not writable, font missing …).
    #[error("{path}: drawing failed: {message}")]
    Draw {
        /// Output path (or `<memory>`).
        path: String,
        /// Backend message.
        message: String,
    },
}

impl PlotError {
    /// Shorthand for [`PlotError::BadData`].
    pub fn bad(figure: &str, field: impl Into<String>, hint: impl Into<String>) -> Self {
        PlotError::BadData {
            figure: figure.to_string(),
            field: field.into(),
            hint: hint.into(),
        }
    }
}

/// A figure that cannot be drawn from the given table and options
/// ([`crate::plot::from_table`], the figures of `pdamp plot`): the message names the column or
/// option and the fix; a cause of another kind is kept as it is.
#[derive(Debug, Error)]
pub enum TableFigureError {
    /// The table or series file cannot be read, or lacks a column.
    #[error(transparent)]
    Data(#[from] DataError),
    /// The figure refuses its data, or drawing failed.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// The estimator behind the figure refused the series or its parameters.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    /// An option, or a combination of options, that the figure cannot use; names it and the
    /// fix.
    #[error("{0}")]
    Options(String),
    /// A failure with what was being done (`Kantz on FILE`) in front of its cause.
    #[error("{context}")]
    Context {
        /// What was being done.
        context: String,
        /// The cause.
        #[source]
        source: Box<TableFigureError>,
    },
    /// An option value that is not a whole number.
    #[error("{context}")]
    Number {
        /// Which option, and what it must be.
        context: String,
        /// The parse failure.
        #[source]
        source: std::num::ParseIntError,
    },
}

/// A study (a pipeline of sweeps, fits and figures, e.g. `pdamp reproduce`) that had to stop:
/// names the step and wraps the cause.
#[derive(Debug, Error)]
pub enum StudyError {
    /// A step of the study failed; `step` names it (e.g. `frf: sweep of the impact model`).
    #[error("{step}: {message}")]
    Step {
        /// The figure or stage, e.g. `effective`.
        step: String,
        /// The cause and, where known, the fix.
        message: String,
    },
    /// Output directory or file not writable.
    #[error("{path}: {message}")]
    Output {
        /// The path.
        path: String,
        /// The cause.
        message: String,
    },
    /// The computed numbers contradict the expected qualitative behaviour (SPEC §1, §3).
    #[error("qualitative check failed: {0}")]
    Check(String),
}

impl StudyError {
    /// Shorthand for [`StudyError::Step`].
    pub fn step(step: impl Into<String>, message: impl ToString) -> Self {
        StudyError::Step {
            step: step.into(),
            message: message.to_string(),
        }
    }
}
