//! The whole chain on a scalar series ([`analyze_series`]): spectrum → recurrence → lag →
//! FNN dimension (4.1.4) → Kantz (4.1.7) → stroboscopic section → 0–1 test → verdict.

use super::evidence::{
    choose_lag, distinct_values, kantz_evidence, return_map_value, spectral_evidence,
    surrogate_evidence,
};
use super::forced::{section_verdict, SectionInput};
use super::report::{empty_report, AnalysisReport, AnalyzeOptions, MAX_ABS_VALUE, MIN_SAMPLES};
use crate::analysis::false_nearest_neighbors::{
    false_nearest_neighbors, suggested_dimension, FnnOptions,
};
use crate::analysis::poincare::{
    classify_section, period_in_samples, stroboscopic_section, ClusterOptions, SecondCoordinate,
    SectionShape, StrobeOptions,
};
use crate::analysis::regime::{classify, recurrence_period, Evidence, Regime};
use crate::analysis::section::{analyze_section, SectionOptions};
use crate::analysis::spectrum::check_finite;
use crate::analysis::zero_one_test::{zero_one_test, ZeroOneOptions};
use crate::error::AnalysisError;

/// Runs the whole analysis chain on a series and classifies its regime.
///
/// # Formula
/// 1. Spectrum (Hann, power per bin) and lines ([`spectral_lines`](crate::analysis::spectrum::spectral_lines), 20 dB over the local median);
///    harmonic fundamental f₀ with tolerance 0.3 bin and f₀ ≥ 8 bins.
/// 2. Exact recurrence ([`recurrence_period`], tolerance 1e−6 of the range, on the last half).
///    With a recurrence, or fewer than max(16, N/20) distinct values, steps 4–5 are skipped
///    (exact duplicates have no neighbours to follow).
/// 3. Lag τ: first minimum of I(τ) (4.1.5), 16 bins, if it comes before I(τ) falls to the
///    estimator floor max(3(b−1)²/(2N), 0.05 I(0)) — else τ = 1 (maps, noise); without a
///    minimum: first τ with I(τ) ≤ I(0)/e, else 1.
/// 4. Dimension: FNN (4.1.4, ratio 10, Theiler window τ), first m with fraction ≤ 0.05.
/// 5. Kantz (4.1.7) with m and τ: an ε-scan upward from the noise floor, the series
///    decimated by a factor chosen from τ, the scaling region of every curve after the first
///    delay and before saturation ([`kantz_scan`](crate::analysis::kantz_scan::kantz_scan)); λ = median slope with an error bar.
///    Without a forcing frequency, nonlinear determinism from IAAFT surrogates (prediction
///    error, rank test, end-matched segment; see `surrogate_evidence`).
/// 6. With a forcing frequency: section (s(t_k), s(t_k + τ)) with cubic interpolation; distinct
///    points at 0.1 % of the range; closed-curve score.
/// 7. 0–1 test on the section's first coordinate (≥ 200 points), else on the series
///    subsampled every τ samples; the last 4000 samples, 100 values of c.
///
/// # Units
/// `dt_s` s, `forcing_hz` Hz; exponents per sample and per second.
///
/// # Parameters
/// See [`AnalyzeOptions`].
///
/// # Errors
/// Non-finite samples; fewer than [`MIN_SAMPLES`] samples; `forcing_hz` without `dt_s`, or a
/// forcing period shorter than 2 samples; `dt_s` ≤ 0; |x| > [`MAX_ABS_VALUE`]. A constant series is not an error: it
/// returns `undetermined` with a note.
///
/// # Pitfalls
/// Feed the steady state: transients blur recurrences and sections (the section tolerates 2 %
/// transient points). Cost grows as N log N (spectrum, kd-trees) plus the fixed-size 0–1 test;
/// measured 0.33 s for 10⁴ and 1.4 s for 10⁵ Lorenz samples (bench `analysis/analyze`).
///
/// # References
/// See the estimators: Fraser & Swinney (1986), Kennel et al. (1992), Kantz (1994),
/// Gottwald & Melbourne (2009).
///
/// # Example
/// ```
/// use pdamp::analysis::analyze::{analyze_series, AnalyzeOptions};
/// use pdamp::analysis::regime::Regime;
/// let x: Vec<f64> = (0..2000).map(|n| [0.3, 0.8][n % 2]).collect();
/// let r = analyze_series(&x, &AnalyzeOptions::default()).unwrap();
/// assert_eq!((r.regime, r.period), (Regime::Periodic, Some(2.0)));
/// ```
pub fn analyze_series(x: &[f64], opts: &AnalyzeOptions) -> Result<AnalysisReport, AnalysisError> {
    check_finite(x, MIN_SAMPLES, "the analysis chain")?;
    let forcing_period = validate_options(opts)?;
    let x = &x[x.len().saturating_sub(opts.max_samples.max(MIN_SAMPLES))..];
    let n = x.len();
    let mut notes = Vec::new();
    let mut evidence = Evidence {
        forcing_period_samples: forcing_period,
        ..Default::default()
    };
    let (lo, hi) = crate::analysis::min_max(x);
    if hi.abs().max(lo.abs()) > MAX_ABS_VALUE {
        return Err(AnalysisError::bad(
            "series",
            format!("values up to {:.3e}", hi.abs().max(lo.abs())),
            format!("|x| must stay below {MAX_ABS_VALUE:e} so that powers are finite; rescale the series (change units)"),
        ));
    }
    let range = hi - lo;
    let mut report = empty_report(n, opts.dt_s);
    if range <= 1e-12 * hi.abs().max(lo.abs()) || range.is_nan() || range == 0.0 {
        report.reason = "the series is constant: nothing to analyse".into();
        report
            .notes
            .push("constant series (a fixed point, or a sensor at rest)".into());
        report.evidence = evidence;
        return Ok(report);
    }

    // Every estimator is scale-invariant: work on z = (x − min)/range in [0, 1] (robust for
    // tiny and offset data), and convert the few data-unit outputs back (powers × range², ε × range).
    let z: Vec<f64> = x.iter().map(|v| (v - lo) / range).collect();
    let x = &z[..];
    spectral_evidence(x, opts, range, &mut evidence, &mut report)?;
    let tail = &x[n / 2..];
    evidence.recurrence_period_samples = recurrence_period(tail, 2000.min(tail.len() / 3), 1e-6);

    let lag = choose_lag(x, opts, &mut notes);
    report.lag = Some(lag);

    let distinct = distinct_values(x);
    if let Some(p) = evidence.recurrence_period_samples {
        // A finite set of states: every delay vector is an exact duplicate of others, so
        // nearest neighbours (FNN) and divergence (Kantz) are undefined — and costly on
        // duplicates. The orbit is periodic; skip them.
        notes.push(format!(
            "exact recurrence every {p} samples: FNN and Kantz skipped (a finite set of states has no neighbours to follow)"
        ));
    } else if distinct < (n / 20).max(16) {
        // Quantised or piecewise-constant data: most delay vectors are exact duplicates, which
        // nearest-neighbour estimators skip one by one (slow) and which carry no divergence.
        notes.push(format!(
            "the series takes only {distinct} distinct values: FNN and Kantz skipped (quantised or piecewise-constant data)"
        ));
    } else {
        // FNN on the tail.
        let fnn_x = &x[n.saturating_sub(opts.max_fnn_samples.max(MIN_SAMPLES))..];
        let fnn_opts = FnnOptions {
            m_min: 1,
            m_max: opts.max_dim,
            tau: lag,
            ..FnnOptions::default()
        };
        let dim = match false_nearest_neighbors(fnn_x, &fnn_opts) {
            Ok(points) => {
                report.fnn_fractions = points.iter().map(|p| (p.m, p.fraction)).collect();
                let found = suggested_dimension(&points, opts.fnn_threshold);
                evidence.fnn_converged = Some(found.is_some());
                found.unwrap_or_else(|| {
                    notes.push(format!(
                        "FNN fraction stays above {} up to m = {}: using m = {}",
                        opts.fnn_threshold, opts.max_dim, opts.max_dim
                    ));
                    opts.max_dim
                })
            }
            Err(e) => {
                notes.push(format!(
                    "false nearest neighbours not computed: {e}; using m = 2"
                ));
                2
            }
        };
        report.embedding_dim = Some(dim);

        kantz_evidence(x, lag, dim, opts, &mut evidence, &mut report, &mut notes);
        if opts.forcing_hz.is_none() {
            surrogate_evidence(x, lag, dim, opts, &mut evidence, &mut notes);
        }
        if let Some(f) = report.kantz_fit.as_mut() {
            f.eps *= range;
        }
    }

    // Stroboscopic section.
    let mut strobe_points: Option<Vec<f64>> = None;
    let mut forced_section: Option<Vec<Vec<f64>>> = None;
    if let Some(t_per) = forcing_period {
        match stroboscopic_section(
            x,
            SecondCoordinate::Delay(lag as f64),
            &StrobeOptions::new(t_per),
        ) {
            Ok(sec) => {
                let summary = classify_section(&sec.points, 1.0, &ClusterOptions::default());
                report.poincare_section_points = Some(summary.n_points);
                report.poincare_distinct_points = summary.n_distinct;
                report.closed_curve_score = Some(summary.closed_curve_score);
                report.poincare_shape = Some(
                    match summary.shape {
                        SectionShape::Points(_) => "points",
                        SectionShape::ClosedCurve => "closed-curve",
                        SectionShape::Cloud => "cloud",
                        SectionShape::TooFew => "too-few",
                    }
                    .to_string(),
                );
                if summary.shape == SectionShape::TooFew {
                    notes.push(format!(
                        "only {} section points: the section is not used for the verdict",
                        summary.n_points
                    ));
                }
                strobe_points = Some(sec.points.iter().map(|p| p[0]).collect());
                forced_section = Some(sec.points.iter().map(|p| p.to_vec()).collect());
                evidence.section = Some(summary);
            }
            Err(e) => notes.push(format!("Poincaré section not computed: {e}")),
        }
    }

    // 0–1 test on one sample per forcing period, else one per lag.
    let zo_input: Vec<f64> = match strobe_points {
        Some(p) if p.len() >= 200 => p,
        _ => x.iter().step_by(lag.max(1)).copied().collect(),
    };
    match zero_one_test(
        &zo_input,
        &ZeroOneOptions {
            seed: opts.seed,
            ..Default::default()
        },
    ) {
        Ok(r) => {
            evidence.zero_one_k = Some(r.k);
            report.zero_one_k = Some(r.k);
            report.zero_one_samples = Some(r.n_samples);
        }
        Err(e) => notes.push(format!("0-1 test not computed: {e}")),
    }

    report.notes = notes;
    match (&forced_section, forcing_period) {
        (Some(points), Some(_)) => {
            // a user's own series of a forced system: judged from its section first (cubic
            // interpolation of the given samples in delay coordinates, so exact to ~1e-4)
            let sopts = SectionOptions {
                exact_tol: 1e-4,
                ..SectionOptions::default()
            };
            let forcing_hz = opts.forcing_hz.unwrap_or(1.0);
            match analyze_section(points, &[1.0, 1.0], &sopts) {
                Ok(sec) => {
                    section_verdict(
                        &mut report,
                        sec,
                        SectionInput {
                            points,
                            scales: &[1.0, 1.0],
                            forcing_hz,
                            model: None,
                            replica: None,
                            replica_deferred: false,
                            source: "interpolated",
                        },
                    );
                    // the per-sample exponent of the report stays the series' Kantz estimate
                    if let Some(l) = evidence.mle_per_sample {
                        report.mle_per_sample = Some(l);
                        report.mle_per_time = opts.dt_s.map(|dt| l / dt);
                    }
                }
                Err(e) => {
                    report.notes.push(format!("section not analysed: {e}"));
                    let verdict = classify(&evidence, &opts.thresholds);
                    report.regime = verdict.regime;
                    report.period = verdict.period;
                    report.reason = verdict.reason;
                }
            }
        }
        _ => {
            let verdict = classify(&evidence, &opts.thresholds);
            report.regime = verdict.regime;
            report.period = verdict.period;
            report.reason = verdict.reason;
            if report.regime == Regime::Chaotic {
                return_map_value(x, opts, &mut report);
            }
        }
    }
    report.evidence = evidence;
    tracing::debug!(
        "analysis of {} samples: lag {:?}, m {:?}, verdict {} ({})",
        x.len(),
        report.lag,
        report.embedding_dim,
        report.verdict(),
        report.reason
    );
    Ok(report)
}

/// Checks the options; returns the forcing period in samples, if any.
fn validate_options(opts: &AnalyzeOptions) -> Result<Option<f64>, AnalysisError> {
    if let Some(dt) = opts.dt_s {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(AnalysisError::bad(
                "dt",
                dt,
                "the sampling interval must be > 0 seconds",
            ));
        }
    }
    if opts.max_dim == 0 || opts.max_dim > 12 {
        return Err(AnalysisError::bad("max_dim", opts.max_dim, "use 1..=12"));
    }
    match (opts.forcing_hz, opts.dt_s) {
        (Some(f), Some(dt)) => period_in_samples(f, dt).map(Some),
        (Some(f), None) => Err(AnalysisError::bad(
            "forcing-hz",
            f,
            "a forcing frequency needs the sampling interval: give --dt (seconds)",
        )),
        (None, _) => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_inputs_are_errors_not_panics() {
        let o = AnalyzeOptions::default();
        assert!(matches!(
            analyze_series(&[1.0; 10], &o),
            Err(AnalysisError::TooShort(_))
        ));
        let mut x = vec![0.5; 100];
        x[7] = f64::NAN;
        assert!(matches!(
            analyze_series(&x, &o),
            Err(AnalysisError::NonFinite { index: 7 })
        ));
        let forcing_without_dt = AnalyzeOptions {
            forcing_hz: Some(10.0),
            ..o
        };
        let err = analyze_series(&[0.0, 1.0].repeat(50), &forcing_without_dt).unwrap_err();
        assert!(err.to_string().contains("dt"));
    }

    #[test]
    fn constant_series_is_undetermined() {
        let r = analyze_series(&[2.5; 500], &AnalyzeOptions::default()).unwrap();
        assert_eq!(r.regime, Regime::Undetermined);
        assert!(r.period.is_none());
    }
}
