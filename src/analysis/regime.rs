//! Regime classifier: periodic-n, quasi-periodic, chaotic, irregular (noise-like) or undetermined, from the
//! evidence of the other estimators (SPEC §4: lines and sub-harmonics, Poincaré points / closed
//! curve / cloud, the sign of Kantz's exponent) cross-checked by the 0–1 test.
//!
//! The pieces here are pure functions of already computed quantities, so the rules can be read
//! and tested on their own: period detection from recurrence ([`recurrence_period`]) and from a
//! harmonic line set ([`harmonic_fundamental`]), and the decision [`classify`].

use crate::analysis::phase_lock::PhaseLock;
use crate::analysis::poincare::{SectionShape, SectionSummary};
use crate::analysis::section_dimension::ChaosDimension;
use crate::analysis::spectrum::SpectralLine;
use serde::{Deserialize, Serialize};

/// Dynamical regime of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Regime {
    /// A periodic orbit (the period is reported separately).
    Periodic,
    /// Motion on a torus: two or more incommensurate frequencies.
    QuasiPeriodic,
    /// Deterministic chaos: positive exponent with a clear scaling region and K ≈ 1.
    Chaotic,
    /// Irregular without low-dimensional determinism that the data can show: noise-like
    /// (noise, or chaos of more degrees of freedom than the record resolves). Never the
    /// verdict on a simulation whose sensitivity was measured (the two-replica test).
    Irregular,
    /// The evidence disagrees (the reason says which indicators conflict).
    Undetermined,
    /// The steady window is too short for a verdict (the reason gives the length needed).
    TooShort,
}

impl Regime {
    /// The name used in JSON and CSV: `periodic`, `quasi-periodic`, `chaotic`, `irregular`
    /// (noise-like; files written before issue 39 say `stochastic`, read as `irregular`),
    /// `undetermined`, `too-short`.
    pub fn as_str(self) -> &'static str {
        match self {
            Regime::Periodic => "periodic",
            Regime::QuasiPeriodic => "quasi-periodic",
            Regime::Chaotic => "chaotic",
            Regime::Irregular => "irregular",
            Regime::Undetermined => "undetermined",
            Regime::TooShort => "too-short",
        }
    }
}

impl std::fmt::Display for Regime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Regime {
    /// Every regime, in the order figures list them.
    pub const ALL: [Regime; 6] = [
        Regime::Periodic,
        Regime::QuasiPeriodic,
        Regime::Chaotic,
        Regime::Irregular,
        Regime::Undetermined,
        Regime::TooShort,
    ];
}

impl std::str::FromStr for Regime {
    type Err = String;

    /// Reads a name written by [`Regime::as_str`] (surrounding blanks ignored).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        if t == "stochastic" {
            return Ok(Regime::Irregular); // the name before issue 39
        }
        Regime::ALL
            .into_iter()
            .find(|r| r.as_str() == t)
            .ok_or_else(|| {
                format!(
                    "unknown regime {t:?}: expected one of {}",
                    Regime::ALL.map(Regime::as_str).join(", ")
                )
            })
    }
}

/// Returns the smallest p ≤ `max_period` with max_n |s_{n+p} − s_n| ≤ `rel_tol`·(max − min)
/// over the series, or `None`.
///
/// # Formula
/// Exact recurrence s_{n+p} = s_n of a period-p orbit sampled at an integer number of samples
/// per period (maps; flows strobed or sampled commensurately), up to a tolerance relative to the
/// range.
///
/// # Units
/// Samples.
///
/// # Pitfalls
/// Feed the steady state: one transient sample breaks the recurrence. Flows sampled with a
/// non-integer number of samples per period never recur exactly; use
/// [`harmonic_fundamental`]. A constant series returns `None`.
pub fn recurrence_period(x: &[f64], max_period: usize, rel_tol: f64) -> Option<usize> {
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    let range = hi - lo;
    if range.is_nan() || range <= 0.0 {
        return None;
    }
    let tol = rel_tol * range;
    let max_p = max_period.min(x.len() / 3);
    (1..=max_p).find(|&p| x.iter().zip(&x[p..]).all(|(a, b)| (b - a).abs() <= tol))
}

/// Returns the fundamental frequency f₀ of which every line is a harmonic, or `None`.
///
/// # Formula
/// With f_s the strongest line, try f₀ = f_s/k for k = 1..=`max_subharmonic` (period-k adds
/// f/k sub-harmonics, SPEC §4) and accept the first for which every line satisfies
/// |f − round(f/f₀)·f₀| ≤ `tol` and f₀ ≥ `min_f0`. For lines at f, √2 f (a torus) no k fits.
///
/// # Units
/// Those of the lines' frequencies; `tol` and `min_f0` in the same unit (use a fraction of
/// the bin width for `tol`, and several bin widths for `min_f0` so that dense harmonics cannot
/// fit any line set).
pub fn harmonic_fundamental(
    lines: &[SpectralLine],
    max_subharmonic: usize,
    tol: f64,
    min_f0: f64,
) -> Option<f64> {
    let strongest = lines
        .iter()
        .max_by(|a, b| a.peak_power.total_cmp(&b.peak_power))?;
    (1..=max_subharmonic.max(1)).find_map(|k| {
        let f0 = strongest.frequency / k as f64;
        if f0 < min_f0 || f0 <= 0.0 {
            return None;
        }
        let fits = lines.iter().all(|l| {
            let h = (l.frequency / f0).round().max(1.0);
            (l.frequency - h * f0).abs() <= tol
        });
        fits.then_some(f0)
    })
}

/// Everything the classifier looks at; each field is `None` when its estimator could not run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Evidence {
    /// Exact recurrence period in samples ([`recurrence_period`]).
    pub recurrence_period_samples: Option<usize>,
    /// Period 1/f₀ in samples when every spectral line is a harmonic of f₀.
    pub harmonic_period_samples: Option<f64>,
    /// Number of spectral lines.
    pub line_count: usize,
    /// Fraction of the power in the lines ([`crate::analysis::spectrum::line_power_fraction`]).
    pub line_power_fraction: f64,
    /// Stroboscopic section (with a forcing frequency), of the steady state.
    pub section: Option<SectionSummary>,
    /// Forcing period in samples (with a forcing frequency).
    pub forcing_period_samples: Option<f64>,
    /// Kantz exponent per sample.
    pub mle_per_sample: Option<f64>,
    /// Standard error of the Kantz exponent per sample.
    pub mle_stderr_per_sample: Option<f64>,
    /// Whether a surrogate test rejected the linear-stochastic null hypothesis (nonlinear
    /// determinism), when it ran.
    pub surrogate_rejects: Option<bool>,
    /// p-value of that surrogate test.
    pub surrogate_p: Option<f64>,
    /// Whether Kantz's curve had a linear scaling region (R² ≥ 0.99 over ≥ 5 points).
    pub kantz_linear: bool,
    /// Growth of S over the fitted region, slope × (end − start), in e-folds.
    pub kantz_growth: Option<f64>,
    /// Gottwald–Melbourne K.
    pub zero_one_k: Option<f64>,
    /// Whether false nearest neighbours vanished (fraction ≤ threshold) at some m ≤ m_max: the
    /// data are low-dimensional deterministic.
    pub fnn_converged: Option<bool>,
}

/// Thresholds of [`classify`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RegimeThresholds {
    /// Lines must carry at least this fraction of the power for a line spectrum (default 0.95).
    pub line_fraction: f64,
    /// K above this is irregular (default 0.5, Gottwald & Melbourne's threshold).
    pub zero_one: f64,
    /// Kantz's scaling region must grow by at least this many e-folds (default 0.5: between
    /// the noise floor and saturation, noisy flows leave a short region).
    pub min_growth: f64,
    /// Largest period reported in forcing periods (default 64); periods in samples (no forcing)
    /// are not limited.
    pub max_period: usize,
}

impl Default for RegimeThresholds {
    fn default() -> Self {
        RegimeThresholds {
            line_fraction: 0.95,
            zero_one: 0.5,
            min_growth: 0.5,
            max_period: 64,
        }
    }
}

/// A verdict with its period, its qualifiers and the rule that decided it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// The regime.
    pub regime: Regime,
    /// Period: in forcing periods when a forcing period is known, else in samples; `None`
    /// unless periodic.
    pub period: Option<f64>,
    /// The rule that fired, in words.
    pub reason: String,
    /// Qualifier: the motion relative to the container follows the forcing (Λ_p ≥
    /// [`LOCKED_FRACTION_MIN`]) although the verdict is not periodic ("chaotic, phase-locked
    /// to the forcing").
    pub phase_locked: Option<PhaseLock>,
    /// Qualifier of a chaotic or irregular verdict: how many degrees of freedom drive the
    /// section ([`crate::analysis::section_dimension`]).
    pub dimension: Option<ChaosDimension>,
}

impl Verdict {
    /// A verdict without qualifiers.
    pub fn new(regime: Regime, period: Option<f64>, reason: String) -> Verdict {
        Verdict {
            regime,
            period,
            reason,
            phase_locked: None,
            dimension: None,
        }
    }

    /// The verdict in words with its qualifiers, e.g. "periodic-3" or "chaotic; phase-locked
    /// to the forcing (Λ₁ = 0.985); high-dimensional" (semicolons: the words are a CSV cell).
    pub fn label(&self) -> String {
        label(
            self.regime,
            self.period,
            self.phase_locked.as_ref(),
            self.dimension.as_ref(),
        )
    }
}

/// The words of a verdict: regime (periodic-n with its period), then the phase-lock and
/// dimension qualifiers.
pub fn label(
    regime: Regime,
    period: Option<f64>,
    lock: Option<&PhaseLock>,
    dimension: Option<&ChaosDimension>,
) -> String {
    let mut s = match (regime, period) {
        (Regime::Periodic, Some(p)) => format!("periodic-{p}"),
        (Regime::Irregular, _) => "irregular (noise-like)".to_string(),
        _ => regime.as_str().to_string(),
    };
    if let Some(l) = lock {
        s.push_str(&format!(
            "; phase-locked to the forcing (Λ{} = {:.3})",
            subscript(l.periods),
            l.locked_fraction
        ));
    }
    if let Some(d) = dimension {
        s.push_str("; ");
        s.push_str(d.as_str());
    }
    s
}

/// A small positive integer in Unicode subscript digits.
fn subscript(n: usize) -> String {
    n.to_string()
        .chars()
        .map(|c| {
            c.to_digit(10)
                .and_then(|d| char::from_u32(0x2080 + d))
                .unwrap_or(c)
        })
        .collect()
}

/// Returns the regime of a series from its [`Evidence`].
///
/// # Formula
/// Rules, first match wins:
/// 1. Periodic: the section is n distinct points (period n forcing periods); without a
///    section, an exact recurrence p (replaced by the spectral period 1/f₀ when p is an
///    integer multiple of it), or a line spectrum (≥ `line_fraction` of the power) whose
///    lines are all harmonics of f₀ (period 1/f₀ samples).
/// 2. Quasi-periodic: the section is a closed curve, or a line spectrum of ≥ 2 lines that is
///    not harmonic,
///    with K < `zero_one` (when available).
/// 3. Chaotic: K > `zero_one`, a Kantz scaling region growing ≥ `min_growth` e-folds with a
///    positive slope, and FNN converged (when available).
/// 4. Irregular (noise-like): K > `zero_one` and (Kantz computed without a scaling region, or FNN not
///    converged).
/// 5. Otherwise undetermined.
///
/// # Parameters
/// See [`RegimeThresholds`].
///
/// # References
/// G. A. Gottwald, I. Melbourne, SIAM J. Appl. Dyn. Syst. 8, 129–145 (2009); H. Kantz, Phys.
/// Lett. A 185, 77–87 (1994); M. B. Kennel, R. Brown, H. D. I. Abarbanel, Phys. Rev. A 45,
/// 3403–3411 (1992).
pub fn classify(e: &Evidence, t: &RegimeThresholds) -> Verdict {
    let verdict = Verdict::new;
    let line_spectrum = e.line_count > 0 && e.line_power_fraction >= t.line_fraction;
    let k_regular = e.zero_one_k.is_none_or(|k| k < t.zero_one);
    let k_irregular = e.zero_one_k.is_some_and(|k| k > t.zero_one);
    let in_forcing = |samples: f64| match e.forcing_period_samples {
        Some(tf) => samples / tf,
        None => samples,
    };
    // 1. Periodic.
    let section_shape = e.section.as_ref().map(|s| s.shape);
    if let Some(SectionShape::Points(n)) = section_shape {
        if n <= t.max_period {
            return verdict(
                Regime::Periodic,
                Some(n as f64),
                format!("the stroboscopic section is {n} distinct point(s)"),
            );
        }
    }
    let section_usable = matches!(
        section_shape,
        Some(SectionShape::Points(_) | SectionShape::ClosedCurve | SectionShape::Cloud)
    );
    if !section_usable {
        let limit = match e.forcing_period_samples {
            Some(_) => t.max_period as f64 + 0.5,
            None => f64::INFINITY,
        };
        if let Some(p) = e.recurrence_period_samples {
            // The recurrence may be a multiple of the true period when the samples per period
            // are not an integer (37.3 samples: exact recurrence after 373): prefer the
            // spectral period when p is an integer multiple of it.
            let p = match e.harmonic_period_samples {
                Some(h)
                    if h < p as f64 - 0.5 && {
                        let ratio = p as f64 / h;
                        (ratio - ratio.round()).abs() < 0.01
                    } =>
                {
                    h
                }
                _ => p as f64,
            };
            let period = in_forcing(p);
            if period <= limit {
                return verdict(
                    Regime::Periodic,
                    Some(round_if_close(period)),
                    format!("the series repeats every {p} samples"),
                );
            }
        }
    }
    // 2. Chaotic: a positive exponent over a linear scaling region of ≥ min_growth e-folds,
    //    resolved against its error bar, from data that are deterministic (the surrogate test
    //    rejects linear noise; without one, FNN converged and the 0–1 test, when run, irregular).
    let scaling = e.kantz_linear
        && e.mle_per_sample.is_some_and(|l| l > 0.0)
        && e.kantz_growth.is_some_and(|g| g >= t.min_growth);
    let resolved = match (e.mle_per_sample, e.mle_stderr_per_sample) {
        (Some(l), Some(se)) => l > 2.0 * se,
        (Some(l), None) => l > 0.0,
        _ => false,
    };
    let deterministic = match e.surrogate_rejects {
        Some(r) => r,
        None => e.fnn_converged.unwrap_or(true) && !e.zero_one_k.is_some_and(|k| k < 0.1),
    };
    if scaling && resolved && deterministic {
        return verdict(
            Regime::Chaotic,
            None,
            format!(
                "Kantz exponent {:.4} ± {:.4} per sample over a linear region of {:.1} e-folds; {}",
                e.mle_per_sample.unwrap_or(f64::NAN),
                e.mle_stderr_per_sample.unwrap_or(f64::NAN),
                e.kantz_growth.unwrap_or(f64::NAN),
                match e.surrogate_rejects {
                    Some(_) => "surrogate data reject linear noise".to_string(),
                    None => format!(
                        "false nearest neighbours vanish (0-1 test K = {:.2})",
                        e.zero_one_k.unwrap_or(f64::NAN)
                    ),
                }
            ),
        );
    }
    // 3. Periodic with noise: harmonic lines hold most of the power, the rest is broadband.
    if !section_usable {
        if let Some(p) = e.harmonic_period_samples {
            let period = in_forcing(p);
            let limit = match e.forcing_period_samples {
                Some(_) => t.max_period as f64 + 0.5,
                None => f64::INFINITY,
            };
            if e.line_count > 0 && e.line_power_fraction >= 0.5 && period <= limit {
                return verdict(
                    Regime::Periodic,
                    Some(round_if_close(period)),
                    format!(
                        "all {} spectral lines are harmonics of 1/{p:.4} per sample and carry {:.1} % of the power; the rest is broadband noise without a positive exponent",
                        e.line_count,
                        100.0 * e.line_power_fraction
                    ),
                );
            }
        }
    }
    // 4. Quasi-periodic.
    if section_shape == Some(SectionShape::ClosedCurve) && k_regular {
        return verdict(
            Regime::QuasiPeriodic,
            None,
            "the stroboscopic section is a closed curve (invariant circle)".into(),
        );
    }
    if !section_usable
        && line_spectrum
        && e.line_count >= 2
        && e.harmonic_period_samples.is_none()
        && k_regular
        && !resolved
    {
        return verdict(
            Regime::QuasiPeriodic,
            None,
            format!(
                "{} spectral lines carry {:.1} % of the power but are not harmonics of one frequency, and no exponent is positive",
                e.line_count,
                100.0 * e.line_power_fraction
            ),
        );
    }
    // 5. Noise: no determinism, or irregular without divergence.
    if !deterministic || (k_irregular && !scaling) {
        let why = match e.surrogate_rejects {
            Some(false) => "surrogate data (linear Gaussian noise with the same spectrum and amplitudes) are not told apart",
            _ if !deterministic => "false nearest neighbours do not vanish (no low-dimensional determinism)",
            _ => "no exponential-divergence region in Kantz's curves",
        };
        return verdict(
            Regime::Irregular,
            None,
            format!("irregular (noise-like): {why}"),
        );
    }
    let mut conflicts = Vec::new();
    if scaling && !resolved {
        conflicts.push("the Kantz exponent is not resolved against its error bar");
    }
    if !scaling && e.mle_per_sample.is_some() {
        conflicts.push("Kantz's curves have no clear scaling region");
    }
    if line_spectrum {
        conflicts.push("the spectrum is made of lines");
    }
    verdict(
        Regime::Undetermined,
        None,
        if conflicts.is_empty() {
            "the indicators are missing".into()
        } else {
            format!("indicators conflict: {}", conflicts.join("; "))
        },
    )
}

/// A Lyapunov exponent with its standard error, per forcing period.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Exponent {
    /// λ per forcing period (natural log).
    pub per_period: f64,
    /// Standard error of λ per forcing period.
    pub stderr_per_period: f64,
}

/// Sign of an exponent, decided with its error bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ExponentSign {
    /// λ > max(3σ, `zero_band`): exponential divergence.
    Positive,
    /// λ < −max(3σ, `zero_band`): contraction.
    Negative,
    /// |λ| within the band: neutral (a torus) or unresolved.
    Zero,
}

impl Exponent {
    /// Sign with a 3σ error bar and a neutral band `zero_band` per period.
    pub fn sign(&self, zero_band: f64) -> ExponentSign {
        let band = (3.0 * self.stderr_per_period).max(zero_band);
        if self.per_period > band {
            ExponentSign::Positive
        } else if self.per_period < -band {
            ExponentSign::Negative
        } else {
            ExponentSign::Zero
        }
    }
}

pub use super::regime_forced::{
    classify_forced, ForcedEvidence, LOCKED_FRACTION_MIN, VERDICT_RULES,
};

/// Rounds to the nearest integer when within 0.1 % of it (periods of maps and strobed flows).
fn round_if_close(p: f64) -> f64 {
    let r = p.round();
    if r >= 1.0 && (p - r).abs() <= 1e-3 * r {
        r
    } else {
        p
    }
}

mod tests;
