//! The speed–accuracy study from stored points: one [`Row`] per rung and frequency (Z, its
//! error, the dissipation, the verdict beside the reference's, λ, the cost) and one
//! [`SettingSummary`] per rung (largest errors, the FRF's resonance against the reference's,
//! M_ef and C_ef fitted through the peak, regime agreement with its confusion matrix, cost and
//! speed-up, Pareto flags).
//!
//! Errors are measured only where both the rung and the reference have a point; a rung's
//! coverage (`frequencies_ok` of `frequencies`) says how much of the grid that is.

use std::collections::BTreeMap;

use crate::error::DataError;
use crate::model::RunSummary;
use crate::sweep::Catalog;

use super::metrics::{effective, relative_error, resonance, Effective, Peak};
use super::observed::{observe, Observed};
use super::pareto::pareto_front;
use super::plan::StudyPlan;
use crate::choice::ladder::{Axis, Change, Rung};

/// One rung at one frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Rung identifier.
    pub setting: String,
    /// Its axis.
    pub axis: Axis,
    /// Its label.
    pub label: String,
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// `ok`, `not computed`, `refused`, `failed`, `other physics`.
    pub status: String,
    /// The guard's or the run's message when refused or failed.
    pub message: String,
    /// The grains' Young's modulus (Pa); none for the one-particle model.
    pub youngs_modulus_pa: Option<f64>,
    /// Time step used (s) (DEM).
    pub dt_s: Option<f64>,
    /// Forcing periods of drive.
    pub periods: Option<f64>,
    /// Steady amplitude of the primary Z (m).
    pub amplitude_m: Option<f64>,
    /// |Z − Z_ref| / Z_ref (–).
    pub amplitude_rel_error: Option<f64>,
    /// Energy the grains dissipate per forcing cycle (J).
    pub dissipation_j_per_cycle: Option<f64>,
    /// Its relative error (–).
    pub dissipation_rel_error: Option<f64>,
    /// Verdict (regime and period, e.g. `periodic-1`, `chaotic`).
    pub regime: Option<String>,
    /// The reference's verdict at this frequency.
    pub regime_reference: Option<String>,
    /// Whether the two verdicts are equal.
    pub regime_match: Option<bool>,
    /// Largest Lyapunov exponent (1/s) where the verdict is chaotic.
    pub mle_per_s: Option<f64>,
    /// CPU seconds (see [`core_seconds`]).
    pub core_seconds: Option<f64>,
    /// Particle-steps (grains × (settling + drive steps)) (DEM).
    pub particle_steps: Option<f64>,
}

/// One rung over all frequencies.
#[derive(Debug, Clone, PartialEq)]
pub struct SettingSummary {
    /// Rung identifier.
    pub setting: String,
    /// Its axis.
    pub axis: Axis,
    /// Its label.
    pub label: String,
    /// `complete`, `partial`, `not computed`, `refused`, `failed`.
    pub status: String,
    /// The first refusal or failure message.
    pub message: String,
    /// Frequencies with a point.
    pub frequencies_ok: usize,
    /// Frequencies of the study.
    pub frequencies: usize,
    /// Frequencies where both this rung and the reference have a point.
    pub frequencies_compared: usize,
    /// Mean CPU seconds per point over the compared frequencies.
    pub core_seconds_per_point: Option<f64>,
    /// The reference's mean CPU seconds per point over the same frequencies ÷ this rung's.
    pub speedup: Option<f64>,
    /// Largest |Z − Z_ref| / Z_ref (–).
    pub amplitude_max_rel_error: Option<f64>,
    /// Median of the same (–).
    pub amplitude_median_rel_error: Option<f64>,
    /// Resonance of the rung's FRF (peak of Z over the compared frequencies).
    pub resonance: Option<Peak>,
    /// |f_res − f_res,ref| / f_res,ref (–).
    pub resonance_frequency_rel_error: Option<f64>,
    /// |Z_res − Z_res,ref| / Z_res,ref (–).
    pub resonance_amplitude_rel_error: Option<f64>,
    /// M_ef and C_ef of (2.1.21) fitted to the compared points.
    pub effective: Option<Effective>,
    /// |M_ef − M_ef,ref| / M_ef,ref (–).
    pub m_ef_rel_error: Option<f64>,
    /// |C_ef − C_ef,ref| / C_ef,ref (–).
    pub c_ef_rel_error: Option<f64>,
    /// Largest relative error of the grains' dissipation per cycle (–).
    pub dissipation_max_rel_error: Option<f64>,
    /// Frequencies whose verdict equals the reference's.
    pub regime_matches: usize,
    /// Frequencies where both verdicts exist.
    pub regime_compared: usize,
    /// `reference verdict → rung verdict: count` pairs, `; `-separated.
    pub confusion: String,
    /// Largest relative error of λ where both are chaotic (–).
    pub mle_max_rel_error: Option<f64>,
    /// On the Pareto front of cost against the Z error.
    pub pareto_amplitude: bool,
    /// On the Pareto front of cost against the resonance-frequency error.
    pub pareto_resonance: bool,
    /// On the Pareto front of cost against the dissipation error.
    pub pareto_dissipation: bool,
    /// On the Pareto front of cost against the verdict disagreement.
    pub pareto_regime: bool,
}

impl SettingSummary {
    /// Share of compared verdicts that differ from the reference's (–).
    pub fn regime_disagreement(&self) -> Option<f64> {
        (self.regime_compared > 0)
            .then(|| 1.0 - self.regime_matches as f64 / self.regime_compared as f64)
    }
}

/// The whole study.
#[derive(Debug, Clone)]
pub struct Study {
    /// Every rung at every frequency, rung by rung.
    pub rows: Vec<Row>,
    /// One summary per rung, reference first.
    pub settings: Vec<SettingSummary>,
}

/// Reads the stored points of every rung of `plan` and measures them against the reference.
///
/// # Errors
/// [`DataError`] when stored points cannot be read.
pub fn study(plan: &StudyPlan, catalog: &Catalog) -> Result<Study, DataError> {
    let observed: Vec<(Rung, Vec<Observed>)> = plan
        .rungs
        .iter()
        .map(|r| Ok((r.clone(), observe(plan, r, catalog)?)))
        .collect::<Result<_, DataError>>()?;
    let reference = observed
        .iter()
        .find(|(r, _)| r.change == Change::None)
        .map(|(_, o)| o.clone())
        .unwrap_or_default();
    let k = plan_stiffness_and_drive(plan);
    let ref_fit = fit_of(&reference, &reference, k);
    let mut rows = Vec::new();
    let mut settings = Vec::new();
    for (rung, obs) in &observed {
        let youngs = youngs_of(plan, rung);
        let r: Vec<Row> = obs
            .iter()
            .zip(&reference)
            .map(|(o, re)| row(rung, o, re, youngs))
            .collect();
        settings.push(summarise(rung, &r, obs, &reference, &ref_fit, k));
        rows.extend(r);
    }
    mark_pareto(&mut settings);
    Ok(Study { rows, settings })
}

/// Primary stiffness K (N/m) and base amplitude U (m) of the reference (for the fit).
fn plan_stiffness_and_drive(plan: &StudyPlan) -> Option<(f64, f64)> {
    let s = plan.reference.scene(&[]).ok()?;
    Some((s.primary.as_ref()?.stiffness, s.excitation.amplitude))
}

fn youngs_of(plan: &StudyPlan, rung: &Rung) -> Option<f64> {
    let s = rung.scene(&plan.reference).ok()?.scene(&[]).ok()?;
    match s.damper {
        crate::scene::Damper::Dem(p) => Some(p.youngs_modulus),
        _ => None,
    }
}

/// Verdict of a summary: the regime with its period (`periodic-2`), without qualifiers.
pub fn core_verdict(s: &RunSummary) -> Option<String> {
    let a = s.analysis.as_ref()?;
    Some(match (a.regime, a.period) {
        (crate::analysis::regime::Regime::Periodic, Some(p)) => format!("periodic-{p}"),
        (r, _) => r.as_str().to_string(),
    })
}

/// The two verdict-rule revisions ([`crate::analysis::regime::VERDICT_RULES`]) when a
/// point and its reference were judged by different ones (their verdicts are not compared).
fn other_rules(s: Option<&RunSummary>, reference: Option<&RunSummary>) -> Option<(u32, u32)> {
    let rules = |s: Option<&RunSummary>| Some(s?.analysis.as_ref()?.verdict_rules());
    match (rules(s), rules(reference)) {
        (Some(a), Some(b)) if a != b => Some((a, b)),
        _ => None,
    }
}

/// λ (1/s) where the verdict is chaotic: the model's exponent where the simulator has one,
/// else the data's.
fn chaotic_mle(s: &RunSummary) -> Option<f64> {
    let a = s.analysis.as_ref()?;
    (a.regime == crate::analysis::regime::Regime::Chaotic)
        .then_some(a.model_mle_per_s.or(a.data_mle_per_s))
        .flatten()
}

/// CPU seconds of a point. DEM: the bed's settling and driven stepping, particle-steps ÷ the
/// measured particle-steps per CPU second (the replica's second bed and the analysis are not
/// counted: the same share for every DEM rung). One particle: the recorded CPU time of the
/// whole point (simulation and analysis).
pub fn core_seconds(s: &RunSummary, cpu_s: Option<f64>) -> Option<f64> {
    let cpu_rate = s.dem.as_ref().and_then(|d| d.particle_steps_per_cpu_s);
    match (particle_steps(s), cpu_rate) {
        (Some(n), Some(rate)) if rate > 0.0 => Some(n / rate),
        (Some(_), _) => None,
        (None, _) => cpu_s,
    }
}

fn particle_steps(s: &RunSummary) -> Option<f64> {
    // (NaN: a figure written as null, read as unknown)
    let known = |x: f64| (!x.is_nan()).then_some(x);
    let d = s.dem.as_ref()?;
    let g = known(d.grains)?;
    let steps = known(d.steps)? + known(d.settle_steps).unwrap_or(0.0);
    Some(g * steps)
}

fn dissipation(s: &RunSummary) -> f64 {
    s.energy_impact_j_per_cycle
}

fn row(rung: &Rung, o: &Observed, re: &Observed, youngs: Option<f64>) -> Row {
    let s = o.summary.as_ref();
    let rs = re.summary.as_ref();
    let both = |f: fn(&RunSummary) -> f64| match (s, rs) {
        (Some(a), Some(b)) => relative_error(f(a), f(b)),
        _ => None,
    };
    let regime = s.and_then(core_verdict);
    let regime_reference = rs.and_then(core_verdict);
    let rules = other_rules(s, rs);
    let mut message = o.status.message();
    if let Some((a, b)) = rules {
        let sep = if message.is_empty() { "" } else { "; " };
        message.push_str(&format!(
            "{sep}verdicts judged by rules {a} (this setting) and {b} (the reference): not \
             compared — recompute the older points"
        ));
    }
    Row {
        setting: rung.id.clone(),
        axis: rung.axis,
        label: rung.label.clone(),
        frequency_hz: o.frequency_hz,
        status: o.status.as_str().to_string(),
        message,
        youngs_modulus_pa: youngs,
        dt_s: s
            .and_then(|s| s.dem.as_ref())
            .map(|d| d.dt_s)
            .filter(|v| !v.is_nan()),
        periods: s.map(|s| (s.duration_s * s.frequency_hz).round()),
        amplitude_m: s.map(|s| s.amplitude_m),
        amplitude_rel_error: both(|s| s.amplitude_m),
        dissipation_j_per_cycle: s.map(dissipation),
        dissipation_rel_error: both(dissipation),
        regime_match: regime
            .as_ref()
            .zip(regime_reference.as_ref())
            .filter(|_| rules.is_none())
            .map(|(a, b)| a == b),
        regime,
        regime_reference,
        mle_per_s: s.and_then(chaotic_mle),
        core_seconds: s.and_then(|x| core_seconds(x, o.cpu_s)),
        particle_steps: s.and_then(particle_steps),
    }
}

/// (f, Z) of the frequencies where both `obs` and `reference` have a point, by frequency.
fn compared_frf(obs: &[Observed], reference: &[Observed]) -> (Vec<f64>, Vec<f64>) {
    let mut v: Vec<(f64, f64)> = obs
        .iter()
        .zip(reference)
        .filter(|(_, r)| r.summary.is_some())
        .filter_map(|(o, _)| Some((o.frequency_hz, o.summary.as_ref()?.amplitude_m)))
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v.into_iter().unzip()
}

struct Fit {
    peak: Option<Peak>,
    effective: Option<Effective>,
}

fn fit_of(obs: &[Observed], reference: &[Observed], k: Option<(f64, f64)>) -> Fit {
    let (f, z) = compared_frf(obs, reference);
    Fit {
        peak: resonance(&f, &z),
        effective: k.and_then(|(k, u)| effective(&f, &z, k, u)),
    }
}

fn max_of(v: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    v.flatten().reduce(f64::max)
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

fn summarise(
    rung: &Rung,
    rows: &[Row],
    obs: &[Observed],
    reference: &[Observed],
    ref_fit: &Fit,
    k: Option<(f64, f64)>,
) -> SettingSummary {
    let compared: Vec<(&Row, &Observed)> = rows
        .iter()
        .zip(reference)
        .filter(|(r, re)| r.status == "ok" && re.summary.is_some())
        .collect();
    let cost = |v: &[Option<f64>]| {
        let c: Vec<f64> = v.iter().flatten().copied().collect();
        (c.len() == v.len() && !c.is_empty()).then(|| c.iter().sum::<f64>() / c.len() as f64)
    };
    let own: Vec<Option<f64>> = compared.iter().map(|(r, _)| r.core_seconds).collect();
    let theirs: Vec<Option<f64>> = compared
        .iter()
        .map(|(_, re)| re.summary.as_ref().and_then(|s| core_seconds(s, re.cpu_s)))
        .collect();
    let (cps, ref_cps) = (cost(&own), cost(&theirs));
    let fit = fit_of(obs, reference, k);
    let rel_opt = |a: Option<f64>, b: Option<f64>| relative_error(a?, b?);
    let mut confusion: BTreeMap<(String, String), usize> = BTreeMap::new();
    for (r, _) in &compared {
        if let (Some(a), Some(b)) = (&r.regime_reference, &r.regime) {
            *confusion.entry((a.clone(), b.clone())).or_default() += 1;
        }
    }
    let ok = rows.iter().filter(|r| r.status == "ok").count();
    let first_msg = rows.iter().find(|r| !r.message.is_empty());
    let status = match (ok, first_msg) {
        (n, _) if n == rows.len() => "complete",
        (0, Some(r)) => r.status.as_str(),
        (0, None) => "not computed",
        _ => "partial",
    };
    SettingSummary {
        setting: rung.id.clone(),
        axis: rung.axis,
        label: rung.label.clone(),
        status: status.to_string(),
        message: first_msg.map(|r| r.message.clone()).unwrap_or_default(),
        frequencies_ok: ok,
        frequencies: rows.len(),
        frequencies_compared: compared.len(),
        core_seconds_per_point: cps,
        speedup: cps.zip(ref_cps).map(|(a, b)| b / a),
        amplitude_max_rel_error: max_of(compared.iter().map(|(r, _)| r.amplitude_rel_error)),
        amplitude_median_rel_error: median(
            compared
                .iter()
                .filter_map(|(r, _)| r.amplitude_rel_error)
                .collect(),
        ),
        resonance_frequency_rel_error: rel_opt(
            fit.peak.map(|p| p.frequency_hz),
            ref_fit.peak.map(|p| p.frequency_hz),
        ),
        resonance_amplitude_rel_error: rel_opt(
            fit.peak.map(|p| p.amplitude_m),
            ref_fit.peak.map(|p| p.amplitude_m),
        ),
        resonance: fit.peak,
        m_ef_rel_error: rel_opt(
            fit.effective.map(|e| e.mass_kg),
            ref_fit.effective.map(|e| e.mass_kg),
        ),
        c_ef_rel_error: rel_opt(
            fit.effective.map(|e| e.damping_n_s_m),
            ref_fit.effective.map(|e| e.damping_n_s_m),
        ),
        effective: fit.effective,
        dissipation_max_rel_error: max_of(compared.iter().map(|(r, _)| r.dissipation_rel_error)),
        regime_matches: compared
            .iter()
            .filter(|(r, _)| r.regime_match == Some(true))
            .count(),
        regime_compared: compared
            .iter()
            .filter(|(r, _)| r.regime_match.is_some())
            .count(),
        confusion: confusion
            .iter()
            .map(|((a, b), n)| format!("{a} → {b}: {n}"))
            .collect::<Vec<_>>()
            .join("; "),
        mle_max_rel_error: max_of(compared.iter().map(|(r, re)| {
            let theirs = re.summary.as_ref().and_then(chaotic_mle);
            relative_error(r.mle_per_s?, theirs?)
        })),
        pareto_amplitude: false,
        pareto_resonance: false,
        pareto_dissipation: false,
        pareto_regime: false,
    }
}

/// Marks the Pareto fronts of cost per point against each error; the reference's errors are 0.
fn mark_pareto(settings: &mut [SettingSummary]) {
    type Get = fn(&SettingSummary) -> Option<f64>;
    type Set = fn(&mut SettingSummary, bool);
    let fronts: [(Get, Set); 4] = [
        (|s| s.amplitude_max_rel_error, |s, b| s.pareto_amplitude = b),
        (
            |s| s.resonance_frequency_rel_error,
            |s, b| s.pareto_resonance = b,
        ),
        (
            |s| s.dissipation_max_rel_error,
            |s, b| s.pareto_dissipation = b,
        ),
        (|s| s.regime_disagreement(), |s, b| s.pareto_regime = b),
    ];
    for (get, set) in fronts {
        let pts: Vec<(f64, f64)> = settings
            .iter()
            .map(|s| {
                (
                    s.core_seconds_per_point.unwrap_or(f64::NAN),
                    get(s).unwrap_or(f64::NAN),
                )
            })
            .collect();
        for (s, on) in settings.iter_mut().zip(pareto_front(&pts)) {
            set(s, on);
        }
    }
}
