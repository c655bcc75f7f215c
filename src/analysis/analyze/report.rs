//! What [`analyze_series`](super::analyze_series) and [`analyze_forced`](super::analyze_forced)
//! accept and return: the options with their automatic choices ([`AnalyzeOptions`]), the
//! limits on the input ([`MIN_SAMPLES`], [`MAX_ABS_VALUE`]) and the report ([`AnalysisReport`]:
//! verdict, automatic choices, evidence; exponents per sample and per second, frequencies in
//! Hz or cycles/sample).

use crate::analysis::phase_lock::PhaseLock;
use crate::analysis::regime::{Evidence, Regime, RegimeThresholds};
use crate::analysis::return_map_lyapunov::ReturnMapLyapunov;
use crate::analysis::section::SectionAnalysis;
use crate::analysis::section_dimension::ChaosDimension;
use crate::analysis::section_lyapunov::SectionLyapunov;
use serde::{Deserialize, Serialize};

/// Largest |x| [`analyze_series`](super::analyze_series) accepts (powers of larger values overflow f64).
pub const MAX_ABS_VALUE: f64 = 1e150;

/// Shortest series [`analyze_series`](super::analyze_series) accepts.
pub const MIN_SAMPLES: usize = 64;

/// Options of [`analyze_series`](super::analyze_series). `Default` gives the automatic choices documented per field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AnalyzeOptions {
    /// Sampling interval in seconds (default `None`: results per sample, frequencies in
    /// cycles/sample).
    pub dt_s: Option<f64>,
    /// Forcing frequency in Hz (default `None`). Needs `dt_s`. Enables the stroboscopic section
    /// and reports the period in forcing periods.
    pub forcing_hz: Option<f64>,
    /// Only the last `max_samples` samples are analysed (default 100 000).
    pub max_samples: usize,
    /// Largest lag searched for the first mutual-information minimum (default 0 = automatic:
    /// N/20 clamped to 20..=500 samples).
    pub max_lag: usize,
    /// Largest embedding dimension tried by FNN (default 8).
    pub max_dim: usize,
    /// FNN fraction at or below which the dimension is accepted (default 0.05).
    pub fnn_threshold: f64,
    /// FNN uses at most the last `max_fnn_samples` samples (default 20 000) to bound its cost.
    pub max_fnn_samples: usize,
    /// Kantz reference points: the first `kantz_references` admissible indices, as TISEAN
    /// `lyap_k -n` (default 2000); neighbours are searched among all points.
    pub kantz_references: usize,
    /// Seed of the 0–1 test's random frequencies (default 1).
    pub seed: u64,
    /// Thresholds of the classifier.
    pub thresholds: RegimeThresholds,
}

impl Default for AnalyzeOptions {
    fn default() -> Self {
        AnalyzeOptions {
            dt_s: None,
            forcing_hz: None,
            max_samples: 100_000,
            max_lag: 0,
            max_dim: 8,
            fnn_threshold: 0.05,
            max_fnn_samples: 20_000,
            kantz_references: 2000,
            seed: 1,
            thresholds: RegimeThresholds::default(),
        }
    }
}

/// A spectral line in the report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineReport {
    /// Interpolated frequency (Hz with `dt_s`, else cycles/sample).
    pub frequency: f64,
    /// Power in the line's main lobe (series units²).
    pub power: f64,
}

/// Kantz fit summary in the report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct KantzFitReport {
    /// First Δn of the scaling region (samples).
    pub start: usize,
    /// Last Δn of the scaling region (samples, inclusive).
    pub end: usize,
    /// R² of the straight-line fit.
    pub r2: f64,
    /// Whether a linear region (R² ≥ 0.99 over ≥ 5 points) was found.
    pub linear: bool,
    /// Embedding dimension of the curve.
    pub m: usize,
    /// Neighbourhood radius (series units).
    pub eps: f64,
    /// Largest Δn computed.
    pub steps: usize,
}

/// Result of [`analyze_series`](super::analyze_series): the verdict, the automatic choices and the evidence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AnalysisReport {
    /// Number of samples analysed (the tail of the series).
    pub n_samples: usize,
    /// Delay τ in samples (first MI minimum, else first τ with I(τ) ≤ I(0)/e, else 1).
    pub lag: Option<usize>,
    /// Embedding dimension used for Kantz (first m with FNN fraction ≤ threshold, else the
    /// largest tried).
    pub embedding_dim: Option<usize>,
    /// Maximal Lyapunov exponent per sample (natural log), `None` if Kantz could not run.
    pub mle_per_sample: Option<f64>,
    /// Maximal Lyapunov exponent per second (`mle_per_sample / dt_s`); `None` without `dt_s`.
    pub mle_per_time: Option<f64>,
    /// R² of the Kantz fit (also in `kantz_fit`).
    pub mle_fit_r2: Option<f64>,
    /// The verdict.
    pub regime: Regime,
    /// Period: in forcing periods with a forcing frequency, else in samples; `None` unless
    /// periodic.
    pub period: Option<f64>,
    /// Why: the rule of the classifier that fired.
    pub reason: String,
    /// Spectral lines (the 12 strongest, by frequency).
    pub spectral_lines: Vec<LineReport>,
    /// Unit of the line frequencies: `"hz"` or `"cycles/sample"`.
    pub frequency_unit: String,
    /// Fraction of the power in lines.
    pub line_power_fraction: f64,
    /// Distinct Poincaré points (period n), when the section is a finite set.
    pub poincare_distinct_points: Option<usize>,
    /// Number of points of the stroboscopic section.
    pub poincare_section_points: Option<usize>,
    /// Shape of the section: `points`, `closed-curve`, `cloud` or `too-few`.
    pub poincare_shape: Option<String>,
    /// Closed-curve score of the section.
    pub closed_curve_score: Option<f64>,
    /// Kantz scaling region and quality.
    pub kantz_fit: Option<KantzFitReport>,
    /// Gottwald–Melbourne 0–1 test K (median over c).
    pub zero_one_k: Option<f64>,
    /// Samples fed to the 0–1 test (section points or the series subsampled by the lag).
    pub zero_one_samples: Option<usize>,
    /// FNN fraction per dimension (m, fraction), `None` where no neighbour was accepted.
    pub fnn_fractions: Vec<(usize, Option<f64>)>,
    /// The stroboscopic section's pattern test (forced systems).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section: Option<SectionAnalysis>,
    /// Where the section came from: `exact` (the simulator's state at t = kT) or
    /// `interpolated` (cubic interpolation of the given series in delay coordinates).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section_source: Option<String>,
    /// Exponent of the stroboscopic map estimated from the data (section divergence), per
    /// second, with its standard error.
    pub data_mle_per_s: Option<f64>,
    /// Standard error of `data_mle_per_s`.
    pub data_mle_stderr_per_s: Option<f64>,
    /// Exponent from the model's equations (tangent dynamics), per second, when known.
    pub model_mle_per_s: Option<f64>,
    /// Standard error of `model_mle_per_s`.
    pub model_mle_stderr_per_s: Option<f64>,
    /// The section exponent's curves S(ε, Δ) and fits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section_exponent: Option<SectionLyapunov>,
    /// Synchronous average of the motion relative to the container
    /// ([`crate::analysis::phase_lock`]): the shortest window p ≤ 4 periods whose mean waveform
    /// carries ≥ 90 % of the variance, or else the one-period result; forced runs only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase_lock: Option<PhaseLock>,
    /// Qualifier of the verdict: the motion follows the forcing (Λ_p ≥ 0.9) although the
    /// verdict is not periodic, e.g. "chaotic; phase-locked to the forcing" (left out of the
    /// JSON when false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub phase_locked: bool,
    /// Qualifier of a chaotic or irregular verdict: low- or high-dimensional section
    /// ([`crate::analysis::section_dimension`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chaos_dimension: Option<ChaosDimension>,
    /// Sampling interval of the series analysed (s), after any decimation.
    pub series_dt_s: Option<f64>,
    /// The exponent of the first-return map of a phase-coherent chaotic flow, when it gave the
    /// reported exponent ([`crate::analysis::return_map_lyapunov`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub return_map_exponent: Option<ReturnMapLyapunov>,
    /// All evidence given to the classifier.
    pub evidence: Evidence,
    /// Fallbacks taken and estimators that could not run.
    pub notes: Vec<String>,
    /// The revision of the verdict rules that judged this report
    /// ([`crate::analysis::regime::VERDICT_RULES`]); absent in reports stored before the
    /// field: read it through [`AnalysisReport::verdict_rules`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verdict_rules: Option<u32>,
}

impl AnalysisReport {
    /// `periodic-p` for a periodic verdict with a period, else the regime's name
    /// (`chaotic`, `quasi-periodic`, …), followed by its qualifiers: "chaotic, phase-locked to
    /// the forcing (Λ₁ = 0.985), high-dimensional" ([`crate::analysis::regime::label`]).
    pub fn verdict(&self) -> String {
        crate::analysis::regime::label(
            self.regime,
            self.period,
            self.phase_lock.as_ref().filter(|_| self.phase_locked),
            self.chaos_dimension.as_ref(),
        )
    }

    /// The revision of the verdict rules that judged this report: the stored field, else —
    /// a report stored before it — 2 when its section kept its scales (stored from
    /// revision 2 on, before the field was) and 1 otherwise. Verdicts of different revisions
    /// are not comparable.
    pub fn verdict_rules(&self) -> u32 {
        self.verdict_rules.unwrap_or(match &self.section {
            Some(s) if !s.scales.is_empty() => 2,
            _ => 1,
        })
    }
}

/// A report with nothing decided yet.
pub(super) fn empty_report(n: usize, dt_s: Option<f64>) -> AnalysisReport {
    AnalysisReport {
        n_samples: n,
        lag: None,
        embedding_dim: None,
        mle_per_sample: None,
        mle_per_time: None,
        mle_fit_r2: None,
        regime: Regime::Undetermined,
        period: None,
        reason: String::new(),
        spectral_lines: Vec::new(),
        frequency_unit: if dt_s.is_some() {
            "hz"
        } else {
            "cycles/sample"
        }
        .to_string(),
        line_power_fraction: 0.0,
        poincare_distinct_points: None,
        poincare_section_points: None,
        poincare_shape: None,
        closed_curve_score: None,
        kantz_fit: None,
        zero_one_k: None,
        zero_one_samples: None,
        fnn_fractions: Vec::new(),
        section: None,
        section_source: None,
        data_mle_per_s: None,
        data_mle_stderr_per_s: None,
        model_mle_per_s: None,
        model_mle_stderr_per_s: None,
        section_exponent: None,
        phase_lock: None,
        phase_locked: false,
        chaos_dimension: None,
        series_dt_s: dt_s,
        return_map_exponent: None,
        evidence: Evidence::default(),
        notes: Vec::new(),
        verdict_rules: Some(crate::analysis::regime::VERDICT_RULES),
    }
}
