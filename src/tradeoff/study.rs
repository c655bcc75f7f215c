//! The trade-off study: every rung of the ladder at a few frequencies (below, at and above
//! resonance), run in parallel with rayon — each run single-threaded, its wall time measured
//! inside the run — and compared with the reference.

use rayon::prelude::*;
use serde::Serialize;

use crate::error::{SceneError, SimError};
use crate::scene::dem::DemParams;

use super::ladder::{settings_ladder, Axis, Case, Change, LadderOptions, Setting};
use super::measure::{
    observe, one_particle_scene, run_dem_case, run_impact_scene, Observation, Rig, RunOutput,
};
use super::metrics::{dynamics, effective, relative_error, Dynamics};
use super::pareto::pareto_front;

/// Options of [`run_study`].
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// Reference and ladder.
    pub ladder: LadderOptions,
    /// Frequencies (Hz); empty (default): 0.7 f_r, f_r, 1.3 f_r with f_r = √(K/(M + m_p))/2π,
    /// the natural frequency with the grains' mass attached.
    pub frequencies_hz: Vec<f64>,
    /// Worker threads (each run is single-threaded); `None` (default): rayon's default.
    pub threads: Option<usize>,
    /// Restitutions tried when fitting the one-particle model's e to the reference
    /// (default 0, 0.1, …, 0.9).
    pub fitted_e_candidates: Vec<f64>,
}

impl Default for StudyOptions {
    fn default() -> Self {
        StudyOptions {
            ladder: LadderOptions::default(),
            frequencies_hz: Vec::new(),
            threads: None,
            fitted_e_candidates: (0..10).map(|i| i as f64 / 10.0).collect(),
        }
    }
}

/// One run (setting × frequency): a row of `tradeoff.csv`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunRow {
    /// The knob.
    pub axis: Axis,
    /// The setting's label.
    pub setting: String,
    /// The knob's value.
    pub value: f64,
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// `ok`, or the error that stopped the run.
    pub status: String,
    /// Wall time of the driven run (s), measured inside the single-threaded run.
    pub wall_time_s: f64,
    /// Wall time including bed building and settling (s).
    pub total_wall_time_s: f64,
    /// Time steps of the driven run (DEM) or events (impact model).
    pub steps: u64,
    /// Time step (s), DEM only.
    pub dt_s: Option<f64>,
    /// Steady amplitude of the primary Z (m).
    pub amplitude_m: Option<f64>,
    /// |Z − Z_ref| / Z_ref (–).
    pub amplitude_rel_error: Option<f64>,
    /// Grain dissipation per cycle (J).
    pub dissipation_j_per_cycle: Option<f64>,
    /// Its relative error (–).
    pub dissipation_rel_error: Option<f64>,
    /// Regime verdict of the steady grain series.
    pub regime: String,
    /// The reference's verdict at this frequency.
    pub regime_reference: String,
    /// Whether both verdicts agree.
    pub regime_match: bool,
    /// Maximal Lyapunov exponent (1/s).
    pub mle_per_s: Option<f64>,
    /// |λ − λ_ref| (1/s).
    pub mle_abs_error_per_s: Option<f64>,
}

/// One setting over all frequencies: a row of `tradeoff_settings.csv`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SettingRow {
    /// The knob.
    pub axis: Axis,
    /// The setting's label.
    pub setting: String,
    /// The knob's value.
    pub value: f64,
    /// Runs that finished / runs tried.
    pub runs_ok: usize,
    /// Runs tried.
    pub runs: usize,
    /// Summed wall time over the frequencies (s).
    pub wall_time_s: f64,
    /// Reference wall time / this wall time (–).
    pub speedup: f64,
    /// Largest amplitude error over the frequencies (–).
    pub amplitude_max_rel_error: Option<f64>,
    /// Largest dissipation error (–).
    pub dissipation_max_rel_error: Option<f64>,
    /// Fitted M_ef (kg).
    pub m_ef_kg: Option<f64>,
    /// Its relative error (–).
    pub m_ef_rel_error: Option<f64>,
    /// Fitted C_ef (N s/m).
    pub c_ef_n_s_m: Option<f64>,
    /// Its relative error (–).
    pub c_ef_rel_error: Option<f64>,
    /// Frequencies where the regime verdict matches the reference's.
    pub regime_matches: usize,
    /// Largest |λ − λ_ref| (1/s).
    pub mle_max_abs_error_per_s: Option<f64>,
    /// On the Pareto front of (wall time, amplitude error).
    pub pareto_amplitude: bool,
}

/// Everything measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// Frequencies (Hz).
    pub frequencies_hz: Vec<f64>,
    /// One row per run.
    pub runs: Vec<RunRow>,
    /// One row per setting.
    pub settings: Vec<SettingRow>,
    /// How the reference and the one-particle model were set up, in words.
    pub notes: Vec<String>,
}

/// Default frequencies: 0.7, 1 and 1.3 × √(K/(M + m_p))/2π (Hz).
pub fn default_frequencies(rig: &Rig, params: &DemParams) -> Result<Vec<f64>, SceneError> {
    let d = params.radius_distribution()?;
    let r = 0.5 * (d.r_min() + d.r_max());
    let m_p = params.count as f64 * params.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let fr =
        (rig.primary.stiffness_n_m / (rig.primary.mass_kg + m_p)).sqrt() / crate::units::TWO_PI;
    Ok([0.7, 1.0, 1.3]
        .iter()
        .map(|k| (k * fr * 100.0).round() / 100.0)
        .collect())
}

/// A finished run with its observation and dynamics, or its error.
type Done = Result<(RunOutput, Observation, Dynamics), String>;

fn finish(out: Result<RunOutput, SimError>, steady_fraction: f64) -> Done {
    let out = out.map_err(|e| e.to_string())?;
    let obs = observe(&out, steady_fraction).map_err(|e| e.to_string())?;
    let dynm = dynamics(&obs, out.frequency_hz);
    Ok((out, obs, dynm))
}

/// Relative cost estimate of a DEM case (for scheduling the longest runs first).
fn cost(c: &Case) -> f64 {
    c.duration_s / c.dt_fraction * c.softening.powf(0.4) * (c.params.count as f64).powf(4.0 / 3.0)
}

/// Runs the study for the grains `params` on `rig`. `progress` is called after each run with
/// a one-line description.
///
/// # Errors
/// Invalid options; the reference failing at any frequency (nothing to compare with).
pub fn run_study(
    params: &DemParams,
    rig: &Rig,
    opts: &StudyOptions,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Study, SimError> {
    opts.ladder.validate()?;
    params.validate()?;
    let freqs = if opts.frequencies_hz.is_empty() {
        default_frequencies(rig, params)?
    } else {
        opts.frequencies_hz.clone()
    };
    if let Some(f) = freqs.iter().find(|f| !(**f > 0.0 && f.is_finite())) {
        return Err(SceneError::invalid("frequencies", f, "must be > 0 (Hz)").into());
    }
    let ladder = settings_ladder(&opts.ladder, params.count);
    let reference = opts.ladder.reference(params);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
        .map_err(|e| SimError::Output(format!("thread pool: {e}")))?;

    // 1. every DEM run (reference included), longest first
    let mut jobs: Vec<(usize, usize, Case)> = Vec::new();
    for (si, s) in ladder.iter().enumerate() {
        if matches!(s.change, Change::OneParticle(_) | Change::SteadyFraction(_)) {
            continue;
        }
        for (fi, &f) in freqs.iter().enumerate() {
            jobs.push((si, fi, s.change.apply(&reference, &rig.drive(f))?));
        }
    }
    jobs.sort_by(|a, b| {
        cost(&b.2)
            .total_cmp(&cost(&a.2))
            .then((a.0, a.1).cmp(&(b.0, b.1)))
    });
    let results: Vec<Done> = pool.install(|| {
        jobs.par_iter()
            .map(|(si, fi, case)| {
                let d = finish(run_dem_case(case, rig, freqs[*fi]), case.steady_fraction);
                progress(&describe(&ladder[*si], freqs[*fi], &d));
                d
            })
            .collect()
    });
    let mut done: Vec<Vec<Option<Done>>> = vec![vec![None; freqs.len()]; ladder.len()];
    let mut ref_out: Vec<Option<RunOutput>> = vec![None; freqs.len()];
    for ((si, fi, _), d) in jobs.iter().zip(results) {
        if ladder[*si].axis == Axis::Reference {
            match &d {
                Ok((o, _, _)) => ref_out[*fi] = Some(o.clone()),
                Err(e) => {
                    return Err(SimError::Output(format!(
                        "the reference run at {} Hz failed: {e}",
                        freqs[*fi]
                    )))
                }
            }
        }
        done[*si][*fi] = Some(d);
    }
    let ref_out: Vec<RunOutput> = ref_out.into_iter().flatten().collect();

    // 2. the same reference runs seen through a shorter steady window
    for (si, s) in ladder.iter().enumerate() {
        if let Change::SteadyFraction(sf) = s.change {
            for (fi, o) in ref_out.iter().enumerate() {
                done[si][fi] = Some(finish(Ok(o.clone()), sf));
            }
        }
    }

    // 3. the one-particle model: m_p and gap = Lz − bed height from the reference's bed
    let m_p = ref_out[0].grain_mass_kg;
    let bed = ref_out[0].bed_height_m.unwrap_or(0.0);
    let gap = (params.r#box[2] - bed).max(0.0);
    let rl = &opts.ladder;
    let impact = |e: f64, f: f64| -> Done {
        let scene = one_particle_scene(rig, f, m_p, gap, e, rl.duration_s, rl.steady_fraction);
        finish(run_impact_scene(&scene), rl.steady_fraction)
    };
    let ref_z: Vec<f64> = (0..freqs.len())
        .map(|fi| {
            done[0][fi]
                .as_ref()
                .and_then(|d| d.as_ref().ok())
                .map_or(f64::NAN, |d| d.1.amplitude_m)
        })
        .collect();
    let mut fitted_e = f64::NAN;
    for (si, s) in ladder.iter().enumerate() {
        let Change::OneParticle(e) = s.change else {
            continue;
        };
        let (e, runs) = match e {
            Some(e) => (
                e,
                pool.install(|| freqs.par_iter().map(|&f| impact(e, f)).collect::<Vec<_>>()),
            ),
            None => fit_restitution(&opts.fitted_e_candidates, &freqs, &ref_z, &pool, &impact),
        };
        if s.value.is_nan() {
            fitted_e = e;
        }
        for (fi, d) in runs.into_iter().enumerate() {
            progress(&describe(s, freqs[fi], &d));
            done[si][fi] = Some(d);
        }
    }
    let mut ladder = ladder;
    for s in ladder.iter_mut().filter(|s| s.value.is_nan()) {
        s.value = fitted_e;
        s.label = format!("one particle, fitted e = {fitted_e:.1}");
    }

    // 4. errors against the reference
    let (runs, settings) = compare(&ladder, &freqs, &done, rig);
    let notes = vec![
        format!(
            "reference: DEM, Young's modulus / {} (damping × {:.4}, e(v) unchanged), Hertz–Kuwabara–Kono, \
             friction and rotations on, dt = t_s × {}, {} s of drive, last {} analysed",
            rl.reference_softening,
            crate::scene::dem::softening_damping_scale(rl.reference_softening),
            rl.reference_dt_fraction,
            rl.duration_s,
            rl.steady_fraction
        ),
        format!(
            "one-particle model: m_p = {m_p:.4} kg (the grains' mass), gap = Lz − settled bed height = {:.4} − {bed:.4} = {gap:.4} m; \
             fitted e = {fitted_e:.1} minimises the largest Z error over the frequencies (in-sample fit; fitting cost not counted)",
            params.r#box[2]
        ),
        "steady-fraction rows re-analyse the reference runs (same wall time)".into(),
    ];
    Ok(Study {
        frequencies_hz: freqs,
        runs,
        settings,
        notes,
    })
}

/// Runs the impact model for every candidate e and keeps the e with the smallest largest
/// amplitude error against `ref_z`.
fn fit_restitution(
    candidates: &[f64],
    freqs: &[f64],
    ref_z: &[f64],
    pool: &rayon::ThreadPool,
    impact: &(dyn Fn(f64, f64) -> Done + Sync),
) -> (f64, Vec<Done>) {
    let grid: Vec<(f64, f64)> = candidates
        .iter()
        .flat_map(|&e| freqs.iter().map(move |&f| (e, f)))
        .collect();
    let all: Vec<Done> = pool.install(|| grid.par_iter().map(|&(e, f)| impact(e, f)).collect());
    let mut best: Option<(f64, f64, Vec<Done>)> = None;
    for (k, chunk) in all.chunks(freqs.len()).enumerate() {
        let worst = chunk
            .iter()
            .zip(ref_z)
            .map(|(d, &z)| {
                d.as_ref()
                    .ok()
                    .and_then(|d| relative_error(d.1.amplitude_m, z))
                    .unwrap_or(f64::INFINITY)
            })
            .fold(0.0, f64::max);
        if best.as_ref().is_none_or(|b| worst < b.1) {
            best = Some((candidates[k], worst, chunk.to_vec()));
        }
    }
    match best {
        Some((e, _, runs)) => (e, runs),
        None => (f64::NAN, Vec::new()),
    }
}

fn describe(s: &Setting, f: f64, d: &Done) -> String {
    match d {
        Ok((o, obs, _)) => format!(
            "{:<28} {f:>7.2} Hz: Z = {:.4e} m, wall {:.2} s",
            s.label, obs.amplitude_m, o.wall_time_s
        ),
        Err(e) => format!("{:<28} {f:>7.2} Hz: failed: {e}", s.label),
    }
}

fn max_opt(v: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    v.flatten()
        .fold(None, |m, x| Some(m.map_or(x, |m: f64| m.max(x))))
}

fn compare(
    ladder: &[Setting],
    freqs: &[f64],
    done: &[Vec<Option<Done>>],
    rig: &Rig,
) -> (Vec<RunRow>, Vec<SettingRow>) {
    let reference: Vec<&(RunOutput, Observation, Dynamics)> = done[0]
        .iter()
        .map(|d| {
            d.as_ref()
                .and_then(|d| d.as_ref().ok())
                .expect("reference checked")
        })
        .collect();
    let ref_wall: f64 = reference.iter().map(|r| r.0.wall_time_s).sum();
    let ref_eff = effective(
        freqs,
        &reference
            .iter()
            .map(|r| r.1.amplitude_m)
            .collect::<Vec<_>>(),
        rig.primary.stiffness_n_m,
        rig.amplitude_m,
    );
    let mut runs = Vec::new();
    let mut settings = Vec::new();
    for (si, s) in ladder.iter().enumerate() {
        let mut rows = Vec::new();
        for (fi, &f) in freqs.iter().enumerate() {
            let (r_out, r_obs, r_dyn) = reference[fi];
            let _ = r_out;
            let row = match done[si][fi].as_ref() {
                None => continue,
                Some(Err(e)) => RunRow {
                    axis: s.axis,
                    setting: s.label.clone(),
                    value: s.value,
                    frequency_hz: f,
                    status: e.clone(),
                    wall_time_s: f64::NAN,
                    total_wall_time_s: f64::NAN,
                    steps: 0,
                    dt_s: None,
                    amplitude_m: None,
                    amplitude_rel_error: None,
                    dissipation_j_per_cycle: None,
                    dissipation_rel_error: None,
                    regime: "n/a".into(),
                    regime_reference: r_dyn.regime.clone(),
                    regime_match: false,
                    mle_per_s: None,
                    mle_abs_error_per_s: None,
                },
                Some(Ok((o, obs, d))) => RunRow {
                    axis: s.axis,
                    setting: s.label.clone(),
                    value: s.value,
                    frequency_hz: f,
                    status: "ok".into(),
                    wall_time_s: o.wall_time_s,
                    total_wall_time_s: o.total_wall_time_s,
                    steps: o.steps,
                    dt_s: o.dt_s,
                    amplitude_m: Some(obs.amplitude_m),
                    amplitude_rel_error: relative_error(obs.amplitude_m, r_obs.amplitude_m),
                    dissipation_j_per_cycle: Some(obs.dissipation_j_per_cycle)
                        .filter(|x| x.is_finite()),
                    dissipation_rel_error: relative_error(
                        obs.dissipation_j_per_cycle,
                        r_obs.dissipation_j_per_cycle,
                    ),
                    regime: d.regime.clone(),
                    regime_reference: r_dyn.regime.clone(),
                    regime_match: d.regime == r_dyn.regime && d.regime != "n/a",
                    mle_per_s: d.mle_per_s,
                    mle_abs_error_per_s: d
                        .mle_per_s
                        .zip(r_dyn.mle_per_s)
                        .map(|(a, b)| (a - b).abs()),
                },
            };
            rows.push(row);
        }
        let ok: Vec<&RunRow> = rows.iter().filter(|r| r.status == "ok").collect();
        let eff = (ok.len() == freqs.len())
            .then(|| {
                let z: Vec<f64> = ok
                    .iter()
                    .map(|r| r.amplitude_m.unwrap_or(f64::NAN))
                    .collect();
                effective(freqs, &z, rig.primary.stiffness_n_m, rig.amplitude_m)
            })
            .flatten();
        let wall = if ok.len() == rows.len() && !rows.is_empty() {
            ok.iter().map(|r| r.wall_time_s).sum()
        } else {
            f64::NAN
        };
        settings.push(SettingRow {
            axis: s.axis,
            setting: s.label.clone(),
            value: s.value,
            runs_ok: ok.len(),
            runs: rows.len(),
            wall_time_s: wall,
            speedup: ref_wall / wall,
            amplitude_max_rel_error: if ok.len() == rows.len() {
                max_opt(ok.iter().map(|r| r.amplitude_rel_error))
            } else {
                None
            },
            dissipation_max_rel_error: if ok.len() == rows.len() {
                max_opt(ok.iter().map(|r| r.dissipation_rel_error))
            } else {
                None
            },
            m_ef_kg: eff.map(|e| e.mass_kg),
            m_ef_rel_error: eff
                .zip(ref_eff)
                .and_then(|(e, r)| relative_error(e.mass_kg, r.mass_kg)),
            c_ef_n_s_m: eff.map(|e| e.damping_n_s_m),
            c_ef_rel_error: eff
                .zip(ref_eff)
                .and_then(|(e, r)| relative_error(e.damping_n_s_m, r.damping_n_s_m)),
            regime_matches: ok.iter().filter(|r| r.regime_match).count(),
            mle_max_abs_error_per_s: max_opt(ok.iter().map(|r| r.mle_abs_error_per_s)),
            pareto_amplitude: false,
        });
        runs.extend(rows);
    }
    let pts: Vec<(f64, f64)> = settings
        .iter()
        .map(|s| (s.wall_time_s, s.amplitude_max_rel_error.unwrap_or(f64::NAN)))
        .collect();
    for (s, on) in settings.iter_mut().zip(pareto_front(&pts)) {
        s.pareto_amplitude = on;
    }
    (runs, settings)
}
