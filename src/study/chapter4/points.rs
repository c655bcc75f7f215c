//! One point of a chapter-4 sweep as the figures and checks read it ([`Point`], from the
//! point's typed summary), and the CSV cell of an optional number.

use crate::analysis::regime::Regime;
use crate::error::StudyError;
use crate::sweep::SweepPoints;

/// One point of a chapter-4 sweep (from its typed summary).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Point {
    pub(super) f_hz: f64,
    pub(super) amplitude_m: f64,
    pub(super) regime: Option<Regime>,
    pub(super) period: Option<f64>,
    /// The verdict with its qualifiers ("chaotic; phase-locked to the forcing (Λ₁ = 0.985);
    /// high-dimensional"); empty when not analysed.
    pub(super) label: String,
    pub(super) phase_locked: bool,
    pub(super) locked_fraction: Option<f64>,
    /// W_n of the tight grouping, else the section's size (relative to the orbit).
    pub(super) section_scatter: Option<f64>,
    pub(super) chaos_dimension: Option<&'static str>,
    pub(super) replica: Option<&'static str>,
    pub(super) replica_saturation_rel: Option<f64>,
    pub(super) replica_growth_per_s: Option<f64>,
    pub(super) mle_per_s: Option<f64>,
    pub(super) mle_stderr_per_s: Option<f64>,
    pub(super) floor_impacts: f64,
    pub(super) ceiling_impacts: f64,
}

impl Point {
    /// Regime and period ("periodic-3", "chaotic"): what the run-length and ensemble checks
    /// compare (the qualifiers are reported beside it).
    pub(super) fn verdict(&self) -> String {
        match self.period {
            Some(p) if self.regime == Some(Regime::Periodic) => format!("periodic-{p}"),
            _ => self.regime_str().to_string(),
        }
    }

    /// The regime's name, empty when the point was not analysed (as in `sweep.csv`).
    pub(super) fn regime_str(&self) -> &'static str {
        self.regime.map_or("", Regime::as_str)
    }
}

pub(super) fn point(
    step: &str,
    dir: &str,
    p: &crate::sweep::SweepPoint,
) -> Result<Point, StudyError> {
    let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
    // a DEM figure of the point (NaN: written as null, read as missing)
    let extra = |key: &str, f: fn(&crate::model::DemExtras) -> f64| {
        p.summary
            .dem
            .as_ref()
            .map(f)
            .filter(|v| !v.is_nan())
            .ok_or_else(|| StudyError::step(step, format!("{dir}: point {}: no `{key}`", p.index)))
    };
    let a = p.summary.analysis.as_ref();
    let r = p.summary.replica.as_ref();
    Ok(Point {
        f_hz: p.summary.frequency_hz,
        amplitude_m: p.summary.amplitude_m,
        regime: a.map(|a| a.regime),
        period: finite(a.and_then(|a| a.period)),
        label: a.map(|a| a.verdict()).unwrap_or_default(),
        phase_locked: a.is_some_and(|a| a.phase_locked),
        locked_fraction: a.and_then(|a| a.phase_lock.map(|l| l.locked_fraction)),
        section_scatter: a
            .and_then(|a| a.section.as_ref())
            .map(|s| s.tight.as_ref().map_or(s.size, |g| g.scatter)),
        chaos_dimension: a.and_then(|a| a.chaos_dimension.map(|d| d.as_str())),
        replica: r.map(|r| r.outcome.as_str()),
        replica_saturation_rel: r.map(|r| r.saturation_rel),
        replica_growth_per_s: r.and_then(|r| r.growth_rate_per_s().map(|g| g.0)),
        mle_per_s: finite(a.and_then(|a| a.data_mle_per_s)),
        mle_stderr_per_s: finite(a.and_then(|a| a.data_mle_stderr_per_s)),
        floor_impacts: extra("bed_floor_impacts_per_cycle", |d| {
            d.bed_floor_impacts_per_cycle
        })?,
        ceiling_impacts: extra("bed_ceiling_impacts_per_cycle", |d| {
            d.bed_ceiling_impacts_per_cycle
        })?,
    })
}

pub(super) fn points(step: &str, pts: &SweepPoints) -> Result<Vec<Point>, StudyError> {
    let mut out = pts
        .iter()
        .map(|p| point(step, &pts.dir, p))
        .collect::<Result<Vec<Point>, StudyError>>()?;
    out.sort_by(|a, b| a.f_hz.total_cmp(&b.f_hz));
    Ok(out)
}

pub(super) fn opt_cell(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}
