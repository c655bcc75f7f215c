//! `[run]`: duration, steady-state window, output sampling and time-step settings.

use super::checks::positive;
use crate::error::SceneError;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Run settings.
///
/// Give exactly one of `duration` (s) and `periods` (number of forcing periods).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Run {
    /// Simulated time (s), > 0. Exclusive with `periods`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Simulated time as a number of forcing periods (dimensionless), > 0; handy in frequency
    /// sweeps. Exclusive with `duration`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub periods: Option<f64>,
    /// Last fraction of the run analysed as steady state (dimensionless), in (0, 1]. Default 0.1
    /// (SPEC §1: "the last 10 %").
    #[serde(default = "default_steady_fraction")]
    pub steady_fraction: f64,
    /// Last fraction of the run whose stroboscopic section and series feed the regime
    /// analysis (dimensionless), in (0, 1], at least `steady_fraction`. Default 0.5: the
    /// section-pattern test needs ≥ 48 forcing periods and the exponents a few hundred, more
    /// than the last 10 % of a short run holds; the amplitude and energy figures keep the
    /// `steady_fraction` window.
    #[serde(default = "default_analysis_fraction")]
    pub analysis_fraction: f64,
    /// Output sampling interval of `series.csv` (s), > 0. Default 1e-4 s. The DEM's automatic
    /// step is put on the analysis window's sample clock (`crate::setup::dem::step_clock_s`),
    /// the same for `simulate` and a sweep point; `series.csv` then has a row every whole
    /// number of steps nearest this interval, each with its exact time.
    #[serde(default = "default_sample_interval")]
    pub sample_interval: f64,
    /// Time step of time-stepping models (DEM): `"auto"` (a fraction `dt_fraction` of the
    /// contact duration) or seconds. The event-driven impact model ignores it. Default: auto.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dt: Option<DtSpec>,
    /// Fraction of the contact duration used as time step when `dt = "auto"` (dimensionless),
    /// in (0, 1]. Default 0.01 (the thesis's δt ≈ t_s/100).
    #[serde(default = "default_dt_fraction")]
    pub dt_fraction: f64,
    /// Seed of every random number generator of the run (packing, polydispersity). Default 0.
    #[serde(default)]
    pub seed: u64,
    /// Largest number of steady-state samples handed to the nonlinear analysis (the series is
    /// decimated to stay below). Default 20000.
    #[serde(default = "default_analysis_max_samples")]
    pub analysis_max_samples: usize,
    /// DEM two-replica test ([`crate::dem::replica`]): by default it runs wherever a regime
    /// verdict needs it (a DEM run with the nonlinear analysis: `pdamp simulate`, analysed
    /// sweeps, the chapter-4 study, whose section is not n tight groups — those are periodic
    /// whatever the replicas do); `false` turns it off (the verdict then rests on the section
    /// and the data exponent alone), `true` or a perturbation δ0 in metres (> 0, below the
    /// smallest grain radius; `true` = 1e-9 m) runs it always. Replica B, every grain raised by
    /// δ0 when the analysis window starts, takes the run's steps over the window (stepped after
    /// the run); `replica.csv` and a `replica` block in `summary.json` report it. It doubles
    /// the cost of the analysis window. DEM only (`damper.kind = "dem"`, or
    /// `"auto"` when it picks the DEM).
    #[serde(
        default,
        skip_serializing_if = "ReplicaChoice::is_default",
        deserialize_with = "replica_choice",
        serialize_with = "write_replica_choice"
    )]
    pub replica: ReplicaChoice,
    /// DEM energy ledger (2.6.1–2.6.6): `true` (default) books the collision and friction
    /// dissipation, the viscous loss in C and the base work every step, checks the balance
    /// and reports it; `false` skips that bookkeeping (the contact loops then compute no
    /// dissipated powers): the per-cycle energies are left out of `summary.json` (its
    /// balance error is null), the ledger columns of `series.csv` and the balance residual
    /// are 0 (nothing booked), and the stability check no longer tests for energy growth.
    /// The impact model ignores it.
    #[serde(default = "default_energy_ledger")]
    pub energy_ledger: bool,
}

/// The scene key `run.replica`: when the DEM two-replica test runs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ReplicaChoice {
    /// Wherever a regime verdict needs it (the default; the key left out): replica B is
    /// cloned in every analysed run and stepped only when the section is not n tight groups
    /// ([`crate::dem::replica::DeferredReplica`]).
    #[default]
    WithVerdict,
    /// Never (`false`).
    Off,
    /// Always, with this perturbation δ0 (m) (`true`: 1e-9 m).
    Delta(f64),
}

impl ReplicaChoice {
    /// The default (the key left out).
    pub fn is_default(&self) -> bool {
        *self == ReplicaChoice::WithVerdict
    }

    /// The perturbation δ0 (m) of a run, when the test runs: `verdict` says whether the run
    /// is analysed for a regime verdict.
    pub fn delta_m(&self, verdict: bool) -> Option<f64> {
        match *self {
            ReplicaChoice::WithVerdict => verdict.then_some(crate::dem::replica::DEFAULT_DELTA_M),
            ReplicaChoice::Off => None,
            ReplicaChoice::Delta(d) => Some(d),
        }
    }
}

/// `run.replica`: `true` → the default δ0, `false` → off, a number → δ0 (m).
fn replica_choice<'de, D: Deserializer<'de>>(d: D) -> Result<ReplicaChoice, D::Error> {
    struct V;
    impl serde::de::Visitor<'_> for V {
        type Value = ReplicaChoice;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("true, false or a perturbation in metres")
        }
        fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<ReplicaChoice, E> {
            Ok(if v {
                ReplicaChoice::Delta(crate::dem::replica::DEFAULT_DELTA_M)
            } else {
                ReplicaChoice::Off
            })
        }
        fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<ReplicaChoice, E> {
            Ok(ReplicaChoice::Delta(v))
        }
        fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<ReplicaChoice, E> {
            Ok(ReplicaChoice::Delta(v as f64))
        }
        fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<ReplicaChoice, E> {
            Ok(ReplicaChoice::Delta(v as f64))
        }
    }
    d.deserialize_any(V)
}

fn write_replica_choice<S: serde::Serializer>(c: &ReplicaChoice, s: S) -> Result<S::Ok, S::Error> {
    match *c {
        ReplicaChoice::WithVerdict | ReplicaChoice::Off => s.serialize_bool(false),
        ReplicaChoice::Delta(d) => s.serialize_f64(d),
    }
}

fn default_steady_fraction() -> f64 {
    crate::model::DEFAULT_STEADY_FRACTION
}
fn default_analysis_fraction() -> f64 {
    crate::model::DEFAULT_ANALYSIS_FRACTION
}
fn default_sample_interval() -> f64 {
    crate::model::DEFAULT_SAMPLE_INTERVAL_S
}
fn default_dt_fraction() -> f64 {
    crate::dem::stability::DEFAULT_DT_FRACTION
}
fn default_energy_ledger() -> bool {
    true
}
fn default_analysis_max_samples() -> usize {
    crate::model::summary::DEFAULT_ANALYSIS_MAX_SAMPLES
}

impl Run {
    /// A run of `duration_s` seconds with the default settings.
    pub fn with_duration(duration_s: f64) -> Run {
        Run {
            duration: Some(duration_s),
            periods: None,
            steady_fraction: default_steady_fraction(),
            analysis_fraction: default_analysis_fraction(),
            sample_interval: default_sample_interval(),
            dt: None,
            dt_fraction: default_dt_fraction(),
            seed: 0,
            analysis_max_samples: default_analysis_max_samples(),
            replica: ReplicaChoice::WithVerdict,
            energy_ledger: default_energy_ledger(),
        }
    }

    /// Duration (s) for forcing frequency `frequency_hz`: `duration`, or `periods / f`.
    pub fn duration_s(&self, frequency_hz: f64) -> f64 {
        match (self.duration, self.periods) {
            (Some(d), _) => d,
            (None, Some(n)) => n / frequency_hz,
            (None, None) => 0.0,
        }
    }

    /// Check the run settings.
    ///
    /// # Errors
    /// [`SceneError`] naming `run.<key>`.
    pub fn validate(&self) -> Result<(), SceneError> {
        match (self.duration, self.periods) {
            (Some(_), Some(_)) => {
                return Err(SceneError::invalid(
                    "run.periods",
                    self.periods.unwrap_or_default(),
                    "give either run.duration (s) or run.periods (forcing periods), not both",
                ))
            }
            (None, None) => {
                return Err(SceneError::Missing {
                    field: "run.duration".into(),
                    hint: "write duration = seconds, or periods = number of forcing periods".into(),
                })
            }
            (Some(d), None) => positive("run.duration", d, "s")?,
            (None, Some(n)) => positive("run.periods", n, "forcing periods")?,
        }
        let sf = self.steady_fraction;
        if !(sf > 0.0 && sf <= 1.0) {
            return Err(SceneError::invalid(
                "run.steady_fraction",
                sf,
                "must lie in (0, 1]",
            ));
        }
        let af = self.analysis_fraction;
        if !(af > 0.0 && af <= 1.0) {
            return Err(SceneError::invalid(
                "run.analysis_fraction",
                af,
                "must lie in (0, 1] (last fraction of the run analysed for the regime)",
            ));
        }
        positive("run.sample_interval", self.sample_interval, "s")?;
        if let Some(DtSpec::Seconds(dt)) = self.dt {
            positive("run.dt", dt, "s, or \"auto\"")?;
        }
        let fr = self.dt_fraction;
        if !(fr > 0.0 && fr <= 1.0) {
            return Err(SceneError::invalid(
                "run.dt_fraction",
                fr,
                "must lie in (0, 1] (fraction of the contact duration)",
            ));
        }
        if let ReplicaChoice::Delta(d) = self.replica {
            if !(d.is_finite() && d > 0.0 && d < 1e-3) {
                return Err(SceneError::invalid(
                    "run.replica",
                    d,
                    "the replica's perturbation must be finite, > 0 and below the grain radius \
                     (true: 1e-9 m; false turns the test off)",
                ));
            }
        }
        if self.analysis_max_samples < 100 {
            return Err(SceneError::invalid(
                "run.analysis_max_samples",
                self.analysis_max_samples,
                "must be ≥ 100",
            ));
        }
        Ok(())
    }
}

/// Time step setting: `"auto"` or a number of seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DtSpec {
    /// A fraction `run.dt_fraction` of the estimated contact duration.
    Auto,
    /// A fixed step (s).
    Seconds(f64),
}

impl Serialize for DtSpec {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            DtSpec::Auto => s.serialize_str("auto"),
            DtSpec::Seconds(x) => s.serialize_f64(*x),
        }
    }
}

impl<'de> Deserialize<'de> for DtSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = DtSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("\"auto\" or a time step in seconds")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<DtSpec, E> {
                if v == "auto" {
                    Ok(DtSpec::Auto)
                } else {
                    Err(E::custom(format!(
                        "run.dt = \"{v}\": expected \"auto\" or a number of seconds"
                    )))
                }
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<DtSpec, E> {
                Ok(DtSpec::Seconds(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<DtSpec, E> {
                Ok(DtSpec::Seconds(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<DtSpec, E> {
                Ok(DtSpec::Seconds(v as f64))
            }
        }
        d.deserialize_any(V)
    }
}
