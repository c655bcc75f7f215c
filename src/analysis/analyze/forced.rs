//! The forced-run path: a simulator's run judged from its exact stroboscopic section
//! ([`analyze_forced`]), and the section verdict the chain also gives a user's forced series
//! (section pattern, section exponent (4.1.7) per forcing period and per second, phase lock,
//! chaos dimension).

use super::evidence::spectral_evidence;
use super::report::{empty_report, AnalysisReport, AnalyzeOptions, MIN_SAMPLES};
use crate::analysis::phase_lock::{phase_lock, PhaseLock};
use crate::analysis::regime::{
    classify_forced, Evidence, Exponent, ForcedEvidence, LOCKED_FRACTION_MIN,
};
use crate::analysis::replica_test::ReplicaReport;
use crate::analysis::section::{analyze_section, normalise, SectionAnalysis, SectionOptions};
use crate::analysis::section_dimension::section_dimension;
use crate::analysis::section_lyapunov::{section_lyapunov, SectionLyapunovOptions};
use crate::error::AnalysisError;

/// A forced run as the simulators deliver it: the steady-state series of the observed
/// coordinate and the exact stroboscopic section of the state.
#[derive(Debug, Clone, Copy)]
pub struct ForcedRun<'a> {
    /// Steady-state series of the observed coordinate (e.g. grain z, m), evenly sampled; may be
    /// empty (then no spectrum is reported).
    pub series: &'a [f64],
    /// Sampling interval of `series` (s).
    pub dt_s: f64,
    /// Forcing frequency f (Hz).
    pub forcing_hz: f64,
    /// Exact section states s(kT), one row per forcing period of the steady window, in order.
    pub section: &'a [Vec<f64>],
    /// Extent of each section coordinate along the continuous trajectory (units of the rows).
    pub scales: &'a [f64],
    /// The exponent computed from the model's equations, when the simulator has one.
    pub model_exponent: Option<Exponent>,
    /// The observed coordinate relative to the container (e.g. grain z − box z, m), sampled as
    /// `series`; its synchronous average measures the noise level of a phase-locked motion
    /// (see [`crate::analysis::phase_lock`]). Empty: `series` is used.
    pub in_box_series: &'a [f64],
    /// The simulator's two-replica test ([`crate::analysis::replica_test`]), when it ran: it
    /// decides whether the motion is sensitive.
    pub replica: Option<&'a ReplicaReport>,
    /// The simulator holds a two-replica test it runs only if the verdict needs it
    /// ([`ForcedEvidence::replica_deferred`]).
    pub replica_deferred: bool,
}

/// Returns the regime of a forced run judged from its exact stroboscopic section first, with
/// the data exponent of the section and, when given, the model's exponent beside it.
///
/// # Formula
/// 1. Section pattern ([`analyze_section`]): periodic-n (exact or with noise), an invariant
///    circle, or a cloud; fewer than 48 points → `too-short`.
/// 2. Data exponent ([`section_lyapunov`], (4.1.7) on the section states) unless the section is
///    a finite set of points.
/// 3. [`classify_forced`]: the model exponent decides chaos when known; otherwise the data
///    exponent with the section's determinism ratio.
/// 4. Spectrum of the series (lines, line power) as supporting evidence only.
///
/// # Units
/// Exponents per second (`*_per_s`) and per forcing period inside `section_exponent`.
///
/// # Errors
/// Bad section rows or scales (see [`analyze_section`]); `forcing_hz` or `dt_s` not positive.
pub fn analyze_forced(
    run: &ForcedRun<'_>,
    opts: &AnalyzeOptions,
) -> Result<AnalysisReport, AnalysisError> {
    if !(run.forcing_hz.is_finite() && run.forcing_hz > 0.0) {
        return Err(AnalysisError::bad(
            "forcing_hz",
            run.forcing_hz,
            "must be > 0 Hz",
        ));
    }
    if !(run.dt_s.is_finite() && run.dt_s > 0.0) {
        return Err(AnalysisError::bad("dt", run.dt_s, "must be > 0 s"));
    }
    let mut report = empty_report(run.series.len(), Some(run.dt_s));
    report.series_dt_s = Some(run.dt_s);
    let mut evidence = Evidence {
        forcing_period_samples: Some(1.0 / (run.forcing_hz * run.dt_s)),
        ..Default::default()
    };
    let x = run.series;
    if x.len() >= MIN_SAMPLES && x.iter().all(|v| v.is_finite()) {
        let (lo, hi) = crate::analysis::min_max(x);
        let range = hi - lo;
        if range > 0.0 {
            let z: Vec<f64> = x.iter().map(|v| (v - lo) / range).collect();
            let sopts = AnalyzeOptions {
                dt_s: Some(run.dt_s),
                ..*opts
            };
            spectral_evidence(&z, &sopts, range, &mut evidence, &mut report)?;
        }
    }
    let sec = analyze_section(run.section, run.scales, &SectionOptions::default())?;
    let lock_series = if run.in_box_series.is_empty() {
        run.series
    } else {
        run.in_box_series
    };
    report.phase_lock = shortest_lock(lock_series, run.dt_s, run.forcing_hz);
    section_verdict(
        &mut report,
        sec,
        SectionInput {
            points: run.section,
            scales: run.scales,
            forcing_hz: run.forcing_hz,
            model: run.model_exponent,
            replica: run.replica,
            replica_deferred: run.replica_deferred,
            source: "exact",
        },
    );
    report.evidence = evidence;
    Ok(report)
}

/// Longest window tried by [`shortest_lock`], in forcing periods.
const LOCK_MAX_PERIODS: usize = 4;

/// The synchronous average over the shortest window p ≤ [`LOCK_MAX_PERIODS`] forcing periods
/// whose locked fraction reaches [`LOCKED_FRACTION_MIN`], else the one-period average; `None`
/// when the series is too short (or not finite) for one.
fn shortest_lock(x: &[f64], dt_s: f64, forcing_hz: f64) -> Option<PhaseLock> {
    let one = phase_lock(x, dt_s, forcing_hz, 1).ok()?;
    if one.locked_fraction >= LOCKED_FRACTION_MIN {
        return Some(one);
    }
    (2..=LOCK_MAX_PERIODS)
        .filter_map(|p| phase_lock(x, dt_s, forcing_hz, p).ok())
        .find(|l| l.locked_fraction >= LOCKED_FRACTION_MIN)
        .or(Some(one))
}

/// What [`section_verdict`] judges besides the section's pattern.
pub(super) struct SectionInput<'a> {
    pub(super) points: &'a [Vec<f64>],
    pub(super) scales: &'a [f64],
    pub(super) forcing_hz: f64,
    pub(super) model: Option<Exponent>,
    pub(super) replica: Option<&'a ReplicaReport>,
    pub(super) replica_deferred: bool,
    pub(super) source: &'static str,
}

/// Section exponent, classification and report fields from a section analysis.
pub(super) fn section_verdict(
    report: &mut AnalysisReport,
    sec: SectionAnalysis,
    input: SectionInput<'_>,
) {
    use crate::analysis::section::SectionPattern as P;
    let SectionInput {
        points,
        scales,
        forcing_hz,
        model,
        replica,
        replica_deferred,
        source,
    } = input;
    let data = match sec.pattern {
        P::Irregular | P::QuasiPeriodic { .. } => {
            match section_lyapunov(points, scales, &SectionLyapunovOptions::default()) {
                Ok(l) => Some(l),
                Err(e) => {
                    report
                        .notes
                        .push(format!("section exponent not computed: {e}"));
                    None
                }
            }
        }
        _ => None,
    };
    let dimension = match sec.pattern {
        P::Irregular => normalise(points, scales)
            .ok()
            .and_then(|u| section_dimension(&u)),
        _ => None,
    };
    let data_exp = data.as_ref().map(|l| Exponent {
        per_period: l.per_period,
        stderr_per_period: l.stderr_per_period,
    });
    let verdict = classify_forced(&ForcedEvidence {
        section: &sec,
        data_exponent: data_exp,
        model_exponent: model,
        zero_band: 0.01,
        phase_lock: report.phase_lock,
        replica,
        replica_deferred,
        dimension,
    });
    report.phase_locked = verdict.phase_locked.is_some();
    report.chaos_dimension = verdict.dimension;
    report.regime = verdict.regime;
    report.period = verdict.period;
    report.reason = verdict.reason;
    report.poincare_section_points = Some(sec.n_points);
    report.poincare_distinct_points = match sec.pattern {
        P::Periodic { period, .. } => Some(period),
        _ => None,
    };
    report.poincare_shape = Some(
        match sec.pattern {
            P::Periodic { .. } => "points",
            P::QuasiPeriodic { .. } => "closed-curve",
            P::Irregular => "cloud",
            P::TooShort { .. } => "too-few",
        }
        .to_string(),
    );
    report.data_mle_per_s = data_exp.map(|d| d.per_period * forcing_hz);
    report.data_mle_stderr_per_s = data_exp.map(|d| d.stderr_per_period * forcing_hz);
    report.model_mle_per_s = model.map(|m| m.per_period * forcing_hz);
    report.model_mle_stderr_per_s = model.map(|m| m.stderr_per_period * forcing_hz);
    report.mle_per_time = report.data_mle_per_s;
    if let (Some(l), Some(dt)) = (report.mle_per_time, report.series_dt_s) {
        report.mle_per_sample = Some(l * dt);
    }
    report.section_source = Some(source.to_string());
    report.section = Some(sec);
    report.section_exponent = data;
}
