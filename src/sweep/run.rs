//! Simulation dispatch: one scene → one [`RunSummary`], whatever the damper model.

use crate::analysis::analyze::{analyze_forced, AnalysisReport, AnalyzeOptions, ForcedRun};
use crate::analysis::regime::{Exponent, Regime};
use crate::error::SimError;
use crate::impact::{ImpactWorld, ModelLyapunovOptions};
use crate::model::{RunOptions, RunSummary};
use crate::observe::{Observer, SteadyCollector, Tee};
use crate::scene::Scene;
use crate::setup::{Resolved, Setup};

/// Run one scene, sending samples to `obs`: resolves it once ([`Scene::resolve`], which
/// makes the `kind = "auto"` choice) and runs the simulator it resolves to
/// ([`crate::setup::simulate`]). The run's warnings are in the summary and also emitted
/// ([`emit_warnings`]).
///
/// # Errors
/// Scene errors naming the key; the model's own errors otherwise.
pub fn run_scene(
    scene: &Scene,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<RunSummary, SimError> {
    let s = crate::setup::simulate(&scene.resolve()?, obs, opts)?;
    emit_warnings(&s);
    Ok(s)
}

/// Emits a run's warnings ([`RunSummary::warnings`]) as `tracing` warnings, which the CLI
/// prints as `warning: …`: for the runners whose summaries do not come back to the CLI one
/// by one (a sweep's points, the studies).
pub fn emit_warnings(s: &RunSummary) {
    for w in &s.warnings {
        tracing::warn!("{w}");
    }
}

/// Run one scene and, if `analyze` is set, the nonlinear analysis of the steady-state grain
/// series (stored in `summary.analysis`, or the reason in `summary.analysis_error`).
/// `obs` receives the samples requested by `opts`; the steady-state series for the analysis is
/// collected alongside. The run's warnings are in the summary and also emitted
/// ([`emit_warnings`]).
///
/// # Errors
/// As [`run_scene`]. A failed analysis is not an error of the run.
pub fn run_with_analysis(
    scene: &Scene,
    obs: &mut dyn Observer,
    opts: &RunOptions,
    analyze: bool,
) -> Result<RunSummary, SimError> {
    let s = run_resolved(&scene.resolve()?, obs, opts, analyze)?;
    emit_warnings(&s);
    Ok(s)
}

/// [`run_with_analysis`] for a scene already resolved; the run's warnings are only in the
/// summary ([`RunSummary::warnings`]: `pdamp simulate` prints them).
///
/// # Errors
/// As [`run_scene`].
pub fn run_resolved(
    resolved: &Resolved,
    obs: &mut dyn Observer,
    opts: &RunOptions,
    analyze: bool,
) -> Result<RunSummary, SimError> {
    if !analyze {
        return crate::setup::simulate(resolved, obs, opts);
    }
    let scene = &resolved.scene;
    if scene.excitation.kind == crate::scene::DriveKind::Free {
        // a decaying motion has no steady state to classify: its figure is the envelope
        let mut s = crate::setup::simulate(resolved, obs, opts)?;
        s.analysis_error = Some(
            "a free decay has no steady state: no regime verdict (the decay envelope is in \
             `decay`, decay.csv)"
                .into(),
        );
        return Ok(s);
    }
    let steady = crate::setup::steady_series(scene);
    let mut collector = SteadyCollector::new(scene.analysis_start_s());
    // the analysis wants evenly spaced samples: use the coarser of the two clocks only when the
    // caller asked for none; otherwise decimate the caller's samples.
    let (run_opts, stride) = match opts.sample_interval_s {
        None => (steady, 1),
        Some(d) => {
            let want = steady.sample_interval_s.unwrap_or(d);
            (*opts, ((want / d).round() as usize).max(1))
        }
    };
    let mut decimator = Decimate {
        inner: &mut collector,
        stride,
        count: 0,
    };
    let mut tee = Tee {
        observers: vec![obs, &mut decimator],
    };
    let mut deferred = None;
    let (mut summary, model) = match &resolved.setup {
        // the impact model's exponent rides on the run itself (one simulation, not two)
        Setup::Impact(setup) if setup.particle.is_some() => {
            let (mut s, estimate) = ImpactWorld::new(setup)
                .run_with_model_lyapunov(&mut tee, &run_opts, &ModelLyapunovOptions::default())
                .map_err(crate::setup::keyed)?;
            if resolved.auto.is_some() {
                s.model = resolved.model_name(&s.model);
            }
            let model = model_exponent_of(estimate.map_err(crate::setup::keyed), &mut s);
            (s, model)
        }
        // a DEM run analysed for a verdict: the two-replica test's replica B is cloned at the
        // analysis start and stepped below only if the section is not n tight groups
        Setup::Dem(dem) => {
            let (s, d) =
                crate::setup::simulate_dem_for_verdict(resolved, dem, &mut tee, &run_opts)?;
            deferred = d;
            (s, None)
        }
        _ => {
            let mut s = crate::setup::simulate(resolved, &mut tee, &run_opts)?;
            let model = model_exponent(resolved, &mut s);
            (s, model)
        }
    };
    let f = scene.frequency_hz();
    analyze_into(&mut summary, &collector, f, model, deferred.is_some());
    if let Some(d) = deferred.filter(|_| replica_needed(&summary)) {
        summary.replica = Some(d.complete());
        analyze_into(&mut summary, &collector, f, model, false);
    }
    Ok(summary)
}

/// Whether a verdict judged without the two-replica test needs it: the section was analysed
/// and is not n tight groups (a tight section is periodic whatever the replicas do,
/// [`crate::analysis::regime_forced`]).
fn replica_needed(summary: &RunSummary) -> bool {
    summary
        .analysis
        .as_ref()
        .and_then(|a| a.section.as_ref())
        .is_some_and(|s| s.tight.is_none())
}

/// Runs the forced-system analysis ([`crate::analysis::analyze::analyze_forced`], SPEC §4) on
/// the run's exact stroboscopic section (grain and box position and velocity at t = kT) with
/// the collected steady-state grain series, and stores the report (or why it failed) in
/// `summary`.
///
/// The section coordinates are scaled by the extents of the continuous motion: positions by
/// the range of z(t) over the steady window, velocities by Ω times that range.
fn analyze_into(
    summary: &mut RunSummary,
    collector: &SteadyCollector,
    forcing_hz: f64,
    model_exponent: Option<Exponent>,
    replica_deferred: bool,
) {
    let (section, scales) = exact_section(summary, collector, forcing_hz);
    let in_box: Vec<f64> = collector
        .grain_z_m
        .iter()
        .zip(&collector.box_z_m)
        .map(|(g, b)| g - b)
        .collect();
    let run = ForcedRun {
        series: &collector.grain_z_m,
        dt_s: collector.dt_s().unwrap_or(1.0 / (64.0 * forcing_hz)),
        forcing_hz,
        section: &section,
        scales: &scales,
        model_exponent,
        in_box_series: &in_box,
        replica: summary.replica.as_ref(),
        replica_deferred,
    };
    match analyze_forced(&run, &AnalyzeOptions::default()) {
        Ok(report) => {
            // the replica test as the verdict judged it: at the same phase of the section's
            // cycle when the section is n tight groups
            let tight = report.section.as_ref().and_then(|s| s.tight.as_ref());
            if let (Some(g), Some(r)) = (tight, summary.replica.as_mut()) {
                *r = r.at_period(g.period);
            }
            summary.analysis = Some(with_scene_keys(report));
        }
        Err(e) => summary.analysis_error = Some(e.to_string()),
    }
}

/// The verdict's advice in the scene's terms: a too-short window names the keys that
/// lengthen it (the analysis itself knows records, not scene files).
fn with_scene_keys(mut report: AnalysisReport) -> AnalysisReport {
    use crate::scene::keys::{RUN_ANALYSIS_FRACTION, RUN_DURATION, RUN_PERIODS};
    if report.regime == Regime::TooShort {
        report.reason.push_str(&format!(
            " (raise {RUN_PERIODS} or {RUN_DURATION}, or {RUN_ANALYSIS_FRACTION})"
        ));
    }
    report
}

/// The impact model's own exponent (tangent dynamics with saltation matrices,
/// [`crate::impact::lyapunov`]) over the analysis window; `None` for other models. A failure
/// is noted in `summary.analysis_error` and does not stop the run.
fn model_exponent(resolved: &Resolved, summary: &mut RunSummary) -> Option<Exponent> {
    let Setup::Impact(setup) = &resolved.setup else {
        return None;
    };
    setup.particle?;
    // the exponent over the analysis window: its start is the steady start of the estimate
    let mut window = *setup;
    window.window.steady_start_s = window.window.analysis_start_s;
    let estimate = ImpactWorld::new(&window)
        .model_lyapunov(&ModelLyapunovOptions::default())
        .map_err(crate::setup::keyed);
    model_exponent_of(estimate, summary)
}

/// The exponent of a model estimate, or `None` (a failure noted in `summary.analysis_error`).
fn model_exponent_of(
    estimate: Result<crate::impact::ModelLyapunov, SimError>,
    summary: &mut RunSummary,
) -> Option<Exponent> {
    match estimate {
        Ok(m) if m.per_period.is_finite() => Some(Exponent {
            per_period: m.per_period,
            stderr_per_period: m.stderr_per_period,
        }),
        // a locked kinematic ball: every perturbation dies (λ = −∞); no finite exponent to
        // report, the exact section (a fixed point) decides
        Ok(_) => None,
        Err(e) => {
            summary.analysis_error = Some(format!("model exponent: {e}"));
            None
        }
    }
}

/// The exact section rows (grain z, grain v, box z, box v) and their scales; coordinates that
/// do not move along the trajectory are left out.
fn exact_section(
    summary: &RunSummary,
    collector: &SteadyCollector,
    forcing_hz: f64,
) -> (Vec<Vec<f64>>, Vec<f64>) {
    let omega = std::f64::consts::TAU * forcing_hz;
    let range = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
        if hi > lo {
            hi - lo
        } else {
            0.0
        }
    };
    let strobe = &summary.strobe;
    let mut zg = range(&mut collector.grain_z_m.iter().copied());
    let mut zb = range(&mut collector.box_z_m.iter().copied());
    if zg == 0.0 {
        zg = range(&mut strobe.iter().map(|p| p.grain_z_m));
    }
    if zb == 0.0 {
        zb = range(&mut strobe.iter().map(|p| p.box_z_m));
    }
    let scales_all = [zg, omega * zg, zb, omega * zb];
    let keep: Vec<usize> = (0..4).filter(|&d| scales_all[d] > 0.0).collect();
    let rows = strobe
        .iter()
        .map(|p| {
            let s = [p.grain_z_m, p.grain_v_m_s, p.box_z_m, p.box_v_m_s];
            keep.iter().map(|&d| s[d]).collect()
        })
        .collect();
    (rows, keep.iter().map(|&d| scales_all[d]).collect())
}

/// Passes every `stride`-th sample (with time ≥ the collector's start) to the inner observer.
struct Decimate<'a> {
    inner: &'a mut SteadyCollector,
    stride: usize,
    count: usize,
}

impl Observer for Decimate<'_> {
    fn sample(&mut self, s: &crate::observe::Sample) -> Result<(), SimError> {
        if s.time_s < self.inner.from_s {
            return Ok(());
        }
        let keep = self.count.is_multiple_of(self.stride);
        self.count += 1;
        if keep {
            self.inner.sample(s)
        } else {
            Ok(())
        }
    }
}
