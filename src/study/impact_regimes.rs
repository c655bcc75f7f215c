//! The impact model's regimes: the FRF coloured by regime with both exponents, the strobed
//! bifurcation diagram, and the regime map over frequency × gap.

use crate::analysis::regime::Regime;
use crate::error::StudyError;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::regime_frf::{Exponents, RegimeFrfFigure};
use crate::plot::regime_map::RegimeMapFigure;
use crate::scene::keys::{DAMPER_GAP, DAMPER_RESTITUTION, EXCITATION_FREQUENCY, RUN_DURATION};

use super::command::Command;
use super::kit::key_values;
use super::pipeline::{Ctx, FigureRecord, SweepResult, IMPACT_B};
use super::settings::Settings;

/// The analysed frequency sweep of the impact model (e = 0.8) behind `regime_frf` and
/// `bifurcation`.
pub(super) fn regime_sweep(ctx: &Ctx, s: &Settings) -> Result<SweepResult, StudyError> {
    ctx.sweep(
        "impact_regimes_e0.8",
        IMPACT_B,
        &[
            (DAMPER_RESTITUTION, "0.8".into()),
            (RUN_DURATION, s.regime_duration_s.to_string()),
        ],
        &[(EXCITATION_FREQUENCY, s.regime_freq.vary())],
        true,
    )
}

/// The columns of an analysed sweep that the regime figures draw.
struct RegimeColumns {
    f: Vec<f64>,
    y: Vec<f64>,
    regime: Vec<Option<Regime>>,
    period: Vec<Option<u32>>,
    mle: Vec<Option<f64>>,
    mle_se: Vec<Option<f64>>,
    model: Vec<Option<f64>>,
    model_se: Vec<Option<f64>>,
    /// The verdict with its qualifiers, and whether it is phase-locked (a qualifier).
    verdict: Vec<String>,
    phase_locked: Vec<bool>,
}

/// Frequency, a second column, regime, period and the data and model exponents (with standard
/// errors) of a sweep, also written to `NAME.csv` (`frequency_hz,<y_header>,regime,period,
/// mle_per_s,mle_stderr_per_s,model_mle_per_s,model_mle_stderr_per_s,verdict,phase_locked`;
/// empty cells: not estimated) next to the figure.
fn regime_columns(
    ctx: &Ctx,
    name: &str,
    sw: &SweepResult,
    y: Vec<f64>,
    y_header: &str,
) -> Result<RegimeColumns, StudyError> {
    let pts = &sw.points;
    let f = pts.map(|s| s.frequency_hz);
    // a value as sweep.csv keeps it: non-finite values are not estimates
    let opt = |pick: fn(&crate::model::RunAnalysis) -> Option<f64>| -> Vec<Option<f64>> {
        pts.iter()
            .map(|p| {
                p.summary
                    .analysis
                    .as_ref()
                    .and_then(pick)
                    .filter(|v| v.is_finite())
            })
            .collect()
    };
    let c = RegimeColumns {
        regime: pts
            .iter()
            .map(|p| p.summary.analysis.as_ref().map(|a| a.regime))
            .collect(),
        period: opt(|a| a.period)
            .into_iter()
            .map(|p| {
                p.filter(|p| *p >= 1.0 && p.fract() == 0.0)
                    .map(|p| p as u32)
            })
            .collect(),
        mle: opt(|a| a.data_mle_per_s),
        mle_se: opt(|a| a.data_mle_stderr_per_s),
        model: opt(|a| a.model_mle_per_s),
        model_se: opt(|a| a.model_mle_stderr_per_s),
        verdict: pts
            .iter()
            .map(|p| {
                p.summary
                    .analysis
                    .as_ref()
                    .map(|a| a.verdict())
                    .unwrap_or_default()
            })
            .collect(),
        phase_locked: pts
            .iter()
            .map(|p| p.summary.analysis.as_ref().is_some_and(|a| a.phase_locked))
            .collect(),
        f,
        y,
    };
    let cell = |v: Option<f64>| v.map(|m| m.to_string()).unwrap_or_default();
    let header = [
        "frequency_hz",
        y_header,
        "regime",
        "period",
        "mle_per_s",
        "mle_stderr_per_s",
        "model_mle_per_s",
        "model_mle_stderr_per_s",
        "verdict",
        "phase_locked",
    ];
    let rows = (0..c.f.len()).map(|i| {
        vec![
            c.f[i].to_string(),
            c.y[i].to_string(),
            c.regime[i].map_or("", Regime::as_str).to_string(),
            c.period[i].map(|p| p.to_string()).unwrap_or_default(),
            cell(c.mle[i]),
            cell(c.mle_se[i]),
            cell(c.model[i]),
            cell(c.model_se[i]),
            c.verdict[i].clone(),
            c.phase_locked[i].to_string(),
        ]
    });
    ctx.write_table(name, &header, rows)?;
    Ok(c)
}

pub(super) fn regime_frf(
    ctx: &Ctx,
    s: &Settings,
    sw: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "regime_frf";
    let amplitude = sw.points.map(|s| s.amplitude_m);
    let c = regime_columns(ctx, name, sw, amplitude, "amplitude_m")?;
    let size = ctx.render(
        name,
        &RegimeFrfFigure {
            frequency_hz: &c.f,
            amplitude_m: &c.y,
            regime: &c.regime,
            period: Some(&c.period),
            data: Some(Exponents {
                per_s: &c.mle,
                stderr_per_s: Some(&c.mle_se),
            }),
            model: Some(Exponents {
                per_s: &c.model,
                stderr_per_s: Some(&c.model_se),
            }),
            phase_locked: Some(&c.phase_locked),
            replica: None,
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8, gap 0.0835 m): FRF coloured by the regime of the \
                  particle's steady state (upper panel); below, the largest Lyapunov exponent \
                  (1/s) of the model's stroboscopic map from tangent dynamics and the one \
                  estimated from the data (Kantz), each ± 1 standard error; frequencies \
                  without an estimate have no marker."
            .into(),
        spec_item: "the FRF with regime bands and the Lyapunov exponent overlaid".into(),
        commands: sw.commands_then_plot("regime-frf", &ctx.path(&format!("{name}.png"))),
        reductions: s.reductions(&["regime"]),
        size_px: size,
    })
}

pub(super) fn bifurcation(
    ctx: &Ctx,
    s: &Settings,
    sw: &SweepResult,
) -> Result<FigureRecord, StudyError> {
    let name = "bifurcation";
    let (f, z): (Vec<f64>, Vec<f64>) = sw
        .points
        .iter()
        .flat_map(|p| {
            let f = p.summary.frequency_hz;
            p.summary.strobe.iter().map(move |s| (f, s.grain_z_m))
        })
        .unzip();
    if f.is_empty() {
        return Err(StudyError::step(name, "the sweep wrote no strobe.csv rows"));
    }
    ctx.write_csv(
        name,
        &["frequency_hz", "grain_z_m"],
        &(0..f.len()).map(|i| vec![f[i], z[i]]).collect::<Vec<_>>(),
    )?;
    let size = ctx.render(
        name,
        &BifurcationFigure {
            x: &f,
            z_m: &z,
            x_label: "frequency f (Hz)".into(),
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8, gap 0.0835 m): particle height strobed once per \
                  forcing period in the steady state, versus frequency."
            .into(),
        spec_item: "a bifurcation-style diagram (strobed z_cm versus f)".into(),
        commands: [
            sw.commands.clone(),
            vec![Command::plot(
                "bifurcation",
                &strobe_csv(sw),
                &ctx.path(&format!("{name}.png")),
            )],
        ]
        .concat(),
        reductions: s.reductions(&["regime"]),
        size_px: size,
    })
}

pub(super) fn regime_map(ctx: &Ctx, s: &Settings) -> Result<FigureRecord, StudyError> {
    let name = "regime_map";
    let sw = ctx.sweep_split(
        "impact_regime_map_e0.8",
        IMPACT_B,
        &[
            (DAMPER_RESTITUTION, "0.8".into()),
            (RUN_DURATION, s.regime_duration_s.to_string()),
        ],
        (DAMPER_GAP, &s.map_gaps_m),
        &[(EXCITATION_FREQUENCY, s.map_freq.vary())],
        true,
    )?;
    let gap = key_values(name, &sw.points, DAMPER_GAP)?;
    let c = regime_columns(ctx, name, &sw, gap, "gap_m")?;
    // chaotic cells are shaded by the model's exponent (the data's where the model has none)
    let shade: Vec<Option<f64>> = c.model.iter().zip(&c.mle).map(|(m, d)| m.or(*d)).collect();
    let size = ctx.render(
        name,
        &RegimeMapFigure {
            x: &c.f,
            y: &c.y,
            regime: &c.regime,
            period: Some(&c.period),
            mle_per_s: Some(&shade),
            mle_label: "model λ (1/s)".into(),
            x_label: "frequency f (Hz)".into(),
            y_label: "gap (m)".into(),
        },
    )?;
    Ok(FigureRecord {
        name: name.into(),
        caption: "Impact model (e = 0.8): regime of the particle's steady state over frequency × \
                  gap (one row per gap); chaotic cells shaded by the model's largest Lyapunov \
                  exponent, periodic cells of period ≥ 2 darker and numbered with the period; \
                  the values are in regime_map.csv."
            .into(),
        spec_item: "regimes over frequency and container height (SPEC §4)".into(),
        commands: sw.commands.clone(),
        reductions: s.reductions(&["map"]),
        size_px: size,
    })
}

/// The `strobe.csv` next to each `sweep.csv` of a sweep.
fn strobe_csv(sw: &SweepResult) -> Vec<std::path::PathBuf> {
    sw.csv
        .iter()
        .map(|p| p.with_file_name("strobe.csv"))
        .collect()
}
