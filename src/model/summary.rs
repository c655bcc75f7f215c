//! What a run reports: [`RunSummary`] (written as `summary.json`), and how it is run
//! ([`RunOptions`]). Shared by every simulator (impact, DEM).

use crate::analysis::analyze::AnalysisReport;
use serde::{Deserialize, Serialize};

use super::dem_extras::DemExtras;

/// Default output sampling interval (s): `run.sample_interval` and the DEM engine's
/// `DemRunConfig` (1e-4 s).
pub const DEFAULT_SAMPLE_INTERVAL_S: f64 = 1e-4;
/// Default largest number of samples of the analysed series (`run.analysis_max_samples`,
/// 20 000): the series is sampled every max(`run.sample_interval`, analysis window / this).
pub const DEFAULT_ANALYSIS_MAX_SAMPLES: usize = 20_000;
/// Default fraction of the run treated as steady state (per-cycle figures):
/// `run.steady_fraction` and the engine's (0.1).
pub const DEFAULT_STEADY_FRACTION: f64 = 0.1;
/// Default last fraction of the run that is analysed (stroboscopic section, analysed
/// series): `run.analysis_fraction` and the engine's (0.5).
pub const DEFAULT_ANALYSIS_FRACTION: f64 = 0.5;

/// Options of one run that are not part of the physics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// Interval between samples sent to the observer (s); `None`: no samples.
    pub sample_interval_s: Option<f64>,
    /// No samples before this time (s).
    pub sample_from_s: f64,
}

/// The time windows of a run (s): its duration, the steady-state window (per-cycle figures)
/// and the analysis window (stroboscopic section and analysed series).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunWindow {
    /// Simulated (driven) time (s).
    pub duration_s: f64,
    /// Start of the steady-state window (s).
    pub steady_start_s: f64,
    /// Start of the analysis window (s), ≤ `steady_start_s`.
    pub analysis_start_s: f64,
}

impl RunOptions {
    /// Samples every `sample_interval_s` (s) from t = 0 (what `pdamp simulate` writes).
    pub fn full_series(sample_interval_s: f64) -> RunOptions {
        RunOptions {
            sample_interval_s: Some(sample_interval_s),
            sample_from_s: 0.0,
        }
    }

    /// Samples of the analysis window of `window` only, every `sample_interval_s` (s) but
    /// decimated so that at most `max_samples` are produced (input of the nonlinear analysis).
    pub fn steady_series(
        window: &RunWindow,
        sample_interval_s: f64,
        max_samples: usize,
    ) -> RunOptions {
        let steady = window.duration_s - window.analysis_start_s;
        let dt = sample_interval_s.max(steady / max_samples as f64);
        RunOptions {
            sample_interval_s: Some(dt),
            sample_from_s: window.analysis_start_s,
        }
    }

    /// No samples at all (summary only).
    pub fn summary_only() -> RunOptions {
        RunOptions {
            sample_interval_s: None,
            sample_from_s: 0.0,
        }
    }
}

/// One stroboscopic sample: the state at exactly t = n/f (once per forcing period, over the
/// analysis window `run.analysis_fraction`). The impact model evaluates its closed forms at t = nT; the DEM interpolates the state
/// linearly between the two time steps around nT (error O(dt²·acceleration)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StrobePoint {
    /// Forcing cycle index n (t = n T).
    pub cycle: u64,
    /// Time (s).
    pub time_s: f64,
    /// Particle position / grains' centre of mass (m).
    pub grain_z_m: f64,
    /// Box position (m).
    pub box_z_m: f64,
    /// Particle velocity / grains' centre-of-mass velocity (m/s).
    #[serde(default)]
    pub grain_v_m_s: f64,
    /// Box velocity (m/s).
    #[serde(default)]
    pub box_v_m_s: f64,
}

/// Energy ledger of a whole run (J).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyTotals {
    /// Work done by the base through spring and damper, ∫ [K(u − z) + C(u' − z')] u' dt (J).
    pub base_work_j: f64,
    /// Viscous loss ∫ C (z' − u')² dt (J).
    pub viscous_j: f64,
    /// Kinetic energy lost in impacts, Σ ΔT (5.3.1) (J) (DEM: collisions + friction).
    pub impact_j: f64,
    /// Mechanical energy at the start: ½Mz'² + ½K(z − u)² + grains' kinetic + m_p g y (J).
    pub initial_mechanical_j: f64,
    /// Mechanical energy at the end (J).
    pub final_mechanical_j: f64,
}

impl EnergyTotals {
    /// |W − ΔE − D − L| / max(|W|, D + L, |ΔE|): relative residual of the energy balance.
    pub fn relative_error(&self) -> f64 {
        let de = self.final_mechanical_j - self.initial_mechanical_j;
        let resid = self.base_work_j - de - self.viscous_j - self.impact_j;
        let scale = self
            .base_work_j
            .abs()
            .max(self.viscous_j + self.impact_j)
            .max(de.abs())
            .max(f64::MIN_POSITIVE);
        resid.abs() / scale
    }
}

/// Summary of one run (`summary.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Model that produced it: "primary", "impact", "dem".
    pub model: String,
    /// Forcing frequency f (Hz).
    pub frequency_hz: f64,
    /// Simulated time (s).
    pub duration_s: f64,
    /// Start of the steady-state window (s).
    pub steady_start_s: f64,
    /// Forcing cycles in the steady-state window.
    pub cycles_steady: f64,
    /// Steady-state amplitude of the primary, Z = (max z − min z)/2 over the window (m).
    pub amplitude_m: f64,
    /// Largest box position in the window (m).
    pub box_z_max_m: f64,
    /// Smallest box position in the window (m).
    pub box_z_min_m: f64,
    /// Reference amplitude of the primary alone, (2.1.21) with M (m); none for a kinematic box.
    pub reference_amplitude_m: Option<f64>,
    /// Work done by the base per forcing cycle in the window (J).
    pub energy_input_j_per_cycle: f64,
    /// Viscous loss in C per forcing cycle in the window (J).
    pub energy_viscous_j_per_cycle: f64,
    /// Impact (collision) loss per forcing cycle in the window (J).
    pub energy_impact_j_per_cycle: f64,
    /// Impacts per forcing cycle in the window.
    pub impacts_per_cycle: f64,
    /// Relative residual of the whole run's energy balance (see [`EnergyTotals::relative_error`]);
    /// none for a kinematic box (no energy ledger).
    pub energy_balance_relative_error: Option<f64>,
    /// The whole run's energy ledger.
    pub energy_totals: EnergyTotals,
    /// Impacts over the whole run.
    pub impacts_total: u64,
    /// Events (impacts, detachments) over the whole run.
    pub events_total: u64,
    /// The DEM's own figures (none for the other models), flattened into the JSON: one key
    /// per field of [`DemExtras`] (e.g. `energy_friction_j_per_cycle`).
    #[serde(flatten)]
    pub dem: Option<DemExtras>,
    /// What the run warns about (a time step too long for the viscous time, an energy
    /// ledger residual above 1 %), for the caller to show (the CLI prints `warning: …`); not
    /// in the JSON.
    #[serde(skip)]
    pub warnings: Vec<String>,
    /// Stroboscopic samples of the steady state (written to strobe.csv, not to the JSON).
    #[serde(skip)]
    pub strobe: Vec<StrobePoint>,
    /// Nonlinear analysis of the steady-state grain series, when run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub analysis: Option<RunAnalysis>,
    /// Why the analysis could not be carried out, when it failed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub analysis_error: Option<String>,
    /// The DEM two-replica test (`run.replica`), when run; its rows go to `replica.csv`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replica: Option<crate::analysis::replica_test::ReplicaReport>,
    /// A free decay's envelope per cycle (`excitation.kind = "free"`): amplitude, logarithmic
    /// decrement and equivalent damping ratio ζ(amplitude) ([`crate::analysis::decay`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decay: Option<crate::analysis::decay::DecayEnvelope>,
}

/// The nonlinear analysis of a run (`summary.analysis`): the [`AnalysisReport`] itself, typed
/// both ways (the sweep tables, the study and the figures read its fields, checked at compile
/// time; a `summary.json` or `points/<i>.json` reads back into the same report).
pub type RunAnalysis = AnalysisReport;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::regime::Regime;

    #[test]
    fn run_analysis_reads_a_report_object() {
        // a report as written by earlier versions (keys sorted, nulls written out) reads back
        // into the typed report and writes the same object again
        let v = serde_json::json!({
            "closed_curve_score": null, "data_mle_per_s": null, "data_mle_stderr_per_s": null,
            "embedding_dim": null,
            "evidence": {"fnn_converged": null, "forcing_period_samples": 64.0,
                "harmonic_period_samples": null, "kantz_growth": null, "kantz_linear": false,
                "line_count": 2, "line_power_fraction": 0.99, "mle_per_sample": null,
                "mle_stderr_per_sample": null, "recurrence_period_samples": null,
                "section": null, "surrogate_p": null, "surrogate_rejects": null,
                "zero_one_k": null},
            "fnn_fractions": [[1, 0.5], [2, null]], "frequency_unit": "hz", "kantz_fit": null,
            "lag": 3, "line_power_fraction": 0.99, "mle_fit_r2": null, "mle_per_sample": null,
            "mle_per_time": null, "model_mle_per_s": -1.5, "model_mle_stderr_per_s": 0.1,
            "n_samples": 2000, "notes": ["x"], "period": 2.0,
            "poincare_distinct_points": 2, "poincare_section_points": 48,
            "poincare_shape": "points", "reason": "r", "regime": "periodic",
            "section_source": "exact", "series_dt_s": 0.001,
            "spectral_lines": [{"frequency": 5.0, "power": 1e-5}],
            "zero_one_k": null, "zero_one_samples": null
        });
        let a: RunAnalysis = serde_json::from_value(v.clone()).unwrap();
        assert_eq!(a.regime, Regime::Periodic);
        assert_eq!(a.period, Some(2.0));
        assert_eq!(a.model_mle_per_s, Some(-1.5));
        assert_eq!(a.poincare_section_points, Some(48));
        assert_eq!(a.poincare_shape.as_deref(), Some("points"));
        assert_eq!(a.verdict(), "periodic-2");
        assert_eq!(serde_json::to_value(&a).unwrap(), v);
    }

    #[test]
    fn a_null_cpu_figure_reads_back_as_absent() {
        // a committed sweep point with its CPU-time figure written as null (not measurable
        // on a loaded machine): the summary reads, without that key
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/figures/data/dem_ch4_p200/points/0.json"
        );
        let point: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let mut v = point["summary"].clone();
        v["particle_steps_per_cpu_s"] = serde_json::Value::Null;
        let s: RunSummary = serde_json::from_value(v.clone()).unwrap();
        let dem = s.dem.as_ref().expect("a DEM point");
        assert!(dem.particle_steps_per_cpu_s.is_none());
        assert!(dem.bed_floor_impacts_per_cycle.is_finite());
        // written back, the DEM's figures are the stored keys and values (the null one left
        // out)
        let back = serde_json::to_value(&s).unwrap();
        let keys = serde_json::to_value(dem).unwrap();
        let keys = keys.as_object().unwrap();
        assert_eq!(keys.len(), 21);
        for k in keys.keys() {
            assert_eq!(back[k], v[k], "{k}");
        }
        assert!(back.get("particle_steps_per_cpu_s").is_none());
        // an earlier version's summary, without a figure added since, reads it as NaN
        let mut older = v.clone();
        older.as_object_mut().unwrap().remove("viscous_time_s");
        let s: RunSummary = serde_json::from_value(older).unwrap();
        assert!(s.dem.as_ref().unwrap().viscous_time_s.is_nan());
        // a summary without them (an impact run) reads without
        let mut impact = v.clone();
        for k in keys.keys() {
            impact.as_object_mut().unwrap().remove(k);
        }
        let s: RunSummary = serde_json::from_value(impact).unwrap();
        assert!(s.dem.is_none());
    }
}
